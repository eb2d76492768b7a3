"""SingleTrack against the linear bicycle, the Magic Formula's kya, closed forms and reference cases."""

import json
from pathlib import Path

import numpy as np
import pytest

import vehdyn
from vehdyn.handling import LinearBicycle, SingleTrack
from vehdyn.tire import FialaTire, LinearTire, MagicFormula, TirParameters, read_tir

SEDAN = vehdyn.load_vehicle("sedan")
_CASES = Path(__file__).resolve().parent.parent / "data" / "single_track_reference_cases.json"


def linear_tires(vehicle, **kwargs):
    return (LinearTire(cornering_stiffness=vehicle.tires.front_cornering_stiffness / 2, **kwargs),
            LinearTire(cornering_stiffness=vehicle.tires.rear_cornering_stiffness / 2, **kwargs))


@pytest.fixture(scope="module")
def mf_model():
    return SingleTrack(SEDAN)  # the vehicle's own law: the Magic Formula of mf_185_80R14.tir


@pytest.mark.parametrize("speed", [5.0, 20.0, 40.0])
@pytest.mark.parametrize("vehicle", ["sedan", "compact", "van"])
def test_linearization_equals_linear_bicycle(vehicle, speed):
    v = vehdyn.load_vehicle(vehicle)
    model = SingleTrack(v, *linear_tires(v), tire_lag=False)
    lin = model.lateral_yaw(speed)
    bike = LinearBicycle(v, speed)
    assert lin.state_names == bike.state_names and lin.output_names == bike.output_names
    for name in "ABCD":
        ours, theirs = getattr(lin, name), getattr(bike, name)
        assert np.allclose(ours, theirs, rtol=1e-8, atol=1e-8 * np.max(np.abs(theirs))), name


def test_linearization_with_tire_lag_has_the_bicycle_eigenvalues():
    # deflection rho = sigma alpha' is a scaling of the bicycle's transient slip state: same eigenvalues
    model = SingleTrack(SEDAN, *linear_tires(SEDAN), tire_lag=True)
    for speed in (10.0, 30.0):
        ours = np.sort_complex(np.linalg.eigvals(model.lateral_yaw(speed).A))
        theirs = np.sort_complex(np.linalg.eigvals(LinearBicycle(SEDAN, speed, tire_lag=True).A))
        assert np.allclose(ours, theirs, rtol=1e-8)


def test_lateral_yaw_block_decouples_from_the_other_states(mf_model):
    full = mf_model.linearize(speed=25.0)
    lateral = [mf_model.index(n) for n in ("lateral_velocity", "yaw_rate", "front_lateral_deflection",
                                           "rear_lateral_deflection")]
    others = [k for k in range(mf_model.n_states) if k not in lateral]
    # straight running: the lateral-yaw rows do not depend on u, x, y, psi (closed form: zero)
    assert np.max(np.abs(full.A[np.ix_(lateral, others)])) < 1e-6


def test_magic_formula_axle_stiffness_is_twice_kya_at_the_static_loads():
    params = read_tir(vehdyn.data_path("tires", "mf_185_80R14.tir"))
    # without the file's lateral shifts (LHY = LVY = 0) the slope at zero slip is B C D = kya exactly
    sections = {s: dict(kv) for s, kv in params.sections.items()}
    sections["SCALING_COEFFICIENTS"].update(LHY=0.0, LVY=0.0)
    unshifted = MagicFormula(TirParameters(sections))
    front_load, rear_load = SEDAN.static_axle_loads()
    model = SingleTrack(SEDAN, unshifted, unshifted)
    stiffness = model.axle_cornering_stiffness()
    for load, value in zip((front_load, rear_load), stiffness):
        kya = float(unshifted.evaluate(load / 2, 0.0, 0.0, vx=20.0).kya)
        assert value == pytest.approx(-2 * kya, rel=1e-7)
    # and the linearization of the model carries it: compare with a LinearBicycle of those stiffnesses
    bike = LinearBicycle.from_parameters(mass=SEDAN.mass.mass, yaw_inertia=SEDAN.mass.yaw_inertia,
                                         a=SEDAN.geometry.a, b=SEDAN.geometry.b,
                                         front_cornering_stiffness=float(stiffness[0]),
                                         rear_cornering_stiffness=float(stiffness[1]), speed=20.0)
    lin = SingleTrack(SEDAN, unshifted, unshifted, tire_lag=False).lateral_yaw(20.0)
    assert np.allclose(lin.A, bike.A, rtol=1e-6)
    # the vehicle file's axle stiffnesses are 2 kya by construction (its comment's formula)
    assert stiffness[0] == pytest.approx(SEDAN.tires.front_cornering_stiffness, rel=1e-9)
    assert stiffness[1] == pytest.approx(SEDAN.tires.rear_cornering_stiffness, rel=1e-9)


