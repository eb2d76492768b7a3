"""Time simulation of any vehdyn model: ``simulate(model, time, inputs, x0, method)``.

Methods
-------
``"exact"``
    For a :class:`~vehdyn.LinearModel`: the exact discretization of dx/dt = A x + B u for inputs
    held constant (``hold="zoh"``) or linear (``hold="foh"``) between samples (a
    :class:`~vehdyn.PiecewiseSignal` too is sampled here: its sines between samples are not exact
    unless the grid resolves them; a ``solve_ivp`` method evaluates it exactly), through one matrix
    exponential per distinct step size (Franklin, Powell & Workman, *Digital Control of Dynamic
    Systems*, 3rd ed., sec. 4.3 and 6.3.2). The recurrence x[k+1] = Ad x[k] + g[k] is evaluated as a
    parallel prefix scan: log2(N) array passes of ``c[d:] += Ad^d c[:-d]`` instead of N Python
    iterations.
any ``scipy.integrate.solve_ivp`` method
    ``"RK45"``, ``"RK23"``, ``"DOP853"``, ``"Radau"``, ``"BDF"``, ``"LSODA"`` with ``rtol``, ``atol``
    and ``max_step``; sampled inputs are interpolated with the same hold; closed-form inputs
    (:class:`~vehdyn.PiecewiseSignal`) are evaluated exactly at every stage and the run is
    restarted on their breakpoints, so that no step straddles a kink (as on the compiled backend).
    The explicit ones (``"RK23"``, ``"RK45"``, ``"DOP853"``) are judged for stiffness: the step
    their stability allows, :func:`stability_interval` / max |Re lambda| of the state Jacobian,
    gives the number of steps the run needs whatever the tolerance; above ``STIFF_STEPS_WARN``
    (1e5) a :class:`~vehdyn.VehdynWarning` says so, above ``STIFF_STEPS_REFUSE`` (1e7) a
    ParameterError names ``method`` and the implicit methods to use instead
    (``check_stability=False`` runs it anyway). A LinearModel is judged before the run (its
    eigenvalues cost microseconds); any other model once the solver has made 20,000 rhs calls, and
    again at every doubling, so that short runs never pay for a Jacobian.
``"rk4"``
    Classical fixed-step Runge-Kutta on the time grid (optionally ``substeps`` per interval),
    vectorized across a trailing batch axis; a PiecewiseSignal is evaluated at every stage (a kink
    between steps is stepped over: the fixed step sets the error there). Before it starts it checks
    the step against the model's fastest eigenvalue at the initial point and refuses a step outside
    RK4's stability region.
``"auto"``
    ``"exact"`` for a linear model; otherwise ``"LSODA"`` when the linearization at the initial
    point is stiff over the run, ``"DOP853"`` when ``rtol < 1e-8``, else ``"RK45"``. The choice and
    its reason are in ``result.method`` and ``result.method_reason``.

Backends (``backend=``): ``"numpy"`` runs the methods above on the model's ``rhs``;
``"compiled"`` runs ``"RK45"``, ``"DOP853"`` (:mod:`vehdyn._compiled_ode`) and ``"BDF"`` (the
stiff one, :mod:`vehdyn._compiled_bdf`: scipy's BDF with a difference Jacobian of the compiled
rhs) compiled (numba, optional) on the model's :meth:`~vehdyn.Model.compiled_rhs` for one vehicle, and a batch
(array parameters, or a batch of initial states or inputs) of a model with a compiled batch
(:meth:`SingleTrack.compiled_batch <vehdyn.handling.SingleTrack.compiled_batch>`): every variant
integrated by the same loop with its own step-size control, so that it gets bitwise the states of
its own compiled run, the variants spread over the cores; ``"auto"`` (default) takes the compiled
one when the method is one of those three, numba is installed and the model has a compiled rhs (and,
for a batch, a compiled batch), and says so in ``result.method_reason``. :func:`simulate_many`
runs many calls, grouping those of one model structure into compiled batches.
"""

from __future__ import annotations

import functools
import math
import time as _time
import warnings
from typing import Any, Callable, Mapping

import numpy as np

from .errors import ParameterError, SimulationError, VehdynWarning
from .model import Model, float_array, signal_vector
from .results import SimulationResult

__all__ = ["simulate", "simulate_many", "SOLVE_IVP_METHODS", "rk4_stability_limit", "stability_interval",
           "exact_discretization", "STIFF_STEPS_WARN", "STIFF_STEPS_REFUSE"]

SOLVE_IVP_METHODS = ("RK45", "RK23", "DOP853", "Radau", "BDF", "LSODA")
_HOLDS = ("zoh", "foh")


# --------------------------------------------------------------------------- input handling
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
    from .piecewise_signal import PiecewiseSignal

    if isinstance(inputs, PiecewiseSignal) and model.n_inputs == 1:
        return {model.input_names[0]: inputs}
    return inputs


