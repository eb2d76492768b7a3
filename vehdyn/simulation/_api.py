"""Time simulation of any vehdyn model: :func:`simulate` and :func:`simulate_many`.

``simulate`` reads as the steps it takes: check the arguments and sample the inputs
(:mod:`~vehdyn.simulation._inputs`), resolve the method (``"auto"``: :mod:`~vehdyn.simulation._stiffness`),
pick the backend (:mod:`~vehdyn.simulation._backend`), integrate on the route the method names
(:mod:`~vehdyn.simulation._exact`, :mod:`~vehdyn.simulation._explicit`,
:mod:`~vehdyn.simulation._ivp`, the compiled loops), then compute the outputs. The private
modules are laid out as SciPy's ``scipy.integrate._ivp``.
"""

from __future__ import annotations

import time as _time

import numpy as np

from vehdyn.errors import ParameterError, SimulationError
from vehdyn.model import LinearModel, Model, signal_vector
from vehdyn.results import SimulationResult
from vehdyn.simulation import _background
from vehdyn.simulation._backend import (
    _auto_backend,
    _compiled_backend,
    _compiled_member,
    _compiled_outputs,
    _run_compiled_group,
    _solve_compiled,
    _solve_compiled_batch,
)
from vehdyn.simulation._domain import _domain_violation
from vehdyn.simulation._exact import _simulate_exact
from vehdyn.simulation._explicit import _EXPLICIT, _simulate_rk4
from vehdyn.simulation._inputs import _checked_options, _common_batch, _named_inputs, _sample_inputs, _time_grid
from vehdyn.simulation._ivp import SOLVE_IVP_METHODS, _simulate_ivp
from vehdyn.simulation._stiffness import _check_rk4_step, _check_stiffness, _choose_method

