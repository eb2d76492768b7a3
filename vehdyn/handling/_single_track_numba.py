"""Compiled right-hand side of :class:`~vehdyn.handling.SingleTrack` (numba, optional).

Imported only when the compiled backend is used. Nothing here restates a single-track equation:
the functions of :mod:`~vehdyn.handling.single_track_equations` are registered with
``register_jitable`` and run with a compiled ``xp`` (:data:`XP`) whose ``axle_tire_loads`` calls
the axle's tire law (forces and rolling-resistance moment): the Magic Formula through the compiled
equations of :mod:`vehdyn.tire._mf_numba` (``magic_formula._forces_kernel`` on the coefficient record, the same
call as :meth:`MagicFormula.forces` with its defaults ``limits=True``, ``alpha_star=False``; in
force mode without lateral load transfer, where the model takes only F_y at kappa = 0, the lean
``magic_formula._lateral_force_kernel``, bitwise the same F_y at a quarter of the cost), or the
linear law. Other laws (brush, Fiala, Dugoff) have no compiled form: the model then refuses
the compiled backend and names the law.

The library calls that have an exact answer on the usual path are skipped (``XP.cos`` at 0 and pi,
``sin`` and ``tanh`` at 0, ``atan2`` at y = 0: an absent rear steer, the low-speed blend above its
speed, no wheel spin, no crosswind), bitwise the library's results (tested): ~6 % of an rhs call
with Magic Formula tires. (Forcing LLVM to inline every equation and tire law saved another ~25 %
but doubled the cold compile time of every model built on these equations: not done.)
"""

from __future__ import annotations

import functools
import math
import sys
import types
from collections import namedtuple

import numba
import numpy as np
from numba.extending import register_jitable
from numba.np.unsafe.ndarray import to_fixed_tuple

from vehdyn import conventions
from vehdyn.simulation.compiled import CompiledBatch, CompiledModel, compiled_copy, source_stamp
from vehdyn.errors import ParameterError
from vehdyn.tire import _mf_numba, linear, magic_formula
from vehdyn.tire.linear import LinearTire
from vehdyn.tire.magic_formula import MagicFormula
from vehdyn.components import aero as crosswind
from vehdyn.handling import single_track_equations as equations

__all__ = ["XP", "compiled_model", "compiled_functions", "compiled_batch", "batch_structure"]

_JIT = {"error_model": "numpy"}
_MAGIC_FORMULA, _LINEAR = 0, 1

for _function in (conventions.planar_tire_slips_sae_to_iso_w, conventions.planar_tire_forces_iso_w_to_sae):
    register_jitable(**_JIT)(_function)
for _name in ("_at", "named_states", "named_inputs", "regularized_speed", "low_speed_blend", "sliding_slip",
              "limit_deflection_rate", "axle_slips", "demanded_forces", "axle_forces", "axle_loads", "normal_loads",
              "evaluate", "derivatives", "outputs", "net_wheel_torque", "deflection_rate", "deflection_rates",
              "lateral_load_transfer", "wheel_pair_loads", "wheel_load_outputs", "rolling_resistance_fade",
              "roll_acceleration"):
    register_jitable(**_JIT)(getattr(equations, _name))
register_jitable(**_JIT)(crosswind.aero_side_force)

TireLaw = namedtuple("TireLaw", ("kind", "mirrored", "records", "record", "linear", "lateral_only"),
                     defaults=(False,))
TireLaw.__doc__ = """The law of one axle's tires for compiled code: ``kind`` (0 Magic Formula, 1 linear),
``mirrored`` (axle force = tire + mirror image, see :meth:`SingleTrack.axle_law_forces`), an array
of Magic Formula coefficient records and which one is this law's (placeholders for other laws:
an array, not a record, so that a batch can pick a variant's record without returning one from a
compiled function) and the linear law's coefficients (:attr:`LinearTire.coefficients`; zeros for
a Magic Formula); ``lateral_only``: the model takes only F_y from the law (force mode without
lateral load transfer: the longitudinal force is the input and M_y unused), so a Magic Formula
evaluates only its lateral force at kappa = 0 (``magic_formula._lateral_force_kernel``) and returns
F_x = M_y = 0."""


