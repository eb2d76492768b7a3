"""The ``scipy.integrate.solve_ivp`` route of :func:`~vehdyn.simulate`: any of its methods on the
model's numpy ``rhs``, sampled inputs interpolated with the call's ``hold``, closed-form inputs
(:class:`~vehdyn.PiecewiseSignal`) evaluated exactly at every stage with one run per segment
between their breakpoints (no step straddles a kink), the model's analytic Jacobian for the
implicit methods, the model's domain as terminal events, and the stiffness of an explicit method
judged once a run turns out long (after ``_STIFFNESS_WATCH_CALLS`` rhs calls, then at every
doubling).
"""

from __future__ import annotations

import numpy as np

from vehdyn.errors import ParameterError, SimulationError
from vehdyn.model import Model
from vehdyn.simulation._domain import _domain_bounds
from vehdyn.simulation._explicit import _EXPLICIT
from vehdyn.simulation._inputs import _input_function
from vehdyn.simulation._stiffness import _check_stiffness, _state_jacobian_eigenvalues

#: The ``scipy.integrate.solve_ivp`` methods :func:`~vehdyn.simulate` takes by name.
SOLVE_IVP_METHODS = ("RK45", "RK23", "DOP853", "Radau", "BDF", "LSODA")
# rhs calls after which an explicit solve_ivp run looks at its stiffness (then at every doubling):
# small runs never pay for the Jacobian, long ones pay well under 1 % of what they have spent
_STIFFNESS_WATCH_CALLS = 20_000


def _simulate_ivp(model, t, u, x0, hold, method, rtol, atol, max_step, first_step, watch_stiffness=False,
                  inputs=None):
    """States (n, n_t[, n_batch]) and counters (nfev, njev, nlu, message) of a ``solve_ivp`` run over
    the grid ``t``; a batch is one system of n * n_batch states. Failures raise SimulationError, a
    crossing of the model's domain the model's :meth:`~vehdyn.Model.domain_error`."""
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
                stiff = _check_stiffness(method, lam, tt, t[-1], f"at t = {tt:.6g} s (after {calls} rhs calls)",
                                         warn=not warned, stacklevel=2)
                warned = warned or stiff
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