__all__ = ["simulate", "simulate_many"]


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
    r"""Simulate ``model`` over the time grid ``time``.

    Parameters
    ----------
    model : Model
        Any vehdyn model (a :class:`~vehdyn.LinearModel` or a user's :class:`~vehdyn.Model`).
    time : array_like
        Strictly increasing output times [s]; the simulation starts at ``time[0]``.
    inputs : None, mapping, array_like or callable
        The inputs [each in its signal's unit, ``model.inputs[i].unit``]: ``None`` (all zero);
        ``{name: value}`` with each value a number, an array of shape (n_times,) or
        (n_times, n_batch) -- time first; a (n_times,) signal next to batched ones is shared by
        every member --, a :class:`~vehdyn.PiecewiseSignal` (closed form, e.g. the manoeuvres of
        :mod:`vehdyn.procedures`) or another callable ``u(t)`` returning one value (or n_batch
        values) per instant (omitted inputs are zero); an array of shape (n_inputs, n_times) or
        (n_inputs, n_times, n_batch); or a callable ``u(t)`` returning the input vector
        (n_inputs,) per instant, or (n_inputs, n_times) when called with the whole grid (a
        PiecewiseSignal alone for a one-input model is that input). Every value must be a finite
        number: other shapes, strings and non-finite samples (callables included) raise
        ParameterError naming the input, the instant and, in a batch, the member.

        A PiecewiseSignal is evaluated exactly at every stage of the adaptive methods and rk4, on
        both backends (method ``"exact"`` samples it). Any other callable is *sampled on the time
        grid* and then held between samples as ``hold`` says, like an array, on both backends (the
        compiled loop cannot call Python): its result is as fine as the grid; give a closed-form
        input as a PiecewiseSignal, or a grid that resolves it.
    x0 : None, mapping or array_like
        Initial state [each in its signal's unit, ``model.states[i].unit``] (zeros by default;
        a mapping sets states by name); shape (n_states,) or (n_states, n_batch) for a batch.
        Batch sizes of ``x0`` and ``inputs`` must agree; a batch of 1 on either side is shared.
    method : str
        ``"auto"``, ``"exact"``, ``"rk4"`` or a ``solve_ivp`` method name (``"RK45"``, ``"RK23"``,
        ``"DOP853"``, ``"Radau"``, ``"BDF"``, ``"LSODA"``); see Notes.
    rtol : float
        Relative tolerance of the adaptive methods [-].
    atol : float
        Absolute tolerance of the adaptive methods [the states' units].
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
        about, or refuse, a stiff problem (Notes). False skips both checks.
    backend : {"auto", "numpy", "compiled"}
        Where the adaptive methods run (Notes); ``"compiled"`` raises ParameterError where it
        cannot run (numba missing, a model without a compiled rhs, a batch without a compiled
        batch, another method), naming why.

    Returns
    -------
    SimulationResult
        Time, states, inputs and outputs (signals x time [x batch]) with their names and units,
        the method and why it was chosen (``method_reason``), the backend that ran and why
        (``backend``, ``backend_reason``), the solver's counters and the wall time of the
        integration.

    Raises
    ------
    ParameterError
        On malformed time, inputs, x0 or options (non-numeric, non-finite, wrong shape, mismatched
        batch sizes), naming the argument; on an explicit method for a problem so stiff that it
        would need more than ``STIFF_STEPS_REFUSE`` steps.
    SimulationError
        When the solver fails (its message is included), a state becomes non-finite (the state
        and the time are named), or a state leaves the model's :attr:`~vehdyn.Model.domain`.

    Warns
    -----
    VehdynWarning
        When an explicit method's stability alone needs more than ``STIFF_STEPS_WARN`` steps.

    See Also
    --------
    simulate_many : many calls at once, compiled batches where they can run.
    vehdyn.simulation.exact_discretization : the matrix-exponential step of ``"exact"``.

    Notes
    -----
    Methods:

    ``"exact"``
        For a :class:`~vehdyn.LinearModel`, dx/dt = A x + B u: the exact discretization for
        inputs held constant (``hold="zoh"``) or linear (``hold="foh"``) between samples,

        .. math::

            x_{k+1} = e^{A\,\Delta t} x_k + B_0 u_k + B_1 u_{k+1},

        from one matrix exponential per distinct step size (Van Loan's block matrix, see
        :func:`~vehdyn.simulation.exact_discretization`); the recurrence is evaluated as a
        parallel prefix scan in log2(N) array passes. A PiecewiseSignal is sampled here: its sines
        between samples are exact only where the grid resolves them.
    ``"RK45"``, ``"RK23"``, ``"DOP853"``, ``"Radau"``, ``"BDF"``, ``"LSODA"``
        ``scipy.integrate.solve_ivp`` with ``rtol``, ``atol`` and ``max_step``; sampled inputs
        are interpolated with ``hold``; a PiecewiseSignal is evaluated exactly at every stage and
        the run restarts on its breakpoints, so that no step straddles a kink (as on the compiled
        backend). The explicit pairs (Dormand & Prince; Bogacki & Shampine) are judged for
        stiffness: a decay rate :math:`\lambda` bounds their step to
        :math:`h \le \text{interval}/|\lambda|` whatever the tolerance
        (:func:`~vehdyn.simulation.stability_interval`); above ``STIFF_STEPS_WARN`` (1e5) such
        steps a :class:`~vehdyn.VehdynWarning` says so, above ``STIFF_STEPS_REFUSE`` (1e7) a
        ParameterError names ``method`` and the implicit methods to use instead. A LinearModel is
        judged before the run (its eigenvalues cost microseconds), any other model once the solver
        has made 20,000 rhs calls and again at every doubling, so that short runs never pay for a
        Jacobian.
    ``"rk4"``
        Classical fixed-step Runge-Kutta on the time grid (``substeps`` per interval), vectorized
        across a trailing batch axis; before it starts, the step is checked against RK4's
        stability region for the eigenvalues of the linearization at the initial point
        (:func:`~vehdyn.simulation.rk4_stability_limit`).
    ``"auto"``
        ``"exact"`` for a linear model; otherwise ``"LSODA"`` when the linearization at the
        initial point is stiff over the run (fastest decay rate times the span above 1e3),
        ``"DOP853"`` when ``rtol < 1e-8``, else ``"RK45"``; ``result.method_reason`` says why.

    Backends: ``"numpy"`` runs the methods above on the model's ``rhs``. ``"compiled"`` runs
    ``"RK45"``, ``"DOP853"`` (scipy's tableaus, error norms and step control, compiled:
    :mod:`vehdyn.simulation.compiled`) and ``"BDF"`` (scipy's variable-order NDF/BDF with a
    difference Jacobian of the compiled rhs) on the model's :meth:`~vehdyn.Model.compiled_rhs`;
    a batch (array parameters, or a batch of initial states or inputs) of a model with a
    compiled batch runs every variant with its own step-size control, bitwise the states of its
    own compiled run, the variants spread over the cores. ``"auto"`` (default) takes the
    compiled backend when the method is one of those three, numba is installed and the model
    has a compiled rhs (and, for a batch, a compiled batch), and says so in
    ``result.method_reason``.

    The first call answers soonest on ``"auto"``: when a single run's compiled code is not built
    yet (numba's on-disk cache; 10-40 s the first time, milliseconds to load afterwards), a
    detached, niced background process builds it -- one per code, under a lock -- and this call
    runs on numpy when numpy's estimated run time is below the build's expected remaining time,
    else it waits for the build. Later calls, in this process or another, run compiled as soon as
    the build has finished; ``result.backend`` and ``result.backend_reason`` say which path ran
    and why. A batch, ``simulate_many`` and an explicit ``"compiled"`` compile first, then run.
    ``VEHDYN_BACKGROUND_COMPILE=0`` turns background builds off (then ``"auto"`` compiles first,
    whatever the call); :func:`vehdyn.warm_up` (``vehdyn compile``) builds the shipped models'
    code ahead of time.

    References
    ----------
    .. [1] E. Hairer, S. P. Nørsett and G. Wanner, *Solving Ordinary Differential Equations I:
       Nonstiff Problems*, 2nd ed., Springer, 1993, sec. II.1-II.6 (Runge-Kutta methods, error
       estimation, step-size control, dense output).
    .. [2] E. Hairer and G. Wanner, *Solving Ordinary Differential Equations II: Stiff and
       Differential-Algebraic Problems*, 2nd ed., Springer, 1996, sec. IV.2 (stability
       functions), IV.8 (Radau IIA), and III.1 (BDF).
    .. [3] L. F. Shampine and M. W. Reichelt, "The MATLAB ODE suite", *SIAM Journal on Scientific
       Computing* 18(1), 1-22, 1997 (the NDF/BDF formulas of ``"BDF"``).
    .. [4] L. Petzold, "Automatic selection of methods for solving stiff and nonstiff systems of
       ordinary differential equations", *SIAM Journal on Scientific and Statistical Computing*
       4(1), 136-148, 1983 (LSODA).
    .. [5] C. F. Van Loan, "Computing integrals involving the matrix exponential", *IEEE
       Transactions on Automatic Control* 23(3), 395-404, 1978.

    Examples
    --------
    A first-order lag, dx/dt = -2 x + 2 u, driven by a unit input: ``"auto"`` takes the exact
    discretization, which meets the closed form 1 - e^(-2t).

    >>> import numpy as np
    >>> import vehdyn
    >>> lag = vehdyn.LinearModel([[-2.0]], [[2.0]], states=["level"], inputs=["flow"])
    >>> t = np.linspace(0.0, 2.0, 201)
    >>> result = vehdyn.simulate(lag, t, inputs={"flow": 1.0})
    >>> result.method, round(float(result["level"][-1]), 6)
    ('exact', 0.981684)

    A nonlinear model: a 1500 kg car coasting against aerodynamic drag, dv/dt = -c v|v| / m,
    whose closed form is v0 / (1 + c v0 t / m).

    >>> class CoastDown(vehdyn.Model):
    ...     states = ("longitudinal_velocity",)
    ...     inputs = ("drive_force",)
    ...
    ...     def rhs(self, t, x, u):
    ...         (v,), (force,) = x, u
    ...         return np.stack([(force - 0.4 * v * np.abs(v)) / 1500.0])
    >>> result = vehdyn.simulate(CoastDown(), np.linspace(0.0, 60.0, 7), x0=[30.0], method="RK45", rtol=1e-9)
    >>> round(float(result["longitudinal_velocity"][-1]), 4), round(30.0 / (1.0 + 0.4 * 30.0 * 60.0 / 1500.0), 4)
    (20.2703, 20.2703)
    >>> result.unit("longitudinal_velocity")
    'm/s'
    """
    if not isinstance(model, Model):
        raise ParameterError(f"model must be a vehdyn Model, got {type(model).__name__}", key="model", value=model)
    t = _time_grid(time)
    rtol, atol, max_step, first_step = _checked_options(t, method, hold, rtol, atol, max_step, first_step, substeps)
    inputs = _named_inputs(model, inputs)
    u = _sample_inputs(model, inputs, t)
    x0v, u = _common_batch(signal_vector(x0, model.states, "x0"), u)
    method, reason = _resolve_method(model, method, t, u, x0v, rtol, check_stability)
    violation = _domain_violation(model, t[0], x0v)
    if violation is not None:
        raise violation
    compiled, why = _compiled_backend(model, method, backend, x0v, u)
    backend_reason, key = why, None
    if compiled is not None:
        run_compiled, key, backend_reason = _auto_backend(model, compiled, method, backend, t, u, x0v)
        if run_compiled:
            reason = f"{reason}; {why}" if reason else why
        else:
            compiled = None

    # a compile here holds the code's build lock (no background build of the same code meanwhile)
    with _background.compiling(key if compiled is not None else None, compiled.key if compiled is not None else ""):
        start = _time.perf_counter()
        x, counters = _integrate(model, compiled, method, t, inputs, u, x0v, hold, rtol, atol, max_step, first_step,
                                 substeps, check_stability)
        wall = _time.perf_counter() - start
        _raise_on_nonfinite(model, t, x, method)
        y = _compiled_outputs(model, compiled, t, x, u) if compiled is not None else None
        if compiled is not None and key is not None:
            _background.mark_ready(key, compiled.key, wall)
    _background.learn(model, t, counters.get("nfev", 0))

    if y is None:
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
        backend="compiled" if compiled is not None else "numpy",
        backend_reason=backend_reason,
        **counters,
    )


