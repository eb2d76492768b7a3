"""Fit a Magic Formula (MF 5.2 / 6.1 / 6.2) to measured tire data: :func:`fit_magic_formula`.

The fit runs on vehdyn's own Magic Formula equations (:mod:`vehdyn.tire.mf_forces`,
:mod:`vehdyn.tire.mf_moments`, validated against MFeval): a candidate coefficient vector replaces
fields of the model's coefficient record (``MFCoefficients._replace``), so that no formula is
written twice. The inputs are post-processed once per step (limits, dfz, dpi: the ``MFState`` of
:mod:`vehdyn.tire.magic_formula`); a pure-slip residual then costs one call of
:func:`~vehdyn.tire.mf_forces.longitudinal_pure` or :func:`~vehdyn.tire.mf_forces.lateral_pure`.
What the varied coefficients cannot change (the pure-slip forces in the combined and moment
stages, the combined forces in the moment stages) is computed once per step. The Jacobian is a
forward difference, one model call per coefficient.

Stages and the coefficients they own: :mod:`vehdyn.tire.fitting.stages`. Each step is a bounded
:func:`scipy.optimize.least_squares` (trust-region reflective) whose residuals are

* the data's, normalized by the peak of the measured output;
* the Magic Formula's validity conditions (:mod:`vehdyn.tire.fitting.validity`: E <= 1 of every
  curve, peaks, shape factors and stiffnesses of their sign, a positive trail at small slip) on a
  grid that fills the span of the data - between the measured loads, cambers and pressures as well
  as at them - as penalties that vanish while each condition holds with a margin;
* a ridge toward the start (or a reference tire's) values, measured in each coefficient's typical
  size (:func:`~vehdyn.tire.fitting.stages.typical_size`), so that the combinations of
  coefficients the data cannot determine - a camber*|camber| term at a single |camber|, a product
  whose factors trade - stay where they started instead of wandering to values that are harmless
  at the data and wrong between them; the coefficients it holds are named.

The nominal step of the pure-slip and aligning stages starts from a few values of the curvature
(and trail stiffness) factors besides the one read from the data and continues the best; after the
fit, each measured condition is left out in turn and the fit redone without it
(:mod:`vehdyn.tire.fitting.cross_validation`), which estimates the error between the conditions.

References
----------
H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., Butterworth-Heinemann, 2012: sec. 4.3.1 (the
Magic Formula, the meaning of B, C, D, E and E <= 1), sec. 4.3.2 (the characteristic values: peak D,
stiffness BCD, shape C from the asymptote y_a, C = 1 + (1 - (2/pi) asin(y_a/D)), and the
parameter determination), the appendix of chapter 4 (eqs. 4.E1-4.E78) and appendix 3 (the MF 6.1
equations and a parameter set).
I. J. M. Besselink, A. J. C. Schmeitz, H. B. Pacejka, "An improved Magic Formula/Swift tyre model
that can handle inflation pressure changes", *Vehicle System Dynamics* 48 (2010), 337-352.
A. N. Tikhonov, V. Y. Arsenin, *Solutions of Ill-Posed Problems*, Winston, 1977 (the ridge).
"""

from __future__ import annotations

import math
import re
import time
import warnings
from dataclasses import dataclass

import numpy as np

from vehdyn.errors import ParameterError, VehdynWarning
from vehdyn.tire._mf_ops import NumpyOps
from vehdyn.tire.mf_forces import lateral_combined, lateral_pure, longitudinal_combined, longitudinal_pure
from vehdyn.tire.mf_moments import aligning_moment, overturning_moment, rolling_resistance_moment
from vehdyn.tire.fitting.columns import canonical_columns, drop_nonfinite
from vehdyn.tire.fitting.cross_validation import RATIO_LIMIT, clusters, cross_validate, exceeded
from vehdyn.tire.fitting.result import StageResult, TireFit
from vehdyn.tire.fitting.stages import STAGE_NAMES, STAGES, STEP_VARIATION, owned, typical_size
from vehdyn.tire.fitting.validity import GridStates, Penalty, ValidityGrid, check_validity

__all__ = ["fit_magic_formula", "DEFAULT_BOUNDS", "PURE_SLIP_ANGLE", "PURE_SLIP_RATIO"]

PURE_SLIP_ANGLE = math.radians(0.5)
"""|alpha| [rad] below which a point counts as pure longitudinal slip."""

PURE_SLIP_RATIO = 0.005
"""|kappa| [-] below which a point counts as pure lateral slip."""

ZERO_CAMBER = math.radians(0.5)
"""|gamma| [rad] below which a point counts as zero camber."""

VALIDITY_WEIGHT = 100.0
"""Weight of the validity penalties, per square root of the step's data values: a condition broken
by 0.01 costs as much as a 100 % r.m.s. error of the fit."""

REGULARIZATION = 1e-3
"""Default weight of the ridge toward the start (or reference) values: a coefficient change of its
typical size (:func:`~.stages.typical_size`) that moves the fit by less than this r.m.s. fraction
of the peak is held back."""

FTOL = 1e-7
"""Relative change of the cost below which a step stops: on noisy data the cost levels off at the
noise's and a valley of the Magic Formula's coefficients can take hundreds of evaluations to gain a
millionth of it; clean data keep converging (the cost falls by a factor per iteration) to xtol."""

CONDITION_LIMIT = 1e8
"""Condition number of the column-normalized Jacobian above which a warning says that some
coefficients are not identifiable from the data."""

DEFAULT_BOUNDS = {
    "PCX1": (0.5, 3.0), "PDX1": (0.05, 5.0), "PEX1": (-np.inf, 1.0),
    "PCY1": (0.5, 3.0), "PDY1": (0.05, 5.0), "PEY1": (-np.inf, 1.0), "PKY2": (0.05, 50.0), "PKY4": (0.5, 5.0),
    "PEY4": (-100.0, 100.0), "PEY5": (-100.0, 100.0), "PKY5": (-100.0, 100.0),
    "QCZ1": (0.5, 3.0), "RCX1": (0.2, 3.0), "RCY1": (0.2, 3.0), "REX1": (-np.inf, 1.0), "REY1": (-np.inf, 1.0),
    "RVY5": (-3.0, 3.0),
}
"""Default (lower, upper) bounds of the coefficients that have physical limits; PKX1 and PKY1 keep
the sign of the measured slope; the rest are free."""

_OUTPUT_OF = {"X": "fx", "Y": "fy", "Z": "mz"}


def _levels_vary(values, span):
    return values.size > 0 and float(np.ptp(values)) > span


