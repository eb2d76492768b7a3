"""Compiled against numpy closed loops: ABS, ESC and a driver around them (vehdyn.interconnect.ClosedLoop).

Run: ``python benchmarks/bench_chassis.py [--quick]``. Prints one table from one run on this
machine: per case the wall time of ``simulate(..., backend="numpy")`` (scipy's solve_ivp on the
numpy rhs, one run) and of ``backend="compiled"`` (numba RK45 on the compiled loop, best of N after
a first call that compiles or loads the cache), their ratio, and the difference of a result metric
between the two (the same RK45 and step control on both; where a step is accepted by one and
rejected by the other, the trajectories part by the local error, which the ABS's apply/release
switching amplifies). Cases:

1. ABS panic stop of the sedan's wheel-spin single track from 100 km/h on mu 0.9, 0.5 and 0.2
   (friction=mu / the tire's own peak, by similarity; 1.2 g of brake-torque demand, 70/30),
   for 0.8 v0 / (mu g): metric the distance travelled;
2. ESC around the force-mode single track, FMVSS 126 sine with dwell at 6.5 A, 80 km/h: metric the
   yaw-rate ratio 1.00 s after completion of steer;
3. the same with ESC(corners=True) braking the wheels of the full vehicle (32 states);
4. the preview driver around ABS around the single track: a 1.5 m swerve while braking fully on
   mu 0.5 from 80 km/h (the abs_braking study's steerability run): metric the final lateral position.

RK45, rtol 1e-4 (ABS cases, as the study) or 1e-5 (ESC, as fmvss126), max_step 0.05 / 0.02 s.
"""

from __future__ import annotations

import _timing  # first: pins BLAS to one thread before numpy loads
import platform
import sys
import time

import numpy as np

G = 9.80665


def _road(car, mu):
    """The ``friction`` ratio of a road of peak friction ``mu`` (the front tire at its static load)."""
    from vehdyn.components.tire_setup import friction_ratio
    from vehdyn.tire import tire_for_vehicle

    return friction_ratio(tire_for_vehicle(car, "front"), mu, 0.5 * car.static_axle_loads()[0])


def abs_case(car, mu, speed=100.0 / 3.6):
    import vehdyn
    from vehdyn.chassis import ABS
    from vehdyn.interconnect import ClosedLoop
    from vehdyn.handling import SingleTrack

    plant = SingleTrack(car, wheel_spin=True, friction=_road(car, mu))
    loop = ClosedLoop(plant, ABS(car))
    torque = 1.2 * car.mass.mass * G * car.tires.rolling_radius
    x0 = loop.state_vector(dict(zip(plant.state_names, plant.straight_running(speed))))
    t = np.linspace(0.0, 0.8 * speed / (mu * G), 101)
    inputs = {"front_brake_torque": 0.7 * torque, "rear_brake_torque": 0.3 * torque}

    def run(backend):
        r = vehdyn.simulate(loop, t, inputs, x0=x0, method="RK45", rtol=1e-4, atol=1e-6, max_step=0.05,
                            backend=backend)
        return float(r["x"][-1])
    return f"ABS stop 100 km/h, mu {mu}", "distance [m]", run


def esc_case(car, plant_name):
    import vehdyn
    from vehdyn.chassis import ESC
    from vehdyn.interconnect import ClosedLoop
    from vehdyn.full_vehicle import FullVehicle
    from vehdyn.handling import SingleTrack, steady_state_cornering
    from vehdyn.procedures import sine_with_dwell, sine_with_dwell_metrics

    speed = 80.0 / 3.6
    if plant_name == "single_track":
        plant = SingleTrack(car)
        a = steady_state_cornering(plant, lateral_acceleration=0.3 * G, speed=speed).steer_angle
        x_car = plant.straight_running(speed)
        esc = ESC(car)
    else:
        plant = FullVehicle(car)
        u_turn = plant.trim(speed, lateral_acceleration=0.3 * G)[1]
        a = u_turn[plant.index("front_steer_angle", "inputs")]
        x_car = plant.trim(speed)[0]
        esc = ESC(car, corners=True)
    loop = ClosedLoop(plant, esc)
    steer = sine_with_dwell(6.5 * a)
    t = np.linspace(0.0, steer.completion_of_steer + 2.0, 301)
    x0 = loop.state_vector(dict(zip(plant.state_names, x_car)))

    def run(backend):
        r = vehdyn.simulate(loop, t, {"front_steer_angle": steer}, x0=x0, method="RK45", rtol=1e-5, atol=1e-8,
                            max_step=0.02, backend=backend)
        return float(sine_with_dwell_metrics(r, steer).yaw_rate_ratio_1000ms)
    return f"ESC sine with dwell 6.5 A, {plant_name.replace('_', ' ')}", "yaw ratio 1.00 s [-]", run


