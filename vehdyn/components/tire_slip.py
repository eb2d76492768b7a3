"""Tire slip and relaxation kinematics, shared by the single-track and the full-vehicle models.

Written once over an ``xp`` namespace (numpy arrays with a batch axis, floats in numba-compiled
code; :mod:`vehdyn.components.xp`): besides arithmetic the functions call ``xp.cos``,
``xp.atan``, ``xp.abs``, ``xp.where``, ``xp.minimum`` and ``xp.maximum``.

Each tire (or lumped axle) has a lateral deflection rho_y and, where its wheel spins, a
longitudinal deflection rho_x: the single-contact-point transient model (Pacejka 2012, sec.
7.2.1, eq. 7.9-7.12, and sec. 8.2)

.. math::

    \\dot\\rho_y = V_{sy} - |V_x| \\rho_y / \\sigma_y,\\qquad \\tan\\alpha' = \\rho_y / \\sigma_y,\\\\
    \\dot\\rho_x = -V_{sx} - |V_x| \\rho_x / \\sigma_x,\\qquad \\kappa' = \\rho_x / \\sigma_x

with V_sx = V_x - omega R_e, V_sy = V_y the slip velocities of the wheel centre in wheel axes. The
deflection cannot grow past the slip at which the law's force peaks (the contact patch slides
there; Pacejka 2012, sec. 7.2 and 8.2; Rill, *Road Vehicle Dynamics*, 2012, sec. 3.10): its outward
rate fades out over the last 5 % before the peak, and past it the kinematic slip takes over when it
lies further out. Below the low-speed damping speed v_l a damping term fades in (Pacejka 2012, sec.
8.7, eq. 8.125-8.126, the k_Vlow damping of MF-Tyre) on the deflection rate, so that it is zero in
the steady state:

.. math::

    \\tan\\alpha' \\leftarrow \\tan\\alpha' + w\\,\\dot\\rho_y / v_l,\\quad
    w = (1 + \\cos(\\pi |V_x| / v_l)) / 2 \\text{ for } |V_x| < v_l \\text{, else } 0

Without relaxation the slips are the steady-state ones, tan(alpha) = V_y / D(V_x) and
kappa = -V_sx / (sign(V_x) D(V_x)), with the regularized speed D of :func:`regularized_speed`.
The signs are SAE (slip angle positive for a wheel moving to its right); :mod:`vehdyn.conventions`
turns them into the tire law's ISO-W.

References
----------
.. [1] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., Butterworth-Heinemann, 2012, sec.
   7.2.1 (eq. 7.9-7.12), 8.2 and 8.7 (eq. 8.125-8.126).
.. [2] G. Rill, *Road Vehicle Dynamics: Fundamentals and Modeling*, CRC Press, 2012, sec. 3.10.
"""

from __future__ import annotations

import math

__all__ = ["REGULARIZATION_SPEED", "regularized_speed", "low_speed_blend", "sliding_slip", "limit_deflection_rate",
           "deflection_rate", "contact_slips"]

REGULARIZATION_SPEED = 0.5
"""v_0 [m/s] of :func:`regularized_speed` (the default of :func:`vehdyn.tire.regularized_speed`)."""


def regularized_speed(xp, vx):
    """The speed D(V_x) that divides the steady-state slips: |V_x| above v_0, smooth below.

    .. math::

        D(V_x) = |V_x| \\text{ for } |V_x| \\ge v_0,\\quad (V_x^2 + v_0^2) / (2 v_0) \\text{ below}

    (:func:`vehdyn.tire.regularized_speed`, v_0 = :data:`REGULARIZATION_SPEED`).

    Parameters
    ----------
    xp : namespace
        The equations' namespace.
    vx : float or ndarray
        Forward speed of the wheel centre V_x [m/s].

    Returns
    -------
    float or ndarray
        D [m/s], >= v_0 / 2.
    """
    v0 = REGULARIZATION_SPEED
    return xp.where(xp.abs(vx) >= v0, xp.abs(vx), (vx * vx + v0 * v0) / (2.0 * v0))


def low_speed_blend(xp, speed, damping_speed):
    """The weight w of the low-speed damping (Pacejka 2012, eq. 8.126).

    .. math::

        w = (1 + \\cos(\\pi \\min(|V_x| / v_l, 1))) / 2

    Parameters
    ----------
    xp : namespace
        The equations' namespace.
    speed : float or ndarray
        |V_x| [m/s].
    damping_speed : float
        v_l [m/s].

    Returns
    -------
    float or ndarray
        w [-]: 1 at standstill, 0 from v_l up.
    """
    return 0.5 * (1.0 + xp.cos(math.pi * xp.minimum(speed / damping_speed, 1.0)))


