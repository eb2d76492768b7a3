"""Compiled backend of :class:`~vehdyn.tire.MagicFormula`: the same equations under numba.

Imported only on first use of ``backend="numba"`` (numba is optional: ``pip install vehdyn[fast]``).
Nothing here restates an equation. The equation functions of :mod:`~vehdyn.tire.mf_forces`,
:mod:`~vehdyn.tire.mf_moments`, :mod:`~vehdyn.tire.mf_vertical` and the passes of
:mod:`~vehdyn.tire.magic_formula` are registered with ``numba.extending.register_jitable`` (the
Python functions stay as they are) and called, one point at a time, with ``xp`` = :data:`OPS`: the
float functions of :class:`~vehdyn.tire._mf_ops.ScalarOps` compiled, with ``div`` giving IEEE
inf/nan like numpy (``error_model="numpy"``). The loops below are compiled with ``cache=True``; the
cache is keyed on the source of every module that contributes equations (see :func:`_source_stamp`),
so editing an equation recompiles.

Speed (``benchmarks/bench_tire.py``): a point costs ~50 scalar libm calls (atan, sin, cos, tan) in
a chain, where numpy evaluates each of them for 8 points at once (AVX-512); on the development
machine this loop is therefore slower than the numpy backend, and ``backend="auto"`` uses numpy.
"""

from __future__ import annotations

import functools
import hashlib
import math
import os
import types
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numba
import numpy as np
from numba.extending import register_jitable

from . import _fast_math, _mf_ops, magic_formula, mf_forces, mf_moments, mf_vertical
from ._mf_ops import ScalarOps

__all__ = ["OPS", "run"]

_JIT_OPTIONS = {"error_model": "numpy"}  # x/0 = inf, 0/0 = nan (MFeval's MATLAB and numpy), no exceptions
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

# ---- the equation functions, callable from compiled code ----------------------------------------
_EQUATION_MODULES = (_fast_math, _mf_ops, mf_forces, mf_moments, mf_vertical, magic_formula)
_EQUATIONS = (
    (_mf_ops, ("sign_nonzero", "cos_atan")),
    (mf_forces, ("turn_slip_spin", "longitudinal_pure", "lateral_pure", "longitudinal_combined",
                 "lateral_combined_factor", "lateral_combined")),
    (mf_moments, ("overturning_moment", "rolling_resistance_moment", "aligning_moment")),
    (mf_vertical, ("_free_radius", "rolling_radius", "loaded_radius_mf61", "_load_mf62", "loaded_radius_mf62",
                   "contact_patch", "carcass_stiffness")),
    (magic_formula, ("_forces_pass", "_forces_kernel", "_full_kernel")),
)
for _module, _names in _EQUATIONS:
    for _name in _names:
        register_jitable(**_JIT_OPTIONS, **_INLINE)(getattr(_module, _name))

_forces_kernel = magic_formula._forces_kernel
_full_kernel = magic_formula._full_kernel


@register_jitable
def _at(values, i):
    """values[i], or values[0] for an input of one value (broadcast without a copy)."""
    return values[i] if values.shape[0] > 1 else values[0]


def _forces_loop(c, fz, kappa, alpha, gamma, vx, pressure, limits, alpha_star, out):
    for i in range(out.shape[1]):
        result = _forces_kernel(OPS, c, _at(fz, i), _at(kappa, i), _at(alpha, i), _at(gamma, i), _at(vx, i),
                                _at(pressure, i), limits, alpha_star)
        for k in range(6):
            out[k, i] = result[k]


def _full_loop(c, fz, kappa, alpha, gamma, phit, vx, pressure, omega, omega_given, limits, alpha_star, turn_slip,
               out):
    for i in range(out.shape[1]):
        result = _full_kernel(OPS, c, _at(fz, i), _at(kappa, i), _at(alpha, i), _at(gamma, i), _at(phit, i),
                              _at(vx, i), _at(pressure, i), _at(omega, i), omega_given, limits, alpha_star,
                              turn_slip)
        for k in range(29):
            out[k, i] = result[k]


def _source_stamp() -> str:
    """A digest of every module whose source the compiled loops contain."""
    digest = hashlib.sha256()
    for module in (*_EQUATION_MODULES, __import__(__name__, fromlist=["_"])):
        digest.update(Path(module.__file__).read_bytes())
    return digest.hexdigest()[:16]


_COMPILED = {}


def _compiled(loop):
    """The loop compiled (cached on disk, per equation-source digest), releasing the GIL."""
    if loop.__name__ not in _COMPILED:
        # a copy of the loop under a name that carries the source digest: numba's on-disk cache is
        # keyed on the qualified name and this file's timestamp only, not on the functions it calls
        name = f"{loop.__name__}_{_source_stamp()}"
        function = types.FunctionType(loop.__code__, loop.__globals__, name, loop.__defaults__, loop.__closure__)
        function.__qualname__ = name
        _COMPILED[loop.__name__] = numba.njit(cache=True, nogil=True, **_JIT_OPTIONS)(function)
    return _COMPILED[loop.__name__]


def _as_vector(value):
    """An input as a float64 vector (length n, or 1 for one value)."""
    return np.ascontiguousarray(np.reshape(value, -1), dtype=np.float64)


@functools.lru_cache(maxsize=64)
def _record(c):
    """The coefficients as a numpy record with the same field names (the equations read ``c.PCX1``
    from either): numba passes a record by reference, where a tuple of ~280 floats would be copied
    into every call of an equation function."""
    return np.array([tuple(c)], dtype=[(name, np.float64) for name in c._fields])[0]


_PARALLEL_MIN_POINTS = 20_000  # below, one thread


def run(c, inputs, switches, full: bool, n: int, parallel: bool = False):
    """Evaluate n points compiled: ``inputs`` as for the numpy kernels (flat or 0-d arrays).

    With ``parallel``, the points are split into one block per core, evaluated in threads (the
    compiled loop releases the GIL). Returns a tuple of output vectors (length n) in the kernels'
    order.
    """
    c = _record(c)
    vectors = [_as_vector(v) for v in inputs]
    flags = tuple(bool(s) for s in switches)
    out = np.empty((29 if full else 6, n))
    loop = _compiled(_full_loop if full else _forces_loop)

    def block(start, stop):
        loop(c, *(v if v.shape[0] == 1 else v[start:stop] for v in vectors), *flags, out[:, start:stop])

    threads = min(os.cpu_count() or 1, n // _PARALLEL_MIN_POINTS) if parallel else 1
    if threads <= 1:
        block(0, n)
    else:
        edges = np.linspace(0, n, threads + 1).astype(int)
        with ThreadPoolExecutor(threads) as pool:
            list(pool.map(block, edges[:-1], edges[1:]))
    return tuple(out)
