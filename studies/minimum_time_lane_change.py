"""Minimum-time lane change: the fastest ISO 3888-2 passage planned on the single track, replayed on the full vehicle.

The planner's model is the nonlinear single track with its Magic Formula tires (vehdyn.handling.SingleTrack,
force mode, no tire lag; the same problem is solved with tire lag too, at 1 m node spacing), made a CasADi function from the same
equations the simulations run (vehdyn.symbolic.to_casadi). vehdyn.optimal.minimum_time_lane_change transcribes
the ISO 3888-2 obstacle-avoidance track by direct multiple shooting along the earth x (nodes 0.5 m apart and on every
lane edge, 1 m in quick mode; the cones narrowed by 2 cm and held at the nodes) and IPOPT chooses the
entry speed and the road-wheel steer (|delta| <= 0.35 rad, |d delta/dt| <= 1 rad/s) that pass the
coned lanes in the least time, throttle released at the entry as the standard prescribes, from a cold
start (straight running at the middle of the speed bracket, zero steer).

The optimal steer is then replayed open loop, as a function of time: on the planner's model itself (the
transcription's error), on the single track with tire lag, and on the full vehicle (vehdyn.full_vehicle,
with its roll, load transfer, tire lag, wheel spin and suspension) -- the fidelity ladder's question
asked of a planner's model: does the plan still clear the cones on the car? The best closed-loop driver
(MacAdam's optimal preview driver, a sweep of line, preview time and gain; vehdyn.procedures.lane_change_limit)
gives the reference a driver model reaches on the same single track.

Second, the same single track inside a nonlinear model-predictive controller (vehdyn.optimal.PathTrackingNMPC:
20 steps of 0.1 s, warm started, |delta| <= 0.5 rad, |d delta/dt| <= 1 rad/s) closes the loop on the full vehicle
through the ISO 3888-1 double lane change with the speed held (least-curvature line through the lanes narrowed by
0.15 m), against the crossover driver tuned at each speed: the loop runs in Python (the controller calls IPOPT), RK4
at 5 ms, the full vehicle's compiled code called point by point (ClosedLoop's plant_backend="compiled"); the solve
time per step, the tracking error and what each loop costs (the driver's loop also in Python around the car's
compiled code).
"""

import time

import numpy as np

import vehdyn
from vehdyn.driver import CrossoverDriver, OptimalPreviewDriver
from vehdyn.interconnect import ClosedLoop
from vehdyn.full_vehicle import FullVehicle
from vehdyn.handling import SingleTrack
from vehdyn.optimal import PathTrackingNMPC, minimum_time_lane_change, passage_time
from vehdyn.plotting import new_figure
from vehdyn.procedures import double_lane_change_track, lane_change_limit, lane_change_outcome, obstacle_avoidance_track
from vehdyn.report import Study


def replay(model, solution, x0, inputs=None):
    """The optimum's steer replayed open loop on ``model`` from ``x0`` (RK45, 5 ms output grid)."""
    t = np.arange(0.0, 1.05 * solution.time[-1], 0.005)
    return vehdyn.simulate(model, t, {**(inputs or {}), **solution.input_signals()}, x0=x0, method="RK45",
                           rtol=1e-8, atol=1e-10)


