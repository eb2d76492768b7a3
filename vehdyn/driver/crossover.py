"""McRuer's crossover-model driver: a gain on the previewed path error, a delay, a neuromuscular lag."""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from vehdyn.driver.base import _PathDriver, preview_offsets, steer_rates
from vehdyn.driver.loop_analysis import driver_loop_response
from vehdyn.model import Model

__all__ = ["CrossoverDriver", "crossover_command"]

CrossoverNumbers = namedtuple("CrossoverNumbers", (
    "path_x", "path_y", "preview_time", "minimum_preview_distance", "gain", "max_steer_angle", "lag", "pade_a",
    "pade_b", "pade_c", "pade_d"))
CrossoverNumbers.__doc__ = """The numbers of the :class:`CrossoverDriver`'s law (SI): the path [m], T_p [s], d_min [m],
K_p [rad/m], delta_max [rad], T_N [s] and the delay's balanced Padé realization (A, B, C, D)."""


def crossover_command(p, x, y, yaw_angle, speed):
    r"""The crossover driver's command :math:`\delta_c = K_p e`, before the delay and the lag.

    .. math::

        d = \max(|u| T_p, d_{min}), \qquad \delta_c = K_p\, e(d)

    Parameters
    ----------
    p : CrossoverNumbers
        The driver's numbers (:attr:`CrossoverDriver.numbers`).
    x, y : float or ndarray
        Earth position of the CG [m].
    yaw_angle : float or ndarray
        Heading psi [rad].
    speed : float or ndarray
        Forward speed u [m/s].

    Returns
    -------
    float or ndarray
        delta_c [rad].
    """
    distance = np.maximum(np.abs(speed) * p.preview_time, p.minimum_preview_distance)
    return p.gain * preview_offsets(p.path_x, p.path_y, x, y, yaw_angle, distance)


def crossover_driver_rhs(p, x, u, dxdt):
    """Rates of the crossover driver's delay and steer into ``dxdt``; ``u`` = (x, y, yaw_angle, longitudinal_velocity)."""
    steer_rates(p, crossover_command(p, u[0], u[1], u[2], u[3]), x, dxdt)


