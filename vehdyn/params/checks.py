"""Checks of plain numbers given as arguments: one place for the message a bad value gets.

A number is any real scalar: a Python ``int`` or ``float`` or a numpy scalar (``np.float32``,
``np.int64``, ...), never a ``bool`` or a string (``"3"`` is refused rather than read as 3).
Counts (iterations, samples, repeats) are whole numbers; a grid whose size would not fit in memory
(more than :data:`MAX_SAMPLES` samples of one signal, :data:`MAX_RUN_SAMPLES` of a simulation's
time grid) is refused before it is allocated.
"""

from __future__ import annotations

import numbers

import numpy as np

from vehdyn.errors import ParameterError

__all__ = ["MAX_RUN_SAMPLES", "MAX_SAMPLES", "check_gains", "check_sample_count", "check_vehicle", "finite_number",
           "is_number", "positive_number", "whole_number"]

#: The most samples a grid of one signal built from arguments may have (a road profile, a track's
#: path, a sweep): 80 MB. A larger one is refused with a message that names the argument that makes it.
MAX_SAMPLES = 10_000_000
#: The most samples of a simulation's time grid built from arguments: every state, input and output
#: of the model is stored on it (tens of signals, 8 MB each at this size).
MAX_RUN_SAMPLES = 1_000_000


def is_number(value) -> bool:
    """Whether ``value`` is a real scalar: int, float or a numpy scalar of either kind.

    Parameters
    ----------
    value : object
        Anything.

    Returns
    -------
    bool
        True for ``3``, ``2.5``, ``np.float32(2.5)``, ``np.int64(3)``; False for bools (Python or
        numpy), strings, arrays, None.
    """
    return isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_))


def _as_float(value, name: str, what: str = "a number") -> float:
    if not is_number(value):
        raise ParameterError(f"{name} must be {what}, got {type(value).__name__} {value!r}", key=name, value=value)
    return float(value)


def check_gains(owner: str, *, positive=(), nonnegative=(), **values) -> dict:
    """Floats of ``values``; ParameterError naming a non-finite one or one of the wrong sign.

    Parameters
    ----------
    owner : str
        Who takes the gains (named in the message, e.g. ``"ABS"``).
    positive, nonnegative : sequence of str
        The names that must be > 0 and >= 0.
    **values
        Name -> value [the gain's own unit].

    Returns
    -------
    dict
        Name -> float.
    """
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
    ``allow_zero``).

    Parameters
    ----------
    value : object
        The argument [its own unit].
    name : str
        The argument's name (the error's ``key``).
    allow_zero : bool
        Accept 0.

    Returns
    -------
    float
    """
    v = _as_float(value, name)
    if not np.isfinite(v) or v < 0 or (v == 0 and not allow_zero):
        raise ParameterError(f"{name} must be a {'non-negative' if allow_zero else 'positive'} number, got {value!r}",
                             key=name, value=value)
    return v


def finite_number(value, name: str, *, positive: bool = False, minimum: float | None = None,
                  maximum: float | None = None) -> float:
    """``float(value)``; ParameterError naming ``name`` unless it is finite (and > 0 with
    ``positive``, >= ``minimum``, <= ``maximum`` where given).

    Parameters
    ----------
    value : object
        The argument [its own unit].
    name : str
        The argument's name (the error's ``key``).
    positive : bool
        Require > 0.
    minimum, maximum : float, optional
        Bounds, inclusive [the argument's unit].

    Returns
    -------
    float
    """
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
    it is a whole number (``3`` or ``3.0``) >= ``minimum`` (and <= ``maximum``).

    Parameters
    ----------
    value : object
        The count [-].
    name : str
        The argument's name (the error's ``key``).
    minimum : int
        Smallest count accepted [-].
    maximum : int, optional
        Largest count accepted [-].

    Returns
    -------
    int
    """
    rule = f">= {minimum}" + (f" and <= {maximum}" if maximum is not None else "")
    if not is_number(value) or not np.isfinite(float(value)) or float(value) != int(value) \
            or int(value) < minimum or (maximum is not None and int(value) > maximum):
        raise ParameterError(f"{name} must be a whole number {rule}, got {value!r}", key=name, value=value)
    return int(value)


def check_sample_count(count: float, name: str, value, how: str, *, limit: int = MAX_SAMPLES) -> int:
    """``int(count)``; ParameterError naming ``name`` = ``value`` when the grid it makes would hold
    more than ``limit`` samples.

    Parameters
    ----------
    count : float
        Samples the grid would hold [-] (inf or NaN are refused too).
    name : str
        The argument that makes the grid large (the error's ``key``).
    value : object
        Its value.
    how : str
        How the count follows from the arguments (for the message).
    limit : int
        The most samples accepted [-]: :data:`MAX_SAMPLES` for one signal, :data:`MAX_RUN_SAMPLES`
        for a simulation's time grid.

    Returns
    -------
    int
    """
    if not np.isfinite(count) or count > limit:
        raise ParameterError(f"{name} = {value!r} gives {count:.3g} samples ({how}), more than the {limit:.0e} the "
                             f"grid may hold ({8 * limit / 1e6:.0f} MB per signal); shorten it or coarsen its step",
                             key=name, value=value)
    return int(count)


def check_vehicle(owner: str, vehicle):
    """``vehicle``; ParameterError unless it is a :class:`~vehdyn.Vehicle`.

    Parameters
    ----------
    owner : str
        Who needs it (named in the message).
    vehicle : object
        The argument.

    Returns
    -------
    Vehicle
    """
    from vehdyn.params.vehicle import Vehicle

    if not isinstance(vehicle, Vehicle):
        raise ParameterError(f"{owner}: vehicle must be a vehdyn Vehicle, got {type(vehicle).__name__}", key="vehicle",
                             value=vehicle)
    return vehicle
