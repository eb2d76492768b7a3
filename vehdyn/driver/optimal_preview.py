"""MacAdam's optimal preview driver (C. C. MacAdam, IEEE Trans. SMC 11(6), 1981): preview gains from
the vehicle's linear model over a preview window."""

from __future__ import annotations
from vehdyn.errors import ParameterError
from vehdyn.driver.base import _PathDriver
import numpy as np
from vehdyn.driver.base import preview_offsets

__all__ = ["OptimalPreviewDriver", "preview_gains"]


def preview_gains(A, B, C, times, weights=None):
    """MacAdam's optimal preview gains for an internal model dx/dt = A x + B delta, y = C x.

    With the steer held constant over the preview window, the steer that minimizes
    J = int_0^T W(eta) [f(t + eta) - y(t + eta)]^2 d eta is (MacAdam 1981, eq. 8-11)::

        delta* = sum_k q_k (f_k - h_k x),   q_k = w_k g_k / sum_j w_j g_j^2,
        g_k = C int_0^{eta_k} e^(A s) ds B  (the step response),   h_k = C e^(A eta_k)

    at the preview instants eta_k with quadrature weights w_k (times the weighting W).

    Parameters
    ----------
    A, B, C : array_like
        (n, n), (n, 1), (1, n).
    times : array_like
        eta_k [s] > 0.
    weights : array_like, optional
        w_k (default: ones).

    Returns
    -------
    q : ndarray (n_k,)
        [rad/m].
    h : ndarray (n_k, n)
        Free-response rows.
    """
    from scipy.linalg import expm

    A, B, C = (np.atleast_2d(np.asarray(m, dtype=float)) for m in (A, B, C))
    times = np.asarray(times, dtype=float)
    weights = np.ones_like(times) if weights is None else np.asarray(weights, dtype=float)
    n = A.shape[0]
    block = np.zeros((n + 1, n + 1))
    block[:n, :n], block[:n, n:] = A, B
    g, h = np.empty(times.size), np.empty((times.size, n))
    for k, eta in enumerate(times):
        e = expm(block * eta)
        g[k] = (C @ e[:n, n:])[0, 0]
        h[k] = (C @ e[:n, :n])[0]
    q = weights * g / np.sum(weights * g**2)
    return q, h


