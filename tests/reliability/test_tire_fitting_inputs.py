"""Tire data and fits at the door (issue 32, "Units"): columns in the wrong unit, fewer points than
coefficients, files with huge fields. Each is refused with a ParameterError (or a TirFileError for
a file) that names the column and suggests the unit; the CLI exits 2 with that one line.

The reference for "the wrong unit" is the tire the data are sampled from: slip angles in degrees
read as radians gave a brush tire with about 1/20 of the real cornering stiffness (issue 32); with
the unit stated the fit recovers it.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from vehdyn.cli import main
from vehdyn.errors import ParameterError, TirFileError, VehdynWarning
from vehdyn.tire import MagicFormula, fit_brush, fit_linear, fit_magic_formula, load_tire, read_tire_data
from vehdyn.tire.fitting.synthetic import sample_tire
from vehdyn.tire.tire_data import PLAUSIBLE_RANGES, check_units

FITTERS = {"fit_magic_formula": lambda data, **kw: fit_magic_formula(data, stages=("pure_lateral",),
                                                                    cross_validation=False, **kw),
           "fit_brush": fit_brush, "fit_linear": fit_linear}


@pytest.fixture(scope="module")
def tire():
    return load_tire("MagicFormula61_Parameters")


@pytest.fixture(scope="module")
def pure(tire):
    """Pure-slip sweeps of the MF 6.1 tire at three loads, zero camber (ISO-W, SI)."""
    return sample_tire(tire, loads=[3000.0, 5000.0, 7000.0], slip_angles=np.radians(np.linspace(-12, 12, 17)),
                       slip_ratios=np.linspace(-0.2, 0.2, 17), cambers=[0.0], combined_angles=[], vx=16.7)


def _scaled(frame, column, factor):
    frame = frame.copy()
    frame[column] = frame[column] * factor
    return frame


@pytest.mark.parametrize("name", list(FITTERS))
@pytest.mark.parametrize("column, factor, unit, words", [
    ("alpha", 180 / math.pi, "deg", "slip angles reach"),
    ("kappa", 100.0, "%", "slip ratios reach"),
    ("gamma", 180 / math.pi, "deg", "inclination angles reach"),
    ("fz", 1e-3, "kN", "the largest load is"),
])
def test_fitters_refuse_a_column_in_another_unit(pure, name, column, factor, unit, words):
    data = _scaled(pure, column, factor)
    if column == "gamma":
        data["gamma"] = math.radians(4.0) * factor  # a cambered test, in degrees
    with pytest.raises(ParameterError, match=rf"data column '{column}': {words} .*units={{'{column}': '{unit}'}}") \
            as error:
        FITTERS[name](data)
    assert error.value.key == column


@pytest.mark.parametrize("name", list(FITTERS))
def test_stating_the_unit_converts_it(pure, tire, name):
    """Degrees with units={'alpha': 'deg'} fit as radians do: the cornering stiffness of the brush
    within 1e-9 of the fit on radians, and within 25 % of the Magic Formula's (1/57 without the unit)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", VehdynWarning)
        in_degrees = FITTERS[name](_scaled(pure, "alpha", 180 / math.pi), units={"alpha": "deg"})
        in_radians = FITTERS[name](pure)
    probe = (5000.0, 0.0, math.radians(1.0))
    assert in_degrees.tire.forces(*probe).fy == pytest.approx(in_radians.tire.forces(*probe).fy, rel=1e-9)
    assert in_degrees.tire.forces(*probe).fy == pytest.approx(tire.forces(*probe).fy, rel=0.25)


def test_negative_loads_suggest_sae_axes(pure):
    data = _scaled(pure, "fz", -1.0)
    for fit in FITTERS.values():
        with pytest.raises(ParameterError, match=r"loads are negative .* SAE tire axes .*convention='SAE'"):
            fit(data)


