"""The drivers closed by ClosedLoop reproduce the old driver loops (tests/data/closed_loop_reference.npz).

The reference holds the trajectories of ``DriverInTheLoop`` (pure pursuit) and ``DrivenVehicle``
(crossover, optimal preview) as the code of commit 255e4dd computed them, numpy and compiled, with
the cases' step control and at a fixed step (tests/data/closed_loop_reference.md). Compared here:
the plant's states and the driver's steer (the delay's states are left out: the drivers' Padé
realization is now the balanced one of :func:`vehdyn.interconnect.pade_delay`, another basis of
the same transfer function).

What was measured, and is held here:

* pure pursuit (with and without speed control, around ABS, around the full vehicle) and the
  crossover driver without delay: the same arithmetic in the same order, so bitwise equal on the
  numpy path, and on the compiled path for pure pursuit (the old compiled crossover twin computed
  ``(K * diff) * cos(psi)`` where the one law computes ``K * (diff * cos(psi))``: 1 ulp in the
  command);
* at a fixed step the crossover and optimal preview loops equal the old ones to 1e-14 of each
  signal's peak (measured at most 2.2e-15, 1.2e-14 around ABS): a Runge-Kutta step commutes with
  a linear change of the delay's coordinates, so the balanced realization changes rounding only;
* under step control (RK45, rtol 1e-7) any rounding difference in the rhs changes the accepted
  step sizes (the error estimate is a difference of nearly equal stages, so its rounding is
  amplified by about 1 / rtol) and the trajectories part by the integration error: measured
  1.8e-6 of the peak (crossover), 2.7e-7 (optimal preview) and 3.9e-4 in the ABS brake torque
  around ABS, whose apply/release switching amplifies the local error. Putting the old companion
  realization back does not remove it (8e-7 and 1.7e-9 measured): the rates are also summed in
  another order than the old ``np.tensordot``. That is the cost of the change, and the bound held.
"""

import numpy as np
import pytest

import vehdyn
from vehdyn.driver import CrossoverDriver, OptimalPreviewDriver, driver_loop_margins, driver_loop_response
from vehdyn.handling import SingleTrack

from .conftest import NAMES, fixed_step

#: Cases whose law and arithmetic are unchanged: bitwise equal (numpy; compiled: pure pursuit only).
SAME_ARITHMETIC = {"preview", "preview_speed", "preview_abs", "preview_full_vehicle", "crossover_no_delay"}
#: Fixed step: |new - old| <= this times each signal's peak (100 ulps; measured <= 1.2e-14).
FIXED_STEP_BOUND = 100 * np.finfo(float).eps
#: Step control: the integration error the changed step sequence shows (measured 1.9e-6; ABS 3.9e-4).
ADAPTIVE_BOUND = {"crossover": 1e-5, "crossover_no_delay": 1e-5, "optimal": 1e-5, "optimal_abs": 2e-3}


def _compared(loop, driver, states):
    """The plant's states and the driver's steer (its last state)."""
    keep = list(range(loop.n_states - driver.n_states)) + [loop.n_states - 1]
    return states[keep]


def _relative(new, old):
    return np.max(np.abs(new - old), axis=1) / np.maximum(np.max(np.abs(old), axis=1), 1e-300)


def _fixed(t):
    h = fixed_step(t)
    return dict(method="RK45", rtol=1e3, atol=1e3, first_step=h, max_step=h)


def test_the_reference_was_made_by_the_old_code(reference):
    assert str(reference["commit"]).startswith("255e4dd")
    assert all(f"{name}/numpy_fixed/states" in reference for name in NAMES)


@pytest.mark.parametrize("name", NAMES)
def test_numpy_loops_reproduce_the_old_ones_at_a_fixed_step(name, reference, closed_loop_case):
    # a fixed step makes the first part of a run independent of where it ends (but for the last step,
    # cut short at the end): the first quarter is run and compared but for its last instant (the whole
    # run costs 11-44 s a case on numpy)
    loop, driver, t, inputs, x0, _ = closed_loop_case(name)
    assert loop.state_names == tuple(reference[f"{name}/state_names"])
    k = (t.size - 1) // 4 + 1
    r = vehdyn.simulate(loop, t[:k], inputs, x0=x0, backend="numpy", **_fixed(t))
    new = _compared(loop, driver, r.states)[:, :-1]
    old = _compared(loop, driver, reference[f"{name}/numpy_fixed/states"])[:, :k - 1]
    assert r.nfev == pytest.approx(reference[f"{name}/numpy_fixed/nfev"][0] * (k - 1) / (t.size - 1), rel=0.02)
    if name in SAME_ARITHMETIC:
        np.testing.assert_array_equal(new, old)
    else:
        assert np.max(_relative(new, old)) <= FIXED_STEP_BOUND
    np.testing.assert_array_equal(r["driver_steer_angle"], r.states[-1])