def test_magic_formula_shifts_change_the_slope_only_to_second_order(mf_model):
    # with the file's shifts S_Hy the slope at alpha = 0 is B C D cos(.)-reduced: within (B S_Hy)^2
    front_load, _ = SEDAN.static_axle_loads()
    kya = -2 * float(mf_model.front_tire.evaluate(front_load / 2, 0.0, 0.0, vx=20.0).kya)
    assert mf_model.axle_cornering_stiffness()[0] == pytest.approx(kya, rel=2e-3)


def test_mirrored_magic_formula_axles_run_straight(mf_model):
    # the left and right tires are mirror images: their shifts cancel and zero steer runs straight
    x = mf_model.straight_running(25.0)
    f = mf_model.rhs(0.0, x, mf_model.input_vector())
    assert abs(f[mf_model.index("lateral_velocity")]) < 1e-12
    assert abs(f[mf_model.index("yaw_rate")]) < 1e-12


def test_sae_signs_positive_steer_turns_right():
    model = SingleTrack(SEDAN, *linear_tires(SEDAN), tire_lag=False)
    t = np.linspace(0, 3, 31)
    r = vehdyn.simulate(model, t, {"front_steer_angle": 0.02}, x0=model.straight_running(20.0), method="RK45")
    assert r["yaw_rate"][-1] > 0 and r["lateral_acceleration"][-1] > 0 and r["y"][-1] > 0
    assert r["front_lateral_force"][-1] > 0  # pushes the front to the right (SAE y)
    assert r["front_slip_angle"][-1] < 0  # SAE slip angle: the wheel points right of its velocity


def test_coast_down_follows_the_drag_closed_form():
    # m du/dt = -k u^2  ->  u(t) = u0 / (1 + k u0 t / m)
    model = SingleTrack(SEDAN, *linear_tires(SEDAN), tire_lag=False)
    k, m, u0 = model.parameters.drag_factor, SEDAN.mass.mass, 30.0
    t = np.linspace(0, 20, 41)
    r = vehdyn.simulate(model, t, None, x0=model.straight_running(u0), method="DOP853", rtol=1e-10, atol=1e-12)
    assert np.allclose(r["longitudinal_velocity"], u0 / (1 + k * u0 * t / m), rtol=1e-8)
    assert np.allclose(r["x"], m / k * np.log(1 + k * u0 * t / m), rtol=1e-8)


