"""The one Padé delay (vehdyn.interconnect.pade_delay): python-control's approximant, all-pass, balanced, the
0 s pass-through, the drivers and the loop analysis on it, errors."""

import numpy as np
import pytest

from vehdyn import ParameterError
from vehdyn.driver import CrossoverDriver
from vehdyn.interconnect import pade_coefficients, pade_delay


def _response(A, B, C, D, omega):
    n = A.shape[0]
    return np.array([(C @ np.linalg.solve(1j * w * np.eye(n) - A, B) + D)[0, 0] for w in omega])


@pytest.mark.parametrize("order", range(1, 11))
@pytest.mark.parametrize("delay", [0.05, 0.2, 1.5])
def test_pade_delay_is_control_pade(delay, order):
    import control

    omega = np.array([0.1, 1.0, 3.0, 10.0]) / delay
    ours = _response(*pade_delay(delay, order), omega)
    num, den = control.pade(delay, order)
    theirs = np.polyval(num, 1j * omega) / np.polyval(den, 1j * omega)
    np.testing.assert_allclose(ours, theirs, rtol=1e-10)
    np.testing.assert_allclose(np.abs(ours), 1.0, rtol=1e-12)  # all-pass


def test_pade_delay_approximates_the_delay():
    w, tau = 5.0, 0.2  # omega tau = 1: the 6th-order approximant's phase error is far below 1e-8
    assert _response(*pade_delay(tau, 6), [w])[0] == pytest.approx(np.exp(-1j * w * tau), abs=1e-9)


def test_balanced_realization_is_better_conditioned_than_the_companion_form():
    from scipy import signal

    for order in (6, 10):
        c = pade_coefficients(order)
        companion = signal.tf2ss((c * (-1.0) ** np.arange(order + 1))[::-1], c[::-1])[0]
        balanced = pade_delay(1.0, order)[0]
        assert np.linalg.cond(balanced) < 1e-3 * np.linalg.cond(companion)
        np.testing.assert_allclose(np.sort_complex(np.linalg.eigvals(balanced)),
                                   np.sort_complex(np.linalg.eigvals(companion)), rtol=1e-8)


def test_zero_delay_is_a_pass_through_and_a_driver_without_delay_states():
    A, B, C, D = pade_delay(0.0, 4)
    assert A.shape == (0, 0) and B.shape == (0, 1) and C.shape == (1, 0)
    assert D[0, 0] == 1.0
    path_x = np.linspace(0.0, 100.0, 11)
    driver = CrossoverDriver(path_x, 0 * path_x, gain=0.1, delay=0.0)
    assert driver.state_names == ("driver_steer_angle",)
    assert CrossoverDriver(path_x, 0 * path_x, gain=0.1, delay=0.1, pade_order=5).n_states == 6


def test_pade_coefficients_closed_form():
    # [1/1]: (1 - p/2) / (1 + p/2); [2/2]: (1 - p/2 + p^2/12) / (1 + p/2 + p^2/12)
    np.testing.assert_allclose(pade_coefficients(1), [1.0, 0.5], rtol=1e-15)
    np.testing.assert_allclose(pade_coefficients(2), [1.0, 0.5, 1.0 / 12.0], rtol=1e-15)


@pytest.mark.parametrize("key, delay, order", [("order", 0.1, 0), ("order", 0.1, 13), ("order", 0.1, 2.0),
                                               ("order", 0.1, True), ("delay", -0.1, 3), ("delay", np.nan, 3),
                                               ("delay", np.inf, 3), ("delay", True, 3), ("delay", "0.1", 3)])
def test_bad_delay_or_order_is_named(key, delay, order):
    with pytest.raises(ParameterError, match=key) as info:
        pade_delay(delay, order)
    assert info.value.key == key
