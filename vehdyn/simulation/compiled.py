"""Compiled adaptive Runge-Kutta integration (numba) of a model's compiled right-hand side.

What :func:`vehdyn.simulate` runs with ``backend="compiled"``: the explicit Runge-Kutta pairs of
``scipy.integrate.solve_ivp`` -- ``"RK45"`` (Dormand-Prince 5(4), its free 4th-order interpolant)
and ``"DOP853"`` (Dormand-Prince 8(5,3), its 7th-order interpolant) -- with scipy's tableaus
(read from ``scipy.integrate.RK45`` / ``DOP853``), error norms, initial-step selection and step-size
control, so ``rtol``/``atol`` mean what they mean for ``solve_ivp`` (Hairer, Norsett & Wanner,
*Solving Ordinary Differential Equations I*, 2nd ed., 1993, sec. II.4-II.6). The whole loop,
the model's rhs and the inputs are compiled, so a step costs the rhs calls and little else.

Inputs, per input signal:

* a number: constant;
* a :class:`~vehdyn.piecewise_signal.PiecewiseSignal` (the standard manoeuvres of
  :mod:`vehdyn.procedures` are): evaluated exactly at every stage;
* samples on the time grid (arrays, and callables without a closed form, sampled as
  :func:`vehdyn.simulate` samples them): held between samples as ``hold`` says (``"zoh"``,
  ``"foh"``), the same meaning as the numpy backend.

An input's breakpoints -- the samples where a held input jumps (zoh) or changes slope (foh), a
piecewise signal's piece edges -- end a step exactly, and the step after starts from the new
input (no step straddles a kink; the error control then sees a smooth problem). A sampled input
that changes at every sample therefore costs at least one step per sample: give smooth inputs in
closed form. The step size carries over a breakpoint.

Failures raise :class:`~vehdyn.SimulationError` with the time and the reason: a step size below
10 ulp of t (underflow), a non-finite state or derivative, too many steps.

``"BDF"``, the stiff method, is :func:`vehdyn.simulation._bdf._integrate_bdf` under the same
contract (inputs, breakpoints, outputs, failures); :func:`integrator` picks the loop by method.

The integrator is generic over the rhs: :func:`integrator` compiles one loop per compiled rhs
(a copy of :func:`_integrate` whose global ``_rhs`` is that function), cached on disk and keyed
on the source of every module that contributes code (editing an equation recompiles).

The model author's contract
---------------------------
A model opts in by overriding :meth:`vehdyn.Model.compiled_rhs` to return a
:class:`CompiledModel`: a function ``rhs(t, x, u, args, dxdt)`` that writes dx/dt of one vehicle
(1-D ``x`` and ``u``) into ``dxdt``, written in the subset of Python numba compiles (loops and
scalar arithmetic over arrays; the model's equations over an ``xp`` namespace where they are
shared with numpy), compiled by :func:`compiled_copy` under a name that carries a
:func:`source_stamp` of every module it draws code from; optionally ``output(t, x, u, args, y)``;
and ``args``, a tuple of the numbers and contiguous arrays the functions read (nested tuples
allowed). For example (a sketch; the compilation takes seconds, once per installation)::

    def _rhs(t, x, u, args, dxdt):
        mass, drag = args
        dxdt[0] = (u[0] - drag * x[0] * abs(x[0])) / mass

    class CoastDown(vehdyn.Model):
        ...
        def compiled_rhs(self):
            key = "coast_down_" + source_stamp(sys.modules[__name__])
            return CompiledModel(compiled_copy(_rhs, f"{key}_rhs"), None, key, (self.mass, self.drag))

Helpers that only compiled code calls (the equations a model registers with ``register_jitable``)
take ``CALLEE_ONLY`` among their options: numba then builds no Python or C entry point for them
(machine code of its own for every function: less to compile).

A model that also runs batches of variants (arrays of parameters, one loop per variant with its
own step-size control) returns a :class:`CompiledBatch` from ``compiled_batch(n_variants)``, with
a compiled ``pick(batch, i)`` that returns variant ``i``'s ``args``. The compiled and the numpy
``rhs`` must agree to rounding: each model's tests compare them.

References
----------
.. [1] E. Hairer, S. P. Nørsett and G. Wanner, *Solving Ordinary Differential Equations I:
   Nonstiff Problems*, 2nd ed., Springer, 1993, sec. II.4 (step-size control and the initial
   step), II.5 (Dormand-Prince pairs), II.6 (dense output).
.. [2] J. R. Dormand and P. J. Prince, "A family of embedded Runge-Kutta formulae", *Journal of
   Computational and Applied Mathematics* 6(1), 19-26, 1980.
"""

from __future__ import annotations

import functools
import hashlib
import math
import sys
import types
from collections import namedtuple
from collections.abc import Mapping
from pathlib import Path

import numpy as np

from vehdyn.errors import ParameterError, SimulationError

__all__ = ["METHODS", "CompiledModel", "CompiledBatch", "integrator", "input_table", "solve", "point_by_point",
           "solve_batch", "outputs", "batch_outputs", "numba_available", "source_stamp", "compiled_copy"]

