"""Pacejka's brush tire model with a parabolic pressure distribution.

The tread is a row of elastic bristles (stiffness ``c_p`` per unit length of the contact line and
per unit deflection, [N/m^2]) attached to a rigid carcass. Over the contact patch ``-a <= x <= a``
the normal pressure is parabolic, ``q_z(x) = 3 F_z / (4 a) (1 - x^2 / a^2)``. A bristle enters at
the leading edge undeflected, adheres to the road while its elastic force ``c_p |e|`` stays below
the static friction limit ``mu_0 q_z`` and slides, with the sliding friction ``mu_s q_z`` directed
against the slip velocity, behind that point.

In adhesion the deflection grows linearly with the distance travelled from the leading edge,
``e = sigma (a - x)``, in the direction of the *theoretical slip* vector (Pacejka 2012,
sec. 3.2.3)::

    sigma_x = kappa / (1 + kappa),      sigma_y = tan(alpha) / (1 + kappa),

so that for this isotropic brush all deflections are parallel and the combined-slip force is the
pure-slip characteristic of ``sigma = |sigma_vec|`` projected on the direction of slip. With
``theta = 2 c_p a^2 / (3 mu_0 F_z)`` and ``lambda = theta sigma`` (0 at zero slip, 1 where
sliding reaches the leading edge), integrating over the adhesion range ``x_t <= x <= a``,
``x_t = a (2 lambda - 1)``, and the sliding range ``-a <= x < x_t`` gives (``r = mu_s / mu_0``)::

    F           = mu_0 F_z [3 lambda (1 - lambda)^2 + r (3 lambda^2 - 2 lambda^3)]
    -int x q dx = mu_0 F_z a lambda (1 - lambda)^2 [1 - lambda + 3 (r - 1) lambda]

for ``lambda <= 1`` and ``F = mu_s F_z``, zero moment, beyond (full sliding). With ``r = 1`` these
are Pacejka's closed forms (sec. 3.2.1, pure side slip): ``F = mu F_z (3 lambda - 3 lambda^2 +
lambda^3)`` and aligning moment ``mu F_z a lambda (1 - lambda)^3``; cornering stiffness and
longitudinal slip stiffness both equal ``2 c_p a^2``; the pneumatic trail is ``a/3`` at zero slip
and falls to zero at full sliding, ``tan(alpha_sl) = 3 mu F_z / (2 c_p a^2)``.

Signs follow ISO-W (:mod:`vehdyn.conventions`): ``F_x = F sigma_x / sigma`` (driving positive),
``F_y = -F sigma_y / sigma`` (a positive slip angle makes a negative side force) and a positive
(self-aligning) ``M_z`` for positive slip angle. Reverse follows MFeval: ``kappa = -V_sx / V_x``
with the signed speed (the wheel turns at ``omega R_e = (1 + kappa) V_x``, see
:mod:`vehdyn.tire.slip`), so that ``F_x`` changes sign with ``vx`` at the same ``kappa``, ``F_y``
does not, and the aligning moment changes sign (the patch is entered from the rear). A wheel that
does not roll in its direction of travel (``1 + kappa <= 0``: locked or spinning the other way)
slides fully.

References
----------
H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., Butterworth-Heinemann, 2012, ch. 3:
sec. 3.2.1 (pure side slip, parabolic pressure), 3.2.2 (pure longitudinal slip), 3.2.3
(interaction: theoretical slip, combined slip; different static and sliding friction).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.params.base import ParameterSet, parameter
from vehdyn.tire._common import (VectorizedTire, broadcast_inputs, load_input, nan_at, planar_forces, rolling_direction,
                                 scalar_rolling_direction)
from vehdyn.tire.base import TireForces

__all__ = ["BrushTire", "brush_force_fraction", "brush_moment_fraction"]


def brush_force_fraction(lam, sliding_ratio=1.0):
    """Resultant force of the parabolic-pressure brush over ``mu_0 F_z``.

    Parameters
    ----------
    lam : float or ndarray
        ``theta sigma`` clipped to [0, 1] [-] (1: full sliding).
    sliding_ratio : float
        ``r = mu_s / mu_0`` [-].

    Returns
    -------
    float or ndarray
        ``3 lam (1 - lam)^2 + r (3 lam^2 - 2 lam^3)``; with ``r = 1`` this is
        ``3 lam - 3 lam^2 + lam^3`` (Pacejka 2012, sec. 3.2.1; Fiala 1954).
    """
    cubic = lam * (3.0 + lam * (lam - 3.0))  # the r = 1 force, in Horner form
    if sliding_ratio == 1.0:
        return cubic
    return cubic + (sliding_ratio - 1.0) * lam * lam * (3.0 - 2.0 * lam)


def brush_moment_fraction(lam, sliding_ratio=1.0):
    """Self-aligning moment of the parabolic-pressure brush over ``mu_0 F_z a``.

    The moment about the contact centre of the force distribution, ``-int x q dx``, positive when
    the force acts behind the centre (restoring): integrating ``x`` times the adhesion and sliding
    forces of the module docstring gives
    ``lam - 6 lam^2 + 9 lam^3 - 4 lam^4 + 3 r lam^2 (1 - lam)^2 = lam (1 - lam)^2 [1 - lam + 3 (r - 1) lam]``.
    With ``r = 1`` it is ``lam (1 - lam)^3``: trail ``a/3`` at zero slip, zero at full sliding
    (Pacejka 2012, sec. 3.2.1).

    Parameters
    ----------
    lam : float or ndarray
        ``theta sigma`` clipped to [0, 1] [-] (1: full sliding).
    sliding_ratio : float
        ``r = mu_s / mu_0`` [-].

    Returns
    -------
    float or ndarray
        ``lam (1 - lam)^2 [1 - lam + 3 (r - 1) lam]`` [-].
    """
    rest = 1.0 - lam
    if sliding_ratio == 1.0:
        return lam * rest * rest * rest
    return lam * rest * rest * (rest + 3.0 * (sliding_ratio - 1.0) * lam)


@dataclasses.dataclass(frozen=True, kw_only=True)
class BrushTire(ParameterSet, VectorizedTire):
    r"""Brush tire with parabolic pressure, combined slip through the theoretical slip.

    Elastic bristles of stiffness c_p per unit length on a rigid carcass, parabolic pressure over
    the contact patch -a <= x <= a, adhesion up to the static friction mu_0 q_z and sliding at
    mu_s q_z behind. The deflections follow the theoretical slip, so the combined-slip force is
    the pure-slip characteristic of its magnitude sigma projected on the slip direction:

    .. math::

        \sigma_x = \frac{\kappa}{1 + \kappa}, \quad \sigma_y = \frac{\tan\alpha}{1 + \kappa},
        \quad \sigma = \sqrt{\sigma_x^2 + \sigma_y^2}, \quad
        \lambda = \min\left(\frac{2 c_p a^2 \sigma}{3 \mu_0 F_z}, 1\right)

        F = \mu_0 F_z \left[3 \lambda (1 - \lambda)^2 + r (3 \lambda^2 - 2 \lambda^3)\right],
        \qquad r = \mu_s / \mu_0

        M_z = \mu_0 F_z a \, \lambda (1 - \lambda)^2 \left[1 - \lambda + 3 (r - 1) \lambda\right]
        \frac{\sigma_y}{\sigma} \operatorname{sgn} V_x

        F_x = F \frac{\sigma_x}{\sigma} \operatorname{sgn} V_x, \qquad F_y = -F \frac{\sigma_y}{\sigma}

    (ISO-W). With r = 1, F = mu F_z (3 lambda - 3 lambda^2 + lambda^3) and M_z =
    mu F_z a lambda (1 - lambda)^3: cornering and slip stiffness 2 c_p a^2, pneumatic trail a/3 at
    zero slip. A wheel that does not roll in its direction of travel (1 + kappa <= 0) slides fully.

    Parameters
    ----------
    contact_half_length : float
        Half length ``a`` of the contact patch [m].
    tread_stiffness : float
        ``c_p``: tread stiffness per unit length of contact line [N/m^2].
    mu : float
        Peak (static) friction coefficient ``mu_0`` [-].
    mu_sliding : float, optional
        Sliding friction coefficient ``mu_s <= mu_0`` [-]; ``None`` (default) uses ``mu``.

    Notes
    -----
    The carcass is rigid (no carcass compliance, sec. 3.3 of the reference), the model has no
    camber or turn slip, and the moment of the longitudinal force about the laterally deflected
    tread is neglected; ``M_x = M_y = 0``. The module docstring derives the integrals.

    References
    ----------
    .. [1] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., Butterworth-Heinemann, 2012, ch. 3:
       sec. 3.2.1 (pure side slip, parabolic pressure), 3.2.2 (pure longitudinal slip), 3.2.3
       (interaction: theoretical slip, combined slip; different static and sliding friction).

    Examples
    --------
    >>> import numpy as np
    >>> from vehdyn.tire import BrushTire
    >>> tire = BrushTire(contact_half_length=0.08, tread_stiffness=5e6, mu=1.0)
    >>> tire.cornering_stiffness                        # 2 c_p a^2 [N/rad]
    64000.0
    >>> lam = tire.cornering_stiffness * np.tan(0.01) / (3 * 1.0 * 4000.0)
    >>> fy = tire.forces(fz=4000.0, kappa=0.0, alpha=0.01).fy
    >>> bool(np.isclose(fy, -4000.0 * (3 * lam - 3 * lam**2 + lam**3), rtol=1e-14))   # Pacejka sec. 3.2.1
    True
    >>> tire.forces(fz=4000.0, kappa=0.0, alpha=np.arctan(tire.full_sliding_slip(4000.0))).fy   # -mu F_z
    -4000.0
    """

    contact_half_length: float = parameter("m", "half length a of the contact patch", gt=0)
    tread_stiffness: float = parameter("N/m^2", "c_p: tread stiffness per unit length of contact line", gt=0)
    mu: float = parameter("-", "peak (static) friction coefficient mu_0", gt=0)
    mu_sliding: float | None = parameter("-", "sliding friction coefficient mu_s (None: equal to mu)",
                                         default=None, gt=0)

    name = "brush"

    def check(self) -> None:
        if self.mu_sliding is not None and self.mu_sliding > self.mu:
            raise ParameterError(f"mu_sliding must be <= mu = {self.mu} [-], got {self.mu_sliding!r}",
                                 key="mu_sliding", value=self.mu_sliding)

    # ------------------------------------------------------------------ derived quantities
    @property
    def cornering_stiffness(self) -> float:
        """Cornering stiffness ``2 c_p a^2`` [N/rad] (independent of load)."""
        return 2.0 * self.tread_stiffness * self.contact_half_length**2

    @property
    def slip_stiffness(self) -> float:
        """Longitudinal slip stiffness ``2 c_p a^2`` [N] (the isotropic brush's equals the cornering stiffness)."""
        return self.cornering_stiffness

    @property
    def sliding_ratio(self) -> float:
        """``mu_s / mu_0`` [-]."""
        return 1.0 if self.mu_sliding is None else self.mu_sliding / self.mu

    def full_sliding_slip(self, fz):
        """Theoretical slip at which the whole patch slides.

        Parameters
        ----------
        fz : float or array_like
            Normal load [N] (negative counts as 0).

        Returns
        -------
        float or ndarray
            ``sigma_sl = 3 mu_0 F_z / (2 c_p a^2)`` [-]; in pure side slip full sliding starts at
            ``tan(alpha) = sigma_sl``.
        """
        return 3.0 * self.mu * load_input(fz) / self.cornering_stiffness

    @classmethod
    def from_cornering_stiffness(cls, cornering_stiffness: float, contact_half_length: float, mu: float,
                                 mu_sliding: float | None = None) -> "BrushTire":
        """The brush of a given cornering stiffness and contact length.

        Parameters
        ----------
        cornering_stiffness : float
            ``C_alpha = 2 c_p a^2`` [N/rad], > 0.
        contact_half_length : float
            ``a`` [m].
        mu : float
            Peak (static) friction coefficient [-].
        mu_sliding : float, optional
            Sliding friction coefficient [-] (None: ``mu``).

        Returns
        -------
        BrushTire
            With ``tread_stiffness = cornering_stiffness / (2 a^2)``.
        """
        if not cornering_stiffness > 0:
            raise ParameterError(f"cornering_stiffness must be > 0 [N/rad], got {cornering_stiffness!r}",
                                 key="cornering_stiffness", value=cornering_stiffness)
        return cls(contact_half_length=contact_half_length,
                   tread_stiffness=cornering_stiffness / (2.0 * contact_half_length**2), mu=mu,
                   mu_sliding=mu_sliding)

    @classmethod
    def from_vehicle(cls, vehicle, axle: str = "front") -> "BrushTire":
        """A brush tire for one wheel of a vehicle's axle (see :func:`vehdyn.tire.tire_for_vehicle`).

        Parameters
        ----------
        vehicle : vehdyn.Vehicle
            The vehicle.
        axle : {"front", "rear"}
            The axle.

        Returns
        -------
        BrushTire
            Per-tire cornering stiffness half the axle's, the vehicle's friction coefficient, and
            the contact half length of the chord of the unloaded tire at its static deflection,
            ``a = sqrt(2 R delta - delta^2)`` with ``delta = F_z / k_z`` (R the rolling radius,
            k_z the vertical stiffness).
        """
        from vehdyn.tire.registry import vehicle_tire_data

        data = vehicle_tire_data(vehicle, axle)
        return cls.from_cornering_stiffness(data.cornering_stiffness, data.contact_half_length, data.mu)

    # ------------------------------------------------------------------ the law
    def _kernel(self, fz, kappa, alpha, gamma, vx):
        """``(F_x, F_y, M_z)`` for float arrays of one shape (``fz >= 0``)."""
        return self.xp_kernel(np, fz, kappa, alpha, gamma, vx)

    def xp_kernel(self, xp, fz, kappa, alpha, gamma, vx):
        """``(F_x, F_y, M_z)`` (ISO-W) over an ``xp`` namespace: numpy (``numpy`` itself, what
        :meth:`forces` evaluates on arrays) or CasADi symbols (:func:`vehdyn.symbolic.casadi_namespace`).

        Parameters
        ----------
        xp : namespace
            ``tan``, ``hypot``, ``where``.
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
        slip = xp.hypot(kappa, tan_alpha)  # |V_s| / |V_x|
        lam = self._adhesion_parameter(fz, kappa, slip, xp)
        r = self.sliding_ratio
        mu_fz = self.mu * fz
        # resultant force and moment over the slip (bounded: F <= C slip), times the direction cosines
        has_slip = slip > 0.0
        safe_slip = xp.where(has_slip, slip, 1.0)
        force = xp.where(has_slip, mu_fz * brush_force_fraction(lam, r) / safe_slip, 0.0)
        moment = xp.where(has_slip, mu_fz * (self.contact_half_length * brush_moment_fraction(lam, r)) / safe_slip,
                          0.0)
        return force * kappa * direction, -(force * tan_alpha), moment * tan_alpha * direction

    def _adhesion_parameter(self, fz, kappa, slip, xp=np):
        """``lambda = theta sigma = C slip / (3 mu_0 F_z (1 + kappa))`` clipped at 1.

        ``slip`` is ``|V_s| / |V_x|``; the rolling factor ``1 + kappa`` is ``V_r / V_x``.
        Written without a division by zero: no load or no rolling means full sliding.
        """
        numerator = self.cornering_stiffness * slip
        denominator = (3.0 * self.mu) * fz * (1.0 + kappa)
        below = numerator < denominator
        return xp.where(below, numerator / xp.where(below, denominator, 1.0), 1.0)

    def _forces_scalar(self, fz: float, kappa: float, alpha: float, gamma: float, vx: float) -> TireForces:
        """The same equations for one point with :mod:`math` (no numpy overhead)."""
        fz = max(fz, 0.0)
        direction = scalar_rolling_direction(vx)
        tan_alpha = math.tan(alpha)
        slip = math.hypot(kappa, tan_alpha)
        if slip == 0.0:
            return planar_forces(0.0, 0.0, fz, 0.0)
        numerator = self.cornering_stiffness * slip
        denominator = 3.0 * self.mu * fz * (1.0 + kappa)
        lam = numerator / denominator if numerator < denominator else 1.0
        r = self.sliding_ratio
        force = self.mu * fz * brush_force_fraction(lam, r)
        moment = self.mu * fz * self.contact_half_length * brush_moment_fraction(lam, r) * direction
        ey = tan_alpha / slip
        return planar_forces(force * kappa / slip * direction, -force * ey, fz, moment * ey)

    def pneumatic_trail(self, fz, kappa, alpha, vx=10.0):
        """Pneumatic trail of the brush.

        Defined through the resultant force, so it is also the trail of the combined-slip force;
        zero at full sliding (Pacejka 2012, sec. 3.2.1).

        Parameters
        ----------
        fz : array_like
            Normal load [N].
        kappa : array_like
            Slip ratio [-] (ISO-W).
        alpha : array_like
            Slip angle [rad] (ISO-W).
        vx : array_like
            Forward speed [m/s] (its sign only).

        Returns
        -------
        ndarray
            ``t = -M_z / F_y`` [m]; its limit ``a/3`` (with the sign of ``vx``) where F_y = 0;
            NaN where an input is not finite.
        """
        (fz, kappa, alpha, _, vx), bad = broadcast_inputs(fz, kappa, alpha, 0.0, vx)
        direction = rolling_direction(vx)
        lam = self._adhesion_parameter(fz, kappa, np.hypot(kappa, np.tan(alpha)))
        r = self.sliding_ratio
        f = brush_force_fraction(lam, r)
        small = lam < 1e-9
        ratio = np.where(small, 1.0 / 3.0, brush_moment_fraction(lam, r) / np.where(small, 1.0, f))
        trail = self.contact_half_length * ratio * direction
        return trail if bad is None else nan_at(bad, (trail,))[0]
