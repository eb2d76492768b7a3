"""Shared by the driver tests: the loops of tests/data/closed_loop_reference.npz, built with the present API.

The same cases as ``tests/data/make_closed_loop_reference.py`` (which built them with the old
``DriverInTheLoop`` and ``DrivenVehicle`` at commit 255e4dd): the same plants, paths, driver
parameters, initial states, inputs and solver options.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import vehdyn
from vehdyn.chassis import ABS
from vehdyn.driver import CrossoverDriver, OptimalPreviewDriver, PreviewDriver
from vehdyn.full_vehicle import FullVehicle
from vehdyn.handling import SingleTrack
from vehdyn.interconnect import ClosedLoop
from vehdyn.procedures import double_lane_change_track
from vehdyn.tire import MagicFormula, characteristic_values, tire_for_vehicle
from vehdyn.tire.tir import TirParameters

REFERENCE = Path(__file__).parents[1] / "data" / "closed_loop_reference.npz"
CAR = vehdyn.load_vehicle("sedan")
TRACK = double_lane_change_track(CAR.geometry.front_track + 0.2)
WHEELBASE = CAR.geometry.wheelbase
SPEED = 20.0
NAMES = ("preview", "preview_speed", "preview_abs", "preview_full_vehicle", "crossover", "crossover_no_delay",
         "optimal", "optimal_abs")


def _drag(model, speed):
    return float(np.asarray(model.parameters.drag_factor)) * speed**2


def _swerve():
    path_x = np.linspace(-10.0, 100.0, 221)
    return path_x, -1.5 * np.clip(path_x / 40.0, 0.0, 1.0) ** 2


def _scaled_friction_tire(tire, mu, load):
    """The reference's low-friction tire: ``tire`` with LMUX, LMUY scaled so that its peaks at ``load`` are ``mu``.

    This is how the old ``chassis.road_friction_tire`` put a tire on a wet road when the reference was
    made (Pacejka 2012, sec. 4.3.2); the models' ``friction=`` argument (similarity, one ratio for
    the road) is a different law, so the reference cases keep the plant they were made with.
    """
    peaks = characteristic_values(tire, [float(load)]).iloc[0]
    ratios = {"LMUX": mu / float(peaks["peak_longitudinal_friction"]),
              "LMUY": mu / float(peaks["peak_lateral_friction"])}
    sections = {name: dict(entries) for name, entries in tire.params.sections.items()}
    for key, ratio in ratios.items():
        where = next(s for s, kv in sections.items() if key in {k.upper() for k in kv})
        written = next(k for k in sections[where] if k.upper() == key)
        sections[where][written] = float(sections[where][written]) * ratio
    return MagicFormula(TirParameters(sections, tables=dict(tire.params.tables), path=tire.params.path))


def _low_mu_plant(mu=0.5):
    loads = CAR.static_axle_loads()
    tires = [_scaled_friction_tire(tire_for_vehicle(CAR, a), mu, 0.5 * w) for a, w in zip(("front", "rear"), loads)]
    return SingleTrack(CAR, *tires, wheel_spin=True)


def fixed_step(t):
    """The fixed step [s] of a case's ``*_fixed`` runs (as the script that made the reference)."""
    return 5e-3 if t[-1] > 2.0 else 1e-3


def build_case(name):
    """(loop, driver, time, inputs, x0, options) of the reference case ``name``."""
    st = SingleTrack(CAR)
    t = np.linspace(0.0, 4.5, 91)
    straight = st.straight_running(SPEED, x=float(TRACK.path_x[0]))
    dlc = dict(method="RK45", rtol=1e-7, atol=1e-9)
    short = dict(method="RK45", rtol=1e-7, atol=1e-9, max_step=0.05)
    braking = {"front_brake_torque": 3000.0, "rear_brake_torque": 1000.0}
    path_x, path_y = _swerve()
    if name in ("preview", "preview_speed"):
        speed = dict(target_speed=18.0, speed_gain=0.8, mass=CAR.mass.mass) if name == "preview_speed" else {}
        driver = PreviewDriver(TRACK.path_x, TRACK.path_y, wheelbase=WHEELBASE, preview_time=0.8, lag=0.1, **speed)
        inputs = None if speed else {"rear_longitudinal_force": _drag(st, SPEED)}
        return driver.close(st), driver, t, inputs, np.append(straight, 0.0), dlc
    if name in ("preview_abs", "optimal_abs"):
        plant = _low_mu_plant()
        if name == "preview_abs":
            driver = PreviewDriver(path_x, path_y, wheelbase=WHEELBASE, preview_time=0.6, lag=0.1)
        else:
            driver = OptimalPreviewDriver(path_x, path_y, vehicle=CAR, speed=15.0, preview_time=0.8, delay=0.1,
                                          pade_order=3)
        loop = driver.close(ClosedLoop(plant, ABS(CAR)))
        x0 = loop.state_vector(dict(zip(plant.state_names, plant.straight_running(15.0))))
        return loop, driver, np.linspace(0.0, 0.8, 17), braking, x0, short
    if name == "preview_full_vehicle":
        # the reference loops were recorded with the unsprung masses' lateral inertia through the
        # springs: lambda = 0 (parallel links) is that model exactly with the roll centres on the
        # ground (issue 28; the default since is lambda = 1, the textbook's)
        full = FullVehicle(CAR.replace(suspension__front_unsprung_transfer_fraction=0.0,
                                       suspension__rear_unsprung_transfer_fraction=0.0))
        driver = PreviewDriver(path_x, path_y, wheelbase=WHEELBASE, preview_time=0.8, lag=0.1)
        x_full = np.asarray(full.trim(15.0)[0], dtype=float).copy()
        x_full[full.index("x")] = 0.0
        return (driver.close(full), driver, np.linspace(0.0, 0.8, 17), None, np.append(x_full, 0.0),
                dict(method="RK45", rtol=1e-7, atol=1e-9))
    if name == "crossover":
        driver = CrossoverDriver(TRACK.path_x, TRACK.path_y, gain=0.04, preview_time=1.0, delay=0.12,
                                 neuromuscular_lag=0.1, pade_order=3)
    elif name == "crossover_no_delay":
        driver = CrossoverDriver(TRACK.path_x, TRACK.path_y, gain=0.04, preview_time=1.0, delay=0.0,
                                 neuromuscular_lag=0.1)
    else:
        driver = OptimalPreviewDriver(TRACK.path_x, TRACK.path_y, vehicle=CAR, speed=SPEED, preview_time=1.0,
                                      delay=0.1, pade_order=4)
    loop = driver.close(st)
    x0 = np.concatenate([straight, np.zeros(loop.n_states - st.n_states)])
    return loop, driver, t, {"rear_longitudinal_force": _drag(st, SPEED)}, x0, dlc


@pytest.fixture(scope="session")
def reference():
    """The stored trajectories of the old driver loops (a mapping of arrays)."""
    with np.load(REFERENCE) as data:
        return dict(data)


@pytest.fixture(scope="session")
def closed_loop_case():
    """``closed_loop_case(name)`` -> (loop, driver, time, inputs, x0, options)."""
    return build_case
