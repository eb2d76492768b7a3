"""Where the compiled Magic Formula ``forces`` spends its time, and how fast it could be at all.

Issue 4 asks for ``MagicFormula.forces`` at 10 M points/s on one core. This script measures, in
one run on one core, what bounds the compiled (numba) backend, so that the gap is a measured
number and not a guess:

1. the best-case cost of each branchless math function of :mod:`vehdyn.tire._fast_math` (and
   of sqrt), inlined in a vectorized loop of independent calls: its throughput;
2. how many of each the ``forces`` kernel evaluates per point: the kernel's own Python source run
   with a counting namespace at points that take every rare branch (low speed, the
   rolling-resistance ramp), because the vectorized loop computes such branches for every point;
3. the compiled ``forces`` loop (MF 6.1, combined slip, no camber: the benchmark's inputs of
   ``bench_tire.py``) as shipped, and compiled again with each of these functions replaced by one
   fused multiply-add (wrong values, everything else the same): the cost of the rest;
4. the bound: rest + sum(count x best-case cost per call), i.e. the rate if every function ran at
   its isolated throughput, and as ratios to the shipped loop (the machine's speed drifts by up
   to ~30 % between runs; ratios within one run much less).

Needs numba. Compiles two loops (~1 minute). Run: ``python benchmarks/bench_tire_anatomy.py``.
"""

from __future__ import annotations

from _timing import best_time  # first: pins BLAS to one thread before numpy loads
import collections
import math
import types

import numpy as np

from bench_tire import inputs  # the same combined-slip points as bench_tire.py
from vehdyn import data_path
from vehdyn.tire import magic_formula
from vehdyn.tire._mf_ops import ScalarOps

N_POINTS = 100_000
FUNCTIONS = ("atan", "sin", "cos", "tan", "exp", "pow", "sqrt", "acos", "log10")


def function_counts(tire):
    """Calls of each math function per point of the ``forces`` kernel inside the vectorized loop.

    The kernel runs on two points that take every rare branch (below VXLOW: the low-speed factor;
    kappa in the rolling-resistance ramp). A call whose arguments are the same at both points (the
    inflation-pressure power, with one pressure) is loop-invariant: LLVM computes it once outside
    the loop, so it is not counted; nor is a repeated call with the same arguments at a point
    (LLVM computes it once).
    """
    def calls_at(fz, kappa, alpha, vx):
        calls = []

        def counted(name, function):
            def wrapper(*args):
                calls.append((name, args))
                return function(*args)
            return staticmethod(wrapper)

        ops = type("CountingOps", (ScalarOps,), {name: counted(name, getattr(ScalarOps, name)) for name in FUNCTIONS})
        magic_formula.forces_kernel(ops, tire._c, fz, kappa, alpha, 0.0, vx, tire._c.NOMPRES, True, False)
        return calls

    vxlow = tire._c.VXLOW
    first, second = calls_at(3000.0, 0.1, 0.1, 0.5 * vxlow), calls_at(4100.0, 0.05, -0.07, 0.7 * vxlow)
    if [name for name, _ in first] != [name for name, _ in second]:
        raise RuntimeError("the kernel took different branches at the two points; choose other points")
    varying = {(name, a) for (name, a), (_, b) in zip(first, second) if a != b}  # a set: a repeated call is one
    return collections.Counter(name for name, _ in varying)


def function_costs(wanted):
    """Best-case cost [ns per call per point] of the compiled math functions in ``wanted``: a vectorized
    loop of independent calls (throughput)."""
    import numba
    from numba.extending import register_jitable

    from vehdyn.tire import _fast_math, _mf_numba

    def make(function, arity):
        if arity == 2:
            function_1 = register_jitable(forceinline=True)(lambda y: function(y, 1.3))
        else:
            function_1 = function

        def loop(x, out):
            for i in range(x.shape[0]):
                y = 0.0
                for k in range(8):
                    y += function_1(x[i] * (1.0 + 0.1 * k))
                out[i] = y
        return _mf_numba._WideVectors(numba.njit(error_model="numpy")(loop))

    sqrt = register_jitable(forceinline=True)(lambda y: math.sqrt(y))
    functions = {name: getattr(_fast_math, "fast_" + name) for name in FUNCTIONS if name != "sqrt"}
    functions["sqrt"] = sqrt
    x = np.random.default_rng(0).uniform(0.1, 2.0, 4096)  # in every function's domain (log10, sqrt, acos)
    x_acos = x / 2.5
    out = np.empty_like(x)
    costs = {}
    for name, function in functions.items():
        if name not in wanted:
            continue
        arity = 2 if name == "pow" else 1
        argument = x_acos if name == "acos" else x
        loop = make(function, arity)
        loop(argument, out)
        seconds, _ = best_time(lambda: loop(argument, out), repeats=300)
        costs[name] = seconds / (8 * argument.size) * 1e9
    return costs