class OptimalPreviewDriver(_PathDriver):
    """MacAdam's optimal preview driver: a linear internal model of the car, a preview window, a delay.

    The driver knows the car as a linear single-track model at the design ``speed`` (lateral
    velocity v, yaw rate r and, in the car's own frame, heading and lateral position; the steer
    is its input, not a state). It predicts the car's free motion over its own delay tau and
    chooses the steer c, held over the preview window [tau, tau + T_p], that minimizes the squared
    distance between the predicted lateral position and the path at the preview points
    (:func:`preview_gains`; Gauss-Legendre points, uniform weighting)::

        c = K sum_k q_k (e_k - h_k [v, r, 0, 0]),   e_k = path offset at u (tau + eta_k) ahead,
        h_k = C e^(A eta_k) e^(A tau)

    then applies it through the delay tau (Pade approximant) and the lag T_N as
    :class:`CrossoverDriver` does (the lag is not in the internal model). With K = 1 the command is the
    optimal one for the internal model; K scales it. C. C. MacAdam, "Application of an optimal
    preview control for simulation of closed-loop automobile driving", IEEE Trans. SMC 11(6),
    393-399, 1981 (the delay ahead of the preview window, eq. 12-16); "Understanding and modeling
    the human driver", Vehicle System Dynamics 40(1-3), 101-134, 2003.

    Parameters
    ----------
    path_x, path_y : array_like
        Desired CG path [m] (SAE earth axes).
    vehicle : Vehicle
        The car the driver knows: its :class:`~vehdyn.handling.LinearBicycle` (cornering
        stiffnesses of its tires) at ``speed`` is the internal model.
    speed : float
        Design speed of the internal model [m/s] > 0.
    preview_time : float
        T_p [s] (default 1.0).
    gain : float
        K [-] > 0 (default 1: the optimal command).
    delay, neuromuscular_lag, max_steer_angle, pade_order
        As :class:`CrossoverDriver`.
    minimum_preview_distance : float
        Lower bound of the preview distances [m] (default 0).
    n_preview : int
        Number of preview points (default 10).

    Signals
    -------
    Inputs (feedback): ``x``, ``y``, ``yaw_angle``, ``longitudinal_velocity``,
    ``lateral_velocity``, ``yaw_rate``; states and output as :class:`CrossoverDriver`.
    """

    feedback = ("x", "y", "yaw_angle", "longitudinal_velocity", "lateral_velocity", "yaw_rate")
    _gain_names = ("gain", "speed")

    def __init__(self, path_x, path_y, *, vehicle, speed: float, preview_time: float = 1.0, gain: float = 1.0,
                 delay: float = 0.15, neuromuscular_lag: float = 0.1, minimum_preview_distance: float = 0.0,
                 max_steer_angle: float = 0.6, pade_order: int = 3, n_preview: int = 10):
        from scipy.linalg import expm

        from vehdyn.handling.bicycle import LinearBicycle

        self._setup(path_x, path_y, delay=delay, neuromuscular_lag=neuromuscular_lag, preview_time=preview_time,
                    minimum_preview_distance=minimum_preview_distance, max_steer_angle=max_steer_angle,
                    pade_order=pade_order, gain=gain, speed=speed)
        if isinstance(n_preview, bool) or n_preview not in range(1, 101):
            raise ParameterError(f"n_preview must be an integer 1..100, got {n_preview!r}", key="n_preview",
                                 value=n_preview)
        bicycle = LinearBicycle(vehicle, self.speed)
        iv, ir = bicycle.index("lateral_velocity"), bicycle.index("yaw_rate")
        steer = bicycle.index("front_steer_angle", "inputs")
        # internal model in the car's frame: [v, r, psi, y], dpsi/dt = r, dy/dt = u psi + v
        A = np.zeros((4, 4))
        A[:2, :2] = bicycle.A[np.ix_([iv, ir], [iv, ir])]
        A[2, 1], A[3, 2], A[3, 0] = 1.0, self.speed, 1.0
        B = np.zeros((4, 1))
        B[:2, 0] = bicycle.B[[iv, ir], steer]
        nodes, weights = np.polynomial.legendre.leggauss(int(n_preview))
        self.preview_times = 0.5 * self.preview_time * (nodes + 1.0)
        q, h = preview_gains(A, B, np.array([[0.0, 0.0, 0.0, 1.0]]), self.preview_times, weights)
        h = h @ expm(A * self.delay)  # the free motion during the delay, then over the window
        self._q, self._h = q, np.column_stack([h[:, 0], h[:, 1], np.zeros(len(q))])
        self.n_preview = int(n_preview)

    def _distances(self, speed):
        return np.maximum(np.abs(speed) * (self.delay + self.preview_times), self.minimum_preview_distance)

    def command(self, t, s, steer):
        shape = (-1,) + (1,) * np.ndim(s["x"])
        distance = np.maximum(np.abs(s["longitudinal_velocity"]) * (self.delay + self.preview_times).reshape(shape),
                              self.minimum_preview_distance)
        offsets = preview_offsets(self.path_x, self.path_y, s["x"], s["y"], s["yaw_angle"], distance)
        h = [self._h[:, j].reshape(shape) for j in range(3)]
        free = h[0] * s["lateral_velocity"] + h[1] * s["yaw_rate"] + h[2] * steer
        return self.gain * np.sum(self._q.reshape(shape) * (offsets - free), axis=0)

    def perception(self, speed) -> dict:
        distance = self._distances(np.full(self.n_preview, float(speed)))
        k = self.gain * self._q
        return {"y": k.sum(), "yaw_angle": np.sum(k * distance), "lateral_velocity": np.sum(k * self._h[:, 0]),
                "yaw_rate": np.sum(k * self._h[:, 1])}
