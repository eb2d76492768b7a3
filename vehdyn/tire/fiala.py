"""Fiala's tire model: the closed-form parabolic-pressure brush in practical slip.

Fiala (1954) integrated a brush with parabolic pressure along the contact length and obtained the
side force and aligning moment in closed form. With ``C_alpha`` the cornering stiffness,
``lambda_y = min(C_alpha |tan alpha| / (3 mu F_z), 1)`` and ``H = 1 - lambda_y``::

    F_y = -mu F_z (1 - H^3) sign(alpha)
        = -[C_alpha tan(alpha) - C_alpha^2 |tan alpha| tan(alpha) / (3 mu F_z)
            + C_alpha^3 tan^3(alpha) / (27 mu^2 F_z^2)]        (|alpha| < alpha_sl)
    M_z =  mu F_z a lambda_y H^3 sign(alpha)
    tan(alpha_sl) = 3 mu F_z / C_alpha

(Pacejka 2012, sec. 3.2.1, the brush with parabolic pressure, where ``C_alpha = 2 c_p a^2``). The
longitudinal force is the same law in the practical slip ratio, ``F_x = mu F_z (1 - H_x^3)
sign(kappa)`` with ``lambda_x = min(C_kappa |kappa| / (3 mu F_z), 1)``. Under combined slip the
longitudinal force has priority and the side force uses the friction left on the friction circle,
``mu F_z -> sqrt((mu F_z)^2 - F_x^2)`` (the "coupled" Fiala model used for vehicles at the limit,
e.g. Hindiyeh & Gerdes 2014), so that ``sqrt(F_x^2 + F_y^2) <= mu F_z``.

Signs follow ISO-W (:mod:`vehdyn.conventions`); in reverse (``vx < 0``) ``kappa`` keeps MFeval's
meaning (``-V_sx / V_x``, see :mod:`vehdyn.tire.slip`), so ``F_x`` changes sign, ``F_y`` does not,
and the aligning moment changes sign (the patch is entered from the rear).

References
----------
E. Fiala, "Seitenkräfte am rollenden Luftreifen", VDI-Zeitschrift 96 (1954) 973-979.
H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., 2012, sec. 3.2.1.
R. Y. Hindiyeh and J. C. Gerdes, "A controller framework for autonomous drifting", ASME J. Dyn.
Sys., Meas., Control 136(5), 2014 (coupled Fiala model with friction-circle derating).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from vehdyn.params.base import ParameterSet, parameter
from vehdyn.tire._common import VectorizedTire, load_input, planar_forces, scalar_rolling_direction, scalar_sign
from vehdyn.tire.base import TireForces
from vehdyn.tire.brush import brush_force_fraction, brush_moment_fraction

__all__ = ["FialaTire"]


def _saturation(xp, stiffness, slip_magnitude, limit):
    """``min(stiffness |slip| / (3 limit), 1)`` without a division by zero (limit 0: fully sliding)."""
    numerator = stiffness * slip_magnitude
    denominator = 3.0 * limit
    below = numerator < denominator
    return xp.where(below, numerator / xp.where(below, denominator, 1.0), 1.0)


@dataclasses.dataclass(frozen=True, kw_only=True)
class FialaTire(ParameterSet, VectorizedTire):
    r"""Fiala tire: closed-form brush side force and aligning moment, friction-circle coupling.

    The brush with parabolic pressure in practical slip, the longitudinal force first and the side
    force on the friction left on the friction circle:

    .. math::

        \lambda_x = \min\left(\frac{C_\kappa |\kappa|}{3 \mu F_z}, 1\right), \qquad
        F_x = \mu F_z \left(3 \lambda_x - 3 \lambda_x^2 + \lambda_x^3\right)
        \operatorname{sgn}\kappa \operatorname{sgn} V_x

        F_{y,\max} = \sqrt{(\mu F_z)^2 - F_x^2}, \qquad
        \lambda_y = \min\left(\frac{C_\alpha |\tan\alpha|}{3 F_{y,\max}}, 1\right)

        F_y = -F_{y,\max} \left(3 \lambda_y - 3 \lambda_y^2 + \lambda_y^3\right) \operatorname{sgn}\alpha,
        \qquad M_z = F_{y,\max} \, a \, \lambda_y (1 - \lambda_y)^3 \operatorname{sgn}\alpha
        \operatorname{sgn} V_x

    (ISO-W). In pure side slip 3 lambda - 3 lambda^2 + lambda^3 = 1 - (1 - lambda)^3: Fiala's
    side force, full sliding from tan(alpha_sl) = 3 mu F_z / C_alpha; so that
    sqrt(F_x^2 + F_y^2) <= mu F_z.

    Parameters
    ----------
    cornering_stiffness : float
        ``C_alpha = -dF_y/dalpha`` at zero slip [N/rad] (a positive magnitude).
    mu : float
        Friction coefficient [-].
    slip_stiffness : float, optional
        Longitudinal slip stiffness ``C_kappa = dF_x/dkappa`` at zero slip [N]; ``None`` uses the
        cornering stiffness (the isotropic brush value).
    contact_half_length : float, optional
        Half contact length ``a`` [m] for the aligning moment (trail ``a/3`` at zero slip);
        ``None`` (default) gives ``M_z = 0``.

    Notes
    -----
    No camber, no load dependence of the stiffnesses; ``M_x = M_y = 0``.

    References
    ----------
    .. [1] E. Fiala, "Seitenkräfte am rollenden Luftreifen", VDI-Zeitschrift 96 (1954) 973-979.
    .. [2] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., 2012, sec. 3.2.1 (the brush with
       parabolic pressure, C_alpha = 2 c_p a^2).
    .. [3] R. Y. Hindiyeh and J. C. Gerdes, "A controller framework for autonomous drifting",
       ASME J. Dyn. Sys., Meas., Control 136(5), 2014 (the coupled Fiala model with
       friction-circle derating).

    Examples
    --------
    >>> from vehdyn.tire import BrushTire, FialaTire
    >>> fiala = FialaTire(cornering_stiffness=64000.0, mu=1.0, contact_half_length=0.08)
    >>> brush = BrushTire(contact_half_length=0.08, tread_stiffness=5e6, mu=1.0)   # 2 c_p a^2 = 64000
    >>> fiala.forces(4000.0, 0.0, 0.01) == brush.forces(4000.0, 0.0, 0.01)          # pure side slip
    True
    >>> round(float(fiala.sliding_slip_angle(4000.0)), 6)                          # atan(3 mu F_z / C) [rad]
    0.185348
    """

    cornering_stiffness: float = parameter("N/rad", "C_alpha: cornering stiffness", gt=0)
    mu: float = parameter("-", "friction coefficient", gt=0)
    slip_stiffness: float | None = parameter("N", "C_kappa: longitudinal slip stiffness (None: cornering_stiffness)",
                                             default=None, gt=0)
    contact_half_length: float | None = parameter("m", "half contact length a for M_z (None: no M_z)",
                                                  default=None, gt=0)

    name = "fiala"

    @property
    def longitudinal_stiffness(self) -> float:
        """``C_kappa`` [N]: ``slip_stiffness`` or, when not given, ``cornering_stiffness``."""
        return self.cornering_stiffness if self.slip_stiffness is None else self.slip_stiffness

    def sliding_slip_angle(self, fz):
        """Slip angle at which the whole patch slides in pure side slip.

        Parameters
        ----------
        fz : float or array_like
            Normal load [N] (negative counts as 0).

        Returns
        -------
        float or ndarray
            ``atan(3 mu F_z / C_alpha)`` [rad].
        """
        return np.arctan(3.0 * self.mu * load_input(fz) / self.cornering_stiffness)

    @classmethod
    def from_vehicle(cls, vehicle, axle: str = "front") -> "FialaTire":
        """A Fiala tire for one wheel of a vehicle's axle (see :func:`vehdyn.tire.tire_for_vehicle`).

        Parameters
        ----------
        vehicle : vehdyn.Vehicle
            The vehicle.
        axle : {"front", "rear"}
            The axle.

        Returns
        -------
        FialaTire
            Half the axle's cornering stiffness, the vehicle's friction coefficient and the contact
            half length of :meth:`BrushTire.from_vehicle`.
        """
        from vehdyn.tire.registry import vehicle_tire_data

        data = vehicle_tire_data(vehicle, axle)
        return cls(cornering_stiffness=data.cornering_stiffness, mu=data.mu,
                   contact_half_length=data.contact_half_length)

    def _kernel(self, fz, kappa, alpha, gamma, vx):
        """``(F_x, F_y, M_z)`` for float arrays of one shape (``fz >= 0``)."""
        fx, fy, mz = self.xp_kernel(np, fz, kappa, alpha, gamma, vx)
        return fx, fy, np.zeros_like(fy) if mz is None else mz

    def xp_kernel(self, xp, fz, kappa, alpha, gamma, vx):
        """``(F_x, F_y, M_z)`` (ISO-W) over an ``xp`` namespace: numpy (``numpy`` itself, what
        :meth:`forces` evaluates on arrays) or CasADi symbols (:func:`vehdyn.symbolic.casadi_namespace`).

        Parameters
        ----------
        xp : namespace
            ``tan``, ``abs``, ``sign``, ``sqrt``, ``where``, ``maximum``.
        fz : float or ndarray
            Normal load [N] (>= 0).
        kappa : float or ndarray
            Slip ratio [-].
        alpha : float or ndarray
            Slip angle [rad].
        gamma : float or ndarray
            Inclination [rad] (unused).
        vx : float or ndarray
            Forward speed of the wheel centre [m/s].

        Returns
        -------
        tuple
            (F_x [N], F_y [N], M_z [N*m], or None without a contact length).
        """
        limit = self.mu * fz
        lam_x = _saturation(xp, self.longitudinal_stiffness, xp.abs(kappa), limit)
        direction = xp.where(vx < 0.0, -1.0, 1.0)  # rolling_direction
        fx = limit * brush_force_fraction(lam_x) * xp.sign(kappa) * direction
        lateral_limit = xp.sqrt(xp.maximum(limit * limit - fx * fx, 0.0))
        tan_alpha = xp.tan(alpha)
        lam_y = _saturation(xp, self.cornering_stiffness, xp.abs(tan_alpha), lateral_limit)
        side = xp.sign(tan_alpha)
        fy = -(lateral_limit * brush_force_fraction(lam_y) * side)
        if self.contact_half_length is None:
            return fx, fy, None
        mz = lateral_limit * (self.contact_half_length * brush_moment_fraction(lam_y)) * side * direction
        return fx, fy, mz

    def _forces_scalar(self, fz: float, kappa: float, alpha: float, gamma: float, vx: float) -> TireForces:
        """The same equations for one point with :mod:`math` (no numpy overhead)."""
        fz = max(fz, 0.0)
        limit = self.mu * fz
        numerator = self.longitudinal_stiffness * abs(kappa)
        lam_x = numerator / (3.0 * limit) if numerator < 3.0 * limit else 1.0
        direction = scalar_rolling_direction(vx)
        fx = limit * brush_force_fraction(lam_x) * scalar_sign(kappa) * direction
        lateral_limit = math.sqrt(max(limit * limit - fx * fx, 0.0))
        tan_alpha = math.tan(alpha)
        numerator = self.cornering_stiffness * abs(tan_alpha)
        lam_y = numerator / (3.0 * lateral_limit) if numerator < 3.0 * lateral_limit else 1.0
        side = scalar_sign(tan_alpha)
        fy = -lateral_limit * brush_force_fraction(lam_y) * side
        mz = 0.0
        if self.contact_half_length is not None:
            mz = lateral_limit * self.contact_half_length * brush_moment_fraction(lam_y) * side * direction
        return planar_forces(fx, fy, fz, mz)
