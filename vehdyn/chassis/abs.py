"""Anti-lock braking: wheel-slip control by a brake-pressure modulator with apply/hold/release.

Production ABS modulates the wheel-cylinder pressure of each channel with inlet and outlet valves
in three modes -- *apply* (pressure builds up towards the master-cylinder pressure), *hold* (both
valves closed) and *release* (pressure drains) -- switched on thresholds of wheel slip
(Bosch, *Automotive Handbook*, 10th ed., 2018, "Antilock braking system"; Burton et al., "Anti-lock
braking systems", Savaresi & Tanelli, *Active Braking Control Systems Design for Vehicles*,
Springer 2010, ch. 1 and 6; Rajamani, *Vehicle Dynamics and Control*, 2nd ed., 2012, sec. 6.4).
Here each axle channel has one state, the wheel brake torque T (the wheel-cylinder pressure times
the brake's torque gain, so no gain needs to be known), with a first-order hydraulic lag::

    lambda = (u - omega R_e) / max(u, u_min)                      braking slip (> 0 braking)
    w_r = s_v sigmoid((lambda - lambda_release) / w)             release weight
    w_a = (1 - s_v) + s_v sigmoid((lambda_apply - lambda) / w)    apply weight
    dT/dt = w_a (T_d - T) / tau_apply - w_r T / tau_release - max(T - T_d, 0) / tau_release

with sigmoid(z) = (1 + tanh z) / 2, the driver's demand T_d >= 0, and s_v = sigmoid((u - v_off) /
0.5 m/s) switching the ABS off below v_off so that the car comes to rest. Between the apply and
release thresholds both weights vanish: the pressure is *held*. The modes are smooth functions of
the slip (width w), so the closed loop is an ODE that adaptive solvers integrate without events;
the last term lets the pressure follow a falling demand (the driver lifting the pedal) in every
mode. The slip uses the true forward speed u (a production ABS estimates it from the wheel speeds).
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.params import Vehicle
from vehdyn.signals import Signal
from vehdyn.chassis.base import ChassisController, channel_signals, check_vehicle, sigmoid
from vehdyn.params.checks import check_gains

__all__ = ["ABS", "ABSGains", "braking_slip", "torque_rate"]

_AXLES = ("front", "rear")

ABSGains = namedtuple("ABSGains", ("rolling_radius", "apply_slip", "release_slip", "slip_width", "apply_time_constant",
                                   "release_time_constant", "cutoff_speed", "minimum_speed"))
ABSGains.__doc__ = """The numbers of the ABS law (SI), see :class:`ABS`.

Parameters
----------
rolling_radius : float
    R_e [m].
apply_slip, release_slip : float
    lambda_apply, lambda_release [-].
slip_width : float
    w [-] of the smooth mode switches.
apply_time_constant, release_time_constant : float
    tau_apply, tau_release [s].
cutoff_speed : float
    v_off [m/s].
minimum_speed : float
    u_min [m/s] of the slip's denominator.
