"""Random response: Lyapunov, PSD integral and time simulation against E-QC-ISO-C and against each other."""

import numpy as np
import pytest

import vehdyn
from vehdyn.road import RoadSpectrum
from vehdyn.ride import random_response

OUTPUTS = {"sprung_acceleration": "rms_body_acceleration", "suspension_travel": "rms_suspension_travel",
           "tire_deflection": "rms_tyre_deflection", "dynamic_tire_load": "rms_dynamic_tyre_load"}


@pytest.fixture(scope="module")
def iso_c(cases):
    return cases["E-QC-ISO-C"]


@pytest.fixture(scope="module")
def car(iso_c, models):
    p = {k: v[0] for k, v in iso_c["inputs"].items()}
    return models.quarter_car(p["ms"], p["mu"], p["ks"], p["cs"], p["kt"])


@pytest.mark.parametrize("method", ["lyapunov", "psd"])
def test_e_qc_iso_c(iso_c, car, method):
    res = random_response(car, "C", iso_c["inputs"]["V"][0], method=method)
    for name, key in OUTPUTS.items():
        value, _unit, tol = iso_c["expected"][key]
        assert res[name] == pytest.approx(value, rel=max(tol, 1e-6)), name
    value, _, tol = iso_c["expected"]["rms_dynamic_tyre_load/static_load"]
    static = (iso_c["inputs"]["ms"][0] + iso_c["inputs"]["mu"][0]) * iso_c["inputs"]["g"][0]
    assert res["dynamic_tire_load"] / static == pytest.approx(value, rel=max(tol, 1e-6))
    if method == "psd":
        assert np.all(res.error < 1e-6 * res.rms)  # the stated error bound


def test_lyapunov_and_psd_agree_with_cut_on(car):
    spec = RoadSpectrum.from_class("D", cut_on=0.02)
    a = random_response(car, spec, 15.0, method="lyapunov")
    b = random_response(car, spec, 15.0, method="psd")
    np.testing.assert_allclose(a.rms, b.rms, rtol=1e-7)
    assert np.all(np.abs(a.rms - b.rms) <= b.error + 1e-9 * b.rms)


def test_simulation_agrees_within_its_statistical_error(car):
    exact = random_response(car, "C", 20.0)
    sim = random_response(car, "C", 20.0, method="simulation", duration=200.0, sample_rate=400.0, seed=4)
    assert np.all(sim.error > 0)
    # 4 standard errors, plus 1 % for the sampled road (foh between samples at 400 Hz)
    assert np.all(np.abs(sim.rms - exact.rms) < 4 * sim.error + 0.01 * exact.rms)


def test_variance_scales_with_road_class_and_speed(car):
    """w = 2: the road velocity PSD is (2 pi n0)^2 Gd(n0) V, so variances scale with Gd(n0) V."""
    a = random_response(car, "B", 10.0).rms
    b = random_response(car, "D", 40.0).rms
    np.testing.assert_allclose(b / a, np.sqrt(16 * 4), rtol=1e-9)


def test_unbounded_outputs_are_infinite(models):
    car = models.quarter_car(300, 60, 16000, 1000, 190000, ct=100.0)
    sel = vehdyn.LinearModel(car.A, car.B, np.vstack([car.C, np.eye(4)[0]]), np.vstack([car.D, [0, 0]]),
                             states=car.states, inputs=car.inputs,
                             outputs=list(car.output_names) + ["sprung_displacement"])
    for method in ("lyapunov", "psd"):
        res = random_response(sel, "C", 20.0, method=method)
        # absolute displacement: the ISO spectrum has infinite variance (no cut-on)
        assert np.isinf(res["sprung_displacement"])
        # tire damping feeds white road velocity into the unsprung force: dynamic tire load unbounded
        assert np.isinf(res["dynamic_tire_load"])
        assert np.isfinite(res["suspension_travel"])
    with_cut_on = random_response(sel, RoadSpectrum.from_class("C", cut_on=0.01), 20.0)
    assert np.isfinite(with_cut_on["sprung_displacement"])


# --------------------------------------------------------------------------- front/rear delay
@pytest.fixture(scope="module")
def half(models):
    return models.half_car()


def test_front_rear_exact_delay_against_pade(half):
    psd = random_response(half, "C", 20.0, method="psd", wheelbase=2.7)
    assert np.all(psd.error < 1e-4 * psd.rms)
    lyap = random_response(half, "C", 20.0, method="lyapunov", wheelbase=2.7, delay="pade", pade_order=10)
    np.testing.assert_allclose(lyap.rms, psd.rms, rtol=1e-5)
    coarse = random_response(half, "C", 20.0, method="lyapunov", wheelbase=2.7, delay="pade", pade_order=4)
    assert np.max(np.abs(coarse.rms / psd.rms - 1)) > 1e-3  # the Pade order matters


