"""The full vehicle: road and friction callables that return the wrong thing, trim settings, numpy
scalars.

Independent references: a flat road given as a callable (zeros) against no road at all, a uniform
friction ratio of 1 against none, the trim at the same speed given as a Python float.
"""

import numpy as np
import pytest

import vehdyn
from vehdyn import ParameterError
from vehdyn.full_vehicle import FullVehicle


@pytest.fixture(scope="module")
def sedan():
    return vehdyn.load_vehicle("sedan")


@pytest.fixture(scope="module")
def running(sedan):
    """(x0, u0) of straight running at 20 m/s."""
    return FullVehicle(sedan).trim(20.0)


def _refused(call, key, value_text):
    with pytest.raises(ParameterError) as info:
        call()
    message = str(info.value)
    assert info.value.key == key, message
    assert key.split(".")[-1] in message and value_text in message, message
    return info.value


@pytest.mark.parametrize("road, text", [
    (lambda X, Y: (0 * X, 0 * X), "tuple"),  # was: not enough values to unpack (expected 3, got 2)
    (lambda X, Y: 0.0, "float 0.0"),  # was: cannot unpack non-iterable float object
    (lambda X, Y: ("a", "b", "c"), "'a'"),  # was numpy's UFuncTypeError
    (lambda X, Y: (np.zeros(3), 0.0, 0.0), "ndarray"),  # three values where X is one
    (lambda X, Y: (np.nan * X, 0 * X, 0 * X), "nan"),  # was NaN in the derivatives
    (lambda X, Y: (0 * X, np.inf + 0 * X, 0 * X), "inf"),
])
def test_road_callable_returning_the_wrong_thing_is_named(sedan, running, road, text):
    model = FullVehicle(sedan, road=road)
    error = _refused(lambda: model.rhs(0.0, *running), "road", text)
    assert "road(X, Y)" in str(error)


@pytest.mark.parametrize("friction, text", [
    (lambda X, Y: np.nan, "nan"), (lambda X, Y: np.inf, "inf"),  # inf gave NaN derivatives
    (lambda X, Y: (1.0, 1.0), "(1.0, 1.0)"),  # was numpy's broadcast ValueError
    (lambda X, Y: "high", "'high'"),  # was float()'s ValueError
    (lambda X, Y: None, "None"),
])
def test_friction_callable_returning_the_wrong_thing_is_named(sedan, running, friction, text):
    model = FullVehicle(sedan, friction=friction)
    _refused(lambda: model.rhs(0.0, *running), "friction", text)


@pytest.mark.parametrize("name", ["road", "friction"])
def test_a_callable_that_does_not_take_x_and_y_is_named_where_it_is_given(sedan, name):
    """road=lambda X: ... raised the lambda's TypeError inside the first rhs call."""
    _refused(lambda: FullVehicle(sedan, **{name: lambda X: X}), name, "(X)")


def test_valid_callables_keep_their_numbers(sedan, running):
    """A flat road and a uniform friction ratio of 1 as callables give the model's own numbers."""
    x0, u0 = running
    plain = FullVehicle(sedan).rhs(0.0, x0, u0)
    flat = FullVehicle(sedan, road=lambda X, Y: (0.0 * X, 0.0 * X, 0.0)).rhs(0.0, x0, u0)
    uniform = FullVehicle(sedan, friction=lambda X, Y: np.ones_like(X)).rhs(0.0, x0, u0)
    np.testing.assert_array_equal(flat, plain)
    np.testing.assert_array_equal(uniform, plain)
    batch = np.repeat(x0[:, None], 3, axis=1)
    ubatch = np.repeat(u0[:, None], 3, axis=1)
    scalar_ratio = FullVehicle(sedan, friction=lambda X, Y: 1.0).rhs(0.0, batch, ubatch)
    np.testing.assert_array_equal(scalar_ratio, FullVehicle(sedan).rhs(0.0, batch, ubatch))


@pytest.mark.parametrize("value, text", [(0, "0"), (float("nan"), "nan"), (-1, "-1"), ("a", "'a'")])
def test_trim_tolerance_is_checked(sedan, value, text):
    """tol=0 reported 'found no steady state ... The solution converged.'"""
    _refused(lambda: FullVehicle(sedan).trim(20.0, tol=value), "tol", text)


def test_numpy_scalars_are_numbers(sedan):
    """np.float32 and np.int64 speeds, accelerations, radii and gravity were refused as non-numbers."""
    model = FullVehicle(sedan)
    for given in (np.float32(20.0), np.int64(20)):
        x_a, u_a = model.trim(given)
        x_b, u_b = model.trim(float(given))
        np.testing.assert_array_equal(x_a, x_b)
        np.testing.assert_array_equal(u_a, u_b)
    x_a, u_a = model.trim(20.0, lateral_acceleration=np.float32(2.0))
    x_b, u_b = model.trim(20.0, lateral_acceleration=float(np.float32(2.0)))
    np.testing.assert_array_equal(u_a, u_b)
    x_a, u_a = model.trim(20.0, radius=np.int64(200))
    np.testing.assert_array_equal(u_a, model.trim(20.0, radius=200.0)[1])
    assert FullVehicle(sedan, gravity=np.float32(9.81)).gravity == float(np.float32(9.81))


@pytest.mark.parametrize("result", [{"x": 1}, None])
def test_wheel_lift_needs_a_full_vehicle_result(result):
    """A dict raised "'dict' object has no attribute 'time'"."""
    _refused(lambda: FullVehicle.wheel_lift(result), "result", type(result).__name__)
