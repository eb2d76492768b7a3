"""LiftOff: the linear ride models with unilateral tire contact (the wheel lifts off and lands)."""

import numpy as np
import pytest
from scipy.linalg import expm

import vehdyn
from vehdyn import ParameterError
from vehdyn.ride import BouncePitch, FullCar, LateralSlip, LiftOff, LongitudinalSlip, QuarterCar
from vehdyn.units import GRAVITY

_QC = dict(sprung_mass=300.0, unsprung_mass=35.0, spring_rate=20e3, damping=1500.0, tire_stiffness=180e3,
           tire_damping=50.0)


@pytest.fixture(scope="module")
def sedan():
    return vehdyn.load_vehicle("sedan")


def test_static_tire_loads_are_the_weights_they_carry(sedan):
    """Quarter car: (m_s + m_u) g; full car: m_s g b / (2 L) + m_u g at a front wheel (statics)."""
    qc = LiftOff(QuarterCar.from_parameters(**_QC))
    assert qc.static_tire_load[0] == pytest.approx((300.0 + 35.0) * GRAVITY, rel=1e-12)
    car = FullCar(sedan, cg_heights=True)
    p = car.parameters
    loads = LiftOff(car).static_tire_load
    front = p.mass * GRAVITY * p.b / (2 * (p.a + p.b)) + p.front_unsprung_mass * GRAVITY
    rear = p.mass * GRAVITY * p.a / (2 * (p.a + p.b)) + p.rear_unsprung_mass * GRAVITY
    np.testing.assert_allclose(loads, [front, front, rear, rear], rtol=1e-10)


def test_without_lift_it_is_the_linear_full_car(sedan):
    """A road that never unloads a tire: the same solver on LiftOff and on FullCar gives the same
    result to round-off (the correction force is exactly 0), here a 5 mm, 1.5 Hz heave-and-roll road."""
    car = FullCar(sedan)
    model = LiftOff(car)
    t = np.linspace(0.0, 0.5, 51)
    w = 2 * np.pi * 1.5
    inputs = {}
    for sfx, phase in zip(("_front_left", "_front_right", "_rear_left", "_rear_right"), (0.0, 0.5, 1.0, 1.5)):
        inputs[f"road_displacement{sfx}"] = 0.005 * np.sin(w * t + phase)
        inputs[f"road_velocity{sfx}"] = 0.005 * w * np.cos(w * t + phase)
    options = dict(method="RK45", rtol=1e-9, atol=1e-12, backend="numpy")
    lifted = vehdyn.simulate(model, t, inputs, **options)
    linear = vehdyn.simulate(car, t, inputs, **options)
    assert np.max(np.abs(lifted.outputs - linear.outputs)) <= 1e-9 * np.max(np.abs(linear.outputs))
    assert np.all(sedan.static_axle_loads(GRAVITY)[1] / 2 + lifted["dynamic_tire_load_rear_left"] > 0)


