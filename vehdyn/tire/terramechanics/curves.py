"""A soil's characteristic curves: sinkage, drawbar pull, torque and efficiency against slip.

Used by ``vehdyn tire --soil NAME`` and the off-road study. matplotlib is imported on use.
"""

from __future__ import annotations

import math

import numpy as np

from vehdyn.tire.terramechanics.soil import Soil, load_soil, shipped_soils, soil_source
from vehdyn.tire.terramechanics.wong_reece import RigidWheel, WheelSoilResult

__all__ = ["soil_curves", "describe_soil", "plot_soil_curves"]

#: The default test wheel of the curves: radius [m], width [m], load [N].
DEFAULT_WHEEL = (0.3, 0.2, 1500.0)


def soil_curves(soil: Soil | str, radius: float = DEFAULT_WHEEL[0], width: float = DEFAULT_WHEEL[1],
                load: float = DEFAULT_WHEEL[2], slips=None) -> WheelSoilResult:
    """The rigid wheel's steady state over a range of slips.

    Parameters
    ----------
    soil : Soil or str
        The soil, or a name for :func:`~vehdyn.tire.terramechanics.load_soil`.
    radius : float
        Wheel radius [m] (default 0.3).
    width : float
        Wheel width [m] (default 0.2).
    load : float
        Vertical load [N] (default 1500).
    slips : array_like, optional
        Slips [-] (default 101 slips in [-1, 1]).

    Returns
    -------
    WheelSoilResult
    """
    soil = load_soil(soil) if isinstance(soil, str) else soil
    slips = np.linspace(-1.0, 1.0, 101) if slips is None else slips
    return RigidWheel(radius=radius, width=width, soil=soil).solve(load, slips)


def describe_soil(soil: Soil | str, radius: float = DEFAULT_WHEEL[0], width: float = DEFAULT_WHEEL[1],
                  load: float = DEFAULT_WHEEL[2]) -> str:
    """A text page: the soil's parameters (SI) and its curves at a few slips for a wheel.

    Parameters
    ----------
    soil : Soil or str
        The soil, or a shipped name.
    radius : float
        Wheel radius [m].
    width : float
        Wheel width [m].
    load : float
        Vertical load [N].

    Returns
    -------
    str
        The parameters, the source of a shipped soil, and sinkage, drawbar pull, torque, motion
        resistance and efficiency at ten slips from -1 to 1.
    """
    soil = load_soil(soil) if isinstance(soil, str) else soil
    lines = [f"soil {soil.name}"]
    if soil.name in shipped_soils() and load_soil(soil.name) == soil:
        lines.append(f"  source: {soil_source(soil.name)}")
    lines += [f"  n = {soil.n:g} [-], k_c = {soil.k_c:g} [N/m^(n+1)], k_phi = {soil.k_phi:g} [N/m^(n+2)]",
              f"  c = {soil.cohesion:g} [Pa], phi = {math.degrees(soil.friction_angle):.4g} [deg], "
              f"K = {soil.shear_modulus:g} [m], density = {soil.density:g} [kg/m^3]",
              f"rigid wheel r = {radius:g} m, b = {width:g} m, W = {load:g} N (Wong-Reece, c1 = 0.43, c2 = 0.32)",
              f"{'slip':>6} {'sinkage [mm]':>13} {'DP [N]':>9} {'DP/W':>7} {'T [N*m]':>9} {'R [N]':>8} "
              f"{'eta':>6}  status"]
    r = soil_curves(soil, radius, width, load, np.array([-1.0, -0.5, -0.2, 0.0, 0.1, 0.2, 0.3, 0.5, 0.8, 1.0]))
    for i in range(r.slip.size):
        lines.append(f"{r.slip[i]:6.2f} {r.sinkage[i] * 1e3:13.2f} {r.drawbar_pull[i]:9.1f} "
                     f"{r.drawbar_pull[i] / load:7.3f} {r.torque[i]:9.1f} {r.motion_resistance[i]:8.1f} "
                     f"{r.tractive_efficiency[i]:6.3f}  {r.status[i]}")
    return "\n".join(lines)


def plot_soil_curves(results: dict, *, fig=None):
    """Sinkage, drawbar pull over load, torque and tractive efficiency against slip.

    Parameters
    ----------
    results : dict of str to WheelSoilResult
        One line per entry (label -> result); stuck points are left out.
    fig : matplotlib Figure, optional
        A 2 x 2 figure to draw into (default a new one).

    Returns
    -------
    matplotlib Figure
    """
    from vehdyn.plotting import new_figure

    if fig is None:
        fig, axes = new_figure(2, 2, width=9.0, height_per_row=2.8)
    else:
        axes = np.asarray(fig.axes).reshape(2, 2)
    for label, r in results.items():
        ok = ~r.stuck
        axes[0, 0].plot(r.slip[ok], r.sinkage[ok] * 1e3, label=label)
        axes[0, 1].plot(r.slip[ok], r.drawbar_pull[ok] / r.load[ok], label=label)
        axes[1, 0].plot(r.slip[ok], r.torque[ok], label=label)
        axes[1, 1].plot(r.slip[ok], r.tractive_efficiency[ok], label=label)
    for ax, ylabel in zip(axes.flat, ("sinkage [mm]", "drawbar pull / load [-]", "torque [N*m]",
                                      "tractive efficiency [-]")):
        ax.set_ylabel(ylabel)
        ax.set_xlabel("slip s [-]")
        ax.grid(True, alpha=0.3)
    axes[0, 1].legend(fontsize=7)
    return fig