def _input_function(model: Model, inputs: Any, t: np.ndarray, u: np.ndarray, hold: str):
    """u(t) for the numpy solvers (``solve_ivp`` methods, rk4) and the breakpoints of its closed forms.

    Closed-form inputs (:class:`~vehdyn.PiecewiseSignal` entries of a mapping) are evaluated exactly
    at every stage, as the compiled backend evaluates them (:func:`vehdyn._compiled_ode.input_table`);
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
    from .piecewise_signal import PiecewiseSignal

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


# --------------------------------------------------------------------------- exact (linear)
def exact_discretization(A: np.ndarray, B: np.ndarray, dt: float, hold: str = "zoh"):
    """Exact discretization of dx/dt = A x + B u over a step ``dt`` [s].

    Returns
    -------
    (Ad, B0, B1) : tuple of ndarray
        x[k+1] = Ad x[k] + B0 u[k] + B1 u[k+1]; ``B1`` is zero for a zero-order hold.

    Notes
    -----
    One matrix exponential of the block matrix [[A dt, B dt, 0], [0, 0, I], [0, 0, 0]] gives
    Ad = e^(A dt), G1 = int_0^dt e^(A s) ds B and G2 = int_0^dt e^(A s) (dt - s)/dt ds B
    (van Loan's method); zoh: B0 = G1, B1 = 0; foh: B0 = G1 - G2, B1 = G2.
    """
    from scipy.linalg import expm

    n, m = B.shape
    if hold == "zoh":
        blk = np.zeros((n + m, n + m))
        blk[:n, :n] = A * dt
        blk[:n, n:] = B * dt
        E = expm(blk)
        return E[:n, :n], E[:n, n:], np.zeros((n, m))
    blk = np.zeros((n + 2 * m, n + 2 * m))
    blk[:n, :n] = A * dt
    blk[:n, n:n + m] = B * dt
    blk[n:n + m, n + m:] = np.eye(m)
    E = expm(blk)
    Ad, G1, G2 = E[:n, :n], E[:n, n:n + m], E[:n, n + m:]
    return Ad, G1 - G2, G2


def _linear_recurrence(Ad: np.ndarray, g: np.ndarray) -> np.ndarray:
    """All partial sums c[k] = sum_{j<=k} Ad^(k-j) g[j] by a Hillis-Steele prefix scan.

    g has shape (N, n, ...); the scan does ceil(log2 N) passes of c[d:] += Ad^d c[:-d].
    """
    c = g.copy()
    N = c.shape[0]
    P = Ad.copy()
    d = 1
    while d < N:
        # the product is formed before the in-place add, so the overlap of c[d:] and c[:-d] is safe
        c[d:] += (c[:-d] @ P.T) if c.ndim == 2 else (P @ c[:-d])
        d *= 2
        if d < N:
            P = P @ P
    return c


def _simulate_exact(model, t, u, x0, hold):
    A, B = model.A, model.B
    n = A.shape[0]
    dts = np.diff(t)
    N = t.size
    batch_shape = x0.shape[1:]
    if u.ndim == 3 and not batch_shape:
        batch_shape = u.shape[2:]
    x = np.empty((N, n) + tuple(batch_shape))
    x0b = np.broadcast_to(x0.reshape((n,) + x0.shape[1:] + (1,) * (len(batch_shape) - len(x0.shape[1:]))),
                          (n,) + tuple(batch_shape))
    uT = np.moveaxis(u, 1, 0)  # (N, m, ...)
    if uT.ndim - 2 < len(batch_shape):
        uT = np.broadcast_to(uT[..., None], uT.shape + tuple(batch_shape))
    x[0] = x0b
    uniform = np.allclose(dts, dts[0], rtol=1e-9, atol=0.0)
    if uniform:
        Ad, B0, B1 = exact_discretization(A, B, float(np.mean(dts)), hold)
        if uT.ndim == 2:
            g = uT[:-1] @ B0.T
            if hold == "foh":
                g += uT[1:] @ B1.T
        else:
            g = B0 @ uT[:-1]
            if hold == "foh":
                g += B1 @ uT[1:]
        g[0] += Ad @ x0b
        x[1:] = _linear_recurrence(Ad, g)
        n_expm = 1
    else:
        # one discretization per distinct step size; the recurrence then runs step by step
        cache: dict[float, tuple] = {}
        for k, dt in enumerate(dts):
            key = float(np.round(dt, 15))
            if key not in cache:
                cache[key] = exact_discretization(A, B, dt, hold)
            Ad, B0, B1 = cache[key]
            x[k + 1] = Ad @ x[k] + B0 @ uT[k] + (B1 @ uT[k + 1] if hold == "foh" else 0.0)
        n_expm = len(cache)
    return np.moveaxis(x, 0, 1), n_expm


# --------------------------------------------------------------------------- rk4
@functools.lru_cache(maxsize=None)
def _stability_polynomial(method: str) -> np.ndarray:
    """Coefficients c_k of the stability function R(z) = sum_k c_k z^k of an explicit Runge-Kutta
    method: c_0 = 1, c_k = b^T A^(k-1) 1 (Hairer & Wanner, *Solving ODEs II*, 2nd ed., sec. IV.2),
    from scipy's tableaus for the ``solve_ivp`` methods."""
    if method == "rk4":
        return np.array([1.0, 1.0, 1 / 2, 1 / 6, 1 / 24])
    from scipy import integrate

    solver = getattr(integrate, method)
    b = np.asarray(solver.B, dtype=float)
    tableau = np.asarray(solver.A, dtype=float)[: b.size, : b.size]
    a = np.zeros((b.size, b.size))
    a[:, : tableau.shape[1]] = tableau
    coefficients, v = [1.0], np.ones(b.size)
    for _ in range(b.size):
        coefficients.append(float(b @ v))
        v = a @ v
    return np.array(coefficients)


def _stability_limit(eigenvalues, method: str) -> float:
    """Largest step [s] for which the explicit ``method`` is stable on ``eigenvalues`` (see
    :func:`rk4_stability_limit`)."""
    lam = np.atleast_1d(np.asarray(eigenvalues, dtype=complex))
    lam = lam[(lam.real < 0) & (np.abs(lam) > 0)]
    if lam.size == 0:
        return float("inf")
    coefficients = _stability_polynomial(method)[::-1]

    def unstable(radius):
        return np.abs(np.polyval(coefficients, radius * lam / np.abs(lam))) > 1.0

    # march out along each ray to the first unstable |z| (every region here lies inside |z| < 8),
    # then bisect: the first crossing, not a later island of the region
    radii = np.linspace(0.0, 8.0, 321)[1:]
    first = np.argmax(unstable(radii[:, None]), axis=0)
    hi = radii[first]
    lo = np.where(first > 0, radii[first - 1], 0.0)
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        bad = unstable(mid)
        lo = np.where(bad, lo, mid)
        hi = np.where(bad, mid, hi)
    return float(np.min(lo / np.abs(lam)))


def rk4_stability_limit(eigenvalues) -> float:
    """Largest step [s] for which classical RK4 is stable on the given eigenvalues.

    Solves |R(h lambda)| = 1 along each ray h lambda (R(z) = 1 + z + z^2/2 + z^3/6 + z^4/24) by
    bisection; eigenvalues with non-negative real part impose no limit (they grow anyway).
    Returns ``inf`` when no eigenvalue limits the step.
    """
    return _stability_limit(eigenvalues, "rk4")


def stability_interval(method: str) -> float:
    """Length of the stability interval of an explicit method on the negative real axis [-].

    An explicit method integrating a decay at rate lambda [1/s] is stable only for steps
    h <= interval / lambda, however smooth the solution: this is what makes a stiff problem
    expensive for it. ``method`` is ``"rk4"``, ``"RK23"``, ``"RK45"`` or ``"DOP853"`` (scipy's
    tableaus). Classical RK4: 2.785; Dormand-Prince 5(4) (``"RK45"``): 3.307 (Hairer & Wanner,
    *Solving ODEs II*, sec. IV.2).
    """
    if not isinstance(method, str) or method not in _EXPLICIT:
        raise ParameterError(f"method must be one of {_EXPLICIT}, got {method!r}", key="method", value=method)
    return _real_stability_interval(method)


@functools.lru_cache(maxsize=None)
def _real_stability_interval(method: str) -> float:
    return _stability_limit([-1.0], method)


_EXPLICIT = ("rk4", "RK23", "RK45", "DOP853")
_IMPLICIT_HINT = "an implicit method: method='LSODA', 'Radau' or 'BDF' (or 'exact' for a LinearModel, or 'auto')"
# stability-limited step counts above which an explicit method is warned about, and refused
STIFF_STEPS_WARN = 1e5
STIFF_STEPS_REFUSE = 1e7


def _stiffness_estimate(method: str, lam, t_from: float, t_to: float, where: str) -> tuple[float, str]:
    """Steps the explicit ``method`` needs for stability alone from ``t_from`` to ``t_to``, given the
    eigenvalues ``lam`` of the state Jacobian (decay rates |Re lambda| against the method's real-axis
    stability interval), and the sentence that says so."""
    fast = float(np.max(-np.asarray(lam).real, initial=0.0))
    if fast <= 0.0:
        return 0.0, ""
    h_max = stability_interval(method) / fast
    steps = (t_to - t_from) / h_max
    return steps, (f"method {method!r} is explicit and the problem is stiff: the fastest decay rate of the state "
                   f"Jacobian {where} is {fast:.3g} 1/s, so {method} is stable only for steps <= {h_max:.3g} s, "
                   f"about {steps:.2g} steps for the {t_to - t_from:g} s to go; use {_IMPLICIT_HINT}")


def _check_stiffness(method: str, lam, t_from: float, t_to: float, where: str, *, warn: bool = True,
                     stacklevel: int = 3) -> float:
    """Warn (VehdynWarning) or refuse (ParameterError) an explicit ``method`` whose stability alone
    needs more than STIFF_STEPS_WARN or STIFF_STEPS_REFUSE steps (see _stiffness_estimate).
    Returns that step count."""
    steps, message = _stiffness_estimate(method, lam, t_from, t_to, where)
    if steps > STIFF_STEPS_REFUSE:
        raise ParameterError(message + ", or check_stability=False to run it anyway", key="method", value=method)
    if warn and steps > STIFF_STEPS_WARN:
        warnings.warn(message, VehdynWarning, stacklevel=stacklevel)
    return steps


def _state_jacobian_eigenvalues(model, t0, x0, u0) -> np.ndarray:
    """Eigenvalues of df/dx at (t0, x0, u0) for every batch member (central differences).

    Works for models whose parameters are arrays along the batch axis: each call perturbs one
    state in every batch member at once. For one vehicle the 2n perturbed states go into one call
    along the batch axis (DESIGN §3; a numpy rhs costs its call overhead, not its columns: the full
    vehicle's 64 calls took 140 ms, one call of 64 columns 6 ms), kept only where the model's
    batched call gives its single call's derivatives at the unperturbed point (an extra column
    checked against an extra call), else one perturbation per call. Returns an array of shape
    (n_batch, n) or (n,).
    """
    n = model.n_states
    single = x0.ndim == 1
    X = x0[:, None] if single else x0
    U = u0[:, None] if u0.ndim == 1 else u0
    if U.shape[1] != X.shape[1]:
        U = np.broadcast_to(U, (U.shape[0], X.shape[1]))
    if single:
        J = _single_jacobian_in_one_call(model, t0, X[:, 0], U[:, 0])
        if J is not None:
            return np.linalg.eigvals(J)
    J = np.empty((X.shape[1], n, n))
    for i in range(n):
        h = _jacobian_steps(X[i])
        Xp, Xm = X.copy(), X.copy()
        Xp[i] += h
        Xm[i] -= h
        J[:, :, i] = ((np.asarray(model.rhs(t0, Xp, U)) - np.asarray(model.rhs(t0, Xm, U))) / (2 * h)).T
    lam = np.linalg.eigvals(J)
    return lam[0] if single else lam


def _jacobian_steps(x):
    """Central-difference steps [state units] of :func:`_state_jacobian_eigenvalues`."""
    return 1e-6 * np.maximum(np.abs(x), 1.0)


def _single_jacobian_in_one_call(model, t0, x, u):
    """df/dx (n, n) of one vehicle by central differences (steps of :func:`_state_jacobian_eigenvalues`)
    from one rhs call on the 2n perturbed states and x itself as batch columns, or None when the
    model's rhs does not take that batch or its column at x differs from its single call there."""
    n = x.size
    h = _jacobian_steps(x)
    columns = np.repeat(x[:, None], 2 * n + 1, axis=1)
    index = np.arange(n)
    columns[index, index] += h
    columns[index, n + index] -= h
    try:
        with np.errstate(all="ignore"):
            f = np.asarray(model.rhs(t0, columns, np.repeat(u[:, None], 2 * n + 1, axis=1)), dtype=float)
            f0 = np.asarray(model.rhs(t0, x, u), dtype=float)
    except Exception:  # a rhs that takes no batch of states (scalar logic): one call per perturbation
        return None
    if f.shape != (n, 2 * n + 1) or f0.shape != (n,):
        return None
    # the batch column at x against the single call: numpy's array path against the laws' scalar path
    # (math), a few ulps apart on CPUs whose numpy runs SIMD kernels; a derivative that is a small
    # difference of larger terms (~0 at a trim) is judged against the largest derivative
    if not np.all(np.isclose(f[:, -1], f0, rtol=1e-12, atol=1e-12 * float(np.max(np.abs(f0), initial=0.0)))):
        return None
    return (f[:, :n] - f[:, n:2 * n]) / (2 * h)


def _simulate_rk4(model, t, u, x0, hold, substeps, check_stability, inputs=None):
    n = model.n_states
    u_at, _ = _input_function(model, inputs, t, u, hold)  # fixed steps: a kink between samples is stepped over
    if check_stability and n > 0:
        lam = _state_jacobian_eigenvalues(model, t[0], x0, u[:, 0]).reshape(-1)
        h_max = rk4_stability_limit(lam)
        h = float(np.max(np.diff(t))) / substeps
        if h > h_max:
            fast = lam[np.argmax(np.abs(lam))]
            raise SimulationError(
                f"rk4 step {h:.3g} s exceeds the stability limit {h_max:.3g} s set by the eigenvalue "
                f"{fast:.4g} 1/s of the state Jacobian at t = {t[0]:g} s; use a smaller step, "
                f"substeps >= {int(np.ceil(h * substeps / h_max))}, or an implicit method ('Radau', 'LSODA')",
                time=float(t[0]),
            )
    batch = x0.shape[1:] if x0.ndim > 1 else (u.shape[2:] if u.ndim == 3 else ())
    x = np.empty((n, t.size) + tuple(batch))
    xk = np.broadcast_to(x0.reshape((n,) + x0.shape[1:] + (1,) * (len(batch) - (x0.ndim - 1))),
                         (n,) + tuple(batch)).astype(float).copy()
    x[:, 0] = xk
    f = model.rhs
    nfev = 0
    names = model.state_names
    for k in range(t.size - 1):
        h = (t[k + 1] - t[k]) / substeps
        tk = t[k]
        for s in range(substeps):
            ta = tk + s * h
            u0, u1, u2 = u_at(ta), u_at(ta + 0.5 * h), u_at(ta + h)
            k1 = f(ta, xk, u0)
            k2 = f(ta + 0.5 * h, xk + 0.5 * h * k1, u1)
            k3 = f(ta + 0.5 * h, xk + 0.5 * h * k2, u1)
            k4 = f(ta + h, xk + h * k3, u2)
            xk = xk + (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
            nfev += 4
        if not np.all(np.isfinite(xk)):
            bad = np.argwhere(~np.isfinite(xk.reshape(n, -1)))[0]
            raise SimulationError(
                f"state {names[bad[0]]!r} became non-finite ({xk.reshape(n, -1)[tuple(bad)]}) at t = "
                f"{t[k + 1]:.6g} s (rk4, step {h:.3g} s" + (f", batch member {bad[1]}" if batch else "") + ")",
                time=float(t[k + 1]), signal=names[bad[0]],
            )
        violation = _domain_violation(model, t[k + 1], xk)
        if violation is not None:
            raise violation
        x[:, k + 1] = xk
    return x, nfev



# --------------------------------------------------------------------------- the model's domain
def _domain_bounds(model):
    """[(state index, name, low, high)] of the model's :attr:`~vehdyn.Model.domain`."""
    domain = getattr(model, "domain", None) or {}
    return [(model.state_names.index(name), name, float(low), float(high)) for name, (low, high) in domain.items()]


def _domain_violation(model, t, x):
    """The first (over time, then over the domain's states) accepted state outside the model's domain,
    as the model's :meth:`~vehdyn.Model.domain_error`, or None. ``x``: (n, n_t, ...) or (n, ...) at ``t``."""
    bounds = _domain_bounds(model)
    if not bounds:
        return None
    x = np.asarray(x)
    t = np.atleast_1d(np.asarray(t, dtype=float))
    xs = x.reshape(x.shape[0], t.size, -1)
    first = None
    for i, name, low, high in bounds:
        values = xs[i]
        outside = ~((values >= low) & (values <= high))
        if np.any(outside):
            k, member = np.argwhere(outside)[0]
            if first is None or k < first[0]:
                first = (int(k), name, float(values[k, member]))
    if first is None:
        return None
    return model.domain_error(first[1], first[2], float(t[first[0]]))


def _domain_events(model, shape):
    """Terminal ``solve_ivp`` events, one per bound of the model's domain (evaluated on accepted steps
    only, so that a rejected trial stage outside the domain never stops a run)."""
    events = []
    for i, name, low, high in _domain_bounds(model):
        for bound, sign in ((low, 1.0), (high, -1.0)):
            def event(tt, y, i=i, bound=bound, sign=sign):
                return float(np.min(sign * (y.reshape(shape)[i] - bound)))

            event.terminal, event.direction = True, -1.0
            event.state = (name, bound)
            events.append(event)
    return events

# --------------------------------------------------------------------------- solve_ivp
# rhs calls after which an explicit solve_ivp run looks at its stiffness (then at every doubling):
# small runs never pay for the Jacobian, long ones pay well under 1 % of what they have spent
_STIFFNESS_WATCH_CALLS = 20_000


def _simulate_ivp(model, t, u, x0, hold, method, rtol, atol, max_step, first_step, watch_stiffness=False,
                  inputs=None):
    from scipy.integrate import solve_ivp

    n = model.n_states
    batch = x0.shape[1:] if x0.ndim > 1 else (u.shape[2:] if u.ndim == 3 else ())
    shape = (n,) + tuple(batch)
    x0b = np.broadcast_to(x0.reshape((n,) + x0.shape[1:] + (1,) * (len(batch) - (x0.ndim - 1))), shape)
    u_at, breakpoints = _input_function(model, inputs, t, u, hold)

    def rhs(tt, y):
        return np.asarray(model.rhs(tt, y.reshape(shape), u_at(tt)), dtype=float).reshape(-1)

    fun = rhs
    if watch_stiffness and method in _EXPLICIT and n > 0:
        calls, next_check = 0, _STIFFNESS_WATCH_CALLS
        warned = False

        def fun(tt, y):
            nonlocal calls, next_check, warned
            calls += 1
            if calls == next_check:
                next_check *= 2
                lam = _state_jacobian_eigenvalues(model, tt, y.reshape(shape), np.asarray(u_at(tt)))
                steps = _check_stiffness(method, lam, tt, t[-1], f"at t = {tt:.6g} s (after {calls} rhs calls)",
                                         warn=not warned, stacklevel=2)
                warned = warned or steps > STIFF_STEPS_WARN
            return rhs(tt, y)

    opts = {"rtol": rtol, "atol": atol}
    if (method in ("Radau", "BDF", "LSODA") and not batch and type(model).jacobian is not Model.jacobian
            and model.jacobian(t[0], x0b, u_at(t[0])) is not None):
        # an analytic Jacobian saves the implicit methods their finite-difference columns
        def jac(tt, y):
            return np.asarray(model.jacobian(tt, y, u_at(tt))[0], dtype=float)

        opts["jac"] = jac
    if max_step is not None:
        opts["max_step"] = max_step
    events = _domain_events(model, shape)
    if events:
        opts["events"] = events
    # one solve_ivp run per segment between the breakpoints of closed-form inputs (their kinks and
    # jumps), as the compiled loop ends its steps on them: no step straddles a kink
    edges = np.concatenate([[t[0]], breakpoints, [t[-1]]])
    y = np.empty((x0b.size, t.size))
    y_start = x0b.reshape(-1).astype(float)
    counters = {"nfev": 0, "njev": 0, "nlu": 0, "message": ""}
    for a, b in zip(edges[:-1], edges[1:]):
        inside = (t >= a) & (t <= b)
        t_eval = t[inside]
        if t_eval.size == 0 or t_eval[-1] != b:  # the segment's end state starts the next segment
            t_eval = np.append(t_eval, b)
        if breakpoints.size:
            u_at.segment_start = a
        if a > t[0]:
            opts.pop("first_step", None)
        elif first_step is not None:
            opts["first_step"] = min(first_step, b - a)
        sol = _solve_ivp_segment(solve_ivp, fun, a, b, y_start, method, t_eval, opts, t[0])
        if sol.status == 1:  # a terminal event: an accepted step crossed a bound of the model's domain
            crossed = [(float(times[0]), event, values[0]) for event, times, values in
                       zip(events, sol.t_events, sol.y_events) if len(times)]
            t_cross, event, y_cross = min(crossed, key=lambda item: item[0])
            name, bound = event.state
            raise model.domain_error(name, bound, t_cross)
        y[:, inside] = sol.y[:, :np.count_nonzero(inside)]
        y_start = sol.y[:, -1]
        counters.update(nfev=counters["nfev"] + int(sol.nfev), njev=counters["njev"] + int(sol.njev),
                        nlu=counters["nlu"] + int(sol.nlu), message=str(sol.message))
    y = y.reshape(shape + (t.size,))
    y = np.moveaxis(y, -1, 1)
    return y, counters


def _solve_ivp_segment(solve_ivp, fun, a, b, y0, method, t_eval, opts, t_first):
    """One ``solve_ivp`` run from ``a`` to ``b`` [s]; its failures as SimulationError (``t_first``:
    the start of the whole run, for the message of a failure in the first step)."""
    try:
        with np.errstate(over="ignore", invalid="ignore"):
            sol = solve_ivp(fun, (a, b), y0, method=method, t_eval=t_eval, **opts)
    except (ArithmeticError, ValueError) as exc:
        # numerical failures raised inside the solver (a LU of a non-finite Jacobian, an overflow),
        # not the user's own errors: those propagate as they are
        if isinstance(exc, ParameterError) or not (isinstance(exc, (ArithmeticError, np.linalg.LinAlgError))
                                                   or "infs or NaNs" in str(exc)):
            raise
        raise SimulationError(f"{method} failed: {exc}", time=None) from exc
    if sol.status < 0:
        reached = np.asarray(sol.t)
        if reached.size:
            t_end = float(reached[-1])
            raise SimulationError(f"{method} failed after t = {t_end:.6g} s (the last output instant it reached): "
                                  f"{sol.message}", time=t_end)
        if a > t_first:
            raise SimulationError(f"{method} failed after t = {a:.6g} s (the breakpoint of an input where its "
                                  f"segment began): {sol.message}", time=float(a))
        raise SimulationError(f"{method} failed in its first step from t = {a:.6g} s: {sol.message}",
                              time=float(a))
    return sol


# --------------------------------------------------------------------------- auto
def _choose_method(model, t, u, x0, rtol) -> tuple[str, str]:
    from .linear import LinearModel

    if isinstance(model, LinearModel):
        return "exact", "linear model: exact discretization through the matrix exponential"
    if model.n_states == 0:
        return "RK45", "no states"
    try:
        lam = _state_jacobian_eigenvalues(model, t[0], x0, u[:, 0]).reshape(-1)
    except Exception as exc:  # pragma: no cover - a model whose Jacobian cannot be evaluated
        return "LSODA", f"linearization at the initial point failed ({exc}); LSODA switches by itself"
    fast = float(np.max(np.abs(lam.real), initial=0.0))
    duration = float(t[-1] - t[0])
    if fast * duration > 1e3:
        return "LSODA", (f"stiff: fastest decay rate {fast:.3g} 1/s times the {duration:g} s run is "
                         f"{fast * duration:.3g} > 1e3")
    if rtol < 1e-8:
        return "DOP853", f"non-stiff, tight tolerance rtol = {rtol:g}: 8th-order Dormand-Prince"
    return "RK45", f"non-stiff (fastest decay rate {fast:.3g} 1/s over {duration:g} s)"


# --------------------------------------------------------------------------- entry point
def simulate(
    model: Model,
    time,
    inputs=None,
    x0=None,
    method: str = "auto",
    *,
    rtol: float = 1e-6,
    atol: float = 1e-9,
    hold: str = "foh",
    max_step: float | None = None,
    first_step: float | None = None,
    substeps: int = 1,
    check_stability: bool = True,
    backend: str = "auto",
) -> SimulationResult:
    """Simulate ``model`` over the time grid ``time``.

    Parameters
    ----------
    model : Model
        Any vehdyn model (a :class:`~vehdyn.LinearModel` or a user's :class:`~vehdyn.Model`).
    time : array_like
        Strictly increasing output times [s]; the simulation starts at ``time[0]``.
    inputs : None, mapping, array_like or callable
        ``None`` (all inputs zero); ``{name: value}`` with each value a number, an array of shape
        (n_times,) or (n_times, n_batch) -- time first; a (n_times,) signal next to batched ones is
        shared by every member --, a :class:`~vehdyn.PiecewiseSignal` (closed form, e.g. the
        manoeuvres of :mod:`vehdyn.handling.maneuvers`) or another callable ``u(t)`` returning one
        value (or n_batch values) per instant (omitted inputs are zero); an array of shape
        (n_inputs, n_times) or (n_inputs, n_times, n_batch); or a callable ``u(t)`` returning the
        input vector (n_inputs,) per instant, or (n_inputs, n_times) when called with the whole grid
        (a PiecewiseSignal alone for a one-input model is that input). Every value must be a finite
        number: other shapes, strings and non-finite samples (callables included) raise
        ParameterError naming the input, the instant and, in a batch, the member.

        A PiecewiseSignal is evaluated exactly at every stage of the adaptive methods and rk4, on
        both backends (method ``"exact"`` samples it). Any other callable is *sampled on the time
        grid* and then held between samples as ``hold`` says, like an array, on both backends (the
        compiled loop cannot call Python): its result is as fine as the grid; give a closed-form
        input as a PiecewiseSignal, or a grid that resolves it.
    x0 : None, mapping or array_like
        Initial state (zeros by default); shape (n_states,) or (n_states, n_batch) for a batch.
        Batch sizes of ``x0`` and ``inputs`` must agree; a batch of 1 on either side is shared.
    method : str
        ``"auto"``, ``"exact"``, ``"rk4"`` or a ``solve_ivp`` method name.
    rtol, atol : float
        Tolerances of the adaptive methods.
    hold : {"foh", "zoh"}
        How sampled inputs (arrays, and callables other than a PiecewiseSignal) vary between
        samples: linearly (default, as ``scipy.signal.lsim`` and ``control.forced_response``) or
        held constant.
    max_step, first_step : float, optional
        Passed to ``solve_ivp`` and the compiled backend [s]; both positive (``max_step`` may be
        ``inf``), ``first_step`` at most the span of ``time``.
    substeps : int
        rk4 steps per interval of the time grid.
    check_stability : bool
        rk4: refuse a step outside RK4's stability region for the fastest eigenvalue of the
        linearization at the initial point. ``"RK23"``, ``"RK45"``, ``"DOP853"`` on numpy: warn
        about, or refuse, a stiff problem (module docstring). False skips both checks.
    backend : {"auto", "numpy", "compiled"}
        See the module docstring; ``"compiled"`` raises ParameterError where it cannot run (numba
        missing, a model without a compiled rhs, a batch, another method), naming why.

    Returns
    -------
    SimulationResult

    Raises
    ------
    ParameterError
        On malformed time, inputs, x0 or options (non-numeric, non-finite, wrong shape, mismatched
        batch sizes), naming the argument; on an explicit method for a problem so stiff that it
        would need more than ``STIFF_STEPS_REFUSE`` steps.
    SimulationError
        When the solver fails (its message is included) or a state becomes non-finite (the state
        and the time are named).

    Warns
    -----
    VehdynWarning
        When an explicit method's stability alone needs more than ``STIFF_STEPS_WARN`` steps.
    """
    from .linear import LinearModel

    if not isinstance(model, Model):
        raise ParameterError(f"model must be a vehdyn Model, got {type(model).__name__}", key="model", value=model)
    t = _time_grid(time)
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
    inputs = _named_inputs(model, inputs)
    u = _sample_inputs(model, inputs, t)
    x0v, u = _common_batch(signal_vector(x0, model.states, "x0"), u)
    reason = ""
    if method == "auto":
        method, reason = _choose_method(model, t, u, x0v, rtol)
    valid = ("exact", "rk4") + SOLVE_IVP_METHODS
    if method not in valid:
        raise ParameterError(f"method must be 'auto' or one of {valid}, got {method!r}", key="method", value=method)
    if method == "exact" and not isinstance(model, LinearModel):
        raise ParameterError(
            f"method 'exact' needs a LinearModel; {type(model).__name__} is not linear "
            "(use model.linearize() first, or a solve_ivp method)", key="method", value=method)
    if check_stability and not reason and method in _EXPLICIT[1:] and isinstance(model, LinearModel) and model.n_states:
        # a linear model's eigenvalues cost microseconds: judge the explicit method before it starts
        # (other models are judged by the solver loop once a run turns out long, see _simulate_ivp)
        _check_stiffness(method, np.linalg.eigvals(model.A), float(t[0]), float(t[-1]), "A")

    violation = _domain_violation(model, t[0], x0v)
    if violation is not None:
        raise violation
    compiled, why = _compiled_backend(model, method, backend, x0v, u)
    if compiled is not None:
        reason = f"{reason}; {why}" if reason else why

    counters = {"nfev": 0, "njev": 0, "nlu": 0, "n_steps": t.size - 1, "message": ""}
    start = _time.perf_counter()
    if compiled is not None and hasattr(compiled, "pick"):
        x, stats = _solve_compiled_batch(model, compiled, t, inputs, u, x0v, hold, method, rtol, atol, first_step,
                                         max_step)
        counters.update(stats)
    elif compiled is not None:
        from . import _compiled_ode

        try:
            x, stats = _compiled_ode.solve(compiled.rhs, compiled.key, compiled.args, t, x0v,
                                           _compiled_ode.input_table(model, inputs, t, u, hold), method, rtol, atol,
                                           first_step, max_step)
        except SimulationError as exc:
            crossing = _domain_crossing(model, t, inputs, u, hold, method, rtol, atol,
                                        getattr(exc, "partial_states", None), exc.time)
            raise crossing or _stiffness_hint(exc, model, method, t, x0v, u) from None
        crossing = _domain_crossing(model, t, inputs, u, hold, method, rtol, atol, x)
        if crossing is not None:
            raise crossing
        counters.update(stats)
    elif method == "exact":
        x, n_expm = _simulate_exact(model, t, u, x0v, hold)
        counters["message"] = f"exact {hold} discretization ({n_expm} matrix exponential{'s' if n_expm > 1 else ''})"
    elif method == "rk4":
        x, nfev = _simulate_rk4(model, t, u, x0v, hold, int(substeps), check_stability, inputs)
        counters.update(nfev=nfev, n_steps=(t.size - 1) * int(substeps), message="fixed-step RK4")
    else:
        x, stats = _simulate_ivp(model, t, u, x0v, hold, method, rtol, atol, max_step, first_step,
                                 watch_stiffness=check_stability, inputs=inputs)
        counters.update(stats, n_steps=stats["nfev"])
    wall = _time.perf_counter() - start

    if not np.all(np.isfinite(x)):
        flat = x.reshape(x.shape[0], x.shape[1], -1)
        bad = np.argwhere(~np.isfinite(flat))
        k = int(bad[:, 1].min())
        i = int(bad[bad[:, 1] == k][0, 0])
        raise SimulationError(
            f"state {model.state_names[i]!r} became non-finite at t = {t[k]:.6g} s ({method})",
            time=float(t[k]), signal=model.state_names[i],
        )
    if compiled is not None:
        from . import _compiled_ode
    if compiled is not None and hasattr(compiled, "pick"):
        uu = np.moveaxis(u, 2, 0) if u.ndim == 3 else u
        y = np.moveaxis(_compiled_ode.batch_outputs(compiled, model.n_outputs, t, np.moveaxis(x, 2, 0), uu), 0, 2)
    elif compiled is not None and compiled.output is not None:
        y = _compiled_ode.outputs(compiled, model.n_outputs, t, x, u)
    else:
        y = _outputs(model, t, x, u)
    if u.ndim < x.ndim:
        u = np.broadcast_to(u[..., None], u.shape + x.shape[2:])
    return SimulationResult(
        time=t,
        states=x,
        inputs=u,
        outputs=y,
        state_signals=model.states,
        input_signals=model.inputs,
        output_signals=model.output_signals,
        method=method,
        method_reason=reason,
        wall_time=wall,
        options={"rtol": rtol, "atol": atol, "hold": hold, "substeps": substeps},
        **counters,
    )


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


def _stiffness_hint(exc: SimulationError, model, method, t, x0, u) -> SimulationError:
    """The compiled backend's failure, with the stiffness estimate at the initial point when that
    explains it (the compiled loop is not judged before it runs: its Jacobian would cost more than
    a short run; its step limit bounds a stiff run to seconds)."""
    if "too many steps" not in str(exc) and "underflow" not in str(exc):
        return exc
    try:
        lam = _state_jacobian_eigenvalues(model, t[0], x0, u[:, 0])
        steps, message = _stiffness_estimate(method, lam, float(t[0]), float(t[-1]), f"at t = {t[0]:g} s")
    except Exception:  # pragma: no cover - the hint is best effort
        return exc
    if steps > STIFF_STEPS_WARN:
        return SimulationError(f"{exc} -- {message}", time=exc.time, signal=exc.signal)
    return exc


def _compiled_backend(model, method, backend, x0, u):
    """(compiled rhs, key, args) and the reason when the compiled backend runs, else (None, "")."""
    from . import _compiled_ode

    backends = ("auto", "numpy", "compiled")
    if backend not in backends:
        raise ParameterError(f"backend must be one of {backends}, got {backend!r}", key="backend", value=backend)
    if backend == "numpy":
        return None, ""
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
        except ParameterError:
            if explicit:
                raise
            return None, ""
        if compiled is None:
            problem = f"{type(model).__name__} has no compiled rhs"
    if problem is not None:
        if explicit:
            raise ParameterError(f"backend='compiled' cannot run: {problem}", key="backend", value=backend)
        return None, ""
    if hasattr(compiled, "pick"):
        return compiled, (f"compiled backend ({method} on {type(model).__name__}'s compiled rhs, numba; "
                          f"{compiled.n_variants} variants, each with its own step-size control)")
    return compiled, f"compiled backend ({method} on {type(model).__name__}'s compiled rhs, numba)"


def _solve_compiled_batch(model, compiled, t, inputs, u, x0, hold, method, rtol, atol, first_step, max_step):
    """States (n, n_t, n_variants) and counters of a batch on the compiled backend
    (:func:`vehdyn._compiled_ode.solve_batch`); the first failed variant raises SimulationError."""
    from . import _compiled_ode

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


def _outputs(model, t, x, u):
    """Outputs for every sample: one batched call when the model allows it."""
    from .linear import LinearModel

    if isinstance(model, LinearModel):
        if x.ndim == 2:
            return model.C @ x + model.D @ u
        uu = u if u.ndim == x.ndim else np.broadcast_to(u[..., None], u.shape + x.shape[2:])
        return np.einsum("pn,nt...->pt...", model.C, x) + np.einsum("pm,mt...->pt...", model.D, uu)
    n_t = t.size
    extra = x.shape[2:]
    # fold time (and batch) into the batch axis: one call to output()
    X = x.reshape(x.shape[0], -1)
    uu = u if u.ndim == x.ndim else np.broadcast_to(u[..., None], u.shape + extra)
    U = uu.reshape(uu.shape[0], X.shape[1])
    T = np.broadcast_to(t.reshape((n_t,) + (1,) * len(extra)), (n_t,) + extra).reshape(-1)
    try:
        Y = np.asarray(model.output(T, X, U), dtype=float)
        if Y.shape != (model.n_outputs, X.shape[1]):
            raise ValueError
    except Exception:
        # one call per time sample, keeping the batch axis (models whose parameters are arrays along
        # the batch axis cannot take time folded into it)
        Y = np.stack([np.asarray(model.output(t[k], x[:, k], uu[:, k]), dtype=float) for k in range(n_t)], axis=1)
    return Y.reshape((model.n_outputs, n_t) + extra)


# --------------------------------------------------------------------------- many runs at once
_BATCH_OPTIONS = {"x0", "method", "rtol", "atol", "hold", "backend"}


def _compiled_member(args, kwargs):
    """A call of :func:`simulate` prepared for a compiled batch, or None when it must run alone:
    (group key, model, t, inputs, u, x0, options). Any doubt (a bad argument, an option a batch
    does not take) leaves the call to :func:`simulate`, which raises the proper error."""
    from . import _compiled_ode

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


def simulate_many(calls, *, threads=None) -> list:
    """Run many :func:`simulate` calls; those that can run as compiled batches do.

    Calls of models with a compiled batch (:meth:`SingleTrack.compiled_batch_of
    <vehdyn.handling.SingleTrack.compiled_batch_of>`), an explicit ``"RK45"``, ``"DOP853"`` or ``"BDF"``, the
    same time grid, options and input layout (constants and sampled inputs with the same
    breakpoints, the same piecewise signals) are grouped; each group is one compiled batch
    (:func:`vehdyn._compiled_ode.solve_batch`) in which every variant keeps its own step-size
    control, on ``threads`` threads. A variant's result is bitwise the one its own ``simulate``
    call gives. Other calls run one by one through :func:`simulate`.

    Parameters
    ----------
    calls : sequence of (args, kwargs)
        The positional ``(model, time, inputs)`` and keyword arguments of each ``simulate`` call.
    threads : int, optional
        Threads of the compiled batches (default: every core).

    Returns
    -------
    list
        Per call, its :class:`~vehdyn.results.SimulationResult` or the exception it raised
        (a :class:`~vehdyn.ParameterError` or :class:`~vehdyn.SimulationError`: one bad call
        never stops the others).
    """
    from . import _compiled_ode

    out: list = [None] * len(calls)
    groups: dict = {}
    for i, (args, kwargs) in enumerate(calls):
        member = _compiled_member(args, kwargs)
        if member is None:
            try:
                out[i] = simulate(*args, **kwargs)
            except (ParameterError, SimulationError) as exc:
                out[i] = exc
        else:
            groups.setdefault(member[0], []).append((i, *member[1:]))
    for members in groups.values():
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
        for j, (i, model, *_rest) in enumerate(members):
            if report[j, 0] != 0:
                out[i] = SimulationError(_compiled_ode.status_message(method, report[j]), time=float(report[j, 1]))
                continue
            violation = _domain_violation(model, t, states[j])
            if violation is not None:
                out[i] = violation
                continue
            status, _, nfev, accepted, rejected = (int(v) for v in report[j])
            out[i] = SimulationResult(
                time=t, states=states[j], inputs=U[..., j], outputs=outputs[j], state_signals=model.states,
                input_signals=model.inputs, output_signals=model.output_signals, method=method,
                method_reason=reason, wall_time=wall, nfev=nfev, n_steps=accepted,
                message=f"compiled {method}: {accepted} steps ({rejected} rejected), {nfev} rhs calls",
                options={"rtol": options["rtol"], "atol": options["atol"], "hold": options["hold"], "substeps": 1})
    return out