METHODS = ("RK45", "DOP853", "BDF")
#: the environment variable that turns ``simulate(..., backend="auto")``'s background builds off ("0")
BACKGROUND_ENV = "VEHDYN_BACKGROUND_COMPILE"
_METHOD_CODE = {"RK45": 0, "DOP853": 1, "BDF": 2}

CALLEE_ONLY = {"no_cpython_wrapper": True, "no_cfunc_wrapper": True}
"""numba options of a function that only compiled code calls (``register_jitable`` helpers, the
equations): without the Python and C entry points numba otherwise builds for every compiled
function (the single track's cold compile, CPU: 38 -> 33 s)."""

CompiledModel = namedtuple("CompiledModel", ("rhs", "output", "key", "args"))
CompiledModel.__doc__ = """What :meth:`vehdyn.Model.compiled_rhs` returns (the model author's contract, module docstring).

Parameters
----------
rhs : numba dispatcher
    Compiled ``rhs(t, x, u, args, dxdt)``: t [s], the states x (n,) [each state's unit] and inputs
    u (m,) [each input's unit] of one vehicle; writes dx/dt into ``dxdt`` (n,).
output : numba dispatcher or None
    Compiled ``output(t, x, u, args, y)`` writing the outputs into ``y`` (p,), or None: the
    numpy ``output`` is used (once, on the time grid).
key : str
    A short name of their source (part of the cached code's name, so that a changed source is
    recompiled; include a :func:`source_stamp`).
args : tuple
    The numbers and contiguous arrays ``rhs`` and ``output`` read [the model's units].
"""

CompiledBatch = namedtuple("CompiledBatch", ("rhs", "output", "key", "pick", "batch", "n_variants"))
CompiledBatch.__doc__ = """A batch of variants of one model structure for :func:`solve_batch`.

Parameters
----------
rhs, output : numba dispatcher
    The compiled ``rhs`` and ``output`` of one vehicle, as in :class:`CompiledModel` (``output``
    may not be None here).
key : str
    A name of their source and ``pick``'s (with a :func:`source_stamp`).
pick : numba dispatcher
    Compiled ``pick(batch, i) -> args``: variant ``i``'s ``args`` from ``batch``.
batch : tuple
    The parameters as arrays, one row per variant [the model's units].
n_variants : int
    The number of variants.
"""

_STATUS = {-1: "step size underflow (the step fell below 10 ulp of t: the problem may be stiff or singular)",
           -2: "non-finite state or derivative at every step size down to the underflow limit", -3: "too many steps"}


_NUMBA_AVAILABLE = None


def numba_available() -> bool:
    """Whether numba (the optional dependency of every compiled backend: this integrator, the Magic
    Formula's loops) is installed; looked up once, imported only on first use.

    Returns
    -------
    bool
        True when ``import numba`` would succeed (``pip install "vehdyn[fast]"``).
    """
    global _NUMBA_AVAILABLE
    if _NUMBA_AVAILABLE is None:
        import importlib.util

        _NUMBA_AVAILABLE = importlib.util.find_spec("numba") is not None
    return _NUMBA_AVAILABLE


def source_stamp(*modules) -> str:
    """A short digest of the source files of ``modules`` (for names of cached compiled code).

    Parameters
    ----------
    *modules : module
        Every module whose code a compiled function draws on.

    Returns
    -------
    str
        The first 16 hex digits of the SHA-256 of their files: any edit changes it.
    """
    digest = hashlib.sha256()
    for module in modules:
        digest.update(Path(module.__file__).read_bytes())
    return digest.hexdigest()[:16]


# ------------------------------------------------------------------------------------ tableaus
def _tableaus():
    from scipy.integrate import DOP853, RK45

    f = np.ascontiguousarray
    return {"rk45_a": f(RK45.A), "rk45_b": f(RK45.B), "rk45_c": f(RK45.C), "rk45_e": f(RK45.E),
            "rk45_p": f(RK45.P), "dop_a": f(DOP853.A), "dop_b": f(DOP853.B), "dop_c": f(DOP853.C),
            "dop_e3": f(DOP853.E3), "dop_e5": f(DOP853.E5), "dop_d": f(DOP853.D),
            "dop_a_extra": f(DOP853.A_EXTRA), "dop_c_extra": f(DOP853.C_EXTRA)}


# ------------------------------------------------------------------------------------ inputs
_CONSTANT, _ZOH, _FOH, _PIECEWISE = 0, 1, 2, 3


