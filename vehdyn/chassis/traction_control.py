"""Traction control: drive-torque reduction and brake intervention on a spinning driven axle.

A traction control system limits the drive slip of the driven wheels in two ways: it asks the
engine for less torque (slow: throttle, ignition and injection cut) when the driven wheels spin
together, and it brakes a wheel that spins alone (fast: the ESC hydraulics) (Bosch, *Automotive
Handbook*, 10th ed., 2018, "Traction control system"; Rajamani, *Vehicle Dynamics and Control*,
2nd ed., 2012, sec. 6.5). With one channel per driven axle (single track) or driven wheel (full
vehicle, ``corners=True``)::

    lambda_i = (omega_i R_e - u) / max(u, u_min)                  drive slip (> 0 spinning)
    d(rho)/dt = (sigmoid((mean_i lambda_i - lambda_t) / w) - rho) / tau_e   engine reduction 0..1
    d(T_b,i)/dt = (k_b T_d,i max(lambda_i - lambda_b, 0) / lambda_b - T_b,i) / tau_b
    T_drive,i = (1 - rho_max rho) T_d,i,    T_brake,i = T_brake,demand,i + T_b,i

with the demands T_d,i >= 0, sigmoid(z) = (1 + tanh z) / 2, rho_max <= 1 the largest reduction the
engine allows and lambda_b > lambda_t the slip above which the brakes join in. The engine is one:
its reduction follows the mean slip of the channels, so a single spinning wheel on split mu is
braked rather than the whole drive cut.

A single-track model lumps the two wheels of an axle, so it cannot represent a split-mu road; its
brake intervention brakes the whole axle. Split mu needs the full vehicle
(:class:`vehdyn.full_vehicle.FullVehicle` with a ``friction(X, Y)`` road). The full vehicle takes
one drive torque per wheel, with no differential: equal demands on the two sides stand for an open
differential with a torque-source engine, so braking the spinning wheel does not send torque to
the other (that coupling needs a driveline model).
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.params import Vehicle
from vehdyn.signals import Signal
from vehdyn.chassis.base import ChassisController, channel_signals, check_vehicle, sigmoid
from vehdyn.params.checks import check_gains

__all__ = ["TractionControl", "TractionGains", "drive_slip", "reduction_rate", "brake_rate", "applied_torques"]

_AXLES = ("front", "rear")

TractionGains = namedtuple("TractionGains", ("rolling_radius", "target_slip", "brake_slip", "slip_width",
                                             "engine_time_constant", "brake_time_constant", "brake_gain",
                                             "maximum_reduction", "minimum_speed"))
TractionGains.__doc__ = """The numbers of the traction-control law (SI), see :class:`TractionControl`.

Parameters
----------
rolling_radius : float
    R_e [m].
target_slip, brake_slip : float
    lambda_t, lambda_b [-].
slip_width : float
    w [-] of the smooth switch.
engine_time_constant, brake_time_constant : float
    tau_e, tau_b [s].
brake_gain : float
    k_b [-].
maximum_reduction : float
    rho_max [-].
minimum_speed : float
    u_min [m/s] of the slip's denominator.
