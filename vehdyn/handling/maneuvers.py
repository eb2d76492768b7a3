"""Standard handling manoeuvres: input signals, scenario helpers and their metrics.

Steer inputs are road-wheel angles [rad] in SAE signs (positive turns right) and are returned as
vectorized callables ``delta(t)`` for :func:`vehdyn.simulate`'s ``inputs``: closed-form
:class:`~vehdyn.piecewise_signal.PiecewiseSignal` s, which both backends of ``simulate`` evaluate
exactly between samples and whose kinks they step onto (``solve_ivp`` methods, compiled RK45/DOP853). Test procedures:

* step steer (ISO 7401:2011, sec. 6.2: steer ramp completed within 0.15 s) and its metrics
  (:func:`vehdyn.handling.step_steer_metrics`);
* ramp steer (ISO 7401 / ISO 4138 slow ramp), sine steer (ISO 7401 continuous sine);
* constant-radius test (ISO 4138:2012, sec. 6.2): the steady state on a circle with growing speed,
  from :func:`~vehdyn.handling.nonlinear_handling_diagram`;
* sine with dwell (FMVSS 126, 49 CFR 571.126, S7.7): 0.7 Hz sine whose second peak dwells 0.5 s;
  metrics S5.2.1-S5.2.3 (yaw-rate ratios 1.0 s and 1.75 s after completion of steer, lateral
  displacement 1.07 s after the beginning of steer);
* crosswind gust (a 1 - cos gust on the aerodynamic side force and yaw moment);
* braking in a turn (ISO 7975:2019): from a steady turn, brake at a constant deceleration demand;
* ISO 3888-1:2018 double lane change track (:func:`double_lane_change_track`), driven by
  :class:`~vehdyn.handling.PreviewDriver`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.piecewise_signal import PiecewiseSignal

__all__ = ["step_steer", "ramp_steer", "sine_steer", "sine_with_dwell", "sine_with_dwell_metrics",
           "SineWithDwellMetrics", "constant_radius_test", "crosswind_gust", "braking_in_turn",
           "BrakingInTurn", "DoubleLaneChangeTrack", "double_lane_change_track", "obstacle_avoidance_track",
           "lane_change_speed_bound", "lane_change_outcome",
           "spin_out_time"]


def _finite(name, value, positive=False):
    value = float(value)
    if not np.isfinite(value) or (positive and value <= 0):
        raise ParameterError(f"{name} must be finite{' and > 0' if positive else ''}, got {value!r}", key=name,
                             value=value)
    return value


def step_steer(amplitude: float, start: float = 0.5, rise_time: float = 0.15) -> PiecewiseSignal:
    """Step steer of ``amplitude`` [rad] beginning at ``start`` [s], a linear ramp over ``rise_time`` [s]."""
    amplitude, start = _finite("amplitude", amplitude), _finite("start", start)
    rise_time = _finite("rise_time", rise_time, positive=True)
    end = start + rise_time
    return PiecewiseSignal([[start, end, 0.0, amplitude / rise_time, 0.0, 0.0, 0.0],
                            [end, np.inf, amplitude, 0.0, 0.0, 0.0, 0.0]])


def ramp_steer(rate: float, start: float = 0.0) -> PiecewiseSignal:
    """Ramp steer of ``rate`` [rad/s] from ``start`` [s]."""
    rate, start = _finite("rate", rate), _finite("start", start)
    return PiecewiseSignal([[start, np.inf, 0.0, rate, 0.0, 0.0, 0.0]])


def sine_steer(amplitude: float, frequency: float, start: float = 0.0, cycles: float | None = None) -> PiecewiseSignal:
    """Sine steer amplitude sin(2 pi f (t - start)) [rad] from ``start``, for ``cycles`` periods (None: forever)."""
    amplitude, start = _finite("amplitude", amplitude), _finite("start", start)
    frequency = _finite("frequency", frequency, positive=True)
    end = np.inf if cycles is None else start + _finite("cycles", cycles, positive=True) / frequency
    return PiecewiseSignal([[start, end, 0.0, 0.0, amplitude, 2 * np.pi * frequency, 0.0]])


def sine_with_dwell(amplitude: float, frequency: float = 0.7, dwell: float = 0.5, start: float = 1.0) -> PiecewiseSignal:
    """FMVSS 126 sine with dwell: a ``frequency`` sine whose second peak is held for ``dwell`` [s].

    delta = A sin(2 pi f tau) for tau = t - start in [0, 3/(4f)], then -A for ``dwell`` s, then
    A sin(2 pi f (tau - dwell)) until tau = 1/f + dwell (completion of steer), then 0.
    The first lobe has the sign of ``amplitude`` [rad].
    """
    amplitude, start = _finite("amplitude", amplitude), _finite("start", start)
    frequency = _finite("frequency", frequency, positive=True)
    dwell = _finite("dwell", dwell)
    if dwell < 0:
        raise ParameterError(f"dwell must be >= 0 [s], got {dwell}", key="dwell", value=dwell)
    omega, quarter3 = 2 * np.pi * frequency, 0.75 / frequency
    pieces = [[start, start + quarter3, 0.0, 0.0, amplitude, omega, 0.0]]
    if dwell > 0:
        pieces.append([start + quarter3, start + quarter3 + dwell, -amplitude, 0.0, 0.0, 0.0, 0.0])
    # the last quarter period continues the sine from its trough: phase 3 pi / 2
    pieces.append([start + quarter3 + dwell, start + 1.0 / frequency + dwell, 0.0, 0.0, amplitude, omega,
                   1.5 * np.pi])
    delta = PiecewiseSignal(pieces)
    delta.completion_of_steer = start + 1.0 / frequency + dwell
    delta.beginning_of_steer = start
    return delta


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


def sine_with_dwell_metrics(result, steer) -> SineWithDwellMetrics:
    """FMVSS 126 metrics of a simulated sine with dwell (``steer`` from :func:`sine_with_dwell`)."""
    t = result.time
    r = np.asarray(result["yaw_rate"], dtype=float)
    y = np.asarray(result["y"], dtype=float)
    cos, bos = steer.completion_of_steer, steer.beginning_of_steer
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


def constant_radius_test(model, radius: float, *, driven_axle: str = "rear", step: float = 0.25):
    """ISO 4138 constant-radius test of a SingleTrack model: steady turns on ``radius`` [m] to the limit.

    Returns
    -------
    pandas.DataFrame
        Indexed by lateral acceleration [m/s^2]: steer angle, sideslip, speed and the understeer
        gradient d(delta)/d(a_y) [rad/(m/s^2)] (on a constant radius the kinematic steer L/R is
        constant, so the whole slope is understeer; ISO 4138 sec. 8).
    """
    from vehdyn.handling.nonlinear_steady_state import nonlinear_handling_diagram

    diagram = nonlinear_handling_diagram(model, radius=radius, driven_axle=driven_axle, step=step)
    frame = diagram.to_frame()
    frame["understeer_gradient"] = np.gradient(diagram.steer_angle, diagram.lateral_acceleration) \
        if diagram.steer_angle.size > 1 else np.nan
    frame.attrs["units"]["understeer_gradient"] = "rad/(m/s^2)"
    frame.attrs["limit_lateral_acceleration"] = diagram.limit_lateral_acceleration
    return frame


def crosswind_gust(vehicle, speed: float, gust_speed: float, *, start: float = 1.0, duration: float = 1.0,
                   side_force_derivative: float = 2.0, yaw_moment_derivative: float = 0.3,
                   side_area: float | None = None):
    """Inputs ``external_lateral_force`` and ``external_yaw_moment`` of a 1 - cos crosswind gust.

    The wind w(t) = w_g (1 - cos(2 pi (t - start)/duration)) / 2 blows toward +y (SAE: from the
    left to the right); with the resultant air speed V_r^2 = u^2 + w^2 and the aerodynamic sideslip
    beta_w = atan(w / u), the linearized aerodynamic side force and yaw moment are (Hucho,
    *Aerodynamics of Road Vehicles*, 4th ed., 1998, sec. 4.4; Wong, *Theory of Ground Vehicles*,
    4th ed., 2008, sec. 3.2)::

        F_y = 0.5 rho V_r^2 A C_Y,beta beta_w,      M_z = 0.5 rho V_r^2 A L C_N,beta beta_w

    with A the side (reference) area and L the wheelbase. The defaults C_Y,beta = 2.0 /rad and
    C_N,beta = 0.3 /rad (referred to the frontal area) are typical of passenger cars in Hucho's
    data, not measured values of the shipped vehicles; positive C_N,beta turns the nose downwind.
    (The same law acts inside :class:`~vehdyn.handling.SingleTrack` through its input
    ``wind_velocity_lateral``, with the coefficients of the vehicle file; see
    :mod:`vehdyn.handling.crosswind`.)

    Parameters
    ----------
    vehicle : Vehicle
    speed : float
        Forward speed u [m/s] at which the gust is met.
    gust_speed : float
        Peak crosswind w_g [m/s] (positive toward the right).
    start, duration : float
        [s].
    side_force_derivative, yaw_moment_derivative : float
        C_Y,beta and C_N,beta [1/rad].
    side_area : float, optional
        Reference area [m^2] (default the frontal area).

    Returns
    -------
    dict
        ``{"external_lateral_force": f(t), "external_yaw_moment": g(t)}`` for ``simulate``.
    """
    speed, gust_speed = _finite("speed", speed, positive=True), _finite("gust_speed", gust_speed)
    start, duration = _finite("start", start), _finite("duration", duration, positive=True)
    area = vehicle.aero.frontal_area if side_area is None else _finite("side_area", side_area, positive=True)
    rho, length = vehicle.aero.air_density, vehicle.geometry.wheelbase

    def wind(t):
        tau = (np.asarray(t, dtype=float) - start) / duration
        return np.where((tau >= 0) & (tau <= 1), 0.5 * gust_speed * (1 - np.cos(2 * np.pi * tau)), 0.0)

    def pressure_angle(t):  # 0.5 rho V_r^2 A beta_w: the side-force law of vehdyn.handling.crosswind per C_Y'
        from vehdyn.handling.crosswind import aero_side_force

        return aero_side_force(np, 0.5 * rho * area, speed, wind(t))

    return {"external_lateral_force": lambda t: side_force_derivative * pressure_angle(t),
            "external_yaw_moment": lambda t: yaw_moment_derivative * length * pressure_angle(t)}


@dataclass(frozen=True)
class BrakingInTurn:
    """Braking in a turn (ISO 7975): the result and the metrics 1 s after brake onset.

    Attributes
    ----------
    result : SimulationResult
    initial : SteadyStateCornering
    yaw_rate_ratio : float
        Yaw rate 1 s after brake onset over the initial yaw rate [-].
    sideslip_change : float
        Sideslip change over that second [rad].
    mean_deceleration : float
        Mean longitudinal deceleration over that second [m/s^2] (positive braking).
    """

    result: object
    initial: object
    yaw_rate_ratio: float
    sideslip_change: float
    mean_deceleration: float


def braking_in_turn(model, *, radius: float = 100.0, lateral_acceleration: float = 5.0, deceleration: float = 4.0,
                    brake_front_share: float = 0.65, brake_start: float = 1.0, duration: float = 4.0,
                    method: str = "RK45", rtol: float = 1e-6):
    """ISO 7975 braking in a turn with a force-mode SingleTrack model.

    The vehicle starts in the steady turn (radius [m], a_y [m/s^2]); at ``brake_start`` the drive is
    released and braking forces m * ``deceleration`` split ``brake_front_share`` : rest between the
    axles are applied (clipped by the tire friction in the model); the steer is held.
    """
    from vehdyn.simulate import simulate
    from vehdyn.handling.nonlinear_steady_state import steady_state_cornering

    if model.wheel_spin:
        raise ParameterError("braking_in_turn drives a force-mode SingleTrack (wheel_spin=False)", key="model",
                             value=model)
    share = _finite("brake_front_share", brake_front_share)
    if not 0 <= share <= 1:
        raise ParameterError(f"brake_front_share must be in [0, 1], got {share}", key="brake_front_share", value=share)
    deceleration = _finite("deceleration", deceleration, positive=True)
    brake_start, duration = _finite("brake_start", brake_start), _finite("duration", duration, positive=True)
    initial = steady_state_cornering(model, lateral_acceleration=lateral_acceleration, radius=radius)
    force = float(model.parameters.mass) * deceleration
    drive = initial.drive
    time = np.linspace(0.0, brake_start + duration, int(round((brake_start + duration) / 0.01)) + 1)
    braking = time >= brake_start
    inputs = {"front_steer_angle": np.full(time.size, initial.steer_angle),
              "front_longitudinal_force": np.where(braking, -share * force, 0.0),
              "rear_longitudinal_force": np.where(braking, -(1 - share) * force, drive)}
    result = simulate(model, time, inputs, x0=initial.state, method=method, rtol=rtol, hold="zoh")
    t1 = brake_start + 1.0
    r = result["yaw_rate"]
    beta = result["sideslip_angle"]
    u = result["longitudinal_velocity"]
    return BrakingInTurn(result, initial, float(np.interp(t1, time, r) / initial.yaw_rate),
                         float(np.interp(t1, time, beta) - np.interp(brake_start, time, beta)),
                         float((np.interp(brake_start, time, u) - np.interp(t1, time, u)) / 1.0))


@dataclass(frozen=True)
class DoubleLaneChangeTrack:
    """A severe lane-change track, ISO 3888-1 or -2 (SAE earth axes: y to the right; the change is to the left).

    Attributes
    ----------
    sections : list of (x_start, x_end, y_left, y_right)
        The three coned lanes [m] (y_left < y_right in SAE).
    path_x, path_y : ndarray
        A centre-line path through the lanes for a driver (cosine transitions) [m].
    vehicle_width : float
        [m].
    standard : str
        ``"ISO 3888-1"`` or ``"ISO 3888-2"``.
    """

    sections: list
    path_x: np.ndarray
    path_y: np.ndarray
    vehicle_width: float
    standard: str = "ISO 3888-1"

    def inner_line(self, margin: float = 0.1):
        """(path_x, path_y): a path that keeps to the inner side of each lane (``margin`` [m] from the cones).

        In lanes 1 and 3 (5) the CG runs ``margin`` + b/2 from the cone line nearer the next
        lane, with cosine transitions across the gaps: the least lateral travel the cones allow
        (3.25 - 0.1 b and 3.25 - 0.3 b m in ISO 3888-1, against 3.5 + 0.05 b and 3.5 - 0.05 b between
        the lane centres),
        the line a test driver aims for.
        """
        margin = _finite("margin", margin)
        half = self.vehicle_width / 2 + margin
        (_, _, l1, _), (_, _, _, r3), (_, _, l5, _) = self.sections
        return self.path_x, _lane_blend(self.path_x, self.sections, [l1 + half, r3 - half, l5 + half])

    def least_curvature_line(self, margin: float = 0.15):
        """(path_x, path_y): the path of least largest curvature through the lanes narrowed by ``margin`` [m].

        The path of :func:`lane_change_speed_bound` for lanes ``margin`` narrower on each side (room
        for the driver's tracking error), held constant before lane 1 and after lane 5: the racing
        line of the lane change.
        """
        margin = _finite("margin", margin)
        narrow = DoubleLaneChangeTrack([(x0, x1, left + margin, right - margin)
                                        for x0, x1, left, right in self.sections], self.path_x, self.path_y,
                                       self.vehicle_width, self.standard)
        _, x, y = lane_change_speed_bound(narrow, 1.0)
        return self.path_x, np.interp(self.path_x, x, y)


def _lane_blend(x, sections, levels):
    """y(x): ``levels`` in the sections, cosine transitions across the gaps between them."""

    def blend(x0, x1, y0, y1):
        s = np.clip((x - x0) / (x1 - x0), 0, 1)
        return y0 + (y1 - y0) * 0.5 * (1 - np.cos(np.pi * s))

    (_, e1, _, _), (s3, e3, _, _), (s5, _, _, _) = sections
    return np.where(x <= e3, blend(e1, s3, levels[0], levels[1]), blend(e3, s5, levels[1], levels[2]))


def _lane_change_track(b, lengths, widths, near_gap, standard, run_in, run_out):
    """Sections from lengths (lane 1, gap, lane 3, gap, lane 5) and lane widths; lane 3's right cone line
    ``near_gap`` [m] left of lane 1's right (ISO 3888-1) cone line; lanes 1 and 5 share their right line."""
    w1, w3, w5 = widths
    edges = np.cumsum((0.0,) + tuple(lengths))
    right1 = w1 / 2  # lane 1 centred on y = 0
    sections = [(edges[0], edges[1], right1 - w1, right1),
                (edges[2], edges[3], right1 - near_gap - w3, right1 - near_gap),
                (edges[4], edges[5], right1 - w5, right1)]
    x = np.linspace(-run_in, edges[5] + run_out, int(round((edges[5] + run_in + run_out) / 0.1)) + 1)
    y = _lane_blend(x, sections, [0.5 * (sec[2] + sec[3]) for sec in sections])
    return DoubleLaneChangeTrack(sections, x, y, b, standard)


def double_lane_change_track(vehicle_width: float, *, lateral_offset: float = 3.5, run_in: float = 30.0,
                             run_out: float = 30.0) -> DoubleLaneChangeTrack:
    """ISO 3888-1:2018 double lane change: cone lanes and a centre-line path.

    Section 1 (length 15 m, width 1.1 b + 0.25), section 2 (30 m), section 3 (25 m, width
    1.2 b + 0.25, its right cone line ``lateral_offset`` = 3.5 m left of section 1's), section 4
    (25 m), section 5 (15 m, width 1.3 b + 0.25), with b the vehicle width; sections 1 and 5 share
    their right boundary (ISO 3888-1, Fig. 1 and Table 1; the same dimensions in Project Chrono's
    ``demo_VEH_HMMWV_DoubleLaneChange``, which however measures the 3.5 m from lane 1's centre
    line to lane 3's near cone line: 1.1 b / 2 + 0.125 m more travel).

    Parameters
    ----------
    vehicle_width : float
        b [m].
    """
    b = _finite("vehicle_width", vehicle_width, positive=True)
    offset = _finite("lateral_offset", lateral_offset, positive=True)
    return _lane_change_track(b, (15.0, 30.0, 25.0, 25.0, 15.0), (1.1 * b + 0.25, 1.2 * b + 0.25, 1.3 * b + 0.25),
                              offset, "ISO 3888-1", run_in, run_out)


def obstacle_avoidance_track(vehicle_width: float, *, run_in: float = 30.0,
                             run_out: float = 30.0) -> DoubleLaneChangeTrack:
    """ISO 3888-2:2011 obstacle avoidance (the "moose test") track: cone lanes and a centre-line path.

    Section 1 (length 12 m, width 1.1 b + 0.25), section 2 (13.5 m), section 3 (11 m, width
    b + 1, its right cone line 1 m left of section 1's left one), section 4 (12.5 m), section 5
    (12 m, width 1.3 b + 0.25 but at least 3 m, its right cone line section 1's): 61 m in all
    (ISO 3888-2:2011, Fig. 1 and Table 1; the same in Project Chrono's
    ``demo_VEH_HMMWV_DoubleLaneChange``). b is the vehicle width [m].
    """
    b = _finite("vehicle_width", vehicle_width, positive=True)
    w1 = 1.1 * b + 0.25
    return _lane_change_track(b, (12.0, 13.5, 11.0, 12.5, 12.0), (w1, b + 1.0, max(1.3 * b + 0.25, 3.0)),
                              w1 + 1.0, "ISO 3888-2", run_in, run_out)


def lane_change_speed_bound(track: DoubleLaneChangeTrack, friction_coefficient: float, *, step: float = 0.5,
                            gravity: float = 9.80665):
    """The cone geometry's speed bound: the highest speed at which a point mass at mu g clears the cones.

    The path y(x) through the coned lanes (the CG kept b/2 from the cone lines, as
    :func:`lane_change_outcome` checks) whose largest curvature |y''| is smallest: a linear program
    on a grid of ``step`` [m] (second differences, the small-angle curvature; free before lane 1
    and after lane 5). A vehicle whose lateral acceleration cannot exceed mu g cannot clear the
    cones faster than u* = sqrt(mu g / kappa_min) [m/s] on any path: a bound from the geometry and
    the friction alone, without yaw dynamics or driver.

    Returns
    -------
    speed : float
        u* [m/s].
    x, y : ndarray
        The minimal-curvature path [m].
    """
    from scipy.optimize import linprog
    from scipy.sparse import diags, hstack, vstack

    mu = _finite("friction_coefficient", friction_coefficient, positive=True)
    h = _finite("step", step, positive=True)
    start, end = track.sections[0][0], track.sections[-1][1]
    x = start + h * np.arange(int(round((end - start) / h)) + 1)
    n = x.size
    if n < 3:
        raise ParameterError(f"step {h!r} m leaves fewer than 3 grid points on the track", key="step", value=h)
    lower, upper = np.full(n, -np.inf), np.full(n, np.inf)
    half = track.vehicle_width / 2
    for x0, x1, left, right in track.sections:
        inside = (x >= x0 - 1e-9) & (x <= x1 + 1e-9)
        lower[inside], upper[inside] = left + half, right - half
    second = diags([1.0, -2.0, 1.0], [0, 1, 2], shape=(n - 2, n)) / h**2
    column = np.ones((n - 2, 1))
    A = vstack([hstack([second, -column]), hstack([-second, -column])]).tocsr()
    cost = np.zeros(n + 1)
    cost[-1] = 1.0
    bounds = [(lo if np.isfinite(lo) else None, hi if np.isfinite(hi) else None) for lo, hi in zip(lower, upper)]
    solution = linprog(cost, A_ub=A, b_ub=np.zeros(2 * (n - 2)), bounds=bounds + [(0.0, None)], method="highs")
    if solution.status != 0:
        raise ParameterError(f"no path through the cones: {solution.message}", key="track", value=track.standard)
    curvature = solution.x[-1]
    speed = np.inf if curvature <= 0 else float(np.sqrt(mu * gravity / curvature))
    return speed, x, solution.x[:-1]


def lane_change_outcome(track: DoubleLaneChangeTrack, result) -> dict:
    """Whether a run stayed inside the cones: ``{"passed", "worst_margin", "section"}``.

    The vehicle is a rectangle of the track's width centred on the CG path (yaw neglected in the
    width, a standard simplification); the margin is the smallest distance [m] from its side to a
    cone line inside the coned sections (negative: a cone is hit).
    """
    x, y = np.asarray(result["x"]), np.asarray(result["y"])
    half = track.vehicle_width / 2
    worst, where = np.inf, None
    for k, (x0, x1, left, right) in enumerate(track.sections):
        inside = (x >= x0) & (x <= x1)
        if not np.any(inside):
            return {"passed": False, "worst_margin": -np.inf, "section": k}
        margin = np.minimum((y[inside] - half) - left, right - (y[inside] + half)).min()
        if margin < worst:
            worst, where = float(margin), k
    return {"passed": bool(worst >= 0), "worst_margin": worst, "section": where}


def spin_out_time(result, sideslip_limit: float = np.pi / 4):
    """The first time [s] at which |sideslip angle| exceeds ``sideslip_limit`` [rad], or None.

    A sideslip of 45 degrees at the CG is far beyond what a driver can recover; it marks the
    vehicle as spun out (the simulation itself carries on through the spin).
    """
    beta = np.abs(np.asarray(result["sideslip_angle"], dtype=float))
    over = np.nonzero(beta > float(sideslip_limit))[0]
    return float(result.time[over[0]]) if over.size else None
