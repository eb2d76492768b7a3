"""Compiled variable-order BDF (numba): ``method="BDF"`` of the compiled backend.

The implicit multistep method of ``scipy.integrate.solve_ivp(method="BDF")``, compiled with the
model's rhs so that a step costs its rhs calls and a few small triangular solves: orders 1 to 5,
the numerical differentiation formulas (NDF, the kappa of Shampine & Reichelt 1997, Table 1) in
the quasi-constant step-size form (the history as a differences array, re-interpolated when the
step changes), Newton iterations on ``I - h / alpha_k J`` with the Jacobian and its LU kept until
an iteration fails to converge, and scipy's error estimate, order selection and step-size
factors, so that ``rtol``/``atol`` mean what they mean for ``solve_ivp`` and a run takes the same
steps as scipy's (tested). The Jacobian is a forward difference of the compiled rhs (column j
perturbed by sqrt(eps max(1e-5, y_j^2)), as RADAU5 does: Hairer & Wanner, *Solving Ordinary
Differential Equations II*, 2nd ed., 1996, sec. IV.8), with n + 1 rhs calls counted in ``nfev``.

What it is for: stiff models. The tire-lag modes of a single track at speed
(lambda = -|V_x| / sigma ~ -50 to -60 1/s at 100 km/h) hold an explicit method at its stability
limit whatever the tolerance (RK45: >= 190 steps, ~1,150 rhs calls in 10 s); BDF's steps follow
the accuracy asked for. On non-stiff models the explicit pairs are cheaper per digit.

Input breakpoints end a step exactly, as in :mod:`vehdyn.simulation.compiled`; the history of a
multistep method does not reach across a kink of the inputs, so the method restarts there at
order 1 (the step size carries over). A sampled input with a kink at every sample therefore
restarts at every sample: give BDF smooth inputs in closed form (PiecewiseSignal).

References
----------
L. F. Shampine and M. W. Reichelt, "The MATLAB ODE Suite", SIAM J. Sci. Comput. 18 (1), 1-22,
1997 (NDF, quasi-constant step size). E. Hairer and G. Wanner, *Solving Ordinary Differential
Equations I*, 2nd ed., 1993, sec. III.2 (BDF error estimate). ``scipy.integrate.BDF``
(the behaviour this loop reproduces).
"""

from __future__ import annotations

import functools
import math

import numpy as np

from vehdyn.simulation.compiled import _initial_step_probe, _initial_step_size, _inputs_at, _sample_interval

__all__ = ["MAX_ORDER", "setup"]

MAX_ORDER = 5
NEWTON_MAXITER = 4
MIN_FACTOR = 0.2
MAX_FACTOR = 10.0
EPS = float(np.finfo(float).eps)
# NDF coefficients kappa_k (Shampine & Reichelt 1997, Table 1; kappa_5 = 0: plain BDF5)
KAPPA = np.array([0.0, -0.1850, -1.0 / 9.0, -0.0823, -0.0415, 0.0])
GAMMA = np.concatenate([[0.0], np.cumsum(1.0 / np.arange(1, MAX_ORDER + 1))])
ALPHA = (1.0 - KAPPA) * GAMMA
ERROR_CONST = KAPPA * GAMMA + 1.0 / np.arange(1, MAX_ORDER + 2)


@functools.lru_cache(maxsize=None)
def setup():
    """Register the loop's helpers with numba (once; :func:`vehdyn.simulation.compiled.integrator` calls it)."""
    from numba.extending import register_jitable

    from vehdyn.simulation.compiled import CALLEE_ONLY

    for helper in (_compute_r, _change_differences, _lu_factor, _lu_solve, _start_history, _scaled_rms,
                   _norm_factor):
        register_jitable(**CALLEE_ONLY)(helper)


# ------------------------------------------------------------------------------ small helpers
def _compute_r(order, factor, m):
    """The matrix R(order, factor) of the differences array's change of step size, into ``m``:
    row 0 ones, m[i, j] = prod_{l <= i} (l - 1 - factor j) / l (Shampine & Reichelt 1997, sec. 2.3)."""
    for j in range(order + 1):
        m[0, j] = 1.0
    for i in range(1, order + 1):
        m[i, 0] = 0.0
        for j in range(1, order + 1):
            m[i, j] = (i - 1 - factor * j) / i
    for i in range(1, order + 1):
        for j in range(order + 1):
            m[i, j] *= m[i - 1, j]


