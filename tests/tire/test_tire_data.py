"""read_tire_data: CSV and test-consortium layouts against known values, and every error path."""

from __future__ import annotations

import math

import numpy as np
import pytest

from vehdyn.errors import ParameterError, TirFileError
from vehdyn.tire import read_tire_data

LBF = 4.4482216152605  # N per lbf (exact by definition of the pound-force)
FT_LB = 0.3048 * LBF  # N*m per ft*lbf
PSI = LBF / 0.0254**2  # Pa per psi

# Known ISO-W SI values of five points
ISO = {
    "fz": np.array([2000.0, 4000.0, 4000.0, 6000.0, 6000.0]),
    "kappa": np.array([0.0, 0.05, -0.1, 0.0, 0.2]),
    "alpha": np.radians([-6.0, 0.0, 2.0, 8.0, -1.0]),
    "gamma": np.radians([0.0, 2.0, -4.0, 0.0, 1.0]),
    "fx": np.array([0.0, 1500.0, -3000.0, 10.0, 4500.0]),
    "fy": np.array([2100.0, -50.0, -1200.0, -5100.0, 600.0]),
    "mz": np.array([-40.0, 1.0, 25.0, 80.0, -7.0]),
    "mx": np.array([3.0, -2.0, 4.0, 10.0, -1.0]),
}


def test_consortium_layout_from_known_values(tmp_path):
    """A run file in SAE axes and lbf/psi/deg/mph/ft-lb reads back to the ISO-W SI values.

    The file is built by hand from the SAE definitions (y right, z down: FY, FZ, MZ and SA
    change sign, FX, MX, SL and IA do not), independently of vehdyn.conventions.
    """
    speed_mph = np.array([25.0, 25.0, 25.0, 40.0, 40.0])
    pressure_psi = np.array([12.0, 12.0, 14.0, 10.0, 12.0])
    channels = {
        "ET": np.arange(5.0), "V": speed_mph, "N": np.full(5, 300.0), "SA": -np.degrees(ISO["alpha"]),
        "IA": np.degrees(ISO["gamma"]), "RL": np.full(5, 9.0), "RE": np.full(5, 9.5), "P": pressure_psi,
        "FX": ISO["fx"] / LBF, "FY": -ISO["fy"] / LBF, "FZ": -ISO["fz"] / LBF, "MX": ISO["mx"] / FT_LB,
        "MZ": -ISO["mz"] / FT_LB, "TSTC": np.full(5, 40.0), "SR": np.zeros(5), "SL": ISO["kappa"],
    }
    units = {"ET": "s", "V": "mph", "N": "rpm", "SA": "deg", "IA": "deg", "RL": "in", "RE": "in", "P": "psi",
             "FX": "lb", "FY": "lb", "FZ": "lb", "MX": "ft-lb", "MZ": "ft-lb", "TSTC": "deg F", "SR": "none",
             "SL": "none"}
    lines = ["Run 8: flat-track test, cornering, English units", "\t".join(channels),
             "\t".join(units[k] for k in channels)]
    for i in range(5):
        lines.append("\t".join(repr(float(v[i])) for v in channels.values()))
    path = tmp_path / "run8.dat"
    path.write_text("\n".join(lines) + "\n")
    frame = read_tire_data(path)
    for name, values in ISO.items():
        np.testing.assert_allclose(frame[name], values, rtol=1e-12, atol=1e-9, err_msg=name)
    np.testing.assert_allclose(frame["vx"], speed_mph * 0.44704, rtol=1e-12)
    np.testing.assert_allclose(frame["pressure"], pressure_psi * PSI, rtol=1e-12)
    np.testing.assert_allclose(frame["omega"], 300.0 * 2 * math.pi / 60, rtol=1e-12)
    np.testing.assert_allclose(frame["effective_radius"], 9.5 * 0.0254, rtol=1e-12)
    assert frame.attrs["units"]["alpha"] == "rad"
    assert "ET" not in frame and "RL" not in frame


def test_csv_aliases_units_and_sae(tmp_path):
    """Aliases and bracketed units; convention='SAE' flips exactly what the SAE definition flips."""
    header = "load [kN],slip_angle [deg],slip_ratio,camber (deg),FX,FY,MZ,Speed [km/h],extra"
    rows = [f"{fz / 1e3!r},{math.degrees(a)!r},{k!r},{math.degrees(g)!r},{fx!r},{fy!r},{mz!r},72,9"
            for fz, a, k, g, fx, fy, mz in zip(*(ISO[n].tolist() for n in ("fz", "alpha", "kappa", "gamma", "fx",
                                                                          "fy", "mz")))]
    path = tmp_path / "data.csv"
    path.write_text(header + "\n" + "\n".join(rows) + "\n")
    iso = read_tire_data(path)
    for name in ("fz", "alpha", "kappa", "gamma", "fx", "fy", "mz"):
        np.testing.assert_allclose(iso[name], ISO[name], rtol=1e-12, atol=1e-12, err_msg=name)
    np.testing.assert_allclose(iso["vx"], 20.0)
    sae = read_tire_data(path, convention="SAE")
    for name, sign in (("fz", -1), ("alpha", -1), ("kappa", 1), ("gamma", 1), ("fx", 1), ("fy", -1), ("mz", -1)):
        np.testing.assert_allclose(sae[name], sign * ISO[name], rtol=1e-12, atol=1e-12, err_msg=name)


def test_units_argument_overrides_header(tmp_path):
    path = tmp_path / "d.csv"
    path.write_text("fz [N];alpha [rad];fy\n4000;2;-100\n")
    frame = read_tire_data(path, units={"alpha": "deg", "fz": "kN"})
    assert frame["alpha"][0] == pytest.approx(math.radians(2.0))
    assert frame["fz"][0] == pytest.approx(4e6)


def test_empty_fields_become_nan(tmp_path):
    path = tmp_path / "d.csv"
    path.write_text("fz,alpha,fy\n4000,0.1,\n4000,,-100\n")
    frame = read_tire_data(path)
    assert frame["fy"].isna().sum() == 1 and frame["alpha"].isna().sum() == 1


@pytest.mark.parametrize("text, match", [
    ("fz,alpha,fy\n4000,0.1,-10\n4000,abc,-10\n", r"line 3: column 'alpha': 'abc' is not a number"),
    ("fz,alpha,fy\n4000,0.1\n", r"line 2: 2 fields, the header names 3"),
    ("fz [lbs],alpha,fy\n4000,0.1,-10\n", r"line 1: column 'fz': unknown force unit 'lbs'"),
    ("", r"line 1: the file is empty"),
    ("time,temperature\n1,2\n", r"line 1: no known column"),
    ("fz,load\n1,2\n", r"duplicates 'fz'"),
    ("x\nSA FZ FY\ndeg lb\n1 2 3\n", r"line 3: the unit row has 2 fields"),
    ("SA FZ FY\ndeg lb furlong\n1 2 3\n", r"column 'fy': unknown force unit 'furlong'"),
    ("SA FZ FY\ndeg lb lb\n1 2 3\n4 x 6\n", r"line 4: column 'FZ': 'x' is not a number"),
])
def test_bad_files_name_line_and_column(tmp_path, text, match):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    with pytest.raises(TirFileError, match=match):
        read_tire_data(path)


def test_bad_arguments(tmp_path):
    path = tmp_path / "d.csv"
    path.write_text("fz,alpha,fy\n4000,0.1,-10\n")
    with pytest.raises(ParameterError, match="convention"):
        read_tire_data(path, convention="ISO")
    with pytest.raises(ParameterError, match="'slip' is not a canonical column"):
        read_tire_data(path, units={"slip": "deg"})
