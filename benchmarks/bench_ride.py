"""Random ride response: Lyapunov vs PSD integral vs time-domain simulation, time and error.

Run: ``python benchmarks/bench_ride.py``. Prints, from one run on this machine, for

1. the quarter car of reference case E-QC-ISO-C (300/60 kg, 16 kN/m, 1 kN s/m, 190 kN/m) at
   20 m/s on an ISO 8608 class-C road, and
2. a 4-DOF half car (front and rear road inputs, wheelbase 2.7 m, rear = front delayed by 0.135 s)
   on the same road,

the r.m.s. of every output by the three routes of ``vehdyn.ride.random_response``:
``"lyapunov"`` (exact covariance with the shaping filter appended; for the half car with a Pade
delay of order 10, and with ``delay="exact"``, lagged covariances), ``"psd"`` (frequency integral
with exact delay and its stated error bound) and
``"simulation"`` (a sum-of-cosines road of 100 s at 1 kHz, exact-discretization simulation;
its time includes the road synthesis). Errors are against the reference: the E-QC-ISO-C values
(computed independently, see tests/data/ride_reference_cases.json) for the quarter car, the PSD
route (exact delay) for the half car. Times are the best of several runs; ratios are simulation
time / route time from the same run.
"""

from __future__ import annotations

import os
import platform
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

# E-QC-ISO-C expected r.m.s. (shared reference cases; computed by Lyapunov and frequency integral, 1e-5)
E_QC_ISO_C = {"sprung_acceleration": 1.258668, "suspension_travel": 0.01348764, "tire_deflection": 0.005466187,
              "dynamic_tire_load": 1038.575}


def best_time(fun, repeats=7):
    best, out = np.inf, None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fun()
        best = min(best, time.perf_counter() - t0)
    return best, out


def quarter_car(ms=300.0, mu=60.0, ks=16000.0, cs=1000.0, kt=190000.0):
    import vehdyn

    M = np.diag([ms, mu])
    C = np.array([[cs, -cs], [-cs, cs]])
    K = np.array([[ks, -ks], [-ks, ks + kt]])
    F = np.array([[0.0, 0.0], [kt, 0.0]])
    acc = -np.linalg.solve(M, np.hstack([K, C]))[0]
    out = np.array([acc, [1.0, -1.0, 0, 0], [0, 1.0, 0, 0], [0, -kt, 0, 0]])
    D = np.array([[0, 0], [0, 0], [-1.0, 0], [kt, 0]])
    return vehdyn.LinearModel.from_second_order(
        M, C, K, F, dof=["sprung_displacement", "unsprung_displacement"], inputs=["road_displacement", "road_velocity"],
        outputs=list(E_QC_ISO_C), output_matrix=out, feedthrough=D, name="quarter car")


def half_car(m=1200.0, iy=1800.0, a=1.2, b=1.5, mu=40.0, kf=30000.0, kr=32000.0, cf=2500.0, cr=2400.0, kt=200000.0):
    import vehdyn

    Tf, Tr = np.array([1.0, -a, -1.0, 0.0]), np.array([1.0, b, 0.0, -1.0])
    K = kf * np.outer(Tf, Tf) + kr * np.outer(Tr, Tr) + np.diag([0, 0, kt, kt])
    C = cf * np.outer(Tf, Tf) + cr * np.outer(Tr, Tr)
    M = np.diag([m, iy, mu, mu])
    F = np.zeros((4, 2))
    F[2, 0] = F[3, 1] = kt
    acc = -np.linalg.solve(M, np.hstack([K, C]))
    out = np.vstack([acc[0], acc[1], np.r_[Tf, 0, 0, 0, 0], np.r_[Tr, 0, 0, 0, 0], [0, 0, -kt, 0, 0, 0, 0, 0],
                     [0, 0, 0, -kt, 0, 0, 0, 0]])
    D = np.vstack([np.linalg.solve(M, F)[:2], [[0, 0], [0, 0], [kt, 0], [0, kt]]])
    return vehdyn.LinearModel.from_second_order(
        M, C, K, F, dof=["sprung_displacement", "pitch_angle", "unsprung_displacement_front",
                         "unsprung_displacement_rear"],
        inputs=["road_displacement_front", "road_displacement_rear"],
        outputs=["sprung_acceleration", "pitch_acceleration", "suspension_travel_front", "suspension_travel_rear",
                 "dynamic_tire_load_front", "dynamic_tire_load_rear"], output_matrix=out, feedthrough=D,
        name="half car")


def run_case(title, model, reference, **kw):
    from vehdyn.ride import random_response

    V = 20.0
    t_lyap, lyap = best_time(lambda: random_response(model, "C", V, method="lyapunov", **kw), 20)
    t_exact, exact = (best_time(lambda: random_response(model, "C", V, method="lyapunov", delay="exact", **kw), 20)
                      if kw else (None, None))
    t_psd, psd = best_time(lambda: random_response(model, "C", V, method="psd", **kw), 7)
    t_sim, sim = best_time(lambda: random_response(model, "C", V, method="simulation", duration=100.0,
                                                   sample_rate=1000.0, seed=1, **kw), 3)
    ref = reference(psd)
    print(f"\n{title}")
    print(f"{'route':<12}{'time [s]':>12}{'sim/route':>12}   max rel. error   stated error (max rel.)")
    rows = [("lyapunov", t_lyap, lyap, "0 (exact" + (", Pade 10)" if kw else ")"))]
    if kw:
        rows.append(("lyap.exact", t_exact, exact, "0 (exact delay)"))
    for name, t, res, stated in (*rows,
                                 ("psd", t_psd, psd, f"{np.max(psd.error / psd.rms):.1e} (quadrature bound)"),
                                 ("simulation", t_sim, sim, f"{np.max(sim.error / sim.rms):.1e} (1 std. error)")):
        err = np.max(np.abs(res.rms / ref - 1))
        print(f"{name:<12}{t:>12.3g}{t_sim / t:>12.3g}   {err:>14.2e}   {stated}")
    print("  r.m.s. per output (lyapunov | psd | simulation):")
    for k, o in enumerate(lyap.output_names):
        print(f"    {o:<26}{lyap.rms[k]:>13.6g}{psd.rms[k]:>13.6g}{sim.rms[k]:>13.6g}")
    return t_sim / t_lyap, t_sim / t_psd, (t_sim / t_exact if t_exact else None)


def main():
    import scipy

    import vehdyn

    print(f"vehdyn {vehdyn.__version__}, numpy {np.__version__}, scipy {scipy.__version__}, "
          f"Python {platform.python_version()} on {platform.machine()}, {os.cpu_count()} cores, load average "
          f"{os.getloadavg()[0]:.1f} (timings of sub-millisecond routes suffer most from a loaded machine)")
    qc = quarter_car()
    r1 = run_case("1. quarter car (E-QC-ISO-C), class C, 20 m/s; reference: E-QC-ISO-C (7 significant digits, so "
                  "errors below ~5e-7 are its rounding)", qc,
                  lambda psd: np.array([E_QC_ISO_C[o] for o in psd.output_names]))
    r2 = run_case("2. half car, front/rear delay 0.135 s, class C, 20 m/s; reference: PSD route (exact delay)",
                  half_car(), lambda psd: psd.rms, wheelbase=2.7)
    print(f"\nspeed-up of the exact routes over 100 s of simulated road: Lyapunov {r1[0]:.0f}x / {r2[0]:.0f}x "
          f"(exact delay {r2[2]:.0f}x), PSD integral {r1[1]:.0f}x / {r2[1]:.0f}x (quarter car / half car)")


if __name__ == "__main__":
    main()
