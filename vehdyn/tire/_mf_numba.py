"""Compiled backend of :class:`~vehdyn.tire.MagicFormula`: the same equations under numba.

Imported only on first use of ``backend="numba"`` (or of ``"auto"`` on a large call; numba is
optional: ``pip install vehdyn[fast]``). Nothing here restates an equation. The equation functions
of :mod:`~vehdyn.tire.mf_forces`, :mod:`~vehdyn.tire.mf_moments`, :mod:`~vehdyn.tire.mf_vertical`
and the passes of :mod:`~vehdyn.tire.magic_formula` are registered with
``numba.extending.register_jitable`` (the Python functions stay as they are) and called, one point
at a time, with ``xp`` = :data:`OPS` or :data:`OPS_VECTOR`: the float functions of
:class:`~vehdyn.tire._mf_ops.ScalarOps` compiled, ``div`` giving IEEE inf/nan like numpy
(``error_model="numpy"``), and the branchless math functions of :mod:`~vehdyn.tire._fast_math`
in place of libm's.

Why it is fast: every function is inlined (LLVM ``alwaysinline``), so the loop over the points of
a block is one straight body of arithmetic, selects and loads/stores with no call and no inner
loop of unknown length; LLVM then vectorizes it, 8 points per AVX-512 instruction (4 with AVX2),
32 points per iteration on AVX-512 (see :class:`_WideVectors`).
What makes that possible: the coefficients passed by value (no pointer to check for aliasing),
the inputs of a block copied into one buffer and the results written to another (indices ``i``
only), the rolling-radius iteration bounded in :data:`OPS_VECTOR` (points that need more steps,
and MF 6.2's loaded-radius iteration, come back as NaN and are repeated one by one with
:data:`OPS`), and ``arcp`` in the equations (x/c becomes x*(1/c), hoisted out of the loop).

Each loop has a copy of the kernel for the default switches (and the usual overturning-moment
form, and one inflation pressure, whose terms are then computed once outside the loop), one more
for blocks without camber, and a general one: a switch that is not a constant inside the
vectorized loop has both of its branches computed for every point.

Speed (``benchmarks/bench_tire.py``, MF 6.1, one core of the development machine's ~2.1 GHz
AVX-512 Xeon): ``forces`` 5.4-7.9 M points/s and ``evaluate`` 3.2-4 M points/s, 4-4.7x and
3.2-3.5x the numpy backend. The first use compiles both loops in ~1 minute; afterwards they load
from numba's on-disk cache in ~1 s (``cache=True``, keyed on the source of every module that
contributes equations, see :data:`SOURCE_MODULES`, so editing an equation recompiles). What
limits it (``benchmarks/bench_tire_anatomy.py``): a point of ``forces`` calls 49 math functions
(22 atan, 8 cos, 7 sqrt, 6 sin, 4 tan, an exp and a power), 80-120 of its 125-160 ns; the same
loop with each function replaced by one multiply-add runs at ~22 M points/s (~45 ns). Adding
every function at its best isolated throughput (1.3-3.9 ns per call and point) to that estimates
the best this formulation can do at this precision on this core: 7.6-8.8 M points/s.

:data:`OPS` is also what a compiled vehicle model calls ``magic_formula.forces_kernel`` with, one
point at a time.
"""

from __future__ import annotations

import contextlib
import functools
import math
import os
import sys
import tempfile
import threading
import types
from concurrent.futures import ThreadPoolExecutor

import llvmlite.binding as llvm_binding
import numba
import numpy as np
from numba.extending import register_jitable

from vehdyn.simulation.compiled import CALLEE_ONLY, compiled_copy, source_stamp
from vehdyn.tire import _fast_math, _mf_ops, magic_formula, mf_forces, mf_moments, mf_vertical
from vehdyn.tire._mf_ops import ScalarOps

__all__ = ["OPS", "OPS_VECTOR", "run"]

_JIT_OPTIONS = {"error_model": "numpy", **CALLEE_ONLY}  # x/0 = inf, 0/0 = nan (MFeval's MATLAB and numpy), no exceptions
# in the equations: x/c as x*(1/c), with 1/c computed once outside the loop (within an ulp; assumes
# nothing about inf/nan, so MFeval's inf/nan cases stay). Not "contract": fused multiply-adds change
# ill-conditioned results (the MF 6.1 deflection's quadratic formula) by 1e-11 against numpy.
_EQUATION_FASTMATH = {"arcp"}
_INLINE = {"forceinline": True}  # LLVM alwaysinline: one flat loop body that LLVM can vectorize

# ---- xp for compiled code: math functions and ScalarOps' float functions, compiled -------------
OPS = types.ModuleType("vehdyn.tire._mf_numba.OPS")
OPS.__doc__ = "The ``xp`` namespace of the equations inside numba-compiled code (one point, floats)."
for _name in ("sqrt", "copysign"):
    setattr(OPS, _name, getattr(math, _name))