def test_wheel_dropping_off_a_step_flies_as_the_free_wheel_closed_form():
    """The road drops 0.1 m under a quarter car at rest: the tire unloads at once and the wheel
    flies under its weight and the suspension until it meets the road again. While airborne the
    motion is that of the quarter car without its tire under the constant force -F_s on the wheel
    (weight and static preloads in the deviation coordinates), solved by the matrix exponential of
    the augmented system; then the wheel lands (the load comes back)."""
    qc = QuarterCar.from_parameters(**_QC)
    model = LiftOff(qc)
    t = np.linspace(0.0, 0.3, 301)
    inputs = {"road_displacement": np.full(t.size, -0.1), "road_velocity": 0.0}
    res = vehdyn.simulate(model, t, inputs, method="RK45", rtol=1e-10, atol=1e-12, backend="numpy")
    # free flight: M q'' + C_s q' + K_s q = [0, -F_s], q = (z_s, z_u)
    ms, mu, k, c = 300.0, 35.0, 20e3, 1500.0
    M = np.diag([ms, mu])
    K = np.array([[k, -k], [-k, k]])
    C = np.array([[c, -c], [-c, c]])
    f = np.array([0.0, -model.static_tire_load[0]])
    Minv = np.linalg.inv(M)
    A = np.zeros((5, 5))
    A[:2, 2:4] = np.eye(2)
    A[2:4, :2], A[2:4, 2:4], A[2:4, 4] = -Minv @ K, -Minv @ C, Minv @ f
    flight = np.array([expm(A * tk) @ np.array([0, 0, 0, 0, 1.0]) for tk in t])
    # the wheel is airborne while its tire is stretched beyond its static compression
    airborne = (-0.1 - flight[:, 1]) + model.static_tire_load[0] / _QC["tire_stiffness"] < 0
    n = int(np.argmin(airborne))  # first sample back on the road
    assert 10 < n < 300
    z_u = res["unsprung_displacement"][:n]
    np.testing.assert_allclose(z_u, flight[:n, 1], atol=1e-8 * 0.1)
    np.testing.assert_allclose(res["sprung_displacement"][:n], flight[:n, 0], atol=1e-8 * 0.1)
    load = model.static_tire_load[0] + res["dynamic_tire_load"]
    assert np.all(np.abs(load[1:n]) < 1e-9 * model.static_tire_load[0]) and np.max(load[n:]) > 0  # off, landed
    # at the start the wheel falls at (F_s - 0) / m_u = (m_s + m_u) g / m_u
    assert res["unsprung_acceleration"][0] == pytest.approx(-(ms + mu) * GRAVITY / mu, rel=1e-12)


@pytest.mark.compiled_vs_numpy
def test_compiled_rhs_is_the_numpy_rhs(sedan):
    pytest.importorskip("numba")
    model = LiftOff(FullCar(sedan, cg_heights=True))
    compiled = model.compiled_rhs()
    rng = np.random.default_rng(1)
    for scale in (1e-3, 5e-2):  # in contact, and wheels off the road
        x, u = rng.normal(0, scale, model.n_states), rng.normal(0, scale, model.n_inputs)
        out = np.empty(model.n_states)
        compiled.rhs(0.0, x, u, compiled.args, out)
        np.testing.assert_allclose(out, model.rhs(0.0, x, u), rtol=1e-12, atol=1e-12 * np.max(np.abs(out)))


def test_full_car_cg_heights_are_the_full_vehicle_s_couplings(sedan):
    """With the CG heights, FullCar's pitch stiffness and inertia carry gravity's moment, the
    unsprung masses' and the wheel spins' share; without them it is the FullCar of before."""
    plain, high = FullCar(sedan), FullCar(sedan, cg_heights=True)
    m, h = sedan.mass, sedan.mass.sprung_cg_height
    h_u = (m.mass * m.cg_height - m.sprung_mass * h) / m.unsprung_mass
    assert 0 < h_u < h
    assert high.stiffness_matrix[1, 1] == pytest.approx(plain.stiffness_matrix[1, 1] - m.sprung_mass * GRAVITY * h)
    extra = m.unsprung_mass * (h - h_u) ** 2 + 4 * sedan.tires.wheel_spin_inertia * (h / sedan.tires.rolling_radius) ** 2
    assert high.mass_matrix[1, 1] == pytest.approx(plain.mass_matrix[1, 1] + extra)
    assert FullCar.from_parameters(**{**plain.parameters.to_dict()}).A == pytest.approx(plain.A)


