"""Tire characteristics: brush, Fiala, Dugoff and linear laws (and the Magic Formula when available).

The standard figure set of a tire - side force and aligning moment against slip angle, longitudinal
force against slip ratio at several loads, the friction ellipse from combined slip, and cornering
stiffness against load - for the simple tire laws of vehdyn.tire matched to one tire. When the
Magic Formula (vehdyn.tire.magic_formula) is installed the reference tire is the shipped MF 6.1
example file, and the brush, Fiala and linear laws are matched to its cornering stiffness and peak
friction at the nominal load; otherwise they are built from the sedan's vehicle file.
"""

from __future__ import annotations

import numpy as np

import vehdyn
from vehdyn.report import Study
from vehdyn.tire import BrushTire, FialaTire, LinearTire, describe_tire, plot_tire_characteristics, tire_for_vehicle
from vehdyn.tire.plots import characteristic_values, nominal_load


def magic_formula_tire():
    """The MF 6.1 example tire, or None when the Magic Formula is not installed."""
    try:
        from vehdyn.tire.magic_formula import MagicFormula
    except ImportError:
        return None
    return MagicFormula.from_tir(vehdyn.data_path("tires", "MagicFormula61_Parameters.tir"))


def matched_laws(reference, load):
    """Brush, Fiala and linear laws with the reference's cornering stiffness and peak friction at ``load``."""
    values = characteristic_values(reference, [load]).iloc[0]
    stiffness = float(values["cornering_stiffness"])
    mu = float(values["peak_lateral_friction"])
    half_length = None
    if hasattr(reference, "evaluate"):
        outputs = reference.evaluate(load, 0.0, 0.0)
        if hasattr(outputs, "contact_length"):
            half_length = float(np.asarray(outputs.contact_length)) / 2.0
    if half_length is None or not half_length > 0:
        trail = float(values["trail_at_zero_slip"])
        half_length = 3.0 * trail if np.isfinite(trail) and trail > 0 else 0.1
    return {
        "brush": BrushTire.from_cornering_stiffness(stiffness, half_length, mu),
        "fiala": FialaTire(cornering_stiffness=stiffness, mu=mu, contact_half_length=half_length),
        "linear": LinearTire(cornering_stiffness=stiffness, nominal_load=load),
    }


def run(study: Study) -> None:
    n_points = 61 if study.quick else 241
    reference = magic_formula_tire()
    if reference is not None:
        load = nominal_load(reference)
        tires = {"magic formula 6.1": reference, **matched_laws(reference, load)}
        study.text(describe_tire(reference))
    else:
        sedan = vehdyn.load_vehicle("sedan")
        tires = {name: tire_for_vehicle(sedan, "front", name) for name in ("brush", "fiala", "dugoff", "linear")}
        load = float(tires["linear"].nominal_load)
        study.text("The Magic Formula (vehdyn.tire.magic_formula) is not installed: the laws are built from "
                   "the sedan's front-tire data (half the axle cornering stiffness, friction coefficient, "
                   "contact half length from the static deflection).")
    loads = load * np.array([0.5, 1.0, 1.5])
    figures = plot_tire_characteristics(tires, loads, n_points=n_points)
    captions = {
        "lateral_force": "Side force against slip angle at three loads (ISO-W: positive slip angle, negative force)",
        "longitudinal_force": "Longitudinal force against slip ratio at three loads",
        "aligning_moment": "Aligning moment against slip angle: the brush trail a/3 at zero slip falls to zero "
                           "at full sliding",
        "friction_ellipse": "Friction ellipse from combined slip at the nominal load",
        "cornering_stiffness": "Cornering stiffness against load",
    }
    for name, fig in figures.items():
        study.figure(fig, name, caption=captions[name])

    import pandas as pd

    frames = {label: characteristic_values(tire, loads) for label, tire in tires.items()}
    table = pd.concat(frames, names=["law"])
    table.attrs["units"] = next(iter(frames.values())).attrs["units"]
    study.table(table, "key_values", caption="Cornering and slip stiffness, peak friction and trail at zero slip")

    brush = tires["brush"]
    alpha_sl = np.degrees(np.arctan(brush.full_sliding_slip(load)))
    combined = brush.forces(load, 0.05, np.deg2rad(4.0))
    pure_y = brush.forces(load, 0.0, np.deg2rad(4.0))
    study.text(
        f"At {load:.0f} N the brush tire slides over the whole contact patch beyond {alpha_sl:.1f} deg of slip "
        f"angle, where its side force reaches mu F_z and its aligning moment vanishes. A slip ratio of 0.05 "
        f"lowers its side force at 4 deg from {-pure_y.fy:.0f} N to {-combined.fy:.0f} N (combined slip through "
        f"the theoretical slip), while the Fiala model, which gives the longitudinal force priority on the "
        f"friction circle, gives {-tires['fiala'].forces(load, 0.05, np.deg2rad(4.0)).fy:.0f} N.")


if __name__ == "__main__":
    Study.main(run, __file__)