# ------------------------------------------------------------------------------------ template
def _template(version, start, columns, messages, nominal_load=None):
    """The parameter set the fit starts from: ``start`` or MFeval's defaults in a shipped layout,
    with FNOMIN (``nominal_load``, else the load level nearest the mean), LONGVL, NOMPRES and the
    ranges taken from the data."""
    from vehdyn.params import data_path
    from vehdyn.tire.magic_formula import MagicFormula, load_tire
    from vehdyn.tire.tir import MFEVAL_DEFAULTS, TirParameters, read_tir

    fz = columns["fz"]
    if start is not None:
        if isinstance(start, MagicFormula):
            params = start.params
        elif isinstance(start, TirParameters):
            params = MagicFormula(start).params  # a file without a Magic Formula version raises here
        else:
            params = load_tire(start).params  # a path, or the name of a shipped tire
        sections = {s: dict(kv) for s, kv in params.sections.items()}
        overrides = {}
    else:
        layout = read_tir(data_path("tires", {"5.2": "MagicFormula52_Parameters.tir", "6.1":
                                              "MagicFormula61_Parameters.tir", "6.2":
                                              "MagicFormula62_Parameters.tir"}[version]))
        sections = {}
        for section, entries in layout.sections.items():
            sections[section] = {}
            for key, value in entries.items():
                default = MFEVAL_DEFAULTS.get(key.upper())
                keep = key.upper() in ("FITTYP", "PROPERTY_FILE_FORMAT") or section.upper() == "UNITS"
                sections[section][key] = value if keep or default is None else default
        params = layout
        levels = _load_levels(fz)
        nominal = float(levels[np.argmin(np.abs(levels - fz.mean()))])
        overrides = {"FNOMIN": nominal if nominal_load is None else nominal_load}
        if "vx" in columns:
            overrides["LONGVL"] = float(np.median(columns["vx"]))
        if "pressure" in columns:
            overrides["NOMPRES"] = overrides["INFLPRES"] = float(np.median(columns["pressure"]))
    values = TirParameters(sections, tables=params.tables).values
    # ranges that would clamp the data
    ranges = (("FZMIN", "FZMAX", "fz"), ("KPUMIN", "KPUMAX", "kappa"), ("ALPMIN", "ALPMAX", "alpha"),
              ("CAMMIN", "CAMMAX", "gamma"), ("PRESMIN", "PRESMAX", "pressure"))
    for low_key, high_key, column in ranges:
        if column not in columns:
            continue
        low, high = float(columns[column].min()), float(columns[column].max())
        if low < values[low_key] and column != "fz":
            overrides[low_key] = low
        if high > values[high_key]:
            overrides[high_key] = high * 1.05 if column in ("fz", "pressure") else high
    if start is not None and set(overrides) - {"FNOMIN", "LONGVL", "NOMPRES", "INFLPRES"}:
        messages.append("widened the start file's ranges to cover the data: "
                        + ", ".join(f"{k} = {v:.6g}" for k, v in overrides.items()))
    _set_values(sections, values, overrides)
    return TirParameters(sections, tables=params.tables, path=None)


_SECTION_OF = (("FNOMIN", "VERTICAL"), ("LONGVL", "MODEL"), ("NOMPRES", "OPERATING_CONDITIONS"),
               ("INFLPRES", "OPERATING_CONDITIONS"), ("FZ", "VERTICAL_FORCE_RANGE"), ("KPU", "LONG_SLIP_RANGE"),
               ("ALP", "SLIP_ANGLE_RANGE"), ("CAM", "INCLINATION_ANGLE_RANGE"), ("PRES", "INFLATION_PRESSURE_RANGE"),
               ("QS", "OVERTURNING_COEFFICIENTS"), ("QSY", "ROLLING_COEFFICIENTS"),
               ("Q", "ALIGNING_COEFFICIENTS"), ("SSZ", "ALIGNING_COEFFICIENTS"),
               ("PPZ", "ALIGNING_COEFFICIENTS"), ("PPMX", "OVERTURNING_COEFFICIENTS"))


def _set_values(sections, si_values, updates):
    """Write SI ``updates`` into ``sections`` (in the file's units: the ratio of the SI value to
    the value written, where the key exists; new keys go to their usual section)."""
    where = {key.upper(): (section, key) for section, entries in sections.items()
             if section.upper() != "UNITS" for key in entries}
    for key, value in updates.items():
        value = float(value)
        if key in where:
            section, raw_key = where[key]
            raw = sections[section][raw_key]
            factor = 1.0
            if isinstance(raw, (int, float)) and raw != 0 and si_values.get(key, 0) not in (0, None):
                factor = float(si_values[key]) / float(raw)
            sections[section][raw_key] = value / factor
            continue
        section = _default_section(key)
        sections.setdefault(section, {})[key] = value


def _default_section(key):
    if re.fullmatch(r"[PR].X\d+", key):
        return "LONGITUDINAL_COEFFICIENTS"
    if re.fullmatch(r"[PR].Y\d+", key):
        return "LATERAL_COEFFICIENTS"
    best = ""
    for prefix, section in _SECTION_OF:
        if key.startswith(prefix) and len(prefix) > len(best):
            best, found = prefix, section
    return found if best else "MODEL"


def _load_levels(fz, tolerance=0.05):
    """The distinct load levels of ``fz`` (clusters within ``tolerance`` of the mean load)."""
    return clusters(fz, tolerance * max(float(np.mean(np.abs(fz))), 1.0))


