"""FMVSS 126 (electronic stability control) compliance: the full sine-with-dwell series.

49 CFR 571.126, Standard No. 126, *Electronic stability control systems for light vehicles*:

* S7.9 (test series): at 80 km/h, a 0.7 Hz sine with a 500 ms dwell at the second peak
  (:func:`~vehdyn.procedures.sine_with_dwell`), steered first counter-clockwise and then clockwise
  (two series). The amplitude starts at 1.5 A, where A is the hand-wheel angle giving 0.3 g in the
  slowly increasing steer test (S7.6; here the steady turn at 0.3 g of the nonlinear model,
  :func:`~vehdyn.handling.steady_state_cornering`), and grows in steps of 0.5 A; the final run is
  the greater of 6.5 A and 270 degrees of hand-wheel angle, provided 6.5 A <= 300 degrees (else
  300 degrees) (S7.9.4).
* S5.2.1, S5.2.2 (lateral stability): the yaw rate 1.00 s after completion of steer is at most
  35 % of the first peak yaw rate after the steer reversal, and 1.75 s after completion of steer at
  most 20 %.
* S5.2.3 (responsiveness): for runs with an amplitude of 5 A or more, the lateral displacement of
  the CG 1.07 s after the beginning of steer is at least 1.83 m (vehicles with GVWR <= 3,500 kg) or
  1.52 m (GVWR > 3,500 kg).

The metrics of one run come from :func:`~vehdyn.procedures.sine_with_dwell_metrics`. The vehicle
model is the nonlinear single track (no roll and no lateral load transfer) or the full vehicle
(:class:`~vehdyn.full_vehicle.FullVehicle`: roll, load transfer, four wheels, which an ESC brakes
one at a time); either way the results describe the model, not a certification.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.params.checks import MAX_RUN_SAMPLES, check_sample_count, finite_number, whole_number
from vehdyn.procedures._sampling import at_samples, union_grid
from vehdyn.units import GRAVITY, kmh_to_ms

__all__ = ["FMVSS126Result", "fmvss126", "SineWithDwellMetrics", "sine_with_dwell_metrics"]

@dataclass(frozen=True)
class SineWithDwellMetrics:
    """FMVSS 126 metrics (S5.2).

    Attributes
    ----------
    peak_yaw_rate : float
        Largest |yaw rate| after the steer reversal (the second lobe) [rad/s].
    yaw_rate_ratio_1000ms, yaw_rate_ratio_1750ms : float
        Yaw rate 1.0 s and 1.75 s after completion of steer over the peak [-] (limits 0.35, 0.20).
    lateral_displacement : float
        |y| of the CG 1.07 s after the beginning of steer [m] (limit >= 1.83 m for GVWR <= 3500 kg).
    stable : bool
        Both ratios within their limits.
    """

    peak_yaw_rate: float
    yaw_rate_ratio_1000ms: float
    yaw_rate_ratio_1750ms: float
    lateral_displacement: float
    stable: bool


#: The coarsest output step [s] the S5.2 metrics are read from: the peak of a 0.7 Hz yaw response
#: sampled this finely is within (2 pi 0.7 * 0.02)^2 / 8 = 1e-3 of its true value, and the yaw
#: rates 1.00 s and 1.75 s after completion of steer are interpolated as closely.
MAX_METRIC_STEP = 0.02
#: The samples of the grid :func:`fmvss126` computes its verdict on, over each run (0 to completion
#: of steer + 2 s: about 16 ms apart), whatever output grid is asked for.
METRIC_POINTS = 301


def sine_with_dwell_metrics(result, steer) -> SineWithDwellMetrics:
    """FMVSS 126 metrics of a simulated sine with dwell (``steer`` from :func:`sine_with_dwell`).

    Parameters
    ----------
    result : SimulationResult
        A run with ``yaw_rate`` [rad/s] and ``y`` [m], sampled at most :data:`MAX_METRIC_STEP`
        (0.02 s) apart up to 1.75 s after completion of steer.
    steer : PiecewiseSignal
        The steer of :func:`~vehdyn.procedures.sine_with_dwell` (its beginning and completion of
        steer time the metrics).

    Returns
    -------
    SineWithDwellMetrics

    Raises
    ------
    ParameterError
        A steer without the sine with dwell's times, a result without ``yaw_rate`` and ``y``, one
        that ends before the metrics' instants or is sampled too coarsely for them.
    """
    cos, bos = getattr(steer, "completion_of_steer", None), getattr(steer, "beginning_of_steer", None)
    if cos is None or bos is None or not callable(steer):
        raise ParameterError(f"steer must be the signal of vehdyn.procedures.sine_with_dwell (it carries the "
                             f"beginning and completion of steer), got {type(steer).__name__}", key="steer",
                             value=steer)
    if not (hasattr(result, "time") and "yaw_rate" in result and "y" in result):
        raise ParameterError(f"result must be a SimulationResult with yaw_rate and y, got {type(result).__name__}",
                             key="result", value=type(result).__name__)
    t = np.asarray(result.time, dtype=float)
    if t[-1] < cos + 1.75:
        raise ParameterError(f"the simulation ends at {t[-1]} s, before {cos + 1.75} s that the metric needs",
                             key="time", value=cos + 1.75)
    used = t <= cos + 1.75 + MAX_METRIC_STEP
    step = float(np.max(np.diff(t[used]))) if np.count_nonzero(used) > 1 else float("inf")
    if step > MAX_METRIC_STEP + 1e-12:
        raise ParameterError(f"result is sampled {step:.3g} s apart: the S5.2 metrics need samples at most "
                             f"{MAX_METRIC_STEP} s apart up to {cos + 1.75:.3g} s (its peak yaw rate and the yaw "
                             "rates after completion of steer are read off them)", key="result", value=step)
    r = np.asarray(result["yaw_rate"], dtype=float)
    y = np.asarray(result["y"], dtype=float)
    delta = steer(t)
    first_sign = np.sign(delta[np.argmax(np.abs(delta) > 0)]) if np.any(delta != 0) else 1.0
    reversal = t[np.argmax((t > bos) & (np.sign(delta) == -first_sign))]
    after = t >= reversal
    peak = float(np.max(np.abs(r[after]))) if np.any(after) else float("nan")

    def at(signal, time):
        if time > t[-1]:
            raise ParameterError(f"the simulation ends at {t[-1]} s, before {time} s that the metric needs",
                                 key="time", value=time)
        return float(np.interp(time, t, signal))

    r1, r175 = at(r, cos + 1.0), at(r, cos + 1.75)
    ratio1 = abs(r1) / peak if peak > 0 else 0.0
    ratio175 = abs(r175) / peak if peak > 0 else 0.0
    displacement = abs(at(y, bos + 1.07) - at(y, bos))
    return SineWithDwellMetrics(peak, ratio1, ratio175, displacement, bool(ratio1 <= 0.35 and ratio175 <= 0.20))


RULE = "49 CFR 571.126 S5.2"
YAW_RATIO_LIMIT_1000MS = 0.35
YAW_RATIO_LIMIT_1750MS = 0.20
GVWR_LIMIT = 3500.0  # kg
_DISPLACEMENT = {True: 1.83, False: 1.52}  # GVWR <= 3500 kg, > 3500 kg [m]


@dataclass(frozen=True)
class FMVSS126Result:
    """Outcome of :func:`fmvss126`.

    Attributes
    ----------
    vehicle : str
    controller : str
        Name of the controller in the loop ("none" without).
    amplitude_a : float
        A [rad] of road-wheel angle (0.3 g steady turn at 80 km/h).
    runs : list of dict
        One per run: ``direction`` ("counterclockwise" / "clockwise"), ``amplitude_multiple``,
        ``hand_wheel_amplitude_deg``, ``road_wheel_amplitude_deg``, ``peak_yaw_rate`` [rad/s],
        ``yaw_rate_ratio_1000ms``, ``yaw_rate_ratio_1750ms``, ``lateral_displacement`` [m],
        ``displacement_required`` (bool), ``passed`` (bool).
    displacement_limit : float
        [m], 1.83 or 1.52 by GVWR.
    results : list of SimulationResult
        Each run's simulation on the output grid asked for (``n_points`` samples), in the order of
        ``runs``.
    """

    vehicle: str
    controller: str
    amplitude_a: float
    displacement_limit: float
    runs: list = field(default_factory=list)
    results: list = field(default_factory=list, repr=False)

    @property
    def passed(self) -> bool:
        """Every run meets S5.2.1, S5.2.2 and (where required) S5.2.3."""
        return bool(self.runs) and all(run["passed"] for run in self.runs)

    def failures(self) -> list[str]:
        """One line per failed criterion, citing the paragraph of 49 CFR 571.126.

        Returns
        -------
        list of str
            For each run (``"<direction> <multiple> A"``) and each criterion it misses: the
            yaw-rate ratio 1.00 s after completion of steer above 0.35 (S5.2.1), the ratio at
            1.75 s above 0.20 (S5.2.2), the lateral displacement below :attr:`displacement_limit`
            where the run requires it (S5.2.3). Empty when every run passes.
        """
        lines = []
        for run in self.runs:
            tag = f"{run['direction']} {run['amplitude_multiple']:.2f} A"
            if run["yaw_rate_ratio_1000ms"] > YAW_RATIO_LIMIT_1000MS:
                lines.append(f"{tag}: yaw-rate ratio at 1.00 s {run['yaw_rate_ratio_1000ms']:.3f} > 0.35 (S5.2.1)")
            if run["yaw_rate_ratio_1750ms"] > YAW_RATIO_LIMIT_1750MS:
                lines.append(f"{tag}: yaw-rate ratio at 1.75 s {run['yaw_rate_ratio_1750ms']:.3f} > 0.20 (S5.2.2)")
            if run["displacement_required"] and run["lateral_displacement"] < self.displacement_limit:
                lines.append(f"{tag}: lateral displacement {run['lateral_displacement']:.2f} m < "
                             f"{self.displacement_limit} m (S5.2.3)")
        return lines

    def to_frame(self):
        """The runs as a table.

        Returns
        -------
        pandas.DataFrame
            One row per run, the columns of :attr:`runs` (``direction``, ``amplitude_multiple``
            [-], ``hand_wheel_amplitude_deg`` and ``road_wheel_amplitude_deg`` [deg],
            ``peak_yaw_rate`` [rad/s], ``yaw_rate_ratio_1000ms`` and ``yaw_rate_ratio_1750ms``
            [-], ``lateral_displacement`` [m], ``displacement_required``, ``passed``); the units in
            ``attrs["units"]``, the rule ("49 CFR 571.126 S5.2") in ``attrs["rule"]``.
        """
        import pandas as pd

        frame = pd.DataFrame(self.runs)
        frame.attrs["units"] = {"hand_wheel_amplitude_deg": "deg", "road_wheel_amplitude_deg": "deg",
                                "peak_yaw_rate": "rad/s", "yaw_rate_ratio_1000ms": "-", "yaw_rate_ratio_1750ms": "-",
                                "lateral_displacement": "m"}
        frame.attrs["rule"] = RULE
        return frame

    def __str__(self) -> str:
        verdict = "passes" if self.passed else "fails"
        text = f"{self.vehicle} ({self.controller}) {verdict} {RULE} in {len(self.runs)} runs"
        failures = self.failures()
        return text + ("" if not failures else ":\n  " + "\n  ".join(failures))


def series_multiples(a: float, steering_ratio: float) -> np.ndarray:
    """Multiples of A of the S7.9.4 series for A [rad road wheel] and the steering ratio [-]."""
    hand = np.degrees(a) * steering_ratio  # degrees of hand wheel per A
    final = max(6.5, 270.0 / hand) if 6.5 * hand <= 300.0 else 300.0 / hand
    multiples = list(np.arange(1.5, final + 1e-9, 0.5))
    if final - multiples[-1] > 1e-9:
        multiples.append(final)
    return np.array(multiples)


def fmvss126(vehicle, controller=None, *, plant: str = "single_track", speed: float | None = None,
             directions=("counterclockwise", "clockwise"), gross_vehicle_weight_rating: float | None = None,
             amplitude_multiples=None, rtol: float = 1e-5, atol: float = 1e-8, n_points: int = 301) -> FMVSS126Result:
    """Run the FMVSS 126 sine-with-dwell series on a model of ``vehicle``.

    Parameters
    ----------
    vehicle : Vehicle
    controller : Model, optional
        A controller for the plant, e.g. ``vehdyn.chassis.ESC(vehicle)`` for the force-mode
        :class:`~vehdyn.handling.SingleTrack` or ``ESC(vehicle, corners=True)`` for the full
        vehicle, closed around it with :class:`vehdyn.interconnect.ClosedLoop`. None: the car alone.
        Each run is compiled where the model (and controller) has a compiled form; otherwise all
        runs go in one numpy batch.
    plant : {"single_track", "full_vehicle"}
        The vehicle model: :class:`~vehdyn.handling.SingleTrack` (force mode, coasting: no
        longitudinal force) or :class:`~vehdyn.full_vehicle.FullVehicle` (from its straight-running
        trim, coasting: no drive torque, S7.9.2). A is the steer angle of the model's own 0.3 g
        steady turn.
    speed : float, optional
        Entry speed [m/s]; default 80 km/h (S7.9.1).
    directions : tuple of str
        "counterclockwise" (first lobe to the left, SAE negative steer) and/or "clockwise".
    gross_vehicle_weight_rating : float, optional
        GVWR [kg] choosing the displacement limit; default the vehicle's mass (the vehicle files
        carry no GVWR: a car of 3,500 kg or less is taken as such).
    amplitude_multiples : sequence of float, optional
        Run only these multiples of A [-], each finite and > 0 (a subset, for quick checks);
        default the S7.9.4 series: 1.5 A to the greater of 6.5 A and 270 degrees of hand-wheel
        angle (300 degrees if 6.5 A exceeds it) in steps of 0.5 A.
    rtol : float
        Relative tolerance of the RK45 integration [-] (default 1e-5; maximum step 0.02 s).
    atol : float
        Absolute tolerance of the RK45 integration [state units] (default 1e-8).
    n_points : int
        Samples of each run's output grid (``FMVSS126Result.results``), >= 2. The metrics and the
        verdict do not depend on it: they are read off the procedure's own grid of
        :data:`METRIC_POINTS` samples per run, in the same integration.

    Returns
    -------
    FMVSS126Result
        ``.passed``, ``.to_frame()`` (one row per run), ``.failures()``, ``.results``.

    Raises
    ------
    ParameterError
        ``vehicle`` not a :class:`~vehdyn.params.Vehicle`, an unknown ``plant`` or direction, a
        ``speed`` or GVWR not finite and > 0, ``n_points`` < 2 (or too many samples), or
        ``amplitude_multiples`` not finite and > 0.

    References
    ----------
    NHTSA, FMVSS No. 126, *Electronic stability control systems*, 49 CFR 571.126 (final rule,
    72 FR 17236, 2007): S7.9 (the sine-with-dwell test series: S7.9.1 entry speed 80 km/h,
    S7.9.4 the amplitudes) and S5.2 (S5.2.1, S5.2.2 lateral stability, S5.2.3 responsiveness).
    """
    from vehdyn.params import Vehicle
    from vehdyn.simulation import simulate
    from vehdyn.procedures import sine_with_dwell, sine_with_dwell_metrics
    from vehdyn.handling.nonlinear_steady_state import steady_state_cornering
    from vehdyn.handling.single_track import SingleTrack

    if not isinstance(vehicle, Vehicle):
        raise ParameterError(f"vehicle must be a vehdyn Vehicle, got {type(vehicle).__name__}", key="vehicle",
                             value=vehicle)
    speed = float(kmh_to_ms(80.0)) if speed is None else finite_number(speed, "speed", positive=True)
    signs = {"counterclockwise": -1.0, "clockwise": 1.0}  # SAE: positive steer turns right (clockwise)
    directions = tuple(directions)
    if not directions or any(d not in signs for d in directions):
        raise ParameterError(f"directions must be drawn from {tuple(signs)}, got {directions!r}", key="directions",
                             value=directions)
    gvwr = float(vehicle.mass.mass) if gross_vehicle_weight_rating is None else \
        finite_number(gross_vehicle_weight_rating, "gross_vehicle_weight_rating", positive=True)
    n_points = whole_number(n_points, "n_points", minimum=2)
    check_sample_count(n_points, "n_points", n_points, "samples per run", limit=MAX_RUN_SAMPLES)
    plants = ("single_track", "full_vehicle")
    if plant not in plants:
        raise ParameterError(f"plant must be one of {plants}, got {plant!r}", key="plant", value=plant)
    if plant == "single_track":
        model = SingleTrack(vehicle)
        a = float(steady_state_cornering(model, lateral_acceleration=0.3 * GRAVITY, speed=speed).steer_angle)
        x_car = model.straight_running(speed)
    else:
        from vehdyn.full_vehicle import FullVehicle

        model = FullVehicle(vehicle)
        _, u_turn = model.trim(speed, lateral_acceleration=0.3 * GRAVITY)
        a = float(u_turn[model.index("front_steer_angle", "inputs")])
        x_car = model.trim(speed)[0]
    ratio = float(vehicle.steering.ratio)
    if amplitude_multiples is None:
        multiples = series_multiples(a, ratio)
    else:
        multiples = np.atleast_1d(np.asarray(amplitude_multiples, dtype=float))
        if multiples.ndim != 1 or not multiples.size or not np.all(np.isfinite(multiples) & (multiples > 0)):
            raise ParameterError(f"amplitude_multiples must be finite numbers > 0, got {amplitude_multiples!r}",
                                 key="amplitude_multiples", value=amplitude_multiples)
    cases = [(d, k) for d in directions for k in multiples]
    steers = [sine_with_dwell(signs[d] * k * a) for d, k in cases]
    end = steers[0].completion_of_steer + 2.0
    # the verdict's own grid and the output grid asked for, integrated together (the adaptive steps
    # do not depend on the output times): the metrics are those of METRIC_POINTS samples however
    # many n_points are
    t, on_metric, on_output = union_grid(np.linspace(0.0, end, METRIC_POINTS), np.linspace(0.0, end, n_points))
    options = dict(method="RK45", rtol=rtol, atol=atol, max_step=0.02)
    name, x0 = "none", x_car
    if controller is not None:
        from vehdyn.interconnect import ClosedLoop

        loop = ClosedLoop(model, controller)
        name = type(controller).__name__
        x0 = loop.state_vector(dict(zip(model.state_names, x_car)))
        model = loop
    if _compiles(model):
        results = [simulate(model, t, {"front_steer_angle": s}, x0=x0, **options) for s in steers]
        members = [(r, None) for r in results]
    else:
        batch = simulate(model, t, {"front_steer_angle": lambda time: np.stack([s(time) for s in steers], axis=-1)},
                         x0=np.repeat(x0[:, None], len(steers), axis=1), **options)
        members = [(batch, k) for k in range(len(steers))]
    limit = _DISPLACEMENT[gvwr <= GVWR_LIMIT]
    runs = []
    for (direction, k), steer, member in zip(cases, steers, members):
        m = sine_with_dwell_metrics(at_samples(member[0], on_metric, member[1]), steer)
        required = bool(k >= 5.0 - 1e-9)
        ok = (m.yaw_rate_ratio_1000ms <= YAW_RATIO_LIMIT_1000MS and m.yaw_rate_ratio_1750ms <= YAW_RATIO_LIMIT_1750MS
              and (not required or m.lateral_displacement >= limit))
        runs.append({"direction": direction, "amplitude_multiple": float(k),
                     "hand_wheel_amplitude_deg": float(np.degrees(k * a) * ratio),
                     "road_wheel_amplitude_deg": float(np.degrees(k * a)), "peak_yaw_rate": m.peak_yaw_rate,
                     "yaw_rate_ratio_1000ms": m.yaw_rate_ratio_1000ms, "yaw_rate_ratio_1750ms": m.yaw_rate_ratio_1750ms,
                     "lateral_displacement": m.lateral_displacement, "displacement_required": required,
                     "passed": bool(ok)})
    return FMVSS126Result(vehicle=vehicle.name, controller=name, amplitude_a=a, displacement_limit=limit, runs=runs,
                          results=[at_samples(r, on_output, k) for r, k in members])


def _compiles(model) -> bool:
    """Whether ``simulate`` runs ``model`` on the compiled backend (numba installed, a compiled rhs)."""
    from vehdyn.simulation.compiled import numba_available

    if not numba_available():
        return False
    try:
        return model.compiled_rhs() is not None
    except ParameterError:
        return False

