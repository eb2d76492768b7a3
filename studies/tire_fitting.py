"""Tire fitting: recover a shipped Magic Formula tire from noisy synthetic test data.

The MF 6.1 example tire (data/tires/MagicFormula61_Parameters.tir) is sampled on the grid of a
flat-track test program - four loads, slip-angle sweeps to +-15 deg, slip-ratio sweeps to +-0.3,
camber 0 and +-4 deg, slip-ratio sweeps at four slip angles - with 3 % Gaussian noise, and a
Magic Formula is fitted to it stage by stage from the default start (peak, slope at zero and shape
read from the data; not the file's coefficients). The fit is judged against the noise-free truth
on the fitting points and on held-out combined-slip points, and the brush and linear laws are
fitted to the same data for comparison.
"""

from __future__ import annotations

import warnings

import numpy as np

import vehdyn
from vehdyn.report import Study
from vehdyn.tire import fit_brush, fit_linear, fit_magic_formula, load_tire
from vehdyn.tire.fitting.synthetic import sample_tire


def relative_rms(tire, frame, truth, names=("fx", "fy", "mz")):
    """R.m.s. error over the peak of the truth [%] per output."""
    model = tire.forces(frame["fz"].to_numpy(), frame["kappa"].to_numpy(), frame["alpha"].to_numpy(),
                        frame["gamma"].to_numpy(), frame["vx"].to_numpy())
    return {name: 100 * float(np.sqrt(np.mean((getattr(model, name) - truth[name]) ** 2)) / np.max(np.abs(truth[name])))
            for name in names}


def every_tire(study: Study, n_angles: int, n_ratios: int) -> None:
    """Every shipped .tir file, clean and with 3 % noise: error against the truth."""
    import pandas as pd

    rows = {}
    for name in ("MagicFormula61_Parameters", "MagicFormula62_Parameters", "MagicFormula52_Parameters",
                 "mf_185_80R14"):
        tire = load_tire(name)
        held = sample_tire(tire, loads=tire.nominal_load * np.array([0.6, 1.0, 1.4]), slip_angles=[],
                           cambers=[0.0], combined_angles=np.radians([-5.0, 1.5, 4.5]))
        held = held[held["sweep"] == "combined"]
        held_truth = {k: v[held.index] for k, v in held.attrs["truth"].items()}
        for noise in (0.0, 0.03):
            data = sample_tire(tire, slip_angles=np.radians(np.linspace(-15, 15, n_angles)),
                               slip_ratios=np.linspace(-0.3, 0.3, n_ratios), noise=noise, seed=5)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", vehdyn.VehdynWarning)
                fit = fit_magic_formula(data, version=tire.version)
            on_data = relative_rms(fit.tire, data, data.attrs["truth"])
            on_held = relative_rms(fit.tire, held, held_truth)
            rows[(name, f"{100 * noise:.0f} %")] = {**{f"{k} data": v for k, v in on_data.items()},
                                                    **{f"{k} held-out": v for k, v in on_held.items()}}
    table = pd.DataFrame(rows).T
    table.index.names = ["tire", "noise"]
    table.attrs["units"] = {name: "% of peak" for name in table.columns}
    study.table(table, "every_tire", caption="Every shipped tire fitted from the default start (MF version of "
                                             "the file): error against the noise-free truth on the fitting data "
                                             "and on held-out combined-slip points [% of the peak]")


def run(study: Study) -> None:
    import pandas as pd

    truth_tire = load_tire("MagicFormula61_Parameters")
    n_angles, n_ratios = (21, 21) if not study.full else (31, 31)
    data = sample_tire(truth_tire, slip_angles=np.radians(np.linspace(-15, 15, n_angles)),
                       slip_ratios=np.linspace(-0.3, 0.3, n_ratios), noise=0.03, seed=2)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", vehdyn.VehdynWarning)
        fit = fit_magic_formula(data)
    study.text(f"{len(data)} points with 3 % noise; MF 6.1 fitted from the default start in "
               f"{sum(s.seconds for s in fit.stages.values()):.1f} s. The fit reports what the data cannot "
               f"determine: " + "; ".join(sorted({str(w.message) for w in caught})[:3]) + ".")
    table = fit.table().set_index(["stage", "output"])
    study.table(table[["points", "rms", "unit", "nrms_percent", "r2", "coefficients", "condition"]], "stages",
                caption="Per stage: r.m.s. error against the noisy data, normalized by the peak, R^2, and the "
                        "condition number of the column-normalized Jacobian")
    held = sample_tire(truth_tire, loads=truth_tire.nominal_load * np.array([0.6, 1.0, 1.4]), slip_angles=[],
                       cambers=[0.0], combined_angles=np.radians([-5.0, 1.5, 4.5]))
    held = held[held["sweep"] == "combined"]
    truth = data.attrs["truth"]
    rows = {"fitting points": relative_rms(fit.tire, data, truth),
            "held-out combined points": relative_rms(fit.tire, held,
                                                     {k: v[held.index] for k, v in held.attrs["truth"].items()})}
    pure = data[data["sweep"] != "combined"]
    lateral = pure[pure["sweep"] == "lateral"]
    lateral_truth = {k: v[lateral.index] for k, v in truth.items()}
    step = np.radians(30.0 / (n_angles - 1))  # the linear range: the sweep's first steps
    linear_range = 1.01 * max(step, np.radians(2.0))
    brush = fit_brush(pure)
    linear = fit_linear(pure, max_slip_angle=linear_range)
    rows["brush (pure slip)"] = relative_rms(brush.tire, lateral, lateral_truth, ("fy",))
    longitudinal = pure[pure["sweep"] == "longitudinal"]
    rows["brush (pure slip)"]["fx"] = relative_rms(brush.tire, longitudinal,
                                                   {k: v[longitudinal.index] for k, v in truth.items()}, ("fx",))["fx"]
    small = lateral[np.abs(lateral["alpha"]) <= linear_range]
    rows[f"linear, on |alpha| <= {np.degrees(linear_range):.1f} deg"] = relative_rms(
        linear.tire, small, {k: v[small.index] for k, v in truth.items()}, ("fy",))
    errors = pd.DataFrame(rows).T
    errors.attrs["units"] = {name: "% of peak" for name in errors.columns}
    study.table(errors, "recovery", caption="Error against the noise-free truth, r.m.s. over the peak force "
                                            "[%]: the Magic Formula on all data (brush and linear: Fy on the "
                                            "slip-angle sweeps, brush also Fx on the slip-ratio sweeps)")
    for stage, fig in fit.plot().items():
        study.figure(fig, f"fit_{stage}", caption=f"{stage.replace('_', ' ')}: data (dots) and fit (lines) per load")
    if study.full:
        every_tire(study, n_angles, n_ratios)
    fitting, held_out = rows["fitting points"], rows["held-out combined points"]
    study.text(f"The fitted Magic Formula recovers the tire's forces to {fitting['fy']:.2f} % (Fy) and "
               f"{fitting['fx']:.2f} % (Fx) of the peak on the fitting points and {held_out['fy']:.2f} % / "
               f"{held_out['fx']:.2f} % on held-out combined-slip points, with 3 % noise on the data. The brush "
               f"law, one stiffness and one friction coefficient for every load, is off by "
               f"{rows['brush (pure slip)']['fy']:.1f} % (Fy): it has no load dependence of its stiffness and "
               f"friction.")


if __name__ == "__main__":
    Study.main(run, __file__)
