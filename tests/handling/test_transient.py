"""Transient handling: ISO 7401 step metrics (A-STEP-*), yaw mode (A-MODAL-*), frequency response (A-FRF-ABE)."""

import numpy as np
import pytest

import vehdyn
from vehdyn import conventions
from vehdyn.handling import (
    LinearBicycle,
    lateral_acceleration_transfer_function,
    steering_frequency_response,
    yaw_mode,
    yaw_rate_transfer_function,
)
from vehdyn.procedures import step_response_metrics, step_steer_metrics


@pytest.mark.parametrize("case_id", ["A-STEP-ABE", "A-STEP-SUV"])
def test_step_steer_metrics(case_id, reference_case, case_bicycle, approx_case):
    case = reference_case(case_id)
    i = {k: v[0] for k, v in case["inputs"].items()}
    e = case["expected"]
    car = case_bicycle(case, speed=i["V"])
    # the case steers to the LEFT (ISO 8855); vehdyn's SAE steer angle is its negative
    delta_sae = float(conventions.steer_angle_iso8855_to_sae(np.deg2rad(i["delta_step_front_wheel"])))
    t = np.linspace(0.0, 6.0, 6001)
    res = vehdyn.simulate(car, t, {"front_steer_angle": delta_sae}, method="exact")
    metrics = step_steer_metrics(res, signals=("yaw_rate", "lateral_acceleration", "sideslip_angle"))
    yaw, ay, beta = metrics["yaw_rate"], metrics["lateral_acceleration"], metrics["sideslip_angle"]

    def iso_yaw_rate(r_sae):  # rotation about z: SAE -> ISO flips the sign
        return conventions.rotation_sae_to_iso8855(0.0, 0.0, r_sae)[2]

    def iso_lateral(ay_sae):  # vector component along y flips
        return conventions.sae_to_iso8855(0.0, ay_sae, 0.0)[1]

    assert np.rad2deg(iso_yaw_rate(yaw.steady_state_value)) == approx_case(e["r_steady"])
    assert iso_lateral(ay.steady_state_value) == approx_case(e["ay_steady"])
    # sideslip is the angle of the velocity from x about z: it flips like the yaw rate
    assert np.rad2deg(iso_yaw_rate(beta.steady_state_value)) == approx_case(e["beta_steady"])
    k02 = np.searchsorted(t, 0.2)
    assert np.rad2deg(iso_yaw_rate(res["yaw_rate"][k02])) == approx_case(e["r_at_t0.2s"])
    assert iso_lateral(res["lateral_acceleration"][k02]) == approx_case(e["ay_at_t0.2s"])
    assert yaw.response_time == approx_case(e["t90_yaw_rate_response_time"])
    assert ay.response_time == approx_case(e["t90_lateral_acc"])
    assert np.rad2deg(iso_yaw_rate(yaw.peak_value)) == approx_case(e["r_peak"])
    assert yaw.peak_response_time == approx_case(e["t_peak_yaw_rate"])
    assert 100 * yaw.overshoot == approx_case(e["yaw_rate_overshoot"])
    t50 = step_response_metrics(res, "yaw_rate")
    assert t50.step_time == 0.0


def test_metrics_of_second_order_system_equal_closed_forms():
    """Underdamped s.o.s. wn^2/(s^2 + 2 zeta wn s + wn^2): overshoot exp(-zeta pi / sqrt(1 - zeta^2)),
    peak time pi / wd (Ogata, Modern Control Engineering, sec. 5-3)."""
    wn, zeta = 6.0, 0.35
    sys = vehdyn.LinearModel([[0, 1], [-wn**2, -2 * zeta * wn]], [[0], [wn**2]], states=["position", "rate"],
                             inputs=["front_steer_angle"])
    t = np.linspace(0.0, 8.0, 8001)
    res = vehdyn.simulate(sys, t, {"front_steer_angle": 1.0})
    m = step_response_metrics(res, "position")
    wd = wn * np.sqrt(1 - zeta**2)
    assert m.overshoot == pytest.approx(np.exp(-zeta * np.pi / np.sqrt(1 - zeta**2)), rel=1e-6)
    # the peak is refined by a parabola through three samples: error O(dt^2) = 1e-6 s here
    assert m.peak_response_time == pytest.approx(np.pi / wd, rel=1e-5)
    assert m.steady_state_value == pytest.approx(1.0, rel=1e-6)


