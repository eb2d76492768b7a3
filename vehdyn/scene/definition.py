"""The :class:`Scene`: what is asked of the vehicle models, as plain data.

A scene names a vehicle, a manoeuvre (steer and braking programme) and/or a road, a constant entry
speed, a duration, the output signals wanted and the relative error acceptable on them. It is
written in Python or in a TOML file (:meth:`Scene.from_toml`, :meth:`Scene.to_toml`)::

    vehicle = "sedan"
    manoeuvre = "step_steer"
    speed = 27.8                  # [m/s]
    duration = 3.0                # [s]
    outputs = ["yaw_rate", "lateral_acceleration"]
    tolerance = 0.02              # max |x - x_ref| / max |x_ref|

    [manoeuvre_parameters]
    lateral_acceleration = 2.0    # [m/s^2], steady-state linear estimate of the step's size

Standard manoeuvres (names and parameters; steer in road-wheel angle [rad], SAE signs)

``"step_steer"``
    ``amplitude`` [rad] or ``lateral_acceleration`` [m/s^2] (steady-state linear a_y of the step),
    ``start`` (0.5 s), ``rise_time`` (0.15 s; ISO 7401).
``"sine_steer"``
    ``amplitude`` or ``lateral_acceleration``, ``frequency`` (0.5 Hz), ``start`` (0.5 s), ``cycles``.
``"sine_with_dwell"``
    FMVSS 126: ``amplitude`` or ``lateral_acceleration``, ``frequency`` (0.7 Hz), ``dwell`` (0.5 s),
    ``start`` (0.5 s).
``"lane_change"``
    One full steer sine whose steady-state lateral acceleration peaks at ``lateral_acceleration``
    [m/s^2] and whose frequency gives a lateral offset of ``offset`` (3.5 m) for a sinusoidal
    lateral acceleration: f = sqrt(a / (2 pi offset)).
``"iso3888_1"``
    The ISO 3888-1 double lane change, steered by :class:`~vehdyn.driver.PreviewDriver`
    (``preview_time`` 0.8 s, ``lag`` 0.1 s) in a :class:`~vehdyn.interconnect.ClosedLoop` with the rung's model.
``"iso4138_circle"``
    Steady-state circular driving at constant speed with a slowly increasing steer (ISO 4138,
    constant-speed method): a ramp from ``start`` (0.5 s) reaching at the end of the scene the
    steer whose linear steady-state lateral acceleration is ``lateral_acceleration`` (default
    mu g: to the limit).
``"braking_in_turn"``
    ISO 7975: from the steady turn at ``lateral_acceleration`` (4 m/s^2) and the scene's speed,
    brake at ``deceleration`` (4 m/s^2) from ``brake_start`` (1 s), ``brake_front_share`` 0.65.
``"straight_braking"``
    Brake in a straight line at ``deceleration`` (6 m/s^2) from ``brake_start`` (0.5 s).

Roads: ``None``; an ISO 8608 class letter (``"A"`` ... ``"H"``: two parallel tracks with the
isotropic coherence, seeded by ``seed``); a :class:`~vehdyn.ride.RoadProfile` (both tracks); or an
event table ``{"event": "pothole" | "bump" | "speed_hump" | "step", "track": "left" | "right" |
"both", ...}`` with the parameters of :mod:`vehdyn.road`'s function of that name (positions
[m] from where the front wheels start).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.params.checks import MAX_RUN_SAMPLES, MAX_SAMPLES, is_number

__all__ = ["Scene", "STANDARD_MANOEUVRES", "ROAD_EVENTS"]

#: The standard manoeuvres and the parameters each accepts.
STANDARD_MANOEUVRES: dict[str, tuple[str, ...]] = {
    "step_steer": ("amplitude", "lateral_acceleration", "start", "rise_time"),
    "sine_steer": ("amplitude", "lateral_acceleration", "frequency", "start", "cycles"),
    "sine_with_dwell": ("amplitude", "lateral_acceleration", "frequency", "dwell", "start"),
    "lane_change": ("lateral_acceleration", "offset", "start"),
    "iso3888_1": ("preview_time", "lag"),
    "iso4138_circle": ("lateral_acceleration", "start"),
    "braking_in_turn": ("lateral_acceleration", "deceleration", "brake_front_share", "brake_start"),
    "straight_braking": ("deceleration", "brake_front_share", "brake_start"),
}

#: Road events (functions of :mod:`vehdyn.road`) and their parameters.
ROAD_EVENTS: dict[str, tuple[str, ...]] = {
    "pothole": ("position", "length", "depth", "edge_length"),
    "bump": ("position", "length", "height"),
    "speed_hump": ("position", "length", "height", "shape"),
    "step": ("position", "height"),
}
_ROAD_CLASSES = tuple("ABCDEFGH")
#: Where the named manoeuvres begin by default [s] (vehdyn.scene.drive).
_DEFAULT_STARTS = {
    "step_steer": {"start": 0.5}, "sine_steer": {"start": 0.5}, "sine_with_dwell": {"start": 0.5},
    "lane_change": {"start": 0.5}, "iso4138_circle": {"start": 0.5},
    "braking_in_turn": {"brake_start": 1.0}, "straight_braking": {"brake_start": 0.5},
}
#: The ranges of the named manoeuvres' parameters (module docstring), checked where the scene is made.
_PARAMETER_RULES = {
    "lateral_acceleration": (lambda v: v != 0, "non-zero [m/s^2] (the steady-state size of the manoeuvre; SAE "
                             "signs, positive turning right)"),
    "amplitude": (lambda v: v != 0, "non-zero [rad] (SAE signs, positive turning right)"),
    "rise_time": (lambda v: v > 0, "> 0 [s]"),
    "frequency": (lambda v: v > 0, "> 0 [Hz]"),
    "cycles": (lambda v: v > 0, "> 0"),
    "dwell": (lambda v: v >= 0, ">= 0 [s]"),
    "offset": (lambda v: v > 0, "> 0 [m]"),
    "preview_time": (lambda v: v > 0, "> 0 [s]"),
    "lag": (lambda v: v >= 0, ">= 0 [s]"),
    "deceleration": (lambda v: v > 0, "> 0 [m/s^2]"),
    "brake_front_share": (lambda v: 0 <= v <= 1, "in [0, 1]"),
}


def _bad(field_name: str, value, why: str) -> ParameterError:
    return ParameterError(f"Scene.{field_name} = {value!r}: {why}", key=field_name, value=value)


def _number(name, value, *, positive=True, upper=None) -> float:
    if not is_number(value):
        raise _bad(name, value, "must be a number")
    x = float(value)
    if not math.isfinite(x) or (positive and x <= 0) or (upper is not None and x >= upper):
        rule = "a finite number" + (" > 0" if positive else "") + (f" < {upper}" if upper is not None else "")
        raise _bad(name, value, f"must be {rule}")
    return x


@dataclass(frozen=True, kw_only=True, eq=False)
class Scene:
    """What is asked: vehicle, manoeuvre and/or road, speed, duration, outputs and accuracy.

    Parameters
    ----------
    vehicle : Vehicle or str
        A :class:`~vehdyn.Vehicle` or the name of a shipped one (``"sedan"``) or a TOML path.
    manoeuvre : None, str, callable or mapping
        The name of a standard manoeuvre (module docstring) with ``manoeuvre_parameters``; a steer
        signal ``delta(t)`` [rad] for ``front_steer_angle`` (e.g.
        :func:`vehdyn.procedures.step_steer`); or a mapping input name -> signal (a
        callable of t or a number). None: no manoeuvre (a ride scene).
    manoeuvre_parameters : mapping
        Parameters of a named manoeuvre (SI units).
    speed : float
        Entry forward speed [m/s], > 0.
    road : None, str, RoadProfile or mapping
        No road input, an ISO 8608 class letter, a profile, or an event table.
    duration : float
        Simulated time [s], > 0.
    outputs : sequence of str
        The signals wanted (e.g. ``"yaw_rate"``, ``"roll_angle"``, ``"sprung_acceleration"``).
    tolerance : float
        Relative error acceptable on every output, max |x - x_ref| / max |x_ref| [-], in (0, 1)
        (default 0.02).
    tire : str, optional
        A ``.tir`` file (path or shipped name) replacing the vehicle's tires in the rungs that use
        a tire law.
    seed : int
        Seed of a random (ISO 8608) road.
    time_step : float, optional
        Output time step [s] of the common time grid, > 0 and at most half the duration; default
        0.01 s for handling, 0.002 s with a road.

    Raises
    ------
    ParameterError
        A field out of its range (``speed``, ``duration`` not finite and > 0, ``tolerance`` not in
        (0, 1), more than ``MAX_RUN_SAMPLES`` samples), an unknown manoeuvre, road class or road
        event, a manoeuvre parameter not taken by its manoeuvre or out of its range (module
        docstring), a manoeuvre or road event that begins after the scene ends, or neither a
        manoeuvre nor a road; the message names the field (``key``) and the value.

    Examples
    --------
    A scene is plain data: :meth:`to_dict` and :meth:`from_dict` (and :meth:`to_toml`,
    :meth:`from_toml`) take it apart and put it back together.

    >>> from vehdyn.scene import Scene
    >>> scene = Scene(manoeuvre="step_steer", manoeuvre_parameters={"lateral_acceleration": 2.0},
    ...               speed=27.8, outputs=["yaw_rate", "lateral_acceleration"])
    >>> data = scene.to_dict()
    >>> for key, value in data.items():
    ...     print(key, "=", value)
    vehicle = sedan
    manoeuvre = step_steer
    manoeuvre_parameters = {'lateral_acceleration': 2.0}
    speed = 27.8
    duration = 3.0
    outputs = ['yaw_rate', 'lateral_acceleration']
    tolerance = 0.02
    seed = 0
    >>> Scene.from_dict(data) == scene
    True

    A steer signal of :mod:`vehdyn.procedures` goes through as its table of pieces:

    >>> from vehdyn.procedures import step_steer
    >>> scene = Scene(manoeuvre=step_steer(0.02), speed=25.0)
    >>> list(scene.to_dict()["manoeuvre"])
    ['front_steer_angle']
    >>> Scene.from_dict(scene.to_dict()) == scene
    True
    """

    vehicle: Any = "sedan"
    manoeuvre: Any = None
    manoeuvre_parameters: Mapping[str, Any] = field(default_factory=dict)
    speed: float = 20.0
    road: Any = None
    duration: float = 3.0
    outputs: tuple[str, ...] = ("yaw_rate",)
    tolerance: float = 0.02
    tire: str | None = None
    seed: int = 0
    time_step: float | None = None

    def __post_init__(self):
        from vehdyn.params import Vehicle

        set_ = lambda k, v: object.__setattr__(self, k, v)  # noqa: E731
        if not isinstance(self.vehicle, (Vehicle, str, Path)):
            raise _bad("vehicle", self.vehicle, "must be a Vehicle or the name of a shipped vehicle")
        if isinstance(self.vehicle, Path):
            set_("vehicle", str(self.vehicle))
        set_("speed", _number("speed", self.speed))
        set_("duration", _number("duration", self.duration))
        set_("tolerance", _number("tolerance", self.tolerance, upper=1.0))
        if self.time_step is not None:
            set_("time_step", _number("time_step", self.time_step))
            if self.time_step > self.duration / 2:
                raise _bad("time_step", self.time_step, f"must be at most half the duration {self.duration} s")
        samples = self.duration / self.effective_time_step
        if samples > MAX_RUN_SAMPLES:
            name = "duration" if self.time_step is None else "time_step"
            raise _bad(name, getattr(self, name), f"a duration of {self.duration:g} s on a time step of "
                       f"{self.effective_time_step:g} s makes {samples:.3g} samples per signal, more than the "
                       f"{MAX_RUN_SAMPLES:.0e} a scene may hold; shorten the duration or give a longer time_step")
        if isinstance(self.seed, bool) or not isinstance(self.seed, (int, np.integer)):
            raise _bad("seed", self.seed, "must be an integer")
        outputs = (self.outputs,) if isinstance(self.outputs, str) else self.outputs
        try:
            outputs = tuple(outputs)
        except TypeError:
            raise _bad("outputs", self.outputs, "must be a list of signal names") from None
        if not outputs or not all(isinstance(o, str) and o.isidentifier() for o in outputs):
            raise _bad("outputs", self.outputs, "must be a non-empty list of signal names")
        set_("outputs", outputs)
        if self.tire is not None and not isinstance(self.tire, (str, Path)):
            raise _bad("tire", self.tire, "must be the path or shipped name of a .tir file")
        if isinstance(self.tire, Path):
            set_("tire", str(self.tire))
        self._check_manoeuvre()
        self._check_road()
        self._check_road_length()
        if self.manoeuvre is None and self.road is None:
            raise _bad("manoeuvre", None, "a scene needs a manoeuvre, a road or both")

    def _check_manoeuvre(self):
        m, params = self.manoeuvre, self.manoeuvre_parameters
        if not isinstance(params, Mapping):
            raise _bad("manoeuvre_parameters", params, "must be a table of parameters")
        object.__setattr__(self, "manoeuvre_parameters", dict(params))
        if isinstance(m, str):
            if m not in STANDARD_MANOEUVRES:
                raise _bad("manoeuvre", m, f"unknown manoeuvre; the standard ones are {sorted(STANDARD_MANOEUVRES)}")
            allowed = STANDARD_MANOEUVRES[m]
            for key, value in params.items():
                where = f"manoeuvre_parameters.{key}"
                if key not in allowed:
                    raise _bad(where, value, f"not a parameter of {m!r}; it takes {list(allowed)}")
                if not is_number(value) or not math.isfinite(value):
                    raise _bad(where, value, "must be a finite number")
            if "amplitude" in params and "lateral_acceleration" in params:
                raise _bad("manoeuvre_parameters", dict(params), "give amplitude or lateral_acceleration, not both")
            for key, value in params.items():
                rule = _PARAMETER_RULES.get(key)
                if rule is not None and not rule[0](value):
                    raise _bad(f"manoeuvre_parameters.{key}", value, f"must be {rule[1]}")
            for key in ("start", "brake_start"):  # a programme that begins after the end drives nothing
                if key in params and not 0.0 <= params[key] < self.duration:
                    raise _bad(f"manoeuvre_parameters.{key}", params[key],
                               f"must be in [0, duration) = [0, {self.duration:g}) s: the manoeuvre must begin "
                               "within the scene")
                default = _DEFAULT_STARTS.get(m, {}).get(key)
                if key not in params and default is not None and default >= self.duration:
                    raise _bad("duration", self.duration, f"the {m} begins at {default:g} s (its default {key}): "
                               f"the scene must last beyond it (or give manoeuvre_parameters.{key})")
        elif m is None or callable(m):
            if params:
                raise _bad("manoeuvre_parameters", dict(params), "only a named manoeuvre takes parameters")
        elif isinstance(m, Mapping):
            if not m:
                raise _bad("manoeuvre", m, "an empty mapping drives nothing")
            for name, signal in m.items():
                if not isinstance(name, str) or not name.isidentifier():
                    raise _bad("manoeuvre", name, "keys must be input signal names")
                if not (callable(signal) or is_number(signal) and math.isfinite(signal)):
                    raise _bad(f"manoeuvre.{name}", signal, "must be a callable of time or a finite number")
            object.__setattr__(self, "manoeuvre", dict(m))
        else:
            raise _bad("manoeuvre", m, "must be a standard manoeuvre name, a steer signal or a mapping of signals")

    def _check_road(self):
        from vehdyn.road import RoadProfile

        r = self.road
        if r is None or isinstance(r, RoadProfile):
            return
        if isinstance(r, str):
            if r.upper() not in _ROAD_CLASSES:
                raise _bad("road", r, f"not an ISO 8608 class; the classes are {list(_ROAD_CLASSES)}")
            object.__setattr__(self, "road", r.upper())
            return
        if isinstance(r, Mapping):
            event = r.get("event")
            if event not in ROAD_EVENTS:
                raise _bad("road.event", event, f"unknown road event; the events are {sorted(ROAD_EVENTS)}")
            track = r.get("track", "left")
            if track not in ("left", "right", "both"):
                raise _bad("road.track", track, "must be 'left', 'right' or 'both'")
            for key, value in r.items():
                if key in ("event", "track"):
                    continue
                if key not in ROAD_EVENTS[event]:
                    raise _bad(f"road.{key}", value,
                               f"not a parameter of {event!r}; it takes {list(ROAD_EVENTS[event])}")
                if key != "shape" and (not is_number(value) or not math.isfinite(value)):
                    raise _bad(f"road.{key}", value, "must be a finite number")
            object.__setattr__(self, "road", dict(r))
            return
        raise _bad("road", r, "must be None, an ISO 8608 class letter, a RoadProfile or an event table")

    def _check_road_length(self):
        """A synthesized road or an event table is sampled along speed * duration: bound its samples."""
        from vehdyn.road import RoadProfile
        from vehdyn.scene.drive import _ROAD_SPACING

        if self.road is None or isinstance(self.road, RoadProfile):
            return
        spacing = _ROAD_SPACING if isinstance(self.road, str) else 0.5 * _ROAD_SPACING
        length = self.speed * self.duration
        if length / spacing > MAX_SAMPLES:
            raise _bad("speed", self.speed, f"covers {length:.3g} m of road in the {self.duration:g} s of the scene: "
                       f"{length / spacing:.3g} road samples {spacing:g} m apart, more than the {MAX_SAMPLES:.0e} a "
                       "scene may hold; lower the speed or shorten the duration")
        position = self.road.get("position") if isinstance(self.road, Mapping) else None
        if position is not None and not 0.0 <= position < length:
            raise _bad("road.position", position, f"must be in [0, {length:.4g}) m: the front wheels start at 0 and "
                       f"cover speed x duration = {length:.4g} m in the scene, so the event would never be driven "
                       "over")

    def __eq__(self, other):
        """Equal plain data (:meth:`to_dict`: profiles and piecewise signals by value); other
        callables by identity."""
        if not isinstance(other, Scene):
            return NotImplemented
        try:
            return self.to_dict() == other.to_dict()
        except ParameterError:  # a callable that is not a PiecewiseSignal
            return all(_same(getattr(self, f.name), getattr(other, f.name)) for f in dataclasses.fields(self))

    __hash__ = None  # mappings inside: not hashable

    # ------------------------------------------------------------------ derived
    @property
    def kind(self) -> str:
        """``"handling"``, ``"ride"`` or ``"combined"`` (manoeuvre and road)."""
        if self.road is None:
            return "handling"
        return "ride" if self.manoeuvre is None else "combined"

    @property
    def effective_time_step(self) -> float:
        """The time step [s] of the common output grid."""
        if self.time_step is not None:
            return self.time_step
        return 0.01 if self.road is None else 0.002

    def time(self) -> np.ndarray:
        """The common time grid (every rung's outputs are compared on it).

        Returns
        -------
        ndarray
            ``0, dt, 2 dt, ..., n dt`` [s] with ``dt`` = :attr:`effective_time_step` and
            ``n = round(duration / dt)``.
        """
        n = int(round(self.duration / self.effective_time_step))
        return np.linspace(0.0, n * self.effective_time_step, n + 1)

    def load_vehicle(self):
        """The scene's vehicle.

        Returns
        -------
        Vehicle
            :attr:`vehicle` itself if it is a :class:`~vehdyn.Vehicle`, else the shipped vehicle of
            that name or the vehicle file at that path (:func:`vehdyn.params.load_vehicle`).
        """
        from vehdyn.params import Vehicle, load_vehicle

        return self.vehicle if isinstance(self.vehicle, Vehicle) else load_vehicle(self.vehicle)

    def replace(self, **changes) -> "Scene":
        """A copy with some fields changed (validated again).

        Parameters
        ----------
        **changes
            New values of fields of :class:`Scene` by name.

        Returns
        -------
        Scene
            The new scene (this one is frozen and unchanged).

        Raises
        ------
        ParameterError
            A new value out of its range (as :class:`Scene`).
        """
        return dataclasses.replace(self, **changes)

    # ------------------------------------------------------------------ TOML
    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> "Scene":
        """A scene from a mapping of its fields (as read from TOML; the inverse of :meth:`to_dict`).

        Parameters
        ----------
        data : mapping
            ``{field name: value}`` of some fields of :class:`Scene` (the others take their
            defaults). Besides the values :class:`Scene` takes: ``vehicle`` may be a table of a
            vehicle's parameters (:meth:`vehdyn.Vehicle.from_dict`), ``manoeuvre`` a table of
            signals each a number or ``{pieces = [[...], ...]}`` (a
            :class:`~vehdyn.PiecewiseSignal`), ``road`` a table ``{distance = [...], elevation =
            [...]}`` [m] (a :class:`~vehdyn.ride.RoadProfile` for both tracks).

        Returns
        -------
        Scene

        Raises
        ------
        ParameterError
            ``data`` not a mapping, an unknown field, a signal that is neither a number nor a
            table of pieces, or a field out of its range (as :class:`Scene`).
        """
        from vehdyn.params import Vehicle

        if not isinstance(data, Mapping):
            raise ParameterError(f"a scene must be a table, got {type(data).__name__}", key="scene", value=data)
        names = {f.name for f in dataclasses.fields(cls)}
        unknown = sorted(set(data) - names)
        if unknown:
            raise _bad(unknown[0], data[unknown[0]], f"unknown field; the fields are {sorted(names)}")
        data = dict(data)
        if isinstance(data.get("vehicle"), Mapping):
            data["vehicle"] = Vehicle.from_dict(data["vehicle"], path="vehicle.")
        m = data.get("manoeuvre")
        if isinstance(m, Mapping):
            data["manoeuvre"] = {k: _signal_from_data(f"manoeuvre.{k}", v) for k, v in m.items()}
        if isinstance(data.get("road"), Mapping) and "distance" in data["road"]:
            from vehdyn.road import RoadProfile

            data["road"] = RoadProfile(np.asarray(data["road"]["distance"], float),
                                       np.asarray(data["road"]["elevation"], float))
        if isinstance(data.get("outputs"), list):
            data["outputs"] = tuple(data["outputs"])
        return cls(**data)

    @classmethod
    def from_toml(cls, path: str | Path) -> "Scene":
        """Read a scene from a TOML file (fields as in :class:`Scene`; see the module docstring).

        Parameters
        ----------
        path : str or os.PathLike
            The TOML file, as :meth:`to_toml` writes it; its tables are read by :meth:`from_dict`.

        Returns
        -------
        Scene
        """
        from vehdyn.params.base import load_toml

        return load_toml(cls, path)

    def to_dict(self) -> dict[str, Any]:
        """The fields as plain data (the inverse of :meth:`from_dict`); None fields are left out.

        Returns
        -------
        dict
            ``{field name: value}`` in the order of the fields, without the None ones and without
            empty ``manoeuvre_parameters``: a :class:`~vehdyn.Vehicle` as its parameter table, a
            steer signal or mapping of signals as ``{input name: {"pieces": [[...]]} or number}``,
            a :class:`~vehdyn.ride.RoadProfile` as ``{"distance": [...], "elevation": [...]}``,
            tuples as lists.

        Raises
        ------
        ParameterError
            A manoeuvre signal that is neither a :class:`~vehdyn.PiecewiseSignal` nor a number
            (another callable has no plain-data form).
        """
        from vehdyn.params import Vehicle
        from vehdyn.road import RoadProfile

        out: dict[str, Any] = {}
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            if value is None or (f.name == "manoeuvre_parameters" and not value):
                continue
            if isinstance(value, Vehicle):
                value = value.to_dict()
            elif f.name == "manoeuvre" and not isinstance(value, str):
                items = value.items() if isinstance(value, Mapping) else [("front_steer_angle", value)]
                value = {k: _signal_to_data(f"manoeuvre.{k}", v) for k, v in items}
            elif isinstance(value, RoadProfile):
                value = {"distance": value.distance.tolist(), "elevation": value.elevation.tolist()}
            elif isinstance(value, tuple):
                value = list(value)
            out[f.name] = value
        return out

    def to_toml(self, path: str | Path | None = None) -> str:
        """TOML text of the scene (written to ``path`` when given); :meth:`from_toml` reads it back.

        Steer signals must be :class:`~vehdyn.PiecewiseSignal` s (the manoeuvre functions return
        them) or numbers; other callables cannot be written (ParameterError).

        Parameters
        ----------
        path : str or os.PathLike, optional
            File to write (atomically); None (the default): only return the text.

        Returns
        -------
        str
            The TOML text: the plain fields of :meth:`to_dict`, then one table per mapping
            (``[manoeuvre_parameters]``, ``[manoeuvre]``, ``[road]``, ``[vehicle]``).
        """
        data = self.to_dict()
        lines, tables = [], []
        for key, value in data.items():
            (tables if isinstance(value, Mapping) else lines).append((key, value))
        text = "\n".join(f"{k} = {_toml(v)}" for k, v in lines)
        for key, value in tables:
            text += f"\n\n[{key}]\n" + "\n".join(f"{k} = {_toml(v)}" for k, v in value.items())
        text += "\n"
        if path is not None:
            from vehdyn._atomic import atomic_write_text

            atomic_write_text(Path(path), text)
        return text


def _same(a, b) -> bool:
    """Field equality with callables compared by identity."""
    if a is b:
        return True
    if callable(a) or callable(b):
        return False
    if isinstance(a, Mapping) and isinstance(b, Mapping):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    try:
        return bool(a == b)
    except ValueError:  # arrays
        return False


def _signal_to_data(name, signal):
    from vehdyn.piecewise_signal import PiecewiseSignal

    if isinstance(signal, PiecewiseSignal):
        return {"pieces": signal.pieces.tolist()}
    if is_number(signal):
        return float(signal)
    raise ParameterError(f"{name}: a {type(signal).__name__} cannot be written to TOML; use a PiecewiseSignal "
                         "(vehdyn.procedures) or a number", key=name, value=signal)


def _signal_from_data(name, value):
    from vehdyn.piecewise_signal import PiecewiseSignal

    if isinstance(value, Mapping) and set(value) == {"pieces"}:
        return PiecewiseSignal(np.asarray(value["pieces"], dtype=float))
    if is_number(value):
        return float(value)
    raise ParameterError(f"{name} = {value!r}: a signal is a number or a table {{pieces = [[...]]}}", key=name,
                         value=value)


def _toml(value) -> str:
    """One TOML value (inline tables and arrays for nested data)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return repr(float(value))
    if isinstance(value, Mapping):
        return "{ " + ", ".join(f"{k} = {_toml(v)}" for k, v in value.items()) + " }"
    if isinstance(value, (list, tuple, np.ndarray)):
        return "[" + ", ".join(_toml(v) for v in value) + "]"
    raise ParameterError(f"cannot write {type(value).__name__} {value!r} to TOML", key="value", value=value)
