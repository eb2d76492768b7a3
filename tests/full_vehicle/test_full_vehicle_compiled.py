"""The compiled FullVehicle (one source with the numpy equations) against the numpy rhs and solve_ivp."""

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import vehdyn
from vehdyn.full_vehicle import FullVehicle
from vehdyn.procedures import sine_steer, step_steer
from vehdyn.road import RoadProfile
from vehdyn.tire import FialaTire, LinearTire

pytest.importorskip("numba")

SEDAN = vehdyn.load_vehicle("sedan")
CAMBERED = SEDAN.replace(suspension__front_camber_gain=0.5, suspension__rear_camber_gain=0.3)
_distance = np.arange(0.0, 60.0, 0.05)
BUMPY = RoadProfile(_distance, 0.015 * (1.0 - np.cos(2 * np.pi * (_distance - 5.0) / 3.0)) * (_distance > 5.0))
LINEAR = (LinearTire.from_vehicle(SEDAN, "front"), LinearTire.from_vehicle(SEDAN, "rear"))
MODELS = {
    "magic_formula": FullVehicle(SEDAN),
    "magic_formula_no_lag": FullVehicle(SEDAN, tire_lag=False),
    "linear": FullVehicle(SEDAN, *LINEAR),
    "camber_magic_formula_front_linear_rear": FullVehicle(CAMBERED, None, LINEAR[1]),
    "road_profile": FullVehicle(SEDAN, road=BUMPY),
    "friction": FullVehicle(SEDAN, friction=0.6),  # a constant road friction ratio compiles
}


def random_point(model, data):
    """A state and input anywhere the model works: reverse through standstill to speed, wheels spinning
    and locking, lifted wheels (unsprung displacement above the static tire deflection), deflections,
    roll and pitch inside the domain, any heading and position (on the road profile)."""
    floats = st.floats(-1.0, 1.0)
    r = np.array(data.draw(st.lists(floats, min_size=model.n_states, max_size=model.n_states)))
    v = np.array(data.draw(st.lists(floats, min_size=model.n_inputs, max_size=model.n_inputs)))
    speed = data.draw(st.one_of(st.floats(-35.0, 35.0), st.floats(-0.5, 0.5)))
    x = model.state_vector()
    names = model.state_names
    scale = {"longitudinal_velocity": 0.0, "lateral_velocity": 3.0, "vertical_velocity": 0.5, "roll_rate": 1.0,
             "pitch_rate": 0.5, "yaw_rate": 1.0, "roll_angle": 0.5, "pitch_angle": 0.3, "yaw_angle": 3.0, "x": 30.0,
             "y": 5.0, "z": 0.05}
    for j, name in enumerate(names):
        kind = name.rsplit("_", 2)[0]
        if name in scale:
            x[j] = scale[name] * r[j]
        elif kind == "wheel_speed":
            x[j] = speed / SEDAN.tires.rolling_radius * (1.0 + 0.5 * r[j])
        elif kind == "unsprung_displacement":
            x[j] = 0.04 * r[j]  # static tire deflections are ~0.02 m: some wheels in the air
        elif kind == "unsprung_velocity":
            x[j] = 0.5 * r[j]
        else:  # tire deflections [m]
            x[j] = 0.03 * r[j]
    x[0] = speed
    x[model.index("x")] += 30.0
    u = model.input_vector()
    for j, name in enumerate(model.input_names):
        if name.endswith("steer_angle"):
            u[j] = 0.3 * v[j]
        elif name.startswith("drive_torque"):
            u[j] = 1500.0 * v[j]
        elif name.startswith("brake_torque"):
            u[j] = 1500.0 * abs(v[j])
        elif name.startswith("road_displacement"):
            u[j] = 0.03 * v[j]
        elif name.startswith("road_velocity"):
            u[j] = 0.5 * v[j]
        else:
            u[j] = 10.0 * v[j]
    return x, u


