"""Crosswind: the side-force law, the bicycle's wind input against closed forms, linear against nonlinear."""

import dataclasses

import numpy as np
import pytest

import vehdyn
from vehdyn.handling import LinearBicycle, SingleTrack, neutral_steer_point
from vehdyn.procedures import crosswind_gust
from vehdyn.components.aero import aero_side_force, centre_of_pressure_ahead_of_cg, wind_side_force_factor
from vehdyn.handling.crosswind import steady_state_crosswind_yaw_rate
from vehdyn.procedures import crosswind_sensitivity, wind_zone_signal
from vehdyn.tire import LinearTire

SEDAN = vehdyn.load_vehicle("sedan")
ABE = dict(mass=1500.0, yaw_inertia=2500.0, a=1.1, b=1.6, front_cornering_stiffness=110e3,
           rear_cornering_stiffness=120e3)


def test_side_force_law_equals_the_gust_formula_of_maneuvers():
    # crosswind_gust (maneuvers) writes F = 0.5 rho (u^2 + w^2) A C_Yb atan(w/u) and M = C_Nb L / C_Yb F
    u, w = 25.0, 10.0
    x_p = centre_of_pressure_ahead_of_cg(SEDAN)
    gust = crosswind_gust(SEDAN, speed=u, gust_speed=w, start=1.0, duration=2.0,
                          side_force_derivative=SEDAN.aero.side_force_coefficient_slope,
                          yaw_moment_derivative=SEDAN.aero.side_force_coefficient_slope * x_p / SEDAN.wheelbase)
    force = aero_side_force(np, wind_side_force_factor(SEDAN), u, w)
    assert force == pytest.approx(gust["external_lateral_force"](np.array([2.0]))[0], rel=1e-12)
    assert x_p * force == pytest.approx(gust["external_yaw_moment"](np.array([2.0]))[0], rel=1e-12)
    # odd in the wind, zero without it, and its slope at w = 0 is k_w u (the bicycle's input column)
    # exactly odd on any CPU: every arctan2 (C library, numpy's SIMD kernels) applies the sign of y, never rounds it
    assert aero_side_force(np, 2.0, u, -w) == -aero_side_force(np, 2.0, u, w)
    assert aero_side_force(np, 2.0, u, 0.0) == 0.0
    eps = 1e-6
    slope = (aero_side_force(np, 2.0, u, eps) - aero_side_force(np, 2.0, u, -eps)) / (2 * eps)
    assert slope == pytest.approx(2.0 * u, rel=1e-9)


def test_centre_of_pressure_from_the_vehicle_file_fields():
    aero, g = SEDAN.aero, SEDAN.geometry
    assert centre_of_pressure_ahead_of_cg(SEDAN) == pytest.approx(
        g.cg_to_front_axle - aero.centre_of_pressure_from_front_axle * g.wheelbase, rel=1e-15)
    assert wind_side_force_factor(SEDAN) == pytest.approx(
        0.5 * aero.air_density * aero.frontal_area * aero.side_force_coefficient_slope, rel=1e-15)


def test_bicycle_wind_is_optional_and_an_exact_input_column():
    plain = LinearBicycle(SEDAN, 30.0)
    windy = LinearBicycle(SEDAN, 30.0, crosswind=True)
    assert plain.input_names == ("front_steer_angle", "rear_steer_angle")
    assert windy.input_names == plain.input_names + ("wind_velocity_lateral",)
    np.testing.assert_array_equal(windy.A, plain.A)  # the wind does not touch the vehicle's modes
    np.testing.assert_array_equal(windy.B[:, :2], plain.B)
    p = windy.bicycle_parameters
    force = p.wind_side_force_factor * 30.0  # dF/dw at w = 0
    np.testing.assert_allclose(windy.B[:, 2], [force / p.mass, p.centre_of_pressure * force / p.yaw_inertia],
                               rtol=1e-14)
    assert "aero" in windy.phenomena
    assert windy.at_speed(20.0).input_names == windy.input_names


@pytest.mark.parametrize("speed", [10.0, 30.0, 50.0])
@pytest.mark.parametrize("x_p", [-1.0, 0.0, 0.7])
def test_steady_yaw_rate_under_a_side_force_matches_the_closed_form(speed, x_p):
    car = LinearBicycle.from_parameters(**ABE, speed=speed, wind_side_force_factor=1.5, centre_of_pressure=x_p)
    gain = car.dc_gain()[car.index("yaw_rate", "outputs"), car.index("wind_velocity_lateral", "inputs")]
    force_per_wind = 1.5 * speed
    expected = steady_state_crosswind_yaw_rate(car, speed, force_per_wind, x_p)
    assert gain == pytest.approx(float(expected), rel=1e-10, abs=1e-15)


