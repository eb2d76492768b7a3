"""Tire-law throughput: points per second of ``forces`` (and of the Magic Formula when present).

For every law, ``forces`` is timed on 1e3, 1e5 and 1e6 combined-slip points (random loads, slip
ratios, slip angles and speeds, both directions of travel) and compared, in the same run, with a
plain per-point Python loop of the same equations (the laws' scalar path, which uses :mod:`math`).
The error column is the largest difference between the vectorized and the per-point results,
relative to mu F_z. ``MagicFormula.evaluate`` (MF 6.1, combined slip, all outputs) and
``MagicFormula.forces`` are timed the same way on each backend: numpy, and numba (when installed)
on one core and on all cores, with the ratio to numpy and numba's first-call (compile or cache
load) time.

Run: ``python benchmarks/bench_tire.py [--quick] [--cold]``.
"""

from __future__ import annotations

from _timing import best_time  # first: pins BLAS to one thread before numpy loads
import argparse
import os
import time

import numpy as np

from vehdyn import data_path
from vehdyn.tire import BrushTire, DugoffTire, FialaTire, LinearTire

SIZES = (1_000, 100_000, 1_000_000)
LOOP_POINTS = 20_000  # points timed in the per-point loop (its rate does not depend on the size)


def inputs(n, rng):
    """Random combined-slip inputs: loads 0-8 kN, |kappa| <= 0.3, |alpha| <= 0.25 rad, |vx| <= 40 m/s."""
    return (rng.uniform(0.0, 8000.0, n), rng.uniform(-0.3, 0.3, n), rng.uniform(-0.25, 0.25, n),
            np.zeros(n), rng.uniform(-40.0, 40.0, n))


def loop_rate_and_error(law, args, reference):
    """Points/s of a per-point Python loop over the law's scalar path, and its largest deviation."""
    fz, kappa, alpha, gamma, vx = (a[:LOOP_POINTS].tolist() for a in args)
    start = time.perf_counter()
    rows = [law.forces(fz[i], kappa[i], alpha[i], gamma[i], vx[i]) for i in range(len(fz))]
    rate = len(fz) / (time.perf_counter() - start)
    fx = np.array([r.fx for r in rows])
    fy = np.array([r.fy for r in rows])
    scale = np.maximum(getattr(law, "mu", 1.0) * np.asarray(fz), 1.0)
    error = max(np.max(np.abs(fx - reference.fx[:LOOP_POINTS]) / scale),
                np.max(np.abs(fy - reference.fy[:LOOP_POINTS]) / scale))
    return rate, error


def main(quick: bool = False, cold: bool = False) -> None:
    rng = np.random.default_rng(1)
    sizes = SIZES[:2] if quick else SIZES
    laws = {
        "linear": LinearTire(cornering_stiffness=80000.0, slip_stiffness=100000.0, nominal_load=4000.0),
        "brush": BrushTire(contact_half_length=0.08, tread_stiffness=6e6, mu=1.0, mu_sliding=0.8),
        "fiala": FialaTire(cornering_stiffness=80000.0, mu=1.0, contact_half_length=0.08),
        "dugoff": DugoffTire(cornering_stiffness=80000.0, slip_stiffness=100000.0, mu=1.0),
    }
    data = {n: inputs(n, rng) for n in sizes}
    print(f"{'law':<22}{'points':>10}{'time [s]':>12}{'M points/s':>12}{'loop M pts/s':>14}{'ratio':>9}"
          f"{'max error':>12}")
    for name, law in laws.items():
        reference = law.forces(*data[max(sizes)])
        loop_rate, error = loop_rate_and_error(law, data[max(sizes)], reference)
        for n in sizes:
            seconds, _ = best_time(lambda: law.forces(*data[n]), 9 if n < 1_000_000 else 5)
            rate = n / seconds
            print(f"{name + '.forces':<22}{n:>10}{seconds:>12.3e}{rate / 1e6:>12.2f}{loop_rate / 1e6:>14.3f}"
                  f"{rate / loop_rate:>9.0f}{error:>12.1e}")
    try:
        from vehdyn.tire import magic_formula
    except ImportError:
        print("\nMagicFormula: vehdyn.tire.magic_formula is not importable in this checkout; skipped.")
        return
    magic_formula_rates(data, sizes, cold)