def test_metrics_of_first_order_system_and_step_time_from_a_ramp():
    """1 - exp(-t/tau): t90 = tau ln 10, 10-90 % rise time tau ln 9, no overshoot; the origin is 50 % of a ramp."""
    tau = 0.3
    sys = vehdyn.LinearModel([[-1 / tau]], [[1 / tau]], states=["yaw_rate"], inputs=["front_steer_angle"])
    t = np.linspace(0.0, 6.0, 6001)
    ramp = np.clip((t - 1.0) / 0.2, 0.0, 1.0) * 0.02  # 0.2-s ramp starting at 1 s
    res = vehdyn.simulate(sys, t, {"front_steer_angle": ramp})
    m = step_response_metrics(res, "yaw_rate")
    assert m.step_time == pytest.approx(1.1, abs=1e-9)
    # response to a ramp of duration T: the step response delayed by T/2 to first order in T/tau
    exact_t90 = _first_crossing(t, _ramp_response(t, tau, 1.0, 0.2), 0.9) - 1.1
    assert m.response_time == pytest.approx(exact_t90, rel=1e-5)
    assert m.overshoot == 0.0 and np.isnan(m.peak_response_time)
    step = vehdyn.simulate(sys, t, {"front_steer_angle": 0.02})
    ms = step_response_metrics(step, "yaw_rate")
    assert ms.response_time == pytest.approx(tau * np.log(10), rel=1e-6)
    assert ms.rise_time == pytest.approx(tau * np.log(9), rel=1e-6)


def _ramp_response(t, tau, t0, T):
    """Closed-form response of tau y' + y = ramp from t0 over T to 1."""
    s = np.clip(t - t0, 0.0, None)
    part = (s - tau * (1 - np.exp(-s / tau))) / T
    late = np.clip(t - t0 - T, 0.0, None)
    return part - (late - tau * (1 - np.exp(-late / tau))) / T


def _first_crossing(t, y, level):
    k = np.argmax(y >= level)
    return t[k - 1] + (level - y[k - 1]) / (y[k] - y[k - 1]) * (t[k] - t[k - 1])


def test_metrics_vectorize_over_a_batch():
    sedan = vehdyn.load_vehicle("sedan")
    car = LinearBicycle(sedan, 25.0)
    t = np.linspace(0.0, 5.0, 2501)
    deltas = np.array([0.01, 0.02, 0.03])
    u = np.zeros((2, t.size, deltas.size))
    u[0] = deltas
    batch = vehdyn.simulate(car, t, u)
    mb = step_response_metrics(batch, "yaw_rate")
    for k, d in enumerate(deltas):
        single = step_response_metrics(vehdyn.simulate(car, t, {"front_steer_angle": d}), "yaw_rate")
        assert mb.response_time[k] == pytest.approx(float(single.response_time), rel=1e-12)
        assert mb.steady_state_value[k] == pytest.approx(float(single.steady_state_value), rel=1e-12)
    # linear model: the response time and the overshoot do not depend on the steer amplitude
    np.testing.assert_allclose(mb.response_time, mb.response_time[0], rtol=1e-9)
    np.testing.assert_allclose(mb.overshoot, mb.overshoot[0], rtol=1e-9)
    assert len(mb.to_frame()) == 3


def test_metric_errors():
    car = LinearBicycle(vehdyn.load_vehicle("sedan"), 25.0)
    res = vehdyn.simulate(car, np.linspace(0, 2, 201), {"front_steer_angle": 0.01})
    with pytest.raises(vehdyn.ParameterError, match="step_time"):
        step_response_metrics(res, "yaw_rate", step_time=5.0)
    with pytest.raises(vehdyn.ParameterError, match="steady_window"):
        step_response_metrics(res, "yaw_rate", steady_window=10.0)
    with pytest.raises(vehdyn.ParameterError, match="steer"):
        step_response_metrics(res, "yaw_rate", steer=None)


