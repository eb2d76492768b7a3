r"""The driver-vehicle loop analysed with python-control: the open loop cut at the steer, its
frequency response, gain and phase margins.

About straight running on a straight path the driver's command is linear in the vehicle's
signals, :math:`\delta_c = -F x` (the driver's ``perception(speed)`` gains), and the loop cut at
the road-wheel steer is

.. math::

    L(s) = \frac{e^{-\tau s}}{T_N s + 1}\, F (sI - A)^{-1} b

with :math:`(A, b)` the plant's linearization at straight running (front steer input). Closed
with negative feedback (:math:`\delta = -L \delta`); margins in Nyquist's sense (Åström & Murray
2021, sec. 10.3; McRuer & Jex 1967 for the driver's crossover form).

References
----------
.. [1] K. J. Åström and R. M. Murray, *Feedback Systems*, 2nd ed., Princeton University Press,
   2021, sec. 10.3 (stability margins).
.. [2] D. T. McRuer and H. R. Jex, "A review of quasi-linear pilot models", IEEE Trans. Human
   Factors in Electronics 8(3), 231-249, 1967.
"""

from __future__ import annotations

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.interconnect import pade_delay
from vehdyn.model import Model

__all__ = ["driver_loop", "driver_loop_response", "driver_loop_margins"]


def _plant_steer_model(plant: Model, speed: float):
    """The plant's linearization at straight running at ``speed`` (cached on the plant per speed)."""
    if not hasattr(plant, "straight_running"):
        raise ParameterError(f"{type(plant).__name__} has no straight_running(speed): give a SingleTrack-like model",
                             key="plant", value=type(plant).__name__)
    cache = plant.__dict__.setdefault("_driver_loop_linearizations", {})
    if float(speed) not in cache:
        cache[float(speed)] = plant.linearize(speed=speed)
    return cache[float(speed)]


def _perception_row(lin, driver, speed):
    """Row F over the linear plant's states such that delta_c = -F x (about straight running)."""
    gains = driver.perception(speed)
    missing = [name for name in gains if name not in lin.state_names and name not in lin.output_names]
    if missing:
        raise ParameterError(f"{type(driver).__name__} cannot be attached to the plant: missing inputs {missing}",
                             key="missing_inputs", value=missing)
    row = np.zeros(lin.n_states)
    for name, k in gains.items():
        if name in lin.state_names:
            row[lin.index(name)] += k
        else:
            j = lin.index(name, "outputs")
            row += k * lin.C[j]
    return row


def driver_loop_response(plant: Model, driver, speed: float, omega) -> np.ndarray:
    r"""Open-loop frequency response :math:`L(j\omega)` of the driver-vehicle loop cut at the steer.

    .. math::

        L(j\omega) = \frac{e^{-j\omega\tau}}{j\omega T_N + 1}\, F (j\omega I - A)^{-1} b

    with the exact delay (module docstring); the loop is closed with negative feedback
    (:math:`\delta = -L \delta`).

    Parameters
    ----------
    plant : Model
        A SingleTrack-like model with ``linearize(speed=...)`` (``straight_running``) and the
        input ``front_steer_angle``; its linearization is cached per speed.
    driver : Controller
        A driver of :mod:`vehdyn.driver` (its ``perception(speed)``, ``delay``, lag).
    speed : float
        Forward speed u [m/s].
    omega : array_like
        Angular frequencies [rad/s].

    Returns
    -------
    ndarray
        :math:`L(j\omega)` [-], complex, one per frequency.
    """
    lin = _plant_steer_model(plant, speed)
    row = _perception_row(lin, driver, speed)
    b = lin.B[:, lin.index("front_steer_angle", "inputs")]
    omega = np.asarray(omega, dtype=float)
    matrices = 1j * omega[:, None, None] * np.eye(lin.n_states) - lin.A
    plant_part = np.linalg.solve(matrices, np.broadcast_to(b[:, None], (omega.size, b.size, 1)))[:, :, 0] @ row
    return plant_part * np.exp(-1j * omega * driver.delay) / (1j * omega * driver.numbers.lag + 1.0)


