"""Optimal control on vehdyn's models (vehdyn.symbolic, vehdyn.optimal), from one run on this machine.

Run: ``python benchmarks/bench_optimal.py [--quick]``. Prints:

1. the single track's rhs (shipped sedan, Magic Formula tires, tire lag, force mode) and its
   Jacobian: CasADi (``to_casadi``, exact derivatives) against numpy and the compiled (numba) rhs --
   the largest relative difference of the values at 50 random states and the time per call (the
   CasADi and numpy calls from Python; the compiled one inside a compiled loop; the Jacobian of
   numpy by ``Model.linearize``'s central differences);
2. the minimum-time ISO 3888-2 lane change (``minimum_time_lane_change``, the single track without
   tire lag): build and solve time and IPOPT iterations from a cold start, at two node spacings;
3. NMPC path tracking (``PathTrackingNMPC``, 40 steps of 50 ms, warm started) closing the loop on the
   single track through the ISO 3888-1 double lane change at 20 m/s: solve time per step (median,
   90th percentile) and iterations, against the same controller and program with the model written
   by hand in CasADi (a dynamic bicycle with a four-coefficient Pacejka lateral force fitted to the
   same tire at the static loads: the usual practice), and the ratio (goal: <= 1.5; per step <= 20 ms),
   both sides with the same solver settings: the exact Hessian, the Gauss-Newton Hessian (the
   controller's default), and the Gauss-Newton Hessian with the interval integration compiled to C
   (``jit=True``);
4. the highest entry speed at which the NMPC loop (on the single track with tire lag, the one without
   lag inside) and the crossover driver (the best of 4 tunings) each clear the ISO 3888-1 cones, the
   speed held: bisection (``lane_change_limit`` for the driver; for the NMPC from the driver's limit
   up, the same assumption that what passes at a speed passes at lower ones).
"""

from __future__ import annotations

import _timing  # first: pins BLAS to one thread before numpy loads
import sys
import time

import numpy as np


def rhs_and_jacobian():
    import vehdyn
    from vehdyn.handling import SingleTrack
    from vehdyn.symbolic import to_casadi

    model = SingleTrack(vehdyn.load_vehicle("sedan"))
    form = to_casadi(model)
    rng = np.random.default_rng(1)
    points = []
    for _ in range(50):
        x = model.straight_running(rng.uniform(5, 35))
        points.append((x + rng.uniform(-0.3, 0.3, x.size) * np.maximum(np.abs(x), 0.05),
                       rng.uniform(-0.1, 0.1, model.n_inputs) * np.array([1 if "steer" in n else 3e4 for n in
                                                                          model.input_names])))
    worst_numpy = max(np.max(np.abs(np.array(form.rhs(x, u)).ravel() - model.rhs(0, x, u))
                             / np.maximum(np.abs(model.rhs(0, x, u)), 1e-9)) for x, u in points)
    compiled = model.compiled_rhs()
    out = np.empty(model.n_states)
    worst_compiled = 0.0
    for x, u in points:
        compiled.rhs(0.0, x, u, compiled.args, out)
        worst_compiled = max(worst_compiled, np.max(np.abs(np.array(form.rhs(x, u)).ravel() - out)
                                                    / np.maximum(np.abs(out), 1e-9)))
    x, u = points[0]
    t_casadi, _ = _timing.best_time(lambda: [form.rhs(x, u) for _ in range(200)])
    t_numpy, _ = _timing.best_time(lambda: [model.rhs(0.0, x, u) for _ in range(200)])
    t_compiled = _timing.compiled_rhs_call_time(model, x, u)
    t_jac_casadi, _ = _timing.best_time(lambda: [form.jacobians(x, u) for _ in range(50)])
    t_jac_fd, _ = _timing.best_time(lambda: model.linearize(x, u, method="finite_difference"), repeats=5)
    exact = form.linear_matrices(x, u)[0]
    fd = model.linearize(x, u, method="finite_difference").A
    print("\n1. SingleTrack rhs and Jacobian (sedan, MF tires, tire lag, force mode)")
    print(f"   largest relative difference of rhs at 50 random states: CasADi vs numpy {worst_numpy:.2e}, "
          f"CasADi vs compiled {worst_compiled:.2e}")
    print(f"   rhs per call: CasADi (from Python) {t_casadi / 200 * 1e6:8.1f} us, numpy {t_numpy / 200 * 1e6:8.1f} us, "
          f"compiled (in a compiled loop) {t_compiled * 1e6:8.2f} us")
    print(f"   Jacobians (A, B, C, D) per call: CasADi exact {t_jac_casadi / 50 * 1e6:8.1f} us, numpy central "
          f"differences {t_jac_fd * 1e6:8.1f} us; largest |A_exact - A_fd| / max|A| = "
          f"{np.max(np.abs(exact - fd)) / np.max(np.abs(fd)):.1e}")