def magic_formula_rates(data, sizes, cold: bool = False) -> None:
    """MF 6.1 ``evaluate`` (all outputs, combined slip) and ``forces`` on each backend.

    numpy: vectorized, chunked (one core). numba: the same equation functions compiled into one
    per-point loop that LLVM vectorizes (32 points per iteration with AVX-512), serial (one core) and,
    as a second figure, in one thread per core. The loop column is a plain per-point Python loop of
    the same equations (the float path of a scalar call); "vs numpy" is the rate over numpy's at the
    same size. The error column is the largest difference from the numpy backend relative to the
    output's nominal size (FNOMIN for forces, FNOMIN*R0 for moments). The first compiled call of a
    process loads the loops from numba's on-disk cache, or compiles them (``--cold``: timed in a
    fresh process with an empty cache).
    """
    from vehdyn.tire import magic_formula

    tire = magic_formula.MagicFormula.from_tir(data_path("tires", "MagicFormula61_Parameters.tir"))
    backends = [("numpy", False)]
    if magic_formula.numba_available():
        backends += [("numba", False), ("numba", True)]
        threads = os.cpu_count()
    else:
        print("\nMagicFormula: numba is not installed; numpy backend only (pip install vehdyn[fast]).")
    scale = {"fx": tire.nominal_load, "fy": tire.nominal_load, "mz": tire.nominal_load * tire.unloaded_radius}
    print(f"\n{'MF 6.1':<22}{'backend':>14}{'points':>10}{'time [s]':>12}{'M points/s':>12}{'loop M pts/s':>14}"
          f"{'ratio':>9}{'vs numpy':>10}{'max error':>12}")
    best = {}
    first_call = {}
    for method in ("forces", "evaluate"):
        function = getattr(tire, method)
        fz0, kappa0, alpha0, gamma0, vx0 = (a[:2000].tolist() for a in data[max(sizes)])
        start = time.perf_counter()
        for i in range(len(fz0)):
            function(fz0[i], kappa0[i], alpha0[i], gamma0[i], vx0[i], backend="numpy")
        loop_rate = len(fz0) / (time.perf_counter() - start)
        numpy_rate = {}
        for backend, parallel in backends:
            magic_formula.NUMBA_PARALLEL = parallel
            try:
                start = time.perf_counter()
                function(*(a[:10] for a in data[min(sizes)]), backend=backend)  # compile (or load the cache)
                first_call.setdefault((method, backend), time.perf_counter() - start)
                for n in sizes:
                    fz, kappa, alpha, gamma, vx = data[n]
                    fz = fz + 500.0  # away from zero load, where MF-specific limits apply
                    seconds, _ = best_time(lambda: function(fz, kappa, alpha, gamma, vx, backend=backend),
                                           5 if n < 1_000_000 else 3)
                    rate = n / seconds
                    numpy_rate.setdefault(n, rate)
                    error = 0.0
                    if backend != "numpy":
                        ours = function(fz, kappa, alpha, gamma, vx, backend=backend)
                        reference = function(fz, kappa, alpha, gamma, vx, backend="numpy")
                        error = max(np.max(np.abs(getattr(ours, k) - getattr(reference, k))) / s
                                    for k, s in scale.items())
                    label = backend + (f" {threads} thr" if parallel else " 1 core")
                    if not parallel:
                        best[method] = max(best.get(method, 0.0), rate)
                    print(f"{'MF6.1.' + method:<22}{label:>14}{n:>10}{seconds:>12.3e}{rate / 1e6:>12.2f}"
                          f"{loop_rate / 1e6:>14.3f}{rate / loop_rate:>9.0f}{rate / numpy_rate[n]:>10.2f}"
                          f"{error:>12.1e}")
            finally:
                magic_formula.NUMBA_PARALLEL = False
    if magic_formula.numba_available():
        print("First numba call in this process (cache load, or compilation if not cached) [s]: "
              + ", ".join(f"{m} {t:.1f}" for (m, b), t in first_call.items() if b == "numba"))
        if cold:
            print(f"Compilation from scratch (empty cache, fresh process) [s]: {cold_compile_seconds():.1f}")
    goals = {"forces": 10e6, "evaluate": 3e6}
    print("Goal (issue 4, one core): forces >= 10 M points/s, evaluate >= 3 M points/s "
          "(MFeval/Octave: 0.54 M/s, full outputs). Best here: "
          + ", ".join(f"{m} {best[m] / 1e6:.2f} M/s ({'met' if best[m] >= goals[m] else 'not met'})" for m in goals))


def cold_compile_seconds() -> float:
    """Seconds for the first forces and evaluate calls in a new process with an empty numba cache."""
    import subprocess
    import sys
    import tempfile

    script = ("import time, numpy as np; from vehdyn import data_path; from vehdyn.tire import MagicFormula\n"
              "t = MagicFormula.from_tir(data_path('tires', 'MagicFormula61_Parameters.tir'))\n"
              "s = time.perf_counter(); t.forces(np.ones(10) * 4e3, 0.0, 0.1, backend='numba')\n"
              "t.evaluate(np.ones(10) * 4e3, 0.0, 0.1, backend='numba'); print(time.perf_counter() - s)")
    with tempfile.TemporaryDirectory() as cache:
        env = {**os.environ, "NUMBA_CACHE_DIR": cache}
        result = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True, text=True, check=True)
    return float(result.stdout.split()[-1])


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="1e3 and 1e5 points only")
    parser.add_argument("--cold", action="store_true", help="also time numba's compilation with an empty cache")
    arguments = parser.parse_args()
    main(arguments.quick, arguments.cold)