@pytest.mark.parametrize("case_id", ["A-MODAL-ABE", "A-MODAL-SUV", "A-MODAL-OVR"])
def test_yaw_mode_against_speed(case_id, reference_case, case_bicycle, approx_case):
    case = reference_case(case_id)
    speeds = np.array(case["inputs"]["speeds"][0])
    car = case_bicycle(case)
    mode = yaw_mode(car, speeds)
    e = case["expected"]
    for k, u in enumerate(speeds):
        tag = f"@{u:g}mps"
        assert mode.natural_frequency_squared[k] == approx_case(e["wn2" + tag])
        eig = np.sort_complex(np.linalg.eigvals(car.at_speed(u).A))  # independent route: eig of A
        if e["wn2" + tag][0] > 0:
            assert mode.natural_frequency[k] == approx_case(e["wn" + tag])
            assert mode.natural_frequency_hz[k] == approx_case(e["fn" + tag])
            assert mode.damping_ratio[k] == approx_case(e["zeta" + tag])
            assert np.sqrt(np.prod(eig).real) == approx_case(e["wn" + tag])  # wn^2 = lambda1 lambda2
            assert -np.sum(eig).real / (2 * mode.natural_frequency[k]) == approx_case(e["zeta" + tag])
        if "eig_real" + tag in e:
            assert eig[0].real == approx_case(e["eig_real" + tag])
            assert abs(eig[0].imag) == approx_case(e["eig_imag_abs" + tag])
            assert mode.eigenvalues[0, k].real == approx_case(e["eig_real" + tag])
        if "eig1" + tag in e:
            assert eig.real[0] == approx_case(e["eig1" + tag])
            assert eig.real[1] == approx_case(e["eig2" + tag])
            np.testing.assert_allclose(np.sort(mode.eigenvalues[:, k].real), eig.real, rtol=1e-10)
    if case_id == "A-MODAL-OVR":
        assert not mode.stable[-1] and np.isnan(mode.natural_frequency[-1])


def test_frequency_response(reference_case, case_bicycle, approx_case):
    from scipy import signal

    case = reference_case("A-FRF-ABE")
    V = case["inputs"]["V"][0]
    car = case_bicycle(case, speed=V)
    e = case["expected"]
    freqs = np.array([0.5, 1.0, 2.0])
    fr = steering_frequency_response(car, 2 * np.pi * freqs)
    num_r, den = yaw_rate_transfer_function(car)
    num_a, _ = lateral_acceleration_transfer_function(car)
    _, h_r = signal.freqs(num_r, den, 2 * np.pi * freqs)
    _, h_a = signal.freqs(num_a, den, 2 * np.pi * freqs)
    assert np.abs(fr.response[0, 0, 0]) > 0
    assert num_r[-1] / den[-1] == approx_case(e["|r/delta|@0Hz"])
    for k, f in enumerate(freqs):
        tag = f"@{f:g}Hz"
        r, ay = fr["yaw_rate", "front_steer_angle"][k], fr["lateral_acceleration", "front_steer_angle"][k]
        for h_model, h_tf, name in ((r, h_r[k], "r"), (ay, h_a[k], "ay")):
            assert abs(h_model) == approx_case(e[f"|{name}/delta|" + tag])
            assert np.rad2deg(np.angle(h_model)) == approx_case(e[f"phase_{name}/delta" + tag])
            assert h_tf == pytest.approx(h_model, rel=1e-12)


def test_frequency_response_of_a_vehicle_at_other_speeds():
    van = vehdyn.load_vehicle("van")
    omega = np.array([1.0, 5.0])
    a = steering_frequency_response(van, omega, 30.0)
    b = steering_frequency_response(LinearBicycle(van, 10.0), omega, 30.0)
    np.testing.assert_allclose(a.response, b.response, rtol=1e-14)
    lag = steering_frequency_response(van, omega, 30.0, tire_lag=True)
    assert not np.allclose(lag.response, a.response)
