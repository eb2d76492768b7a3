"""Driver models: the preview driver, McRuer's crossover model, MacAdam's optimal preview driver.

Three drivers steer a vehicle model along a path:

* :class:`PreviewDriver` with :class:`DriverInTheLoop` (pure pursuit with a lag, below);
* :class:`CrossoverDriver` (McRuer) and :class:`OptimalPreviewDriver` (MacAdam 1981): controller
  :class:`~vehdyn.Model` objects with named parameters (gain, preview time, delay as a Pade
  approximant, neuromuscular lag) that close the loop through :class:`vehdyn.chassis.ClosedLoop`
  (``driver.close(plant)``; compiled with a :class:`~vehdyn.handling.SingleTrack`).

:func:`driver_loop` / :func:`driver_loop_margins` analyse the driver-vehicle loop with
python-control; :func:`lane_change_limit` finds the highest entry speed at which some tuning of a
driver sweep clears the cones of a lane change.

The preview driver (pure pursuit):

The driver looks ahead along the vehicle's heading by the preview distance d = max(u T_p, d_min)
(T_p the preview time), measures the lateral offset e of the desired path from that preview point
(in vehicle axes, SAE: positive when the path lies to the right) and steers the front wheels toward
it with the pure-pursuit law, through a first-order lag tau that stands for the driver's
neuromuscular and reaction delay::

    delta_c = K 2 L e / d^2,        tau d(delta)/dt = delta_c - delta

(Pure pursuit: R. C. Coulter, *Implementation of the Pure Pursuit Path Tracking Algorithm*,
CMU-RI-TR-92-01, 1992, eq. for the curvature 2 x / l^2; single-point preview with lag:
C. C. MacAdam, "Application of an optimal preview control for simulation of closed-loop automobile
driving", IEEE Trans. SMC 11(6), 1981, and Abe, *Vehicle Handling Dynamics*, 2009, sec. 8.2.) K is
a gain (1: pure geometry). Optionally the driver holds a target speed with a proportional law on
the driven axle's longitudinal force, F = m k_u (u_target - u).

:class:`DriverInTheLoop` closes the loop around any model that has the states ``x``, ``y``,
``yaw_angle`` and ``longitudinal_velocity`` (or takes the speed as constant) and a
``front_steer_angle`` input: the :class:`~vehdyn.handling.SingleTrack`, or a user's model.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.model import Model
from vehdyn.signals import Signal

__all__ = ["PreviewDriver", "DriverInTheLoop", "CrossoverDriver", "OptimalPreviewDriver", "pade_delay",
           "preview_gains", "preview_offsets", "driver_loop", "driver_loop_response", "driver_loop_margins",
           "DrivenVehicle", "lane_change_run", "lane_change_limit",
           "slip_angle_utilization"]


@dataclass(frozen=True)
class PreviewDriver:
    """Path-following driver with preview and lag (see the module docstring).

    Parameters
    ----------
    path_x, path_y : array_like
        Desired path of the CG in earth axes [m] (SAE: y to the right), x strictly increasing.
    preview_time : float
        T_p [s] (default 1.0 s).
    lag : float
        tau [s] (default 0.15 s).
    gain : float
        K [-] (default 1).
    minimum_preview_distance : float
        d_min [m] (default 3 m).
    target_speed : float, optional
        u_target [m/s] held with the driven axle's longitudinal force; None: no speed control.
    speed_gain : float
        k_u [1/s] (default 1).
    """

    path_x: np.ndarray
    path_y: np.ndarray
    preview_time: float = 1.0
    lag: float = 0.15
    gain: float = 1.0
    minimum_preview_distance: float = 3.0
    target_speed: float | None = None
    speed_gain: float = 1.0

    def __post_init__(self):
        px, py = _check_path(self.path_x, self.path_y)
        object.__setattr__(self, "path_x", px)
        object.__setattr__(self, "path_y", py)
        for name in ("preview_time", "lag", "gain", "minimum_preview_distance", "speed_gain"):
            value = getattr(self, name)
            if not (np.isfinite(value) and value > 0):
                raise ParameterError(f"PreviewDriver.{name} must be > 0, got {value!r}", key=name, value=value)
        if self.target_speed is not None and not np.isfinite(self.target_speed):
            raise ParameterError(f"target_speed must be finite, got {self.target_speed!r}", key="target_speed",
                                 value=self.target_speed)

    def steer_command(self, x, y, yaw_angle, speed, wheelbase):
        """delta_c [rad] for the vehicle at (x, y) [m] heading yaw_angle [rad] at ``speed`` [m/s]."""
        distance = np.maximum(np.abs(speed) * self.preview_time, self.minimum_preview_distance)
        offset = preview_offsets(self.path_x, self.path_y, x, y, yaw_angle, distance)
        return self.gain * 2.0 * wheelbase * offset / distance**2


class DriverInTheLoop(Model):
    """A vehicle model steered (and optionally speed-controlled) by a :class:`PreviewDriver`.

    Parameters
    ----------
    vehicle_model : Model
        Has states ``x``, ``y``, ``yaw_angle``, input ``front_steer_angle`` and, for speed control,
        state ``longitudinal_velocity`` and input ``rear_longitudinal_force``.
    driver : PreviewDriver
    wheelbase : float
        L [m] of the pure-pursuit law.
    mass : float, optional
        [kg], for the speed law (needed with ``driver.target_speed``).
    max_steer_angle : float
        The driver's steer command is limited to +- this [rad] (default 0.6).

    Signals
    -------
    The vehicle model's states plus ``driver_steer_angle`` [rad]; its inputs without
    ``front_steer_angle`` (and without ``rear_longitudinal_force`` under speed control); its
    outputs plus ``driver_steer_angle``.
    """

    def __init__(self, vehicle_model: Model, driver: PreviewDriver, *, wheelbase: float, mass: float | None = None,
                 max_steer_angle: float = 0.6):
        names = set(vehicle_model.state_names)
        missing = [n for n in ("x", "y", "yaw_angle") if n not in names]
        if missing or "front_steer_angle" not in vehicle_model.input_names:
            raise ParameterError(f"{type(vehicle_model).__name__} must have states x, y, yaw_angle and input "
                                 f"front_steer_angle for a driver (missing {missing or ['front_steer_angle']})",
                                 key="vehicle_model", value=type(vehicle_model).__name__)
        if not isinstance(driver, PreviewDriver):
            raise ParameterError(f"driver must be a PreviewDriver, got {type(driver).__name__}", key="driver",
                                 value=driver)
        self.speed_control = driver.target_speed is not None
        if self.speed_control and ("longitudinal_velocity" not in names or mass is None
                                   or "rear_longitudinal_force" not in vehicle_model.input_names):
            raise ParameterError("speed control needs a model with state longitudinal_velocity, input "
                                 "rear_longitudinal_force, and the mass", key="target_speed", value=driver.target_speed)
        for name, value in (("wheelbase", wheelbase), ("max_steer_angle", max_steer_angle)):
            if not (np.isfinite(value) and value > 0):
                raise ParameterError(f"{name} must be > 0, got {value!r}", key=name, value=value)
        self.vehicle_model, self.driver = vehicle_model, driver
        self.wheelbase, self.mass, self.max_steer_angle = float(wheelbase), mass, float(max_steer_angle)
        steer = Signal("driver_steer_angle", "rad", "front road-wheel steer angle applied by the driver")
        controlled = {"front_steer_angle"} | ({"rear_longitudinal_force"} if self.speed_control else set())
        self._passed = [k for k, n in enumerate(vehicle_model.input_names) if n not in controlled]
        self.declare(states=tuple(vehicle_model.states) + (steer,),
                     inputs=[vehicle_model.inputs[k] for k in self._passed],
                     outputs=tuple(vehicle_model.output_signals) + (steer,))
        self.phenomena = frozenset(vehicle_model.phenomena)
        vm = vehicle_model
        self._ix = {n: vm.index(n) for n in ("x", "y", "yaw_angle")}
        self._iu = vm.index("longitudinal_velocity") if "longitudinal_velocity" in names else None
        self._i_steer = vm.index("front_steer_angle", "inputs")
        self._i_force = vm.index("rear_longitudinal_force", "inputs") if self.speed_control else None

    def _vehicle_inputs(self, x, u):
        vm = self.vehicle_model
        xv, steer = x[:-1], x[-1]
        batch = np.shape(x)[1:]
        uv = np.zeros((vm.n_inputs,) + batch)
        if len(self._passed):
            uv[self._passed] = u
        uv[self._i_steer] = steer
        if self.speed_control:
            speed = xv[self._iu]
            uv[self._i_force] = self.mass * self.driver.speed_gain * (self.driver.target_speed - speed)
        return xv, uv

    def rhs(self, t, x, u):
        x = np.asarray(x, dtype=float)
        xv, uv = self._vehicle_inputs(x, np.asarray(u, dtype=float))
        speed = xv[self._iu] if self._iu is not None else self.driver.target_speed or 0.0
        command = self.driver.steer_command(xv[self._ix["x"]], xv[self._ix["y"]], xv[self._ix["yaw_angle"]], speed,
                                            self.wheelbase)
        command = np.clip(command, -self.max_steer_angle, self.max_steer_angle)
        steer_rate = (command - x[-1]) / self.driver.lag
        return np.concatenate([np.asarray(self.vehicle_model.rhs(t, xv, uv), dtype=float),
                               np.asarray(steer_rate, dtype=float)[None]])

    def output(self, t, x, u):
        x = np.asarray(x, dtype=float)
        xv, uv = self._vehicle_inputs(x, np.asarray(u, dtype=float))
        return np.concatenate([np.asarray(self.vehicle_model.output(t, xv, uv), dtype=float), x[-1:]])

    def compiled_rhs(self):
        """The loop compiled by numba (:mod:`vehdyn.handling._driver_in_the_loop_numba`) when the vehicle
        model has a compiled rhs and output, else None (see :meth:`vehdyn.Model.compiled_rhs`)."""
        from vehdyn.handling import _driver_in_the_loop_numba

        return _driver_in_the_loop_numba.compiled_model(self)


# ====================================================================== drivers as controllers
# The crossover-model driver (McRuer) and the optimal preview driver (MacAdam) are controller
# Models for vehdyn.chassis.ClosedLoop: their inputs are the plant's states they read (feedback),
# their one output ``front_steer_angle`` replaces the plant's input.

def pade_delay(delay: float, order: int):
    """State-space matrices (A, B, C, D) of the [n/n] Pade approximant of e^(-delay s).

    e^(-tau s) ~ N(s) / D(s), N(s) = sum_k (-1)^k c_k (tau s)^k, D(s) = sum_k c_k (tau s)^k,
    c_k = (2n - k)! n! / ((2n)! k! (n - k)!) (Baker & Graves-Morris, *Pade Approximants*, 1996;
    the same approximant as ``control.pade``), realized in controllable canonical form. A zero delay
    gives an empty realization (A 0x0, D = 1).
    """
    from math import factorial

    n = int(order)
    tau = float(delay)
    if tau == 0.0 or n == 0:
        return np.zeros((0, 0)), np.zeros((0, 1)), np.zeros((1, 0)), np.ones((1, 1))
    c = np.array([factorial(2 * n - k) * factorial(n) / (factorial(2 * n) * factorial(k) * factorial(n - k))
                  for k in range(n + 1)])
    scale = c * tau ** np.arange(n + 1)
    a = scale[:n] / scale[n]                                 # monic denominator s^n + sum a_k s^k
    b = (-1.0) ** np.arange(n + 1) * scale / scale[n]        # numerator, b_n = (-1)^n
    A = np.zeros((n, n))
    A[:-1, 1:] = np.eye(n - 1)
    A[-1] = -a
    B = np.zeros((n, 1))
    B[-1, 0] = 1.0
    C = (b[:n] - b[n] * a)[None, :]
    D = np.array([[b[n]]])
    return A, B, C, D


def preview_offsets(path_x, path_y, x, y, yaw_angle, distance):
    """Lateral offset [m] of the path from the point ``distance`` [m] ahead along the heading.

    In vehicle axes (SAE: positive when the path lies to the right of the preview point); the
    path is read at the preview point's earth x. Broadcasts over ``distance`` and the batch.
    """
    cos_psi, sin_psi = np.cos(yaw_angle), np.sin(yaw_angle)
    preview_x = x + distance * cos_psi
    preview_y = y + distance * sin_psi
    return (np.interp(preview_x, path_x, path_y) - preview_y) * cos_psi


def _check_path(path_x, path_y):
    px, py = np.asarray(path_x, dtype=float), np.asarray(path_y, dtype=float)
    if px.ndim != 1 or px.shape != py.shape or px.size < 2:
        raise ParameterError(f"path_x and path_y must be 1-D arrays of the same length >= 2, got {px.shape} and "
                             f"{py.shape}", key="path_x", value=px.shape)
    if not (np.all(np.isfinite(px)) and np.all(np.isfinite(py))) or np.any(np.diff(px) <= 0):
        raise ParameterError("path_x must be finite and strictly increasing (path_y finite)", key="path_x", value=px)
    return px, py


_FEEDBACK_UNITS = {"x": "m", "y": "m", "yaw_angle": "rad", "longitudinal_velocity": "m/s",
                   "lateral_velocity": "m/s", "yaw_rate": "rad/s"}


class _PathDriver(Model):
    """Base of the controller drivers: command -> delay (Pade) -> neuromuscular lag -> steer.

    ``tau_N d(delta)/dt = delta_d - delta`` with delta_d the command delayed by ``delay`` (a Pade
    approximant, states ``driver_delay_1..n``); the output ``front_steer_angle`` is the state
    ``driver_steer_angle``, so the driver's output never depends on its feedback at the same
    instant (the loop is not algebraic).
    """

    feedback = ("x", "y", "yaw_angle", "longitudinal_velocity")
    _gain_names: tuple = ()

    def _setup(self, path_x, path_y, *, delay, neuromuscular_lag, preview_time, minimum_preview_distance,
               max_steer_angle, pade_order, **gains):
        from vehdyn.chassis.closed_loop import check_gains

        self.path_x, self.path_y = _check_path(path_x, path_y)
        owner = type(self).__name__
        values = check_gains(owner, positive=("neuromuscular_lag", "preview_time", "max_steer_angle") + tuple(gains),
                             nonnegative=("delay", "minimum_preview_distance"), delay=delay,
                             neuromuscular_lag=neuromuscular_lag, preview_time=preview_time,
                             minimum_preview_distance=minimum_preview_distance, max_steer_angle=max_steer_angle,
                             **gains)
        if isinstance(pade_order, bool) or pade_order not in range(1, 11):
            raise ParameterError(f"{owner} pade_order must be an integer 1..10, got {pade_order!r}", key="pade_order",
                                 value=pade_order)
        for name, value in values.items():
            setattr(self, name, value)
        self.pade_order = int(pade_order)
        self._pade = pade_delay(self.delay, self.pade_order)
        n = self._pade[0].shape[0]
        states = tuple(Signal(f"driver_delay_{k + 1}", "-", f"Pade state {k + 1} of the driver's delay")
                       for k in range(n))
        self.declare(states=states + (Signal("driver_steer_angle", "rad", "road-wheel steer applied by the driver"),),
                     inputs=tuple(Signal(name, _FEEDBACK_UNITS[name], f"{name} of the vehicle (feedback)")
                                  for name in self.feedback),
                     outputs=(Signal("front_steer_angle", "rad", "front road-wheel steer commanded by the driver"),))

    def named_parameters(self) -> dict:
        """The driver's named parameters (SI)."""
        names = ("delay", "neuromuscular_lag", "preview_time", "minimum_preview_distance", "max_steer_angle")
        return {name: getattr(self, name) for name in self._gain_names + names} | {"pade_order": self.pade_order}

    def preview_distance(self, speed):
        """d = max(|u| T_p, d_min) [m]."""
        return np.maximum(np.abs(speed) * self.preview_time, self.minimum_preview_distance)

    def _feedback(self, u):
        return {name: u[k] for k, name in enumerate(self.feedback)}

    def command(self, t, signals, steer):
        """The driver's steer command [rad] (before delay and lag) from the feedback signals and the
        present road-wheel steer ``steer`` [rad] (the driver's own state)."""
        raise NotImplementedError

    def perception(self, speed) -> dict:
        """The linear command law about straight running on a straight path at y = 0.

        ``{signal: k}`` such that delta_c = -sum_k k * signal (the driver's gains on the vehicle's
        signals; used by :func:`driver_loop_margins`).
        """
        raise NotImplementedError

    def rhs(self, t, x, u):
        x = np.asarray(x, dtype=float)
        u = np.asarray(u, dtype=float)
        A, B, C, D = self._pade
        n = A.shape[0]
        z, steer = x[:n], x[n]
        command = np.clip(self.command(t, self._feedback(u), steer), -self.max_steer_angle, self.max_steer_angle)
        dz = np.tensordot(A, z, axes=1) + B[:, 0].reshape((n,) + (1,) * (x.ndim - 1)) * command
        delayed = np.tensordot(C[0], z, axes=1) + D[0, 0] * command
        return np.concatenate([dz, ((delayed - steer) / self.neuromuscular_lag)[None]])

    def output(self, t, x, u):
        x = np.asarray(x, dtype=float)
        return x[-1:].copy()

    def close(self, plant: Model):
        """The driver steering ``plant``: a :class:`vehdyn.chassis.ClosedLoop` (errors name the feedback
        the plant lacks) that also has a compiled rhs when the plant has one (:class:`DrivenVehicle`)."""
        return DrivenVehicle(plant, self)

    def _compiled_args(self):
        A, B, C, D = self._pade
        empty = np.zeros(0)
        times, q, h = (getattr(self, "preview_times", empty), getattr(self, "_q", empty),
                       getattr(self, "_h", np.zeros((0, 3))))
        return (1 if times.size else 0, self.path_x, self.path_y, self.gain, self.preview_time,
                self.minimum_preview_distance, self.max_steer_angle, np.ascontiguousarray(A), B[:, 0].copy(),
                C[0].copy(), float(D[0, 0]), self.neuromuscular_lag, np.ascontiguousarray(times),
                np.ascontiguousarray(q), np.ascontiguousarray(h[:, 0]), np.ascontiguousarray(h[:, 1]),
                np.ascontiguousarray(h[:, 2]), self.delay)


