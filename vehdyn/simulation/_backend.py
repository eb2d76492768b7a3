"""The compiled backend of :func:`~vehdyn.simulate` (numba, optional): whether it runs and why, one
model's compiled run, a batch's, their outputs, and the compiled batches of
:func:`~vehdyn.simulate_many`.

The loops are :mod:`vehdyn.simulation.compiled` (the explicit Runge-Kutta pairs) and
:mod:`vehdyn.simulation._bdf` (BDF); this module connects them to ``simulate``'s arguments and
results. The compiled loop does not watch the model's domain: a run that crossed it is located
by ``solve_ivp`` with terminal events over the output interval where it happened
(:func:`_domain_crossing`), so that both backends report the same crossing.
"""

from __future__ import annotations

import time as _time

import numpy as np

from vehdyn.errors import ParameterError, SimulationError
from vehdyn.model import signal_vector
from vehdyn.results import SimulationResult
from vehdyn.simulation._domain import _domain_bounds, _domain_violation
from vehdyn.simulation._inputs import _HOLDS, _named_inputs, _positive_option, _sample_inputs, _time_grid
from vehdyn.simulation._ivp import _simulate_ivp
from vehdyn.simulation._stiffness import _stiffness_hint

#: the keyword arguments of a simulate call that a compiled batch of simulate_many takes
_BATCH_OPTIONS = {"x0", "method", "rtol", "atol", "hold", "backend"}


def _compiled_backend(model, method, backend, x0, u):
    """(compiled rhs, key, args) and the reason when the compiled backend can run, else (None, why not)."""
    from vehdyn.simulation import compiled as _compiled_ode

    backends = ("auto", "numpy", "compiled")
    if backend not in backends:
        raise ParameterError(f"backend must be one of {backends}, got {backend!r}", key="backend", value=backend)
    if backend == "numpy":
        return None, "backend='numpy' asked for"
    explicit = backend == "compiled"
    problem = None
    if method not in _compiled_ode.METHODS:
        problem = f"method {method!r} (the compiled backend integrates with {_compiled_ode.METHODS})"
    elif (x0.ndim > 1 or u.ndim > 2) and not hasattr(model, "compiled_batch"):
        problem = (f"a batch ({type(model).__name__} has no compiled batch: batches of it run vectorized on "
                   "numpy)")
    elif not _compiled_ode.numba_available():
        problem = "numba is not installed (pip install vehdyn[fast])"
    else:
        try:
            if x0.ndim > 1 or u.ndim > 2:
                compiled = model.compiled_batch(x0.shape[1] if x0.ndim > 1 else u.shape[2])
            else:
                compiled = model.compiled_rhs()
        except ParameterError as exc:
            if explicit:
                raise
            return None, f"no compiled form of this configuration: {exc}"
        if compiled is None:
            problem = f"{type(model).__name__} has no compiled rhs"
    if problem is not None:
        if explicit:
            raise ParameterError(f"backend='compiled' cannot run: {problem}", key="backend", value=backend)
        return None, problem
    if hasattr(compiled, "pick"):
        return compiled, (f"compiled backend ({method} on {type(model).__name__}'s compiled rhs, numba; "
                          f"{compiled.n_variants} variants, each with its own step-size control)")
    return compiled, f"compiled backend ({method} on {type(model).__name__}'s compiled rhs, numba)"


def _auto_backend(model, compiled, method, backend, t, u, x0):
    """Whether a call whose compiled backend can run runs compiled now, with the code key and why
    (:func:`vehdyn.simulation._background.decide` for one run on ``"auto"``; an explicit
    ``"compiled"`` and a batch compile here first)."""
    from vehdyn.simulation import _background

    if hasattr(compiled, "pick"):
        return True, None, "a batch: compiled in this process first if not cached (it waits for the compiler once)"
    if backend == "compiled":
        return True, _background.code_key(compiled, method), ("backend='compiled' asked for: compiled in this "
                                                              "process first if not cached")
    return _background.decide(model, compiled, method, t, u, x0)