def minimum_time(quick):
    import vehdyn
    from vehdyn.handling import SingleTrack
    from vehdyn.optimal import minimum_time_lane_change
    from vehdyn.procedures import obstacle_avoidance_track

    car = vehdyn.load_vehicle("sedan")
    track = obstacle_avoidance_track(max(car.geometry.front_track, car.geometry.rear_track) + 0.2)
    print("\n2. Minimum-time ISO 3888-2 lane change (single track, MF tires, no tire lag), cold start")
    for spacing in ((1.0,) if quick else (1.0, 0.5)):
        start = time.perf_counter()
        s = minimum_time_lane_change(SingleTrack(car, tire_lag=False), track, spacing=spacing)
        wall = time.perf_counter() - start
        print(f"   spacing {spacing} m: {s.problem.intervals} intervals, {s.iterations} iterations, solve "
              f"{s.solve_time:.2f} s, with building {wall:.2f} s; entry {s.entry_speed * 3.6:.1f} km/h, "
              f"passage {s.passage_time:.3f} s")


def hand_bicycle(car):
    """A Model whose symbolic form is a hand-written dynamic bicycle with a fitted Pacejka lateral force."""
    import casadi as ca
    from scipy.optimize import least_squares

    import vehdyn
    from vehdyn.handling import SingleTrack

    reference = SingleTrack(car, tire_lag=False)
    p = reference.parameters
    m, iz, a, b, drag = p.mass, p.yaw_inertia, p.a, p.b, p.drag_factor
    g = 9.80665
    alpha = np.linspace(-0.25, 0.25, 101)
    fits = []
    for axle, load in ((0, m * g * b / (a + b)), (1, m * g * a / (a + b))):
        one = np.ones_like(alpha)
        fy = np.array(reference.axle_law_forces(axle, load * one, 0.0 * one, alpha, 20.0 * one)[1])  # ISO-W

        def residual(c):
            B, C, D, E = c
            return D * np.sin(C * np.arctan(B * alpha - E * (B * alpha - np.arctan(B * alpha)))) + fy
        fits.append(least_squares(residual, [10.0, 1.3, np.max(np.abs(fy)), 0.0]).x)

    class Bicycle(vehdyn.Model):
        def __init__(self):
            self.declare(states=reference.states, inputs=reference.inputs, outputs=reference.output_signals[:1])

        def symbolic_equations(self, xp, x, u, parameters):
            vx, vy, r, _, _, psi = (x[i] for i in range(6))
            delta, force = u[0], u[3]

            def lateral(c, slip):
                B, C, D, E = c
                return D * ca.sin(C * ca.atan(B * slip - E * (B * slip - ca.atan(B * slip))))

            # SAE axes (y right): a wheel sliding right is pushed left
            vxf = vx * ca.cos(delta) + (vy + a * r) * ca.sin(delta)
            vyf = -vx * ca.sin(delta) + (vy + a * r) * ca.cos(delta)
            ff = -lateral(fits[0], ca.atan(vyf / vxf))
            fr = -lateral(fits[1], ca.atan((vy - b * r) / vx))
            dvx = (force - ff * ca.sin(delta) - drag * vx * vx) / m + vy * r
            dvy = (ff * ca.cos(delta) + fr) / m - vx * r
            dr = (a * ff * ca.cos(delta) - b * fr) / iz
            dX = vx * ca.cos(psi) - vy * ca.sin(psi)
            dY = vx * ca.sin(psi) + vy * ca.cos(psi)
            return [dvx, dvy, dr, dX, dY, r], [(ff + fr) / m], {}

        def rhs(self, t, x, u):
            raise NotImplementedError("symbolic only")

    return Bicycle()


