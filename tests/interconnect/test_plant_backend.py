"""ClosedLoop(plant, controller, plant_backend="compiled"): a loop that runs in Python (its controller has no
compiled form) evaluates the plant's compiled code point by point. Its rhs and outputs equal the numpy loop's
at random points (one state vector and a batch of them), a run equals the numpy run within the integrator's
tolerance, and bad input names plant_backend."""

import numpy as np
import pytest

import vehdyn
from vehdyn import LinearModel, ParameterError
from vehdyn.full_vehicle import FullVehicle
from vehdyn.handling import SingleTrack
from vehdyn.interconnect import ClosedLoop
from vehdyn.tire import FialaTire

pytest.importorskip("numba")

CAR = vehdyn.load_vehicle("sedan")


def _steer_controller():
    """A Python controller with no compiled form: steer = 0.05 * integral of -yaw_rate, plus the demand."""
    return LinearModel(np.array([[-1.0]]), np.array([[0.0, -1.0]]), np.array([[0.05]]), np.array([[1.0, 0.0]]),
                       states=["integral"], inputs=["front_steer_angle", "yaw_rate"], outputs=["front_steer_angle"])


def _points(loop, base, rng, n):
    x_car = base.trim(20.0)[0] if isinstance(base, FullVehicle) else base.straight_running(20.0)
    X = np.empty((loop.n_states, n))
    for j in range(n):
        x = loop.state_vector(dict(zip(base.state_names, x_car)))
        x[:2] += rng.normal(0.0, [2.0, 1.0])
        x[base.index("yaw_rate")] = rng.normal(0.0, 0.5)
        x[base.index("yaw_angle")] = rng.normal(0.0, 0.2)
        x[-1] = rng.normal(0.0, 0.05)
        X[:, j] = x
    U = np.repeat(loop.input_vector()[:, None], n, axis=1)
    U[loop.index("front_steer_angle", "inputs")] = rng.normal(0.0, 0.05, n)
    return X, U


@pytest.mark.compiled_vs_numpy
@pytest.mark.parametrize("plant", ["single_track", "full_vehicle"])
def test_the_compiled_plant_equals_the_numpy_plant_in_the_loop(plant):
    base = SingleTrack(CAR) if plant == "single_track" else FullVehicle(CAR)
    numpy_loop = ClosedLoop(base, _steer_controller())
    loop = ClosedLoop(base, _steer_controller(), plant_backend="compiled")
    assert numpy_loop.compiled_rhs() is None and loop.compiled_rhs() is None  # runs in Python
    X, U = _points(loop, base, np.random.default_rng(3), 12)
    for j in range(X.shape[1]):  # one state vector at a time: the compiled code (a few ulps from numpy)
        for f, g in ((loop.rhs, numpy_loop.rhs), (loop.output, numpy_loop.output)):
            expected = g(0.0, X[:, j], U[:, j])
            np.testing.assert_allclose(f(0.0, X[:, j], U[:, j]), expected, rtol=1e-12,
                                       atol=1e-12 * np.max(np.abs(expected)))
    # a batch: column by column, the same numbers as one at a time (bitwise)
    batch = loop.rhs(0.0, X, U)
    assert batch.shape == (loop.n_states, X.shape[1])
    for j in range(X.shape[1]):
        assert np.array_equal(batch[:, j], loop.rhs(0.0, X[:, j], U[:, j]))
    # read-only states (as some solvers pass them) call the code compiled for the integrator's
    # arrays: no second compilation of the plant
    compiled = base.compiled_rhs()
    signatures = len(compiled.rhs.signatures), len(compiled.output.signatures)
    frozen = X[:, 0].copy()
    frozen.flags.writeable = False
    assert np.array_equal(loop.rhs(0.0, frozen, U[:, 0]), loop.rhs(0.0, X[:, 0], U[:, 0]))
    loop.output(0.0, frozen, U[:, 0])
    assert (len(compiled.rhs.signatures), len(compiled.output.signatures)) == signatures


@pytest.mark.compiled_vs_numpy
def test_a_run_with_the_compiled_plant_equals_the_numpy_run():
    base = SingleTrack(CAR)
    x0 = ClosedLoop(base, _steer_controller()).state_vector(dict(zip(base.state_names, base.straight_running(20.0))))
    t = np.linspace(0.0, 2.0, 201)
    steer = {"front_steer_angle": lambda time: 0.03 * np.sin(3.0 * time)}
    runs = [vehdyn.simulate(ClosedLoop(base, _steer_controller(), plant_backend=backend), t, steer, x0=x0,
                            method="RK45", rtol=1e-9, atol=1e-12) for backend in ("numpy", "compiled")]
    # the step-size control sees ulp-level differences and takes other steps: the runs differ by the
    # integrator's error, each within about 1e-7 of the exact solution at rtol 1e-9 (measured 9e-8
    # of the largest value, 1.2e-7 with numpy's results perturbed by 2 ulps)
    for name in ("yaw_rate", "lateral_velocity", "y", "integral"):
        scale = np.max(np.abs(runs[0][name]))
        np.testing.assert_allclose(runs[1][name], runs[0][name], rtol=0.0, atol=1e-6 * scale)
    assert runs[1].backend == "numpy"  # the loop's integrator is numpy's; the plant's code is compiled


def test_bad_plant_backend_is_named():
    with pytest.raises(ParameterError, match="plant_backend") as info:
        ClosedLoop(SingleTrack(CAR), _steer_controller(), plant_backend="fast")
    assert info.value.key == "plant_backend" and info.value.value == "fast"
    plant = SingleTrack(CAR, front_tire=FialaTire.from_vehicle(CAR, "front"))  # no compiled form
    with pytest.raises(ParameterError, match="plant_backend='compiled'") as info:
        ClosedLoop(plant, _steer_controller(), plant_backend="compiled")
    assert info.value.key == "plant_backend"
