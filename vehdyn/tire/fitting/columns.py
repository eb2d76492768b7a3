"""Measured data in for the fits: canonical columns, stated units, plausibility, non-finite rows."""

from __future__ import annotations

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.tire.tire_data import check_units, to_si

__all__ = ["FIT_COLUMNS", "canonical_columns", "drop_nonfinite"]

FIT_COLUMNS = ("fz", "kappa", "alpha", "gamma", "vx", "pressure", "fx", "fy", "mx", "my", "mz")
"""The columns the fits use (names of :func:`vehdyn.tire.read_tire_data`)."""


def canonical_columns(data, units=None):
    """DataFrame or mapping -> dict of float arrays of the columns in :data:`FIT_COLUMNS`, SI.

    Parameters
    ----------
    data : pandas.DataFrame or mapping of str to array_like
        Columns by canonical name [SI, or the unit given in ``units``]; others are ignored.
    units : dict of str to str, optional
        Unit of a column that is not SI (``{"alpha": "deg"}``; names of
        :data:`vehdyn.tire.tire_data.UNIT_FACTORS`); converted here. A column named here, or in
        ``data.attrs["stated_units"]`` (set by :func:`~vehdyn.tire.read_tire_data` for the units a
        file states), is taken as the user says; every other column must lie in
        :data:`~vehdyn.tire.tire_data.PLAUSIBLE_RANGES`.

    Returns
    -------
    dict of str to ndarray
        The columns present, 1-d float arrays of one length [SI].

    Raises
    ------
    ParameterError
        If ``data`` is not a mapping, lacks ``fz``, has a non-numeric column or columns of different
        lengths, ``units`` names an unknown column or unit, or a column's values are implausible in
        SI units (the message names the column and the unit it most likely has).
    """
    try:
        keys = list(data.keys())
    except AttributeError:
        raise ParameterError(f"data must be a DataFrame or a mapping of columns, got {type(data).__name__}",
                             key="data", value=type(data).__name__) from None
    columns = {}
    for key in keys:
        if key in FIT_COLUMNS:
            try:
                columns[key] = np.asarray(data[key], dtype=float).ravel()
            except (TypeError, ValueError):
                raise ParameterError(f"data column {key!r} is not numeric", key=key, value=None) from None
    if "fz" not in columns:
        raise ParameterError(f"data needs a column 'fz' (normal load [N]); it has {', '.join(map(str, keys))}",
                             key="fz", value=None)
    lengths = {len(v) for v in columns.values()}
    if len(lengths) != 1:
        raise ParameterError(f"data columns differ in length: { {k: len(v) for k, v in columns.items()} }",
                             key="data", value=None)
    try:
        units = dict(units or {})
    except (TypeError, ValueError):
        raise ParameterError(f"units must be a mapping of column to unit, got {units!r}", key="units",
                             value=units) from None
    for name, unit in units.items():
        if name not in columns:
            raise ParameterError(f"units[{name!r}]: the data have no column {name!r} (they have "
                                 f"{', '.join(columns)})", key="units", value=name)
        columns[name] = to_si(name, columns[name], unit)
    stated = set(units) | set(getattr(data, "attrs", {}).get("stated_units", ()))
    check_units(columns, stated=stated)
    return columns


def drop_nonfinite(columns, messages):
    """The columns without the rows that hold a NaN or an infinity.

    Parameters
    ----------
    columns : dict of str to ndarray
        Columns of one length (with ``fz``) [SI units of each column].
    messages : list of str
        Receives the count of rows dropped, if any.

    Returns
    -------
    dict of str to ndarray
        The finite rows.
    """
    bad = np.zeros(len(columns["fz"]), dtype=bool)
    for values in columns.values():
        bad |= ~np.isfinite(values)
    if bad.any():
        messages.append(f"dropped {int(bad.sum())} of {bad.size} rows with NaN or inf")
        columns = {k: v[~bad] for k, v in columns.items()}
    return columns
