"""The compiled integrator (vehdyn.simulation.compiled) against closed forms and scipy's solve_ivp."""

import math

import numpy as np
import pytest

import vehdyn
from vehdyn.simulation import compiled as _compiled_ode
from vehdyn.piecewise_signal import PiecewiseSignal

numba = pytest.importorskip("numba")

# the test problems dy/dt = f(t, y, u) in one compiled function (one integrator to compile):
# args = (problem, p1, p2)
OSCILLATOR, GROWTH, VAN_DER_POL, BLOW_UP, NAN_AFTER_HALF, ROBERTSON = 0.0, 1.0, 2.0, 3.0, 4.0, 5.0


@numba.njit(cache=True)
def _problems(t, y, u, args, dydt):
    problem, p1, p2 = args
    if problem == OSCILLATOR:  # x'' + 2 zeta omega x' + omega^2 x = u, (omega, zeta) = (p1, p2)
        dydt[0] = y[1]
        dydt[1] = u[0] - 2.0 * p2 * p1 * y[1] - p1 * p1 * y[0]
    elif problem == GROWTH:  # y' = lambda y + u
        dydt[0] = p1 * y[0] + u[0]
    elif problem == VAN_DER_POL:
        dydt[0] = y[1]
        dydt[1] = p1 * (1.0 - y[0] * y[0]) * y[1] - y[0]
    elif problem == BLOW_UP:  # y' = y^2: y = 1 / (1 - t) from y(0) = 1, singular at t = 1
        dydt[0] = y[0] * y[0]
    elif problem == ROBERTSON:  # Robertson's chemical kinetics (Hairer & Wanner II, sec. IV.1): very stiff
        dydt[0] = -0.04 * y[0] + 1e4 * y[1] * y[2]
        dydt[1] = 0.04 * y[0] - 1e4 * y[1] * y[2] - 3e7 * y[1] * y[1]
        dydt[2] = 3e7 * y[1] * y[1]
    else:  # a derivative that turns NaN after t = 0.5
        dydt[0] = math.nan if t > 0.5 else 1.0


class Compiled(vehdyn.Model):
    """A model with a compiled rhs and the same rhs on numpy (for solve_ivp)."""

    def __init__(self, problem, numpy_rhs, n_states, parameters):
        args = (problem, *(float(p) for p in parameters), *(0.0,) * (2 - len(parameters)))
        self.declare(states=[f"s{k}" for k in range(n_states)], inputs=["u"])
        self._compiled = _compiled_ode.CompiledModel(_problems, None, "test_problems", args)
        self._numpy_rhs = numpy_rhs
        self.args = args

    def compiled_rhs(self):
        return self._compiled

    def rhs(self, t, x, u):
        return self._numpy_rhs(t, np.asarray(x, float), np.asarray(u, float), self.args)


def oscillator(omega=2.0, zeta=0.1):
    def rhs(t, y, u, args):
        return np.stack([y[1], u[0] - 2 * args[2] * args[1] * y[1] - args[1] ** 2 * y[0]])

    return Compiled(OSCILLATOR, rhs, 2, (omega, zeta))


def growth(rate=1.0):
    return Compiled(GROWTH, lambda t, y, u, args: args[1] * y + u, 1, (rate,))


def test_damped_oscillator_matches_its_closed_form():
    omega, zeta = 2.0, 0.1
    model = oscillator(omega, zeta)
    t = np.linspace(0.0, 10.0, 101)
    wd = omega * np.sqrt(1 - zeta**2)
    exact = np.exp(-zeta * omega * t) * (np.cos(wd * t) + zeta * omega / wd * np.sin(wd * t))
    for method, rtol in (("RK45", 1e-8), ("DOP853", 1e-10)):
        result = vehdyn.simulate(model, t, x0=[1.0, 0.0], method=method, rtol=rtol, atol=rtol * 1e-3,
                                 backend="compiled")
        assert "compiled" in result.method_reason
        assert np.max(np.abs(result["s0"] - exact)) < 50 * rtol


@pytest.mark.parametrize("method, order, steps", [("RK45", 5, (0.1, 0.05)), ("DOP853", 8, (0.4, 0.2))])
def test_order_of_accuracy_on_exponential_growth(method, order, steps):
    # fixed steps (first_step = max_step, a tolerance that accepts every step): the global error
    # of a p-th order method falls by 2^p when the step halves
    model = growth(1.0)
    errors = []
    for h in steps:
        t = np.linspace(0.0, 2.0, int(round(2.0 / h)) + 1)
        result = vehdyn.simulate(model, t, x0=[1.0], method=method, rtol=1e3, atol=1e3, first_step=h, max_step=h,
                                 backend="compiled")
        assert result.n_steps == t.size - 1
        errors.append(abs(result["s0"][-1] - np.exp(2.0)))
    assert np.log2(errors[0] / errors[1]) == pytest.approx(order, abs=0.3)


