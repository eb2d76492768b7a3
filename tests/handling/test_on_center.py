"""Weave test (ISO 13674-1) metrics against closed forms of the linear loop and the friction trend."""

import numpy as np
import pytest

import vehdyn
from vehdyn.handling import LinearBicycle, SteeredVehicle, SteeringSystem
from vehdyn.procedures import weave_test
from vehdyn.handling.steering_system import boost_torque
from vehdyn.tire import LinearTire
from vehdyn.units import GRAVITY

SEDAN = vehdyn.load_vehicle("sedan")
SPEED = 100 / 3.6
FRICTIONLESS = dict(steering_friction_torque=0.0, assist_gain=0.0)


def bicycle_gain():
    bike = LinearBicycle(SEDAN, SPEED)
    return bike.dc_gain()[bike.index("lateral_acceleration", "outputs"), 0]


def torque_per_ay(params):
    return params.trail * SEDAN.mass.mass * SEDAN.geometry.cg_to_rear_axle / (SEDAN.wheelbase * params.ratio)


def fitted_slope(curve, level, band=0.01 * GRAVITY):
    """Least-squares slope of the exact steady curve ``curve(a_y)`` over the metrics' band around ``level``."""
    a = np.linspace(level - band, level + band, 2001)
    return np.polyfit(a, curve(a), 1)[0]


def column_torque(a_y, k, gain, knee):
    """Steady column torque: T_c + T_a(T_c) = k a_y, solved by bisection (elementwise)."""
    target = k * np.asarray(a_y, dtype=float)
    lo, hi = np.minimum(target, 0.0), np.maximum(target, 0.0)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        low = mid + boost_torque(mid, gain, knee) < target
        lo, hi = np.where(low, mid, lo), np.where(low, hi, mid)
    return 0.5 * (lo + hi)


def test_stiff_column_low_frequency_sensitivity_is_the_bicycle_gain_over_the_ratio():
    # a stiff column (its mode damped so that it stays cheap to integrate): the compliance term
    # t m b / (L N k_c) is 0.2 % of N / G; the quasi-static closed form keeps it
    k_c = 1e4
    m = weave_test(SEDAN, frequency=0.02, column_stiffness=k_c, steering_damping=20.0, cycles=2, iterations=2,
                   **FRICTIONLESS)
    ratio = SEDAN.steering.ratio
    p = SteeringSystem(SEDAN).parameters
    assert m.steering_sensitivity == pytest.approx(bicycle_gain() / ratio, rel=5e-3)
    assert m.steering_sensitivity == pytest.approx(1 / (ratio / bicycle_gain() + torque_per_ay(p) / k_c), rel=1e-3)
    assert m.peak_lateral_acceleration == pytest.approx(0.2 * GRAVITY, rel=1e-3)


def test_low_frequency_torque_gradients_follow_the_trail_and_the_boost_curve():
    manual = weave_test(SEDAN, frequency=0.02, cycles=2, iterations=2, **FRICTIONLESS)
    p = SteeringSystem(SEDAN).parameters
    k = torque_per_ay(p)
    assert manual.torque_gradient_zero_g == pytest.approx(k, rel=2e-3)
    assert manual.torque_gradient_01g == pytest.approx(k, rel=2e-3)
    # with the boost curve: the steady curve T_c(a_y) of T_c + T_a(T_c) = k a_y, fitted over the same band
    gain, knee = 2.0, 1.5
    assisted = weave_test(SEDAN, frequency=0.02, cycles=2, iterations=2, steering_friction_torque=0.0,
                          assist_gain=gain, assist_knee_torque=knee)
    curve = lambda a: column_torque(a, k, gain, knee)  # noqa: E731
    assert assisted.torque_gradient_zero_g == pytest.approx(fitted_slope(curve, 0.0), rel=3e-3)
    assert assisted.torque_gradient_01g == pytest.approx(fitted_slope(curve, 0.1 * GRAVITY), rel=3e-3)
    # on centre the boost is flat: nearly the manual gradient; at 0.1 g it is k / (1 + T_a'(T_c))
    tc = float(column_torque(0.1 * GRAVITY, k, gain, knee))
    slope = gain * (tc**4 + 3 * tc**2 * knee**2) / (tc**2 + knee**2) ** 2
    assert assisted.torque_gradient_01g == pytest.approx(k / (1 + slope), rel=2e-2)
    assert assisted.torque_gradient_zero_g > 0.95 * k > assisted.torque_gradient_01g


