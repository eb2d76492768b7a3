"""Steady-state handling against the reference cases A-SS-*, A-GAIN-*, A-SS-WONG, A-ACK-1, A-STEER-ABE."""

import numpy as np
import pytest

import vehdyn
from vehdyn import conventions
from vehdyn.handling import (
    BicycleParameters,
    LinearBicycle,
    ackermann_steer_angle,
    ackermann_wheel_angles,
    characteristic_speed,
    critical_speed,
    handling_diagram,
    neutral_steer_point,
    stability_factor,
    static_margin,
    steady_state_gains,
    steer_angle_for,
    understeer_gradient,
    understeer_gradient_deg_per_g,
    understeer_gradient_rad_per_g,
    yaw_mode,
    zero_sideslip_speed,
)
from vehdyn.units import GRAVITY


@pytest.mark.parametrize("case_id", ["A-SS-ABE", "A-SS-SUV", "A-SS-OVR", "A-SS-NEU"])
def test_understeer_and_stability_numbers(case_id, reference_case, case_bicycle, approx_case):
    case = reference_case(case_id)
    car = case_bicycle(case)
    e = case["expected"]
    assert car.wheelbase == approx_case(e["L"])
    wf, wr = np.array([car.bicycle_parameters.b, car.bicycle_parameters.a]) * car.bicycle_parameters.mass * GRAVITY \
        / car.wheelbase
    assert wf == approx_case(e["Wf_axle"]) and wr == approx_case(e["Wr_axle"])
    # the neutral case is zero only to the rounding of its Cr (111392.4 = Cf lf / lr to 7 digits)
    zero = 1e-9
    assert understeer_gradient(car) == approx_case(e["K_rad_per_mps2"], abs_tol=zero)
    assert understeer_gradient_rad_per_g(car) == approx_case(e["K_rad_per_g"], abs_tol=zero * 10)
    assert understeer_gradient_deg_per_g(car) == approx_case(e["K_deg_per_g"], abs_tol=zero * 1e3)
    assert stability_factor(car) == approx_case(e["stability_factor_A"], abs_tol=zero)
    nsp = neutral_steer_point(car)
    assert nsp.from_front_axle == approx_case(e["x_NSP_from_front_axle"])
    assert nsp.behind_cg == approx_case(e["NSP_behind_CG"], abs_tol=1e-6)
    assert static_margin(car) == approx_case(e["static_margin"], abs_tol=1e-6)
    assert zero_sideslip_speed(car) == approx_case(e["V_beta_zero"])
    if "V_characteristic" in e:
        assert characteristic_speed(car) == approx_case(e["V_characteristic"])
        assert critical_speed(car) == np.inf
    if "V_critical" in e:
        assert critical_speed(car) == approx_case(e["V_critical"])
        assert characteristic_speed(car) == np.inf


def test_identity_between_understeer_gradient_and_static_margin(reference_case, case_bicycle):
    """K = m (Cf + Cr) SM / (Cf Cr), the identity quoted by the A-SS cases."""
    for case_id in ("A-SS-ABE", "A-SS-SUV", "A-SS-OVR"):
        car = case_bicycle(reference_case(case_id))
        p = car.bicycle_parameters
        cf, cr = p.front_cornering_stiffness, p.rear_cornering_stiffness
        assert understeer_gradient(car) == pytest.approx(p.mass * (cf + cr) * static_margin(car) / (cf * cr), rel=1e-12)


@pytest.mark.parametrize("case_id", ["A-GAIN-ABE", "A-GAIN-SUV", "A-GAIN-OVR", "A-GAIN-NEU"])
def test_steady_state_gains(case_id, reference_case, case_bicycle, approx_case):
    case = reference_case(case_id)
    speeds = np.array(case["inputs"]["speeds"][0])
    car = case_bicycle(case)
    gains = steady_state_gains(car, speeds)  # one vectorized call
    e = case["expected"]
    for k, u in enumerate(speeds):
        tag = f"@{u:g}mps"
        assert gains.yaw_rate[k] == approx_case(e["yaw_gain_r_per_delta" + tag])
        assert gains.lateral_acceleration[k] == approx_case(e["lat_acc_gain_ay_per_delta" + tag])
        assert gains.lateral_acceleration_g_per_deg[k] == approx_case(e["lat_acc_gain_g_per_deg" + tag])
        assert gains.sideslip_angle[k] == approx_case(e["sideslip_gain_beta_per_delta" + tag])
        # and the state-space model at that speed agrees (the "-A^-1 B" cross-check of the case)
        dc = car.at_speed(u).dc_gain()[:, 0]
        assert dc[car.index("yaw_rate", "outputs")] == approx_case(e["yaw_gain_r_per_delta" + tag])
        assert dc[car.index("sideslip_angle", "outputs")] == approx_case(e["sideslip_gain_beta_per_delta" + tag])


