"""The compiled closed loops (numba) against the numpy ones: laws equal at random points, trajectories within the
integrator's error, stopping distances; fallback to numpy; ESC and ABS around the full vehicle (compiled)."""

import numpy as np
import pytest

import vehdyn
from vehdyn import LinearModel, ParameterError
from vehdyn.chassis import ABS, ESC, ClosedLoop, TractionControl, road_friction_tire
from vehdyn.full_vehicle import FullVehicle
from vehdyn.handling import DriverInTheLoop, PreviewDriver, SingleTrack, fmvss126
from vehdyn.tire import tire_for_vehicle

pytest.importorskip("numba")

CAR = vehdyn.load_vehicle("sedan")
G = vehdyn.units.GRAVITY
WHEELS = ("front_left", "front_right", "rear_left", "rear_right")


def _tires(mu):
    loads = CAR.static_axle_loads()
    return [road_friction_tire(tire_for_vehicle(CAR, a), mu, 0.5 * w) for a, w in zip(("front", "rear"), loads)]


def _loops():
    spin = SingleTrack(CAR, wheel_spin=True)
    full = FullVehicle(CAR)
    return {
        "abs": ClosedLoop(spin, ABS(CAR)),
        "traction_control": ClosedLoop(spin, TractionControl(CAR)),
        "esc_force": ClosedLoop(SingleTrack(CAR), ESC(CAR)),
        "esc_around_abs": ClosedLoop(ClosedLoop(spin, ABS(CAR)), ESC(CAR, wheel_spin=True)),
        "full_esc_around_abs": ClosedLoop(ClosedLoop(full, ABS(CAR, corners=True)), ESC(CAR, corners=True)),
        "full_traction_control": ClosedLoop(full, TractionControl(CAR, corners=True)),
    }


@pytest.mark.compiled_vs_numpy
@pytest.mark.parametrize("name", list(_loops()))
def test_compiled_rhs_and_outputs_equal_the_numpy_ones(name):
    loop = _loops()[name]
    compiled = loop.compiled_rhs()
    assert compiled is not None and compiled.output is not None
    rng = np.random.default_rng(7)
    base = loop.plant
    while isinstance(base, ClosedLoop):
        base = base.plant
    x_car = base.trim(20.0)[0] if isinstance(base, FullVehicle) else base.straight_running(20.0)
    for _ in range(20):
        x = loop.state_vector(dict(zip(base.state_names, x_car)))
        x[:2] += rng.normal(0.0, [2.0, 1.0])  # speed, sideslip
        x[base.index("yaw_rate")] = rng.normal(0.0, 0.5)
        for k, state in enumerate(loop.state_names):
            if "wheel_speed" in state:
                x[k] *= 1.0 + rng.uniform(-0.3, 0.3)  # braking and spinning wheels
            if state.endswith("brake_torque") and k >= base.n_states:
                x[k] = rng.uniform(-100.0, 1500.0)
            if state == "engine_torque_reduction":
                x[k] = rng.uniform(-0.1, 1.1)
        u = loop.input_vector()
        for k, signal in enumerate(loop.input_names):
            if "torque" in signal or "force" in signal or "moment" in signal:
                u[k] = rng.uniform(-200.0, 2000.0)
        u[loop.index("front_steer_angle", "inputs")] = rng.normal(0.0, 0.05)
        dxdt = np.empty(loop.n_states)
        compiled.rhs(0.0, x, u, compiled.args, dxdt)
        expected = loop.rhs(0.0, x, u)
        np.testing.assert_allclose(dxdt, expected, rtol=1e-12, atol=1e-12 * np.max(np.abs(expected)))
        y = np.empty(loop.n_outputs)
        compiled.output(0.0, x, u, compiled.args, y)
        expected = loop.output(0.0, x, u)
        np.testing.assert_allclose(y, expected, rtol=1e-12, atol=1e-12 * np.max(np.abs(expected)))


def _panic(speed, mu, backend, rtol, duration=1.0):
    plant = SingleTrack(CAR, *_tires(mu), wheel_spin=True)
    loop = ClosedLoop(plant, ABS(CAR))
    torque = 1.2 * CAR.mass.mass * G * CAR.tires.rolling_radius
    x0 = loop.state_vector(dict(zip(plant.state_names, plant.straight_running(speed))))
    t = np.linspace(0.0, duration, 41)
    return vehdyn.simulate(loop, t, {"front_brake_torque": 0.7 * torque, "rear_brake_torque": 0.3 * torque}, x0=x0,
                           method="RK45", rtol=rtol, atol=rtol * 1e-2, max_step=0.05, backend=backend)


