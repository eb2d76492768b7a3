"""Preview (pure pursuit), crossover (McRuer) and optimal preview (MacAdam) drivers: closed forms, closed
loops, loop analysis, errors."""

import numpy as np
import pytest

import vehdyn
from vehdyn import ParameterError
from vehdyn.driver import (
    CrossoverDriver,
    OptimalPreviewDriver,
    PreviewDriver,
    driver_loop,
    driver_loop_margins,
    driver_loop_response,
    preview_gains,
)
from vehdyn.handling import SingleTrack
from vehdyn.model import LinearModel

SEDAN = vehdyn.load_vehicle("sedan")
PATH_X = np.linspace(-100.0, 1000.0, 200)


class Integrator(LinearModel):
    """y' = k * front_steer_angle (heading fixed): the loop with a crossover driver is K_p k / s."""

    def __init__(self, k, states=("y", "yaw_angle")):
        n = len(states)
        super().__init__(np.zeros((n, n)), [[k]] + [[0.0]] * (n - 1), states=list(states),
                         inputs=["front_steer_angle"])

    def straight_running(self, speed):
        return np.zeros(2)

    def linearize(self, x0=None, u0=None, t=0.0, *, speed=None):
        return self


@pytest.mark.parametrize("b, T", [(2.0, 1.0), (0.5, 0.6)])
def test_preview_gains_closed_forms(b, T):
    nodes, weights = np.polynomial.legendre.leggauss(8)
    eta = 0.5 * T * (nodes + 1)
    # integrator y' = b delta: delta* = (int_0^T b t dt / int_0^T b^2 t^2 dt) (f - y) = 3 (f - y) / (2 b T)
    q, h = preview_gains([[0.0]], [[b]], [[1.0]], eta, weights)
    assert q.sum() == pytest.approx(3.0 / (2.0 * b * T), rel=1e-12)
    assert h[:, 0] == pytest.approx(np.ones_like(eta))
    # double integrator y'' = b delta: g = b t^2 / 2, h = [1, t] -> gains 10 / (3 b T^2) on y, 5 / (2 b T) on y'
    q, h = preview_gains([[0.0, 1.0], [0.0, 0.0]], [[0.0], [b]], [[1.0, 0.0]], eta, weights)
    assert q.sum() == pytest.approx(10.0 / (3.0 * b * T**2), rel=1e-12)
    assert np.sum(q * h[:, 1]) == pytest.approx(5.0 / (2.0 * b * T), rel=1e-12)


def test_crossover_loop_has_mcruers_closed_forms():
    k, wc, tau, tn = 3.0, 2.0, 0.2, 0.1
    plant = Integrator(k)
    driver = CrossoverDriver.tuned(plant, 20.0, PATH_X, 0 * PATH_X, crossover_frequency=wc, delay=tau,
                                   neuromuscular_lag=tn)
    # |K_p k e^(-tau s) / ((T_N s + 1) s)| = 1 at omega_c
    assert driver.gain == pytest.approx(wc * np.sqrt(1 + (wc * tn) ** 2) / k, rel=1e-12)
    m = driver_loop_margins(plant, driver, 20.0)
    assert m["crossover_frequency"] == pytest.approx(wc, rel=1e-4)
    # McRuer: phase margin pi/2 - omega_c tau_e, here tau_e = tau + atan(omega_c T_N) / omega_c
    assert m["phase_margin"] == pytest.approx(np.pi / 2 - wc * tau - np.arctan(wc * tn), abs=1e-4)
    assert m["stable"]
    # the delay at which the margin vanishes: the closed loop (Pade 6) becomes unstable there
    critical = (np.pi / 2 - np.arctan(wc * tn)) / wc
    for factor, stable in ((0.9, True), (1.1, False)):
        d = CrossoverDriver(PATH_X, 0 * PATH_X, gain=driver.gain, delay=factor * critical, neuromuscular_lag=tn)
        assert driver_loop_margins(plant, d, 20.0)["stable"] is stable


def test_gain_margin_of_the_pure_crossover_loop():
    # L = omega_c e^(-tau s) / s (T_N -> 0): phase -180 deg at pi / (2 tau), gain margin pi / (2 omega_c tau)
    k, wc, tau = 1.0, 1.5, 0.3
    d = CrossoverDriver(PATH_X, 0 * PATH_X, gain=wc / k, delay=tau, neuromuscular_lag=1e-7)
    m = driver_loop_margins(Integrator(k), d, 20.0)
    assert m["phase_crossover_frequency"] == pytest.approx(np.pi / (2 * tau), rel=1e-4)
    assert m["gain_margin"] == pytest.approx(np.pi / (2 * wc * tau), rel=1e-4)


def test_loop_response_of_the_state_space_loop_matches_the_exact_one():
    import control

    model = SingleTrack(SEDAN)
    d = OptimalPreviewDriver(PATH_X, 0 * PATH_X, vehicle=SEDAN, speed=20.0, delay=0.1)
    omega = np.array([0.5, 2.0, 5.0])
    exact = driver_loop_response(model, d, 20.0, omega)
    pade = control.frequency_response(driver_loop(model, d, 20.0, pade_order=8), omega)
    assert np.asarray(pade.complex).ravel() == pytest.approx(exact, rel=1e-6)


