"""Wong-Reece rigid wheel: against adaptive quadrature of the same stress integrals (scipy), Bekker's
closed forms where their assumptions hold, the Coulomb limit, equilibrium and bounds, bad input."""

import math

import numpy as np
import pytest

from vehdyn import ParameterError
from vehdyn.tire.terramechanics import (RigidWheel, compaction_resistance, load_soil, parabolic_wheel_sinkage,
                                        rigid_wheel_sinkage, shipped_soils)
from vehdyn.tire.terramechanics.reference import adaptive_integrals, stress_functions

RADIUS, WIDTH = 0.3, 0.2


def reference_integrals(wheel, theta1, slip):
    """W, H, R, T point by point with scipy.integrate.quad (vehdyn.tire.terramechanics.reference)."""
    return np.array(adaptive_integrals(wheel, theta1, slip))


@pytest.mark.parametrize("name", ["dry_sand", "clayey_soil", "heavy_clay", "snow"])
def test_vectorized_quadrature_matches_adaptive_quadrature(name):
    wheel = RigidWheel(radius=RADIUS, width=WIDTH, soil=load_soil(name), rebound=0.1)
    slips = np.array([-1.0, -0.4, 0.0, 0.2, 0.9])
    theta1 = 0.5
    got = np.array(wheel._integrals(np.full(slips.size, theta1), slips)[:4]).T
    ref = np.array([reference_integrals(wheel, theta1, s) for s in slips])
    scale = np.abs(ref).max(axis=1, keepdims=True)
    # Gauss-Legendre error grows as n falls (sigma ~ (theta_1 - theta)^n at the entry): 2e-4 at n = 0.11
    assert np.max(np.abs(got - ref) / scale) < (2e-4 if wheel.soil.n < 0.6 else 1e-5)


def test_solution_satisfies_vertical_equilibrium():
    wheel = RigidWheel(radius=RADIUS, width=WIDTH, soil=load_soil("sandy_loam"))
    loads = np.array([200.0, 1000.0, 3000.0])[:, None]
    slips = np.linspace(-1, 1, 9)[None, :]
    result = wheel.solve(loads, slips)
    assert result.sinkage.shape == (3, 9) and not result.stuck.any()
    for (i, j), s in np.ndenumerate(result.slip):
        w = reference_integrals(wheel, result.entry_angle[i, j], s)[0]
        assert w == pytest.approx(result.load[i, j], rel=2e-5)
    assert result.sinkage == pytest.approx(RADIUS * (1 - np.cos(result.entry_angle)), rel=1e-12)


@pytest.mark.parametrize("name", ["lunar_soil", "dry_sand", "snow", "sandy_loam", "clayey_soil"])
def test_reduces_to_closed_forms_at_small_sinkage_and_zero_slip(name):
    # Bekker's assumptions: maximum stress at the bottom (c1 = c2 = 0), no rebound, z0/D ~ 1 %
    soil = load_soil(name)
    wheel = RigidWheel(radius=RADIUS, width=WIDTH, soil=soil, c1=0.0, c2=0.0)
    load = float(wheel.supported_load(0.0015))  # z0 / D = 0.25 %
    result = wheel.solve(load, 0.0)
    exact = parabolic_wheel_sinkage(soil, load, 2 * RADIUS, WIDTH)
    assert result.sinkage == pytest.approx(exact, rel=0.01)
    closed = rigid_wheel_sinkage(soil, load, 2 * RADIUS, WIDTH)
    resistance = compaction_resistance(soil, load, 2 * RADIUS, WIDTH)
    if soil.n == 1.0:  # Bekker's (3 - n)/3 factor is exact at n = 1 only (bekker module docstring)
        assert result.sinkage == pytest.approx(closed, rel=0.01)
        assert result.motion_resistance == pytest.approx(resistance, rel=0.01)
    # at the same sinkage the compaction resistance integral is exact for any n
    k = soil.k_c / WIDTH + soil.k_phi
    assert result.motion_resistance == pytest.approx(WIDTH * k * result.sinkage ** (soil.n + 1) / (soil.n + 1),
                                                     rel=1e-3)


