"""ISO 3888-1 double lane change with a preview driver: paths, steer and the speed at which each vehicle fails.

Each shipped vehicle (nonlinear single-track model, its Magic Formula tires) is driven through the
ISO 3888-1 severe lane-change track by vehdyn.handling.PreviewDriver: a pure-pursuit steer law at
a preview point 0.8 s ahead, through a 0.1 s lag, holding the entry speed with the rear axle
force. The run fails when the vehicle (a rectangle of the vehicle width, track + 0.2 m) crosses a
cone line in a coned section, or spins. The entry speed is raised until the run fails. The figure
shows the paths and the driver's steer at the highest passing speed and the first failing one for
the first vehicle.
"""

import numpy as np

import vehdyn
from vehdyn.handling import (DriverInTheLoop, PreviewDriver, SingleTrack, double_lane_change_track,
                             lane_change_outcome, spin_out_time)
from vehdyn.plotting import new_figure
from vehdyn.report import Study


def drive(model, vehicle, track, speed):
    driver = PreviewDriver(track.path_x, track.path_y, preview_time=0.8, lag=0.1, target_speed=speed)
    loop = DriverInTheLoop(model, driver, wheelbase=vehicle.wheelbase, mass=vehicle.mass.mass)
    t = np.linspace(0.0, (track.path_x[-1] - track.path_x[0]) / speed, 301)
    x0 = np.concatenate([model.straight_running(speed, x=float(track.path_x[0])), [0.0]])
    result = vehdyn.simulate(loop, t, None, x0=x0, method="RK45", rtol=1e-5, atol=1e-8)
    outcome = lane_change_outcome(track, result)
    outcome["passed"] = outcome["passed"] and spin_out_time(result) is None
    return result, outcome


def run(study: Study) -> None:
    import pandas as pd

    vehicles = ["sedan"] if study.quick else vehdyn.shipped_vehicles("passenger_car")
    speeds = [14.0, 20.0] if study.quick else list(np.arange(12.0, 30.1, 1.0))
    rows, shown = [], {}
    for name in vehicles:
        vehicle = vehdyn.load_vehicle(name)
        width = max(vehicle.geometry.front_track, vehicle.geometry.rear_track) + 0.2
        track = double_lane_change_track(width)
        model = SingleTrack(vehicle)
        last_pass, first_fail = None, None
        for speed in speeds:
            result, outcome = drive(model, vehicle, track, speed)
            if outcome["passed"]:
                last_pass = (speed, result)
                continue
            first_fail = (speed, result, outcome)
            break
        rows.append({"vehicle": name, "vehicle_width": width,
                     "highest_passing_speed": last_pass[0] if last_pass else np.nan,
                     "first_failing_speed": first_fail[0] if first_fail else np.nan,
                     "failed_in_section": (first_fail[2]["section"] if first_fail else None)})
        if name == vehicles[0]:
            shown = {"track": track, "pass": last_pass, "fail": first_fail}
    fig, axes = new_figure(2, 1, height_per_row=2.8, width=8.0)
    track = shown["track"]
    for x0, x1, left, right in track.sections:
        for y in (left, right):
            axes[0, 0].plot([x0, x1], [y, y], "ko", ms=3)
    for label, entry in (("pass", shown["pass"]), ("fail", shown["fail"])):
        if entry:
            r = entry[1]
            axes[0, 0].plot(r["x"], r["y"], label=f"{label} at {entry[0]:g} m/s")
            axes[1, 0].plot(r["x"], np.degrees(r["driver_steer_angle"]), label=f"{label} at {entry[0]:g} m/s")
    axes[0, 0].invert_yaxis()  # SAE y to the right: draw the left turn upwards
    axes[0, 0].set_ylabel("y (SAE, right) [m]")
    axes[0, 0].legend(fontsize=8)
    axes[1, 0].set_ylabel("driver steer [deg]")
    axes[1, 0].set_xlabel("x [m]")
    study.figure(fig, "paths", caption=f"{vehicles[0]}: CG paths between the cones and the driver's road-wheel steer")
    frame = pd.DataFrame(rows).set_index("vehicle")
    frame.attrs["units"] = {"vehicle_width": "m", "highest_passing_speed": "m/s", "first_failing_speed": "m/s"}
    study.table(frame, "failure_speeds", caption="Entry speed at which each vehicle fails the lane change")


if __name__ == "__main__":
    Study.main(run, __file__)