def _driver(kind, model, path_y, **options):
    if kind == "preview":
        return PreviewDriver(PATH_X, path_y, wheelbase=SEDAN.geometry.wheelbase, **options)
    if kind == "crossover":
        return CrossoverDriver.tuned(model, 20.0, PATH_X, path_y, **options)
    return OptimalPreviewDriver(PATH_X, path_y, vehicle=SEDAN, speed=20.0, **options)


@pytest.mark.compiled_vs_numpy
@pytest.mark.parametrize("kind", ["preview", "crossover", "optimal"])
def test_drivers_settle_on_an_offset_path_numpy_and_compiled_agree(kind):
    model = SingleTrack(SEDAN)
    path_y = np.full_like(PATH_X, -1.5)
    options = {"preview": dict(preview_time=1.2, lag=0.1), "crossover": dict(preview_time=1.2, delay=0.1),
               "optimal": dict(delay=0.1)}[kind]
    driver = _driver(kind, model, path_y, **options)
    loop = driver.close(model)
    assert loop.state_names[:model.n_states] == model.state_names
    assert loop.state_names[model.n_states:] == driver.state_names
    assert "front_steer_angle" not in loop.input_names  # the driver commands it
    suffix = {"preview": "preview_driver", "crossover": "crossover_driver", "optimal": "optimal_preview_driver"}[kind]
    assert loop.output_names[-1] == "front_steer_angle_after_" + suffix
    t = np.linspace(0, 12, 121)
    x0 = np.concatenate([model.straight_running(20.0), np.zeros(loop.n_states - model.n_states)])
    drag = float(model.parameters.drag_factor) * 400.0
    runs = [vehdyn.simulate(loop, t, {"rear_longitudinal_force": drag}, x0=x0, method="RK45", rtol=1e-9, atol=1e-11,
                            backend=backend) for backend in ("numpy", "compiled")]
    assert "compiled" in runs[1].method_reason
    for r in runs:
        assert r["y"][-1] == pytest.approx(-1.5, abs=0.01)
        assert r["yaw_angle"][-1] == pytest.approx(0.0, abs=1e-3)
    assert runs[1].states == pytest.approx(runs[0].states, abs=1e-6)


def test_driver_errors_name_the_parameter():
    with pytest.raises(ParameterError, match="gain") as info:
        CrossoverDriver(PATH_X, PATH_X, gain=-0.1)
    assert info.value.key == "gain"
    for bad in (np.nan, np.inf, -0.1):
        with pytest.raises(ParameterError, match="delay"):
            CrossoverDriver(PATH_X, PATH_X, gain=0.1, delay=bad)
    with pytest.raises(ParameterError, match="neuromuscular_lag"):
        OptimalPreviewDriver(PATH_X, PATH_X, vehicle=SEDAN, speed=20.0, neuromuscular_lag=0.0)
    with pytest.raises(ParameterError, match="preview_time"):
        OptimalPreviewDriver(PATH_X, PATH_X, vehicle=SEDAN, speed=20.0, preview_time=np.nan)
    with pytest.raises(ParameterError, match="pade_order"):
        CrossoverDriver(PATH_X, PATH_X, gain=0.1, pade_order=0)
    with pytest.raises(ParameterError, match="crossover_frequency"):
        CrossoverDriver.tuned(SingleTrack(SEDAN), 20.0, PATH_X, PATH_X, crossover_frequency=-1.0)
    with pytest.raises(ParameterError, match="path_x"):
        CrossoverDriver(PATH_X[::-1], PATH_X, gain=0.1)


def test_preview_driver_errors_name_the_parameter():
    x = np.linspace(0, 10, 5)
    L = SEDAN.geometry.wheelbase
    with pytest.raises(ParameterError, match="increasing") as info:
        PreviewDriver(x[::-1], x, wheelbase=L)
    assert info.value.key == "path_x"
    with pytest.raises(ParameterError, match="path_x"):
        PreviewDriver(x, x[:3], wheelbase=L)
    for key, value in (("preview_time", 0.0), ("lag", -0.1), ("gain", np.nan), ("wheelbase", 0.0),
                       ("minimum_preview_distance", 0.0), ("max_steer_angle", np.inf), ("speed_gain", 0.0)):
        options = {"wheelbase": L, key: value}
        with pytest.raises(ParameterError, match=key) as info:
            PreviewDriver(x, x, **options)
        assert info.value.key == key and info.value.value is value
    with pytest.raises(TypeError, match="wheelbase"):
        PreviewDriver(x, x)
    with pytest.raises(ParameterError, match="mass") as info:
        PreviewDriver(x, x, wheelbase=L, target_speed=15.0)
    assert info.value.key == "mass"
    for key, value in (("target_speed", np.nan), ("mass", -1500.0)):
        options = {"target_speed": 15.0, "mass": 1500.0, key: value}
        with pytest.raises(ParameterError, match=key) as info:
            PreviewDriver(x, x, wheelbase=L, **options)
        assert info.value.key == key