def test_bad_inputs_name_the_parameter(sedan):
    with pytest.raises(ParameterError, match="linear ride model") as info:
        LiftOff(vehdyn.handling.LinearBicycle(sedan, 20.0))
    assert info.value.key == "model"
    with pytest.raises(ParameterError, match="unsprung mass at every corner"):
        LiftOff(BouncePitch.from_parameters(mass=1000.0, pitch_inertia=1500.0, a=1.2, b=1.4, front_spring_rate=2e4,
                                            rear_spring_rate=2e4))
    with pytest.raises(ParameterError, match="passive"):
        LiftOff(QuarterCar.from_parameters(**_QC, actuator=True))
    for bad in (float("nan"), -9.81, 0.0, True, "9.81"):
        with pytest.raises(ParameterError, match="gravity") as info:
            LiftOff(QuarterCar.from_parameters(**_QC), gravity=bad)
        assert info.value.key == "gravity"
    with pytest.raises(ParameterError, match="sprung_cg_height") as info:
        FullCar(sedan).replace(sprung_cg_height=10.0)
    assert info.value.key == "sprung_cg_height"


def _slip(speed=15.0):
    return LateralSlip(speed=speed, yaw_inertia=1800.0, front_cornering_stiffness=4e4,
                       rear_cornering_stiffness=3.5e4, front_load_sensitivity=5.0, rear_load_sensitivity=5.0,
                       front_relaxation_length=0.45, rear_relaxation_length=0.4)


def test_lateral_slip_stays_out_of_a_road_without_roll(sedan):
    """Equal tracks excite no roll: v, r and the tire deflections stay 0 (to round-off), and the
    outputs are those of the model without the option (the same solver)."""
    car = FullCar(sedan, cg_heights=True)
    plain, lateral = LiftOff(car), LiftOff(car, lateral=_slip())
    t = np.linspace(0.0, 0.4, 41)
    w = 2 * np.pi * 8.0
    inputs = {}
    for sfx, delay in zip(("_front_left", "_front_right", "_rear_left", "_rear_right"), (0.0, 0.0, 0.17, 0.17)):
        inputs[f"road_displacement{sfx}"] = 0.02 * np.sin(w * (t - delay)) * (t > delay)  # lifts the wheels
        inputs[f"road_velocity{sfx}"] = 0.02 * w * np.cos(w * (t - delay)) * (t > delay)
    options = dict(method="RK45", rtol=1e-9, atol=1e-12, backend="numpy")
    a = vehdyn.simulate(plain, t, inputs, **options)
    b = vehdyn.simulate(lateral, t, inputs, **options)
    assert np.min(plain.static_tire_load[0] + a["dynamic_tire_load_front_left"]) < 1e-9  # a wheel lifted
    assert np.max(np.abs(b.states[plain.n_states:])) < 1e-15  # round-off of the left-right sums
    # the same up to the integration error (rtol 1e-9; the extra states' round-off changes the steps)
    np.testing.assert_allclose(b.outputs[:plain.n_outputs], a.outputs, rtol=0, atol=1e-6 * np.max(np.abs(a.outputs)))


