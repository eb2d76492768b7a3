"""Fits of the simple tire laws to measured data: :func:`fit_brush` and :func:`fit_linear`.

Both fit the pure-slip points (the same selection as the Magic Formula stages: slip-angle sweeps
at |kappa| < :data:`~vehdyn.tire.fitting.magic_formula_fit.PURE_SLIP_RATIO`, slip-ratio sweeps
at |alpha| < :data:`~vehdyn.tire.fitting.magic_formula_fit.PURE_SLIP_ANGLE`) through the laws'
own ``forces`` (:class:`vehdyn.tire.BrushTire`, :class:`vehdyn.tire.LinearTire`).
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from vehdyn.errors import ParameterError, VehdynWarning
from vehdyn.tire.fitting.columns import canonical_columns, drop_nonfinite
from vehdyn.tire.fitting.magic_formula_fit import PURE_SLIP_ANGLE, PURE_SLIP_RATIO
from vehdyn.tire.fitting.result import StageResult, TireFit

__all__ = ["fit_brush", "fit_linear"]


def _pure_rows(data, messages, units):
    """The data's columns (SI, finite rows), with the pure lateral and pure longitudinal rows."""
    columns = drop_nonfinite(canonical_columns(data, units), messages)
    n = columns["fz"].size
    for name in ("kappa", "alpha", "gamma"):
        columns.setdefault(name, np.zeros(n))
    columns.setdefault("vx", np.full(n, 10.0))
    lateral = np.abs(columns["kappa"]) < PURE_SLIP_RATIO
    longitudinal = np.abs(columns["alpha"]) < PURE_SLIP_ANGLE
    return columns, lateral, longitudinal


def _metrics(name, coefficients, outputs, model, columns, masks, condition=float("nan")):
    rms, nrms, r2 = {}, {}, {}
    for out in outputs:
        on = masks[out]
        t, m = columns[out][on], getattr(model, out)[on]
        err = m - t
        rms[out] = float(np.sqrt(np.mean(err**2)))
        nrms[out] = rms[out] / max(float(np.max(np.abs(t))), 1e-12)
        total = float(np.sum((t - t.mean()) ** 2))
        r2[out] = 1.0 - float(np.sum(err**2)) / total if total > 0 else float("nan")
    n_points = int(np.count_nonzero(np.logical_or.reduce([masks[o] for o in outputs])))
    return StageResult(name, coefficients=coefficients, steps=("nominal",), outputs=tuple(outputs),
                       n_points=n_points, rms=rms, nrms=nrms, r2=r2, condition=condition)