@pytest.mark.parametrize("column, values, match", [
    ("fz", [2e6, 3e6], r"a load of 3e\+06 N is beyond any tire's"),
    ("pressure", [2.4, 2.6], r"pressures of at most 2.6 Pa .* look like bar; .*units={'pressure': 'bar'}"),
    ("pressure", [33.0, 36.0], r"look like psi"),
    ("pressure", [230.0, 260.0], r"look like kPa"),
    ("pressure", [2e8, 2e8], r"beyond any tire's pressure"),
    ("vx", [200.0, 250.0], r"speeds reach 250 m/s, beyond \+-150: they look like km/h"),
])
def test_implausible_loads_pressures_and_speeds(column, values, match):
    columns = {"fz": np.array([4000.0, 5000.0]), column: np.array(values)}
    with pytest.raises(ParameterError, match=match) as error:
        check_units(columns)
    assert error.value.key == column
    check_units(columns, stated=[column])  # a stated unit is taken as stated


def test_ranges_are_physical():
    """The bounds are the physical ones: +-pi/2 for angles, the Magic Formula's +-1.5 for slip ratios."""
    assert PLAUSIBLE_RANGES["alpha"] == (-math.pi / 2, math.pi / 2)
    assert PLAUSIBLE_RANGES["gamma"] == (-math.pi / 2, math.pi / 2)
    assert PLAUSIBLE_RANGES["kappa"] == (-1.5, 1.5)
    check_units({"fz": [100.0], "alpha": [-1.5, 1.5], "kappa": [-1.0, 1.5], "gamma": [0.9]})  # a motorcycle


@pytest.mark.parametrize("units, match", [
    ({"slip": "deg"}, r"units\['slip'\]: the data have no column 'slip'"),
    ({"alpha": "furlong"}, r"units\['alpha'\]: unknown angle unit 'furlong'"),
    ("deg", r"units must be a mapping"),
])
def test_bad_units_argument(pure, units, match):
    with pytest.raises(ParameterError, match=match):
        fit_brush(pure, units=units)


def test_read_tire_data_judges_unlabelled_columns(tmp_path, pure):
    """An unlabelled column in degrees is refused with the file and the unit to state; a header unit
    or units= reads it; the frame remembers which units were stated, and the fit accepts them."""
    frame = _scaled(pure, "alpha", 180 / math.pi)[["fz", "kappa", "alpha", "fy", "mz"]]
    plain = tmp_path / "plain.csv"
    frame.to_csv(plain, index=False)
    with pytest.raises(ParameterError, match=r"plain.csv: data column 'alpha': slip angles reach .*deg") as error:
        read_tire_data(plain)
    assert error.value.key == "alpha"
    read = read_tire_data(plain, units={"alpha": "deg"})
    np.testing.assert_allclose(read["alpha"], pure["alpha"], rtol=1e-12)
    assert read.attrs["stated_units"] == ["alpha"]
    labelled = tmp_path / "labelled.csv"
    frame.rename(columns={"alpha": "alpha [deg]"}).to_csv(labelled, index=False)
    np.testing.assert_allclose(read_tire_data(labelled)["alpha"], pure["alpha"], rtol=1e-12)
    fit_brush(read)  # stated units are not judged again
    insisted = tmp_path / "insisted.csv"
    frame.rename(columns={"alpha": "alpha [rad]"}).to_csv(insisted, index=False)
    assert read_tire_data(insisted)["alpha"].abs().max() == pytest.approx(12.0)  # the user said radians


def test_percent_slip_ratio_in_a_file(tmp_path, pure):
    path = tmp_path / "percent.csv"
    _scaled(pure, "kappa", 100.0)[["fz", "kappa", "alpha", "fx", "fy"]].to_csv(path, index=False)
    with pytest.raises(ParameterError, match=r"data column 'kappa': slip ratios reach -?20 -, .*percent"):
        read_tire_data(path)
    np.testing.assert_allclose(read_tire_data(path, units={"kappa": "%"})["kappa"], pure["kappa"], atol=1e-15)


def test_sae_csv_without_the_convention_is_refused(tmp_path, pure):
    path = tmp_path / "sae.csv"
    sae = pure[["fz", "alpha", "fy"]].copy()
    sae["fz"] = -sae["fz"]
    sae.to_csv(path, index=False)
    with pytest.raises(ParameterError, match=r"convention='SAE'"):
        read_tire_data(path)
    assert (read_tire_data(path, convention="SAE")["fz"] > 0).all()


