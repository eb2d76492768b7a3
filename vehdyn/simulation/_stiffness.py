"""Stiffness: the state Jacobian's eigenvalues, the steps an explicit method needs for its stability
alone, the warning and refusal that follow, and the method choice of ``method="auto"``.

The eigenvalues of df/dx at a point (central differences, one batched rhs call where the model
allows it) bound the step of an explicit method: ``stability_interval(method) / max |Re lambda|``
on the negative real axis (Hairer & Wanner, *Solving Ordinary Differential Equations II*, 2nd ed.,
1996, sec. IV.2). A run that would need more than ``STIFF_STEPS_WARN`` such steps is warned
about, more than ``STIFF_STEPS_REFUSE`` refused, naming the implicit methods; ``"auto"`` picks
LSODA when the fastest decay rate times the span exceeds 1e3.
"""

from __future__ import annotations

import warnings

import numpy as np

from vehdyn.errors import ParameterError, SimulationError, VehdynWarning
from vehdyn.model import LinearModel
from vehdyn.simulation._explicit import rk4_stability_limit, stability_interval

_IMPLICIT_HINT = "an implicit method: method='LSODA', 'Radau' or 'BDF' (or 'exact' for a LinearModel, or 'auto')"
#: Steps [-] an explicit method would need for its stability alone above which simulate warns
#: (:class:`~vehdyn.VehdynWarning`).
STIFF_STEPS_WARN = 1e5
#: Steps [-] an explicit method would need for its stability alone above which simulate refuses the
#: method (:class:`~vehdyn.ParameterError`; ``check_stability=False`` runs it anyway).
STIFF_STEPS_REFUSE = 1e7


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
                     stacklevel: int = 3) -> bool:
    """Warn (VehdynWarning) or refuse (ParameterError) an explicit ``method`` whose stability alone
    needs more than STIFF_STEPS_WARN or STIFF_STEPS_REFUSE steps (see _stiffness_estimate).
    Returns whether the step count is above STIFF_STEPS_WARN (warned about, when ``warn``)."""
    steps, message = _stiffness_estimate(method, lam, t_from, t_to, where)
    if steps > STIFF_STEPS_REFUSE:
        raise ParameterError(message + ", or check_stability=False to run it anyway", key="method", value=method)
    if warn and steps > STIFF_STEPS_WARN:
        warnings.warn(message, VehdynWarning, stacklevel=stacklevel)
    return steps > STIFF_STEPS_WARN


def _check_rk4_step(model, t, x0, u, substeps) -> None:
    """Refuse (SimulationError) an rk4 step (the widest interval of ``t`` over ``substeps``) outside
    RK4's stability region for the eigenvalues of the state Jacobian at the initial point."""
    if model.n_states == 0:
        return
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


def _choose_method(model, t, u, x0, rtol) -> tuple[str, str]:
    """The method of ``method="auto"`` and the reason: ``"exact"`` for a LinearModel; ``"LSODA"``
    when the linearization at the initial point is stiff over the run (fastest decay rate times the
    span > 1e3); ``"DOP853"`` for ``rtol < 1e-8``; else ``"RK45"``."""
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