# --------------------------------------------------------------------------------- evaluation
class _Problem:
    """One least-squares step: points, outputs, the coefficients varied and the model call.

    The inputs are post-processed once (``MFState``); so are the quantities that the varied
    coefficients cannot change: the pure-slip forces in the combined and moment stages, and the
    combined forces in the moment stages (unless combined-slip coefficients ``R*`` vary).
    """

    def __init__(self, base, stage, rows, outputs, names, weights):
        from vehdyn.tire.magic_formula import _forces_pass

        self.base, self.stage, self.names = base, stage, names
        self.targets = [rows[o] for o in outputs]
        self.outputs = outputs
        self.scales = [max(float(np.max(np.abs(t))), 1e-9) if t.size else 1.0 for t in self.targets]
        self.weights = weights
        fz, kappa, alpha, gamma, vx, pressure = (rows[k] for k in ("fz", "kappa", "alpha", "gamma", "vx", "pressure"))
        with np.errstate(all="ignore"):
            forces, extras = _forces_pass(NumpyOps, base, fz, kappa, alpha, gamma, 0.0, vx, pressure, 0.0, False, True,
                                          False, False, False)
            self.state, self.pure, self.kxk = extras[0], extras[1], extras[4]
            if stage not in ("pure_longitudinal", "pure_lateral"):
                self.fx0 = longitudinal_pure(NumpyOps, base, self.state)[0]
                self.combined = (forces[0], *lateral_combined(NumpyOps, base, self.state, self.pure))
        self.varies_combined = any(n.startswith("R") for n in names)
        self.n_data = sum(t.size for t in self.targets)
        self.penalty, self.ridge = None, None
        self._cache = (None, None)
        self.nfev = 0

    def penalize(self, penalty, ridge):
        """Add the validity conditions (a :class:`~.validity.Penalty` or None) and the ridge (a
        :class:`_Ridge` or None) to the residuals."""
        self.penalty, self.ridge = penalty, ridge
        self._cache = (None, None)

    def coefficients(self, x):
        return self.base._replace(**dict(zip(self.names, x)))

    def model(self, c):
        """Model outputs for coefficient record ``c``: list of arrays, one per output."""
        xp, s = NumpyOps, self.state
        with np.errstate(all="ignore"):
            if self.stage == "pure_longitudinal":
                return [longitudinal_pure(xp, c, s)[0]]
            if self.stage == "pure_lateral":
                return [lateral_pure(xp, c, s, s.gamma_star, False).fy0]
            if self.varies_combined:
                fx = longitudinal_combined(xp, c, s, self.fx0)
                fy, gyk, svyk = lateral_combined(xp, c, s, self.pure)
            else:
                fx, fy, gyk, svyk = self.combined
            values = []
            for out in self.outputs:
                if out == "fx":
                    values.append(fx)
                elif out == "fy":
                    values.append(fy)
                elif out == "mz":
                    values.append(aligning_moment(xp, c, s, self.pure, fy, fx, self.kxk, gyk, svyk).mz)
                elif out == "mx":
                    values.append(overturning_moment(xp, c, s, fy))
                else:
                    values.append(rolling_resistance_moment(xp, c, s, fx))
        return values

    def residuals(self, values):
        r = np.concatenate([(m - t) / scale for m, t, scale in zip(values, self.targets, self.scales)])
        if self.weights is not None:
            r = r * self.weights
        return np.where(np.isfinite(r), r, 1e3)

    def total(self, x, base=None, moved=None):
        """Residuals of the data, then the validity penalties, then the ridge rows. With ``base``
        (the residuals at a point that differs from ``x`` in coefficient ``moved`` alone), only the
        penalties that coefficient moves are evaluated again."""
        c = self.coefficients(x)
        parts = [self.residuals(self.model(c))]
        if self.penalty is not None:
            if base is None:
                parts.append(self.penalty.residuals(c))
            else:
                previous = base[self.n_data:self.n_data + len(self.penalty.names)]
                parts.append(self.penalty.residuals(c, previous, moved))
        if self.ridge is not None:
            parts.append(self.ridge.residuals(x))
        return np.concatenate(parts) if len(parts) > 1 else parts[0]

    def fun(self, x):
        self.nfev += 1
        r = self.total(x)
        self._cache = (x.copy(), r)
        return r

    def jac(self, x, lower, upper):
        """Forward differences, one model call per coefficient on the step's points.

        (Evaluating all coefficients in one call on (k, n) arrays was 1.4x slower at 7,000 points:
        the arrays leave the cache; ``benchmarks/bench_tire_fit.py``.)
        """
        cached_x, f0 = self._cache
        if cached_x is None or not np.array_equal(cached_x, x):
            f0 = self.fun(x)
        h = 1e-7 * np.maximum(np.abs(x), 1.0)
        h = np.where(x + h > upper, -h, h)
        jac = np.empty((f0.size, x.size))
        for j in range(x.size):
            shifted = x.copy()
            shifted[j] += h[j]
            jac[:, j] = (self.total(shifted, f0, self.names[j]) - f0) / h[j]
        return jac


def _solve(problem, x0, lower, upper, max_nfev):
    from scipy.optimize import least_squares

    span = upper - lower
    inside = np.clip(x0, lower + 1e-9 * np.where(np.isfinite(span), span, 1.0),
                     upper - 1e-9 * np.where(np.isfinite(span), span, 1.0))
    result = least_squares(problem.fun, inside, jac=lambda x: problem.jac(x, lower, upper), bounds=(lower, upper),
                           x_scale="jac", method="trf", max_nfev=max_nfev, ftol=FTOL, xtol=1e-10, gtol=1e-10)
    return result


# ------------------------------------------------------------------------------ start values
SHAPE_STARTS = {
    ("pure_longitudinal", "nominal"): ({"PEX1": -1.0}, {"PEX1": 0.5}),
    ("pure_lateral", "nominal"): ({"PEY1": -1.0}, {"PEY1": 0.5}),
    ("aligning", "nominal"): tuple({"QBZ1": b, "QEZ1": e} for b in (5.0, 10.0, 20.0) for e in (0.0, -2.0)),
}
"""Further starts of the shape and curvature factors of the nominal step (besides the one read from
the data): the curvature factor E and the stiffness factor B trade against each other on one load's
sweep, and a start on the wrong side of that valley ends in a local minimum."""

START_EVALUATIONS = 25
"""Residual evaluations given to each start before the best is continued."""


def _best_start(problem, x0, lower, upper, variants):
    """The start, among ``x0`` and ``x0`` with each of ``variants``, that reaches the smallest cost in
    :data:`START_EVALUATIONS` evaluations (its end point)."""
    best, best_cost = x0, math.inf
    for variant in ({},) + tuple(variants):
        x = x0.copy()
        for name, value in variant.items():
            if name in problem.names:
                x[problem.names.index(name)] = value
        result = _solve(problem, np.clip(x, lower, upper), lower, upper, START_EVALUATIONS)
        if result.cost < best_cost:
            best, best_cost = result.x, result.cost
    return best


def _slope_at_zero(x, y):
    """Slope dy/dx at x = 0 from the points nearest zero (least squares line)."""
    ax = np.abs(x)
    distinct = np.unique(np.round(ax, 9))
    limit = distinct[min(3, distinct.size - 1)] if distinct.size > 1 else ax.max()
    near = ax <= max(limit, 1e-9)
    if near.sum() < 2 or np.ptp(x[near]) == 0:
        return float("nan")
    return float(np.polyfit(x[near], y[near], 1)[0])