def test_fewer_points_than_coefficients(pure):
    """fit_brush on one point returned an arbitrary tire (issue 32); now every fitter refuses."""
    one = pure[(pure["sweep"] == "lateral")].iloc[[3]]
    with pytest.raises(ParameterError, match=r"fit_brush: 2 measured values .* for 3 coefficients") as error:
        fit_brush(one)
    assert error.value.key == "data"
    with pytest.raises(ParameterError, match=r"fit_brush: 1 measured values .* for 2 coefficients"):
        fit_brush(one.drop(columns=["mz"]), contact_half_length=0.1)
    with pytest.raises(ParameterError, match=r"fit_linear: 1 points"):
        fit_linear(one, max_slip_angle=1.0)
    with pytest.raises(ParameterError, match=r"stage pure_lateral: 1 points \(1 values\) for 7 coefficients"):
        fit_magic_formula(one, stages=("pure_lateral",), cross_validation=False)
    two = pure[(pure["sweep"] == "lateral")].iloc[[9, 13]]  # 1.5 and 7.5 deg x (fy, mz): 4 values, 3 coefficients
    assert fit_brush(two).stages["brush"].n_points == 2


def test_huge_csv_fields_are_a_file_error(tmp_path):
    """The csv module's field limit (131072 characters) raised a bare _csv.Error."""
    cases = {
        "field.csv": ("fz,alpha,fy\n4000,0.1," + "9" * 200_000 + "\n", r"huge.*line 2: not a readable CSV row"),
        "quoted.csv": ('fz,alpha,fy\n4000,0.1,"' + "x" * 200_000 + '"\n', r"line 2: not a readable CSV row"),
        "header.csv": ("fz,alpha," + "y" * 200_000 + "\n1,2,3\n", r"line 1: the header line has 200009 characters"),
        "text.csv": ("fz,alpha,fy\n4000,0.1," + "z" * 50_000 + "\n",
                     r"line 2: column 'fy': 'z{40}\.\.\. \(50000 characters\)' is not a number"),
    }
    for name, (text, match) in cases.items():
        path = tmp_path / "huge" / name
        path.parent.mkdir(exist_ok=True)
        path.write_text(text)
        with pytest.raises(TirFileError, match=match):
            read_tire_data(path)


def test_a_sniffer_failure_falls_back_to_the_delimiter(tmp_path):
    path = tmp_path / "odd.csv"
    path.write_text("fz;alpha;fy;;\n4000;0.1;-300;;\n")
    frame = read_tire_data(path)
    assert frame["fy"].tolist() == [-300.0]


@pytest.fixture(scope="module")
def degrees_file(tmp_path_factory, pure):
    path = tmp_path_factory.mktemp("cli") / "degrees.csv"
    _scaled(pure, "alpha", 180 / math.pi).drop(columns=["sweep"]).to_csv(path, index=False)
    return path


def test_cli_refuses_degrees_with_one_line(degrees_file, tmp_path, capsys):
    """`vehdyn tire-fit` fitted degrees as radians and exited 0 (issue 32); now exit 2, one line."""
    out = tmp_path / "fitted.tir"
    assert main(["tire-fit", str(degrees_file), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "data column 'alpha'" in err and "--unit alpha=deg" in err
    assert not out.exists()
    assert main(["tire-fit", str(degrees_file), "--out", str(out), "--unit", "alpha"]) == 2
    assert "--unit takes COLUMN=UNIT" in capsys.readouterr().err
    assert main(["tire-fit", str(degrees_file), "--out", str(out), "--unit", "alpha=parsec"]) == 2
    assert "unknown angle unit 'parsec'" in capsys.readouterr().err


def test_cli_with_the_unit_fits(degrees_file, pure, tmp_path, capsys, tire):
    out = tmp_path / "fitted.tir"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", VehdynWarning)
        assert main(["tire-fit", str(degrees_file), "--out", str(out), "--unit", "alpha=deg",
                     "--no-cross-validation"]) == 0
    text = capsys.readouterr().out
    assert f"wrote {out}" in text and "held out" not in text
    fitted = MagicFormula.from_tir(out)
    alpha = np.radians(np.linspace(-10, 10, 11))
    error = fitted.forces(5000.0, 0.0, alpha).fy - tire.forces(5000.0, 0.0, alpha).fy
    assert np.max(np.abs(error)) < 0.01 * np.max(np.abs(pure["fy"]))
