"""ESC: reference against the linear bicycle's steady-state gain and mu g / u, one-wheel yaw moment in closed form,
the FMVSS 126 ratios brought within limits where the car alone fails, gain errors; fmvss126 series and result."""

import numpy as np
import pytest

import vehdyn
from vehdyn import ParameterError
from vehdyn.chassis import ABS, ESC
from vehdyn.handling import SingleTrack
from vehdyn.interconnect import ClosedLoop
from vehdyn.procedures import fmvss126
from vehdyn.handling import steady_state_gains
from vehdyn.procedures.esc_compliance import series_multiples

CAR = vehdyn.load_vehicle("sedan")
G = vehdyn.units.GRAVITY


def test_reference_is_the_bicycle_gain_limited_by_friction():
    esc = ESC(CAR)
    speed = 20.0
    small = 0.002
    gain = steady_state_gains(CAR, speed).yaw_rate
    assert esc.reference_yaw_rate(small, speed) == pytest.approx(gain * small, rel=1e-9)
    assert esc.reference_yaw_rate(0.2, speed) == pytest.approx(CAR.tires.friction_coefficient * G / speed)
    assert esc.reference_yaw_rate(-0.2, speed) == pytest.approx(-CAR.tires.friction_coefficient * G / speed)


@pytest.mark.parametrize("wheel, sign, axle", [(0, -1, "front"), (1, 1, "front"), (2, -1, "rear"), (3, 1, "rear")])
def test_one_wheel_braking_is_a_yaw_moment_and_a_longitudinal_force(wheel, sign, axle):
    esc = ESC(CAR)
    torque = 600.0
    x = np.zeros(4)
    x[wheel] = torque
    u = esc.input_vector(front_longitudinal_force=100.0, rear_longitudinal_force=-50.0, external_yaw_moment=7.0)
    front, rear, moment = esc.output(0.0, x, u)
    track = CAR.geometry.front_track if axle == "front" else CAR.geometry.rear_track
    force = torque / CAR.tires.rolling_radius
    assert moment == pytest.approx(7.0 + sign * force * track / 2)  # SAE: braking the right wheel turns right
    assert (front, rear) == pytest.approx((100.0 - force, -50.0) if axle == "front" else (100.0, -50.0 - force))


def test_oversteer_brakes_the_outer_front_wheel():
    esc = ESC(CAR)
    # turning right (r > 0) more than the reference: a negative moment, from the LEFT (outer) front wheel
    moment = esc.yaw_moment_demand(0.01, 20.0, 0.0, 0.6)
    assert moment < 0
    commands = esc.wheel_torque_commands(moment, 0.6)
    assert commands[0] > 0 and commands[0] > 100 * max(commands[1:])


def test_esc_brings_the_fmvss126_ratios_within_limits():
    kwargs = dict(amplitude_multiples=[6.5], directions=("clockwise",))
    alone = fmvss126(CAR, **kwargs)
    assert not alone.passed and alone.runs[0]["yaw_rate_ratio_1000ms"] > 0.35
    assert any("S5.2.1" in line for line in alone.failures())
    with_esc = fmvss126(CAR, ESC(CAR), **kwargs)
    run = with_esc.runs[0]
    assert with_esc.passed, with_esc.failures()
    assert run["yaw_rate_ratio_1000ms"] <= 0.35 and run["yaw_rate_ratio_1750ms"] <= 0.20
    assert run["lateral_displacement"] >= 1.83
    frame = with_esc.to_frame()
    assert len(frame) == 1 and frame.attrs["rule"] == "49 CFR 571.126 S5.2"


def test_series_multiples_follow_s7_9_4():
    ratio = 16.0
    # A = 1 deg of road wheel: 16 deg of hand wheel; 6.5 A = 104 deg < 270: the last run is 270 deg
    m = series_multiples(np.radians(1.0), ratio)
    assert m[0] == 1.5 and np.allclose(np.diff(m[:-1]), 0.5)
    assert m[-1] * 16.0 == pytest.approx(270.0)
    # A = 4 deg: 6.5 A = 416 deg > 300: the last run is 300 deg
    m = series_multiples(np.radians(4.0), ratio)
    assert m[-1] * 64.0 == pytest.approx(300.0) and m[-2] * 64.0 < 300.0
    # A = 3 deg: 6.5 A = 312 deg > 300 as well; A = 2.8 deg: 6.5 A = 291 deg > 270: the last run is 6.5 A
    m = series_multiples(np.radians(2.8), ratio)
    assert m[-1] == pytest.approx(6.5)


@pytest.mark.parametrize("kwargs, key", [
    ({"yaw_rate_gain": -1.0}, "yaw_rate_gain"), ({"sideslip_gain": float("nan")}, "sideslip_gain"),
    ({"hydraulic_time_constant": 0.0}, "hydraulic_time_constant"), ({"friction_coefficient": -0.5}, "friction"),
])
def test_esc_bad_gains(kwargs, key):
    with pytest.raises(ParameterError, match=key):
        ESC(CAR, **kwargs)


def test_fmvss126_bad_input():
    with pytest.raises(ParameterError, match="directions"):
        fmvss126(CAR, directions=("up",))
    with pytest.raises(ParameterError, match="amplitude_multiples"):
        fmvss126(CAR, amplitude_multiples=[-1.0])
    with pytest.raises(ParameterError, match="vehicle"):
        fmvss126("sedan")


@pytest.mark.parametrize("controller", [ABS, ESC])
def test_controllers_need_a_vehicle(controller):
    with pytest.raises(ParameterError, match="vehicle must be a vehdyn Vehicle, got str") as info:
        controller("sedan")
    assert info.value.key == "vehicle"


def test_linearized_esc_loop_inside_its_deadband_is_the_car():
    car = vehdyn.load_vehicle("sedan")
    plant = SingleTrack(car)
    loop = ClosedLoop(plant, ESC(car))
    x0 = loop.state_vector(dict(zip(plant.state_names, plant.straight_running(20.0))))
    lin = loop.linearize(x0)
    alone = plant.linearize(plant.straight_running(20.0))
    n = plant.n_states
    assert lin.state_names == loop.state_names and lin.output_names == loop.output_names
    np.testing.assert_allclose(lin.A[:n, :n], alone.A, rtol=1e-5, atol=1e-6)
    # the hydraulic channels are first-order lags of -1 / tau, decoupled from the car at this point
    np.testing.assert_allclose(np.diag(lin.A)[n:], -1.0 / 0.1, rtol=1e-6)
    np.testing.assert_allclose(lin.A[n:, :n], 0.0, atol=1e-9)