def input_table(model, inputs, t, u, hold):
    """The inputs as the compiled loop reads them.

    Parameters
    ----------
    model : Model
        The model (its input names).
    inputs : mapping or other
        The ``inputs`` argument of :func:`vehdyn.simulate`: its PiecewiseSignal entries are
        taken in closed form; anything else through its samples ``u``.
    t : ndarray
        Time grid (n_t,) [s].
    u : ndarray
        The inputs sampled on the grid, (n_inputs, n_t) or (n_inputs, n_t, n_variants) [each
        input's unit].
    hold : {"zoh", "foh"}
        How sampled inputs vary between samples.

    Returns
    -------
    tuple
        ``(kinds, values, pieces, piece_rows, breakpoints)``: per input its kind (constant, zoh,
        foh, piecewise), the sampled values (n_inputs, n_t) -- (n_variants, n_inputs, n_t) for
        inputs ``u`` of shape (n_inputs, n_t, n_variants) --, all pieces stacked with each input's
        row range, and the sorted breakpoints inside (t[0], t[-1]) [s] (in a batch, those of
        every variant: a variant's steps also end where another's input has a kink).
    """
    from vehdyn.piecewise_signal import PiecewiseSignal

    names = model.input_names
    given = inputs if isinstance(inputs, Mapping) else {}
    kinds = np.zeros(len(names), dtype=np.int64)
    rows = np.zeros((len(names), 2), dtype=np.int64)
    tables, breaks, count = [], [], 0
    for i, name in enumerate(names):
        signal = given.get(name)
        if isinstance(signal, PiecewiseSignal):
            kinds[i] = _PIECEWISE
            tables.append(signal.pieces)
            rows[i] = count, count + len(signal.pieces)
            count += len(signal.pieces)
            breaks.append(signal.breakpoints)
            continue
        samples = u[i].reshape(t.size, -1)  # (n_t, n_variants)
        if np.all(samples == samples[0]):
            kinds[i] = _CONSTANT
            continue
        kinds[i] = _ZOH if hold == "zoh" else _FOH
        if hold == "zoh":
            changes = np.nonzero(np.any(np.diff(samples, axis=0) != 0, axis=1))[0] + 1
        else:
            slope = np.diff(samples, axis=0) / np.diff(t)[:, None]
            kink = np.abs(np.diff(slope, axis=0)) > 1e-14 * np.max(np.abs(slope), axis=0)
            changes = np.nonzero(np.any(kink, axis=1))[0] + 1
        breaks.append(t[changes])
    pieces = np.concatenate(tables) if tables else np.zeros((0, 7))
    points = np.unique(np.concatenate(breaks)) if breaks else np.zeros(0)
    points = points[(points > t[0]) & (points < t[-1])]
    values = np.moveaxis(u, 2, 0) if u.ndim == 3 else u
    return kinds, np.ascontiguousarray(values, dtype=float), np.ascontiguousarray(pieces), rows, points


def _sample_interval(t_grid, t_ref):
    """The sample interval k with t_grid[k] <= t_ref < t_grid[k + 1] (0 before the grid)."""
    k = np.searchsorted(t_grid, t_ref, side="right") - 1
    return k if k > 0 else 0


def _inputs_at(t, t_ref, k, t_grid, kinds, values, pieces, rows, out):
    """Inputs at ``t`` by the formulas active at ``t_ref`` (the start of the current step's input
    segment, in sample interval ``k``: between breakpoints every input is one smooth formula, also
    at the segment's end)."""
    n_t = t_grid.shape[0]
    for i in range(kinds.shape[0]):
        kind = kinds[i]
        if kind == _CONSTANT:
            out[i] = values[i, 0]
        elif kind == _ZOH:
            out[i] = values[i, k] if k < n_t else values[i, n_t - 1]
        elif kind == _FOH:
            if k >= n_t - 1:
                out[i] = values[i, n_t - 1]
            else:
                w = (t - t_grid[k]) / (t_grid[k + 1] - t_grid[k])
                out[i] = (1.0 - w) * values[i, k] + w * values[i, k + 1]
        else:
            value = 0.0
            for j in range(rows[i, 0], rows[i, 1]):
                if pieces[j, 0] <= t_ref < pieces[j, 1]:
                    value = _piece_value(_XP, pieces[j], t)
            out[i] = value


# ------------------------------------------------------------------------------------ the loop
def _stage_state(y, K, weights, count, h, out):
    """out = y + h * sum_r weights[r] K[r] over the first ``count`` stages."""
    for j in range(y.shape[0]):
        acc = 0.0
        for r in range(count):
            acc += weights[r] * K[r, j]
        out[j] = y[j] + h * acc


def _initial_step_probe(y, f, rtol, atol, span, scale, probe):
    """First half of scipy's ``select_initial_step`` (Hairer, Norsett & Wanner 1993, sec. II.4):
    the trial step h0 (returned), the error weights into ``scale`` and the Euler probe
    ``y + h0 f`` into ``probe``, where the caller evaluates the rhs."""
    n = y.shape[0]
    for j in range(n):
        scale[j] = atol[j] + abs(y[j]) * rtol
    d0 = 0.0
    d1 = 0.0
    for j in range(n):
        d0 += (y[j] / scale[j]) ** 2
        d1 += (f[j] / scale[j]) ** 2
    d0 = math.sqrt(d0 / n)
    d1 = math.sqrt(d1 / n)
    h0 = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
    h0 = min(h0, span)
    for j in range(n):
        probe[j] = y[j] + h0 * f[j]
    return h0


def _initial_step_size(y, f, f_probe, rtol, atol, h0, order, span, max_step, scale):
    """Second half of scipy's ``select_initial_step``: the first step from the rhs ``f_probe`` at the
    probe of :func:`_initial_step_probe` for an error estimator of order ``order``."""
    n = y.shape[0]
    d1 = 0.0
    for j in range(n):
        d1 += (f[j] / scale[j]) ** 2
    d1 = math.sqrt(d1 / n)
    d2 = 0.0
    for j in range(n):
        d2 += ((f_probe[j] - f[j]) / scale[j]) ** 2
    d2 = math.sqrt(d2 / n) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / (order + 1))
    return min(100 * h0, h1, span, max_step)


