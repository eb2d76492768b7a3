"""``.tir`` files: every coefficient checked, truncated files said, byte-order marks, atomic writes.

References: the shipped files and the MFeval reference copies (read unchanged, no warning), the
line of each key in the file's own text (found independently of the parser), the section headers
of the original file (which sections a truncated copy lacks), and round trips through
``write_tir``/``read_tir``.
"""

from __future__ import annotations

import errno
import functools
import re
import warnings
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import vehdyn
from vehdyn import TirFileError, VehdynWarning
from vehdyn.cli import main
from vehdyn.tire import MagicFormula, TirParameters, load_tire, read_tir, write_tir
from vehdyn.tire import tir as tir_module
from vehdyn.tire.tir import REQUIRED_SECTIONS, STANDARD_SECTIONS, parse_tir

NAMES = ("MagicFormula61_Parameters", "MagicFormula62_Parameters", "MagicFormula52_Parameters", "mf_185_80R14")
SHARED = Path("/work/shared/data/tir")
FILES = [vehdyn.data_path("tires", n + ".tir") for n in NAMES] + [
    SHARED / (n + ".tir") for n in NAMES if (SHARED / (n + ".tir")).exists()]
NON_FINITE_TEXT = ("nan", "NaN", "inf", "-inf", "+Infinity", "1e999", "-1e400")
NUMBER_LINE = re.compile(r"^\s*([A-Za-z0-9_]+)\s*=\s*([-+0-9.eE]+)\s*(\$.*)?$")


@functools.cache
def text_of(name: str) -> str:
    return Path(vehdyn.data_path("tires", name + ".tir")).read_text(encoding="latin-1")


@functools.cache
def number_lines(name: str):
    """(line number, key) of every numeric ``KEY = value`` line of a shipped file, read with a regex."""
    found = []
    section = None
    for number, line in enumerate(text_of(name).splitlines(), start=1):
        if line.strip().startswith("["):
            section = line.strip()[1:line.strip().index("]")]
        match = NUMBER_LINE.match(line)
        if match and section not in ("UNITS", "SHAPE"):
            found.append((number, match.group(1)))
    return tuple(found)


def with_line(name: str, number: int, replacement: str) -> str:
    lines = text_of(name).splitlines()
    lines[number - 1] = replacement
    return "\n".join(lines) + "\n"


def with_value(name: str, key: str, value: str) -> tuple[str, int]:
    """The file's text with ``key``'s value replaced, and that key's line number."""
    number = next(n for n, k in number_lines(name) if k == key)
    return with_line(name, number, f"{key} = {value}"), number


