"""Electronic stability control: yaw-rate control by braking one wheel, with a sideslip guard.

The yaw-rate reference is the steady-state response of the linear bicycle model to the driver's
steer angle (Rajamani, *Vehicle Dynamics and Control*, 2nd ed., 2012, sec. 8.4, eq. 8.55-8.57;
van Zanten, "Bosch ESP systems: 5 years of experience", SAE 2000-01-1633), limited by what the
road can give, |r| <= mu g / u::

    r_ref = clip(u delta / (L (1 + A u^2)), -mu g / u, mu g / u)     (A = K / L, Abe's stability factor)

A direct yaw moment acts on the yaw-rate error beyond a deadband and on the sideslip beyond a
limit (the guard that catches a slow spin the yaw rate alone misses)::

    M = s_v I_z [-k_r db(r - r_ref, e_0) + k_beta db(beta, beta_0)],   db(e, d) = e - clip(e, -d, d)

(SAE: M > 0 turns right; a spin to the right has r > 0 and beta < 0, so both terms oppose it;
s_v = sigmoid((u - v_min) / 1 m/s) keeps the ESC off at parking speeds.) One wheel makes it: an
oversteering car (M against the yaw rate) is braked at the OUTER FRONT wheel, an understeering one
(M with the yaw rate) at the INNER REAR wheel (van Zanten 2000). A brake force F_b on a wheel at
y = +-t/2 gives the yaw moment +-F_b t/2 (right wheel: M > 0) and the longitudinal force -F_b.
Each of the four wheel channels has a first-order hydraulic lag tau and is limited to the friction
of the wheel's static load, mu F_z,static R_e.

On the full vehicle (:class:`vehdyn.full_vehicle.FullVehicle`, ``corners=True``) the four channels
are added to the driver's brake torques of the four wheels (``brake_torque_front_left``, ...): the
braked wheel's own tire makes the yaw moment, with its friction-ellipse loss of side force.

The single-track model has one wheel per axle: it represents the braking of one wheel as the
equivalent yaw moment (input ``external_yaw_moment``) plus the longitudinal force of the axle
(``<axle>_longitudinal_force`` in force mode, ``<axle>_brake_torque`` with wheel spin). That
leaves out the friction-ellipse loss of side force at the braked wheel alone (its axle loses it
instead, in wheel-spin mode) and the yaw moment of the steered front wheel's side force change.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from vehdyn.params import Vehicle
from vehdyn.signals import Signal
from vehdyn.units import GRAVITY
from vehdyn.chassis.base import ChassisController, check_vehicle, deadband, sigmoid
from vehdyn.params.checks import check_gains

__all__ = ["ESC", "ESCGains", "reference_yaw_rate", "yaw_moment_demand", "wheel_torque_commands", "axle_commands"]

_WHEELS = ("front_left", "front_right", "rear_left", "rear_right")

ESCGains = namedtuple("ESCGains", ("wheelbase", "stability_factor", "yaw_inertia", "rolling_radius",
                                   "friction_coefficient", "yaw_rate_gain", "sideslip_gain", "yaw_rate_deadband",
                                   "sideslip_limit", "hydraulic_time_constant", "minimum_speed", "half_tracks",
                                   "torque_limits"))
ESCGains.__doc__ = """The numbers of the ESC law (SI), see :class:`ESC`.

Parameters
----------
wheelbase : float
    L [m].