@pytest.mark.parametrize("name", ["dry_sand", "sandy_loam", "clayey_soil", "heavy_clay", "lete_sand", "lunar_soil"])
def test_drawbar_pull_rises_toward_the_coulomb_limit(name):
    soil = load_soil(name)
    wheel = RigidWheel(radius=RADIUS, width=WIDTH, soil=soil, c2=0.0)  # fixed maximum-stress position
    load = 1000.0
    result = wheel.solve(load, np.linspace(-1.0, 1.0, 41))
    assert np.all(np.diff(result.drawbar_pull) > 0)
    area = WIDTH * RADIUS * np.sin(result.entry_angle)  # b l, no rebound
    limit = soil.cohesion * area + load * math.tan(soil.friction_angle)
    assert np.all(result.thrust <= limit * (1 + 1e-9))
    # with a stiff shear law (K -> 0) the thrust at s = 1 is c A + tan(phi) (W - V_tau), V_tau =
    # r b int tau sin(theta) the share of the load the shear carries, which vanishes with the sinkage:
    # the thrust approaches the Coulomb limit c A + W tan(phi) from below
    stiff = RigidWheel(radius=RADIUS, width=WIDTH, soil=soil.replace(shear_modulus=1e-7), c2=0.0)
    ratios = []
    for z in (0.02, 0.005, 0.0015):
        w = float(stiff.supported_load(z, 1.0))
        top = stiff.solve(w, 1.0)
        t1 = float(top.entry_angle)
        _, tau, integral = stress_functions(stiff, t1, 1.0)
        v_tau = RADIUS * WIDTH * integral(lambda t: tau(t) * math.sin(t), epsrel=1e-7)
        area = WIDTH * RADIUS * math.sin(t1)
        tan_phi = math.tan(soil.friction_angle)
        assert float(top.thrust) == pytest.approx(soil.cohesion * area + tan_phi * (w - v_tau), rel=1e-4)
        ratios.append(float(top.thrust) / (soil.cohesion * area + tan_phi * w))
    assert ratios[0] < ratios[1] < ratios[2] < 1.0 and ratios[2] > 0.96


def test_efficiency_and_torque_bounds():
    wheel = RigidWheel(radius=RADIUS, width=WIDTH, soil=load_soil("lete_sand"))
    s = np.linspace(0.0, 1.0, 21)
    result = wheel.solve(1500.0, s)
    # H r <= T where tau >= 0 (cos theta <= 1), so eta = DP (1 - s) r / T <= 1 - s
    assert np.all(result.thrust * RADIUS <= result.torque * (1 + 1e-12))
    assert np.all(result.tractive_efficiency <= 1.0 - s + 1e-12)
    assert np.all(result.tractive_efficiency >= 0.0)
    locked = wheel.solve(1500.0, -1.0)
    assert locked.torque < 0 and locked.drawbar_pull < result.drawbar_pull[0]


def test_stuck_wheel_reports_status_not_nan():
    wheel = RigidWheel(radius=RADIUS, width=WIDTH, soil=load_soil("snow"))
    result = wheel.solve([500.0, 5000.0], 0.3)
    assert list(result.status) == ["ok", "stuck"]
    assert result.sinkage[1] == RADIUS
    assert result.entry_angle[1] == pytest.approx(math.pi / 2)
    for name in ("sinkage", "drawbar_pull", "torque", "motion_resistance", "tractive_efficiency"):
        assert np.all(np.isfinite(getattr(result, name)))
    # the soil carries less than the load even at z = r
    assert wheel.supported_load(RADIUS, 0.3) < 5000.0


