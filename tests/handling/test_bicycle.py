"""LinearBicycle: matrices against the textbook's [beta, r] form, signs, simulation, tire lag, errors."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import vehdyn
from vehdyn.handling import BicycleParameters, LinearBicycle, bicycle_parameters, steady_state_gains

ABE = dict(mass=1500.0, yaw_inertia=2500.0, a=1.1, b=1.6, front_cornering_stiffness=110e3,
           rear_cornering_stiffness=120e3)


def textbook_beta_r(m, iz, a, b, cf, cr, u):
    """A, B of the [beta, r] model as printed by Abe (2009) eq. 3.11-3.12 with 2K = axle C.

    Written in Abe's (ISO, left-positive) form; the ratios are convention-independent because
    beta, r and delta all flip together.
    """
    A = np.array([[-(cf + cr) / (m * u), -1.0 - (a * cf - b * cr) / (m * u**2)],
                  [-(a * cf - b * cr) / iz, -(a**2 * cf + b**2 * cr) / (iz * u)]])
    B = np.array([[cf / (m * u), cr / (m * u)], [a * cf / iz, -b * cr / iz]])
    return A, B


@pytest.mark.parametrize("speed", [5.0, 20.0, 40.0])
def test_matrices_equal_textbook_form_after_v_equals_u_beta(speed):
    car = LinearBicycle.from_parameters(**ABE, speed=speed)
    A_tb, B_tb = textbook_beta_r(*ABE.values(), speed)
    T = np.diag([speed, 1.0])  # x = [v, r] = T [beta, r]
    np.testing.assert_allclose(car.A, T @ A_tb @ np.linalg.inv(T), rtol=1e-13, atol=1e-12)
    np.testing.assert_allclose(car.B, T @ B_tb, rtol=1e-13)
    assert car.state_names == ("lateral_velocity", "yaw_rate")
    assert car.input_names == ("front_steer_angle", "rear_steer_angle")
    assert isinstance(car, vehdyn.LinearModel)


def test_sae_signs_positive_steer_turns_right():
    car = LinearBicycle(vehdyn.load_vehicle("sedan"), 20.0)
    gain = car.dc_gain()[:, 0]
    for name in ("yaw_rate", "lateral_acceleration", "path_curvature", "front_lateral_force", "rear_lateral_force"):
        assert gain[car.index(name, "outputs")] > 0, name
    # initial response: the front axle pushes right at once and the yaw acceleration is positive
    dx = car.B[:, 0]
    assert dx[0] > 0 and dx[1] > 0
    # front slip angle goes negative (SAE: the contact point slides to the left of the wheel plane)
    assert car.D[car.index("front_slip_angle", "outputs"), 0] == -1.0


def test_outputs_are_consistent_with_the_states():
    car = LinearBicycle.from_parameters(**ABE, speed=25.0)
    rng = np.random.default_rng(1)
    x = rng.normal(size=2) * [0.5, 0.2]
    u = rng.normal(size=2) * 0.02
    y = dict(zip(car.output_names, car.output(0.0, x, u)))
    v, r = x
    dv = (car.A @ x + car.B @ u)[0]
    assert y["lateral_acceleration"] == pytest.approx(dv + 25.0 * r, rel=1e-12)
    assert y["sideslip_angle"] == pytest.approx(v / 25.0, rel=1e-12)
    assert y["path_curvature"] == pytest.approx(y["lateral_acceleration"] / 25.0**2, rel=1e-12)
    assert y["front_slip_angle"] == pytest.approx((v + 1.1 * r) / 25.0 - u[0], rel=1e-12)
    assert y["rear_slip_angle"] == pytest.approx((v - 1.6 * r) / 25.0 - u[1], rel=1e-12)
    # Newton: m a_y = F_f + F_r
    assert 1500.0 * y["lateral_acceleration"] == pytest.approx(y["front_lateral_force"] + y["rear_lateral_force"],
                                                               rel=1e-12)


@pytest.mark.parametrize("method", ["exact", "RK45"])
def test_step_steer_steady_state_equals_algebraic_gains(method):
    """Issue 5 item 6: the steady state reached by simulation equals the algebraic gains (<= 1e-6)."""
    car = LinearBicycle(vehdyn.load_vehicle("compact"), 25.0)
    delta = np.deg2rad(1.0)
    t = np.linspace(0.0, 12.0, 1201)
    res = vehdyn.simulate(car, t, {"front_steer_angle": delta}, method=method, rtol=1e-10, atol=1e-12)
    gains = steady_state_gains(car)
    for name in ("yaw_rate", "lateral_acceleration", "sideslip_angle", "path_curvature"):
        expected = getattr(gains, name) * delta
        assert res[name][-1] == pytest.approx(expected, rel=1e-6), name


@pytest.mark.parametrize("method", ["RK45", "rk4"])
def test_sine_steer_response_equals_its_closed_form(method):
    # x' = A x + B a sin(w t), x(0) = 0: x = x_p(t) - e^(A t) x_p(0) with the steady-state harmonic
    # x_p(t) = Im[(j w I - A)^-1 B a e^(j w t)]; the sine_steer evaluated at every stage on a
    # coarse grid (sampled and interpolated it was 3 % off)
    from scipy.linalg import expm

    from vehdyn.procedures import sine_steer

    car = LinearBicycle(vehdyn.load_vehicle("sedan"), 25.0)
    amplitude, omega = np.radians(2.0), 2 * np.pi * 0.5
    t = np.linspace(0.0, 3.0, 16)
    harmonic = np.linalg.solve(1j * omega * np.eye(2) - car.A, car.B[:, 0] * amplitude)
    x_p = np.imag(harmonic[:, None] * np.exp(1j * omega * t))
    exact = x_p - np.stack([expm(car.A * tk) @ x_p[:, 0] for tk in t], axis=1)
    options = {"rtol": 1e-10, "atol": 1e-12} if method == "RK45" else {"substeps": 40}
    result = vehdyn.simulate(car, t, {"front_steer_angle": sine_steer(amplitude, 0.5)}, method=method, **options)
    assert np.max(np.abs(result.states - exact)) < 1e-8 * np.max(np.abs(exact))


def test_vehicle_parameters_are_mapped():
    sedan = vehdyn.load_vehicle("sedan")
    p = bicycle_parameters(LinearBicycle(sedan, 10.0))
    assert p.mass == sedan.mass.mass
    assert p.yaw_inertia == sedan.mass.yaw_inertia
    assert p.a == sedan.geometry.cg_to_front_axle and p.b == sedan.geometry.cg_to_rear_axle
    assert p.front_cornering_stiffness == sedan.tires.front_cornering_stiffness
    assert p.rear_cornering_stiffness == sedan.tires.rear_cornering_stiffness


def test_round_trip_through_python_control_and_linearize():
    import control as ct

    car = LinearBicycle(vehdyn.load_vehicle("van"), 30.0, tire_lag=True)
    sys = car.to_control()
    assert list(sys.state_labels) == list(car.state_names)
    back = vehdyn.LinearModel.from_control(sys)
    np.testing.assert_array_equal(back.A, car.A)
    np.testing.assert_array_equal(back.D, car.D)
    np.testing.assert_allclose(ct.dcgain(sys), car.dc_gain(), rtol=1e-10)
    lin = car.linearize()
    np.testing.assert_array_equal(lin.A, car.A)
    np.testing.assert_array_equal(lin.B, car.B)


def _complex_stiffness_response(p, u, omega, sigma_f, sigma_r):
    """Yaw-rate response of the 2-DOF model whose axle stiffnesses are C / (1 + j w sigma / u).

    The relaxation-length law turns a stiffness into this first-order complex stiffness
    (Pacejka 2012, sec. 7.1.2), an independent route to the model with lag states.
    """
    out = []
    for w in omega:
        cf = p.front_cornering_stiffness / (1 + 1j * w * sigma_f / u)
        cr = p.rear_cornering_stiffness / (1 + 1j * w * sigma_r / u)
        A, B = textbook_beta_r(p.mass, p.yaw_inertia, p.a, p.b, cf, cr, u)
        x = np.linalg.solve(1j * w * np.eye(2) - A, B[:, 0])
        out.append(x[1])
    return np.array(out)


def test_tire_lag_equals_complex_cornering_stiffness():
    sedan = vehdyn.load_vehicle("sedan")
    car = LinearBicycle(sedan, 15.0, tire_lag=True)
    assert car.state_names == ("lateral_velocity", "yaw_rate", "front_transient_slip_angle",
                               "rear_transient_slip_angle")
    assert "tire_lag" in car.phenomena
    omega = np.logspace(-1, 2, 25)
    fr = car.frequency_response(omega, outputs=["yaw_rate"], inputs=["front_steer_angle"])
    expected = _complex_stiffness_response(car.bicycle_parameters, 15.0, omega,
                                           sedan.tires.front_relaxation_length, sedan.tires.rear_relaxation_length)
    np.testing.assert_allclose(fr["yaw_rate", "front_steer_angle"], expected, rtol=1e-10)
    # the lag does not change the steady state
    np.testing.assert_allclose(car.dc_gain()[:, 0], LinearBicycle(sedan, 15.0).dc_gain()[:, 0], rtol=1e-10)


def test_tire_lag_on_one_axle_only():
    car = LinearBicycle.from_parameters(**ABE, speed=20.0, rear_relaxation_length=0.5)
    assert car.state_names == ("lateral_velocity", "yaw_rate", "rear_transient_slip_angle")
    rear = np.linalg.eigvals(car.A)
    assert rear.size == 3 and np.all(rear.real < 0)


def test_at_speed_keeps_the_parameters():
    car = LinearBicycle.from_parameters(**ABE, speed=10.0)
    fast = car.at_speed(30.0)
    np.testing.assert_array_equal(fast.A, LinearBicycle.from_parameters(**ABE, speed=30.0).A)  # same code, inputs


@pytest.mark.parametrize("speed", [0.0, -5.0, np.nan, np.inf])
def test_bad_speed_raises(speed):
    with pytest.raises(vehdyn.ParameterError, match="speed"):
        LinearBicycle.from_parameters(**ABE, speed=speed)


@pytest.mark.parametrize("field,value", [("mass", 0.0), ("yaw_inertia", -1.0), ("a", 0.0),
                                         ("front_cornering_stiffness", -80e3), ("rear_cornering_stiffness", np.nan)])
def test_bad_parameter_raises_naming_it(field, value):
    kwargs = dict(ABE, speed=20.0)
    kwargs[field] = value
    with pytest.raises(vehdyn.ParameterError) as err:
        LinearBicycle.from_parameters(**kwargs)
    assert err.value.key == field


def test_negative_relaxation_length_and_wrong_vehicle_raise():
    with pytest.raises(vehdyn.ParameterError, match="front_relaxation_length"):
        LinearBicycle.from_parameters(**ABE, speed=20.0, front_relaxation_length=-0.1)
    with pytest.raises(vehdyn.ParameterError, match="Vehicle"):
        LinearBicycle("sedan", 20.0)


positive = st.floats(min_value=0.5, max_value=2.0)


@settings(max_examples=40, deadline=None)
@given(positive, positive, positive, positive, positive, st.floats(min_value=2.0, max_value=60.0))
def test_dc_gain_equals_closed_form_gains(fm, fiz, fa, fcf, fcr, speed):
    """Property: -C A^-1 B of the state-space model equals the closed-form gains of steady_state."""
    p = BicycleParameters(mass=1400 * fm, yaw_inertia=2200 * fiz, a=1.2 * fa, b=1.4, front_cornering_stiffness=9e4 * fcf,
                          rear_cornering_stiffness=9e4 * fcr)
    car = LinearBicycle(p, speed)
    K = p.understeer_gradient
    if K < 0 and abs(speed - np.sqrt(-p.wheelbase / K)) < 0.05 * speed:
        return  # next to the critical speed the gains are singular
    gains = steady_state_gains(p, speed)
    dc = car.dc_gain()
    for name in ("yaw_rate", "lateral_acceleration", "sideslip_angle", "path_curvature"):
        assert dc[car.index(name, "outputs"), 0] == pytest.approx(float(getattr(gains, name)), rel=1e-8, abs=1e-12)
