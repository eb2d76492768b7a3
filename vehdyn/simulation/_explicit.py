"""Explicit Runge-Kutta methods: their stability on a linearized problem (:func:`stability_interval`,
:func:`rk4_stability_limit`) and the fixed-step classical RK4 of ``method="rk4"``.

An explicit method integrating a decay at rate lambda is stable only for steps h with
abs(R(h lambda)) <= 1, R its stability polynomial, however smooth the solution: the steps a stiff
problem costs it (Hairer & Wanner, *Solving Ordinary Differential Equations II*, 2nd ed., 1996,
sec. IV.2). :mod:`vehdyn.simulation._stiffness` turns these limits into the warning and the
refusal of an explicit method on a stiff problem.
"""

from __future__ import annotations

import functools

import numpy as np

from vehdyn.errors import ParameterError, SimulationError
from vehdyn.simulation._domain import _domain_violation
from vehdyn.simulation._inputs import _input_function

#: the explicit methods: classical RK4 and scipy's explicit Runge-Kutta pairs
_EXPLICIT = ("rk4", "RK23", "RK45", "DOP853")


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
    r"""Largest step for which classical RK4 is stable on the given eigenvalues.

    Parameters
    ----------
    eigenvalues : array_like
        Eigenvalues :math:`\lambda` of the state Jacobian (complex or real) [1/s].

    Returns
    -------
    float
        The largest step h [s] with :math:`|R(h\lambda)| \le 1` for every eigenvalue, ``inf`` when
        none limits it (eigenvalues with a non-negative real part impose no limit: they grow anyway).

    Notes
    -----
    RK4's stability function is the Taylor polynomial of :math:`e^z` to 4th order,

    .. math::

        R(z) = 1 + z + \frac{z^2}{2} + \frac{z^3}{6} + \frac{z^4}{24},

    and :math:`|R(h\lambda)| = 1` is solved along each ray :math:`h\lambda` by bisection from the
    origin to the first crossing (Hairer & Wanner, sec. IV.2, Fig. 2.1). On the negative real axis
    the limit is 2.785/|lambda| (:func:`stability_interval`).

    References
    ----------
    .. [1] E. Hairer and G. Wanner, *Solving Ordinary Differential Equations II: Stiff and
       Differential-Algebraic Problems*, 2nd ed., Springer, 1996, sec. IV.2.

    Examples
    --------
    >>> from vehdyn.simulation import rk4_stability_limit
    >>> round(rk4_stability_limit([-10.0]), 6)          # a decay at 10 1/s: 2.7853 / 10 s
    0.278529
    >>> round(rk4_stability_limit([-10 + 10j, -1.0]), 6)  # the oscillatory pair limits the step
    0.191227
    """
    return _stability_limit(eigenvalues, "rk4")


def stability_interval(method: str) -> float:
    r"""Length of the stability interval of an explicit method on the negative real axis.

    An explicit method integrating a decay at rate :math:`\lambda` [1/s] is stable only for steps
    :math:`h \le \text{interval} / |\lambda|`, however smooth the solution: this is what makes a
    stiff problem expensive for it.

    Parameters
    ----------
    method : {"rk4", "RK23", "RK45", "DOP853"}
        Classical RK4, or one of scipy's explicit Runge-Kutta pairs (their tableaus are read from
        ``scipy.integrate``).

    Returns
    -------
    float
        The largest :math:`x` with :math:`|R(-\xi)| \le 1` for every :math:`0 \le \xi \le x` [-],
        R the method's stability polynomial.

    Notes
    -----
    For an explicit Runge-Kutta method with tableau :math:`(A, b)` of s stages the stability
    function is the polynomial

    .. math::

        R(z) = 1 + \sum_{k=1}^{s} \left(b^T A^{k-1} \mathbf{1}\right) z^k

    (Hairer & Wanner, sec. IV.2, eq. 2.6 and 2.8). Classical RK4: 2.785; Bogacki-Shampine 3(2)
    (``"RK23"``): 2.513; Dormand-Prince 5(4) (``"RK45"``): 3.307; Dormand-Prince 8(5,3)
    (``"DOP853"``): 6.394.

    References
    ----------
    .. [1] E. Hairer and G. Wanner, *Solving Ordinary Differential Equations II: Stiff and
       Differential-Algebraic Problems*, 2nd ed., Springer, 1996, sec. IV.2.

    Examples
    --------
    >>> from vehdyn.simulation import stability_interval
    >>> round(stability_interval("rk4"), 4), round(stability_interval("RK45"), 4)
    (2.7853, 3.3066)
    """
    if not isinstance(method, str) or method not in _EXPLICIT:
        raise ParameterError(f"method must be one of {_EXPLICIT}, got {method!r}", key="method", value=method)
    return _real_stability_interval(method)


@functools.lru_cache(maxsize=None)
def _real_stability_interval(method: str) -> float:
    return _stability_limit([-1.0], method)


def _simulate_rk4(model, t, u, x0, hold, substeps, inputs=None):
    """States (n, n_t[, n_batch]) and rhs calls of classical RK4 with ``substeps`` fixed steps per
    interval of ``t``, vectorized over the batch; a non-finite state or one outside the model's
    domain raises at the step it appears. (Its stability on the problem is checked before, by
    :func:`vehdyn.simulation._stiffness._check_rk4_step`.)"""
    n = model.n_states
    u_at, _ = _input_function(model, inputs, t, u, hold)  # fixed steps: a kink between samples is stepped over
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
