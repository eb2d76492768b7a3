"""Driveline and brakes: the spin of each wheel under drive and brake torque.

Per wheel (spin inertia I_w, effective rolling radius R_e, longitudinal tire force F_x in wheel
axes)::

    I_w d(omega)/dt = T_drive - T_brake sat(omega / omega_b) - R_e F_x,     sat(z) = z / sqrt(1 + z^2)

the law of :func:`vehdyn.components.wheel.net_wheel_torque` (the same function as the single track's):
the brake torque T_brake >= 0 opposes the spin and vanishes at omega = 0, so it can stop a wheel
but never drive it backwards through standstill. The sign function of dry friction is regularized
over omega_b (``brake_regularization_speed``, default 1 rad/s, i.e. 0.34 m/s of tread speed for a
0.34 m wheel): smooth, so explicit solvers keep their order, and stiff only as 2 T_b / (I_w omega_b)
per second -- about 2000 1/s for 1700 N*m on a 1.7 kg*m^2 wheel, which the step-size control of an
explicit method meets near a locked wheel. A held wheel under a torque T_d < T_brake then creeps at
omega = omega_b z, z / sqrt(1 + z^2) = T_d / T_brake, instead of standing exactly still.

:func:`axle_torques` splits an axle-level demand by the vehicle's ``[driveline]`` fractions.
"""

from __future__ import annotations

from vehdyn.components.wheel import net_wheel_torque

__all__ = ["wheel_acceleration", "axle_torques"]


def wheel_acceleration(xp, k, wheel_speed, drive, brake, longitudinal_force, rolling_moment):
    """d(omega)/dt of one wheel (module docstring): the net torque plus the tire's rolling-resistance moment.

    Parameters
    ----------
    xp : namespace
        The equations' namespace.
    k : Constants
        The model's constants (``wheel_spin_inertia`` [kg*m^2], ``rolling_radius`` [m],
        ``brake_regularization_speed`` [rad/s]).
    wheel_speed : float or ndarray
        omega [rad/s].
    drive : float or ndarray
        Drive torque [N*m].
    brake : float or ndarray
        Brake torque magnitude [N*m].
    longitudinal_force : float or ndarray
        The tire's F_x in wheel axes [N].
    rolling_moment : float or ndarray
        The tire's M_y [N*m] (ISO-W, about the axis of forward spin).

    Returns
    -------
    float or ndarray
        d(omega)/dt [rad/s^2].
    """
    return (net_wheel_torque(xp, k, wheel_speed, drive, brake, longitudinal_force) + rolling_moment) \
        / k.wheel_spin_inertia


def axle_torques(total, front_fraction):
    """Per-wheel torques of a total split between the axles and equally between sides.

    Parameters
    ----------
    total : float or ndarray
        The total torque [N*m].
    front_fraction : float
        The front axle's share [-] (the rest goes to the rear).

    Returns
    -------
    tuple
        (front left, front right, rear left, rear right) [N*m].
    """
    front = 0.5 * front_fraction * total
    rear = 0.5 * (1.0 - front_fraction) * total
    return front, front, rear, rear