class CrossoverDriver(_PathDriver):
    """McRuer's crossover-model driver: a gain on the previewed path error, a delay, a neuromuscular lag.

    The driver reads the lateral offset e of the path from the point d = max(u T_p, d_min) ahead
    (:func:`preview_offsets`) and steers the front wheels through a pure delay tau and a
    first-order neuromuscular lag T_N::

        delta(s) = K_p e^(-tau s) / (T_N s + 1) e(s)

    The preview is the driver's lead equalization: to the lateral position y of a car (about a
    double integrator of the steer at low frequency, Y_c ~ K / s^2) the preview point adds
    d psi, a lead of time constant about d / u = T_p, so that near the crossover frequency omega_c
    the open loop takes McRuer's form Y_p Y_c ~ omega_c e^(-tau_e s) / s, tau_e ~ tau + T_N: phase
    margin pi/2 - omega_c tau_e, stable for omega_c tau_e < pi/2 (McRuer & Jex, "A review of
    quasi-linear pilot models", IEEE Trans. HFE 8(3), 1967; McRuer et al., "New results in driver
    steering control models", Human Factors 19(4), 1977). :meth:`tuned` sets K_p for a
    crossover frequency on a given car, as the human adapts (McRuer's adjustment rule).

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
        Pade approximant of order ``pade_order`` (default 3) in time-domain runs.
    neuromuscular_lag : float
        T_N [s] > 0 (default 0.1).
    minimum_preview_distance : float
        d_min [m] (default 3).
    max_steer_angle : float
        Limit of the command [rad] (default 0.6).

    Signals
    -------
    Inputs (feedback, read from the plant's states by ClosedLoop): ``x``, ``y``, ``yaw_angle``,
    ``longitudinal_velocity``. States: ``driver_delay_1..n``, ``driver_steer_angle``. Output:
    ``front_steer_angle``.
    """

    _gain_names = ("gain",)

    def __init__(self, path_x, path_y, *, gain: float, preview_time: float = 1.0, delay: float = 0.15,
                 neuromuscular_lag: float = 0.1, minimum_preview_distance: float = 3.0,
                 max_steer_angle: float = 0.6, pade_order: int = 3):
        self._setup(path_x, path_y, delay=delay, neuromuscular_lag=neuromuscular_lag, preview_time=preview_time,
                    minimum_preview_distance=minimum_preview_distance, max_steer_angle=max_steer_angle,
                    pade_order=pade_order, gain=gain)

    def command(self, t, s, steer):
        distance = self.preview_distance(s["longitudinal_velocity"])
        return self.gain * preview_offsets(self.path_x, self.path_y, s["x"], s["y"], s["yaw_angle"], distance)

    def perception(self, speed) -> dict:
        return {"y": self.gain, "yaw_angle": self.gain * float(self.preview_distance(speed))}

    @classmethod
    def tuned(cls, plant: Model, speed: float, path_x, path_y, *, crossover_frequency: float = 2.5, **options):
        """The driver whose open loop with ``plant`` at ``speed`` [m/s] crosses over at ``crossover_frequency`` [rad/s].

        K_p = 1 / |L_1(j omega_c)| with L_1 the loop at unit gain (McRuer's adjustment of the
        gain to the controlled element; the default 2.5 rad/s is within the 2-4 rad/s that
        McRuer et al. 1977 report for lane keeping). ``options`` are the other parameters.
        """
        from vehdyn.chassis.closed_loop import check_gains

        wc = check_gains(cls.__name__, positive=("crossover_frequency",),
                         crossover_frequency=crossover_frequency)["crossover_frequency"]
        unit = cls(path_x, path_y, gain=1.0, **options)
        loop = driver_loop_response(plant, unit, speed, np.array([wc]))
        return cls(path_x, path_y, gain=1.0 / abs(loop[0]), **options)


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