@pytest.mark.parametrize("method", ["RK45", "DOP853"])
def test_equals_solve_ivp_step_by_step(method):
    # the same tableaus, error norm, initial step and step control as scipy: the same steps
    from scipy.integrate import solve_ivp

    mu = 2.0
    model = Compiled(VAN_DER_POL, None, 2, (mu,))
    t = np.linspace(0.0, 10.0, 51)
    ours = vehdyn.simulate(model, t, x0=[2.0, 0.0], method=method, rtol=1e-6, atol=1e-8, backend="compiled")
    theirs = solve_ivp(lambda tt, y: [y[1], mu * (1 - y[0] ** 2) * y[1] - y[0]], (0, 10), [2.0, 0.0],
                       method=method, rtol=1e-6, atol=1e-8, t_eval=t)
    assert np.allclose(ours.states, theirs.y, rtol=1e-9, atol=1e-9)
    assert ours.n_steps == theirs.t.size - 1 or ours.nfev == pytest.approx(theirs.nfev, rel=0.02)


def test_sampled_inputs_hold_as_in_simulate_and_their_kinks_are_steps():
    # dy/dt = u with u held (zoh) or linear (foh) between samples: y is the exact integral
    model = growth(0.0)
    t = np.linspace(0.0, 2.0, 21)
    u = np.sin(3.0 * t) + (t > 1.0)
    for hold in ("zoh", "foh"):
        result = vehdyn.simulate(model, t, {"u": u}, method="RK45", hold=hold, rtol=1e-10, atol=1e-12,
                                 backend="compiled")
        numpy = vehdyn.simulate(model, t, {"u": u}, method="RK45", hold=hold, rtol=1e-10, atol=1e-12,
                                backend="numpy")
        dt = np.diff(t)
        steps = u[:-1] * dt if hold == "zoh" else 0.5 * (u[:-1] + u[1:]) * dt
        exact = np.concatenate([[0.0], np.cumsum(steps)])
        assert np.max(np.abs(result["s0"] - exact)) < 1e-11
        assert np.max(np.abs(numpy["s0"] - exact)) < 1e-6  # scipy straddles the kinks


def test_piecewise_signal_is_integrated_exactly_between_samples():
    model = growth(0.0)
    omega = 2 * np.pi * 0.5
    signal = PiecewiseSignal([[0.3, 1.3, 0.0, 0.0, 1.0, omega, 0.0], [1.3, np.inf, 0.5, 0.0, 0.0, 0.0, 0.0]])
    t = np.linspace(0.0, 3.0, 7)  # coarse grid: samples of the signal would not do
    result = vehdyn.simulate(model, t, {"u": signal}, method="DOP853", rtol=1e-12, atol=1e-14, backend="compiled")
    tau = np.clip(t - 0.3, 0.0, 1.0)
    exact = (1 - np.cos(omega * tau)) / omega + 0.5 * np.maximum(t - 1.3, 0.0)
    assert np.max(np.abs(result["s0"] - exact)) < 1e-12


def test_singularity_raises_with_its_time():
    model = Compiled(BLOW_UP, None, 1, ())
    with pytest.raises(vehdyn.SimulationError, match="underflow|non-finite") as info:
        vehdyn.simulate(model, np.linspace(0.0, 2.0, 5), x0=[1.0], method="RK45", backend="compiled")
    assert info.value.time == pytest.approx(1.0, abs=1e-3)


def test_non_finite_derivative_raises_never_a_silent_nan():
    model = Compiled(NAN_AFTER_HALF, None, 1, ())
    with pytest.raises(vehdyn.SimulationError, match="non-finite") as info:
        vehdyn.simulate(model, np.linspace(0.0, 1.0, 5), x0=[0.0], method="DOP853", backend="compiled")
    assert 0.4 < info.value.time <= 0.5 + 1e-9


@pytest.mark.parametrize("option, value", [("rtol", 1e-20), ("rtol", np.inf), ("atol", -1.0), ("max_step", -0.1),
                                           ("first_step", 0.0)])
