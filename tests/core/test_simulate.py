"""Simulation engines against closed forms, convergence orders and error paths."""

import numpy as np
import pytest

import vehdyn
from vehdyn import LinearModel, Model, ParameterError, SimulationError, simulate
from vehdyn.simulation import exact_discretization, rk4_stability_limit

WN, ZETA = 2.0, 0.1


def oscillator():
    return LinearModel([[0, 1], [-WN**2, -2 * ZETA * WN]], [[0], [WN**2]],
                       states=["position", "position_velocity"], inputs=["force"])


def free_response(t, x0=1.0):
    """Closed form of x'' + 2 zeta wn x' + wn^2 x = 0, x(0) = x0, x'(0) = 0."""
    wd = WN * np.sqrt(1 - ZETA**2)
    return x0 * np.exp(-ZETA * WN * t) * (np.cos(wd * t) + ZETA * WN / wd * np.sin(wd * t))


def step_response(t):
    """Closed form of the unit step response (static gain 1)."""
    return 1.0 - free_response(t)


def test_exact_free_response_matches_closed_form():
    t = np.linspace(0, 20, 20001)
    r = simulate(oscillator(), t, x0=[1.0, 0.0], method="exact")
    assert np.max(np.abs(r["position"] - free_response(t))) <= 1e-12


def test_exact_zoh_step_response_matches_closed_form():
    t = np.linspace(0, 20, 4001)
    r = simulate(oscillator(), t, inputs={"force": 1.0}, method="exact", hold="zoh")
    assert np.max(np.abs(r["position"] - step_response(t))) <= 1e-12


def test_exact_foh_is_exact_for_ramp_input():
    # x' = -x + u, u = t, x(0) = 0  =>  x = t - 1 + exp(-t)
    m = LinearModel([[-1.0]], [[1.0]], states=["level"], inputs=["ramp"])
    t = np.linspace(0, 5, 51)
    r = simulate(m, t, inputs={"ramp": t}, method="exact", hold="foh")
    assert np.max(np.abs(r["level"] - (t - 1 + np.exp(-t)))) <= 1e-13


def test_exact_nonuniform_grid_matches_closed_form():
    t = np.sort(np.concatenate([[0.0], np.random.default_rng(1).uniform(0, 10, 300)]))
    r = simulate(oscillator(), t, x0=[1.0, 0.0], method="exact")
    assert np.max(np.abs(r["position"] - free_response(t))) <= 1e-12


def test_exact_batch_equals_individual_runs():
    t = np.linspace(0, 5, 501)
    x0 = np.array([[1.0, -0.5, 2.0], [0.0, 1.0, 0.3]])
    rb = simulate(oscillator(), t, x0=x0, method="exact")
    for k in range(3):
        rk = simulate(oscillator(), t, x0=x0[:, k], method="exact")
        np.testing.assert_allclose(rb.states[:, :, k], rk.states, rtol=0, atol=1e-14)


def test_exact_discretization_against_series():
    # zoh: B0 = A^-1 (Ad - I) B for invertible A
    A = np.array([[0.0, 1.0], [-3.0, -0.7]])
    B = np.array([[0.0], [1.0]])
    Ad, B0, B1 = exact_discretization(A, B, 0.05, "zoh")
    np.testing.assert_allclose(B0, np.linalg.solve(A, (Ad - np.eye(2)) @ B), rtol=1e-12)
    assert np.all(B1 == 0)


def test_solve_ivp_methods_agree_with_closed_form():
    t = np.linspace(0, 10, 501)
    for method in vehdyn.simulate.__globals__["SOLVE_IVP_METHODS"]:
        r = simulate(oscillator(), t, x0=[1.0, 0.0], method=method, rtol=1e-10, atol=1e-12)
        assert np.max(np.abs(r["position"] - free_response(t))) < 2e-7, method
        assert r.nfev > 0 and r.method == method


def test_rk4_convergence_order_is_four():
    errors = []
    steps = [0.1, 0.05, 0.025]
    for h in steps:
        t = np.arange(0, 10 + h / 2, h)
        r = simulate(oscillator(), t, x0=[1.0, 0.0], method="rk4")
        errors.append(np.max(np.abs(r["position"] - free_response(t))))
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(np.abs(orders - 4.0) < 0.15), orders


