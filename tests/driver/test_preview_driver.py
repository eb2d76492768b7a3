"""The preview driver (pure pursuit with a lag, speed control) in closed loops: settling, the ISO 3888-1 lane
change, its speed law's feedthrough from a plant state."""

import numpy as np
import pytest

import vehdyn
from vehdyn.driver import PreviewDriver
from vehdyn.handling import SingleTrack
from vehdyn.procedures import double_lane_change_track, lane_change_outcome
from vehdyn.tire import FialaTire

SEDAN = vehdyn.load_vehicle("sedan")


def fiala_model(**kwargs):
    return SingleTrack(SEDAN, FialaTire.from_vehicle(SEDAN, "front"), FialaTire.from_vehicle(SEDAN, "rear"), **kwargs)


def test_preview_driver_settles_on_an_offset_straight_path_at_its_speed():
    model = fiala_model(tire_lag=False)
    x = np.linspace(-50, 500, 200)
    driver = PreviewDriver(x, np.full_like(x, 2.0), wheelbase=SEDAN.wheelbase, preview_time=1.0, lag=0.1,
                           target_speed=15.0, mass=SEDAN.mass.mass)
    loop = driver.close(model)
    t = np.linspace(0, 15, 151)
    x0 = np.concatenate([model.straight_running(15.0), [0.0]])
    r = vehdyn.simulate(loop, t, None, x0=x0, method="RK45", rtol=1e-6)
    assert r["y"][-1] == pytest.approx(2.0, abs=0.02)
    assert r["yaw_angle"][-1] == pytest.approx(0.0, abs=1e-3)
    assert r["longitudinal_velocity"][-1] == pytest.approx(15.0, rel=1e-2)
    # the speed law's force balances the drag at the end: m k_u (u_target - u) = F_drag(u)
    u = r["longitudinal_velocity"][-1]
    force = r["rear_longitudinal_force_after_preview_driver"]
    assert force[-1] == pytest.approx(SEDAN.mass.mass * 1.0 * (15.0 - u), rel=1e-12)
    assert force[-1] == pytest.approx(float(model.parameters.drag_factor) * u**2, rel=0.05)


def test_double_lane_change_passes_slowly():
    model = fiala_model(tire_lag=False)
    track = double_lane_change_track(1.61)
    driver = PreviewDriver(track.path_x, track.path_y, wheelbase=SEDAN.wheelbase, preview_time=0.8, lag=0.1,
                           target_speed=12.0, mass=SEDAN.mass.mass)
    loop = driver.close(model)
    t = np.linspace(0, 150 / 12.0, 301)
    r = vehdyn.simulate(loop, t, None, x0=np.concatenate([model.straight_running(12.0, x=-30.0), [0.0]]),
                        method="RK45", rtol=1e-6)
    outcome = lane_change_outcome(track, r)
    assert outcome["passed"], outcome


def test_speed_law_is_feedthrough_from_a_plant_state_and_linearizes_as_such():
    # F = m k_u (u_target - u) reads the plant's state u at the same instant: the closed loop's Jacobian
    # entry d(du/dt)/du changes by -m k_u times the plant's d(du/dt)/dF_x,rear
    model = fiala_model(tire_lag=False)
    x = np.linspace(-50, 500, 200)
    common = dict(wheelbase=SEDAN.wheelbase, preview_time=1.0, lag=0.1)
    held = PreviewDriver(x, 0 * x, **common).close(model)
    speed = PreviewDriver(x, 0 * x, target_speed=15.0, speed_gain=0.7, mass=SEDAN.mass.mass, **common).close(model)
    assert "rear_longitudinal_force" in held.input_names and "rear_longitudinal_force" not in speed.input_names
    x0 = np.concatenate([model.straight_running(15.0), [0.0]])
    iu = model.index("longitudinal_velocity")
    a_held = held.linearize(x0).A[iu, iu]
    a_speed = speed.linearize(x0).A[iu, iu]
    plant = model.linearize(model.straight_running(15.0)).B[iu, model.index("rear_longitudinal_force", "inputs")]
    assert a_speed - a_held == pytest.approx(-SEDAN.mass.mass * 0.7 * plant, rel=1e-6)