def test_batch_equals_pointwise():
    wheel = RigidWheel(radius=RADIUS, width=WIDTH, soil=load_soil("dry_sand"))
    loads, slips = np.array([300.0, 1200.0]), np.array([-0.5, 0.1, 0.7])
    batch = wheel.solve(loads[:, None], slips[None, :], slip_angle=0.1)
    for i, w in enumerate(loads):
        for j, s in enumerate(slips):
            one = wheel.solve(w, s, slip_angle=0.1)
            assert float(one.drawbar_pull) == pytest.approx(batch.drawbar_pull[i, j], rel=1e-9, abs=1e-9)
            assert float(one.lateral_force) == pytest.approx(batch.lateral_force[i, j], rel=1e-9)


def test_side_force_is_odd_and_grows_with_slip_angle():
    wheel = RigidWheel(radius=RADIUS, width=WIDTH, soil=load_soil("sandy_loam"))
    alpha = np.array([-0.3, -0.1, 0.0, 0.1, 0.3])
    fy = wheel.solve(1000.0, 0.2, alpha).lateral_force
    assert fy == pytest.approx(-fy[::-1], rel=1e-12)
    assert fy[2] == 0.0 and fy[3] < 0 and fy[4] < fy[3]  # ISO-W: alpha > 0 pushes to -y


@pytest.mark.parametrize("kwargs, key", [(dict(load=1000.0, slip=1.2), "slip"),
                                         (dict(load=1000.0, slip=-1.01), "slip"),
                                         (dict(load=-1.0, slip=0.1), "load"),
                                         (dict(load=math.nan, slip=0.1), "load"),
                                         (dict(load=1000.0, slip=0.1, slip_angle=2.0), "slip_angle")])
def test_bad_input_names_field_and_value(kwargs, key):
    wheel = RigidWheel(radius=RADIUS, width=WIDTH, soil=load_soil("dry_sand"))
    with pytest.raises(ParameterError) as info:
        wheel.solve(**kwargs)
    assert info.value.key == key
    bad = kwargs[key]
    assert info.value.value == bad or (math.isnan(bad) and math.isnan(info.value.value))


def test_bad_wheel_parameters():
    with pytest.raises(ParameterError) as info:
        RigidWheel(radius=-0.3, width=WIDTH, soil=load_soil("dry_sand"))
    assert info.value.key == "radius"
    with pytest.raises(ParameterError) as info:
        RigidWheel(radius=0.3, width=WIDTH, soil="dry_sand")
    assert info.value.key == "soil"
    assert set(shipped_soils()) >= {"dry_sand"}


def test_side_force_against_adaptive_quadrature():
    # side shear r b int (c + sigma tan phi)(1 - exp(-j_y/K_y)) + |sin a| r int F_wall(h) cos(theta)
    soil = load_soil("sandy_loam")
    wheel = RigidWheel(radius=RADIUS, width=WIDTH, soil=soil)
    slip, alpha = 0.3, 0.2
    result = wheel.solve(1200.0, slip, alpha)
    t1 = float(result.entry_angle)
    sigma, _, integral = stress_functions(wheel, t1, slip)
    tan_phi, k_y = math.tan(soil.friction_angle), soil.side_shear_modulus
    travel = 1 - slip
    shear = RADIUS * WIDTH * integral(lambda t: (soil.cohesion + sigma(t) * tan_phi)
                                      * (1 - math.exp(-RADIUS * (t1 - t) * travel * math.tan(alpha) / k_y)))
    n_phi = math.tan(math.pi / 4 + soil.friction_angle / 2) ** 2
    gamma = soil.density * 9.81

    def wall(t):  # Rankine passive pressure integrated over the local depth h
        h = RADIUS * max(math.cos(t) - math.cos(t1), 0.0)
        return (0.5 * gamma * h * h * n_phi + 2 * soil.cohesion * h * math.sqrt(n_phi)) * math.cos(t)

    bulldozing = math.sin(alpha) * RADIUS * integral(wall)
    assert float(result.lateral_force) == pytest.approx(-(shear + bulldozing), rel=1e-4)
