"""Traction control: drive-torque reduction and brake intervention on a spinning driven axle.

A traction control system limits the drive slip of the driven wheels in two ways: it asks the
engine for less torque (slow: throttle, ignition and injection cut) and it brakes the spinning
wheel (fast: the ESC hydraulics) (Bosch, *Automotive Handbook*, 10th ed., 2018, "Traction control
system"; Rajamani, *Vehicle Dynamics and Control*, 2nd ed., 2012, sec. 6.5). Per driven axle::

    lambda_s = (omega R_e - u) / max(u, u_min)                  drive slip (> 0 spinning)
    d(rho)/dt = (sigmoid((lambda_s - lambda_t) / w) - rho) / tau_e   torque reduction 0..1
    d(T_b)/dt = (k_b T_d max(lambda_s - lambda_b, 0) / lambda_b - T_b) / tau_b
    T_drive = (1 - rho_max rho) T_d,    T_brake = T_brake,demand + T_b

with the demand T_d >= 0, sigmoid(z) = (1 + tanh z) / 2, rho_max < 1 the largest reduction the
engine allows and lambda_b > lambda_t the slip above which the brakes join in.

A single-track model lumps the two wheels of an axle, so it cannot represent a split-mu road
(different friction left and right); its brake intervention brakes the whole axle and so acts as a
second, faster torque reduction. On split mu, braking the spinning wheel transfers torque across
an open differential to the wheel on high friction; that needs the per-wheel model
(:class:`vehdyn.full_vehicle.FullVehicle`), which this controller does not drive yet.
"""

from __future__ import annotations

import numpy as np

from ..errors import ParameterError
from ..params import Vehicle
from ..signals import Signal
from .closed_loop import ChassisController, check_gains, check_vehicle, sigmoid

__all__ = ["TractionControl"]

_AXLES = ("front", "rear")


class TractionControl(ChassisController):
    """Traction control of a wheel-spin :class:`~vehdyn.handling.SingleTrack` (module docstring).

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

    Signals
    -------
    states
        ``<axle>_torque_reduction`` [-], ``<axle>_tcs_brake_torque`` [N*m].
    inputs
        demands ``<axle>_drive_torque``, ``<axle>_brake_torque``; feedback ``<axle>_wheel_speed``,
        ``longitudinal_velocity``.
    outputs
        ``<axle>_drive_torque``, ``<axle>_brake_torque`` applied.
    """

    def __init__(self, vehicle: Vehicle, *, target_slip: float = 0.08, brake_slip: float = 0.15,
                 slip_width: float = 0.02, engine_time_constant: float = 0.15, brake_time_constant: float = 0.05,
                 brake_gain: float = 1.0, maximum_reduction: float = 0.95, minimum_speed: float = 1.0, axles=None):
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
        axles = tuple(axles)
        if not axles or any(a not in _AXLES for a in axles) or len(set(axles)) != len(axles):
            raise ParameterError(f"TractionControl axles must be distinct names from {_AXLES}, got {axles!r}",
                                 key="axles", value=axles)
        self.__dict__.update(gains)
        self.vehicle, self.axles = vehicle, axles
        self.rolling_radius = float(vehicle.tires.rolling_radius)
        self.declare(
            states=[Signal(f"{a}_torque_reduction", "-", f"share of the {a} drive demand the engine withholds")
                    for a in axles]
            + [Signal(f"{a}_tcs_brake_torque", "N*m", f"brake torque of the traction control on the {a} axle")
               for a in axles],
            inputs=[Signal(f"{a}_drive_torque", "N*m", f"drive torque demand on the {a} axle") for a in axles]
            + [Signal(f"{a}_brake_torque", "N*m", f"driver's brake torque demand on the {a} axle") for a in axles]
            + [Signal(f"{a}_wheel_speed", "rad/s", f"spin of the {a} wheels") for a in axles]
            + [Signal("longitudinal_velocity", "m/s", "forward velocity u")],
            outputs=[Signal(f"{a}_drive_torque", "N*m", f"drive torque on the {a} axle after the reduction")
                     for a in axles]
            + [Signal(f"{a}_brake_torque", "N*m", f"brake torque on the {a} axle with the intervention")
               for a in axles])

    def drive_slip(self, wheel_speed, speed):
        """lambda_s = (omega R_e - u) / max(u, u_min) [-] (positive spinning)."""
        return (wheel_speed * self.rolling_radius - speed) / np.maximum(speed, self.minimum_speed)

    def rhs(self, t, x, u):
        n = len(self.axles)
        x, u = np.asarray(x, dtype=float), np.asarray(u, dtype=float)
        reduction, brake = x[:n], x[n:]
        demand = np.maximum(u[:n], 0.0)
        slip = self.drive_slip(u[2 * n:3 * n], u[3 * n])
        d_reduction = (sigmoid((slip - self.target_slip) / self.slip_width) - reduction) / self.engine_time_constant
        target = self.brake_gain * demand * np.maximum(slip - self.brake_slip, 0.0) / self.brake_slip
        d_brake = (target - brake) / self.brake_time_constant
        return np.concatenate([d_reduction, d_brake])

    def output(self, t, x, u):
        n = len(self.axles)
        x, u = np.asarray(x, dtype=float), np.asarray(u, dtype=float)
        reduction = np.clip(x[:n], 0.0, 1.0)
        drive = (1.0 - self.maximum_reduction * reduction) * np.maximum(u[:n], 0.0)
        brake = np.maximum(u[n:2 * n], 0.0) + np.maximum(x[n:], 0.0)
        return np.concatenate([drive, brake])

    def __repr__(self) -> str:
        return f"<TractionControl of {self.vehicle.name!r}: target slip {self.target_slip:g}, axles {self.axles}>"
