"""Newton-Euler equations: published case, term-by-term SAE equations, inertial-frame dH/dt."""

import json
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.linalg import expm
from scipy.spatial.transform import Rotation

from vehdyn import ParameterError
from vehdyn.mechanics import InertiaTensor, angular_momentum, kinetic_energy, newton_euler

DATA = Path(__file__).resolve().parents[1] / "data" / "rigid_body_reference.json"


def reference_case(case_id):
    cases = json.loads(DATA.read_text())["cases"]
    return next(c for c in cases if c["id"] == case_id)


def printed_tolerance(value):
    """Half a unit in the last of 7 printed significant figures."""
    return 0.5 * 10.0 ** (np.floor(np.log10(abs(value))) - 6)


def test_H_EULER_FULLTENSOR_angular_acceleration():
    case = reference_case("H-EULER-FULLTENSOR")
    tensor = np.array(case["inputs"]["I_body_tensor"][0])
    omega = np.array(case["inputs"]["omega"][0])
    moment = np.array(case["inputs"]["M_applied"][0])
    _, omega_dot = newton_euler(1.0, tensor, np.zeros(3), omega, np.zeros(3), moment)
    for k, axis in enumerate("xyz"):
        expected = case["expected"][f"omega_dot_{axis}"][0]
        assert abs(omega_dot[k] - expected) <= printed_tolerance(expected)
    # the same through InertiaTensor, whose products are the negated tensor entries
    inertia = InertiaTensor.from_matrix(tensor)
    assert inertia.ixy == pytest.approx(-case["expected"]["I_xy_tensor_entry"][0], abs=printed_tolerance(0.48))
    assert inertia.ixz == pytest.approx(-case["expected"]["I_xz_tensor_entry"][0], abs=printed_tolerance(0.16))
    assert inertia.iyz == pytest.approx(-case["expected"]["I_yz_tensor_entry"][0], abs=printed_tolerance(0.27))
    _, omega_dot_tensor = newton_euler(1.0, inertia, np.zeros(3), omega, np.zeros(3), moment)
    np.testing.assert_allclose(omega_dot_tensor, omega_dot, rtol=1e-13)


def sae_moments(ixx, iyy, izz, ixy, ixz, iyz, p, q, r, p_dot, q_dot, r_dot):
    """The SAE/Etkin moment equations written out term by term (products Ixy = int x y dm)."""
    roll = ixx * p_dot - ixy * (q_dot - p * r) - ixz * (r_dot + p * q) - iyz * (q * q - r * r) + (izz - iyy) * q * r
    pitch = iyy * q_dot - iyz * (r_dot - p * q) - ixy * (p_dot + q * r) - ixz * (r * r - p * p) + (ixx - izz) * r * p
    yaw = izz * r_dot - ixz * (p_dot - q * r) - iyz * (q_dot + r * p) - ixy * (p * p - q * q) + (iyy - ixx) * p * q
    return np.array([roll, pitch, yaw])