def _resolve_method(model, method, t, u, x0, rtol, check_stability) -> tuple[str, str]:
    """The method to run and the reason ``"auto"`` chose it ("" for a named method), checked against
    the model; an explicit method on a LinearModel is judged for stiffness before it starts (its
    eigenvalues cost microseconds; other models are judged by the solver loop once a run turns out
    long, see :func:`vehdyn.simulation._ivp._simulate_ivp`)."""
    reason = ""
    if method == "auto":
        method, reason = _choose_method(model, t, u, x0, rtol)
    valid = ("exact", "rk4") + SOLVE_IVP_METHODS
    if method not in valid:
        raise ParameterError(f"method must be 'auto' or one of {valid}, got {method!r}", key="method", value=method)
    if method == "exact" and not isinstance(model, LinearModel):
        raise ParameterError(
            f"method 'exact' needs a LinearModel; {type(model).__name__} is not linear "
            "(use model.linearize() first, or a solve_ivp method)", key="method", value=method)
    if check_stability and not reason and method in _EXPLICIT[1:] and isinstance(model, LinearModel) and model.n_states:
        _check_stiffness(method, np.linalg.eigvals(model.A), float(t[0]), float(t[-1]), "A", stacklevel=4)
    return method, reason


def _integrate(model, compiled, method, t, inputs, u, x0, hold, rtol, atol, max_step, first_step, substeps,
               check_stability):
    """States (n_states, n_times[, n_batch]) and the solver's counters (nfev, njev, nlu, n_steps,
    message) on the route ``compiled`` and ``method`` name."""
    counters = {"nfev": 0, "njev": 0, "nlu": 0, "n_steps": t.size - 1, "message": ""}
    if compiled is not None and hasattr(compiled, "pick"):
        x, stats = _solve_compiled_batch(model, compiled, t, inputs, u, x0, hold, method, rtol, atol, first_step,
                                         max_step)
    elif compiled is not None:
        x, stats = _solve_compiled(model, compiled, t, inputs, u, x0, hold, method, rtol, atol, first_step, max_step)
    elif method == "exact":
        x, n_expm = _simulate_exact(model, t, u, x0, hold)
        stats = {"message": f"exact {hold} discretization ({n_expm} matrix exponential{'s' if n_expm > 1 else ''})"}
    elif method == "rk4":
        if check_stability:
            _check_rk4_step(model, t, x0, u, int(substeps))
        x, nfev = _simulate_rk4(model, t, u, x0, hold, int(substeps), inputs)
        stats = {"nfev": nfev, "n_steps": (t.size - 1) * int(substeps), "message": "fixed-step RK4"}
    else:
        x, stats = _simulate_ivp(model, t, u, x0, hold, method, rtol, atol, max_step, first_step,
                                 watch_stiffness=check_stability, inputs=inputs)
        stats = dict(stats, n_steps=stats["nfev"])
    counters.update(stats)
    return x, counters