# ====================================================================== loop analysis
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
    """Open-loop frequency response L(j omega) of the driver-vehicle loop cut at the steer [-].

    L(s) = e^(-tau s) / (T_N s + 1) F (sI - A)^-1 B, with the exact delay, (A, B) the plant's
    linearization at straight running at ``speed`` [m/s] (front steer input) and F the driver's
    linear gains on the vehicle's signals (``driver.perception(speed)``); the loop is closed with
    negative feedback (delta = -L delta).
    """
    lin = _plant_steer_model(plant, speed)
    row = _perception_row(lin, driver, speed)
    b = lin.B[:, lin.index("front_steer_angle", "inputs")]
    omega = np.asarray(omega, dtype=float)
    matrices = 1j * omega[:, None, None] * np.eye(lin.n_states) - lin.A
    plant_part = np.linalg.solve(matrices, np.broadcast_to(b[:, None], (omega.size, b.size, 1)))[:, :, 0] @ row
    return plant_part * np.exp(-1j * omega * driver.delay) / (1j * omega * driver.neuromuscular_lag + 1.0)


def driver_loop(plant: Model, driver, speed: float, *, pade_order: int = 6):
    """The open loop L(s) as a ``control.StateSpace`` (delay as a Pade approximant of ``pade_order``).

    Input and output are the road-wheel steer [rad]: the car (its states that the steer reaches and
    that the driver sees; the position x and the speed drop out in straight running), the driver's
    gains, its delay and its lag in series. ``control.feedback(L, 1)`` is the closed loop.
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
    A[-1, :n] = Dp[0, 0] * rc / driver.neuromuscular_lag
    A[-1, n:n + m] = Cp[0] / driver.neuromuscular_lag
    A[-1, -1] = -1.0 / driver.neuromuscular_lag
    B = np.zeros((n + m + 1, 1))
    B[:n, 0] = bc
    C = np.zeros((1, n + m + 1))
    C[0, -1] = 1.0
    return control.ss(A, B, C, 0.0)


def driver_loop_margins(plant: Model, driver, speed: float, *, pade_order: int = 6) -> dict:
    """Gain and phase margins of the driver-vehicle loop at ``speed`` [m/s] (python-control).

    ``control.stability_margins`` of :func:`driver_loop` (the delay as a Pade approximant of
    ``pade_order``: at the default 6 its phase error is below 1e-8 rad up to omega tau = 1.6, so
    the margins are those of the exact delay) and ``stable`` from the poles of the closed loop
    ``control.feedback(L, 1)``. The margins are Nyquist's when the open loop has no poles in the
    right half-plane (the car below its critical speed); ``stable`` holds in any case.

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