for _name in ("sin", "cos", "tan", "atan", "acos", "exp", "log10", "pow"):
    setattr(OPS, _name, getattr(_fast_math, "fast_" + _name))
for _name in ("where", "minimum", "maximum", "clip", "fmax", "isnan", "any", "all", "full_broadcast", "div_ieee"):
    setattr(OPS, _name, numba.njit(**_JIT_OPTIONS)(getattr(ScalarOps, _name)))
OPS.div = OPS.div_ieee  # ScalarOps.div raises for numpy to take over; compiled code is IEEE itself
OPS.sign = numba.njit(**_JIT_OPTIONS)(_mf_ops._sign)
OPS.abs = numba.njit(**_JIT_OPTIONS)(lambda x: abs(x))
OPS.scalar = True
OPS.iterate_to_convergence = True
OPS.radius_iterations = _mf_ops.RADIUS_ITERATIONS

# the same, for loops that LLVM vectorizes: no loop of unknown length inside the loop over points
OPS_VECTOR = types.ModuleType("vehdyn.tire._mf_numba.OPS_VECTOR")
OPS_VECTOR.__doc__ = ("``OPS`` with the rolling-radius iteration unrolled to a fixed number of steps (NaN radius "
                      "where a point needs more) and no MF 6.2 loaded-radius iteration (NaN): the caller "
                      "repeats those points with ``OPS``.")
vars(OPS_VECTOR).update({k: v for k, v in vars(OPS).items() if not k.startswith("__")})
OPS_VECTOR.iterate_to_convergence = False
OPS_VECTOR.radius_iterations = 8

# ---- the equation functions, callable from compiled code ----------------------------------------
_EQUATION_MODULES = (_fast_math, _mf_ops, mf_forces, mf_moments, mf_vertical, magic_formula)
_EQUATIONS = (
    (_mf_ops, ("sign_nonzero", "cos_atan")),
    (mf_forces, ("turn_slip_spin", "longitudinal_pure", "lateral_pure", "longitudinal_combined",
                 "lateral_combined_factor", "lateral_combined")),
    (mf_moments, ("overturning_moment", "rolling_resistance_moment", "aligning_moment")),
    (mf_vertical, ("_free_radius", "rolling_radius", "loaded_radius_mf61", "_load_mf62", "loaded_radius_mf62",
                   "contact_patch", "carcass_stiffness")),
    (magic_formula, ("_pass_inputs", "_forces_pass", "forces_kernel",
                     "lateral_force_kernel", "_full_kernel")),
)
for _module, _names in _EQUATIONS:
    for _name in _names:
        register_jitable(**_JIT_OPTIONS, **_INLINE, fastmath=_EQUATION_FASTMATH)(getattr(_module, _name))

forces_kernel = magic_formula.forces_kernel
_full_kernel = magic_formula._full_kernel


_BLOCK = 128  # points per block: a block's inputs are copied into one buffer (one pointer for LLVM)


@register_jitable(**CALLEE_ONLY)
def _load_block(inputs, start, m, buffer):
    """Rows 0..len(inputs)-1 of ``buffer[:, :m]`` = the inputs' points start..start+m (one value: repeated)."""
    for k in range(len(inputs)):
        values = inputs[k]
        if values.shape[0] == 1:
            buffer[k, :m] = values[0]
        else:
            buffer[k, :m] = values[start:start + m]


@register_jitable(**CALLEE_ONLY)
def _zero_inclination(values, m):
    """Whether values[:m] are all +0.0: then the loops pass the literal 0.0, and (with the limits
    CAMMIN <= 0 <= CAMMAX tested by the caller, the same comparisons as the clip in the kernel)
    LLVM drops every camber term, among them the second, camber-free Fy0 that Mz needs."""
    for k in range(m):
        if values[k] != 0.0 or math.copysign(1.0, values[k]) < 0.0:
            return False
    return True


def _column_store(n):
    """A compiled ``store(results, i, r)``: results[k, i] = r[k] for k < n, one statement each
    (a loop over a tuple compiles to a switch, which stops LLVM from vectorizing)."""
    body = "\n".join(f"    results[{k}, i] = r[{k}]" for k in range(n))
    namespace = {}
    exec(f"def store(results, i, r):\n{body}\n", namespace)  # noqa: S102 (generated from n only)
    return register_jitable(forceinline=True, **CALLEE_ONLY)(namespace["store"])


_store_forces = _column_store(6)
_store_full = _column_store(29)