def test_wong_problem_per_tire_stiffness(reference_case, approx_case):
    """A-SS-WONG: Wong prints PER-TIRE cornering stiffness; the axle value is twice it."""
    case = reference_case("A-SS-WONG")
    i = {k: v[0] for k, v in case["inputs"].items()}
    e = case["expected"]
    L, f = i["L"], i["front_weight_fraction"]

    def car(cf_tire, cr_tire):
        return BicycleParameters(mass=i["W"] / i["g"], yaw_inertia=3000.0, a=(1 - f) * L, b=f * L,
                                 front_cornering_stiffness=2 * cf_tire, rear_cornering_stiffness=2 * cr_tire)

    base = car(i["C_alpha_front_per_tyre"], i["C_alpha_rear_per_tyre"])
    assert understeer_gradient_rad_per_g(base) == approx_case(e["K_us_rad"])
    assert understeer_gradient_deg_per_g(base) == approx_case(e["K_us_deg_per_g"])
    assert characteristic_speed(base) == approx_case(e["V_characteristic"])
    assert float(vehdyn.units.ms_to_kmh(characteristic_speed(base))) == approx_case(e["V_characteristic_kmh"])
    b = car(i["C_alpha_front_per_tyre"], i["C_alpha_rear_per_tyre_case_b"])
    assert understeer_gradient_rad_per_g(b) == approx_case(e["K_us_rad_case_b"])
    assert characteristic_speed(b) == approx_case(e["V_characteristic_case_b"])
    c = car(i["C_alpha_rear_per_tyre_case_b"], i["C_alpha_rear_per_tyre"])
    assert understeer_gradient_rad_per_g(c) == approx_case(e["K_us_rad_case_c_front_47.82"])
    assert critical_speed(c) == approx_case(e["V_critical_case_c"])


def test_ackermann_angles(reference_case, approx_case):
    case = reference_case("A-ACK-1")
    i = {k: v[0] for k, v in case["inputs"].items()}
    e = case["expected"]
    L, R, t = i["L"], i["R_rear_axle_centre"], i["track_front"]
    deg = np.rad2deg
    assert deg(ackermann_steer_angle(L, R)) == approx_case(e["delta_Ackermann_small_angle"])
    assert deg(ackermann_steer_angle(L, R, exact=True)) == approx_case(e["delta_bicycle_exact_atan"])
    exact = ackermann_wheel_angles(L, R, track=t, exact=True)
    small = ackermann_wheel_angles(L, R, track=t)
    assert deg(exact.inner) == approx_case(e["delta_inner_exact"])
    assert deg(exact.outer) == approx_case(e["delta_outer_exact"])
    assert deg(small.inner) == approx_case(e["delta_inner_small_angle"])
    assert deg(small.outer) == approx_case(e["delta_outer_small_angle"])
    # SAE: a left turn (negative radius) needs negative angles of the same size
    left = ackermann_wheel_angles(L, -R, track=t, exact=True)
    assert left.inner == pytest.approx(-exact.inner) and left.outer == pytest.approx(-exact.outer)


def test_ackermann_with_a_vehicle_uses_its_wheelbase_and_track():
    sedan = vehdyn.load_vehicle("sedan")
    got = ackermann_wheel_angles(sedan, 20.0)
    L, t = sedan.wheelbase, sedan.geometry.front_track
    assert got.inner == pytest.approx(L / (20.0 - t / 2), rel=1e-14)
    assert ackermann_steer_angle(sedan, 20.0) == pytest.approx(L / 20.0, rel=1e-14)


def test_steer_angle_for_radius_and_speed(reference_case, case_bicycle, approx_case):
    case = reference_case("A-STEER-ABE")
    car = case_bicycle(case)
    i = {k: v[0] for k, v in case["inputs"].items()}
    e = case["expected"]
    R, V = i["R"], i["V"]
    assert V**2 / R == approx_case(e["ay"])
    assert np.rad2deg(ackermann_steer_angle(car, R)) == approx_case(e["delta_Ackermann"])
    # the case's radius is a left turn in ISO axes: SAE radius and steer angle are negative
    R_sae = -R
    delta_sae = steer_angle_for(car, R_sae, V)
    delta_iso = conventions.steer_angle_sae_to_iso8855(delta_sae)
    assert np.rad2deg(delta_iso) == approx_case(e["delta_required"])
    assert np.rad2deg(delta_iso - ackermann_steer_angle(car, R)) == approx_case(e["understeer_part"])