# ====================================================================== compiled driver-vehicle loop
def _closed_loop_class():
    from vehdyn.chassis.closed_loop import ClosedLoop

    return ClosedLoop


class DrivenVehicle(_closed_loop_class()):
    """A :class:`vehdyn.chassis.ClosedLoop` of a vehicle model and a :class:`CrossoverDriver` or
    :class:`OptimalPreviewDriver` (made by ``driver.close(plant)``).

    Identical signals and numpy evaluation to ``ClosedLoop(plant, driver)``; in addition, when the
    plant has a compiled rhs (:class:`~vehdyn.handling.SingleTrack` with Magic Formula or linear
    tires), :meth:`compiled_rhs` composes it with the driver's law in numba, so that
    ``vehdyn.simulate(loop, t, ..., method="RK45")`` runs compiled (tens of times faster than numpy
    for one run).
    """

    def compiled_rhs(self):
        from vehdyn._compiled_ode import CompiledModel, compiled_copy, source_stamp

        plant = self.plant.compiled_rhs()
        if plant is None:
            return None
        from vehdyn.handling import _driver_numba

        key = f"driven_{plant.key}_{source_stamp(_driver_numba)}"
        cached = self.__dict__.get("_compiled")
        if cached is not None and cached.key == key:
            return cached
        rhs = compiled_copy(_driver_numba.driven_rhs, f"{key}_rhs", _plant_rhs=plant.rhs)
        p = self.plant
        index = tuple(p.index(n) for n in ("x", "y", "yaw_angle", "longitudinal_velocity", "lateral_velocity",
                                           "yaw_rate"))
        args = ((plant.args, p.n_states, p.index("front_steer_angle", "inputs")) + index
                + self.controller._compiled_args())
        self._compiled = CompiledModel(rhs, None, key, args)
        return self._compiled