def sliding_slip(xp, transient, kinematic, peak):
    """The slip that makes the force: the transient (deflection) slip, or the kinematic slip where the
    deflection sits at its peak-force limit and the kinematic slip lies beyond it (the patch slides).

    Parameters
    ----------
    xp : namespace
        The equations' namespace.
    transient : float or ndarray
        rho / sigma [-].
    kinematic : float or ndarray
        The steady-state slip at the present velocities [-].
    peak : float or ndarray
        The slip of the law's peak force [-].

    Returns
    -------
    float or ndarray
        The acting slip [-].
    """
    at_limit = xp.where(xp.abs(transient) >= 0.999 * peak, 1.0, 0.0)
    beyond = xp.where(transient * kinematic > 0, 1.0, 0.0) * xp.where(xp.abs(kinematic) > xp.abs(transient), 1.0, 0.0)
    return xp.where(at_limit * beyond > 0, kinematic, transient)


def limit_deflection_rate(xp, rate, slip, peak):
    """A deflection rate with its outward part faded out over the last 5 % before the peak slip.

    Parameters
    ----------
    xp : namespace
        The equations' namespace.
    rate : float or ndarray
        d(rho)/dt [m/s].
    slip : float or ndarray
        rho / sigma [-].
    peak : float or ndarray
        The slip of the law's peak force [-].

    Returns
    -------
    float or ndarray
        The limited rate [m/s].
    """
    room = xp.minimum(xp.maximum((peak - xp.abs(slip)) / (0.05 * peak), 0.0), 1.0)
    return xp.where(rate * slip > 0, rate * room, rate)


def deflection_rate(xp, slip_velocity, vx, deflection, length, peak):
    """The rate of a tire deflection, its outward part limited at the peak slip.

    .. math::

        \\dot\\rho = V_s - |V_x| \\rho / \\sigma

    Parameters
    ----------
    xp : namespace
        The equations' namespace.
    slip_velocity : float or ndarray
        V_sy, or -V_sx for the longitudinal deflection [m/s].
    vx : float or ndarray
        Forward speed of the wheel centre [m/s].
    deflection : float or ndarray
        rho [m].
    length : float or ndarray
        Relaxation length sigma [m].
    peak : float or ndarray
        The slip of the law's peak force [-].

    Returns
    -------
    float or ndarray
        d(rho)/dt [m/s].
    """
    rate = slip_velocity - xp.abs(vx) * deflection / length
    return limit_deflection_rate(xp, rate, deflection / length, peak)


def contact_slips(xp, k, vx, vy, wheel_speed, lateral_deflection, longitudinal_deflection, lateral_rate,
                  longitudinal_rate, lateral_length, longitudinal_length, peak_slip_ratio, peak_tan_slip_angle):
    """The slips acting in a tire law (SAE), from the wheel-centre velocity and the deflections.

    With relaxation (``k.tire_lag``) the transient slips of the deflections, the sliding rule of
    :func:`sliding_slip` and the low-speed damping on the deflection rates (module docstring);
    without it the steady-state slips. Without wheel spin (``k.wheel_spin`` False) the slip ratio is 0.

    Parameters
    ----------
    xp : namespace
        The equations' namespace.
    k : namedtuple
        The model's constants; read: ``tire_lag``, ``wheel_spin`` (bools), ``rolling_radius`` R_e [m],
        ``low_speed_damping_speed`` v_l [m/s].
    vx, vy : float or ndarray
        Velocity of the wheel centre in wheel axes (SAE) [m/s].
    wheel_speed : float or ndarray
        Spin omega [rad/s] (unused without wheel spin).
    lateral_deflection, longitudinal_deflection : float or ndarray
        rho_y, rho_x [m] (unused without relaxation).
    lateral_rate, longitudinal_rate : float or ndarray
        Their rates [m/s] (:func:`deflection_rate`; the low-speed damping's input).
    lateral_length, longitudinal_length : float or ndarray
        sigma_y, sigma_x [m].
    peak_slip_ratio, peak_tan_slip_angle : float or ndarray
        The slips of the law's peak forces [-].

    Returns
    -------
    tuple
        (alpha SAE [rad], kappa [-], sign of V_x with sign(0) = +1 [-], |V_x| [m/s]).
    """
    speed = xp.abs(vx)
    direction = xp.where(vx < 0.0, -1.0, 1.0)  # sign(vx) with sign(0) = +1
    blend = low_speed_blend(xp, speed, k.low_speed_damping_speed)
    if k.tire_lag:
        tan_alpha = sliding_slip(xp, lateral_deflection / lateral_length, vy / regularized_speed(xp, vx),
                                 peak_tan_slip_angle)
        tan_alpha = tan_alpha + blend * lateral_rate / k.low_speed_damping_speed
    else:
        tan_alpha = vy / regularized_speed(xp, vx)
    alpha = xp.atan(tan_alpha)
    if k.wheel_spin:
        vsx = vx - wheel_speed * k.rolling_radius
        if k.tire_lag:
            slip = sliding_slip(xp, longitudinal_deflection / longitudinal_length, -vsx / regularized_speed(xp, vx),
                                peak_slip_ratio)
            slip = slip + blend * longitudinal_rate / k.low_speed_damping_speed
            kappa = slip * direction
        else:
            kappa = -vsx / (direction * regularized_speed(xp, vx))
    else:
        kappa = 0.0 * alpha
    return alpha, kappa, direction, speed