def test_frictionless_loop_widths_are_the_phase_lags_of_the_linear_loop():
    # a linear loop answers theta = A sin(w t) with r = R sin(w t - phi): r = 0 at theta = +-A sin(phi)
    f = 0.2
    m = weave_test(SEDAN, frequency=f, **FRICTIONLESS)
    model = SteeredVehicle(LinearBicycle(SEDAN, SPEED), SteeringSystem(SEDAN, **FRICTIONLESS)).linearize()
    fr = model.frequency_response([2 * np.pi * f], inputs=["steering_wheel_angle"])
    h = {name: fr.response[fr.output_names.index(name), 0, 0]
         for name in ("yaw_rate", "lateral_acceleration", "steering_wheel_torque")}
    A = m.steering_wheel_amplitude
    assert m.yaw_rate_hysteresis == pytest.approx(2 * A * abs(np.sin(np.angle(h["yaw_rate"]))), rel=1e-3)
    lag = np.angle(h["lateral_acceleration"]) - np.angle(h["steering_wheel_torque"])
    assert m.torque_at_zero_g == pytest.approx(A * abs(h["steering_wheel_torque"]) * abs(np.sin(lag)), rel=1e-3)
    assert m.torque_deadband == pytest.approx(2 * A * abs(np.sin(np.angle(h["steering_wheel_torque"]))), rel=1e-3)


def test_hysteresis_vanishes_as_friction_and_frequency_go_to_zero():
    slow = weave_test(SEDAN, frequency=0.01, **FRICTIONLESS)
    fast = weave_test(SEDAN, frequency=0.2, **FRICTIONLESS)
    rough = weave_test(SEDAN, frequency=0.2, steering_friction_torque=2.0)
    for name in ("yaw_rate_hysteresis", "torque_at_zero_g", "torque_deadband", "lateral_acceleration_at_zero_torque"):
        assert getattr(slow, name) < 0.1 * getattr(fast, name), name
    assert np.degrees(slow.yaw_rate_hysteresis) < 0.2
    # friction opens the loops felt on centre (the torque deadband is not monotonic: the friction's
    # torque leads the angle while the aligning moment lags it)
    for name in ("yaw_rate_hysteresis", "torque_at_zero_g", "lateral_acceleration_at_zero_torque"):
        assert getattr(rough, name) > getattr(fast, name), name
    assert rough.torque_at_zero_g > fast.torque_at_zero_g + 1.0


def test_single_track_with_linear_tires_gives_the_bicycle_metrics():
    tires = (LinearTire(cornering_stiffness=SEDAN.tires.front_cornering_stiffness / 2),
             LinearTire(cornering_stiffness=SEDAN.tires.rear_cornering_stiffness / 2))
    track = vehdyn.handling.SingleTrack(SEDAN, *tires, tire_lag=False)
    ours = weave_test(SEDAN, vehicle_model=track, cycles=2, iterations=2)
    theirs = weave_test(SEDAN, cycles=2, iterations=2)
    for name in ("steering_sensitivity", "torque_gradient_zero_g", "torque_gradient_01g", "yaw_rate_hysteresis"):
        assert getattr(ours, name) == pytest.approx(getattr(theirs, name), rel=2e-2), name


def test_units_of_the_customary_metrics():
    m = weave_test(SEDAN, cycles=2, iterations=1)
    assert m.steering_sensitivity_g_per_100deg == pytest.approx(m.steering_sensitivity * np.radians(100) / GRAVITY)
    assert m.torque_gradient_zero_g_per_g == pytest.approx(m.torque_gradient_zero_g * GRAVITY)


def test_errors_name_the_parameter():
    with pytest.raises(vehdyn.ParameterError, match="amplitude_g"):
        weave_test(SEDAN, amplitude_g=0.0)
    with pytest.raises(vehdyn.ParameterError, match="frequency"):
        weave_test(SEDAN, frequency=-0.2)
    with pytest.raises(vehdyn.ParameterError, match="cycles"):
        weave_test(SEDAN, cycles=1)
    with pytest.raises(vehdyn.ParameterError, match="speed"):
        weave_test(SEDAN, speed=0.0)
    with pytest.raises(vehdyn.ParameterError, match="vehicle"):
        weave_test("sedan")
    with pytest.raises(vehdyn.ParameterError, match="steering"):
        weave_test(SEDAN, steering=SteeringSystem(SEDAN, steering_input="torque"))
    with pytest.raises(vehdyn.ParameterError, match="steering"):
        weave_test(SEDAN, steering=SteeringSystem(SEDAN), assist_gain=1.0)