# ------------------------------------------------------------------------------------- real files pass
@pytest.mark.parametrize("path", FILES, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_real_files_pass_every_rule_without_warning(path):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        params = read_tir(path, strict=True)
        MagicFormula.from_tir(path, strict=True)
    assert params.missing_sections == ()
    assert params == read_tir(vehdyn.data_path("tires", path.name))  # the shared copies equal the shipped files


def test_standard_sections_cover_every_parameter_mfeval_reads_once():
    keys = [k for section in STANDARD_SECTIONS.values() for k in section]
    assert len(keys) == len(set(keys))
    assert set(keys) == set(tir_module.MFEVAL_DEFAULTS)
    for sections in REQUIRED_SECTIONS.values():
        assert set(sections) <= set(STANDARD_SECTIONS)


# ------------------------------------------------------------------------------ non-finite coefficients
@pytest.mark.parametrize("value", NON_FINITE_TEXT)
def test_non_finite_coefficient_is_an_error_with_key_value_and_line(value, tmp_path):
    text, line = with_value("MagicFormula61_Parameters", "PDY2", value)
    path = tmp_path / "bad.tir"
    path.write_text(text)
    with pytest.raises(TirFileError, match=r"PDY2 = .* is not a finite number") as info:
        read_tir(path)
    assert info.value.line == line and f"line {line}" in str(info.value)
    assert info.value.key == "PDY2" and not np.isfinite(info.value.value)


def test_non_finite_after_unit_conversion_is_an_error():
    """1e306 kN is finite as written, infinite in newtons."""
    text = re.sub(r"^FORCE\s*=.*$", "FORCE = 'kN'", text_of("MagicFormula61_Parameters"), flags=re.M)
    text = re.sub(r"^FZMAX\s*=.*$", "FZMAX = 1e306", text, flags=re.M)
    with pytest.raises(TirFileError, match="FZMAX = 1e.306 .*SI units.* not a finite"):
        parse_tir(text)


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(name=st.sampled_from(NAMES), data=st.data(), value=st.sampled_from(NON_FINITE_TEXT))
def test_any_coefficient_made_non_finite_is_refused_at_its_line(name, data, value):
    number, key = data.draw(st.sampled_from(number_lines(name)))
    with pytest.raises(TirFileError) as info:
        parse_tir(with_line(name, number, f"{key} = {value}"), path="x.tir")
    assert info.value.line == number and info.value.key == key
    assert f"{key} = " in str(info.value) and "x.tir, line" in str(info.value)


def test_cli_exits_non_zero_on_a_non_finite_coefficient(tmp_path, capsys):
    text, line = with_value("MagicFormula61_Parameters", "QSX3", "inf")
    path = tmp_path / "bad.tir"
    path.write_text(text)
    assert main(["tire", str(path), "--out", str(tmp_path / "plots")]) != 0
    err = capsys.readouterr().err
    assert "QSX3" in err and f"line {line}" in err and not (tmp_path / "plots").exists()


# ------------------------------------------------------------------------------------ ranges and signs
@pytest.mark.parametrize("changes, blamed, message", [
    ({"FZMIN": "20000"}, "FZMIN", "FZMIN = 20000 must be < FZMAX = 18000"),
    ({"FZMAX": "0"}, "FZMAX", "largest load .* > 0"),
    ({"FZMAX": "-5"}, "FZMAX", "largest load .* > 0"),
    ({"FZMIN": "-1"}, "FZMIN", "smallest vertical load .* >= 0"),
    ({"ALPMIN": "0.96"}, "ALPMIN", "slip angle range is empty or inverted"),
    ({"ALPMIN": "0.1"}, "ALPMIN", "slip angle range must contain 0"),
    ({"ALPMAX": "-0.1"}, "ALPMAX", "slip angle range must contain 0"),
    ({"KPUMIN": "1"}, "KPUMIN", "slip ratio range is empty or inverted"),
    ({"KPUMAX": "0"}, "KPUMAX", "slip ratio range must contain 0"),
    ({"CAMMIN": "0.2"}, "CAMMIN", "inclination angle range is inverted"),
    ({"CAMMAX": "-0.01"}, "CAMMAX", "inclination angle range must contain 0"),
    ({"PRESMIN": "500000"}, "PRESMIN", "inflation pressure range is inverted"),
    ({"PRESMIN": "-1"}, "PRESMIN", ">= 0"),
    ({"PDX1": "-1.1632"}, "PDX1", "PDX1 = -1.1632 must be > 0"),
    ({"PDY1": "-1.0085"}, "PDY1", "PDY1 = -1.0085 must be > 0"),
    ({"PDY1": "0"}, "PDY1", "must be > 0"),
    ({"QCZ1": "-1.1676"}, "QCZ1", "must be > 0"),
    ({"LFZO": "0"}, "LFZO", "must be > 0"),
    ({"LMUY": "-1"}, "LMUY", "must be >= 0"),
    ({"LMUX": "-0.5"}, "LMUX", "must be >= 0"),
])
def test_range_and_sign_rules(changes, blamed, message):
    name = "MagicFormula61_Parameters"
    text = text_of(name)
    for key, value in changes.items():
        text = re.sub(rf"^{key}\s*=[^$\n]*", f"{key} = {value} ", text, count=1, flags=re.M)
    with pytest.raises(TirFileError, match=message) as info:
        parse_tir(text, path="x.tir")
    line = next(n for n, k in number_lines(name) if k == blamed)
    assert info.value.key == blamed and info.value.line == line


def test_sign_rules_only_where_the_equations_need_them():
    """PCX1, PCY1 of the opposite sign give the same forces and moments (B = K/(C D) flips with C):
    not refused; QCZ1 of the opposite sign changes M_z (through E_t): refused."""
    text = text_of("MagicFormula61_Parameters")
    flipped = text
    for key in ("PCX1", "PCY1"):
        flipped = re.sub(rf"^({key}\s*=\s*)([0-9.]+)", r"\1-\2", flipped, count=1, flags=re.M)
    tire, mirror = MagicFormula(parse_tir(text)), MagicFormula(parse_tir(flipped))
    assert mirror.params["PCY1"] == -tire.params["PCY1"]
    alpha = np.linspace(-0.3, 0.3, 13)
    a, b = tire.forces(4000.0, 0.0, alpha), mirror.forces(4000.0, 0.0, alpha)
    # equal but for the epsilon in B = K/(C D + eps) (about 1e-9 relative)
    np.testing.assert_allclose(b.fy, a.fy, rtol=1e-8)
    np.testing.assert_allclose(b.mz, a.mz, rtol=1e-8)
    kappa = np.linspace(-0.3, 0.3, 13)
    np.testing.assert_allclose(mirror.forces(4000.0, kappa, 0.0).fx, tire.forces(4000.0, kappa, 0.0).fx, rtol=1e-8)
    # with C_t flipped the trail's curvature E_t (QEZ4 = 0.378 in this file) mirrors: another M_z
    sections = {k: dict(v) for k, v in tire.params.sections.items()}
    sections["ALIGNING_COEFFICIENTS"]["QCZ1"] *= -1
    with pytest.raises(TirFileError, match="QCZ1"):
        TirParameters(sections)
    ct_flipped = MagicFormula.__new__(MagicFormula)
    ct_flipped.__dict__.update(tire.__dict__, _c=tire._c._replace(QCZ1=-tire._c.QCZ1))
    assert np.max(np.abs(ct_flipped.forces(4000.0, 0.0, alpha).mz - a.mz)) > 1.0


def test_legitimate_ranges_pass():
    """Zero-width camber and pressure ranges (a file fitted without camber, at one pressure)."""
    text = text_of("MagicFormula61_Parameters")
    for key, value in {"CAMMIN": "0", "CAMMAX": "0", "PRESMIN": "260000", "PRESMAX": "260000", "LMUX": "0"}.items():
        text = re.sub(rf"^{key}\s*=[^$\n]*", f"{key} = {value} ", text, count=1, flags=re.M)
    tire = MagicFormula(parse_tir(text))
    assert tire.forces(4000.0, 0.0, 0.05, 0.1).fx == 0.0  # LMUX = 0: no longitudinal friction
    assert np.isfinite(tire.forces(4000.0, 0.0, 0.05, 0.1).fy)


def test_rule_against_a_default_names_the_default():
    """A file setting FZMAX = 50 N only: MFeval's default FZMIN = 100 N takes part (and is said)."""
    with pytest.raises(TirFileError, match=r"FZMIN = 100.0 \(MFeval's default.*FZMAX = 50") as info:
        parse_tir("[MODEL]\nFITTYP = 61\n[VERTICAL_FORCE_RANGE]\nFZMAX = 50\n")
    assert info.value.key == "FZMAX" and info.value.line == 4


def test_write_tir_refuses_what_read_tir_refuses(tmp_path):
    sections = {s: dict(kv) for s, kv in read_tir(vehdyn.data_path("tires", NAMES[0] + ".tir")).sections.items()}
    sections["LATERAL_COEFFICIENTS"]["PKY1"] = float("nan")
    with pytest.raises(TirFileError, match="PKY1"):
        write_tir(sections, tmp_path / "nan.tir")
    assert list(tmp_path.iterdir()) == []


# --------------------------------------------------------------------------------------- missing sections
def section_headers(name: str):
    """(line number, section) of every header of a shipped file."""
    return [(n, line.strip()[1:line.strip().index("]")]) for n, line in enumerate(text_of(name).splitlines(), 1)
            if line.strip().startswith("[")]


def truncated(name: str, keep_lines: int) -> str:
    return "\n".join(text_of(name).splitlines()[:keep_lines]) + "\n"


def first_key_lines(name: str):
    """{section: line of its first ``KEY = value`` line} of a shipped file, and the line naming the version."""
    first, section, version_lines = {}, None, {}
    for number, line in enumerate(text_of(name).splitlines(), start=1):
        stripped = line.strip()
        if stripped.startswith("["):
            section = stripped[1:stripped.index("]")]
        elif re.match(r"^[A-Za-z0-9_]+\s*=", stripped):
            first.setdefault(section, number)
            key = stripped.split("=")[0].strip()
            if key in ("FITTYP", "PROPERTY_FILE_FORMAT"):
                version_lines[key] = number
    return first, version_lines.get("FITTYP", version_lines.get("PROPERTY_FILE_FORMAT"))


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(name=st.sampled_from(NAMES), data=st.data())
def test_truncated_file_lists_the_sections_it_lost(name, data):
    """Cut after any line once the version is known: exactly the required sections none of whose
    lines survived are missing (a truncated file), in the file's order."""
    first, version_line = first_key_lines(name)
    keep = data.draw(st.integers(version_line, len(text_of(name).splitlines())))
    params = parse_tir(truncated(name, keep))
    lost = [s for s, n in first.items() if n > keep and s in REQUIRED_SECTIONS[params.version]]
    assert set(params.missing_sections) == set(lost)


def test_truncated_file_warns_on_from_tir_and_strict_raises(tmp_path):
    name = "MagicFormula61_Parameters"
    cut = next(n for n, s in section_headers(name) if s == "ROLLING_COEFFICIENTS") - 1
    path = tmp_path / "cut.tir"
    path.write_text(truncated(name, cut))
    expected = ["ROLLING_COEFFICIENTS", "ALIGNING_COEFFICIENTS", "TURNSLIP_COEFFICIENTS"]
    n_defaulted = sum(len(STANDARD_SECTIONS[s]) for s in expected)  # the MF 6.1 file sets every one
    with pytest.warns(VehdynWarning) as record:
        tire = MagicFormula.from_tir(path)
    message = str(record[0].message)
    assert "lacks 3 sections" in message and f"{n_defaulted} coefficients" in message
    assert all(f"[{s}]" in message for s in expected)
    assert record[0].filename == __file__  # points at the caller, not inside vehdyn
    assert tire.params.missing_sections == tuple(expected)
    with pytest.warns(VehdynWarning, match="lacks 3 sections"):
        load_tire(path)
    for loader in (MagicFormula.from_tir, load_tire, read_tir):
        with pytest.raises(TirFileError, match="lacks 3 sections"):
            loader(path, strict=True)


def test_cli_says_which_sections_are_missing(tmp_path, capsys):
    name = "MagicFormula61_Parameters"
    cut = next(n for n, s in section_headers(name) if s == "TURNSLIP_COEFFICIENTS") - 1
    path = tmp_path / "cut.tir"
    path.write_text(truncated(name, cut))
    assert main(["tire", str(path), "--out", str(tmp_path / "plots")]) == 0
    out = capsys.readouterr()
    assert "warning" in out.err and "[TURNSLIP_COEFFICIENTS]" in out.err
    assert "missing sections: TURNSLIP_COEFFICIENTS" in out.out


# --------------------------------------------------------------------------------------- encodings
@pytest.mark.parametrize("encoding, bom", [("utf-8", b"\xef\xbb\xbf"), ("utf-16-le", b"\xff\xfe"),
                                           ("utf-16-be", b"\xfe\xff")])
@pytest.mark.parametrize("name", NAMES)
def test_byte_order_mark_is_accepted(tmp_path, name, encoding, bom):
    path = tmp_path / "bom.tir"
    path.write_bytes(bom + text_of(name).encode(encoding))
    params = read_tir(path)
    original = read_tir(vehdyn.data_path("tires", name + ".tir"))
    assert params == original and dict(params.values) == dict(original.values)
    assert params.lines == original.lines  # the mark does not shift the line numbers


def test_utf8_and_latin1_text_are_read(tmp_path):
    for encoding, dash in (("utf-8", "–"), ("latin-1", "-")):
        body = text_of("MagicFormula61_Parameters").replace(
            "[MDI_HEADER]", f"[MDI_HEADER]\n$ Größe 205/55 R16 {dash} links\nCOMMENT_TEXT = 'Reifen Größe'", 1)
        path = tmp_path / f"{encoding}.tir"
        path.write_bytes(body.encode(encoding))
        assert read_tir(path)["COMMENT_TEXT"] == "Reifen Größe", encoding


def test_write_tir_round_trips_a_string_that_needs_utf8(tmp_path):
    params = read_tir(vehdyn.data_path("tires", NAMES[0] + ".tir"))
    sections = {s: dict(kv) for s, kv in params.sections.items()}
    sections["MDI_HEADER"]["COMMENT_TEXT"] = "pneu – été"  # '–' has no Latin-1 code
    back = read_tir(write_tir(sections, tmp_path / "u.tir"))
    assert back["COMMENT_TEXT"] == "pneu – été"
    assert (tmp_path / "u.tir").read_bytes().decode("utf-8")
    assert read_tir(write_tir(params, tmp_path / "l.tir")) == params  # Latin-1 text where it suffices


# ---------------------------------------------------------------------------------------- atomic writes
def leftovers(folder: Path):
    return sorted(p.name for p in folder.iterdir() if p.name.startswith("."))


class Interrupted(Exception):
    pass


def interrupt_after(monkeypatch, count: int, folder: Path) -> list:
    """Make write_tir's value formatting raise after ``count`` values: the writer stops mid-file.

    Returns a list that receives, at the interruption, the partly written files of ``folder``
    (proof that the interruption came mid-write, with a torn file on disk).
    """
    original = tir_module._format_value
    calls, torn = [0], []

    def failing(value):
        calls[0] += 1
        if calls[0] > count:
            torn.extend(p for p in folder.iterdir() if p.name.startswith("."))
            raise Interrupted(f"after {count} values")
        return original(value)

    monkeypatch.setattr(tir_module, "_format_value", failing)
    return torn


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(count=st.integers(0, 300), name=st.sampled_from(NAMES))
def test_interrupted_write_leaves_the_old_file(tmp_path, monkeypatch, count, name):
    old = read_tir(vehdyn.data_path("tires", name + ".tir"))
    folder = tmp_path / f"{name}-{count}"
    folder.mkdir()
    path = write_tir(old, folder / "tire.tir")
    before = path.read_bytes()
    new = {s: dict(kv) for s, kv in read_tir(vehdyn.data_path("tires", NAMES[1] + ".tir")).sections.items()}
    values = sum(len(kv) for kv in new.values())
    with monkeypatch.context() as patch:
        torn = interrupt_after(patch, min(count, values - 1), folder)
        with pytest.raises(Interrupted):
            write_tir(new, path)
    assert len(torn) == 1  # a partial file existed when the writer failed ...
    assert path.read_bytes() == before and read_tir(path) == old  # ... yet the old file is intact
    assert leftovers(folder) == []  # and the partial one is gone


def test_interrupted_write_of_a_new_file_leaves_no_file(tmp_path, monkeypatch):
    torn = interrupt_after(monkeypatch, 40, tmp_path)
    with pytest.raises(Interrupted):
        write_tir(read_tir(vehdyn.data_path("tires", NAMES[0] + ".tir")), tmp_path / "new.tir")
    assert len(torn) == 1 and list(tmp_path.iterdir()) == []


def test_disk_full_leaves_the_old_file(tmp_path, monkeypatch):
    import vehdyn._atomic as atomic

    old = read_tir(vehdyn.data_path("tires", NAMES[2] + ".tir"))
    path = write_tir(old, tmp_path / "tire.tir")

    def full(fd):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(atomic.os, "fsync", full)
    with pytest.raises(OSError, match="No space"):
        write_tir(read_tir(vehdyn.data_path("tires", NAMES[0] + ".tir")), path)
    assert read_tir(path) == old and leftovers(tmp_path) == []