@pytest.mark.compiled_vs_numpy
def test_coast_down_decelerates_by_the_rolling_resistance_moment():
    # MF 5.2 file with QSY2 = QSY3 = QSY4 = 0: M_y = -R0 F_z LMY QSY1 per tire, linear in the load, so
    # that the four tires together give -R0 LMY QSY1 m g whatever the load transfer. A free-rolling
    # axle has 2 I_w d(omega)/dt = M_y - R_e F_x; with omega = (1 + kappa) u / R_e and no drag or lift
    #   m du/dt = sum F_x  ->  du/dt = -g QSY1 LMY (R0 / R_e) m / (m + 4 I_w / R_e^2)
    # up to the relative term |kappa| (4 I_w / R_e^2) / m (kappa ~ -2e-3 here: < 1e-4); the moment's
    # fade at standstill, tanh(omega / omega_b), is 1 to the last bit at omega ~ 66 rad/s.
    tire = MagicFormula.from_tir(vehdyn.data_path("tires", "MagicFormula52_Parameters.tir"))
    c = tire._c
    assert (c.QSY2, c.QSY3, c.QSY4, c.QSY1) == (0.0, 0.0, 0.0, 0.01) and c.is_mf52
    model = SingleTrack(SEDAN, tire, tire, wheel_spin=True, tire_lag=False).variants(
        drag_factor=0.0, front_lift_factor=0.0, rear_lift_factor=0.0)
    p = model.parameters
    t = np.linspace(0.0, 2.0, 21)
    r = vehdyn.simulate(model, t, None, x0=model.straight_running(20.0), method="DOP853", rtol=1e-10, atol=1e-10,
                        backend="numpy")
    rotating = 4.0 * p.wheel_spin_inertia / p.rolling_radius**2
    expected = -p.gravity * c.QSY1 * c.LMY * c.UNLOADED_RADIUS / p.rolling_radius * p.mass / (p.mass + rotating)
    assert np.allclose(r["longitudinal_acceleration"][10:], expected, rtol=2e-4)
    assert np.allclose(r["longitudinal_velocity"][10:], 20.0 + expected * t[10:], rtol=2e-4, atol=0)
    # the compiled rhs carries the same moment. Not bit for bit (it was, at this state on this machine,
    # by luck): the numpy rhs takes the tires' scalar path (the C library) and numpy's tanh for the
    # moment's fade (a SIMD kernel, within 2 ulps), the compiled one vehdyn's branchless functions
    # (tire/_fast_math, 2-4 ulps from the C library) and the C library's tanh. Budget: 4 ulps per value,
    # or 4 ulps of the wheels' moment term M_y / (2 I_w) (12.6 rad/s^2, 1.1e-14) in the wheel equations
    # 2 I_w dw/dt = M_y - R_e F_x, a difference of terms ~40x the result (measured at 800 states near
    # this run: <= 1.1 such ulps, 1.5 with numpy's results moved by 2 ulps; <= 4 ulps in du/dt); the
    # moment lost or doubled would be 0.3 rad/s^2 off.
    pytest.importorskip("numba")
    from tests._tolerances import EPS, ONE_CALL_ULPS, assert_close_ulps
    compiled = model.compiled_rhs()
    x, u = r.states[:, 15].copy(), model.input_vector()
    dxdt = np.empty(model.n_states)
    compiled.rhs(0.0, x, u, compiled.args, dxdt)
    moment_term = p.gravity * p.mass * c.QSY1 * c.LMY * c.UNLOADED_RADIUS / (2.0 * p.wheel_spin_inertia)
    assert_close_ulps(dxdt, model.rhs(0.0, x, u), ulps=ONE_CALL_ULPS, rtol=ONE_CALL_ULPS * EPS, scale=moment_term,
                      what="compiled vs numpy rhs of the coast-down")


def test_magic_formula_wheels_at_rest_stay_at_rest():
    # the law's rolling-resistance moment at zero speed (-R0 F_z QSY1) fades with the wheel's spin
    # like a brake: the wheels of a car at rest do not spin up backwards (the law's small force at
    # zero slip and speed leaves derivatives below 1e-4, as FullVehicle's rest state; it was 1e-2)
    model = SingleTrack(SEDAN, wheel_spin=True)
    assert np.max(np.abs(model.rhs(0.0, model.state_vector(), model.input_vector()))) < 1e-4


def test_load_transfer_case_I_BRAKE_1():
    case = {c["id"]: c for c in json.loads(_CASES.read_text())["cases"]}["I-BRAKE-1"]
    i = {k: v[0] for k, v in case["inputs"].items()}
    model = SingleTrack(SEDAN, *linear_tires(SEDAN)).variants(
        mass=i["m"], a=i["b_front_axle_to_CG"], b=i["L"] - i["b_front_axle_to_CG"], cg_height=i["h_CG"],
        friction_coefficient=i["mu"], drag_factor=0.0, gravity=i["g"])
    force = i["m"] * i["decel"] * i["g"]
    share = case["expected"]["ideal_front_brake_share_at_0.8g"][0]
    x = model.straight_running(20.0)
    u = model.input_vector(front_longitudinal_force=-share * force, rear_longitudinal_force=-(1 - share) * force)
    y = dict(zip(model.output_names, model.output(0.0, x, u)))
    assert y["front_normal_load"] == pytest.approx(case["expected"]["Wf_at_0.8g"][0], rel=1e-4)
    assert y["rear_normal_load"] == pytest.approx(case["expected"]["Wr_at_0.8g"][0], rel=1e-4)
    assert y["longitudinal_acceleration"] == pytest.approx(-i["decel"] * i["g"], rel=1e-12)


def test_batch_of_variants_equals_single_runs():
    masses = np.array([1000.0, 1300.0, 1700.0])
    base = SingleTrack(SEDAN, *linear_tires(SEDAN))
    batch = base.variants(mass=masses)
    t = np.linspace(0, 2, 201)
    steer = {"front_steer_angle": lambda tt: 0.03 * np.sin(2 * np.pi * tt)}
    x0 = np.repeat(base.straight_running(20.0)[:, None], masses.size, axis=1)
    together = vehdyn.simulate(batch, t, steer, x0=x0, method="rk4")
    for k, mass in enumerate(masses):
        alone = vehdyn.simulate(base.variants(mass=mass), t, steer, x0=x0[:, k], method="rk4")
        assert np.allclose(together.states[:, :, k], alone.states, rtol=1e-12, atol=1e-12)