@pytest.mark.compiled_vs_numpy
@pytest.mark.parametrize("mu", [0.9, 0.5, 0.2])
def test_compiled_abs_braking_equals_solve_ivp_within_the_integration_error(mu):
    # The same RK45 with the same step control on the same rhs: where both take the same steps the states agree
    # to rounding; where one accepts a step the other rejects (error norms equal to rounding), they differ by the
    # local error, which the apply/release cycles amplify (measured at rtol 1e-8: up to 6e-8 in speed, 3e-6 in
    # wheel speed, 3e-5 in brake torque, relative to the peak; 1e-6, 3e-4 and 2e-3 at rtol 1e-6 over 1 s).
    runs = {backend: _panic(20.0, mu, backend, 1e-8, duration=0.6) for backend in ("numpy", "compiled")}
    assert "compiled" in runs["compiled"].method_reason and "compiled" not in runs["numpy"].method_reason
    for name, bound in (("longitudinal_velocity", 1e-6), ("x", 1e-6), ("front_wheel_speed", 1e-4),
                        ("front_abs_brake_torque", 1e-3)):
        reference = runs["numpy"][name]
        assert np.max(np.abs(runs["compiled"][name] - reference)) < bound * np.max(np.abs(reference)), name


@pytest.mark.compiled_vs_numpy
def test_compiled_abs_stopping_distance_equals_numpy():
    # the stopping distance (speed below 2 m/s) from 72 km/h on mu 0.5 at a loose tolerance, both backends
    distances = {}
    for backend in ("numpy", "compiled"):
        r = _panic(20.0, 0.5, backend, 1e-4, duration=4.5)
        k = int(np.argmax(r["longitudinal_velocity"] < 2.0))
        assert k > 0
        distances[backend] = np.interp(2.0, r["longitudinal_velocity"][[k, k - 1]], r["x"][[k, k - 1]])
    # friction-limited: v0^2 / (2 mu g) = 40.8 m to rest
    assert 35.0 < distances["compiled"] < 45.0
    assert distances["compiled"] == pytest.approx(distances["numpy"], rel=2e-3)


@pytest.mark.compiled_vs_numpy
def test_compiled_driver_around_abs_equals_numpy():
    plant = SingleTrack(CAR, *_tires(0.5), wheel_spin=True)
    path_x = np.linspace(-10.0, 100.0, 221)
    path_y = -1.5 * np.clip(path_x / 40.0, 0.0, 1.0) ** 2
    loop = DriverInTheLoop(ClosedLoop(plant, ABS(CAR)), PreviewDriver(path_x, path_y, preview_time=0.6, lag=0.1),
                           wheelbase=CAR.geometry.wheelbase)
    x0 = loop.state_vector(dict(zip(plant.state_names, plant.straight_running(15.0))))
    x0[-1] = 0.01
    u = loop.input_vector(front_brake_torque=3000.0, rear_brake_torque=1000.0)
    compiled = loop.compiled_rhs()
    dxdt = np.empty(loop.n_states)
    compiled.rhs(0.0, x0, u, compiled.args, dxdt)
    np.testing.assert_allclose(dxdt, loop.rhs(0.0, x0, u), rtol=1e-12, atol=1e-12)
    t = np.linspace(0.0, 1.0, 21)
    runs = [vehdyn.simulate(loop, t, {"front_brake_torque": 3000.0, "rear_brake_torque": 1000.0}, x0=x0,
                            method="RK45", rtol=1e-8, atol=1e-10, max_step=0.05, backend=backend)
            for backend in ("numpy", "compiled")]
    assert "compiled" in runs[1].method_reason
    for name in ("y", "driver_steer_angle"):
        assert np.max(np.abs(runs[1][name] - runs[0][name])) < 1e-5 * np.max(np.abs(runs[0][name])), name


