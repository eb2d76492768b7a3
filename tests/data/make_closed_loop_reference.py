"""Reference trajectories of the driver loops as the OLD code computed them (closed_loop_reference.npz).

Run once on the code of commit 255e4dd (before ``DriverInTheLoop``, ``DrivenVehicle`` and their
compiled twins ``vehdyn/driver/_driver_in_the_loop_numba.py``, ``vehdyn/driver/_driver_numba.py``
were replaced by :class:`vehdyn.interconnect.ClosedLoop` with the drivers as controller models)::

    mkdir /tmp/old && git archive 255e4dd | tar -x -C /tmp/old
    VEHDYN_REFERENCE_COMMIT=255e4dd PYTHONPATH=/tmp/old python tests/data/make_closed_loop_reference.py

It needs the old API and does not run on later commits; ``tests/driver/test_closed_loop_reference.py``
rebuilds the same cases with the new API and compares (see ``closed_loop_reference.md``).

For every case and run -- ``numpy`` (scipy's RK45 on the numpy rhs) and ``compiled`` (the numba
RK45 on the old compiled twin) with the case's step control, ``numpy_fixed`` and
``compiled_fixed`` the same Dormand-Prince pair at a fixed step (``first_step = max_step = h``,
tolerances so loose that no step is rejected: the trajectory is then a smooth function of the
rhs's values, so that a rounding difference in the rhs stays a rounding difference instead of
changing the step sequence) -- the file holds ``<case>/<run>/states`` (n_states x n_t, the
plant's states then the driver's), ``<case>/<run>/steer`` (the road-wheel steer the driver
applies) and ``<case>/<run>/nfev`` (rhs evaluations, steps); ``<case>/time`` and ``<case>/state_names``. The old Padé
realization of the crossover and optimal preview drivers (controllable canonical form) is kept
as ``pade/<delay>/<order>/{A,B,C,D}``, and the old driver-loop margins as ``margins/<case>``
(gain margin, phase margin [rad], crossover and phase-crossover frequencies [rad/s]).
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np

import vehdyn
from vehdyn.chassis import ABS, road_friction_tire
from vehdyn.driver import CrossoverDriver, DriverInTheLoop, OptimalPreviewDriver, PreviewDriver, driver_loop_margins
from vehdyn.driver.base import pade_delay
from vehdyn.full_vehicle import FullVehicle
from vehdyn.handling import SingleTrack
from vehdyn.interconnect import ClosedLoop
from vehdyn.procedures import double_lane_change_track
from vehdyn.tire import tire_for_vehicle

OUT = Path(__file__).with_name("closed_loop_reference.npz")
CAR = vehdyn.load_vehicle("sedan")
G = vehdyn.units.GRAVITY
TRACK = double_lane_change_track(CAR.geometry.front_track + 0.2)
WHEELBASE = CAR.geometry.wheelbase
SPEED = 20.0


def _drag(model, speed):
    return float(np.asarray(model.parameters.drag_factor)) * speed**2


def _swerve():
    path_x = np.linspace(-10.0, 100.0, 221)
    return path_x, -1.5 * np.clip(path_x / 40.0, 0.0, 1.0) ** 2


def _low_mu_plant(mu=0.5):
    loads = CAR.static_axle_loads()
    tires = [road_friction_tire(tire_for_vehicle(CAR, a), mu, 0.5 * w) for a, w in zip(("front", "rear"), loads)]
    return SingleTrack(CAR, *tires, wheel_spin=True)


def cases():
    """{name: (loop, plant, time, inputs, x0, rtol, atol, max_step)} with the old API (the fixed step of
    a case is ``FIXED_STEP`` by its duration)."""
    out = {}
    st = SingleTrack(CAR)
    t = np.linspace(0.0, 4.5, 91)  # through the first lane change
    x0 = np.concatenate([st.straight_running(SPEED, x=float(TRACK.path_x[0])), [0.0]])
    # 1. pure pursuit, speed held by the drag force
    driver = PreviewDriver(TRACK.path_x, TRACK.path_y, preview_time=0.8, lag=0.1)
    out["preview"] = (DriverInTheLoop(st, driver, wheelbase=WHEELBASE), st, t,
                      {"rear_longitudinal_force": _drag(st, SPEED)}, x0, 1e-7, 1e-9, np.inf)
    # 2. pure pursuit with speed control (the driver's rear axle force)
    driver = PreviewDriver(TRACK.path_x, TRACK.path_y, preview_time=0.8, lag=0.1, target_speed=18.0, speed_gain=0.8)
    out["preview_speed"] = (DriverInTheLoop(st, driver, wheelbase=WHEELBASE, mass=CAR.mass.mass), st, t, None, x0,
                            1e-7, 1e-9, np.inf)
    # 3. pure pursuit around ABS around the wheel-spin single track on mu 0.5, braking through a swerve
    plant = _low_mu_plant()
    path_x, path_y = _swerve()
    loop = DriverInTheLoop(ClosedLoop(plant, ABS(CAR)), PreviewDriver(path_x, path_y, preview_time=0.6, lag=0.1),
                           wheelbase=WHEELBASE)
    x0_abs = loop.state_vector(dict(zip(plant.state_names, plant.straight_running(15.0))))
    out["preview_abs"] = (loop, plant, np.linspace(0.0, 0.8, 17),
                          {"front_brake_torque": 3000.0, "rear_brake_torque": 1000.0}, x0_abs, 1e-7, 1e-9, 0.05)
    # 4. pure pursuit around the full vehicle (compiled Magic Formula, 32 states)
    full = FullVehicle(CAR)
    loop = DriverInTheLoop(full, PreviewDriver(path_x, path_y, preview_time=0.8, lag=0.1), wheelbase=WHEELBASE)
    x_full = np.asarray(full.trim(15.0)[0], dtype=float).copy()
    x_full[full.index("x")] = 0.0
    out["preview_full_vehicle"] = (loop, full, np.linspace(0.0, 0.8, 17), None, np.append(x_full, 0.0), 1e-7, 1e-9,
                                   np.inf)
    # 5.-7. crossover (with and without the delay) and optimal preview drivers (DrivenVehicle)
    x0_d = st.straight_running(SPEED, x=float(TRACK.path_x[0]))
    for name, driver in (
            ("crossover", CrossoverDriver(TRACK.path_x, TRACK.path_y, gain=0.04, preview_time=1.0, delay=0.12,
                                          neuromuscular_lag=0.1, pade_order=3)),
            ("crossover_no_delay", CrossoverDriver(TRACK.path_x, TRACK.path_y, gain=0.04, preview_time=1.0, delay=0.0,
                                                   neuromuscular_lag=0.1)),
            ("optimal", OptimalPreviewDriver(TRACK.path_x, TRACK.path_y, vehicle=CAR, speed=SPEED, preview_time=1.0,
                                             delay=0.1, pade_order=4))):
        loop = driver.close(st)
        out[name] = (loop, st, t, {"rear_longitudinal_force": _drag(st, SPEED)},
                     np.concatenate([x0_d, np.zeros(loop.n_states - st.n_states)]), 1e-7, 1e-9, np.inf)
    # 8. optimal preview around ABS (DrivenVehicle of a ClosedLoop), braking through the swerve
    loop = OptimalPreviewDriver(path_x, path_y, vehicle=CAR, speed=15.0, preview_time=0.8, delay=0.1,
                                pade_order=3).close(ClosedLoop(plant, ABS(CAR)))
    x0_o = np.concatenate([x0_abs[:-1], np.zeros(loop.n_states - loop.plant.n_states)])
    out["optimal_abs"] = (loop, plant, np.linspace(0.0, 0.8, 17),
                          {"front_brake_torque": 3000.0, "rear_brake_torque": 1000.0}, x0_o, 1e-7, 1e-9, 0.05)
    return out


def fixed_step(t):
    """The fixed step [s] of a case's ``*_fixed`` runs: 5 ms over the lane change, 1 ms over the short runs."""
    return 5e-3 if t[-1] > 2.0 else 1e-3