@pytest.mark.parametrize("speed", [10.0, 40.0])
def test_a_force_at_the_neutral_steer_point_makes_pure_sideslip(speed):
    x_n = -neutral_steer_point(LinearBicycle.from_parameters(**ABE, speed=speed)).behind_cg
    car = LinearBicycle.from_parameters(**ABE, speed=speed, wind_side_force_factor=2.0, centre_of_pressure=x_n)
    dc = car.dc_gain()[:, car.index("wind_velocity_lateral", "inputs")]
    force = 2.0 * speed
    assert abs(dc[car.index("yaw_rate", "outputs")]) < 1e-12 * force / ABE["mass"]
    # r = 0: the tires balance F alone, (C_f + C_r) v / u = F
    cs = ABE["front_cornering_stiffness"] + ABE["rear_cornering_stiffness"]
    assert dc[car.index("lateral_velocity", "outputs")] == pytest.approx(force * speed / cs, rel=1e-10)


def test_signs_downwind_ahead_of_the_neutral_steer_point_upwind_behind():
    x_n = -neutral_steer_point(LinearBicycle.from_parameters(**ABE, speed=25.0)).behind_cg
    for x_p, sign in ((x_n + 0.5, 1.0), (x_n - 0.5, -1.0)):
        car = LinearBicycle.from_parameters(**ABE, speed=25.0, wind_side_force_factor=2.0, centre_of_pressure=x_p)
        assert np.sign(car.dc_gain()[car.index("yaw_rate", "outputs"), 2]) == sign
    x_n = -neutral_steer_point(SEDAN).behind_cg
    # the shipped sedan: centre of pressure ahead of its NSP -> a wind toward +y turns it toward +y
    car = LinearBicycle(SEDAN, 25.0, crosswind=True)
    assert centre_of_pressure_ahead_of_cg(SEDAN) > x_n
    assert car.dc_gain()[car.index("yaw_rate", "outputs"), 2] > 0
    assert car.dc_gain()[car.index("lateral_acceleration", "outputs"), 2] > 0


@pytest.mark.parametrize("speed", [15.0, 35.0])
def test_single_track_linearization_has_the_bicycle_wind_column(speed):
    tires = (LinearTire(cornering_stiffness=SEDAN.tires.front_cornering_stiffness / 2),
             LinearTire(cornering_stiffness=SEDAN.tires.rear_cornering_stiffness / 2))
    lin = SingleTrack(SEDAN, *tires, tire_lag=False).lateral_yaw(speed, crosswind=True)
    bike = LinearBicycle(SEDAN, speed, crosswind=True)
    assert lin.input_names == bike.input_names
    for name in "ABCD":
        ours, theirs = getattr(lin, name), getattr(bike, name)
        assert np.allclose(ours, theirs, rtol=1e-7, atol=1e-7 * np.max(np.abs(theirs))), name


def test_nonlinear_model_follows_the_bicycle_at_small_wind():
    # Magic Formula tires with lag against the linear bicycle with tire lag, a 0.5 m/s wind step:
    # side force ~ 36 N, lateral acceleration ~ 0.03 m/s^2, deep in the linear range
    speed, w = 25.0, 0.5
    t = np.linspace(0.0, 4.0, 801)
    wind = wind_zone_signal(speed, w, 1e4, SEDAN.wheelbase, start=0.5)
    model = SingleTrack(SEDAN)
    drag = SEDAN.aero.drag_force(speed).item()
    nl = vehdyn.simulate(model, t, {"wind_velocity_lateral": wind, "rear_longitudinal_force": drag},
                         x0=model.straight_running(speed), method="RK45", rtol=1e-9, atol=1e-12, backend="numpy")
    bike = LinearBicycle(SEDAN, speed, tire_lag=True, crosswind=True)
    lin = vehdyn.simulate(bike, t, {"wind_velocity_lateral": wind(t)}, method="exact", hold="foh")
    for name in ("yaw_rate", "lateral_acceleration"):
        peak = np.max(np.abs(lin[name]))
        assert np.max(np.abs(nl[name] - lin[name])) < 0.03 * peak, name


