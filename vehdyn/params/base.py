"""Frozen, validated parameter dataclasses and their TOML round trip.

Every parameter group is a ``@dataclass(frozen=True, kw_only=True)`` subclass of
:class:`ParameterSet` whose fields are declared with :func:`parameter`: a unit, a description and
bounds. Construction checks every field (type, finiteness, bounds) and raises
:class:`~vehdyn.ParameterError` naming the field's dotted path and the bad value; ``from_dict``
adds the checks for missing and unknown keys. ``dataclasses.replace`` makes validated variants.
"""

from __future__ import annotations

import codecs
import dataclasses
import functools
import math
import os
import tomllib
import typing
from pathlib import Path
from typing import Any, Mapping

from vehdyn.errors import ParameterError
from vehdyn.params.checks import is_number

__all__ = ["ParameterSet", "parameter", "text", "read_toml", "load_toml", "dump_toml"]

_MISSING = dataclasses.MISSING


def parameter(
    unit: str,
    description: str,
    *,
    default: Any = _MISSING,
    gt: float | None = None,
    ge: float | None = None,
    lt: float | None = None,
    le: float | None = None,
):
    """A numeric field with its unit, description and bounds, for a :class:`ParameterSet`.

    Parameters
    ----------
    unit : str
        The unit, as written in messages and TOML comments (``"kg"``, ``"N/m"``, ``"-"`` for a
        ratio).
    description : str
        What the parameter is (shown in the API documentation and in "missing parameter" errors).
    default : float or None, optional
        Default value [``unit``]; none: the parameter is required. ``default=None`` makes it
        optional: ``None`` is then accepted and means "not given".
    gt, ge, lt, le : float, optional
        Strict and non-strict lower and upper bounds [``unit``], checked on construction.

    Returns
    -------
    dataclasses.Field
        A field whose ``metadata`` holds the unit, description and bounds.
    """
    meta = {"unit": unit, "description": description, "gt": gt, "ge": ge, "lt": lt, "le": le}
    return dataclasses.field(default=default, metadata=meta)


def text(description: str, *, default: Any = _MISSING, choices: tuple[str, ...] | None = None):
    """A string field (a name, a file name, a model name) with optional allowed values.

    Parameters
    ----------
    description : str
        What the field is.
    default : str or None, optional
        Default value; none: the field is required (``None``: optional, "not given").
    choices : tuple of str, optional
        The allowed values (a ParameterError lists them for any other).

    Returns
    -------
    dataclasses.Field
        A field marked as text in its ``metadata``.
    """
    return dataclasses.field(default=default, metadata={"unit": "", "description": description,
                                                         "choices": choices, "text": True})


def _type_name(value: Any) -> str:
    return type(value).__name__


@functools.lru_cache(maxsize=None)
def _type_hints(cls) -> dict:
    """``typing.get_type_hints`` of a parameter class, once per class (it costs about a
    millisecond: a sweep validates thousands of variants)."""
    return typing.get_type_hints(cls)


