"""Active and semi-active suspension: closed forms, E-QC-ISO-C, LQR optimality and the Riccati equation."""

import numpy as np
import pytest
import scipy.integrate
import scipy.linalg

import vehdyn
from vehdyn.ride import (
    QuarterCar,
    SemiActiveQuarterCar,
    compare_suspensions,
    groundhook,
    lqr_quarter_car,
    random_response,
    relative_quarter_car,
    skyhook,
)
from vehdyn.road import RoadSpectrum

from .conftest import check, load_case


def iso_c_car(**changes):
    i = {k: v[0] for k, v in load_case("E-QC-ISO-C")["inputs"].items()}
    kw = dict(sprung_mass=i["ms"], unsprung_mass=i["mu"], spring_rate=i["ks"], damping=i["cs"],
              tire_stiffness=i["kt"])
    kw.update(changes)
    return QuarterCar.from_parameters(**kw)


def iso_c_road():
    """(RoadSpectrum, speed [m/s]) of E-QC-ISO-C."""
    i = {k: v[0] for k, v in load_case("E-QC-ISO-C")["inputs"].items()}
    return RoadSpectrum(gd0=i["Gd(n0)_class_C"], waviness=i["waviness_w"]), i["V"]


def iso_c_intensity():
    """One-sided road-velocity PSD [(m/s)^2/Hz] of E-QC-ISO-C: twice the square of the shaping filter's gain."""
    spectrum, speed = iso_c_road()
    return 2.0 * spectrum.white_noise_gain(speed) ** 2


def white_noise_rms(model, outputs=None):
    """R.m.s. on the E-QC-ISO-C road by the Lyapunov route, as a dict."""
    res = random_response(model, *iso_c_road(), outputs=outputs)
    return dict(zip(res.output_names, res.rms))


def test_passive_rms_on_class_c_road():
    exp = load_case("E-QC-ISO-C")["expected"]
    spectrum, speed = iso_c_road()
    f = np.array([0.3, 3.0, 30.0])  # white: (2 pi f)^2 G_z(f) is the same at every frequency
    for G in (iso_c_intensity(), *((2 * np.pi * f) ** 2 * spectrum.temporal_psd(f, speed))):
        check(G, exp["road_velocity_PSD_white_Gzr'"], "velocity PSD")
    rms = white_noise_rms(relative_quarter_car(iso_c_car(), actuator=False))
    check(rms["sprung_acceleration"], exp["rms_body_acceleration"], "acceleration")
    check(rms["suspension_travel"], exp["rms_suspension_travel"], "travel")
    check(rms["tire_deflection"], exp["rms_tyre_deflection"], "tire deflection")
    check(rms["dynamic_tire_load"], exp["rms_dynamic_tyre_load"], "tire load")
    check(rms["dynamic_tire_load"] / (9.81 * (300 + 60)), exp["rms_dynamic_tyre_load/static_load"], "ratio")


def test_relative_form_matches_absolute_model():
    """Per unit road velocity: H_rel = H_abs,displacement / (j w) + H_abs,velocity."""
    qc = iso_c_car(tire_damping=150.0)
    rel = relative_quarter_car(qc, actuator=False)
    w = np.logspace(-1, 2.5, 25)
    ha = qc.frequency_response(w, outputs=list(rel.output_names))
    hr = rel.frequency_response(w)
    expected = ha.response[:, 0] / (1j * w) + ha.response[:, 1]
    np.testing.assert_allclose(hr.response[:, 0], expected, rtol=1e-9, atol=1e-12)