"""


def braking_slip(p, wheel_speed, speed):
    r"""The braking slip :math:`\lambda = (u - \omega R_e) / \max(u, u_{min})` (positive braking).

    Parameters
    ----------
    p : ABSGains
        The law's numbers.
    wheel_speed : float or ndarray
        omega [rad/s].
    speed : float or ndarray
        Forward speed u [m/s].

    Returns
    -------
    float or ndarray
        lambda [-].
    """
    return (speed - wheel_speed * p.rolling_radius) / np.maximum(speed, p.minimum_speed)


def torque_rate(p, torque, demand, wheel_speed, speed):
    r"""The rate of one channel's brake torque (the equations of :class:`ABS`): numpy arrays or, compiled, floats.

    .. math::

        \dot T = w_a \frac{T_d - T}{\tau_{apply}} - w_r \frac{T}{\tau_{release}}
                 - (1 - w_a) \frac{\max(T - T_d, 0)}{\tau_{release}}

    Parameters
    ----------
    p : ABSGains
        The law's numbers.
    torque : float or ndarray
        T [N*m], the channel's state.
    demand : float or ndarray
        T_d [N*m], the driver's demand (negative taken as 0).
    wheel_speed : float or ndarray
        omega [rad/s].
    speed : float or ndarray
        Forward speed u [m/s].

    Returns
    -------
    float or ndarray
        dT/dt [N*m/s].
    """
    demand = np.maximum(demand, 0.0)
    slip = braking_slip(p, wheel_speed, speed)
    active = sigmoid((speed - p.cutoff_speed) / 0.5)
    release = active * sigmoid((slip - p.release_slip) / p.slip_width)
    apply = (1.0 - active) + active * sigmoid((p.apply_slip - slip) / p.slip_width)
    return (apply * (demand - torque) / p.apply_time_constant - release * torque / p.release_time_constant
            - (1.0 - apply) * np.maximum(torque - demand, 0.0) / p.release_time_constant)


class ABS(ChassisController):
    r"""Anti-lock braking of a wheel-spin single track or the full vehicle: an apply/hold/release modulator.

    Each channel (axle, or wheel with ``corners``) has one state, the brake torque :math:`T` that
    the modulated wheel-cylinder pressure applies, with a first-order hydraulic lag; the modes are
    smooth functions of the braking slip (module docstring):

    .. math::

        \lambda &= \frac{u - \omega R_e}{\max(u, u_{min})}, \qquad
        s_v = \sigma\!\left(\frac{u - v_{off}}{0.5\ \mathrm{m/s}}\right), \\
        w_r &= s_v\, \sigma\!\left(\frac{\lambda - \lambda_{release}}{w}\right), \qquad
        w_a = (1 - s_v) + s_v\, \sigma\!\left(\frac{\lambda_{apply} - \lambda}{w}\right), \\
        \dot T &= w_a \frac{T_d - T}{\tau_{apply}} - w_r \frac{T}{\tau_{release}}
                 - (1 - w_a) \frac{\max(T - T_d, 0)}{\tau_{release}}

    with :math:`\sigma(z) = (1 + \tanh z) / 2`; the torque applied is :math:`\max(T, 0)`.

    Parameters
    ----------
    vehicle : Vehicle
        Gives the rolling radius R_e [m].
    apply_slip : float
        lambda_apply [-]: below it the pressure builds up towards the demand (default 0.05).
    release_slip : float
        lambda_release [-]: above it the pressure is released (default 0.12); > apply_slip.
    slip_width : float
        w [-] of the smooth mode switches (default 0.01).
    apply_time_constant, release_time_constant : float
        tau_apply, tau_release [s] of the hydraulic lag (defaults 0.1 s and 0.02 s).
    cutoff_speed : float
        v_off [m/s] below which the ABS lets the demand through (default 2 m/s).
    minimum_speed : float
        u_min [m/s] of the slip's denominator (default 1 m/s).
    axles : tuple of str
        Axles controlled, ``("front", "rear")`` by default.
    corners : bool
        One channel per wheel with the full vehicle's names (``brake_torque_front_left``,
        ``wheel_speed_front_left``, ...) instead of one per axle with the single track's
        (``front_brake_torque``, ``front_wheel_speed``).

    Signals
    -------
    states
        ``<channel>_abs_brake_torque`` [N*m]: the brake torque the modulated pressure applies.
    inputs
        demands ``<axle>_brake_torque`` [N*m]; feedback ``<axle>_wheel_speed`` [rad/s] and
        ``longitudinal_velocity`` [m/s] (per wheel with ``corners``).
    outputs
        ``<axle>_brake_torque`` [N*m], the modulated torque (replaces the demand at the plant).

    References
    ----------
    .. [1] Robert Bosch GmbH, *Automotive Handbook*, 10th ed., 2018, "Antilock braking system"
       (the apply, hold and release modes on slip thresholds).
    .. [2] S. M. Savaresi and M. Tanelli, *Active Braking Control Systems Design for Vehicles*,
       Springer, 2010, ch. 1 and 6.
    .. [3] R. Rajamani, *Vehicle Dynamics and Control*, 2nd ed., Springer, 2012, sec. 6.4.

    Examples
    --------
    >>> import vehdyn
    >>> from vehdyn import ClosedLoop
    >>> from vehdyn.chassis import ABS
    >>> from vehdyn.handling import SingleTrack
    >>> car = vehdyn.load_vehicle("sedan")
    >>> loop = ClosedLoop(SingleTrack(car, wheel_spin=True), ABS(car))
    >>> loop.output_names[-2:]
    ('front_brake_torque_after_abs', 'rear_brake_torque_after_abs')
    """

    def __init__(self, vehicle: Vehicle, *, apply_slip: float = 0.05, release_slip: float = 0.12,
                 slip_width: float = 0.01, apply_time_constant: float = 0.1, release_time_constant: float = 0.02,
                 cutoff_speed: float = 2.0, minimum_speed: float = 1.0, axles=_AXLES, corners: bool = False):
        check_vehicle("ABS", vehicle)
        gains = check_gains("ABS", apply_slip=apply_slip, release_slip=release_slip, slip_width=slip_width,
                            apply_time_constant=apply_time_constant, release_time_constant=release_time_constant,
                            cutoff_speed=cutoff_speed, minimum_speed=minimum_speed,
                            positive=("apply_slip", "release_slip", "slip_width", "apply_time_constant",
                                      "release_time_constant", "minimum_speed"), nonnegative=("cutoff_speed",))
        if gains["release_slip"] <= gains["apply_slip"]:
            raise ParameterError(f"ABS release_slip must exceed apply_slip ({apply_slip}), got {release_slip!r}",
                                 key="release_slip", value=release_slip)
        self.__dict__.update(gains)
        self.vehicle, self.axles, self.corners = vehicle, axles, bool(corners)
        self.rolling_radius = float(vehicle.tires.rolling_radius)
        self.channels, names = channel_signals("ABS", axles, self.corners, ("brake_torque", "wheel_speed"))
        self.declare(
            states=[Signal(f"{c}_abs_brake_torque", "N*m", f"brake torque of the {c} ABS channel (pressure x gain)")
                    for c in self.channels],
            inputs=[Signal(n, "N*m", "driver's brake torque demand") for n in names["brake_torque"]]
            + [Signal(n, "rad/s", "wheel spin") for n in names["wheel_speed"]]
            + [Signal("longitudinal_velocity", "m/s", "forward velocity u")],
            outputs=[Signal(n, "N*m", "brake torque after the ABS modulator") for n in names["brake_torque"]])

    @property
    def gains(self) -> ABSGains:
        """The numbers of the law as an :data:`ABSGains` (read from the attributes on every call)."""
        return ABSGains(*(getattr(self, name) for name in ABSGains._fields))

    def braking_slip(self, wheel_speed, speed):
        """The braking slip lambda = (u - omega R_e) / max(u, u_min) (:func:`braking_slip`).

        Parameters
        ----------
        wheel_speed : float or array_like
            omega [rad/s].
        speed : float or array_like
            Forward speed u [m/s].

        Returns
        -------
        float or ndarray
            lambda [-] (positive braking).
        """
        return braking_slip(self.gains, wheel_speed, speed)

    def rhs(self, t, x, u):
        n = len(self.channels)
        x, u = np.asarray(x, dtype=float), np.asarray(u, dtype=float)
        return torque_rate(self.gains, x, u[:n], u[n:2 * n], u[2 * n])

    def output(self, t, x, u):
        return np.maximum(np.asarray(x, dtype=float), 0.0)

    def compiled_rhs(self):
        """The law compiled by numba (:mod:`vehdyn.chassis._chassis_numba`), for a compiled :class:`ClosedLoop`.

        Returns
        -------
        vehdyn.simulation.compiled.CompiledModel
            The compiled rhs and output of the channels, their key and the gains as arguments.
        """
        from vehdyn.chassis import _chassis_numba

        return _chassis_numba.compiled_abs(self)

    def __repr__(self) -> str:
        return (f"<ABS of {self.vehicle.name!r}: apply below slip {self.apply_slip:g}, release above "
                f"{self.release_slip:g}, channels {self.channels}>")
