"""The common interface of vehdyn's tire laws.

Every tire law is one class in one module with a ``forces(fz, kappa, alpha, gamma=0.0, vx=...)``
method that returns :class:`TireForces` in the ISO-W (TYDEX) axis system of ``.tir`` files
(x forward, y left, z up; see :mod:`vehdyn.conventions`). Inputs broadcast against each other
(numpy rules); outputs have the broadcast shape.
"""

from __future__ import annotations

from ..conventions import TireForces

__all__ = ["TireForces", "TireModel"]


class TireModel:
    """Base class of a tire law: subclasses implement :meth:`forces`.

    Attributes
    ----------
    name : str
        Registry name of the law (``"linear"``, ``"brush"``, ``"fiala"``, ``"dugoff"``,
        ``"magic_formula"``).
    """

    name: str = ""

    def forces(self, fz, kappa, alpha, gamma=0.0, vx=10.0) -> TireForces:
        """Steady-state forces and moments.

        Parameters
        ----------
        fz : array_like
            Normal load [N], >= 0.
        kappa : array_like
            Longitudinal slip ratio [-] (ISO-W: positive when driving).
        alpha : array_like
            Slip angle [rad] (ISO-W).
        gamma : array_like
            Inclination (camber) angle [rad].
        vx : array_like
            Longitudinal speed of the wheel centre [m/s].
        """
        raise NotImplementedError
