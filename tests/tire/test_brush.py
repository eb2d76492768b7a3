"""Brush tire against Pacejka's closed forms and an independent quadrature of the tread elements."""

import math

import numpy as np
import pytest

from vehdyn import ParameterError
from vehdyn.tire import BrushTire

A, CP, MU = 0.08, 5.0e6, 1.0
FZ = 4000.0


@pytest.fixture
def tire():
    return BrushTire(contact_half_length=A, tread_stiffness=CP, mu=MU)


def quadrature(a, cp, mu0, mus, fz, kappa, alpha, n=200001):
    """Force magnitude and moment int x q dx of the parabolic-pressure brush, integrated numerically.

    Independent of the closed forms: a bristle entering at x = a adheres while c_p sigma (a - x)
    <= mu0 q(x) and slides with mus q(x) from the first point where it does not (Pacejka 2012,
    sec. 3.2.3). Returns (F, M, sigma).
    """
    sigma = math.hypot(kappa, math.tan(alpha)) / (1.0 + kappa)
    x = np.linspace(a, -a, n)
    q = 3.0 * fz / (4.0 * a) * (1.0 - (x / a) ** 2)
    elastic = cp * sigma * (a - x)
    exceeded = elastic > mu0 * q
    exceeded[0] = False  # leading edge: both vanish
    first = np.argmax(exceeded[1:]) + 1 if exceeded[1:].any() else n
    density = np.where(np.arange(n) < first, elastic, mus * q)
    force = -np.trapezoid(density, x)
    moment = -np.trapezoid(x * density, x)
    return force, moment, sigma


def test_cornering_and_slip_stiffness_are_2_cp_a2(tire):
    # Pacejka 2012 sec. 3.2.1: C_Falpha = 2 c_p a^2; isotropic brush: C_Fkappa the same
    h = 1e-7
    c_alpha = -(tire.forces(FZ, 0.0, h).fy - tire.forces(FZ, 0.0, -h).fy) / (2 * h)
    c_kappa = (tire.forces(FZ, h, 0.0).fx - tire.forces(FZ, -h, 0.0).fx) / (2 * h)
    assert c_alpha == pytest.approx(2 * CP * A**2, rel=1e-6)
    assert c_kappa == pytest.approx(2 * CP * A**2, rel=1e-6)
    assert tire.cornering_stiffness == 2 * CP * A**2


