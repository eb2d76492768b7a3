"""The minimum-time passage of a severe lane change (ISO 3888) over a model's own equations."""

from __future__ import annotations

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.optimal.transcription import Problem
from vehdyn.params.checks import finite_number
from vehdyn.procedures import DoubleLaneChangeTrack

__all__ = ["minimum_time_lane_change", "passage_time"]


def minimum_time_lane_change(model, track, *, spacing: float = 0.5, run_in: float = 10.0, margin: float = 0.02,
                             speeds=(5.0, 45.0),
                             steer_limit: float = 0.35, steer_rate_limit: float = 1.0, steer_rate_weight: float = 1e-4,
                             steer_weight: float = 0.0,
                             substeps: int | None = None, deflection_limit: float = 0.98, options=None):
    r"""The fastest passage of a lane-change track from straight running, the throttle released.

    The optimizer chooses the entry speed and the front steer angle along the track: the grid runs
    along the earth x (at most ``spacing`` apart and on every lane's start and end, from ``run_in``
    before the first lane to the end of the last), the car enters straight at y = 0 on the track's
    centre line, and the vehicle (a rectangle of the track's vehicle width, yaw neglected as in
    :func:`vehdyn.procedures.lane_change_outcome`)
    stays inside the cones at every node of a coned lane. The cost is the passage time from the
    first lane's start to the last lane's end, plus a small steer-rate penalty that makes the
    optimum unique where it is flat:

    .. math::

        \min\; t(x_{\mathrm{end}}) - t(x_{\mathrm{start}}) + w \int \dot\delta^2\,dt
        + w_\delta \int \delta^2\,dt, \quad
        |\delta| \le \delta_{\max},\ |\dot\delta| \le \dot\delta_{\max}

    (the inputs other than the front steer angle held at 0: the throttle released, ISO 3888-2).

    Parameters
    ----------
    model : Model
        A model with a symbolic form and the states ``x``, ``y``, ``longitudinal_velocity`` and the
        input ``front_steer_angle`` (:class:`~vehdyn.handling.SingleTrack`), with ``straight_running``.
    track : DoubleLaneChangeTrack
        The cones (:func:`vehdyn.procedures.obstacle_avoidance_track`, ...).
    spacing : float
        Node spacing along x [m].
    run_in : float
        Straight approach before the first lane [m] (>= 0).
    margin : float
        The lanes narrowed by this on each side [m] (the cones hold at the nodes; between them the
        path bulges by up to curvature x spacing^2 / 8, a few millimetres).
    speeds : tuple of float
        Bounds of the entry speed [m/s].
    steer_limit : float
        Road-wheel steer bound [rad].
    steer_rate_limit : float
        Road-wheel steer-rate bound [rad/s].
    steer_rate_weight : float
        w [s] (on rad^2/s^2).
    steer_weight : float
        w_delta [1/s] (on rad^2) of a steer-effort term :math:`w_\delta \int \delta^2\,dt`.
    substeps : int, optional
        Runge-Kutta steps per interval; default 1, and with tire lag as many as keep a step within
        half the shortest lateral relaxation length (the deflections' time constant sigma / V_x: the
        sedan at 1 m spacing, 5 steps; with 1 step the RK4 step sits at its stability limit and
        the plan strays 1.8 m from its own model's replay, with 2 by 2 cm, with 4 by 0.9 mm).
    deflection_limit : float
        With tire lag (the states ``front_lateral_deflection`` and ``rear_lateral_deflection``), the
        transient slip rho/sigma bounded to this fraction of the axle's peak-force slip
        (:meth:`~vehdyn.handling.SingleTrack.peak_slip`) [-]: at 0.999 of the peak slip the force
        switches from the transient to the kinematic slip (a jump), on which IPOPT cycles without
        converging (the sedan: a continuity gap of 1e-4 m left at the nodes past 0.999, 1000
        iterations); at 0.98 (0.94) it converges in 29 (30) iterations, the passage 1 ms (2 ms)
        slower than the cycling iterate.
    options : mapping, optional
        IPOPT options.

    Returns
    -------
    Solution
        The optimum; its ``passage_time`` [s] and ``entry_speed`` [m/s] are set.

    Raises
    ------
    OptimalControlError
        When IPOPT finds no passage (e.g. an upper entry speed too low to pass the last lane before
        the car stops).

    References
    ----------
    .. [1] ISO 3888-2:2011, *Passenger cars -- Test track for a severe lane-change manoeuvre -- Part 2:
       Obstacle avoidance*.
    """
    if not isinstance(track, DoubleLaneChangeTrack):
        raise ParameterError(f"track must be a DoubleLaneChangeTrack, got {type(track).__name__}", key="track",
                             value=type(track).__name__)
    spacing = finite_number(spacing, "spacing", positive=True)
    steer_rate_weight = finite_number(steer_rate_weight, "steer_rate_weight", minimum=0.0)
    steer_weight = finite_number(steer_weight, "steer_weight", minimum=0.0)
    run_in = finite_number(run_in, "run_in", minimum=0.0)
    margin = finite_number(margin, "margin", minimum=0.0)
    low, high = (finite_number(v, "speeds", positive=True) for v in speeds)
    start, first, last = track.sections[0][0] - run_in, track.sections[0][0], track.sections[-1][1]
    edges = np.unique([start] + [edge for section in track.sections for edge in section[:2]])
    grid = np.concatenate([np.linspace(a, b, int(np.ceil((b - a) / spacing - 1e-9)) + 1)[:-1]
                           for a, b in zip(edges[:-1], edges[1:]) if b > a] + [[last]])  # a node on every edge
    lengths = [float(getattr(model.parameters, f"{axle}_lateral_relaxation_length")) for axle in ("front", "rear")
               if f"{axle}_lateral_deflection" in model.state_names]
    if substeps is None:
        substeps = int(np.ceil(2.0 * np.max(np.diff(grid)) / min(lengths) - 1e-9)) if lengths else 1
    problem = Problem(model, grid.size - 1, controls=["front_steer_angle"], along="x", span=grid, substeps=substeps)
    problem.free_initial("longitudinal_velocity")
    problem.bound("longitudinal_velocity", low, high, nodes=[0])
    problem.bound("longitudinal_velocity", 0.5, np.inf)  # moving forwards all along
    problem.bound("front_steer_angle", -steer_limit, steer_limit)
    problem.bound("front_steer_angle_rate", -steer_rate_limit, steer_rate_limit)
    deflection_limit = finite_number(deflection_limit, "deflection_limit", positive=True)
    for axle in ("front", "rear"):
        if f"{axle}_lateral_deflection" in model.state_names:
            friction = model.friction if isinstance(model.friction, float) else 1.0  # the peaks scale with it
            reach = deflection_limit * friction * model.peak_slip(axle)[1] * \
                float(getattr(model.parameters, f"{axle}_lateral_relaxation_length"))
            problem.bound(f"{axle}_lateral_deflection", -reach, reach)
    half = track.vehicle_width / 2 + margin
    for x0, x1, left, right in track.sections:
        nodes = np.nonzero((problem.grid >= x0 - 1e-9) & (problem.grid <= x1 + 1e-9))[0]
        problem.bound("y", left + half, right - half, nodes=nodes)
    k_first = int(np.argmin(np.abs(problem.grid - first)))
    t_first = problem.signals(k_first)["time"]
    problem.minimize(final=lambda s, k: s["time"] - t_first,
                     integral=lambda s, k: steer_rate_weight * s["front_steer_angle_rate"] ** 2
                     + steer_weight * s["front_steer_angle"] ** 2)
    guess_speed = min(max(0.5 * (low + high), low), high)
    solution = problem.solve(model.straight_running(guess_speed, x=start), options=options)
    solution.passage_time = float(solution.time[-1] - solution.time[k_first])
    solution.entry_speed = float(solution["longitudinal_velocity"][0])
    return solution


def passage_time(result, track) -> float:
    """The time [s] a run takes from the first lane's start to the last lane's end (x interpolated).

    Parameters
    ----------
    result : SimulationResult
        A run with the earth ``x`` [m] increasing through the track.
    track : DoubleLaneChangeTrack
        The cones.

    Returns
    -------
    float
        NaN where the run does not reach the end.
    """
    x, t = np.asarray(result["x"], dtype=float), np.asarray(result.time, dtype=float)
    first, last = track.sections[0][0], track.sections[-1][1]
    if x.max() < last or x.min() > first or np.any(np.diff(x) <= 0):
        return float("nan")
    return float(np.interp(last, x, t) - np.interp(first, x, t))