def test_lyapunov_rms_equals_psd_integral():
    qc = iso_c_car()
    rel = relative_quarter_car(qc, actuator=False)
    G = iso_c_intensity()
    f_max = 1e4
    f = np.logspace(-5, np.log10(f_max), 200001)
    fr = rel.frequency_response(2 * np.pi * f, outputs=["suspension_travel", "dynamic_tire_load"])
    var = scipy.integrate.trapezoid(np.abs(fr.response[:, 0]) ** 2 * G, f, axis=-1)
    # tail above f_max: the tire load tends to k_t z_r = k_t z_r' / (j w), |H|^2 = k_t^2 / (2 pi f)^2
    var[1] += qc.parameters.tire_stiffness**2 * G / (4 * np.pi**2 * f_max)
    rms = white_noise_rms(rel, outputs=["suspension_travel", "dynamic_tire_load"])
    assert np.sqrt(var[0]) == pytest.approx(rms["suspension_travel"], rel=1e-4)
    assert np.sqrt(var[1]) == pytest.approx(rms["dynamic_tire_load"], rel=1e-4)


def test_skyhook_and_groundhook_closed_forms():
    qc = iso_c_car(damping=0.0)
    p = qc.parameters
    ms, mu, ks, kt = p.sprung_mass, p.unsprung_mass, p.spring_rate, p.tire_stiffness
    csky, cg = 2500.0, 900.0
    w = 2 * np.pi * np.logspace(-1, 1.5, 30)
    s = 1j * w
    sky = skyhook(qc, csky)
    h = sky.frequency_response(w, outputs=["sprung_displacement"], inputs=["road_displacement"]).response[0, 0]
    np.testing.assert_allclose(h, ks * kt / ((ms * s**2 + csky * s + ks) * (mu * s**2 + ks + kt) - ks * (ks + csky * s)),
                               rtol=1e-9)
    gh = groundhook(qc, cg)
    h = gh.frequency_response(w, outputs=["sprung_displacement"], inputs=["road_displacement"]).response[0, 0]
    np.testing.assert_allclose(
        h, kt * (ks + cg * s) / ((ms * s**2 + ks) * (mu * s**2 + cg * s + ks + kt) - ks * (ks + cg * s)), rtol=1e-9)
    # the actuator force is an output: -c_sky z_s'
    y = sky.frequency_response(w, outputs=["actuator_force", "sprung_velocity"], inputs=["road_displacement"])
    np.testing.assert_allclose(y.response[0, 0], -csky * y.response[1, 0], rtol=1e-12)


def test_skyhook_without_feedback_is_passive():
    qc = iso_c_car()
    closed = skyhook(qc, 0.0)
    w = np.logspace(-1, 2, 9)
    np.testing.assert_allclose(closed.frequency_response(w, outputs=list(qc.output_names)).response,
                               qc.frequency_response(w).response, rtol=1e-12)


def test_lqr_gain_solves_the_riccati_equation_and_is_optimal():
    qc = iso_c_car()
    weights = {"sprung_acceleration": 1.0, "suspension_travel": 2e4, "tire_deflection": 5e4}
    r = 1e-7
    design = lqr_quarter_car(qc, weights, force_weight=r)
    plant = design.plant
    j = plant.index("actuator_force", "inputs")
    sel = plant.select(outputs=list(weights), inputs=["actuator_force"])
    W = np.diag(list(weights.values()))
    Q, R, N = sel.C.T @ W @ sel.C, sel.D.T @ W @ sel.D + r, sel.C.T @ W @ sel.D
    B = plant.B[:, [j]]
    S = scipy.linalg.solve_continuous_are(plant.A, B, Q, R, s=N)
    K = np.linalg.solve(R, B.T @ S + N.T).ravel()
    np.testing.assert_allclose(design.gain, K, rtol=1e-6)
    assert design.closed_loop.is_stable()
    # expected cost from the closed loop's covariance equals the Riccati value (G/2) b' S b
    rms = white_noise_rms(design.closed_loop, outputs=list(weights) + ["actuator_force"])
    cost = sum(w * rms[k] ** 2 for k, w in weights.items()) + r * rms["actuator_force"] ** 2
    assert cost == pytest.approx(design.cost(*iso_c_road()), rel=1e-6)
    # the passive car (K = 0) is an admissible feedback: its cost cannot be lower
    passive = white_noise_rms(relative_quarter_car(qc, actuator=False), outputs=list(weights))
    assert sum(w * passive[k] ** 2 for k, w in weights.items()) > cost


