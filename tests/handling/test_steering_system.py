"""The steering system and its loop with the vehicle, against closed forms of the steady state."""

import dataclasses

import numpy as np
import pytest

import vehdyn
from vehdyn.handling import LinearBicycle, SteeredVehicle, SteeringSystem
from vehdyn.handling.steering_system import boost_torque, steering_system_parameters
from vehdyn.tire import LinearTire

SEDAN = vehdyn.load_vehicle("sedan")
SPEED = 100 / 3.6


def closed_forms(vehicle, speed, params):
    """Steady a_y per steering-wheel angle and column torque per a_y without assist and friction.

    delta = (theta_sw - T_c / k_c) / N, T_c = t F_yf / N, F_yf = m b a_y / L, a_y = G delta (G the
    bicycle's steady lateral-acceleration gain): eliminate delta and T_c.
    """
    bike = LinearBicycle(vehicle, speed)
    gain = bike.dc_gain()[bike.index("lateral_acceleration", "outputs"), 0]
    m, b, L = vehicle.mass.mass, vehicle.geometry.cg_to_rear_axle, vehicle.wheelbase
    torque_per_ay = params.trail * m * b / (L * params.ratio)
    sensitivity = 1.0 / (params.ratio / gain + torque_per_ay / params.column_stiffness)
    return sensitivity, torque_per_ay


def test_boost_curve_is_odd_flat_on_centre_and_tends_to_the_boost_ratio():
    t = np.array([0.0, 1e-3, 5.0, 100.0])
    out = boost_torque(t, 3.0, 1.5)
    assert out[0] == 0.0
    assert out[1] / t[1] < 1e-5  # slope 0 at the centre
    assert out[3] / t[3] == pytest.approx(3.0 * 100.0**2 / (100.0**2 + 1.5**2), rel=1e-14)
    assert boost_torque(-t, 3.0, 1.5).tolist() == (-out).tolist()


def test_pneumatic_trail_comes_from_the_tire_law():
    from vehdyn.tire import tire_for_vehicle

    p = steering_system_parameters(SEDAN)
    tire = tire_for_vehicle(SEDAN, "front")
    load = 0.5 * SEDAN.static_axle_loads()[0]
    # the law's own trail over a wider slip range, +-1e-3 rad (the file's shifts cancel in the differences)
    plus, minus = tire.forces(load, 0.0, 1e-3, 0.0, 20.0), tire.forces(load, 0.0, -1e-3, 0.0, 20.0)
    assert p.pneumatic_trail == pytest.approx(-float(plus.mz - minus.mz) / float(plus.fy - minus.fy), rel=1e-3)
    assert 0.01 < p.pneumatic_trail < 0.08
    assert steering_system_parameters(SEDAN, pneumatic_trail=0.01).pneumatic_trail == 0.01


@pytest.mark.parametrize("column_stiffness", [60.0, 115.0, 1e4])
def test_steady_gains_of_the_loop_match_the_closed_forms(column_stiffness):
    steering = SteeringSystem(SEDAN, column_stiffness=column_stiffness, steering_friction_torque=0.0,
                              assist_gain=0.0)
    model = SteeredVehicle(LinearBicycle(SEDAN, SPEED), steering)
    lin = model.linearize()
    dc = lin.dc_gain()[:, lin.index("steering_wheel_angle", "inputs")]
    ay = dc[lin.index("lateral_acceleration", "outputs")]
    torque = dc[lin.index("steering_wheel_torque", "outputs")]
    sensitivity, torque_per_ay = closed_forms(SEDAN, SPEED, steering.parameters)
    assert ay == pytest.approx(sensitivity, rel=1e-8)
    assert torque / ay == pytest.approx(torque_per_ay, rel=1e-8)
    # SAE signs: steering right turns right, and the driver holds it against the aligning moment
    assert ay > 0 and torque > 0 and dc[lin.index("yaw_rate", "outputs")] > 0


def test_driver_torque_input_holds_the_same_steady_state():
    steering = SteeringSystem(SEDAN, steering_input="torque", steering_friction_torque=0.0)
    model = SteeredVehicle(LinearBicycle(SEDAN, SPEED), steering)
    assert model.input_names[0] == "driver_torque"
    lin = model.linearize()
    dc = lin.dc_gain()[:, 0]
    _, torque_per_ay = closed_forms(SEDAN, SPEED, steering.parameters)
    assert dc[lin.index("lateral_acceleration", "outputs")] == pytest.approx(1.0 / torque_per_ay, rel=1e-8)
    assert dc[lin.index("steering_wheel_torque", "outputs")] == pytest.approx(1.0, rel=1e-8)
    assert lin.is_stable()


