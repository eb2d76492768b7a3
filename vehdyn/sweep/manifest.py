"""What produced a sweep's results: the manifest a results folder keeps, and how two compare.

A sweep written to ``out=`` records in ``_vehdyn_sweep.json`` (a name Parquet readers skip) what
its rows depend on: the target's identity (a Scene's fields and its vehicle's parameters, the
rung and the solver options; or a function's qualified name, a hash of its source and the values
its closure and defaults hold), the parameter names, the grid or sample design and its seed, the
metrics, the number of variants, a hash of the parameter table and the vehdyn version. Each chunk
file carries the manifest's ``id`` in its Parquet metadata, so that a folder's files are known to
be this sweep's. ``resume=True`` compares the manifest of the folder with the one of the sweep
asked for and names every difference (:func:`differences`).

What the manifest leaves out because it does not change a result: the executor, the chunk size,
the progress bar. What it cannot see: the module-level globals a function reads (a constant
edited between two runs of the same function source).
"""

from __future__ import annotations

import dataclasses
import functools
import hashlib
import inspect
import json
import marshal
import math
import re
import types
from collections.abc import Mapping
from pathlib import Path

import numpy as np

__all__ = ["FORMAT", "canonical", "describe", "differences", "table_digest"]

#: Manifest format; a folder written in another format is another sweep's.
FORMAT = 1

_SMALL = 64  # sequences up to this length are kept whole, longer ones by their hash
_DEPTH = 8  # nesting depth followed before an object is named by its type only


def _qualname(obj) -> str:
    module = getattr(obj, "__module__", None) or ""
    name = getattr(obj, "__qualname__", None) or getattr(obj, "__name__", None) or type(obj).__qualname__
    return f"{module}.{name}" if module else name


def _digest(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def _source_digest(function) -> str:
    """sha256 of the function's source, or of its code object when the source is not available
    (a function typed at the prompt or built by ``exec``)."""
    try:
        return _digest(inspect.getsource(function).encode())
    except (OSError, TypeError):
        return _digest(marshal.dumps(function.__code__))


def _array(values: np.ndarray, depth: int, seen: set):
    if values.dtype.kind in "biufc" and values.size > _SMALL:
        data = np.ascontiguousarray(values)
        return {"array": list(values.shape), "dtype": str(values.dtype), "sha256": _digest(data.tobytes())}
    if values.dtype.kind in "biufc":
        return [_number(v) for v in values.ravel().tolist()] if values.ndim <= 1 else \
            {"array": list(values.shape), "values": [_number(v) for v in values.ravel().tolist()]}
    return [canonical(v, depth + 1, seen) for v in values.ravel().tolist()]


def _number(value):
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, complex):
        return {"complex": [_number(value.real), _number(value.imag)]}
    value = float(value)
    return value if math.isfinite(value) else repr(value)  # JSON has no inf or NaN


