"""Random ride response: Lyapunov vs PSD integral vs time-domain simulation, time and error.

Run: ``python benchmarks/bench_ride.py``. Prints, from one run on this machine, for

1. the quarter car of reference case E-QC-ISO-C (``vehdyn.ride.QuarterCar``: 300/60 kg, 16 kN/m,
   1 kN s/m, 190 kN/m) at 20 m/s on an ISO 8608 class-C road, and
2. a 4-DOF half car (``vehdyn.ride.BouncePitch``: front and rear road inputs, wheelbase 2.7 m,
   rear = front delayed by 0.135 s) on the same road,

the r.m.s. of every output by the three routes of ``vehdyn.ride.random_vibration``:
``"lyapunov"`` (exact covariance with the shaping filter appended; for the half car with the
exact delay through lagged covariances, the default, and with ``delay="pade"``, a Pade delay of
order 10), ``"psd"`` (frequency integral with exact delay and its stated error bound) and
``"simulation"`` (a sum-of-cosines road of 100 s at 1 kHz, exact-discretization simulation;
its time includes the road synthesis). Errors are against the reference: the E-QC-ISO-C values
(computed independently, see tests/data/ride_reference_cases.json) for the quarter car, the PSD
route (exact delay) for the half car. Times are the best of several runs; ratios are simulation
time / route time from the same run.

The ratios move with the machine's state more than with the code: the exact routes are a few
hundred microseconds of small numpy/LAPACK calls, while the simulation's time (100 000 steps of
matrix products and an FFT synthesis) varied from 0.09 s to 0.8 s between runs on a loaded 2-core
machine, where multithreaded BLAS on small products contends with other processes (compare a run
with ``OPENBLAS_NUM_THREADS=1``).
"""

from __future__ import annotations

from _timing import best_time  # first: pins BLAS to one thread before numpy loads
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


def quarter_car():
    """vehdyn.ride.QuarterCar with the E-QC-ISO-C numbers, restricted to the case's four outputs."""
    from vehdyn.ride import QuarterCar

    qc = QuarterCar.from_parameters(sprung_mass=300.0, unsprung_mass=60.0, spring_rate=16000.0, damping=1000.0,
                                    tire_stiffness=190000.0, name="quarter car")
    return qc.select(outputs=list(E_QC_ISO_C))


HALF_CAR_OUTPUTS = ["sprung_acceleration", "pitch_acceleration", "suspension_travel_front", "suspension_travel_rear",
                    "dynamic_tire_load_front", "dynamic_tire_load_rear"]


def half_car():
    """vehdyn.ride.BouncePitch (4 DOF, axle rates), wheelbase 2.7 m, restricted to six outputs."""
    from vehdyn.ride import BouncePitch

    bp = BouncePitch.from_parameters(mass=1200.0, pitch_inertia=1800.0, a=1.2, b=1.5, front_spring_rate=30000.0,
                                     rear_spring_rate=32000.0, front_damping=2500.0, rear_damping=2400.0,
                                     front_unsprung_mass=40.0, rear_unsprung_mass=40.0, front_tire_stiffness=200000.0,
                                     rear_tire_stiffness=200000.0, name="half car")
    return bp.select(outputs=HALF_CAR_OUTPUTS)


def run_case(title, model, reference, **kw):
    from vehdyn.ride import random_response

    V = 20.0
    t_lyap, lyap = best_time(lambda: random_response(model, "C", V, method="lyapunov", **kw), 20)
    t_pade, pade = (best_time(lambda: random_response(model, "C", V, method="lyapunov", delay="pade", **kw), 20)
                    if kw else (None, None))
    t_psd, psd = best_time(lambda: random_response(model, "C", V, method="psd", **kw), 7)
    t_sim, sim = best_time(lambda: random_response(model, "C", V, method="simulation", duration=100.0,
                                                   sample_rate=1000.0, seed=1, **kw), 3)
    ref = reference(psd)
    print(f"\n{title}")
    print(f"{'route':<12}{'time [s]':>12}{'sim/route':>12}   max rel. error   stated error (max rel.)")
    rows = [("lyapunov", t_lyap, lyap, "0 (exact" + (" delay)" if kw else ")"))]
    if kw:
        rows.append(("lyap.pade", t_pade, pade, "0 (but Pade 10 delay)"))
    for name, t, res, stated in (*rows,
                                 ("psd", t_psd, psd, f"{np.max(psd.error / psd.rms):.1e} (quadrature bound)"),
                                 ("simulation", t_sim, sim, f"{np.max(sim.error / sim.rms):.1e} (1 std. error)")):
        err = np.max(np.abs(res.rms / ref - 1))
        print(f"{name:<12}{t:>12.3g}{t_sim / t:>12.3g}   {err:>14.2e}   {stated}")
    print("  r.m.s. per output (lyapunov | psd | simulation):")
    for k, o in enumerate(lyap.output_names):
        print(f"    {o:<26}{lyap.rms[k]:>13.6g}{psd.rms[k]:>13.6g}{sim.rms[k]:>13.6g}")
    return t_sim / t_lyap, t_sim / t_psd, (t_sim / t_pade if t_pade else None)


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
          f"(Pade delay {r2[2]:.0f}x), PSD integral {r1[1]:.0f}x / {r2[1]:.0f}x (quarter car / half car)")


if __name__ == "__main__":
    main()