def driver_case(car):
    import vehdyn
    from vehdyn.chassis import ABS
    from vehdyn.interconnect import ClosedLoop
    from vehdyn.driver import PreviewDriver
    from vehdyn.handling import SingleTrack

    mu, speed = 0.5, 80.0 / 3.6
    plant = SingleTrack(car, wheel_spin=True, friction=_road(car, mu))
    path_x = np.linspace(-10.0, 200.0, 421)
    length = speed**2 / (2 * mu * G)
    ramp = np.clip((path_x - 2.0) / length, 0.0, 1.0)
    driver = PreviewDriver(path_x, -1.5 * ramp**2 * (3 - 2 * ramp), wheelbase=car.geometry.wheelbase,
                           preview_time=0.6, lag=0.1)
    loop = driver.close(ClosedLoop(plant, ABS(car)))
    x0 = loop.state_vector(dict(zip(plant.state_names, plant.straight_running(speed))))
    t = np.linspace(0.0, 0.9 * speed / (0.7 * mu * G), 300)
    torque = 1.2 * car.mass.mass * G * car.tires.rolling_radius
    inputs = {"front_brake_torque": 0.7 * torque, "rear_brake_torque": 0.3 * torque}

    def run(backend):
        r = vehdyn.simulate(loop, t, inputs, x0=x0, method="RK45", rtol=1e-4, atol=1e-6, max_step=0.05,
                            backend=backend)
        return float(r["y"][-1])
    return "driver + ABS swerve, mu 0.5, 80 km/h", "final y [m]", run


def main(quick: bool = False):
    import vehdyn
    from _timing import best_time

    print(f"vehdyn {vehdyn.__version__}, Python {platform.python_version()}, numpy {np.__version__}, "
          f"{platform.machine()}; wall times from one run, the machine may be shared")
    car = vehdyn.load_vehicle("sedan")
    cases = [abs_case(car, mu) for mu in ((0.5,) if quick else (0.9, 0.5, 0.2))]
    cases += [esc_case(car, "single_track")] + ([] if quick else [esc_case(car, "full_vehicle")])
    cases += [driver_case(car)]
    header = (f"{'case':42s} {'numpy [s]':>10s} {'compiled [s]':>13s} {'ratio':>7s} {'first call [s]':>15s}  "
              f"{'metric':22s} {'numpy':>10s} {'compiled':>10s} {'rel. diff':>9s}")
    print(header)
    print("-" * len(header))
    for label, metric, run in cases:
        start = time.perf_counter()
        compiled_first = run("compiled")
        first = time.perf_counter() - start
        compiled_time, compiled_value = best_time(lambda: run("compiled"), repeats=3 if quick else 5)
        assert compiled_value == compiled_first  # deterministic
        numpy_time, numpy_value = best_time(lambda: run("numpy"), repeats=1)
        diff = abs(compiled_value - numpy_value) / max(abs(numpy_value), 1e-12)
        print(f"{label:42s} {numpy_time:10.3f} {compiled_time:13.4f} {numpy_time / compiled_time:7.0f} {first:15.2f}  "
              f"{metric:22s} {numpy_value:10.5g} {compiled_value:10.5g} {diff:9.1e}", flush=True)


if __name__ == "__main__":
    main(quick="--quick" in sys.argv)
