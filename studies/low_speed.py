"""Low speed: braking to standstill, launch with wheel spin, reverse driving and the kinematic limit.

The nonlinear single-track model with wheel-spin and tire-deflection (relaxation) states runs
through standstill without a singular slip definition: the tire deflections are driven by the slip
velocities and a low-speed damping fades in below 2 m/s (see vehdyn.handling.single_track). The
shipped sedan is used with the Fiala law built from its data (vehdyn.tire.tire_for_vehicle),
which keeps the stiff wheel-spin runs short; the Magic Formula behaves the same, more slowly.
Cases: (1) a locked-wheel stop from 20 m/s, against the closed-form stopping distance
u^2 / (2 mu g); (2) a launch from rest with more drive torque than the rear tires can carry,
against the traction limit a_x / g = mu a / (L - mu h) of a rear-driven car; the drive torque is
that of an engine of 100 kW (an assumed value: the vehicle files carry no engine data), at most
the 3000 N*m demand and at most P / omega at the wheel speed omega, built up with a 0.1-s lag - a
small controller Model in the loop (vehdyn.interconnect.ClosedLoop) - so the spinning wheel's speed is
held near P / F_x instead of running away as under a constant torque; (3) a slow turn forwards
and in reverse, against the kinematic single track r = u tan(delta) / L, v = b r.
"""

import numpy as np

import vehdyn
from vehdyn.interconnect import ClosedLoop
from vehdyn.handling import SingleTrack
from vehdyn.plotting import new_figure
from vehdyn.report import Study
from vehdyn.tire import tire_for_vehicle

G = vehdyn.units.GRAVITY
ENGINE_POWER = 100e3  # [W], assumed
TORQUE_LAG = 0.1  # [s]


class PowerLimitedDrive(vehdyn.Model):
    """Rear drive torque of an engine of power P: T -> min(T_demand, P / |omega|) with a first-order lag."""

    states = (vehdyn.Signal("engine_drive_torque", "N*m", "drive torque the engine delivers to the rear axle"),)
    inputs = (vehdyn.Signal("rear_drive_torque", "N*m", "driver's drive torque demand"),
              vehdyn.Signal("rear_wheel_speed", "rad/s", "rear wheel spin"))
    outputs = (vehdyn.Signal("rear_drive_torque", "N*m", "drive torque after the power limit"),)
    phenomena = frozenset({"longitudinal"})

    def __init__(self, power: float, lag: float):
        self.power, self.lag = power, lag

    def rhs(self, t, x, u):
        demand, omega = u
        available = np.minimum(demand, self.power / np.maximum(np.abs(omega), 1.0))
        return ((available - x[0]) / self.lag)[np.newaxis]

    def output(self, t, x, u):
        return x[:1]


