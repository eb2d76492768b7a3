"""Nonlinear model-predictive path tracking (:class:`PathTrackingNMPC`): a receding-horizon steer controller."""

from __future__ import annotations

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.interconnect import Controller
from vehdyn.optimal.transcription import Problem
from vehdyn.params.checks import finite_number
from vehdyn.signals import Signal

__all__ = ["PathTrackingNMPC"]

# IPOPT from the previous solution's primal and dual point, with a small first barrier parameter (a warm start
# needs no centring) adapted on the way: 4 iterations per step instead of 7 on the benchmark's ISO 3888-1 loop
_WARM_START = {"max_iter": 200, "warm_start_init_point": "yes", "mu_init": 1e-3, "mu_strategy": "adaptive"}
_FEEDBACK = (("x", "m"), ("y", "m"), ("yaw_angle", "rad"), ("longitudinal_velocity", "m/s"),
             ("lateral_velocity", "m/s"), ("yaw_rate", "rad/s"))


class PathTrackingNMPC(Controller):
    r"""Receding-horizon steer control along a path, with a vehicle model inside (a controller Model).

    Every ``period`` the controller reads the vehicle's planar states, predicts ``horizon`` periods
    with ``model`` (its symbolic form: the same equations as its simulations) and solves

    .. math::

        \min_{\delta_0..\delta_{N-1}} \sum_{k=0}^{N-1} \left[ w_y (y_k - y^{\mathrm{ref}}_k)^2
        + w_\psi (\psi_k - \psi^{\mathrm{ref}}_k)^2 + w_{\dot\delta} \dot\delta_k^2 \right] \Delta t
        + w_N \left[ w_y (y_N - y^{\mathrm{ref}}_N)^2 + w_\psi (\psi_N - \psi^{\mathrm{ref}}_N)^2 \right]

    subject to the model, |delta| <= ``steer_limit`` and |d delta/dt| <= ``steer_rate_limit``, by
    direct multiple shooting and IPOPT, warm started from the previous solution (:class:`Problem`),
    with the Gauss-Newton Hessian of the cost in squares by default (the model's curvature left out
    of the Hessian: on the benchmark's loop the same 4 iterations, 1.8x less CPU time per step);
    the reference is the path at the points the car would reach at its present speed. The first
    steer is held until the next sample (zero-order hold). It samples the state at the first
    evaluation at or after each sampling instant: on ``simulate(..., method="rk4")`` with the
    loop's output grid at ``period`` that is the last Runge-Kutta stage of the step, x_k + h k_3,
    which differs from the step's result by O(h^2) -- a small measurement error. A run that starts
    again at an earlier time starts afresh (:meth:`reset`). It has no compiled
    form (it calls IPOPT): a :class:`~vehdyn.interconnect.ClosedLoop` with it runs on numpy.

    Parameters
    ----------
    model : Model
        The prediction model (a :class:`~vehdyn.handling.SingleTrack` with the states
        ``longitudinal_velocity``, ``lateral_velocity``, ``yaw_rate``, ``x``, ``y``, ``yaw_angle``
        and no others, e.g. ``SingleTrack(vehicle, tire_lag=False)``).
    path_x, path_y : array_like
        The path [m] (x increasing).
    horizon : int
        N, the prediction steps.
    period : float
        The sampling period and prediction step [s].
    inputs : mapping, optional
        The model's other inputs over the horizon (e.g. the rear axle force holding the speed).
    steer_limit, steer_rate_limit : float
        [rad], [rad/s].
    weights : mapping, optional
        ``lateral`` w_y [1/m^2/s], ``yaw`` w_psi [1/rad^2/s], ``steer_rate`` [s/rad^2], ``terminal``
        w_N [s]; defaults 1, 1, 0.01, 5.
    options : mapping, optional
        IPOPT options, over the defaults ``max_iter`` 200, ``warm_start_init_point`` "yes",
        ``mu_init`` 1e-3, ``mu_strategy`` "adaptive".
    hessian : {"gauss-newton", "exact", "limited-memory"}
        The Hessian IPOPT uses (:class:`Problem`): by default the Gauss-Newton one of the
        least-squares tracking cost.
    jit : bool
        Compile the program to C when it is built (:class:`Problem`; needs a C compiler).

    Attributes
    ----------
    log : list of tuple
        (time [s], steer [rad], solve time [s], iterations) of every solve.

    References
    ----------
    .. [1] J. B. Rawlings, D. Q. Mayne and M. M. Diehl, *Model Predictive Control: Theory, Computation,
       and Design*, 2nd ed., Nob Hill, 2017, ch. 1 and 8.
    .. [2] P. Falcone, F. Borrelli, J. Asgari, H. E. Tseng and D. Hrovat, "Predictive active steering
       control for autonomous vehicle systems", *IEEE Transactions on Control Systems Technology*
       15(3), 566-580, 2007.
    """

    def __init__(self, model, path_x, path_y, *, horizon: int = 40, period: float = 0.05, inputs=None,
                 steer_limit: float = 0.5, steer_rate_limit: float = 1.0, weights=None, options=None,
                 hessian: str = "gauss-newton", jit: bool = False):
        names = tuple(name for name, _ in _FEEDBACK)
        if sorted(model.state_names) != sorted(names):
            raise ParameterError(f"the prediction model must have the states {names}, got {model.state_names} (e.g. "
                                 "SingleTrack(vehicle, tire_lag=False))", key="model", value=model.state_names)
        self.path_x, self.path_y = np.asarray(path_x, dtype=float), np.asarray(path_y, dtype=float)
        if self.path_x.ndim != 1 or self.path_x.shape != self.path_y.shape or np.any(np.diff(self.path_x) <= 0):
            raise ParameterError("path_x and path_y must be 1-D of one length, path_x increasing", key="path_x",
                                 value=self.path_x.shape)
        self.period = finite_number(period, "period", positive=True)
        self.model = model
        w = {"lateral": 1.0, "yaw": 1.0, "steer_rate": 0.01, "terminal": 5.0, **(weights or {})}
        for key, value in w.items():
            finite_number(value, f"weights[{key!r}]", minimum=0.0)
        problem = Problem(model, horizon, controls=["front_steer_angle"], duration=horizon * self.period,
                          inputs=inputs, expand=True, hessian=hessian, jit=jit)
        self._y_ref = problem.parameter("y_ref", horizon + 1)
        self._yaw_ref = problem.parameter("yaw_ref", horizon + 1)

        def tracking(s, k, scale=1.0):  # the residuals whose squares are the tracking cost
            return [np.sqrt(scale * w["lateral"]) * (s["y"] - self._y_ref[k]),
                    np.sqrt(scale * w["yaw"]) * (s["yaw_angle"] - self._yaw_ref[k])]

        problem.bound("front_steer_angle", -steer_limit, steer_limit)
        problem.bound("front_steer_angle_rate", -steer_rate_limit, steer_rate_limit)
        rate_weight = np.sqrt(w["steer_rate"])
        problem.minimize(final=lambda s, k: tracking(s, k, w["terminal"]),
                         integral=lambda s, k: tracking(s, k) + [rate_weight * s["front_steer_angle_rate"]],
                         squares=True)
        self.problem, self.options = problem, {**_WARM_START, **(options or {})}
        self.log, self._last, self._next_sample, self._steer = [], None, 0.0, 0.0
        self.declare(inputs=tuple(Signal(n, unit, f"{n} of the vehicle (feedback)") for n, unit in _FEEDBACK),
                     outputs=(Signal("front_steer_angle", "rad", "front road-wheel steer commanded by the NMPC"),))

    def reset(self):
        """Forget the previous solves (a new run)."""
        self.log, self._last, self._next_sample, self._steer = [], None, 0.0, 0.0

    def command(self, t: float, feedback) -> float:
        """Solve at time ``t`` from the vehicle's states and return the first steer [rad].

        Parameters
        ----------
        t : float
            Time [s].
        feedback : array_like
            The controller's inputs (``x``, ``y``, ``yaw_angle``, ``longitudinal_velocity``,
            ``lateral_velocity``, ``yaw_rate``) [m, m, rad, m/s, m/s, rad/s].

        Returns
        -------
        float
            The steer to hold until the next sample [rad].
        """
        values = dict(zip(self.input_names, np.asarray(feedback, dtype=float)))
        x0 = self.model.state_vector(values)
        times = self.problem.grid
        ahead = values["x"] + values["longitudinal_velocity"] * np.cos(values["yaw_angle"]) * times
        y_ref = np.interp(ahead, self.path_x, self.path_y)
        slope = np.interp(ahead, self.path_x, np.gradient(self.path_y, self.path_x))
        solution = self.problem.solve(x0, u0=[self._steer], guess=self._last,
                                      parameters={"y_ref": y_ref, "yaw_ref": np.arctan(slope)}, options=self.options)
        self._last = solution
        self._steer = float(solution["front_steer_angle"][0])
        self.log.append((float(t), self._steer, solution.solve_time, solution.iterations))
        return self._steer

    def rhs(self, t, x, u):
        return np.zeros((0,) + np.shape(u)[1:])

    def output(self, t, x, u):
        u = np.asarray(u, dtype=float)
        if u.ndim > 1:  # outputs of a finished run: the commands held, from the log
            times = np.array([entry[0] for entry in self.log] or [0.0])
            steers = np.array([entry[1] for entry in self.log] or [0.0])
            k = np.clip(np.searchsorted(times, np.broadcast_to(np.asarray(t, float), u.shape[1:]), "right") - 1, 0,
                        None)
            return steers[k][None]
        if self.log and t < self.log[-1][0] - self.period:  # time ran back: a new run
            self.reset()
        if t >= self._next_sample - 1e-9 * self.period:
            self.command(t, u)
            self._next_sample = (np.floor(t / self.period + 1e-9) + 1.0) * self.period
        return np.array([self._steer])
