r"""The preview driver: pure pursuit with a lag (Coulter 1992; MacAdam 1981), optional speed control.

The driver looks ahead along the vehicle's heading by the preview distance
:math:`d = \max(|u| T_p, d_{min})`, measures the lateral offset :math:`e` of the desired path from
that preview point (:func:`~vehdyn.driver.preview_offsets`) and steers the front wheels toward it
with the pure-pursuit law, through a first-order lag :math:`\tau` that stands for the driver's
neuromuscular and reaction delay; optionally it holds a target speed with a proportional law on
the rear axle's longitudinal force (:class:`PreviewDriver`).
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from vehdyn.driver.base import _PathDriver, preview_offsets, steer_output, steer_rates
from vehdyn.errors import ParameterError
from vehdyn.signals import Signal

__all__ = ["PreviewDriver", "pure_pursuit_command", "speed_control_force"]

PreviewNumbers = namedtuple("PreviewNumbers", (
    "path_x", "path_y", "preview_time", "minimum_preview_distance", "gain", "wheelbase", "target_speed",
    "speed_gain", "mass", "max_steer_angle", "lag", "pade_a", "pade_b", "pade_c", "pade_d"))
PreviewNumbers.__doc__ = """The numbers of the :class:`PreviewDriver`'s law (SI): the path [m], T_p [s], d_min [m],
K [-], L [m], u_target [m/s] (0 without speed control), k_u [1/s], m [kg] (0 without speed control),
delta_max [rad], tau [s] and the empty delay (A 0x0, B, C empty, D = 1)."""


def pure_pursuit_command(p, x, y, yaw_angle, speed):
    r"""The pure-pursuit steer command :math:`\delta_c = K\, 2 L e / d^2`.

    .. math::

        d = \max(|u| T_p, d_{min}), \qquad \delta_c = K \frac{2 L\, e}{d^2}

    with :math:`e` the previewed offset (:func:`~vehdyn.driver.preview_offsets`): the curvature
    :math:`2 e / d^2` of the circular arc through the preview point (Coulter 1992) times the
    wheelbase (the kinematic steer of that curvature).

    Parameters
    ----------
    p : PreviewNumbers
        The driver's numbers (:attr:`PreviewDriver.numbers`).
    x, y : float or ndarray
        Earth position of the CG [m].
    yaw_angle : float or ndarray
        Heading psi [rad].
    speed : float or ndarray
        Forward speed u [m/s].

    Returns
    -------
    float or ndarray
        delta_c [rad] (before the limit and the lag).
    """
    distance = np.maximum(np.abs(speed) * p.preview_time, p.minimum_preview_distance)
    offset = preview_offsets(p.path_x, p.path_y, x, y, yaw_angle, distance)
    return p.gain * 2.0 * p.wheelbase * offset / distance**2


def speed_control_force(p, speed):
    r"""The speed law's rear axle force :math:`F = m k_u (u_{target} - u)`.

    Parameters
    ----------
    p : PreviewNumbers
        The driver's numbers (:attr:`PreviewDriver.numbers`).
    speed : float or ndarray
        Forward speed u [m/s].

    Returns
    -------
    float or ndarray
        F [N].
    """
    return p.mass * p.speed_gain * (p.target_speed - speed)


def preview_driver_rhs(p, x, u, dxdt):
    """Rates of the preview driver's steer (the lag) into ``dxdt``; ``u`` = (x, y, yaw_angle, longitudinal_velocity)."""
    steer_rates(p, pure_pursuit_command(p, u[0], u[1], u[2], u[3]), x, dxdt)


def preview_driver_output(p, x, u, y):
    """The preview driver's outputs into ``y``: the steer and, with speed control, the rear axle force."""
    steer_output(p, x, u, y)
    if y.shape[0] > 1:
        y[1] = speed_control_force(p, u[3])


