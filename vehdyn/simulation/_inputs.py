"""The arguments of a :func:`~vehdyn.simulate` call, checked: the time grid, the options, the
inputs sampled on the grid and interpolated between samples (``hold``), the batch of ``x0`` and
the inputs.

Every check raises :class:`~vehdyn.ParameterError` naming the argument (and, for an input, the
instant and the batch member) before any solver runs.
"""

from __future__ import annotations

import math
from typing import Any, Callable, Mapping

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.model import Model, float_array

_HOLDS = ("zoh", "foh")


def _time_grid(time) -> np.ndarray:
    t = float_array(time, "time")
    if t.ndim != 1 or t.size < 2:
        raise ParameterError(f"time must be a 1-D array of at least two instants, got shape {t.shape}",
                             key="time", value=t.shape)
    if not np.all(np.isfinite(t)):
        raise ParameterError("time contains non-finite values", key="time", value=t[~np.isfinite(t)][0])
    dt = np.diff(t)
    if np.any(dt <= 0):
        k = int(np.argmax(dt <= 0))
        raise ParameterError(f"time must increase strictly; time[{k + 1}] = {t[k + 1]} <= time[{k}] = {t[k]}",
                             key="time", value=t[k + 1])
    return t


def _checked_options(t: np.ndarray, method, hold, rtol, atol, max_step, first_step, substeps):
    """The options of a :func:`~vehdyn.simulate` call checked, each with a ParameterError naming it:
    ``(rtol, atol, max_step, first_step)`` as floats (the step options None when not given)."""
    if not isinstance(hold, str) or hold not in _HOLDS:
        raise ParameterError(f"hold must be one of {_HOLDS}, got {hold!r}", key="hold", value=hold)
    rtol = _positive_option(rtol, "rtol")
    atol = _positive_option(atol, "atol")
    if max_step is not None:
        max_step = _positive_option(max_step, "max_step", allow_inf=True)
    if first_step is not None:
        first_step = _positive_option(first_step, "first_step")
        if first_step > t[-1] - t[0]:
            raise ParameterError(f"first_step {first_step:g} s exceeds the time span {t[-1] - t[0]:g} s",
                                 key="first_step", value=first_step)
    if isinstance(substeps, bool) or not (isinstance(substeps, (int, np.integer)) and substeps >= 1):
        raise ParameterError(f"substeps must be a positive integer, got {substeps!r}", key="substeps", value=substeps)
    if not isinstance(method, str):
        raise ParameterError(f"method must be a string, got {method!r}", key="method", value=method)
    return rtol, atol, max_step, first_step


def _positive_option(value, name: str, *, allow_inf: bool = False) -> float:
    """A positive number option (``rtol``, ``max_step``, ...) as a float, or a ParameterError naming it."""
    if type(value) is float or type(value) is int:  # the usual case, without numpy's overhead
        v = float(value)
    else:
        arr = float_array(value, name)
        v = float(arr) if arr.ndim == 0 and not isinstance(value, (bool, np.bool_)) else math.nan
    if not (v > 0) or not (math.isfinite(v) or (allow_inf and v == math.inf)):
        raise ParameterError(f"{name} must be a positive{'' if allow_inf else ', finite'} number, got {value!r}",
                             key=name, value=value)
    return v


def _common_batch(x0: np.ndarray, u: np.ndarray):
    """x0 (n,) or (n, n_batch) and inputs (m, n_t) or (m, n_t, n_batch) with one batch size: a batch of
    1 on either side is shared by the other's members; any other mismatch raises ParameterError."""
    if x0.ndim > 2 or (x0.ndim == 2 and x0.shape[1] == 0):
        raise ParameterError(f"x0 must have shape (n_states,) or (n_states, n_batch), got {x0.shape}", key="x0",
                             value=x0.shape)
    if x0.ndim == 2 and u.ndim == 3 and x0.shape[1] != u.shape[2]:
        nx, nu = x0.shape[1], u.shape[2]
        if nx == 1:
            x0 = np.broadcast_to(x0, (x0.shape[0], nu))
        elif nu == 1:
            u = np.broadcast_to(u, u.shape[:2] + (nx,))
        else:
            raise ParameterError(f"x0 has a batch of {nx} initial states but inputs a batch of {nu}: give one "
                                 "batch size (or 1 to share)", key="x0", value=(nx, nu))
    return x0, u