def _rms(v):
    total = 0.0
    for x in v:
        total += x * x
    return math.sqrt(total / v.shape[0])


def _integrate(t_eval, y0, args, kinds, values, pieces, rows, breakpoints, method, rtol, atol, first_step, max_step,
               max_steps, y_out):
    """Integrate from t_eval[0] to t_eval[-1], writing the states at t_eval into y_out (n, n_t).

    Returns (status, t, nfev, n_accepted, n_rejected): status 0 success, -1 step underflow,
    -2 non-finite, -3 too many steps; t where it stopped. The pair is the one the copy was compiled
    for (``_DOP853``, bound by :func:`integrator`); ``method`` is the code of that pair.
    """
    n = y0.shape[0]
    n_t = t_eval.shape[0]
    t = t_eval[0]
    t_final = t_eval[n_t - 1]
    dop = _DOP853  # a compile-time constant (integrator): the other pair's code is not compiled
    n_stages = 12 if dop else 6
    order = 7 if dop else 4
    exponent = -1.0 / (order + 1)
    if dop:
        a, b, c = DOP_A, DOP_B, DOP_C
    else:
        a, b, c = RK45_A, RK45_B, RK45_C
    K = np.zeros((16, n))
    u = np.zeros(kinds.shape[0])
    y = y0.copy()
    y_new = np.empty(n)
    stage_y = np.empty(n)
    scale = np.empty(n)
    err = np.empty(n)
    err3 = np.empty(n)
    f = np.empty(n)
    f_new = np.empty(n)
    coeffs = np.empty(7)
    nonfinite = False
    nfev = 0
    accepted = 0
    rejected = 0
    # input segments end at the breakpoints and at t_final
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
    # initial step (scipy's select_initial_step, Hairer et al. sec. II.4)
    if first_step > 0:
        h_abs = first_step
    else:
        h0 = _initial_step_probe(y, f, rtol, atol, t_final - t, scale, stage_y)
        _inputs_at(t + h0, t_ref, k_ref, t_eval, kinds, values, pieces, rows, u)
        _rhs(t + h0, stage_y, u, args, f_new)
        nfev += 1
        h_abs = _initial_step_size(y, f, f_new, rtol, atol, h0, order, t_final - t, max_step, scale)
    while t < t_final:
        min_step = 10.0 * abs(np.nextafter(t, np.inf) - t)
        if h_abs > max_step:
            h_abs = max_step
        elif h_abs < min_step:
            h_abs = min_step
        step_rejected = False
        while True:
            if h_abs < min_step:
                return (-2 if nonfinite else -1), t, nfev, accepted, rejected
            t_new = t + h_abs
            if t_new >= segment_end or segment_end - t_new < min_step:
                t_new = segment_end
            h = t_new - t
            # stages
            for j in range(n):
                K[0, j] = f[j]
            for s in range(1, n_stages):
                _stage_state(y, K, a[s], s, h, stage_y)
                _inputs_at(t + c[s] * h, t_ref, k_ref, t_eval, kinds, values, pieces, rows, u)
                _rhs(t + c[s] * h, stage_y, u, args, K[s])
            for j in range(n):
                acc = 0.0
                for r in range(n_stages):
                    acc += b[r] * K[r, j]
                y_new[j] = y[j] + h * acc
            _inputs_at(t_new, t_ref, k_ref, t_eval, kinds, values, pieces, rows, u)
            _rhs(t_new, y_new, u, args, f_new)
            nfev += n_stages
            for j in range(n):
                K[n_stages, j] = f_new[j]
                scale[j] = atol[j] + max(abs(y[j]), abs(y_new[j])) * rtol
            finite = True
            for j in range(n):
                if not (math.isfinite(y_new[j]) and math.isfinite(f_new[j])):
                    finite = False
            if dop:
                for j in range(n):
                    e5 = 0.0
                    e3 = 0.0
                    for r in range(n_stages + 1):
                        e5 += DOP_E5[r] * K[r, j]
                        e3 += DOP_E3[r] * K[r, j]
                    err[j] = e5 / scale[j]
                    err3[j] = e3 / scale[j]
                n5 = np.sum(err * err)
                n3 = np.sum(err3 * err3)
                if n5 == 0.0 and n3 == 0.0:
                    error_norm = 0.0
                else:
                    error_norm = h * n5 / math.sqrt((n5 + 0.01 * n3) * n)
            else:
                for j in range(n):
                    e = 0.0
                    for r in range(n_stages + 1):
                        e += RK45_E[r] * K[r, j]
                    err[j] = h * e / scale[j]
                error_norm = _rms(err)
            nonfinite = not finite
            if not finite:
                error_norm = math.inf  # a step into non-finite values: shrink it (as solve_ivp does)
            if error_norm < 1.0:
                if error_norm == 0.0:
                    factor = 10.0
                else:
                    factor = min(10.0, 0.9 * error_norm ** exponent)
                if step_rejected:
                    factor = min(1.0, factor)
                h_abs = h * factor
                break
            h_abs = h * max(0.2, 0.9 * error_norm ** exponent) if math.isfinite(error_norm) else 0.2 * h
            step_rejected = True
            rejected += 1
        accepted += 1
        if accepted > max_steps:
            return -3, t, nfev, accepted, rejected
        # dense output on (t, t_new]
        if i_out < n_t and t_eval[i_out] <= t_new:
            if dop:
                for s in range(3):
                    sa = n_stages + 1 + s
                    _stage_state(y, K, DOP_A_EXTRA[s], sa, h, stage_y)
                    _inputs_at(t + DOP_C_EXTRA[s] * h, t_ref, k_ref, t_eval, kinds, values, pieces, rows, u)
                    _rhs(t + DOP_C_EXTRA[s] * h, stage_y, u, args, K[sa])
                    nfev += 1
            while i_out < n_t and t_eval[i_out] <= t_new:
                x = (t_eval[i_out] - t) / h
                if dop:
                    for j in range(n):
                        dy = y_new[j] - y[j]
                        coeffs[0] = dy
                        coeffs[1] = h * K[0, j] - dy
                        coeffs[2] = 2.0 * dy - h * (f_new[j] + K[0, j])
                        for q in range(4):
                            acc = 0.0
                            for r in range(16):
                                acc += DOP_D[q, r] * K[r, j]
                            coeffs[3 + q] = h * acc
                        value = 0.0
                        for q in range(7):
                            value += coeffs[6 - q]
                            value *= x if q % 2 == 0 else 1.0 - x
                        y_out[j, i_out] = y[j] + value
                else:
                    for j in range(n):
                        value = 0.0
                        power = 1.0
                        for q in range(4):
                            power *= x
                            acc = 0.0
                            for r in range(7):
                                acc += K[r, j] * RK45_P[r, q]
                            value += acc * power
                        y_out[j, i_out] = y[j] + h * value
                i_out += 1
        t = t_new
        for j in range(n):
            y[j] = y_new[j]
            f[j] = f_new[j]
        if t >= segment_end and t < t_final:  # an input breakpoint: new formulas, new derivative
            i_break += 1
            segment_end = breakpoints[i_break] if i_break < n_break else t_final
            t_ref = t
            k_ref = _sample_interval(t_eval, t_ref)
            _inputs_at(t, t_ref, k_ref, t_eval, kinds, values, pieces, rows, u)
            _rhs(t, y, u, args, f)
            nfev += 1
    while i_out < n_t:  # the last instant (exactly t_final)
        for j in range(n):
            y_out[j, i_out] = y[j]
        i_out += 1
    return 0, t, nfev, accepted, rejected