def _axle_tire_loads(tires, axle, fz, kappa, alpha, vx):
    """ISO-W axle forces and rolling-resistance moment (fx, fy, my) [N, N, N*m]: two tires at half the
    load ``fz`` (see ``SingleTrack.axle_law_loads``); the linear law has no M_y."""
    law = tires[axle]
    load = 0.5 * fz
    if law.kind == _MAGIC_FORMULA:
        c = law.records[law.record]
        if law.lateral_only:
            fy = magic_formula._lateral_force_kernel(_mf_numba.OPS, c, load, alpha, vx, c.INFLPRES)
            if law.mirrored:
                return 0.0, fy - magic_formula._lateral_force_kernel(_mf_numba.OPS, c, load, -alpha, vx,
                                                                      c.INFLPRES), 0.0
            return 0.0, 2.0 * fy, 0.0
        f = magic_formula._forces_kernel(_mf_numba.OPS, c, load, kappa, alpha, 0.0, vx, c.INFLPRES, True, False)
        if law.mirrored:
            g = magic_formula._forces_kernel(_mf_numba.OPS, c, load, kappa, -alpha, 0.0, vx, c.INFLPRES, True, False)
            return f[0] + g[0], f[1] - g[1], f[4] + g[4]
        return 2.0 * f[0], 2.0 * f[1], 2.0 * f[4]
    fx, fy, _ = linear.linear_tire_law(_mf_numba.OPS, law.linear, load, kappa, alpha, 0.0, vx)
    if law.mirrored:
        gx, gy, _ = linear.linear_tire_law(_mf_numba.OPS, law.linear, load, kappa, -alpha, 0.0, vx)
        return fx + gx, fy - gy, 0.0
    return 2.0 * fx, 2.0 * fy, 0.0


def _wheel_pair_tire_loads(tires, axle, left_load, right_load, kappa, alpha, vx):
    """ISO-W (fx, fy, my) of the left, then the right tire of an axle at their own loads [N]: the
    left one is the law's mirror image when the law has ply steer (``SingleTrack.wheel_pair_law_loads``)."""
    law = tires[axle]
    mirror = -1.0 if law.mirrored else 1.0
    if law.kind == _MAGIC_FORMULA:
        c = law.records[law.record]
        f = magic_formula._forces_kernel(_mf_numba.OPS, c, left_load, kappa, mirror * alpha, 0.0, vx, c.INFLPRES,
                                         True, False)
        g = magic_formula._forces_kernel(_mf_numba.OPS, c, right_load, kappa, alpha, 0.0, vx, c.INFLPRES, True, False)
        return f[0], mirror * f[1], f[4], g[0], g[1], g[4]
    fx, fy, _ = linear.linear_tire_law(_mf_numba.OPS, law.linear, left_load, kappa, mirror * alpha, 0.0, vx)
    gx, gy, _ = linear.linear_tire_law(_mf_numba.OPS, law.linear, right_load, kappa, alpha, 0.0, vx)
    return fx, mirror * fy, 0.0, gx, gy, 0.0


def _axle_tire_forces(tires, axle, fz, kappa, alpha, vx):
    """ISO-W axle forces (fx, fy) [N] of :func:`_axle_tire_loads`."""
    fx, fy, _ = _axle_tire_loads(tires, axle, fz, kappa, alpha, vx)
    return fx, fy


def _cos(x):
    """cos(x), without the library call at x = 0 (an absent steer angle) and x = pi (the low-speed
    blend above its speed): exactly 1.0 and -1.0, as the library returns."""
    if x == 0.0:
        return 1.0
    if x == math.pi:
        return -1.0
    return math.cos(x)


def _sin(x):
    """sin(x), without the library call at x = +-0 (sin(+-0) = +-0)."""
    return x if x == 0.0 else math.sin(x)


def _tanh(x):
    """tanh(x), without the library call at x = +-0 (a wheel that does not spin)."""
    return x if x == 0.0 else math.tanh(x)


def _atan2(y, x):
    """atan2(y, x), without the library call at y = +-0, x > 0 (no crosswind): +-0."""
    return y if y == 0.0 and x > 0.0 else math.atan2(y, x)


XP = types.ModuleType("vehdyn.handling._single_track_numba.XP")
XP.__doc__ = "The ``xp`` of the single-track equations in compiled code (floats; the tire laws compiled)."
for _name in ("atan", "sqrt"):
    setattr(XP, _name, getattr(math, _name))
for _function in (_cos, _sin, _tanh, _atan2):
    setattr(XP, _function.__name__[1:], register_jitable(**_JIT, forceinline=True)(_function))
for _name in ("abs", "where", "minimum", "maximum"):
    setattr(XP, _name, getattr(_mf_numba.OPS, _name))
XP.axle_tire_loads = numba.njit(**_JIT)(_axle_tire_loads)
XP.axle_tire_forces = numba.njit(**_JIT)(_axle_tire_forces)
XP.wheel_pair_tire_loads = numba.njit(**_JIT)(_wheel_pair_tire_loads)
register_jitable(**_JIT)(linear.linear_tire_law)


def _rhs(t, x, u, args, dxdt):
    """dx/dt of a SingleTrack at (t, x, u) into ``dxdt``; ``args`` from :func:`rhs_and_args`."""
    k, tires, state_index, input_index = args
    states = equations.named_states(x, state_index)
    inputs = equations.named_inputs(u, input_index)
    e = equations.evaluate(XP, tires, k, states, inputs)
    rates = equations.derivatives(XP, k, e, states, inputs)
    for j in range(len(rates)):
        if state_index[j] >= 0:
            dxdt[state_index[j]] = rates[j]