def _sample_inputs(model: Model, inputs: Any, t: np.ndarray) -> np.ndarray:
    """Inputs on the time grid, shape (n_inputs, n_times) or (n_inputs, n_times, n_batch).

    Only the documented forms pass (see :func:`simulate`); any other shape, a non-numeric or a
    non-finite value raises ParameterError naming the input. A mapping's arrays are (n_times,) or
    (n_times, n_batch): time is always their first axis, so a (n_times,) entry next to a
    (n_times, n_batch) one is one signal for the whole batch, never a batch of its own.
    """
    m, n_t = model.n_inputs, t.size
    names = model.input_names
    if inputs is None:
        return np.zeros((m, n_t))
    if callable(inputs):
        u = _sample_callable(inputs, t, m, "inputs", "inputs")
    elif isinstance(inputs, Mapping):
        unknown = [k for k in inputs if k not in names]
        if unknown:
            raise ParameterError(f"inputs: {type(model).__name__} has no input {unknown[0]!r}; its inputs are "
                                 f"{list(names)}", key="inputs", value=unknown[0])
        rows = []
        for name in names:
            v = inputs.get(name, 0.0)
            what = f"inputs[{name!r}]"
            key = f"inputs.{name}"
            v = _sample_callable(v, t, None, what, key) if callable(v) else float_array(v, key)
            if v.ndim == 0:
                v = np.full(n_t, float(v))
            if v.ndim > 2 or v.shape[0] != n_t or (v.ndim == 2 and v.shape[1] == 0):
                raise ParameterError(f"{what} must have shape (n_times,) = ({n_t},) or (n_times, n_batch) = "
                                     f"({n_t}, n_batch), got {v.shape}", key=key, value=v.shape)
            rows.append(v)
        batches = {r.shape[1] for r in rows if r.ndim == 2} - {1}
        if len(batches) > 1:
            sizes = {name: r.shape[1] for name, r in zip(names, rows) if r.ndim == 2}
            raise ParameterError(f"inputs: the batch sizes {sizes} differ (give one n_batch, or 1 to share a column)",
                                 key="inputs", value=sizes)
        batched = any(r.ndim == 2 for r in rows)
        u = np.empty((m, n_t) + ((max(batches, default=1),) if batched else ()))
        for i, r in enumerate(rows):
            u[i] = r[:, None] if batched and r.ndim == 1 else r
    else:
        u = float_array(inputs, "inputs")
        if u.ndim == 1 and m == 1 and u.shape[0] == n_t:
            u = u[None, :]
        if u.ndim not in (2, 3) or u.shape[0] != m or u.shape[1] != n_t or (u.ndim == 3 and u.shape[2] == 0):
            raise ParameterError(f"inputs must have shape (n_inputs, n_times) = ({m}, {n_t}) or (n_inputs, n_times, "
                                 f"n_batch) for inputs {list(names)}, got {u.shape}", key="inputs", value=u.shape)
    finite = np.isfinite(u)
    if not finite.all():
        idx = tuple(np.argwhere(~finite)[0])
        member = f", batch member {idx[2]}" if len(idx) == 3 else ""
        raise ParameterError(f"input {names[idx[0]]!r} is not finite at t = {t[idx[1]]}{member} ({u[idx]})",
                             key=f"inputs.{names[idx[0]]}", value=u[idx])
    return u


