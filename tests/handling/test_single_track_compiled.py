"""The compiled SingleTrack (one source with the numpy equations) against the numpy rhs and solve_ivp."""

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import vehdyn
from vehdyn.handling import SingleTrack
from vehdyn.procedures import sine_steer, sine_with_dwell, step_steer
from vehdyn.tire import FialaTire, LinearTire

pytest.importorskip("numba")

SEDAN = vehdyn.load_vehicle("sedan")
LINEAR = (LinearTire(cornering_stiffness=SEDAN.tires.front_cornering_stiffness / 2, nominal_load=3000.0),
          LinearTire(cornering_stiffness=SEDAN.tires.rear_cornering_stiffness / 2))
MODELS = {(law, spin, lag): SingleTrack(SEDAN, *(LINEAR if law == "linear" else (None, None)), wheel_spin=spin,
                                        tire_lag=lag)
          for law in ("magic_formula", "linear") for spin in (False, True) for lag in (False, True)}
# with the quasi-static lateral load transfer (roll centres raised so that both of its parts act)
MODELS.update({(law, spin, lag, "lateral_load_transfer"): SingleTrack(
    SEDAN.replace(geometry__front_roll_centre_height=0.05, geometry__rear_roll_centre_height=0.1),
    *(LINEAR if law == "linear" else (None, None)), wheel_spin=spin, tire_lag=lag, lateral_load_transfer=True)
    for law in ("magic_formula", "linear") for spin in (False, True) for lag in (False, True)})
# with the roll degree of freedom (states between the wheel speeds and the deflections): the rhs
# test only (the batch test's loop is the same compiled code for every key)
ROLL_MODELS = ({(law, spin, True, "roll"): SingleTrack(
    SEDAN.replace(geometry__front_roll_centre_height=0.05, geometry__rear_roll_centre_height=0.1),
    *(LINEAR if law == "linear" else (None, None)), wheel_spin=spin, lateral_load_transfer=True, roll=True)
    for law in ("magic_formula", "linear") for spin in (False, True)})
# on a road of 0.6 times the laws' friction (similarity in the shared tire step), with and without the transfer
FRICTION_MODELS = {("magic_formula", spin, True, "friction", transfer): SingleTrack(
    SEDAN.replace(geometry__front_roll_centre_height=0.05, geometry__rear_roll_centre_height=0.1), wheel_spin=spin,
    lateral_load_transfer=bool(transfer), friction=0.6) for spin in (False, True) for transfer in ("", "llt")}
RHS_MODELS = {**MODELS, **ROLL_MODELS, **FRICTION_MODELS}