@pytest.mark.compiled_vs_numpy
@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(key=st.sampled_from(sorted(MODELS)), data=st.data())
def test_compiled_rhs_and_outputs_equal_the_numpy_ones(key, data):
    model = MODELS[key]
    compiled = model.compiled_rhs()
    x, u = random_point(model, data)
    dxdt = np.empty(model.n_states)
    compiled.rhs(0.0, x, u, compiled.args, dxdt)
    expected = model.rhs(0.0, x, u)
    assert np.allclose(dxdt, expected, rtol=1e-12, atol=1e-12 * max(1.0, np.max(np.abs(expected))))
    y = np.empty(model.n_outputs)
    compiled.output(0.0, x, u, compiled.args, y)
    expected = model.output(0.0, x, u)
    assert np.allclose(y, expected, rtol=1e-12, atol=1e-12 * max(1.0, np.max(np.abs(expected))))


def test_random_points_cover_lifted_wheels_low_speed_and_reverse():
    """The cases the equality above must include do occur among its points."""
    model = MODELS["magic_formula"]
    loads, speeds = [], []

    @settings(max_examples=60, deadline=None, database=None)
    @given(data=st.data())
    def collect(data):
        x, u = random_point(model, data)
        y = model.output(0.0, x, u)
        loads.append(min(y[model.index(f"normal_load{s}", "outputs")] for s in vehdyn.full_vehicle.CORNERS))
        speeds.append(x[0])

    collect()
    assert min(loads) == 0.0 and max(loads) > 0.0
    assert min(speeds) < 0.0 < max(speeds) and min(np.abs(speeds)) < 0.5


def sine_run(model, backend, method, rtol, duration=1.5):
    t = np.linspace(0.0, duration, int(round(duration / 0.05)) + 1)
    x0, u0 = model.trim(20.0)
    inputs = dict(zip(model.input_names, u0))
    inputs["front_steer_angle"] = sine_steer(np.radians(3.0), 0.7)(t)  # samples: the same input on both paths
    return vehdyn.simulate(model, t, inputs, x0=x0, method=method, rtol=rtol, atol=rtol * 1e-3, backend=backend)


@pytest.fixture(scope="module")
def solve_ivp_reference():
    return sine_run(MODELS["magic_formula"], "numpy", "DOP853", 1e-10)


@pytest.mark.compiled_vs_numpy
@pytest.mark.parametrize("method", ["RK45", "DOP853"])
def test_compiled_simulation_equals_solve_ivp(method, solve_ivp_reference):
    """A sine steer to 0.45 g with Magic Formula tires: the compiled run (integrator and rhs) agrees with
    scipy's solve_ivp on the numpy rhs within the solver tolerance."""
    reference = solve_ivp_reference
    compiled = sine_run(MODELS["magic_formula"], "compiled", method, 1e-9)
    assert "compiled" in compiled.method_reason and "compiled" not in reference.method_reason
    assert np.max(np.abs(reference["lateral_acceleration"])) > 4.0
    for name in ("yaw_rate", "lateral_velocity", "roll_angle", "pitch_angle", "longitudinal_velocity",
                 "normal_load_front_left", "slip_ratio_rear_right", "wheel_speed_front_right"):
        scale = np.max(np.abs(reference[name]))
        assert np.max(np.abs(compiled[name] - reference[name])) < 1e-6 * scale, name


@pytest.mark.compiled_vs_numpy
def test_auto_backend_runs_the_compiled_rhs_on_a_road_profile():
    """A RoadProfile runs compiled (backend "auto" picks it) and agrees with the numpy path."""
    model = MODELS["road_profile"]
    t = np.linspace(0.0, 0.6, 61)
    x0, u0 = model.trim(15.0)
    inputs = dict(zip(model.input_names, u0))
    # max_step: a step grown on the flat start must not stride onto the bumps (see FullVehicle.domain)
    runs = {backend: vehdyn.simulate(model, t, inputs, x0=x0, method="RK45", rtol=1e-8, atol=1e-11, max_step=0.01,
                                     backend=backend) for backend in ("auto", "numpy")}
    assert "compiled" in runs["auto"].method_reason and "compiled" not in runs["numpy"].method_reason
    travel = runs["numpy"]["suspension_travel_front_left"]
    assert np.ptp(travel) > 5e-3  # the bumps move the suspension
    for name in ("suspension_travel_front_left", "normal_load_rear_right", "pitch_angle", "sprung_acceleration"):
        scale = np.max(np.abs(runs["numpy"][name]))
        assert np.max(np.abs(runs["auto"][name] - runs["numpy"][name])) < 1e-5 * scale, name


