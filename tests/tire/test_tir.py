"""read_tir / write_tir: parameters against MFeval's readTIR, round trips, units, errors."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import vehdyn
from vehdyn import TirFileError
from vehdyn.tire import MagicFormula, TirParameters, read_tir, write_tir
from vehdyn.tire.tir import MFEVAL_DEFAULTS, parse_tir

DATA = Path(__file__).resolve().parent.parent / "data" / "mf_reference"
TIRES = {
    "MagicFormula61_Parameters": "6.1",
    "MagicFormula62_Parameters": "6.2",
    "MagicFormula52_Parameters": "5.2",
    "mf_185_80R14": "5.2",  # PROPERTY_FILE_FORMAT = 'PAC2002', no FITTYP line
}
# MF 6.2 / MF 5.2 parameters that MFeval reads for every file, but that a file of the other
# versions never uses (vehdyn does not list them as defaulted there).
MF62_ONLY = frozenset({"FUNCTION_NAME", "SWITCH_INTEG", "Q_FCY2", "Q_CAM1", "Q_CAM2", "Q_CAM3", "Q_FYS1", "Q_FYS2",
             "Q_FYS3", "ENV_C1", "ENV_C2"})
MF52_ONLY = frozenset({"Q_A1", "Q_A2", "PHY3", "PTX1", "PTX2", "PTX3", "PTY1", "PTY2", "LSGKP", "LSGAL"})


def tir_path(name):
    return vehdyn.data_path("tires", name + ".tir")


def mfeval_parameters(name):
    """MFeval's parameter struct after readTIR (tests/data/mf_reference/S__mfeval_params.csv)."""
    return pd.read_csv(DATA / f"{name}__mfeval_params.csv", dtype={"value": str}, keep_default_na=False)


@pytest.mark.parametrize("name", TIRES)
def test_version_detected(name):
    assert read_tir(tir_path(name)).version == TIRES[name]


@pytest.mark.parametrize("name", TIRES)
def test_parameters_equal_the_values_mfeval_used(name):
    """Every numeric parameter equals MFeval's (file value or readTIR default), bit for bit."""
    params = read_tir(tir_path(name))
    table = mfeval_parameters(name)
    unused = set(MF62_ONLY) if params.version != "6.2" else set()
    unused |= MF52_ONLY if params.version != "5.2" else set()
    checked = 0
    for row in table.itertuples():
        key = "MASS" if row.name == "MASS1" else row.name
        if key in unused or key in ("LENGTH", "FORCE", "ANGLE", "MASS", "TIME") and row.name != "MASS1":
            continue  # [UNITS] entries live in params.units
        if key == "FITTYP" and name == "mf_185_80R14":
            continue  # the reference set FITTYP = 6 by hand; vehdyn reads the PAC2002 format instead
        try:
            expected = float(row.value)
        except ValueError:
            assert str(params[key]) == row.value.strip("'"), key
            continue
        assert params[key] == expected, key
        checked += 1
    assert checked > 150


@pytest.mark.parametrize("name", TIRES)
def test_defaulted_lists_what_mfeval_took_from_its_defaults(name):
    params = read_tir(tir_path(name))
    table = mfeval_parameters(name)
    from_defaults = set(table.name[table.in_file == 0]) - {"MASS1"}
    from_defaults -= MF62_ONLY if params.version != "6.2" else set()
    from_defaults -= MF52_ONLY if params.version != "5.2" else set()
    defaulted = set(params.defaulted) - {"MASS"}  # MFeval calls the inertia-section MASS 'MASS1'
    assert defaulted == from_defaults
    for key in params.defaulted:
        assert params[key] == MFEVAL_DEFAULTS[key]


def test_units_and_sections_kept_verbatim():
    params = read_tir(tir_path("MagicFormula61_Parameters"))
    assert dict(params.units) == {"LENGTH": "meter", "FORCE": "newton", "ANGLE": "radians", "MASS": "kg",
                                  "TIME": "second"}
    assert params.sections["VERTICAL"]["FNOMIN"] == 6752
    assert params.sections["MODEL"]["FITTYP"] == 61
    assert params.sections["INERTIA"]["MASS"] == params["MASS"]
    assert "SHAPE" in read_tir(tir_path("MagicFormula52_Parameters")).tables


