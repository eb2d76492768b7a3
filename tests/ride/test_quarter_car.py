"""Quarter car against closed forms and the reference cases E-QC-GOLDENCAR and E-HOP-BF."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import vehdyn
from vehdyn.ride import QuarterCar, ride_modes, transmissibility, suspension_travel_response, \
    dynamic_tire_load_response

from .conftest import check, load_case


def golden_car(**extra):
    inp = load_case("E-QC-GOLDENCAR")["inputs"]
    return QuarterCar.from_parameters(sprung_mass=inp["ms"][0], unsprung_mass=inp["mu"][0], spring_rate=inp["ks"][0],
                                      damping=inp["cs"][0], tire_stiffness=inp["kt"][0], **extra)


def closed_form(p, s):
    """Textbook transfer functions of the 2-DOF quarter car per unit road elevation (Wong 2008, sec. 7.2.1)."""
    ms, mu, ks, cs, kt, ct = (p[k] for k in ("sprung_mass", "unsprung_mass", "spring_rate", "damping",
                                             "tire_stiffness", "tire_damping"))
    det = (ms * s**2 + cs * s + ks) * (mu * s**2 + (cs + ct) * s + ks + kt) - (cs * s + ks) ** 2
    zs = (kt + ct * s) * (ks + cs * s) / det
    zu = (kt + ct * s) * (ms * s**2 + cs * s + ks) / det
    return zs, zu, (kt + ct * s) * (1 - zu)


def test_golden_car_estimates_and_modes():
    exp = load_case("E-QC-GOLDENCAR")["expected"]
    qc = golden_car()
    est = qc.estimates()
    check(est["ride_rate"], exp["ride_rate_RR"], "ride rate")
    check(est["body_frequency_hz"], exp["f_body_simple_sqrt(RR/ms)"], "body frequency estimate")
    check(est["wheel_hop_frequency_hz"], exp["f_wheelhop_simple_sqrt((ks+kt)/mu)"], "hop estimate")
    check(est["body_damping_ratio"], exp["zeta_body_simple_cs/(2sqrt(ks ms))"], "zeta estimate")
    f = qc.modal_analysis().natural_frequency_hz
    check(f[0], exp["f1_undamped_2dof"], "f1")
    check(f[1], exp["f2_undamped_2dof"], "f2")
    modes = ride_modes(qc)
    assert modes.labels == ("body bounce", "wheel hop")
    for k, m in enumerate(("mode1", "mode2")):
        lam = qc.modes().eigenvalues[k]
        check(lam.real, exp[f"{m}_eig_real"], f"{m} real")
        check(lam.imag, exp[f"{m}_eig_imag"], f"{m} imag")
        check(modes.damping_ratio[k], exp[f"{m}_zeta"], f"{m} zeta")
        check(modes.natural_frequency_hz[k], exp[f"{m}_f_undamped"], f"{m} |lambda|")


@pytest.mark.parametrize("f_hz", [0.5, 1, 1.5, 2, 5, 10, 15])
def test_golden_car_transmissibility(f_hz):
    exp = load_case("E-QC-GOLDENCAR")["expected"]
    qc = golden_car()
    w = [2 * np.pi * f_hz]
    zs = transmissibility(qc, w)["sprung_displacement"][0]
    tag = f"{f_hz:g}Hz"
    check(abs(zs), exp[f"|zs/zr|@{tag}"], "|zs/zr|")
    check(np.degrees(np.angle(zs)), exp[f"phase_zs/zr@{tag}"], "phase")
    check(abs(suspension_travel_response(qc, w)["suspension_travel"][0]), exp[f"|(zs-zu)/zr|@{tag}"], "travel")
    check(abs(dynamic_tire_load_response(qc, w)["dynamic_tire_load"][0]), exp[f"|Ftyre_dyn/zr|@{tag}"], "tire")


def test_published_wheel_hop_example():
    """E-HOP-BF (Barton & Fieldhouse 2018, p. 213): 14.25 Hz, 2.85 m/s over 0.2 m cobbles."""
    c = load_case("E-HOP-BF")
    inp, exp = c["inputs"], c["expected"]
    static = inp["vehicle_mass"][0] * inp["front_weight_fraction"][0] * inp["g"][0] / 2
    check(static, exp["static_load_per_front_tyre"], "static load")
    qc = QuarterCar.from_parameters(sprung_mass=static / inp["g"][0] - inp["mu_unsprung"][0],
                                    unsprung_mass=inp["mu_unsprung"][0], spring_rate=inp["ks_wheel_rate"][0],
                                    tire_stiffness=inp["kt"][0])
    f_est = qc.estimates()["wheel_hop_frequency_hz"]
    check(f_est, exp["f_wheel_hop"], "estimate")
    # the exact 2-DOF hop frequency is within the book's 3 digits too
    check(ride_modes(qc).undamped_frequency_hz[1], exp["f_wheel_hop"], "exact hop")
    check(f_est * inp["cobble_pitch"][0], exp["critical_speed"], "critical speed")
    check(static / (inp["mu_unsprung"][0] * (2 * np.pi * f_est) ** 2), exp["amplitude_for_contact_loss"], "amplitude")


@settings(max_examples=40, deadline=None)
@given(ms=st.floats(100, 800), mu=st.floats(15, 80), ks=st.floats(1e4, 6e4), cs=st.floats(0, 5e3),
       kt=st.floats(1e5, 4e5), ct=st.floats(0, 500), f=st.floats(0.05, 40))
def test_frequency_response_equals_closed_form(ms, mu, ks, cs, kt, ct, f):
    p = dict(sprung_mass=ms, unsprung_mass=mu, spring_rate=ks, damping=cs, tire_stiffness=kt, tire_damping=ct)
    qc = QuarterCar.from_parameters(**p)
    w = 2 * np.pi * f
    fr = vehdyn.ride.road_frequency_response(qc, [w])
    zs, zu, load = closed_form(p, 1j * w)
    assert fr["sprung_displacement"][0] == pytest.approx(zs, rel=1e-9, abs=1e-12)
    assert fr["unsprung_displacement"][0] == pytest.approx(zu, rel=1e-9, abs=1e-12)
    assert fr["suspension_travel"][0] == pytest.approx(zs - zu, rel=1e-8, abs=1e-10)
    assert fr["tire_deflection"][0] == pytest.approx(1 - zu, rel=1e-8, abs=1e-10)
    assert fr["dynamic_tire_load"][0] == pytest.approx(load, rel=1e-8, abs=1e-6)
    assert fr["sprung_acceleration"][0] == pytest.approx(-(w**2) * zs, rel=1e-9, abs=1e-12)
    # a rigid displacement of road and car is static equilibrium: unit DC gain, no deflection
    dc = qc.dc_gain()[:, qc.index("road_displacement", "inputs")]
    for name, value in (("sprung_displacement", 1.0), ("unsprung_displacement", 1.0), ("suspension_travel", 0.0),
                        ("dynamic_tire_load", 0.0)):
        assert dc[qc.index(name, "outputs")] == pytest.approx(value, abs=1e-9 * max(1.0, kt))


def test_single_dof_limit_damping_ratio():
    """Stiff tire, light wheel: the body mode tends to the 1-DOF oscillator zeta = c / (2 sqrt(k m))."""
    qc = QuarterCar.from_parameters(sprung_mass=400.0, unsprung_mass=1e-3, spring_rate=2e4, damping=1500.0,
                                    tire_stiffness=1e10)
    m = ride_modes(qc)
    assert m.damping_ratio[0] == pytest.approx(1500.0 / (2 * np.sqrt(2e4 * 400.0)), rel=1e-5)
    assert m.natural_frequency_hz[0] == pytest.approx(np.sqrt(2e4 / 400.0) / (2 * np.pi), rel=1e-5)


def test_a_vehicle_corner_shares():
    v = vehdyn.load_vehicle("sedan")
    front, rear = QuarterCar(v, "front"), QuarterCar(v, "rear")
    # the four corners carry the sprung mass (static moment balance about each axle)
    total = 2 * (front.parameters.sprung_mass + rear.parameters.sprung_mass)
    assert total == pytest.approx(v.mass.sprung_mass, rel=1e-12)
    assert front.parameters.sprung_mass * v.geometry.sprung_cg_to_front_axle == pytest.approx(
        rear.parameters.sprung_mass * v.geometry.sprung_cg_to_rear_axle, rel=1e-12)
    assert front.parameters.spring_rate == v.suspension.front_spring_rate


def test_round_trip_through_python_control():
    qc = golden_car(tire_damping=0.05)
    back = vehdyn.LinearModel.from_control(qc.to_control())
    assert back.output_names == qc.output_names and back.input_names == qc.input_names
    w = np.logspace(-1, 2, 7)
    np.testing.assert_allclose(back.frequency_response(w).response, qc.frequency_response(w).response, rtol=1e-12)


def test_time_simulation_of_a_step_settles_to_the_step():
    qc = golden_car()
    t = np.linspace(0, 10, 2001)
    r = vehdyn.simulate(qc, t, inputs={"road_displacement": 0.01}, method="exact")
    assert r["sprung_displacement"][-1] == pytest.approx(0.01, rel=1e-5)
    assert r["dynamic_tire_load"][-1] == pytest.approx(0.0, abs=1e-6)


@pytest.mark.parametrize("key,value", [("sprung_mass", 0.0), ("unsprung_mass", -1.0), ("spring_rate", float("nan")),
                                       ("damping", -5.0), ("tire_stiffness", 0.0), ("tire_damping", -1.0)])
def test_bad_parameters_are_named(key, value):
    kw = dict(sprung_mass=300.0, unsprung_mass=40.0, spring_rate=2e4, damping=1e3, tire_stiffness=2e5)
    kw[key] = value
    with pytest.raises(vehdyn.ParameterError) as err:
        QuarterCar.from_parameters(**kw)
    assert err.value.key == key


def test_bad_axle():
    with pytest.raises(vehdyn.ParameterError, match="axle"):
        QuarterCar(vehdyn.load_vehicle("sedan"), "middle")


def test_replace_validates_and_keeps_the_actuator_option():
    qc = golden_car()
    active = qc.replace(actuator=True)
    assert "actuator_force" in active.input_names and active.parameters == qc.parameters
    assert "actuator_force" in active.replace(damping=2.0).input_names
    with pytest.raises(vehdyn.ParameterError) as err:
        qc.replace(damping=-1.0)
    assert err.value.key == "damping"
    # actuator force extends the suspension: statically it lifts the body by f / k_s more than the wheel
    f = 10.0
    dc = active.dc_gain()[:, active.index("actuator_force", "inputs")] * f
    assert dc[active.index("suspension_travel", "outputs")] == pytest.approx(f / qc.parameters.spring_rate, rel=1e-10)
    assert dc[active.index("dynamic_tire_load", "outputs")] == pytest.approx(0.0, abs=1e-9)
