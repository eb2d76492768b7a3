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
    """The standard scenes for ``vehicle`` (a name or a Vehicle), by name."""
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