stability_factor : float
    A [s^2/m^2] (Abe's stability factor, K / L).
yaw_inertia : float
    I_z [kg*m^2].
rolling_radius : float
    R_e [m].
friction_coefficient : float
    mu [-].
yaw_rate_gain : float
    k_r [1/s].
sideslip_gain : float
    k_beta [1/s^2].
yaw_rate_deadband : float
    e_0 [rad/s].
sideslip_limit : float
    beta_0 [rad].
hydraulic_time_constant : float
    tau [s].
minimum_speed : float
    v_min [m/s].
half_tracks : array_like
    t/2 of front_left, front_right, rear_left, rear_right [m].
torque_limits : array_like
    mu F_z,static R_e of the four wheels [N*m].
"""


def reference_yaw_rate(p, steer_angle, speed):
    r"""The yaw-rate reference: the linear bicycle's steady-state yaw rate, limited by :math:`\mu g / u`.

    .. math::

        r_{ref} = \mathrm{clip}\!\left(\frac{u \delta}{L (1 + A u^2)}, -\frac{\mu g}{\max(|u|, 1)},
        \frac{\mu g}{\max(|u|, 1)}\right)

    Parameters
    ----------
    p : ESCGains
        The law's numbers (:attr:`ESC.gains`).
    steer_angle : float or ndarray
        delta [rad], the driver's front road-wheel steer.
    speed : float or ndarray
        Forward speed u [m/s].

    Returns
    -------
    float or ndarray
        r_ref [rad/s].
    """
    u = np.maximum(np.abs(speed), 1.0)
    steady = speed * steer_angle / (p.wheelbase * (1.0 + p.stability_factor * speed**2))
    limit = p.friction_coefficient * GRAVITY / u
    return np.minimum(np.maximum(steady, -limit), limit)


def yaw_moment_demand(p, steer_angle, speed, lateral_velocity, yaw_rate):
    r"""The yaw moment the ESC asks for (SAE z: positive turns right).

    .. math::

        M = s_v I_z \left[-k_r\, \mathrm{db}(r - r_{ref}, e_0) + k_\beta\, \mathrm{db}(\beta, \beta_0)\right],
        \qquad \beta = \arctan(v / |u|)

    Parameters
    ----------
    p : ESCGains
        The law's numbers (:attr:`ESC.gains`).
    steer_angle : float or ndarray
        delta [rad].
    speed : float or ndarray
        Forward speed u [m/s].
    lateral_velocity : float or ndarray
        v [m/s].
    yaw_rate : float or ndarray
        r [rad/s].

    Returns
    -------
    float or ndarray
        M [N*m].
    """
    error = yaw_rate - reference_yaw_rate(p, steer_angle, speed)
    sideslip = np.arctan2(lateral_velocity, np.abs(speed))
    active = sigmoid((speed - p.minimum_speed) / 1.0)
    return active * p.yaw_inertia * (-p.yaw_rate_gain * deadband(error, p.yaw_rate_deadband)
                                     + p.sideslip_gain * deadband(sideslip, p.sideslip_limit))


def wheel_torque_commands(p, moment, yaw_rate):
    """Brake torque commands of the four wheels that make the yaw moment (one wheel at a time).

    An oversteering car (M against the yaw rate) is braked at the outer front wheel, an
    understeering one at the inner rear wheel (van Zanten 2000); a brake force F_b at y = +-t/2
    gives +-F_b t/2, so the torque is |M| R_e / (t/2), limited to mu F_z,static R_e.

    Parameters
    ----------
    p : ESCGains
        The law's numbers (:attr:`ESC.gains`).
    moment : float or ndarray
        M [N*m].
    yaw_rate : float or ndarray
        r [rad/s].

    Returns
    -------
    tuple of float or ndarray
        Brake torques [N*m] of front_left, front_right, rear_left, rear_right.
    """
    # oversteer: the moment opposes the yaw rate -> front outer wheel; understeer -> rear inner
    front = sigmoid(-np.tanh(yaw_rate / 0.02) * moment / 100.0)
    right, left = np.maximum(moment, 0.0), np.maximum(-moment, 0.0)
    radius, h, limit = p.rolling_radius, p.half_tracks, p.torque_limits
    return (np.minimum(front * left * radius / h[0], limit[0]), np.minimum(front * right * radius / h[1], limit[1]),
            np.minimum((1.0 - front) * left * radius / h[2], limit[2]),
            np.minimum((1.0 - front) * right * radius / h[3], limit[3]))


def axle_commands(p, wheel_spin, fl, fr, rl, rr, front_demand, rear_demand, moment_demand):
    """The single track's (front, rear, external_yaw_moment) with the ESC's wheel torques applied.

    Parameters
    ----------
    p : ESCGains
        The law's numbers (:attr:`ESC.gains`).
    wheel_spin : bool
        The plant takes axle brake torques (True) or axle longitudinal forces (False).
    fl, fr, rl, rr : float or ndarray
        The ESC's brake torques of the four wheels [N*m] (negative taken as 0).
    front_demand, rear_demand : float or ndarray
        The driver's axle brake torques [N*m] (``wheel_spin``) or longitudinal forces [N].
    moment_demand : float or ndarray
        The demanded ``external_yaw_moment`` [N*m].

    Returns
    -------
    tuple of float or ndarray
        (front, rear) axle brake torques [N*m] or forces [N], and the yaw moment [N*m].

    ``front_demand``, ``rear_demand`` are the axle brake torques (``wheel_spin``) or longitudinal forces.
    """
    fl, fr, rl, rr = np.maximum(fl, 0.0), np.maximum(fr, 0.0), np.maximum(rl, 0.0), np.maximum(rr, 0.0)
    radius, h = p.rolling_radius, p.half_tracks
    if wheel_spin:
        front, rear = np.maximum(front_demand, 0.0) + fl + fr, np.maximum(rear_demand, 0.0) + rl + rr
    else:
        front, rear = front_demand - (fl + fr) / radius, rear_demand - (rl + rr) / radius
    moment = moment_demand + (h[1] * fr - h[0] * fl + h[3] * rr - h[2] * rl) / radius
    return front, rear, moment



class ESC(ChassisController):
    r"""Electronic stability control of the :class:`~vehdyn.handling.SingleTrack` or the full vehicle.

    A yaw-rate reference from the linear bicycle's steady state, limited by the road, a direct
    yaw moment on the yaw-rate error beyond a deadband and on the sideslip beyond a limit, made by
    braking one wheel through a first-order hydraulic lag (module docstring):

    .. math::

        r_{ref} &= \mathrm{clip}\!\left(\frac{u \delta}{L (1 + A u^2)}, \pm\frac{\mu g}{u}\right), \qquad
        \mathrm{db}(e, d) = e - \mathrm{clip}(e, -d, d), \\
        M &= s_v I_z \left[-k_r\, \mathrm{db}(r - r_{ref}, e_0) + k_\beta\, \mathrm{db}(\beta, \beta_0)\right],
        \qquad s_v = \sigma\!\left(\frac{u - v_{min}}{1\ \mathrm{m/s}}\right), \\
        \tau \dot T_j &= T_{c,j}(M, r) - T_j, \qquad
        T_{c,j} = \min\!\left(\frac{|M| R_e}{t_j / 2}, \mu F_{z,j} R_e\right) \text{ on the wheel chosen}

    (the outer front wheel when oversteering, the inner rear wheel when understeering).

    Parameters
    ----------
    vehicle : Vehicle
        Mass, geometry, tracks, tires (mu, R_e) and the understeer gradient of its linear bicycle.
    wheel_spin : bool
        Command the plant's brake torques (``SingleTrack(..., wheel_spin=True)``) instead of its
        axle longitudinal forces (default False, the force mode).
    corners : bool
        Command the four wheel brake torques of :class:`~vehdyn.full_vehicle.FullVehicle`
        (``brake_torque_front_left``, ...; default False). ``wheel_spin`` is then not used.
    yaw_rate_gain : float
        k_r [1/s] (default 10).
    sideslip_gain : float
        k_beta [1/s^2] (default 50).
    yaw_rate_deadband : float
        e_0 [rad/s] (default 0.03).
    sideslip_limit : float
        beta_0 [rad] (default 0.07, 4 degrees).
    hydraulic_time_constant : float
        tau [s] (default 0.1).
    friction_coefficient : float, optional
        mu [-] of the reference limit and the wheel torque limit; default the vehicle's.
    minimum_speed : float
        v_min [m/s] (default 5).

    Signals
    -------
    states
        ``<wheel>_esc_brake_torque`` [N*m] for front_left, front_right, rear_left, rear_right.
    inputs
        demands ``front_steer_angle`` (read, not changed), ``front_longitudinal_force``,
        ``rear_longitudinal_force`` (or ``front_brake_torque``, ``rear_brake_torque``),
        ``external_yaw_moment`` (or, with ``corners``, ``brake_torque_front_left`` ...
        ``brake_torque_rear_right``); feedback ``longitudinal_velocity``, ``lateral_velocity``,
        ``yaw_rate``.
    outputs
        The longitudinal forces (or brake torques) and ``external_yaw_moment`` with the ESC's
        share; with ``corners`` the four wheel brake torques.

    References
    ----------
    .. [1] A. T. van Zanten, "Bosch ESP systems: 5 years of experience", SAE Technical Paper
       2000-01-1633, 2000 (the yaw-rate and sideslip control, the wheel braked).
    .. [2] R. Rajamani, *Vehicle Dynamics and Control*, 2nd ed., Springer, 2012, sec. 8.4,
       eq. 8.55-8.57 (the yaw-rate reference and its friction limit).
    .. [3] M. Abe, *Vehicle Handling Dynamics*, 2nd ed., Butterworth-Heinemann, 2015 (the
       stability factor).

    Examples
    --------
    >>> import vehdyn
    >>> from vehdyn import ClosedLoop
    >>> from vehdyn.chassis import ESC
    >>> from vehdyn.full_vehicle import FullVehicle
    >>> from vehdyn.handling import SingleTrack
    >>> car = vehdyn.load_vehicle("sedan")
    >>> ClosedLoop(SingleTrack(car), ESC(car)).output_names[-3:]
    ('front_longitudinal_force_after_esc', 'rear_longitudinal_force_after_esc', 'external_yaw_moment_after_esc')
    >>> ClosedLoop(FullVehicle(car), ESC(car, corners=True)).output_names[-1]
    'brake_torque_rear_right_after_esc'
    """

    def __init__(self, vehicle: Vehicle, *, wheel_spin: bool = False, corners: bool = False,
                 yaw_rate_gain: float = 10.0, sideslip_gain: float = 50.0, yaw_rate_deadband: float = 0.03,
                 sideslip_limit: float = 0.07, hydraulic_time_constant: float = 0.1,
                 friction_coefficient: float | None = None, minimum_speed: float = 5.0):
        check_vehicle("ESC", vehicle)
        from vehdyn.handling import stability_factor

        mu = vehicle.tires.friction_coefficient if friction_coefficient is None else friction_coefficient
        gains = check_gains("ESC", yaw_rate_gain=yaw_rate_gain, sideslip_gain=sideslip_gain,
                            yaw_rate_deadband=yaw_rate_deadband, sideslip_limit=sideslip_limit,
                            hydraulic_time_constant=hydraulic_time_constant, friction_coefficient=mu,
                            minimum_speed=minimum_speed,
                            positive=("hydraulic_time_constant", "friction_coefficient"),
                            nonnegative=("yaw_rate_gain", "sideslip_gain", "yaw_rate_deadband", "sideslip_limit",
                                         "minimum_speed"))
        self.__dict__.update(gains)
        self.vehicle, self.wheel_spin, self.corners = vehicle, bool(wheel_spin), bool(corners)
        g, t = vehicle.geometry, vehicle.tires
        self.wheelbase = float(g.wheelbase)
        self.stability_factor = float(stability_factor(vehicle))
        self.yaw_inertia = float(vehicle.mass.yaw_inertia)
        self.rolling_radius = float(t.rolling_radius)
        self.half_tracks = np.array([g.front_track, g.front_track, g.rear_track, g.rear_track]) / 2.0
        front, rear = vehicle.static_axle_loads(GRAVITY)
        self.torque_limits = (self.friction_coefficient * np.array([front, front, rear, rear]) / 2.0
                              * self.rolling_radius)
        if self.corners:
            commanded = [Signal(f"brake_torque_{w}", "N*m", f"brake torque of the {w.replace('_', ' ')} wheel")
                         for w in _WHEELS]
        else:
            axle_input = "brake_torque" if self.wheel_spin else "longitudinal_force"
            unit = "N*m" if self.wheel_spin else "N"
            commanded = [Signal(n, unit, f"{n.replace('_', ' ')}")
                         for n in (f"front_{axle_input}", f"rear_{axle_input}")]
            commanded.append(Signal("external_yaw_moment", "N*m", "yaw moment about the CG (SAE z)"))
        self.declare(
            states=[Signal(f"{w}_esc_brake_torque", "N*m", f"ESC brake torque on the {w.replace('_', ' ')} wheel")
                    for w in _WHEELS],
            inputs=[Signal("front_steer_angle", "rad", "driver's front road-wheel steer angle")] + commanded
            + [Signal("longitudinal_velocity", "m/s", "forward velocity u"),
               Signal("lateral_velocity", "m/s", "lateral velocity v (SAE)"),
               Signal("yaw_rate", "rad/s", "yaw rate r (SAE)")],
            outputs=commanded)

    @property
    def gains(self) -> ESCGains:
        """The numbers of the law as an :data:`ESCGains` (read from the attributes on every call)."""
        values = {name: getattr(self, name) for name in ESCGains._fields}
        values["half_tracks"] = tuple(float(v) for v in self.half_tracks)
        values["torque_limits"] = tuple(float(v) for v in self.torque_limits)
        return ESCGains(**values)

    def reference_yaw_rate(self, steer_angle, speed):
        """The yaw-rate reference (:func:`reference_yaw_rate`).

        Parameters
        ----------
        steer_angle : float or array_like
            delta [rad].
        speed : float or array_like
            Forward speed u [m/s].

        Returns
        -------
        float or ndarray
            r_ref [rad/s].
        """
        return reference_yaw_rate(self.gains, steer_angle, speed)

    def yaw_moment_demand(self, steer_angle, speed, lateral_velocity, yaw_rate):
        """The yaw moment the ESC asks for (:func:`yaw_moment_demand`; SAE z: positive turns right).

        Parameters
        ----------
        steer_angle : float or array_like
            delta [rad].
        speed : float or array_like
            Forward speed u [m/s].
        lateral_velocity : float or array_like
            v [m/s].
        yaw_rate : float or array_like
            r [rad/s].

        Returns
        -------
        float or ndarray
            M [N*m].
        """
        return yaw_moment_demand(self.gains, steer_angle, speed, lateral_velocity, yaw_rate)

    def wheel_torque_commands(self, moment, yaw_rate):
        """Brake torque commands of the four wheels (:func:`wheel_torque_commands`; one wheel at a time).

        Parameters
        ----------
        moment : float or array_like
            M [N*m].
        yaw_rate : float or array_like
            r [rad/s].

        Returns
        -------
        list
            Brake torques [N*m] of front_left, front_right, rear_left, rear_right.
        """
        return list(wheel_torque_commands(self.gains, moment, yaw_rate))

    def rhs(self, t, x, u):
        x, u = np.asarray(x, dtype=float), np.asarray(u, dtype=float)
        p = self.gains
        k = 5 if self.corners else 4  # the first feedback input
        moment = yaw_moment_demand(p, u[0], u[k], u[k + 1], u[k + 2])
        commands = wheel_torque_commands(p, moment, u[k + 2])
        return np.stack([(c - x[j]) / p.hydraulic_time_constant for j, c in enumerate(commands)])

    def output(self, t, x, u):
        x, u = np.asarray(x, dtype=float), np.asarray(u, dtype=float)
        if self.corners:
            return np.maximum(u[1:5], 0.0) + np.maximum(x, 0.0)
        return np.stack(axle_commands(self.gains, self.wheel_spin, *x, u[1], u[2], u[3]))

    def compiled_rhs(self):
        """The law compiled by numba (:mod:`vehdyn.chassis._chassis_numba`), for a compiled :class:`ClosedLoop`.

        Returns
        -------
        vehdyn.simulation.compiled.CompiledModel
            The compiled rhs and output of the four channels, their key and the gains as arguments.
        """
        from vehdyn.chassis import _chassis_numba

        return _chassis_numba.compiled_esc(self)

    def __repr__(self) -> str:
        commands = "wheel brake torques" if self.corners else "brake torques" if self.wheel_spin else "axle forces"
        return (f"<ESC of {self.vehicle.name!r}: k_r = {self.yaw_rate_gain:g} 1/s, k_beta = {self.sideslip_gain:g} "
                f"1/s^2, {commands}>")
