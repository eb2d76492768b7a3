"""The pure delay e^(-s tau) as a state space: the [n/n] Padé approximant, balanced.

The one realization of a delay in the package: the driver models' reaction delay and the ride
models' wheelbase delay both use :func:`pade_delay`. Its accuracy: the [n/n] approximant P is
all-pass (|P(j omega)| = 1 exactly) and |P(j omega) - exp(-j omega tau)| < 1e-3 for
omega tau < 1.5 n - 3.5 and < 1e-2 for omega tau < 1.6 n - 2.3 (n = 4..10, checked in the tests);
the phase error of the [10/10] approximant is 4e-11 rad at omega tau = 5, 3e-8 at 7, 4e-6 at 9,
2e-4 at 11 and 3e-2 at 15; orders above 10 gain little (rounding grows with the order).

References
----------
.. [1] G. A. Baker and P. Graves-Morris, *Padé Approximants*, 2nd ed., Cambridge University
   Press, 1996 (the coefficients c_k).
.. [2] G. F. Franklin, J. D. Powell and A. Emami-Naeini, *Feedback Control of Dynamic Systems*,
   6th ed., 2010, sec. 5.6.3 (the Padé approximant of a delay).
.. [3] G. H. Golub and C. F. Van Loan, *Matrix Computations*, 4th ed., 2013, sec. 9.3.1
   (balancing by a diagonal similarity).
"""

from __future__ import annotations

from functools import lru_cache
from math import factorial

import numpy as np

from vehdyn.errors import ParameterError

__all__ = ["pade_coefficients", "pade_delay"]


def pade_coefficients(order: int) -> np.ndarray:
    r"""Coefficients :math:`c_k` of the [n/n] Padé approximant of :math:`e^{-p}`.

    .. math::

        e^{-p} \approx \frac{\sum_k c_k (-p)^k}{\sum_k c_k p^k}, \qquad
        c_k = \frac{(2n - k)!\, n!}{(2n)!\, k!\, (n - k)!}, \quad k = 0..n

    (Baker & Graves-Morris 1996).

    Parameters
    ----------
    order : int
        n >= 1.

    Returns
    -------
    ndarray
        c_0 .. c_n [-] (ascending powers; c_0 = 1).
    """
    if isinstance(order, bool) or not (isinstance(order, (int, np.integer)) and order >= 1):
        raise ParameterError(f"order must be a positive integer, got {order!r}", key="order", value=order)
    n = int(order)
    return np.array([factorial(2 * n - k) * factorial(n) / (factorial(2 * n) * factorial(k) * factorial(n - k))
                     for k in range(n + 1)])


def pade_delay(delay: float, order: int):
    r"""State space (A, B, C, D) of the [order/order] Padé approximant of :math:`e^{-s \tau}`.

    .. math::

        e^{-s\tau} \approx \frac{\sum_k c_k (-s\tau)^k}{\sum_k c_k (s\tau)^k}
        = C (sI - A)^{-1} B + D

    Built for a unit delay from :func:`pade_coefficients`, balanced by a diagonal similarity (the
    companion form is ill-conditioned beyond order 4) and scaled in time (A / delay, B / delay).
    All-pass; see the module docstring for its phase error. The same transfer function as
    python-control's ``control.pade`` (another realization of it). The one delay of the package:
    the drivers' reaction delay, the ride models' wheelbase delay and the driver-loop analysis.

    Parameters
    ----------
    delay : float
        tau [s] >= 0; 0 is a pass-through: an empty realization (A 0x0, D = 1).
    order : int
        n, from 1 to 12.

    Returns
    -------
    A : ndarray (n, n)
        [1/s].
    B : ndarray (n, 1)
        [1/s].
    C : ndarray (1, n)
        [-].
    D : ndarray (1, 1)
        [-], (-1)^n.

    Raises
    ------
    ParameterError
        On an order outside 1..12 or a delay that is not a finite number >= 0.
    """
    if isinstance(order, bool) or not (isinstance(order, (int, np.integer)) and 1 <= order <= 12):
        raise ParameterError(f"order of the Padé delay must be an integer from 1 to 12 (higher orders lose accuracy "
                             f"to rounding), got {order!r}", key="order", value=order)
    if isinstance(delay, bool) or not (isinstance(delay, (int, float, np.integer, np.floating)) and np.isfinite(delay)
                                       and delay >= 0):
        raise ParameterError(f"delay must be a finite number >= 0 [s], got {delay!r}", key="delay", value=delay)
    if delay == 0:
        return np.zeros((0, 0)), np.zeros((0, 1)), np.zeros((1, 0)), np.ones((1, 1))
    A, B, C, D = _unit_pade(int(order))
    return A / delay, B / delay, C.copy(), D.copy()


@lru_cache(maxsize=16)
def _unit_pade(order: int):
    from scipy import signal
    from scipy.linalg import matrix_balance

    c = pade_coefficients(order)
    num = (c * (-1.0) ** np.arange(order + 1))[::-1]  # descending powers of s
    den = c[::-1]
    A, B, C, D = signal.tf2ss(num, den)
    _, (scale, _) = matrix_balance(A, permute=False, separate=True)
    A = (A / scale[:, None]) * scale[None, :]
    B = B / scale[:, None]
    C = C * scale[None, :]
    for M in (A, B, C, D):
        M.flags.writeable = False
    return A, B, C, D
