"""SingleTrack at one state: evaluated on Python floats (components.xp.SCALAR), the numbers of the
numpy batch path, numpy's rules where a float operation has no IEEE result, the model's own errors kept.

math's functions against numpy's: kind (b) of tests/_tolerances.py (bitwise on the development
machine; a few ulps apart where numpy has SIMD kernels of its own).
"""

import numpy as np
import pytest

import vehdyn
from tests._tolerances import ONE_CALL_ULPS, assert_close_ulps
from vehdyn.components import xp as components_xp
from vehdyn.errors import ParameterError
from vehdyn.handling import SingleTrack

OPTIONS = {"default": {}, "no_lag": {"tire_lag": False}, "wheel_spin": {"wheel_spin": True},
           "load_transfer_roll": {"lateral_load_transfer": True, "roll": True},
           "split_friction": {"friction": lambda X, Y: 0.6 + 0.3 * (Y > 0.0)}}


def _near(model, seed=5, n=4):
    """``n`` states around a 20-m/s drift (columns) and inputs: a little steer, drive and brake."""
    rng = np.random.default_rng(seed)
    named = {"longitudinal_velocity": 20.0, "lateral_velocity": 0.3, "yaw_rate": 0.15}
    for name in model.state_names:
        if name.startswith("wheel_speed"):
            named[name] = 20.0 / 0.31
    x0 = model.state_vector(**{k: v for k, v in named.items() if k in model.state_names})
    X = x0[:, None] + 1e-2 * rng.standard_normal((x0.size, n)) * np.maximum(np.abs(x0), 0.01)[:, None]
    U = np.zeros((model.n_inputs, n))
    U[model.input_names.index("front_steer_angle")] = 0.02 + 0.01 * rng.standard_normal(n)
    for name in model.input_names:
        if "torque" in name:
            U[model.input_names.index(name)] = 200.0 * rng.random(n)
    return X, U


@pytest.mark.compiled_vs_numpy
@pytest.mark.parametrize("options", list(OPTIONS.values()), ids=list(OPTIONS))
def test_one_point_equals_the_numpy_batch(options):
    model = SingleTrack(vehdyn.load_vehicle("sedan"), **options)
    X, U = _near(model)
    F, G = model.rhs(0.0, X, U), model.output(0.0, X, U)
    for j in range(X.shape[1]):
        states, _, _, _ = model._evaluate(X[:, j], U[:, j])
        assert type(states[0]) is float  # the float path ran
        assert_close_ulps(model.rhs(0.0, X[:, j], U[:, j]), F[:, j], ulps=ONE_CALL_ULPS, rtol=1e-12,
                          what="float vs numpy rhs")
        assert_close_ulps(model.output(0.0, X[:, j], U[:, j]), G[:, j], ulps=ONE_CALL_ULPS, rtol=1e-12,
                          what="float vs numpy output")


@pytest.mark.compiled_vs_numpy
def test_a_float_operation_without_ieee_result_falls_back_to_numpy(monkeypatch):
    model = SingleTrack(vehdyn.load_vehicle("sedan"), wheel_spin=True)
    X, U = _near(model, n=1)
    expected = model.rhs(0.0, X, U)[:, 0]

    def no_result(*args):
        raise ZeroDivisionError("float division by zero")

    monkeypatch.setattr(components_xp.SCALAR, "atan", staticmethod(no_result))
    assert_close_ulps(model.rhs(0.0, X[:, 0], U[:, 0]), expected, ulps=ONE_CALL_ULPS, rtol=1e-12,
                      what="fallback rhs")
    states, _, _, _ = model._evaluate(X[:, 0], U[:, 0])
    assert type(states[0]) is not float  # numpy's path answered


def test_the_model_s_own_errors_are_not_retried(monkeypatch):
    model = SingleTrack(vehdyn.load_vehicle("sedan"))
    X, U = _near(model, n=1)
    calls = []

    def refuse(*args):
        calls.append(args)
        raise ParameterError("refused", key="speed", value=args[0])

    monkeypatch.setattr(components_xp.SCALAR, "maximum", staticmethod(refuse))
    with pytest.raises(ParameterError, match="refused"):
        model.rhs(0.0, X[:, 0], U[:, 0])
    assert len(calls) == 1