# ====================================================================== the lane change that measures the car
def lane_change_run(model: Model, track, driver, speed: float, *, throttle: str = "hold", rtol: float = 1e-5):
    """One run of ``driver`` steering ``model`` through ``track`` from ``speed`` [m/s].

    The car starts on the path's first point in straight running. ``throttle="hold"``: the rear
    axle force balances the aerodynamic drag at the entry speed (the speed held, ISO 3888-1);
    ``"release"``: no drive force (coasting from the entry, the ISO 3888-2 procedure). Compiled
    when the model has a compiled rhs. Returns ``(result, outcome)`` with
    :func:`~vehdyn.handling.lane_change_outcome` plus ``spin_out_time``; ``passed`` is False on a
    spin (|sideslip| > 45 deg).
    """
    from vehdyn.simulate import simulate
    from vehdyn.handling.maneuvers import lane_change_outcome, spin_out_time

    if throttle not in ("hold", "release"):
        raise ParameterError(f"throttle must be 'hold' or 'release', got {throttle!r}", key="throttle", value=throttle)
    loop = driver.close(model)
    x_start, x_end = float(track.path_x[0]), float(track.path_x[-1])
    n = int(np.ceil((x_end - x_start) / 0.25)) + 1
    t = np.linspace(0.0, 1.15 * (x_end - x_start) / speed, n)
    x0 = np.concatenate([model.straight_running(speed, x=x_start), np.zeros(loop.n_states - model.n_states)])
    force = float(np.asarray(model.parameters.drag_factor)) * speed**2 if throttle == "hold" else 0.0
    result = simulate(loop, t, {"rear_longitudinal_force": force}, x0=x0, method="RK45", rtol=rtol, atol=1e-8)
    outcome = lane_change_outcome(track, result)
    outcome["spin_out_time"] = spin_out_time(result)
    outcome["passed"] = outcome["passed"] and outcome["spin_out_time"] is None
    return result, outcome


