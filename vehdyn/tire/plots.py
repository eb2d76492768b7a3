"""The standard figure set of a tire, for any tire law, in the textbook's form.

:func:`plot_tire_characteristics` draws, for one tire or several overlaid (``{label: tire}``):
side force against slip angle, longitudinal force against slip ratio and aligning moment against
slip angle at several loads; the friction ellipse from combined slip (lines of constant slip
angle over a slip-ratio sweep and of constant slip ratio over a slip-angle sweep); and cornering
stiffness against load. :func:`characteristic_values` gives the key numbers of a tire
(cornering and slip stiffness, peak friction, trail at zero slip) and :func:`describe_tire` prints
them, with the version and key ``.tir`` values for a Magic Formula tire. Forces and slips are in
ISO-W (:mod:`vehdyn.conventions`); angles are shown in degrees.

matplotlib and pandas are imported inside the functions.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from vehdyn.tire.base import TireModel

__all__ = ["plot_tire_characteristics", "characteristic_values", "cornering_stiffness", "describe_tire", "nominal_load"]

_DEFAULT_NOMINAL_LOAD = 4000.0  # [N], for laws that carry no load of their own
_STIFFNESS_STEP = 1e-7  # slip step [rad or -] of the central differences at zero slip


def _tir_parameters(tire) -> Mapping:
    """The ``.tir`` values of a Magic Formula tire (flat, upper-case keys, SI), else ``{}``."""
    params = getattr(tire, "params", None)
    return params if isinstance(params, Mapping) else {}


def nominal_load(tire) -> float:
    """A representative load of a tire.

    Parameters
    ----------
    tire : TireModel
        Any tire law.

    Returns
    -------
    float
        Its ``nominal_load`` (``FNOMIN`` of a ``.tir``) if it has a finite positive one, else
        4000 [N].
    """
    value = getattr(tire, "nominal_load", None)
    try:
        value = float(value)
    except (TypeError, ValueError):
        return _DEFAULT_NOMINAL_LOAD
    return value if np.isfinite(value) and value > 0 else _DEFAULT_NOMINAL_LOAD


def _tires(tire) -> dict:
    if isinstance(tire, Mapping):
        return dict(tire)
    return {getattr(tire, "name", "") or type(tire).__name__: tire}


def cornering_stiffness(tire: TireModel, loads, *, vx: float = 20.0) -> np.ndarray:
    """Cornering stiffness of a tire at zero slip, for each load.

    Parameters
    ----------
    tire : TireModel
        Any tire law.
    loads : array_like
        Normal loads [N].
    vx : float
        Forward speed [m/s] passed to the law.

    Returns
    -------
    ndarray
        ``-dF_y/dalpha`` at zero slip [N/rad] (ISO-W), by a central difference of step 1e-7 rad.
    """
    h = _STIFFNESS_STEP
    lateral = tire.forces(np.asarray(loads, dtype=float)[..., None], 0.0, np.array([-h, h]), 0.0, vx)
    return -(lateral.fy[..., 1] - lateral.fy[..., 0]) / (2 * h)


def characteristic_values(tire: TireModel, loads=None, *, vx: float = 20.0):
    """Key numbers of a tire at each load.

    Parameters
    ----------
    tire : TireModel
        Any tire law.
    loads : array_like, optional
        Normal loads [N] (default the tire's :func:`nominal_load`).
    vx : float
        Forward speed [m/s] passed to the law.

    Returns
    -------
    pandas.DataFrame
        Indexed by ``normal_load`` [N], with ``attrs["units"]``. Columns: ``cornering_stiffness`` [N/rad] (``-dF_y/dalpha`` at zero slip, central difference),
    ``slip_stiffness`` [N] (``dF_x/dkappa``), ``peak_lateral_friction`` and
    ``peak_longitudinal_friction`` [-] (``max |F|/F_z`` over |alpha| <= 30 deg, |kappa| <= 1; for a
    law without friction limit, such as the linear tire, the value at the end of the sweep),
    ``trail_at_zero_slip`` [m] (``-dM_z/dF_y`` at zero slip).

    Examples
    --------
    >>> from vehdyn.tire import BrushTire, characteristic_values
    >>> brush = BrushTire(contact_half_length=0.08, tread_stiffness=5e6, mu=1.0)
    >>> row = characteristic_values(brush, [4000.0]).iloc[0]
    >>> round(float(row["cornering_stiffness"])), round(float(row["trail_at_zero_slip"]), 5)   # 2 c_p a^2, a / 3
    (64000, 0.02667)
    """
    import pandas as pd

    loads = np.atleast_1d(np.asarray(loads if loads is not None else nominal_load(tire), dtype=float))
    h = _STIFFNESS_STEP
    fz = loads[:, None]
    lateral = tire.forces(fz, 0.0, np.array([-h, h]), 0.0, vx)
    longitudinal = tire.forces(fz, np.array([-h, h]), 0.0, 0.0, vx)
    cornering = cornering_stiffness(tire, loads, vx=vx)
    slip_stiffness = (longitudinal.fx[:, 1] - longitudinal.fx[:, 0]) / (2 * h)
    dfy = lateral.fy[:, 1] - lateral.fy[:, 0]
    trail = np.where(dfy != 0.0, -(lateral.mz[:, 1] - lateral.mz[:, 0]) / np.where(dfy != 0.0, dfy, 1.0), np.nan)
    alpha = np.deg2rad(np.linspace(-30.0, 30.0, 601))
    kappa = np.linspace(-1.0, 1.0, 801)
    peak_y = np.max(np.abs(tire.forces(fz, 0.0, alpha, 0.0, vx).fy), axis=1) / loads
    peak_x = np.max(np.abs(tire.forces(fz, kappa, 0.0, 0.0, vx).fx), axis=1) / loads
    frame = pd.DataFrame({"cornering_stiffness": cornering, "slip_stiffness": slip_stiffness,
                          "peak_lateral_friction": peak_y, "peak_longitudinal_friction": peak_x,
                          "trail_at_zero_slip": trail}, index=pd.Index(loads, name="normal_load"))
    frame.attrs["units"] = {"normal_load": "N", "cornering_stiffness": "N/rad", "slip_stiffness": "N",
                            "peak_lateral_friction": "-", "peak_longitudinal_friction": "-",
                            "trail_at_zero_slip": "m"}
    return frame


def describe_tire(tire: TireModel, loads=None, *, vx: float = 20.0) -> str:
    """A text summary of a tire.

    Parameters
    ----------
    tire : TireModel
        Any tire law.
    loads : array_like, optional
        Normal loads [N] (default 0.5, 1 and 1.5 times the :func:`nominal_load`).
    vx : float
        Forward speed [m/s] passed to the law.

    Returns
    -------
    str
        The law and its parameters (for a Magic Formula: version and key ``.tir`` values) and
        the :func:`characteristic_values` at the loads.
    """
    lines = [f"tire law: {getattr(tire, 'name', '') or type(tire).__name__} ({type(tire).__name__})"]
    version = getattr(tire, "version", None)
    params = _tir_parameters(tire)
    if version is not None:
        lines.append(f"Magic Formula version: {version}")
    if params:
        for key in ("FITTYP", "PROPERTY_FILE_FORMAT", "TYRESIDE", "FNOMIN", "UNLOADED_RADIUS", "WIDTH",
                    "NOMPRES", "LONGVL", "VERTICAL_STIFFNESS", "PDX1", "PDY1", "PKX1", "PKY1", "PKY2"):
            if key in params:
                lines.append(f"  {key:<20} = {params[key]}")
        defaulted = getattr(params, "defaulted", ())
        missing = getattr(params, "missing_sections", ())
        if defaulted:
            lines.append(f"  {len(defaulted)} coefficients not in the file take MFeval's defaults"
                         + (f"; missing sections: {', '.join(missing)}" if missing else ""))
    elif hasattr(tire, "to_dict"):
        for key, value in tire.to_dict().items():
            lines.append(f"  {key:<26} = {value:.6g}" if isinstance(value, float) else f"  {key:<26} = {value}")
    if loads is None:
        loads = nominal_load(tire) * np.array([0.5, 1.0, 1.5])
    frame = characteristic_values(tire, loads, vx=vx)
    lines.append(f"at vx = {vx:g} m/s:")
    lines.append(frame.to_string(float_format=lambda v: f"{v:.5g}"))
    return "\n".join(lines)


def plot_tire_characteristics(tire, loads=None, *, vx: float = 20.0, max_slip_angle_deg: float = 15.0,
                              max_slip_ratio: float = 0.5, n_points: int = 201) -> dict:
    """The standard figure set of one tire or of several overlaid.

    Parameters
    ----------
    tire : TireModel or mapping of str to TireModel
        A tire, or ``{label: tire}`` to compare laws (one line style per tire, one colour per load).
    loads : sequence of float, optional
        Normal loads [N]; default 0.5, 1 and 1.5 times the (first) tire's nominal load.
    vx : float
        Forward speed [m/s] passed to the laws.
    max_slip_angle_deg, max_slip_ratio : float
        Sweep ranges [deg] and [-], > 0.
    n_points : int
        Points per sweep, >= 2.

    Returns
    -------
    dict of str to matplotlib Figure
        ``lateral_force``, ``longitudinal_force``, ``aligning_moment``, ``friction_ellipse``,
        ``cornering_stiffness``.
    """
    from vehdyn.params.checks import check_sample_count, finite_number, whole_number
    from vehdyn.plotting import new_figure

    n_points = whole_number(n_points, "n_points", minimum=2)
    check_sample_count(n_points, "n_points", n_points, "points per sweep")
    max_slip_angle_deg = finite_number(max_slip_angle_deg, "max_slip_angle_deg", positive=True)
    max_slip_ratio = finite_number(max_slip_ratio, "max_slip_ratio", positive=True)
    tires = _tires(tire)
    first = next(iter(tires.values()))
    nominal = nominal_load(first)
    loads = np.asarray(loads if loads is not None else nominal * np.array([0.5, 1.0, 1.5]), dtype=float)
    alpha_deg = np.linspace(-max_slip_angle_deg, max_slip_angle_deg, n_points)
    alpha = np.deg2rad(alpha_deg)
    kappa = np.linspace(-max_slip_ratio, max_slip_ratio, n_points)
    styles = ["-", "--", ":", "-."]
    figures = {}

    sweeps = (("lateral_force", "slip angle [deg]", "lateral force F_y [N]", alpha_deg),
              ("longitudinal_force", "slip ratio [-]", "longitudinal force F_x [N]", kappa),
              ("aligning_moment", "slip angle [deg]", "aligning moment M_z [N*m]", alpha_deg))
    for name, xlabel, ylabel, x in sweeps:
        fig, axes = new_figure(1, 1, height_per_row=3.6)
        ax = axes[0, 0]
        extent = 0.0  # the first tire's range sets the axes (a linear tire would dwarf the rest)
        for i, (label, law) in enumerate(tires.items()):
            for j, fz in enumerate(loads):
                if name == "longitudinal_force":
                    y = law.forces(fz, kappa, 0.0, 0.0, vx).fx
                else:
                    out = law.forces(fz, 0.0, alpha, 0.0, vx)
                    y = out.fy if name == "lateral_force" else out.mz
                if i == 0:
                    extent = max(extent, float(np.max(np.abs(y))))
                ax.plot(x, y, styles[i % len(styles)], color=f"C{j}",
                        label=f"{label}, F_z = {fz:.0f} N" if len(tires) > 1 else f"F_z = {fz:.0f} N")
        if extent > 0:
            ax.set_ylim(-1.3 * extent, 1.3 * extent)
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        ax.grid(True, alpha=0.3)
        ax.axhline(0.0, color="k", lw=0.5)
        ax.legend(fontsize=7)
        fig.tight_layout()
        figures[name] = fig

    fig, axes = new_figure(1, 1, width=5.6, height_per_row=5.0)
    ax = axes[0, 0]
    fixed_alpha = np.deg2rad(np.linspace(0.0, max_slip_angle_deg, 6))
    fixed_kappa = np.linspace(0.0, max_slip_ratio, 6)
    extent = 0.0  # the first tire's largest force sets the axes (a linear tire would dwarf the rest)
    for i, (label, law) in enumerate(tires.items()):
        style = styles[i % len(styles)]
        out = law.forces(nominal, kappa[:, None], fixed_alpha[None, :], 0.0, vx)
        ax.plot(out.fy, out.fx, style, color="C0", lw=0.9)
        extent = extent or max(np.max(np.abs(out.fx)), np.max(np.abs(out.fy)))
        for sign in (1.0, -1.0):
            out = law.forces(nominal, sign * fixed_kappa[None, :], alpha[:, None], 0.0, vx)
            ax.plot(out.fy, out.fx, style, color="C1", lw=0.9)
        ax.plot([], [], style, color="k", label=label)
    mu = getattr(first, "mu", None)
    if isinstance(mu, float):
        extent = max(extent, mu * nominal)
    if extent > 0:
        ax.set_xlim(-1.2 * extent, 1.2 * extent)
        ax.set_ylim(-1.2 * extent, 1.2 * extent)
    if isinstance(mu, float):
        theta = np.linspace(0.0, 2.0 * np.pi, 361)
        ax.plot(mu * nominal * np.cos(theta), mu * nominal * np.sin(theta), color="0.5", lw=0.6,
                label=f"friction circle mu F_z (mu = {mu:g})")
    ax.plot([], [], color="C0", label="constant slip angle (0 to %g deg)" % max_slip_angle_deg)
    ax.plot([], [], color="C1", label="constant slip ratio (0 to +/-%g)" % max_slip_ratio)
    ax.set_xlabel("lateral force F_y [N]")
    ax.set_ylabel("longitudinal force F_x [N]")
    ax.set_title(f"combined slip at F_z = {nominal:.0f} N", fontsize=9)
    ax.set_aspect("equal")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    figures["friction_ellipse"] = fig

    fig, axes = new_figure(1, 1, height_per_row=3.6)
    ax = axes[0, 0]
    load_axis = np.linspace(0.05, 2.0, 40) * nominal
    for i, (label, law) in enumerate(tires.items()):
        ax.plot(load_axis, cornering_stiffness(law, load_axis, vx=vx), styles[i % len(styles)], label=label)
    ax.set_xlabel("normal load F_z [N]")
    ax.set_ylabel("cornering stiffness [N/rad]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    figures["cornering_stiffness"] = fig
    return figures
