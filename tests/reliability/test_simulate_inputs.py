"""simulate's edges: the documented input shapes only, non-numeric and non-finite values, solver
failures and stiffness, each against an independent result (closed forms, single runs)."""

import importlib
import warnings

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from hypothesis.extra import numpy as hnp

import vehdyn
from vehdyn import LinearModel, Model, ParameterError, SimulationError, VehdynWarning, simulate
from vehdyn.handling import LinearBicycle

stiffness_module = importlib.import_module("vehdyn.simulation._stiffness")  # STIFF_STEPS_* as simulate reads them
ivp_module = importlib.import_module("vehdyn.simulation._ivp")

N_T = 101
T = np.linspace(0.0, 1.0, N_T)


def bicycle():
    return LinearBicycle.from_parameters(mass=1500, yaw_inertia=2500, a=1.1, b=1.6, front_cornering_stiffness=110e3,
                                         rear_cornering_stiffness=120e3, speed=20.0)


def lag():
    """x' = -x + u: its foh response has the closed form of first_order_foh."""
    return LinearModel([[-1.0]], [[1.0]], states=["level"], inputs=["flow"])


def first_order_foh(t, u, x0=0.0):
    """Exact solution of x' = -x + u for u linear between samples (independent of simulate)."""
    x = np.empty(np.shape(u))
    x[0] = x0
    for k in range(len(t) - 1):
        h = t[k + 1] - t[k]
        e = np.exp(-h)
        x[k + 1] = e * x[k] + u[k] * (1 - e) + (u[k + 1] - u[k]) * (h - 1 + e) / h
    return x


# --------------------------------------------------------------------------- shapes of a mapping's arrays
def test_column_next_to_a_signal_is_a_batch_of_one_not_of_n_times():
    """The issue's case: (n_times, 1) + (n_times,) used to broadcast into a (101, 101) "batch"."""
    car = bicycle()
    batched = simulate(car, T, inputs={"front_steer_angle": np.full((N_T, 1), 0.01), "rear_steer_angle": 0.002 * T})
    single = simulate(car, T, inputs={"front_steer_angle": np.full(N_T, 0.01), "rear_steer_angle": 0.002 * T})
    assert batched.states.shape == (2, N_T, 1)
    np.testing.assert_allclose(batched.states[..., 0], single.states, rtol=1e-13, atol=1e-16)


def test_shared_signal_goes_to_every_member_of_a_batch():
    car = bicycle()
    steer = np.outer(np.sin(2 * T), [0.01, 0.02, -0.01])  # (n_times, 3)
    rear = 0.002 * T
    batched = simulate(car, T, inputs={"front_steer_angle": steer, "rear_steer_angle": rear})
    for j in range(3):
        one = simulate(car, T, inputs={"front_steer_angle": steer[:, j], "rear_steer_angle": rear})
        np.testing.assert_allclose(batched.states[..., j], one.states, rtol=1e-12, atol=1e-15)


@pytest.mark.parametrize("shape", [(N_T, 2, 2), (N_T + 1,), (1, N_T), (N_T, 0), (2, N_T)])
def test_mapping_array_of_another_shape_raises_naming_the_input(shape):
    with pytest.raises(ParameterError, match=r"inputs\['front_steer_angle'\] must have shape") as info:
        simulate(bicycle(), T, inputs={"front_steer_angle": np.zeros(shape)})
    assert info.value.key == "inputs.front_steer_angle"


def test_mapping_batches_of_different_sizes_raise():
    with pytest.raises(ParameterError, match="batch sizes") as info:
        simulate(bicycle(), T, inputs={"front_steer_angle": np.zeros((N_T, 2)), "rear_steer_angle": np.zeros((N_T, 3))})
    assert info.value.key == "inputs"


@pytest.mark.parametrize("shape", [(2, N_T, 3, 1), (2,), (2, N_T, 0), (N_T, 2)])
def test_array_of_another_shape_raises(shape):
    with pytest.raises(ParameterError, match=r"shape \(n_inputs, n_times\)") as info:
        simulate(bicycle(), T, inputs=np.zeros(shape))
    assert info.value.key == "inputs"