def _solve_compiled(model, compiled, t, inputs, u, x0, hold, method, rtol, atol, first_step, max_step):
    """States (n, n_t) and counters of one model's run on the compiled backend
    (:func:`vehdyn.simulation.compiled.solve`); a failure raises SimulationError, with the domain
    crossing or the stiffness estimate where either explains it."""
    from vehdyn.simulation import compiled as _compiled_ode

    try:
        x, stats = _compiled_ode.solve(compiled.rhs, compiled.key, compiled.args, t, x0,
                                       _compiled_ode.input_table(model, inputs, t, u, hold), method, rtol, atol,
                                       first_step, max_step)
    except SimulationError as exc:
        crossing = _domain_crossing(model, t, inputs, u, hold, method, rtol, atol,
                                    getattr(exc, "partial_states", None), exc.time)
        raise crossing or _stiffness_hint(exc, model, method, t, x0, u) from None
    crossing = _domain_crossing(model, t, inputs, u, hold, method, rtol, atol, x)
    if crossing is not None:
        raise crossing
    return x, stats


def _solve_compiled_batch(model, compiled, t, inputs, u, x0, hold, method, rtol, atol, first_step, max_step):
    """States (n, n_t, n_variants) and counters of a batch on the compiled backend
    (:func:`vehdyn.simulation.compiled.solve_batch`); the first failed variant raises SimulationError."""
    from vehdyn.simulation import compiled as _compiled_ode

    n = compiled.n_variants
    x0 = np.broadcast_to(x0.reshape(x0.shape[0], -1), (x0.shape[0], n))
    table = _compiled_ode.input_table(model, inputs, t, u, hold)
    y, report = _compiled_ode.solve_batch(compiled, t, x0, table, method, rtol, atol, first_step, max_step)
    failed = np.nonzero(report[:, 0] != 0)[0]
    if failed.size:
        i = int(failed[0])
        raise SimulationError(f"variant {i} of the batch: {_compiled_ode.status_message(method, report[i])}",
                              time=float(report[i, 1]))
    x = np.moveaxis(y, 0, 2)
    violation = _domain_violation(model, t, x)
    if violation is not None:
        raise violation
    nfev, accepted, rejected = (int(v) for v in report[:, 2:].sum(axis=0))
    return x, {"nfev": nfev, "n_steps": accepted,
               "message": f"compiled {method}, {n} variants: {accepted} steps ({rejected} rejected), {nfev} rhs calls"}


def _compiled_outputs(model, compiled, t, x, u):
    """Outputs (p, n_t[, n_variants]) of a compiled run by the model's compiled output function, or
    None when it has none (then the numpy ``output`` computes them)."""
    from vehdyn.simulation import compiled as _compiled_ode

    if hasattr(compiled, "pick"):
        uu = np.moveaxis(u, 2, 0) if u.ndim == 3 else u
        return np.moveaxis(_compiled_ode.batch_outputs(compiled, model.n_outputs, t, np.moveaxis(x, 2, 0), uu), 0, 2)
    if compiled.output is not None:
        return _compiled_ode.outputs(compiled, model.n_outputs, t, x, u)
    return None


def _domain_crossing(model, t, inputs, u, hold, method, rtol, atol, states, failed_at=None) -> SimulationError | None:
    """The first crossing of a bound of the model's domain by the compiled loop's run, as the model's
    :meth:`~vehdyn.Model.domain_error`, or None.

    The compiled loop does not watch the domain (its rhs is NaN only far beyond it, where every step
    is rejected): ``states`` are the output instants it reached (all, or those before the failure at
    ``failed_at``). The crossing is located by ``solve_ivp`` with terminal events over the output
    interval where it happened (or the one where the loop failed).
    """
    if not _domain_bounds(model) or states is None or states.shape[1] == 0:
        return None
    coarse = _domain_violation(model, t[:states.shape[1]], states)  # vectorized over the instants
    if coarse is not None:
        k = int(np.searchsorted(t, coarse.time))
        if k == 0:
            return coarse
        first, last = k - 1, k
    elif failed_at is not None:
        first = states.shape[1] - 1
        last = max(int(np.searchsorted(t, failed_at, side="left")), first + 1)
        if last >= t.size:
            return None
    else:
        return None
    try:
        _simulate_ivp(model, t[first:last + 1], u[:, first:last + 1], states[:, first], hold, method, rtol, atol,
                      None, None, inputs=inputs)
    except SimulationError as located:
        if located.signal in model.domain:
            return located
    return coarse