def _integrate_batch(lo, hi, t_eval, Y0, batch, kinds, values, pieces, rows, breakpoints, method, rtol, atol,
                     first_step, max_step, max_steps, Y_out, report):
    """:func:`_integrate` of the variants ``lo <= i < hi``, each with its own step-size control:
    variant ``i`` starts from ``Y0[i]`` with the inputs ``values[i]`` (``values[0]`` if shared) and the arguments
    ``_pick(batch, i)``, and writes its states into ``Y_out[i]`` and (status, t, nfev, accepted,
    rejected) into ``report[i]``. Compiled without the GIL: threads run blocks side by side."""
    for i in range(lo, hi):
        inputs = values[i if values.shape[0] > 1 else 0]
        status, t, nfev, accepted, rejected = _integrate_one(
            t_eval, Y0[i], _pick(batch, i), kinds, inputs, pieces, rows, breakpoints, method, rtol, atol, first_step,
            max_step, max_steps, Y_out[i])
        report[i, 0] = status
        report[i, 1] = t
        report[i, 2] = nfev
        report[i, 3] = accepted
        report[i, 4] = rejected


def _output_batch(lo, hi, t, X, U, batch, Y):
    """Outputs of the variants ``lo <= i < hi``: X (n_variants, n_t, n), U (n_variants, n_t, m) ->
    Y (n_variants, n_t, p)."""
    for i in range(lo, hi):
        args = _pick(batch, i)
        for k in range(t.shape[0]):
            _output(t[k], X[i, k], U[i, k], args, Y[i, k])


# ------------------------------------------------------------------------------------ compile
_XP = None
_piece_value = None
_DOP853 = False  # the pair of a copy of _integrate: bound by integrator() (one pair compiled per copy)


@functools.lru_cache(maxsize=None)
def _setup():
    """Import numba, compile the helpers and bind the tableaus (once)."""
    import numba
    from numba.extending import register_jitable

    from vehdyn import piecewise_signal

    global _XP, _piece_value
    xp = types.ModuleType("vehdyn.simulation.compiled.XP")
    xp.sin = math.sin
    _XP = xp
    _piece_value = register_jitable(**CALLEE_ONLY)(piecewise_signal.piece_value)
    for name, value in _tableaus().items():
        globals()[name.upper()] = value
    for helper in (_rms, _initial_step_probe, _initial_step_size, _stage_state, _inputs_at, _sample_interval):
        register_jitable(**CALLEE_ONLY)(helper)
    return numba


def _output_loop(t, x, u, args, y):
    """Outputs at every instant: x (n_t, n), u (n_t, m) -> y (n_t, p)."""
    for i in range(t.shape[0]):
        _output(t[i], x[i], u[i], args, y[i])