def fit_linear(data, *, nominal_load=None, max_slip_angle=math.radians(2.0), max_slip_ratio=0.02, units=None):
    """Fit :class:`vehdyn.tire.LinearTire` to the linear range of measured data (closed form).

    .. math:: F_y = (C_\\gamma \\gamma - C_\\alpha \\alpha) \\frac{F_z}{F_{z0}}, \\qquad
              F_x = C_\\kappa \\kappa \\frac{F_z}{F_{z0}}, \\qquad M_z = -t F_y

    are linear in the stiffnesses and the trail, so ordinary least squares gives them exactly.

    Parameters
    ----------
    data : pandas.DataFrame or mapping
        Canonical columns (:func:`vehdyn.tire.read_tire_data`, SI): ``fz`` [N], ``alpha`` [rad]
        and ``fy`` [N] (needed), ``kappa`` [-] and ``fx`` [N], ``gamma`` [rad], ``mz`` [N*m] (used
        where present). Columns beyond a tire test's range in SI units are refused unless their
        unit is stated (``units``).
    nominal_load : float, optional
        ``F_z0`` [N]; default the mean load of the points used.
    max_slip_angle : float
        |alpha| [rad] of the linear range (default 2 degrees).
    max_slip_ratio : float
        |kappa| [-] of the linear range (default 0.02).
    units : dict of str to str, optional
        Units of columns that are not SI (``{"alpha": "deg"}``), converted.

    Returns
    -------
    TireFit
        ``tire`` a :class:`~vehdyn.tire.LinearTire`; one stage ``"linear"`` (coefficients
        ``cornering_stiffness``, ``camber_stiffness`` [N/rad], ``slip_stiffness`` [N],
        ``pneumatic_trail`` [m]).

    Raises
    ------
    ParameterError
        Without a slip-angle sweep, with fewer points in the linear range than stiffnesses, when
        the cornering stiffness comes out not positive, or for a column in another unit than SI.

    References
    ----------
    H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., 2012, ch. 1 (the linear range of the tire
    characteristics: cornering, camber and longitudinal slip stiffness, pneumatic trail).
    """
    from vehdyn.tire.linear import LinearTire

    messages = []
    columns, lateral, longitudinal = _pure_rows(data, messages, units)
    if "fy" not in columns or not np.any(columns["alpha"]):
        raise ParameterError("fit_linear needs the columns fz, alpha and fy (a slip-angle sweep)", key="data",
                             value=sorted(columns))
    lateral &= np.abs(columns["alpha"]) <= max_slip_angle
    longitudinal &= np.abs(columns["kappa"]) <= max_slip_ratio
    fz0 = float(np.mean(columns["fz"][lateral])) if nominal_load is None else float(nominal_load)
    scale = columns["fz"] / fz0
    design = [-columns["alpha"] * scale]
    camber = "gamma" in columns and np.ptp(columns["gamma"][lateral]) > 0
    if camber:
        design.append(columns["gamma"] * scale)
    matrix = np.column_stack([d[lateral] for d in design])
    slopes = np.unique(columns["alpha"][lateral & (columns["alpha"] != 0)]).size
    if lateral.sum() < matrix.shape[1] + 1 or slopes == 0:
        raise ParameterError(f"fit_linear: {int(lateral.sum())} points with |alpha| <= {max_slip_angle:.4g} rad and "
                             f"|kappa| < {PURE_SLIP_RATIO}, {slopes} of them at a non-zero slip angle; needs at least "
                             f"{matrix.shape[1] + 1} and one (raise max_slip_angle for a coarse sweep)", key="data",
                             value=int(lateral.sum()))
    solution, *_ = np.linalg.lstsq(matrix, columns["fy"][lateral], rcond=None)
    values = {"cornering_stiffness": float(solution[0]), "camber_stiffness": float(solution[1]) if camber else 0.0}
    outputs, masks = ["fy"], {"fy": lateral}
    if "fx" in columns and np.count_nonzero(longitudinal & (columns["kappa"] != 0)) >= 2:
        k = (columns["kappa"] * scale)[longitudinal]
        values["slip_stiffness"] = float(np.dot(k, columns["fx"][longitudinal]) / np.dot(k, k))
        outputs.append("fx")
        masks["fx"] = longitudinal
    if "mz" in columns:
        fy = columns["fy"][lateral]
        values["pneumatic_trail"] = max(float(-np.dot(fy, columns["mz"][lateral]) / np.dot(fy, fy)), 0.0)
        outputs.append("mz")
        masks["mz"] = lateral
    if not values["cornering_stiffness"] > 0:
        raise ParameterError(f"fit_linear: the fitted cornering stiffness {values['cornering_stiffness']:.4g} N/rad is "
                             f"not positive (ISO-W data: F_y falls with alpha)", key="cornering_stiffness",
                             value=values["cornering_stiffness"])
    tire = LinearTire(nominal_load=fz0, **values)
    model = tire.forces(columns["fz"], columns["kappa"], columns["alpha"], columns["gamma"], columns["vx"])
    stage = _metrics("linear", values, outputs, model, columns, masks)
    return TireFit(tire=tire, stages={"linear": stage}, messages=messages, data=columns)


