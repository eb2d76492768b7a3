"""The standard scenes on which the ladder's thresholds are measured (``benchmarks/bench_ladder.py``).

Handling: gentle (0.1 g) and limit step steer, sine with dwell, lane change at 60 and 100 km/h,
steady circle to the limit, braking in a turn. Ride: a smooth (ISO 8608 class B) and a rough
(class D) road at 54 and 108 km/h and a pothole under the left wheels. Combined: cornering on a
rough road. Speeds in m/s, accelerations in m/s^2.
"""

from __future__ import annotations

from vehdyn.scene.definition import Scene

__all__ = ["standard_scenes"]

_HANDLING = ("yaw_rate", "lateral_acceleration")


def standard_scenes(vehicle="sedan", *, tolerance: float = 0.02) -> dict[str, Scene]:
    """The standard scenes for ``vehicle`` (a name or a Vehicle), by name.

    Parameters
    ----------
    vehicle : Vehicle or str
        The vehicle of every scene: a :class:`~vehdyn.Vehicle`, the name of a shipped one or a
        vehicle file (default ``"sedan"``).
    tolerance : float
        Relative error acceptable on every output [-], in (0, 1) (default 0.02; see
        :class:`~vehdyn.scene.Scene`).

    Returns
    -------
    dict of str to Scene
        Thirteen scenes (module docstring), in this order: handling ``gentle_step_steer`` (1 m/s^2)
        and ``limit_step_steer`` (8 m/s^2) at 22.2 m/s, ``sine_with_dwell`` (5 m/s^2, 22.2 m/s),
        ``lane_change_60`` and ``lane_change_100`` (16.7 and 27.8 m/s), ``circle_to_limit``
        (ISO 4138 ramp to mu g at 16.7 m/s), ``braking_in_turn`` (4 m/s^2 turn, 4 m/s^2 braking,
        22.2 m/s), all with outputs ``yaw_rate`` and ``lateral_acceleration``; ride
        ``smooth_road_54``, ``smooth_road_108`` (ISO 8608 class B), ``rough_road_54``,
        ``rough_road_108`` (class D) at 15 and 30 m/s, ``pothole`` (4 cm deep, 0.6 m long, left
        wheels, 10 m/s), with output ``sprung_acceleration``; combined ``cornering_rough_road``
        (a 4 m/s^2 step steer on a class D road at 20 m/s).

    Raises
    ------
    ParameterError
        A ``vehicle`` that is neither a Vehicle nor a name, or a ``tolerance`` outside (0, 1).

    Examples
    --------
    >>> from vehdyn.scene import standard_scenes
    >>> scenes = standard_scenes()
    >>> for name, scene in scenes.items():
    ...     print(f"{name:21s} {scene.kind:8s} {scene.speed:5.1f} m/s {scene.duration:3.1f} s")
    gentle_step_steer     handling  22.2 m/s 3.0 s
    limit_step_steer      handling  22.2 m/s 3.0 s
    sine_with_dwell       handling  22.2 m/s 4.5 s
    lane_change_60        handling  16.7 m/s 6.0 s
    lane_change_100       handling  27.8 m/s 4.5 s
    circle_to_limit       handling  16.7 m/s 8.0 s
    braking_in_turn       handling  22.2 m/s 3.0 s
    smooth_road_54        ride      15.0 m/s 4.0 s
    smooth_road_108       ride      30.0 m/s 4.0 s
    rough_road_54         ride      15.0 m/s 4.0 s
    rough_road_108        ride      30.0 m/s 4.0 s
    pothole               ride      10.0 m/s 2.0 s
    cornering_rough_road  combined  20.0 m/s 3.0 s
    >>> standard_scenes(tolerance=0.05)["pothole"].tolerance
    0.05
    """
    S = lambda **kw: Scene(vehicle=vehicle, tolerance=tolerance, **kw)  # noqa: E731
    return {
        "gentle_step_steer": S(manoeuvre="step_steer", manoeuvre_parameters={"lateral_acceleration": 1.0},
                               speed=22.2, duration=3.0, outputs=_HANDLING),
        "limit_step_steer": S(manoeuvre="step_steer", manoeuvre_parameters={"lateral_acceleration": 8.0},
                              speed=22.2, duration=3.0, outputs=_HANDLING),
        "sine_with_dwell": S(manoeuvre="sine_with_dwell", manoeuvre_parameters={"lateral_acceleration": 5.0},
                             speed=22.2, duration=4.5, outputs=_HANDLING),
        "lane_change_60": S(manoeuvre="lane_change", manoeuvre_parameters={"lateral_acceleration": 1.0},
                            speed=16.7, duration=6.0, outputs=_HANDLING),
        "lane_change_100": S(manoeuvre="lane_change", manoeuvre_parameters={"lateral_acceleration": 2.0},
                             speed=27.8, duration=4.5, outputs=_HANDLING),
        "circle_to_limit": S(manoeuvre="iso4138_circle", speed=16.7, duration=8.0, outputs=_HANDLING),
        "braking_in_turn": S(manoeuvre="braking_in_turn",
                             manoeuvre_parameters={"lateral_acceleration": 4.0, "deceleration": 4.0},
                             speed=22.2, duration=3.0, outputs=_HANDLING),
        "smooth_road_54": S(road="B", speed=15.0, duration=4.0, outputs=("sprung_acceleration",)),
        "smooth_road_108": S(road="B", speed=30.0, duration=4.0, outputs=("sprung_acceleration",)),
        "rough_road_54": S(road="D", speed=15.0, duration=4.0, outputs=("sprung_acceleration",)),
        "rough_road_108": S(road="D", speed=30.0, duration=4.0, outputs=("sprung_acceleration",)),
        "pothole": S(road={"event": "pothole", "position": 5.0, "length": 0.6, "depth": 0.04,
                           "edge_length": 0.1, "track": "left"},
                     speed=10.0, duration=2.0, outputs=("sprung_acceleration", "sprung_acceleration_front")),
        "cornering_rough_road": S(manoeuvre="step_steer", manoeuvre_parameters={"lateral_acceleration": 4.0},
                                  road="D", speed=20.0, duration=3.0, outputs=("sprung_acceleration",)),
    }