def _peak_shape(x, y):
    """Peak D (half the peak-to-peak force), stiffness at zero and shape factor C from the asymptote."""
    peak = 0.5 * (float(y.max()) - float(y.min()))
    slope = _slope_at_zero(x, y)
    ax = np.abs(x)
    outer = ax >= 0.95 * ax.max()
    asymptote = float(np.mean(np.abs(y[outer]))) if outer.any() else peak
    ratio = min(max(asymptote / peak, 0.0), 0.999) if peak > 0 else 0.5
    shape = 1.0 + (1.0 - (2.0 / math.pi) * math.asin(ratio))  # Pacejka 2012, sec. 4.3.2
    return peak, slope, shape


def _physical_start(stage, rows, c):
    """Initial values of the nominal-step coefficients read from the data (Pacejka 2012, 4.3.2)."""
    fz = float(np.mean(rows["fz"]))
    fz0 = c.Fz0_prime
    if stage == "pure_longitudinal":
        peak, slope, shape = _peak_shape(rows["kappa"], rows["fx"])
        start = {"PDX1": peak / fz, "PCX1": min(max(shape, 1.05), 2.5), "PEX1": 0.0, "PEX4": 0.0, "PHX1": 0.0,
                 "PVX1": 0.0}
        if np.isfinite(slope) and slope != 0:
            start["PKX1"] = slope / fz
        return start
    if stage == "pure_lateral":
        peak, slope, shape = _peak_shape(rows["alpha"], rows["fy"])
        start = {"PDY1": peak / fz, "PCY1": min(max(shape, 1.05), 2.5), "PEY1": 0.0, "PEY3": 0.0, "PHY1": 0.0,
                 "PVY1": 0.0, "PKY2": 2.0, "PKY4": 2.0}
        if np.isfinite(slope) and slope != 0:
            start["PKY1"] = slope / (fz0 * math.sin(2.0 * math.atan(fz / (fz0 * 2.0))))
        return start
    if stage == "aligning":
        fy_slope = _slope_at_zero(rows["alpha"], rows["fy"]) if "fy" in rows else float("nan")
        mz_slope = _slope_at_zero(rows["alpha"], rows["mz"])
        if np.isfinite(fy_slope) and fy_slope != 0 and np.isfinite(mz_slope):
            trail = -mz_slope / fy_slope
            return {"QDZ1": trail * fz0 / (c.UNLOADED_RADIUS * fz)}
    return {}


def _bounds(names, x0, user_bounds):
    lower = np.full(len(names), -np.inf)
    upper = np.full(len(names), np.inf)
    for j, name in enumerate(names):
        if name in user_bounds:
            lower[j], upper[j] = user_bounds[name]
        elif name in DEFAULT_BOUNDS:
            lower[j], upper[j] = DEFAULT_BOUNDS[name]
        elif name in ("PKX1", "PKY1") and x0[j] != 0:
            lower[j], upper[j] = (0.0, np.inf) if x0[j] > 0 else (-np.inf, 0.0)
    return lower, upper


