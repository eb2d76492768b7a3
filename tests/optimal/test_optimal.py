"""vehdyn.optimal: a closed form, the minimum-time lane change against the closed-loop driver, friction-ellipse
constraints, infeasible problems and bad input."""

import shutil

import numpy as np
import pytest

import vehdyn
from vehdyn import LinearModel, ParameterError

pytest.importorskip("casadi")
from vehdyn.driver import OptimalPreviewDriver  # noqa: E402
from vehdyn.handling import SingleTrack  # noqa: E402
from vehdyn.optimal import OptimalControlError, Problem, minimum_time_lane_change, passage_time  # noqa: E402
from vehdyn.procedures import lane_change_limit, lane_change_outcome, obstacle_avoidance_track  # noqa: E402
from vehdyn.tire import LinearTire  # noqa: E402

SEDAN = vehdyn.load_vehicle("sedan")
TRACK = obstacle_avoidance_track(max(SEDAN.geometry.front_track, SEDAN.geometry.rear_track) + 0.2)
CART = LinearModel([[0.0, 1.0], [0.0, 0.0]], [[0.0], [1.0]], [[1.0, 0.0]], [[0.0]],
                   states=["position", "velocity"], inputs=["force"], outputs=["y"])


def rest_to_rest(intervals, duration=2.0, force_limit=np.inf, **options):
    p = Problem(CART, intervals, controls=["force"], duration=duration, **options)
    p.bound("force", -force_limit, force_limit)
    p.constrain(lambda s, k: s["position"], 1.0, 1.0, "arrive", nodes=[intervals])
    p.constrain(lambda s, k: s["velocity"], 0.0, 0.0, "stop", nodes=[intervals])
    if options.get("hessian") == "gauss-newton":
        p.minimize(integral=lambda s, k: s["force"], squares=True)
    else:
        p.minimize(integral=lambda s, k: s["force"] ** 2)
    return p


C_COMPILER = shutil.which("cc") or shutil.which("gcc")


@pytest.mark.parametrize("intervals", [5, 20, 60])
def test_rest_to_rest_energy_is_the_closed_form_of_piecewise_constant_forces(intervals):
    # the least integral of F^2 moving a unit mass by d in T with N constant pieces: 12 d^2 / T^3 * N^2 / (N^2 - 1)
    solution = rest_to_rest(intervals).solve([0.0, 0.0])
    assert solution.cost == pytest.approx(12.0 / 8.0 * intervals**2 / (intervals**2 - 1), rel=1e-9)
    assert solution["position"][-1] == pytest.approx(1.0, abs=1e-9)
    assert solution.status == "Solve_Succeeded"


@pytest.mark.parametrize("options", [{"hessian": "gauss-newton"}, {"hessian": "limited-memory"},
                                     pytest.param({"hessian": "gauss-newton", "jit": True}, marks=pytest.mark.skipif(
                                         C_COMPILER is None, reason="no C compiler for jit"))])
def test_rest_to_rest_closed_form_with_each_hessian_and_compiled(options):
    # the cost in squares (residual F, weighted by sqrt(dt)) is the same cost: the same closed form
    solution = rest_to_rest(20, **options).solve([0.0, 0.0])
    assert solution.cost == pytest.approx(12.0 / 8.0 * 400 / 399, rel=1e-8)
    assert solution["position"][-1] == pytest.approx(1.0, abs=1e-8)


@pytest.fixture(scope="module")
def optimum():
    return minimum_time_lane_change(SingleTrack(SEDAN, tire_lag=False), TRACK, spacing=1.0)


def test_minimum_time_lane_change_converges_from_a_cold_start_and_replays_inside_the_cones(optimum):
    assert optimum.status == "Solve_Succeeded" and optimum.iterations < 200
    model = optimum.problem.model
    t = np.arange(0.0, 1.05 * optimum.time[-1], 0.005)
    result = vehdyn.simulate(model, t, optimum.input_signals(), x0=optimum.states[:, 0], method="RK45", rtol=1e-9,
                             atol=1e-11)
    # the transcription integrates the model's own equations (RK4 at ~45 ms): the replay stays on the plan
    assert np.max(np.abs(np.interp(optimum.grid, result["x"], result["y"]) - optimum["y"])) < 0.01
    assert lane_change_outcome(TRACK, result)["passed"]
    assert passage_time(result, TRACK) == pytest.approx(optimum.passage_time, rel=1e-3)
    assert np.all(np.abs(optimum["front_steer_angle"]) <= 0.35 + 1e-8)
    assert np.all(np.abs(np.diff(optimum["front_steer_angle"]) / np.diff(optimum.time[:-1])) <= 1.0 + 1e-6)


