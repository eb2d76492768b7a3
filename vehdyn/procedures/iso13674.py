"""On-centre handling: the weave test and its metrics (ISO 13674-1).

The weave test drives the vehicle straight at 100 km/h and turns the steering wheel sinusoidally
at 0.2 Hz with the amplitude that gives a peak lateral acceleration of 0.2 g (ISO 13674-1:2010,
*Road vehicles -- Test method for the quantification of on-centre handling -- Part 1: Weave
test*; the test and most metrics go back to D. J. Norman, "Objective evaluation of on-center
handling performance", SAE 840069, 1984). The metrics are read off the cross-plots of one steady
cycle, each branch (steering-wheel angle rising, falling) on its own; they are defined here as
follows (after ISO 13674-1, sec. 8, and Norman 1984; descriptions in this package's words):

* steering sensitivity at 0.1 g: slope of lateral acceleration against steering-wheel angle
  where |a_y| = 0.1 g, mean of both branches and both signs [(m/s^2)/rad] (also in the customary
  g per 100 deg);
* yaw-rate hysteresis: width, in steering-wheel angle, of the yaw-rate-against-angle loop at zero
  yaw rate [rad] (the lag of the yaw response seen as an angle);
* torque deadband: width, in steering-wheel angle, of the torque-against-angle loop at zero
  torque [rad];
* torque at 0 g: half the width, in steering-wheel torque, of the torque-against-lateral-
  acceleration loop at a_y = 0 [N*m] (friction and damping felt on centre);
* lateral acceleration at 0 torque: half the width of that loop, in a_y, at zero torque [m/s^2];
* torque gradient at 0 g and at 0.1 g: slope of steering-wheel torque against lateral
  acceleration at a_y = 0 and where |a_y| = 0.1 g, mean of both branches (and signs)
  [N*m/(m/s^2)] (the road feel on centre and off centre).

Slopes are least-squares lines through the samples of a branch within +-0.01 g of the level;
crossings are linear interpolations between samples.

The model is a vehicle steered through a :class:`~vehdyn.handling.SteeringSystem`
(:class:`~vehdyn.handling.SteeredVehicle`), by default the linear bicycle. Without friction and
power assist and with a rigid column, the steering sensitivity at low frequency is the bicycle's
steady lateral-acceleration gain over the steering ratio, and the torque gradient is the aligning
moment's: (t_m + t_p) m b / (L N) (the front axle carries m a_y b / L).
"""

from __future__ import annotations


from dataclasses import dataclass

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.model import Model
from vehdyn.procedures._sampling import at_samples, union_grid
from vehdyn.signals import Signal
from vehdyn.units import GRAVITY

__all__ = ["WeaveTestMetrics", "weave_test", "weave_metrics"]

_BAND = 0.01 * GRAVITY  # half-width of the fitting band [m/s^2]


@dataclass(frozen=True)
class WeaveTestMetrics:
    """The ISO 13674-1 weave-test metrics (definitions in :mod:`vehdyn.procedures.iso13674`).

    Attributes
    ----------
    speed : float
        [m/s].
    frequency : float
        [Hz].
    steering_wheel_amplitude : float
        Steering-wheel angle amplitude used [rad].
    peak_lateral_acceleration : float
        Peak |a_y| of the evaluated cycle [m/s^2].
    steering_sensitivity : float
        [(m/s^2)/rad] at 0.1 g.
    yaw_rate_hysteresis : float
        [rad] of steering-wheel angle.
    torque_deadband : float
        [rad] of steering-wheel angle.
    torque_at_zero_g : float
        [N*m].
    lateral_acceleration_at_zero_torque : float
        [m/s^2].
    torque_gradient_zero_g, torque_gradient_01g : float
        [N*m/(m/s^2)].
    result : SimulationResult
        The run; the metrics use its last cycle.
    """

    speed: float
    frequency: float
    steering_wheel_amplitude: float
    peak_lateral_acceleration: float
    steering_sensitivity: float
    yaw_rate_hysteresis: float
    torque_deadband: float
    torque_at_zero_g: float
    lateral_acceleration_at_zero_torque: float
    torque_gradient_zero_g: float
    torque_gradient_01g: float
    result: object

    @property
    def steering_sensitivity_g_per_100deg(self) -> float:
        """Steering sensitivity in g per 100 deg of steering-wheel angle."""
        return self.steering_sensitivity / GRAVITY * np.radians(100.0)

    @property
    def torque_gradient_zero_g_per_g(self) -> float:
        """Torque gradient at 0 g in N*m/g."""
        return self.torque_gradient_zero_g * GRAVITY

    @property
    def torque_gradient_01g_per_g(self) -> float:
        """Torque gradient at 0.1 g in N*m/g."""
        return self.torque_gradient_01g * GRAVITY


