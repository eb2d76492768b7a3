"""The components' one source on both backends: the tire step compiled (numba, the compiled ``xp``) against numpy,
and the planar kinematics and wheel torques against closed forms."""

import numpy as np
import pytest

import vehdyn
from vehdyn.components import planar, tire_forces, wheel
from vehdyn.components.xp import NUMPY
from vehdyn.mechanics import rotation_body_to_earth
from vehdyn.tire import LinearTire, tire_for_vehicle

SEDAN = vehdyn.load_vehicle("sedan")
MF = tire_for_vehicle(SEDAN, "front")
LINEAR = LinearTire(cornering_stiffness=60e3, slip_stiffness=80e3, camber_stiffness=2e3, nominal_load=3000.0)
RNG = np.random.default_rng(11)
N = 1000
FZ, KAPPA, ALPHA = RNG.uniform(500.0, 8000.0, N), RNG.uniform(-0.5, 0.5, N), RNG.uniform(-0.5, 0.5, N)
GAMMA, VX, MU = RNG.uniform(-0.05, 0.05, N), RNG.uniform(-30.0, 30.0, N), RNG.uniform(0.2, 1.2, N)
# the compiled Magic Formula runs the branchless math functions of vehdyn.tire._fast_math (each within a few ulps of
# libm's) where numpy runs the half-angle sin and cos of the tire kernels: the step's forces agree to ~30 ulps of
# the force scale (measured: 6.8e-15 relative to max(|F|, 1e-3 F_z) over these points); the budget is 1e-13
BUDGET = 1e-13


def _compiled_steps():
    numba = pytest.importorskip("numba")
    from vehdyn.components.compiled import XP

    @numba.njit
    def steps(law, fz, kappa, alpha, gamma, vx, mu, mirror, scaled, out):
        for i in range(fz.size):
            out[0, i], out[1, i], out[2, i] = tire_forces.tire_loads(XP, law, fz[i], kappa[i], alpha[i], gamma[i],
                                                                     vx[i], mirror, mu[i], scaled)
            out[3, i], out[4, i], out[5, i] = tire_forces.axle_tire_loads(XP, law, fz[i], kappa[i], alpha[i], vx[i],
                                                                          mirror, mu[i], scaled)
            w = tire_forces.wheel_pair_tire_loads(XP, law, fz[i], 0.5 * fz[i], kappa[i], alpha[i], gamma[i], vx[i],
                                                  mirror, not mirror, mu[i], scaled)
            for j in range(6):
                out[6 + j, i] = w[j]
            out[12, i] = tire_forces.tire_aligning_moment(XP, law, fz[i], kappa[i], alpha[i], gamma[i], vx[i], mirror,
                                                          mu[i], scaled)

    return steps


@pytest.mark.compiled_vs_numpy
@pytest.mark.parametrize("tire", [MF, LINEAR], ids=["magic_formula", "linear"])
@pytest.mark.parametrize("mirror", [False, True])
@pytest.mark.parametrize("scaled", [False, True])
def test_the_compiled_tire_step_is_the_numpy_one(tire, mirror, scaled):
    from vehdyn.tire.compiled import tire_law

    out = np.empty((13, N))
    _compiled_steps()(tire_law(tire), FZ, KAPPA, ALPHA, GAMMA, VX, MU, mirror, scaled, out)
    expected = (tire_forces.tire_loads(NUMPY, tire, FZ, KAPPA, ALPHA, GAMMA, VX, mirror, MU, scaled)
                + tire_forces.axle_tire_loads(NUMPY, tire, FZ, KAPPA, ALPHA, VX, mirror, MU, scaled)
                + tire_forces.wheel_pair_tire_loads(NUMPY, tire, FZ, 0.5 * FZ, KAPPA, ALPHA, GAMMA, VX, mirror,
                                                    not mirror, MU, scaled)
                + (tire_forces.tire_aligning_moment(NUMPY, tire, FZ, KAPPA, ALPHA, GAMMA, VX, mirror, MU, scaled),))
    expected = np.array(expected)
    scale = np.maximum(np.abs(expected), 1e-3 * FZ)
    assert np.max(np.abs(out - expected) / scale) < BUDGET


def test_the_lean_lateral_law_is_the_full_one_at_zero_slip_ratio():
    """A force-mode single track takes F_y alone (TireLaw.lateral_only): the same F_y at kappa = gamma = 0."""
    numba = pytest.importorskip("numba")
    from vehdyn.components.compiled import XP
    from vehdyn.tire.compiled import tire_law

    @numba.njit
    def lateral(lean, full, fz, alpha, vx, out):
        for i in range(fz.size):
            out[0, i] = XP.tire_law(lean, fz[i], 0.0, alpha[i], 0.0, vx[i])[1]
            out[1, i] = XP.tire_law(full, fz[i], 0.0, alpha[i], 0.0, vx[i])[1]

    out = np.empty((2, N))
    lateral(tire_law(MF, lateral_only=True), tire_law(MF), FZ, ALPHA, VX, out)
    assert np.allclose(out[0], out[1], rtol=1e-12, atol=1e-9)


def test_a_law_without_a_compiled_form_is_named():
    pytest.importorskip("numba")
    from vehdyn.tire import FialaTire
    from vehdyn.tire.compiled import tire_law

    with pytest.raises(vehdyn.ParameterError, match="FialaTire") as info:
        tire_law(FialaTire.from_vehicle(SEDAN, "front"), "rear_tire")
    assert info.value.key == "rear_tire"


def test_the_planar_position_rates_are_the_body_velocity_turned_by_the_heading():
    u, v, yaw = RNG.uniform(-30, 30, N), RNG.uniform(-5, 5, N), RNG.uniform(-7, 7, N)
    dx, dy = planar.position_rates(NUMPY, u, v, yaw)
    R = rotation_body_to_earth(0.0 * yaw, 0.0 * yaw, yaw)
    assert np.allclose(dx, R[0, 0] * u + R[0, 1] * v, rtol=1e-14, atol=1e-12)
    assert np.allclose(dy, R[1, 0] * u + R[1, 1] * v, rtol=1e-14, atol=1e-12)
    X, Y = planar.body_point(NUMPY, 1.0, 2.0, yaw, 1.5, -0.8)
    assert np.allclose(X, 1.0 + R[0, 0] * 1.5 - R[0, 1] * 0.8) and np.allclose(Y, 2.0 + R[1, 0] * 1.5 - R[1, 1] * 0.8)


def test_the_brake_torque_opposes_the_spin_and_vanishes_at_standstill():
    class K:
        brake_regularization_speed, rolling_radius = 1.0, 0.3

    omega = np.array([-100.0, -1.0, 0.0, 1.0, 100.0])
    torque = wheel.net_wheel_torque(NUMPY, K, omega, 0.0, 1000.0, 0.0)
    assert torque[2] == 0.0 and np.all(np.sign(torque) == -np.sign(omega))
    assert torque[4] == pytest.approx(-1000.0 * 100.0 / np.sqrt(1.0 + 100.0**2), rel=1e-15)
    assert wheel.net_wheel_torque(NUMPY, K, 50.0, 200.0, 0.0, 1000.0) == pytest.approx(200.0 - 0.3 * 1000.0)
    # tanh(20) rounds to 1; a SIMD kernel within numpy's 1-2 ulp spec may return its neighbour
    assert wheel.rolling_resistance_fade(NUMPY, K, 0.0) == 0.0
    assert wheel.rolling_resistance_fade(NUMPY, K, 20.0) == pytest.approx(1.0, rel=0.0, abs=4 * np.finfo(float).eps)
