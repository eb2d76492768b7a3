"""Tire slip from the wheel's motion, with a low-speed regularization.

All quantities are in the ISO-W wheel axes of the ``.tir`` file and MFeval (x forward in the wheel
plane, y to the left; :mod:`vehdyn.conventions` converts from the SAE vehicle axes). With ``V_x``,
``V_y`` the velocity of the wheel centre (≈ of the contact centre), ``omega`` the wheel spin
(positive rolling forwards) and ``R_e`` the effective rolling radius (Pacejka 2012, ch. 1 and
ch. 4; MFeval's definitions)::

    V_r  = omega R_e                    rolling speed
    V_sx = V_x - V_r,   V_sy = V_y      slip velocity of the contact point
    kappa = -V_sx / V_x                 longitudinal slip ratio
    tan(alpha) = V_sy / |V_x|           slip angle

``kappa`` divides by the *signed* speed, as MFeval does: ``omega R_e = (1 + kappa) V_x`` in both
directions of travel, ``kappa > 0`` means the wheel turns faster than it travels, and the tire laws
flip ``F_x`` with ``sign(V_x)``; ``alpha`` divides by ``|V_x|`` so the side force keeps its sign in
reverse. Neither slip changes sign when the car reverses with the same wheel behaviour.

Low-speed regularization
------------------------
Both definitions divide by the forward speed, which vanishes at standstill. Here ``|V_x|`` is
replaced by

    D(V_x) = |V_x|                          for |V_x| >= v_0
    D(V_x) = (V_x^2 + v_0^2) / (2 v_0)      for |V_x| <  v_0

(``v_0`` = ``regularization_speed``, default 0.5 m/s): exact above ``v_0``, continuous with a
continuous derivative at ``v_0``, and at least ``v_0 / 2`` everywhere, so there is no division by
zero and the slips stay bounded by ``2 |V_s| / v_0``. The sign used with ``kappa`` is that of
``V_x`` with ``sign(0) = +1``; the force-producing product ``kappa sign(V_x) = -V_sx / D`` is
continuous through ``V_x = 0``. Below ``v_0`` steady-state slip is not physical (the tire behaves
as a spring); use the relaxation model of :mod:`vehdyn.tire.relaxation`, whose states are driven
by the slip *velocities* and need no division at all.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from vehdyn.errors import ParameterError

__all__ = ["WheelSlip", "regularized_speed", "wheel_slip", "slip_velocities", "theoretical_slip",
           "DEFAULT_REGULARIZATION_SPEED"]

#: Default ``v_0`` [m/s] of the low-speed regularization.
DEFAULT_REGULARIZATION_SPEED = 0.5


class WheelSlip(NamedTuple):
    """Slip of one wheel (ISO-W).

    Attributes
    ----------
    kappa : ndarray
        Longitudinal slip ratio ``-V_sx / V_x`` [-] (regularized).
    alpha : ndarray
        Slip angle ``atan(V_sy / |V_x|)`` [rad] (regularized).
    slip_velocity_x, slip_velocity_y : ndarray
        ``V_sx = V_x - omega R_e`` and ``V_sy = V_y`` [m/s].
    rolling_speed : ndarray
        ``V_r = omega R_e`` [m/s].
    """

    kappa: np.ndarray
    alpha: np.ndarray
    slip_velocity_x: np.ndarray
    slip_velocity_y: np.ndarray
    rolling_speed: np.ndarray


def _check_speed(regularization_speed: float) -> float:
    if isinstance(regularization_speed, bool) or not isinstance(regularization_speed, (int, float)) \
            or not np.isfinite(regularization_speed) or regularization_speed <= 0:
        raise ParameterError(f"regularization_speed must be a finite number > 0 [m/s], got {regularization_speed!r}",
                             key="regularization_speed", value=regularization_speed)
    return float(regularization_speed)


def regularized_speed(vx, regularization_speed: float = DEFAULT_REGULARIZATION_SPEED):
    r"""The denominator of the slips, regularized at low speed.

    .. math::

        D(V_x) = \begin{cases} |V_x| & |V_x| \ge v_0 \\
        (V_x^2 + v_0^2) / (2 v_0) & |V_x| < v_0 \end{cases}

    exact above v_0, continuous with a continuous derivative at v_0, at least v_0 / 2 everywhere.

    Parameters
    ----------
    vx : array_like
        Forward speed of the wheel centre [m/s].
    regularization_speed : float
        ``v_0`` [m/s], > 0.

    Returns
    -------
    ndarray
        D(V_x) [m/s].

    Raises
    ------
    ParameterError
        If ``regularization_speed`` is not a finite number > 0.
    """
    v0 = _check_speed(regularization_speed)
    vx = np.asarray(vx, dtype=float)
    speed = np.abs(vx)
    return np.where(speed >= v0, speed, (vx * vx + v0 * v0) / (2.0 * v0))


def slip_velocities(vx, vy, omega, effective_radius):
    """Slip velocities of the contact point (ISO-W).

    Parameters
    ----------
    vx, vy : array_like
        Wheel-centre velocity in the ISO-W wheel axes [m/s].
    omega : array_like
        Wheel spin [rad/s], positive rolling forwards.
    effective_radius : array_like
        Effective rolling radius R_e [m].

    Returns
    -------
    V_sx, V_sy : ndarray
        ``V_x - omega R_e`` and ``V_y`` [m/s], broadcast together.

    References
    ----------
    .. [1] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., 2012, ch. 1 and 4 (slip
       definitions, as MFeval uses them).
    """
    vx, vy, omega, radius = np.broadcast_arrays(*(np.asarray(v, dtype=float)
                                                  for v in (vx, vy, omega, effective_radius)))
    return vx - omega * radius, vy.copy()


def wheel_slip(vx, vy, omega, effective_radius, *,
               regularization_speed: float = DEFAULT_REGULARIZATION_SPEED) -> WheelSlip:
    r"""Slip ratio and slip angle of a wheel from its motion.

    .. math::

        \kappa = -\frac{V_{sx}}{\operatorname{sgn}(V_x) D(V_x)}, \qquad
        \tan\alpha = \frac{V_{sy}}{D(V_x)}, \qquad
        V_{sx} = V_x - \omega R_e, \quad V_{sy} = V_y

    with :math:`D(V_x)` = :func:`regularized_speed` (|V_x| above the regularization speed) and
    sgn 0 = +1: MFeval's definitions (kappa divides by the signed speed, alpha by its magnitude).

    Parameters
    ----------
    vx, vy : array_like
        Wheel-centre velocity in the ISO-W wheel axes [m/s] (x forward in the wheel plane, y left).
    omega : array_like
        Wheel spin [rad/s], positive when rolling forwards.
    effective_radius : array_like
        Effective rolling radius ``R_e`` [m], > 0.
    regularization_speed : float
        ``v_0`` [m/s] of the low-speed regularization.

    Returns
    -------
    WheelSlip
        Arrays of the broadcast shape.

    References
    ----------
    .. [1] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., 2012, ch. 1 and 4 (slip
       definitions).

    Examples
    --------
    >>> s = wheel_slip(20.0, 1.0, 20.0 * 1.05 / 0.3, 0.3)     # driving, sliding left
    >>> round(float(s.kappa), 12), round(float(np.tan(s.alpha)), 12)
    (0.05, 0.05)
    """
    radius = np.asarray(effective_radius, dtype=float)
    if np.any(~(radius > 0)) or np.any(~np.isfinite(radius)):
        raise ParameterError(f"effective_radius must be finite and > 0 [m], got {effective_radius!r}",
                             key="effective_radius", value=effective_radius)
    vx, vy, omega, radius = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (vx, vy, omega, radius)))
    rolling = omega * radius
    vsx, vsy = slip_velocities(vx, vy, omega, radius)
    denominator = regularized_speed(vx, regularization_speed)
    direction = np.where(vx < 0.0, -1.0, 1.0)
    kappa = -vsx / (direction * denominator)
    alpha = np.arctan(vsy / denominator)
    return WheelSlip(kappa, alpha, vsx, vsy, rolling)


def theoretical_slip(kappa, alpha):
    """Pacejka's theoretical slip: the slip velocity over the rolling speed.

    Parameters
    ----------
    kappa : array_like
        Slip ratio [-] (ISO-W).
    alpha : array_like
        Slip angle [rad] (ISO-W).

    Returns
    -------
    sigma_x, sigma_y : ndarray
        ``(kappa, tan alpha) / (1 + kappa)`` [-], which drive the brush model; infinite (full
        sliding, with the sign of the slip) where the wheel does not roll in its direction of
        travel (``1 + kappa <= 0``).

    References
    ----------
    .. [1] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., 2012, sec. 3.2.3.
    """
    kappa = np.asarray(kappa, dtype=float)
    tan_alpha = np.tan(np.asarray(alpha, dtype=float))
    rolling = 1.0 + kappa
    rolls = rolling > 0.0
    safe = np.where(rolls, rolling, 1.0)
    def component(value):
        sliding = np.where(value != 0.0, np.copysign(np.inf, value), 0.0)
        return np.where(rolls, value / safe, sliding)

    return component(kappa), component(tan_alpha)
