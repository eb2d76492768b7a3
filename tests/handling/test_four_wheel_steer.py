"""Four-wheel steering against C-4WS-ABE and the steady-state balance."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import vehdyn
from vehdyn.handling import (
    BicycleParameters,
    LinearBicycle,
    compare_four_wheel_steering,
    proportional_rear_steer,
    steady_state_gains,
    yaw_rate_feedback_rear_steer,
    zero_sideslip_rear_steer_ratio,
    zero_sideslip_speed,
)

ABE_YAW_INERTIA = 2500.0  # the C case omits I_z (steady state does not depend on it); A-SS-ABE gives it


@pytest.fixture
def abe(reference_case, case_bicycle):
    return case_bicycle(reference_case("C-4WS-ABE"), yaw_inertia=ABE_YAW_INERTIA)


def test_zero_sideslip_ratio_and_gains(reference_case, abe, approx_case):
    e = reference_case("C-4WS-ABE")["expected"]
    speeds = np.array([5.0, 10.0, 20.0, 30.0, 40.0])
    k = zero_sideslip_rear_steer_ratio(abe, speeds)
    four = steady_state_gains(abe, speeds, rear_steer_ratio=k)
    two = steady_state_gains(abe, speeds)
    for j, u in enumerate(speeds):
        tag = f"@{u:g}mps"
        assert k[j] == approx_case(e["k" + tag])
        assert four.yaw_rate[j] == approx_case(e["r/delta_f_4WS" + tag])
        assert two.yaw_rate[j] == approx_case(e["r/delta_f_2WS" + tag])
        assert four.sideslip_angle[j] == pytest.approx(0.0, abs=1e-12)
    assert zero_sideslip_rear_steer_ratio(abe, 0.0) == approx_case(e["k_limit_V_to_0"])
    assert zero_sideslip_rear_steer_ratio(abe, 1e7) == approx_case(e["k_limit_V_to_inf"])
    assert zero_sideslip_speed(abe) == approx_case(e["V_k_zero"])
    assert zero_sideslip_rear_steer_ratio(abe, zero_sideslip_speed(abe)) == pytest.approx(0.0, abs=1e-12)


def test_proportional_rear_steer_model_has_zero_sideslip_by_simulation(abe):
    """The 4WS model built from the bicycle reaches zero sideslip: simulated, not algebraic."""
    car = abe.at_speed(25.0)
    four = proportional_rear_steer(car)
    assert four.input_names == ("front_steer_angle",)
    t = np.linspace(0.0, 10.0, 1001)
    res = vehdyn.simulate(four, t, {"front_steer_angle": 0.01})
    assert abs(res["sideslip_angle"][-1]) < 1e-9 * abs(res["yaw_rate"][-1])
    k = zero_sideslip_rear_steer_ratio(car)
    np.testing.assert_allclose(res["rear_steer_angle"], k * 0.01, rtol=1e-14)
    # the same run of the 2-input bicycle with delta_r = k delta_f
    both = vehdyn.simulate(car, t, {"front_steer_angle": 0.01, "rear_steer_angle": k * 0.01})
    np.testing.assert_allclose(res["yaw_rate"], both["yaw_rate"], rtol=1e-12, atol=1e-15)


def test_in_phase_rear_steer_reduces_yaw_gain_at_speed(abe):
    """At high speed the zero-sideslip ratio is positive (in phase) and lowers the yaw-rate gain."""
    comparison = compare_four_wheel_steering(abe, [10.0, 30.0], frequency_hz=1.0)
    assert comparison.rear_steer_ratio[0] < 0 < comparison.rear_steer_ratio[1]
    assert comparison.yaw_rate_gain_4ws[1] < comparison.yaw_rate_gain_2ws[1]
    assert comparison.yaw_rate_gain_4ws[0] > comparison.yaw_rate_gain_2ws[0]
    np.testing.assert_allclose(comparison.sideslip_gain_4ws, 0.0, atol=1e-12)
    # the 1-Hz phase equals that of the proportional-rear-steer model's own frequency response
    fr = proportional_rear_steer(abe.at_speed(30.0)).frequency_response([2 * np.pi], outputs=["yaw_rate"])
    assert comparison.yaw_rate_phase_4ws[1] == pytest.approx(np.rad2deg(np.angle(fr.response[0, 0, 0])), rel=1e-12)
    assert comparison.to_frame().attrs["units"]["yaw_rate_phase_4ws"] == "deg"


def test_yaw_rate_feedback_closed_loop():
    """delta_r = g r: A_cl = A + B_r g e_r^T; its steady yaw gain is u / (L + K u^2 + u g) from the balance
    delta_f - delta_r = r (L/u + K u)."""
    car = LinearBicycle(vehdyn.load_vehicle("compact"), 20.0)
    g = 0.05
    closed = yaw_rate_feedback_rear_steer(car, g)
    p = car.bicycle_parameters
    expected = 20.0 / (p.wheelbase + p.understeer_gradient * 20.0**2 + 20.0 * g)
    dc = closed.dc_gain()[:, 0]
    assert dc[closed.index("yaw_rate", "outputs")] == pytest.approx(expected, rel=1e-12)
    assert dc[closed.index("rear_steer_angle", "outputs")] == pytest.approx(g * expected, rel=1e-12)
    t = np.linspace(0, 3, 301)
    res = vehdyn.simulate(closed, t, {"front_steer_angle": 0.01})
    np.testing.assert_allclose(res["rear_steer_angle"], g * res["yaw_rate"], rtol=1e-12)


def test_four_wheel_steer_errors(abe):
    with pytest.raises(vehdyn.ParameterError, match="LinearBicycle"):
        proportional_rear_steer(vehdyn.load_vehicle("sedan"))
    with pytest.raises(vehdyn.ParameterError, match="ratio"):
        proportional_rear_steer(abe, np.nan)
    with pytest.raises(vehdyn.ParameterError, match="gain"):
        yaw_rate_feedback_rear_steer(abe, np.inf)
    with pytest.raises(vehdyn.ParameterError, match="speed"):
        zero_sideslip_rear_steer_ratio(vehdyn.load_vehicle("sedan"))
    with pytest.raises(vehdyn.ParameterError, match="frequency_hz"):
        compare_four_wheel_steering(abe, [10.0], frequency_hz=0.0)


@settings(max_examples=30, deadline=None)
@given(st.floats(0.3, 0.7), st.floats(0.6, 1.6), st.floats(1.0, 50.0))
def test_zero_sideslip_ratio_property(cg_fraction, stiffness_ratio, speed):
    """For any CG position, stiffness balance and speed, the 4WS model's steady sideslip is zero and the
    yaw-rate gain follows the balance delta_f - delta_r = r (L/u + K u)."""
    L = 2.7
    p = BicycleParameters(mass=1500.0, yaw_inertia=2500.0, a=cg_fraction * L, b=(1 - cg_fraction) * L,
                          front_cornering_stiffness=1e5 * stiffness_ratio, rear_cornering_stiffness=1e5)
    four = proportional_rear_steer(LinearBicycle(p, speed))
    if not four.is_stable():
        return  # beyond the critical speed the steady state is not reached
    dc = four.dc_gain()[:, 0]
    k = four.rear_steer_ratio
    assert dc[four.index("sideslip_angle", "outputs")] == pytest.approx(0.0, abs=1e-10)
    expected = (1 - k) / (L / speed + p.understeer_gradient * speed)
    assert dc[four.index("yaw_rate", "outputs")] == pytest.approx(expected, rel=1e-9)