def test_front_rear_simulation(half):
    psd = random_response(half, "C", 20.0, method="psd", wheelbase=2.7)
    sim = random_response(half, "C", 20.0, method="simulation", wheelbase=2.7, duration=150.0, sample_rate=400.0,
                          seed=9)
    assert np.all(np.abs(sim.rms - psd.rms) < 4 * sim.error + 0.01 * psd.rms)


def test_delay_matters(half):
    """Wheelbase filtering: at wavelength = wheelbase the pitch input cancels; compare two wheelbases."""
    a = random_response(half, "C", 20.0, method="psd", wheelbase=2.7)["pitch_acceleration"]
    b = random_response(half, "C", 20.0, method="psd", wheelbase=1e-6)["pitch_acceleration"]
    assert b < 0.5 * a


# --------------------------------------------------------------------------- left / right tracks
@pytest.fixture(scope="module")
def two_tracks(models):
    """Two identical quarter cars on the left and right tracks; output: the mean of their body accelerations."""
    q = models.quarter_car(300, 60, 16000, 1000, 190000)
    n = q.n_states
    A = np.block([[q.A, np.zeros((n, n))], [np.zeros((n, n)), q.A]])
    B = np.block([[q.B, np.zeros((n, 2))], [np.zeros((n, 2)), q.B]])
    C = 0.5 * np.hstack([q.C[:1], q.C[:1]])
    D = 0.5 * np.hstack([q.D[:1], q.D[:1]])
    return vehdyn.LinearModel(A, B, C, D, states=[f"x{k}" for k in range(2 * n)],
                              inputs=["road_displacement_left", "road_velocity_left", "road_displacement_right",
                                      "road_velocity_right"], outputs=["mean_acceleration"])


def test_track_coherence_limits(two_tracks, car):
    single = random_response(car, "C", 20.0)["sprung_acceleration"]
    for method in ("lyapunov", "psd"):
        same = random_response(two_tracks, "C", 20.0, method=method, track_coherence="identical")
        indep = random_response(two_tracks, "C", 20.0, method=method, track_coherence="independent")
        assert same["mean_acceleration"] == pytest.approx(single, rel=1e-7)
        assert indep["mean_acceleration"] == pytest.approx(single / np.sqrt(2), rel=1e-7)
    iso = random_response(two_tracks, "C", 20.0, method="psd", track_width=1.5)["mean_acceleration"]
    assert single / np.sqrt(2) < iso < single
    sim = random_response(two_tracks, "C", 20.0, method="simulation", track_width=1.5, duration=150.0,
                          sample_rate=400.0, seed=2)
    assert abs(sim["mean_acceleration"] - iso) < 4 * sim.error[0] + 0.01 * iso


def test_errors(car, half, two_tracks):
    with pytest.raises(vehdyn.ParameterError, match="wheelbase"):
        random_response(half, "C", 20.0)
    with pytest.raises(vehdyn.ParameterError, match="track_width"):
        random_response(two_tracks, "C", 20.0, method="psd")
    with pytest.raises(vehdyn.ParameterError, match="isotropic"):
        random_response(two_tracks, "C", 20.0, track_width=1.5)
    with pytest.raises(vehdyn.ParameterError, match="speed"):
        random_response(car, "C", -1.0)
    with pytest.raises(vehdyn.ParameterError, match="method"):
        random_response(car, "C", 10.0, method="guess")
    with pytest.raises(vehdyn.ParameterError, match="pade_order"):
        random_response(half, "C", 10.0, wheelbase=2.7, pade_order=20)
    no_road = vehdyn.LinearModel([[-1.0]], [[1.0]], states=["x"], inputs=["force"])
    with pytest.raises(vehdyn.ParameterError, match="no road input"):
        random_response(no_road, "C", 10.0)


def test_to_frame(car):
    res = random_response(car, "C", 20.0)
    df = res.to_frame()
    assert list(df.index) == list(car.output_names)
    assert df.attrs["units"]["dynamic_tire_load"] == car.output_signals[3].unit
    with pytest.raises(vehdyn.ParameterError, match="no output"):
        res["yaw_rate"]


