"""Manoeuvre signals against their defining formulas, metrics on signals with known answers (the drivers:
tests/driver)."""

import numpy as np
import pytest

import vehdyn
from vehdyn.handling import SingleTrack
from vehdyn.procedures import (
    braking_in_turn,
    crosswind_gust,
    double_lane_change_track,
    obstacle_avoidance_track,
    ramp_steer,
    sine_steer,
    sine_with_dwell,
    sine_with_dwell_metrics,
    step_steer,
)
from vehdyn.results import SimulationResult
from vehdyn.tire import FialaTire

SEDAN = vehdyn.load_vehicle("sedan")


def fiala_model(**kwargs):
    return SingleTrack(SEDAN, FialaTire.from_vehicle(SEDAN, "front"), FialaTire.from_vehicle(SEDAN, "rear"), **kwargs)


def test_step_ramp_and_sine_follow_their_formulas():
    t = np.linspace(0, 2, 2001)
    assert np.allclose(step_steer(0.1, start=0.5, rise_time=0.15)(t), 0.1 * np.clip((t - 0.5) / 0.15, 0, 1))
    assert np.allclose(ramp_steer(0.2, start=1.0)(t), 0.2 * np.maximum(t - 1.0, 0))
    s = sine_steer(0.05, 0.5, start=0.2, cycles=1)(t)
    assert np.allclose(s[(t >= 0.2) & (t <= 2.2)], 0.05 * np.sin(np.pi * (t[(t >= 0.2)] - 0.2)))
    with pytest.raises(vehdyn.ParameterError, match="rise_time"):
        step_steer(0.1, rise_time=0.0)


def test_sine_with_dwell_shape_fmvss_126():
    a, f, dwell, start = 0.1, 0.7, 0.5, 1.0
    steer = sine_with_dwell(a, f, dwell, start)
    t = np.linspace(0, 5, 50001)
    d = steer(t)
    quarter3 = start + 0.75 / f
    assert steer.completion_of_steer == pytest.approx(start + 1 / f + dwell)
    assert np.allclose(d[(t > quarter3 + 1e-9) & (t <= quarter3 + dwell)], -a)  # the dwell at the second peak
    assert d[np.argmin(np.abs(t - (start + 0.25 / f)))] == pytest.approx(a, rel=1e-6)  # first peak
    assert np.all(d[t > steer.completion_of_steer] == 0) and np.all(d[t < start] == 0)
    assert np.max(np.abs(np.diff(d))) < 2 * np.pi * f * a * 1e-4 * 1.01  # continuous: no jumps


def test_sine_with_dwell_metrics_on_a_known_yaw_signal():
    steer = sine_with_dwell(0.1, start=1.0)
    t = np.linspace(0, 6, 601)
    cos = steer.completion_of_steer
    # a made-up yaw rate: a lobe of peak -0.5 up to COS, then exponential decay (time constant 0.5 s)
    r = np.where(t < cos, -0.5 * np.sin(np.pi * np.clip(t - 1.0, 0, None) / (cos - 1.0)) ** 2, 0.0)
    r = np.where(t >= cos, -0.5 * np.exp(-(t - cos) / 0.5), r)
    y = 0.8 * np.clip(t - 1.0, 0, None) ** 2
    states = np.vstack([r, y])
    result = SimulationResult(time=t, states=states, inputs=np.zeros((0, t.size)), outputs=states,
                              state_signals=vehdyn.signals.as_signals(["yaw_rate", "y"], "states"),
                              input_signals=(), output_signals=vehdyn.signals.as_signals(["yaw_rate", "y"], "outputs"),
                              method="given")
    m = sine_with_dwell_metrics(result, steer)
    assert m.peak_yaw_rate == pytest.approx(0.5, rel=1e-3)
    assert m.yaw_rate_ratio_1000ms == pytest.approx(np.exp(-2.0), rel=1e-2)
    assert m.yaw_rate_ratio_1750ms == pytest.approx(np.exp(-3.5), rel=2e-2)
    assert m.lateral_displacement == pytest.approx(0.8 * 1.07**2, rel=1e-3)
    assert m.stable


def test_crosswind_gust_force_formula():
    wind = crosswind_gust(SEDAN, speed=25.0, gust_speed=10.0, start=1.0, duration=2.0)
    # at the gust's peak (t = start + duration/2) w = w_g: F = 0.5 rho (u^2 + w^2) A C_Yb atan(w/u)
    expected = 0.5 * SEDAN.aero.air_density * (25.0**2 + 10.0**2) * SEDAN.aero.frontal_area * 2.0 * np.arctan(0.4)
    assert wind["external_lateral_force"](np.array([2.0]))[0] == pytest.approx(expected, rel=1e-12)
    assert wind["external_yaw_moment"](np.array([2.0]))[0] == pytest.approx(expected * 0.3 / 2.0 * SEDAN.wheelbase,
                                                                           rel=1e-12)
    assert wind["external_lateral_force"](np.array([0.5, 3.5])).tolist() == [0.0, 0.0]