def run(study: Study) -> None:
    import importlib.util

    import pandas as pd

    if importlib.util.find_spec("casadi") is None:
        study.text("The optimal-control problems need CasADi (with its IPOPT), which is not installed here: "
                   'pip install "vehdyn[optimal]" and run this study again.')
        return
    car = vehdyn.load_vehicle("sedan")
    width = max(car.geometry.front_track, car.geometry.rear_track) + 0.2
    track = obstacle_avoidance_track(width)
    planner = SingleTrack(car, tire_lag=False)
    spacing = 1.0 if study.quick else 0.5
    start = time.perf_counter()
    optimum = minimum_time_lane_change(planner, track, spacing=spacing)
    wall = time.perf_counter() - start
    entry = optimum.entry_speed
    # the same problem on the single track with tire lag (its transient slips bounded to 0.98 of the peak-force
    # slip, where the force's switch to the kinematic slip lies: minimum_time_lane_change's deflection_limit),
    # at 1 m in both modes: at 0.5 m IPOPT ends at its 1000 iterations with a 1e-7 m continuity gap in a
    # lateral deflection at that bound
    lagged = SingleTrack(car, tire_lag=True)
    start = time.perf_counter()
    optimum_lag = minimum_time_lane_change(lagged, track, spacing=1.0)
    wall_lag = time.perf_counter() - start
    # the optimum flicks the steer (+7 deg, then -11 deg) in the run-in before the first lane: a time-optimal
    # set-up, not an artefact of a flat cost; a heavier steer-rate weight (0.1 s against 1e-4 s) calms it, at a price
    calm = minimum_time_lane_change(planner, track, spacing=spacing, steer_rate_weight=0.1)

    rows, runs = [], {}

    def score(label, result):
        outcome = lane_change_outcome(track, result)
        deviation = np.max(np.abs(np.interp(optimum.grid, result["x"], result["y"]) - optimum["y"]))
        rows.append({"model": label, "passage_time_s": passage_time(result, track),
                     "worst_cone_margin_m": outcome["worst_margin"], "passed": outcome["passed"],
                     "max_path_deviation_m": deviation})
        runs[label] = result

    score("single track (the planner's model)", replay(planner, optimum, optimum.states[:, 0]))
    score("single track with tire lag", replay(lagged, optimum, lagged.straight_running(entry, x=optimum.grid[0])))
    full = FullVehicle(car)
    x0, u0 = full.trim(entry)
    x0 = np.array(x0, dtype=float)
    x0[full.index("x")] = optimum.grid[0]
    held = {name: (0.0 if "drive_torque" in name else value) for name, value in zip(full.input_names, u0)}
    score("full vehicle", replay(full, optimum, x0, held))

    # the closed-loop driver on the planner's model: the best tuning's highest passing entry speed
    paths = {"centre": (track.path_x, track.path_y), "least curvature": track.least_curvature_line(0.15)}
    if study.quick:
        tunings, resolution = [{"line": "least curvature", "preview_time": 0.5, "gain": 1.0}], 1.0
    else:
        tunings = [{"line": line, "preview_time": p, "gain": g} for line in paths for p in (0.5, 0.8)
                   for g in (1.0, 1.5)]
        resolution = 0.25

    def make(speed, line, **tuning):
        return OptimalPreviewDriver(*paths[line], vehicle=car, speed=speed, delay=0.1, **tuning)

    limit = lane_change_limit(planner, track, make, tunings, throttle="release", speeds=(8.0, 40.0),
                              resolution=resolution)
    driver_time = passage_time(limit["passing"][0], track) if limit["passing"] else np.nan

    summary = pd.DataFrame([
        {"method": "minimum time (IPOPT, single track)", "entry_speed_kmh": entry * 3.6,
         "passage_time_s": optimum.passage_time, "iterations": optimum.iterations, "solve_time_s": optimum.solve_time,
         "wall_time_s": wall, "intervals": optimum.problem.intervals},
        {"method": "minimum time, steer-rate weight 0.1 s (IPOPT, single track)",
         "entry_speed_kmh": calm.entry_speed * 3.6, "passage_time_s": calm.passage_time,
         "iterations": calm.iterations, "solve_time_s": calm.solve_time, "wall_time_s": np.nan,
         "intervals": calm.problem.intervals},
        {"method": "minimum time (IPOPT, single track with tire lag)", "entry_speed_kmh": optimum_lag.entry_speed * 3.6,
         "passage_time_s": optimum_lag.passage_time, "iterations": optimum_lag.iterations,
         "solve_time_s": optimum_lag.solve_time, "wall_time_s": wall_lag, "intervals": optimum_lag.problem.intervals},
        {"method": f"best closed-loop driver ({len(tunings)} tunings)", "entry_speed_kmh": limit["speed"] * 3.6,
         "passage_time_s": driver_time, "iterations": limit["runs"], "solve_time_s": np.nan, "wall_time_s": np.nan,
         "intervals": np.nan}]).set_index("method")
    summary.attrs["units"] = {"entry_speed_kmh": "km/h", "passage_time_s": "s", "iterations": "- (runs for the driver)",
                              "solve_time_s": "s", "wall_time_s": "s (with building the program)"}
    study.table(summary, "optimum", caption="The fastest ISO 3888-2 passage of the sedan's single track (lanes 1 to 5, "
                "throttle released at the entry) against the best closed-loop driver on the same model")
    frame = pd.DataFrame(rows).set_index("model")
    frame.attrs["units"] = {"passage_time_s": "s", "worst_cone_margin_m": "m", "max_path_deviation_m": "m"}
    study.table(frame, "replays", caption="The optimal steer replayed open loop: cone margin (negative: a cone hit) "
                "and "
                "the largest lateral deviation from the planned path")
    full_row = frame.loc["full vehicle"]
    study.text(f"The planner enters at {entry * 3.6:.1f} km/h and passes in {optimum.passage_time:.3f} s "
               f"({optimum.iterations} IPOPT iterations from a cold start, {optimum.solve_time:.2f} s); the best "
               f"closed-loop driver on the same model clears the cones up to {limit['speed'] * 3.6:.1f} km/h "
               f"({driver_time:.3f} s). With tire lag in the planner's model the optimum enters at "
               f"{optimum_lag.entry_speed * 3.6:.1f} km/h and passes in {optimum_lag.passage_time:.3f} s "
               f"({optimum_lag.iterations} iterations; the transient slips held within 0.98 of the peak-force slip, "
               "below the equations' switch to the kinematic slip on which IPOPT otherwise cycles). "
               "Before the first lane the optimal steer flicks right, then left (up to "
               f"{np.degrees(optimum['front_steer_angle'][optimum.grid[:-1] < 0.0].max()):.1f} deg in the run-in): "
               "a time-optimal set-up of the first lane change; a steer-rate weight of 0.1 s instead of 1e-4 s "
               f"keeps it within {np.degrees(np.abs(calm['front_steer_angle'][calm.grid[:-1] < 0.0]).max()):.1f} deg "
               f"and costs {1e3 * (calm.passage_time - optimum.passage_time):.0f} ms of passage "
               f"({calm.entry_speed * 3.6:.1f} km/h entry). "
               f"Replayed open loop on the planner's model the path stays within "
               f"{frame.iloc[0]['max_path_deviation_m'] * 1000:.1f} mm of the plan; on the full vehicle it deviates "
               f"by {full_row['max_path_deviation_m']:.2f} m (cone margin {full_row['worst_cone_margin_m']:.2f} m): "
               "a plan made at the limit on the single track does not carry the full vehicle through open loop -- "
               "the roll, the load transfer and the tire lag the planner leaves out matter at the limit, which is "
               "what a tracking controller (or a planner on a richer rung) must absorb.")

    fig, axes = new_figure(2, 1, height_per_row=2.8, width=8.0)
    ax = axes[0, 0]
    for x0_, x1_, left, right in track.sections:
        for y in (left, right):
            ax.plot([x0_, x1_], [y, y], "ko", ms=3)
    ax.plot(optimum["x"], optimum["y"], "k-", lw=2, label=f"optimum at {entry * 3.6:.1f} km/h")
    for label, result in runs.items():
        ax.plot(result["x"], result["y"], lw=1, label=f"replay: {label}")
    if limit["passing"]:
        ax.plot(limit["passing"][0]["x"], limit["passing"][0]["y"], ":",
                label=f"driver at {limit['speed'] * 3.6:.1f} km/h")
    ax.invert_yaxis()
    ax.set_xlim(optimum.grid[0], optimum.grid[-1] + 5)
    ax.set_ylabel("y (SAE, right) [m]")
    ax.legend(fontsize=7)
    ax = axes[1, 0]
    ax.step(optimum["x"][:-1], np.degrees(optimum["front_steer_angle"]), where="post", label="optimal steer")
    ax.step(calm["x"][:-1], np.degrees(calm["front_steer_angle"]), where="post", lw=1,
            label="optimal steer, steer-rate weight 0.1 s")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("road-wheel steer [deg]")
    ax.legend(fontsize=7)
    study.figure(fig, "paths", caption="The minimum-time path and steer, and the steer replayed open loop")
    nmpc_on_the_full_vehicle(study, car, planner, full)


