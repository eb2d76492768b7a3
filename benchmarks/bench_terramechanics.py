"""Wong-Reece rigid wheel: a 100-slip drawbar pull-slip curve, vectorized against per-slip loops.

Timed in one run, on one wheel (r = 0.3 m, b = 0.2 m, W = 1.5 kN) on each of three shipped soils
over s in [-1, 1]:

* ``vectorized``: ``RigidWheel.solve(load, slips)``: fixed Gauss-Legendre nodes on the contact arc,
  the vertical equilibrium solved for all slips at once (batched Illinois). Goal: <= 5 ms.
* ``loop, same numerics``: the same call once per slip (a Python loop over slips).
* ``loop, quad + brentq``: the textbook implementation, per slip
  (:mod:`vehdyn.tire.terramechanics.reference`): ``scipy.integrate.quad`` of the stress integrals
  inside ``scipy.optimize.brentq`` for the entry angle. It is the error reference
  (adaptive quadrature to 1e-10, root to 1e-13): the error columns are the largest differences of
  the vectorized sinkage and drawbar pull from it, relative to the sinkage and to the load.

Run: ``python benchmarks/bench_terramechanics.py [--quick]``.
"""

from __future__ import annotations

from _timing import best_time  # first: pins BLAS to one thread before numpy loads
import argparse
import time

import numpy as np

from vehdyn.tire.terramechanics import RigidWheel, load_soil
from vehdyn.tire.terramechanics.reference import adaptive_solve

SOILS = ("dry_sand", "sandy_loam", "clayey_soil")
LOAD = 1500.0


def main(quick: bool = False) -> None:
    slips = np.linspace(-1.0, 1.0, 100)
    print(f"Wong-Reece rigid wheel r = 0.3 m, b = 0.2 m, W = {LOAD:.0f} N, {slips.size} slips in [-1, 1]")
    header = (f"{'soil':<12} {'vectorized [ms]':>16} {'loop same [ms]':>15} {'ratio':>7} {'loop quad [ms]':>15} "
              f"{'ratio':>7} {'err z / z':>10} {'err DP / W':>11}")
    print(header)
    for name in SOILS:
        wheel = RigidWheel(radius=0.3, width=0.2, soil=load_soil(name))
        fast, result = best_time(lambda: wheel.solve(LOAD, slips), repeats=20)
        loop, _ = best_time(lambda: [wheel.solve(LOAD, float(s)) for s in slips], repeats=3)
        sub = slips[::10] if quick else slips
        start = time.perf_counter()
        reference = np.array([adaptive_solve(wheel, LOAD, float(s)) for s in sub])
        textbook = (time.perf_counter() - start) * slips.size / sub.size
        pick = np.searchsorted(slips, sub)
        err_z = np.max(np.abs(result.sinkage[pick] - reference[:, 0]) / reference[:, 0])
        err_dp = np.max(np.abs(result.drawbar_pull[pick] - reference[:, 1])) / LOAD
        print(f"{name:<12} {fast * 1e3:16.2f} {loop * 1e3:15.1f} {loop / fast:7.1f} {textbook * 1e3:15.0f} "
              f"{textbook / fast:7.0f} {err_z:10.1e} {err_dp:11.1e}")
    print("goal: vectorized <= 5 ms per 100-slip curve" + (" (quick: quad reference on every 10th slip)" if quick else ""))


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="quad reference on every 10th slip")
    main(**vars(parser.parse_args()))