def _change_differences(D, order, factor, r, u, ru, tmp):
    """Re-express the differences D[:order + 1] (backward differences at spacing h) at spacing
    ``factor`` h: the same interpolating polynomial, D <- (R U)^T D."""
    _compute_r(order, factor, r)
    _compute_r(order, 1.0, u)
    for i in range(order + 1):
        for j in range(order + 1):
            acc = 0.0
            for k in range(order + 1):
                acc += r[i, k] * u[k, j]
            ru[i, j] = acc
    n = D.shape[1]
    for i in range(order + 1):
        for j in range(n):
            acc = 0.0
            for k in range(order + 1):
                acc += ru[k, i] * D[k, j]
            tmp[i, j] = acc
    for i in range(order + 1):
        for j in range(n):
            D[i, j] = tmp[i, j]


def _lu_factor(a, piv):
    """LU factorization with partial pivoting of the small matrix ``a``, in place (row swaps in
    ``piv``, LAPACK's getrf convention). numba has no factor-and-reuse; the Newton matrix here is
    the model's size (a handful of states), where this loop costs less than a LAPACK call."""
    n = a.shape[0]
    for k in range(n):
        p = k
        big = abs(a[k, k])
        for i in range(k + 1, n):
            if abs(a[i, k]) > big:
                big = abs(a[i, k])
                p = i
        piv[k] = p
        if p != k:
            for j in range(n):
                a[k, j], a[p, j] = a[p, j], a[k, j]
        pivot = a[k, k]
        for i in range(k + 1, n):
            a[i, k] /= pivot
            factor = a[i, k]
            for j in range(k + 1, n):
                a[i, j] -= factor * a[k, j]


def _lu_solve(a, piv, b):
    """Solve with the factors of :func:`_lu_factor`, ``b`` in place."""
    n = a.shape[0]
    for k in range(n):
        p = piv[k]
        if p != k:
            b[k], b[p] = b[p], b[k]
    for i in range(n):
        acc = b[i]
        for j in range(i):
            acc -= a[i, j] * b[j]
        b[i] = acc
    for i in range(n - 1, -1, -1):
        acc = b[i]
        for j in range(i + 1, n):
            acc -= a[i, j] * b[j]
        b[i] = acc / a[i, i]


def _start_history(D, y, f, h):
    """The differences of a start at order 1 (at t0 and after an input breakpoint): D[0] = y,
    D[1] = h f, the rest zero."""
    D[:, :] = 0.0
    for j in range(y.shape[0]):
        D[0, j] = y[j]
        D[1, j] = f[j] * h


def _scaled_rms(v, weight, scale):
    """sqrt(mean((weight v / scale)^2)): scipy's error norm of ``weight * v``."""
    total = 0.0
    for j in range(v.shape[0]):
        e = weight * v[j] / scale[j]
        total += e * e
    return math.sqrt(total / v.shape[0])


def _norm_factor(norm, exponent):
    """norm ** (-exponent), inf for a zero norm (numpy's 0 ** -x)."""
    return math.inf if norm == 0.0 else norm ** (-exponent)