@functools.lru_cache(maxsize=None)
def compiled_copy(python, name, *, nogil=False, **functions):
    """``python`` compiled by numba under the name ``name``, cached on disk; its globals bind ``functions``.

    numba's on-disk cache is keyed on a function's qualified name and its file's timestamp only,
    not on the functions it calls: callers put a :func:`source_stamp` of every contributing module
    into ``name`` so that editing any of them recompiles. Compiled with ``error_model="numpy"``
    (IEEE inf/nan, no exceptions) and, with ``nogil``, releasing the GIL. One compilation per
    (function, name, bindings) in a process.
    """
    import numba

    namespace = dict(python.__globals__)
    namespace.update(functions)
    function = types.FunctionType(python.__code__, namespace, name, python.__defaults__, python.__closure__)
    function.__qualname__ = name
    return numba.njit(cache=True, nogil=nogil, error_model="numpy", no_cfunc_wrapper=True)(function)


@functools.lru_cache(maxsize=None)
def _stamp():
    from vehdyn import piecewise_signal
    from vehdyn.simulation import _bdf as _compiled_bdf

    return source_stamp(sys.modules[__name__], piecewise_signal, _compiled_bdf)


def point_by_point(model):
    """A model's compiled ``rhs`` and ``output`` as Python functions ``f(t, x, u)``, one state vector at a time.

    For a Python loop around a compiled model (a controller without a compiled form, such as an
    NMPC, in :class:`vehdyn.interconnect.ClosedLoop` with ``plant_backend="compiled"``): each call
    runs the model's compiled code (:meth:`vehdyn.Model.compiled_rhs`, compiled or loaded from the
    cache on the first call) at one state (n,) and input vector (m,); states (n, k) and inputs
    (m, k) are taken column by column. The same equations as the model's numpy ``rhs`` and
    ``output``, equal within a few ulps (compiled math against numpy's).

    Parameters
    ----------
    model : Model
        A model with a compiled rhs and output.

    Returns
    -------
    rhs, output : callable
        ``rhs(t, x, u)`` -> dx/dt (n,) or (n, k) [each state's unit/s]; ``output(t, x, u)`` ->
        y (p,) or (p, k) [each output's unit].

    Raises
    ------
    ParameterError
        When the model has no compiled rhs or output (naming it), or its configuration has none
        (the model's own error).
    """
    compiled = model.compiled_rhs()
    if compiled is None or compiled.output is None:
        raise ParameterError(f"{type(model).__name__} has no compiled rhs and output to call point by point",
                             key="model", value=type(model).__name__)
    n, p, args = model.n_states, model.n_outputs, compiled.args

    def vector(v):
        # contiguous and writable, as the integrator passes them: a read-only or strided array is
        # another type to numba, which would compile the model's code again for it
        return np.require(v, dtype=float, requirements=("C", "W"))

    def columns(function, size):
        def call(t, x, u):
            x, u = np.asarray(x, dtype=float), np.asarray(u, dtype=float)
            if x.ndim == 1:
                out = np.empty(size)
                function(float(t), vector(x), vector(u), args, out)
                return out
            u = np.broadcast_to(u.reshape(u.shape[0], -1), (u.shape[0], x.shape[1]))
            out, column = np.empty((size, x.shape[1])), np.empty(size)
            for j in range(x.shape[1]):
                function(float(t), vector(x[:, j]), vector(u[:, j]), args, column)
                out[:, j] = column
            return out
        return call

    return columns(compiled.rhs, n), columns(compiled.output, p)


def outputs(model: CompiledModel, n_outputs: int, t, x, u):
    """Outputs of a compiled model along a run, by its compiled ``output``.

    Parameters
    ----------
    model : CompiledModel
        With a compiled ``output``.
    n_outputs : int
        The number of outputs p.
    t : ndarray
        Time (n_t,) [s].
    x : ndarray
        States (n, n_t) [each state's unit].
    u : ndarray
        Inputs (m, n_t) [each input's unit].

    Returns
    -------
    ndarray
        Outputs (p, n_t) [each output's unit].
    """
    _setup()
    loop = compiled_copy(_output_loop, f"_output_loop_{model.key}_{_stamp()}", _output=model.output)
    y = np.empty((t.size, n_outputs))
    loop(np.ascontiguousarray(t, dtype=float), np.ascontiguousarray(x.T), np.ascontiguousarray(u.T), model.args, y)
    return y.T


def integrator(rhs, key: str, method: str = "RK45"):
    """The loop of ``method`` compiled for a compiled rhs.

    Parameters
    ----------
    rhs : numba dispatcher
        Compiled ``rhs(t, y, u, args, dydt)`` (:class:`CompiledModel`).
    key : str
        Names the rhs and the source it is compiled from (it becomes part of the cached
        function's name, so that a changed source never loads a stale cache).
    method : {"RK45", "DOP853", "BDF"}
        The method.

    Returns
    -------
    numba dispatcher
        :func:`_integrate` (the explicit pairs) or :func:`vehdyn.simulation._bdf._integrate_bdf`
        bound to ``rhs``, with one signature (that of :func:`_integrate`).
    """
    _setup()
    if method == "BDF":
        from vehdyn.simulation import _bdf as _compiled_bdf

        _compiled_bdf.setup()
        return compiled_copy(_compiled_bdf._integrate_bdf, f"_integrate_bdf_{key}_{_stamp()}", _rhs=rhs)
    # one pair per copy: compiling both pairs into one loop cost 1.1 s more CPU per model (5.6 -> 4.5 s)
    pair = "dop853" if method == "DOP853" else "rk45"
    return compiled_copy(_integrate, f"_integrate_{pair}_{key}_{_stamp()}", _rhs=rhs, _DOP853=method == "DOP853")


