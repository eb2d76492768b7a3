"""What the driver models share: the path and its preview, the controller drivers' base class
(command -> delay -> neuromuscular lag -> steer) and their loop with a vehicle.

The preview: the driver looks ahead along the vehicle's heading by the preview distance
d = max(u T_p, d_min) (T_p the preview time) and measures the lateral offset e of the desired path
from that preview point, in vehicle axes (SAE: positive when the path lies to the right)
(:func:`preview_offsets`).
"""

from __future__ import annotations


import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.interconnect import ClosedLoop
from vehdyn.model import Model
from vehdyn.signals import Signal

__all__ = ["preview_offsets", "DrivenVehicle"]


# ====================================================================== drivers as controllers
# The crossover-model driver (McRuer) and the optimal preview driver (MacAdam) are controller
# Models for vehdyn.interconnect.ClosedLoop: their inputs are the plant's states they read (feedback),
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
        from vehdyn.params.checks import check_gains

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
        """The driver steering ``plant``: a :class:`vehdyn.interconnect.ClosedLoop` (errors name the feedback
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


# ====================================================================== loop analysis


# ====================================================================== compiled driver-vehicle loop
class DrivenVehicle(ClosedLoop):
    """A :class:`vehdyn.interconnect.ClosedLoop` of a vehicle model and a :class:`CrossoverDriver` or
    :class:`OptimalPreviewDriver` (made by ``driver.close(plant)``).

    Identical signals and numpy evaluation to ``ClosedLoop(plant, driver)``; in addition, when the
    plant has a compiled rhs (:class:`~vehdyn.handling.SingleTrack` with Magic Formula or linear
    tires), :meth:`compiled_rhs` composes it with the driver's law in numba, so that
    ``vehdyn.simulate(loop, t, ..., method="RK45")`` runs compiled (tens of times faster than numpy
    for one run).
    """

    def compiled_rhs(self):
        from vehdyn.simulation.compiled import CompiledModel, compiled_copy, source_stamp

        plant = self.plant.compiled_rhs()
        if plant is None:
            return None
        from vehdyn.driver import _driver_numba

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


