"""Dugoff's tire model: linear stiffnesses with a friction-circle saturation.

Dugoff, Fancher and Segel (1970) take a uniform pressure and linear tread stiffness. With the slip
ratio ``kappa``, slip angle ``alpha``, ``rho = 1 + kappa`` (the rolling speed over the forward
speed, ``omega R_e / V_x``) and::

    S      = sqrt((C_kappa kappa)^2 + (C_alpha tan alpha)^2)
    lambda = mu F_z rho / (2 S)
    f      = lambda (2 - lambda)   (lambda < 1),   1   (lambda >= 1)
    F_x    =  C_kappa kappa / rho f
    F_y    = -C_alpha tan(alpha) / rho f

(ISO-W signs: a positive slip angle makes a negative side force). The resultant is
``S / rho`` while adhering and ``mu F_z (1 - lambda/2) < mu F_z`` once sliding has started, so
``sqrt(F_x^2 + F_y^2) <= mu F_z``. The friction coefficient may fall with the sliding speed,
``mu = mu_0 (1 - A_s |vx| sqrt(kappa^2 + tan^2 alpha))`` (Dugoff et al.'s road-adhesion reduction
factor ``A_s`` [s/m], default 0), floored at zero.

The equations are written in the resultant form above so that a locked or backwards-spinning
wheel (``rho <= 0``) slides fully instead of dividing by zero. In reverse (``vx < 0``) ``kappa``
keeps MFeval's meaning (``-V_sx / V_x``, see :mod:`vehdyn.tire.slip`): ``F_x`` and the trail moment
change sign, ``F_y`` does not.

References
----------
H. Dugoff, P. S. Fancher and L. Segel, "An analysis of tire traction properties and their
influence on vehicle dynamic performance", SAE Technical Paper 700377, 1970.
R. Rajamani, *Vehicle Dynamics and Control*, 2nd ed., Springer, 2012, ch. 13 (Dugoff's tire model).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from vehdyn.params.base import ParameterSet, parameter
from vehdyn.tire._common import VectorizedTire, planar_forces, scalar_rolling_direction
from vehdyn.tire.base import TireForces

__all__ = ["DugoffTire"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class DugoffTire(ParameterSet, VectorizedTire):
    r"""Dugoff tire: linear stiffnesses with a friction-circle saturation (uniform pressure).

    .. math::

        S = \sqrt{(C_\kappa \kappa)^2 + (C_\alpha \tan\alpha)^2}, \qquad
        \rho = 1 + \kappa, \qquad \lambda = \frac{\mu F_z \rho}{2 S}, \qquad
        f(\lambda) = \begin{cases} \lambda (2 - \lambda) & \lambda < 1 \\ 1 & \lambda \ge 1 \end{cases}

        F_x = \frac{C_\kappa \kappa}{\rho} f(\lambda) \operatorname{sgn} V_x, \qquad
        F_y = -\frac{C_\alpha \tan\alpha}{\rho} f(\lambda), \qquad
        M_z = -t F_y \operatorname{sgn} V_x

        \mu = \mu_0 \max\left(1 - A_s |V_x| \sqrt{\kappa^2 + \tan^2\alpha}, 0\right)

    (ISO-W). The resultant is S / rho while adhering and mu F_z (1 - lambda/2) < mu F_z once
    sliding has started; a locked or backwards-spinning wheel (rho <= 0) slides fully.

    Parameters
    ----------
    cornering_stiffness : float
        ``C_alpha`` [N/rad] (a positive magnitude).
    slip_stiffness : float
        ``C_kappa`` [N].
    mu : float
        Friction coefficient at zero sliding speed ``mu_0`` [-].
    speed_friction_reduction : float
        ``A_s`` [s/m]: friction reduction per unit sliding speed; default 0.
    pneumatic_trail : float
        ``t`` [m]: ``M_z = -t F_y`` rolling forwards; default 0 (Dugoff's model has no moment).

    Notes
    -----
    No camber (``gamma`` has no effect); ``vx`` enters through its sign and, with
    ``speed_friction_reduction``, through the sliding speed. ``M_x = M_y = 0``.

    References
    ----------
    .. [1] H. Dugoff, P. S. Fancher and L. Segel, "An analysis of tire traction properties and
       their influence on vehicle dynamic performance", SAE Technical Paper 700377, 1970.
    .. [2] R. Rajamani, *Vehicle Dynamics and Control*, 2nd ed., Springer, 2012, ch. 13 (Dugoff's
       tire model).

    Examples
    --------
    >>> import numpy as np
    >>> from vehdyn.tire import DugoffTire
    >>> tire = DugoffTire(cornering_stiffness=64000.0, slip_stiffness=64000.0, mu=1.0)
    >>> round(tire.forces(fz=4000.0, kappa=0.0, alpha=0.01).fy, 4)      # adhering: -C_alpha tan(alpha) [N]
    -640.0213
    >>> out = tire.forces(fz=4000.0, kappa=0.1, alpha=0.1)               # sliding: inside mu F_z
    >>> bool(np.hypot(out.fx, out.fy) < 4000.0)
    True
    """

    cornering_stiffness: float = parameter("N/rad", "C_alpha: cornering stiffness", gt=0)
    slip_stiffness: float = parameter("N", "C_kappa: longitudinal slip stiffness", gt=0)
    mu: float = parameter("-", "friction coefficient at zero sliding speed", gt=0)
    speed_friction_reduction: float = parameter("s/m", "A_s: friction reduction per unit sliding speed",
                                                default=0.0, ge=0)
    pneumatic_trail: float = parameter("m", "pneumatic trail t", default=0.0, ge=0)

    name = "dugoff"

    @classmethod
    def from_vehicle(cls, vehicle, axle: str = "front") -> "DugoffTire":
        """A Dugoff tire for one wheel of a vehicle's axle (see :func:`vehdyn.tire.tire_for_vehicle`).

        Parameters
        ----------
        vehicle : vehdyn.Vehicle
            The vehicle.
        axle : {"front", "rear"}
            The axle.

        Returns
        -------
        DugoffTire
            Half the axle's cornering stiffness, the slip stiffness taken equal to it (isotropic
            brush: vehicle files carry no slip stiffness) and the vehicle's friction coefficient.
        """
        from vehdyn.tire.registry import vehicle_tire_data

        data = vehicle_tire_data(vehicle, axle)
        return cls(cornering_stiffness=data.cornering_stiffness, slip_stiffness=data.cornering_stiffness,
                   mu=data.mu)

    def _kernel(self, fz, kappa, alpha, gamma, vx):
        """``(F_x, F_y, M_z)`` for float arrays of one shape (``fz >= 0``)."""
        return self.xp_kernel(np, fz, kappa, alpha, gamma, vx)

    def xp_kernel(self, xp, fz, kappa, alpha, gamma, vx):
        """``(F_x, F_y, M_z)`` (ISO-W) over an ``xp`` namespace: numpy (``numpy`` itself, what
        :meth:`forces` evaluates on arrays) or CasADi symbols (:func:`vehdyn.symbolic.casadi_namespace`).

        Parameters
        ----------
        xp : namespace
            ``tan``, ``abs``, ``hypot``, ``where``, ``maximum``.
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
            (F_x [N], F_y [N], M_z [N*m]).
        """
        direction = xp.where(vx < 0.0, -1.0, 1.0)  # rolling_direction
        tan_alpha = xp.tan(alpha)
        rolling = 1.0 + kappa
        limit = self.mu * fz
        if self.speed_friction_reduction:
            limit = limit * xp.maximum(1.0 - self.speed_friction_reduction * xp.abs(vx) * xp.hypot(kappa, tan_alpha),
                                       0.0)
        ux = self.slip_stiffness * kappa
        uy = self.cornering_stiffness * tan_alpha
        stiff_slip = xp.hypot(ux, uy)  # S
        adhering = 2.0 * stiff_slip <= limit * rolling  # lambda >= 1 (includes S = 0 under load)
        # resultant over S: 1/rho while adhering (there rho > 0), mu F_z (1 - lambda/2) / S once sliding
        # (0 at S = 0); each branch with harmless denominators where the other applies
        sliding_part = limit - limit * limit * xp.maximum(rolling, 0.0) / xp.where(adhering, 1.0, 4.0 * stiff_slip)
        sliding = ~adhering & (stiff_slip > 0.0)
        per_slip = xp.where(adhering, 1.0 / xp.where(adhering, rolling, 1.0),
                            xp.where(sliding, sliding_part / xp.where(sliding, stiff_slip, 1.0), 0.0))
        fx = per_slip * ux * direction
        fy = -(per_slip * uy)
        return fx, fy, (-self.pneumatic_trail) * fy * direction

    def _forces_scalar(self, fz: float, kappa: float, alpha: float, gamma: float, vx: float) -> TireForces:
        """The same equations for one point with :mod:`math` (no numpy overhead)."""
        fz = max(fz, 0.0)
        direction = scalar_rolling_direction(vx)
        tan_alpha = math.tan(alpha)
        rolling = 1.0 + kappa
        mu = self.mu * max(1.0 - self.speed_friction_reduction * abs(vx) * math.hypot(kappa, tan_alpha), 0.0)
        limit = mu * fz
        ux = self.slip_stiffness * kappa
        uy = self.cornering_stiffness * tan_alpha
        stiff_slip = math.hypot(ux, uy)
        if stiff_slip == 0.0:
            return planar_forces(0.0, 0.0, fz, 0.0)
        if 2.0 * stiff_slip <= limit * rolling:
            resultant = stiff_slip / rolling
        else:
            resultant = limit - limit * limit * max(rolling, 0.0) / (4.0 * stiff_slip)
        fy = -resultant * uy / stiff_slip
        return planar_forces(resultant * ux / stiff_slip * direction, fy, fz, -self.pneumatic_trail * fy * direction)
