"""Nonlinear steady state against the linear closed form (case A-STEER-ABE), simulation and friction."""

import numpy as np
import pytest

import vehdyn
from vehdyn.handling import SingleTrack, nonlinear_handling_diagram, steady_state_cornering, steer_angle_for
from vehdyn.procedures import constant_radius_test
from vehdyn.tire import FialaTire, LinearTire

SEDAN = vehdyn.load_vehicle("sedan")


def abe_model(reference_case, tire_lag=True):
    case = reference_case("A-STEER-ABE")
    i = {k: v[0] for k, v in case["inputs"].items()}
    tires = (LinearTire(cornering_stiffness=i["Cf_axle"] / 2), LinearTire(cornering_stiffness=i["Cr_axle"] / 2))
    model = SingleTrack(SEDAN, *tires, tire_lag=tire_lag).variants(
        mass=i["m"], yaw_inertia=i["Iz"], a=i["lf"], b=i["lr"], drag_factor=0.0, friction_coefficient=1e3)
    return model, case, i


def test_steer_for_a_turn_matches_case_A_STEER_ABE(reference_case):
    # linear tires, no drag, friction ellipse out of the way: the nonlinear equilibrium differs from
    # delta = L/R + K a_y only by the small-angle terms (cos and atan of slip angles, ~1e-4 rad^2)
    model, case, i = abe_model(reference_case)
    point = steady_state_cornering(model, lateral_acceleration=4.0, radius=i["R"])
    expected = np.radians(case["expected"]["delta_required"][0])
    assert point.speed == pytest.approx(i["V"], rel=1e-12)
    assert point.steer_angle == pytest.approx(expected, rel=2e-3)
    # and tends to the linear value as the turn gets gentle (the error is second order in a_y)
    gentle = steady_state_cornering(model, lateral_acceleration=0.04, radius=i["R"])
    linear = float(steer_angle_for(vehdyn.handling.LinearBicycle.from_parameters(
        mass=i["m"], yaw_inertia=i["Iz"], a=i["lf"], b=i["lr"], front_cornering_stiffness=i["Cf_axle"],
        rear_cornering_stiffness=i["Cr_axle"], speed=2.0), i["R"], speed=2.0))
    assert gentle.steer_angle == pytest.approx(linear, rel=4e-4)


def test_simulation_settles_on_the_algebraic_steady_state():
    tires = (FialaTire.from_vehicle(SEDAN, "front"), FialaTire.from_vehicle(SEDAN, "rear"))
    model = SingleTrack(SEDAN, *tires)
    point = steady_state_cornering(model, lateral_acceleration=6.0, speed=20.0)
    # start in straight running at the same speed: the lateral transient dies out; the speed mode is
    # slow (m / (2 k u) ~ 60 s), so compare after it has been given time with a tight solver
    t = np.linspace(0, 200, 201)
    inputs = {"front_steer_angle": point.steer_angle, "rear_longitudinal_force": point.drive}
    r = vehdyn.simulate(model, t, inputs, x0=model.straight_running(20.0), method="LSODA", rtol=1e-9, atol=1e-11)
    assert r["longitudinal_velocity"][-1] == pytest.approx(point.speed, rel=1e-5)
    assert r["yaw_rate"][-1] == pytest.approx(point.yaw_rate, rel=1e-5)
    assert r["lateral_velocity"][-1] == pytest.approx(point.state[model.index("lateral_velocity")], rel=1e-4)
    # and the equilibrium is an equilibrium of the model's rhs
    f = model.rhs(0.0, point.state, point.inputs)
    assert np.max(np.abs(np.delete(f, [model.index("x"), model.index("y"), model.index("yaw_angle")]))) < 1e-8


def test_wheel_spin_model_has_the_same_steady_state_as_force_mode():
    tires = (FialaTire.from_vehicle(SEDAN, "front"), FialaTire.from_vehicle(SEDAN, "rear"))
    force = steady_state_cornering(SingleTrack(SEDAN, *tires), lateral_acceleration=3.0, speed=15.0)
    spin = steady_state_cornering(SingleTrack(SEDAN, *tires, wheel_spin=True), lateral_acceleration=3.0, speed=15.0)
    # the drive torque is the drive force times the rolling radius; the tiny difference comes from the
    # friction ellipse of force mode against the law's own combined slip
    assert spin.drive == pytest.approx(force.drive * SEDAN.tires.rolling_radius, rel=2e-2)
    assert spin.steer_angle == pytest.approx(force.steer_angle, rel=1e-3)


def test_limit_lateral_acceleration_is_bounded_by_friction():
    tires = (FialaTire.from_vehicle(SEDAN, "front"), FialaTire.from_vehicle(SEDAN, "rear"))
    model = SingleTrack(SEDAN, *tires, tire_lag=False)
    diagram = nonlinear_handling_diagram(model, radius=60.0, step=0.5, tolerance=0.02)
    mu_g = SEDAN.tires.friction_coefficient * 9.81
    # both axles at mu F_z would give mu g; the drive force on the rear uses some of its friction
    assert 0.85 * mu_g < diagram.limit_lateral_acceleration <= mu_g
    assert np.all(np.diff(diagram.steer_angle) > 0)  # understeering sedan: steer grows to the limit
    frame = constant_radius_test(model, 60.0, step=0.5)
    assert frame.attrs["limit_lateral_acceleration"] == pytest.approx(diagram.limit_lateral_acceleration, abs=0.05)
    # at small a_y the constant-radius understeer gradient is the linear one, K = (m/L)(b/Cf - a/Cr)
    p = model.parameters
    cf, cr = model.axle_cornering_stiffness()
    k_linear = p.mass / p.wheelbase * (p.b / cf - p.a / cr)
    assert frame["understeer_gradient"].iloc[1] == pytest.approx(k_linear, rel=0.15)


def test_beyond_the_limit_is_a_clear_error():
    tires = (FialaTire.from_vehicle(SEDAN, "front"), FialaTire.from_vehicle(SEDAN, "rear"))
    model = SingleTrack(SEDAN, *tires, tire_lag=False)
    with pytest.raises(vehdyn.SimulationError, match="no steady-state turn"):
        steady_state_cornering(model, lateral_acceleration=12.0, radius=60.0)


def test_argument_errors():
    model = SingleTrack(SEDAN, LinearTire(cornering_stiffness=4e4), LinearTire(cornering_stiffness=4e4))
    with pytest.raises(vehdyn.ParameterError, match="exactly one"):
        steady_state_cornering(model, lateral_acceleration=2.0)
    with pytest.raises(vehdyn.ParameterError, match="same sign"):
        steady_state_cornering(model, lateral_acceleration=2.0, radius=-50.0)
    with pytest.raises(vehdyn.ParameterError, match="driven_axle"):
        steady_state_cornering(model, lateral_acceleration=2.0, speed=10.0, driven_axle="middle")
    with pytest.raises(vehdyn.ParameterError, match="SingleTrack"):
        steady_state_cornering("car", lateral_acceleration=2.0, speed=10.0)
    with pytest.raises(vehdyn.ParameterError, match="variants"):
        steady_state_cornering(model.variants(mass=[1000.0, 1100.0]), lateral_acceleration=2.0, speed=10.0)
