"""The fidelity ladder: cost against error of every model on the standard scenes.

Every standard scene (vehdyn.scene.standard_scenes: step steer gentle and at the limit, sine with
dwell, lane changes at 60 and 100 km/h, a circle to the limit, braking in a turn, smooth and rough
roads at 54 and 108 km/h, a one-sided pothole, cornering on a rough road) is run on every model
that can answer it (vehdyn.ladder), for the sedan (the three shipped cars: ``python
benchmarks/bench_ladder.py sedan compact van``, too long for the report). The error of each model is
max |x - x_ref| / max |x_ref| over the scene's outputs against the most complete model that
answers (the reference), its cost the wall time of one run. The model vehdyn.plan picks without
running the reference (the cheapest whose estimated error is within the 2 % tolerance) is marked;
the table gives its measured error and its cost relative to the reference. The reference is the
full vehicle (vehdyn.full_vehicle.FullVehicle, compiled), the top of both ladders.
"""

import numpy as np

import vehdyn
from vehdyn.simulation.compiled import numba_available
from vehdyn.plotting import new_figure
from vehdyn.report import Study
from vehdyn.scene import standard_scenes

QUICK_SCENES = ("gentle_step_steer", "limit_step_steer", "rough_road_54", "pothole")


def run(study: Study) -> None:
    import pandas as pd

    vehicles = ["sedan"]  # the three cars: benchmarks/bench_ladder.py
    rows, frames = [], {}
    for vehicle in vehicles:
        scenes = standard_scenes(vehicle)
        if study.quick or not numba_available():
            scenes = {k: v.replace(duration=min(v.duration, 1.5)) for k, v in scenes.items() if k in QUICK_SCENES}
        for name, scene in scenes.items():
            # the first run of a compiled model includes compiling or loading its code, and a rung of
            # a few milliseconds is easily hit by a pause of the machine (the other studies run beside
            # this one): one run per rung, as before, put 4 of the sedan's 13 scenes under 1/10 of the
            # reference in a fresh clone, where benchmarks/bench_ladder.py finds 8. Three runs per rung
            # at least and 0.1 s after the first, the fastest.
            frame = vehdyn.ladder(scene, repeat=3, min_time=0.1)
            planned = frame[frame["planned"]].iloc[0]
            reference = frame[frame["reference"]].iloc[0]
            rows.append({"vehicle": vehicle, "scene": name, "planned": planned["rung"],
                         "estimated_error": planned["estimated_error"], "error": planned["error"],
                         "reference": reference["rung"],
                         "cost_ratio": planned["wall_time_s"] / reference["wall_time_s"]})
            if vehicle == vehicles[0]:
                frames[name] = frame
    names = list(frames)
    ncols = 3
    nrows = int(np.ceil(len(names) / ncols))
    fig, axes = new_figure(nrows, ncols, width=12.0, height_per_row=3.2)
    for k, name in enumerate(names):
        vehdyn.plot_ladder(frames[name], ax=axes.flat[k], title=f"{vehicles[0]}: {name}")
    for ax in list(axes.flat)[len(names):]:
        ax.set_visible(False)
    fig.tight_layout()
    study.figure(fig, "cost_error", caption=f"{vehicles[0]}: wall time against error of each model per scene "
                                            "(red: the planned model; dashed: the tolerance)")
    table = pd.DataFrame(rows).set_index(["vehicle", "scene"])
    table.attrs["units"] = {"error": "-", "estimated_error": "-", "cost_ratio": "-"}
    study.table(table, "planned", caption="The planned model per scene: estimated and measured error against the "
                                          "reference, cost relative to it")
    if not numba_available():
        study.text("numba is not installed (pip install \"vehdyn[fast]\"), so the full vehicle runs in numpy, "
                   "hundreds of times slower: only the scenes " + ", ".join(QUICK_SCENES) + " are run here, "
                   "shortened to 1.5 s.")
    elif study.quick:
        study.text("Quick mode: only the scenes " + ", ".join(QUICK_SCENES) + " are run, shortened to 1.5 s. A "
                   "shortened scene is another scene (its transient weighs more), so the planner may pick another "
                   "model than for the full one; the text below is about the full scenes (vehdyn report).")
    wrong = table[table["error"] > 0.02]
    cheap = (table["cost_ratio"] <= 0.1).sum()
    study.text(f"Planned model within the 2 % tolerance on {len(table) - len(wrong)} of {len(table)} scenes; "
               f"costing at most 1/10 of the reference on {cheap} of {len(table)} (timed while the report runs other "
               "studies beside this one: a cheap rung's few milliseconds move with that load; quiet, best of 5, "
               "benchmarks/bench_ladder.py finds 8 of 13 for each of the three cars). A model's cost is its run for "
               "the scene: the full vehicle's trim (tens of milliseconds) and simulation, a linearization, the "
               "derivation of LateralYawRoll+lag's stiffnesses from the tire law; building a model from the "
               "vehicle file is not counted. At 0.1 g the linear lateral-yaw-roll model with tire lag, its "
               "parameters from the tire law at the running loads, is within 2 % of the full vehicle; in the "
               "slow circle to the limit the single track with the quasi-static lateral load transfer "
               "(SingleTrack+LLT: the tire law at each wheel's load) is. The single track with a roll degree of "
               "freedom (SingleTrack+roll: the roll moment sets the dynamic lateral load transfer) is 1.5-2.2 % "
               "off the full vehicle in the lane change at 100 km/h and the transient limit manoeuvres (sedan, "
               "compact, van: benchmarks/bench_ladder.py), too close to the tolerance for its estimate, which "
               "grows with the speed squared: the planner leaves those scenes to the full vehicle, and braking "
               "in a turn (the inner rear wheel locks: per-wheel spin) needs it; on the rough roads and in the "
               "pothole, where the wheels lift, the full car whose tires lift off, slip and spin up in the "
               "air (FullCar+lift) is within it.")


if __name__ == "__main__":
    Study.main(run, __file__)
