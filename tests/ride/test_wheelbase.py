"""Wheelbase delay: exact frequency domain, exact time domain and the Padé state space agree."""

import numpy as np
import pytest

import vehdyn
from vehdyn.ride import BouncePitch, FullCar, QuarterCar, road_frequency_response, road_inputs, wheel_delays, \
    with_wheelbase_delay
from vehdyn.interconnect import pade_coefficients


@pytest.fixture(scope="module")
def half_car():
    return BouncePitch(vehdyn.load_vehicle("sedan"))


def test_pade_error_bound_stated_in_the_docstring():
    """|P_n(j x) - exp(-j x)| < 1e-3 for x < 1.5 n - 3.5 and < 1e-2 for x < 1.6 n - 2.3; |P| = 1."""
    for n in range(4, 11):
        c = pade_coefficients(n)
        for bound, tol in ((1.5 * n - 3.5, 1e-3), (1.6 * n - 2.3, 1e-2)):
            x = np.linspace(0, bound, 2001)
            p = np.polyval((c * (-1.0) ** np.arange(n + 1))[::-1], 1j * x) / np.polyval(c[::-1], 1j * x)
            assert np.max(np.abs(p - np.exp(-1j * x))) < tol
            np.testing.assert_allclose(np.abs(p), 1.0, rtol=1e-12)


def test_pade_state_space_matches_exact_delay_at_low_frequency(half_car):
    speed = 20.0
    tau = half_car.wheelbase / speed
    w = np.linspace(0.1, 5.0 / tau, 300)  # omega tau < 5 < 1.5 * 6 - 3.5
    exact = road_frequency_response(half_car, w, speed=speed, outputs=["sprung_acceleration", "pitch_angle"])
    padé = with_wheelbase_delay(half_car, speed, order=6)
    fr = padé.frequency_response(w, outputs=["sprung_acceleration", "pitch_angle"],
                                 inputs=["road_displacement", "road_velocity"])
    approx = fr.response[:, 0] + 1j * w * fr.response[:, 1]
    scale = np.abs(exact.response[:, 0]).max(axis=1, keepdims=True)
    assert np.max(np.abs(approx - exact.response[:, 0]) / scale) < 2e-3
    assert padé.is_stable()


def test_exact_delay_frequency_response_is_front_plus_delayed_rear(half_car):
    w = np.array([3.0, 17.0])
    per_wheel = road_frequency_response(half_car, w, outputs=["pitch_angle"])
    delayed = road_frequency_response(half_car, w, speed=10.0, outputs=["pitch_angle"])
    tau = half_car.wheelbase / 10.0
    expected = per_wheel.response[0, 0] + np.exp(-1j * w * tau) * per_wheel.response[0, 1]
    np.testing.assert_allclose(delayed.response[0, 0], expected, rtol=1e-13)
    np.testing.assert_allclose(wheel_delays(half_car, 10.0), [0.0, tau])


def test_wheelbase_filtering_cancels_pitch_or_bounce():
    """Symmetric 2-DOF car (a = b, equal rates, DI = 1): pitch vanishes where L / wavelength is whole (Gillespie ch. 5)."""
    bp = BouncePitch.from_parameters(mass=1000.0, pitch_inertia=1000.0 * 1.3**2, a=1.3, b=1.3, front_spring_rate=3e4,
                                     rear_spring_rate=3e4, front_damping=2e3, rear_damping=2e3)
    speed = 13.0
    L = 2.6
    w = 2 * np.pi * speed / np.array([L, L / 2])  # wavelength = L, L/2: front and rear in phase
    fr = road_frequency_response(bp, w, speed=speed, outputs=["pitch_angle", "sprung_displacement"])
    np.testing.assert_allclose(np.abs(fr.response[0, 0]), 0.0, atol=1e-14)
    w_anti = 2 * np.pi * speed / (2 * L)  # wavelength 2L: antiphase, no bounce
    fr = road_frequency_response(bp, [w_anti], speed=speed, outputs=["sprung_displacement"])
    assert abs(fr.response[0, 0, 0]) < 1e-14


def test_time_domain_exact_delay_agrees_with_pade(half_car):
    speed = 20.0
    t = np.linspace(0, 4, 1601)
    s = np.linspace(0, 120, 6001)
    ramp = 0.5 * (1 - np.cos(np.pi * np.clip((s - 10.0) / 16.0, 0.0, 1.0)))  # smooth onset over 16 m
    z = 0.01 * np.sin(2 * np.pi * s / 8.0) * ramp  # 2.5 Hz at 20 m/s: omega tau = 2.0
    exact = vehdyn.simulate(half_car, t, inputs=road_inputs(half_car, t, speed, s, z), method="exact")
    front = road_inputs(QuarterCar(vehdyn.load_vehicle("sedan")), t, speed, s, z)
    padé = with_wheelbase_delay(half_car, speed, order=6)
    approx = vehdyn.simulate(padé, t, inputs=front, method="exact")
    peak = np.max(np.abs(exact["pitch_angle"]))
    assert np.max(np.abs(exact["pitch_angle"] - approx["pitch_angle"])) < 2e-3 * peak
    # the rear input is the front input a wheelbase later
    ins = road_inputs(half_car, t, speed, s, z)
    lag = int(round(half_car.wheelbase / speed / (t[1] - t[0])))
    np.testing.assert_allclose(ins["road_displacement_rear"][lag + 50:], ins["road_displacement_front"][50:-lag],
                               atol=2e-4)