def _forces_loop(c, inputs, limits, alpha_star, out, first, stop):
    buffer = np.empty((6, _BLOCK))
    results = np.empty((6, _BLOCK))
    for start in range(first, stop, _BLOCK):
        m = min(_BLOCK, stop - start)
        _load_block(inputs, start, m, buffer)
        # vectorized by LLVM: no calls, no inner loops, indices i only; the default switches (and
        # the usual overturning-moment form) as constants, one pressure (see _full_loop)
        if limits and not alpha_star and not c.mx_draft_form and inputs[5].shape[0] == 1:
            pressure = inputs[5][0]  # one value: the pressure terms are computed once, outside the loop
            if not (0.0 < c.CAMMIN) and not (0.0 > c.CAMMAX) and _zero_inclination(buffer[3], m):
                for i in range(m):  # no camber: the camber-free lateral force of Mz is Fy0 itself
                    _store_forces(results, i, forces_kernel(OPS_VECTOR, c, buffer[0, i], buffer[1, i],
                                                             buffer[2, i], 0.0, buffer[4, i], pressure, True, False))
            else:
                for i in range(m):
                    _store_forces(results, i, forces_kernel(OPS_VECTOR, c, buffer[0, i], buffer[1, i],
                                                             buffer[2, i], buffer[3, i], buffer[4, i], pressure, True,
                                                             False))
        else:
            for i in range(m):
                _store_forces(results, i, forces_kernel(OPS_VECTOR, c, buffer[0, i], buffer[1, i], buffer[2, i],
                                                         buffer[3, i], buffer[4, i], buffer[5, i], limits,
                                                         alpha_star))
        out[:, start:start + m] = results[:, :m]


def _full_loop(c, inputs, omega_given, limits, alpha_star, turn_slip, out, first, stop):
    buffer = np.empty((8, _BLOCK))
    results = np.empty((29, _BLOCK))
    for start in range(first, stop, _BLOCK):
        m = min(_BLOCK, stop - start)
        _load_block(inputs, start, m, buffer)
        # vectorized: iterations bounded (OPS_VECTOR), NaN radii where they did not finish. The
        # default switches get a loop of their own with the switches as constants, folded away; in
        # the general loop both branches of every switch are computed for every point (if-conversion).
        # The same for the overturning moment's form: the rare draft form (c.mx_draft_form) is left
        # to the general loop, so that the other one is known inside the first (LLVM propagates
        # the condition tested here to the same test inside the kernel)
        if (limits and not alpha_star and not turn_slip and not omega_given and not c.mx_draft_form
                and inputs[6].shape[0] == 1):
            pressure = inputs[6][0]  # one value (see _forces_loop)
            if not (0.0 < c.CAMMIN) and not (0.0 > c.CAMMAX) and _zero_inclination(buffer[3], m):
                for i in range(m):  # no camber (see _forces_loop)
                    r = _full_kernel(OPS_VECTOR, c, buffer[0, i], buffer[1, i], buffer[2, i], 0.0, buffer[4, i],
                                     buffer[5, i], pressure, buffer[7, i], False, True, False, False)
                    _store_full(results, i, r)
            else:
                for i in range(m):
                    r = _full_kernel(OPS_VECTOR, c, buffer[0, i], buffer[1, i], buffer[2, i], buffer[3, i],
                                     buffer[4, i], buffer[5, i], pressure, buffer[7, i], False, True, False, False)
                    _store_full(results, i, r)
        else:
            for i in range(m):
                r = _full_kernel(OPS_VECTOR, c, buffer[0, i], buffer[1, i], buffer[2, i], buffer[3, i],
                                 buffer[4, i], buffer[5, i], buffer[6, i], buffer[7, i], omega_given, limits,
                                 alpha_star, turn_slip)
                _store_full(results, i, r)
        for i in range(m):  # those points again, one by one, iterated to convergence (OPS)
            if math.isnan(results[12, i]) or math.isnan(results[13, i]) or math.isnan(results[19, i]):
                r = _full_kernel(OPS, c, buffer[0, i], buffer[1, i], buffer[2, i], buffer[3, i], buffer[4, i],
                                 buffer[5, i], buffer[6, i], buffer[7, i], omega_given, limits, alpha_star,
                                 turn_slip)
                for k in range(29):
                    results[k, i] = r[k]
        out[:, start:start + m] = results[:, :m]


SOURCE_MODULES = (*_EQUATION_MODULES, sys.modules[__name__])
"""Every module whose source compiled code calling the Magic Formula contains (for cache names)."""


_COMPILED = {}


def _compiled(loop):
    """The loop compiled (cached on disk, per digest of :data:`SOURCE_MODULES`), releasing the GIL."""
    if loop.__name__ not in _COMPILED:
        name = f"{loop.__name__}_{source_stamp(*SOURCE_MODULES)}"
        _COMPILED[loop.__name__] = _WideVectors(compiled_copy(loop, name, nogil=True))
    return _COMPILED[loop.__name__]


