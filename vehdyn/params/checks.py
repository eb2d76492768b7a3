"""Checks of plain numbers given as arguments: one place for the message a bad value gets.

A number is any real scalar: a Python ``int`` or ``float`` or a numpy scalar (``np.float32``,
``np.int64``, ...), never a ``bool`` or a string (``"3"`` is refused rather than read as 3).
Counts (iterations, samples, repeats) are whole numbers; a grid whose size would not fit in memory
(more than :data:`MAX_SAMPLES` samples) is refused before it is allocated.
"""

from __future__ import annotations

import numbers

import numpy as np

from vehdyn.errors import ParameterError

__all__ = ["MAX_SAMPLES", "check_gains", "check_sample_count", "check_vehicle", "finite_number", "is_number",
           "positive_number", "whole_number"]

#: The most samples a time grid, a profile or a search grid built from an argument may have: 8 MB
#: per signal. A larger one is refused with a message that names the arguments that make it.
MAX_SAMPLES = 1_000_000


def is_number(value) -> bool:
    """True for a real scalar: int, float or a numpy scalar of either kind (never bool or str)."""
    return isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_))


def _as_float(value, name: str, what: str = "a number") -> float:
    if not is_number(value):
        raise ParameterError(f"{name} must be {what}, got {type(value).__name__} {value!r}", key=name, value=value)
    return float(value)


def check_gains(owner: str, *, positive=(), nonnegative=(), **values) -> dict:
    """Floats of ``values``; ParameterError naming a non-finite one or one of the wrong sign."""
    out = {}
    for name, value in values.items():
        if not is_number(value):
            raise ParameterError(f"{owner} gain {name} must be a number, got {value!r}", key=name, value=value)
        number = float(value)
        if not np.isfinite(number):
            raise ParameterError(f"{owner} gain {name} must be a finite number, got {value!r}", key=name, value=value)
        if name in positive and number <= 0:
            raise ParameterError(f"{owner} gain {name} must be > 0, got {value!r}", key=name, value=value)
        if name in nonnegative and number < 0:
            raise ParameterError(f"{owner} gain {name} must be >= 0, got {value!r}", key=name, value=value)
        out[name] = number
    return out


def positive_number(value, name: str, *, allow_zero: bool = False) -> float:
    """``float(value)``; ParameterError naming ``name`` unless it is a finite number > 0 (>= 0 with
    ``allow_zero``)."""
    v = _as_float(value, name)
    if not np.isfinite(v) or v < 0 or (v == 0 and not allow_zero):
        raise ParameterError(f"{name} must be a {'non-negative' if allow_zero else 'positive'} number, got {value!r}",
                             key=name, value=value)
    return v


def finite_number(value, name: str, *, positive: bool = False, minimum: float | None = None,
                  maximum: float | None = None) -> float:
    """``float(value)``; ParameterError naming ``name`` unless it is finite (and > 0 with
    ``positive``, >= ``minimum``, <= ``maximum`` where given)."""
    number = _as_float(value, name)
    if not np.isfinite(number) or (positive and number <= 0):
        raise ParameterError(f"{name} must be finite{' and > 0' if positive else ''}, got {value!r}", key=name,
                             value=value)
    if (minimum is not None and number < minimum) or (maximum is not None and number > maximum):
        bounds = " and ".join(filter(None, [f">= {minimum:g}" if minimum is not None else "",
                                            f"<= {maximum:g}" if maximum is not None else ""]))
        raise ParameterError(f"{name} must be {bounds}, got {value!r}", key=name, value=value)
    return number


def whole_number(value, name: str, *, minimum: int = 1, maximum: int | None = None) -> int:
    """``int(value)`` of a count (iterations, samples, repeats); ParameterError naming ``name`` unless
    it is a whole number (``3`` or ``3.0``) >= ``minimum`` (and <= ``maximum``)."""
    rule = f">= {minimum}" + (f" and <= {maximum}" if maximum is not None else "")
    if not is_number(value) or not np.isfinite(float(value)) or float(value) != int(value) \
            or int(value) < minimum or (maximum is not None and int(value) > maximum):
        raise ParameterError(f"{name} must be a whole number {rule}, got {value!r}", key=name, value=value)
    return int(value)


def check_sample_count(count: float, name: str, value, how: str) -> int:
    """``int(count)``; ParameterError naming ``name`` = ``value`` when the grid it makes would hold
    more than :data:`MAX_SAMPLES` samples (``how`` says how the count follows from the arguments)."""
    if not np.isfinite(count) or count > MAX_SAMPLES:
        raise ParameterError(f"{name} = {value!r} gives {count:.3g} samples ({how}), more than the {MAX_SAMPLES:.0e} "
                             "a grid may hold (8 MB per signal); shorten it or coarsen its step", key=name, value=value)
    return int(count)


def check_vehicle(owner: str, vehicle):
    """``vehicle``; ParameterError unless it is a :class:`~vehdyn.Vehicle` (``owner`` names who needs it)."""
    from vehdyn.params.vehicle import Vehicle

    if not isinstance(vehicle, Vehicle):
        raise ParameterError(f"{owner}: vehicle must be a vehdyn Vehicle, got {type(vehicle).__name__}", key="vehicle",
                             value=vehicle)
    return vehicle