def test_bad_options_name_the_option_and_value(option, value):
    with pytest.raises(vehdyn.ParameterError, match=option) as info:
        vehdyn.simulate(growth(), np.linspace(0, 1, 3), x0=[1.0], method="RK45", backend="compiled",
                        **{option: value})
    assert info.value.key == option


def test_backend_choice_and_its_errors(monkeypatch):
    model = growth()
    t = np.linspace(0, 1, 3)
    assert "compiled" in vehdyn.simulate(model, t, x0=[1.0], method="RK45").method_reason  # auto
    assert "compiled" not in vehdyn.simulate(model, t, x0=[1.0], method="LSODA").method_reason
    with pytest.raises(vehdyn.ParameterError, match="LSODA"):
        vehdyn.simulate(model, t, x0=[1.0], method="LSODA", backend="compiled")
    with pytest.raises(vehdyn.ParameterError, match="backend"):
        vehdyn.simulate(model, t, x0=[1.0], backend="fortran")
    with pytest.raises(vehdyn.ParameterError, match="batch"):
        vehdyn.simulate(model, t, x0=np.ones((1, 3)), method="RK45", backend="compiled")
    plain = vehdyn.LinearModel([[-1.0]], [[1.0]], [[1.0]], [[0.0]], states=["s0"], inputs=["u"])
    with pytest.raises(vehdyn.ParameterError, match="no compiled rhs"):
        vehdyn.simulate(plain, t, x0=[1.0], method="RK45", backend="compiled")
    # without numba: a clear error when asked for, the numpy path under auto
    monkeypatch.setattr(_compiled_ode, "numba_available", lambda: False)
    with pytest.raises(vehdyn.ParameterError, match="numba is not installed"):
        vehdyn.simulate(model, t, x0=[1.0], method="RK45", backend="compiled")
    fallback = vehdyn.simulate(model, t, x0=[1.0], method="RK45")
    assert "compiled" not in fallback.method_reason
    assert fallback["s0"][-1] == pytest.approx(np.e, rel=1e-5)


# --------------------------------------------------------------------------- BDF (stiff problems)
def _van_der_pol(mu):
    return lambda tt, y: [y[1], mu * (1 - y[0] ** 2) * y[1] - y[0]]


@pytest.mark.parametrize("mu, rtol", [(2.0, 1e-3), (2.0, 1e-6), (100.0, 1e-6)])
def test_bdf_takes_scipys_steps_to_scipys_accuracy(mu, rtol):
    # the same NDF formulas, Newton iteration, error estimate and order/step selection as
    # solve_ivp's BDF: the same number of steps and the same error against a tight reference
    # (the Jacobians differ -- forward differences here, scipy's num_jac there -- so the Newton
    # iterates, not the steps, differ within the Newton tolerance)
    from scipy.integrate import solve_ivp

    t = np.linspace(0.0, 10.0, 51)
    reference = solve_ivp(_van_der_pol(mu), (0, 10), [2.0, 0.0], method="Radau", rtol=1e-12, atol=1e-14,
                          t_eval=t).y
    ours = vehdyn.simulate(Compiled(VAN_DER_POL, None, 2, (mu,)), t, x0=[2.0, 0.0], method="BDF", rtol=rtol,
                           atol=rtol * 1e-2, backend="compiled")
    theirs = solve_ivp(_van_der_pol(mu), (0, 10), [2.0, 0.0], method="BDF", rtol=rtol, atol=rtol * 1e-2)
    sampled = solve_ivp(_van_der_pol(mu), (0, 10), [2.0, 0.0], method="BDF", rtol=rtol, atol=rtol * 1e-2, t_eval=t)
    assert "compiled BDF" in ours.message
    assert ours.n_steps == pytest.approx(theirs.t.size - 1, rel=0.02)
    ours_error, their_error = (np.max(np.abs(y - reference)) for y in (ours.states, sampled.y))
    assert ours_error < 1.5 * their_error


def test_bdf_on_the_damped_oscillator_matches_its_closed_form_as_scipys_bdf_does():
    from scipy.integrate import solve_ivp

    omega, zeta = 2.0, 0.1
    t = np.linspace(0.0, 10.0, 101)
    wd = omega * np.sqrt(1 - zeta**2)
    exact = np.exp(-zeta * omega * t) * (np.cos(wd * t) + zeta * omega / wd * np.sin(wd * t))
    for rtol in (1e-4, 1e-7):
        ours = vehdyn.simulate(oscillator(omega, zeta), t, x0=[1.0, 0.0], method="BDF", rtol=rtol, atol=rtol * 1e-2,
                               backend="compiled")
        theirs = solve_ivp(lambda tt, y: [y[1], -2 * zeta * omega * y[1] - omega**2 * y[0]], (0, 10), [1.0, 0.0],
                           method="BDF", rtol=rtol, atol=rtol * 1e-2, t_eval=t)
        ours_error, their_error = (np.max(np.abs(y - exact)) for y in (ours["s0"], theirs.y[0]))
        assert ours_error < 1.5 * their_error and ours_error < 100 * rtol