def fit_brush(data, *, contact_half_length=None, sliding=False, units=None):
    """Fit :class:`vehdyn.tire.BrushTire` (parabolic pressure) to pure-slip data.

    Fits the cornering stiffness ``2 c_p a^2`` (= slip stiffness: the brush is isotropic), the
    friction coefficient and, from the aligning moment (trail ``a/3`` at zero slip), the contact
    half length ``a``, by bounded least squares on ``F_y`` (and ``F_x``, ``M_z`` where measured),
    each normalized by its peak. The brush has no load dependence of its stiffness.

    Parameters
    ----------
    data : pandas.DataFrame or mapping
        Canonical columns (SI): ``fz`` [N], ``alpha`` [rad], ``fy`` [N]; ``kappa`` [-] and ``fx``
        [N], ``mz`` [N*m] where present. Columns beyond a tire test's range in SI units are
        refused unless their unit is stated (``units``).
    contact_half_length : float, optional
        ``a`` [m], held fixed. Needed when the data have no ``mz`` (then ``a`` cannot be identified).
    sliding : bool
        Also fit a sliding friction ``mu_sliding <= mu``.
    units : dict of str to str, optional
        Units of columns that are not SI (``{"alpha": "deg"}``), converted.

    Returns
    -------
    TireFit
        ``tire`` a :class:`~vehdyn.tire.BrushTire`; one stage ``"brush"`` (coefficients
        ``cornering_stiffness`` [N/rad], ``mu`` [-], ``contact_half_length`` [m], ``mu_sliding`` [-]).

    Raises
    ------
    ParameterError
        Without a slip-angle sweep, without ``mz`` and ``contact_half_length``, with fewer measured
        values at non-zero slip than coefficients, or for a column in another unit than SI.

    Warns
    -----
    VehdynWarning
        When the Jacobian's condition exceeds 1e8 (the data do not determine the coefficients
        independently).

    References
    ----------
    H. B. Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., 2012, sec. 3.2.1 (pure side slip of the
    brush model with a parabolic pressure distribution), 3.2.2 (pure longitudinal slip).
    """
    from scipy.optimize import least_squares

    from vehdyn.tire.brush import BrushTire

    messages = []
    columns, lateral, longitudinal = _pure_rows(data, messages, units)
    if "fy" not in columns or not np.any(columns["alpha"]):
        raise ParameterError("fit_brush needs the columns fz, alpha and fy (a slip-angle sweep)", key="data",
                             value=sorted(columns))
    has_mz = "mz" in columns
    if not has_mz and contact_half_length is None:
        raise ParameterError("fit_brush: without an mz column the contact half length cannot be identified; "
                             "give contact_half_length", key="contact_half_length", value=None)
    outputs, masks = ["fy"], {"fy": lateral}
    if "fx" in columns and np.any(columns["kappa"][longitudinal]):
        outputs.append("fx")
        masks["fx"] = longitudinal & (columns["kappa"] > -0.99)
    if has_mz:
        outputs.append("mz")
        masks["mz"] = lateral
    fz = columns["fz"]
    on = lateral
    alpha, fy = columns["alpha"][on], columns["fy"][on]
    near = np.abs(alpha) <= max(np.sort(np.unique(np.abs(alpha)))[:4].max(), 1e-6)
    slope = float(np.polyfit(alpha[near], fy[near], 1)[0]) if np.ptp(alpha[near]) > 0 else -1e4
    mu0 = max(float(np.max(np.abs(fy) / np.maximum(fz[on], 1.0))), 0.05)
    if has_mz and np.any(fy[near]):
        trail = float(-np.dot(fy[near], columns["mz"][on][near]) / np.dot(fy[near], fy[near]))
        a0 = min(max(3.0 * trail, 0.01), 0.5)
    else:
        a0 = contact_half_length
    names = ["cornering_stiffness", "mu"] + (["contact_half_length"] if contact_half_length is None else []) \
        + (["mu_sliding"] if sliding else [])
    x0 = np.array([max(abs(slope), 1.0), mu0] + ([a0] if contact_half_length is None else [])
                  + ([0.9 * mu0] if sliding else []))
    informative = {"fy": lateral & (columns["alpha"] != 0), "mz": lateral & (columns["alpha"] != 0),
                   "fx": longitudinal & (columns["kappa"] != 0)}
    n_values = sum(int(np.count_nonzero(informative[o] & masks[o])) for o in outputs)
    if n_values < len(names):
        raise ParameterError(f"fit_brush: {n_values} measured values at non-zero slip ({', '.join(outputs)}) for "
                             f"{len(names)} coefficients ({', '.join(names)}); the fit needs at least as many values "
                             f"as coefficients", key="data", value=n_values)
    targets = [columns[o][masks[o]] for o in outputs]
    scales = [max(float(np.max(np.abs(t))), 1e-9) for t in targets]

    def build(x):
        p = dict(zip(names, x))
        a = p.get("contact_half_length", contact_half_length)
        mu_s = min(p["mu_sliding"], p["mu"]) if sliding else None
        return BrushTire.from_cornering_stiffness(p["cornering_stiffness"], a, p["mu"], mu_s)

    def residuals(x):
        model = build(x).forces(fz, columns["kappa"], columns["alpha"], 0.0, columns["vx"])
        return np.concatenate([(getattr(model, o)[masks[o]] - t) / s for o, t, s in zip(outputs, targets, scales)])

    lower = np.array([1e-3, 1e-3] + ([1e-4] if contact_half_length is None else []) + ([1e-3] if sliding else []))
    result = least_squares(residuals, x0, bounds=(lower, np.inf), x_scale="jac")
    jac = result.jac / np.maximum(np.linalg.norm(result.jac, axis=0), 1e-300)
    sv = np.linalg.svd(jac, compute_uv=False)
    condition = float(sv[0] / sv[-1]) if sv[-1] > 0 else float("inf")
    if condition > 1e8:
        warnings.warn(f"fit_brush: Jacobian condition {condition:.3g}; the data do not determine "
                      f"{', '.join(names)} independently", VehdynWarning, stacklevel=2)
    tire = build(result.x)
    values = {"cornering_stiffness": float(tire.cornering_stiffness), "mu": float(tire.mu),
              "contact_half_length": float(tire.contact_half_length)}
    if sliding:
        values["mu_sliding"] = float(tire.mu_sliding)
    model = tire.forces(fz, columns["kappa"], columns["alpha"], 0.0, columns["vx"])
    stage = _metrics("brush", values, outputs, model, columns, masks, condition)
    return TireFit(tire=tire, stages={"brush": stage}, messages=messages, data=columns)