def _output(t, x, u, args, y):
    """The outputs of a SingleTrack at (t, x, u) into ``y``."""
    k, tires, state_index, input_index = args
    states = equations.named_states(x, state_index)
    e = equations.evaluate(XP, tires, k, states, equations.named_inputs(u, input_index))
    values = equations.outputs(XP, states, e)
    for j in range(len(values)):
        y[j] = values[j]
    n = len(values)
    if k.lateral_load_transfer:
        loads = equations.wheel_load_outputs(e)
        for j in range(len(loads)):
            y[n + j] = loads[j]
        n += len(loads)
    if state_index[12] >= 0:  # the roll degree of freedom: roll angle and rate
        y[n] = states[12]
        y[n + 1] = states[13]


@functools.lru_cache(maxsize=None)
def compiled_functions():
    """(rhs, output, cache key): compiled on first call, cached on disk per source digest."""
    key = "single_track_" + source_stamp(equations, crosswind, conventions, linear, *_mf_numba.SOURCE_MODULES,
                                         sys.modules[__name__])
    compiled = [compiled_copy(python, f"{key}_{suffix}") for python, suffix in ((_rhs, "rhs"), (_output, "output"))]
    return compiled[0], compiled[1], key


def _records(c=None):
    """An array of one coefficient record (zeros without ``c``), the fields of :func:`_mf_numba._record`."""
    dtype = [(name, np.float64) for name in magic_formula.MFCoefficients._fields]
    return np.zeros(1, dtype=dtype) if c is None else np.array([tuple(c)], dtype=dtype)


def tire_law(tire, mirrored: bool, axle: str, lateral_only: bool = False) -> TireLaw:
    """The compiled description of ``tire`` (a MagicFormula or LinearTire), else ParameterError."""
    if isinstance(tire, MagicFormula):
        return TireLaw(_MAGIC_FORMULA, bool(mirrored), _records(tire._c), 0, (0.0, 0.0, 0.0, 0.0, 0.0),
                       bool(lateral_only))
    if isinstance(tire, LinearTire):
        return TireLaw(_LINEAR, bool(mirrored), _records(), 0, tire.coefficients)
    raise ParameterError(f"the compiled SingleTrack supports the MagicFormula and LinearTire laws; the {axle} tire is "
                         f"a {type(tire).__name__}: use backend='numpy'", key=f"{axle}_tire", value=type(tire).__name__)


def compiled_model(model) -> CompiledModel:
    """The compiled rhs and outputs of a SingleTrack with scalar parameters."""
    if model.n_variants is not None:
        raise ParameterError("the compiled SingleTrack runs one vehicle; this model has array parameters "
                             f"({model.n_variants} variants): use backend='numpy'", key="variants",
                             value=model.n_variants)
    k = model._constants()
    k = k._replace(**{name: float(getattr(k, name)) for name in _FLOATS})
    lateral = _lateral_only(model.wheel_spin, model.lateral_load_transfer)
    tires = (tire_law(model.front_tire, model._mirrored["front"], "front", lateral),
             tire_law(model.rear_tire, model._mirrored["rear"], "rear", lateral))
    rhs, output, key = compiled_functions()
    # tuples, not arrays: passed by value, without reference counting on every call
    index = (tuple(int(i) for i in model._state_index), tuple(int(i) for i in model._input_index))
    return CompiledModel(rhs, output, key, (k, tires, *index))


# ------------------------------------------------------------------------------ batches
_FLAGS = ("wheel_spin", "tire_lag", "lateral_load_transfer")
assert equations.Constants._fields[-3:] == _FLAGS  # the floats first, then the flags
_FLOATS = equations.Constants._fields[:-3]
_N_FLOATS = len(_FLOATS)
_N_LINEAR = 5


def _lateral_only(wheel_spin, lateral_load_transfer):
    """Whether the model takes only F_y from its tire laws (:class:`TireLaw`)."""
    return not (wheel_spin or lateral_load_transfer)


def _law(axle, i, lateral_only):
    """Variant ``i``'s TireLaw from an axle of a batch (kind, mirrored, tire index, records, linear)."""
    kind, mirrored, which, records, linear_coefficients = axle
    j = which[i]
    return TireLaw(kind, mirrored[i], records, j, to_fixed_tuple(linear_coefficients[j], _N_LINEAR), lateral_only)


def _pick(batch, i):
    """The ``args`` of :func:`_rhs` for variant ``i`` of a batch built by :func:`compiled_batch`."""
    K, wheel_spin, tire_lag, lateral_load_transfer, front, rear, state_index, input_index = batch
    k = equations.Constants(*(to_fixed_tuple(K[i], _N_FLOATS) + (wheel_spin, tire_lag, lateral_load_transfer)))
    lateral = _lateral_only(wheel_spin, lateral_load_transfer)
    return k, (_law(front, i, lateral), _law(rear, i, lateral)), state_index, input_index