def test_steer_angle_is_twice_ackermann_at_the_characteristic_speed(reference_case, case_bicycle):
    car = case_bicycle(reference_case("A-SS-ABE"))
    vch = characteristic_speed(car)
    assert steer_angle_for(car, 80.0, vch) == pytest.approx(2 * ackermann_steer_angle(car, 80.0), rel=1e-12)
    # the yaw-rate gain peaks at the characteristic speed
    speeds = vch * np.array([0.98, 1.0, 1.02])
    yaw = steady_state_gains(car, speeds).yaw_rate
    assert yaw[1] > yaw[0] and yaw[1] > yaw[2]
    assert yaw[1] == pytest.approx(vch / (2 * car.wheelbase), rel=1e-12)


def test_critical_speed_is_where_an_eigenvalue_crosses_zero(reference_case, case_bicycle):
    """Issue 5 item 6: above u_crit the model has a real positive eigenvalue; u_crit predicts the crossing."""
    car = case_bicycle(reference_case("A-SS-OVR"))
    ucrit = critical_speed(car)
    below = np.linalg.eigvals(car.at_speed(0.999 * ucrit).A)
    above = np.linalg.eigvals(car.at_speed(1.001 * ucrit).A)
    assert np.all(below.real < 0)
    positive = above[above.real > 0]
    assert positive.size == 1 and positive[0].imag == 0
    # the determinant of A (product of eigenvalues) vanishes at u_crit
    assert abs(np.linalg.det(car.at_speed(ucrit).A)) < 1e-9 * abs(np.linalg.det(car.at_speed(0.5 * ucrit).A))
    assert yaw_mode(car, ucrit).natural_frequency_squared == pytest.approx(0.0, abs=1e-9)
    # an understeering car stays stable at any speed
    stable = case_bicycle(reference_case("A-SS-ABE"))
    for u in (10.0, 50.0, 100.0):
        assert stable.at_speed(u).is_stable()


def test_handling_diagram_slopes(reference_case, case_bicycle):
    car = case_bicycle(reference_case("A-SS-ABE"))
    ay = np.linspace(0.0, 4.0, 9)
    radius = handling_diagram(car, ay, radius=100.0)
    K = understeer_gradient(car)
    np.testing.assert_allclose(np.diff(radius.steer_angle) / np.diff(ay), K, rtol=1e-10)
    assert radius.steer_angle[0] == pytest.approx(car.wheelbase / 100.0)
    np.testing.assert_allclose(radius.speed, np.sqrt(ay * 100.0))
    speed = handling_diagram(car, ay, speed=20.0)
    np.testing.assert_allclose(np.diff(speed.steer_angle) / np.diff(ay), car.wheelbase / 400.0 + K, rtol=1e-10)
    # both diagrams meet the steer_angle_for line where the conditions coincide (R = 100 m, u = 20 m/s)
    assert np.interp(4.0, ay, radius.steer_angle) == pytest.approx(float(steer_angle_for(car, 100.0, 20.0)))
    assert np.interp(4.0, ay, speed.steer_angle) == pytest.approx(float(steer_angle_for(car, 100.0, 20.0)))
    df = speed.to_frame()
    assert df.attrs["units"]["steer_angle"] == "rad"


def test_functions_accept_vehicle_and_bicycle_alike():
    van = vehdyn.load_vehicle("van")
    car = LinearBicycle(van, 22.0)
    assert understeer_gradient(van) == understeer_gradient(car)
    g1, g2 = steady_state_gains(van, 22.0), steady_state_gains(car)
    assert g1.yaw_rate == g2.yaw_rate and g1.sideslip_angle == g2.sideslip_angle
    frame = steady_state_gains(van, [10.0, 20.0]).to_frame()
    assert list(frame.index) == [10.0, 20.0] and frame.attrs["units"]["yaw_rate"] == "1/s"


def test_errors_name_the_parameter():
    van = vehdyn.load_vehicle("van")
    with pytest.raises(vehdyn.ParameterError, match="speed"):
        steady_state_gains(van)  # a Vehicle has no speed
    with pytest.raises(vehdyn.ParameterError, match="speed"):
        steady_state_gains(van, -1.0)
    with pytest.raises(vehdyn.ParameterError, match="radius"):
        steer_angle_for(van, 0.0, 10.0)
    with pytest.raises(vehdyn.ParameterError, match="radius"):
        ackermann_wheel_angles(van, 0.5)
    with pytest.raises(vehdyn.ParameterError, match="track"):
        ackermann_wheel_angles(2.7, 30.0)
    with pytest.raises(vehdyn.ParameterError, match="wheelbase"):
        ackermann_steer_angle(-2.7, 30.0)
    with pytest.raises(vehdyn.ParameterError, match="radius or speed"):
        handling_diagram(van, [1.0], radius=50.0, speed=10.0)
    with pytest.raises(vehdyn.ParameterError, match="Vehicle"):
        understeer_gradient(3.0)