def canonical(obj, depth: int = 0, seen: set | None = None):
    """A JSON-able description of ``obj`` that is equal for equal values in any process.

    Numbers, text, ``None``, mappings and sequences map to themselves (numpy scalars to Python
    numbers, non-finite floats to ``"inf"``/``"nan"``, long numeric sequences and arrays to their
    shape and sha256); dataclasses and other objects to their type's qualified name and their
    public attributes; functions to their qualified name, the sha256 of their source and the values
    of their defaults and closure; frozen ``scipy.stats`` laws to the law's name and arguments.
    Memory addresses never enter it.

    Parameters
    ----------
    obj : object
        Anything a sweep's identity holds: a Scene, a Vehicle, a function, a distribution, ...
    depth : int
        Nesting depth reached (objects deeper than 8 levels are named by their type only).
    seen : set, optional
        ``id`` of the objects being described (a cycle is named by its type).

    Returns
    -------
    None, bool, int, float, str, list or dict
    """
    if obj is None or isinstance(obj, (bool, str)):
        return obj
    if isinstance(obj, (int, float, complex, np.number, np.bool_)):
        return _number(obj)
    if isinstance(obj, Path):
        return str(obj)
    if isinstance(obj, bytes):
        return {"bytes": _digest(obj)}
    seen = set() if seen is None else seen
    if depth > _DEPTH or id(obj) in seen:
        return {"type": _qualname(type(obj))}
    seen = seen | {id(obj)}
    deeper = functools.partial(canonical, depth=depth + 1, seen=seen)
    if isinstance(obj, np.ndarray):
        return _array(obj, depth, seen)
    if isinstance(obj, Mapping):
        return {str(k): deeper(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        if len(obj) > _SMALL and all(isinstance(v, (int, float, np.number)) and not isinstance(v, bool) for v in obj):
            return _array(np.asarray(obj), depth, seen)
        return [deeper(v) for v in obj]
    if isinstance(obj, (set, frozenset)):
        return sorted((deeper(v) for v in obj), key=lambda v: json.dumps(v, sort_keys=True))
    if type(obj).__module__.startswith("pandas") and (hasattr(obj, "columns") or hasattr(obj, "to_frame")):
        frame = obj if hasattr(obj, "columns") else obj.to_frame()  # a DataFrame, Series or Index: its values
        return {"type": _qualname(type(obj)), "sha256": table_digest(frame.reset_index(drop=not hasattr(obj, "index")))}
    if hasattr(obj, "dist") and hasattr(obj, "ppf") and hasattr(obj, "args"):  # a frozen scipy.stats law
        return {"law": getattr(obj.dist, "name", _qualname(type(obj.dist))), "args": deeper(list(obj.args)),
                "kwds": deeper(dict(obj.kwds))}
    if isinstance(obj, functools.partial):
        return {"partial": deeper(obj.func), "args": deeper(list(obj.args)), "keywords": deeper(dict(obj.keywords))}
    if isinstance(obj, types.FunctionType):
        cells = [c.cell_contents if _filled(c) else None for c in (obj.__closure__ or ())]
        return {"function": _qualname(obj), "source_sha256": _source_digest(obj),
                "defaults": deeper(list(obj.__defaults__ or ())), "kwdefaults": deeper(dict(obj.__kwdefaults__ or {})),
                "closure": deeper(dict(zip(obj.__code__.co_freevars, cells)))}
    if isinstance(obj, types.MethodType):
        return {"method": deeper(obj.__func__), "self": deeper(obj.__self__)}
    if isinstance(obj, (type, types.ModuleType, types.BuiltinFunctionType)):
        return {"name": _qualname(obj)}
    if dataclasses.is_dataclass(obj):
        return {"type": _qualname(type(obj)),
                **{f.name: deeper(getattr(obj, f.name)) for f in dataclasses.fields(obj)}}
    state = _state(obj)
    if state is not None:
        return {"type": _qualname(type(obj)), **{k: deeper(v) for k, v in state.items()}}
    return {"type": _qualname(type(obj)), "repr": re.sub(r" at 0x[0-9a-fA-F]+", "", repr(obj))}


def _filled(cell) -> bool:
    try:
        cell.cell_contents
    except ValueError:  # an empty cell
        return False
    return True


def _state(obj) -> dict | None:
    """An object's public attributes (``__dict__`` and ``__slots__``; its private ones when it has
    no public one - private attributes are often caches filled on first use), or None."""
    state = dict(getattr(obj, "__dict__", {}) or {})
    for klass in type(obj).__mro__:
        for name in getattr(klass, "__slots__", ()):
            if name not in ("__dict__", "__weakref__") and hasattr(obj, name):
                state.setdefault(name, getattr(obj, name))
    state = {k: v for k, v in state.items() if not (k.startswith("__") and k.endswith("__"))}
    public = {k: v for k, v in state.items() if not k.startswith("_")}
    return public or state or None


def table_digest(table) -> str:
    """sha256 of a parameter table: its column names, dtypes and values in order.

    Parameters
    ----------
    table : pandas.DataFrame
        One row per variant, one column per parameter.

    Returns
    -------
    str
        The hexadecimal digest.
    """
    h = hashlib.sha256()
    h.update(json.dumps([str(c) for c in table.columns]).encode())
    for name in table.columns:
        values = table[name].to_numpy()
        if values.dtype.kind in "biufc":
            h.update(str(values.dtype).encode())
            h.update(np.ascontiguousarray(values).tobytes())
        else:
            h.update(json.dumps(canonical(list(values)), sort_keys=True).encode())
    return h.hexdigest()


def describe(*, target, parameters, metrics, design, table, version: str) -> dict:
    """The manifest of a sweep (a JSON-able dict with its ``id``).

    Parameters
    ----------
    target : dict
        The target's identity (``SceneTarget.identity()`` or ``FunctionTarget.identity()``).
    parameters : sequence of str
        The parameter names, in the table's order.
    metrics : sequence of str or None
        The metric names (None: every key a function returns).
    design : mapping or None
        How the table was made (grid, samples, n, sampling, seed); None for a table given as is.
    table : pandas.DataFrame
        The parameter table (its digest is recorded).
    version : str
        The vehdyn version.

    Returns
    -------
    dict
        ``format``, ``vehdyn``, ``target``, ``parameters``, ``metrics``, ``design``,
        ``variants``, ``table_sha256`` and ``id`` (16 hexadecimal digits of the sha256 of the
        rest): the same for two sweeps that give the same rows.
    """
    manifest = {"format": FORMAT, "written_by": "vehdyn.sweep", "vehdyn": version, "target": canonical(target),
                "parameters": list(parameters), "metrics": None if metrics is None else list(metrics),
                "design": canonical(design), "variants": int(len(table)), "table_sha256": table_digest(table)}
    manifest = json.loads(json.dumps(manifest))  # tuples -> lists: equal to what the folder reads back
    manifest["id"] = _digest(json.dumps(manifest, sort_keys=True).encode())[:16]
    return manifest


def _flat(value, prefix: str, out: dict) -> dict:
    if isinstance(value, dict) and value:
        for k, v in value.items():
            _flat(v, f"{prefix}.{k}" if prefix else str(k), out)
    else:
        out[prefix] = value
    return out


def _show(value) -> str:
    text = "absent" if value is _ABSENT else json.dumps(value, sort_keys=True)
    return text if len(text) <= 70 else text[:67] + "..."


_ABSENT = object()
_ORDER = ("format", "written_by", "vehdyn", "target", "design", "parameters", "variants", "metrics", "table_sha256")


def differences(stored: Mapping, wanted: Mapping, limit: int = 6) -> list[str]:
    """What differs between the manifest of a folder and that of the sweep asked for.

    Parameters
    ----------
    stored : mapping
        The folder's manifest.
    wanted : mapping
        This sweep's manifest (:func:`describe`).
    limit : int
        At most this many differences are named (the count of the others follows).

    Returns
    -------
    list of str
        One line per difference, ``"<dotted key>: <folder's value> in the folder, <this sweep's>
        here"``, the target first; empty when the two describe the same sweep.
    """
    lines = []
    for section in _ORDER:
        a = _flat(stored.get(section, _ABSENT), section, {})
        b = _flat(wanted.get(section, _ABSENT), section, {})
        for key in list(a) + [k for k in b if k not in a]:
            x, y = a.get(key, _ABSENT), b.get(key, _ABSENT)
            if x != y:
                lines.append(f"{key}: {_show(x)} in the folder, {_show(y)} here")
    if len(lines) > limit:
        lines = lines[:limit] + [f"... and {len(lines) - limit} more"]
    return lines