def test_minimum_time_with_tire_lag_converges_and_replays_on_its_model(optimum):
    # with tire lag the transient slips are bounded to 0.98 of the peak-force slip (deflection_limit), off the
    # force's switch to the kinematic slip at 0.999: a cold start converges, the replay on the lagged model stays
    # on the plan and inside the cones, and the lag costs time against the plan without it
    model = SingleTrack(SEDAN)
    lagged = minimum_time_lane_change(model, TRACK, spacing=1.0)
    assert lagged.status == "Solve_Succeeded" and lagged.iterations < 200
    for axle in ("front", "rear"):
        reach = 0.98 * model.peak_slip(axle)[1] * getattr(model.parameters, f"{axle}_lateral_relaxation_length")
        assert np.max(np.abs(lagged[f"{axle}_lateral_deflection"])) <= reach * (1 + 1e-6)  # IPOPT relaxes bounds
    t = np.arange(0.0, 1.05 * lagged.time[-1], 0.005)
    result = vehdyn.simulate(model, t, lagged.input_signals(), x0=lagged.states[:, 0], method="RK45", rtol=1e-9,
                             atol=1e-11)
    assert np.max(np.abs(np.interp(lagged.grid, result["x"], result["y"]) - lagged["y"])) < 0.01
    assert lane_change_outcome(TRACK, result)["passed"]
    assert optimum.passage_time < lagged.passage_time < 1.01 * optimum.passage_time
    with pytest.raises(ParameterError, match="deflection_limit"):
        minimum_time_lane_change(model, TRACK, deflection_limit=0.0)


def test_minimum_time_is_at_most_the_best_closed_loop_driver(optimum):
    model = optimum.problem.model
    paths = {"centre": (TRACK.path_x, TRACK.path_y), "least curvature": TRACK.least_curvature_line(0.15)}

    def make(speed, line, **tuning):
        return OptimalPreviewDriver(*paths[line], vehicle=SEDAN, speed=speed, delay=0.1, **tuning)

    tunings = [{"line": line, "preview_time": 0.5, "gain": g} for line in paths for g in (1.0, 1.5)]
    limit = lane_change_limit(model, TRACK, make, tunings, throttle="release", speeds=(8.0, 40.0), resolution=1.0)
    driver_time = passage_time(limit["passing"][0], TRACK)
    assert np.isfinite(driver_time)
    assert optimum.passage_time <= driver_time
    assert optimum.entry_speed >= limit["speed"]


def test_a_friction_ellipse_bounds_the_linear_tires_minimum_time():
    # linear tires have no limit of their own: the axles' forces within mu F_z (written in signal names)
    # bound the entry speed, and the optimum runs the ellipse to its edge
    tires = (LinearTire(cornering_stiffness=SEDAN.tires.front_cornering_stiffness / 2),
             LinearTire(cornering_stiffness=SEDAN.tires.rear_cornering_stiffness / 2))
    model = SingleTrack(SEDAN, *tires, tire_lag=False)
    mu = 0.8
    problem = Problem(model, 60, controls=["front_steer_angle"], along="x", span=(-5.0, 55.0))
    problem.free_initial("longitudinal_velocity")
    problem.bound("longitudinal_velocity", 5.0, 60.0, nodes=[0])
    problem.bound("y", -3.0, -3.0, nodes=[60])
    problem.bound("yaw_angle", 0.0, 0.0, nodes=[60])
    for axle in ("front", "rear"):
        problem.constrain(lambda s, k, a=axle: (s[f"{a}_lateral_force"] / (mu * s[f"{a}_normal_load"])) ** 2
                          + (s[f"{a}_longitudinal_force"] / (mu * s[f"{a}_normal_load"])) ** 2, -np.inf, 1.0,
                          f"{axle} friction ellipse")
    problem.minimize(final=lambda s, k: s["time"])
    solution = problem.solve(model.straight_running(20.0, x=-5.0))
    use = np.max([np.abs(solution[f"{a}_lateral_force"] / (mu * solution[f"{a}_normal_load"]))
                  for a in ("front", "rear")])
    assert use == pytest.approx(1.0, abs=1e-6)
    assert 5.0 < solution["longitudinal_velocity"][0] < 60.0