def test_full_car_tracks():
    fc = FullCar(vehdyn.load_vehicle("van"))
    model = with_wheelbase_delay(fc, 25.0, order=4)
    assert model.input_names == ("road_displacement_left", "road_velocity_left", "road_displacement_right",
                                 "road_velocity_right")
    fr = road_frequency_response(fc, [5.0], speed=25.0, outputs=["roll_angle"])
    # antisymmetric road (left up, right down) rolls the car; the two tracks act with opposite signs
    assert fr.response[0, 0, 0] == pytest.approx(-fr.response[0, 1, 0], rel=1e-10)
    t = np.linspace(0, 1, 11)
    ins = road_inputs(fc, t, 25.0, [0.0, 100.0], [0.0, 1.0], elevation_right=[0.0, 0.0])
    assert np.all(ins["road_displacement_front_right"] == 0.0)
    np.testing.assert_allclose(ins["road_velocity_front_left"], 0.25)


def test_quarter_car_has_no_delay():
    qc = QuarterCar.from_parameters(sprung_mass=300.0, unsprung_mass=40.0, spring_rate=2e4, tire_stiffness=2e5)
    assert with_wheelbase_delay(qc, 20.0) is qc


@pytest.mark.parametrize("bad", [0.0, -3.0, float("inf"), "fast"])
def test_bad_speed(half_car, bad):
    with pytest.raises(vehdyn.ParameterError) as err:
        with_wheelbase_delay(half_car, bad)
    assert err.value.key == "speed"


def test_bad_profile_and_order(half_car):
    with pytest.raises(vehdyn.ParameterError):
        road_inputs(half_car, [0, 1], 10.0, [0.0, 0.0], [0.0, 0.0])
    with pytest.raises(vehdyn.ParameterError):
        road_inputs(half_car, [0, 1], 10.0, [0.0, 1.0], [0.0, 0.0, 1.0])
    with pytest.raises(vehdyn.ParameterError):
        with_wheelbase_delay(half_car, 10.0, order=0)


def test_pade_routes_share_one_delay(half_car):
    """random_response's Padé route and with_wheelbase_delay + the road's shaping filter + stationary_covariance
    build the same Padé-delayed car in two ways: equal variances; the exact delay (default) differs by the
    Padé error only."""
    from vehdyn.road import RoadSpectrum
    from vehdyn.ride import random_response, stationary_covariance

    speed, outputs = 10.0, ["sprung_acceleration", "pitch_acceleration", "suspension_travel_rear"]
    spectrum = RoadSpectrum.from_class("C", cut_on=0.01)
    pade = random_response(half_car, spectrum, speed, outputs=outputs, delay="pade", pade_order=6)
    delayed = with_wheelbase_delay(half_car, speed, order=6).select(outputs=outputs)
    car = vehdyn.connect_in_series(spectrum.shaping_filter(speed), delayed)
    Y = stationary_covariance(car.A, car.B, car.C, car.D)
    np.testing.assert_allclose(pade.rms, np.sqrt(np.diag(Y))[:3], rtol=1e-9)  # then the filter's own outputs
    exact = random_response(half_car, spectrum, speed, outputs=outputs)  # wheelbase from the model
    assert 1e-6 < np.max(np.abs(pade.rms / exact.rms - 1)) < 0.05


def test_road_inputs_on_any_time_grid_sample_the_profile_exactly_at_the_nodes():
    """Synthesized profile: on a time grid whose positions fall on the profile's nodes the inputs are the sum of
    cosines itself (independent, direct evaluation); off the profile the elevation is held, the velocity zero."""
    from vehdyn.road import synthesize_profile

    p = synthesize_profile("C", 32.0, 0.05, seed=2, n_max=4.0)
    n = np.arange(p.coefficients.size) / p.length

    def direct(x, deriv=False):
        e = np.exp(2j * np.pi * np.outer(x, n))
        return np.real(e @ (p.coefficients * (2j * np.pi * n if deriv else 1)))

    V = 10.0
    t = np.arange(0, 400) * p.spacing / V  # nodes 0..399
    offset = 20 * p.spacing
    _, u = p.road_inputs(V, {"_front": 0.0, "_rear": offset}, time=t)
    np.testing.assert_allclose(u["road_displacement_front"], direct(V * t), atol=1e-12)
    np.testing.assert_allclose(u["road_velocity_front"], V * direct(V * t, True), atol=1e-9)
    inside = V * t >= offset
    np.testing.assert_allclose(u["road_displacement_rear"][inside], direct(V * t[inside] - offset), atol=1e-12)
    np.testing.assert_allclose(u["road_displacement_rear"][~inside], p.elevation[0])
    assert np.all(u["road_velocity_rear"][~inside] == 0.0)
