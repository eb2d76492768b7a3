"""The fidelity ladder on the standard scenes: cost and error of every rung, the plan's pick.

Run: ``python benchmarks/bench_ladder.py [vehicle ...] [--repeat N] [--scenes a,b]`` (default: sedan,
best of 3; ``--repeat 1`` when the full vehicle runs on numpy: minutes per road scene). For each standard scene
(:func:`vehdyn.scene.standard.standard_scenes`: gentle and limit step steer, sine with dwell, lane
change at 60 and 100 km/h, circle to the limit, braking in a turn, smooth and rough roads at two
speeds, a pothole, cornering on a rough road) it runs ``vehdyn.ladder`` (every admissible rung,
best of 3 runs) and prints

1. the cost/error matrix: wall time [s] and max relative error against the reference (top
   admissible) rung of every rung, the planned rung marked;
2. the goals, measured in this one run: on every scene the planned rung's measured error is within
   the scene's tolerance, and on at least 8 of 12 the planned rung costs at most 1/10 of the
   reference rung (ratios of wall times within the run; a rung's wall time is its ``Setup.run()``:
   the per-scene start -- the full vehicle's trim, a linearization -- and the simulation, the best
   of the repeats, the first of which loads compiled code), per vehicle;
3. the calibration of the model-based estimates (:mod:`vehdyn.scene.estimates`): estimated /
   measured error of every non-reference rung (the goal: within a factor 3), and the measured
   cost per simulated second of each rung and a fit of start + rate * duration, from which
   ``COST_PER_SIMULATED_SECOND`` and ``START_COST_S`` are set.
"""

from __future__ import annotations

from _timing import best_time  # noqa: F401  (first: pins BLAS to one thread before numpy loads)
import platform
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))


def main(vehicles, repeat: int = 3, only=None) -> None:
    import pandas as pd

    import vehdyn
    from vehdyn.scene.standard import standard_scenes

    print(f"vehdyn {vehdyn.__version__}, Python {platform.python_version()}, {platform.machine()}; "
          f"rungs: {[r.name for r in vehdyn.scene.rungs()]}")
    began = time.perf_counter()
    matrix, goals, calibration, costs = [], [], [], []
    for name_v in vehicles:
        for name, scene in standard_scenes(name_v).items():
            if only and name not in only:
                continue
            frame = vehdyn.ladder(scene, repeat=repeat)
            planned = frame[frame["planned"]].iloc[0]
            reference = frame[frame["reference"]].iloc[0]
            goals.append({"vehicle": name_v, "scene": name, "planned": planned["rung"],
                          "reference": reference["rung"], "planned_error": planned["error"],
                          "within_tolerance": bool(planned["error"] <= scene.tolerance),
                          "cost_ratio": planned["wall_time_s"] / reference["wall_time_s"],
                          "cost_goal": bool(planned["wall_time_s"] <= 0.1 * reference["wall_time_s"])})
            print(f"{name_v} {name}: {time.perf_counter() - began:.0f} s", file=sys.stderr, flush=True)
            for _, row in frame.iterrows():
                matrix.append({"vehicle": name_v, "scene": name, "rung": row["rung"] + (" *" if row["planned"] else ""),
                               "wall_time_s": row["wall_time_s"], "error": row["error"],
                               "estimated_error": row["estimated_error"]})
                costs.append({"rung": row["rung"], "cost_per_s": row["wall_time_s"] / scene.duration,
                              "duration": scene.duration, "wall_time_s": row["wall_time_s"]})
                if not row["reference"]:
                    calibration.append({"vehicle": name_v, "scene": name, "rung": row["rung"],
                                        "estimated": row["estimated_error"], "measured": row["error"],
                                        "ratio": row["estimated_error"] / max(row["error"], 1e-12)})
    pd.set_option("display.width", 200)
    pd.set_option("display.max_rows", 500)
    m = pd.DataFrame(matrix)
    print("\n1. cost [s] / error against the reference, per scene and rung (* = planned)")
    print(m.to_string(index=False, float_format=lambda v: f"{v:.3g}"))
    g = pd.DataFrame(goals)
    print("\n2. goals")
    print(g.to_string(index=False, float_format=lambda v: f"{v:.3g}"))
    n = len(g)
    print(f"planned error within tolerance: {int(g['within_tolerance'].sum())}/{n} (goal: all); planned cost <= 1/10 "
          f"of the reference: {int(g['cost_goal'].sum())}/{n}")
    for vehicle, rows in g.groupby("vehicle", sort=False):
        met = int(rows["cost_goal"].sum())
        print(f"  {vehicle}: planned cost <= 1/10 of the reference on {met} of {len(rows)} scenes (goal: at least 8 "
              f"of the 12 standard scenes{', met' if met >= 8 else ', not met'}); wrong picks: "
              f"{int((~rows['within_tolerance']).sum())}")
    c = pd.DataFrame(calibration)
    ratio = c["ratio"].to_numpy()
    finite = np.isfinite(ratio)
    negligible = np.maximum(c["estimated"].to_numpy(), c["measured"].to_numpy()) < 1e-4
    within = ((ratio <= 3) & (ratio >= 1 / 3) | negligible)[finite]
    print("\n3a. estimated / measured error of the non-reference rungs")
    print(c.to_string(index=False, float_format=lambda v: f"{v:.3g}"))
    print(f"within a factor 3 (or both below 1e-4): {int(within.sum())}/{int(finite.sum())}")
    k = pd.DataFrame(costs).groupby("rung")["cost_per_s"].median()
    print("\n3b. median cost per simulated second [s/s] (COST_PER_SIMULATED_SECOND)")
    print(k.to_string(float_format=lambda v: f"{v:.2e}"))
    fits = []
    for rung, group in pd.DataFrame(costs).groupby("rung"):
        duration, wall = group["duration"].to_numpy(), group["wall_time_s"].to_numpy()
        if np.unique(duration).size < 2:
            continue
        # wall = start + rate * duration, least squares (the start: trim, linearization, derivation)
        start, rate = np.linalg.lstsq(np.column_stack([np.ones_like(duration), duration]), wall, rcond=None)[0]
        fits.append({"rung": rung, "start_s": start, "per_s": rate, "scenes": duration.size})
    print("\n3c. wall time = start + rate * duration, least squares over the scenes (START_COST_S and the rate)")
    print(pd.DataFrame(fits).to_string(index=False, float_format=lambda v: f"{v:.2e}"))
    print(f"\ntotal {time.perf_counter() - began:.1f} s")


if __name__ == "__main__":
    import argparse

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("vehicles", nargs="*", default=["sedan"])
    parser.add_argument("--repeat", type=int, default=3, help="runs per rung (the best is reported)")
    parser.add_argument("--scenes", default=None, help="comma-separated standard scene names (default: all)")
    args = parser.parse_args()
    main(args.vehicles, args.repeat, args.scenes.split(",") if args.scenes else None)