def run(study: Study) -> None:
    import pandas as pd

    vehicle = vehdyn.load_vehicle("sedan")
    tires = (tire_for_vehicle(vehicle, "front", "fiala"), tire_for_vehicle(vehicle, "rear", "fiala"))
    model = SingleTrack(vehicle, *tires, wheel_spin=True)
    mu, radius = vehicle.tires.friction_coefficient, vehicle.tires.rolling_radius
    g = vehicle.geometry
    rows = []

    # (1) locked-wheel stop
    t = np.linspace(0, 4, 401)
    stop = vehdyn.simulate(model, t, {"front_brake_torque": 5000.0, "rear_brake_torque": 4000.0},
                           x0=model.straight_running(20.0), method="LSODA", rtol=1e-6, atol=1e-8)
    rows.append({"case": "locked-wheel stop from 20 m/s", "quantity": "stopping distance [m]",
                 "model": stop["x"][-1], "closed_form": 20.0**2 / (2 * mu * G)})
    # (2) launch with wheel spin
    engine = ClosedLoop(model, PowerLimitedDrive(ENGINE_POWER, TORQUE_LAG))
    x0 = np.concatenate([model.straight_running(0.0), [3000.0]])
    launch = vehdyn.simulate(engine, np.linspace(0, 3, 301), {"rear_drive_torque": 3000.0},
                             x0=x0, method="LSODA", rtol=1e-6, atol=1e-8)
    limit = mu * g.a / (g.wheelbase - mu * vehicle.mass.cg_height) * G
    rows.append({"case": "launch, 3000 N*m and 100 kW on the rear axle", "quantity": "peak a_x [m/s^2]",
                 "model": float(np.max(launch["longitudinal_acceleration"])), "closed_form": limit})
    # the spinning wheel settles where the engine's torque P / omega equals the tire's: omega R = P / F_x
    k = np.searchsorted(launch.time, 2.0)
    rows.append({"case": "launch, spinning rear wheel at 2 s", "quantity": "wheel speed omega R [m/s]",
                 "model": launch["rear_wheel_speed"][k] * radius,
                 "closed_form": ENGINE_POWER / launch["rear_longitudinal_force"][k]})
    # (3) slow turns forwards and in reverse (force mode)
    turning = SingleTrack(vehicle, *tires)
    steer = 0.35
    turns = {}
    for speed in (0.5, -0.5):
        drag = turning.parameters.drag_factor * speed * abs(speed)
        r = vehdyn.simulate(turning, np.linspace(0, 30, 301), {"front_steer_angle": steer,
                                                               "rear_longitudinal_force": drag},
                            x0=turning.straight_running(speed), method="LSODA", rtol=1e-9, atol=1e-11)
        turns[speed] = r
        u = r["longitudinal_velocity"][-1]
        rows.append({"case": f"turn at {speed:+g} m/s, steer {steer} rad", "quantity": "yaw rate [rad/s]",
                     "model": r["yaw_rate"][-1], "closed_form": u * np.tan(steer) / vehicle.wheelbase})

    fig, axes = new_figure(3, 2, height_per_row=2.4, width=10.0)
    axes[0, 0].plot(stop.time, stop["longitudinal_velocity"], label="vehicle u")
    axes[0, 0].plot(stop.time, stop["front_wheel_speed"] * radius, label="front wheel omega R")
    axes[0, 0].set_ylabel("speed [m/s]")
    axes[0, 0].set_title("locked-wheel stop")
    axes[0, 0].legend(fontsize=8)
    axes[1, 0].plot(stop.time, stop["front_longitudinal_force"] / 1e3, label="front")
    axes[1, 0].plot(stop.time, stop["rear_longitudinal_force"] / 1e3, label="rear")
    axes[1, 0].set_ylabel("tire force x [kN]")
    axes[1, 0].legend(fontsize=8)
    axes[2, 0].plot(stop.time, stop["x"])
    axes[2, 0].set_ylabel("distance [m]")
    axes[2, 0].set_xlabel("time [s]")
    axes[0, 1].plot(launch.time, launch["longitudinal_velocity"], label="vehicle u")
    axes[0, 1].plot(launch.time, launch["rear_wheel_speed"] * radius, label="rear wheel omega R")
    axes[0, 1].set_ylabel("speed [m/s]")
    axes[0, 1].set_title(f"launch: 3000 N*m, at most {ENGINE_POWER / 1e3:.0f} kW")
    axes[0, 1].legend(fontsize=8)
    axes[1, 1].plot(launch.time, launch["longitudinal_acceleration"], label="model")
    axes[1, 1].axhline(limit, color="0.4", ls=":", label="traction limit")
    axes[1, 1].set_ylabel("a_x [m/s^2]")
    axes[1, 1].legend(fontsize=8)
    for speed, r in turns.items():
        axes[2, 1].plot(r["x"], r["y"], label=f"u = {speed:+g} m/s")
    axes[2, 1].set_xlabel("x [m]")
    axes[2, 1].set_ylabel("y (SAE) [m]")
    axes[2, 1].set_aspect("equal", adjustable="datalim")
    axes[2, 1].legend(fontsize=8)
    study.figure(fig, "low_speed", caption="Stop, launch and slow turns of the sedan (Fiala tires, relaxation states); "
                 f"the launch torque is limited by an assumed engine power of {ENGINE_POWER / 1e3:.0f} kW")
    frame = pd.DataFrame(rows)
    frame["relative_difference"] = (frame["model"] - frame["closed_form"]) / np.abs(frame["closed_form"])
    study.table(frame, "checks", caption="Model against the closed forms")


if __name__ == "__main__":
    Study.main(run, __file__)
