"""Kinematics: rotations against scipy, Euler rates against R^T dR/dt, point transfer, five-term formula."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from vehdyn import ParameterError
from vehdyn.mechanics import (
    absolute_acceleration,
    body_rates,
    body_to_earth,
    check_gimbal_lock,
    earth_to_body,
    euler_angle_rates,
    euler_angles_from_rotation,
    moving_point_acceleration,
    moving_point_velocity,
    point_acceleration,
    point_velocity,
    rotation_body_to_earth,
    rotation_earth_to_body,
)


def test_rotation_matches_scipy_intrinsic_yaw_pitch_roll():
    rng = np.random.default_rng(1)
    roll, pitch, yaw = rng.uniform(-1.4, 1.4, (3, 8))
    matrices = rotation_body_to_earth(roll, pitch, yaw)
    assert matrices.shape == (3, 3, 8)
    for k in range(8):
        expected = Rotation.from_euler("ZYX", [yaw[k], pitch[k], roll[k]]).as_matrix()
        np.testing.assert_allclose(matrices[..., k], expected, atol=1e-15)
        np.testing.assert_allclose(rotation_earth_to_body(roll[k], pitch[k], yaw[k]), expected.T, atol=1e-15)
    back = euler_angles_from_rotation(matrices)
    np.testing.assert_allclose(np.array(back), [roll, pitch, yaw], atol=1e-13)


def test_sae_sign_of_each_elementary_rotation():
    angle = 0.3
    c, s = np.cos(angle), np.sin(angle)
    # yaw right (z down): the nose turns towards +Y
    np.testing.assert_allclose(body_to_earth([1, 0, 0], 0, 0, angle), [c, s, 0], atol=1e-15)
    # pitch nose up: the nose rises, i.e. its Z (down) component is negative
    np.testing.assert_allclose(body_to_earth([1, 0, 0], 0, angle, 0), [c, 0, -s], atol=1e-15)
    # roll right: the right side (+y) goes down (+Z)
    np.testing.assert_allclose(body_to_earth([0, 1, 0], angle, 0, 0), [0, c, s], atol=1e-15)
    # earth_to_body inverts body_to_earth, also for a batch of vectors
    vectors = np.arange(12.0).reshape(3, 4)
    np.testing.assert_allclose(earth_to_body(body_to_earth(vectors, 0.1, -0.2, 2.0), 0.1, -0.2, 2.0), vectors,
                               atol=1e-13)


def test_euler_angle_rates_reproduce_the_body_rates_through_dR_dt():
    """R^T dR/dt = [omega x] when the angles move at the rates from euler_angle_rates."""
    angles = np.array([0.4, -0.7, 2.1])
    omega = np.array([0.3, -0.5, 0.8])
    rates = np.array(euler_angle_rates(*angles[:2], *omega))
    h = 1e-6
    dR = (rotation_body_to_earth(*(angles + h * rates)) - rotation_body_to_earth(*(angles - h * rates))) / (2 * h)
    skew = rotation_body_to_earth(*angles).T @ dR
    np.testing.assert_allclose([skew[2, 1], skew[0, 2], skew[1, 0]], omega, atol=1e-8)
    np.testing.assert_allclose(skew + skew.T, 0.0, atol=1e-8)
    np.testing.assert_allclose(body_rates(*angles[:2], *rates), omega, atol=1e-14)


@pytest.mark.parametrize("pitch", [np.pi / 2, -np.pi / 2, np.pi / 2 - 1e-5, np.pi / 2 + 1e-5, np.nan])
def test_gimbal_lock_is_refused(pitch):
    with pytest.raises(ParameterError, match="gimbal lock") as info:
        euler_angle_rates(0.0, pitch, 0.1, 0.2, 0.3)
    assert info.value.key == "pitch_angle"


def test_gimbal_lock_names_the_batch_member_and_accepts_pitch_near_it():
    with pytest.raises(ParameterError, match="batch member 2"):
        check_gimbal_lock(np.array([0.0, 1.0, np.pi / 2]))
    rates = euler_angle_rates(0.0, np.pi / 2 - 0.01, 0.0, 0.0, 1.0)
    assert np.isfinite(rates).all() and rates[2] == pytest.approx(1 / np.cos(np.pi / 2 - 0.01))
    with pytest.raises(ParameterError):
        euler_angles_from_rotation(rotation_body_to_earth(0.1, np.pi / 2, 0.2))


def test_point_transfer_car_in_the_x_z_plane():
    """V_O = u i + w k, omega = q j, r = l i: V_P = u i + (w - q l) k,
    a_P = (du + q w - q^2 l) i + (dw - q u - dq l) k (the H-POINT-TRANSFER pitfall: omega x V)."""
    u, w, q, l, du, dw, dq = 25.0, 0.4, 0.2, 1.6, 1.5, -0.3, 0.7
    velocity = point_velocity([u, 0, w], [0, q, 0], [l, 0, 0])
    np.testing.assert_allclose(velocity, [u, 0, w - q * l], rtol=1e-15)
    a_o = absolute_acceleration([u, 0, w], [0, q, 0], [du, 0, dw])
    np.testing.assert_allclose(a_o, [du + q * w, 0, dw - q * u], rtol=1e-15)
    acceleration = point_acceleration(a_o, [0, q, 0], [0, dq, 0], [l, 0, 0])
    np.testing.assert_allclose(acceleration, [du + q * w - q * q * l, 0, dw - q * u - dq * l], rtol=1e-14)
    # steady turn: lateral acceleration r u although dv/dt = 0
    np.testing.assert_allclose(absolute_acceleration([20, 0, 0], [0, 0, 0.3], [0, 0, 0]), [0, 6.0, 0], atol=1e-15)


def test_five_term_formula_against_the_inertial_trajectory():
    """a_P in body axes equals R^T d2/dt2 [X_O(t) + R(t) r(t)], differentiated numerically."""

    def origin(t):
        return np.array([10 * t + t * t, np.sin(t), 0.1 * t**3])

    def angles(t):
        return np.array([0.1 * np.sin(t), 0.2 * np.cos(2 * t), 0.3 * t])

    def rel(t):
        return np.array([1 + 0.1 * t, -0.5 + 0.2 * t * t, 0.3 * np.sin(t)])

    def point(t):
        return origin(t) + rotation_body_to_earth(*angles(t)) @ rel(t)

    def d(f, t, h=1e-4):
        return (f(t + h) - f(t - h)) / (2 * h)

    def d2(f, t, h=1e-4):
        return (f(t + h) - 2 * f(t) + f(t - h)) / (h * h)

    t0 = 0.7
    R = rotation_body_to_earth(*angles(t0))

    def omega(t):
        return np.array(body_rates(*angles(t)[:2], *d(angles, t)))

    def body_velocity(t):
        return rotation_body_to_earth(*angles(t)).T @ d(origin, t)

    v_o = body_velocity(t0)
    a_o = R.T @ d2(origin, t0)
    np.testing.assert_allclose(absolute_acceleration(v_o, omega(t0), d(body_velocity, t0)), a_o, rtol=1e-6,
                               atol=1e-6)
    r, r_dot, r_ddot = rel(t0), d(rel, t0), d2(rel, t0)
    expected_v = R.T @ d(point, t0)
    expected_a = R.T @ d2(point, t0)
    np.testing.assert_allclose(moving_point_velocity(v_o, omega(t0), r, r_dot), expected_v, rtol=1e-7, atol=1e-7)
    np.testing.assert_allclose(moving_point_acceleration(a_o, omega(t0), d(omega, t0), r, r_dot, r_ddot), expected_a,
                               rtol=1e-6, atol=1e-6)


def test_point_functions_broadcast_a_batch():
    rng = np.random.default_rng(5)
    omega = rng.normal(size=(3, 6))
    r = np.array([1.2, -0.7, 0.3])
    batch = point_acceleration(np.zeros(3), omega, np.zeros(3), r)
    assert batch.shape == (3, 6)
    for k in range(6):
        np.testing.assert_allclose(batch[:, k], point_acceleration([0, 0, 0], omega[:, k], [0, 0, 0], r), rtol=1e-14)
    # centripetal: omega x (omega x r) = -|omega|^2 r for omega perpendicular to r
    np.testing.assert_allclose(point_acceleration([0, 0, 0], [0, 0, 2.0], [0, 0, 0], [1.5, 0, 0]), [-6.0, 0, 0])


@pytest.mark.parametrize("call, key", [
    (lambda: point_velocity([1, 2], [0, 0, 0], [0, 0, 0]), "v_o"),
    (lambda: point_acceleration([0, 0, 0], [0, 0, 0], [0, 0, 0], np.zeros((3, 2, 2))), "r"),
    (lambda: body_to_earth([1.0], 0, 0, 0), "vector"),
    (lambda: euler_angles_from_rotation(np.eye(2)), "rotation"),
])
def test_kinematics_error_paths(call, key):
    with pytest.raises(ParameterError) as info:
        call()
    assert info.value.key == key