# --------------------------------------------------------------------------- building blocks
def test_gauss_kronrod_constants_are_exact_on_polynomials():
    """K15 integrates x^k exactly up to degree 22, the embedded G7 up to degree 13 (on [-1, 1])."""
    from vehdyn.ride.random_vibration import GAUSS_7_IN_15, GAUSS_KRONROD_15

    x, wk = GAUSS_KRONROD_15
    for k in range(23):
        exact = 0.0 if k % 2 else 2.0 / (k + 1)
        assert np.sum(wk * x**k) == pytest.approx(exact, abs=1e-14), k
        if k < 14:
            assert np.sum(GAUSS_7_IN_15 * x**k) == pytest.approx(exact, abs=1e-14), k
    assert abs(np.sum(GAUSS_7_IN_15 * x**14) - 2 / 15) > 1e-6  # and no further


def test_lyapunov_route_equals_the_appended_shaping_filter(car):
    """Appending the public shaping filter with connect_in_series and solving the Lyapunov equation directly."""
    from scipy.linalg import solve_continuous_lyapunov

    spec = RoadSpectrum.from_class("C", cut_on=0.03)
    aug = vehdyn.connect_in_series(spec.shaping_filter(20.0), car)
    X = solve_continuous_lyapunov(aug.A, -aug.B @ aug.B.T)  # unit-intensity white noise
    C = aug.C[: car.n_outputs]
    direct = np.sqrt(np.einsum("ij,jk,ik->i", C, X, C))
    np.testing.assert_allclose(random_response(car, spec, 20.0).rms, direct, rtol=1e-10)


def test_weighted_rms_in_the_frequency_domain(car):
    """Wk appended as a state-space filter (Lyapunov) against quad of |Wk(f)|^2 |H(f)|^2 G(f) with weighting_factor."""
    from scipy.integrate import quad

    from vehdyn.ride import weighting, weighting_factor

    wk = weighting("Wk").to_linear_model(input_name="sprung_acceleration", output_name="weighted_acceleration")
    weighted = vehdyn.connect_in_series(car, wk)
    exact = random_response(weighted, "C", 20.0, outputs=["weighted_acceleration"]).rms[0]
    spec = RoadSpectrum.from_class("C")

    def integrand(f):
        H = car.frequency_response([2 * np.pi * f], outputs=["sprung_acceleration"], inputs=["road_displacement"])
        return float(abs(H.response[0, 0, 0]) ** 2 * weighting_factor("Wk", f) ** 2 * spec.temporal_psd(f, 20.0))

    var = sum(quad(integrand, a, b, limit=200, epsrel=1e-10)[0]
              for a, b in ((1e-4, 0.4), (0.4, 2), (2, 20), (20, 200), (200, 1e4)))
    assert exact == pytest.approx(np.sqrt(var), rel=1e-7)


def test_not_a_linear_model():
    class Dummy(vehdyn.Model):
        states = ("x",)
        inputs = ("road_displacement",)
        outputs = ("x",)

        def rhs(self, t, x, u):
            return -x

        def output(self, t, x, u):
            return x

    with pytest.raises(vehdyn.ParameterError, match="LinearModel"):
        random_response(Dummy(), "C", 10.0)


def test_four_corners_with_delays_and_tracks(models):
    """Four quarter cars on the four corners (inputs *_front_left ... *_rear_right), output their mean acceleration."""
    q = models.quarter_car(300, 60, 16000, 1000, 190000)
    n = q.n_states
    corners = ["front_left", "front_right", "rear_left", "rear_right"]
    A = np.kron(np.eye(4), q.A)
    B = np.kron(np.eye(4), q.B)
    C = 0.25 * np.kron(np.ones((1, 4)), q.C[:1])
    D = 0.25 * np.kron(np.ones((1, 4)), q.D[:1])
    inputs = [f"road_{k}_{c}" for c in corners for k in ("displacement", "velocity")]
    car4 = vehdyn.LinearModel(A, B, C, D, states=[f"x{k}" for k in range(4 * n)], inputs=inputs,
                              outputs=["mean_acceleration"])
    # two axles on one track: the same as a model with front and rear inputs only
    two_axle = vehdyn.LinearModel(np.kron(np.eye(2), q.A), np.kron(np.eye(2), q.B),
                                  0.5 * np.kron(np.ones((1, 2)), q.C[:1]), 0.5 * np.kron(np.ones((1, 2)), q.D[:1]),
                                  states=[f"x{k}" for k in range(2 * n)],
                                  inputs=[f"road_{k}_{c}" for c in ("front", "rear") for k in ("displacement",
                                                                                                 "velocity")],
                                  outputs=["mean_acceleration"])
    ref = random_response(two_axle, "C", 20.0, method="psd", wheelbase=2.5).rms[0]
    same = random_response(car4, "C", 20.0, method="psd", wheelbase=2.5, track_coherence="identical").rms[0]
    assert same == pytest.approx(ref, rel=1e-9)
    for coherence in ("identical", "independent"):
        a = random_response(car4, "C", 20.0, wheelbase=2.5, track_coherence=coherence).rms[0]
        b = random_response(car4, "C", 20.0, method="psd", wheelbase=2.5, track_coherence=coherence).rms[0]
        assert a == pytest.approx(b, rel=1e-5), coherence
    iso = random_response(car4, "C", 20.0, method="psd", wheelbase=2.5, track_width=1.5).rms[0]
    indep = random_response(car4, "C", 20.0, method="psd", wheelbase=2.5, track_coherence="independent").rms[0]
    assert indep < iso < same