def _compiled_member(args, kwargs):
    """A call of :func:`~vehdyn.simulate` prepared for a compiled batch, or None when it must run alone:
    (group key, model, t, inputs, u, x0, options). Any doubt (a bad argument, an option a batch
    does not take) leaves the call to ``simulate``, which raises the proper error."""
    from vehdyn.simulation import compiled as _compiled_ode

    if len(args) != 3 or not set(kwargs) <= _BATCH_OPTIONS:
        return None
    model, time, inputs = args
    inputs = _named_inputs(model, inputs)
    method = kwargs.get("method", "auto")
    if (not hasattr(model, "compiled_batch_of") or method not in _compiled_ode.METHODS
            or kwargs.get("backend", "auto") not in ("auto", "compiled") or not _compiled_ode.numba_available()):
        return None
    try:
        t = _time_grid(time)
        hold = kwargs.get("hold", "foh")
        if hold not in _HOLDS:
            return None
        options = {"method": method, "rtol": _positive_option(kwargs.get("rtol", 1e-6), "rtol"),
                   "atol": _positive_option(kwargs.get("atol", 1e-9), "atol"), "hold": hold}
        u = _sample_inputs(model, inputs, t)
        x0 = signal_vector(kwargs.get("x0"), model.states, "x0")
        if x0.ndim != 1 or u.ndim != 2 or _domain_violation(model, t[0], x0) is not None:
            return None
        model.compiled_rhs()  # a configuration without a compiled form runs alone (and says why)
        table = _compiled_ode.input_table(model, inputs, t, u, hold)
    except (ParameterError, SimulationError):
        return None
    kinds, _, pieces, rows, breakpoints = table
    key = (type(model), model.batch_structure(), t.tobytes(), tuple(sorted((k, repr(v)) for k, v in options.items())),
           kinds.tobytes(), pieces.tobytes(), rows.tobytes(), breakpoints.tobytes())
    return key, model, t, table, u, x0, options


def _run_compiled_group(members, threads) -> list:
    """The results of one group of :func:`_compiled_member` calls (one model structure, grid, options
    and input layout) as one compiled batch: per member its SimulationResult, or the SimulationError
    or domain error of its variant."""
    from vehdyn.simulation import compiled as _compiled_ode

    models = [m[1] for m in members]
    first, t, table, options = models[0], members[0][2], members[0][3], members[0][6]
    method = options["method"]
    start = _time.perf_counter()
    compiled = type(first).compiled_batch_of(models)
    U = np.stack([m[4] for m in members], axis=2)
    table = (table[0], np.ascontiguousarray(np.moveaxis(U, 2, 0)), *table[2:])
    states, report = _compiled_ode.solve_batch(compiled, t, np.stack([m[5] for m in members], axis=1), table,
                                               method, options["rtol"], options["atol"], threads=threads)
    outputs = _compiled_ode.batch_outputs(compiled, first.n_outputs, t, states, table[1], threads=threads)
    wall = (_time.perf_counter() - start) / len(members)
    reason = f"compiled backend ({method} on {type(first).__name__}'s compiled rhs, numba; one of a batch " \
             f"of {len(members)} variants, each with its own step-size control)"
    results = []
    for j, (i, model, *_rest) in enumerate(members):
        if report[j, 0] != 0:
            results.append(SimulationError(_compiled_ode.status_message(method, report[j]), time=float(report[j, 1])))
            continue
        violation = _domain_violation(model, t, states[j])
        if violation is not None:
            results.append(violation)
            continue
        status, _, nfev, accepted, rejected = (int(v) for v in report[j])
        results.append(SimulationResult(
            time=t, states=states[j], inputs=U[..., j], outputs=outputs[j], state_signals=model.states,
            input_signals=model.inputs, output_signals=model.output_signals, method=method,
            method_reason=reason, wall_time=wall, nfev=nfev, n_steps=accepted, backend="compiled",
            backend_reason="simulate_many: one compiled batch (compiled in this process first if not cached)",
            message=f"compiled {method}: {accepted} steps ({rejected} rejected), {nfev} rhs calls",
            options={"rtol": options["rtol"], "atol": options["atol"], "hold": options["hold"], "substeps": 1}))
    return results