"""


def drive_slip(p, wheel_speed, speed):
    r"""The drive slip :math:`\lambda_s = (\omega R_e - u) / \max(u, u_{min})` (positive spinning).

    Parameters
    ----------
    p : TractionGains
        The law's numbers (:attr:`TractionControl.gains`).
    wheel_speed : float or ndarray
        omega [rad/s].
    speed : float or ndarray
        Forward speed u [m/s].

    Returns
    -------
    float or ndarray
        lambda_s [-].
    """
    return (wheel_speed * p.rolling_radius - speed) / np.maximum(speed, p.minimum_speed)


def reduction_rate(p, reduction, mean_slip):
    r"""The rate of the engine's torque reduction at the channels' mean drive slip.

    .. math::

        \dot\rho = \left[\sigma\!\left(\frac{\bar\lambda - \lambda_t}{w}\right) - \rho\right] / \tau_e

    Parameters
    ----------
    p : TractionGains
        The law's numbers (:attr:`TractionControl.gains`).
    reduction : float or ndarray
        rho [-], the state.
    mean_slip : float or ndarray
        The channels' mean drive slip [-].

    Returns
    -------
    float or ndarray
        d(rho)/dt [1/s].
    """
    return (sigmoid((mean_slip - p.target_slip) / p.slip_width) - reduction) / p.engine_time_constant


def brake_rate(p, brake, demand, slip):
    r"""The rate of one channel's brake intervention.

    .. math::

        \tau_b \dot T_b = k_b \max(T_d, 0) \frac{\max(\lambda - \lambda_b, 0)}{\lambda_b} - T_b

    Parameters
    ----------
    p : TractionGains
        The law's numbers (:attr:`TractionControl.gains`).
    brake : float or ndarray
        T_b [N*m], the state.
    demand : float or ndarray
        The drive-torque demand T_d [N*m].
    slip : float or ndarray
        The channel's drive slip [-].

    Returns
    -------
    float or ndarray
        d(T_b)/dt [N*m/s].
    """
    target = p.brake_gain * np.maximum(demand, 0.0) * np.maximum(slip - p.brake_slip, 0.0) / p.brake_slip
    return (target - brake) / p.brake_time_constant


def applied_torques(p, reduction, brake, drive_demand, brake_demand):
    r"""The drive and brake torques applied to one channel.

    .. math::

        T_{drive} = (1 - \rho_{max}\, \mathrm{clip}(\rho, 0, 1)) \max(T_d, 0), \qquad
        T_{brake} = \max(T_{brake,d}, 0) + \max(T_b, 0)

    Parameters
    ----------
    p : TractionGains
        The law's numbers (:attr:`TractionControl.gains`).
    reduction : float or ndarray
        rho [-].
    brake : float or ndarray
        T_b [N*m], the intervention.
    drive_demand, brake_demand : float or ndarray
        The demands T_d and T_brake,d [N*m].

    Returns
    -------
    tuple of float or ndarray
        (drive, brake) torques [N*m].
    """
    drive = (1.0 - p.maximum_reduction * np.minimum(np.maximum(reduction, 0.0), 1.0)) * np.maximum(drive_demand, 0.0)
    return drive, np.maximum(brake_demand, 0.0) + np.maximum(brake, 0.0)


class TractionControl(ChassisController):
    r"""Traction control of a wheel-spin single track or the full vehicle: engine reduction and brake intervention.

    With one channel per driven axle (or driven wheel with ``corners``), the engine's torque
    reduction :math:`\rho` follows the channels' mean drive slip, and each channel's brakes join
    in above a higher slip (module docstring):

    .. math::

        \lambda_i &= \frac{\omega_i R_e - u}{\max(u, u_{min})}, \qquad
        \tau_e \dot\rho = \sigma\!\left(\frac{\bar\lambda - \lambda_t}{w}\right) - \rho, \\
        \tau_b \dot T_{b,i} &= k_b T_{d,i} \frac{\max(\lambda_i - \lambda_b, 0)}{\lambda_b} - T_{b,i}, \qquad
        T_{drive,i} = (1 - \rho_{max} \rho) T_{d,i}, \quad T_{brake,i} = T_{brake,d,i} + T_{b,i}

    Parameters
    ----------
    vehicle : Vehicle
        Gives R_e and the driven axles (``driveline.front_drive_fraction``: > 0 front, < 1 rear).
    target_slip : float
        lambda_t [-] where the torque reduction is half way (default 0.08).
    brake_slip : float
        lambda_b [-] above which the brakes intervene (default 0.15), > target_slip.
    slip_width : float
        w [-] of the smooth switch (default 0.02).
    engine_time_constant : float
        tau_e [s] (default 0.15 s).
    brake_time_constant : float
        tau_b [s] of the hydraulic lag (default 0.05 s).
    brake_gain : float
        k_b [-]: brake torque per unit demand per unit slip excess (relative to lambda_b), default 1.
    maximum_reduction : float
        rho_max [-] in (0, 1] (default 0.95).
    minimum_speed : float
        u_min [m/s] of the slip's denominator (default 1 m/s).
    axles : tuple of str, optional
        Controlled axles; default the driven ones.
    corners : bool
        One channel per driven wheel with the full vehicle's names (``drive_torque_rear_left``,
        ``brake_torque_rear_left``, ``wheel_speed_rear_left``, ...) instead of one per axle with the
        single track's (``rear_drive_torque``, ``rear_brake_torque``, ``rear_wheel_speed``).

    Signals
    -------
    states
        ``engine_torque_reduction`` [-], ``<channel>_tcs_brake_torque`` [N*m].
    inputs
        demands (drive and brake torque per channel); feedback the wheel speeds and
        ``longitudinal_velocity``.
    outputs
        The drive and brake torques applied per channel.

    References
    ----------
    .. [1] Robert Bosch GmbH, *Automotive Handbook*, 10th ed., 2018, "Traction control system"
       (engine intervention and brake intervention on a spinning wheel).
    .. [2] R. Rajamani, *Vehicle Dynamics and Control*, 2nd ed., Springer, 2012, sec. 6.5.
    """

    def __init__(self, vehicle: Vehicle, *, target_slip: float = 0.08, brake_slip: float = 0.15,
                 slip_width: float = 0.02, engine_time_constant: float = 0.15, brake_time_constant: float = 0.05,
                 brake_gain: float = 1.0, maximum_reduction: float = 0.95, minimum_speed: float = 1.0, axles=None,
                 corners: bool = False):
        check_vehicle("TractionControl", vehicle)
        gains = check_gains("TractionControl", target_slip=target_slip, brake_slip=brake_slip, slip_width=slip_width,
                            engine_time_constant=engine_time_constant, brake_time_constant=brake_time_constant,
                            brake_gain=brake_gain, maximum_reduction=maximum_reduction, minimum_speed=minimum_speed,
                            positive=("target_slip", "brake_slip", "slip_width", "engine_time_constant",
                                      "brake_time_constant", "maximum_reduction", "minimum_speed"),
                            nonnegative=("brake_gain",))
        if gains["brake_slip"] <= gains["target_slip"]:
            raise ParameterError(f"TractionControl brake_slip must exceed target_slip ({target_slip}), got "
                                 f"{brake_slip!r}", key="brake_slip", value=brake_slip)
        if gains["maximum_reduction"] > 1:
            raise ParameterError(f"TractionControl maximum_reduction must be <= 1, got {maximum_reduction!r}",
                                 key="maximum_reduction", value=maximum_reduction)
        if axles is None:
            share = float(vehicle.driveline.front_drive_fraction)
            axles = tuple(a for a, s in zip(_AXLES, (share, 1.0 - share)) if s > 0)
        self.__dict__.update(gains)
        self.vehicle, self.axles, self.corners = vehicle, axles, bool(corners)
        self.rolling_radius = float(vehicle.tires.rolling_radius)
        self.channels, names = channel_signals("TractionControl", axles, self.corners,
                                               ("drive_torque", "brake_torque", "wheel_speed"))
        self.declare(
            states=[Signal("engine_torque_reduction", "-", "share of the drive demand the engine withholds")]
            + [Signal(f"{c}_tcs_brake_torque", "N*m", f"brake torque of the traction control on {c}")
               for c in self.channels],
            inputs=[Signal(n, "N*m", "drive torque demand") for n in names["drive_torque"]]
            + [Signal(n, "N*m", "driver's brake torque demand") for n in names["brake_torque"]]
            + [Signal(n, "rad/s", "wheel spin") for n in names["wheel_speed"]]
            + [Signal("longitudinal_velocity", "m/s", "forward velocity u")],
            outputs=[Signal(n, "N*m", "drive torque after the engine reduction") for n in names["drive_torque"]]
            + [Signal(n, "N*m", "brake torque with the intervention") for n in names["brake_torque"]])

    @property
    def gains(self) -> TractionGains:
        """The numbers of the law as a :data:`TractionGains` (read from the attributes on every call)."""
        return TractionGains(*(getattr(self, name) for name in TractionGains._fields))

    def drive_slip(self, wheel_speed, speed):
        """The drive slip lambda_s = (omega R_e - u) / max(u, u_min) (:func:`drive_slip`).

        Parameters
        ----------
        wheel_speed : float or array_like
            omega [rad/s].
        speed : float or array_like
            Forward speed u [m/s].

        Returns
        -------
        float or ndarray
            lambda_s [-] (positive spinning).
        """
        return drive_slip(self.gains, wheel_speed, speed)

    def rhs(self, t, x, u):
        n = len(self.channels)
        x, u = np.asarray(x, dtype=float), np.asarray(u, dtype=float)
        p = self.gains
        slip = drive_slip(p, u[2 * n:3 * n], u[3 * n])
        mean = slip[0]
        for k in range(1, n):  # the compiled law's order of summation
            mean = mean + slip[k]
        d_reduction = reduction_rate(p, x[0], mean / n)
        return np.concatenate([np.asarray(d_reduction)[None], brake_rate(p, x[1:], u[:n], slip)])

    def output(self, t, x, u):
        n = len(self.channels)
        x, u = np.asarray(x, dtype=float), np.asarray(u, dtype=float)
        return np.concatenate(applied_torques(self.gains, x[0], x[1:], u[:n], u[n:2 * n]))

    def compiled_rhs(self):
        """The law compiled by numba (:mod:`vehdyn.chassis._chassis_numba`), for a compiled :class:`ClosedLoop`.

        Returns
        -------
        vehdyn.simulation.compiled.CompiledModel
            The compiled rhs and output of the channels, their key and the gains as arguments.
        """
        from vehdyn.chassis import _chassis_numba

        return _chassis_numba.compiled_traction_control(self)

    def __repr__(self) -> str:
        return f"<TractionControl of {self.vehicle.name!r}: target slip {self.target_slip:g}, channels {self.channels}>"
