"""fit_magic_formula: recovery of shipped tires from the default start, diagnostics, bad input.

The reference is the shipped .tir file the data are sampled from (vehdyn's Magic Formula is
validated against MFeval); errors are r.m.s. over the peak force of the noise-free truth.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from vehdyn.errors import ParameterError, TirFileError, VehdynWarning
from vehdyn.tire import MagicFormula, TireFit, fit_magic_formula, read_tir
from vehdyn.tire.fitting.synthetic import sample_tire

from .conftest import shipped_tire

PURE = ("pure_longitudinal", "pure_lateral")
ANGLES = np.radians(np.linspace(-15.0, 15.0, 21))
RATIOS = np.linspace(-0.3, 0.3, 21)


def _fit(data, **kwargs):
    """The fit, whose validity conditions hold on the grid spanning the data (unless it is stopped
    after one evaluation)."""
    kwargs.setdefault("cross_validation", False)  # tested in test_tire_fitting_cross_validation.py
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", VehdynWarning)  # no pressure sweep: PPX*, PPY* not identifiable
        fit = fit_magic_formula(data, **kwargs)
    if kwargs.get("max_nfev", 200) > 1:
        assert fit.validity["ok"].all(), fit.violations
    return fit


def _relative_rms(tire, frame, truth, outputs=("fx", "fy")):
    """R.m.s. error over the peak of the truth, per output; on pure-slip data only the force of each
    sweep (Fx of the slip-ratio sweeps, Fy of the slip-angle sweeps: the pure-slip stages fit those)."""
    model = tire.forces(frame["fz"].to_numpy(), frame["kappa"].to_numpy(), frame["alpha"].to_numpy(),
                        frame["gamma"].to_numpy(), frame["vx"].to_numpy())
    sweep = frame["sweep"].to_numpy()
    own = {"fx": sweep != "lateral", "fy": sweep != "longitudinal"}
    errors = {}
    for o in outputs:
        on = own[o]
        error = getattr(model, o)[on] - truth[o][on]
        errors[o] = float(np.sqrt(np.mean(error**2)) / np.max(np.abs(truth[o][on])))
    return errors


def _pure(frame):
    return frame[frame["sweep"] != "combined"]


@pytest.mark.parametrize("name", ["MagicFormula61_Parameters", "MagicFormula52_Parameters"])
@pytest.mark.parametrize("noise, tolerance", [(0.0, 0.01), (0.03, 0.03)])
def test_recovers_pure_slip_with_load_and_camber(name, noise, tolerance):
    """4 loads, slip angle +-15 deg, slip ratio +-0.3, camber 0/+-4 deg, from the default start:
    within 1 % of the peak force (3 % with 3 % noise), on the data and on held-out loads and slips."""
    truth_tire = shipped_tire(name)
    frame = _pure(sample_tire(truth_tire, slip_angles=ANGLES, slip_ratios=RATIOS, noise=noise, seed=7))
    fit = _fit(frame, version=truth_tire.version, stages=PURE)
    truth = {o: v[frame.index] for o, v in frame.attrs["truth"].items()}
    errors = _relative_rms(fit.tire, frame, truth)
    assert errors["fx"] < tolerance and errors["fy"] < tolerance, errors
    held = _pure(sample_tire(truth_tire, loads=truth_tire.nominal_load * np.array([0.6, 1.0, 1.4]),
                             slip_angles=ANGLES[:-1] + np.radians(0.75), slip_ratios=RATIOS[:-1] + 0.015,
                             cambers=np.radians([-2.0, 3.0])))
    held_errors = _relative_rms(fit.tire, held, {o: v[held.index] for o, v in held.attrs["truth"].items()})
    assert held_errors["fx"] < tolerance and held_errors["fy"] < tolerance, held_errors
    for stage in PURE:
        result = fit.stages[stage]
        assert result.steps == ("nominal", "load", "camber")
        output = result.outputs[0]
        assert result.nrms[output] < 0.01 + noise and result.r2[output] > 0.99  # the residual includes the noise


def test_default_start_is_not_the_truth():
    """The start is read from the data (peak, slope at zero): the fit has something to do."""
    truth_tire = shipped_tire("MagicFormula61_Parameters")
    frame = _pure(sample_tire(truth_tire, slip_angles=ANGLES, slip_ratios=RATIOS, cambers=[0.0]))
    fit = _fit(frame, stages=PURE, max_nfev=1)
    errors = _relative_rms(fit.tire, frame, {o: v[frame.index] for o, v in frame.attrs["truth"].items()})
    assert max(errors.values()) > 0.01


def test_combined_slip_recovered_on_held_out_points():
    truth_tire = shipped_tire("MagicFormula61_Parameters")
    frame = sample_tire(truth_tire, slip_angles=ANGLES, slip_ratios=RATIOS, cambers=[0.0],
                        combined_angles=np.radians([-6.0, -2.0, 3.0, 8.0]))
    fit = _fit(frame, stages=PURE + ("combined",))
    held = sample_tire(truth_tire, loads=truth_tire.nominal_load * np.array([0.7, 1.3]), slip_angles=[],
                       cambers=[0.0], combined_angles=np.radians([-4.0, 5.0]))
    held = held[held["sweep"] == "combined"]
    errors = _relative_rms(fit.tire, held, {o: v[held.index] for o, v in held.attrs["truth"].items()})
    assert errors["fx"] < 0.01 and errors["fy"] < 0.01, errors
    assert fit.stages["combined"].outputs == ("fx", "fy", "mz")


def test_start_from_a_different_tire_converges():
    """Data of the MF 6.1 example tire, start from the 185/80 R14 MF 5.2 file."""
    truth_tire = shipped_tire("MagicFormula61_Parameters")
    frame = _pure(sample_tire(truth_tire, slip_angles=ANGLES, slip_ratios=RATIOS, cambers=[0.0]))
    start = shipped_tire("mf_185_80R14")
    fit = _fit(frame, start=start, stages=PURE)
    assert fit.tire.version == "5.2" and fit.tire.nominal_load == start.nominal_load
    errors = _relative_rms(fit.tire, frame, {o: v[frame.index] for o, v in frame.attrs["truth"].items()})
    assert errors["fx"] < 0.01 and errors["fy"] < 0.01, errors
    assert any("widened the start file's ranges" in m for m in fit.messages)


@pytest.fixture(scope="module")
def small_fit():
    frame = _pure(sample_tire(shipped_tire("MagicFormula61_Parameters"), slip_angles=ANGLES, slip_ratios=RATIOS,
                              cambers=[0.0]))
    return _fit(frame, stages=PURE + ("aligning", "combined")), frame


def test_to_tir_round_trip_is_exact(small_fit, tmp_path):
    fit, frame = small_fit
    path = fit.to_tir(tmp_path / "fitted.tir")
    back = MagicFormula(read_tir(path))
    for name, value in fit.coefficients.items():
        assert back.params[name] == value, name
    args = (frame["fz"].to_numpy(), frame["kappa"].to_numpy(), frame["alpha"].to_numpy(), 0.0, 16.6)
    for a, b in zip(fit.tire.forces(*args), back.forces(*args)):  # equal coefficients, the same code: bitwise
        np.testing.assert_array_equal(a, b)


def test_skipped_stages_and_report(small_fit):
    fit, _ = small_fit
    assert isinstance(fit, TireFit)
    skipped = fit.stages["combined"].skipped
    assert "no combined points" in skipped
    assert "stage aligning skipped" not in str(fit)
    table = fit.table()
    assert set(table["stage"]) == {"pure_longitudinal", "pure_lateral", "aligning", "combined"}
    assert "pure_lateral" in str(fit) and fit.stages["pure_lateral"].condition > 1


def test_stage_without_its_columns_is_skipped_with_a_message():
    frame = _pure(sample_tire(shipped_tire("MagicFormula61_Parameters"), slip_angles=ANGLES, slip_ratios=RATIOS,
                              cambers=[0.0])).drop(columns=["mz", "fx"])
    fit = _fit(frame, stages=("pure_longitudinal", "aligning", "pure_lateral"))
    assert "needs the columns fx, fz, kappa" in fit.stages["pure_longitudinal"].skipped
    assert "missing or all zero: mz" in fit.stages["aligning"].skipped
    assert fit.stages["pure_lateral"].skipped is None


def test_nan_rows_dropped_with_count():
    frame = _pure(sample_tire(shipped_tire("MagicFormula61_Parameters"), slip_angles=ANGLES, slip_ratios=RATIOS,
                              cambers=[0.0])).reset_index(drop=True)
    frame.loc[[3, 50, 51], "fy"] = np.nan
    fit = _fit(frame, stages=("pure_lateral",))
    assert "dropped 3 of" in fit.messages[0]


def test_identifiability_warnings():
    frame = _pure(sample_tire(shipped_tire("MagicFormula61_Parameters"), loads=[4000.0], slip_angles=ANGLES,
                              cambers=[0.0]))
    with pytest.warns(VehdynWarning) as record:
        fit = fit_magic_formula(frame, stages=("pure_lateral",))
    texts = [str(w.message) for w in record]
    assert "stage pure_lateral: PDY2, PEY2, PKY2, PKY4, PHY2, PVY2 not identifiable (no fz sweep" in texts[0]
    assert any("PDY3, PEY4" in t and "no gamma sweep" in t for t in texts)
    assert all(w.filename == __file__ for w in record)  # reported where fit_magic_formula was called
    assert fit.stages["pure_lateral"].not_identifiable["PDY3"] == "no gamma sweep in the pure_lateral data"


def test_fixed_and_bounds():
    truth_tire = shipped_tire("MagicFormula61_Parameters")
    frame = _pure(sample_tire(truth_tire, slip_angles=ANGLES, cambers=[0.0]))
    fit = _fit(frame, start=truth_tire, stages=("pure_lateral",), fixed=("PCY1",), bounds={"PDY1": (0.5, 0.9)})
    result = fit.stages["pure_lateral"]
    assert "PCY1" not in result.coefficients and fit.tire.params["PCY1"] == truth_tire.params["PCY1"]
    assert result.coefficients["PDY1"] == pytest.approx(0.9) and "PDY1" in result.at_bounds


def test_bad_input():
    frame = _pure(sample_tire(shipped_tire("MagicFormula61_Parameters"), loads=[4000.0], slip_angles=ANGLES[:5],
                              slip_ratios=[], cambers=[0.0]))
    with pytest.raises(ParameterError, match="5 points .* for 7 coefficients"):
        _fit(frame, stages=("pure_lateral",))
    with pytest.raises(ParameterError, match="version"):
        fit_magic_formula(frame, version="7.0")
    with pytest.raises(ParameterError, match="unknown stage 'lateral'"):
        fit_magic_formula(frame, stages=("lateral",))
    with pytest.raises(ParameterError, match="'XYZ1' is not a coefficient"):
        fit_magic_formula(frame, fixed=("XYZ1",))
    with pytest.raises(ParameterError, match="lower must be < upper"):
        fit_magic_formula(frame, bounds={"PDY1": (2.0, 1.0)})
    with pytest.raises(ParameterError, match="weights must be 5 finite values"):
        fit_magic_formula(frame, weights=np.ones(3))
    with pytest.raises(ParameterError, match="needs a column 'fz'"):
        fit_magic_formula(frame.drop(columns=["fz"]))
    with pytest.raises(ParameterError, match="data must be a DataFrame"):
        fit_magic_formula([1, 2, 3])
    for value in (-1e-3, math.nan, math.inf, "0.1", True):
        with pytest.raises(ParameterError, match="regularization must be a finite number >= 0") as error:
            fit_magic_formula(frame, regularization=value)
        assert error.value.key == "regularization"
    with pytest.raises(ParameterError, match="validity must be True or False, got 'yes'"):
        fit_magic_formula(frame, validity="yes")
    with pytest.raises(ParameterError, match="cross_validation must be True or False, got 1"):
        fit_magic_formula(frame, cross_validation=1)
    with pytest.raises(ParameterError, match="max_nfev must be an integer >= 1, got 0"):
        fit_magic_formula(frame, max_nfev=0)
    with pytest.raises(TirFileError, match="no_such_tire: cannot read the file"):
        fit_magic_formula(frame, reference="no_such_tire")  # as start= does


@pytest.mark.parametrize("stage, outputs", [("pure_longitudinal", ("fx",)), ("pure_lateral", ("fy",)),
                                            ("combined", ("fx", "fy", "mz")), ("overturning", ("mx",)),
                                            ("rolling_resistance", ("my",))])
def test_fit_model_path_equals_magic_formula_forces(stage, outputs):
    """The fit's cheap evaluation (state computed once, stage functions only) gives exactly what
    MagicFormula.forces gives, for the shipped coefficients and for changed ones."""
    from vehdyn.tire.fitting.magic_formula_fit import _Problem

    tire = shipped_tire("MagicFormula61_Parameters")
    frame = sample_tire(tire, slip_angles=ANGLES, slip_ratios=RATIOS)
    if stage == "pure_longitudinal":
        frame = frame[frame["sweep"] == "longitudinal"]
    elif stage == "pure_lateral":
        frame = frame[frame["sweep"] == "lateral"]
    rows = {k: frame[k].to_numpy() for k in ("fz", "kappa", "alpha", "gamma", "vx", "fx", "fy", "mz", "mx", "my")}
    rows["pressure"] = np.full(len(frame), tire._c.INFLPRES)
    changed = {"pure_longitudinal": {"PDX1": 1.3}, "pure_lateral": {"PKY1": -20.0},
               "combined": {"RBY1": 12.0, "SSZ1": 0.01}, "overturning": {"QSX3": 0.5},
               "rolling_resistance": {"QSY1": 0.02}}[stage]
    problem = _Problem(tire._c, stage, rows, outputs, tuple(changed), None)
    for values in ({}, changed):
        c = tire._c._replace(**values)
        reference = MagicFormula.__new__(MagicFormula)
        reference.__dict__.update(tire.__dict__, _c=c)
        expected = reference.forces(rows["fz"], rows["kappa"], rows["alpha"], rows["gamma"], rows["vx"],
                                    backend="numpy")
        for out, got in zip(outputs, problem.model(c)):  # both the NumpyOps equation functions: bitwise
            np.testing.assert_array_equal(got, getattr(expected, out), err_msg=f"{out} {values}")


def test_pressure_dependence_recovered():
    """Sweeps at 0.8 and 1.2 times the nominal pressure: the pressure step runs and recovers Fx, Fy
    (MagicFormula.evaluate with pressure as the reference)."""
    truth_tire = shipped_tire("MagicFormula61_Parameters")
    p0 = truth_tire._c.NOMPRES
    frame = _pure(sample_tire(truth_tire, slip_angles=ANGLES, slip_ratios=RATIOS, cambers=[0.0],
                              pressures=[0.8 * p0, 1.2 * p0]))
    fit = _fit(frame, stages=PURE)
    assert fit.stages["pure_lateral"].steps == ("nominal", "load", "pressure")
    assert "PPY1" in fit.stages["pure_lateral"].coefficients and "PPX1" in fit.stages["pure_longitudinal"].coefficients
    held = _pure(sample_tire(truth_tire, loads=[truth_tire.nominal_load], slip_angles=ANGLES[:-1] + np.radians(0.75),
                             slip_ratios=RATIOS[:-1] + 0.015, cambers=[0.0], pressures=[0.9 * p0, 1.1 * p0]))
    held = held[held["pressure"] != truth_tire._c.INFLPRES]
    sweep = held["sweep"].to_numpy()
    model = fit.tire.evaluate(held["fz"].to_numpy(), held["kappa"].to_numpy(), held["alpha"].to_numpy(), 0.0,
                              held["vx"].to_numpy(), pressure=held["pressure"].to_numpy())
    for out, on in (("fx", sweep == "longitudinal"), ("fy", sweep == "lateral")):
        truth = held.attrs["truth"][out][held.index][on]
        error = np.sqrt(np.mean((getattr(model, out)[on] - truth) ** 2)) / np.max(np.abs(truth))
        assert error < 0.01, (out, error)


def test_condition_warning_names_held_coefficients():
    """Camber at 0 and +-4 deg only: gamma and gamma*|gamma| are proportional, so the residual-torque
    pairs QDZ8/QDZ10 and QDZ9/QDZ11 cannot be told apart: the fit holds the higher-order QDZ10, QDZ11
    at their start values (0) and names them; with +-2 deg added they are determined, nothing is
    held, and the fit recovers the file's aligning moment."""
    truth_tire = shipped_tire("MagicFormula61_Parameters")
    results = {}
    for cambers in ((0.0, -4.0, 4.0), (0.0, -4.0, -2.0, 2.0, 4.0)):
        frame = sample_tire(truth_tire, slip_angles=ANGLES, slip_ratios=[], cambers=np.radians(cambers),
                            combined_angles=[])
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", VehdynWarning)
            fit = fit_magic_formula(frame, stages=("pure_lateral", "aligning"), cross_validation=False)
        results[len(cambers)] = ([str(w.message) for w in caught if "stage aligning: the data do not" in str(w.message)],
                                 fit.stages["aligning"], fit)
    texts, stage, _ = results[3]
    assert len(texts) == 1 and stage.condition > 1e8
    assert {"QDZ10", "QDZ11"} <= set(stage.held) and "QDZ10" in texts[0] and "held at their start values" in texts[0]
    assert set(stage.weakest) & {"QDZ8", "QDZ10", "QDZ9", "QDZ11"}
    texts, stage, fit = results[5]
    assert not any("QDZ" in t for t in texts) and stage.condition < 1e4
    assert not set(stage.held) & {"QDZ8", "QDZ9", "QDZ10", "QDZ11"}
    assert stage.nrms["mz"] < 1e-3
    alpha = np.radians(np.linspace(-15, 15, 61))
    for gamma in np.radians([1.0, 3.0]):
        error = fit.tire.forces(4000.0, 0.0, alpha, gamma).mz - truth_tire.forces(4000.0, 0.0, alpha, gamma).mz
        assert np.max(np.abs(error)) < 0.01 * np.max(np.abs(frame["mz"]))