def nmpc_on_the_full_vehicle(study, car, planner, full):
    """The NMPC loop and the crossover driver on the full vehicle through ISO 3888-1 (speed held)."""
    import pandas as pd

    track = double_lane_change_track(max(car.geometry.front_track, car.geometry.rear_track) + 0.2)
    px, py = track.least_curvature_line(0.15)
    rows, shown = [], {}
    # the loop runs in Python (a few s per speed, mostly IPOPT): one speed in quick mode, two by default, three with
    # --full
    for speed in ((22.0,) if study.quick else (18.0, 22.0, 26.0) if study.full else (22.0, 26.0)):
        drag = float(planner.parameters.drag_factor) * speed**2
        nmpc = PathTrackingNMPC(planner, px, py, horizon=20, period=0.1, inputs={"rear_longitudinal_force": drag})
        loop = ClosedLoop(full, nmpc, plant_backend="compiled")  # the NMPC in Python, the car's compiled code
        x0, u0 = full.trim(speed)
        x0 = np.array(x0, dtype=float)
        x0[full.index("x")] = px[0]
        held = {n: v for n, v in zip(full.input_names, u0) if n in loop.input_names}
        t = np.arange(0.0, 1.05 * (px[-1] - px[0]) / speed, 0.025)
        start = time.perf_counter()
        result = vehdyn.simulate(loop, t, held, x0=x0, method="rk4", substeps=5)
        wall = time.perf_counter() - start
        outcome = lane_change_outcome(track, result)
        solves = np.array(nmpc.log)[1:]
        coned = (result["x"] >= 0.0) & (result["x"] <= track.sections[-1][1])
        error = np.abs(result["y"] - np.interp(result["x"], px, py))[coned].max()
        driver = CrossoverDriver.tuned(planner, speed, px, py, preview_time=1.0)
        # the driver's loop as the NMPC's: in Python around the car's compiled code (its own compiled loop would
        # cost a compile of about 20 s CPU for these few runs)
        driven_loop = ClosedLoop(full, driver, plant_backend="compiled")
        start = time.perf_counter()
        run = vehdyn.simulate(driven_loop, t, {n: v for n, v in held.items() if n in driven_loop.input_names},
                              x0=np.concatenate([x0, np.zeros(driven_loop.n_states - full.n_states)]),
                              method="RK45", rtol=1e-6, backend="numpy")
        driver_wall = time.perf_counter() - start
        driven = lane_change_outcome(track, run)
        driver_error = np.abs(run["y"] - np.interp(run["x"], px, py))[(run["x"] >= 0.0)
                                                                       & (run["x"] <= track.sections[-1][1])].max()
        rows.append({"speed_kmh": speed * 3.6, "nmpc_passed": outcome["passed"],
                     "nmpc_margin_m": outcome["worst_margin"],
                     "nmpc_max_tracking_error_m": error, "solve_median_ms": 1e3 * np.median(solves[:, 2]),
                     "solve_p90_ms": 1e3 * np.percentile(solves[:, 2], 90),
                     "iterations_median": np.median(solves[:, 3]),
                     "nmpc_loop_wall_s": wall, "crossover_passed": driven["passed"],
                     "crossover_margin_m": driven["worst_margin"], "crossover_max_tracking_error_m": driver_error,
                     "crossover_loop_wall_s": driver_wall})
        shown[speed] = (result, run)
    frame = pd.DataFrame(rows).set_index("speed_kmh")
    frame.attrs["units"] = {"nmpc_margin_m": "m", "nmpc_max_tracking_error_m": "m", "solve_median_ms": "ms",
                            "solve_p90_ms": "ms", "nmpc_loop_wall_s": "s", "crossover_margin_m": "m",
                            "crossover_max_tracking_error_m": "m", "crossover_loop_wall_s": "s"}
    study.table(frame, "nmpc", caption="ISO 3888-1 on the full vehicle: the NMPC loop (single track inside) against the "
                "crossover driver, both in a Python loop around the car's compiled code")
    last = rows[-1]
    study.text(f"At {last['speed_kmh']:.0f} km/h the NMPC loop tracks the line within "
               f"{last['nmpc_max_tracking_error_m'] * 100:.1f} cm (cone margin {last['nmpc_margin_m']:.2f} m), "
               f"{last['solve_median_ms']:.0f} ms per solve (median, this machine under its load), the crossover "
               f"driver within {last['crossover_max_tracking_error_m'] * 100:.1f} cm "
               f"(margin {last['crossover_margin_m']:.2f} m). "
               f"The NMPC loop takes {last['nmpc_loop_wall_s']:.1f} s, mostly IPOPT, where the driver's loop "
               f"takes {last['crossover_loop_wall_s']:.2f} s (both in Python around the car's compiled code).")
    fig, axes = new_figure(1, 1, height_per_row=3.0, width=8.0)
    ax = axes[0, 0]
    for x0_, x1_, left, right in track.sections:
        for y in (left, right):
            ax.plot([x0_, x1_], [y, y], "ko", ms=3)
    ax.plot(px, py, "k:", lw=0.8, label="line")
    for speed, (result, run) in shown.items():
        ax.plot(result["x"], result["y"], label=f"NMPC at {speed * 3.6:.0f} km/h")
        ax.plot(run["x"], run["y"], "--", label=f"crossover at {speed * 3.6:.0f} km/h")
    ax.invert_yaxis()
    ax.set_xlim(-10.0, track.sections[-1][1] + 10.0)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y (SAE, right) [m]")
    ax.legend(fontsize=7)
    study.figure(fig, "nmpc_paths",
                 caption="The full vehicle through ISO 3888-1 under the NMPC and the crossover driver")


if __name__ == "__main__":
    Study.main(run, __file__)