def slip_angle_utilization(model, result) -> dict:
    """``{axle: (largest |tan(slip angle)| over the peak-force one, first time [s] it passed 1 or None)}``.

    The peak-force slip angle is the tire law's at the static axle load (``model`` a SingleTrack).
    """
    out = {}
    for axle in ("front", "rear"):
        peak = float(np.asarray(model._peak_slip[axle][1]))
        ratio = np.abs(np.tan(np.asarray(result[f"{axle}_slip_angle"]))) / peak
        over = np.nonzero(ratio > 1.0)[0]
        out[axle] = (float(ratio.max()), float(result.time[over[0]]) if over.size else None)
    return out


def lane_change_limit(model: Model, track, make_driver, tunings, *, throttle: str = "hold",
                      speeds=(8.0, 40.0), resolution: float = 0.25) -> dict:
    """The highest entry speed [m/s] at which some driver tuning clears the cones (bisection on speed).

    At each trial speed the tunings are tried (the last one that passed first) until one passes;
    the speed is raised if one did, lowered if none did, until the bracket is ``resolution`` wide.
    So the speed found is the car's (within the drivers swept), not one tuning's; it assumes that
    what passes at a speed passes at lower ones.

    Parameters
    ----------
    model : SingleTrack
    track : DoubleLaneChangeTrack
    make_driver : callable
        ``make_driver(speed, **tuning)`` -> a driver (:class:`OptimalPreviewDriver`, ...).
    tunings : sequence of dict
        The driver parameters swept.
    throttle, speeds, resolution
        :func:`lane_change_run`'s throttle; the bracket [m/s]; its final width [m/s].

    Returns
    -------
    dict
        ``speed`` (highest passing, NaN if none passed at ``speeds[0]``; ``speeds[1]`` if that passed),
        ``tuning`` (the tuning that passed there), ``failing_speed`` (the lowest failing speed tried),
        ``passing`` (``(result, outcome)`` of the passing run) and ``failing`` (that of the run
        closest to passing at ``failing_speed``: the largest cone margin over the tunings), ``runs``
        (simulations made), and ``limiting_factor``: ``"tire saturation, front axle"`` / ``"... rear
        axle"`` (the axle whose slip angle first passed its peak-force one in that failing run or,
        failing that, in the passing run at the limit), else ``"driver"`` (the cones were hit with
        unsaturated tires: no tuning swept found a line through them).
    """
    tunings = list(tunings)
    if not tunings:
        raise ParameterError("tunings must not be empty", key="tunings", value=tunings)
    lo, hi = (float(s) for s in speeds)
    if not (0 < lo < hi) or not np.isfinite(hi):
        raise ParameterError(f"speeds must be 0 < low < high, finite, got {speeds!r}", key="speeds", value=speeds)
    order = list(range(len(tunings)))
    runs = 0

    def attempt(speed):
        nonlocal runs
        best_fail = None
        for i in list(order):
            result, outcome = lane_change_run(model, track, make_driver(speed, **tunings[i]), speed, throttle=throttle)
            runs += 1
            if outcome["passed"]:
                order.remove(i)
                order.insert(0, i)
                return i, (result, outcome)
            if best_fail is None or outcome["worst_margin"] > best_fail[2][1]["worst_margin"]:
                best_fail = (i, None, (result, outcome))
        return None, best_fail

    low_pass = attempt(lo)
    if low_pass[0] is None:
        return {"speed": np.nan, "tuning": None, "failing_speed": lo, "passing": None, "failing": low_pass[1][2],
                "runs": runs, "limiting_factor": _factor(model, low_pass[1][2][0])}
    passing, failing, failing_speed = low_pass, None, None
    high = attempt(hi)
    if high[0] is not None:
        return {"speed": hi, "tuning": tunings[high[0]], "failing_speed": np.nan, "passing": high[1], "failing": None,
                "runs": runs, "limiting_factor": "none within the bracket"}
    failing, failing_speed = high[1], hi
    while hi - lo > resolution:
        mid = 0.5 * (lo + hi)
        trial = attempt(mid)
        if trial[0] is not None:
            lo, passing = mid, trial
        else:
            hi, failing, failing_speed = mid, trial[1], mid
    return {"speed": lo, "tuning": tunings[passing[0]], "failing_speed": failing_speed, "passing": passing[1],
            "failing": failing[2], "runs": runs, "limiting_factor": _factor(model, failing[2][0], passing[1][0])}


def _factor(model, *results) -> str:
    """The axle that passed its peak-force slip angle first in the first of ``results`` where one did, else "driver"."""
    for result in results:
        first = [(time, axle) for axle, (_, time) in slip_angle_utilization(model, result).items() if time is not None]
        if first:
            return f"tire saturation, {min(first)[1]} axle"
    return "driver"
