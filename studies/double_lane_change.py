"""Severe lane changes that measure the car: ISO 3888-1 double lane change and ISO 3888-2 obstacle avoidance.

Each vehicle (nonlinear single-track model, its Magic Formula tires, compiled) is steered through
the cones by MacAdam's optimal preview driver (vehdyn.driver.OptimalPreviewDriver: a linear
bicycle of the car as internal model, a preview window after its delay, a 0.1 s neuromuscular
lag) along one of two lines: the lanes' centre line (cosine transitions) or the least-curvature
line through the lanes narrowed by 0.15 m (DoubleLaneChangeTrack.least_curvature_line).
vehdyn.procedures.lane_change_limit finds by bisection on the entry speed the highest speed at which
ANY tuning of a sweep of driver parameters (line, preview time, gain, delay) clears the cones,
so the speed reported is the car's limit within the drivers swept, not one tuning's. ISO 3888-1 is
driven with the speed held (the rear axle force balances the drag), ISO 3888-2 with the throttle
released at the entry. A run fails when the vehicle (a rectangle of width track + 0.2 m) crosses a
cone line in a coned lane, or spins (|sideslip| > 45 deg).

The cone geometry's bound (vehdyn.procedures.lane_change_speed_bound) is the highest speed at which
a point mass at the tires' friction coefficient could clear the cones on the least-curvature
path: a car at it is limited by the geometry and friction ("cone geometry"). Otherwise the
limiting factor is the axle whose slip angle first passed its peak-force slip angle (tire
saturation) in the failing run closest to passing just above the limit or, failing that, in the
passing run at the limit; else "driver" (the cones were hit with tires short of saturation: no
tuning swept found a line). Axle utilizations are the largest |tan slip angle| over the
peak-force one (static load), in the passing run at the limit and in that failing run. Default:
the sedan, 8 tunings (delay 0.1 s); ``vehdyn report --full``: the three cars, 36 tunings with
delays 0.05, 0.1 and 0.2 s (and the limit against the delay).
"""

import itertools

import numpy as np

import vehdyn
from vehdyn.driver import OptimalPreviewDriver
from vehdyn.handling import SingleTrack
from vehdyn.procedures import (
    double_lane_change_track,
    lane_change_limit,
    lane_change_speed_bound,
    obstacle_avoidance_track,
    slip_angle_utilization,
)
from vehdyn.plotting import new_figure
from vehdyn.report import Study

TRACKS = (("ISO 3888-1", double_lane_change_track, "hold"), ("ISO 3888-2", obstacle_avoidance_track, "release"))