@pytest.mark.parametrize("name", TIRES)
def test_write_read_round_trip_is_exact(name, tmp_path):
    original = read_tir(tir_path(name))
    copy = read_tir(write_tir(original, tmp_path / "copy.tir"))
    assert copy == original
    assert dict(copy.values) == dict(original.values)
    assert copy.defaulted == original.defaulted and copy.version == original.version
    # and the written file evaluates identically (the same coefficients through the same numpy code)
    a = MagicFormula(original).evaluate(4000.0, 0.05, np.linspace(-0.3, 0.3, 7), 0.02, vx=15.0)
    b = MagicFormula(copy).evaluate(4000.0, 0.05, np.linspace(-0.3, 0.3, 7), 0.02, vx=15.0)
    for field in a.keys():
        np.testing.assert_array_equal(a[field], b[field])


def test_units_section_is_honoured(tmp_path):
    """A file in mm, kN, deg and g equals the SI file after conversion (closed-form factors)."""
    si = read_tir(tir_path("MagicFormula61_Parameters"))
    sections = {s: dict(kv) for s, kv in si.sections.items()}
    sections["UNITS"] = {"LENGTH": "mm", "FORCE": "kN", "ANGLE": "deg", "MASS": "gram", "TIME": "second"}
    sections["DIMENSION"]["UNLOADED_RADIUS"] = si["UNLOADED_RADIUS"] * 1000.0
    sections["VERTICAL"]["FNOMIN"] = si["FNOMIN"] / 1000.0
    sections["VERTICAL"]["VERTICAL_STIFFNESS"] = si["VERTICAL_STIFFNESS"] / 1000.0 / 1000.0  # kN/mm
    sections["OPERATING_CONDITIONS"]["NOMPRES"] = si["NOMPRES"] * 1e-9  # kN/mm^2
    sections["SLIP_ANGLE_RANGE"]["ALPMAX"] = np.degrees(si["ALPMAX"])
    sections["MODEL"]["LONGVL"] = si["LONGVL"] * 1000.0
    sections["INERTIA"]["MASS"] = si["MASS"] * 1000.0
    converted = read_tir(write_tir(sections, tmp_path / "mm.tir"))
    for key in ("UNLOADED_RADIUS", "FNOMIN", "VERTICAL_STIFFNESS", "NOMPRES", "ALPMAX", "LONGVL", "MASS"):
        assert converted[key] == pytest.approx(si[key], rel=1e-14), key
    assert converted["PKY1"] == si["PKY1"]  # Magic Formula coefficients are dimensionless


def test_unknown_unit_is_an_error(tmp_path):
    path = tmp_path / "bad.tir"
    path.write_text("[UNITS]\nLENGTH = 'furlong'\n[DIMENSION]\nUNLOADED_RADIUS = 1\n")
    with pytest.raises(TirFileError, match="furlong"):
        read_tir(path)


@pytest.mark.parametrize(
    "body, line, message",
    [
        ("[MODEL]\nFITTYP = 61\nLONGVL = 16.7 16\n", 3, "neither a number"),
        ("[MODEL]\nFITTYP = 61\n[VERTICAL\nFNOMIN = 1\n", 3, "section header"),
        ("FITTYP = 61\n", 1, "before the first"),
        ("[MODEL]\nFITTYP = 61\nLONGVL\n", 3, "KEY = value"),
        ("[MODEL]\nPROPERTY_FILE_FORMAT = 'PAC2002\n", 2, "unterminated"),
        ("[MODEL]\nFITTYP = 61\n\n$ comment\nFITTYP = 62\n", 5, "twice"),
        ("[MODEL]\nFITTYP =\n", 2, "missing value"),
        ("[MODEL]\nFIT TYP = 61\n", 2, "invalid parameter name"),
    ],
)
def test_malformed_file_names_the_line(tmp_path, body, line, message):
    path = tmp_path / "bad.tir"
    path.write_text(body)
    with pytest.raises(TirFileError, match=message) as info:
        read_tir(path)
    assert info.value.line == line
    assert f"line {line}" in str(info.value)