@pytest.mark.parametrize("speed", [3.0, 20.0])
@pytest.mark.parametrize("cut_on", [0.0, 0.05])
def test_exact_delay_lyapunov_against_psd(half, speed, cut_on):
    """Lagged covariances through e^(A tau): exact at any speed (the Pade route is 2 % off at 5 m/s)."""
    spec = RoadSpectrum.from_class("C", cut_on=cut_on)
    psd = random_response(half, spec, speed, method="psd", wheelbase=2.7)
    exact = random_response(half, spec, speed, wheelbase=2.7, delay="exact")
    np.testing.assert_allclose(exact.rms, psd.rms, rtol=1e-7)
    assert np.all(np.abs(exact.rms - psd.rms) <= psd.error + 1e-9 * psd.rms)


def test_exact_delay_with_independent_tracks(models):
    q = models.quarter_car(300, 60, 16000, 1000, 190000)
    corners = ["front_left", "front_right", "rear_left", "rear_right"]
    car4 = vehdyn.LinearModel(np.kron(np.eye(4), q.A), np.kron(np.eye(4), q.B),
                              np.vstack([0.25 * np.kron(np.ones((1, 4)), q.C[:1]),
                                         np.kron(np.eye(4), q.C[1:2])[3]]),
                              np.vstack([0.25 * np.kron(np.ones((1, 4)), q.D[:1]), np.zeros(8)]),
                              states=[f"x{k}" for k in range(16)],
                              inputs=[f"road_{k}_{c}" for c in corners for k in ("displacement", "velocity")],
                              outputs=["mean_acceleration", "travel_rear_right"])
    for coherence in ("identical", "independent"):
        a = random_response(car4, "B", 8.0, wheelbase=2.5, track_coherence=coherence, delay="exact").rms
        b = random_response(car4, "B", 8.0, method="psd", wheelbase=2.5, track_coherence=coherence).rms
        np.testing.assert_allclose(a, b, rtol=1e-7)
    with pytest.raises(vehdyn.ParameterError, match="delay"):
        random_response(car4, "B", 8.0, wheelbase=2.5, track_coherence="identical", delay="approximate")


def test_pitch_angle_is_finite_and_exact(half):
    """A uniform lift does not pitch the car, so the pitch angle has a finite variance on the ISO road; the
    PSD route's low-frequency end must use the (cancelling) delay terms themselves."""
    pitch = vehdyn.LinearModel(half.A, half.B, np.eye(8)[1:2], np.zeros((1, 2)), states=half.states,
                               inputs=half.inputs, outputs=["pitch_angle"])
    a = random_response(pitch, "C", 20.0, wheelbase=2.7, delay="exact").rms[0]
    b = random_response(pitch, "C", 20.0, method="psd", wheelbase=2.7)
    assert np.isfinite(a) and a > 0
    # within the PSD route's stated bound (most of it the delay terms dropped above f_c, ~2e-7 here)
    assert abs(b.rms[0] - a) <= b.error[0]
    assert b.error[0] < 1e-6 * a


def test_left_right_difference_on_identical_tracks_is_zero(models):
    q = models.quarter_car(300, 60, 16000, 1000, 190000)
    n = q.n_states
    model = vehdyn.LinearModel(np.kron(np.eye(2), q.A), np.kron(np.eye(2), q.B),
                               np.hstack([q.C[:1], -q.C[:1]]), np.hstack([q.D[:1], -q.D[:1]]),
                               states=[f"x{k}" for k in range(2 * n)],
                               inputs=["road_displacement_left", "road_velocity_left", "road_displacement_right",
                                       "road_velocity_right"], outputs=["acceleration_difference"])
    for method in ("lyapunov", "psd"):
        res = random_response(model, "C", 20.0, method=method, track_coherence="identical")
        assert res.rms[0] == pytest.approx(0.0, abs=1e-6)