def test_lateral_slip_holds_the_contact_points_steady_state(sedan):
    """A steady roll rate p with the body otherwise at rest: each tire's deflection settles at
    sigma V / u with V = -h p (first-order relaxation), the force at -C V / u (the tire law's
    steady slip), and the roll moment of the forces is -h sum F (closed forms)."""
    car = FullCar(sedan, cg_heights=True)
    slip = _slip()
    model = LiftOff(car, lateral=slip)
    x = np.zeros(model.n_states)
    p_rate, h, u = 0.1, sedan.mass.sprung_cg_height, slip.speed
    x[model.index("roll_rate")] = p_rate
    sigma = np.array([0.45, 0.45, 0.4, 0.4])
    stiffness = np.array([4e4, 4e4, 3.5e4, 3.5e4])
    deflection = sigma * (-h * p_rate) / u
    x[model.n_states - 4:] = deflection
    d = model.rhs(0.0, x, np.zeros(model.n_inputs))
    np.testing.assert_allclose(d[model.n_states - 4:], 0.0, atol=1e-15)  # settled
    y = dict(zip(model.output_names, model.output(0.0, x, np.zeros(model.n_inputs))))
    forces = np.array([y[f"lateral_force{s}"] for s in ("_front_left", "_front_right", "_rear_left", "_rear_right")])
    np.testing.assert_allclose(forces, -stiffness * (-h * p_rate) / u, rtol=1e-12)
    # lateral and roll equations: [m, -m_c; -m_c, I] [a_v; p'] = [sum F; M_susp - h sum F], M_susp the
    # suspension dampers' roll moment (the linear full car's roll equation)
    m_u = car.parameters.front_unsprung_mass, car.parameters.rear_unsprung_mass
    m = car.parameters.mass + 2 * sum(m_u)
    lever = car.parameters.sprung_cg_height - car.parameters.unsprung_cg_height
    m_c = 2 * sum(m_u) * lever
    inertia = car.mass_matrix[2, 2]
    n = car.n_states
    suspension = inertia * (car.A @ x[:n])[car.index("roll_rate")]
    assert suspension < 0  # the dampers resist the roll rate
    a_v, roll = np.linalg.solve([[m, -m_c], [-m_c, inertia]], [forces.sum(), suspension - h * forces.sum()])
    assert d[model.index("roll_rate")] == pytest.approx(roll, rel=1e-12)
    assert d[model.index("lateral_velocity")] == pytest.approx(a_v, rel=1e-12)
    x_i = np.array([car.parameters.a] * 2 + [-car.parameters.b] * 2)
    assert d[model.index("yaw_rate")] == pytest.approx(np.sum(x_i * forces) / 1800.0, rel=1e-12)


@pytest.mark.compiled_vs_numpy
def test_compiled_rhs_with_both_slips_is_the_numpy_rhs(sedan):
    pytest.importorskip("numba")
    model = LiftOff(FullCar(sedan, cg_heights=True), lateral=_slip(), longitudinal=_spin())
    compiled = model.compiled_rhs()
    rng = np.random.default_rng(2)
    for scale in (1e-3, 5e-2):
        x, u = rng.normal(0, scale, model.n_states), rng.normal(0, scale, model.n_inputs)
        out = np.empty(model.n_states)
        compiled.rhs(0.0, x, u, compiled.args, out)
        np.testing.assert_allclose(out, model.rhs(0.0, x, u), rtol=1e-12, atol=1e-12 * np.max(np.abs(out)))


def test_lateral_slip_bad_inputs(sedan):
    with pytest.raises(ParameterError, match="FullCar") as info:
        LiftOff(QuarterCar.from_parameters(**_QC), lateral=_slip())
    assert info.value.key == "lateral"
    with pytest.raises(ParameterError, match="LateralSlip"):
        LiftOff(FullCar(sedan), lateral={"speed": 10.0})
    with pytest.raises(ParameterError, match="speed"):
        LateralSlip(speed=0.0, yaw_inertia=1.0, front_cornering_stiffness=1.0, rear_cornering_stiffness=1.0,
                    front_relaxation_length=0.4, rear_relaxation_length=0.4)


_CORNERS = ("_front_left", "_front_right", "_rear_left", "_rear_right")


def _spin(speed=15.0, **kw):
    values = dict(speed=speed, rolling_radius=0.31, wheel_spin_inertia=1.2, front_slip_stiffness=8e4,
                  rear_slip_stiffness=7e4, front_load_sensitivity=10.0, rear_load_sensitivity=10.0,
                  front_relaxation_length=0.3, rear_relaxation_length=0.3, rear_drive_torque=60.0,
                  front_rolling_resistance=3e-3, rear_rolling_resistance=3e-3, rear_zero_slip_force=-0.03)
    return LongitudinalSlip(**{**values, **kw})


