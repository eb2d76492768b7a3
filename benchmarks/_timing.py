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

__all__ = ["best_time"]


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
