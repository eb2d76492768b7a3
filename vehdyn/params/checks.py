"""Checks of plain numbers given as arguments: one place for the message a bad value gets."""

from __future__ import annotations

import numpy as np

from vehdyn.errors import ParameterError

__all__ = ["check_gains", "check_vehicle", "finite_number", "positive_number"]


def check_gains(owner: str, *, positive=(), nonnegative=(), **values) -> dict:
    """Floats of ``values``; ParameterError naming a non-finite one or one of the wrong sign."""
    out = {}
    for name, value in values.items():
        try:
            number = float(value)
        except (TypeError, ValueError):
            raise ParameterError(f"{owner} gain {name} must be a number, got {value!r}", key=name,
                                 value=value) from None
        if isinstance(value, bool) or not np.isfinite(number):
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
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a number, got {value!r}", key=name, value=value) from None
    if not np.isfinite(v) or v < 0 or (v == 0 and not allow_zero):
        raise ParameterError(f"{name} must be a {'non-negative' if allow_zero else 'positive'} number, got {value!r}",
                             key=name, value=value)
    return v


def finite_number(value, name: str, *, positive: bool = False) -> float:
    """``float(value)``; ParameterError naming ``name`` unless it is finite (and > 0 with ``positive``)."""
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a number, got {value!r}", key=name, value=value) from None
    if not np.isfinite(number) or (positive and number <= 0):
        raise ParameterError(f"{name} must be finite{' and > 0' if positive else ''}, got {value!r}", key=name,
                             value=value)
    return number


def check_vehicle(owner: str, vehicle):
    """``vehicle``; ParameterError unless it is a :class:`~vehdyn.Vehicle` (``owner`` names who needs it)."""
    from vehdyn.params.vehicle import Vehicle

    if not isinstance(vehicle, Vehicle):
        raise ParameterError(f"{owner}: vehicle must be a vehdyn Vehicle, got {type(vehicle).__name__}", key="vehicle",
                             value=vehicle)
    return vehicle
