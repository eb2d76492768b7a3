"""Slip from wheel motion: the ISO-W definitions, the low-speed regularization, reverse, conventions."""

import math

import numpy as np
import pytest

from vehdyn import ParameterError
from vehdyn.conventions import (tire_forces_iso_w_to_sae, tire_forces_sae_to_iso_w, tire_slips_iso_w_to_sae,
                                tire_slips_sae_to_iso_w)
from vehdyn.tire import BrushTire, regularized_speed, theoretical_slip, wheel_slip

R = 0.31


@pytest.mark.compiled_vs_numpy
def test_definitions_above_the_regularization_speed():
    # kappa = (omega R - V_x) / V_x, tan(alpha) = V_y / |V_x| (ISO-W; Pacejka 2012 sec. 1.2)
    vx, vy, omega = 25.0, -1.5, 25.0 * 0.97 / R
    s = wheel_slip(vx, vy, omega, R)
    assert float(s.kappa) == pytest.approx(-0.03, rel=1e-12)
    # numpy's arctan against the C library's (math): one call each, ONE_CALL_ULPS apart at most on any CPU
    from tests._tolerances import ONE_CALL_ULPS, assert_close_ulps
    assert_close_ulps(float(s.alpha), math.atan(-1.5 / 25.0), ulps=ONE_CALL_ULPS, what="slip angle vs math.atan")
    assert float(s.slip_velocity_x) == pytest.approx(25.0 * 0.03, rel=1e-12)
    assert float(s.rolling_speed) == pytest.approx(25.0 * 0.97, rel=1e-15)


def test_reverse_keeps_the_signs_of_the_mirrored_motion():
    # the same wheel behaviour backwards: omega R = (1 + kappa) V_x in both directions
    forward = wheel_slip(10.0, 0.5, 10.0 * 1.04 / R, R)
    reverse = wheel_slip(-10.0, 0.5, -10.0 * 1.04 / R, R)
    assert float(reverse.kappa) == pytest.approx(float(forward.kappa), rel=1e-12)
    assert float(reverse.alpha) == pytest.approx(float(forward.alpha), rel=1e-15)
    # the tire then pushes backwards when the wheel spins faster than it travels backwards
    tire = BrushTire(contact_half_length=0.08, tread_stiffness=5e6, mu=1.0)
    push = tire.forces(4000.0, reverse.kappa, 0.0, vx=-10.0).fx
    assert push < 0


def test_regularized_speed_is_exact_continuous_and_smooth():
    v0 = 0.5
    assert regularized_speed(3.0, v0) == 3.0
    assert regularized_speed(-0.7, v0) == 0.7
    assert regularized_speed(0.0, v0) == pytest.approx(v0 / 2, rel=1e-15)
    h = 1e-7
    for side in (v0, -v0):
        assert regularized_speed(side - h, v0) == pytest.approx(regularized_speed(side + h, v0), abs=3 * h)
        slope_in = (regularized_speed(side, v0) - regularized_speed(side - np.sign(side) * h, v0)) / h
        assert slope_in == pytest.approx(1.0, abs=1e-6)  # C1: derivative of |V_x| outside is 1
    v = np.linspace(-2, 2, 4001)
    assert np.all(regularized_speed(v, v0) >= v0 / 2)


def test_no_division_by_zero_at_standstill():
    s = wheel_slip(np.array([0.0, 0.0, -0.0]), np.array([0.3, 0.0, -0.2]), np.array([0.0, 2.0, -1.0]), R,
                   regularization_speed=0.4)
    for value in s:
        assert np.all(np.isfinite(value))
    # bounded by 2 |V_s| / v0
    assert np.all(np.abs(s.kappa) <= 2 * np.abs(s.slip_velocity_x) / 0.4 + 1e-12)
    assert float(s.kappa[1]) == pytest.approx(2.0 * R / 0.2, rel=1e-12)


def test_force_producing_slip_is_continuous_through_zero_speed():
    omega = 1.0
    v = np.array([-1e-9, 1e-9])
    s = wheel_slip(v, 0.0, omega, R)
    np.testing.assert_allclose(s.kappa * np.sign(v), s.kappa[1], rtol=1e-6)


@pytest.mark.compiled_vs_numpy
def test_theoretical_slip():
    sx, sy = theoretical_slip(np.array([0.1, -0.5, -1.0]), np.array([0.05, 0.0, 0.1]))
    np.testing.assert_allclose(sx[:2], [0.1 / 1.1, -1.0], rtol=1e-15)
    # numpy's tan against the C library's (math): one call, then the same division (one more rounding)
    from tests._tolerances import ONE_CALL_ULPS, assert_close_ulps
    assert_close_ulps(sy[:2], [math.tan(0.05) / 1.1, 0.0], ulps=ONE_CALL_ULPS + 1, what="theoretical slip vs math.tan")
    assert sx[2] == -np.inf and sy[2] == np.inf


@pytest.mark.parametrize("kwargs", [dict(effective_radius=0.0), dict(effective_radius=-0.3),
                                    dict(regularization_speed=0.0), dict(regularization_speed=math.nan)])
def test_bad_arguments_raise(kwargs):
    args = dict(effective_radius=R)
    args.update(kwargs)
    radius = args.pop("effective_radius")
    with pytest.raises(ParameterError) as info:
        wheel_slip(10.0, 0.0, 30.0, radius, **args)
    assert info.value.key in ("effective_radius", "regularization_speed")


def test_sae_iso_w_conversions_round_trip_and_agree_with_the_physics():
    kappa, alpha_sae, gamma, phit = 0.03, 0.05, 0.02, 0.01
    iso = tire_slips_sae_to_iso_w(kappa, alpha_sae, gamma, phit)
    assert (float(iso.kappa), float(iso.alpha), float(iso.gamma), float(iso.phit)) == (kappa, -alpha_sae, gamma, -phit)
    back = tire_slips_iso_w_to_sae(*iso)
    assert (float(back.alpha), float(back.phit)) == (alpha_sae, phit)
    loads = (100.0, -200.0, 3000.0, 5.0, -6.0, 7.0)
    assert tuple(map(float, tire_forces_sae_to_iso_w(*tire_forces_iso_w_to_sae(*loads)))) == loads
    # a tire sliding to its right (SAE alpha = atan(v/u) > 0, v to the right) must be pushed left:
    # SAE F_y < 0, and the aligning moment turns it towards its velocity (SAE M_z > 0 about z down)
    tire = BrushTire(contact_half_length=0.08, tread_stiffness=5e6, mu=1.0)
    iso = tire_slips_sae_to_iso_w(0.0, math.atan(1.0 / 20.0))
    out = tire.forces(4000.0, iso.kappa, iso.alpha)
    sae = tire_forces_iso_w_to_sae(*out)
    assert float(sae.fy) < 0 and float(sae.fz) == -4000.0
    assert float(sae.mz) > 0