def _crossing(x, y, level=0.0) -> float:
    """y where x first crosses ``level`` on a branch (linear interpolation); NaN if it does not."""
    d = np.asarray(x, dtype=float) - level
    k = np.nonzero(np.signbit(d[:-1]) != np.signbit(d[1:]))[0]
    if k.size == 0:
        return float("nan")
    i = int(k[np.argmin(np.abs(k - d.size // 2))])  # the crossing nearest the branch's middle
    w = d[i] / (d[i] - d[i + 1])
    return float(y[i] + w * (y[i + 1] - y[i]))


def _slope(x, y, level, band) -> float:
    """Least-squares slope dy/dx of a branch's samples with |x - level| <= band (x: the band variable)."""
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    near = np.abs(x - level) <= band
    if np.count_nonzero(near) < 3:
        return float("nan")
    return float(np.polyfit(x[near], y[near], 1)[0])


#: The fewest samples per period the metrics are read from: the slopes are fitted to the samples
#: within +-0.01 g of a level, which a 0.2 g sine crosses in about 1.6 % of its period (three
#: samples at least need about 200 per period).
MIN_SAMPLES_PER_CYCLE = 200
#: The samples per period of the grid :func:`weave_test` reads its metrics from, whatever output
#: grid is asked for.
METRIC_SAMPLES_PER_CYCLE = 800


def weave_metrics(result, frequency: float, *, start: float | None = None) -> dict:
    """The weave metrics of one cycle of ``result`` (a run with ``steering_wheel_angle``,
    ``lateral_acceleration``, ``yaw_rate``, ``steering_wheel_torque``), from ``start`` (a trough of
    the steering-wheel angle) over one period; default the last whole period of the run.

    Parameters
    ----------
    result : SimulationResult
        The run, sampled at least :data:`MIN_SAMPLES_PER_CYCLE` times per period over the cycle.
    frequency : float
        Steer frequency [Hz], > 0.
    start : float, optional
        Start of the evaluated cycle [s], within the run a whole period before its end.

    Returns
    -------
    dict
        The fields of :class:`WeaveTestMetrics` but ``speed``, ``frequency``, the amplitude and ``result``.

    Raises
    ------
    ParameterError
        A result without the four signals, a cycle outside the run, or one sampled too coarsely for
        the slopes and crossings.
    """
    from vehdyn.params.checks import finite_number

    frequency = finite_number(frequency, "frequency", positive=True)
    needed = ("steering_wheel_angle", "lateral_acceleration", "yaw_rate", "steering_wheel_torque")
    if not (hasattr(result, "time") and all(name in result for name in needed)):
        raise ParameterError(f"result must be a SimulationResult with {', '.join(needed)}, got "
                             f"{type(result).__name__}", key="result", value=type(result).__name__)
    t = result.time
    period = 1.0 / frequency
    if start is None:
        start = t[-1] - period
    start = finite_number(start, "start")
    if start < t[0] - 1e-9 or start + period > t[-1] + 1e-9:
        raise ParameterError(f"start = {start!r} s: the cycle [{start:g}, {start + period:g}] s must lie within "
                             f"the run [{t[0]:g}, {t[-1]:g}] s", key="start", value=start)
    sel = (t >= start - 1e-9) & (t <= start + period + 1e-9)
    if np.count_nonzero(sel) < MIN_SAMPLES_PER_CYCLE:
        raise ParameterError(f"result has {np.count_nonzero(sel)} samples in the evaluated cycle: the weave metrics "
                             f"need at least {MIN_SAMPLES_PER_CYCLE} per period (their slopes are fitted within "
                             "+-0.01 g of a level)", key="result", value=int(np.count_nonzero(sel)))
    tt = t[sel]
    wheel, ay = result["steering_wheel_angle"][sel], result["lateral_acceleration"][sel]
    yaw, torque = result["yaw_rate"][sel], result["steering_wheel_torque"][sel]
    k_top = int(np.argmax(wheel))
    branches = [slice(0, k_top + 1), slice(k_top, tt.size)]  # angle rising, falling
    level = 0.1 * GRAVITY
    sens, grad0, grad1 = [], [], []
    at_zero = {"yaw": [], "torque_angle": [], "torque_g": [], "g_torque": []}
    for b in branches:
        w, a, r, m = wheel[b], ay[b], yaw[b], torque[b]
        for sign in (1.0, -1.0):
            # d a_y / d theta near a_y = +-0.1 g: fit theta against a_y and invert (a_y is the band variable)
            dtheta = _slope(a, w, sign * level, _BAND)
            sens.append(1.0 / dtheta if dtheta else float("nan"))
            grad1.append(_slope(a, m, sign * level, _BAND))
        grad0.append(_slope(a, m, 0.0, _BAND))
        at_zero["yaw"].append(_crossing(r, w))
        at_zero["torque_angle"].append(_crossing(m, w))
        at_zero["torque_g"].append(_crossing(a, m))
        at_zero["g_torque"].append(_crossing(m, a))
    return dict(
        peak_lateral_acceleration=float(np.max(np.abs(ay))),
        steering_sensitivity=float(np.nanmean(sens)),
        yaw_rate_hysteresis=float(abs(at_zero["yaw"][0] - at_zero["yaw"][1])),
        torque_deadband=float(abs(at_zero["torque_angle"][0] - at_zero["torque_angle"][1])),
        torque_at_zero_g=float(0.5 * abs(at_zero["torque_g"][0] - at_zero["torque_g"][1])),
        lateral_acceleration_at_zero_torque=float(0.5 * abs(at_zero["g_torque"][0] - at_zero["g_torque"][1])),
        torque_gradient_zero_g=float(np.nanmean(grad0)),
        torque_gradient_01g=float(np.nanmean(grad1)),
    )


class _SineDriven(Model):
    """``model`` with its input ``name`` driven by amplitude sin(omega t), made by two oscillator
    states (sine_phase, cosine_phase) so that the integrator sees a smooth input, exact at every stage
    (a sampled input would put a kink at every sample). The other inputs pass through; the outputs
    are the model's."""

    def __init__(self, model, name: str, amplitude: float, omega: float):
        self.model, self.amplitude, self.omega = model, float(amplitude), float(omega)
        self._j = model.index(name, "inputs")
        self._passed = [k for k in range(model.n_inputs) if k != self._j]
        self.declare(states=tuple(model.states) + (Signal("sine_phase", "-"), Signal("cosine_phase", "-")),
                     inputs=[model.inputs[k] for k in self._passed],
                     outputs=tuple(model.output_signals))
        self.phenomena = model.phenomena

    def initial_state(self, x0):
        return np.concatenate([np.asarray(x0, dtype=float), [0.0, 1.0]])

    def _inner(self, x, u):
        x, u = np.asarray(x, dtype=float), np.asarray(u, dtype=float)
        um = np.zeros((self.model.n_inputs,) + x.shape[1:])
        if self._passed:
            um[self._passed] = u
        um[self._j] = self.amplitude * x[-2]
        return x[:-2], um

    def rhs(self, t, x, u):
        xm, um = self._inner(x, u)
        return np.concatenate([np.asarray(self.model.rhs(t, xm, um), dtype=float),
                               np.stack([self.omega * x[-1], -self.omega * x[-2]])])

    def output(self, t, x, u):
        xm, um = self._inner(x, u)
        return self.model.output(t, xm, um)


def weave_test(vehicle, speed: float = 100 / 3.6, amplitude_g: float = 0.2, frequency: float = 0.2, *,
               vehicle_model=None, steering=None, cycles: int = 3, iterations: int = 3, samples_per_cycle: int = 800,
               method: str = "LSODA", rtol: float = 1e-7, **steering_overrides) -> WeaveTestMetrics:
    """The ISO 13674-1 weave test: a sinusoidal steering-wheel angle at ``frequency`` sized for a
    peak lateral acceleration of ``amplitude_g``, and its metrics (module docstring).

    Parameters
    ----------
    vehicle : Vehicle
    speed : float
        [m/s] (default 100 km/h).
    amplitude_g : float
        Target peak lateral acceleration [g] (default 0.2), in [0.11, 0.8]: the metrics at 0.1 g
        need the peak beyond their +-0.01 g band, and beyond 0.8 g the band holds fewer than three
        samples of the metric grid.
    frequency : float
        [Hz] (default 0.2).
    vehicle_model : Model, optional
        Default ``LinearBicycle(vehicle, speed)``; e.g. ``SingleTrack(vehicle)`` (held at ``speed``
        by a rear-axle force equal to the drag).
    steering : SteeringSystem, optional
        Default ``SteeringSystem(vehicle, **steering_overrides)`` (steering-wheel angle input).
    cycles : int
        Periods simulated, >= 2; the metrics use the last (default 3).
    iterations : int
        Runs to size the amplitude, >= 1: each scales it by target / measured peak (default 3).
    samples_per_cycle : int
        Output samples per period of the returned ``result``, >= 1. The metrics do not depend on
        it: they are read off the procedure's own grid of :data:`METRIC_SAMPLES_PER_CYCLE` samples
        per period, in the same integration.
    method : str
        Integrator of :func:`vehdyn.simulate` (default ``"LSODA"``: the steering friction law is
        stiff).
    rtol : float
        Relative tolerance of the integration [-] (default 1e-7).
    **steering_overrides
        Fields of :class:`~vehdyn.handling.SteeringSystemParameters` for the default steering.

    Returns
    -------
    WeaveTestMetrics
        The metrics of the last cycle (module docstring), the steering-wheel amplitude found and
        the run.

    Raises
    ------
    ParameterError
        A speed or frequency not finite and > 0, ``amplitude_g`` outside [0.11, 0.8], ``cycles``
        < 2, ``iterations`` < 1, ``samples_per_cycle`` < 1 (or too many samples), both
        ``steering`` and ``steering_overrides``, or a steering system that is not angle-driven.

    References
    ----------
    ISO 13674-1:2010, *Road vehicles - Test method for the quantification of on-centre handling -
    Part 1: Weave test* (100 km/h, 0.2 Hz, 0.2 g; the metrics after its sec. 8).
    D. J. Norman, "Objective evaluation of on-center handling performance", SAE 840069, 1984.
    """
    from vehdyn.simulation import simulate
    from vehdyn.handling.bicycle import LinearBicycle, check_speed
    from vehdyn.params.checks import MAX_RUN_SAMPLES, check_sample_count, check_vehicle, finite_number, whole_number
    from vehdyn.handling.steady_state import steady_state_gains
    from vehdyn.handling.steering_system import SteeredVehicle, SteeringSystem

    check_vehicle("weave_test", vehicle)
    u = float(check_speed(speed))
    target = finite_number(amplitude_g, "amplitude_g", minimum=0.11, maximum=0.8) * GRAVITY
    f = finite_number(frequency, "frequency", positive=True)
    cycles = whole_number(cycles, "cycles", minimum=2)
    iterations = whole_number(iterations, "iterations", minimum=1)
    samples_per_cycle = whole_number(samples_per_cycle, "samples_per_cycle", minimum=1)
    finer = samples_per_cycle > max(cycles, METRIC_SAMPLES_PER_CYCLE)
    name, value = ("samples_per_cycle", samples_per_cycle) if finer else ("cycles", cycles)
    check_sample_count((cycles + 0.75) * max(samples_per_cycle, METRIC_SAMPLES_PER_CYCLE), name, value,
                       "(cycles + 0.75) x samples per cycle", limit=MAX_RUN_SAMPLES)
    if vehicle_model is None:
        vehicle_model = LinearBicycle(vehicle, u)
    if steering is None:
        steering = SteeringSystem(vehicle, **steering_overrides)
    elif steering_overrides:
        raise ParameterError("give steering overrides or a SteeringSystem, not both", key="steering",
                             value=sorted(steering_overrides))
    if steering.steering_input != "angle":
        raise ParameterError("the weave test needs a SteeringSystem with steering_input='angle'", key="steering",
                             value=steering.steering_input)
    model = SteeredVehicle(vehicle_model, steering)
    x0 = model.state_vector()
    inputs = {}
    if hasattr(vehicle_model, "straight_running"):
        x0[:vehicle_model.n_states] = vehicle_model.straight_running(u)
    if "rear_longitudinal_force" in model.input_names:
        inputs["rear_longitudinal_force"] = vehicle.aero.drag_force(u).item()
    # first guess: the bicycle's steady gain through the steering ratio
    gain = float(steady_state_gains(vehicle, u).lateral_acceleration)
    amplitude = target / gain * steering.parameters.ratio
    period = 1.0 / f
    end = (cycles + 0.75) * period  # ends at a trough of the angle: the last period is trough to trough
    # the metrics' own grid and the output grid asked for, integrated together (the adaptive steps
    # do not depend on the output times)
    def grid(per_cycle):
        return np.linspace(0.0, end, int(round((cycles + 0.75) * per_cycle)) + 1)

    t, on_metric, on_output = union_grid(grid(METRIC_SAMPLES_PER_CYCLE), grid(samples_per_cycle))
    omega = 2 * np.pi * f
    for _ in range(iterations):
        driven = _SineDriven(model, "steering_wheel_angle", amplitude, omega)
        res = simulate(driven, t, inputs, x0=driven.initial_state(x0), method=method, rtol=rtol, atol=1e-10,
                       max_step=period / 50)
        metrics = weave_metrics(at_samples(res, on_metric), f)
        amplitude *= target / metrics["peak_lateral_acceleration"]
    amplitude /= target / metrics["peak_lateral_acceleration"]  # the amplitude of the run returned
    return WeaveTestMetrics(speed=u, frequency=f, steering_wheel_amplitude=float(amplitude),
                            result=at_samples(res, on_output), **metrics)

