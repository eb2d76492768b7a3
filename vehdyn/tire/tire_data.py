"""Measured tire data in: CSV files and flat-track test-consortium run files -> canonical columns.

:func:`read_tire_data` returns a pandas DataFrame in vehdyn's tire convention (ISO-W, SI, radians;
see :mod:`vehdyn.conventions`) with the canonical columns

==================  ======  ===============================================
``fz``              N       normal load (positive, compressive)
``kappa``           -       longitudinal slip ratio (> 0 driving)
``alpha``           rad     slip angle (ISO-W)
``gamma``           rad     inclination (camber) angle
``vx``              m/s     wheel-centre forward speed
``pressure``        Pa      inflation pressure
``fx, fy``          N       longitudinal and lateral force (ISO-W)
``mx, my, mz``      N*m     overturning, rolling-resistance and aligning moment (ISO-W)
``omega``           rad/s   wheel spin (where present)
``effective_radius`` m      effective rolling radius (where present)
==================  ======  ===============================================

Two layouts are read:

* **CSV** (comma, semicolon or tab separated) with a header row. Column names are matched without
  regard to case against the canonical names and common aliases (``slip_angle``, ``SA``,
  ``camber``, ``load``, ...); a unit may follow the name in brackets (``alpha [deg]``,
  ``Fz (kN)``) or be given with ``units={"alpha": "deg"}``; otherwise SI is assumed. With
  ``convention="SAE"`` the values are in SAE tire axes and converted.
* **Test-consortium run files** of flat-track machines: an optional free-text first line, a row of
  channel names (``ET V N SA IA RL RE P FX FY FZ MX MZ ... SL``), a row of units (``lbf``,
  ``psi``, ``deg``, ``mph``, ``ft-lb``, or their metric counterparts ``N``, ``kPa``, ``kph``,
  ``N-m``; ``none`` for a ratio) and the data, tab separated (units such as ``deg C`` may hold a
  space) or, without tabs, whitespace separated. These channels are in SAE tire axes (``FZ`` is
  negative: the road pushes up on a z-down axis), so they are always converted from SAE,
  whatever ``convention`` says. The slip ratio is ``SL`` (``SR`` if ``SL`` is absent).

Every sign flip goes through :func:`vehdyn.conventions.tire_slips_sae_to_iso_w` and
:func:`vehdyn.conventions.tire_forces_sae_to_iso_w`.

**Units at the door.** A column without a stated unit is taken as SI, and its values must be
what a tire test produces in SI (:data:`PLAUSIBLE_RANGES`: slip angles within +-pi/2 rad, slip
ratios within +-1.5, loads positive and between 20 N and 1 MN, pressures between 0.1 and 100
bar, speeds below 150 m/s); otherwise :func:`check_units` refuses it with the unit it most likely
has (slip angles in degrees read as radians would give a tire with 1/57 of its cornering
stiffness). The fits judge their data the same way (:mod:`vehdyn.tire.fitting`).
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np

from vehdyn.errors import ParameterError, TirFileError

__all__ = ["read_tire_data", "check_units", "to_si", "TireDataError", "CANONICAL_COLUMNS", "UNIT_FACTORS",
           "PLAUSIBLE_RANGES"]

CANONICAL_COLUMNS = ("fz", "kappa", "alpha", "gamma", "vx", "pressure", "fx", "fy", "mx", "my", "mz", "omega",
                     "effective_radius")
"""The columns :func:`read_tire_data` returns (the last two only where the file has them)."""

_QUANTITY = {"fz": "force", "fx": "force", "fy": "force", "mx": "moment", "my": "moment", "mz": "moment",
             "kappa": "ratio", "alpha": "angle", "gamma": "angle", "vx": "speed", "pressure": "pressure",
             "omega": "rate", "effective_radius": "length"}

UNIT_FACTORS = {
    "force": {"n": 1.0, "kn": 1e3, "lbf": 4.4482216152605, "lb": 4.4482216152605, "kgf": 9.80665},
    "moment": {"nm": 1.0, "n-m": 1.0, "n*m": 1.0, "n.m": 1.0, "knm": 1e3, "ft-lb": 1.3558179483314004,
               "lb-ft": 1.3558179483314004, "ft-lbf": 1.3558179483314004, "lbf-ft": 1.3558179483314004,
               "lbf*ft": 1.3558179483314004, "in-lb": 0.1129848290276167, "lb-in": 0.1129848290276167},
    "ratio": {"-": 1.0, "": 1.0, "1": 1.0, "none": 1.0, "%": 0.01},
    "angle": {"rad": 1.0, "deg": math.pi / 180.0, "degree": math.pi / 180.0, "degrees": math.pi / 180.0},
    "speed": {"m/s": 1.0, "kph": 1 / 3.6, "km/h": 1 / 3.6, "kmh": 1 / 3.6, "mph": 0.44704},
    "pressure": {"pa": 1.0, "kpa": 1e3, "bar": 1e5, "psi": 6894.757293168361, "mpa": 1e6},
    "rate": {"rad/s": 1.0, "rpm": 2 * math.pi / 60.0, "1/min": 2 * math.pi / 60.0},
    "length": {"m": 1.0, "cm": 1e-2, "mm": 1e-3, "in": 0.0254},
}
"""Factor to SI of each unit a file may name, per quantity (lower case, no spaces)."""

_ALIASES = {
    "fz": ("fz", "load", "normal_load", "vertical_load"),
    "kappa": ("kappa", "slip_ratio", "longitudinal_slip", "sl"),
    "alpha": ("alpha", "slip_angle", "sa"),
    "gamma": ("gamma", "camber", "inclination", "inclination_angle", "ia"),
    "vx": ("vx", "speed", "velocity", "v"),
    "pressure": ("pressure", "inflation_pressure", "p"),
    "fx": ("fx",), "fy": ("fy",), "mx": ("mx",), "my": ("my",), "mz": ("mz",),
    "omega": ("omega", "wheel_speed", "n"),
    "effective_radius": ("effective_radius", "re"),
}
_ALIAS_TO_NAME = {alias: name for name, aliases in _ALIASES.items() for alias in aliases}

PLAUSIBLE_RANGES = {
    "alpha": (-math.pi / 2, math.pi / 2),
    "gamma": (-math.pi / 2, math.pi / 2),
    "kappa": (-1.5, 1.5),
    "fz": (20.0, 1e6),
    "pressure": (1e4, 1e7),
    "vx": (-150.0, 150.0),
}
"""Range [SI] of each column that a tire test can produce: slip and inclination angles within
+-pi/2 rad, slip ratios within the Magic Formula's usual KPUMIN/KPUMAX of +-1.5, a largest load
between 20 N and 1 MN (a model-car tire to an aircraft's), pressures between 0.1 and 100 bar,
speeds below 150 m/s. :func:`check_units` refuses a column beyond its range unless its unit was
stated (the values then are what the user says they are)."""

_LIKELY_UNIT = {
    "alpha": ("deg", "degrees"), "gamma": ("deg", "degrees"), "kappa": ("%", "percent"), "fz": ("kN", "kN"),
    "vx": ("km/h", "km/h"),
}

# Test-consortium channels (SAE tire axes) -> canonical name; SR is used when SL is absent.
_CONSORTIUM = {"FZ": "fz", "SL": "kappa", "SA": "alpha", "IA": "gamma", "V": "vx", "P": "pressure", "FX": "fx",
               "FY": "fy", "MX": "mx", "MY": "my", "MZ": "mz", "N": "omega", "RE": "effective_radius"}


class TireDataError(TirFileError):
    """A tire data file cannot be read; the message names the file, the line and the column.

    Parameters
    ----------
    message : str
        What is wrong.
    path : str or pathlib.Path, optional
        The file.
    line : int, optional
        The line (1-based).
    column : str, optional
        The column, as the file names it.
    """

    def __init__(self, message: str, *, path=None, line=None, column=None):
        super().__init__(message, path=None if path is None else str(path), line=line)
        self.column = column


def _unit_factor(name, unit, path, line):
    quantity = _QUANTITY[name]
    key = unit.strip().lower().replace(" ", "")
    table = UNIT_FACTORS[quantity]
    if key not in table:
        raise TireDataError(f"column {name!r}: unknown {quantity} unit {unit!r}; known: {', '.join(sorted(table))}",
                            path=path, line=line, column=name)
    return table[key]


def to_si(name, values, unit):
    """Values of a canonical column in a named unit, converted to SI.

    Parameters
    ----------
    name : str
        Canonical column (:data:`CANONICAL_COLUMNS`).
    values : array_like
        The values [``unit``].
    unit : str
        A unit of the column's quantity in :data:`UNIT_FACTORS` (case and spaces ignored).

    Returns
    -------
    ndarray
        The values in SI (N, N*m, rad, m/s, Pa, rad/s, m; slip ratio as a fraction).

    Raises
    ------
    ParameterError
        If ``name`` is not a canonical column or ``unit`` not a unit of its quantity.
    """
    if name not in _QUANTITY:
        raise ParameterError(f"units: {name!r} is not a canonical column ({', '.join(CANONICAL_COLUMNS)})",
                             key="units", value=name)
    table = UNIT_FACTORS[_QUANTITY[name]]
    key = str(unit).strip().lower().replace(" ", "")
    if key not in table:
        raise ParameterError(f"units[{name!r}]: unknown {_QUANTITY[name]} unit {unit!r}; known: "
                             f"{', '.join(sorted(table))}", key="units", value=unit)
    return np.asarray(values, dtype=float) * table[key]


def check_units(columns, *, stated=()):
    """Refuse columns whose values no tire test produces in SI units (:data:`PLAUSIBLE_RANGES`).

    Slip angles in degrees in a column taken as radians (|alpha| up to 15 "rad") would be fitted
    without a word and give a tire with a fraction of the real cornering force; so would slip ratios
    in percent, loads in kN, pressures in bar. Each column beyond its range is refused with the unit
    it most likely has.

    Parameters
    ----------
    columns : mapping of str to array_like
        Canonical columns [SI] (others are ignored); NaN values are ignored.
    stated : collection of str
        Columns whose unit the user (or the file) stated: not judged.

    Raises
    ------
    ParameterError
        Naming the column, its extreme value and the likely unit; ``key`` is the column.
    """
    def how(name, unit):
        return (f"state the unit: units={{{name!r}: {unit!r}}}, a CSV header '{name} [{unit}]' or, for vehdyn "
                f"tire-fit, --unit {name}={unit}")

    for name, (low, high) in PLAUSIBLE_RANGES.items():
        if name not in columns or name in stated:
            continue
        values = np.asarray(columns[name], dtype=float).ravel()
        values = values[np.isfinite(values)]
        if not values.size:
            continue
        if name == "fz":
            typical = float(np.median(values))
            if typical < 0:
                raise ParameterError(
                    f"data column 'fz': the loads are negative (median {typical:.4g} N): these look like SAE tire "
                    f"axes (z down); read the file with convention='SAE' (vehdyn.tire.read_tire_data) or convert "
                    f"with vehdyn.conventions.tire_forces_sae_to_iso_w", key="fz", value=typical)
            largest = float(values.max())
            if largest < low:
                raise ParameterError(f"data column 'fz': the largest load is {largest:.4g} N, below any tire test's "
                                     f"({low:g} N): it looks like kN; {how('fz', 'kN')}", key="fz", value=largest)
            if largest > high:
                raise ParameterError(f"data column 'fz': a load of {largest:.4g} N is beyond any tire's ({high:g} N): "
                                     f"check the unit; {how('fz', 'N')} if it is right", key="fz", value=largest)
            continue
        if name == "pressure":
            largest = float(np.max(np.abs(values)))
            if largest < low:
                unit = "bar" if largest < 15 else "psi" if largest < 100 else "kPa"
                raise ParameterError(f"data column 'pressure': pressures of at most {largest:.4g} Pa are not tire "
                                     f"pressures: they look like {unit}; {how('pressure', unit)}", key="pressure",
                                     value=largest)
            if largest > high:
                raise ParameterError(f"data column 'pressure': {largest:.4g} Pa is beyond any tire's pressure "
                                     f"({high:g} Pa); {how('pressure', 'Pa')} if it is right", key="pressure",
                                     value=largest)
            continue
        extreme = float(values[np.argmax(np.abs(values))])
        if low <= extreme <= high:
            continue
        unit, word = _LIKELY_UNIT[name]
        what = {"alpha": "slip angles", "gamma": "inclination angles", "kappa": "slip ratios",
                "vx": "speeds"}[name]
        raise ParameterError(f"data column {name!r}: {what} reach {extreme:.4g} {_SI_UNIT[_QUANTITY[name]]}, beyond "
                             f"+-{high:.4g}: they look like {word}; {how(name, unit)}", key=name, value=extreme)


def _split_name(header: str):
    """``"alpha [deg]"`` -> ("alpha", "deg"); ``"Fz"`` -> ("Fz", None)."""
    match = re.fullmatch(r"\s*([^\[\(]+?)\s*(?:[\[\(]\s*([^\]\)]*)\s*[\]\)])?\s*", header)
    if match is None:
        return header.strip(), None
    return match.group(1), match.group(2)


def _is_consortium(lines) -> int | None:
    """Index of the channel-name row when ``lines`` look like a test-consortium run file, else None."""
    for i in range(min(2, len(lines))):
        tokens = lines[i].split()
        if {"SA", "FZ", "FY"} <= set(tokens) or {"SL", "FZ", "FX"} <= set(tokens):
            return i
    return None


def _numbers(rows, names, path):
    """Rows ``(line number, text fields)`` -> float array (n_rows, n_columns); errors name the line
    and the column."""
    data = np.empty((len(rows), len(names)))
    for r, (line, fields) in enumerate(rows):
        if len(fields) != len(names):
            raise TireDataError(f"{len(fields)} fields, the header names {len(names)}", path=path, line=line)
        for j, field in enumerate(fields):
            text = field.strip()
            try:
                data[r, j] = float(text) if text else math.nan
            except ValueError:
                shown = text if len(text) <= 40 else f"{text[:40]}... ({len(text)} characters)"
                raise TireDataError(f"column {names[j]!r}: {shown!r} is not a number", path=path, line=line,
                                    column=names[j]) from None
    return data


def _to_frame(columns, sae, path):
    """Canonical SI columns (dict of arrays) -> ISO-W DataFrame, converting from SAE if ``sae``."""
    import pandas as pd

    from vehdyn.conventions import tire_forces_sae_to_iso_w, tire_slips_sae_to_iso_w

    if sae:
        n = len(next(iter(columns.values())))
        zero = np.zeros(n)
        if {"kappa", "alpha", "gamma"} & set(columns):
            slips = tire_slips_sae_to_iso_w(columns.get("kappa", zero), columns.get("alpha", zero),
                                            columns.get("gamma", zero))
            for name in ("kappa", "alpha", "gamma"):
                if name in columns:
                    columns[name] = np.asarray(getattr(slips, name), dtype=float)
        loads = tire_forces_sae_to_iso_w(*(columns.get(name, zero) for name in ("fx", "fy", "fz", "mx", "my", "mz")))
        for name in ("fx", "fy", "fz", "mx", "my", "mz"):
            if name in columns:
                columns[name] = np.asarray(getattr(loads, name), dtype=float)
    order = [name for name in CANONICAL_COLUMNS if name in columns]
    frame = pd.DataFrame({name: columns[name] for name in order})
    frame.attrs["units"] = {name: _SI_UNIT[_QUANTITY[name]] for name in order}
    frame.attrs["source"] = str(path)
    return frame


MAX_FIELD = 100_000
"""Characters a CSV header line may hold."""

_SI_UNIT = {"force": "N", "moment": "N*m", "ratio": "-", "angle": "rad", "speed": "m/s", "pressure": "Pa",
            "rate": "rad/s", "length": "m"}


def read_tire_data(path, *, convention: str = "ISO-W", units=None):
    """Read measured tire data into canonical ISO-W SI columns.

    Parameters
    ----------
    path : str or pathlib.Path
        A CSV file with a header row, or a flat-track test-consortium run file (see the module
        docstring for both layouts).
    convention : {"ISO-W", "SAE"}
        Axis system of a CSV file's slips, forces and moments. Consortium run files are SAE by
        definition and converted regardless.
    units : dict, optional
        Unit of a CSV column, by canonical name (``{"alpha": "deg", "fz": "kN"}``); overrides a unit
        in the header. Columns without a unit are taken as SI, and must look like it
        (:func:`check_units`).

    Returns
    -------
    pandas.DataFrame
        The canonical columns the file has (:data:`CANONICAL_COLUMNS`), ISO-W, SI and radians;
        ``attrs["units"]`` (each column's SI unit), ``attrs["source"]`` (the path) and
        ``attrs["stated_units"]`` (the columns whose unit the file or ``units`` stated; the fits
        do not judge those again). Rows with NaN are kept (the fit drops them and says how many).

    Raises
    ------
    TireDataError
        (a :class:`~vehdyn.errors.TirFileError`) If the file is empty, has no known column, a
        field that is not a number, a row of the wrong length or one the csv module cannot read
        (a field beyond its size limit), an over-long header line (message: file, line, column), or
        an unknown unit.
    ParameterError
        If ``convention`` or ``units`` is not understood, or an unlabelled column's values are not
        plausible in SI units (the message names the file, the column and the unit it looks like).

    Examples
    --------
    A CSV file whose header states the units:

    >>> import tempfile, pathlib
    >>> from vehdyn.tire import read_tire_data
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "sweep.csv"
    >>> _ = path.write_text("load [kN],slip_angle [deg],FY\\n4,2,-2800\\n4,4,-4300\\n")
    >>> frame = read_tire_data(path)
    >>> frame[["fz", "alpha", "fy"]].round(4).values.tolist()
    [[4000.0, 0.0349, -2800.0], [4000.0, 0.0698, -4300.0]]

    The same slip angles without a unit are refused, since 4 rad is no slip angle:

    >>> _ = path.write_text("fz,alpha,fy\\n4000,2,-2800\\n4000,4,-4300\\n")
    >>> read_tire_data(path)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    vehdyn.errors.ParameterError: ...sweep.csv: data column 'alpha': slip angles reach 4 rad, beyond +-1.571: ...
    >>> float(read_tire_data(path, units={"alpha": "deg"})["alpha"].iloc[1].round(4))
    0.0698
    """
    if convention not in ("ISO-W", "SAE"):
        raise ParameterError(f"convention must be 'ISO-W' or 'SAE', got {convention!r}", key="convention",
                             value=convention)
    units = dict(units or {})
    for name in units:
        if name not in _QUANTITY:
            raise ParameterError(f"units: {name!r} is not a canonical column ({', '.join(CANONICAL_COLUMNS)})",
                                 key="units", value=name)
    path = Path(path)
    text = path.read_text(encoding="utf-8", errors="replace")
    lines = text.splitlines()
    if not any(line.strip() for line in lines):
        raise TireDataError("the file is empty", path=path, line=1)
    head = _is_consortium(lines)
    if head is not None:
        return _read_consortium(lines, head, path)
    return _read_csv(lines, path, convention == "SAE", units)


def _read_consortium(lines, head, path):
    # tab-separated files may have units with spaces ("deg C"); otherwise any whitespace separates
    split = (lambda line: [f.strip() for f in line.strip("\r\n").split("\t")]) if "\t" in lines[head] \
        else str.split
    names = split(lines[head])
    unit_row = split(lines[head + 1]) if head + 1 < len(lines) else []
    if len(unit_row) != len(names):
        raise TireDataError(f"the unit row has {len(unit_row)} fields, the channel row {len(names)}", path=path,
                            line=head + 2)
    wanted = dict(_CONSORTIUM)
    if "SL" not in names and "SR" in names:
        wanted["SR"] = "kappa"
    rows = [(i + 1, split(line)) for i, line in enumerate(lines) if i >= head + 2 and line.strip()]
    data = _numbers(rows, names, path)
    columns = {}
    for j, channel in enumerate(names):
        name = wanted.get(channel)
        if name is None:
            continue
        columns[name] = data[:, j] * _unit_factor(name, unit_row[j], path, head + 2)
    frame = _to_frame(columns, True, path)
    frame.attrs["stated_units"] = sorted(columns)  # the unit row states every channel's unit
    return frame


def _read_csv(lines, path, sae, units):
    import csv

    header_index = next(i for i, line in enumerate(lines) if line.strip())
    header_line = lines[header_index]
    if len(header_line) > MAX_FIELD:
        raise TireDataError(f"the header line has {len(header_line)} characters (at most {MAX_FIELD}): not a CSV "
                            f"header", path=path, line=header_index + 1)
    delimiters = [d for d in ",;\t" if d in header_line]
    try:
        dialect = csv.Sniffer().sniff(header_line, delimiters=",;\t") if delimiters else csv.excel
    except csv.Error:  # the sniffer gives up on some headers: the most frequent delimiter
        dialect = type("Header", (csv.excel,), {"delimiter": max(delimiters, key=header_line.count)})
    reader = csv.reader(lines[header_index:], dialect)
    try:
        reader = list(reader)
    except csv.Error as error:  # e.g. a field beyond the csv module's size limit, a NUL byte
        raise TireDataError(f"not a readable CSV row ({error})", path=path,
                            line=header_index + reader.line_num) from None
    header = reader[0]
    names, header_units, keep = [], {}, []
    for j, field in enumerate(header):
        raw, unit = _split_name(field)
        name = _ALIAS_TO_NAME.get(raw.strip().lower())
        names.append(raw.strip())
        if name is None:
            continue
        if name in {names_[1] for names_ in keep}:
            raise TireDataError(f"column {raw!r} duplicates {name!r}", path=path, line=header_index + 1, column=raw)
        keep.append((j, name))
        if unit is not None:
            header_units[name] = unit
    if not keep:
        raise TireDataError(f"no known column in the header {header!r}; expected some of "
                            f"{', '.join(CANONICAL_COLUMNS)} (or aliases such as slip_angle, camber, load)",
                            path=path, line=header_index + 1)
    rows = [(header_index + 2 + i, r) for i, r in enumerate(reader[1:]) if any(field.strip() for field in r)]
    data = _numbers(rows, names, path)
    columns = {}
    for j, name in keep:
        unit = units.get(name, header_units.get(name))
        factor = 1.0 if unit is None else _unit_factor(name, unit, path, header_index + 1)
        columns[name] = data[:, j] * factor
    frame = _to_frame(columns, sae, path)
    stated = sorted(set(units) | set(header_units))
    try:
        check_units(frame, stated=stated)
    except ParameterError as error:
        raise ParameterError(f"{path}: {error}", key=error.key, value=error.value) from None
    frame.attrs["stated_units"] = stated
    return frame
