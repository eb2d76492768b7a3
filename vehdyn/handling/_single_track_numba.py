"""Compiled right-hand side of :class:`~vehdyn.handling.SingleTrack` (numba, optional).

Imported only when the compiled backend is used. Nothing here restates an equation: the functions
of :mod:`~vehdyn.handling.single_track_equations` are registered with ``register_jitable`` and run
with the compiled ``xp`` of :mod:`vehdyn.components.compiled` (the shared components registered
there), whose tire hooks evaluate each axle's law, a :class:`vehdyn.tire.compiled.TireLaw`: the
Magic Formula as :meth:`MagicFormula.forces` evaluates it (in force mode without lateral load
transfer, where the model takes only F_y at kappa = 0, the lean
:func:`~vehdyn.tire.kernels.lateral_force_kernel`, bitwise the same F_y at a quarter of the cost)
or the linear law. Other laws (brush, Fiala, Dugoff) have no compiled form: the model then refuses
the compiled backend and names the law. A constant road friction compiles (``friction=0.5``); a
callable ``friction(X, Y)`` does not.

(Forcing LLVM to inline every equation and tire law saved another ~25 % of an rhs call but doubled
the cold compile time of every model built on these equations: not done.)
"""

from __future__ import annotations

import functools
import sys

import numpy as np
from numba.extending import register_jitable
from numba.np.unsafe.ndarray import to_fixed_tuple

from vehdyn.components.compiled import JIT_OPTIONS as _JIT
from vehdyn.components.compiled import SOURCE_MODULES, XP, XP_WITHOUT_ALIGNING
from vehdyn.errors import ParameterError
from vehdyn.handling import single_track_equations as equations
from vehdyn.simulation.compiled import CompiledBatch, CompiledModel, compiled_copy, source_stamp
from vehdyn.tire.compiled import LINEAR, MAGIC_FORMULA, N_LINEAR, TireLaw, tire_law
from vehdyn.tire.linear import LinearTire
from vehdyn.tire.magic_formula import MagicFormula

__all__ = ["XP", "compiled_model", "compiled_functions", "compiled_batch", "batch_structure"]

for _name in ("_at", "named_states", "named_inputs", "axle_loads", "normal_loads", "evaluate", "derivatives",
              "outputs", "deflection_rates", "lateral_load_transfer", "wheel_pair_loads", "wheel_load_outputs",
              "roll_acceleration", "axle_aligning_moment"):
    register_jitable(**_JIT)(getattr(equations, _name))


def _friction(k):
    """The road's friction ratio under the (front, rear) axle: the model's constant."""
    return k.road_friction, k.road_friction


register_jitable(**_JIT)(_friction)


def _rhs(t, x, u, args, dxdt):
    """dx/dt of a SingleTrack at (t, x, u) into ``dxdt``; ``args`` from :func:`rhs_and_args`."""
    k, tires, state_index, input_index = args
    states = equations.named_states(x, state_index)
    inputs = equations.named_inputs(u, input_index)
    e = equations.evaluate(XP, tires, k, states, inputs, _friction(k))
    rates = equations.derivatives(XP, k, e, states, inputs)
    for j in range(len(rates)):
        if state_index[j] >= 0:
            dxdt[state_index[j]] = rates[j]


def _output(t, x, u, args, y):
    """The outputs of a SingleTrack at (t, x, u) into ``y``."""
    k, tires, state_index, input_index = args
    states = equations.named_states(x, state_index)
    e = equations.evaluate(XP, tires, k, states, equations.named_inputs(u, input_index), _friction(k))
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
        n += 2
    if k.compliance_steer > 0.5:
        y[n] = e.front_compliance_steer_angle
        y[n + 1] = e.rear_compliance_steer_angle


@functools.lru_cache(maxsize=None)
def compiled_functions(aligning: bool = False):
    """(rhs, output, cache key): compiled on first call, cached on disk per source digest; with
    ``aligning`` the copy whose compliance steer reads the laws' M_z (``XP``), else without it
    (``XP_WITHOUT_ALIGNING``, :data:`vehdyn.components.compiled.WITHOUT_ALIGNING`)."""
    key = "single_track_" + source_stamp(equations, *SOURCE_MODULES, sys.modules[__name__])
    key += "_aligning" if aligning else ""
    xp = XP if aligning else XP_WITHOUT_ALIGNING
    compiled = [compiled_copy(python, f"{key}_{suffix}", XP=xp) for python, suffix in ((_rhs, "rhs"),
                                                                                       (_output, "output"))]
    return compiled[0], compiled[1], key


def _aligning(front, rear) -> bool:
    """Whether a model (or any variant) has an aligning-moment compliance steer."""
    return bool(np.any(np.asarray(front) != 0.0) or np.any(np.asarray(rear) != 0.0))


def _tire_laws(model, lateral_only):
    """The (front, rear) TireLaw of a model, or ParameterError naming a law without a compiled form."""
    return tuple(tire_law(getattr(model, f"{axle}_tire"), f"{axle}_tire", lateral_only) for axle in ("front", "rear"))


