"""Steering: the road-wheel angles of the four corners.

The front steer input delta is the bicycle model's road-wheel angle; the left and right wheels
turn by the Ackermann blend

    delta_in/out = delta + A (atan(L tan(delta) / (L -/+ (T/2) tan(delta))) - delta)

with A the vehicle's ``steering.ackermann_fraction`` (0 parallel steer, 1 full Ackermann: both
wheel axes pass through the turn centre on the rear axle line; Gillespie 1992, sec. 6.1; Milliken
& Milliken 1995, sec. 19.2), "in" the wheel on the inside of the turn (the right one for delta > 0,
SAE). The rear wheels turn by the rear steer input. Each corner adds roll steer eps phi (the
vehicle's ``suspension.front_roll_steer``, ``rear_roll_steer``, road-wheel steer per unit roll,
SAE signs, as in :class:`vehdyn.handling.LateralYawRoll`).
"""

from __future__ import annotations

__all__ = ["corner_steer_angles"]


def corner_steer_angles(xp, k, front_steer, rear_steer, roll):
    """Road-wheel steer angles of the four corners: Ackermann blend and roll steer (module docstring).

    Parameters
    ----------
    xp : namespace
        The equations' namespace (:mod:`vehdyn.components.xp`).
    k : Constants
        The model's constants (:class:`vehdyn.full_vehicle.assembly.Constants`).
    front_steer, rear_steer : float or ndarray
        The bicycle steer angles [rad].
    roll : float or ndarray
        Roll angle [rad].

    Returns
    -------
    tuple
        Four steer angles [rad] (SAE, positive turns right), corner order.
    """
    t = xp.tan(front_steer)
    L, half = k.wheelbase, 0.5 * k.front_track
    # atan2 keeps the angle continuous where L -/+ (T/2) tan(delta) passes zero (never, below 60 deg)
    right = xp.atan2(L * t, L - half * t)
    left = xp.atan2(L * t, L + half * t)
    A = k.ackermann_fraction
    return (front_steer + A * (left - front_steer) + k.roll_steer[0] * roll,
            front_steer + A * (right - front_steer) + k.roll_steer[1] * roll,
            rear_steer + k.roll_steer[2] * roll, rear_steer + k.roll_steer[3] * roll)
