"""TireFit's leave-one-condition-out errors: each load, camber and pressure level left out in turn.

Independent references: the training errors are recomputed here from the fitted tire's forces; a
held-out error is compared with that of a separate fit made without the condition; a condition
without which the data hold no camber dependence must be reported (and warned about).
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from vehdyn.errors import VehdynWarning
from vehdyn.tire import fit_magic_formula
from vehdyn.tire.fitting.synthetic import sample_tire

from .conftest import shipped_tire

ANGLES = np.radians(np.linspace(-15.0, 15.0, 13))
STAGES = ("pure_lateral", "aligning")


def _quiet_fit(data, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", VehdynWarning)
        fit = fit_magic_formula(data, stages=STAGES, **kwargs)
    assert fit.validity["ok"].all(), fit.violations  # every fit of these tests is valid on its data's span
    return fit


@pytest.fixture(scope="module")
def three_by_three():
    """MF 6.1 tire at 0.6, 1.0, 1.4 FNOMIN and -3/0/+3 deg, 2 % noise, cross-validated."""
    truth = shipped_tire("MagicFormula61_Parameters")
    data = sample_tire(truth, loads=truth.nominal_load * np.array([0.6, 1.0, 1.4]), slip_angles=ANGLES,
                       slip_ratios=[], cambers=np.radians([-3.0, 0.0, 3.0]), combined_angles=[], noise=0.02, seed=4)
    return data, _quiet_fit(data)


def test_every_condition_and_channel_is_reported(three_by_three):
    data, fit = three_by_three
    table = fit.cross_validation
    loads = sorted(set(table.loc[table["variable"] == "load", "level"]))
    cambers = sorted(set(table.loc[table["variable"] == "camber", "level"]))
    np.testing.assert_allclose(loads, np.unique(data["fz"]))
    np.testing.assert_allclose(cambers, np.radians([-3.0, 0.0, 3.0]), atol=1e-12)
    assert set(table["channel"]) == {"fy", "mz"} and len(table) == 2 * (3 + 3)
    assert list(table["extrapolation"]) == [True, True, False, False, True, True] * 2
    assert set(table["level_text"]) >= {"camber -3.0 deg", "camber +0.0 deg", "camber +3.0 deg"}
    # the training error, recomputed from the fitted tire at each condition's points
    for _, row in table.iterrows():
        column = {"load": "fz", "camber": "gamma"}[row["variable"]]
        on = np.isclose(data[column], row["level"])
        model = fit.tire.forces(data["fz"][on].to_numpy(), 0.0, data["alpha"][on].to_numpy(),
                                data["gamma"][on].to_numpy(), data["vx"][on].to_numpy())
        measured = data[row["channel"]][on].to_numpy()
        expected = 100 * np.sqrt(np.mean((getattr(model, row["channel"]) - measured) ** 2)) / np.abs(measured).max()
        assert row["training_percent"] == pytest.approx(expected, rel=1e-9)
        assert row["points"] == on.sum() and row["held_out_percent"] >= 0.9 * row["training_percent"]
    assert "held out (each measured condition left out" in str(fit)
    assert fit.table()["held_out_max_percent"].notna().all()


def test_a_left_out_camber_matches_a_fit_without_it(three_by_three):
    """The refit of the cross-validation (from the fit's solution, the last step of each stage) and a
    separate fit from the default start on the data without camber +3 deg predict it alike."""
    data, fit = three_by_three
    on = np.isclose(data["gamma"], math.radians(3.0))
    separate = _quiet_fit(data[~on], cross_validation=False)
    held = data[on]
    model = separate.tire.forces(held["fz"].to_numpy(), 0.0, held["alpha"].to_numpy(), held["gamma"].to_numpy(),
                                 held["vx"].to_numpy())
    table = fit.cross_validation
    for channel in ("fy", "mz"):
        measured = held[channel].to_numpy()
        expected = 100 * np.sqrt(np.mean((getattr(model, channel) - measured) ** 2)) / np.abs(measured).max()
        row = table[(table["variable"] == "camber") & np.isclose(table["level"], math.radians(3.0))
                    & (table["channel"] == channel)]
        assert row["held_out_percent"].item() == pytest.approx(expected, rel=0.1), channel


def test_a_condition_the_fit_rests_on_is_warned_about():
    """Cambers 0 and +4 deg only: without +4 deg the data hold no camber dependence, so the refit
    keeps the start values (no camber effect) and misses +4 deg by far more than 3x the training
    error; the fit warns and names the condition."""
    truth = shipped_tire("MagicFormula61_Parameters")
    data = sample_tire(truth, loads=truth.nominal_load * np.array([0.8, 1.2]), slip_angles=ANGLES, slip_ratios=[],
                       cambers=np.radians([0.0, 4.0]), combined_angles=[])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", VehdynWarning)
        fit = fit_magic_formula(data, stages=STAGES)
    texts = [str(w.message) for w in caught if "held-out errors above 3x" in str(w.message)]
    assert len(texts) == 1 and "at camber +4.0 deg (extrapolated)" in texts[0]
    assert all(w.filename == __file__ for w in caught)
    table = fit.cross_validation
    row = table[(table["variable"] == "camber") & (table["level"] > 0) & (table["channel"] == "mz")].iloc[0]
    assert row["held_out_percent"] > 3 * max(row["training_percent"], 1.0)
    # the refit has no camber effect: its Mz at +4 deg is the zero-camber fit's there
    without = _quiet_fit(data[data["gamma"] == 0], cross_validation=False)
    held = data[data["gamma"] > 0]
    measured = held["mz"].to_numpy()
    model = without.tire.forces(held["fz"].to_numpy(), 0.0, held["alpha"].to_numpy(), held["gamma"].to_numpy())
    expected = 100 * np.sqrt(np.mean((model.mz - measured) ** 2)) / np.abs(measured).max()
    assert row["held_out_percent"] == pytest.approx(expected, rel=0.1)


def test_pressure_levels_are_left_out_in_turn():
    truth = shipped_tire("MagicFormula61_Parameters")
    p0 = truth.params["NOMPRES"]
    data = sample_tire(truth, loads=truth.nominal_load * np.array([0.7, 1.3]), slip_angles=ANGLES, slip_ratios=[],
                       cambers=[0.0], combined_angles=[], pressures=[0.8 * p0, 1.2 * p0])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", VehdynWarning)
        fit = fit_magic_formula(data, stages=("pure_lateral",))
    table = fit.cross_validation
    pressures = table.loc[table["variable"] == "pressure", "level"].to_numpy()
    np.testing.assert_allclose(pressures, [0.8 * p0, p0, 1.2 * p0], rtol=1e-9)
    assert list(table.loc[table["variable"] == "pressure", "level_text"]) == [
        f"pressure {f * p0 / 1e5:.2f} bar" for f in (0.8, 1.0, 1.2)]
    middle = table[(table["variable"] == "pressure") & np.isclose(table["level"], p0)]
    assert middle["held_out_percent"].item() < 1.0  # between two measured pressures: interpolated


def test_off_gives_no_table():
    truth = shipped_tire("MagicFormula61_Parameters")
    data = sample_tire(truth, loads=[4000.0, 6000.0], slip_angles=ANGLES, slip_ratios=[], cambers=[0.0],
                       combined_angles=[])
    fit = _quiet_fit(data, cross_validation=False)
    assert fit.cross_validation is None and fit.held_out is None and "held out" not in str(fit)


def test_plots_show_the_fit_between_the_measured_conditions(three_by_three):
    """The camber figure's dashed curves are the fitted tire at the cambers midway between the
    measured ones; the cross-validation figure's bars are the table's errors."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    data, fit = three_by_three
    figures = fit.plot()
    assert {"pure_lateral", "aligning", "camber", "cross_validation"} <= set(figures)
    load = float(np.unique(data["fz"])[1])  # the load nearest FNOMIN
    for ax, channel in zip(figures["camber"].axes, ("fy", "mz")):
        dashed = [line for line in ax.get_lines() if line.get_linestyle() == "--" and len(line.get_xdata())]
        assert len(dashed) == 2
        for line, gamma in zip(dashed, np.radians([-1.5, 1.5])):
            alpha = np.radians(line.get_xdata())
            expected = getattr(fit.tire.forces(np.full(alpha.size, load), 0.0, alpha, gamma,
                                               float(np.median(data["vx"]))), channel)
            np.testing.assert_allclose(line.get_ydata(), expected, rtol=1e-10, atol=1e-9)
    table = fit.cross_validation
    for ax, channel in zip(figures["cross_validation"].axes, ("fy", "mz")):
        heights = [patch.get_height() for patch in ax.patches]
        rows = table[table["channel"] == channel]
        np.testing.assert_allclose(heights, list(rows["held_out_percent"]) + list(rows["training_percent"]))
    plt.close("all")