def solve(rhs, key, args, t, y0, inputs_table, method="RK45", rtol=1e-6, atol=1e-9, first_step=None,
          max_step=None, max_steps=10_000_000):
    """Integrate a compiled rhs over a time grid.

    Parameters
    ----------
    rhs : numba dispatcher
        Compiled ``rhs(t, y, u, args, dydt)`` (:class:`CompiledModel`).
    key : str
        Its source's name (see :func:`integrator`).
    args : tuple
        The arguments ``rhs`` reads.
    t : ndarray
        Output grid (n_t,) [s]; the run starts at ``t[0]``.
    y0 : array_like
        Initial state (n,) [each state's unit].
    inputs_table : tuple
        :func:`input_table` of the inputs.
    method : {"RK45", "DOP853", "BDF"}
        The method.
    rtol : float
        Relative tolerance [-], at least 100 machine epsilons.
    atol : float or array_like
        Absolute tolerance, a number or one per state [each state's unit].
    first_step, max_step : float, optional
        First and largest step [s] (default: chosen as ``solve_ivp`` chooses it; unbounded).
    max_steps : int
        Accepted steps after which the run fails (a bound on a stiff run's cost).

    Returns
    -------
    y : ndarray
        States (n, n_t) [each state's unit].
    counters : dict
        ``nfev``, ``n_steps`` (accepted steps) and ``message``.

    Raises
    ------
    SimulationError
        On failure (step underflow, a non-finite state, too many steps), with the time; its
        ``partial_states`` are the output instants reached.
    ParameterError
        On bad options, naming the option and its value.
    """
    y0 = np.ascontiguousarray(y0, dtype=float)
    rtol, atol_vec = _check_options(method, rtol, atol, y0.shape, first_step, max_step)
    loop = integrator(rhs, key, method)
    y = np.empty((y0.size, t.size))
    kinds, values, pieces, rows, breakpoints = inputs_table
    status, t_stop, nfev, accepted, rejected = loop(
        np.ascontiguousarray(t, dtype=float), y0, args, kinds, values, pieces, rows, breakpoints,
        _METHOD_CODE[method], rtol, atol_vec, 0.0 if first_step is None else float(first_step),
        np.inf if max_step is None else float(max_step), int(max_steps), y)
    if status != 0:
        error = SimulationError(status_message(method, (status, t_stop)), time=float(t_stop))
        error.partial_states = y[:, t <= t_stop]  # the output instants the loop reached
        raise error
    return y, {"nfev": int(nfev), "n_steps": int(accepted),
               "message": f"compiled {method}: {accepted} steps ({rejected} rejected), {nfev} rhs calls"}


def _check_options(method, rtol, atol, shape, first_step, max_step):
    """rtol (float) and atol (array of ``shape``), or ParameterError naming the bad option."""
    if method not in METHODS:
        raise ParameterError(f"the compiled backend integrates with {METHODS}, got method {method!r}", key="method",
                             value=method)
    rtol = float(rtol)
    if not (math.isfinite(rtol) and rtol >= 100 * np.finfo(float).eps):
        raise ParameterError(f"rtol must be a finite number >= 100 machine epsilons (2.2e-14), got {rtol!r}",
                             key="rtol", value=rtol)
    atol_vec = np.ascontiguousarray(np.broadcast_to(np.asarray(atol, dtype=float), shape))
    if not (np.all(np.isfinite(atol_vec)) and np.all(atol_vec > 0)):
        raise ParameterError(f"atol must be positive and finite, got {atol!r}", key="atol", value=atol)
    for name, value in (("first_step", first_step), ("max_step", max_step)):
        if value is not None and not (value > 0):
            raise ParameterError(f"{name} must be > 0 [s], got {value!r}", key=name, value=value)
    return rtol, atol_vec


def backend_option(backend, key: str = "backend") -> str:
    """How a Python loop evaluates a model's equations -- ``"numpy"``, or ``"compiled"`` (its compiled
    code, :func:`point_by_point`; numba installed) -- or ParameterError naming ``key``."""
    if backend not in ("numpy", "compiled"):
        raise ParameterError(f"{key} must be 'numpy' or 'compiled', got {backend!r}", key=key, value=backend)
    if backend == "compiled" and not numba_available():
        raise ParameterError(f"{key}='compiled' needs numba (pip install \"vehdyn[fast]\"); use {key}='numpy'",
                             key=key, value=backend)
    return backend


