"""The compiled ClosedLoop (numba) against the numpy one: rhs and outputs equal at random points for chassis
controllers, drivers and nests of them; a driver's compiled law equals its numpy law bitwise; the fallback to
numpy when a part has no compiled form."""

import numpy as np
import pytest

from tests._tolerances import ONE_CALL_ULPS, assert_close_ulps

import vehdyn
from vehdyn import LinearModel, ParameterError
from vehdyn.chassis import ABS, ESC, TractionControl
from vehdyn.driver import CrossoverDriver, OptimalPreviewDriver, PreviewDriver
from vehdyn.full_vehicle import FullVehicle
from vehdyn.handling import SingleTrack
from vehdyn.interconnect import ClosedLoop

pytest.importorskip("numba")

CAR = vehdyn.load_vehicle("sedan")
PATH_X = np.linspace(-10.0, 300.0, 120)
PATH_Y = 2.0 * np.sin(PATH_X / 25.0)
L = CAR.geometry.wheelbase


def _loops():
    spin = SingleTrack(CAR, wheel_spin=True)
    full = FullVehicle(CAR)
    return {
        "abs": ClosedLoop(spin, ABS(CAR)),
        "traction_control": ClosedLoop(spin, TractionControl(CAR)),
        "esc_force": ClosedLoop(SingleTrack(CAR), ESC(CAR)),
        "esc_around_abs": ClosedLoop(ClosedLoop(spin, ABS(CAR)), ESC(CAR, wheel_spin=True)),
        "full_esc_around_abs": ClosedLoop(ClosedLoop(full, ABS(CAR, corners=True)), ESC(CAR, corners=True)),
        "full_traction_control": ClosedLoop(full, TractionControl(CAR, corners=True)),
        "preview_speed_control": PreviewDriver(PATH_X, PATH_Y, wheelbase=L, target_speed=18.0,
                                               mass=CAR.mass.mass).close(SingleTrack(CAR)),
        "crossover_around_abs": CrossoverDriver(PATH_X, PATH_Y, gain=0.05, delay=0.12).close(
            ClosedLoop(spin, ABS(CAR))),
        "optimal_preview_full": OptimalPreviewDriver(PATH_X, PATH_Y, vehicle=CAR, speed=20.0, delay=0.1,
                                                     pade_order=5).close(full),
        "preview_around_esc_around_abs": PreviewDriver(PATH_X, PATH_Y, wheelbase=L, lag=0.1).close(
            ClosedLoop(ClosedLoop(spin, ABS(CAR)), ESC(CAR, wheel_spin=True))),
    }


@pytest.mark.compiled_vs_numpy
@pytest.mark.parametrize("name", list(_loops()))
def test_compiled_rhs_and_outputs_equal_the_numpy_ones(name):
    loop = _loops()[name]
    compiled = loop.compiled_rhs()
    assert compiled is not None and compiled.output is not None
    rng = np.random.default_rng(7)
    base = loop.plant
    while isinstance(base, ClosedLoop):
        base = base.plant
    x_car = base.trim(20.0)[0] if isinstance(base, FullVehicle) else base.straight_running(20.0)
    for _ in range(20):
        x = loop.state_vector(dict(zip(base.state_names, x_car)))
        x[:2] += rng.normal(0.0, [2.0, 1.0])  # speed, sideslip
        x[base.index("yaw_rate")] = rng.normal(0.0, 0.5)
        x[base.index("x")] = rng.uniform(0.0, 250.0)
        x[base.index("y")] = rng.normal(0.0, 1.0)
        x[base.index("yaw_angle")] = rng.normal(0.0, 0.2)
        for k, state in enumerate(loop.state_names):
            if "wheel_speed" in state:
                x[k] *= 1.0 + rng.uniform(-0.3, 0.3)  # braking and spinning wheels
            if state.endswith("brake_torque") and k >= base.n_states:
                x[k] = rng.uniform(-100.0, 1500.0)
            if state == "engine_torque_reduction":
                x[k] = rng.uniform(-0.1, 1.1)
            if state.startswith("driver_"):
                x[k] = rng.normal(0.0, 0.05)
        u = loop.input_vector()
        for k, signal in enumerate(loop.input_names):
            if "torque" in signal or "force" in signal or "moment" in signal:
                u[k] = rng.uniform(-200.0, 2000.0)
        if "front_steer_angle" in loop.input_names:
            u[loop.index("front_steer_angle", "inputs")] = rng.normal(0.0, 0.05)
        dxdt = np.empty(loop.n_states)
        compiled.rhs(0.0, x, u, compiled.args, dxdt)
        expected = loop.rhs(0.0, x, u)
        np.testing.assert_allclose(dxdt, expected, rtol=1e-12, atol=1e-12 * np.max(np.abs(expected)))
        y = np.empty(loop.n_outputs)
        compiled.output(0.0, x, u, compiled.args, y)
        expected = loop.output(0.0, x, u)
        np.testing.assert_allclose(y, expected, rtol=1e-12, atol=1e-12 * np.max(np.abs(expected)))