_AVX512_VECTOR_WIDTH = 32  # doubles per vectorized iteration on AVX-512: 4 zmm registers per operation


class _WideVectors:
    """A dispatcher whose compilation vectorizes 32 points per loop iteration on AVX-512 machines.

    LLVM's default for AVX-512 CPUs is 256-bit vectors (4 doubles) and one vector per iteration.
    These loop bodies are long chains of dependent arithmetic (~40 inlined transcendental
    functions per point), too long for the processor's out-of-order window to overlap one
    iteration with the next: the loop is bound by latency, not by execution ports (``llvm-mca``:
    ~2,600 cycles per iteration of 8 points against ~880 for the ports alone). A vector width of
    32 doubles makes every operation four independent 512-bit instructions side by side, which
    the processor runs in parallel: measured 12-17 % faster than one 512-bit vector per
    iteration (``forces`` and ``evaluate``), which was itself faster than LLVM's default. Results
    are the same bit for bit (each point's arithmetic is unchanged). The setting is LLVM's global
    ``-force-vector-width``, applied only while numba compiles (or loads from the cache) this
    dispatcher's first call, then reset to LLVM's default (0: cost model). On CPUs without
    AVX-512 LLVM's default is kept (wider settings measured within noise of it with AVX2).
    With it, LLVM prints a "remark: loop not vectorized" to the process's stderr for every loop it
    leaves scalar (numba's helpers); those lines are dropped, anything else written meanwhile is
    passed on.
    """

    _lock = threading.Lock()  # one first call at a time (threads of NUMBA_PARALLEL; stderr is shared)

    def __init__(self, dispatcher):
        self.dispatcher = dispatcher
        self.ready = False

    def __call__(self, *args):
        if self.ready:
            return self.dispatcher(*args)
        with self._lock:
            if self.ready:
                return self.dispatcher(*args)
            wide = "+avx512f" in llvm_binding.get_host_cpu_features().flatten()
            if not wide:
                self.ready = True
                return self.dispatcher(*args)
            with _without_llvm_remarks():
                llvm_binding.set_option("", f"-force-vector-width={_AVX512_VECTOR_WIDTH}")
                try:
                    return self.dispatcher(*args)
                finally:
                    llvm_binding.set_option("", "-force-vector-width=0")
                    self.ready = True


@contextlib.contextmanager
def _without_llvm_remarks():
    """Capture file descriptor 2 (where LLVM writes); pass on every line but LLVM's remarks."""
    sys.stderr.flush()
    saved = os.dup(2)
    with tempfile.TemporaryFile() as capture:
        os.dup2(capture.fileno(), 2)
        try:
            yield
        finally:
            os.dup2(saved, 2)
            os.close(saved)
            capture.seek(0)
            kept = [line for line in capture.read().decode(errors="replace").splitlines(keepends=True)
                    if not line.startswith("remark: ")]
            if kept:
                sys.stderr.write("".join(kept))


def _as_vector(value):
    """An input as a read-only float64 vector (length n, or 1 for one value; one numba type for all)."""
    vector = np.ascontiguousarray(np.reshape(value, -1), dtype=np.float64).view()
    vector.flags.writeable = False
    return vector


@functools.lru_cache(maxsize=64)
def _record(c):
    """The coefficients as a numpy record with the same field names (the equations read ``c.PCX1``
    from either): numba passes a record by reference, for compiled callers of the kernels that call
    from Python often (the loops here take the named tuple by value: no pointer for LLVM to check)."""
    return np.array([tuple(c)], dtype=[(name, np.float64) for name in c._fields])[0]


_PARALLEL_MIN_POINTS = 20_000  # below, one thread


def run(c, inputs, switches, full: bool, n: int, parallel: bool = False):
    """Evaluate n points compiled: ``inputs`` as for the numpy kernels (flat or 0-d arrays).

    With ``parallel``, the points are split into one block per core, evaluated in threads (the
    compiled loop releases the GIL). Returns a tuple of output vectors (length n) in the kernels'
    order.
    """
    vectors = tuple(_as_vector(v) for v in inputs)
    flags = tuple(bool(s) for s in switches)
    out = np.empty((29 if full else 6, n))
    loop = _compiled(_full_loop if full else _forces_loop)

    def block(start, stop):
        loop(c, vectors, *flags, out, start, stop)

    threads = min(os.cpu_count() or 1, n // _PARALLEL_MIN_POINTS) if parallel else 1
    if threads <= 1:
        block(0, n)
    else:
        edges = np.linspace(0, n, threads + 1).astype(int)
        with ThreadPoolExecutor(threads) as pool:
            list(pool.map(block, edges[:-1], edges[1:]))
    return tuple(out)