def test_double_lane_change_track_dimensions_iso_3888_1():
    track = double_lane_change_track(1.8)
    widths = [right - left for _, _, left, right in track.sections]
    assert widths == pytest.approx([1.1 * 1.8 + 0.25, 1.2 * 1.8 + 0.25, 1.3 * 1.8 + 0.25])
    lengths = [x1 - x0 for x0, x1, _, _ in track.sections]
    assert lengths == [15.0, 25.0, 15.0]
    assert [track.sections[k][0] for k in range(3)] == [0.0, 45.0, 95.0]
    assert track.sections[0][3] - track.sections[1][3] == pytest.approx(3.5)  # right boundaries 3.5 m apart
    assert track.sections[0][3] == pytest.approx(track.sections[2][3])
    assert track.standard == "ISO 3888-1"
    # the inner line keeps b/2 + margin from the inner cone lines: lateral travel 3.25 - 0.1 b, 3.25 - 0.3 b
    x, y = track.inner_line(margin=0.0)
    assert np.max(y) - np.min(y) == pytest.approx(3.25 - 0.1 * 1.8, rel=1e-12)
    assert y[-1] - np.min(y) == pytest.approx(3.25 - 0.3 * 1.8, rel=1e-12)


def test_obstacle_avoidance_track_dimensions_iso_3888_2():
    for b, w5 in ((1.8, 3.0), (2.2, 1.3 * 2.2 + 0.25)):
        track = obstacle_avoidance_track(b)
        (s1, e1, l1, r1), (s3, e3, l3, r3), (s5, e5, l5, r5) = track.sections
        assert [s1, e1, s3, e3, s5, e5] == pytest.approx([0, 12, 25.5, 36.5, 49, 61])  # 61 m in all
        assert [r1 - l1, r3 - l3, r5 - l5] == pytest.approx([1.1 * b + 0.25, b + 1.0, w5])
        assert l1 - r3 == pytest.approx(1.0)  # 1 m between lane 1's left and lane 3's right cone lines
        assert r5 == pytest.approx(r1)


def test_braking_in_turn_decelerates_as_asked():
    model = fiala_model()
    out = braking_in_turn(model, radius=100.0, lateral_acceleration=4.0, deceleration=3.0, duration=1.5)
    # demanded 3 m/s^2 from the brakes, plus drag and the cornering drag of the front axle
    assert out.mean_deceleration == pytest.approx(3.0, rel=0.1)
    assert np.all(np.isfinite(out.result.states))
    assert out.yaw_rate_ratio > 0.5  # no spin at moderate braking


def test_lane_change_speed_bound_closed_form_and_real_tracks():
    from vehdyn.procedures import DoubleLaneChangeTrack, lane_change_speed_bound

    # three zero-slack gates y(0) = 0, y(L) = D, y(2L) = 0: the least largest |y''| is the parabola's 2 D / L^2
    # (the second difference (y(0) - 2 y(L) + y(2L)) / L^2 = -2 D / L^2 is an average of y'')
    b, L, D = 1.6, 30.0, 2.0
    gates = [(0.0, 0.0, -b / 2, b / 2), (L, L, -D - b / 2, -D + b / 2), (2 * L, 2 * L, -b / 2, b / 2)]
    track = DoubleLaneChangeTrack(gates, np.array([0.0, 2 * L]), np.zeros(2), b)
    speed, x, y = lane_change_speed_bound(track, 1.0, step=0.5, gravity=9.81)
    assert speed == pytest.approx(np.sqrt(9.81 * L**2 / (2 * D)), rel=1e-6)
    # on the ISO tracks the path stays inside the lanes
    for build in (double_lane_change_track, obstacle_avoidance_track):
        track = build(1.6)
        speed, x, y = lane_change_speed_bound(track, 0.9)
        for x0, x1, left, right in track.sections:
            inside = (x >= x0) & (x <= x1)
            assert np.all(y[inside] >= left + 0.8 - 1e-7) and np.all(y[inside] <= right - 0.8 + 1e-7)
        assert 10.0 < speed < 60.0
    with pytest.raises(vehdyn.ParameterError, match="friction_coefficient"):
        lane_change_speed_bound(track, -0.5)


def test_least_curvature_line_keeps_its_margin_inside_the_lanes():
    track = obstacle_avoidance_track(1.6)
    x, y = track.least_curvature_line(0.2)
    assert np.array_equal(x, track.path_x)
    for x0, x1, left, right in track.sections:
        inside = (x >= x0) & (x <= x1)
        assert np.all(y[inside] >= left + 0.8 + 0.2 - 1e-6) and np.all(y[inside] <= right - 0.8 - 0.2 + 1e-6)
