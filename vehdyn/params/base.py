"""Frozen, validated parameter dataclasses and their TOML round trip.

Every parameter group is a ``@dataclass(frozen=True, kw_only=True)`` subclass of
:class:`ParameterSet` whose fields are declared with :func:`parameter`: a unit, a description and
bounds. Construction checks every field (type, finiteness, bounds) and raises
:class:`~vehdyn.ParameterError` naming the field's dotted path and the bad value; ``from_dict``
adds the checks for missing and unknown keys. ``dataclasses.replace`` makes validated variants.
"""

from __future__ import annotations

import dataclasses
import math
import tomllib
import typing
from pathlib import Path
from typing import Any, Mapping

from ..errors import ParameterError

__all__ = ["ParameterSet", "parameter", "text", "load_toml", "dump_toml"]

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
    """A numeric field with its unit, description and bounds (``gt``, ``ge``, ``lt``, ``le``).

    ``default=None`` makes the parameter optional: ``None`` is then accepted and means "not given".
    """
    meta = {"unit": unit, "description": description, "gt": gt, "ge": ge, "lt": lt, "le": le}
    return dataclasses.field(default=default, metadata=meta)


def text(description: str, *, default: Any = _MISSING, choices: tuple[str, ...] | None = None):
    """A string field (a name, a file name, a model name) with optional allowed values."""
    return dataclasses.field(default=default, metadata={"unit": "", "description": description,
                                                         "choices": choices, "text": True})


def _type_name(value: Any) -> str:
    return type(value).__name__


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
        hints = typing.get_type_hints(type(self))
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
            if isinstance(value, bool) or not isinstance(value, (int, float)):
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
            if isinstance(value, int):
                object.__setattr__(self, f.name, float(value))

    # ------------------------------------------------------------------ dict round trip
    @classmethod
    def from_dict(cls, data: Mapping[str, Any], *, path: str = ""):
        """Build from a (nested) mapping, checking for missing and unknown keys.

        Errors name the dotted path of the key (``suspension.front_spring_rate``).
        """
        if not isinstance(data, Mapping):
            where = path.rstrip(".")
            raise ParameterError(f"{where or cls.__name__} must be a table of parameters, got "
                                 f"{_type_name(data)} {data!r}", key=where or None, value=data)
        hints = typing.get_type_hints(cls)
        fields = {f.name: f for f in dataclasses.fields(cls)}
        unknown = [k for k in data if k not in fields]
        if unknown:
            key = f"{path}{unknown[0]}"
            raise ParameterError(f"unknown parameter {key!r} (value {data[unknown[0]]!r}); {cls.__name__} takes "
                                 f"{sorted(fields)}", key=key, value=data[unknown[0]])
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
            if path and exc.key and not exc.key.startswith(path):
                full = f"{path}{exc.key}"
                raise ParameterError(str(exc).replace(exc.key, full, 1), key=full, value=exc.value) from None
            raise

    def to_dict(self) -> dict[str, Any]:
        """A nested dict of plain values (the inverse of :meth:`from_dict`)."""
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
        """``{field: unit}`` of this group's numeric fields."""
        return {f.name: f.metadata["unit"] for f in dataclasses.fields(cls) if "unit" in f.metadata}

    def replace(self, **changes):
        """A validated copy with ``changes`` (``dataclasses.replace``)."""
        return dataclasses.replace(self, **changes)


def load_toml(cls: type[ParameterSet], path: str | Path) -> ParameterSet:
    """Load a parameter set of type ``cls`` from a TOML file."""
    path = Path(path)
    try:
        with path.open("rb") as fh:
            data = tomllib.load(fh)
    except FileNotFoundError:
        raise ParameterError(f"no such parameter file: {path}", key="path", value=str(path)) from None
    except tomllib.TOMLDecodeError as exc:
        raise ParameterError(f"{path}: not valid TOML ({exc})", key="path", value=str(path)) from None
    return cls.from_dict(data)


def _toml_value(value: Any) -> str:
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, bool):
        return "true" if value else "false"
    return repr(float(value))


def dump_toml(params: ParameterSet) -> str:
    """TOML text of a parameter set; ``load_toml`` reads it back to an equal object."""
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