def test_preview_driver_needs_the_plant_signals_it_reads_and_commands():
    plant = LinearModel(np.zeros((1, 1)), np.zeros((1, 1)), np.eye(1), np.zeros((1, 1)), states=["x"], inputs=["u"],
                        outputs=["x_out"])
    x = np.linspace(0, 10, 5)
    with pytest.raises(ParameterError, match=r"missing inputs \['y', 'yaw_angle', 'longitudinal_velocity', "
                                             r"'front_steer_angle'\]") as info:
        PreviewDriver(x, x, wheelbase=2.5).close(plant)
    assert info.value.key == "missing_inputs"
    # speed control needs the rear axle force: the force-mode SingleTrack has it, the wheel-spin one does not
    driver = PreviewDriver(x, x, wheelbase=2.5, target_speed=15.0, mass=1500.0)
    with pytest.raises(ParameterError, match="rear_longitudinal_force"):
        driver.close(SingleTrack(SEDAN, wheel_spin=True))


def test_driver_on_a_model_without_its_feedback_names_the_missing_inputs():
    driver = OptimalPreviewDriver(PATH_X, 0 * PATH_X, vehicle=SEDAN, speed=20.0)
    with pytest.raises(ParameterError, match=r"missing inputs \['x', 'y', 'yaw_angle'") as info:
        driver.close(vehdyn.handling.LinearBicycle(SEDAN, 20.0))
    assert info.value.key == "missing_inputs"
    with pytest.raises(ParameterError, match=r"missing inputs \['yaw_angle'\]"):
        driver_loop_margins(Integrator(1.0, states=("y", "lateral_velocity", "yaw_rate")), driver, 20.0)


def test_lane_change_limit_brackets_the_speed_at_which_the_cones_are_cleared():
    from vehdyn.procedures import lane_change_limit, lane_change_run, obstacle_avoidance_track

    model = SingleTrack(SEDAN)
    track = obstacle_avoidance_track(SEDAN.geometry.front_track + 0.2)

    def make(speed, **tuning):
        return OptimalPreviewDriver(track.path_x, track.path_y, vehicle=SEDAN, speed=speed, **tuning)

    tunings = [{"preview_time": 0.5, "gain": 1.5, "delay": 0.1}]
    res = lane_change_limit(model, track, make, tunings, throttle="release", speeds=(8.0, 30.0), resolution=1.0)
    assert 8.0 <= res["speed"] < res["failing_speed"] <= res["speed"] + 1.0
    # independent re-runs: passes at the limit, fails at the failing speed
    passing = lane_change_run(model, track, make(res["speed"], **tunings[0]), res["speed"], throttle="release")[1]
    assert passing["passed"]
    fail = lane_change_run(model, track, make(res["failing_speed"], **tunings[0]), res["failing_speed"],
                           throttle="release")[1]
    assert not fail["passed"]
    assert res["failing"][1]["worst_margin"] == pytest.approx(fail["worst_margin"])
    assert res["limiting_factor"] in ("driver", "tire saturation, front axle", "tire saturation, rear axle")
    with pytest.raises(ParameterError, match="tunings"):
        lane_change_limit(model, track, make, [])
    with pytest.raises(ParameterError, match="speeds"):
        lane_change_limit(model, track, make, tunings, speeds=(20.0, 10.0))
    with pytest.raises(ParameterError, match="throttle"):
        lane_change_run(model, track, make(20.0, **tunings[0]), 20.0, throttle="coast")


@pytest.mark.parametrize("kind", ["preview", "crossover", "optimal"])
def test_loop_analysis_matches_the_linearized_closed_loop(kind):
    # the linear driver law of the analysis (perception) is the linearization of the driver's command:
    # the closed-loop poles of driver_loop are poles of the finite-difference linearization of the ClosedLoop
    import control

    model = SingleTrack(SEDAN)
    path_y = np.zeros_like(PATH_X)
    if kind == "preview":
        driver = PreviewDriver(PATH_X, path_y, wheelbase=SEDAN.geometry.wheelbase, preview_time=1.0, lag=0.12)
    elif kind == "crossover":
        driver = CrossoverDriver(PATH_X, path_y, gain=0.03, preview_time=1.0, delay=0.12, pade_order=3)
    else:
        driver = OptimalPreviewDriver(PATH_X, path_y, vehicle=SEDAN, speed=20.0, delay=0.12, pade_order=3)
    loop = driver.close(model)
    x0 = np.concatenate([model.straight_running(20.0), np.zeros(loop.n_states - model.n_states)])
    drag = float(model.parameters.drag_factor) * 400.0
    full = np.linalg.eigvals(loop.linearize(x0, {"rear_longitudinal_force": drag}).A)
    analysed = control.feedback(driver_loop(model, driver, 20.0, pade_order=3), 1.0).poles()
    for pole in analysed:
        assert np.min(np.abs(full - pole)) < 1e-4 * max(1.0, abs(pole))