def test_bdf_solves_a_stiff_problem_an_explicit_method_cannot():
    # Prothero-Robinson: y' = lambda (y - cos t) - sin t, y(0) = 1, solution cos t whatever lambda;
    # the forcing -lambda cos t - sin t = R sin(t + phi) as a closed-form input. With lambda = -1e4
    # RK45's stability holds it to h <= 3.3e-4 s (>= 30,000 steps in 10 s); BDF's steps follow the
    # smooth solution.
    lam = -1e4
    forcing = PiecewiseSignal([[0.0, np.inf, 0.0, 0.0, math.hypot(lam, 1.0), 1.0, math.atan2(-lam, -1.0)]])
    t = np.linspace(0.0, 10.0, 201)
    result = vehdyn.simulate(growth(lam), t, {"u": forcing}, x0=[1.0], method="BDF", rtol=1e-6, atol=1e-9,
                             backend="compiled")
    assert np.max(np.abs(result["s0"] - np.cos(t))) < 1e-5
    assert result.n_steps < 1000
    explicit = vehdyn.simulate(growth(lam), t[:3], {"u": forcing}, x0=[1.0], method="RK45", rtol=1e-6, atol=1e-9,
                               backend="compiled")
    assert explicit.n_steps / (t[2] - t[0]) * (t[-1] - t[0]) > 20 * result.n_steps


def test_bdf_on_robertsons_kinetics_conserves_mass_and_matches_radau():
    # y1 + y2 + y3 = 1 is a linear invariant that every linear multistep method keeps exactly
    # (up to the Newton tolerance); the reference: scipy's Radau at a tight tolerance
    from scipy.integrate import solve_ivp

    t = np.array([0.0, 0.4, 4.0, 40.0, 400.0])
    result = vehdyn.simulate(Compiled(ROBERTSON, None, 3, ()), t, x0=[1.0, 0.0, 0.0], method="BDF", rtol=1e-6,
                             atol=1e-12, backend="compiled")
    assert np.max(np.abs(result.states.sum(axis=0) - 1.0)) < 1e-9
    reference = solve_ivp(lambda tt, y: [-0.04 * y[0] + 1e4 * y[1] * y[2],
                                         0.04 * y[0] - 1e4 * y[1] * y[2] - 3e7 * y[1] ** 2, 3e7 * y[1] ** 2],
                          (0, 400), [1.0, 0.0, 0.0], method="Radau", rtol=1e-10, atol=[1e-12, 1e-18, 1e-12], t_eval=t)
    assert np.allclose(result.states, reference.y, rtol=1e-4, atol=[[1e-7], [1e-12], [1e-7]])
    assert result.n_steps < 500


def test_bdf_restarts_at_input_kinks_and_integrates_held_inputs_exactly():
    # dy/dt = u, u held between samples: BDF restarts at every kink (order 1, exact for constants)
    model = growth(0.0)
    t = np.linspace(0.0, 2.0, 21)
    u = np.sin(3.0 * t) + (t > 1.0)
    result = vehdyn.simulate(model, t, {"u": u}, method="BDF", hold="zoh", rtol=1e-10, atol=1e-12,
                             backend="compiled")
    exact = np.concatenate([[0.0], np.cumsum(u[:-1] * np.diff(t))])
    assert np.max(np.abs(result["s0"] - exact)) < 1e-11


def test_bdf_failures_raise_with_their_time():
    with pytest.raises(vehdyn.SimulationError, match="BDF failed.*(underflow|non-finite)") as info:
        vehdyn.simulate(Compiled(BLOW_UP, None, 1, ()), np.linspace(0.0, 2.0, 5), x0=[1.0], method="BDF",
                        backend="compiled")
    assert info.value.time == pytest.approx(1.0, abs=1e-3)
    with pytest.raises(vehdyn.SimulationError, match="non-finite") as info:
        vehdyn.simulate(Compiled(NAN_AFTER_HALF, None, 1, ()), np.linspace(0.0, 1.0, 5), x0=[0.0], method="BDF",
                        backend="compiled")
    assert 0.4 < info.value.time <= 0.5 + 1e-9