@dataclasses.dataclass(frozen=True, kw_only=True)
class ParameterSet:
    """Base of vehdyn's parameter groups: validation on construction, dict and TOML round trip."""

    def __post_init__(self):
        self._validate_fields()
        self.check()

    # subclasses add cross-field checks here
    def check(self) -> None:
        """Cross-field checks (override); raise :class:`ParameterError` naming the fields."""

    def _path(self, name: str) -> str:
        prefix = getattr(self, "_prefix", "")
        return f"{prefix}{name}"

    def _validate_fields(self) -> None:
        hints = _type_hints(type(self))
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            key = f.name
            hint = hints.get(f.name)
            if isinstance(hint, type) and issubclass(hint, ParameterSet):
                if not isinstance(value, hint):
                    raise ParameterError(f"{key} must be a {hint.__name__}, got {_type_name(value)} {value!r}",
                                         key=key, value=value)
                continue
            meta = f.metadata
            if meta.get("text"):
                if value is None and f.default is None:
                    continue
                if not isinstance(value, str):
                    raise ParameterError(f"{key} must be a string, got {_type_name(value)} {value!r}",
                                         key=key, value=value)
                choices = meta.get("choices")
                if choices and value not in choices:
                    raise ParameterError(f"{key} must be one of {list(choices)}, got {value!r}", key=key, value=value)
                continue
            if "unit" not in meta:
                continue
            if value is None and f.default is None:  # an optional parameter left unset
                continue
            if not is_number(value):
                raise ParameterError(f"{key} must be a number [{meta['unit']}], got {_type_name(value)} {value!r}",
                                     key=key, value=value)
            if not math.isfinite(value):
                raise ParameterError(f"{key} must be finite, got {value!r}", key=key, value=value)
            for bound, ok, word in (("gt", lambda v, b: v > b, ">"), ("ge", lambda v, b: v >= b, ">="),
                                    ("lt", lambda v, b: v < b, "<"), ("le", lambda v, b: v <= b, "<=")):
                b = meta.get(bound)
                if b is not None and not ok(value, b):
                    raise ParameterError(f"{key} must be {word} {b} [{meta['unit']}], got {value!r}",
                                         key=key, value=value)
            if not isinstance(value, float):  # an int or a numpy scalar other than float64
                object.__setattr__(self, f.name, float(value))

    # ------------------------------------------------------------------ dict round trip
    @classmethod
    def from_dict(cls, data: Mapping[str, Any], *, path: str = ""):
        """Build from a (nested) mapping, checking for missing and unknown keys.

        Parameters
        ----------
        data : Mapping
            ``{field: value}``, with a nested mapping for each nested group (a TOML table).
        path : str, optional
            Dotted prefix of this group in the errors (``"suspension."``); empty at the top.

        Returns
        -------
        ParameterSet
            An instance of ``cls``, validated.

        Raises
        ------
        ParameterError
            For a missing, unknown, ill-typed or out-of-range parameter, naming the dotted path of
            its key (``suspension.front_spring_rate``).
        """
        if not isinstance(data, Mapping):
            where = path.rstrip(".")
            raise ParameterError(f"{where or cls.__name__} must be a table of parameters, got "
                                 f"{_type_name(data)} {data!r}", key=where or None, value=data)
        hints = typing.get_type_hints(cls)
        fields = {f.name: f for f in dataclasses.fields(cls)}
        cls._reject_unknown(data, path)
        kwargs = {}
        for name, f in fields.items():
            key = f"{path}{name}"
            if name not in data:
                if f.default is _MISSING and f.default_factory is _MISSING:
                    raise ParameterError(f"missing parameter {key!r} ({f.metadata.get('description', '')}"
                                         f"{', ' + f.metadata['unit'] if f.metadata.get('unit') else ''})",
                                         key=key, value=None)
                continue
            hint = hints.get(name)
            if isinstance(hint, type) and issubclass(hint, ParameterSet):
                kwargs[name] = hint.from_dict(data[name], path=f"{key}.")
            else:
                kwargs[name] = data[name]
        try:
            return cls(**kwargs)
        except ParameterError as exc:
            raise _with_prefix(exc, path) from None

    def to_dict(self) -> dict[str, Any]:
        """A nested dict of plain values (the inverse of :meth:`from_dict`).

        Returns
        -------
        dict
            ``{field: value}`` with a nested dict per group; optional fields left at ``None`` are
            omitted.
        """
        out: dict[str, Any] = {}
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            if isinstance(value, ParameterSet):
                out[f.name] = value.to_dict()
            elif value is not None:
                out[f.name] = value
        return out

    @classmethod
    def units(cls) -> dict[str, str]:
        """The units of this group's numeric fields.

        Returns
        -------
        dict of str to str
            ``{field: unit}`` (``""`` for text fields).
        """
        return {f.name: f.metadata["unit"] for f in dataclasses.fields(cls) if "unit" in f.metadata}

    @classmethod
    def _reject_unknown(cls, data: Mapping[str, Any], path: str = "") -> None:
        """Raise :class:`ParameterError` for the first key of ``data`` that is not a field of ``cls``."""
        fields = {f.name for f in dataclasses.fields(cls)}
        unknown = [k for k in data if k not in fields]
        if unknown:
            key = f"{path}{unknown[0]}"
            raise ParameterError(f"unknown parameter {key!r} (value {data[unknown[0]]!r}); {cls.__name__} takes "
                                 f"{sorted(fields)}", key=key, value=data[unknown[0]])

    def replace(self, **changes):
        """A validated copy with ``changes``; ``group__field=value`` changes a field of a nested group.

        Parameters
        ----------
        **changes
            New values by field name. A double underscore reaches into a nested parameter group
            (``mass__mass=1500.0`` changes ``self.mass.mass``), to any depth.

        Returns
        -------
        ParameterSet
            A new, validated object of the same type; ``self`` is unchanged (frozen).

        Raises
        ------
        ParameterError
            If a name is not a field (or not a nested group), or a new value fails validation; the
            message names the dotted path (``mass.mass``) and the value.

        Examples
        --------
        >>> import vehdyn
        >>> sedan = vehdyn.load_vehicle("sedan")
        >>> sedan.replace(mass__mass=1500.0).mass.mass
        1500.0
        """
        return self._replace(changes, path="")

    def _replace(self, changes: Mapping[str, Any], path: str):
        nested: dict[str, dict[str, Any]] = {}
        flat: dict[str, Any] = {}
        for key, value in changes.items():
            group, sep, rest = key.partition("__")
            if sep and group and rest:
                nested.setdefault(group, {})[rest] = value
            else:
                flat[key] = value
        self._reject_unknown(flat, path)
        names = {f.name for f in dataclasses.fields(self)}
        for group, fields in nested.items():
            if group not in names:
                key = f"{path}{group}"
                given = ", ".join(f"{group}__{f}={v!r}" for f, v in fields.items())
                raise ParameterError(f"unknown parameter group {key!r} (in {given}); {type(self).__name__} takes "
                                     f"{sorted(names)}", key=key, value=fields)
            member = getattr(self, group)
            if not isinstance(member, ParameterSet):
                key = f"{path}{group}"
                raise ParameterError(f"{key!r} is a parameter, not a group of parameters: cannot set "
                                     f"{', '.join(f'{group}__{f}' for f in fields)}", key=key, value=fields)
            if group in flat:
                raise ParameterError(f"{path}{group} is given both whole and by field ({group}__...)",
                                     key=f"{path}{group}", value=flat[group])
            flat[group] = member._replace(fields, path=f"{path}{group}.")
        try:
            return dataclasses.replace(self, **flat)
        except ParameterError as exc:
            raise _with_prefix(exc, path) from None


