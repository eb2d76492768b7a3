"""Dugoff tire against the equations of Dugoff, Fancher & Segel (1970) as printed (Rajamani 2012, ch. 13)."""

import math

import numpy as np
import pytest

from vehdyn import ParameterError
from vehdyn.tire import DugoffTire

CA, CK, MU, FZ = 70000.0, 100000.0, 0.95, 4500.0


def dugoff_textbook(kappa, alpha, fz=FZ, mu=MU):
    """The original form: F = C s/(1 + kappa) f(lambda), lambda = mu F_z (1 + kappa) / (2 sqrt(...))."""
    t = math.tan(alpha)
    root = math.hypot(CK * kappa, CA * t)
    lam = mu * fz * (1 + kappa) / (2 * root)
    f = lam * (2 - lam) if lam < 1 else 1.0
    return CK * kappa / (1 + kappa) * f, -CA * t / (1 + kappa) * f


@pytest.fixture
def tire():
    return DugoffTire(cornering_stiffness=CA, slip_stiffness=CK, mu=MU)


@pytest.mark.parametrize("kappa, alpha", [(0.01, 0.0), (0.0, 0.01), (0.02, 0.03), (-0.05, 0.08), (0.3, -0.2),
                                          (-0.5, 0.4), (0.001, -0.002), (-0.9, 0.05)])
def test_matches_the_textbook_equations(tire, kappa, alpha):
    fx, fy = dugoff_textbook(kappa, alpha)
    out = tire.forces(FZ, kappa, alpha)
    assert out.fx == pytest.approx(fx, rel=1e-12, abs=1e-9)
    assert out.fy == pytest.approx(fy, rel=1e-12, abs=1e-9)
    arr = tire.forces(np.array([FZ]), np.array([kappa]), np.array([alpha]))
    assert arr.fx[0] == pytest.approx(fx, rel=1e-12, abs=1e-9)


def test_small_slip_is_linear(tire):
    out = tire.forces(FZ, 1e-6, 1e-6)
    assert out.fx == pytest.approx(CK * 1e-6 / (1 + 1e-6), rel=1e-12)
    assert out.fy == pytest.approx(-CA * math.tan(1e-6) / (1 + 1e-6), rel=1e-12)


def test_large_slip_tends_to_mu_fz(tire):
    out = tire.forces(FZ, 0.0, 1.5)
    assert -out.fy < MU * FZ
    assert -out.fy == pytest.approx(MU * FZ, rel=0.05)


def test_locked_wheel_slides_at_mu_fz(tire):
    out = tire.forces(FZ, -1.0, 0.0)
    assert out.fx == pytest.approx(-MU * FZ, rel=1e-14)
    assert np.isfinite(out.fy)


def test_speed_reduces_friction():
    tire = DugoffTire(cornering_stiffness=CA, slip_stiffness=CK, mu=MU, speed_friction_reduction=0.01)
    kappa, alpha, vx = 0.0, 0.3, 20.0
    sliding_speed = vx * math.hypot(kappa, math.tan(alpha))
    fx, fy = dugoff_textbook(kappa, alpha, mu=MU * (1 - 0.01 * sliding_speed))
    assert tire.forces(FZ, kappa, alpha, vx=vx).fy == pytest.approx(fy, rel=1e-12)


def test_trail_moment_and_reverse():
    tire = DugoffTire(cornering_stiffness=CA, slip_stiffness=CK, mu=MU, pneumatic_trail=0.04)
    f, r = tire.forces(FZ, 0.02, 0.03, vx=5.0), tire.forces(FZ, 0.02, 0.03, vx=-5.0)
    assert f.mz == pytest.approx(-0.04 * f.fy, rel=1e-15)
    assert (r.fx, r.fy, r.mz) == pytest.approx((-f.fx, f.fy, -f.mz), rel=1e-15)


@pytest.mark.parametrize("field, value", [("cornering_stiffness", 0.0), ("slip_stiffness", -2.0), ("mu", 0.0),
                                          ("speed_friction_reduction", -0.1), ("pneumatic_trail", math.nan)])
def test_bad_parameters_raise(field, value):
    kwargs = dict(cornering_stiffness=CA, slip_stiffness=CK, mu=MU)
    kwargs[field] = value
    with pytest.raises(ParameterError) as info:
        DugoffTire(**kwargs)
    assert info.value.key == field