def test_assist_divides_the_steady_torque_by_one_plus_the_boost_slope():
    steering = SteeringSystem(SEDAN, steering_friction_torque=0.0, assist_gain=2.0, assist_knee_torque=1.5)
    model = SteeredVehicle(LinearBicycle(SEDAN, SPEED), steering)
    # about a steady column torque of 3 N*m: linearize at the matching operating point
    column = 3.0
    p = steering.parameters
    _, torque_per_ay = closed_forms(SEDAN, SPEED, p)
    ay = (column + boost_torque(column, p.assist_gain, p.assist_knee_torque)) / torque_per_ay
    bike = LinearBicycle(SEDAN, SPEED)
    gain = bike.dc_gain()[bike.index("lateral_acceleration", "outputs"), 0]
    delta = ay / gain
    x_bike = -np.linalg.solve(bike.A, bike.B[:, 0] * delta)
    x0 = np.concatenate([x_bike, [p.ratio * delta, 0.0]])
    u0 = model.input_vector({"steering_wheel_angle": p.ratio * delta + column / p.column_stiffness})
    assert np.allclose(model.rhs(0.0, x0, u0), 0.0, atol=1e-9)  # it is an equilibrium
    lin = model.linearize(x0, u0)
    dc = lin.dc_gain()[:, 0]
    slope = 2.0 * (column**4 + 3 * column**2 * 1.5**2) / (column**2 + 1.5**2) ** 2
    ratio = dc[lin.index("steering_wheel_torque", "outputs")] / dc[lin.index("lateral_acceleration", "outputs")]
    assert ratio == pytest.approx(torque_per_ay / (1.0 + slope), rel=1e-6)


def test_composes_with_the_single_track():
    tires = (LinearTire(cornering_stiffness=SEDAN.tires.front_cornering_stiffness / 2),
             LinearTire(cornering_stiffness=SEDAN.tires.rear_cornering_stiffness / 2))
    track = vehdyn.handling.SingleTrack(SEDAN, *tires, tire_lag=False)
    steering = SteeringSystem(SEDAN, steering_friction_torque=0.0)
    model = SteeredVehicle(track, steering)
    x0 = np.concatenate([track.straight_running(SPEED), [0.0, 0.0]])
    theta = np.radians(10.0)
    u0 = model.input_vector({"steering_wheel_angle": theta})
    # the single track's rates equal the bicycle's on the shared states at this instant (v = r = 0)
    bike = SteeredVehicle(LinearBicycle(SEDAN, SPEED), steering)
    xb = np.zeros(bike.n_states)
    ours, theirs = model.rhs(0.0, x0, u0), bike.rhs(0.0, xb, bike.input_vector({"steering_wheel_angle": theta}))
    for name in ("pinion_rate",):
        assert ours[model.index(name)] == pytest.approx(theirs[bike.index(name)], rel=1e-12)
    x0[model.index("pinion_angle")] = theta  # wheels turned: the lateral forces appear
    xb[bike.index("pinion_angle")] = theta
    ours, theirs = model.rhs(0.0, x0, u0), bike.rhs(0.0, xb, bike.input_vector({"steering_wheel_angle": theta}))
    for name in ("lateral_velocity", "yaw_rate", "pinion_rate"):
        assert ours[model.index(name)] == pytest.approx(theirs[bike.index(name)], rel=2e-3), name


def test_errors_name_the_parameter():
    with pytest.raises(vehdyn.ParameterError, match="steering_input"):
        SteeringSystem(SEDAN, steering_input="wheel")
    with pytest.raises(vehdyn.ParameterError, match="column_stiffness"):
        SteeringSystem(SEDAN, column_stiffness=-1.0)
    with pytest.raises(vehdyn.ParameterError, match="rack_stiffness"):
        SteeringSystem(SEDAN, rack_stiffness=1.0)
    with pytest.raises(vehdyn.ParameterError, match="vehicle"):
        SteeringSystem("sedan")
    with pytest.raises(vehdyn.ParameterError, match="steering.column_stiffness|column_stiffness"):
        dataclasses.replace(SEDAN.steering, column_stiffness=0.0)
    plain = vehdyn.LinearModel([[-1.0]], [[1.0]], states=["yaw_rate"], inputs=["front_steer_angle"])
    with pytest.raises(vehdyn.ParameterError, match="front_lateral_force"):
        SteeredVehicle(plain, SteeringSystem(SEDAN))
    with pytest.raises(vehdyn.ParameterError, match="steering"):
        SteeredVehicle(LinearBicycle(SEDAN, SPEED), object())
