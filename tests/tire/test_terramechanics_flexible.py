"""Flexible tire on soft soil (rigid/elastic mode) and the SoftSoilTire law, including a SingleTrack
run on sand."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

import vehdyn
from vehdyn import ParameterError
from vehdyn.tire import SoftSoilTire, TireForces
from vehdyn.tire.terramechanics import (FlexibleWheel, SoftSoilTireGeometry, bekker_pressure,
                                        critical_ground_pressure, load_soil, plate_sinkage, rigid_wheel_sinkage)

GEOMETRY = SoftSoilTireGeometry(radius=0.344, width=0.205, inflation_pressure=1.0e5)


def test_mode_criterion_and_critical_pressure():
    soil = load_soil("lete_sand")  # firm: a soft tire flattens
    wheel = FlexibleWheel(geometry=GEOMETRY, soil=soil)
    loads = np.array([200.0, 3000.0, 8000.0])
    p_gcr = critical_ground_pressure(soil, loads, 0.688, 0.205)
    # p_gcr is the plate pressure at Bekker's sinkage
    assert p_gcr == pytest.approx(bekker_pressure(soil, rigid_wheel_sinkage(soil, loads, 0.688, 0.205), 0.205))
    result = wheel.solve(loads, 0.1)
    assert list(result.mode) == list(np.where(1.0e5 < p_gcr, "elastic", "rigid"))
    assert "elastic" in result.mode and "rigid" in result.mode
    rigid = wheel.rigid_wheel.solve(loads, 0.1)
    is_rigid = result.mode == "rigid"
    assert result.drawbar_pull[is_rigid] == pytest.approx(rigid.drawbar_pull[is_rigid], rel=1e-12)


def test_elastic_mode_against_plate_and_janosi_hanamoto_integral():
    soil = load_soil("lete_sand")
    wheel = FlexibleWheel(geometry=GEOMETRY, soil=soil)
    load, slip = 8000.0, 0.15
    r = wheel.solve(load, slip)
    assert r.mode == "elastic"
    p = GEOMETRY.stiffness_pressure
    z = plate_sinkage(soil, p, GEOMETRY.width)
    assert r.sinkage == pytest.approx(z, rel=1e-12)
    # compaction resistance: b int_0^z p dz (the rut's work per unit length)
    work = GEOMETRY.width * quad(lambda d: bekker_pressure(soil, d, GEOMETRY.width), 0, z)[0]
    assert r.motion_resistance == pytest.approx(work, rel=1e-9)
    # thrust: Janosi-Hanamoto over the flat contact, j = s x, uniform pressure p
    length = load / (GEOMETRY.width * p)
    thrust = GEOMETRY.width * quad(lambda x: (soil.cohesion + p * math.tan(soil.friction_angle))
                                   * (1 - math.exp(-slip * x / soil.shear_modulus)), 0, length)[0]
    assert r.thrust == pytest.approx(thrust, rel=1e-9)
    assert r.drawbar_pull == pytest.approx(thrust - work, rel=1e-9)
    assert wheel.solve(load, 0.0).thrust == 0.0
    assert wheel.solve(load, -0.15).thrust == pytest.approx(-thrust, rel=1e-12)


def test_soft_soil_tire_interface():
    tire = SoftSoilTire(GEOMETRY, load_soil("dry_sand"))
    one = tire.forces(3000.0, 0.25, 0.05)
    assert isinstance(one, TireForces) and isinstance(one.fx, float)
    many = tire.forces(np.full((2, 3), 3000.0), np.array([0.0, 0.25, -0.5]), 0.05)
    assert many.fx.shape == (2, 3)
    assert many.fx[1, 1] == pytest.approx(one.fx, rel=1e-9) and many.fy[0, 1] == pytest.approx(one.fy, rel=1e-9)
    # ISO-W slip ratio 0.25 is the driven slip s = 0.25 / 1.25 = 0.2; -0.5 the skid s = -0.5
    wheel = FlexibleWheel(geometry=GEOMETRY, soil=load_soil("dry_sand"))
    assert one.fx == pytest.approx(float(wheel.solve(3000.0, 0.2, 0.05).drawbar_pull), rel=1e-9)
    assert many.fx[0, 2] == pytest.approx(float(wheel.solve(3000.0, -0.5, 0.05).drawbar_pull), rel=1e-9)
    # reverse: F_x flips with the rolling direction, F_y does not
    back = tire.forces(3000.0, 0.25, 0.05, 0.0, -5.0)
    assert back.fx == pytest.approx(-one.fx) and back.fy == pytest.approx(one.fy)
    state = tire.evaluate(3000.0, 0.25)
    assert state.sinkage > 0 and state.motion_resistance > 0 and state.status == "ok"
    # moment balance about the axle: soil torque = r F_x - M_y, and M_y <= 0 rolling forwards
    assert -state.torque == pytest.approx(-GEOMETRY.radius * one.fx + one.my, rel=1e-12)
    assert one.my <= 0 and back.my >= 0
    with pytest.raises(ParameterError) as info:
        SoftSoilTire(GEOMETRY, "dry_sand")
    assert info.value.key == "soil"
    with pytest.raises(ParameterError) as info:
        SoftSoilTireGeometry(radius=0.3, width=0.2, inflation_pressure=-1.0)
    assert info.value.key == "inflation_pressure"


def test_single_track_launches_on_sand_below_the_traction_limit():
    from vehdyn.handling import SingleTrack

    vehicle = vehdyn.load_vehicle("sedan")
    soil = load_soil("sandy_loam")
    # aired down to 0.8 bar: the elastic (flattened) mode at these loads
    geometry = SoftSoilTireGeometry(radius=vehicle.tires.rolling_radius, width=0.205, inflation_pressure=0.8e5)
    tire = SoftSoilTire(geometry, soil)
    model = SingleTrack(vehicle, tire, tire, wheel_spin=True, tire_lag=False)
    t = np.linspace(0.0, 0.5, 26)
    result = vehdyn.simulate(model, t, {"rear_drive_torque": 2500.0}, x0=model.straight_running(2.0), method="rk4",
                             substeps=8)
    ax = result["longitudinal_acceleration"]
    assert np.all(np.isfinite(ax))
    assert np.all(tire.evaluate(result["rear_normal_load"] / 2, 0.5, 0.0).mode == "elastic")
    # independent bound: the rear axle cannot push more than its Coulomb limit (A c + W tan(phi) per
    # tire, A = W / p the flat contact), at most the static rear load plus 20 % transfer; the
    # free-rolling front axle only resists (its wheel balances M_y - R_e F_x: a towed wheel, F_x <= 0)
    g = vehicle.geometry
    weight = vehicle.mass.mass * vehdyn.units.GRAVITY
    rear_load = 1.2 * weight * g.a / vehicle.wheelbase
    limit = rear_load / geometry.stiffness_pressure * soil.cohesion + rear_load * math.tan(soil.friction_angle)
    assert np.max(ax[5:]) < limit / vehicle.mass.mass
    assert np.max(ax[5:]) > 0.0  # it does accelerate on sandy loam, aired down
    assert np.all(result["front_longitudinal_force"][5:] < 0.0)


def test_single_track_coasts_down_on_soil_by_the_compaction_resistance():
    # Free-rolling tires in the elastic mode: the wheel balance 2 I_w d(omega)/dt = M_y - R_e F_x with
    # M_y = r F_x - T (SoftSoilTire) and r = R_e settles at T = 0, i.e. zero thrust (slip 0) and
    # F_x = -R_c = -b k z^(n+1) / (n+1), z = ((p_i + p_c) / k)^(1/n) the flat section's sinkage
    # (Wong 2008, sec. 2.7), the same at every load. With no drag or lift and omega = (1 + kappa) u / R_e
    # (the thrust that spins the wheels down needs a small slip kappa):
    #   du/dt = -4 R_c / (m + 4 I_w / R_e^2)    up to the relative term |kappa| (4 I_w / R_e^2) / m
    from vehdyn.handling import SingleTrack

    vehicle = vehdyn.load_vehicle("sedan")
    soil = load_soil("sandy_loam")
    geometry = SoftSoilTireGeometry(radius=vehicle.tires.rolling_radius, width=0.205, inflation_pressure=0.8e5)
    tire = SoftSoilTire(geometry, soil)
    model = SingleTrack(vehicle, tire, tire, wheel_spin=True, tire_lag=False).variants(
        drag_factor=0.0, front_lift_factor=0.0, rear_lift_factor=0.0)
    p = model.parameters
    t = np.linspace(0.0, 2.0, 11)
    r = vehdyn.simulate(model, t, None, x0=model.straight_running(10.0), method="DOP853", rtol=1e-9, atol=1e-9)
    loads = np.concatenate([r["front_normal_load"], r["rear_normal_load"]]) / 2
    assert np.all(tire.evaluate(loads, 0.0, 0.0).mode == "elastic")  # the closed form's premise
    k = soil.modulus(geometry.width)
    z = (geometry.stiffness_pressure / k) ** (1.0 / soil.n)
    resistance = geometry.width * k * z ** (soil.n + 1.0) / (soil.n + 1.0)
    expected = -4.0 * resistance / (p.mass + 4.0 * p.wheel_spin_inertia / p.rolling_radius**2)
    kappa = np.max(np.abs(np.concatenate([r["front_slip_ratio"][2:], r["rear_slip_ratio"][2:]])))
    assert kappa < 2e-3
    rotating_share = 4.0 * p.wheel_spin_inertia / p.rolling_radius**2 / p.mass
    assert np.allclose(r["longitudinal_acceleration"][2:], expected, rtol=kappa * rotating_share + 1e-6)


def test_elastic_side_force_against_quadrature():
    soil = load_soil("lete_sand")
    wheel = FlexibleWheel(geometry=GEOMETRY, soil=soil)
    load, slip, alpha = 8000.0, -0.3, -0.15  # braked: V / (r omega) = 1 / (1 + s)
    r = wheel.solve(load, slip, alpha)
    assert r.mode == "elastic"
    p = GEOMETRY.stiffness_pressure
    length, z = load / (GEOMETRY.width * p), float(r.sinkage)
    travel = 1 / (1 + slip)
    shear = GEOMETRY.width * quad(lambda x: (soil.cohesion + p * math.tan(soil.friction_angle))
                                  * (1 - math.exp(-x * travel * math.tan(-alpha) / soil.side_shear_modulus)),
                                  0, length)[0]
    n_phi = math.tan(math.pi / 4 + soil.friction_angle / 2) ** 2
    wall = length * (0.5 * soil.density * 9.81 * z * z * n_phi + 2 * soil.cohesion * z * math.sqrt(n_phi))
    assert r.lateral_force == pytest.approx(shear + math.sin(-alpha) * wall, rel=1e-9)  # alpha < 0: F_y > 0


@pytest.mark.parametrize("soil_name", ["dry_sand", "snow", "heavy_clay"])
def test_soft_soil_tire_is_finite_on_its_whole_domain(soil_name):
    # lift-off, locked and backwards-spinning wheels, spinning in place, large slip angles, reverse
    tire = SoftSoilTire(GEOMETRY, load_soil(soil_name))
    fz, kappa, alpha, vx = np.meshgrid([0.0, 500.0, 4000.0, 20000.0], [-3.0, -1.0, -0.2, 0.0, 0.3, 50.0],
                                       [-1.6, -0.3, 0.0, 0.3, 1.6], [-5.0, 0.0, 5.0], indexing="ij")
    f = tire.forces(fz, kappa, alpha, 0.0, vx)
    for name in ("fx", "fy", "my"):
        assert np.all(np.isfinite(getattr(f, name))), name
    lifted = fz == 0.0
    assert np.all(f.fx[lifted] == 0.0) and np.all(f.fy[lifted] == 0.0)
    state = tire.evaluate(fz, kappa, alpha, vx)
    assert set(np.unique(state.status)) <= {"ok", "stuck"} and np.all(np.isfinite(state.sinkage))
    assert np.all(state.sinkage <= GEOMETRY.radius)