@pytest.mark.compiled_vs_numpy
@settings(max_examples=90, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(key=st.sampled_from(sorted(RHS_MODELS)), data=st.data())
def test_compiled_rhs_and_outputs_equal_the_numpy_ones(key, data):
    model = RHS_MODELS[key]
    compiled = model.compiled_rhs()
    floats = st.floats(-1.0, 1.0)
    x = np.array(data.draw(st.lists(floats, min_size=model.n_states, max_size=model.n_states)))
    u = np.array(data.draw(st.lists(floats, min_size=model.n_inputs, max_size=model.n_inputs)))
    x[0] = data.draw(st.floats(-35.0, 35.0))  # from reverse through standstill to speed
    if model.wheel_spin:
        x[6:8] = x[0] / model.parameters.rolling_radius * (1 + 0.3 * x[6:8])
    if model.tire_lag:
        x[-4 if model.wheel_spin else -2:] *= 0.05  # deflections [m]
    u[2:] *= 3000.0  # forces [N] or torques [N m]
    dxdt = np.empty(model.n_states)
    compiled.rhs(0.0, x, u, compiled.args, dxdt)
    expected = model.rhs(0.0, x, u)
    assert np.allclose(dxdt, expected, rtol=1e-12, atol=1e-12 * max(1.0, np.max(np.abs(expected))))
    y = np.empty(model.n_outputs)
    compiled.output(0.0, x, u, compiled.args, y)
    expected = model.output(0.0, x, u)
    assert np.allclose(y, expected, rtol=1e-12, atol=1e-12 * max(1.0, np.max(np.abs(expected))))


def sine_run(backend, method, rtol, sampled, model=None):
    model = MODELS[("magic_formula", False, True)] if model is None else model
    t = np.linspace(0.0, 2.0, 41)
    steer = sine_steer(np.radians(2.0), 0.5)
    drag = float(model.parameters.drag_factor) * 20.0**2
    inputs = {"front_steer_angle": steer(t) if sampled else steer, "rear_longitudinal_force": drag}
    return vehdyn.simulate(model, t, inputs, x0=model.straight_running(20.0), method=method, rtol=rtol,
                           atol=rtol * 1e-3, backend=backend)


@pytest.fixture(scope="module")
def solve_ivp_reference():
    return sine_run("numpy", "DOP853", 1e-11, sampled=True)


@pytest.mark.compiled_vs_numpy
@pytest.mark.parametrize("method", ["RK45", "DOP853"])
def test_compiled_simulation_equals_solve_ivp(method, solve_ivp_reference):
    # the same ODE (sampled steer, first-order hold on both backends) at a tight tolerance
    compiled = sine_run("compiled", method, 1e-10, sampled=True)
    reference = solve_ivp_reference
    assert "compiled" in compiled.method_reason and "compiled" not in reference.method_reason
    for name in ("yaw_rate", "lateral_velocity", "lateral_acceleration", "front_lateral_force"):
        scale = np.max(np.abs(reference[name]))
        assert np.max(np.abs(compiled[name] - reference[name])) < 1e-7 * scale, name


@pytest.mark.compiled_vs_numpy
@pytest.mark.parametrize("method, rtol, accuracy", [("DOP853", 1e-10, 1e-7), ("BDF", 1e-8, 1e-6)])
def test_manoeuvre_signal_in_closed_form_equals_the_steer_computed_inside_the_rhs(method, rtol, accuracy):
    # the independent reference: a numpy model whose rhs computes delta(t) itself (no sampling);
    # BDF: the compiled stiff method on the tire-lag model (relaxation modes ~ -40 1/s at 20 m/s)
    base = MODELS[("magic_formula", False, True)]
    steer = sine_steer(np.radians(2.0), 0.5)
    drag = float(base.parameters.drag_factor) * 20.0**2

    class Steered(vehdyn.Model):
        def __init__(self):
            self.declare(states=base.states)

        def rhs(self, t, x, u):
            return base.rhs(t, x, base.input_vector(front_steer_angle=float(steer(t)), rear_longitudinal_force=drag))

    t = np.linspace(0.0, 2.0, 41)
    reference = vehdyn.simulate(Steered(), t, x0=base.straight_running(20.0), method="DOP853", rtol=1e-10,
                                atol=1e-13, backend="numpy")
    compiled = sine_run("compiled", method, rtol, sampled=False)
    assert f"compiled {method}" in compiled.message
    for name in ("yaw_rate", "lateral_velocity"):
        ref = reference[name]
        assert np.max(np.abs(compiled[name] - ref)) < accuracy * np.max(np.abs(ref)), name


@pytest.mark.parametrize("steer", [step_steer(np.radians(3.0), start=0.503, rise_time=0.15),
                                   sine_with_dwell(np.radians(3.0), frequency=1.5, dwell=0.2, start=0.105)],
                         ids=["step_steer", "sine_with_dwell"])
@pytest.mark.compiled_vs_numpy
def test_manoeuvre_signals_on_both_backends_equal_solve_ivp_with_the_exact_steer(steer):
    # kinks between the samples of a coarse grid: both backends evaluate the steer at every stage
    # and end steps on its breakpoints (the numpy one used to sample it: 3-5 % off here); the reference
    # is scipy's solve_ivp on the rhs with the steer computed inside, restarted at each breakpoint
    from scipy.integrate import solve_ivp

    model = MODELS[("magic_formula", False, True)]
    drag = float(model.parameters.drag_factor) * 20.0**2
    t = np.linspace(0.0, 1.4, 15)

    def rhs(tt, x, t_ref):  # the documented formula of the piece active on the segment from t_ref
        delta = 0.0
        for start, end, offset, slope, amplitude, omega, phase in steer.pieces:
            if start <= t_ref < end:
                delta = offset + slope * (tt - start) + amplitude * np.sin(omega * (tt - start) + phase)
        return model.rhs(tt, x, model.input_vector(front_steer_angle=delta, rear_longitudinal_force=drag))

    edges = np.concatenate([[0.0], steer.breakpoints[steer.breakpoints < t[-1]], [t[-1]]])
    reference, x = np.empty((model.n_states, t.size)), model.straight_running(20.0)
    for a, b in zip(edges[:-1], edges[1:]):
        sol = solve_ivp(rhs, (a, b), x, method="DOP853", rtol=1e-12, atol=1e-14, dense_output=True, args=(a,))
        inside = (t >= a) & (t <= b)
        reference[:, inside], x = sol.sol(t[inside]), sol.y[:, -1]
    inputs = {"front_steer_angle": steer, "rear_longitudinal_force": drag}
    for backend in ("numpy", "compiled"):
        result = vehdyn.simulate(model, t, inputs, x0=model.straight_running(20.0), method="DOP853", rtol=1e-10,
                                 atol=1e-12, backend=backend)
        for name in ("yaw_rate", "lateral_velocity"):
            ref = reference[model.state_names.index(name)]
            assert np.max(np.abs(result[name] - ref)) < 1e-7 * np.max(np.abs(ref)), (backend, name)


def test_unsupported_tire_law_is_named_and_auto_falls_back():
    fiala = FialaTire.from_vehicle(SEDAN, "front")
    model = SingleTrack(SEDAN, fiala, fiala)
    with pytest.raises(vehdyn.ParameterError, match="FialaTire") as info:
        sine_run("compiled", "RK45", 1e-6, sampled=False, model=model)
    assert info.value.key == "front_tire"
    result = sine_run("auto", "RK45", 1e-4, sampled=False, model=model)
    assert "compiled" not in result.method_reason and np.all(np.isfinite(result.states))


def test_a_friction_callable_has_no_compiled_form_and_auto_falls_back():
    model = SingleTrack(SEDAN, friction=lambda X, Y: np.where(np.asarray(Y) > 0.0, 0.3, 1.0))
    with pytest.raises(vehdyn.ParameterError, match="friction is a Python callable") as info:
        sine_run("compiled", "RK45", 1e-6, sampled=False, model=model)
    assert info.value.key == "friction"
    result = sine_run("auto", "RK45", 1e-4, sampled=False, model=model)
    assert "compiled" not in result.method_reason and np.all(np.isfinite(result.states))


def _sine_batch(model, n, speed=20.0):
    """A batch of ``n`` variants of ``model`` (mass, yaw inertia, CG and, when it has them, the
    relaxation lengths varied) and its straight-running initial states."""
    p = model.parameters
    f = np.linspace(0.9, 1.1, n)
    batch = model.variants(mass=p.mass * f, yaw_inertia=p.yaw_inertia * f, a=p.a * f, b=p.b * (2 - f),
                           front_lateral_relaxation_length=p.front_lateral_relaxation_length * f)
    x0 = np.repeat(model.straight_running(speed)[:, None], n, axis=1)
    return batch, x0, f


@pytest.mark.parametrize("key, method", [(key, "RK45") for key in sorted(MODELS)]
                         + [(("magic_formula", True, True), "BDF")])
def test_compiled_batch_gives_each_variant_its_own_compiled_run_bitwise(key, method):
    base = MODELS[key]
    batch, x0, f = _sine_batch(base, 3)
    t = np.linspace(0.0, 2.0, 101)
    drive = "rear_drive_torque" if base.wheel_spin else "rear_longitudinal_force"
    inputs = {"front_steer_angle": sine_steer(np.radians(3.0), 0.5), drive: 200.0}
    result = vehdyn.simulate(batch, t, inputs, x0=x0, method=method, rtol=1e-8, atol=1e-10)
    assert "3 variants" in result.method_reason and result.states.shape == (base.n_states, t.size, 3)
    p = base.parameters
    for i, fi in enumerate(f):
        one = base.variants(mass=p.mass * fi, yaw_inertia=p.yaw_inertia * fi, a=p.a * fi, b=p.b * (2 - fi),
                            front_lateral_relaxation_length=p.front_lateral_relaxation_length * fi)
        single = vehdyn.simulate(one, t, inputs, x0=x0[:, i], method=method, rtol=1e-8, atol=1e-10)
        # bitwise: both the compiled loop, each variant with its own step-size control
        assert np.array_equal(single.states, result.states[..., i])
        assert np.array_equal(single.outputs, result.outputs[..., i])


# The chain above is complete for every structure: batch = single compiled runs (bitwise, here),
# single compiled rhs = numpy rhs (test_compiled_rhs_and_outputs_equal_the_numpy_ones). The numpy
# batch under solve_ivp costs seconds per structure, so the direct check runs on two structures
# (linear tires plain; Magic Formula with every option) over the steer's onset.
@pytest.mark.parametrize("key", [("linear", False, False),
                                 ("magic_formula", True, True, "lateral_load_transfer")])
@pytest.mark.compiled_vs_numpy
def test_compiled_batch_equals_the_numpy_batch_under_solve_ivp(key):
    base = MODELS[key]
    batch, x0, _ = _sine_batch(base, 3)
    t = np.linspace(0.0, 0.4, 21)
    drive = "rear_drive_torque" if base.wheel_spin else "rear_longitudinal_force"
    sampled = {"front_steer_angle": sine_steer(np.radians(3.0), 0.5)(t), drive: 200.0}
    ours = vehdyn.simulate(batch, t, sampled, x0=x0, method="DOP853", rtol=1e-9, atol=1e-11, backend="compiled")
    numpy = vehdyn.simulate(batch, t, sampled, x0=x0, method="DOP853", rtol=1e-9, atol=1e-11, backend="numpy")
    assert "compiled" in ours.method_reason and "compiled" not in numpy.method_reason
    for name in ("yaw_rate", "lateral_velocity"):
        scale = np.max(np.abs(numpy[name]), axis=0)
        assert np.all(np.max(np.abs(ours[name] - numpy[name]), axis=0) < 1e-6 * scale), name


def test_compiled_batch_of_models_with_different_tires_and_its_errors():
    from vehdyn.simulation import compiled as _compiled_ode
    from vehdyn.handling import _single_track_numba

    t = np.linspace(0.0, 1.0, 51)
    soft = LinearTire(cornering_stiffness=0.7 * LINEAR[0].cornering_stiffness, nominal_load=3000.0)
    models = [SingleTrack(SEDAN, *LINEAR), SingleTrack(SEDAN, soft, LINEAR[1]), SingleTrack(SEDAN, *LINEAR)]
    compiled = _single_track_numba.compiled_batch(models)
    assert compiled.n_variants == 3
    inputs = {"front_steer_angle": sine_steer(np.radians(2.0), 1.0)}
    x0 = np.stack([m.straight_running(25.0) for m in models], axis=1)
    x0[0, 2] = np.nan  # variant 2 cannot start: it alone fails
    table = _compiled_ode.input_table(models[0], inputs, t, vehdyn.simulate.__globals__["_sample_inputs"](
        models[0], inputs, t), "foh")
    states, report = _compiled_ode.solve_batch(compiled, t, x0, table, "RK45", 1e-8, 1e-10, threads=2)
    assert list(report[:, 0]) == [0, 0, -2]
    assert "non-finite" in _compiled_ode.status_message("RK45", report[2])
    assert _compiled_ode.status_message("RK45", report[0]) == ""
    for i in range(2):
        single = vehdyn.simulate(models[i], t, inputs, x0=x0[:, i], method="RK45", rtol=1e-8, atol=1e-10)
        assert np.array_equal(single.states, states[i])  # both the compiled loop: bitwise
    softer = np.max(np.abs(states[1, 2])) / np.max(np.abs(states[0, 2]))
    assert softer < 0.99  # the softer front tire understeers more: a smaller yaw rate
    with pytest.raises(vehdyn.ParameterError, match="one structure"):
        _single_track_numba.compiled_batch([models[0], SingleTrack(SEDAN, *LINEAR, tire_lag=False)])
    with pytest.raises(vehdyn.ParameterError, match="threads"):
        _compiled_ode.solve_batch(compiled, t, x0, table, threads=0)
    with pytest.raises(vehdyn.ParameterError, match="n_variants"):
        _single_track_numba.compiled_batch(models[0].variants(mass=[1000.0, 1100.0]), 3)


def test_a_failing_variant_of_a_batch_is_named():
    base = MODELS[("linear", False, False)]
    batch = base.variants(mass=[1500.0, 1500.0])
    x0 = np.repeat(base.straight_running(20.0)[:, None], 2, axis=1)
    x0[2, 1] = 1e308  # a yaw rate whose derivatives overflow at every step size
    with pytest.raises(vehdyn.SimulationError, match="variant 1 of the batch.*non-finite"):
        vehdyn.simulate(batch, np.linspace(0.0, 1.0, 11), x0=x0, method="RK45", backend="compiled")


def test_compiled_math_functions_are_the_library_functions_bitwise():
    """XP's cos, sin, tanh and atan2 skip the library call where its result is exact (cos at 0 and
    pi, sin and tanh at +-0, atan2 at y = +-0, x > 0): the same bits as math's, signed zeros and
    NaN included, at those points and around them."""
    import math

    import numba

    from vehdyn.components.compiled import XP

    @numba.njit
    def evaluate(x, y, out):
        for i in range(x.size):
            out[0, i] = XP.cos(x[i])
            out[1, i] = XP.sin(x[i])
            out[2, i] = XP.tanh(x[i])
            out[3, i] = XP.atan2(x[i], y[i])

    special = [0.0, -0.0, math.pi, -math.pi, np.nextafter(math.pi, 4.0), np.nextafter(math.pi, 3.0), 5e-324,
               -5e-324, 1e-300, 0.3, -2.0, 1e300, math.inf, -math.inf, math.nan]
    x = np.array([v for v in special for _ in special])
    y = np.array([w for _ in special for w in special])
    out = np.empty((4, x.size))
    evaluate(x, y, out)
    expected = np.array([[math.cos(v) if math.isfinite(v) else math.nan for v in x],
                         [math.sin(v) if math.isfinite(v) else math.nan for v in x],
                         [math.tanh(v) for v in x], [math.atan2(v, w) for v, w in zip(x, y)]])
    # bitwise on any CPU: math and numba-compiled code call the same C library (numba without Intel SVML)
    same = (out.view(np.int64) == expected.view(np.int64)) | (np.isnan(out) & np.isnan(expected))
    assert np.all(same), (x[~np.all(same, axis=0)], y[~np.all(same, axis=0)])
