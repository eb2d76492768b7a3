"""The common interface of vehdyn's tire laws.

Every tire law is one class in one module with a ``forces(fz, kappa, alpha, gamma=0.0, vx=...)``
method that returns :class:`TireForces` in the ISO-W (TYDEX) axis system of ``.tir`` files
(x forward, y left, z up; see :mod:`vehdyn.conventions`). Inputs broadcast against each other
(numpy rules); outputs have the broadcast shape.

Inputs that are not finite
--------------------------
Every law and backend (``LinearTire``, ``BrushTire``, ``FialaTire``, ``DugoffTire`` and
``MagicFormula.forces``/``evaluate`` on numpy and numba) follows one rule: **a point at which any
input (``fz``, ``kappa``, ``alpha``, ``gamma``, ``vx``, and for the Magic Formula ``pressure``,
``phit``, ``omega``) is NaN or infinite comes out NaN in every output, and no other point
changes.** A scalar call returns NaN floats. No finite number is ever returned for such a point:
an infinite load used to clamp to FZMAX, a NaN speed used to act as a forward speed.
Bools (``fz=True``) and anything that is not real numbers raise :class:`vehdyn.ParameterError`
naming the input, as in the parameter sets.

Why NaN and not an error: a vectorized call over a grid or a batch of vehicles keeps the valid
points, as numpy does; and inside a simulation a NaN state must be reported by
:func:`vehdyn.simulate` as the state and time at which it appeared (``SimulationError``), which a
tire error raised from within the right-hand side would hide. NaN forces make that state NaN at
the same step. Users who want an error can test ``np.isnan(out.fx)``.

The check is one vectorized ``np.isfinite`` pass per input array and call (the mask is built
only when a point is bad), one sum for a scalar call, never a test per point inside the laws or
the compiled loops. Legitimate edge values are unchanged:
``fz <= 0`` is a wheel off the ground (zero forces), ``vx = 0`` is standstill, and large finite
inputs are evaluated (the Magic Formula clamps them to the file's ranges with ``limits=True``).
"""

from __future__ import annotations

from vehdyn.conventions import TireForces

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
            Normal load [N]; values <= 0 mean the wheel is off the ground (zero forces).
        kappa : array_like
            Longitudinal slip ratio [-] (ISO-W: positive when driving).
        alpha : array_like
            Slip angle [rad] (ISO-W).
        gamma : array_like
            Inclination (camber) angle [rad].
        vx : array_like
            Longitudinal speed of the wheel centre [m/s].

        Returns
        -------
        TireForces
            NaN at the points where an input is not finite (module docstring).

        Raises
        ------
        vehdyn.ParameterError
            If an input is a bool, not numeric, or the shapes do not broadcast.
        """
        raise NotImplementedError
