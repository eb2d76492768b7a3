"""Wheel spin: the torques on a spinning wheel, shared by the single-track and the full-vehicle models.

Written once over an ``xp`` namespace (:mod:`vehdyn.components.xp`; ``xp.abs``, ``xp.sqrt``,
``xp.tanh``). A wheel (or the two wheels of an axle, lumped) of spin inertia I spins at omega
under the drive torque T_d, the brake torque T_b (a magnitude that opposes the spin), the tire's
longitudinal force F_x at the rolling radius R_e and its rolling-resistance moment M_y
(Pacejka 2012, sec. 4.3.5 and 7.2; ISO-W: M_y negative rolling forwards):

.. math::

    I \\dot\\omega = T_d - T_b\\,\\mathrm{sat}(\\omega / \\omega_b) - R_e F_x + M_y \\tanh(|\\omega| / \\omega_b),
    \\qquad \\mathrm{sat}(z) = z / \\sqrt{1 + z^2}

The brake torque's sign is regularized within omega_b so that a locked wheel stops without
chatter; the rolling resistance fades out at standstill the same way (else a law's M_y at zero
speed would spin a wheel at rest backwards).

References
----------
.. [1] H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., Butterworth-Heinemann, 2012, sec. 4.3.5
   (rolling resistance) and sec. 7.2 (the wheel's spin equation).
"""

from __future__ import annotations

__all__ = ["net_wheel_torque", "rolling_resistance_fade"]


def net_wheel_torque(xp, k, wheel_speed, drive, brake, longitudinal_force):
    """The torque on a wheel without its rolling resistance: T_d - |T_b| sat(omega / omega_b) - R_e F_x.

    Parameters
    ----------
    xp : namespace
        The equations' namespace.
    k : namedtuple
        The model's constants; read: ``brake_regularization_speed`` omega_b [rad/s] and
        ``rolling_radius`` R_e [m].
    wheel_speed : float or ndarray
        omega [rad/s] (positive rolling forwards).
    drive : float or ndarray
        Drive torque T_d [N*m].
    brake : float or ndarray
        Brake torque T_b [N*m] (its magnitude is used).
    longitudinal_force : float or ndarray
        The tire's F_x in wheel axes [N] (positive driving).

    Returns
    -------
    float or ndarray
        The torque [N*m] about the axis of forward spin.
    """
    z = wheel_speed / k.brake_regularization_speed
    return drive - xp.abs(brake) * z / xp.sqrt(1.0 + z * z) - k.rolling_radius * longitudinal_force


def rolling_resistance_fade(xp, k, wheel_speed):
    """tanh(|omega| / omega_b): the rolling resistance opposes rolling and fades to 0 at standstill.

    1 to rounding (within an ulp of numpy's or the C library's tanh) above about 19 omega_b.

    Parameters
    ----------
    xp : namespace
        The equations' namespace.
    k : namedtuple
        The model's constants; read: ``brake_regularization_speed`` omega_b [rad/s].
    wheel_speed : float or ndarray
        omega [rad/s].

    Returns
    -------
    float or ndarray
        The factor [-] on M_y.
    """
    return xp.tanh(xp.abs(wheel_speed) / k.brake_regularization_speed)