def test_longitudinal_slip_stays_out_of_a_road_without_pitch(sedan):
    """Without drive torque or rolling resistance and on a road that rolls the body only (left up,
    right down, the same under both axles): no pitch, no slip; the wheels' spin, the fore-aft speed
    and the deflections stay 0 and the outputs are those of the model without the option."""
    car = FullCar(sedan, cg_heights=True)
    plain = LiftOff(car)
    spin = LiftOff(car, longitudinal=_spin(rear_drive_torque=0.0, front_rolling_resistance=0.0,
                                           rear_rolling_resistance=0.0, rear_zero_slip_force=0.0))
    t = np.linspace(0.0, 0.3, 31)
    w = 2 * np.pi * 6.0
    inputs = {}
    for sfx, side in zip(_CORNERS, (1.0, -1.0, 1.0, -1.0)):
        inputs[f"road_displacement{sfx}"] = side * 0.01 * np.sin(w * t)
        inputs[f"road_velocity{sfx}"] = side * 0.01 * w * np.cos(w * t)
    options = dict(method="RK45", rtol=1e-9, atol=1e-12, backend="numpy")
    a = vehdyn.simulate(plain, t, inputs, **options)
    b = vehdyn.simulate(spin, t, inputs, **options)
    assert np.max(np.abs(a["roll_angle"])) > 1e-3
    assert np.max(np.abs(b.states[plain.n_states:])) < 1e-15
    assert np.max(np.abs(b.outputs[plain.n_outputs:])) < 1e-9  # the forces: C * round-off
    np.testing.assert_allclose(b.outputs[:plain.n_outputs], a.outputs, rtol=0, atol=1e-6 * np.max(np.abs(a.outputs)))


def test_longitudinal_slip_steady_rolling_and_airborne_spin_up(sedan):
    """Steady rolling: at the zero state the drive torque T_d holds F_x0 = (T_d - r F_s) / R_e
    against the rolling resistance (whatever the law's force at zero slip) and every derivative is
    0. A wheel lifted off the road carries no load and no force: it spins up at T_d / I_w exactly
    (closed form omega(t) = T_d t / I_w)."""
    car = FullCar(sedan, cg_heights=True)
    slip = _spin()
    model = LiftOff(car, longitudinal=slip)
    zero_x, zero_u = np.zeros(model.n_states), np.zeros(model.n_inputs)
    np.testing.assert_allclose(model.rhs(0.0, zero_x, zero_u), 0.0, atol=1e-12)
    y = dict(zip(model.output_names, model.output(0.0, zero_x, zero_u)))
    drive = np.array([0.0, 0.0, 60.0, 60.0])
    expected = (drive - 3e-3 * model.static_tire_load) / 0.31
    np.testing.assert_allclose([y[f"longitudinal_force{s}"] for s in _CORNERS], expected, rtol=1e-12)
    # the rear left wheel starts 6 cm up: off the road until it falls back
    x0 = np.zeros(model.n_states)
    x0[model.index("unsprung_displacement_rear_left")] = 0.06
    t = np.linspace(0.0, 0.04, 21)
    res = vehdyn.simulate(model, t, {}, x0=x0, method="RK45", rtol=1e-10, atol=1e-12, backend="numpy")
    airborne = np.abs(res["dynamic_tire_load_rear_left"] + model.static_tire_load[2]) < 1e-9 * model.static_tire_load[2]
    assert airborne[:10].all()
    np.testing.assert_allclose(res["wheel_speed_change_rear_left"][airborne], 60.0 * t[airborne] / 1.2,
                               rtol=1e-8, atol=1e-12)
    assert np.all(res["longitudinal_force_rear_left"][airborne] == 0.0)


def test_longitudinal_slip_bad_inputs(sedan):
    with pytest.raises(ParameterError, match="FullCar") as info:
        LiftOff(QuarterCar.from_parameters(**_QC), longitudinal=_spin())
    assert info.value.key == "longitudinal"
    with pytest.raises(ParameterError, match="LongitudinalSlip"):
        LiftOff(FullCar(sedan), longitudinal={"speed": 10.0})
    with pytest.raises(ParameterError, match="differs") as info:
        LiftOff(FullCar(sedan), lateral=_slip(15.0), longitudinal=_spin(12.0))
    assert info.value.key == "longitudinal.speed"
    with pytest.raises(ParameterError, match="rolling_radius"):
        _spin(rolling_radius=-0.3)
