"""Fiala tire against Fiala's closed form (Pacejka 2012, sec. 3.2.1) and the friction circle."""

import math

import numpy as np
import pytest

from vehdyn import ParameterError
from vehdyn.tire import BrushTire, FialaTire

C, MU, FZ, A = 60000.0, 0.9, 5000.0, 0.09


@pytest.fixture
def tire():
    return FialaTire(cornering_stiffness=C, mu=MU, contact_half_length=A)


def fiala_side_force(alpha, c=C, mu=MU, fz=FZ):
    """Fiala (1954): F_y = mu F_z (1 - H^3) sign(alpha), H = 1 - C |tan alpha| / (3 mu F_z), ISO-W sign."""
    h = 1.0 - c * abs(math.tan(alpha)) / (3 * mu * fz)
    if h <= 0:
        return -mu * fz * math.copysign(1.0, alpha)
    return -mu * fz * (1 - h**3) * math.copysign(1.0, alpha)


def test_pure_side_force_is_fiala_closed_form(tire):
    alphas = np.linspace(-0.3, 0.3, 121)
    fy = tire.forces(FZ, 0.0, alphas).fy
    np.testing.assert_allclose(fy, [fiala_side_force(a) if a != 0 else 0.0 for a in alphas], rtol=1e-12, atol=1e-9)


def test_sliding_angle_and_saturation(tire):
    alpha_sl = math.atan(3 * MU * FZ / C)
    assert tire.sliding_slip_angle(FZ) == pytest.approx(alpha_sl, rel=1e-15)
    assert tire.forces(FZ, 0.0, alpha_sl * 1.01).fy == pytest.approx(-MU * FZ, rel=1e-12)
    assert tire.forces(FZ, 0.0, alpha_sl * 0.99).fy > -MU * FZ


def test_cornering_stiffness_and_trail_at_zero_slip(tire):
    h = 1e-7
    out_p, out_m = tire.forces(FZ, 0.0, h), tire.forces(FZ, 0.0, -h)
    assert -(out_p.fy - out_m.fy) / (2 * h) == pytest.approx(C, rel=1e-6)
    assert -(out_p.mz - out_m.mz) / (out_p.fy - out_m.fy) == pytest.approx(A / 3, rel=1e-6)


def test_equals_brush_in_pure_side_slip():
    # Fiala's model is the parabolic-pressure brush with C = 2 c_p a^2 (Pacejka 2012, sec. 3.2.1)
    brush = BrushTire(contact_half_length=A, tread_stiffness=C / (2 * A**2), mu=MU)
    fiala = FialaTire(cornering_stiffness=C, mu=MU, contact_half_length=A)
    alphas = np.linspace(-0.4, 0.4, 81)
    b, f = brush.forces(FZ, 0.0, alphas), fiala.forces(FZ, 0.0, alphas)
    np.testing.assert_allclose(f.fy, b.fy, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(f.mz, b.mz, rtol=1e-10, atol=1e-9)


def test_longitudinal_force_is_the_same_law_in_slip_ratio():
    tire = FialaTire(cornering_stiffness=C, mu=MU, slip_stiffness=90000.0)
    kappas = np.linspace(-0.5, 0.5, 101)
    lam = np.minimum(90000.0 * np.abs(kappas) / (3 * MU * FZ), 1.0)
    expected = MU * FZ * (1 - (1 - lam) ** 3) * np.sign(kappas)
    np.testing.assert_allclose(tire.forces(FZ, kappas, 0.0).fx, expected, rtol=1e-12, atol=1e-9)


def test_combined_slip_uses_the_friction_left_by_fx(tire):
    kappa, alpha = 0.02, 0.05
    out = tire.forces(FZ, kappa, alpha)
    pure_fx = tire.forces(FZ, kappa, 0.0).fx
    assert out.fx == pytest.approx(pure_fx, rel=1e-14)  # longitudinal priority
    left = math.sqrt((MU * FZ) ** 2 - out.fx**2)
    assert out.fy == pytest.approx(fiala_side_force(alpha, fz=left / MU), rel=1e-12)
    assert math.hypot(out.fx, out.fy) <= MU * FZ


def test_no_moment_without_contact_length():
    tire = FialaTire(cornering_stiffness=C, mu=MU)
    np.testing.assert_array_equal(tire.forces(FZ, 0.0, np.array([0.01, 0.1])).mz, 0.0)
    assert tire.forces(FZ, 0.0, 0.01).mz == 0.0


def test_reverse_flips_fx_and_mz_not_fy(tire):
    f, r = tire.forces(FZ, 0.03, 0.04, vx=5.0), tire.forces(FZ, 0.03, 0.04, vx=-5.0)
    assert (r.fx, r.fy, r.mz) == pytest.approx((-f.fx, f.fy, -f.mz), rel=1e-15)


@pytest.mark.parametrize("field, value", [("cornering_stiffness", 0.0), ("cornering_stiffness", math.inf),
                                          ("mu", -0.5), ("slip_stiffness", 0.0), ("contact_half_length", -0.1),
                                          ("mu", True)])
def test_bad_parameters_raise(field, value):
    kwargs = dict(cornering_stiffness=C, mu=MU)
    kwargs[field] = value
    with pytest.raises(ParameterError) as info:
        FialaTire(**kwargs)
    assert info.value.key == field
