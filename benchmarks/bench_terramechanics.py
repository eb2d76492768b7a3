"""Wong-Reece rigid wheel: a 100-slip drawbar pull-slip curve, vectorized against per-slip loops.

Timed in one run, on one wheel (r = 0.3 m, b = 0.2 m, W = 1.5 kN) on each of three shipped soils
over s in [-1, 1]:

* ``vectorized``: ``RigidWheel.solve(load, slips)``: fixed Gauss-Legendre nodes on the contact arc,
  the vertical equilibrium solved for all slips at once (batched Illinois). Goal: <= 5 ms.
* ``loop, same numerics``: the same call once per slip (a Python loop over slips).
* ``loop, quad + brentq``: the textbook implementation, per slip: ``scipy.integrate.quad`` of the
  stress integrals inside ``scipy.optimize.brentq`` for the entry angle. It is the error reference
  (adaptive quadrature to 1e-10, root to 1e-13): the error columns are the largest differences of
  the vectorized sinkage and drawbar pull from it, relative to the sinkage and to the load.

Run: ``python benchmarks/bench_terramechanics.py [--quick]``.
"""

from __future__ import annotations

from _timing import best_time  # first: pins BLAS to one thread before numpy loads
import argparse
import math
import time
import warnings

import numpy as np

from vehdyn.tire.terramechanics import RigidWheel, load_soil

SOILS = ("dry_sand", "sandy_loam", "clayey_soil")
LOAD = 1500.0


def textbook_point(wheel: RigidWheel, load: float, slip: float):
    """(sinkage, drawbar pull) of one slip: quad for the integrals, brentq for theta_1."""
    from scipy.integrate import quad
    from scipy.optimize import brentq

    soil, r, b = wheel.soil, wheel.radius, wheel.width
    k = soil.k_c / b + soil.k_phi
    tan_phi = math.tan(soil.friction_angle)

    def parts(theta1):
        tm = min(max(wheel.c1 + wheel.c2 * slip, 0.0), 1.0) * theta1
        t2 = -wheel.rebound * theta1

        def sigma(t):
            e = t if t >= tm else theta1 - (t - t2) / (tm - t2) * (theta1 - tm)
            return k * (r * max(math.cos(e) - math.cos(theta1), 0.0)) ** soil.n

        def tau(t):
            if slip >= 0:
                j = r * ((theta1 - t) - (1 - slip) * (math.sin(theta1) - math.sin(t)))
            else:
                j = r * ((1 + slip) * (theta1 - t) - (math.sin(theta1) - math.sin(t)))
            return math.copysign((soil.cohesion + sigma(t) * tan_phi) * (1 - math.exp(-abs(j) / soil.shear_modulus)), j)

        def integral(f):
            pieces = [(t2, tm), (tm, theta1)] if tm > t2 else [(tm, theta1)]
            return sum(quad(f, a, c, epsabs=0, epsrel=1e-10, limit=200)[0] for a, c in pieces)

        return sigma, tau, integral

    def vertical(theta1):
        sigma, tau, integral = parts(theta1)
        return r * b * integral(lambda t: sigma(t) * math.cos(t) + tau(t) * math.sin(t)) - load

    with warnings.catch_warnings():  # quad's round-off notice near 1e-10 on the kinked integrands
        warnings.simplefilter("ignore")
        theta1 = brentq(vertical, 1e-9, 0.5 * math.pi, xtol=1e-13)
        sigma, tau, integral = parts(theta1)
        pull = r * b * integral(lambda t: tau(t) * math.cos(t) - sigma(t) * math.sin(t))
    return r * (1 - math.cos(theta1)), pull


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
        reference = np.array([textbook_point(wheel, LOAD, float(s)) for s in sub])
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