def _sample_callable(fun: Callable, t: np.ndarray, m: int | None, what: str, key: str) -> np.ndarray:
    """Samples of a callable input on the grid: (m, n_t[, n_batch]) for the whole input vector
    (``m`` given), (n_t[, n_batch]) for one named input; vectorized calls first, else sample by sample."""
    n_t = t.size
    try:
        v = np.asarray(fun(t))
        if m is None:
            vectorized = v.shape[:1] == (n_t,)
        else:
            vectorized = v.shape[:2] == (m, n_t) or (m == 1 and v.shape == (n_t,))
    except Exception:  # a scalar-only callable: evaluate sample by sample
        vectorized = False
    if not vectorized:
        # one value (or one batch of values) per instant, stacked along the time axis
        samples = [np.asarray(fun(tk)) for tk in t]
        if len({sample.shape for sample in samples}) > 1:
            raise ParameterError(f"{what}: u(t) returned values of different shapes "
                                 f"{sorted({sample.shape for sample in samples})}", key=key, value=None)
        v = np.stack(samples)
        if m is not None and v.ndim > 1:
            v = np.moveaxis(v, 0, 1)
    try:
        v = float_array(v, key)
    except ParameterError as exc:
        raise ParameterError(f"{what}: u(t) must return numbers, got {v.dtype} values", key=key, value=exc.value) from None
    if m is not None:
        if v.ndim == 1 and m == 1:
            v = v[None, :]
        if v.ndim not in (2, 3) or v.shape[:2] != (m, n_t):
            raise ParameterError(f"{what}: u(t) must return {m} values per instant (one per input), got samples of "
                                 f"shape {v.shape}", key=key, value=v.shape)
    return v


def _interpolator(t: np.ndarray, u: np.ndarray, hold: str) -> Callable[[float], np.ndarray]:
    """u(t) between samples: previous sample (zoh) or linear (foh); held beyond the grid."""
    n_t = t.size
    if u.shape[0] == 0 or np.all(u == u[:, :1]):
        constant = np.ascontiguousarray(u[:, 0])
        return lambda tt: constant

    def u_at(tt: float) -> np.ndarray:
        k = int(np.searchsorted(t, tt, side="right") - 1)
        if k < 0:
            return u[:, 0]
        if k >= n_t - 1:
            return u[:, -1]
        if hold == "zoh":
            return u[:, k]
        w = (tt - t[k]) / (t[k + 1] - t[k])
        return (1.0 - w) * u[:, k] + w * u[:, k + 1]

    return u_at


def _named_inputs(model: Model, inputs: Any) -> Any:
    """``inputs`` with a bare :class:`~vehdyn.PiecewiseSignal` given to a one-input model named
    (``{name: signal}``), so that both backends see it as the closed form it is."""
    from vehdyn.piecewise_signal import PiecewiseSignal

    if isinstance(inputs, PiecewiseSignal) and model.n_inputs == 1:
        return {model.input_names[0]: inputs}
    return inputs


def _input_function(model: Model, inputs: Any, t: np.ndarray, u: np.ndarray, hold: str):
    """u(t) for the numpy solvers (``solve_ivp`` methods, rk4) and the breakpoints of its closed forms.

    Closed-form inputs (:class:`~vehdyn.PiecewiseSignal` entries of a mapping) are evaluated exactly
    at every stage, as the compiled backend evaluates them (:func:`vehdyn.simulation.compiled.input_table`);
    the sampled ones (arrays, numbers, other callables) between samples as ``hold`` says
    (:func:`_interpolator`).

    Returns
    -------
    u_at : callable
        ``u_at(t)``; ``u_at.segment_start`` (None by default) is the start of the integration segment
        (between two breakpoints) being integrated: a closed-form input then takes the piece active
        there, also at the segment's end, so that no step sees the next piece.
    breakpoints : ndarray
        Sorted times inside (t[0], t[-1]) where a closed-form input begins a new piece [s].
    """
    from vehdyn.piecewise_signal import PiecewiseSignal

    sampled = _interpolator(t, u, hold)
    given = inputs if isinstance(inputs, Mapping) else {}
    exact = [(i, given[name]) for i, name in enumerate(model.input_names)
             if isinstance(given.get(name), PiecewiseSignal)]
    if not exact:
        return sampled, np.zeros(0)

    def u_at(tt: float) -> np.ndarray:
        value = np.array(sampled(tt), dtype=float)  # a copy: the interpolator may return a view of u
        tt = float(tt)
        for i, signal in exact:
            value[i] = signal.value_at(tt, u_at.segment_start)
        return value

    u_at.segment_start = None
    points = np.unique(np.concatenate([signal.breakpoints for _, signal in exact]))
    return u_at, points[(points > t[0]) & (points < t[-1])]
