"""MacAdam's optimal preview driver (C. C. MacAdam, IEEE Trans. SMC 11(6), 1981): preview gains from
the vehicle's linear model over a preview window."""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from vehdyn.driver.base import _PathDriver, heading_offsets, steer_rates
from vehdyn.errors import ParameterError

__all__ = ["OptimalPreviewDriver", "preview_gains", "optimal_preview_command"]

OptimalPreviewNumbers = namedtuple("OptimalPreviewNumbers", (
    "path_x", "path_y", "delay", "preview_times", "minimum_preview_distance", "gain", "q", "h_lateral_velocity",
    "h_yaw_rate", "max_steer_angle", "lag", "pade_a", "pade_b", "pade_c", "pade_d"))
OptimalPreviewNumbers.__doc__ = """The numbers of the :class:`OptimalPreviewDriver`'s law (SI): the path [m], tau [s],
the preview instants eta_k [s], d_min [m], K [-], the preview gains q_k [rad/m], the free-response
coefficients of v [s] and r [m*s/rad], delta_max [rad], T_N [s] and the delay's balanced Padé realization."""


def preview_gains(A, B, C, times, weights=None):
    r"""MacAdam's optimal preview gains for an internal model :math:`\dot x = A x + B\delta`, :math:`y = C x`.

    With the steer held constant over the preview window, the steer that minimizes
    :math:`J = \int_0^T W(\eta) [f(t + \eta) - y(t + \eta)]^2 d\eta` is (MacAdam 1981, eq. 8-11)

    .. math::

        \delta^* = \sum_k q_k (f_k - h_k x), \qquad q_k = \frac{w_k g_k}{\sum_j w_j g_j^2}, \qquad
        g_k = C \int_0^{\eta_k} e^{A s} ds\, B, \qquad h_k = C e^{A \eta_k}

    at the preview instants :math:`\eta_k` with quadrature weights :math:`w_k` (times the
    weighting :math:`W`): :math:`g_k` is the step response, :math:`h_k` the free response.

    Parameters
    ----------
    A, B, C : array_like
        The internal model's matrices, (n, n) [1/s], (n, 1) and (1, n) in the units of its
        states and output [-].
    times : array_like
        eta_k [s] > 0.
    weights : array_like, optional
        w_k [-] (default: ones).

    Returns
    -------
    q : ndarray (n_k,)
        The preview gains [rad/m].
    h : ndarray (n_k, n)
        Free-response rows [-].

    References
    ----------
    .. [1] C. C. MacAdam, "Application of an optimal preview control for simulation of closed-loop
       automobile driving", IEEE Trans. Systems, Man, and Cybernetics 11(6), 393-399, 1981, eq. 8-11.
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


def optimal_preview_command(p, x, y, yaw_angle, speed, lateral_velocity, yaw_rate):
    r"""MacAdam's command: the preview gains on the previewed offsets less the predicted free motion.

    .. math::

        \delta_c = K \sum_k q_k \left[e_k - (h_{v,k} v + h_{r,k} r)\right], \qquad
        e_k = e\!\left(\max(|u| (\tau + \eta_k), d_{min})\right)

    Parameters
    ----------
    p : OptimalPreviewNumbers
        The driver's numbers (:attr:`OptimalPreviewDriver.numbers`).
    x, y : float or ndarray
        Earth position of the CG [m].
    yaw_angle : float or ndarray
        Heading psi [rad].
    speed : float or ndarray
        Forward speed u [m/s].
    lateral_velocity : float or ndarray
        v [m/s].
    yaw_rate : float or ndarray
        r [rad/s].

    Returns
    -------
    float or ndarray
        delta_c [rad], before the delay and the lag.
    """
    total = 0.0
    cos_psi, sin_psi = np.cos(yaw_angle), np.sin(yaw_angle)
    for k in range(p.q.shape[0]):
        distance = np.maximum(np.abs(speed) * (p.delay + p.preview_times[k]), p.minimum_preview_distance)
        offset = heading_offsets(p.path_x, p.path_y, x, y, cos_psi, sin_psi, distance)
        free = p.h_lateral_velocity[k] * lateral_velocity + p.h_yaw_rate[k] * yaw_rate
        total = total + p.q[k] * (offset - free)
    return p.gain * total


def optimal_preview_driver_rhs(p, x, u, dxdt):
    """Rates of the optimal preview driver's delay and steer into ``dxdt``; ``u`` = (x, y, yaw_angle,
    longitudinal_velocity, lateral_velocity, yaw_rate)."""
    steer_rates(p, optimal_preview_command(p, u[0], u[1], u[2], u[3], u[4], u[5]), x, dxdt)


class OptimalPreviewDriver(_PathDriver):
    r"""MacAdam's optimal preview driver: a linear internal model of the car, a preview window, a delay.

    The driver knows the car as a linear single-track model at the design ``speed`` (lateral
    velocity :math:`v`, yaw rate :math:`r` and, in the car's own frame, heading and lateral
    position; the steer is its input, not a state). It predicts the car's free motion over its
    own delay :math:`\tau` and chooses the steer :math:`c`, held over the preview window
    :math:`[\tau, \tau + T_p]`, that minimizes the squared distance between the predicted lateral
    position and the path at the preview points (:func:`preview_gains`; Gauss-Legendre points,
    uniform weighting):

    .. math::

        c = K \sum_k q_k \left(e_k - h_k [v, r, 0, 0]^T\right), \qquad
        h_k = C e^{A \eta_k} e^{A \tau},

    :math:`e_k` the path offset at :math:`\max(u (\tau + \eta_k), d_{min})` ahead
    (:func:`optimal_preview_command`), then applies it through the delay :math:`\tau` (balanced
    Padé approximant) and the lag :math:`T_N` as :class:`CrossoverDriver` does (the lag is not in
    the internal model):

    .. math::

        \delta(s) = \frac{e^{-\tau s}}{T_N s + 1}\, c(s)

    With :math:`K = 1` the command is the optimal one for the internal model; :math:`K` scales it.

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
    delay : float
        tau [s] >= 0 (default 0.15).
    neuromuscular_lag : float
        T_N [s] > 0 (default 0.1).
    minimum_preview_distance : float
        Lower bound of the preview distances [m] (default 0).
    max_steer_angle : float
        delta_max [rad]: limit of the command (default 0.6).
    pade_order : int
        Order of the delay's Padé approximant, 1 to 10 (default 3).
    n_preview : int
        Number of preview points (default 10).

    Signals
    -------
    states
        ``driver_delay_1..n`` [-], ``driver_steer_angle`` [rad].
    inputs (feedback)
        ``x``, ``y``, ``yaw_angle``, ``longitudinal_velocity``, ``lateral_velocity``, ``yaw_rate``.
    outputs
        ``front_steer_angle`` [rad].

    References
    ----------
    .. [1] C. C. MacAdam, "Application of an optimal preview control for simulation of closed-loop
       automobile driving", IEEE Trans. Systems, Man, and Cybernetics 11(6), 393-399, 1981 (the
       preview gains, eq. 8-11; the delay ahead of the preview window, eq. 12-16).
    .. [2] C. C. MacAdam, "Understanding and modeling the human driver", Vehicle System Dynamics
       40(1-3), 101-134, 2003.
    """

    feedback = ("x", "y", "yaw_angle", "longitudinal_velocity", "lateral_velocity", "yaw_rate")
    _parameter_names = ("gain", "speed") + _PathDriver._parameter_names
    _law_rhs = staticmethod(optimal_preview_driver_rhs)

    def __init__(self, path_x, path_y, *, vehicle, speed: float, preview_time: float = 1.0, gain: float = 1.0,
                 delay: float = 0.15, neuromuscular_lag: float = 0.1, minimum_preview_distance: float = 0.0,
                 max_steer_angle: float = 0.6, pade_order: int = 3, n_preview: int = 10):
        from scipy.linalg import expm

        from vehdyn.handling.bicycle import LinearBicycle

        self._setup(path_x, path_y, delay=delay, lag=neuromuscular_lag, preview_time=preview_time,
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
        self.q = q  # q_k [rad/m]
        self.free_response = np.ascontiguousarray(h[:, :2])  # on v and r (psi and y are 0 in the car's frame)
        self.n_preview = int(n_preview)

    @property
    def numbers(self) -> OptimalPreviewNumbers:
        """The numbers of the law as an :data:`OptimalPreviewNumbers` (read from the attributes on every call)."""
        a, b, c, d = self._pade
        h = self.free_response
        return OptimalPreviewNumbers(self.path_x, self.path_y, self.delay, self.preview_times,
                                     self.minimum_preview_distance, self.gain, self.q,
                                     np.ascontiguousarray(h[:, 0]), np.ascontiguousarray(h[:, 1]),
                                     self.max_steer_angle, self.neuromuscular_lag, a, b, c, d)

    def perception(self, speed) -> dict:
        r"""The linear command law about straight running on a straight path at y = 0.

        :math:`\delta_c = -K \sum_k q_k (y + d_k \psi + h_{v,k} v + h_{r,k} r)` with
        :math:`d_k = \max(u (\tau + \eta_k), d_{min})` (used by
        :func:`~vehdyn.driver.driver_loop_margins`).

        Parameters
        ----------
        speed : float
            Forward speed u [m/s].

        Returns
        -------
        dict
            Gains on ``y`` [rad/m], ``yaw_angle`` [-], ``lateral_velocity`` [rad*s/m] and
            ``yaw_rate`` [s] such that delta_c = -sum k * signal.
        """
        distance = np.maximum(np.abs(float(speed)) * (self.delay + self.preview_times), self.minimum_preview_distance)
        k = self.gain * self.q
        return {"y": k.sum(), "yaw_angle": np.sum(k * distance), "lateral_velocity": np.sum(k * self.free_response[:, 0]),
                "yaw_rate": np.sum(k * self.free_response[:, 1])}

    def __repr__(self) -> str:
        return (f"<OptimalPreviewDriver at {self.speed:g} m/s: T_p = {self.preview_time:g} s, K = {self.gain:g}, "
                f"delay {self.delay:g} s, T_N = {self.neuromuscular_lag:g} s>")
