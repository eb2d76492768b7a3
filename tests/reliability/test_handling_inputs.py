"""Handling closed forms and the nonlinear handling diagram: bad numbers named, search settings
that cannot produce the answer refused.

Independent references: the closed forms with Python floats (Gillespie 1992, eq. 6-15 to 6-22 as
coded in vehdyn.handling.steady_state), the diagram's own default run.
"""

import numpy as np
import pytest

import vehdyn
from vehdyn import ParameterError
from vehdyn.handling import SingleTrack, ackermann_steer_angle, handling_diagram, steady_state_gains, steer_angle_for
from vehdyn.handling.nonlinear_steady_state import nonlinear_handling_diagram


@pytest.fixture(scope="module")
def sedan():
    return vehdyn.load_vehicle("sedan")


def _refused(call, key, value_text):
    with pytest.raises(ParameterError) as info:
        call()
    message = str(info.value)
    assert info.value.key == key, message
    assert key.split(".")[-1] in message and value_text in message, message
    return info.value


def test_rear_steer_ratio_is_checked_and_valid_ratios_keep_the_closed_form(sedan):
    """NaN gave NaN gains without a word; 'a' raised numpy's ValueError. Valid ratios give the
    closed form r / delta = u (1 - k) / (L + K u^2)."""
    from vehdyn.handling import understeer_gradient

    for value, text in ((float("nan"), "nan"), ("a", "'a'"), ([0.1, float("inf")], "inf")):
        _refused(lambda: steady_state_gains(sedan, 20.0, rear_steer_ratio=value), "rear_steer_ratio", text)
        _refused(lambda: steer_angle_for(sedan, 50.0, 20.0, rear_steer_ratio=value), "rear_steer_ratio", text)
    k = np.array([-0.2, 0.0, 0.3])
    gains = steady_state_gains(sedan, 20.0, rear_steer_ratio=k)
    L, K = sedan.wheelbase, understeer_gradient(sedan)
    np.testing.assert_allclose(gains.yaw_rate, 20.0 * (1 - k) / (L + K * 400.0), rtol=1e-14)


@pytest.mark.parametrize("value, text", [("x", "'x'"), ([1.0, None], "None")])
def test_handling_diagram_lateral_acceleration_is_checked(sedan, value, text):
    _refused(lambda: handling_diagram(sedan, value, radius=50.0), "lateral_acceleration", text)


def test_radius_is_checked(sedan):
    """'x' raised numpy's ValueError."""
    _refused(lambda: steer_angle_for(sedan, "x", 20.0), "radius", "'x'")


def test_a_bool_is_not_a_wheelbase():
    """True was taken as a 1 m wheelbase."""
    with pytest.raises(ParameterError) as info:
        ackermann_steer_angle(True, 50.0)
    assert "True" in str(info.value) or "bool" in str(info.value)
    assert ackermann_steer_angle(np.float32(2.5), 50.0) == ackermann_steer_angle(float(np.float32(2.5)), 50.0)


# ---------------------------------------------------------------------------- nonlinear handling diagram
@pytest.fixture(scope="module")
def single_track(sedan):
    return SingleTrack(sedan)


def test_a_step_below_the_tolerance_is_refused_not_reported_as_no_turn(single_track):
    """step=1e-9 below the 0.01 m/s^2 tolerance stopped the continuation before its first step and
    raised 'no steady-state turn found even at the first step'."""
    _refused(lambda: vehdyn.procedures.constant_radius_test(single_track, 50.0, step=1e-9), "step", "1e-09")
    _refused(lambda: nonlinear_handling_diagram(single_track, radius=50.0, step=1e-3, tolerance=1e-4,
                                                max_lateral_acceleration=30.0), "step", "0.001")


@pytest.mark.parametrize("name, value, text", [("max_lateral_acceleration", -1.0, "-1.0"),
                                               ("max_lateral_acceleration", float("inf"), "inf"),
                                               ("step", "0.25", "'0.25'")])
def test_diagram_settings_are_checked(single_track, name, value, text):
    _refused(lambda: nonlinear_handling_diagram(single_track, radius=50.0, **{name: value}), name, text)


def test_constant_radius_test_radius_is_checked(single_track):
    """'a' raised float()'s ValueError."""
    _refused(lambda: vehdyn.procedures.constant_radius_test(single_track, "a"), "radius", "'a'")