@pytest.mark.compiled_vs_numpy
def test_a_compiled_driver_equals_its_numpy_law():
    # the law is one function (no restatement): compiled (the C library's cos, sin) and numpy (its own
    # kernels, an ulp or two apart on SIMD CPUs) agree to rounding at random points
    for driver in (PreviewDriver(PATH_X, PATH_Y, wheelbase=L, target_speed=18.0, mass=CAR.mass.mass),
                   CrossoverDriver(PATH_X, PATH_Y, gain=0.05, delay=0.12, pade_order=4),
                   OptimalPreviewDriver(PATH_X, PATH_Y, vehicle=CAR, speed=20.0, delay=0.1)):
        compiled = driver.compiled_rhs()
        rng = np.random.default_rng(3)
        for _ in range(50):
            x = rng.normal(0.0, 0.05, driver.n_states)
            u = np.array([rng.uniform(0.0, 250.0), rng.normal(0.0, 2.0), rng.normal(0.0, 0.2), rng.uniform(5.0, 30.0),
                          rng.normal(0.0, 1.0), rng.normal(0.0, 0.3)])[:driver.n_inputs]
            dxdt, y = np.empty(driver.n_states), np.empty(driver.n_outputs)
            compiled.rhs(0.0, x, u, compiled.args, dxdt)
            compiled.output(0.0, x, u, compiled.args, y)
            assert_close_ulps(dxdt, driver.rhs(0.0, x, u), ulps=ONE_CALL_ULPS, rtol=1e-13, what="driver rhs")
            assert_close_ulps(y, driver.output(0.0, x, u), ulps=ONE_CALL_ULPS, rtol=1e-13, what="driver output")


def test_a_driver_evaluates_a_batch_as_single_runs():
    driver = OptimalPreviewDriver(PATH_X, PATH_Y, vehicle=CAR, speed=20.0, delay=0.1)
    rng = np.random.default_rng(5)
    x = rng.normal(0.0, 0.05, (driver.n_states, 4))
    u = np.stack([rng.uniform(0.0, 250.0, 4), rng.normal(0.0, 2.0, 4), rng.normal(0.0, 0.2, 4),
                  rng.uniform(5.0, 30.0, 4), rng.normal(0.0, 1.0, 4), rng.normal(0.0, 0.3, 4)])
    batch = driver.rhs(0.0, x, u)
    for k in range(4):
        np.testing.assert_array_equal(batch[:, k], driver.rhs(0.0, x[:, k], u[:, k]))


def test_loop_without_compiled_parts_falls_back_to_numpy():
    A = np.array([[-1.0]])
    ctrl = LinearModel(A, np.array([[0.0, 1.0]]), np.array([[2.0]]), np.array([[1.0, 0.0]]), states=["integral"],
                       inputs=["front_brake_torque", "yaw_rate"], outputs=["front_brake_torque"])
    loop = ClosedLoop(SingleTrack(CAR, wheel_spin=True), ctrl)
    assert loop.compiled_rhs() is None
    x0 = loop.state_vector(dict(zip(loop.plant.state_names, loop.plant.straight_running(20.0))))
    t = np.linspace(0.0, 0.2, 5)
    r = vehdyn.simulate(loop, t, x0=x0, method="RK45", rtol=1e-4)
    assert "compiled" not in r.method_reason
    with pytest.raises(ParameterError, match="has no compiled rhs"):
        vehdyn.simulate(loop, t, x0=x0, method="RK45", backend="compiled")