class PreviewDriver(_PathDriver):
    r"""Path-following driver: pure pursuit with preview and lag, optionally holding a speed.

    The driver looks ahead along the heading by :math:`d`, measures the path's offset :math:`e`
    from the preview point and steers the front wheels with the pure-pursuit law through a
    first-order lag :math:`\tau` (the neuromuscular and reaction delay); with ``target_speed`` it
    also commands the rear axle's longitudinal force:

    .. math::

        d &= \max(|u| T_p, d_{min}), \qquad
        \delta_c = K \frac{2 L e}{d^2}, \qquad
        \tau \dot\delta = \min(\max(\delta_c, -\delta_{max}), \delta_{max}) - \delta, \\
        F_{x,r} &= m k_u (u_{target} - u)

    The steer applied, :math:`\delta`, is the driver's state; the force depends on the plant's
    state :math:`u` only (not an algebraic loop). :math:`K = 1` is pure geometry.

    Parameters
    ----------
    path_x, path_y : array_like
        Desired path of the CG in earth axes [m] (SAE: y to the right), x strictly increasing.
    wheelbase : float
        L [m] of the pure-pursuit law (the vehicle's ``geometry.wheelbase``).
    preview_time : float
        T_p [s] (default 1.0 s).
    lag : float
        tau [s] (default 0.15 s).
    gain : float
        K [-] (default 1).
    minimum_preview_distance : float
        d_min [m] (default 3 m).
    target_speed : float, optional
        u_target [m/s] held with the rear axle's longitudinal force; None (default): no speed
        control.
    speed_gain : float
        k_u [1/s] (default 1).
    mass : float, optional
        m [kg] of the speed law (the vehicle's ``mass.mass``); needed with ``target_speed``.
    max_steer_angle : float
        delta_max [rad]: the command is limited to +- this (default 0.6).

    Signals
    -------
    states
        ``driver_steer_angle`` [rad]: the road-wheel steer the driver applies.
    inputs (feedback, read from the plant's states)
        ``x``, ``y``, ``yaw_angle``, ``longitudinal_velocity``.
    outputs
        ``front_steer_angle`` [rad] and, with ``target_speed``, ``rear_longitudinal_force`` [N].

    References
    ----------
    .. [1] R. C. Coulter, *Implementation of the Pure Pursuit Path Tracking Algorithm*, Carnegie
       Mellon University, CMU-RI-TR-92-01, 1992 (the curvature 2 x / l^2 of the arc through the
       goal point).
    .. [2] C. C. MacAdam, "Application of an optimal preview control for simulation of closed-loop
       automobile driving", IEEE Trans. Systems, Man, and Cybernetics 11(6), 393-399, 1981
       (single-point preview with a lag).
    .. [3] M. Abe, *Vehicle Handling Dynamics*, 2nd ed., Butterworth-Heinemann, 2015, sec. 8.2
       (the driver's first-order preview model).

    Examples
    --------
    >>> import numpy as np
    >>> import vehdyn
    >>> from vehdyn.driver import PreviewDriver
    >>> from vehdyn.handling import SingleTrack
    >>> car = vehdyn.load_vehicle("sedan")
    >>> path_x = np.linspace(-10.0, 200.0, 50)
    >>> driver = PreviewDriver(path_x, np.full_like(path_x, 1.0), wheelbase=car.geometry.wheelbase,
    ...                        target_speed=15.0, mass=car.mass.mass)
    >>> loop = driver.close(SingleTrack(car))
    >>> loop.output_names[-2:]
    ('front_steer_angle_after_preview_driver', 'rear_longitudinal_force_after_preview_driver')
    """

    _lag_name = "lag"
    _parameter_names = ("gain", "lag", "preview_time", "minimum_preview_distance", "max_steer_angle", "wheelbase",
                        "target_speed", "speed_gain", "mass")
    _law_rhs = staticmethod(preview_driver_rhs)
    _law_output = staticmethod(preview_driver_output)

    def __init__(self, path_x, path_y, *, wheelbase: float, preview_time: float = 1.0, lag: float = 0.15,
                 gain: float = 1.0, minimum_preview_distance: float = 3.0, target_speed: float | None = None,
                 speed_gain: float = 1.0, mass: float | None = None, max_steer_angle: float = 0.6):
        from vehdyn.params.checks import check_gains

        outputs = (Signal("front_steer_angle", "rad", "front road-wheel steer commanded by the driver"),)
        if target_speed is not None:
            if mass is None:
                raise ParameterError("PreviewDriver speed control (target_speed) needs the vehicle's mass [kg]",
                                     key="mass", value=mass)
            speed = check_gains("PreviewDriver", target_speed=target_speed, speed_gain=speed_gain, mass=mass,
                                positive=("speed_gain", "mass"))
            outputs += (Signal("rear_longitudinal_force", "N", "rear axle force commanded by the driver's speed law"),)
        else:
            speed = check_gains("PreviewDriver", speed_gain=speed_gain, positive=("speed_gain",)) | {
                "target_speed": None, "mass": None if mass is None else float(mass)}
        self._setup(path_x, path_y, delay=0.0, lag=lag, preview_time=preview_time,
                    minimum_preview_distance=minimum_preview_distance, max_steer_angle=max_steer_angle, pade_order=1,
                    outputs=outputs, gain=gain, wheelbase=wheelbase)
        if self.minimum_preview_distance <= 0:
            raise ParameterError(f"PreviewDriver minimum_preview_distance must be > 0 (the law divides by d^2), got "
                                 f"{minimum_preview_distance!r}", key="minimum_preview_distance",
                                 value=minimum_preview_distance)
        self.__dict__.update(speed)

    @property
    def numbers(self) -> PreviewNumbers:
        """The numbers of the law as a :data:`PreviewNumbers` (read from the attributes on every call)."""
        a, b, c, d = self._pade
        return PreviewNumbers(self.path_x, self.path_y, self.preview_time, self.minimum_preview_distance, self.gain,
                              self.wheelbase, 0.0 if self.target_speed is None else self.target_speed,
                              self.speed_gain, 0.0 if self.target_speed is None else self.mass, self.max_steer_angle,
                              self.lag, a, b, c, d)

    def perception(self, speed) -> dict:
        r"""The linear command law about straight running on a straight path at y = 0.

        :math:`\delta_c = -K (2L/d^2) (y + d \psi)`, so the gains are :math:`2KL/d^2` on
        :math:`y` and :math:`2KL/d` on :math:`\psi` (used by :func:`~vehdyn.driver.driver_loop_margins`).

        Parameters
        ----------
        speed : float
            Forward speed u [m/s].

        Returns
        -------
        dict
            ``{"y": [rad/m], "yaw_angle": [rad/rad]}`` such that delta_c = -sum k * signal.
        """
        d = float(self.preview_distance(speed))
        k = self.gain * 2.0 * self.wheelbase / d**2
        return {"y": k, "yaw_angle": k * d}

    def __repr__(self) -> str:
        speed = "" if self.target_speed is None else f", holding {self.target_speed:g} m/s"
        return f"<PreviewDriver T_p = {self.preview_time:g} s, lag {self.lag:g} s, K = {self.gain:g}{speed}>"