@pytest.mark.parametrize("name", ["preview_speed", "crossover"])
def test_numpy_loops_under_step_control(name, reference, closed_loop_case):
    loop, driver, t, inputs, x0, options = closed_loop_case(name)
    r = vehdyn.simulate(loop, t, inputs, x0=x0, backend="numpy", **options)
    new = _compared(loop, driver, r.states)
    old = _compared(loop, driver, reference[f"{name}/numpy/states"])
    if name in SAME_ARITHMETIC:
        np.testing.assert_array_equal(new, old)
        assert r.nfev == reference[f"{name}/numpy/nfev"][0]
    else:
        assert np.max(_relative(new, old)) <= ADAPTIVE_BOUND[name]


@pytest.mark.parametrize("run", ["compiled_fixed", "compiled"])
@pytest.mark.parametrize("name", NAMES)
def test_compiled_loops_reproduce_the_old_compiled_twins(name, run, reference, closed_loop_case):
    pytest.importorskip("numba")
    loop, driver, t, inputs, x0, options = closed_loop_case(name)
    options = _fixed(t) if run == "compiled_fixed" else options
    r = vehdyn.simulate(loop, t, inputs, x0=x0, backend="compiled", **options)
    assert "compiled" in r.method_reason
    new = _compared(loop, driver, r.states)
    old = _compared(loop, driver, reference[f"{name}/{run}/states"])
    if name.startswith("preview"):  # the same compiled law, bitwise
        np.testing.assert_array_equal(new, old)
        assert r.nfev == reference[f"{name}/{run}/nfev"][0]
    elif run == "compiled_fixed":
        assert np.max(_relative(new, old)) <= FIXED_STEP_BOUND
    else:
        assert np.max(_relative(new, old)) <= ADAPTIVE_BOUND[name]


@pytest.mark.parametrize("kind", ["crossover", "optimal"])
@pytest.mark.parametrize("order", [3, 6])
def test_driver_loop_margins_are_the_old_ones_and_python_controls(kind, order, reference):
    # the old numbers (the companion-form Padé of the old driver module), and the loop's frequency response
    # with python-control's control.pade in place of the exact delay at the two crossovers: the balanced
    # realization has the same transfer function, so the same margins
    import control

    car = vehdyn.load_vehicle("sedan")
    model = SingleTrack(car)
    path_x = np.linspace(-100.0, 1000.0, 200)
    if kind == "crossover":
        driver = CrossoverDriver(path_x, 0 * path_x, gain=0.03, preview_time=1.0, delay=0.12)
    else:
        driver = OptimalPreviewDriver(path_x, 0 * path_x, vehicle=car, speed=20.0, delay=0.1)
    m = driver_loop_margins(model, driver, 20.0, pade_order=order)
    got = np.array([m["gain_margin"], m["phase_margin"], m["crossover_frequency"], m["phase_crossover_frequency"]])
    old = reference[f"margins/{kind}/{order}"]
    np.testing.assert_allclose(got, old[:4], rtol=1e-9)
    assert m["stable"] is bool(old[4])
    omega = np.array([m["crossover_frequency"], m["phase_crossover_frequency"]])
    num, den = control.pade(driver.delay, order)
    pade = np.polyval(num, 1j * omega) / np.polyval(den, 1j * omega)
    loop = driver_loop_response(model, driver, 20.0, omega) * np.exp(1j * omega * driver.delay) * pade
    assert abs(loop[0]) == pytest.approx(1.0, rel=1e-7)
    assert np.angle(-loop[0]) == pytest.approx(m["phase_margin"], abs=1e-7)
    assert np.angle(-loop[1]) == pytest.approx(0.0, abs=1e-7)
    assert 1.0 / abs(loop[1]) == pytest.approx(m["gain_margin"], rel=1e-7)