def test_sae_equations_term_by_term_all_products_nonzero():
    rng = np.random.default_rng(3)
    inertia = InertiaTensor(520.0, 2100.0, 2300.0, ixy=35.0, ixz=-80.0, iyz=22.0)
    mass = 1450.0
    for _ in range(20):
        u, v, w, p, q, r, u_dot, v_dot, w_dot, p_dot, q_dot, r_dot = rng.normal(size=12) * [20, 2, 1, 1, 1, 1, 3,
                                                                                                2, 2, 4, 4, 4]
        force = mass * np.array([u_dot + q * w - r * v, v_dot + r * u - p * w, w_dot + p * v - q * u])
        moment = sae_moments(inertia.ixx, inertia.iyy, inertia.izz, inertia.ixy, inertia.ixz, inertia.iyz,
                             p, q, r, p_dot, q_dot, r_dot)
        velocity_rate, omega_dot = newton_euler(mass, inertia, [u, v, w], [p, q, r], force, moment)
        np.testing.assert_allclose(velocity_rate, [u_dot, v_dot, w_dot], rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(omega_dot, [p_dot, q_dot, r_dot], rtol=1e-12, atol=1e-12)


@settings(max_examples=60, deadline=None)
@given(
    moments=st.lists(st.floats(0.1, 10.0), min_size=2, max_size=2),
    largest_fraction=st.floats(0.0, 1.0),
    quat=st.lists(st.floats(-1, 1), min_size=4, max_size=4).filter(lambda v: np.linalg.norm(v) > 0.1),
    attitude=st.lists(st.floats(-1, 1), min_size=4, max_size=4).filter(lambda v: np.linalg.norm(v) > 0.1),
    vectors=st.lists(st.floats(-3, 3), min_size=12, max_size=12),
    mass=st.floats(0.5, 50.0),
)
def test_newton_euler_agrees_with_inertial_frame_momentum_rates(moments, largest_fraction, quat, attitude, vectors,
                                                                 mass):
    """d(R I omega)/dt = R M and d(m R V)/dt = R F, differentiated numerically in the inertial frame."""
    small, mid = sorted(moments)
    large = mid + largest_fraction * small  # mid <= large <= small + mid
    principal_axes = Rotation.from_quat(quat).as_matrix()
    tensor = principal_axes @ np.diag([small, mid, large]) @ principal_axes.T
    r0 = Rotation.from_quat(attitude).as_matrix()
    velocity, omega, force, moment = np.reshape(vectors, (4, 3))
    velocity_rate, omega_dot = newton_euler(mass, tensor, velocity, omega, force, moment)

    skew = np.array([[0, -omega[2], omega[1]], [omega[2], 0, -omega[0]], [-omega[1], omega[0], 0]])

    def inertial(t):
        attitude_t = r0 @ expm(t * skew)  # body axes turning with omega
        return (attitude_t @ tensor @ (omega + t * omega_dot), mass * attitude_t @ (velocity + t * velocity_rate))

    h = 1e-4
    (h_plus, p_plus), (h_minus, p_minus) = inertial(h), inertial(-h)
    scale_m = np.linalg.norm(moment) + np.linalg.norm(tensor) * (np.linalg.norm(omega) ** 2 + 1)
    scale_f = np.linalg.norm(force) + mass * (np.linalg.norm(velocity) + 1) * (np.linalg.norm(omega) + 1) ** 2
    np.testing.assert_allclose((h_plus - h_minus) / (2 * h), r0 @ moment, atol=1e-6 * scale_m)
    np.testing.assert_allclose((p_plus - p_minus) / (2 * h), r0 @ force, atol=1e-6 * scale_f)


def test_batch_axis_matches_one_by_one():
    rng = np.random.default_rng(7)
    n = 5
    masses = rng.uniform(800, 2000, n)
    tensors = np.stack([InertiaTensor(400 + 50 * k, 1800.0, 2000.0, ixz=10.0 * k).matrix for k in range(n)], axis=-1)
    velocity, omega, force, moment = (rng.normal(size=(3, n)) for _ in range(4))
    v_dot, w_dot = newton_euler(masses, tensors, velocity, omega, force, moment)
    assert v_dot.shape == w_dot.shape == (3, n)
    for k in range(n):
        v1, w1 = newton_euler(masses[k], tensors[..., k], velocity[:, k], omega[:, k], force[:, k], moment[:, k])
        np.testing.assert_allclose(v_dot[:, k], v1, rtol=1e-13)
        np.testing.assert_allclose(w_dot[:, k], w1, rtol=1e-13)
    # single vectors broadcast against a batch of states
    v_dot, _ = newton_euler(1000.0, tensors[..., 0], velocity, omega, [1000.0, 0, 0], np.zeros(3))
    np.testing.assert_allclose(v_dot[0], 1.0 - (omega[1] * velocity[2] - omega[2] * velocity[1]), rtol=1e-12)


def test_energy_and_momentum_helpers():
    inertia = InertiaTensor(2.0, 3.0, 4.0, ixz=0.5)
    omega = np.array([0.3, -0.2, 0.1])
    h = angular_momentum(inertia, omega)
    np.testing.assert_allclose(h, [2 * 0.3 - 0.5 * 0.1, 3 * -0.2, -0.5 * 0.3 + 4 * 0.1])
    expected = 0.5 * 10 * (1 + 4) + 0.5 * (2 * 0.09 + 3 * 0.04 + 4 * 0.01 - 2 * 0.5 * 0.3 * 0.1)
    assert kinetic_energy(10.0, inertia, [1.0, 2.0, 0.0], omega) == pytest.approx(expected, rel=1e-14)


@pytest.mark.parametrize("kwargs, key", [
    ({"mass": 0.0}, "mass"),
    ({"mass": np.nan}, "mass"),
    ({"inertia": np.diag([1.0, 1.0, 0.0])}, "inertia"),
    ({"inertia": np.array([[1.0, 0.1, 0], [0, 1, 0], [0, 0, 1]])}, "inertia"),
    ({"inertia": np.eye(2)}, "inertia"),
    ({"velocity": [1.0, 2.0]}, "velocity"),
    ({"moment": np.zeros((4, 2))}, "moment"),
])
def test_newton_euler_rejects_bad_input(kwargs, key):
    args = {"mass": 1.0, "inertia": np.eye(3), "velocity": np.zeros(3), "angular_velocity": np.zeros(3),
            "force": np.zeros(3), "moment": np.zeros(3), **kwargs}
    with pytest.raises(ParameterError) as info:
        newton_euler(**args)
    assert info.value.key == key


def test_torque_free_period_limits():
    from vehdyn.mechanics import torque_free_period

    inertia = InertiaTensor(1.0, 2.0, 3.0)
    # small wobble about the major axis: omega_wobble = r sqrt((I3 - I1)(I3 - I2) / (I1 I2))
    r = 0.8
    expected = 2 * np.pi / (r * np.sqrt((3 - 1) * (3 - 2) / (1 * 2)))
    assert torque_free_period(inertia, [0.0, 0.0, r]) == pytest.approx(expected, rel=1e-12)
    assert torque_free_period(inertia, [1e-7, 1e-7, r]) == pytest.approx(expected, rel=1e-9)
    # about the minor axis likewise, with I1 and I3 exchanged
    expected_minor = 2 * np.pi / (r * np.sqrt((2 - 1) * (3 - 1) / (2 * 3)))
    assert torque_free_period(inertia, [r, 0.0, 0.0]) == pytest.approx(expected_minor, rel=1e-12)
    # exactly about the intermediate axis: on the separatrix, the period is infinite
    assert torque_free_period(inertia, [0.0, 1.0, 0.0]) == np.inf
    # the period does not depend on the axes the tensor is written in
    turned = InertiaTensor.from_principal([1.0, 2.0, 3.0], Rotation.from_euler("xyz", [0.3, -0.2, 1.0]).as_matrix())
    rot = Rotation.from_euler("xyz", [0.3, -0.2, 1.0]).as_matrix()
    omega = np.array([0.05, 1.0, 0.02])
    assert torque_free_period(turned, rot @ omega) == pytest.approx(torque_free_period(inertia, omega), rel=1e-10)
    with pytest.raises(ParameterError):
        torque_free_period(InertiaTensor(1.0, 1.0, 1.5), omega)
