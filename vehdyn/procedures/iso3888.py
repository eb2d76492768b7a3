"""ISO 3888 severe lane changes: the tracks, the outcome of a run, and the limit speed.

ISO 3888-1:2018 (double lane change, :func:`double_lane_change_track`) and ISO 3888-2:2011
(obstacle avoidance, :func:`obstacle_avoidance_track`) as cone lanes; :func:`lane_change_outcome`
scores a run against the cones, :func:`lane_change_run` drives one run with a driver model
(a controller closed around the vehicle by :class:`vehdyn.interconnect.ClosedLoop`), and
:func:`lane_change_limit` finds the highest entry speed at which some tuning of a driver clears the
cones; :func:`lane_change_speed_bound` is the friction-limited bound on that speed.
"""

from __future__ import annotations

from vehdyn.params.checks import finite_number, is_number
from vehdyn.model import Model
from vehdyn.errors import ParameterError
from dataclasses import dataclass
import numpy as np

__all__ = ["DoubleLaneChangeTrack", "double_lane_change_track", "obstacle_avoidance_track", "lane_change_speed_bound", "lane_change_outcome", "spin_out_time", "lane_change_run", "lane_change_limit", "slip_angle_utilization"]


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

        Parameters
        ----------
        margin : float
            Clearance [m] between the vehicle's side and the cone line (finite; default 0.1 m;
            negative: the side overlaps the cones).

        Returns
        -------
        path_x : ndarray
            The track's :attr:`path_x` [m].
        path_y : ndarray
            Lateral position of the CG on the inner line at ``path_x`` [m] (SAE: y to the right).

        Raises
        ------
        ParameterError
            A non-finite ``margin``.
        """
        margin = finite_number(margin, "margin")
        half = self.vehicle_width / 2 + margin
        (_, _, l1, _), (_, _, _, r3), (_, _, l5, _) = self.sections
        return self.path_x, _lane_blend(self.path_x, self.sections, [l1 + half, r3 - half, l5 + half])

    def least_curvature_line(self, margin: float = 0.15):
        """(path_x, path_y): the path of least largest curvature through the lanes narrowed by ``margin`` [m].

        The path of :func:`lane_change_speed_bound` for lanes ``margin`` narrower on each side (room
        for the driver's tracking error), held constant before lane 1 and after lane 5: the racing
        line of the lane change.

        Parameters
        ----------
        margin : float
            Narrowing of each lane on each side [m] (finite; default 0.15 m).

        Returns
        -------
        path_x : ndarray
            The track's :attr:`path_x` [m].
        path_y : ndarray
            Lateral position of the CG on the least-curvature line at ``path_x`` [m] (the linear
            program's path on a 0.5 m grid, interpolated; constant outside it).

        Raises
        ------
        ParameterError
            A non-finite ``margin``, or one that narrows the lanes so far that no path is left.
        """
        margin = finite_number(margin, "margin")
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


_PATH_SPACING = 0.1  # [m] between the points of a track's centre-line path
_MAX_BOUND_POINTS = 20_000  # grid points of lane_change_speed_bound's linear program at most (5 mm on 100 m)
#: The coarsest spacing [m] along x of a run :func:`lane_change_outcome` scores: between samples
#: the path is a chord, within (curvature x spacing^2 / 8) of the arc, a few millimetres at the
#: curvature of a lane change.
MAX_OUTCOME_SPACING = 1.0


def _lane_change_track(b, lengths, widths, near_gap, standard, run_in, run_out):
    """Sections from lengths (lane 1, gap, lane 3, gap, lane 5) and lane widths; lane 3's right cone line
    ``near_gap`` [m] left of lane 1's right (ISO 3888-1) cone line; lanes 1 and 5 share their right line."""
    from vehdyn.params.checks import check_sample_count

    run_in = finite_number(run_in, "run_in", minimum=0.0)
    run_out = finite_number(run_out, "run_out", minimum=0.0)
    for name, value in (("run_in", run_in), ("run_out", run_out)):
        check_sample_count((sum(lengths) + run_in + run_out) / _PATH_SPACING, name, value,
                           f"path points {_PATH_SPACING} m apart")
    w1, w3, w5 = widths
    edges = np.cumsum((0.0,) + tuple(lengths))
    right1 = w1 / 2  # lane 1 centred on y = 0
    sections = [(edges[0], edges[1], right1 - w1, right1),
                (edges[2], edges[3], right1 - near_gap - w3, right1 - near_gap),
                (edges[4], edges[5], right1 - w5, right1)]
    x = np.linspace(-run_in, edges[5] + run_out, int(round((edges[5] + run_in + run_out) / _PATH_SPACING)) + 1)
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
    lateral_offset : float
        Lane 3's right cone line left of lane 1's [m] (3.5 m in the standard).
    run_in, run_out : float
        Straight path before lane 1 and after lane 5 [m], >= 0.

    Returns
    -------
    DoubleLaneChangeTrack
    """
    b = finite_number(vehicle_width, "vehicle_width", positive=True)
    offset = finite_number(lateral_offset, "lateral_offset", positive=True)
    return _lane_change_track(b, (15.0, 30.0, 25.0, 25.0, 15.0), (1.1 * b + 0.25, 1.2 * b + 0.25, 1.3 * b + 0.25),
                              offset, "ISO 3888-1", run_in, run_out)


def obstacle_avoidance_track(vehicle_width: float, *, run_in: float = 30.0,
                             run_out: float = 30.0) -> DoubleLaneChangeTrack:
    """ISO 3888-2:2011 obstacle avoidance (the "moose test") track: cone lanes and a centre-line path.

    Section 1 (length 12 m, width 1.1 b + 0.25), section 2 (13.5 m), section 3 (11 m, width
    b + 1, its right cone line 1 m left of section 1's left one), section 4 (12.5 m), section 5
    (12 m, width 1.3 b + 0.25 but at least 3 m, its right cone line section 1's): 61 m in all
    (ISO 3888-2:2011, Fig. 1 and Table 1; the same in Project Chrono's
    ``demo_VEH_HMMWV_DoubleLaneChange``).

    Parameters
    ----------
    vehicle_width : float
        b [m].
    run_in, run_out : float
        Straight path before lane 1 and after lane 5 [m], >= 0.

    Returns
    -------
    DoubleLaneChangeTrack
    """
    b = finite_number(vehicle_width, "vehicle_width", positive=True)
    w1 = 1.1 * b + 0.25
    return _lane_change_track(b, (12.0, 13.5, 11.0, 12.5, 12.0), (w1, b + 1.0, max(1.3 * b + 0.25, 3.0)),
                              w1 + 1.0, "ISO 3888-2", run_in, run_out)


def lane_change_speed_bound(track: DoubleLaneChangeTrack, friction_coefficient: float, *, step: float = 0.5,
                            gravity: float = 9.80665):
    r"""The cone geometry's speed bound: the highest speed at which a point mass at mu g clears the cones.

    The path y(x) through the coned lanes (the CG kept b/2 from the cone lines, as
    :func:`lane_change_outcome` checks) whose largest curvature |y''| is smallest: a linear program
    on a grid of ``step`` [m] (second differences, the small-angle curvature; free before lane 1
    and after lane 5). A vehicle whose lateral acceleration cannot exceed mu g cannot clear the
    cones faster than u* = sqrt(mu g / kappa_min) [m/s] on any path: a bound from the geometry and
    the friction alone, without yaw dynamics or driver.

    .. math::

        \kappa_{\min} = \min_{y} \max_i \left|\frac{y_{i+1} - 2 y_i + y_{i-1}}{h^2}\right|
        \quad \text{subject to the cone lines}, \qquad
        u^* = \sqrt{\mu g / \kappa_{\min}}

    Parameters
    ----------
    track : DoubleLaneChangeTrack
        The coned track (:func:`double_lane_change_track` or :func:`obstacle_avoidance_track`)
        with the vehicle's width.
    friction_coefficient : float
        Tire-road friction coefficient :math:`\mu` [-], > 0.
    step : float
        Grid spacing :math:`h` along x [m], > 0 (default 0.5 m), leaving at least 3 and at most
        20,000 grid points on the coned length.
    gravity : float
        Gravitational acceleration :math:`g` [m/s^2], > 0 (default 9.80665).

    Returns
    -------
    speed : float
        u* [m/s] (``inf`` if a straight path clears the cones).
    x, y : ndarray
        The minimal-curvature path [m].

    Raises
    ------
    ParameterError
        ``track`` not a :class:`DoubleLaneChangeTrack`, a ``friction_coefficient``, ``gravity``
        or ``step`` not finite and > 0, a ``step`` giving too few or too many grid points, or no
        path through the cones (the linear program infeasible).

    References
    ----------
    ISO 3888-1:2018, *Passenger cars - Test track for a severe lane-change manoeuvre - Part 1:
    Double lane-change*, Fig. 1 and Table 1 (the cone layout); ISO 3888-2:2011, *Part 2:
    Obstacle avoidance*, Fig. 1 and Table 1.
    """
    from scipy.optimize import linprog
    from scipy.sparse import diags, hstack, vstack

    _check_track(track)
    mu = finite_number(friction_coefficient, "friction_coefficient", positive=True)
    gravity = finite_number(gravity, "gravity", positive=True)
    h = finite_number(step, "step", positive=True)
    start, end = track.sections[0][0], track.sections[-1][1]
    if (end - start) / h > _MAX_BOUND_POINTS:
        raise ParameterError(f"step = {h!r} m makes {(end - start) / h:.3g} grid points on the {end - start:g} m of "
                             f"coned track, more than the {_MAX_BOUND_POINTS} the linear program takes", key="step",
                             value=h)
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
    cone line inside the coned sections (negative: a cone is hit), read off the run's samples,
    which must lie at most :data:`MAX_OUTCOME_SPACING` (1 m) apart along x in the coned sections.

    Parameters
    ----------
    track : DoubleLaneChangeTrack
    result : SimulationResult
        A run with the CG's earth position ``x``, ``y`` [m].

    Returns
    -------
    dict
        ``passed`` (bool), ``worst_margin`` [m] and ``section`` (index of the section where it is).

    Raises
    ------
    ParameterError
        Not a track, a result without ``x`` and ``y``, or one sampled too coarsely to score.
    """
    _check_track(track)
    try:
        x, y = np.asarray(result["x"], dtype=float), np.asarray(result["y"], dtype=float)
    except (KeyError, TypeError, IndexError, ValueError):
        raise ParameterError(f"result must be a run with the CG's earth position x and y, got "
                             f"{type(result).__name__}", key="result", value=type(result).__name__) from None
    if x.ndim != 1 or x.shape != y.shape or x.size < 2:
        raise ParameterError(f"result must hold one run of x and y of the same length (>= 2 samples), got shapes "
                             f"{x.shape} and {y.shape}", key="result", value=(x.shape, y.shape))
    coned = (x >= track.sections[0][0]) & (x <= track.sections[-1][1])
    spacing = np.abs(np.diff(x))[coned[1:] | coned[:-1]]
    if spacing.size and float(spacing.max()) > MAX_OUTCOME_SPACING:
        raise ParameterError(f"result is sampled {float(spacing.max()):.3g} m apart along the coned track: scoring the "
                             f"cones needs samples at most {MAX_OUTCOME_SPACING} m apart (a finer output grid)",
                             key="result", value=float(spacing.max()))
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

    Parameters
    ----------
    result : SimulationResult
        A run with ``sideslip_angle`` [rad].
    sideslip_limit : float
        [rad], in (0, pi].

    Returns
    -------
    float or None
    """
    sideslip_limit = finite_number(sideslip_limit, "sideslip_limit", positive=True, maximum=np.pi)
    if not (hasattr(result, "time") and "sideslip_angle" in result):
        raise ParameterError(f"result must be a SimulationResult with sideslip_angle, got {type(result).__name__}",
                             key="result", value=type(result).__name__)
    beta = np.abs(np.asarray(result["sideslip_angle"], dtype=float))
    over = np.nonzero(beta > sideslip_limit)[0]
    return float(result.time[over[0]]) if over.size else None


def lane_change_run(model: Model, track, driver, speed: float, *, throttle: str = "hold", rtol: float = 1e-5):
    """One run of ``driver`` steering ``model`` through ``track`` from ``speed``.

    The car starts on the path's first point in straight running. ``throttle="hold"``: the rear
    axle force balances the aerodynamic drag at the entry speed (the speed held, ISO 3888-1);
    ``"release"``: no drive force (coasting from the entry, the ISO 3888-2 procedure); a driver
    that commands the rear axle force itself (a :class:`~vehdyn.driver.PreviewDriver` with a
    target speed) holds the speed its way. The loop is ``driver.close(model)`` (a
    :class:`~vehdyn.interconnect.ClosedLoop`), compiled when the model and the driver have
    compiled forms; RK45.

    Parameters
    ----------
    model : SingleTrack
        The vehicle model (with ``straight_running`` and the states ``x``, ``y``, ``yaw_angle``,
        ``longitudinal_velocity``).
    track : DoubleLaneChangeTrack
        The cones and the path.
    driver : Controller
        A driver of :mod:`vehdyn.driver` on the track's path.
    speed : float
        Entry speed [m/s].
    throttle : str
        ``"hold"`` or ``"release"``.
    rtol : float
        Relative tolerance of the RK45 integration [-] (atol 1e-8).

    Returns
    -------
    result : SimulationResult
        The run.
    outcome : dict
        :func:`~vehdyn.procedures.lane_change_outcome` plus ``spin_out_time``; ``passed`` is
        False on a spin (|sideslip| > 45 deg).
    """
    from vehdyn.simulation import simulate
    from vehdyn.procedures import lane_change_outcome, spin_out_time

    if throttle not in ("hold", "release"):
        raise ParameterError(f"throttle must be 'hold' or 'release', got {throttle!r}", key="throttle", value=throttle)
    _check_track(track)
    speed = finite_number(speed, "speed", positive=True)
    loop = driver.close(model)
    x_start, x_end = float(track.path_x[0]), float(track.path_x[-1])
    n = int(np.ceil((x_end - x_start) / 0.25)) + 1
    t = np.linspace(0.0, 1.15 * (x_end - x_start) / speed, n)
    x0 = np.concatenate([model.straight_running(speed, x=x_start), np.zeros(loop.n_states - model.n_states)])
    force = float(np.asarray(model.parameters.drag_factor)) * speed**2 if throttle == "hold" else 0.0
    inputs = {"rear_longitudinal_force": force} if "rear_longitudinal_force" in loop.input_names else None
    result = simulate(loop, t, inputs, x0=x0, method="RK45", rtol=rtol, atol=1e-8)
    outcome = lane_change_outcome(track, result)
    outcome["spin_out_time"] = spin_out_time(result)
    outcome["passed"] = outcome["passed"] and outcome["spin_out_time"] is None
    return result, outcome


def slip_angle_utilization(model, result) -> dict:
    """How far each axle's slip angle went toward and past the one of its law's peak force.

    The peak-force slip angle is the tire law's at the static axle load
    (:meth:`~vehdyn.handling.SingleTrack.peak_slip`).

    Parameters
    ----------
    model : SingleTrack
        The vehicle model of the run.
    result : SimulationResult
        A run of it with the outputs ``front_slip_angle`` and ``rear_slip_angle``.

    Returns
    -------
    dict
        ``{axle: (largest |tan(slip angle)| over the peak-force one [-], first time [s] it passed 1
        or None)}``.
    """
    out = {}
    for axle in ("front", "rear"):
        peak = float(np.asarray(model.peak_slip(axle)[1]))
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
    try:
        lo, hi = speeds
    except (TypeError, ValueError):
        raise ParameterError(f"speeds must be the bracket (low, high) [m/s], got {speeds!r}", key="speeds",
                             value=speeds) from None
    if not (is_number(lo) and is_number(hi) and 0 < lo < hi < np.inf):
        raise ParameterError(f"speeds must be 0 < low < high, finite, got {speeds!r}", key="speeds", value=speeds)
    lo, hi = float(lo), float(hi)
    resolution = finite_number(resolution, "resolution", positive=True)
    if np.log2((hi - lo) / resolution) > _MAX_BISECTIONS:
        raise ParameterError(f"resolution = {resolution!r} m/s takes more than {_MAX_BISECTIONS} bisections of the "
                             f"bracket {speeds!r}", key="resolution", value=resolution)
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


def _check_track(track):
    if not isinstance(track, DoubleLaneChangeTrack):
        raise ParameterError(f"track must be a DoubleLaneChangeTrack (double_lane_change_track(...) or "
                             f"obstacle_avoidance_track(...)), got {type(track).__name__}", key="track", value=track)


_MAX_BISECTIONS = 40  # a bracket of 40 m/s to 4e-11 m/s: beyond it the runs cannot tell the speeds apart


def _factor(model, *results) -> str:
    """The axle that passed its peak-force slip angle first in the first of ``results`` where one did, else "driver"."""
    for result in results:
        first = [(time, axle) for axle, (_, time) in slip_angle_utilization(model, result).items() if time is not None]
        if first:
            return f"tire saturation, {min(first)[1]} axle"
    return "driver"
