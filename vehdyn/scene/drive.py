"""What a scene drives: the time grid, steer and braking programmes, the road under each track.

:func:`drive_of` turns a :class:`~vehdyn.scene.Scene` (plain data) into the signals every rung
reads, once per scene, so that all rungs see the same inputs.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.units import GRAVITY

__all__ = ["Drive", "drive_of"]

_ROAD_SPACING = 0.02  # [m] profile grid of synthesized roads and events


@dataclass
class Drive:
    """The materialized inputs of a scene.

    Attributes
    ----------
    scene : Scene
    vehicle : Vehicle
    time : ndarray
        The common time grid [s].
    inputs : dict
        Input name -> callable of t or number (steer ``front_steer_angle`` [rad] and any other
        input of a user's mapping).
    braking : tuple or None
        ``(front, rear, start)`` of a braking manoeuvre: the front and rear axle longitudinal
        force programmes (callables of t [s], [N], negative braking; zero before ``start``) and the
        brake onset ``start`` [s].
    initial_turn : float or None
        Steady lateral acceleration [m/s^2] the scene starts in (braking in a turn).
    track : DoubleLaneChangeTrack or None
        The ISO 3888-1 track with the driver's parameters in ``driver``.
    driver : dict
        ``{"preview_time": [s], "lag": [s]}`` of the ISO 3888-1 preview driver (defaults 0.8 s,
        0.1 s); empty for other manoeuvres.
    road : tuple of (distance, left, right) or None
        Road profile of each track [m] on a common distance grid (front axle at distance V t).
    built : dict
        What rung builders made from the vehicle (per vehicle, not per scene: a model, its tire
        laws), shared between the rungs of one plan, by a key of the builder's choosing.
    """

    scene: Any
    vehicle: Any
    time: np.ndarray
    inputs: dict = field(default_factory=dict)
    braking: tuple | None = None
    initial_turn: float | None = None
    track: Any = None
    driver: dict = field(default_factory=dict)
    road: tuple | None = None
    built: dict = field(default_factory=dict)

    def once(self, key, make: Callable):
        """``make()`` the first time ``key`` is asked for, the same object after (see ``built``).

        Parameters
        ----------
        key : hashable
            The builder's name for what ``make`` builds (e.g. a model class and its options).
        make : callable
            Called without arguments, once per key and Drive.

        Returns
        -------
        object
            What ``make()`` returned the first time.
        """
        if key not in self.built:
            self.built[key] = make()
        return self.built[key]

    @property
    def steer(self) -> Callable | None:
        return self.inputs.get("front_steer_angle")

    @property
    def handling_input(self) -> bool:
        """True when something acts in the ground plane (steer, wind, braking, a driver, a turn)."""
        return bool(self.inputs) or self.track is not None or self.braking is not None \
            or self.initial_turn is not None

    @property
    def longitudinal(self) -> bool:
        """True when the scene commands longitudinal forces (braking or a user's force input)."""
        return self.braking is not None or any("longitudinal_force" in k or "torque" in k for k in self.inputs)


def _steer_gain(vehicle, speed) -> float:
    """Steady-state lateral acceleration per unit front steer [m/s^2/rad] of the linear bicycle."""
    from vehdyn.handling.steady_state import steady_state_gains

    gain = float(steady_state_gains(vehicle, speed).lateral_acceleration)
    if not np.isfinite(gain) or gain <= 0:
        raise ParameterError(f"speed {speed} m/s is at or above the vehicle's critical speed: no steady-state "
                             "steer gain to size the manoeuvre", key="speed", value=speed)
    return gain


def _amplitude(params, vehicle, speed) -> float:
    if "amplitude" in params:
        return float(params["amplitude"])
    return float(params.get("lateral_acceleration", 2.0)) / _steer_gain(vehicle, speed)


def _constant(value) -> Callable:
    return lambda t: np.full(np.shape(t), float(value))


def drive_of(scene) -> Drive:
    """The :class:`Drive` of ``scene``: its vehicle, time grid and inputs, made once per scene.

    A named manoeuvre becomes its signals here: a steer given as ``lateral_acceleration`` is sized
    by the linear bicycle's steady-state gain at the scene's speed (default 2 m/s^2 for the steps
    and sines); ``lane_change`` is one period of a sine at f = sqrt(a / (2 pi offset));
    ``iso3888_1`` a track for a vehicle 0.2 m wider than its wider axle track with a run-in of
    max(30 m, 1.5 s at the speed); ``iso4138_circle`` a ramp from ``start`` reaching at the end of
    the scene the steer of ``lateral_acceleration`` (default mu g); the braking manoeuvres axle
    forces m ``deceleration`` split by ``brake_front_share``.

    Parameters
    ----------
    scene : Scene
        The scene (its fields already checked by :class:`~vehdyn.scene.Scene`).

    Returns
    -------
    Drive
        The vehicle loaded, :meth:`Scene.time`, the input signals, the braking programme,
        initial turn, track and driver as the manoeuvre needs, and the road profiles of both
        tracks [m] over speed x duration + wheelbase + 10 m (synthesized roads and events on a
        0.02 m and 0.01 m grid).

    Raises
    ------
    ParameterError
        A sized steer at or above the vehicle's critical speed (no steady-state gain), road event
        parameters its function does not take, or other inconsistent manoeuvre parameters.
    """
    from vehdyn import procedures as mv

    vehicle = scene.load_vehicle()
    drive = Drive(scene, vehicle, scene.time())
    m, p, u = scene.manoeuvre, scene.manoeuvre_parameters, scene.speed
    if callable(m):
        drive.inputs["front_steer_angle"] = m
    elif isinstance(m, dict):
        drive.inputs.update({k: (v if callable(v) else _constant(v)) for k, v in m.items()})
    elif m == "step_steer":
        drive.inputs["front_steer_angle"] = mv.step_steer(_amplitude(p, vehicle, u), p.get("start", 0.5),
                                                          p.get("rise_time", 0.15))
    elif m == "sine_steer":
        drive.inputs["front_steer_angle"] = mv.sine_steer(_amplitude(p, vehicle, u), p.get("frequency", 0.5),
                                                          p.get("start", 0.5), p.get("cycles"))
    elif m == "sine_with_dwell":
        drive.inputs["front_steer_angle"] = mv.sine_with_dwell(_amplitude(p, vehicle, u), p.get("frequency", 0.7),
                                                               p.get("dwell", 0.5), p.get("start", 0.5))
    elif m == "lane_change":
        a = float(p.get("lateral_acceleration", 1.0))
        offset = float(p.get("offset", 3.5))
        if a <= 0 or offset <= 0:
            raise ParameterError(f"lane_change needs lateral_acceleration > 0 and offset > 0, got {a}, {offset}",
                                 key="manoeuvre_parameters", value=dict(p))
        frequency = np.sqrt(a / (2 * np.pi * offset))
        drive.inputs["front_steer_angle"] = mv.sine_steer(a / _steer_gain(vehicle, u), frequency,
                                                          p.get("start", 0.5), 1.0)
    elif m == "iso3888_1":
        width = max(vehicle.geometry.front_track, vehicle.geometry.rear_track) + 0.2
        drive.track = mv.double_lane_change_track(width, run_in=max(30.0, u * 1.5))
        drive.driver = {"preview_time": float(p.get("preview_time", 0.8)), "lag": float(p.get("lag", 0.1))}
    elif m == "iso4138_circle":
        mu_g = vehicle.tires.friction_coefficient * GRAVITY
        start = float(p.get("start", 0.5))
        if start >= scene.duration:
            raise ParameterError(f"iso4138_circle: start {start} s is not before the end {scene.duration} s",
                                 key="manoeuvre_parameters.start", value=start)
        target = float(p.get("lateral_acceleration", mu_g)) / _steer_gain(vehicle, u)
        drive.inputs["front_steer_angle"] = mv.ramp_steer(target / (scene.duration - start), start)
    elif m in ("braking_in_turn", "straight_braking"):
        deceleration = float(p.get("deceleration", 4.0 if m == "braking_in_turn" else 6.0))
        share = float(p.get("brake_front_share", 0.65))
        start = float(p.get("brake_start", 1.0 if m == "braking_in_turn" else 0.5))
        if not 0 <= share <= 1 or deceleration <= 0:
            raise ParameterError(f"{m}: brake_front_share must be in [0, 1] and deceleration > 0, got {share}, "
                                 f"{deceleration}", key="manoeuvre_parameters", value=dict(p))
        force = vehicle.mass.mass * deceleration
        on = lambda t: (np.asarray(t, dtype=float) >= start).astype(float)  # noqa: E731
        drive.braking = (lambda t: -share * force * on(t), lambda t: -(1 - share) * force * on(t), start)
        if m == "braking_in_turn":
            drive.initial_turn = float(p.get("lateral_acceleration", 4.0))
    if scene.road is not None:
        drive.road = _road(scene, vehicle)
    return drive


def _road(scene, vehicle):
    """(distance, left, right) profiles [m] covering the scene (front axle at distance V t)."""
    from vehdyn import road as rd

    wheelbase = vehicle.geometry.wheelbase
    length = scene.speed * scene.duration + wheelbase + 10.0
    r = scene.road
    if isinstance(r, rd.RoadProfile):
        return r.distance, r.elevation, r.elevation
    if isinstance(r, str):
        track = 0.5 * (vehicle.geometry.front_track + vehicle.geometry.rear_track)
        left, right = rd.synthesize_parallel_profiles(r, length, _ROAD_SPACING, track, seed=int(scene.seed))
        return left.distance, left.elevation, right.elevation
    params = {k: v for k, v in r.items() if k not in ("event", "track")}
    x = np.arange(0.0, length, _ROAD_SPACING / 2)
    try:
        z = getattr(rd, r["event"])(x, **params)
    except TypeError as exc:
        raise ParameterError(f"road: {r['event']} parameters {params}: {exc}", key="road", value=dict(r)) from None
    zero = np.zeros_like(z)
    side = r.get("track", "left")
    return x, (z if side in ("left", "both") else zero), (z if side in ("right", "both") else zero)