def test_rk4_batch_of_nonlinear_models():
    class Decay(Model):
        states = ("level",)

        def __init__(self, rate):
            self.rate = np.asarray(rate)

        def rhs(self, t, x, u):
            return -self.rate * x

    rates = np.array([0.5, 1.0, 2.0])
    t = np.linspace(0, 2, 201)
    r = simulate(Decay(rates), t, x0=np.ones((1, 3)), method="rk4")
    np.testing.assert_allclose(r["level"], np.exp(-np.outer(t, rates)), rtol=1e-8)


def test_rk4_refuses_unstable_step():
    m = LinearModel([[-1000.0]], np.zeros((1, 0)), states=["level"], inputs=[])
    with pytest.raises(SimulationError, match="stability limit"):
        simulate(m, np.linspace(0, 1, 11), x0=[1.0], method="rk4")
    # just inside the limit it runs
    h = rk4_stability_limit([-1000.0])
    assert h == pytest.approx(2.785293563 / 1000, rel=1e-6)  # RK4 real-axis limit
    simulate(m, np.arange(0, 0.1, 0.99 * h), x0=[1.0], method="rk4")


def test_blow_up_raises_simulation_error():
    class Quadratic(Model):
        states = ("level",)

        def rhs(self, t, x, u):
            return x**2

    # x' = x^2, x(0) = 1 blows up at t = 1
    with pytest.raises(SimulationError) as info:
        simulate(Quadratic(), np.linspace(0, 2, 21), x0=[1.0], method="RK45")
    assert "RK45" in str(info.value) and info.value.time is not None and 0.9 < info.value.time <= 1.0
    with pytest.raises(SimulationError, match="'level' became non-finite") as info:
        with np.errstate(over="ignore", invalid="ignore"):
            simulate(Quadratic(), np.linspace(0, 2, 201), x0=[1.0], method="rk4", check_stability=False)
    assert info.value.signal == "level"


def test_auto_picks_exact_for_linear_and_lsoda_for_stiff():
    assert simulate(oscillator(), np.linspace(0, 1, 11)).method == "exact"

    class Stiff(Model):
        states = ("fast", "slow")

        def rhs(self, t, x, u):
            fast, slow = x
            return np.stack([-1e4 * (fast - np.cos(t)), -slow + 0 * fast])

    r = simulate(Stiff(), np.linspace(0, 1, 11), x0=[0.0, 1.0])
    assert r.method == "LSODA" and "stiff" in r.method_reason
    np.testing.assert_allclose(r["slow"], np.exp(-r.time), rtol=1e-4)


def _van_der_pol_jacobian(mu, x):
    return np.array([[0.0, 1.0], [-1.0 - 2.0 * mu * x[0] * x[1], mu * (1.0 - x[0] ** 2)]])


class _VanDerPol(Model):
    states = ("position", "velocity")
    mu = 3.0

    def rhs(self, t, x, u):
        return np.stack([x[1], self.mu * (1 - x[0] ** 2) * x[1] - x[0]])


class _ScalarLogic(_VanDerPol):  # a rhs that takes no batch of states
    def rhs(self, t, x, u):
        if x[0] > 100.0:
            raise AssertionError("not reached")
        return super().rhs(t, x, u)


class _FirstColumnOnly(_VanDerPol):  # a rhs that evaluates a batch wrongly: every column as the first
    def rhs(self, t, x, u):
        x = np.asarray(x)
        first = x if x.ndim == 1 else np.broadcast_to(x[:, :1], x.shape)
        return super().rhs(t, first, u)


@pytest.mark.parametrize("model", [_VanDerPol(), _ScalarLogic(), _FirstColumnOnly()], ids=lambda m: type(m).__name__)
def test_the_method_choice_linearizes_in_one_batched_call_where_the_model_allows(model):
    # auto's eigenvalues of df/dx against the closed-form Jacobian; the one-call path is taken only
    # where the batch evaluates as single calls do (a rhs with scalar logic or a wrong batch falls
    # back to one call per perturbation, with the same eigenvalues)
    from vehdyn.simulation._stiffness import _single_jacobian_in_one_call, _state_jacobian_eigenvalues

    x = np.array([0.7, -1.3])
    expected = np.sort_complex(np.linalg.eigvals(_van_der_pol_jacobian(3.0, x)))
    found = np.sort_complex(_state_jacobian_eigenvalues(model, 0.0, x, np.zeros(0)))
    np.testing.assert_allclose(found, expected, rtol=1e-8)
    one_call = _single_jacobian_in_one_call(model, 0.0, x, np.zeros(0))
    assert (one_call is not None) == (type(model) is _VanDerPol)
    if one_call is not None:
        np.testing.assert_allclose(one_call, _van_der_pol_jacobian(3.0, x), rtol=1e-8, atol=1e-8)


