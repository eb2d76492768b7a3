"""Leave-one-condition-out cross-validation of a Magic Formula fit.

Measured tire data come at a handful of loads, cambers and pressures, and a fitted tire is used
between them. Its error there is estimated by leaving each measured condition out in turn - each
load level, each camber level, each pressure level - refitting on the rest and comparing the refit
with the left-out measurements; the same points' error of the full fit (the training error) stands
beside it. A held-out error much larger than the training error means that the data hold the
coefficients only at the measured conditions.

Each refit starts from the full fit's coefficients (it converges in a few iterations), runs the
last (cumulative) step of every stage the fit ran, with the same validity penalties and the same
ridge toward the same start values; coefficients the reduced data cannot determine go back to
their start values, so that nothing learned from the left-out condition survives in the refit.
Data of more than :data:`MAX_POINTS` points are thinned for the refits (every k-th row); the
errors are computed on every left-out point.
"""

from __future__ import annotations

import dataclasses
import math
import warnings

import numpy as np

from vehdyn.errors import ParameterError, VehdynWarning

__all__ = ["cross_validate", "condition_levels", "exceeded", "level_text", "MAX_POINTS", "MAX_NFEV", "RATIO_LIMIT",
           "ERROR_FLOOR"]

MAX_POINTS = 2500
"""Rows a refit uses at most (the rest are thinned evenly)."""

MAX_NFEV = 30
"""Residual evaluations per refit step at most (a refit starts at the fit's solution)."""

RATIO_LIMIT = 3.0
"""A held-out error above this multiple of the training error is warned about."""

ERROR_FLOOR = 0.01
"""Errors below this fraction of the peak [-] are not warned about (clean data fit to rounding: any
held-out error is many times the training error)."""

CHANNELS = ("fx", "fy", "mz", "mx", "my")

CAMBER_GAP = math.radians(0.25)
"""Cambers further apart than this [rad] are different conditions (loads: 5 % of the mean load,
pressures: 2 % of the mean pressure)."""

_VARIABLES = (("load", "fz"), ("camber", "gamma"), ("pressure", "pressure"))


def clusters(values, gap):
    """Levels of ``values``: the medians of the groups that sorted values separate by more than ``gap``.

    Parameters
    ----------
    values : ndarray
        Values of one variable (loads [N], cambers [rad] or pressures [Pa]).
    gap : float
        Smallest difference between two levels, in the values' unit.

    Returns
    -------
    ndarray
        The levels, ascending.
    """
    ordered = np.sort(values)
    groups = np.split(ordered, np.flatnonzero(np.diff(ordered) > gap) + 1)
    return np.array([float(np.median(g)) for g in groups if g.size])


def condition_levels(full):
    """The measured conditions: ``(variable, level, mask)`` for every level of a variable with two or more.

    Parameters
    ----------
    full : dict of str to ndarray
        The fit's columns (``fz`` [N], ``gamma`` [rad], ``pressure`` [Pa]).

    Returns
    -------
    list of (str, float, ndarray of bool, bool)
        Variable (``"load"``, ``"camber"``, ``"pressure"``), the level [N, rad or Pa], the rows at it,
        and whether it is the smallest or largest level (leaving it out extrapolates).
    """
    out = []
    for variable, column in _VARIABLES:
        values = full[column]
        scale = max(float(np.mean(np.abs(values))), 1.0) if values.size else 1.0
        gap = {"fz": 0.05 * scale, "gamma": CAMBER_GAP, "pressure": 0.02 * scale}[column]
        levels = clusters(values, gap)
        if levels.size < 2:
            continue
        nearest = np.argmin(np.abs(values[:, None] - levels[None, :]), axis=1)
        for i, level in enumerate(levels):
            out.append((variable, float(level), nearest == i, i in (0, levels.size - 1)))
    return out


def _outputs(c, rows):
    from vehdyn.tire._mf_ops import NumpyOps
    from vehdyn.tire.magic_formula import _forces_pass

    with np.errstate(all="ignore"):
        fx, fy, _, mx, my, mz = _forces_pass(NumpyOps, c, rows["fz"], rows["kappa"], rows["alpha"], rows["gamma"],
                                              0.0, rows["vx"], rows["pressure"], 0.0, False, True, False, False,
                                              False)[0]
    return {"fx": fx, "fy": fy, "mx": mx, "my": my, "mz": mz}