@pytest.mark.compiled_vs_numpy
def test_compiled_driver_with_speed_control_equals_numpy():
    plant = SingleTrack(CAR)
    path_x = np.linspace(-10.0, 100.0, 111)
    driver = PreviewDriver(path_x, np.sin(path_x / 20.0), preview_time=0.8, lag=0.1, target_speed=18.0)
    loop = DriverInTheLoop(plant, driver, wheelbase=CAR.geometry.wheelbase, mass=CAR.mass.mass)
    compiled = loop.compiled_rhs()
    rng = np.random.default_rng(3)
    for _ in range(5):
        x = np.concatenate([plant.straight_running(15.0), [0.0]]) + rng.normal(0.0, 0.2, loop.n_states)
        u = rng.normal(0.0, 100.0, loop.n_inputs)
        dxdt, y = np.empty(loop.n_states), np.empty(loop.n_outputs)
        compiled.rhs(0.0, x, u, compiled.args, dxdt)
        compiled.output(0.0, x, u, compiled.args, y)
        np.testing.assert_allclose(dxdt, loop.rhs(0.0, x, u), rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(y, loop.output(0.0, x, u), rtol=1e-12, atol=1e-9)


def test_loop_without_compiled_parts_falls_back_to_numpy():
    A = np.array([[-1.0]])
    ctrl = LinearModel(A, np.array([[0.0, 1.0]]), np.array([[2.0]]), np.array([[1.0, 0.0]]), states=["integral"],
                       inputs=["front_brake_torque", "yaw_rate"], outputs=["front_brake_torque"])
    loop = ClosedLoop(SingleTrack(CAR, wheel_spin=True), ctrl)
    assert loop.compiled_rhs() is None
    x0 = loop.state_vector(dict(zip(loop.plant.state_names, loop.plant.straight_running(20.0))))
    t = np.linspace(0.0, 0.2, 5)
    r = vehdyn.simulate(loop, t, x0=x0, method="RK45", rtol=1e-4)
    assert "compiled" not in r.method_reason
    with pytest.raises(ParameterError, match="has no compiled rhs"):
        vehdyn.simulate(loop, t, x0=x0, method="RK45", backend="compiled")


def test_fullvehicle_with_esc_passes_fmvss126_where_it_fails_alone():
    # 8 A: within the standard's series (up to 6.5 A or 270 deg at the hand wheel, whichever is larger)
    kwargs = dict(plant="full_vehicle", amplitude_multiples=[8.0], directions=("clockwise",))
    alone = fmvss126(CAR, **kwargs)
    assert not alone.passed and alone.runs[0]["yaw_rate_ratio_1000ms"] > 0.35
    with_esc = fmvss126(CAR, ESC(CAR, corners=True), **kwargs)
    run = with_esc.runs[0]
    assert with_esc.passed, with_esc.failures()
    assert run["yaw_rate_ratio_1000ms"] <= 0.35 and run["yaw_rate_ratio_1750ms"] <= 0.20
    assert run["lateral_displacement"] >= 1.83
    # the ESC of the single track's signals cannot drive the full vehicle: the missing inputs are named
    with pytest.raises(ParameterError, match="front_longitudinal_force") as info:
        fmvss126(CAR, ESC(CAR), **kwargs)
    assert "corners=True" in str(info.value)


def test_fmvss126_bad_plant():
    with pytest.raises(ParameterError, match="plant"):
        fmvss126(CAR, plant="bicycle")


def test_esc_on_the_full_vehicle_brakes_the_outer_front_wheel_when_oversteering():
    esc = ESC(CAR, corners=True)
    assert esc.output_names == tuple(f"brake_torque_{w}" for w in WHEELS)
    # turning right faster than the reference: the outer (left) front channel is commanded
    u = esc.input_vector(front_steer_angle=0.01, longitudinal_velocity=20.0, yaw_rate=0.6,
                         brake_torque_rear_right=100.0)
    rates = esc.rhs(0.0, np.zeros(4), u)
    assert rates[0] > 0 and rates[0] > 100 * np.max(np.abs(rates[1:]))
    out = esc.output(0.0, np.array([300.0, 0.0, 0.0, 0.0]), u)
    np.testing.assert_allclose(out, [300.0, 0.0, 0.0, 100.0])  # ESC torque added to the driver's demand


@pytest.mark.parametrize("mu", [0.9, 0.5, 0.2])
def test_abs_on_the_compiled_full_vehicle_holds_slip_on_every_road(mu):
    plant = FullVehicle(CAR, *_tires(mu))
    abs_ = ABS(CAR, corners=True)
    loop = ClosedLoop(plant, abs_)
    x0 = plant.trim(20.0)[0]
    torque = 1.2 * CAR.mass.mass * G * CAR.tires.rolling_radius / 2
    demand = {f"brake_torque_{w}": (0.7 if w.startswith("front") else 0.3) * torque for w in WHEELS}
    t = np.linspace(0.0, 1.0, 41)
    r = vehdyn.simulate(loop, t, demand, x0=loop.state_vector(dict(zip(plant.state_names, x0))), method="RK45",
                        rtol=1e-4, atol=1e-6, max_step=0.05)
    assert "compiled" in r.method_reason
    late = r.time >= 0.3
    for c in abs_.channels:
        slip = abs_.braking_slip(r[f"wheel_speed_{c}"], r["longitudinal_velocity"])
        assert np.all(np.isfinite(slip)), c
        assert np.all(slip[late] > 0.5 * abs_.apply_slip) and np.all(slip[late] < abs_.release_slip + 0.05), c
    decel = -np.mean(r["longitudinal_acceleration"][late])
    assert 0.85 * mu * G < decel < 1.05 * mu * G
