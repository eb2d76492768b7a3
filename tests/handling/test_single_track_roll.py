"""SingleTrack with the roll degree of freedom (``roll=True``) against its reductions: the quasi-static
lateral load transfer (steady state, infinite roll stiffness), Segel's coupling, the full vehicle's trim."""

import numpy as np
import pytest

import vehdyn
from vehdyn.handling import SingleTrack
from vehdyn.procedures import sine_steer
from vehdyn.handling.lateral_yaw_roll import lateral_yaw_roll_parameters
from vehdyn.handling.single_track import lateral_load_transfer_coefficients
from vehdyn.handling.nonlinear_steady_state import steady_state_cornering
from vehdyn.tire import LinearTire
from vehdyn.units import GRAVITY

# raised roll centres, so that the geometric part of the transfer acts too (shipped: at the ground)
SEDAN = vehdyn.load_vehicle("sedan").replace(geometry__front_roll_centre_height=0.05,
                                            geometry__rear_roll_centre_height=0.1)
WHEEL_LOADS = ("front_left_normal_load", "front_right_normal_load", "rear_left_normal_load", "rear_right_normal_load")


def roll_arm(vehicle):
    g = vehicle.geometry
    return vehicle.mass.cg_height - (g.front_roll_centre_height * g.b + g.rear_roll_centre_height * g.a) / g.wheelbase


@pytest.fixture(scope="module")
def turns():
    models = {roll: SingleTrack(SEDAN, lateral_load_transfer=True, roll=roll) for roll in (False, True)}
    return models, {roll: steady_state_cornering(m, lateral_acceleration=4.0, speed=20.0) for roll, m in models.items()}


def test_steady_roll_angle_is_the_roll_moment_over_the_net_roll_stiffness(turns):
    # phi = -m h_1 a_y / (K_f + K_r - m g h_1) (Gillespie 1992, ch. 6; SAE: right side down +)
    models, turn = turns
    y = turn[True].outputs
    m, h1 = SEDAN.mass.mass, roll_arm(SEDAN)
    stiffness = SEDAN.front_roll_stiffness + SEDAN.rear_roll_stiffness - m * GRAVITY * h1
    assert y["roll_angle"] == pytest.approx(-m * h1 * y["lateral_acceleration"] / stiffness, rel=1e-9)
    assert y["roll_rate"] == pytest.approx(0.0, abs=1e-12)


def test_steady_turn_equals_the_quasi_static_transfer(turns):
    # in a steady turn the roll's elastic transfer is the quasi-static one: the same turn to the bit
    # of the solver (steer, sideslip, wheel loads)
    _, turn = turns
    a, b = turn[False], turn[True]
    assert b.steer_angle == pytest.approx(a.steer_angle, rel=1e-9)
    assert b.sideslip_angle == pytest.approx(a.sideslip_angle, rel=1e-8)
    for name in WHEEL_LOADS:
        assert b.outputs[name] == pytest.approx(a.outputs[name], rel=1e-9)


def test_infinitely_stiff_roll_is_the_quasi_static_transfer():
    # roll stiffness x400 (same distribution): the roll mode (~46 Hz) follows the forces, and the
    # transfer is the quasi-static law of the axle forces at every instant; at the vehicle's own
    # stiffness the roll lags them
    def transfer_error(vehicle):
        model = SingleTrack(vehicle, lateral_load_transfer=True, roll=True)
        t = np.linspace(0.0, 1.5, 151)
        inputs = {"front_steer_angle": sine_steer(0.025, 0.7), "rear_longitudinal_force": 250.0}
        r = vehdyn.simulate(model, t, inputs, x0=model.straight_running(22.0), method="RK45", rtol=1e-8,
                            atol=1e-10)
        (gf, ef), _ = lateral_load_transfer_coefficients(vehicle)
        front_lateral = r["front_lateral_force"] * np.cos(r.inputs[model.index("front_steer_angle", "inputs")])
        law = gf * front_lateral + ef * vehicle.mass.mass * r["lateral_acceleration"]
        moved = r["front_left_normal_load"] - 0.5 * r["front_normal_load"]
        return np.max(np.abs(moved - law)) / np.max(np.abs(law))

    s = SEDAN.suspension
    stiff = SEDAN.replace(suspension__front_antiroll_stiffness=400 * SEDAN.front_roll_stiffness,
                          suspension__rear_antiroll_stiffness=400 * SEDAN.rear_roll_stiffness,
                          suspension__front_spring_rate=400 * s.front_spring_rate,
                          suspension__rear_spring_rate=400 * s.rear_spring_rate)
    assert transfer_error(stiff) < 2e-3
    assert transfer_error(SEDAN) > 0.05