def test_lqr_with_expensive_force_tends_to_passive():
    qc = iso_c_car()
    design = lqr_quarter_car(qc, force_weight=1e3)
    assert np.max(np.abs(design.gain)) < 1e-3
    passive = relative_quarter_car(qc, actuator=False)
    np.testing.assert_allclose(np.sort_complex(design.poles), np.sort_complex(passive.poles()), rtol=1e-6)


def test_comparison_table():
    qc = iso_c_car()
    df = compare_suspensions({"passive": relative_quarter_car(qc, actuator=False),
                              "lqr": lqr_quarter_car(qc).closed_loop, "absolute": qc}, *iso_c_road())
    assert list(df.index) == ["passive", "lqr", "absolute"]
    # the relative form and the absolute quarter car (road displacement and velocity) are the same car
    np.testing.assert_allclose(df.loc["absolute", ["sprung_acceleration", "suspension_travel", "dynamic_tire_load"]],
                               df.loc["passive", ["sprung_acceleration", "suspension_travel", "dynamic_tire_load"]],
                               rtol=1e-9)
    exp = load_case("E-QC-ISO-C")["expected"]
    check(df.loc["passive", "sprung_acceleration"], exp["rms_body_acceleration"], "acceleration")
    np.testing.assert_allclose(df.loc["passive", ["sprung_acceleration_ratio", "suspension_travel_ratio"]], 1.0)
    assert df.attrs["units"]["dynamic_tire_load"] == "N"
    assert np.isfinite(df.loc["lqr", "actuator_force"])


def _road(t, G, seed):
    rng = np.random.default_rng(seed)
    dt = t[1] - t[0]
    v = rng.standard_normal(t.size) * np.sqrt(G / (2 * dt))
    return {"road_displacement": np.concatenate([[0.0], np.cumsum(v[:-1]) * dt]), "road_velocity": v}


def test_semi_active_with_fixed_damping_is_passive():
    qc = iso_c_car()
    sa = SemiActiveQuarterCar(qc, skyhook_damping=3000.0, min_damping=1000.0, max_damping=1000.0)
    t = np.arange(0, 2, 1e-3)
    road = _road(t, iso_c_intensity(), 3)
    a = vehdyn.simulate(sa, t, inputs=road, method="rk4", hold="zoh")
    b = vehdyn.simulate(qc, t, inputs=road, method="rk4", hold="zoh")  # same integrator: only the law differs
    scale = np.max(np.abs(b["sprung_acceleration"]))
    assert np.max(np.abs(a["sprung_acceleration"] - b["sprung_acceleration"])) < 1e-6 * scale


def test_semi_active_damper_only_dissipates_and_respects_limits():
    qc = iso_c_car()
    sa = SemiActiveQuarterCar(qc, skyhook_damping=4000.0, groundhook_damping=500.0, min_damping=300.0,
                              max_damping=3000.0)
    t = np.arange(0, 2, 1e-3)
    r = vehdyn.simulate(sa, t, inputs=_road(t, iso_c_intensity(), 5), method="rk4", hold="zoh")
    assert np.all(r["damper_force"] * r["suspension_velocity"] <= 1e-12)
    c = r["damper_coefficient"]
    assert c.min() >= 300.0 and c.max() <= 3000.0 and (c > 300.0).any()
    # a batch of two states in one call (trailing batch axis)
    x = np.array([[0.0, 0.01], [0.0, 0.0], [0.1, -0.2], [0.0, 0.3]])
    assert sa.rhs(0.0, x, np.zeros((2, 2))).shape == (4, 2)