def run(study: Study) -> None:
    import pandas as pd

    lines = ("centre", "least curvature")
    if study.quick:
        vehicles, lines, previews, gains, delays, resolution = ["sedan"], ("centre",), (0.5,), (1.5,), (0.1,), 1.0
    elif study.full:
        vehicles = vehdyn.shipped_vehicles("passenger_car")
        previews, gains, delays, resolution = (0.3, 0.5, 0.8), (1.0, 1.5), (0.05, 0.1, 0.2), 0.25
    else:
        vehicles, previews, gains, delays, resolution = ["sedan"], (0.5, 0.8), (1.0, 1.5), (0.1,), 0.5
    rows, by_delay, shown = [], [], {}
    for name in vehicles:
        car = vehdyn.load_vehicle(name)
        model = SingleTrack(car)
        width = max(car.geometry.front_track, car.geometry.rear_track) + 0.2
        for standard, build, throttle in TRACKS:
            track = build(width)

            paths = {"centre": (track.path_x, track.path_y), "least curvature": track.least_curvature_line(0.15)}

            def make(speed, line, **tuning):
                return OptimalPreviewDriver(*paths[line], vehicle=car, speed=speed, **tuning)

            results = []
            for delay in delays:  # one search per driver delay: the driver's share in the limit
                tunings = [{"line": line, "preview_time": p, "gain": g, "delay": delay}
                           for line, p, g in itertools.product(lines, previews, gains)]
                results.append(lane_change_limit(model, track, make, tunings, throttle=throttle, speeds=(8.0, 40.0),
                                                 resolution=resolution))
                by_delay.append({"vehicle": name, "test": standard, "delay": delay,
                                 "limit_speed_kmh": results[-1]["speed"] * 3.6})
            res = max(results, key=lambda r: np.nan_to_num(r["speed"], nan=-1.0))
            bound, bound_x, bound_y = lane_change_speed_bound(track, car.tires.friction_coefficient)
            factor = res["limiting_factor"]
            if res["speed"] >= 0.95 * bound:
                factor = "cone geometry (at the friction bound)"
            none = {"front": (np.nan,), "rear": (np.nan,)}
            use = slip_angle_utilization(model, res["failing"][0]) if res["failing"] else none
            passing = res["passing"][0] if res["passing"] else None
            use_limit = slip_angle_utilization(model, passing) if passing is not None else none
            rows.append({"vehicle": name, "test": standard, "limit_speed_kmh": res["speed"] * 3.6,
                         "failing_speed_kmh": res["failing_speed"] * 3.6, "cone_geometry_bound_kmh": bound * 3.6,
                         **{k: (res["tuning"] or {}).get(k, np.nan) for k in ("line", "preview_time", "gain", "delay")},
                         "limiting_factor": factor,
                         "cone_hit_in_lane": 1 + 2 * res["failing"][1]["section"] if res["failing"] else None,
                         "peak_lateral_acceleration_g": (np.abs(passing["lateral_acceleration"]).max() / 9.80665
                                                         if passing is not None else np.nan),
                         "front_utilization_at_limit": use_limit["front"][0],
                         "rear_utilization_at_limit": use_limit["rear"][0],
                         "front_utilization_failing": use["front"][0], "rear_utilization_failing": use["rear"][0],
                         "runs": sum(r["runs"] for r in results)})
            if name == vehicles[0]:
                path = paths[res["tuning"]["line"]] if res["tuning"] else None
                shown[standard] = (track, res, bound_x, bound_y, path)
    frame = pd.DataFrame(rows).set_index(["vehicle", "test"])
    frame.attrs["units"] = {"limit_speed_kmh": "km/h", "failing_speed_kmh": "km/h", "cone_geometry_bound_kmh": "km/h",
                            "line": "-", "preview_time": "s",
                            "gain": "-", "delay": "s", "peak_lateral_acceleration_g": "g",
                            "front_utilization_at_limit": "-", "rear_utilization_at_limit": "-",
                            "front_utilization_failing": "-", "rear_utilization_failing": "-"}
    n_tunings = len(lines) * len(previews) * len(gains) * len(delays)
    study.table(frame, "limit_speeds", caption=f"Highest entry speed clearing the cones over {n_tunings} driver "
                "tunings (line, preview time, gain, delay), what limits it, and the point-mass bound of the cone "
                "geometry")
    if len(delays) > 1:
        table = pd.DataFrame(by_delay).pivot_table(index=["vehicle", "test"], columns="delay", values="limit_speed_kmh")
        table.columns = [f"delay_{d:g}_s" for d in table.columns]
        table.attrs["units"] = {c: "km/h" for c in table.columns}
        study.table(table, "limit_vs_delay", caption="Limit speed [km/h] against the driver's delay (best preview "
                    "time and gain at each delay)")

    fig, axes = new_figure(2, 1, height_per_row=2.8, width=8.0)
    for ax, (standard, (track, res, bound_x, bound_y, path)) in zip(axes[:, 0], shown.items()):
        for x0, x1, left, right in track.sections:
            for y in (left, right):
                ax.plot([x0, x1], [y, y], "ko", ms=3)
        for label, entry, speed in (("pass", res["passing"], res["speed"]), ("fail", res["failing"],
                                                                              res["failing_speed"])):
            if entry:
                ax.plot(entry[0]["x"], entry[0]["y"], label=f"{label} at {speed * 3.6:.1f} km/h")
        if path is not None:
            ax.plot(*path, "k:", lw=0.8, label=f"driver's path ({res['tuning']['line']} line)")
        ax.plot(bound_x, bound_y, "--", color="0.5", lw=0.8, label="least-curvature path (geometry bound)")
        ax.invert_yaxis()  # SAE y to the right: draw the left turn upwards
        ax.set_xlim(track.path_x[0] + 20, track.path_x[-1] - 10)
        ax.set_ylabel("y (SAE, right) [m]")
        ax.set_title(f"{vehicles[0]}, {standard}", fontsize=9)
        ax.legend(fontsize=7)
    axes[-1, 0].set_xlabel("x [m]")
    study.figure(fig, "paths", caption=f"{vehicles[0]}: CG paths at the limit speed and just above it (best tunings)")


if __name__ == "__main__":
    Study.main(run, __file__)