def test_any_tire_law_runs_and_saturates_at_mu():
    v = SEDAN
    fiala = (FialaTire.from_vehicle(v, "front"), FialaTire.from_vehicle(v, "rear"))
    model = SingleTrack(v, *fiala, tire_lag=False)
    x = model.straight_running(20.0, lateral_velocity=-8.0)  # sliding sideways: both axles saturated
    y = dict(zip(model.output_names, model.output(0.0, x, model.input_vector())))
    mu = v.tires.friction_coefficient
    assert abs(y["front_lateral_force"]) == pytest.approx(mu * y["front_normal_load"], rel=1e-6)
    assert abs(y["rear_lateral_force"]) == pytest.approx(mu * y["rear_normal_load"], rel=1e-6)


def test_parameter_errors_name_the_parameter():
    model = SingleTrack(SEDAN, *linear_tires(SEDAN))
    with pytest.raises(vehdyn.ParameterError, match="mass"):
        model.variants(mass=-1.0)
    with pytest.raises(vehdyn.ParameterError, match="differ in length"):
        model.variants(mass=[1000.0, 1100.0], a=[1.0, 1.1, 1.2])
    with pytest.raises(vehdyn.ParameterError, match="no parameter 'massa'"):
        model.variants(massa=1.0)
    with pytest.raises(vehdyn.ParameterError, match="front_tire"):
        SingleTrack(SEDAN, front_tire="magic")
    with pytest.raises(vehdyn.ParameterError, match="vehicle"):
        SingleTrack({"mass": 1000})
    with pytest.raises(vehdyn.ParameterError, match="low_speed_damping_speed"):
        SingleTrack(SEDAN, *linear_tires(SEDAN), low_speed_damping_speed=0.0)
    with pytest.raises(vehdyn.ParameterError, match="relaxation_length"):
        SingleTrack(SEDAN.replace(tires__front_relaxation_length=0.0), *linear_tires(SEDAN), tire_lag=True)
    with pytest.raises(vehdyn.ParameterError, match="longitudinal_relaxation_length"):
        SingleTrack(SEDAN, *linear_tires(SEDAN), longitudinal_relaxation_length=-0.1)


def test_signals_and_phenomena():
    model = SingleTrack(SEDAN, *linear_tires(SEDAN), wheel_spin=True)
    assert model.state_names[:6] == ("longitudinal_velocity", "lateral_velocity", "yaw_rate", "x", "y", "yaw_angle")
    assert {"front_wheel_speed", "rear_longitudinal_deflection"} <= set(model.state_names)
    assert {"wheel_spin", "tire_lag", "load_transfer", "aero"} <= model.phenomena
    assert {"front_brake_torque", "external_lateral_force"} <= set(model.input_names)


def test_default_longitudinal_relaxation_lengths_belong_to_the_tire_law():
    # a Magic Formula tire: K_xkappa / C_x at half the static axle load, checked against the MF 5.2
    # closed form sigma_kappa = (PTX1 + PTX2 dfz) exp(-PTX3 dfz) LSGKP R_0 F_z / F_z0 (PAC2002, as MFeval)
    vehicle = vehdyn.load_vehicle("sedan")
    model = SingleTrack(vehicle, wheel_spin=True)
    p = model.front_tire.params
    for axle, load in zip(("front", "rear"), vehicle.static_axle_loads()):
        fz = 0.5 * load
        dfz = (fz - p["FNOMIN"] * p["LFZO"]) / (p["FNOMIN"] * p["LFZO"])
        closed = ((p["PTX1"] + p["PTX2"] * dfz) * np.exp(-p["PTX3"] * dfz) * p["LSGKP"] * p["UNLOADED_RADIUS"]
                  * fz / p["FNOMIN"])
        assert getattr(model.parameters, f"{axle}_longitudinal_relaxation_length") == pytest.approx(closed, rel=1e-12)
    # another law carries no longitudinal length of its own: the vehicle file's lateral lengths
    fiala = SingleTrack(vehicle, FialaTire.from_vehicle(vehicle, "front"), FialaTire.from_vehicle(vehicle, "rear"),
                        wheel_spin=True)
    assert fiala.parameters.front_longitudinal_relaxation_length == vehicle.tires.front_relaxation_length
    assert fiala.parameters.rear_longitudinal_relaxation_length == vehicle.tires.rear_relaxation_length