@pytest.mark.compiled_vs_numpy
def test_compiled_and_numpy_single_track_agree_with_wind():
    model = SingleTrack(SEDAN)
    rng = np.random.default_rng(3)
    x = model.straight_running(22.0) + rng.normal(0.0, 0.05, model.n_states)
    u = model.input_vector({"wind_velocity_lateral": 7.0, "front_steer_angle": 0.01})
    compiled = model.compiled_rhs()
    dx = np.empty(model.n_states)
    compiled.rhs(0.0, x, u, compiled.args, dx)
    np.testing.assert_allclose(dx, model.rhs(0.0, x, u), rtol=1e-12, atol=1e-12)
    no_wind = model.rhs(0.0, x, model.input_vector({"front_steer_angle": 0.01}))
    assert dx[model.index("lateral_velocity")] > no_wind[model.index("lateral_velocity")]


def test_crosswind_sensitivity_open_and_closed_loop():
    speed = 25.0
    open_loop = crosswind_sensitivity(SEDAN, speed, wind_speed=10.0, wind_length=30.0, duration=2.5)
    closed = crosswind_sensitivity(SEDAN, speed, wind_speed=10.0, wind_length=30.0, duration=2.5, driver=True)
    assert open_loop.centre_of_pressure > open_loop.neutral_steer_point
    # downwind: yaw and drift toward +y; the driver brings the car back toward the path
    assert open_loop.peak_yaw_rate > 0 and open_loop.lateral_deviation_at_exit > 0
    assert open_loop.lateral_deviation > open_loop.lateral_deviation_at_exit
    assert abs(closed.lateral_deviation) < 0.5 * open_loop.lateral_deviation
    assert closed.driver and not open_loop.driver
    # the wind reaches its full value and no more
    w = open_loop.result["wind_velocity_lateral"]
    assert w.max() == pytest.approx(10.0, rel=1e-12) and w.min() == 0.0
    # mirror image: the opposite wind gives the opposite response
    mirror = crosswind_sensitivity(SEDAN, speed, wind_speed=-10.0, wind_length=30.0, duration=2.5)
    assert mirror.lateral_deviation == pytest.approx(-open_loop.lateral_deviation, rel=1e-5)


def test_parameter_errors_name_the_field():
    with pytest.raises(vehdyn.ParameterError, match="side_force_coefficient_slope"):
        dataclasses.replace(SEDAN.aero, side_force_coefficient_slope=-1.0)
    with pytest.raises(vehdyn.ParameterError, match="centre_of_pressure_from_front_axle"):
        dataclasses.replace(SEDAN.aero, centre_of_pressure_from_front_axle=float("nan"))
    with pytest.raises(vehdyn.ParameterError, match="wind_length"):
        crosswind_sensitivity(SEDAN, 25.0, wind_length=1.0)
    with pytest.raises(vehdyn.ParameterError, match="wind_speed"):
        crosswind_sensitivity(SEDAN, 25.0, wind_speed=float("inf"))
    with pytest.raises(vehdyn.ParameterError, match="speed"):
        crosswind_sensitivity(SEDAN, -1.0)
    with pytest.raises(vehdyn.ParameterError, match="model"):
        crosswind_sensitivity(SEDAN, 25.0, model=LinearBicycle(SEDAN, 25.0, crosswind=True))
    with pytest.raises(vehdyn.ParameterError, match="vehicle"):
        crosswind_sensitivity("sedan", 25.0)


def test_wind_zone_signal_rises_over_the_wheelbase_and_holds():
    u, w, length, L = 25.0, 12.0, 50.0, 2.5
    wind = wind_zone_signal(u, w, length, L, start=1.0)
    rise = L / u
    leave = 1.0 + length / u
    t = np.array([0.99, 1.0 + 0.5 * rise, 1.0 + rise, 0.5 * (1.0 + rise + leave), leave + 0.5 * rise,
                  leave + rise + 0.01])
    np.testing.assert_allclose(wind(t), [0.0, 0.5 * w, w, w, 0.5 * w, 0.0], atol=1e-12)
    # the half-cosine rise: w (1 - cos(pi tau / rise)) / 2
    tau = 0.3 * rise
    assert wind(np.array([1.0 + tau]))[0] == pytest.approx(0.5 * w * (1 - np.cos(np.pi * tau / rise)), rel=1e-12)
