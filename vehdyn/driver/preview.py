"""The preview driver: pure pursuit with a lag (Coulter 1992; MacAdam 1981).

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
from vehdyn.model import Model
from vehdyn.errors import ParameterError
from vehdyn.signals import Signal
from vehdyn.driver.base import _check_path
from dataclasses import dataclass
import numpy as np
from vehdyn.driver.base import preview_offsets

__all__ = ["PreviewDriver", "DriverInTheLoop"]


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
        """The loop compiled by numba (:mod:`vehdyn.driver._driver_in_the_loop_numba`) when the vehicle
        model has a compiled rhs and output, else None (see :meth:`vehdyn.Model.compiled_rhs`)."""
        from vehdyn.driver import _driver_in_the_loop_numba

        return _driver_in_the_loop_numba.compiled_model(self)