# --------------------------------------------------------------------------- callables
@pytest.mark.parametrize("backend", ["numpy", "compiled"])
def test_callable_inputs_are_checked_finite_like_arrays(backend):
    from vehdyn.handling import SingleTrack

    model = SingleTrack(vehdyn.load_vehicle("sedan"))  # has a compiled rhs: the check comes before either backend
    x0 = model.straight_running(20.0)
    bad = lambda t: np.where(t > 0.5, np.nan, 0.01)  # noqa: E731
    with pytest.raises(ParameterError, match=r"'front_steer_angle' is not finite at t = 0.51") as info:
        simulate(model, T, inputs={"front_steer_angle": bad}, x0=x0, method="RK45", backend=backend)
    assert info.value.key == "inputs.front_steer_angle"
    whole = lambda t: np.zeros(model.n_inputs) + (np.inf if t > 0.2 else 0.0)  # noqa: E731  scalar-only
    with pytest.raises(ParameterError, match=r"'front_steer_angle' is not finite at t = 0.21"):
        simulate(model, T, inputs=whole, x0=x0, method="RK45", backend=backend)


@pytest.mark.compiled_vs_numpy
def test_callable_per_instant_and_vectorized_agree_with_the_closed_form():
    u = lambda t: np.sin(3 * t)  # noqa: E731
    expected = first_order_foh(T, np.sin(3 * T))
    vectorized = simulate(lag(), T, inputs={"flow": u})
    per_instant = simulate(lag(), T, inputs={"flow": lambda t: float(np.sin(3 * t))})
    whole = simulate(lag(), T, inputs=lambda t: [float(np.sin(3 * t))])
    # numpy's exp in the closed form against scipy's expm in simulate (two libraries): the closed form's
    # (h - 1 + e^-h) ~ 5e-5 is a small difference, which an ulp of exp moves by 2e-12 relative; over the
    # 100 steps with |du/dt| <= 3, 4 ulps of exp add up to at most 100 * 3 * 4 ulps of 1 = 2.7e-13 (an input
    # sampled half a step off would be ~1e-3 off)
    from tests._tolerances import EPS, ONE_CALL_ULPS, assert_close_ulps
    for r in (vectorized, per_instant, whole):
        assert_close_ulps(r["level"], expected, ulps=ONE_CALL_ULPS, rtol=ONE_CALL_ULPS * EPS, scale=3.0 * (N_T - 1),
                          what="exact discretization vs the closed form")


def test_callable_of_the_wrong_size_or_text_raises():
    with pytest.raises(ParameterError, match="must return 2 values"):
        simulate(bicycle(), T, inputs=lambda t: [0.01, 0.0, 0.0])
    with pytest.raises(ParameterError, match=r"inputs\['flow'\]: u\(t\) must return numbers") as info:
        simulate(lag(), T, inputs={"flow": lambda t: "1.0"})
    assert info.value.key == "inputs.flow"


# --------------------------------------------------------------------------- non-numeric arguments and options
@pytest.mark.parametrize(
    "kwargs, key",
    [
        ({"time": "0 1 2"}, "time"),
        ({"time": ["0", "1"]}, "time"),
        ({"time": [0.0, 1j]}, "time"),
        ({"inputs": {"flow": "fast"}}, "inputs.flow"),
        ({"inputs": [["1"] * N_T]}, "inputs"),
        ({"x0": ["a"]}, "x0"),
        ({"x0": {"level": "a"}}, "x0.level"),
        ({"x0": [[1.0, 2.0], [3.0]]}, "x0"),
        ({"rtol": "1e-6"}, "rtol"),
        ({"atol": [1e-9, 1e-9]}, "atol"),
        ({"max_step": 0.0, "method": "RK45"}, "max_step"),
        ({"max_step": -1.0, "method": "RK45"}, "max_step"),
        ({"max_step": "big", "method": "RK45"}, "max_step"),
        ({"first_step": 0.0, "method": "RK45"}, "first_step"),
        ({"first_step": 2.0, "method": "RK45"}, "first_step"),
        ({"first_step": np.nan, "method": "RK45"}, "first_step"),
        ({"substeps": True, "method": "rk4"}, "substeps"),
        ({"method": None}, "method"),
        ({"x0": np.zeros((1, 2, 2))}, "x0"),
    ],
)
def test_non_numeric_or_out_of_range_arguments_raise_naming_them(kwargs, key):
    args = {"time": T}
    args.update(kwargs)
    with pytest.raises(ParameterError) as info:
        simulate(lag(), args.pop("time"), **args)
    assert info.value.key == key
    assert key.split(".")[0].split("[")[0] in str(info.value)