def driver_loop(plant: Model, driver, speed: float, *, pade_order: int = 6):
    r"""The open loop :math:`L(s)` as a ``control.StateSpace``, the delay as a Padé approximant.

    Input and output are the road-wheel steer [rad]: the car (its states that the steer reaches
    and that the driver sees; the position x and the speed drop out in straight running), the
    driver's gains, its delay (:func:`vehdyn.interconnect.pade_delay`, balanced) and its lag in
    series. ``control.feedback(L, 1)`` is the closed loop.

    Parameters
    ----------
    plant : Model
        As for :func:`driver_loop_response`.
    driver : Controller
        A driver of :mod:`vehdyn.driver`.
    speed : float
        Forward speed u [m/s].
    pade_order : int
        Order of the delay's Padé approximant (default 6).

    Returns
    -------
    control.StateSpace
        L(s), one input and one output [rad/rad].
    """
    import control

    lin = _plant_steer_model(plant, speed)
    row = _perception_row(lin, driver, speed)
    b = lin.B[:, lin.index("front_steer_angle", "inputs")]
    reached, seen = b != 0, row != 0
    while True:  # structural reachability from the steer and observability by the driver
        grown = (reached | np.any(lin.A[:, reached] != 0, axis=1), seen | np.any(lin.A[seen, :] != 0, axis=0))
        if np.array_equal(grown[0], reached) and np.array_equal(grown[1], seen):
            break
        reached, seen = grown
    keep = np.nonzero(reached & seen)[0]
    Ac, bc, rc = lin.A[np.ix_(keep, keep)], b[keep], row[keep]
    Ap, Bp, Cp, Dp = pade_delay(driver.delay, pade_order)
    n, m = keep.size, Ap.shape[0]
    A = np.zeros((n + m + 1, n + m + 1))
    A[:n, :n] = Ac
    A[n:n + m, :n] = np.outer(Bp[:, 0], rc)
    A[n:n + m, n:n + m] = Ap
    A[-1, :n] = Dp[0, 0] * rc / driver.numbers.lag
    A[-1, n:n + m] = Cp[0] / driver.numbers.lag
    A[-1, -1] = -1.0 / driver.numbers.lag
    B = np.zeros((n + m + 1, 1))
    B[:n, 0] = bc
    C = np.zeros((1, n + m + 1))
    C[0, -1] = 1.0
    return control.ss(A, B, C, 0.0)


def driver_loop_margins(plant: Model, driver, speed: float, *, pade_order: int = 6) -> dict:
    """Gain and phase margins of the driver-vehicle loop at ``speed`` (python-control).

    ``control.stability_margins`` of :func:`driver_loop` (the delay as a Padé approximant of
    ``pade_order``: at the default 6 its phase error is below 1e-8 rad up to omega tau = 1.6, so
    the margins are those of the exact delay) and ``stable`` from the poles of the closed loop
    ``control.feedback(L, 1)``. The margins are Nyquist's when the open loop has no poles in the
    right half-plane (the car below its critical speed); ``stable`` holds in any case.

    Parameters
    ----------
    plant : Model
        As for :func:`driver_loop_response`.
    driver : Controller
        A driver of :mod:`vehdyn.driver`.
    speed : float
        Forward speed u [m/s].
    pade_order : int
        Order of the delay's Padé approximant (default 6).

    Returns
    -------
    dict
        ``gain_margin`` [-] (inf if the phase never crosses -180 deg), ``phase_margin`` [rad],
        ``crossover_frequency`` omega_c [rad/s], ``phase_crossover_frequency`` [rad/s], ``stable``.
    """
    import control

    loop = driver_loop(plant, driver, speed, pade_order=pade_order)
    with np.errstate(over="ignore", invalid="ignore"):  # polynomial evaluation far above crossover
        gm, pm, _, wpc, wgc, _ = control.stability_margins(loop, returnall=False)
    stable = bool(np.all(np.real(control.feedback(loop, 1.0).poles()) < 0))
    return {"gain_margin": float(gm), "phase_margin": float(np.radians(pm)), "crossover_frequency": float(wgc),
            "phase_crossover_frequency": float(wpc), "stable": stable}