def test_semi_active_one_state_on_floats_equals_the_batch(monkeypatch):
    """One state runs the law on Python floats: the same IEEE operations as the batch path (no
    transcendental function), so the same numbers on every CPU; non-finite states take numpy's path."""
    sa = SemiActiveQuarterCar(iso_c_car(), skyhook_damping=4000.0, groundhook_damping=500.0, min_damping=300.0,
                              max_damping=3000.0)
    i_s, i_u = sa.index("sprung_velocity"), sa.index("unsprung_velocity")
    rng = np.random.default_rng(7)
    X = rng.standard_normal((4, 200)) * 0.3
    X[i_s, :4], X[i_u, :4] = [0.2, 0.0, 1e-9, 0.5], [0.2, 0.0, -1e-9, 0.5]  # v_rel = 0, tiny, 0 again
    X[i_s, 4], X[i_u, 4] = 1.0, 0.999  # wants 3.5e6 N*s/m: clipped to c_max
    X[i_s, 5], X[i_s, 6], X[i_u, 7] = np.nan, np.inf, -np.inf
    U = rng.standard_normal((sa.n_inputs, 200)) * 0.01
    with np.errstate(invalid="ignore"):
        c, f = sa.damper(X)
        F, Y = sa.rhs(0.0, X, U), sa.output(0.0, X, U)
        for j in range(X.shape[1]):
            cj, fj = sa.damper(X[:, j])
            assert np.array_equal(cj, c[j], equal_nan=True) and np.array_equal(fj, f[j], equal_nan=True), j
            # the linear part, A @ x, is a matrix-vector product here and a matrix product for the batch
            # (BLAS may sum in another order): within an ulp or so of the terms
            np.testing.assert_allclose(sa.rhs(0.0, X[:, j], U[:, j]), F[:, j], rtol=1e-13, atol=1e-9)
            np.testing.assert_allclose(sa.output(0.0, X[:, j], U[:, j]), Y[:, j], rtol=1e-13, atol=1e-9)
    assert c[4] == 3000.0 and np.ndim(sa.damper(X[:, 0])[0]) == 0

    def no_numpy(*args, **kwargs):
        raise AssertionError("a finite state took numpy's path")

    monkeypatch.setattr(np, "clip", no_numpy)
    monkeypatch.setattr(np, "where", no_numpy)
    assert sa.damper(X[:, 4])[0] == 3000.0  # the float path: no numpy clip or where


@pytest.mark.parametrize("kw,key", [
    (dict(min_damping=-1.0, max_damping=10.0), "min_damping"),
    (dict(min_damping=100.0, max_damping=10.0), "max_damping"),
    (dict(min_damping=0.0, max_damping=10.0, skyhook_damping=float("nan")), "skyhook_damping"),
])
def test_semi_active_bad_parameters(kw, key):
    with pytest.raises(vehdyn.ParameterError) as err:
        SemiActiveQuarterCar(iso_c_car(), **kw)
    assert err.value.key == key


def test_bad_inputs_of_the_active_functions():
    qc = iso_c_car()
    with pytest.raises(vehdyn.ParameterError):
        skyhook(qc, -1.0)
    with pytest.raises(vehdyn.ParameterError):
        lqr_quarter_car(qc, {"no_such_output": 1.0})
    with pytest.raises(vehdyn.ParameterError):
        lqr_quarter_car(qc, force_weight=0.0)
    with pytest.raises(vehdyn.ParameterError):
        compare_suspensions({"passive": relative_quarter_car(qc, actuator=False)}, "C", -20.0)
    with pytest.raises(vehdyn.ParameterError):
        relative_quarter_car("not a quarter car")
    # a vehicle where its corner is meant: the message says how to build the corner
    with pytest.raises(vehdyn.ParameterError, match=r"QuarterCar\(vehicle, axle='front'\)") as err:
        SemiActiveQuarterCar(vehdyn.load_vehicle("sedan"), min_damping=100.0, max_damping=3000.0)
    assert err.value.key == "quarter_car"
    unstable = vehdyn.LinearModel([[1.0]], [[1.0]], states=["x"], inputs=["road_velocity"])
    with pytest.raises(vehdyn.ParameterError):
        white_noise_rms(unstable)
    # an output fed through by the white road velocity has infinite variance
    qct = relative_quarter_car(iso_c_car(tire_damping=100.0), actuator=False)
    assert white_noise_rms(qct, outputs=["dynamic_tire_load"])["dynamic_tire_load"] == np.inf