def test_pure_side_slip_matches_fiala_polynomial(tire):
    # closed form (Pacejka 2012 sec. 3.2.1), written as the polynomial in tan(alpha)
    c = 2 * CP * A**2
    alpha = np.linspace(-0.2, 0.2, 81)
    t = np.tan(alpha)
    sl = 3 * MU * FZ / c
    poly = -(c * t - c**2 * np.abs(t) * t / (3 * MU * FZ) + c**3 * t**3 / (27 * MU**2 * FZ**2))
    expected = np.where(np.abs(t) < sl, poly, -MU * FZ * np.sign(t))
    lam = np.minimum(c * np.abs(t) / (3 * MU * FZ), 1.0)
    expected_mz = MU * FZ * A * lam * (1 - lam) ** 3 * np.sign(t)
    out = tire.forces(FZ, 0.0, alpha)
    np.testing.assert_allclose(out.fy, expected, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(out.mz, expected_mz, rtol=1e-10, atol=1e-10)
    np.testing.assert_array_equal(out.fx, 0.0)


def test_full_sliding_point(tire):
    # full sliding from tan(alpha_sl) = 3 mu F_z / (2 c_p a^2): |F_y| = mu F_z, M_z = 0
    sl = 3 * MU * FZ / (2 * CP * A**2)
    assert tire.full_sliding_slip(FZ) == pytest.approx(sl, rel=1e-15)
    beyond = tire.forces(FZ, 0.0, np.arctan(sl * np.array([1.0, 1.5, 3.0])))
    np.testing.assert_allclose(beyond.fy, -MU * FZ, rtol=1e-12)
    np.testing.assert_allclose(beyond.mz, 0.0, atol=1e-9)
    below = tire.forces(FZ, 0.0, np.arctan(sl * 0.999))
    assert -MU * FZ < below.fy < -0.999 * MU * FZ


def test_trail_is_a_third_at_zero_slip_and_falls_to_zero(tire):
    sl = tire.full_sliding_slip(FZ)
    alphas = np.arctan(np.array([0.0, 1e-6, 0.3, 0.6, 0.9, 1.0, 1.2]) * sl)
    trail = tire.pneumatic_trail(FZ, 0.0, alphas)
    assert trail[0] == pytest.approx(A / 3, rel=1e-15)
    assert trail[1] == pytest.approx(A / 3, rel=1e-5)
    assert np.all(np.diff(trail[:6]) < 0)
    assert trail[5] == pytest.approx(0.0, abs=1e-12)
    assert trail[6] == pytest.approx(0.0, abs=1e-12)
    # t = -M_z / F_y, and closed form a/3 (1 - lam)^3 / (1 - lam + lam^2/3) (sec. 3.2.1)
    lam = 0.6
    out = tire.forces(FZ, 0.0, np.arctan(lam * sl))
    assert -out.mz / out.fy == pytest.approx(trail[3], rel=1e-12)
    assert trail[3] == pytest.approx(A / 3 * (1 - lam) ** 3 / (1 - lam + lam**2 / 3), rel=1e-12)


@pytest.mark.parametrize("mu_sliding", [None, 0.7])
@pytest.mark.parametrize("kappa, alpha", [(0.0, 0.02), (0.0, 0.08), (0.03, 0.0), (-0.05, 0.0), (0.04, 0.03),
                                          (-0.1, 0.05), (0.2, -0.1), (-0.02, -0.15), (0.5, 0.3)])
def test_combined_slip_against_quadrature(kappa, alpha, mu_sliding):
    tire = BrushTire(contact_half_length=A, tread_stiffness=CP, mu=MU, mu_sliding=mu_sliding)
    mus = MU if mu_sliding is None else mu_sliding
    force, moment, _ = quadrature(A, CP, MU, mus, FZ, kappa, alpha)
    out = tire.forces(FZ, kappa, alpha)
    assert math.hypot(out.fx, out.fy) == pytest.approx(force, rel=2e-4)
    slip = math.hypot(kappa, math.tan(alpha))
    # direction: opposite the slip velocity (V_sx, V_sy) = |V_x| (-kappa, tan alpha), ISO-W
    assert out.fx == pytest.approx(force * kappa / slip, rel=2e-4, abs=1e-6)
    assert out.fy == pytest.approx(-force * math.tan(alpha) / slip, rel=2e-4, abs=1e-6)
    # M_z = -(int x q dx) sigma_y / sigma
    assert out.mz == pytest.approx(-moment * math.tan(alpha) / slip, rel=2e-3, abs=2e-3)


def test_sliding_friction_limits_the_force_at_full_sliding():
    tire = BrushTire(contact_half_length=A, tread_stiffness=CP, mu=1.0, mu_sliding=0.7)
    alpha = np.arctan(np.linspace(0.0, 2.0, 2001) * tire.full_sliding_slip(FZ))
    fy = tire.forces(FZ, 0.0, alpha).fy
    assert np.min(fy) < -0.7 * FZ * 1.05  # a peak above the sliding level
    assert fy[-1] == pytest.approx(-0.7 * FZ, rel=1e-12)
    assert np.all(np.abs(fy) <= FZ * (1 + 1e-12))


def test_locked_wheel_slides_fully_against_the_slip_velocity(tire):
    out = tire.forces(FZ, -1.0, 0.1)
    slip = math.hypot(1.0, math.tan(0.1))
    assert out.fx == pytest.approx(-MU * FZ / slip, rel=1e-12)
    assert out.fy == pytest.approx(-MU * FZ * math.tan(0.1) / slip, rel=1e-12)
    assert out.mz == pytest.approx(0.0, abs=1e-9)


def test_reverse_flips_fx_and_mz_not_fy(tire):
    forward = tire.forces(FZ, np.array([0.02, -0.03]), np.array([0.05, -0.02]), vx=10.0)
    reverse = tire.forces(FZ, np.array([0.02, -0.03]), np.array([0.05, -0.02]), vx=-10.0)
    np.testing.assert_allclose(reverse.fx, -forward.fx, rtol=1e-14)
    np.testing.assert_allclose(reverse.fy, forward.fy, rtol=1e-14)
    np.testing.assert_allclose(reverse.mz, -forward.mz, rtol=1e-14)


def test_lift_off_and_standstill_give_finite_zero_forces(tire):
    out = tire.forces(np.array([0.0, -100.0]), 0.1, 0.1, vx=0.0)
    for value in out:
        assert np.all(np.isfinite(value))
    np.testing.assert_array_equal(out.fx, 0.0)
    np.testing.assert_array_equal(out.fz, 0.0)


def test_from_cornering_stiffness_round_trip():
    tire = BrushTire.from_cornering_stiffness(70000.0, 0.1, 0.9)
    assert tire.cornering_stiffness == pytest.approx(70000.0, rel=1e-15)
    with pytest.raises(ParameterError, match="cornering_stiffness"):
        BrushTire.from_cornering_stiffness(-1.0, 0.1, 0.9)


@pytest.mark.parametrize("field, value", [("contact_half_length", 0.0), ("contact_half_length", -0.1),
                                          ("tread_stiffness", 0.0), ("tread_stiffness", float("nan")),
                                          ("mu", 0.0), ("mu", "1.0"), ("mu_sliding", 0.0),
                                          ("mu_sliding", 1.5)])
def test_bad_parameters_raise(field, value):
    kwargs = dict(contact_half_length=A, tread_stiffness=CP, mu=MU)
    kwargs[field] = value
    with pytest.raises(ParameterError) as info:
        BrushTire(**kwargs)
    assert field in str(info.value)
    assert info.value.key == field


def test_parameters_are_frozen(tire):
    with pytest.raises(AttributeError):
        tire.mu = 2.0