# ------------------------------------------------------------------------------------ the fit
def fit_magic_formula(data, *, version="6.1", start=None, stages=STAGE_NAMES, fixed=(), bounds=None, weights=None,
                      max_nfev=200, regularization=REGULARIZATION, reference=None, validity=True,
                      cross_validation=True, units=None):
    """Fit a Magic Formula to measured forces and moments, stage by stage, valid between the data.

    Parameters
    ----------
    data : pandas.DataFrame or mapping of str to array_like
        Canonical columns of :func:`vehdyn.tire.read_tire_data` (ISO-W, SI, radians): ``fz``
        [N] and the slips (``kappa`` [-], ``alpha``, ``gamma`` [rad]; missing ones are 0),
        ``vx`` [m/s] and ``pressure`` [Pa] (missing: the file's LONGVL and NOMPRES), and the
        measured ``fx``, ``fy`` [N], ``mz``, ``mx``, ``my`` [N*m]. Rows with NaN are dropped (the
        count is in :attr:`TireFit.messages`). Columns beyond a tire test's range in SI units
        (slip angles beyond +-pi/2 rad, slip ratios beyond +-1.5, ...) are refused unless their
        unit is stated (``units``, or a file's header read by :func:`~vehdyn.tire.read_tire_data`).
    version : {"6.1", "6.2", "5.2"}
        Magic Formula version of the result (ignored when ``start`` is given: its version).
    start : MagicFormula, TirParameters, str or pathlib.Path, optional
        Start coefficients and every parameter the fit does not touch (dimensions, stiffness): a
        model, parameters, a ``.tir`` path or the name of a shipped tire (:func:`~vehdyn.tire.load_tire`).
        None: MFeval's defaults, with the pure-slip peak, slope at zero and shape factor and
        the trail at zero slip read from the data, and FNOMIN, LONGVL, NOMPRES set from it.
    stages : sequence of str
        Stages to run, in order (see :data:`vehdyn.tire.fitting.STAGES`): ``"pure_longitudinal"``,
        ``"pure_lateral"``, ``"aligning"``, ``"combined"``, ``"overturning"``,
        ``"rolling_resistance"``. A stage whose columns the data lack is skipped with a message.
    fixed : sequence of str
        Coefficients held at their start values.
    bounds : dict of str to (float, float), optional
        Bounds of coefficients [the coefficient's unit], overriding :data:`DEFAULT_BOUNDS`.
    weights : array_like, optional
        One non-negative weight per row of ``data`` [-] (multiplies the residuals).
    max_nfev : int
        Residual evaluations per step at most.
    regularization : float
        Weight of the ridge toward the start (or ``reference``) values [-]: a combination of
        coefficients that moves the fit by less than this fraction of the peak (r.m.s.) per
        typical size of its coefficients is held. 0 turns the ridge off. Default
        :data:`REGULARIZATION`.
    reference : MagicFormula, TirParameters, str or pathlib.Path, optional
        A tire whose coefficients the ridge holds instead of the start values (e.g. a fit of a
        similar tire whose camber dependence was measured). Without ``start``, the fit then uses
        the reference's FNOMIN, so that its load coefficients mean the same.
    validity : bool
        Enforce the validity conditions (:mod:`~vehdyn.tire.fitting.validity`) on the grid that
        spans the data. They are checked and reported on the result either way.
    cross_validation : bool
        Leave each measured load, camber and pressure level out in turn, refit, and report the
        errors at the left-out points (:attr:`TireFit.cross_validation`). About as long again as
        the fit on a few thousand points; refits of larger data use a thinned copy.
    units : dict of str to str, optional
        Units of columns that are not SI, by canonical name (``{"alpha": "deg", "kappa": "%"}``;
        the names of :data:`vehdyn.tire.tire_data.UNIT_FACTORS`); such a column is converted and
        not judged.

    Returns
    -------
    TireFit
        The fitted :class:`~vehdyn.tire.MagicFormula`; per stage its coefficients, errors,
        coefficients at a bound or held, and the Jacobian's condition; the validity conditions on
        the grid (:attr:`TireFit.validity`); the held-out errors (:attr:`TireFit.cross_validation`).

    Raises
    ------
    ParameterError
        Unknown version, stage or coefficient name, bad bounds, weights, regularization or units,
        data without ``fz``, a column in another unit than SI (named, with the unit it looks like),
        or a stage with fewer values than coefficients.

    Warns
    -----
    VehdynWarning
        When coefficients are not identifiable from the data (no load, camber or pressure sweep)
        or are held by the ridge (named); when a validity condition fails somewhere on the grid;
        when an error at a left-out condition exceeds 3 times the training error there (and 1 %).

    References
    ----------
    H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., 2012, sec. 4.3.1, 4.3.2 and the appendix of
    chapter 4 (eqs. 4.E1-4.E78, the equations fitted); see the module's references.

    Examples
    --------
    Recover the MF 6.1 example tire's side force from two loads' slip-angle sweeps:

    >>> import warnings
    >>> import numpy as np
    >>> from vehdyn.tire import fit_magic_formula, load_tire
    >>> from vehdyn.tire.fitting import sample_tire
    >>> tire = load_tire("MagicFormula61_Parameters")
    >>> data = sample_tire(tire, loads=[4000.0, 6000.0], slip_angles=np.radians(np.linspace(-12, 12, 13)),
    ...                    slip_ratios=[], cambers=[0.0], combined_angles=[])
    >>> with warnings.catch_warnings():
    ...     warnings.simplefilter("ignore")  # no camber or pressure sweep: those terms are not identifiable
    ...     fit = fit_magic_formula(data, stages=("pure_lateral",))
    >>> bool(fit.stages["pure_lateral"].nrms["fy"] < 1e-3), bool(fit.validity["ok"].all())
    (True, True)
    >>> sorted(set(fit.cross_validation["level_text"]))
    ['load 4000 N', 'load 6000 N']
    """
    from vehdyn.tire.magic_formula import MagicFormula

    if isinstance(regularization, bool) or not isinstance(regularization, (int, float, np.integer, np.floating)) \
            or not (math.isfinite(regularization) and regularization >= 0):
        raise ParameterError(f"regularization must be a finite number >= 0, got {regularization!r}",
                             key="regularization", value=regularization)
    for name, flag in (("validity", validity), ("cross_validation", cross_validation)):
        if not isinstance(flag, (bool, np.bool_)):
            raise ParameterError(f"{name} must be True or False, got {flag!r}", key=name, value=flag)
    if isinstance(max_nfev, bool) or not isinstance(max_nfev, (int, np.integer)) or max_nfev < 1:
        raise ParameterError(f"max_nfev must be an integer >= 1, got {max_nfev!r}", key="max_nfev", value=max_nfev)
    if version not in ("5.2", "6.1", "6.2"):
        raise ParameterError(f"version must be '5.2', '6.1' or '6.2', got {version!r}", key="version", value=version)
    stages = (stages,) if isinstance(stages, str) else tuple(stages)
    for stage in stages:
        if stage not in STAGES:
            raise ParameterError(f"unknown stage {stage!r}; stages are {', '.join(STAGE_NAMES)}", key="stages",
                                 value=stage)
    bounds = dict(bounds or {})
    all_owned = {n for s in STAGE_NAMES for _, names in STAGES[s].steps for n in names}
    for name in list(fixed) + list(bounds):
        if name not in all_owned:
            raise ParameterError(f"{name!r} is not a coefficient any stage fits", key="fixed" if name in fixed
                                 else "bounds", value=name)
    for name, pair in bounds.items():
        try:
            low, high = (float(v) for v in pair)
        except (TypeError, ValueError):
            raise ParameterError(f"bounds[{name!r}] must be (lower, upper), got {pair!r}", key="bounds",
                                 value=pair) from None
        if not low < high:
            raise ParameterError(f"bounds[{name!r}]: lower must be < upper, got {pair!r}", key="bounds", value=pair)
        bounds[name] = (low, high)
    messages = []
    columns = canonical_columns(data, units)
    if weights is not None:
        w = np.asarray(weights, dtype=float).ravel()
        if w.shape != columns["fz"].shape or not np.all(np.isfinite(w)) or np.any(w < 0):
            raise ParameterError(f"weights must be {columns['fz'].size} finite values >= 0", key="weights",
                                 value=w.shape)
        columns["_weight"] = w
    columns = drop_nonfinite(columns, messages)
    if columns["fz"].size == 0:
        raise ParameterError("data has no finite rows", key="data", value=0)
    reference_values, reference_name = _reference_values(reference)
    # a reference tire's load coefficients mean something at its own FNOMIN (dfz = Fz/FNOMIN - 1)
    params = _template(version, start, columns, messages, reference_values.get("FNOMIN"))
    version = params.version
    model = MagicFormula(params)
    c = model._c
    n = columns["fz"].size
    full = {"fz": columns["fz"], "kappa": columns.get("kappa", np.zeros(n)), "alpha": columns.get("alpha", np.zeros(n)),
            "gamma": columns.get("gamma", np.zeros(n)), "vx": columns.get("vx", np.full(n, c.LONGVL)),
            "pressure": columns.get("pressure", np.full(n, c.INFLPRES))}
    for out in ("fx", "fy", "mx", "my", "mz"):
        if out in columns:
            full[out] = columns[out]
    row_weights = columns.get("_weight")
    grid = ValidityGrid.from_data(full, model)
    ctx = _Context(version=version, fixed=set(fixed), bounds=bounds, physical=start is None, max_nfev=max_nfev,
                   regularization=float(regularization), reference=reference_values, reference_name=reference_name,
                   states=GridStates(c, grid) if validity else None, messages=messages)
    results = {}
    for stage in stages:
        began = time.perf_counter()
        result, c = _fit_stage(stage, ctx, c, full, row_weights, results)
        result.seconds = time.perf_counter() - began
        results[stage] = result
    fitted = {name: getattr(c, name) for r in results.values() for name in r.coefficients}
    sections = {s: dict(kv) for s, kv in params.sections.items()}
    _set_values(sections, params.values, fitted)
    from vehdyn.tire.tir import TirParameters

    tire = MagicFormula(TirParameters(sections, tables=params.tables))
    table = check_validity(tire, grid)
    broken = table[~table["ok"]]
    if len(broken):
        text = ("validity conditions violated on the grid spanning the data: "
                + "; ".join(f"{name} at {row.violations} of {row.points} points (worst {row.worst:.3g})"
                            for name, row in broken.iterrows()))
        messages.append(text)
        warnings.warn(text, VehdynWarning, stacklevel=2)
    held_out = None
    if cross_validation:
        began = time.perf_counter()
        ran = [name for name, r in results.items() if not r.skipped]
        channel_rows = {}
        for name in ran:
            for out in results[name].outputs:
                channel_rows[out] = channel_rows.get(out, np.zeros(n, dtype=bool)) | _stage_rows(name, full)
        held_out = cross_validate(ctx, c, full, row_weights, ran, channel_rows, _fit_stage)
        too_large = exceeded(held_out)
        if too_large:
            text = (f"held-out errors above {RATIO_LIMIT:g}x the training error (each condition left out of the "
                    f"fit in turn): " + "; ".join(too_large[:6]) + ("; ..." if len(too_large) > 6 else "")
                    + "; the data do not hold the fit between (or beyond) the measured conditions")
            messages.append(text)
            warnings.warn(text, VehdynWarning, stacklevel=2)
        messages.append(f"cross-validation: {len({(r['variable'], r['level']) for r in held_out})} conditions left "
                        f"out in turn, {time.perf_counter() - began:.1f} s")
    return TireFit(tire=tire, stages=results, messages=messages, data=full, validity=table, grid=grid,
                   held_out=held_out)


