"""ClosedLoop: names kept, linearization against the block formula, batch against single runs, errors."""

import numpy as np
import pytest

import vehdyn
from vehdyn import LinearModel, ParameterError
from vehdyn.chassis import ABS, ESC
from vehdyn.interconnect import ClosedLoop
from vehdyn.handling import SingleTrack


def _plant():
    # two states, inputs force (commanded) and wind (free), outputs position and speed
    A = np.array([[0.0, 1.0], [-4.0, -0.4]])
    B = np.array([[0.0, 0.0], [1.0, 0.5]])
    C = np.array([[1.0, 0.0], [0.0, 1.0]])
    return LinearModel(A, B, C, np.zeros((2, 2)), states=["position", "velocity"], inputs=["force", "wind"],
                       outputs=["position_out", "speed_out"])


def _controller(feedthrough=0.0):
    # integral state on the feedback "speed_out"; the demand "force" passes through
    A = np.array([[-1.0]])
    B = np.array([[0.0, 2.0]])
    C = np.array([[-3.0]])
    D = np.array([[1.0, feedthrough]])
    return LinearModel(A, B, C, D, states=["integral"], inputs=["force", "speed_out"], outputs=["force"])


def test_linearization_equals_block_formula():
    plant, ctrl = _plant(), _controller()
    loop = ClosedLoop(plant, ctrl)
    assert loop.state_names == ("position", "velocity", "integral")
    assert loop.input_names == ("force", "wind")
    assert loop.output_names == ("position_out", "speed_out", "force_after_linear_model")
    lin = loop.linearize()
    # u_force = C_c x_c + D_demand * force ; x_c' = A_c x_c + B_fb * (C_p x_p)
    Ap, Bp, Cp = plant.A, plant.B, plant.C
    A = np.block([[Ap, Bp[:, :1] @ ctrl.C], [ctrl.B[:, 1:] @ Cp[1:2], ctrl.A]])
    B = np.block([[Bp[:, :1] * 1.0, Bp[:, 1:]], [np.zeros((1, 2))]])
    np.testing.assert_allclose(lin.A, A, atol=1e-7)
    np.testing.assert_allclose(lin.B, B, atol=1e-7)


def test_batch_equals_single_runs():
    loop = ClosedLoop(_plant(), _controller())
    t = np.linspace(0.0, 3.0, 61)
    x0 = np.array([[0.1, -0.2], [0.0, 0.3], [0.0, 0.1]])
    batch = vehdyn.simulate(loop, t, {"force": np.sin(t)}, x0=x0, method="RK45", rtol=1e-9, atol=1e-12)
    for k in range(2):
        one = vehdyn.simulate(loop, t, {"force": np.sin(t)}, x0=x0[:, k], method="RK45", rtol=1e-9, atol=1e-12)
        np.testing.assert_allclose(batch["position_out"][:, k], one["position_out"], atol=1e-7)


def test_algebraic_loop_refused():
    with pytest.raises(ParameterError, match="algebraic"):
        ClosedLoop(_plant(), _controller(feedthrough=0.5))


def test_missing_inputs_are_named():
    car = vehdyn.load_vehicle("sedan")
    with pytest.raises(ParameterError, match="front_brake_torque") as info:
        ClosedLoop(SingleTrack(car), ABS(car))  # force mode: no brake torques, no wheel speeds
    assert "front_wheel_speed" in str(info.value)
    with pytest.raises(ParameterError, match="front_longitudinal_force"):
        ClosedLoop(SingleTrack(car, wheel_spin=True), ESC(car))  # ESC built for the force mode
    with pytest.raises(ParameterError, match="plant must be a vehdyn Model"):
        ClosedLoop("car", ESC(car))


def test_nested_loops_keep_every_name():
    car = vehdyn.load_vehicle("sedan")
    inner = ClosedLoop(SingleTrack(car, wheel_spin=True), ABS(car))
    outer = ClosedLoop(inner, ESC(car, wheel_spin=True))
    assert outer.state_names[-4:] == tuple(f"{w}_esc_brake_torque" for w in
                                           ("front_left", "front_right", "rear_left", "rear_right"))
    assert "front_abs_brake_torque" in outer.state_names
    assert outer.input_names == SingleTrack(car, wheel_spin=True).input_names
    # straight running, no demand: an equilibrium of the whole loop (drag aside: zero speed derivative
    # is not expected, so compare the controller states only)
    x = outer.state_vector(dict(zip(inner.plant.state_names, inner.plant.straight_running(20.0))))
    rates = outer.rhs(0.0, x, outer.input_vector())
    controller_rates = rates[inner.plant.n_states:]
    np.testing.assert_allclose(controller_rates, 0.0, atol=1e-9)


@pytest.mark.parametrize("controller", [ABS, ESC])
def test_controllers_need_a_vehicle(controller):
    with pytest.raises(ParameterError, match="vehicle must be a vehdyn Vehicle"):
        controller("sedan")


def test_linearized_esc_loop_inside_its_deadband_is_the_car():
    car = vehdyn.load_vehicle("sedan")
    plant = SingleTrack(car)
    loop = ClosedLoop(plant, ESC(car))
    x0 = loop.state_vector(dict(zip(plant.state_names, plant.straight_running(20.0))))
    lin = loop.linearize(x0)
    alone = plant.linearize(plant.straight_running(20.0))
    n = plant.n_states
    assert lin.state_names == loop.state_names and lin.output_names == loop.output_names
    np.testing.assert_allclose(lin.A[:n, :n], alone.A, rtol=1e-5, atol=1e-6)
    # the hydraulic channels are first-order lags of -1 / tau, decoupled from the car at this point
    np.testing.assert_allclose(np.diag(lin.A)[n:], -1.0 / 0.1, rtol=1e-6)
    np.testing.assert_allclose(lin.A[n:, :n], 0.0, atol=1e-9)
