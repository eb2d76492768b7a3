"""ABS braking: stopping distance and deceleration on three roads, and steering while braking.

The sedan's wheel-spin single-track model (vehdyn.handling.SingleTrack with wheel_spin=True, on a
road of peak friction mu: friction=mu / the Magic Formula's own peak longitudinal friction at the
front tire's static load, applied to every tire by similarity) brakes
in a panic stop -- a brake-torque demand of 1.2 g, 70/30 front/rear, more than any of the roads can
take -- with the ABS of vehdyn.chassis (apply/hold/release pressure modulator with a hydraulic lag)
and without it. Reported per road (mu 0.9, 0.5, 0.2): the stopping distance, the mean fully
developed deceleration (MFDD, UN ECE R13-H Annex 4: between 0.8 v0 and 0.1 v0), the mean
deceleration v0 / t_stop and the friction limit's distance v0^2 / (2 mu g). The last 0.1 v0 is
extrapolated at the MFDD (below 2 m/s the ABS hands back to the driver anyway).

Steerability: on mu 0.5 the preview driver (vehdyn.driver.PreviewDriver) follows a 1.5 m swerve
(a smooth step over the friction-limited stopping distance) while the car brakes fully. With ABS the wheels keep rolling near the peak slip and keep
side force: the car follows the path. Without ABS the front wheels lock, the front axle has no
side force left and the car slides straight on whatever the driver does.

Every run uses compiled code (numba): the stops run the compiled closed loop of car and ABS
(vehdyn.interconnect.ClosedLoop); the two swerves run the preview driver in Python around that compiled loop or
the compiled car (ClosedLoop's plant_backend="compiled": two runs of 1-2 s, where compiling a loop of its own for
each cost about 15 s CPU). The stops from 100 km/h and the swerve from 80 km/h take a few seconds together (numpy:
about 2 minutes; without numba the study brakes from 40 km/h and swerves at 50 km/h unless run with --full).
"""

import numpy as np

import vehdyn
from vehdyn.simulation.compiled import numba_available
from vehdyn.chassis import ABS
from vehdyn.components.tire_setup import friction_ratio
from vehdyn.interconnect import ClosedLoop
from vehdyn.driver import PreviewDriver
from vehdyn.handling import SingleTrack
from vehdyn.plotting import new_figure
from vehdyn.report import Study
from vehdyn.tire import tire_for_vehicle

G = vehdyn.units.GRAVITY
OFFSET = 1.5  # [m] lateral offset of the swerve while braking


def plant_on(car, mu):
    ratio = friction_ratio(tire_for_vehicle(car, "front"), mu, 0.5 * car.static_axle_loads()[0])
    return SingleTrack(car, wheel_spin=True, friction=ratio)


def panic_demand(car):
    torque = 1.2 * car.mass.mass * G * car.tires.rolling_radius
    return {"front_brake_torque": 0.7 * torque, "rear_brake_torque": 0.3 * torque}


def stop(model, plant, speed, mu, demand):
    """Brake until the speed is below 0.1 v0, in pieces of the time the friction limit needs for 0.3 v0.

    Returns {signal: history} of time, speed, x, y and the wheel speeds (the slow crawl to rest, which
    the ABS leaves to the driver, is not simulated: stopping_metrics extrapolates it)."""
    x0 = model.state_vector(dict(zip(plant.state_names, plant.straight_running(speed))))
    piece, t0, parts = 0.3 * speed / (mu * G), 0.0, []
    while True:
        t = np.linspace(t0, t0 + piece, 60)
        r = vehdyn.simulate(model, t, demand, x0=x0, method="RK45", rtol=1e-4, atol=1e-6, max_step=0.05)
        parts.append({n: r[n] for n in ("speed", "x", "front_wheel_speed", "longitudinal_velocity")} | {"time": t})
        x0, t0 = r.final_state, t[-1]
        if r["speed"][-1] < 0.1 * speed or len(parts) > 10:
            return {n: np.concatenate([p[n][:-1] if k < len(parts) - 1 else p[n] for k, p in enumerate(parts)])
                    for n in parts[0]}


def stopping_metrics(r, v0):
    u, s, t = r["speed"], r["x"], r["time"]

    def cross(level):
        if not np.any(u < level):
            raise vehdyn.SimulationError(f"the car is still faster than {level:.2f} m/s at {t[-1]:.1f} s")
        k = int(np.argmax(u < level))
        return np.interp(level, [u[k], u[k - 1]], [s[k], s[k - 1]]), np.interp(level, [u[k], u[k - 1]], [t[k], t[k - 1]])
    (s_b, _), (s_e, t_e) = cross(0.8 * v0), cross(0.1 * v0)
    mfdd = ((0.8 * v0) ** 2 - (0.1 * v0) ** 2) / (2.0 * (s_e - s_b))
    tail = 0.1 * v0
    return s_e + tail**2 / (2 * mfdd), mfdd, v0 / (t_e + tail / mfdd)