def cross_validate(ctx, c, full, row_weights, stages, channel_rows, fit_stage):
    """Leave each measured condition out, refit, and compare with the left-out points.

    Parameters
    ----------
    ctx : object
        The fit's settings (a ``magic_formula_fit._Context``; copied for the refits: warm start,
        no warnings, at most :data:`MAX_NFEV` evaluations per step, its own copy of the reference
        values).
    c : MFCoefficients
        The full fit's coefficients.
    full : dict of str to ndarray
        The fit's data, canonical columns [SI].
    row_weights : ndarray or None
        The fit's row weights [-].
    stages : sequence of str
        The stages the fit ran (not skipped).
    channel_rows : dict of str to ndarray of bool
        Per output, the rows the fit fitted it on.
    fit_stage : callable
        ``fit_stage(stage, ctx, c, rows, weights, done) -> (StageResult, c)``.

    Returns
    -------
    list of dict
        One record per left-out condition and channel: ``variable``, ``level`` (SI), ``channel``,
        ``points`` (left-out points of the channel), ``held_out`` and ``training`` (r.m.s. error over
        the largest |measured value| at the condition [-]), ``extrapolation`` (the condition is the
        smallest or largest level) and ``note`` (why a refit failed).
    """
    records = []
    for variable, level, mask, edge in condition_levels(full):
        train = {k: v[~mask] for k, v in full.items()}
        weights = None if row_weights is None else row_weights[~mask]
        n = train["fz"].size
        if n > MAX_POINTS:
            keep = np.arange(0, n, math.ceil(n / MAX_POINTS))
            train = {k: v[keep] for k, v in train.items()}
            weights = None if weights is None else weights[keep]
        refit = dataclasses.replace(ctx, warm=True, quiet=True, messages=[], reference=dict(ctx.reference),
                                    max_nfev=min(ctx.max_nfev, MAX_NFEV))
        held_c, note, done = c, "", {}
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", VehdynWarning)
                for stage in stages:
                    done[stage], held_c = fit_stage(stage, refit, held_c, train, weights, done)
        except ParameterError as error:  # too few points left for a stage
            note, held_c = str(error), None
        rows = {k: v[mask] for k, v in full.items()}
        full_out = _outputs(c, rows)
        held_out = None if held_c is None else _outputs(held_c, rows)
        for channel in CHANNELS:
            on = channel_rows.get(channel)
            if on is None:
                continue
            on = on[mask]
            if not on.any():
                continue
            measured = rows[channel][on]
            records.append({"variable": variable, "level": level, "channel": channel, "points": int(on.sum()),
                            "held_out": math.nan if held_out is None else _error(held_out[channel][on], measured),
                            "training": _error(full_out[channel][on], measured), "extrapolation": bool(edge),
                            "note": note})
    return records


def _error(model, measured):
    """R.m.s. of ``model - measured`` over the largest |measured| [-]."""
    return float(np.sqrt(np.mean((model - measured) ** 2))) / max(float(np.max(np.abs(measured))), 1e-12)


def level_text(variable, level):
    """A condition in words.

    Parameters
    ----------
    variable : {"load", "camber", "pressure"}
        The variable.
    level : float
        Its level [N, rad or Pa].

    Returns
    -------
    str
        ``"load 4000 N"``, ``"camber +1.5 deg"``, ``"pressure 2.40 bar"``.
    """
    if variable == "load":
        return f"load {level:.0f} N"
    if variable == "camber":
        return f"camber {math.degrees(level):+.1f} deg"
    return f"pressure {level / 1e5:.2f} bar"


def exceeded(records):
    """The conditions whose held-out error exceeds :data:`RATIO_LIMIT` times the training error.

    Parameters
    ----------
    records : list of dict
        Records of :func:`cross_validate`.

    Returns
    -------
    list of str
        One text per record whose held-out error exceeds both :data:`RATIO_LIMIT` times its
        training error and :data:`ERROR_FLOOR`, largest first (``"Mz at camber +3.0 deg
        (extrapolated) 4.9 % (training 0.05 %)"``).
    """
    bad = [r for r in records if r["held_out"] > RATIO_LIMIT * max(r["training"], ERROR_FLOOR / RATIO_LIMIT)]
    bad.sort(key=lambda r: -r["held_out"])
    return [f"{r['channel'].capitalize()} at {level_text(r['variable'], r['level'])}"
            f"{' (extrapolated)' if r['extrapolation'] else ''} {100 * r['held_out']:.1f} % "
            f"(training {100 * r['training']:.2f} %)" for r in bad]
