"""ClosedLoop: names kept, linearization against the block formula (with and without feedthrough from a plant
state), batch against single runs, commanded inputs, nesting, errors."""

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


def _controller(feedthrough=0.0, feedback="speed_out"):
    # integral state on the feedback (the plant output "speed_out" or the plant state "velocity"); the demand
    # "force" passes through
    A = np.array([[-1.0]])
    B = np.array([[0.0, 2.0]])
    C = np.array([[-3.0]])
    D = np.array([[1.0, feedthrough]])
    return LinearModel(A, B, C, D, states=["integral"], inputs=["force", feedback], outputs=["force"])


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
    with pytest.raises(ParameterError, match=r"algebraic") as info:
        ClosedLoop(_plant(), _controller(feedthrough=0.5))
    assert "speed_out" in str(info.value) and info.value.key == "controller"


def test_feedthrough_from_a_plant_state_is_allowed_and_linearizes_to_the_block_formula():
    # a state does not depend on the input at the same instant: u_force = C_c x_c + D_d force + D_v velocity
    plant, ctrl = _plant(), _controller(feedthrough=0.5, feedback="velocity")
    loop = ClosedLoop(plant, ctrl)
    lin = loop.linearize()
    Ap, Bp = plant.A, plant.B
    S = np.array([[0.0, 1.0]])  # the plant state velocity
    A = np.block([[Ap + Bp[:, :1] @ (ctrl.D[:, 1:] @ S), Bp[:, :1] @ ctrl.C], [ctrl.B[:, 1:] @ S, ctrl.A]])
    B = np.block([[Bp[:, :1] * ctrl.D[0, 0], Bp[:, 1:]], [np.zeros((1, 2))]])
    np.testing.assert_allclose(lin.A, A, atol=1e-7)
    np.testing.assert_allclose(lin.B, B, atol=1e-7)
    # the command output carries the feedthrough too
    y = loop.output(0.0, np.array([0.0, 2.0, 1.0]), np.array([3.0, 0.0]))
    assert y[-1] == pytest.approx(-3.0 * 1.0 + 1.0 * 3.0 + 0.5 * 2.0, rel=1e-15)


def test_an_input_the_controller_commands_and_does_not_read_leaves_the_loop():
    plant = _plant()
    ctrl = LinearModel(np.array([[-1.0]]), np.array([[1.0]]), np.array([[2.0]]), np.zeros((1, 1)),
                       states=["integral"], inputs=["position"], outputs=["force"])
    loop = ClosedLoop(plant, ctrl)
    assert loop.input_names == ("wind",)
    t = np.linspace(0.0, 2.0, 21)
    r = vehdyn.simulate(loop, t, {"wind": 1.0}, x0=[0.1, 0.0, 0.0], method="RK45", rtol=1e-10, atol=1e-12)
    # the same loop written out: force = 2 integral, integral' = -integral + position
    A = np.array([[0.0, 1.0, 0.0], [-4.0, -0.4, 2.0], [1.0, 0.0, -1.0]])
    B = np.array([[0.0], [0.5], [0.0]])
    direct = vehdyn.simulate(LinearModel(A, B, np.eye(3), np.zeros((3, 1)), states=["p", "v", "i"], inputs=["w"]),
                             t, {"w": 1.0}, x0=[0.1, 0.0, 0.0], method="exact")
    np.testing.assert_allclose(r.states, direct.states, atol=1e-9)
    with pytest.raises(ParameterError, match="force"):
        vehdyn.simulate(loop, t, {"force": 1.0}, method="RK45")


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


def test_a_driver_around_esc_around_abs_around_the_car_keeps_every_name():
    from vehdyn.driver import PreviewDriver

    car = vehdyn.load_vehicle("sedan")
    plant = SingleTrack(car, wheel_spin=True)
    inner = ClosedLoop(ClosedLoop(plant, ABS(car)), ESC(car, wheel_spin=True))
    path_x = np.linspace(-10.0, 300.0, 50)
    loop = PreviewDriver(path_x, 0 * path_x, wheelbase=car.geometry.wheelbase).close(inner)
    assert loop.state_names == inner.state_names + ("driver_steer_angle",)
    assert loop.input_names == tuple(n for n in plant.input_names if n != "front_steer_angle")
    assert loop.output_names[-1] == "front_steer_angle_after_preview_driver"
    assert loop.output_names[:-1] == inner.output_names
    # the ESC reads the driver's steer as its demand: its reference yaw rate follows the driver's state
    x = loop.state_vector(dict(zip(plant.state_names, plant.straight_running(20.0))), driver_steer_angle=0.05)
    y = loop.output(0.0, x, loop.input_vector())
    assert y[-1] == 0.05
    rates = loop.rhs(0.0, x, loop.input_vector())
    esc_rates = rates[[loop.index(f"{w}_esc_brake_torque") for w in ("front_left", "front_right", "rear_left",
                                                                      "rear_right")]]
    assert np.max(esc_rates) > 0  # 0.05 rad of steer and no yaw rate: understeer, the inner rear wheel is braked