@pytest.mark.compiled_vs_numpy
def test_the_method_choice_of_the_full_vehicle_takes_one_rhs_call_for_its_jacobian():
    # the 32-state full vehicle: one batched numpy call instead of 64 (140 ms -> ~10 ms here), the
    # same Jacobian as one perturbation per call to rounding (the batch is numpy's array path, a single
    # call the tire laws' scalar path, math: the check that picks the one call allows for both)
    from vehdyn.full_vehicle import FullVehicle
    from vehdyn.simulation._stiffness import _single_jacobian_in_one_call

    model = FullVehicle(vehdyn.load_vehicle("sedan"))
    x0, u0 = (np.asarray(v, dtype=float) for v in model.trim(20.0))
    calls = []
    rhs = model.rhs
    model.rhs = lambda t, x, u: calls.append(np.shape(x)) or rhs(t, x, u)
    jacobian = _single_jacobian_in_one_call(model, 0.0, x0, u0)
    assert calls == [(32, 65), (32,)]
    per_call = np.empty((32, 32))
    for i in range(32):
        h = 1e-6 * max(abs(x0[i]), 1.0)
        plus, minus = x0.copy(), x0.copy()
        plus[i] += h
        minus[i] -= h
        per_call[:, i] = (rhs(0.0, plus, u0) - rhs(0.0, minus, u0)) / (2 * h)
    np.testing.assert_allclose(jacobian, per_call, rtol=0, atol=1e-9 * np.max(np.abs(per_call)))


def test_callable_and_mapping_inputs_agree():
    t = np.linspace(0, 5, 501)
    r1 = simulate(oscillator(), t, inputs=lambda tt: np.sin(tt)[None] if np.ndim(tt) else [np.sin(tt)],
                  method="exact")
    r2 = simulate(oscillator(), t, inputs={"force": np.sin(t)}, method="exact")
    r3 = simulate(oscillator(), t, inputs={"force": np.sin}, method="exact")
    np.testing.assert_allclose(r1.states, r2.states, atol=1e-15)
    np.testing.assert_allclose(r3.states, r2.states, atol=1e-15)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"time": [0.0]}, "at least two"),
        ({"time": [0.0, 1.0, 1.0]}, "increase strictly"),
        ({"time": [0.0, np.nan]}, "non-finite"),
        ({"inputs": {"torque": 1.0}}, "no input 'torque'"),
        ({"inputs": np.zeros((2, 11))}, r"shape \(n_inputs, n_times\)"),
        ({"inputs": {"force": np.full(11, np.inf)}}, "'force' is not finite"),
        ({"x0": [1.0]}, "expected 2 values"),
        ({"x0": {"speed": 1.0}}, "unknown name 'speed'"),
        ({"x0": [np.nan, 0.0]}, "'position' is not finite"),
        ({"method": "euler"}, "method must be"),
        ({"hold": "cubic"}, "hold must be"),
        ({"rtol": -1.0}, "rtol must be"),
        ({"substeps": 0}, "substeps"),
    ],
)
def test_simulate_rejects_bad_arguments(kwargs, match):
    args = {"time": np.linspace(0, 1, 11)}
    args.update(kwargs)
    with pytest.raises(ParameterError, match=match):
        simulate(oscillator(), args.pop("time"), **args)


def test_exact_requires_linear_model():
    class Pend(Model):
        states = ("angle", "angle_rate")

        def rhs(self, t, x, u):
            return np.stack([x[1], -np.sin(x[0])])

    with pytest.raises(ParameterError, match="needs a LinearModel"):
        simulate(Pend(), np.linspace(0, 1, 3), method="exact")


def test_result_named_access_frame_and_units():
    t = np.linspace(0, 1, 11)
    r = simulate(oscillator(), t, x0=[1.0, 0.0], inputs={"force": 0.5})
    assert r["position"] is r.states[0] or np.array_equal(r["position"], r.outputs[0])
    np.testing.assert_array_equal(r.position_velocity, r["position_velocity"])
    df = r.to_frame()
    assert list(df.columns) == ["position", "position_velocity", "force"]
    assert df.index.name == "time" and df.attrs["units"]["position_velocity"] == "m/s"
    assert df.attrs["units"]["position"] == "" or df.attrs["units"]["position"] == "m"
    with pytest.raises(KeyError, match="no signal named 'speed'"):
        r["speed"]
    assert r.wall_time > 0 and r.method == "exact"