def _with_prefix(exc: ParameterError, path: str) -> ParameterError:
    """``exc`` with its key (and the key in its message) prefixed by a group path (``"mass."``)."""
    if path and exc.key and not exc.key.startswith(path):
        full = f"{path}{exc.key}"
        return ParameterError(str(exc).replace(exc.key, full, 1), key=full, value=exc.value)
    return exc


_BOMS = ((codecs.BOM_UTF32_LE, "UTF-32"), (codecs.BOM_UTF32_BE, "UTF-32"),
         (codecs.BOM_UTF16_LE, "UTF-16"), (codecs.BOM_UTF16_BE, "UTF-16"))


def read_toml(path: str | Path) -> dict[str, Any]:
    """The table of a TOML file, with every failure as a :class:`ParameterError` naming the file.

    A UTF-8 byte-order mark (as some Windows editors write) is accepted; UTF-16/32 files, binary
    files, folders and unreadable files are reported as such.

    Parameters
    ----------
    path : str or os.PathLike
        The TOML file.

    Returns
    -------
    dict
        The parsed top-level table.

    Raises
    ------
    ParameterError
        If the file is missing, a folder, unreadable, not UTF-8 text or not valid TOML
        (key ``"path"``).
    """
    if not isinstance(path, (str, os.PathLike)):
        raise ParameterError(f"a parameter file must be given as a path (str or os.PathLike), got "
                             f"{_type_name(path)} {path!r}", key="path", value=path)
    path = Path(path)
    try:
        raw = path.read_bytes()
    except FileNotFoundError:
        raise ParameterError(f"no such parameter file: {path}", key="path", value=str(path)) from None
    except IsADirectoryError:
        raise ParameterError(f"{path} is a folder, not a parameter file", key="path", value=str(path)) from None
    except OSError as exc:
        if path.is_dir():  # Windows reports a folder as PermissionError
            raise ParameterError(f"{path} is a folder, not a parameter file", key="path", value=str(path)) from None
        raise ParameterError(f"cannot read parameter file {path}: {exc.strerror or exc}", key="path",
                             value=str(path)) from None
    if raw.startswith(codecs.BOM_UTF8):
        raw = raw[len(codecs.BOM_UTF8):]
    for bom, encoding in _BOMS:
        if raw.startswith(bom):
            raise ParameterError(f"{path} is encoded in {encoding}; TOML files must be UTF-8 (save it as UTF-8)",
                                 key="path", value=str(path))
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = raw.count(b"\n", 0, exc.start) + 1
        raise ParameterError(f"{path}: not a UTF-8 text file (byte 0x{raw[exc.start]:02x} at line {line}); "
                             "is it a TOML parameter file?", key="path", value=str(path)) from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ParameterError(f"{path}: not valid TOML ({exc})", key="path", value=str(path)) from None


def load_toml(cls: type[ParameterSet], path: str | Path) -> ParameterSet:
    """Load a parameter set of type ``cls`` from a TOML file.

    Parameters
    ----------
    cls : type
        A :class:`ParameterSet` subclass (:class:`~vehdyn.params.Vehicle`, ...).
    path : str or os.PathLike
        The TOML file (see :func:`read_toml` for the file checks).

    Returns
    -------
    ParameterSet
        ``cls.from_dict`` of the file's table.
    """
    return cls.from_dict(read_toml(path))


def _toml_value(value: Any) -> str:
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, bool):
        return "true" if value else "false"
    return repr(float(value))


def dump_toml(params: ParameterSet) -> str:
    """TOML text of a parameter set; :func:`load_toml` reads it back to an equal object.

    Parameters
    ----------
    params : ParameterSet
        The parameters (top-level values, then one ``[table]`` per nested group).

    Returns
    -------
    str
        The TOML text, each number written exactly (``repr``) with its unit as a comment.
    """
    lines: list[str] = []
    tables: list[tuple[str, ParameterSet]] = []
    for f in dataclasses.fields(params):
        value = getattr(params, f.name)
        if isinstance(value, ParameterSet):
            tables.append((f.name, value))
        elif value is not None:
            lines.append(f"{f.name} = {_toml_value(value)}")
    for name, table in tables:
        lines.append("")
        lines.append(f"[{name}]")
        for f in dataclasses.fields(table):
            value = getattr(table, f.name)
            if value is not None:
                unit = f.metadata.get("unit")
                comment = f"  # [{unit}]" if unit else ""
                lines.append(f"{f.name} = {_toml_value(value)}{comment}")
    return "\n".join(lines) + "\n"