def test_equal_loads_segel_coupling():
    # load-insensitive linear tires: the axle forces do not see the transfer, so the yaw and
    # longitudinal rates are SingleTrack's and the lateral one differs by Segel's coupling
    # m (dv/dt + u r) + m h_1 dp/dt = F_y, with J dp/dt = -m h_1 a_y - (K - m g h_1) phi - C p
    tires = [LinearTire(cornering_stiffness=getattr(SEDAN.tires, f"{axle}_cornering_stiffness") / 2)
             for axle in ("front", "rear")]
    roll, plain = SingleTrack(SEDAN, *tires, lateral_load_transfer=True, roll=True), SingleTrack(SEDAN, *tires)
    p = lateral_yaw_roll_parameters(SEDAN)
    inertia = p.roll_inertia - (p.sprung_mass * p.roll_arm) ** 2 / p.mass
    m, h1, g = SEDAN.mass.mass, roll_arm(SEDAN), GRAVITY
    stiffness = SEDAN.front_roll_stiffness + SEDAN.rear_roll_stiffness
    s, tr = SEDAN.suspension, SEDAN.geometry
    damping = s.front_damping * tr.front_track**2 / 2 + s.rear_damping * tr.rear_track**2 / 2
    rng = np.random.default_rng(5)
    for _ in range(10):
        values = dict(lateral_velocity=rng.uniform(-1, 1), yaw_rate=rng.uniform(-0.3, 0.3),
                      front_lateral_deflection=rng.uniform(-0.01, 0.01),
                      rear_lateral_deflection=rng.uniform(-0.01, 0.01))
        phi, rate = rng.uniform(-0.05, 0.05), rng.uniform(-0.3, 0.3)
        u = plain.input_vector(front_steer_angle=rng.uniform(-0.05, 0.05))
        a = plain.rhs(0.0, plain.straight_running(25.0, **values), u)
        b = roll.rhs(0.0, roll.straight_running(25.0, roll_angle=phi, roll_rate=rate, **values), u)
        y = plain.output(0.0, plain.straight_running(25.0, **values), u)
        a_y = y[plain.index("lateral_acceleration", "outputs")]
        roll_acceleration = (-m * h1 * a_y - (stiffness - m * g * h1) * phi - damping * rate) / inertia
        assert b[roll.index("roll_angle")] == rate
        assert b[roll.index("roll_rate")] == pytest.approx(roll_acceleration, rel=1e-12)
        for name in ("longitudinal_velocity", "yaw_rate", "front_lateral_deflection"):
            assert b[roll.index(name)] == pytest.approx(a[plain.index(name)], rel=1e-12, abs=1e-12)
        assert b[roll.index("lateral_velocity")] == pytest.approx(
            a[plain.index("lateral_velocity")] - h1 * roll_acceleration, rel=1e-12)


def test_steady_turn_balance_against_the_full_vehicle_trim():
    # the shipped sedan at 2 m/s^2: steer and wheel loads of the full vehicle's trim (its tires'
    # vertical compliance and unsprung masses are what differ; measured 0.6 % and 0.5-1.2 %)
    from vehdyn.full_vehicle import FullVehicle

    sedan = vehdyn.load_vehicle("sedan")
    full = FullVehicle(sedan)
    x0, u0 = full.trim(22.2, lateral_acceleration=2.0)
    y = dict(zip(full.output_names, full.output(0.0, x0, u0)))
    model = SingleTrack(sedan, lateral_load_transfer=True, roll=True)
    turn = steady_state_cornering(model, lateral_acceleration=2.0, speed=22.2)
    assert turn.steer_angle == pytest.approx(float(u0[full.index("front_steer_angle", "inputs")]), rel=0.015)
    for axle in ("front", "rear"):
        for side in ("left", "right"):
            assert turn.outputs[f"{axle}_{side}_normal_load"] == pytest.approx(y[f"normal_load_{axle}_{side}"],
                                                                               rel=0.025)


@pytest.mark.compiled_vs_numpy
def test_compiled_equals_numpy():
    model = SingleTrack(SEDAN, lateral_load_transfer=True, roll=True)
    t = np.linspace(0.0, 0.6, 13)
    # a callable, evaluated at every stage by both backends (a closed-form signal is held on the
    # output grid by the numpy backend)
    inputs = {"front_steer_angle": lambda tt: 0.025 * np.sin(2 * np.pi * 0.7 * np.asarray(tt)),
              "rear_longitudinal_force": 250.0}
    runs = {backend: vehdyn.simulate(model, t, inputs, x0=model.straight_running(22.0), method="RK45", rtol=1e-8,
                                     atol=1e-11, backend=backend) for backend in ("numpy", "compiled")}
    assert "compiled" in runs["compiled"].method_reason
    for name in ("yaw_rate", "lateral_acceleration", "roll_angle", "roll_rate") + WHEEL_LOADS:
        scale = np.max(np.abs(runs["numpy"][name]))
        assert np.max(np.abs(runs["compiled"][name] - runs["numpy"][name])) < 1e-6 * scale, name


@pytest.mark.parametrize("kwargs, key", [
    (dict(roll=True), "roll"),  # roll without the transfer it sets
    (dict(lateral_load_transfer=True, roll=1), "roll"),
    (dict(lateral_load_transfer="yes"), "lateral_load_transfer"),
])
def test_bad_options(kwargs, key):
    with pytest.raises(vehdyn.ParameterError) as info:
        SingleTrack(SEDAN, **kwargs)
    assert info.value.key == key