def test_compiled_path_keeps_the_domain_check():
    """Leaving the domain raises the same SimulationError, naming the state and the time, on both paths:
    a domain narrowed to 0.01 rad of roll, which a 0.3 g step steer leaves when the free run's roll
    angle passes 0.01 rad."""
    free = FullVehicle(SEDAN)
    narrow = FullVehicle(SEDAN)
    narrow.domain = {"roll_angle": (-0.01, 0.01), "pitch_angle": (-np.pi / 4, np.pi / 4)}
    t = np.linspace(0.0, 1.0, 201)
    x0, u0 = free.trim(20.0)
    inputs = dict(zip(free.input_names, u0))
    inputs["front_steer_angle"] = step_steer(np.radians(2.0), start=0.2)  # linear ramp: the same on both paths
    options = dict(method="RK45", rtol=1e-7, atol=1e-10, max_step=0.005)  # trial stages near the solution
    roll = np.abs(vehdyn.simulate(free, t, inputs, x0=x0, backend="compiled", **options)["roll_angle"])
    k = int(np.argmax(roll > 0.01))
    crossing = np.interp(0.01, roll[k - 1:k + 1], t[k - 1:k + 1])
    for backend in ("numpy", "compiled"):
        with pytest.raises(vehdyn.SimulationError, match="roll_angle = .* leaves the full vehicle's domain") as info:
            vehdyn.simulate(narrow, t, inputs, x0=x0, backend=backend, **options)
        assert info.value.signal == "roll_angle"
        assert crossing - 0.005 <= info.value.time <= crossing + 1e-3, backend  # within a step before it


def test_what_has_no_compiled_form_is_refused_with_the_reason():
    """A road or friction given as a Python callable and a tire law without a compiled form: the
    compiled backend names the parameter, "auto" runs numpy."""
    flat = lambda X, Y: (0.0 * X, 0.0 * X, 0.0 * X)  # noqa: E731
    cases = {"road": FullVehicle(SEDAN, road=flat), "friction": FullVehicle(SEDAN, friction=lambda X, Y: 0.0 * X + 1),
             "front_tire": FullVehicle(SEDAN, FialaTire.from_vehicle(SEDAN, "front"))}
    t = np.linspace(0.0, 0.1, 3)
    for key, model in cases.items():
        x0 = model.state_vector(longitudinal_velocity=10.0, **{f"wheel_speed{s}": 10.0 / SEDAN.tires.rolling_radius
                                                                for s in vehdyn.full_vehicle.CORNERS})
        with pytest.raises(vehdyn.ParameterError, match="use backend='numpy'") as info:
            vehdyn.simulate(model, t, x0=x0, method="RK45", backend="compiled")
        assert info.value.key == key
        result = vehdyn.simulate(model, t, x0=x0, method="RK45")
        assert "compiled" not in result.method_reason and np.all(np.isfinite(result.states))


@pytest.mark.compiled_vs_numpy
def test_a_rejected_trial_stage_beyond_the_domain_does_not_stop_a_good_run():
    """Without max_step, a step grown on the flat start strides onto the bumps: its trial stage
    reaches a pitch of -1 rad and used to abort the run as 'pitching over' on both paths. The domain
    is watched on accepted steps only (simulate; the rhs is NaN far beyond it): the run completes,
    and the compiled and numpy runs agree as with max_step."""
    model = MODELS["road_profile"]
    t = np.linspace(0.0, 0.6, 61)
    x0, u0 = model.trim(15.0)
    inputs = dict(zip(model.input_names, u0))
    runs = {backend: vehdyn.simulate(model, t, inputs, x0=x0, method="RK45", rtol=1e-8, atol=1e-11,
                                     backend=backend) for backend in ("compiled", "numpy")}
    assert np.all(np.abs(runs["numpy"]["pitch_angle"]) < 0.05)
    for name in ("suspension_travel_front_left", "pitch_angle", "sprung_acceleration"):
        scale = np.max(np.abs(runs["numpy"][name]))
        assert np.max(np.abs(runs["compiled"][name] - runs["numpy"][name])) < 1e-5 * scale, name