def forces_rates(tire, args):
    """Points/s of the shipped compiled ``forces`` loop and of the same loop without transcendental functions."""
    import numba

    from vehdyn.tire import _fast_math, _mf_numba

    vectors = tuple(_mf_numba._as_vector(v) for v in (*args, np.array(tire._c.NOMPRES)))
    n = args[0].size
    out = np.empty((6, n))

    def rate(loop):
        loop(tire._c, vectors, True, False, out, 0, n)  # compile (or load from the cache)
        seconds, _ = best_time(lambda: loop(tire._c, vectors, True, False, out, 0, n), repeats=30)
        return n / seconds

    shipped = rate(_mf_numba._compiled(_mf_numba._forces_loop))

    @numba.extending.register_jitable(forceinline=True)
    def stand_in(x):
        return _fast_math.fma(x, 0.99, 0.01)

    @numba.extending.register_jitable(forceinline=True)
    def stand_in_2(x, y):
        return _fast_math.fma(x, y, 0.01)

    ops = types.ModuleType("OPS_WITHOUT_TRANSCENDENTALS")  # a new namespace: numba compiles the kernel anew
    vars(ops).update({k: v for k, v in vars(_mf_numba.OPS_VECTOR).items() if not k.startswith("__")})
    for name in FUNCTIONS:
        setattr(ops, name, stand_in)
    ops.pow = stand_in_2
    source = _mf_numba._forces_loop
    loop = types.FunctionType(source.__code__, dict(source.__globals__, OPS_VECTOR=ops), "forces_loop_without_functions")
    without = rate(_mf_numba._WideVectors(numba.njit(nogil=True, error_model="numpy")(loop)))
    return shipped, without


def main() -> None:
    try:
        import numba  # noqa: F401
    except ImportError:
        print("numba is not installed: nothing to measure (pip install 'vehdyn[fast]').")
        return
    tire = magic_formula.MagicFormula.from_tir(data_path("tires", "MagicFormula61_Parameters.tir"))
    counts = function_counts(tire)
    costs = function_costs(set(counts))
    args = inputs(N_POINTS, np.random.default_rng(1))
    shipped, without = forces_rates(tire, args)

    print(f"MagicFormula.forces, compiled, MF 6.1 combined slip, {N_POINTS} points, one core")
    print(f"{'function':>9} {'calls/pt':>9} {'ns/call':>8} {'ns/pt':>7}")
    functions_ns = 0.0
    for name in FUNCTIONS:
        if counts[name]:
            functions_ns += counts[name] * costs[name]
            print(f"{name:>9} {counts[name]:>9d} {costs[name]:>8.2f} {counts[name] * costs[name]:>7.1f}")
    shipped_ns, rest_ns = 1e9 / shipped, 1e9 / without
    bound_ns = rest_ns + functions_ns
    calls = sum(counts.values())
    print(f"\nshipped loop:                           {shipped_ns:6.1f} ns/pt = {shipped / 1e6:5.2f} M points/s")
    print(f"same loop, functions replaced by fma:    {rest_ns:6.1f} ns/pt = {without / 1e6:5.2f} M points/s")
    print(f"time in the functions (difference):      {shipped_ns - rest_ns:6.1f} ns/pt "
          f"({calls} calls, {(shipped_ns - rest_ns) / calls:.2f} ns each; isolated: {functions_ns:.1f} ns/pt)")
    print(f"bound, functions at isolated throughput: {bound_ns:6.1f} ns/pt = {1e3 / bound_ns:5.2f} M points/s "
          f"(goal 10 M/s = 100 ns/pt)")
    # ratios within this run: the machine's speed drifts between runs, their ratios much less
    print(f"headroom of this formulation: bound/shipped = {shipped_ns / bound_ns:.2f}x; "
          f"the goal needs {shipped_ns / 100.0:.2f}x")


if __name__ == "__main__":
    main()