def _stage_rows(stage, full):
    """The rows a stage fits (its selection; the combined stage needs non-zero slip angles too)."""
    select = _select(stage, full)
    if stage == "combined" and not np.any(select & (np.abs(full["alpha"]) >= PURE_SLIP_ANGLE)):
        select[:] = False
    return select


def _reference_values(reference):
    """The coefficient values the ridge pulls toward: {} (each coefficient's start value, filled as
    the stages run) or every coefficient of a reference tire; and how to name them."""
    from vehdyn.tire.magic_formula import MagicFormula, load_tire
    from vehdyn.tire.tir import TirParameters

    if reference is None:
        return {}, "their start values"
    if isinstance(reference, MagicFormula):
        tire = reference
    elif isinstance(reference, TirParameters):
        tire = MagicFormula(reference)
    else:
        tire = load_tire(reference)
    c = tire._c
    return {name: float(getattr(c, name)) for name in c._fields}, "the reference tire's values"


def _select(stage, rows):
    kind = STAGES[stage].selection
    n = rows["fz"].size
    if kind == "pure_longitudinal":
        return np.abs(rows["alpha"]) < PURE_SLIP_ANGLE
    if kind == "pure_lateral":
        return np.abs(rows["kappa"]) < PURE_SLIP_RATIO
    if kind == "combined":
        return np.abs(rows["kappa"]) >= PURE_SLIP_RATIO
    return np.ones(n, dtype=bool)


def _step_rows(step, rows, c):
    """The points of one step: nominal load, zero camber and nominal pressure as far as the data vary."""
    keep = np.ones(rows["fz"].size, dtype=bool)
    if step == "nominal" and _levels_vary(rows["fz"], 0.2 * c.FNOMIN):
        levels = _load_levels(rows["fz"])
        nearest = levels[np.argmin(np.abs(levels - c.FNOMIN))]  # the load level nearest FNOMIN
        keep &= np.abs(rows["fz"] - nearest) < 0.1 * nearest
    if step in ("nominal", "load") and _levels_vary(rows["gamma"], 2 * ZERO_CAMBER):
        keep &= np.abs(rows["gamma"] - _nearest(rows["gamma"], 0.0)) < ZERO_CAMBER
    if step in ("nominal", "load", "camber") and _levels_vary(rows["pressure"], 0.1 * c.NOMPRES):
        keep &= np.abs(rows["pressure"] - _nearest(rows["pressure"], c.NOMPRES)) < 0.05 * c.NOMPRES
    return keep


def _nearest(values, target):
    """The value of ``values`` nearest ``target`` (zero camber and the nominal pressure, or the level
    nearest them when the data, e.g. of a cross-validation refit, lack them)."""
    return float(values[np.argmin(np.abs(values - target))])


def _sweeps(step, rows, c):
    """Whether ``rows`` sweep the quantity the load, camber or pressure step needs."""
    column = STEP_VARIATION[step]
    span = {"fz": 0.2 * c.FNOMIN, "gamma": 2 * ZERO_CAMBER, "pressure": 0.1 * c.NOMPRES}[column]
    return _levels_vary(rows[column], span)


@dataclass
class _Context:
    """Settings of one fit, shared by its stages (and by the refits of the cross-validation)."""

    version: str
    fixed: set
    bounds: dict
    physical: bool
    max_nfev: int
    regularization: float
    reference: dict
    reference_name: str
    states: object
    messages: list
    warm: bool = False
    quiet: bool = False


