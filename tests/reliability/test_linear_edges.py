"""Edges of the linear models: the linear handling models' speed, and dc_gain with integrators,
against closed forms, python-control and limits of the transfer function."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import vehdyn
from vehdyn import LinearModel, ParameterError
from vehdyn.interconnect import connect_in_series
from vehdyn.handling import LateralYawRoll, LinearBicycle, steady_state_gains
from vehdyn.handling.bicycle import LINEAR_MIN_SPEED, BicycleParameters

CAR = BicycleParameters(mass=1500, yaw_inertia=2500, a=1.1, b=1.6, front_cornering_stiffness=110e3,
                        rear_cornering_stiffness=120e3)


# --------------------------------------------------------------------------- speed of the linear handling models
@pytest.mark.parametrize("cls, vehicle", [(LinearBicycle, CAR), (LateralYawRoll, vehdyn.load_vehicle("sedan"))])
def test_array_of_speeds_is_refused_naming_speed_and_its_value(cls, vehicle):
    speeds = np.array([10.0, 20.0])
    with pytest.raises(ParameterError, match=r"speed must be one number.*array\(\[10\., 20\.\]\).*at_speed") as info:
        cls(vehicle, speeds)
    assert info.value.key == "speed"
    # one speed in an array of one is that speed
    np.testing.assert_array_equal(cls(vehicle, np.array([15.0])).A, cls(vehicle, 15.0).A)  # the same float, code


@pytest.mark.parametrize("cls, vehicle", [(LinearBicycle, CAR), (LateralYawRoll, vehdyn.load_vehicle("sedan"))])
@pytest.mark.parametrize("speed", [1e-9, 1e-6, 0.999 * LINEAR_MIN_SPEED, "fast", None])
def test_speed_below_the_minimum_or_not_a_number_is_refused(cls, vehicle, speed):
    with pytest.raises(ParameterError, match="speed") as info:
        cls(vehicle, speed)
    assert info.value.key == "speed"


@settings(max_examples=60, deadline=None)
@given(st.floats(min_value=np.log10(LINEAR_MIN_SPEED), max_value=np.log10(60.0)))
def test_path_curvature_gain_is_the_closed_form_from_the_minimum_speed_up(log_speed):
    """-C A^-1 B + D of path_curvature against 1 / (L + K u^2) (Gillespie eq. 6-11): the steady
    curvature per steer angle, down to LINEAR_MIN_SPEED (relative rounding ~ eps (C_f + C_r) b / (m u^2))."""
    u = 10.0**log_speed
    car = LinearBicycle(CAR, u)
    closed = steady_state_gains(CAR, u).path_curvature
    gain = car.dc_gain()[car.index("path_curvature", "outputs"), 0]
    assert gain == pytest.approx(float(closed), rel=1e-8)
    # the same through a time simulation to steady state (exact discretization, then C x + D u)
    t = np.array([0.0, 25.0, 50.0])  # the slowest mode (at 60 m/s) has decayed by e^-30
    r = vehdyn.simulate(car, t, inputs={"front_steer_angle": 0.01}, method="exact")
    assert r["path_curvature"][-1] == pytest.approx(0.01 * float(closed), rel=1e-7)


def test_documented_loss_below_the_minimum_speed_is_real():
    """What the minimum guards against: built below it (bypassing the check), the curvature gain
    loses digits as 1/u^2, while r/u from the same model keeps them (conditioning, not a formula)."""
    from vehdyn.handling.bicycle import _state_space

    L, K = CAR.wheelbase, CAR.understeer_gradient
    errors = {}
    for u in (1e-2, 1e-4, 1e-6):
        A, B, C, D, _ = _state_space(CAR, u)
        B, D = B[:, :2], D[:, :2]  # the steer columns (the third is the crosswind input)
        model = LinearModel(A, B, C, D, states=["lateral_velocity", "yaw_rate"], inputs=["df", "dr"],
                            outputs=[s.name for s in LinearBicycle(CAR, 20.0).outputs])
        gain = model.dc_gain()
        closed = 1.0 / (L + K * u**2)
        errors[u] = abs(gain[model.index("path_curvature", "outputs"), 0] / closed - 1)
        assert gain[model.index("yaw_rate", "outputs"), 0] / u == pytest.approx(closed, rel=1e-12)
    assert errors[1e-2] < 1e-8 and errors[1e-6] > 1e-3
    # the documented size, eps (C_f + C_r) b / (m u^2), within a factor of 10
    for u, error in errors.items():
        estimate = np.finfo(float).eps * (CAR.front_cornering_stiffness + CAR.rear_cornering_stiffness) * CAR.b / (
            CAR.mass * u**2)
        assert error < 10 * estimate and (error > estimate / 10 or u == 1e-2)


# --------------------------------------------------------------------------- dc_gain with integrators
def heading():
    return LinearModel([[0.0]], [[1.0]], [[1.0]], states=["yaw_angle"], inputs=["yaw_rate"], outputs=["yaw_angle"])


def test_dc_gain_with_a_heading_integrator_is_inf_there_and_unchanged_elsewhere():
    car = LinearBicycle(CAR, 20.0)
    full = connect_in_series(car, heading())
    dc = full.dc_gain()
    k = full.index("yaw_angle", "outputs")
    # a positive front steer turns right (positive yaw rate): the yaw angle grows without bound, positively
    assert dc[k, 0] == np.inf
    # rear steer turns the other way: -inf
    assert dc[k, 1] == -np.inf
    for name in car.output_names:
        np.testing.assert_allclose(dc[full.index(name, "outputs")], car.dc_gain()[car.index(name, "outputs")],
                                   rtol=1e-10)


def test_dc_gain_of_a_double_integrator_has_the_sign_of_its_step_response():
    for b, sign in ((1.0, 1.0), (-2.0, -1.0)):
        m = LinearModel([[0, 1], [0, 0]], [[0], [b]], states=["position", "position_velocity"], inputs=["force"])
        np.testing.assert_array_equal(m.dc_gain(), [[sign * np.inf], [sign * np.inf]])


def test_dc_gain_matches_python_control_where_python_control_is_defined():
    control = pytest.importorskip("control")
    integrator = LinearModel([[0, 1], [0, -1]], [[0], [1]], [[1, 0]], states=["position", "position_velocity"],
                             inputs=["force"], outputs=["position"])
    assert integrator.dc_gain()[0, 0] == control.ss(integrator.A, integrator.B, integrator.C, integrator.D).dcgain()
    # the velocity of the same system has a finite gain 1 (python-control: nan there)
    velocity = LinearModel(integrator.A, integrator.B, [[0, 1]], states=integrator.states, inputs=integrator.inputs,
                           outputs=["position_velocity"])
    assert velocity.dc_gain()[0, 0] == pytest.approx(1.0, rel=1e-14)


@settings(max_examples=60, deadline=None)
@given(st.integers(1, 4), st.integers(1, 3), st.integers(0, 2**32 - 1), st.sampled_from([0.0, 1.0]))
def test_integrator_of_a_stable_system_property(n, m, seed, through):
    """Random stable (A, B, C, D) plus z' = c.y (an integrator fed by one combination of outputs):
    every output of the stable part keeps its finite gain; z's gain is +-inf with the sign of c.H(0)
    for each input, or finite where c.H(0) = 0 (then lim H(s) for s -> 0, checked at small s)."""
    rng = np.random.default_rng(seed)
    A = -np.diag(rng.uniform(0.5, 5.0, n)) + 0.3 * rng.standard_normal((n, n)) * (n > 1)
    if np.max(np.linalg.eigvals(A).real) > -0.1:
        A -= (np.max(np.linalg.eigvals(A).real) + 0.5) * np.eye(n)
    B, C, D = rng.standard_normal((n, m)), rng.standard_normal((2, n)), rng.standard_normal((2, m))
    plant = LinearModel(A, B, C, D, states=[f"x{i}" for i in range(n)], inputs=[f"u{j}" for j in range(m)],
                        outputs=["y0", "y1"])
    c = np.array([1.0, -0.5]) * through if through else np.zeros(2)
    if through:
        # one input that the integrator does not see: make c.H(0) column 0 exactly zero through D
        h0 = plant.dc_gain()
        D = D.copy()
        D[:, 0] -= h0[:, 0]  # now H(0)[:, 0] = 0 for both outputs
        plant = LinearModel(A, B, C, D, states=plant.states, inputs=plant.inputs, outputs=plant.outputs)
    z = LinearModel([[0.0]], [c if through else [0.0, 1.0]], [[1.0]], states=["z"], inputs=["y0", "y1"],
                    outputs=["z"])
    full = connect_in_series(plant, z)
    dc = full.dc_gain()
    h0 = plant.dc_gain()
    for name in ("y0", "y1"):
        np.testing.assert_allclose(dc[full.index(name, "outputs")], h0[plant.index(name, "outputs")], rtol=1e-9,
                                   atol=1e-12)
    weights = c if through else np.array([0.0, 1.0])
    drive = weights @ h0
    row = dc[full.index("z", "outputs")]
    for j in range(m):
        if abs(drive[j]) > 1e-9:
            assert row[j] == np.copysign(np.inf, drive[j])
        else:
            # no 1/s term: the limit of the transfer function at s -> 0 (at s = 1e-7 j, to first order in s)
            H = full.frequency_response([1e-7], outputs=["z"]).response[0, j, 0]
            assert np.isfinite(row[j]) and row[j] == pytest.approx(H.real, rel=1e-5, abs=1e-6)