def threads_option(threads) -> int:
    """The number of threads of a batch (None: every core), or ParameterError."""
    import os

    if threads is None:
        return os.cpu_count() or 1
    if isinstance(threads, bool) or not isinstance(threads, (int, np.integer)) or threads < 1:
        raise ParameterError(f"threads must be an integer >= 1, got {threads!r}", key="threads", value=threads)
    return int(threads)


def _in_threads(loop, n: int, threads: int, *args) -> None:
    """``loop(lo, hi, *args)`` over blocks of [0, n) on ``threads`` threads (the loop releases the
    GIL); small blocks, taken in turn, balance variants of unequal cost."""
    block = max(1, min(64, -(-n // (8 * threads))))
    edges = [(lo, min(n, lo + block)) for lo in range(0, n, block)]
    if threads == 1 or len(edges) == 1:
        loop(0, n, *args)
        return
    from concurrent.futures import ThreadPoolExecutor

    with ThreadPoolExecutor(max_workers=threads) as pool:
        for _ in pool.map(lambda edge: loop(edge[0], edge[1], *args), edges):
            pass


def solve_batch(model: CompiledBatch, t, y0, inputs_table, method="RK45", rtol=1e-6, atol=1e-9, first_step=None,
                max_step=None, max_steps=10_000_000, threads=None):
    """Integrate every variant of a :class:`CompiledBatch` over the grid ``t``, in parallel.

    Each variant runs :func:`_integrate` -- the loop of :func:`solve`, with its own adaptive
    step-size control -- so that it gives bitwise the states of its own :func:`solve` run; blocks
    of variants run on ``threads`` threads, the compiled loop releasing the GIL.

    Parameters
    ----------
    model : CompiledBatch
        The batch.
    t : ndarray
        Output grid (n_t,) [s], shared.
    y0 : ndarray
        Initial states (n, n_variants) [each state's unit].
    inputs_table : tuple
        :func:`input_table` of inputs of shape (n_inputs, n_t, n_variants).
    method, rtol, atol, first_step, max_step, max_steps : optional
        As :func:`solve` [-, the states' units, s]; ``atol`` a number or (n,).
    threads : int, optional
        Threads to run on (default: every core).

    Returns
    -------
    y : ndarray
        States (n_variants, n, n_t); a failed variant's states are valid up to its stop time.
    report : ndarray
        (n_variants, 5): status (0 success, -1 step underflow, -2 non-finite, -3 too many steps),
        the time reached, rhs calls, accepted and rejected steps (see :func:`status_message`).
    """
    y0 = np.ascontiguousarray(np.asarray(y0, dtype=float).T)
    rtol, atol_vec = _check_options(method, rtol, atol, y0.shape[1:], first_step, max_step)
    threads = threads_option(threads)
    kinds, values, pieces, rows, breakpoints = inputs_table
    if values.ndim == 2:  # inputs shared by every variant
        values = values[None]
    _setup()
    one = integrator(model.rhs, model.key, method)
    loop = compiled_copy(_integrate_batch, f"_integrate_batch_{method.lower()}_{model.key}_{_stamp()}",
                         nogil=True,
                         _integrate_one=one, _pick=model.pick)
    y = np.empty((y0.shape[0], y0.shape[1], t.size))
    report = np.zeros((y0.shape[0], 5))
    _in_threads(loop, y0.shape[0], threads, np.ascontiguousarray(t, dtype=float), y0, model.batch, kinds, values,
                pieces, rows, breakpoints, _METHOD_CODE[method], rtol, atol_vec,
                0.0 if first_step is None else float(first_step), np.inf if max_step is None else float(max_step),
                int(max_steps), y, report)
    return y, report


def status_message(method: str, report_row) -> str:
    """The failure of one variant's run from its row of :func:`solve_batch`'s report ("" on success)."""
    status = int(report_row[0])
    return "" if status == 0 else f"compiled {method} failed at t = {report_row[1]:.6g} s: {_STATUS[status]}"


def batch_outputs(model: CompiledBatch, n_outputs: int, t, x, u, threads=None):
    """Outputs of every variant of a :class:`CompiledBatch` along their runs, in parallel.

    Parameters
    ----------
    model : CompiledBatch
        The batch.
    n_outputs : int
        The number of outputs p.
    t : ndarray
        Time (n_t,) [s].
    x : ndarray
        States (n_variants, n, n_t) [each state's unit].
    u : ndarray
        Inputs (m, n_t), shared, or (n_variants, m, n_t) [each input's unit].
    threads : int, optional
        Threads to run on (default: every core).

    Returns
    -------
    ndarray
        Outputs (n_variants, p, n_t) [each output's unit].
    """
    _setup()
    loop = compiled_copy(_output_batch, f"_output_batch_{model.key}_{_stamp()}", nogil=True,
                         _output=model.output, _pick=model.pick)
    u = np.broadcast_to(u, (x.shape[0],) + u.shape[-2:])  # (the transposed copy below is per variant)
    y = np.empty((x.shape[0], t.size, n_outputs))
    _in_threads(loop, x.shape[0], threads_option(threads), np.ascontiguousarray(t, dtype=float),
                np.ascontiguousarray(np.swapaxes(x, 1, 2)), np.ascontiguousarray(np.swapaxes(u, 1, 2)), model.batch, y)
    return np.swapaxes(y, 1, 2)