def _fit_stage(stage, ctx, c, full, row_weights, done_stages):
    spec = STAGES[stage]
    missing = [k for k in spec.needs if k not in full or (k in ("kappa", "alpha") and not np.any(full[k]))]
    outputs = tuple(o for o in spec.outputs if o in full)
    if not outputs:
        missing += [o for o in spec.outputs]
    if missing:
        needs = sorted(set(spec.needs) | ({spec.outputs[0]} if len(spec.outputs) == 1 else set()))
        text = (f"stage {stage} skipped: it needs the columns {', '.join(needs)}"
                + (f" ({' or '.join(spec.outputs)})" if len(spec.outputs) > 1 else "")
                + f"; missing or all zero: {', '.join(missing)}")
        ctx.messages.append(text)
        return StageResult(stage, skipped=text), _unlearned(stage, ctx, c)
    select = _stage_rows(stage, full)  # (slip-ratio sweeps at zero slip angle alone do not determine Gyk)
    rows = {k: v[select] for k, v in full.items()}
    weights = None if row_weights is None else row_weights[select]
    steps = owned(stage, ctx.version)
    if stage == "combined":
        # forces first (Gxa, Gyk, SVyk) on the slip-ratio sweeps; then the aligning moment with the
        # forces held: SSZ (the Fx arm) and, refined on every point, the trail and residual torque
        # coefficients of the aligning stage, because combined slip evaluates the trail at the
        # equivalent slip angle sqrt(alpha^2 + (Kxk/Kya)^2 kappa^2), far beyond the slip-angle sweeps
        forces = tuple(o for o in ("fx", "fy") if o in outputs)
        groups = [(forces, tuple((s, tuple(n for n in names if _OUTPUT_OF[n[2]] in forces)) for s, names in steps),
                   None)] if forces else []
        if "mz" in outputs:
            aligned = done_stages.get("aligning")
            refined = dict(owned("aligning", ctx.version)) if aligned is not None and not aligned.skipped else {}
            mz_steps = tuple((s, tuple(n for n in refined.get(s, ()) if n in aligned.coefficients)
                              + tuple(n for n in names if n.startswith("SSZ"))) for s, names in steps)
            groups.append((("mz",), mz_steps, {k: v for k, v in full.items()} if refined else None))
    else:
        groups = [(outputs, steps, None)]
    if rows["fz"].size == 0:
        text = f"stage {stage} skipped: no {spec.selection.replace('_', ' ')} points in the data"
        ctx.messages.append(text)
        return StageResult(stage, skipped=text), _unlearned(stage, ctx, c)
    n_coefficients = sum(len([n for n in names if n not in ctx.fixed]) for _, st, _ in groups for step, names in st
                         if step == "nominal" or _sweeps(step, rows, c))
    n_values = rows["fz"].size * len(outputs)
    if n_values < n_coefficients:
        raise ParameterError(f"stage {stage}: {rows['fz'].size} points ({n_values} values) for {n_coefficients} "
                             f"coefficients; the fit needs at least as many values as coefficients", key="data",
                             value=n_values)
    fitted, not_identifiable, done, lasts, used = [], {}, [], [], set()
    for group, group_steps, group_rows in groups:
        group_rows = rows if group_rows is None else group_rows
        group_weights = weights if group_rows is rows else row_weights
        runnable = []
        for step, names in group_steps:
            if step != "nominal" and not _sweeps(step, group_rows, c):
                for name in names:
                    not_identifiable[name] = f"no {STEP_VARIATION[step]} sweep in the {stage} data"
                continue
            runnable.append((step, names))
        if ctx.warm and runnable:  # from a fit's solution: the last (cumulative) step alone
            runnable = [(runnable[-1][0], tuple(n for _, names in runnable for n in names))]
        active, last = [], None
        for step, names in runnable:
            active += [n for n in names if n not in ctx.fixed]
            keep = _step_rows(step, group_rows, c)
            sub = {k: v[keep] for k, v in group_rows.items()}
            w = None if group_weights is None else np.tile(group_weights[keep], len(group))
            if ctx.physical and not ctx.warm and step == "nominal":
                start = {k: v for k, v in _physical_start(stage, sub, c).items()
                         if k not in ctx.fixed and np.isfinite(v)}
                c = c._replace(**start)
            if not active:
                continue
            for name in active:  # the ridge pulls toward the value a coefficient had when first fitted
                ctx.reference.setdefault(name, float(getattr(c, name)))
            problem = _Problem(c, stage, sub, group, tuple(active), w)
            x0 = np.array([getattr(c, n) for n in active], dtype=float)
            lower, upper = _bounds(active, x0, ctx.bounds)
            # coefficients without effect on these points (e.g. RBX3: camber only at zero slip angle),
            # judged away from the start, where a product with a zero coefficient hides an effect (a
            # refit from a solution keeps them: the ridge keeps what has no effect at its reference)
            probe = x0 if ctx.warm else np.clip(x0 + 0.1 * np.maximum(np.abs(x0), 0.1), lower, upper)
            jac = problem.jac(probe, lower, upper)
            unused = np.zeros(len(active), dtype=bool) if ctx.warm else np.linalg.norm(jac, axis=0) == 0
            used.update(n for n, u in zip(active, unused) if not u)
            if unused.all():
                continue
            names_used = tuple(n for n, u in zip(active, unused) if not u)
            if unused.any():  # held in this step (a later step's points may move them)
                problem = _Problem(c, stage, sub, group, names_used, w)
                x0, lower, upper, jac = x0[~unused], lower[~unused], upper[~unused], jac[:, ~unused]
            penalty = None
            if ctx.states is not None:
                signs = (math.copysign(1.0, c.PKX1), math.copysign(1.0, c.PKY1))  # kept by the bounds
                penalty = Penalty(ctx.states, names_used, VALIDITY_WEIGHT * math.sqrt(problem.n_data), signs)
            reference = np.array([ctx.reference[n] for n in names_used])
            ridge = _Ridge.of(names_used, reference, ctx.regularization, problem.n_data)
            problem.penalize(penalty, ridge)
            if ctx.physical and not ctx.warm and (stage, step) in SHAPE_STARTS:
                x0 = _best_start(problem, x0, lower, upper, SHAPE_STARTS[stage, step])
            if ctx.warm and ridge is not None:  # what these data leave open starts from the reference
                x0 = np.clip(ridge.forget(x0, jac), lower, upper)
            result = _solve(problem, x0, lower, upper, ctx.max_nfev)
            last = (result, problem, lower, upper, ridge)
            c = problem.coefficients(result.x)
            if step not in done:
                done.append(step)
        for name in active:
            if name not in used:
                not_identifiable[name] = f"no effect on the {stage} data"
        fitted += [n for n in active if n in used]
        if last is not None:
            lasts.append(last)
    if ctx.warm:  # a refit from another fit's solution keeps nothing it cannot determine itself
        c = c._replace(**{n: ctx.reference[n] for n in not_identifiable if n in ctx.reference})
    if not_identifiable and not ctx.quiet:
        by_reason = {}
        for name, reason in not_identifiable.items():
            by_reason.setdefault(reason, []).append(name)
        for reason, names in by_reason.items():
            text = f"stage {stage}: {', '.join(names)} not identifiable ({reason}); kept at their start values"
            ctx.messages.append(text)
            warnings.warn(text, VehdynWarning, stacklevel=3)
    return _stage_result(stage, ctx, c, rows, outputs, fitted, lasts, not_identifiable, done), c


def _unlearned(stage, ctx, c):
    """``c`` with a skipped stage's coefficients back at their reference values in a refit from a
    solution (which learned them from data the refit does not have); ``c`` itself otherwise."""
    if not ctx.warm:
        return c
    names = {n for _, names in owned(stage, ctx.version) for n in names}
    return c._replace(**{n: ctx.reference[n] for n in names if n in ctx.reference})