def test_an_infeasible_problem_raises_with_the_status_the_horizon_and_the_constraint():
    with pytest.raises(OptimalControlError) as error:
        rest_to_rest(20, force_limit=0.1).solve([0.0, 0.0])
    e = error.value
    assert e.status == "Infeasible_Problem_Detected"
    assert e.horizon == (0.0, 2.0) and e.violation > 0
    assert "Infeasible_Problem_Detected" in str(e) and "0 to 2" in str(e) and e.constraint in str(e)
    assert isinstance(e, vehdyn.SimulationError)


def test_bad_input_is_refused():
    with pytest.raises(ParameterError, match="control 'throttle' is not an input"):
        Problem(CART, 10, controls=["throttle"], duration=1.0)
    with pytest.raises(ParameterError, match="either duration"):
        Problem(CART, 10, controls=["force"], duration=1.0, along="position", span=(0, 1))
    with pytest.raises(ParameterError, match="span"):
        Problem(CART, 10, controls=["force"], along="position", span=(1.0, 0.0))
    with pytest.raises(ParameterError, match="intervals"):
        Problem(CART, 0, controls=["force"], duration=1.0)
    p = Problem(CART, 10, controls=["force"], duration=1.0)
    with pytest.raises(ParameterError, match="'speed' is not a signal"):
        p.bound("speed", 0.0, 1.0)
    with pytest.raises(ParameterError, match="low <= high"):
        p.bound("force", 1.0, -1.0)
    p.parameter("target")
    with pytest.raises(ParameterError, match="give the value of parameter 'target'"):
        p.solve([0.0, 0.0])
    with pytest.raises(ParameterError, match="DoubleLaneChangeTrack"):
        minimum_time_lane_change(SingleTrack(SEDAN), "ISO 3888-2")
    for key in ("steer_weight", "steer_rate_weight"):
        with pytest.raises(ParameterError, match=key) as error:
            minimum_time_lane_change(SingleTrack(SEDAN), TRACK, **{key: -1.0})
        assert error.value.key == key
    with pytest.raises(ParameterError, match="hessian must be one of") as error:
        Problem(CART, 10, controls=["force"], duration=1.0, hessian="newton")
    assert error.value.key == "hessian" and error.value.value == "newton"
    p = Problem(CART, 10, controls=["force"], duration=1.0, hessian="gauss-newton")
    with pytest.raises(ParameterError, match="needs a cost in squares"):
        p.minimize(integral=lambda s, k: s["force"] ** 2)
    with pytest.raises(ParameterError, match="needs a cost in squares"):
        p.solve([0.0, 0.0])  # no cost at all