class CrossoverDriver(_PathDriver):
    r"""McRuer's crossover-model driver: a gain on the previewed path error, a delay, a neuromuscular lag.

    The driver reads the lateral offset :math:`e` of the path from the point
    :math:`d = \max(|u| T_p, d_{min})` ahead (:func:`~vehdyn.driver.preview_offsets`) and steers the
    front wheels through a pure delay :math:`\tau` and a first-order neuromuscular lag :math:`T_N`:

    .. math::

        \delta(s) = \frac{K_p e^{-\tau s}}{T_N s + 1}\, e(s)

    (in the time domain the delay is the balanced Padé approximant of order ``pade_order``,
    :func:`vehdyn.interconnect.pade_delay`, and the command is limited to :math:`\pm\delta_{max}`
    ahead of it). The preview is the driver's lead equalization: to the lateral position
    :math:`y` of a car (about a double integrator of the steer at low frequency,
    :math:`Y_c \approx K / s^2`) the preview point adds :math:`d \psi`, a lead of time constant
    about :math:`d / u = T_p`, so that near the crossover frequency :math:`\omega_c` the open loop
    takes McRuer's form

    .. math::

        Y_p Y_c \approx \frac{\omega_c e^{-\tau_e s}}{s}, \qquad \tau_e \approx \tau + T_N,

    phase margin :math:`\pi/2 - \omega_c \tau_e`, stable for :math:`\omega_c \tau_e < \pi/2`.
    :meth:`tuned` sets :math:`K_p` for a crossover frequency on a given car, as the human adapts
    (McRuer's adjustment rule).

    Parameters
    ----------
    path_x, path_y : array_like
        Desired CG path in earth axes [m] (SAE, y right), x strictly increasing.
    gain : float
        K_p [rad/m] > 0 (road-wheel steer per metre of previewed error).
    preview_time : float
        T_p [s] > 0 (default 1.0).
    delay : float
        tau [s] >= 0 (default 0.15; McRuer's effective delays are 0.1-0.3 s), through a
        Padé approximant of order ``pade_order`` in time-domain runs (0: no delay states).
    neuromuscular_lag : float
        T_N [s] > 0 (default 0.1).
    minimum_preview_distance : float
        d_min [m] (default 3).
    max_steer_angle : float
        delta_max [rad]: limit of the command (default 0.6).
    pade_order : int
        Order of the delay's Padé approximant, 1 to 10 (default 3).

    Signals
    -------
    states
        ``driver_delay_1..n`` [-] (the Padé states), ``driver_steer_angle`` [rad].
    inputs (feedback, read from the plant's states by ClosedLoop)
        ``x``, ``y``, ``yaw_angle``, ``longitudinal_velocity``.
    outputs
        ``front_steer_angle`` [rad].

    References
    ----------
    .. [1] D. T. McRuer and H. R. Jex, "A review of quasi-linear pilot models", IEEE Trans. Human
       Factors in Electronics 8(3), 231-249, 1967 (the crossover model, the adjustment rule).
    .. [2] D. T. McRuer, R. W. Allen, D. H. Weir and R. H. Klein, "New results in driver steering
       control models", Human Factors 19(4), 381-397, 1977 (crossover frequencies and delays of
       lane keeping).

    Examples
    --------
    >>> import numpy as np
    >>> import vehdyn
    >>> from vehdyn.driver import CrossoverDriver
    >>> from vehdyn.handling import SingleTrack
    >>> path_x = np.linspace(-10.0, 500.0, 100)
    >>> driver = CrossoverDriver(path_x, np.zeros_like(path_x), gain=0.03, delay=0.12)
    >>> driver.state_names
    ('driver_delay_1', 'driver_delay_2', 'driver_delay_3', 'driver_steer_angle')
    >>> loop = driver.close(SingleTrack(vehdyn.load_vehicle("sedan")))
    >>> loop.output_names[-1]
    'front_steer_angle_after_crossover_driver'
    """

    _parameter_names = ("gain",) + _PathDriver._parameter_names
    _law_rhs = staticmethod(crossover_driver_rhs)

    def __init__(self, path_x, path_y, *, gain: float, preview_time: float = 1.0, delay: float = 0.15,
                 neuromuscular_lag: float = 0.1, minimum_preview_distance: float = 3.0,
                 max_steer_angle: float = 0.6, pade_order: int = 3):
        self._setup(path_x, path_y, delay=delay, lag=neuromuscular_lag, preview_time=preview_time,
                    minimum_preview_distance=minimum_preview_distance, max_steer_angle=max_steer_angle,
                    pade_order=pade_order, gain=gain)

    @property
    def numbers(self) -> CrossoverNumbers:
        """The numbers of the law as a :data:`CrossoverNumbers` (read from the attributes on every call)."""
        a, b, c, d = self._pade
        return CrossoverNumbers(self.path_x, self.path_y, self.preview_time, self.minimum_preview_distance, self.gain,
                                self.max_steer_angle, self.neuromuscular_lag, a, b, c, d)

    def perception(self, speed) -> dict:
        r"""The linear command law about straight running on a straight path at y = 0.

        :math:`\delta_c = -K_p (y + d \psi)` (used by :func:`~vehdyn.driver.driver_loop_margins`).

        Parameters
        ----------
        speed : float
            Forward speed u [m/s].

        Returns
        -------
        dict
            ``{"y": K_p [rad/m], "yaw_angle": K_p d [rad/rad]}`` such that delta_c = -sum k * signal.
        """
        return {"y": self.gain, "yaw_angle": self.gain * float(self.preview_distance(speed))}

    @classmethod
    def tuned(cls, plant: Model, speed: float, path_x, path_y, *, crossover_frequency: float = 2.5, **options):
        r"""The driver whose open loop with ``plant`` at ``speed`` crosses over at ``crossover_frequency``.

        :math:`K_p = 1 / |L_1(j\omega_c)|` with :math:`L_1` the loop at unit gain
        (:func:`~vehdyn.driver.driver_loop_response`; McRuer's adjustment of the gain to the
        controlled element; the default 2.5 rad/s is within the 2-4 rad/s that McRuer et al.
        1977 report for lane keeping).

        Parameters
        ----------
        plant : Model
            The vehicle model, linearized at straight running (a SingleTrack-like model with
            ``straight_running(speed)``).
        speed : float
            Forward speed u [m/s].
        path_x, path_y : array_like
            Desired CG path [m], as for the constructor.
        crossover_frequency : float
            omega_c [rad/s] (default 2.5).
        **options
            The other parameters of the constructor (``delay``, ``neuromuscular_lag``, ...).

        Returns
        -------
        CrossoverDriver
            The driver with that gain.
        """
        from vehdyn.params.checks import check_gains

        wc = check_gains(cls.__name__, positive=("crossover_frequency",),
                         crossover_frequency=crossover_frequency)["crossover_frequency"]
        unit = cls(path_x, path_y, gain=1.0, **options)
        loop = driver_loop_response(plant, unit, speed, np.array([wc]))
        return cls(path_x, path_y, gain=1.0 / abs(loop[0]), **options)

    def __repr__(self) -> str:
        return (f"<CrossoverDriver K_p = {self.gain:g} rad/m, T_p = {self.preview_time:g} s, delay {self.delay:g} s, "
                f"T_N = {self.neuromuscular_lag:g} s>")