def compiled_model(model) -> CompiledModel:
    """The compiled rhs and outputs of a SingleTrack with scalar parameters."""
    if callable(model.friction):
        raise ParameterError("the compiled SingleTrack takes a constant road friction; friction is a Python callable "
                             f"({type(model.friction).__name__}), which compiled code cannot call: use backend='numpy'",
                             key="friction", value=model.friction)
    if model.n_variants is not None:
        raise ParameterError("the compiled SingleTrack runs one vehicle; this model has array parameters "
                             f"({model.n_variants} variants): use backend='numpy'", key="variants",
                             value=model.n_variants)
    k = model._constants()
    k = k._replace(**{name: float(getattr(k, name)) for name in _FLOATS})
    tires = _tire_laws(model, _lateral_only(model.wheel_spin, model.lateral_load_transfer))
    rhs, output, key = compiled_functions(_aligning(k.front_aligning_moment_compliance,
                                                    k.rear_aligning_moment_compliance))
    # tuples, not arrays: passed by value, without reference counting on every call
    index = (tuple(int(i) for i in model._state_index), tuple(int(i) for i in model._input_index))
    return CompiledModel(rhs, output, key, (k, tires, *index))


# ------------------------------------------------------------------------------ batches
_FLAGS = ("wheel_spin", "tire_lag", "lateral_load_transfer", "friction_scaled")
assert equations.Constants._fields[-len(_FLAGS):] == _FLAGS  # the floats first, then the flags
_FLOATS = equations.Constants._fields[:-len(_FLAGS)]
_N_FLOATS = len(_FLOATS)


def _lateral_only(wheel_spin, lateral_load_transfer):
    """Whether the model takes only F_y from its tire laws (:class:`TireLaw`)."""
    return not (wheel_spin or lateral_load_transfer)


def _law(axle, i, lateral_only):
    """Variant ``i``'s TireLaw from an axle of a batch (kind, tire index, records, linear)."""
    kind, which, records, linear_coefficients = axle
    j = which[i]
    return TireLaw(kind, records, j, to_fixed_tuple(linear_coefficients[j], N_LINEAR), lateral_only)


def _pick(batch, i):
    """The ``args`` of :func:`_rhs` for variant ``i`` of a batch built by :func:`compiled_batch`."""
    K, wheel_spin, tire_lag, lateral_load_transfer, friction_scaled, front, rear, state_index, input_index = batch
    k = equations.Constants(*(to_fixed_tuple(K[i], _N_FLOATS) + (wheel_spin, tire_lag, lateral_load_transfer,
                                                               friction_scaled)))
    lateral = _lateral_only(wheel_spin, lateral_load_transfer)
    return k, (_law(front, i, lateral), _law(rear, i, lateral)), state_index, input_index


# inlined into the batch loops (a compiled function of its own could not return a record to Python)
register_jitable(**_JIT)(_lateral_only)
register_jitable(**_JIT)(_law)
register_jitable(**_JIT)(_pick)


def batch_structure(model) -> tuple:
    """What variants must share to run in one compiled batch: the modes, the tire laws' kinds
    and the signals' layout (a hashable key)."""
    kinds = tuple(LINEAR if isinstance(tire, LinearTire) else MAGIC_FORMULA if isinstance(tire, MagicFormula)
                  else type(tire).__name__ for tire in (model.front_tire, model.rear_tire))
    return (type(model).__name__, model.wheel_spin, model.tire_lag, model.lateral_load_transfer,
            model.friction is not None, kinds, tuple(model.state_names), tuple(model.input_names),
            tuple(model.output_names))


def _axle(tires, axle):
    """A batch axle: (kind, tire index per variant, unique records, unique linear rows)."""
    laws, which, index = [], np.empty(len(tires), dtype=np.int64), {}
    for i, tire in enumerate(tires):
        key = id(tire)
        if key not in index:
            index[key] = len(laws)
            laws.append(tire_law(tire, f"{axle}_tire"))
        which[i] = index[key]
    kinds = {law.kind for law in laws}
    if len(kinds) > 1:
        raise ParameterError(f"a compiled batch needs one {axle} tire law for every variant", key=f"{axle}_tire",
                             value=sorted(kinds))
    records = np.concatenate([law.records for law in laws])
    linear_rows = np.array([law.linear for law in laws], dtype=float).reshape(len(laws), N_LINEAR)
    return laws[0].kind, which, records, linear_rows


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
    if callable(first.friction):
        raise ParameterError("a compiled batch takes a constant road friction, not a Python callable",
                             key="friction", value=first.friction)
    rhs, output, key = compiled_functions(_aligning(K[:, _FLOATS.index("front_aligning_moment_compliance")],
                                                    K[:, _FLOATS.index("rear_aligning_moment_compliance")]))
    batch = (np.ascontiguousarray(K), bool(first.wheel_spin), bool(first.tire_lag), bool(first.lateral_load_transfer),
             first.friction is not None, _axle(tires["front"], "front"), _axle(tires["rear"], "rear"),
             tuple(int(i) for i in first._state_index), tuple(int(i) for i in first._input_index))
    return CompiledBatch(rhs, output, key, _pick, batch, K.shape[0])