def test_missing_file_is_a_tir_file_error(tmp_path):
    with pytest.raises(TirFileError, match="cannot read"):
        read_tir(tmp_path / "nope.tir")


def test_comments_quotes_and_tables():
    text = (
        "[MDI_HEADER]\nFILE_TYPE ='tir'   $ a comment with = and 'quote'\n"
        "! a bang comment\n[MODEL]\nPROPERTY_FILE_FORMAT = 'PAC2002'\nFUNCTION_NAME = 'a$b'\n"
        "[SHAPE]\n{radial width}\n 1.0 0.0\n 0.9 1.0\n[VERTICAL]\nFNOMIN = 4e3 $ load\n"
    )
    params = parse_tir(text)
    assert params["FILE_TYPE"] == "tir" and params["FUNCTION_NAME"] == "a$b"
    assert params["FNOMIN"] == 4000.0
    assert params.version == "5.2"
    assert params.tables["SHAPE"] == ("{radial width}", " 1.0 0.0", " 0.9 1.0")


@pytest.mark.parametrize("fittyp, version", [(6, "5.2"), (21, "5.2"), (61, "6.1"), (62, "6.2"), (5, None)])
def test_version_from_fittyp(fittyp, version):
    assert parse_tir(f"[MODEL]\nFITTYP = {fittyp}\n").version == version


def test_unsupported_version_is_refused_by_the_model():
    params = parse_tir("[MODEL]\nFITTYP = 5\n")
    with pytest.raises(TirFileError, match="FITTYP"):
        MagicFormula(params)


def test_non_numeric_coefficient_and_non_positive_load_are_parameter_errors():
    with pytest.raises(vehdyn.ParameterError, match="PKY1"):
        MagicFormula(parse_tir("[MODEL]\nFITTYP = 61\n[LATERAL_COEFFICIENTS]\nPKY1 = 'x'\n"))
    with pytest.raises(vehdyn.ParameterError, match="FNOMIN"):
        MagicFormula(parse_tir("[MODEL]\nFITTYP = 61\n[VERTICAL]\nFNOMIN = 0\n"))


def test_tir_parameters_from_sections_mapping():
    params = TirParameters({"MODEL": {"FITTYP": 62}, "VERTICAL": {"FNOMIN": 5000.0}})
    assert params.version == "6.2" and params["FNOMIN"] == 5000.0
    assert "Q_FCY2" in params.defaulted and "PTX1" not in params.defaulted


def test_unknown_keys_are_kept_and_listed():
    """The MF 5.2 files carry MF-Tyre 5.x keys that MFeval ignores (its readTIR has no slot)."""
    params = read_tir(tir_path("MagicFormula52_Parameters"))
    assert set(params.unknown) == {"LGAX", "LGAY", "LGAZ", "LGYR", "QTZ1", "MBELT"}
    assert set(params.unknown).isdisjoint(MFEVAL_DEFAULTS)
    assert all(key in params.values for key in params.unknown)
    assert read_tir(tir_path("MagicFormula61_Parameters")).unknown == ()


def test_keys_are_case_insensitive_in_the_flat_view_and_verbatim_in_sections():
    params = parse_tir("[Model]\nfittyp = 62\n[vertical]\nFnomin = 5000\n")
    assert params.version == "6.2" and params["FNOMIN"] == 5000
    assert params.sections["vertical"] == {"Fnomin": 5000}


def test_parameters_are_a_read_only_mapping_of_the_flat_si_values():
    params = read_tir(tir_path("mf_185_80R14"))
    flat = dict(params)
    assert flat == params.to_dict() == dict(params.values)
    assert len(params) == len(flat) and "FNOMIN" in params and params.get("NOPE") is None
    assert flat["QSY7"] == 0.85  # a defaulted value is part of the view
    with pytest.raises(TypeError):
        params["FNOMIN"] = 1.0