def run(study: Study) -> None:
    import pandas as pd

    car = vehdyn.load_vehicle("sedan")
    heavy = study.full or numba_available()  # the numpy loops take minutes from 100 km/h
    speed = float(vehdyn.units.kmh_to_ms(100.0 if heavy else 40.0))
    demand = panic_demand(car)
    rows = []
    fig, axes = new_figure(2, 1, height_per_row=2.8)
    for mu in (0.9, 0.5, 0.2):
        plant = plant_on(car, mu)
        abs_ = ABS(car)
        for label, model in (("ABS", ClosedLoop(plant, abs_)), ("locked", plant)):
            r = stop(model, plant, speed, mu, demand)
            distance, mfdd, mean = stopping_metrics(r, speed)
            rows.append({"mu": mu, "brakes": label, "stopping_distance": distance, "mfdd_g": mfdd / G,
                         "mean_deceleration_g": mean / G, "friction_limit_distance": speed**2 / (2 * mu * G)})
            moving = r["speed"] > 0.1 * speed
            slip = abs_.braking_slip(r["front_wheel_speed"], r["longitudinal_velocity"])
            axes[0, 0].plot(r["time"][moving], slip[moving], label=f"mu {mu} {label}")
            axes[1, 0].plot(r["x"], r["longitudinal_velocity"] * 3.6, label=f"mu {mu} {label}")
    axes[0, 0].set_ylabel("front braking slip [-]")
    axes[0, 0].set_xlabel("time [s]")
    axes[1, 0].set_ylabel("speed [km/h]")
    axes[1, 0].set_xlabel("distance [m]")
    axes[0, 0].legend(fontsize=7, ncol=3)
    axes[0, 0].set_title(f"sedan: panic stop from {speed * 3.6:.0f} km/h")
    study.figure(fig, "straight_braking", caption="Front braking slip and speed over distance, with and without ABS")
    frame = pd.DataFrame(rows)
    frame.attrs["units"] = {"stopping_distance": "m", "mfdd_g": "g", "mean_deceleration_g": "g",
                            "friction_limit_distance": "m"}
    study.table(frame, "stopping", caption="Stopping distance, MFDD and mean deceleration (v0 / t_stop)")

    # steerability: full braking through a swerve on mu 0.5
    mu, speed = 0.5, float(vehdyn.units.kmh_to_ms(80.0 if heavy else 50.0))
    plant = plant_on(car, mu)
    path_x = np.linspace(-10.0, 200.0, 421)
    start, length = 2.0, speed**2 / (2 * mu * G)  # the swerve takes the whole friction-limited stopping distance
    ramp = np.clip((path_x - start) / length, 0.0, 1.0)
    path_y = -OFFSET * ramp**2 * (3 - 2 * ramp)
    driver = PreviewDriver(path_x, path_y, wheelbase=car.geometry.wheelbase, preview_time=0.6, lag=0.1)
    fig, axes = new_figure(1, 1, height_per_row=3.2)
    ax = axes[0, 0]
    near = path_x < 1.3 * (start + length)
    ax.plot(path_x[near], path_y[near], "k--", label="path")
    rows = []
    for label, model in (("ABS", ClosedLoop(plant, ABS(car))), ("locked", plant)):
        loop = ClosedLoop(model, driver, plant_backend="compiled" if numba_available() else "numpy")
        x0 = loop.state_vector(dict(zip(plant.state_names, plant.straight_running(speed))))
        t = np.linspace(0.0, 0.9 * speed / (0.7 * mu * G), 300)
        r = vehdyn.simulate(loop, t, demand, x0=x0, method="RK45", rtol=1e-4, atol=1e-6, max_step=0.05,
                            backend="numpy")
        moving = r["longitudinal_velocity"] > 0.5
        error = r["y"] - np.interp(r["x"], path_x, path_y)
        rows.append({"brakes": label, "final_lateral_offset": float(r["y"][moving][-1]),
                     "max_path_error": float(np.max(np.abs(error[moving]))),
                     "max_driver_steer_deg": float(np.degrees(np.max(np.abs(r["driver_steer_angle"]))))})
        ax.plot(r["x"][moving], r["y"][moving], label=label)
    ax.invert_yaxis()  # SAE y to the right: draw it downwards so that the plan view is as seen from above
    ax.set_xlabel("X [m]")
    ax.set_ylabel("Y [m] (SAE, right)")
    ax.legend(fontsize=8)
    ax.set_title(f"swerve while braking fully, mu {mu}, from {speed * 3.6:.0f} km/h")
    study.figure(fig, "steerability", caption="Path of the CG with ABS and with locked wheels (plan view)")
    frame = pd.DataFrame(rows)
    frame.attrs["units"] = {"final_lateral_offset": "m", "max_path_error": "m", "max_driver_steer_deg": "deg"}
    study.table(frame, "steerability", caption=f"Swerve ({OFFSET} m to the left) during full braking")
    abs_row, locked = rows
    study.text(f"With ABS the car follows the path until it stops (largest path error "
               f"{abs_row['max_path_error']:.2f} m, at rest {abs(abs_row['final_lateral_offset']):.2f} m to the side); "
               f"with locked wheels it slides on ({locked['max_path_error']:.2f} m off the path, at rest "
               f"{abs(locked['final_lateral_offset']):.2f} m to the side) although the driver steers up to "
               f"{locked['max_driver_steer_deg']:.0f} deg.")


if __name__ == "__main__":
    Study.main(run, __file__)
