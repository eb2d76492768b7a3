"""How far numpy's float64 transcendental ufuncs are from the C library on this CPU, with numpy's SIMD
dispatch on and off.

``python tests/_perturb/dispatch_differences.py`` evaluates each ufunc on 200,000 arguments in two
subprocesses, one with the host's dispatch and one with ``NPY_DISABLE_CPU_FEATURES`` set to every
target this numpy dispatches to, and prints, per function, the share of arguments whose results
differ and the largest difference in ulps: SIMD on against SIMD off, and each against the C library
(``math``, which numba-compiled code calls too).
"""

from __future__ import annotations

import math
import os
import subprocess
import sys
import tempfile

import numpy as np

N = 200_000
ARGUMENTS = {  # (numpy name, math name, arguments)
    "sin": ("sin", lambda r: r.uniform(-10, 10, N)), "cos": ("cos", lambda r: r.uniform(-10, 10, N)),
    "tan": ("tan", lambda r: r.uniform(-1.5, 1.5, N)), "arctan": ("atan", lambda r: r.normal(0, 5, N)),
    "arcsin": ("asin", lambda r: r.uniform(-1, 1, N)), "arccos": ("acos", lambda r: r.uniform(-1, 1, N)),
    "exp": ("exp", lambda r: r.uniform(-30, 30, N)), "expm1": ("expm1", lambda r: r.uniform(-3, 3, N)),
    "log": ("log", lambda r: np.exp(r.uniform(-20, 20, N))), "log10": ("log10", lambda r: np.exp(r.uniform(-5, 5, N))),
    "log1p": ("log1p", lambda r: r.uniform(-0.9, 3, N)), "sinh": ("sinh", lambda r: r.uniform(-5, 5, N)),
    "cosh": ("cosh", lambda r: r.uniform(-5, 5, N)), "tanh": ("tanh", lambda r: r.normal(0, 2, N)),
    "arctanh": ("atanh", lambda r: r.uniform(-0.99, 0.99, N)),
}
BINARY = {"power": ("pow", lambda r: (r.uniform(0.01, 10, N), r.uniform(-3, 3, N))),
          "arctan2": ("atan2", lambda r: (r.normal(size=N), r.normal(size=N)))}


def _arguments(name):
    rng = np.random.default_rng(sorted({**ARGUMENTS, **BINARY}).index(name))
    return (ARGUMENTS[name][1](rng),) if name in ARGUMENTS else BINARY[name][1](rng)


def _evaluate(path):
    """In a subprocess: every ufunc's results into the .npz file ``path``."""
    np.savez(path, **{name: getattr(np, name)(*_arguments(name)) for name in {**ARGUMENTS, **BINARY}})


def _ulps(a, b):
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    from _tolerances import ulp_distance

    return ulp_distance(a, b)


def main():
    try:
        from numpy._core import _multiarray_umath as umath
    except ImportError:  # numpy < 2
        from numpy.core import _multiarray_umath as umath
    off = " ".join(umath.__cpu_dispatch__)
    found = [f for f in umath.__cpu_dispatch__ if umath.__cpu_features__.get(f)]
    print(f"numpy {np.__version__}: baseline {' '.join(umath.__cpu_baseline__)}, dispatches to "
          f"{' '.join(found) or 'nothing more'} here; off: NPY_DISABLE_CPU_FEATURES={off!r}")
    with tempfile.TemporaryDirectory() as folder:
        results = {}
        for setting, extra in (("on", {}), ("off", {"NPY_DISABLE_CPU_FEATURES": off})):
            path = os.path.join(folder, setting + ".npz")
            subprocess.run([sys.executable, __file__, "--evaluate", path], check=True, env={**os.environ, **extra})
            results[setting] = dict(np.load(path))
    print(f"{'function':10s} {'on vs off':>20s} {'on vs C library':>20s} {'off vs C library':>20s}   ({N} arguments)")
    for name in {**ARGUMENTS, **BINARY}:
        math_name = (ARGUMENTS.get(name) or BINARY[name])[0]
        library = np.frompyfunc(getattr(math, math_name), len(_arguments(name)), 1)
        reference = library(*_arguments(name)).astype(float)
        cells = []
        for a, b in ((results["on"][name], results["off"][name]), (results["on"][name], reference),
                     (results["off"][name], reference)):
            d = _ulps(a, b)
            cells.append(f"{np.count_nonzero(d) / d.size:7.2%} max {d.max():3.0f} ulp")
        print(f"{name:10s} " + " ".join(f"{c:>20s}" for c in cells))


if __name__ == "__main__":
    if sys.argv[1:2] == ["--evaluate"]:
        _evaluate(sys.argv[2])
    else:
        main()
