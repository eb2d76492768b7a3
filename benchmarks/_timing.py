"""Timing helper shared by the benchmark scripts (run them as ``python benchmarks/bench_*.py``).

Import it before numpy: it pins the BLAS/LAPACK thread pools to one thread (unless the caller set
them), because the speed targets are stated for one core and because a multithreaded OpenBLAS on
tiny matrices can take 10 ms instead of 30 us per call when the other core is busy (measured
here: ``scipy.linalg.expm`` of a 4x4 matrix, 12 ms with two threads under load, 0.03 ms with one).
"""

from __future__ import annotations

import os
import time

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

__all__ = ["best_time", "compiled_rhs_call_time"]


def best_time(fun, repeats: int = 5):
    """Best wall-clock time [s] of ``repeats`` calls of ``fun()`` and the last call's result.

    The minimum is the least disturbed by other load on the machine.
    """
    best, out = float("inf"), None
    for _ in range(max(1, int(repeats))):
        start = time.perf_counter()
        out = fun()
        best = min(best, time.perf_counter() - start)
    return best, out


def compiled_rhs_call_time(model, x, u, step: float = 1e-6, calls: int = 20000) -> float:
    """Best time [s] of one call of ``model``'s compiled rhs inside a compiled loop (no Python between
    calls, as in the compiled integrator), at ``x``, ``u`` with the second state varied by multiples
    of ``step`` so that nothing is constant across calls."""
    import numba
    import numpy as np

    compiled = model.compiled_rhs()
    rhs = compiled.rhs

    @numba.njit
    def loop(n, x, u, args, out):
        for i in range(n):
            x[1] = step * (i % 1000)
            rhs(0.0, x, u, args, out)

    x = np.array(x, dtype=float)
    u = np.asarray(u, dtype=float)
    out = np.empty(model.n_states)
    loop(10, x, u, compiled.args, out)
    best, _ = best_time(lambda: loop(calls, x, u, compiled.args, out), repeats=5)
    return best / calls