# inlined into the batch loops (a compiled function of its own could not return a record to Python)
register_jitable(**_JIT)(_lateral_only)
register_jitable(**_JIT)(_law)
register_jitable(**_JIT)(_pick)


def batch_structure(model) -> tuple:
    """What variants must share to run in one compiled batch: the modes, the tire laws' kinds
    and the signals' layout (a hashable key)."""
    kinds = tuple(_LINEAR if isinstance(tire, LinearTire) else _MAGIC_FORMULA if isinstance(tire, MagicFormula)
                  else type(tire).__name__ for tire in (model.front_tire, model.rear_tire))
    return (type(model).__name__, model.wheel_spin, model.tire_lag, model.lateral_load_transfer, kinds,
            tuple(model.state_names), tuple(model.input_names), tuple(model.output_names))


def _axle(tires, mirrored, axle):
    """A batch axle: (kind, mirrored per variant, tire index per variant, unique records, unique linear rows)."""
    laws, which, index = [], np.empty(len(tires), dtype=np.int64), {}
    for i, tire in enumerate(tires):
        key = id(tire)
        if key not in index:
            index[key] = len(laws)
            laws.append(tire_law(tire, False, axle))
        which[i] = index[key]
    kinds = {law.kind for law in laws}
    if len(kinds) > 1:
        raise ParameterError(f"a compiled batch needs one {axle} tire law for every variant", key=f"{axle}_tire",
                             value=sorted(kinds))
    records = np.concatenate([law.records for law in laws])
    linear_rows = np.array([law.linear for law in laws], dtype=float).reshape(len(laws), _N_LINEAR)
    return laws[0].kind, np.asarray(mirrored, dtype=np.bool_), which, records, linear_rows


def compiled_batch(models, n_variants: int | None = None) -> CompiledBatch:
    """The compiled rhs of many single-track vehicles for :func:`vehdyn.simulation.compiled.solve_batch`.

    Parameters
    ----------
    models : SingleTrack or sequence of SingleTrack
        One model whose parameters are arrays (:meth:`SingleTrack.variants`, one entry per
        variant) or scalars shared by ``n_variants`` variants; or one scalar model per variant,
        all of one :func:`batch_structure` (their tires may differ).
    n_variants : int, optional
        With one model: the number of variants (default: its ``n_variants``).

    Raises
    ------
    ParameterError
        For a tire law without a compiled form, or models of different structures.
    """
    rhs, output, key = compiled_functions()
    if isinstance(models, (list, tuple)):
        if not models:
            raise ParameterError("a compiled batch needs at least one model", key="models", value=models)
        structure = batch_structure(models[0])
        for m in models:
            if m.n_variants is not None:
                raise ParameterError("a list of models for a compiled batch holds models with scalar parameters",
                                     key="models", value=m.n_variants)
            if batch_structure(m) != structure:
                raise ParameterError(f"the models of a compiled batch must share one structure; {batch_structure(m)} "
                                     f"differs from {structure}", key="models", value=batch_structure(m))
        constants = [m._constants() for m in models]
        K = np.array([[getattr(k, name) for name in _FLOATS] for k in constants], dtype=float)
        tires = {axle: [getattr(m, f"{axle}_tire") for m in models] for axle in ("front", "rear")}
        mirrored = {axle: [m._mirrored[axle] for m in models] for axle in ("front", "rear")}
        first = models[0]
    else:
        first = models
        n = first.n_variants if n_variants is None else int(n_variants)
        if n is None or n < 1 or (first.n_variants not in (None, n)):
            raise ParameterError(f"n_variants = {n_variants!r} for a model of {first.n_variants} variants",
                                 key="n_variants", value=n_variants)
        k = first._constants()
        K = np.empty((n, _N_FLOATS))
        for j, name in enumerate(_FLOATS):
            K[:, j] = np.broadcast_to(np.asarray(getattr(k, name), dtype=float), (n,))
        tires = {axle: [getattr(first, f"{axle}_tire")] * n for axle in ("front", "rear")}
        mirrored = {axle: [first._mirrored[axle]] * n for axle in ("front", "rear")}
    batch = (np.ascontiguousarray(K), bool(first.wheel_spin), bool(first.tire_lag), bool(first.lateral_load_transfer),
             _axle(tires["front"], mirrored["front"], "front"), _axle(tires["rear"], mirrored["rear"], "rear"),
             tuple(int(i) for i in first._state_index), tuple(int(i) for i in first._input_index))
    return CompiledBatch(rhs, output, key, _pick, batch, K.shape[0])