def test_the_nmpc_loop_clears_the_double_lane_change_above_the_crossover_drivers_limit():
    # ISO 3888-1, speed held, on the single track with tire lag: the crossover driver (the best of 4 tunings) has
    # a highest passing entry speed; the NMPC (the single track without lag inside, 20 steps of 0.1 s) clears the
    # cones 1 m/s above it, where every crossover tuning tried hit a cone
    from vehdyn.driver import CrossoverDriver
    from vehdyn.interconnect import ClosedLoop
    from vehdyn.optimal import PathTrackingNMPC
    from vehdyn.procedures import double_lane_change_track

    track = double_lane_change_track(TRACK.vehicle_width)
    plant, planner = SingleTrack(SEDAN), SingleTrack(SEDAN, tire_lag=False)
    px, py = track.least_curvature_line(0.15)
    paths = {"centre": (track.path_x, track.path_y), "least curvature": (px, py)}

    def make(speed, line, **tuning):
        return CrossoverDriver.tuned(planner, speed, *paths[line], **tuning)

    tunings = [{"line": line, "preview_time": 1.0, "crossover_frequency": w} for line in paths for w in (2.5, 4.0)]
    limit = lane_change_limit(plant, track, make, tunings, throttle="hold", speeds=(10.0, 30.0), resolution=0.5)
    assert 10.0 < limit["speed"] < 30.0 and not limit["failing"][1]["passed"]
    speed = limit["speed"] + 1.0
    drag = float(planner.parameters.drag_factor) * speed**2
    nmpc = PathTrackingNMPC(planner, px, py, horizon=20, period=0.1, inputs={"rear_longitudinal_force": drag})
    loop = ClosedLoop(plant, nmpc)
    t = np.arange(0.0, 1.05 * (px[-1] - px[0]) / speed, 0.05)
    result = vehdyn.simulate(loop, t, {"rear_longitudinal_force": drag}, x0=plant.straight_running(speed, x=px[0]),
                             method="rk4", substeps=5)
    assert lane_change_outcome(track, result)["passed"]
    solves = np.array(nmpc.log)
    assert solves.shape[0] == int(np.ceil(t[-1] / 0.1 - 1e-9)) + 1  # one solve per sample, none in between
    steer = result["front_steer_angle_after_path_tracking_nmpc"]
    assert np.all(np.abs(steer) <= 0.5 + 1e-9)


def test_nmpc_refuses_a_prediction_model_of_other_states():
    from vehdyn.optimal import PathTrackingNMPC

    with pytest.raises(ParameterError, match="prediction model must have the states"):
        PathTrackingNMPC(SingleTrack(SEDAN), [0.0, 1.0], [0.0, 0.0])
    with pytest.raises(ParameterError, match="path_x"):
        PathTrackingNMPC(SingleTrack(SEDAN, tire_lag=False), [1.0, 0.0], [0.0, 0.0])
    with pytest.raises(ParameterError, match="weights\\['yaw'\\]"):
        PathTrackingNMPC(SingleTrack(SEDAN, tire_lag=False), [0.0, 1.0], [0.0, 0.0], weights={"yaw": -1.0})


@pytest.mark.parametrize("options", [{"hessian": "exact"}, {"hessian": "limited-memory"},
                                     pytest.param({"jit": True}, marks=pytest.mark.skipif(
                                         C_COMPILER is None, reason="no C compiler for jit"))])
def test_nmpc_finds_the_same_optimum_with_each_hessian(options):
    # the Hessian changes IPOPT's path, not the optimum (a KKT point of the same program): the Gauss-Newton
    # default, the exact Hessian, L-BFGS and the compiled interval give one first steer, the car 0.3 m off a
    # straight path and turned towards it
    from vehdyn.optimal import PathTrackingNMPC

    planner = SingleTrack(SEDAN, tire_lag=False)
    path_x = np.linspace(-10.0, 200.0, 50)
    feedback = [0.0, 0.3, -0.02, 20.0, 0.0, 0.0]
    steers = []
    for each in ({}, options):
        nmpc = PathTrackingNMPC(planner, path_x, 0.0 * path_x, horizon=30, period=0.05, options={"tol": 1e-10},
                                **each)
        steers.append(nmpc.command(0.0, feedback))
    assert abs(steers[0]) > 1e-3
    assert steers[1] == pytest.approx(steers[0], rel=1e-6, abs=1e-9)


def test_nmpc_steers_back_to_a_straight_path_and_a_second_run_starts_afresh():
    from vehdyn.interconnect import ClosedLoop
    from vehdyn.optimal import PathTrackingNMPC

    planner = SingleTrack(SEDAN, tire_lag=False)
    path_x = np.linspace(-10.0, 200.0, 300)
    nmpc = PathTrackingNMPC(planner, path_x, 0.0 * path_x, horizon=10, period=0.1)
    loop = ClosedLoop(planner, nmpc)
    t = np.arange(0.0, 2.0, 0.05)
    runs = [vehdyn.simulate(loop, t, x0=planner.straight_running(15.0, x=0.0, y=0.3), method="rk4", substeps=2)
            for _ in range(2)]
    assert abs(runs[0]["y"][-1]) < 0.05 * 0.3  # 0.3 m off the path at the start, back within 5 % in 2 s
    assert np.array_equal(runs[0]["y"], runs[1]["y"]) and len(nmpc.log) == 20
