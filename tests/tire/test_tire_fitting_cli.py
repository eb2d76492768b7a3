"""`vehdyn tire-fit`: data file in, .tir and figures out; bad input reported in one line (exit 2)."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from vehdyn.cli import main
from vehdyn.errors import VehdynWarning
from vehdyn.tire import load_tire
from vehdyn.tire.fitting.synthetic import sample_tire


@pytest.fixture(scope="module")
def data_file(tmp_path_factory):
    tire = load_tire("MagicFormula61_Parameters")
    frame = sample_tire(tire, slip_angles=np.radians(np.linspace(-15, 15, 13)), slip_ratios=np.linspace(-0.3, 0.3, 13),
                        cambers=[0.0])
    path = tmp_path_factory.mktemp("cli") / "data.csv"
    frame.drop(columns=["sweep"]).to_csv(path, index=False)
    return path, tire, frame


def test_tire_fit_writes_tir_and_figures(data_file, tmp_path, capsys):
    path, tire, frame = data_file
    out = tmp_path / "out" / "fitted.tir"
    with warnings.catch_warnings():
        warnings.simplefilter("error", VehdynWarning)  # the command reports them in its table instead
        assert main(["tire-fit", str(path), "--out", str(out)]) == 0
    captured = capsys.readouterr()
    text = captured.out
    assert "pure_lateral" in text and f"wrote {out}" in text
    assert "PPY1, PPY2, PPY3, PPY4, PPY5 not identifiable (no pressure sweep" in text
    assert "held out (each measured condition left out of the fit in turn" in text  # 4 loads, cross-validated
    assert "validity: all 18 conditions hold" in text
    assert "VehdynWarning" not in captured.err
    fitted = load_tire(out)
    lateral = frame[frame["sweep"] == "lateral"]
    args = (lateral["fz"].to_numpy(), 0.0, lateral["alpha"].to_numpy())
    error = fitted.forces(*args).fy - tire.forces(*args).fy
    assert np.sqrt(np.mean(error**2)) < 0.01 * np.max(np.abs(lateral["fy"]))
    for stage in ("pure_longitudinal", "pure_lateral", "aligning", "combined", "overturning", "rolling_resistance",
                  "cross_validation"):
        assert (out.parent / f"fitted_{stage}.png").stat().st_size > 0


def test_tire_fit_bad_data_is_one_line(tmp_path, capsys):
    bad = tmp_path / "bad.csv"
    bad.write_text("fz,alpha,fy\n4000,0.1,x\n")
    assert main(["tire-fit", str(bad), "--out", str(tmp_path / "f.tir")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "line 2: column 'fy': 'x' is not a number" in err
    assert main(["tire-fit", str(tmp_path / "missing.csv")]) == 2
    assert "No such file" in capsys.readouterr().err