# ------------------------------------------------------------------------------ the loop
def _integrate_bdf(t_eval, y0, args, kinds, values, pieces, rows, breakpoints, method, rtol, atol, first_step,
                   max_step, max_steps, y_out):
    """BDF from t_eval[0] to t_eval[-1], the states at t_eval into y_out (n, n_t); the contract of
    :func:`vehdyn.simulation.compiled._integrate` (``method`` unused). Returns (status, t, nfev,
    n_accepted, n_rejected)."""
    n = y0.shape[0]
    n_t = t_eval.shape[0]
    t = t_eval[0]
    t_final = t_eval[n_t - 1]
    D = np.zeros((MAX_ORDER + 3, n))
    tmp = np.empty((MAX_ORDER + 3, n))
    r = np.empty((MAX_ORDER + 1, MAX_ORDER + 1))
    rr = np.empty((MAX_ORDER + 1, MAX_ORDER + 1))
    ru = np.empty((MAX_ORDER + 1, MAX_ORDER + 1))
    jac = np.empty((n, n))
    lu = np.empty((n, n))
    piv = np.zeros(n, dtype=np.int64)
    basis = np.empty(MAX_ORDER)
    u = np.zeros(kinds.shape[0])
    y = y0.copy()
    f = np.empty(n)
    y_predict = np.empty(n)
    y_new = np.empty(n)
    d = np.empty(n)
    dy = np.empty(n)
    psi = np.empty(n)
    scale = np.empty(n)
    probe = np.empty(n)
    f_probe = np.empty(n)
    nfev = 0
    accepted = 0
    rejected = 0
    nonfinite = False
    newton_tol = max(10.0 * EPS / rtol, min(0.03, math.sqrt(rtol)))
    n_break = breakpoints.shape[0]
    i_break = 0
    segment_end = breakpoints[0] if n_break > 0 else t_final
    t_ref = t
    k_ref = _sample_interval(t_eval, t_ref)
    _inputs_at(t, t_ref, k_ref, t_eval, kinds, values, pieces, rows, u)
    _rhs(t, y, u, args, f)
    nfev += 1
    for j in range(n):
        y_out[j, 0] = y[j]
        if not math.isfinite(f[j]) or not math.isfinite(y[j]):
            return -2, t, nfev, accepted, rejected
    i_out = 1
    # initial step: scipy's select_initial_step with the error estimator's order 1
    if first_step > 0:
        h_abs = first_step
    else:
        h0 = _initial_step_probe(y, f, rtol, atol, t_final - t, scale, probe)
        _inputs_at(t + h0, t_ref, k_ref, t_eval, kinds, values, pieces, rows, u)
        _rhs(t + h0, probe, u, args, f_probe)
        nfev += 1
        h_abs = _initial_step_size(y, f, f_probe, rtol, atol, h0, 1, t_final - t, max_step, scale)
    def difference_jacobian(tt, base, f_base):
        """Forward differences of the rhs at (tt, base) into ``lu`` (the inputs set for tt);
        True when every entry is finite."""
        for j in range(n):
            probe[j] = base[j]
        finite = True
        for j in range(n):
            delta = math.sqrt(EPS * max(1e-5, base[j] * base[j]))
            probe[j] = base[j] + delta
            delta = probe[j] - base[j]
            _rhs(tt, probe, u, args, f_probe)
            for i in range(n):
                lu[i, j] = (f_probe[i] - f_base[i]) / delta
                finite = finite and math.isfinite(lu[i, j])
            probe[j] = base[j]
        return finite

    # the Jacobian at the start (scipy evaluates it when the solver is built)
    _inputs_at(t, t_ref, k_ref, t_eval, kinds, values, pieces, rows, u)
    difference_jacobian(t, y, f)
    jac[:, :] = lu
    nfev += n
    _start_history(D, y, f, h_abs)
    order = 1
    n_equal_steps = 0
    lu_valid = False
    while t < t_final:
        min_step = 10.0 * abs(np.nextafter(t, np.inf) - t)
        if h_abs > max_step:
            _change_differences(D, order, max_step / h_abs, r, rr, ru, tmp)
            h_abs = max_step
            n_equal_steps = 0
            lu_valid = False
        elif h_abs < min_step:
            _change_differences(D, order, min_step / h_abs, r, rr, ru, tmp)
            h_abs = min_step
            n_equal_steps = 0
            lu_valid = False
        current_jac = False
        step_accepted = False
        n_iter = 0
        error_norm = 0.0
        t_new = t
        while not step_accepted:
            if h_abs < min_step:
                return (-2 if nonfinite else -1), t, nfev, accepted, rejected
            t_new = t + h_abs
            if t_new >= segment_end or segment_end - t_new < min_step:
                t_new = segment_end
                _change_differences(D, order, (t_new - t) / h_abs, r, rr, ru, tmp)
                n_equal_steps = 0
                lu_valid = False
            h_abs = t_new - t
            for j in range(n):
                acc = 0.0
                for k in range(order + 1):
                    acc += D[k, j]
                y_predict[j] = acc
                scale[j] = atol[j] + rtol * abs(acc)
                acc = 0.0
                for k in range(1, order + 1):
                    acc += D[k, j] * GAMMA[k]
                psi[j] = acc / ALPHA[order]
            c = h_abs / ALPHA[order]
            _inputs_at(t_new, t_ref, k_ref, t_eval, kinds, values, pieces, rows, u)
            converged = False
            while not converged:
                if not lu_valid:
                    for i in range(n):
                        for j in range(n):
                            lu[i, j] = (1.0 if i == j else 0.0) - c * jac[i, j]
                    _lu_factor(lu, piv)
                    lu_valid = True
                # Newton iterations on the BDF system (scipy's solve_bdf_system)
                for j in range(n):
                    y_new[j] = y_predict[j]
                    d[j] = 0.0
                dy_norm_old = -1.0
                for k in range(NEWTON_MAXITER):
                    n_iter = k + 1
                    _rhs(t_new, y_new, u, args, f_probe)
                    nfev += 1
                    finite = True
                    for j in range(n):
                        if not math.isfinite(f_probe[j]):
                            finite = False
                    if not finite:
                        nonfinite = True
                        break
                    for j in range(n):
                        dy[j] = c * f_probe[j] - psi[j] - d[j]
                    _lu_solve(lu, piv, dy)
                    dy_norm = _scaled_rms(dy, 1.0, scale)
                    rate = -1.0 if dy_norm_old < 0.0 else dy_norm / dy_norm_old
                    if rate >= 0.0 and (rate >= 1.0 or rate ** (NEWTON_MAXITER - k) / (1.0 - rate) * dy_norm
                                        > newton_tol):
                        break
                    for j in range(n):
                        y_new[j] += dy[j]
                        d[j] += dy[j]
                    if dy_norm == 0.0 or (rate >= 0.0 and rate / (1.0 - rate) * dy_norm < newton_tol):
                        converged = True
                        break
                    dy_norm_old = dy_norm
                if not converged:
                    if current_jac:
                        break
                    # a fresh Jacobian at the prediction, then try again (kept only when finite:
                    # a step into a region where the rhs fails is shortened with the old one)
                    _rhs(t_new, y_predict, u, args, f)
                    finite = difference_jacobian(t_new, y_predict, f)
                    nfev += n + 1
                    lu_valid = False
                    current_jac = True
                    if not finite:
                        nonfinite = True
                        break
                    jac[:, :] = lu
            if converged:
                for j in range(n):
                    scale[j] = atol[j] + rtol * abs(y_new[j])
                error_norm = _scaled_rms(d, ERROR_CONST[order], scale)
                if not math.isfinite(error_norm):
                    nonfinite = True
                    converged = False
            if not converged:
                _change_differences(D, order, 0.5, r, rr, ru, tmp)
                h_abs *= 0.5
                n_equal_steps = 0
                lu_valid = False
                rejected += 1
                continue
            safety = 0.9 * (2 * NEWTON_MAXITER + 1) / (2 * NEWTON_MAXITER + n_iter)
            if error_norm > 1.0:
                factor = max(MIN_FACTOR, safety * error_norm ** (-1.0 / (order + 1)))
                _change_differences(D, order, factor, r, rr, ru, tmp)
                h_abs *= factor
                n_equal_steps = 0
                rejected += 1
            else:
                step_accepted = True
        accepted += 1
        if accepted > max_steps:
            return -3, t, nfev, accepted, rejected
        n_equal_steps += 1
        t = t_new
        for j in range(n):
            y[j] = y_new[j]
            # the differences of the new step: D^{k+1} y_n = d, then down the table
            D[order + 2, j] = d[j] - D[order + 1, j]
            D[order + 1, j] = d[j]
        for k in range(order, -1, -1):
            for j in range(n):
                D[k, j] += D[k + 1, j]
        if n_equal_steps >= order + 1:
            # order selection among k - 1, k, k + 1 by their steps' sizes (Shampine & Reichelt 1997)
            f_minus = _norm_factor(_scaled_rms(D[order], ERROR_CONST[order - 1], scale), 1.0 / order) \
                if order > 1 else 0.0
            f_same = _norm_factor(error_norm, 1.0 / (order + 1))
            f_plus = _norm_factor(_scaled_rms(D[order + 2], ERROR_CONST[order + 1], scale), 1.0 / (order + 2)) \
                if order < MAX_ORDER else 0.0
            best = f_minus
            delta_order = -1
            if f_same > best:
                best = f_same
                delta_order = 0
            if f_plus > best:
                best = f_plus
                delta_order = 1
            order += delta_order
            factor = min(MAX_FACTOR, safety * best)
            h_abs *= factor
            _change_differences(D, order, factor, r, rr, ru, tmp)
            n_equal_steps = 0
            lu_valid = False
        # dense output on (t - h, t]: the interpolating polynomial of the differences (scipy's BdfDenseOutput)
        while i_out < n_t and t_eval[i_out] <= t:
            p = 1.0
            for m in range(order):
                p *= (t_eval[i_out] - (t - h_abs * m)) / (h_abs * (1 + m))
                basis[m] = p
            for j in range(n):
                value = 0.0
                for m in range(order):
                    value += D[m + 1, j] * basis[m]
                y_out[j, i_out] = value + D[0, j]
            i_out += 1
        if t >= segment_end and t < t_final:  # an input breakpoint: new formulas, restart at order 1
            i_break += 1
            segment_end = breakpoints[i_break] if i_break < n_break else t_final
            t_ref = t
            k_ref = _sample_interval(t_eval, t_ref)
            _inputs_at(t, t_ref, k_ref, t_eval, kinds, values, pieces, rows, u)
            _rhs(t, y, u, args, f)
            nfev += 1
            _start_history(D, y, f, h_abs)
            order = 1
            n_equal_steps = 0
            lu_valid = False
    while i_out < n_t:
        for j in range(n):
            y_out[j, i_out] = y[j]
        i_out += 1
    return 0, t, nfev, accepted, rejected