def test_plots_label_axes_with_units():
    import matplotlib

    matplotlib.use("Agg")
    t = np.linspace(0, 2, 201)
    r = simulate(oscillator(), t, x0=[1.0, 0.0])
    fig = r.plot(["position_velocity", "force"])
    labels = [ax.get_ylabel() for ax in fig.axes]
    assert labels == ["position velocity [m/s]", "force"] and fig.axes[-1].get_xlabel() == "time [s]"
    fr = oscillator().frequency_response(np.logspace(-1, 1, 50))
    fig = fr.plot(outputs=["position"])
    assert fig.axes[0].get_xscale() == "log" and fig.axes[1].get_ylabel() == "phase [deg]"
    assert fig.axes[1].get_xlabel() == "frequency [Hz]"


INTEGRATOR = LinearModel([[0.0]], [[1.0]], states=["level"], inputs=["rate"])  # y' = u


def piecewise_rate():
    """A half-period sine on [0.3, 1.3) then a jump to 0.5 (a kink and a jump between coarse
    samples) and y = its integral, the closed form."""
    omega = np.pi
    signal = vehdyn.PiecewiseSignal([[0.3, 1.3, 0.0, 0.0, 1.0, omega, 0.0], [1.3, np.inf, 0.5, 0.0, 0.0, 0.0, 0.0]])

    def integral(t):
        return (1 - np.cos(omega * np.clip(t - 0.3, 0.0, 1.0))) / omega + 0.5 * np.maximum(t - 1.3, 0.0)

    return signal, integral


@pytest.mark.parametrize("method, rtol, error", [("RK45", 1e-10, 1e-9), ("DOP853", 1e-12, 1e-12),
                                                 ("LSODA", 1e-10, 1e-8)])
def test_piecewise_signal_is_integrated_exactly_between_samples_on_numpy(method, rtol, error):
    # the numpy solvers evaluate a closed-form input at every stage and stop on its breakpoints, as
    # the compiled backend does (they used to sample it on the output grid and interpolate: an
    # error of 0.09 here, whatever the tolerance)
    signal, integral = piecewise_rate()
    t = np.linspace(0.0, 3.0, 7)  # coarse grid: samples of the signal would not do
    result = simulate(INTEGRATOR, t, {"rate": signal}, method=method, rtol=rtol, atol=rtol * 1e-2, backend="numpy")
    assert np.max(np.abs(result["level"] - integral(t))) < error
    bare = simulate(INTEGRATOR, t, signal, method=method, rtol=rtol, atol=rtol * 1e-2, backend="numpy")
    assert np.array_equal(bare.states, result.states)  # a bare signal of a one-input model is the same input


def test_rk4_evaluates_a_piecewise_signal_at_its_stages():
    # fixed steps over a smooth piece: the error is RK4's, O(h^4), not the O(dt^2) of sampled inputs
    omega = 2.0
    signal = vehdyn.PiecewiseSignal([[0.0, np.inf, 0.0, 0.0, 1.0, omega, 0.0]])
    t = np.linspace(0.0, 2.0, 5)
    result = simulate(INTEGRATOR, t, {"rate": signal}, method="rk4", substeps=20)
    assert np.max(np.abs(result["level"] - (1 - np.cos(omega * t)) / omega)) < 1e-7
    sampled = simulate(INTEGRATOR, t, {"rate": signal(t)}, method="rk4", substeps=20)
    assert np.max(np.abs(sampled["level"] - (1 - np.cos(omega * t)) / omega)) > 1e-2  # what foh would give


def test_piecewise_signal_segments_keep_failures_and_options():
    # first_step beyond the first segment is capped to it; a failure after a breakpoint names its time
    signal, integral = piecewise_rate()
    t = np.linspace(0.0, 3.0, 7)
    result = simulate(INTEGRATOR, t, {"rate": signal}, method="RK45", rtol=1e-10, atol=1e-12, first_step=2.0,
                      backend="numpy")
    assert np.max(np.abs(result["level"] - integral(t))) < 1e-9

    class BlowUp(Model):  # y' = y^2 + u: from y(0) = 1 singular before t = 1, after the breakpoint 0.3
        def __init__(self):
            self.declare(states=["level"], inputs=["rate"])

        def rhs(self, t, x, u):
            return x**2 + u

    with pytest.raises(SimulationError, match=r"RK45 failed after t = 0.3 s \(the breakpoint") as info:
        simulate(BlowUp(), [0.0, 3.0], {"rate": signal}, x0=[1.0], method="RK45", backend="numpy")
    assert info.value.time == pytest.approx(0.3)