def _raise_on_nonfinite(model, t, x, method) -> None:
    """SimulationError naming the first state (over time) that is not finite, and when."""
    if not np.all(np.isfinite(x)):
        flat = x.reshape(x.shape[0], x.shape[1], -1)
        bad = np.argwhere(~np.isfinite(flat))
        k = int(bad[:, 1].min())
        i = int(bad[bad[:, 1] == k][0, 0])
        raise SimulationError(
            f"state {model.state_names[i]!r} became non-finite at t = {t[k]:.6g} s ({method})",
            time=float(t[k]), signal=model.state_names[i],
        )


def _outputs(model, t, x, u):
    """Outputs for every sample: one batched call when the model allows it."""
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


def simulate_many(calls, *, threads=None) -> list:
    """Run many :func:`simulate` calls; those that can run as compiled batches do.

    Calls of models with a compiled batch (:meth:`SingleTrack.compiled_batch_of
    <vehdyn.handling.SingleTrack.compiled_batch_of>`), an explicit ``"RK45"``, ``"DOP853"`` or ``"BDF"``, the
    same time grid, options and input layout (constants and sampled inputs with the same
    breakpoints, the same piecewise signals) are grouped; each group is one compiled batch
    (:func:`vehdyn.simulation.compiled.solve_batch`) in which every variant keeps its own step-size
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

    See Also
    --------
    simulate : one call.

    Examples
    --------
    Two runs of a first-order lag, dx/dt = -2 x + 2 u, with different input levels (a
    LinearModel has no compiled batch: each call runs through ``simulate``); a bad call comes
    back as its error, the others still run.

    >>> import numpy as np
    >>> import vehdyn
    >>> lag = vehdyn.LinearModel([[-2.0]], [[2.0]], states=["level"], inputs=["flow"])
    >>> t = np.linspace(0.0, 2.0, 201)
    >>> calls = [((lag, t, {"flow": level}), {}) for level in (1.0, 2.0)]
    >>> calls.append(((lag, t, {"flow": np.nan}), {}))
    >>> first, second, bad = vehdyn.simulate_many(calls)
    >>> round(float(first["level"][-1]), 6), round(float(second["level"][-1]), 6)
    (0.981684, 1.963369)
    >>> type(bad).__name__, bad.key
    ('ParameterError', 'inputs.flow')
    """
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
        for (i, *_rest), result in zip(members, _run_compiled_group(members, threads)):
            out[i] = result
    return out
