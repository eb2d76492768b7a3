"""Named signals: the states, inputs and outputs of every vehdyn model.

A :class:`Signal` carries a snake_case name, a unit and a description. Names never contain a dot,
because python-control reads ``a.b`` as signal ``b`` of subsystem ``a``. Common vehicle-dynamics
names have a default unit in :data:`GLOSSARY`, so ``LinearModel(..., states=["yaw_rate"])`` knows
that its state is in rad/s.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Iterable

from vehdyn.errors import ParameterError

__all__ = ["Signal", "GLOSSARY", "STEER_INPUTS", "as_signals", "names_of"]

_NAME = re.compile(r"^[a-z][a-z0-9_]*$")

#: Default units [SI] of the glossary's signal names; suffix rules cover the rest (see
#: :func:`default_unit`).
GLOSSARY: dict[str, tuple[str, str]] = {
    "longitudinal_velocity": ("m/s", "body-frame velocity u along x (forward)"),
    "lateral_velocity": ("m/s", "body-frame velocity v along y (right, SAE)"),
    "vertical_velocity": ("m/s", "body-frame velocity w along z (down, SAE)"),
    "roll_rate": ("rad/s", "body rate p about x"),
    "pitch_rate": ("rad/s", "body rate q about y"),
    "yaw_rate": ("rad/s", "body rate r about z"),
    "roll_angle": ("rad", "Euler roll angle phi"),
    "pitch_angle": ("rad", "Euler pitch angle theta"),
    "yaw_angle": ("rad", "Euler yaw (heading) angle psi"),
    "sideslip_angle": ("rad", "vehicle sideslip beta = atan(v/u)"),
    "course_angle": ("rad", "course angle nu = psi + beta"),
    "steer_angle": ("rad", "road-wheel steer angle (positive turns right, SAE)"),
    "front_steer_angle": ("rad", "front road-wheel steer angle (positive turns right, SAE)"),
    "rear_steer_angle": ("rad", "rear road-wheel steer angle (positive turns right, SAE)"),
    "lateral_acceleration": ("m/s^2", "lateral acceleration of the CG"),
    "longitudinal_acceleration": ("m/s^2", "longitudinal acceleration of the CG"),
    "vertical_acceleration": ("m/s^2", "vertical acceleration"),
    "path_curvature": ("1/m", "curvature of the CG path"),
    "x": ("m", "earth-fixed x position"),
    "y": ("m", "earth-fixed y position"),
    "z": ("m", "earth-fixed z position (down, SAE)"),
    "time": ("s", "time"),
}

_SUFFIX_UNITS = (
    ("_angle", "rad"),
    ("_rate", "rad/s"),
    ("_velocity", "m/s"),
    ("_speed", "m/s"),
    ("_acceleration", "m/s^2"),
    ("_displacement", "m"),
    ("_travel", "m"),
    ("_deflection", "m"),
    ("_position", "m"),
    ("_force", "N"),
    ("_load", "N"),
    ("_moment", "N*m"),
    ("_torque", "N*m"),
    ("_curvature", "1/m"),
)


def default_unit(name: str) -> str:
    """Default unit of a signal name: from :data:`GLOSSARY`, else from its suffix, else ``""``.

    Parameters
    ----------
    name : str
        A snake_case signal name.

    Returns
    -------
    str
        The SI unit (``"rad/s"`` for ``"yaw_rate"``, ``"N"`` for any ``"..._force"``), or ``""``.
    """
    if name in GLOSSARY:
        return GLOSSARY[name][0]
    for suffix, unit in _SUFFIX_UNITS:
        if name.endswith(suffix):
            return unit
    return ""


@dataclass(frozen=True)
class Signal:
    """A named signal of a model.

    Parameters
    ----------
    name : str
        snake_case name, no dots (``"yaw_rate"``).
    unit : str, optional
        SI unit (``"rad/s"``). Defaults to the glossary's unit for known names.
    description : str, optional
        One line of text. Defaults to the glossary's description for known names.

    Examples
    --------
    >>> from vehdyn import Signal
    >>> Signal("yaw_rate").unit                  # from the glossary
    'rad/s'
    >>> Signal("front_axle_load").unit           # from the suffix
    'N'
    >>> Signal("throttle", unit="-", description="pedal position, 0 to 1")
    Signal(name='throttle', unit='-', description='pedal position, 0 to 1')
    """

    name: str
    unit: str | None = None
    description: str = ""

    def __post_init__(self):
        if not isinstance(self.name, str) or not _NAME.match(self.name):
            raise ParameterError(
                f"signal name {self.name!r} is not snake_case (lower-case letters, digits and "
                "underscores, starting with a letter; no dots)",
                key="name",
                value=self.name,
            )
        if self.unit is None:
            object.__setattr__(self, "unit", default_unit(self.name))
        if not self.description and self.name in GLOSSARY:
            object.__setattr__(self, "description", GLOSSARY[self.name][1])

    def __str__(self) -> str:
        return self.name


def as_signals(items: Iterable[str | Signal] | None, kind: str = "signals") -> tuple[Signal, ...]:
    """Turn names or :class:`Signal` objects into a tuple of unique signals.

    Parameters
    ----------
    items : None, str, Signal or iterable of str and Signal
        The signals, by name (a unit from :func:`default_unit`) or as Signal objects; ``None`` is
        no signal.
    kind : str
        What the signals are (``"states"``, ``"inputs"``, ``"outputs"``), for error messages.

    Returns
    -------
    tuple of Signal
        The signals, in the given order.

    Raises
    ------
    ParameterError
        If a name is malformed or repeated; the message names ``kind`` and the name.
    """
    if items is None:
        return ()
    if isinstance(items, (str, Signal)):
        items = (items,)
    out = tuple(item if isinstance(item, Signal) else Signal(item) for item in items)
    seen: set[str] = set()
    for sig in out:
        if sig.name in seen:
            raise ParameterError(f"{kind}: the name {sig.name!r} appears twice", key=kind, value=sig.name)
        seen.add(sig.name)
    return out


def names_of(signals: Iterable[Signal]) -> tuple[str, ...]:
    """The names of ``signals`` as a tuple of strings.

    Parameters
    ----------
    signals : iterable of Signal
        The signals.

    Returns
    -------
    tuple of str
        Their names, in order.
    """
    return tuple(s.name for s in signals)


#: The front and rear road-wheel steer inputs shared by the handling models (SAE: positive turns right).
STEER_INPUTS: tuple[Signal, ...] = (Signal("front_steer_angle"), Signal("rear_steer_angle"))