def nmpc(quick):
    import os

    import vehdyn
    from vehdyn.handling import SingleTrack
    from vehdyn.optimal import PathTrackingNMPC
    from vehdyn.procedures import double_lane_change_track

    car = vehdyn.load_vehicle("sedan")
    track = double_lane_change_track(max(car.geometry.front_track, car.geometry.rear_track) + 0.2)
    px, py = track.least_curvature_line(0.15)
    speed, steps, repeats = 20.0, (30 if quick else 120), 3
    plant = SingleTrack(car, tire_lag=False)
    drag = float(plant.parameters.drag_factor) * speed**2
    print(f"\n3. NMPC path tracking, 40 steps of 50 ms, warm start, {steps} steps of the ISO 3888-1 lane change at "
          f"{speed:g} m/s on the single track (plant simulated by RK45 between samples); CPU time "
          f"(time.process_time) of each controller call (the least of {repeats} identical ones), the first "
          f"(cold) left out; load average "
          f"{os.getloadavg()[0]:.1f}")
    models = (("vehdyn SingleTrack (MF 6.1 tires)", plant), ("hand-written CasADi bicycle", hand_bicycle(car)))
    settings = (("exact Hessian", {"hessian": "exact"}), ("Gauss-Newton Hessian", {}),
                ("Gauss-Newton, jit", {"jit": True}))
    for setting, options in settings:
        runs = []  # both controllers step by step in turn (the same load on both), each on its own plant
        for label, model in models:
            controller = PathTrackingNMPC(model, px, py, horizon=40, period=0.05,
                                          inputs={"rear_longitudinal_force": drag}, **options)
            runs.append({"label": label, "controller": controller, "x": plant.straight_running(speed, x=-20.0),
                         "cpu": [], "errors": []})
        for k in range(steps):
            for run in runs:
                controller, x = run["controller"], run["x"]
                feedback = [x[plant.index(n)] for n in controller.input_names]
                before = controller._last, controller._steer, len(controller.log)
                best = np.inf
                for _ in range(repeats):  # the least disturbed of identical solves from the same warm start
                    controller._last, controller._steer = before[:2]
                    del controller.log[before[2]:]
                    start = time.process_time()
                    steer = controller.command(0.05 * k, feedback)
                    best = min(best, time.process_time() - start)
                run["cpu"].append(best)
                u = plant.input_vector(rear_longitudinal_force=drag, front_steer_angle=steer)
                run["x"] = vehdyn.simulate(plant, [0.0, 0.05], dict(zip(plant.input_names, u)), x0=x, method="RK45",
                                           rtol=1e-8).states[:, -1]
                run["errors"].append(abs(run["x"][plant.index("y")] - np.interp(run["x"][plant.index("x")], px, py)))
        for run in runs:
            log, cpu = np.array(run["controller"].log)[1:], np.array(run["cpu"][1:])
            run["median"] = np.median(cpu)
            print(f"   {setting:21s} {run['label']:34s}: per step median {np.median(cpu) * 1e3:6.1f} ms CPU, 90 % "
                  f"{np.percentile(cpu, 90) * 1e3:6.1f} ms, iterations median {np.median(log[:, 3]):.0f}, "
                  f"lateral error largest {max(run['errors']):.4f} m")
        print(f"   {setting:21s} ratio vehdyn / hand-written: {runs[0]['median'] / runs[1]['median']:.2f} (goals: <= "
              f"1.5, and vehdyn <= 20 ms)")

