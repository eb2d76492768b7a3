"""RigidBody6DOF: linearized groups, torque-free invariants, closed-form motions, batch, gimbal lock."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import vehdyn
from vehdyn import ParameterError, SimulationError
from vehdyn.mechanics import (
    InertiaTensor,
    RigidBody6DOF,
    angular_momentum,
    body_to_earth,
    kinetic_energy,
    torque_free_period,
)

CAR = InertiaTensor(540.0, 2400.0, 2600.0, ixz=-60.0)  # symmetric about the x-z plane: ixy = iyz = 0

GROUPS = {
    "longitudinal": (["longitudinal_velocity", "x"], ["longitudinal_force"]),
    "vertical_pitch": (["vertical_velocity", "pitch_rate", "z", "pitch_angle"], ["vertical_force", "pitch_moment"]),
    "lateral_roll_yaw": (["lateral_velocity", "roll_rate", "yaw_rate", "y", "roll_angle", "yaw_angle"],
                         ["lateral_force", "roll_moment", "yaw_moment"]),
}


def test_linearization_about_straight_running_splits_into_three_groups():
    body = RigidBody6DOF(mass=1500.0, inertia=CAR)
    u0 = 25.0
    lin = body.linearize({"longitudinal_velocity": u0})
    group_of_state = {s: g for g, (states, _) in GROUPS.items() for s in states}
    group_of_input = {i: g for g, (_, inputs) in GROUPS.items() for i in inputs}
    assert sorted(group_of_state) == sorted(body.state_names)
    assert sorted(group_of_input) == sorted(body.input_names)
    for i, row in enumerate(body.state_names):
        for j, col in enumerate(body.state_names):
            if group_of_state[row] != group_of_state[col]:
                assert lin.A[i, j] == 0.0, (row, col, lin.A[i, j])
        for j, col in enumerate(body.input_names):
            if group_of_state[row] != group_of_input[col]:
                assert lin.B[i, j] == 0.0, (row, col, lin.B[i, j])
    a = lambda r, c: lin.A[body.index(r), body.index(c)]  # noqa: E731
    b = lambda r, c: lin.B[body.index(r), body.index(c, "inputs")]  # noqa: E731
    # small-perturbation equations about straight running with no gravity: dw/dt = Z/m + u0 q,
    # dv/dt = Y/m - u0 r, dz/dt = w - u0 theta, dy/dt = v + u0 psi
    assert a("vertical_velocity", "pitch_rate") == pytest.approx(u0, rel=1e-9)
    assert a("lateral_velocity", "yaw_rate") == pytest.approx(-u0, rel=1e-9)
    assert a("z", "pitch_angle") == pytest.approx(-u0, rel=1e-9)
    assert a("y", "yaw_angle") == pytest.approx(u0, rel=1e-9)
    assert b("longitudinal_velocity", "longitudinal_force") == pytest.approx(1 / 1500.0, rel=1e-9)
    # roll and yaw couple through Ixz: [L, N] = [[Ixx, -Ixz], [-Ixz, Izz]] [dp, dr]
    coupled = np.linalg.inv([[CAR.ixx, -CAR.ixz], [-CAR.ixz, CAR.izz]])
    np.testing.assert_allclose([[b("roll_rate", "roll_moment"), b("roll_rate", "yaw_moment")],
                                [b("yaw_rate", "roll_moment"), b("yaw_rate", "yaw_moment")]], coupled, rtol=1e-8)
    assert b("pitch_rate", "pitch_moment") == pytest.approx(1 / CAR.iyy, rel=1e-9)


def test_gravity_couples_pitch_into_the_longitudinal_group():
    g = vehdyn.units.GRAVITY
    body = RigidBody6DOF(mass=1500.0, inertia=CAR, gravity=g)
    lin = body.linearize({"longitudinal_velocity": 25.0}, {"vertical_force": -1500.0 * g})
    A = lin.A
    assert A[body.index("longitudinal_velocity"), body.index("pitch_angle")] == pytest.approx(-g, rel=1e-9)
    assert A[body.index("lateral_velocity"), body.index("roll_angle")] == pytest.approx(g, rel=1e-9)
    # the weight is balanced: the operating point is an equilibrium of the velocities
    np.testing.assert_allclose(body.rhs(0.0, lin.x_op, lin.u_op)[:6], 0.0, atol=1e-12)


def invariants(result, inertia, mass=1.0):
    omega = np.stack([result["roll_rate"], result["pitch_rate"], result["yaw_rate"]])
    energy = kinetic_energy(mass, inertia, np.zeros_like(omega), omega)
    h_body = angular_momentum(inertia, omega)
    h_earth = body_to_earth(h_body, result["roll_angle"], result["pitch_angle"], result["yaw_angle"])
    return energy, np.linalg.norm(h_body, axis=0), h_earth


def test_torque_free_spin_about_a_principal_axis_stays_there():
    inertia = InertiaTensor(1.0, 2.0, 3.0)  # x minor, y intermediate, z major axis
    body = RigidBody6DOF(mass=1.0, inertia=inertia)
    # a steady pitch spin pitches through the vertical (gimbal lock), so it runs for 2 s only
    for axis, rate, duration in (("yaw_rate", 1.0, 50.0), ("pitch_rate", 0.7, 2.0), ("roll_rate", -1.3, 50.0)):
        t = np.linspace(0.0, duration, 501)
        result = vehdyn.simulate(body, t, x0={axis: rate}, method="DOP853", rtol=1e-10, atol=1e-12)
        np.testing.assert_allclose(result[axis], rate, rtol=1e-12)
        others = [s for s in ("roll_rate", "pitch_rate", "yaw_rate") if s != axis]
        assert np.max(np.abs([result[s] for s in others])) < 1e-12
    # minor and major axes are stable: a 1 % perturbation stays small
    t = np.linspace(0.0, 50.0, 501)
    for axis in ("roll_rate", "yaw_rate"):
        start = {"roll_rate": 0.01, "pitch_rate": 0.01, "yaw_rate": 0.01, axis: 1.0}
        result = vehdyn.simulate(body, t, x0=start, method="DOP853", rtol=1e-10, atol=1e-12)
        assert np.min(result[axis]) > 0.99


def test_intermediate_axis_tumbles_with_energy_and_momentum_conserved():
    """Dzhanibekov flip: the yaw rate reverses periodically with the elliptic-function period
    (torque_free_period, Landau & Lifshitz sec. 37);
    T, |H| and the earth-axis H stay constant (relative drift <= 1e-8 over 100 s at rtol 1e-10)."""
    inertia = InertiaTensor(1.0, 3.0, 2.0)  # x minor, y major, z intermediate axis
    body = RigidBody6DOF(mass=1.0, inertia=inertia)
    # spinning about z with H nearly vertical keeps |pitch| below ~35 deg through the flips
    omega0 = np.array([0.03, 0.0, 1.0])
    t = np.linspace(0.0, 100.0, 4001)
    result = vehdyn.simulate(body, t, x0=dict(zip(("roll_rate", "pitch_rate", "yaw_rate"), omega0)), method="DOP853",
                             rtol=1e-10, atol=1e-12)
    yaw_rate = result["yaw_rate"]
    assert yaw_rate.min() < -0.99 and yaw_rate.max() > 0.99  # it flips, and flips back
    k = np.flatnonzero(np.diff(np.sign(yaw_rate)))
    crossings = t[k] - yaw_rate[k] * (t[k + 1] - t[k]) / (yaw_rate[k + 1] - yaw_rate[k])
    assert crossings.size >= 4
    np.testing.assert_allclose(np.diff(crossings[::2]), torque_free_period(inertia, omega0), rtol=1e-6)
    energy, h_norm, h_earth = invariants(result, inertia)
    assert np.max(np.abs(energy / energy[0] - 1)) <= 1e-8
    assert np.max(np.abs(h_norm / h_norm[0] - 1)) <= 1e-8
    assert np.max(np.linalg.norm(h_earth - h_earth[:, :1], axis=0)) / h_norm[0] <= 1e-8


def test_steady_turn_follows_the_circle():
    """Y = m u r with constant r: v stays 0, the CG runs on a circle of radius u / r."""
    mass, speed, yaw_rate = 1200.0, 15.0, 0.25
    body = RigidBody6DOF(mass=mass, inertia=InertiaTensor(540.0, 2400.0, 2600.0))  # z principal: no wobble
    t = np.linspace(0.0, 10.0, 201)
    result = vehdyn.simulate(body, t, inputs={"lateral_force": mass * speed * yaw_rate},
                             x0={"longitudinal_velocity": speed, "yaw_rate": yaw_rate}, method="DOP853", rtol=1e-11,
                             atol=1e-12)
    radius = speed / yaw_rate
    np.testing.assert_allclose(result["x"], radius * np.sin(yaw_rate * t), atol=1e-7)
    np.testing.assert_allclose(result["y"], radius * (1 - np.cos(yaw_rate * t)), atol=1e-7)
    np.testing.assert_allclose(result["yaw_angle"], yaw_rate * t, atol=1e-9)
    np.testing.assert_allclose(result["lateral_velocity"], 0.0, atol=1e-9)
    np.testing.assert_allclose(result["lateral_acceleration"], speed * yaw_rate, rtol=1e-9)
    np.testing.assert_allclose(result["course_angle"], result["yaw_angle"], atol=1e-9)
    np.testing.assert_allclose(result["x_velocity"], speed * np.cos(yaw_rate * t), atol=1e-8)


def test_projectile_under_gravity():
    g = 9.81
    body = RigidBody6DOF(mass=3.0, inertia=InertiaTensor(1.0, 1.0, 1.0), gravity=g)
    pitch = 0.3
    t = np.linspace(0.0, 2.0, 41)
    result = vehdyn.simulate(body, t, x0={"longitudinal_velocity": 10.0, "pitch_angle": pitch}, method="DOP853",
                             rtol=1e-11, atol=1e-12)
    np.testing.assert_allclose(result["x"], 10.0 * np.cos(pitch) * t, atol=1e-8)
    np.testing.assert_allclose(result["z"], -10.0 * np.sin(pitch) * t + 0.5 * g * t * t, atol=1e-8)
    # absolute acceleration in body axes is gravity: g R^T e_Z
    np.testing.assert_allclose(result["longitudinal_acceleration"], -g * np.sin(pitch), rtol=1e-12)
    np.testing.assert_allclose(result["vertical_acceleration"], g * np.cos(pitch), rtol=1e-12)


def test_outputs_sideslip_course_speed():
    body = RigidBody6DOF(mass=1000.0, inertia=CAR)
    x = body.state_vector(longitudinal_velocity=20.0, lateral_velocity=-1.5, vertical_velocity=0.2, yaw_angle=0.4)
    y = dict(zip(body.output_names, body.output(0.0, x, np.zeros(6))))
    assert y["sideslip_angle"] == pytest.approx(np.arctan(-1.5 / 20.0), rel=1e-15)
    assert y["course_angle"] == pytest.approx(0.4 + np.arctan(-1.5 / 20.0), rel=1e-15)
    assert y["speed"] == pytest.approx(np.sqrt(400 + 2.25 + 0.04))
    assert y["x_velocity"] == pytest.approx(20 * np.cos(0.4) + 1.5 * np.sin(0.4))
    assert y["y_velocity"] == pytest.approx(20 * np.sin(0.4) - 1.5 * np.cos(0.4))


def test_batch_axis_matches_one_by_one():
    rng = np.random.default_rng(11)
    n = 4
    masses = rng.uniform(900, 1800, n)
    tensors = np.stack([InertiaTensor(500 + 40 * k, 2000.0, 2300.0, ixz=5.0 * k).matrix for k in range(n)], -1)
    batch_body = RigidBody6DOF(mass=masses, inertia=tensors, gravity=9.81)
    x = rng.normal(size=(12, n)) * 0.3
    x[0] += 20
    u = rng.normal(size=(6, n)) * 500
    f, y = batch_body.rhs(0.0, x, u), batch_body.output(0.0, x, u)
    assert f.shape == (12, n) and y.shape == (9, n)
    for k in range(n):
        single = RigidBody6DOF(mass=masses[k], inertia=tensors[..., k], gravity=9.81)
        np.testing.assert_allclose(f[:, k], single.rhs(0.0, x[:, k], u[:, k]), rtol=1e-13, atol=1e-13)
        np.testing.assert_allclose(y[:, k], single.output(0.0, x[:, k], u[:, k]), rtol=1e-13, atol=1e-13)
    t = np.linspace(0, 1, 11)
    result = vehdyn.simulate(batch_body, t, x0=x, inputs=np.repeat(u[:, None, :], 11, axis=1), method="rk4",
                             check_stability=False)  # a batch of parameters has no single linearization
    assert result.states.shape == (12, 11, n)
    with pytest.raises(ParameterError):
        batch_body.linearize(x[:, 0], u[:, 0])
    # a batch of initial states with inputs shared by all of them, with every integrator path
    body = RigidBody6DOF(mass=1500.0, inertia=CAR)
    for method in ("rk4", "RK45"):
        shared = vehdyn.simulate(body, t, x0=x, inputs={"lateral_force": 800.0}, method=method)
        for k in (0, n - 1):
            alone = vehdyn.simulate(body, t, x0=x[:, k], inputs={"lateral_force": 800.0}, method=method)
            np.testing.assert_allclose(shared.states[:, :, k], alone.states, rtol=1e-5, atol=1e-8)
            np.testing.assert_allclose(shared.outputs[:, :, k], alone.outputs, rtol=1e-5, atol=1e-8)


@pytest.mark.parametrize("seed", range(5))
def test_analytic_jacobian_agrees_with_central_differences(seed):
    rng = np.random.default_rng(seed)
    body = RigidBody6DOF(mass=1300.0, inertia=InertiaTensor(500, 2000, 2200, ixy=20, ixz=-40, iyz=15), gravity=9.81)
    x = rng.normal(size=12) * 0.6
    x[0] += 20.0
    u = rng.normal(size=6) * 400.0
    for exact, numeric in zip(body.jacobian(0.0, x, u), body._finite_difference_jacobian(0.0, x, u)):
        np.testing.assert_allclose(exact, numeric, atol=1e-9 * max(1.0, np.max(np.abs(numeric))))


def test_gimbal_lock_raises_a_simulation_error():
    body = RigidBody6DOF(mass=1.0, inertia=InertiaTensor(1.0, 1.0, 1.0))
    with pytest.raises(SimulationError, match="gimbal lock") as info:
        body.rhs(0.0, body.state_vector(pitch_angle=np.pi / 2), np.zeros(6))
    assert info.value.signal == "pitch_angle"
    # pitching up at 1 rad/s from 1.5 rad reaches the margin at t = pi/2 - 1e-3 - 1.5
    t = np.linspace(0.0, 0.2, 21)
    with pytest.raises(SimulationError, match="gimbal lock") as info:
        vehdyn.simulate(body, t, x0={"pitch_rate": 1.0, "pitch_angle": 1.5}, method="RK45", rtol=1e-9)
    assert info.value.time == pytest.approx(np.pi / 2 - 1e-3 - 1.5, abs=2e-3)


@pytest.mark.parametrize("kwargs, key", [
    ({"mass": 0.0}, "mass"),
    ({"mass": [1.0, -2.0]}, "mass"),
    ({"inertia": np.diag([1.0, 1.0, 0.0])}, "inertia"),
    ({"gravity": float("nan")}, "gravity"),
    ({"gimbal_lock_margin": 0.0}, "gimbal_lock_margin"),
])
def test_rigid_body_parameter_errors(kwargs, key):
    args = {"mass": 1.0, "inertia": InertiaTensor(1.0, 1.0, 1.0), **kwargs}
    with pytest.raises(ParameterError) as info:
        RigidBody6DOF(**args)
    assert info.value.key == key


@settings(max_examples=60, deadline=None)
@given(states=st.lists(st.floats(-3.0, 3.0), min_size=12, max_size=12),
       pitch=st.floats(-1.55, 1.55), inputs=st.lists(st.floats(-1e4, 1e4), min_size=6, max_size=6))
def test_rhs_is_finite_and_batch_consistent_away_from_gimbal_lock(states, pitch, inputs):
    body = RigidBody6DOF(mass=1500.0, inertia=CAR, gravity=9.81)
    x = np.array(states)
    x[10] = pitch
    u = np.array(inputs)
    single = body.rhs(0.0, x, u)
    assert np.all(np.isfinite(single)) and np.all(np.isfinite(body.output(0.0, x, u)))
    pair = body.rhs(0.0, np.stack([x, np.zeros(12)], axis=1), np.stack([u, np.zeros(6)], axis=1))
    np.testing.assert_allclose(pair[:, 0], single, rtol=1e-14, atol=1e-14)
    # the rates of the rotational states conserve nothing in general, but with no moment the
    # kinetic energy of rotation is constant: omega . I domega/dt = 0
    omega = x[3:6]
    u_free = np.concatenate([u[:3], np.zeros(3)])
    omega_dot = body.rhs(0.0, x, u_free)[3:6]
    assert abs(omega @ CAR.matrix @ omega_dot) <= 1e-9 * (1 + np.abs(CAR.matrix @ omega) @ np.abs(omega) ** 2)