def test_zero_weights_remove_corrupted_rows():
    """Rows with weight 0 do not count: corrupted side forces on them leave the fit exact."""
    truth_tire = shipped_tire("MagicFormula61_Parameters")
    frame = _pure(sample_tire(truth_tire, slip_angles=ANGLES, slip_ratios=RATIOS, cambers=[0.0]))
    truth = {o: v[frame.index] for o, v in frame.attrs["truth"].items()}
    frame = frame.reset_index(drop=True)
    bad = (frame["sweep"] == "lateral").to_numpy() & (np.arange(len(frame)) % 5 == 0)
    frame.loc[bad, "fy"] += 2000.0
    weights = np.where(bad, 0.0, 1.0)
    errors = {w is None: _relative_rms(_fit(frame, stages=("pure_lateral",), weights=w).tire, frame, truth, ("fy",))
              for w in (None, weights)}
    assert errors[False]["fy"] < 0.001 < 0.01 < errors[True]["fy"], errors


def test_start_by_name_path_and_bad_file(tmp_path):
    from vehdyn.errors import TirFileError

    frame = _pure(sample_tire(shipped_tire("MagicFormula52_Parameters"), loads=[4000.0, 8000.0], slip_angles=ANGLES,
                              slip_ratios=[], cambers=[0.0]))
    by_name = _fit(frame, start="mf_185_80R14", stages=("pure_lateral",))
    assert by_name.tire.nominal_load == shipped_tire("mf_185_80R14").nominal_load
    bad = tmp_path / "bad.tir"
    bad.write_text("[MODEL]\nFITTYP = 99\n")
    with pytest.raises(TirFileError, match="no supported Magic Formula version"):
        _fit(frame, start=bad, stages=("pure_lateral",))