def highest_passing_speed(quick):
    """The highest entry speed at which the NMPC loop and the crossover driver clear ISO 3888-1 (bisection)."""
    import vehdyn
    from vehdyn.driver import CrossoverDriver
    from vehdyn.interconnect import ClosedLoop
    from vehdyn.optimal import PathTrackingNMPC
    from vehdyn.procedures import double_lane_change_track, lane_change_limit, lane_change_outcome

    car = vehdyn.load_vehicle("sedan")
    track = double_lane_change_track(max(car.geometry.front_track, car.geometry.rear_track) + 0.2)
    plant, planner = single_track_pair(car)
    px, py = track.least_curvature_line(0.15)
    paths = {"centre": (track.path_x, track.path_y), "least curvature": (px, py)}
    resolution = 0.5 if quick else 0.25
    print(f"\n4. Highest entry speed clearing the ISO 3888-1 cones, speed held (the single track with tire lag as the "
          f"car), by bisection to {resolution} m/s")
    start = time.process_time()

    def make(speed, line, **tuning):
        return CrossoverDriver.tuned(planner, speed, *paths[line], **tuning)

    tunings = [{"line": line, "preview_time": 1.0, "crossover_frequency": w} for line in paths for w in (2.5, 4.0)]
    crossover = lane_change_limit(plant, track, make, tunings, throttle="hold", speeds=(10.0, 35.0),
                                  resolution=resolution)
    print(f"   crossover driver (best of {len(tunings)} tunings): {crossover['speed']:.2f} m/s "
          f"({crossover['speed'] * 3.6:.1f} km/h), {crossover['runs']} runs, {time.process_time() - start:.0f} s CPU")

    def nmpc_passes(speed):
        drag = float(planner.parameters.drag_factor) * speed**2
        controller = PathTrackingNMPC(planner, px, py, horizon=20, period=0.1, inputs={"rear_longitudinal_force": drag})
        t = np.arange(0.0, 1.05 * (px[-1] - px[0]) / speed, 0.025)  # the cones scored at most 1 m apart
        try:
            result = vehdyn.simulate(ClosedLoop(plant, controller), t, {"rear_longitudinal_force": drag},
                                     x0=plant.straight_running(speed, x=px[0]), method="rk4", substeps=3)
        except vehdyn.SimulationError:  # IPOPT failed (the car beyond recovery) or the run diverged
            return False, None
        outcome = lane_change_outcome(track, result)
        return bool(outcome["passed"]), outcome

    start = time.process_time()
    low, high, runs = crossover["speed"], 35.0, 0
    passed, _ = nmpc_passes(low)
    runs += 1
    if not passed:
        print(f"   NMPC loop: fails already at the crossover driver's limit {low:.2f} m/s")
        return
    while high - low > resolution:
        middle = 0.5 * (low + high)
        passed, _ = nmpc_passes(middle)
        runs += 1
        low, high = (middle, high) if passed else (low, middle)
    print(f"   NMPC loop (single track without lag inside, 20 x 0.1 s, Gauss-Newton, warm start): {low:.2f} m/s "
          f"({low * 3.6:.1f} km/h), {runs} runs, {time.process_time() - start:.0f} s CPU; "
          f"{low - crossover['speed']:+.2f} m/s over the crossover driver (goal: higher)")


def single_track_pair(car):
    from vehdyn.handling import SingleTrack

    return SingleTrack(car), SingleTrack(car, tire_lag=False)


if __name__ == "__main__":
    quick = "--quick" in sys.argv
    rhs_and_jacobian()
    minimum_time(quick)
    nmpc(quick)
    highest_passing_speed(quick)