def _stage_result(stage, ctx, c, rows, outputs, fitted, lasts, not_identifiable, done):
    problem = _Problem(c, stage, rows, outputs, tuple(fitted), None)
    model = problem.model(c)
    rms, nrms, r2 = {}, {}, {}
    for out, m, t in zip(outputs, model, problem.targets):
        err = m - t
        rms[out] = float(np.sqrt(np.mean(err**2)))
        nrms[out] = rms[out] / max(float(np.max(np.abs(t))), 1e-12)
        total = float(np.sum((t - t.mean()) ** 2))
        r2[out] = 1.0 - float(np.sum(err**2)) / total if total > 0 else float("nan")
    at_bounds, condition, weak, held = [], float("nan"), [], []
    for result, prob, lower, upper, ridge in ([] if ctx.warm else lasts):  # (a refit needs no diagnostics)
        x = result.x
        tol = 1e-6 * np.maximum(np.abs(x), 1.0)
        at_bounds += [n for n, xi, lo, hi, t in zip(prob.names, x, lower, upper, tol)
                      if abs(xi - lo) <= t or abs(xi - hi) <= t]
        jac = np.asarray(result.jac)[:prob.n_data]  # the data's rows (not the penalties', the ridge's)
        norms = np.linalg.norm(jac, axis=0)
        zero = norms == 0
        scaled = _triangular(jac[:, ~zero] / norms[~zero])
        sv = np.linalg.svd(scaled, compute_uv=False) if scaled.size else np.array([1.0])
        cond = float("inf") if zero.any() or not sv[-1] > 0 else float(sv[0] / sv[-1])
        condition = cond if np.isnan(condition) else max(condition, cond)
        if cond > CONDITION_LIMIT:
            weak += [n for n in _weak_coefficients(prob.names, scaled, zero) if n not in weak]
        if ridge is not None:
            held += [n for n in ridge.held(prob.names, jac) if n not in held]
    if held and not ctx.quiet:
        text = (f"stage {stage}: the data do not determine {', '.join(held)} (Jacobian condition {condition:.3g}); "
                f"held at {ctx.reference_name} along the directions the data leave open (regularization "
                f"{ctx.regularization:g})")
        ctx.messages.append(text)
        warnings.warn(text, VehdynWarning, stacklevel=4)
    elif weak and not ctx.quiet:
        text = (f"stage {stage}: Jacobian condition {condition:.3g}: coefficients not identifiable from these "
                f"data (weakest: {', '.join(weak)}); consider fixing them")
        ctx.messages.append(text)
        warnings.warn(text, VehdynWarning, stacklevel=4)
    coefficients = {n: float(getattr(c, n)) for n in fitted}
    return StageResult(stage, coefficients=coefficients, steps=tuple(done), outputs=outputs,
                       n_points=int(rows["fz"].size), rms=rms, nrms=nrms, r2=r2, at_bounds=tuple(at_bounds),
                       condition=condition, not_identifiable=dict(not_identifiable), weakest=tuple(weak),
                       held=tuple(held), nfev=sum(int(last[0].nfev) for last in lasts))


def _triangular(matrix):
    """R of the QR factorization of a tall matrix: the same singular values and right singular
    vectors, in an n x n matrix (an SVD of the n x n factor instead of the m x n matrix)."""
    if matrix.shape[0] <= matrix.shape[1] or not matrix.size:
        return matrix
    return np.linalg.qr(matrix, mode="r")


def _weak_coefficients(names, scaled, zero):
    """The coefficients that dominate the Jacobian's smallest singular direction (and the unused)."""
    unused = [n for n, z in zip(names, zero) if z]
    kept = [n for n, z in zip(names, zero) if not z]
    if not kept:
        return tuple(unused)
    _, _, vt = np.linalg.svd(scaled, full_matrices=False)
    v = np.abs(vt[-1])
    order = np.argsort(v)[::-1]
    return list(unused + [kept[i] for i in order[:3] if v[i] > 0.2])


class _Ridge:
    """The ridge toward the reference values: rows ``weight * (x - reference) / size``.

    ``size`` is each coefficient's typical size (:func:`~.stages.typical_size`) or its reference value,
    whichever is larger, and ``weight`` the regularization times the square root of the step's data
    values. A direction in which the data move the fit by less than the regularization (r.m.s.
    fraction of the peak) per typical size of its coefficients is held at the reference; one that
    the data determine is not (its bias is of the order of the regularization squared over the
    data's sensitivity squared). Where the data cannot tell a higher-order term from a lower-order
    one (camber*|camber| from camber at a single |camber|), the change goes to the term whose
    typical size is reached first, the lower-order one, instead of splitting in proportion to their
    effect at the data.
    """

    def __init__(self, reference, size, weight):
        self.reference, self.size, self.weight = reference, size, weight

    @classmethod
    def of(cls, names, reference, regularization, n_data):
        """The ridge of coefficients ``names`` (None when ``regularization`` is 0)."""
        if not regularization > 0:
            return None
        size = np.maximum(np.abs(reference), [typical_size(n) for n in names])
        return cls(reference, size, regularization * math.sqrt(n_data))

    def residuals(self, x):
        return self.weight * (x - self.reference) / self.size

    def forget(self, x, jac, factor=10.0):
        """``x`` with its components along the directions the ridge influences (singular values of the
        data Jacobian ``jac`` in the ridge's scaling below ``factor`` times its weight) set to the
        reference's: a start from another fit's solution keeps nothing those directions learned from
        data this fit does not have."""
        _, sv, vt = np.linalg.svd(_triangular(jac * self.size), full_matrices=False)
        weak = vt[sv < factor * self.weight]
        z = (x - self.reference) / self.size
        return self.reference + self.size * (z - weak.T @ (weak @ z))

    def held(self, names, jac):
        """The coefficients of the directions the ridge holds: right singular vectors of the data
        Jacobian ``jac`` in the ridge's scaling whose singular value is below the ridge's weight (the
        ridge keeps more than half of the reference's component), largest components first."""
        if not jac.size:
            return []
        _, sv, vt = np.linalg.svd(_triangular(jac * self.size), full_matrices=False)
        found = []
        for s, v in zip(sv, vt):
            if s < self.weight:
                order = np.argsort(np.abs(v))[::-1]
                found += [names[i] for i in order[:4] if abs(v[i]) > 0.3 and names[i] not in found]
        return found
