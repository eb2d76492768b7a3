"""FullVehicle at one state: evaluated on Python floats (assembly.SCALAR), the numbers of the numpy
batch path, numpy's rules where a float operation has no IEEE result, the model's own errors kept.

The float path calls :mod:`math`'s functions where the batch calls numpy's: equal on CPUs whose
numpy uses the C library's (bitwise on the development machine), a few ulps apart where numpy has
SIMD kernels of its own (AVX-512); so the comparisons are of kind (b) of tests/_tolerances.py, at
the budget of the suite's other rhs comparisons across the two libraries.
"""

import numpy as np
import pytest

from tests._tolerances import ONE_CALL_ULPS, assert_close_ulps
from vehdyn.errors import ParameterError
from vehdyn.full_vehicle import FullVehicle, assembly
from vehdyn.road import RoadProfile


def _states_near(model, x0, n=4, seed=3):
    """``n`` states around ``x0`` (columns), each entry moved by up to 1 % of its size (at least 1e-3)."""
    rng = np.random.default_rng(seed)
    return x0[:, None] + 1e-2 * rng.standard_normal((x0.size, n)) * np.maximum(np.abs(x0), 0.1)[:, None]


@pytest.mark.compiled_vs_numpy
@pytest.mark.parametrize("options", [{}, {"tire_lag": False}, {"compliance_steer": True}, {"road": "profile"}],
                         ids=["default", "no_lag", "compliance", "road"])
def test_one_point_equals_the_numpy_batch(sedan, options):
    if options.get("road") == "profile":
        x = np.linspace(-50.0, 500.0, 1101)
        options = {"road": RoadProfile(x, 0.01 * np.sin(x / 3.0))}
    if options.pop("compliance_steer", False):
        sedan = sedan.replace(suspension__front_lateral_force_compliance_steer=-1e-6,
                              suspension__front_aligning_moment_compliance_steer=2e-5)
    model = FullVehicle(sedan, **options)
    x0, u0 = model.trim(20.0, lateral_acceleration=4.0)
    X = _states_near(model, x0)
    U = np.repeat(u0[:, None], X.shape[1], axis=1)
    U[0] += 0.01  # steer a little more
    F, G = model.rhs(0.0, X, U), model.output(0.0, X, U)
    for j in range(X.shape[1]):
        states, _ = model._evaluate(X[:, j], U[:, j])
        assert type(states[0]) is float  # the float path ran
        assert_close_ulps(model.rhs(0.0, X[:, j], U[:, j]), F[:, j], ulps=ONE_CALL_ULPS, rtol=1e-12,
                          what="float vs numpy rhs")
        assert_close_ulps(model.output(0.0, X[:, j], U[:, j]), G[:, j], ulps=ONE_CALL_ULPS, rtol=1e-12,
                          what="float vs numpy output")


@pytest.mark.compiled_vs_numpy
def test_a_float_operation_without_ieee_result_falls_back_to_numpy(sedan, monkeypatch):
    model = FullVehicle(sedan)
    x0, u0 = model.trim(15.0)
    expected = model.rhs(0.0, x0[:, None], u0[:, None])[:, 0]
    # the same numpy path but for the tire law, which takes its own float path at one point

    def no_result(*args):
        raise ZeroDivisionError("float division by zero")

    monkeypatch.setattr(assembly.SCALAR, "sqrt", staticmethod(no_result))
    assert_close_ulps(model.rhs(0.0, x0, u0), expected, ulps=ONE_CALL_ULPS, rtol=1e-12, what="fallback rhs")
    states, _ = model._evaluate(x0, u0)
    assert isinstance(states[0], np.ndarray) or type(states[0]) is not float  # numpy's path answered

    def domain(*args):
        raise ValueError("math domain error")

    monkeypatch.setattr(assembly.SCALAR, "sqrt", staticmethod(domain))
    assert_close_ulps(model.rhs(0.0, x0, u0), expected, ulps=ONE_CALL_ULPS, rtol=1e-12, what="fallback rhs")


def test_the_model_s_own_errors_are_not_retried(sedan, monkeypatch):
    model = FullVehicle(sedan)
    x0, u0 = model.trim(15.0)
    calls = []

    def refuse(*args):
        calls.append(args)
        raise ParameterError("refused", key="pitch_angle", value=args[1])

    monkeypatch.setattr(assembly.SCALAR, "euler_angle_rates", staticmethod(refuse))
    with pytest.raises(ParameterError, match="refused"):
        model.rhs(0.0, x0, u0)
    assert len(calls) == 1


@pytest.mark.compiled_vs_numpy
def test_a_simulation_is_unchanged_by_the_path(sedan):
    """A step steer on numpy: one state per rhs call (floats) against the same run with every rhs call
    made on a batch of one (numpy's path). Through the integrator an ulp of difference may flip a step
    decision: within a tenth of the solver's rtol (1e-6), and bitwise where the libraries agree."""
    import vehdyn

    model = FullVehicle(sedan)
    x0, u0 = model.trim(20.0)
    inputs = dict(zip(model.input_names, u0))
    inputs["front_steer_angle"] = lambda t: 0.02 * min(t / 0.2, 1.0)
    t = np.linspace(0.0, 1.0, 101)
    floats = vehdyn.simulate(model, t, inputs, x0=x0, backend="numpy")

    class Batched(FullVehicle):
        def rhs(self, t, x, u):
            return super().rhs(t, np.asarray(x)[:, None], np.asarray(u)[:, None])[:, 0]

    batched = vehdyn.simulate(Batched(sedan), t, inputs, x0=x0, backend="numpy")
    np.testing.assert_allclose(floats.states, batched.states, rtol=1e-7, atol=1e-9)