def test_max_step_inf_and_first_step_equal_to_the_span_are_allowed():
    r = simulate(lag(), T, inputs={"flow": np.ones(N_T)}, method="RK45", max_step=np.inf, first_step=1.0,
                 rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(r["level"], 1 - np.exp(-T), atol=1e-8)


def test_batch_sizes_of_x0_and_inputs_must_agree_or_be_one():
    car = bicycle()
    steer = np.stack([np.full((N_T, 3), 0.01), np.zeros((N_T, 3))])  # (2, n_times, 3)
    with pytest.raises(ParameterError, match="batch of 2 initial states but inputs a batch of 3") as info:
        simulate(car, T, inputs=steer, x0=np.zeros((2, 2)))
    assert info.value.key == "x0"
    x0 = np.array([[0.1], [0.05]])  # a batch of one initial state, shared by three input columns
    for method, atol in (("exact", 1e-14), ("rk4", 1e-14), ("RK45", 1e-6)):  # RK45: steps differ, its tolerance
        shared = simulate(car, T, inputs=steer * [1, 2, 3], x0=x0, method=method)
        for j in range(3):
            one = simulate(car, T, inputs=steer[:, :, j] * (j + 1), x0=x0[:, 0], method=method)
            np.testing.assert_allclose(shared.states[..., j], one.states, rtol=1e-5, atol=atol)


# --------------------------------------------------------------------------- solver failures
class NanAfterStart(Model):
    """dx/dt = 1 at t = 0 and NaN after: every solver fails in its first step."""

    states = ("level",)

    def rhs(self, t, x, u):
        return np.where(t > 0, np.nan, 1.0) * np.ones_like(x)


@pytest.mark.parametrize("method", ["RK45", "RK23", "DOP853"])
def test_failure_before_the_first_output_is_a_simulation_error_with_the_solver_message(method):
    """solve_ivp returns no output at all then (its t is an empty list): simulate used to crash on it."""
    with pytest.raises(SimulationError, match=f"{method} failed in its first step from t = 0 s: Required step size") \
            as info:
        simulate(NanAfterStart(), T, method=method)
    assert info.value.time == 0.0


@pytest.mark.parametrize("method", ["Radau", "BDF"])
def test_failure_inside_an_implicit_solver_is_a_simulation_error(method):
    """The implicit methods raise from their LU of a NaN Jacobian instead of returning a status."""
    with pytest.raises(SimulationError, match=f"{method} failed: array must not contain infs or NaNs"):
        simulate(NanAfterStart(), T, method=method)


def test_failure_after_an_output_names_the_last_instant_reached():
    class Quadratic(Model):
        states = ("level",)

        def rhs(self, t, x, u):
            return x**2  # x(0) = 1: x = 1 / (1 - t), singular at t = 1

    with pytest.raises(SimulationError, match=r"RK45 failed after t = [\d.]+ s \(the last output instant") as info:
        simulate(Quadratic(), np.linspace(0, 2, 21), x0=[1.0], method="RK45")
    assert 0.9 <= info.value.time <= 1.0


# --------------------------------------------------------------------------- stiffness of explicit methods
def stiff_linear(fast):
    return LinearModel(np.diag([-fast, -1.0]), np.zeros((2, 0)), states=["fast", "slow"], inputs=[])


class StiffNonlinear(Model):
    """The same diagonal system through a numpy rhs (no eigenvalues before the run)."""

    states = ("fast", "slow")

    def __init__(self, fast):
        self.fast = fast

    def rhs(self, t, x, u):
        return np.stack([-self.fast * x[0], -x[1]])


def test_issue_case_is_refused_before_it_runs_naming_method_and_implicit_methods():
    """diag(-1e6, -1) over 1,000 s with RK45: 3e8 stability-limited steps (hours), refused at once."""
    with pytest.raises(ParameterError, match="'LSODA', 'Radau' or 'BDF'") as info:
        simulate(stiff_linear(1e6), np.linspace(0, 1000, 11), x0=[1.0, 1.0], method="RK45")
    assert info.value.key == "method"
    # the estimate is span * rate / (Dormand-Prince's real stability interval 3.3066, Hairer & Wanner IV.2)
    assert "3e+08 steps" in str(info.value)
    # 'auto' picks an implicit method for it and gets the closed form
    r = simulate(stiff_linear(1e6), np.linspace(0, 1000, 11), x0=[1.0, 1.0])
    np.testing.assert_allclose(r["slow"], np.exp(-r.time), rtol=1e-9)


def test_stiff_run_warns_or_is_refused_by_step_estimate_and_check_stability_false_runs_it(monkeypatch):
    monkeypatch.setattr(stiffness_module, "STIFF_STEPS_WARN", 100.0)
    monkeypatch.setattr(stiffness_module, "STIFF_STEPS_REFUSE", 10_000.0)
    t = np.linspace(0.0, 1.0, 11)
    # 1e3 1/s over 1 s: 1e3 / 3.31 = 302 steps -> warned, runs, and is right
    with pytest.warns(VehdynWarning, match="about 3e\\+02 steps"):
        r = simulate(stiff_linear(1e3), t, x0=[1.0, 1.0], method="RK45", rtol=1e-8, atol=1e-12)
    np.testing.assert_allclose(r["slow"], np.exp(-t), rtol=1e-6)
    # 1e5 1/s: 3e4 steps -> refused; check_stability=False runs it, without a warning
    with pytest.raises(ParameterError, match="method 'DOP853' is explicit"):
        simulate(stiff_linear(1e5), t, x0=[1.0, 1.0], method="DOP853")
    with warnings.catch_warnings():
        warnings.simplefilter("error", VehdynWarning)
        r = simulate(stiff_linear(1e5), t, x0=[1.0, 1.0], method="RK23", check_stability=False)
    np.testing.assert_allclose(r["slow"], np.exp(-t), rtol=1e-3)
    # implicit methods are never judged
    with warnings.catch_warnings():
        warnings.simplefilter("error", VehdynWarning)
        simulate(stiff_linear(1e5), t, x0=[1.0, 1.0], method="LSODA")


def test_nonlinear_stiff_run_is_judged_by_the_solver_loop(monkeypatch):
    monkeypatch.setattr(ivp_module, "_STIFFNESS_WATCH_CALLS", 200)
    t = np.linspace(0.0, 100.0, 11)
    with pytest.raises(ParameterError, match=r"at t = .* \(after 200 rhs calls\)") as info:
        simulate(StiffNonlinear(1e6), t, x0=[1.0, 1.0], method="RK45")
    assert info.value.key == "method"
    monkeypatch.setattr(stiffness_module, "STIFF_STEPS_WARN", 10.0)
    with pytest.warns(VehdynWarning, match="after 200 rhs calls"):
        r = simulate(StiffNonlinear(1e3), np.linspace(0, 1, 11), x0=[1.0, 1.0], method="RK45")
    np.testing.assert_allclose(r["slow"], np.exp(-r.time), rtol=1e-4)


@pytest.mark.parametrize("method, reference", [("rk4", 2.785293563), ("RK45", 3.306567892)])
def test_stability_intervals_equal_published_values(method, reference):
    """RK4 2.7853 and Dormand-Prince 5(4) 3.3066 on the negative real axis (Hairer & Wanner II, IV.2)."""
    assert vehdyn.simulation.stability_interval(method) == pytest.approx(reference, rel=1e-8)


@pytest.mark.parametrize("method", ["RK23", "RK45", "DOP853"])
def test_stability_interval_is_where_scipys_own_steps_stop_decaying(method):
    """Fixed steps of scipy's stepper on y' = -y: |y| decays just inside the interval, grows just outside."""
    from scipy import integrate

    interval = vehdyn.simulation.stability_interval(method)

    def growth(h):
        solver = getattr(integrate, method)(lambda t, y: -y, 0.0, np.array([1.0]), t_bound=400 * h, first_step=h,
                                            max_step=h, rtol=1e3, atol=1e3)
        while solver.status == "running":
            solver.step()
        return abs(solver.y[0])

    assert growth(0.999 * interval) < 1.0 < growth(1.001 * interval)


# --------------------------------------------------------------------------- properties
finite = st.floats(min_value=-1e3, max_value=1e3, allow_nan=False)
non_finite = st.sampled_from([np.nan, np.inf, -np.inf])


@settings(max_examples=40, deadline=None)
@given(st.data(), non_finite, st.sampled_from(["mapping", "array", "callable"]), st.integers(0, 3))
def test_any_non_finite_input_sample_raises_naming_the_input_and_instant(data, bad, form, batch):
    car = bicycle()
    shape = (2, N_T) + ((batch,) if batch else ())
    u = data.draw(hnp.arrays(float, shape, elements=finite))
    index = tuple(data.draw(st.integers(0, n - 1)) for n in shape)
    u[index] = bad
    name = car.input_names[index[0]]
    if form == "mapping":
        inputs = {"front_steer_angle": u[0], "rear_steer_angle": u[1]}
    elif form == "array":
        inputs = u
    else:
        if batch:
            inputs = {"front_steer_angle": lambda t: u[0], "rear_steer_angle": u[1]}  # vectorized: (n_times, batch)
        else:
            inputs = lambda t: u[:, np.searchsorted(T, t)]  # noqa: E731  per instant and vectorized alike
    with pytest.raises(ParameterError, match=f"input '{name}' is not finite at t = {T[index[1]]}") as info:
        simulate(car, T, inputs=inputs)
    assert info.value.key == f"inputs.{name}"


@settings(max_examples=30, deadline=None)
@given(st.data(), non_finite, st.integers(0, 3))
def test_any_non_finite_x0_entry_raises_naming_the_state(data, bad, batch):
    car = bicycle()
    shape = (2,) + ((batch,) if batch else ())
    x0 = data.draw(hnp.arrays(float, shape, elements=finite))
    index = tuple(data.draw(st.integers(0, n - 1)) for n in shape)
    x0[index] = bad
    name = car.state_names[index[0]]
    with pytest.raises(ParameterError, match=f"'{name}' is not finite") as info:
        simulate(car, T, x0=x0)
    assert info.value.key == f"x0.{name}"


allowed_mapping_shapes = {(N_T,), (N_T, 1), (N_T, 2)}


@settings(max_examples=40, deadline=None)
@given(hnp.array_shapes(min_dims=1, max_dims=4, min_side=0, max_side=N_T + 1))
def test_any_mapping_array_shape_but_the_documented_ones_raises(shape):
    inputs = {"flow": np.zeros(shape)}
    documented = shape[0] == N_T and (len(shape) == 1 or (len(shape) == 2 and shape[1] >= 1))
    if documented:
        r = simulate(lag(), T, inputs=inputs)
        assert r.states.shape == (1, N_T) + shape[1:]
    else:
        with pytest.raises(ParameterError, match=r"inputs\['flow'\] must have shape") as info:
            simulate(lag(), T, inputs=inputs)
        assert info.value.key == "inputs.flow"


@settings(max_examples=40, deadline=None)
@given(st.data(), st.integers(0, 3), st.sampled_from(["mapping", "array", "callable"]),
       st.sampled_from(["exact", "RK45"]))
def test_any_finite_input_runs_and_gives_the_closed_form(data, batch, form, method):
    t = np.linspace(0.0, 2.0, 21)
    shape = (t.size,) + ((batch,) if batch else ())
    u = data.draw(hnp.arrays(float, shape, elements=st.floats(-10, 10)))
    x0 = data.draw(st.floats(-10, 10))
    if form == "mapping":
        inputs = {"flow": u}
    elif form == "array":
        inputs = u[None]
    else:
        inputs = {"flow": lambda tt: u}  # vectorized callable
    # an adaptive method must not step over samples: max_step = the sample interval
    r = simulate(lag(), t, inputs=inputs, x0=[x0], method=method, rtol=1e-10, atol=1e-10, max_step=0.1)
    expected = first_order_foh(t, u, x0)
    # RK45 steps straddle the kinks of the sampled input: its error is not the tolerance asked
    np.testing.assert_allclose(r["level"], expected, atol=1e-12 if method == "exact" else 1e-5)


@pytest.mark.slow
def test_compiled_backend_failing_on_a_stiff_problem_says_why():
    """The compiled loop is not judged before it runs (a Jacobian would cost more than a short
    run); its step limit stops a stiff run, and the error then carries the stiffness estimate."""
    numba = pytest.importorskip("numba")
    from vehdyn.simulation import compiled as _compiled_ode

    @numba.njit
    def decay_rhs(t, y, u, args, dydt):
        dydt[0] = args[0] * y[0]

    class Decay(Model):
        states = ("level",)

        def __init__(self, rate):
            self.rate = rate

        def compiled_rhs(self):
            return _compiled_ode.CompiledModel(decay_rhs, None, "reliability_decay", (self.rate,))

        def rhs(self, t, x, u):
            return self.rate * x

    t = np.linspace(0.0, 1.0, 11)
    r = simulate(Decay(-1.0), t, x0=[1.0], method="RK45", backend="compiled", rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(r["level"], np.exp(-t), rtol=1e-7)
    with pytest.raises(SimulationError, match=r"too many steps -- .*1\.2e\+07 steps.*'LSODA'"):
        simulate(Decay(-1e6), np.linspace(0.0, 40.0, 11), x0=[1.0], method="RK45", backend="compiled")