def _steer(loop, result):
    if isinstance(loop, DriverInTheLoop):
        return result["driver_steer_angle"]
    return result.states[-1]


def main():
    commit = os.environ.get("VEHDYN_REFERENCE_COMMIT") or subprocess.run(
        ["git", "rev-parse", "HEAD"], capture_output=True, text=True, cwd=Path(vehdyn.__file__).parent).stdout.strip()
    data = {"commit": np.array(commit)}
    for name, (loop, plant, t, inputs, x0, rtol, atol, max_step) in cases().items():
        data[f"{name}/time"] = t
        data[f"{name}/state_names"] = np.array(loop.state_names)
        h = fixed_step(t)
        for run in ("numpy", "compiled", "numpy_fixed", "compiled_fixed"):
            backend = run.split("_")[0]
            options = (dict(rtol=rtol, atol=atol, max_step=max_step) if run == backend else
                       dict(rtol=1e3, atol=1e3, first_step=h, max_step=h))
            r = vehdyn.simulate(loop, t, inputs, x0=x0, method="RK45", backend=backend, **options)
            assert (backend == "compiled") == ("compiled" in r.method_reason), (name, r.method_reason)
            data[f"{name}/{run}/states"] = r.states
            data[f"{name}/{run}/steer"] = np.asarray(_steer(loop, r))
            data[f"{name}/{run}/nfev"] = np.array([r.nfev, r.n_steps])
            error = np.max(np.abs(r.states - data[f"{name}/numpy/states"]), axis=1) / np.maximum(
                np.max(np.abs(data[f"{name}/numpy/states"]), axis=1), 1e-12)
            print(f"{name:22s} {run:15s} n_states {loop.n_states:3d}  y[-1] {r['y'][-1]: .6f}  nfev {r.nfev:6d}  "
                  f"vs numpy {error.max():.1e}  wall {r.wall_time:.2f} s", flush=True)
    for delay in (0.1, 0.12, 0.2):
        for order in (1, 3, 4, 6, 8):
            for key, value in zip("ABCD", pade_delay(delay, order)):
                data[f"pade/{delay}/{order}/{key}"] = value
    st = SingleTrack(CAR)
    path_x = np.linspace(-100.0, 1000.0, 200)
    for name, driver in (
            ("crossover", CrossoverDriver(path_x, 0 * path_x, gain=0.03, preview_time=1.0, delay=0.12)),
            ("optimal", OptimalPreviewDriver(path_x, 0 * path_x, vehicle=CAR, speed=SPEED, delay=0.1))):
        for order in (3, 6):
            m = driver_loop_margins(st, driver, SPEED, pade_order=order)
            data[f"margins/{name}/{order}"] = np.array([m["gain_margin"], m["phase_margin"],
                                                         m["crossover_frequency"], m["phase_crossover_frequency"],
                                                         float(m["stable"])])
    np.savez_compressed(OUT, **data)
    print(f"wrote {OUT} ({OUT.stat().st_size / 1e3:.0f} kB) at {commit}")


if __name__ == "__main__":
    sys.exit(main())
