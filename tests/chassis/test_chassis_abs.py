"""ABS and traction control on the wheel-spin single track: slip held near target on every road, friction-limited
deceleration; locked wheels without ABS; gain errors (the road's friction: tests/components)."""

import numpy as np
import pytest

import vehdyn
from vehdyn import ParameterError
from vehdyn.chassis import ABS, TractionControl
from vehdyn.components.tire_setup import friction_ratio
from vehdyn.interconnect import ClosedLoop
from vehdyn.handling import SingleTrack
from vehdyn.tire import tire_for_vehicle

CAR = vehdyn.load_vehicle("sedan")
G = vehdyn.units.GRAVITY


def _plant(mu):
    ratio = friction_ratio(tire_for_vehicle(CAR, "front"), mu, 0.5 * CAR.static_axle_loads()[0])
    return SingleTrack(CAR, wheel_spin=True, friction=ratio)


def _brake(model, plant, speed, duration):
    demand = 1.2 * CAR.mass.mass * G * CAR.tires.rolling_radius  # panic: more than any road can take
    x0 = model.state_vector(dict(zip(plant.state_names, plant.straight_running(speed))))
    t = np.linspace(0.0, duration, 41)
    return vehdyn.simulate(model, t, {"front_brake_torque": 0.7 * demand, "rear_brake_torque": 0.3 * demand}, x0=x0,
                           method="RK45", rtol=1e-4, atol=1e-6, max_step=0.05)


@pytest.mark.parametrize("mu", [0.9, 0.5, 0.2])
def test_abs_holds_slip_near_target_and_decelerates_at_the_friction_limit(mu):
    plant = _plant(mu)
    abs_ = ABS(CAR)
    r = _brake(ClosedLoop(plant, abs_), plant, 20.0, 0.8)
    late = r.time >= 0.3
    for axle in ("front", "rear"):
        slip = abs_.braking_slip(r[f"{axle}_wheel_speed"], r["longitudinal_velocity"])
        assert np.all(np.isfinite(slip))
        # held inside the apply/release band (with the overshoot of a 0.02 s release lag)
        assert np.all(slip[late] > 0.5 * abs_.apply_slip) and np.all(slip[late] < abs_.release_slip + 0.05)
    # the whole car brakes near mu g (friction limit; aerodynamic drag adds under 1 %)
    decel = -np.mean(r["longitudinal_acceleration"][late])
    assert 0.85 * mu * G < decel < 1.05 * mu * G


def test_without_abs_the_wheels_lock():
    plant = _plant(0.5)
    r = _brake(plant, plant, 20.0, 0.8)
    assert r["front_wheel_speed"][-1] * CAR.tires.rolling_radius < 0.05 * r["longitudinal_velocity"][-1]


def test_traction_control_limits_spin_on_low_friction():
    plant = _plant(0.3)
    tc = TractionControl(CAR)
    assert tc.axles == ("rear",) if CAR.driveline.front_drive_fraction == 0 else True
    axle = tc.axles[0]
    torque = 0.8 * CAR.mass.mass * G * CAR.tires.rolling_radius  # far beyond 0.3 g
    t = np.linspace(0.0, 1.0, 41)
    runs = {}
    for name, model in (("open", plant), ("tc", ClosedLoop(plant, tc))):
        x0 = model.state_vector(dict(zip(plant.state_names, plant.straight_running(5.0))))
        runs[name] = vehdyn.simulate(model, t, {f"{axle}_drive_torque": torque}, x0=x0, method="RK45", rtol=1e-4,
                                     atol=1e-6, max_step=0.05)
    spin = {k: tc.drive_slip(r[f"{axle}_wheel_speed"], r["longitudinal_velocity"])[-1] for k, r in runs.items()}
    assert spin["open"] > 1.0 and 0.0 < spin["tc"] < tc.brake_slip + 0.05
    # more acceleration with the slip held near the peak than with the wheel spinning
    assert runs["tc"]["longitudinal_velocity"][-1] > runs["open"]["longitudinal_velocity"][-1]


@pytest.mark.parametrize("kwargs, key", [
    ({"apply_slip": -0.05}, "apply_slip"), ({"release_slip": float("nan")}, "release_slip"),
    ({"apply_time_constant": 0.0}, "apply_time_constant"), ({"release_slip": 0.03}, "release_slip"),
    ({"axles": ("middle",)}, "axles"),
])
def test_abs_bad_gains(kwargs, key):
    with pytest.raises(ParameterError, match=key):
        ABS(CAR, **kwargs)


@pytest.mark.parametrize("kwargs, key", [
    ({"target_slip": -0.1}, "target_slip"), ({"brake_gain": float("inf")}, "brake_gain"),
    ({"maximum_reduction": 1.5}, "maximum_reduction"), ({"brake_slip": 0.05}, "brake_slip"),
])
def test_traction_control_bad_gains(kwargs, key):
    with pytest.raises(ParameterError, match=key):
        TractionControl(CAR, **kwargs)


def test_traction_control_launch_on_split_mu_full_vehicle():
    from vehdyn.full_vehicle import FullVehicle

    def split(X, Y):  # ice (0.2) under the left wheels (SAE y < 0), dry (1.0) under the right
        return np.where(np.asarray(Y) < 0, 0.2, 1.0) * np.ones_like(np.asarray(X, dtype=float))

    plant = FullVehicle(CAR, friction=split)
    x0, u0 = plant.trim(3.0)
    tc = TractionControl(CAR, corners=True)
    assert tc.channels == ("rear_left", "rear_right")
    demand = {**dict(zip(plant.input_names, u0)), "drive_torque_rear_left": 750.0, "drive_torque_rear_right": 750.0}
    t = np.linspace(0.0, 1.0, 21)
    runs = {}
    for name, model in (("open", plant), ("tc", ClosedLoop(plant, tc))):
        runs[name] = vehdyn.simulate(model, t, demand, x0=model.state_vector(dict(zip(plant.state_names, x0))),
                                     method="RK45", rtol=1e-4, atol=1e-6, max_step=0.05)
    slip = {k: tc.drive_slip(r["wheel_speed_rear_left"], r["longitudinal_velocity"])[-1] for k, r in runs.items()}
    assert slip["open"] > 2.0  # the wheel on ice spins up
    assert 0.0 < slip["tc"] < tc.brake_slip + 0.05  # held near the brake threshold by braking that wheel
    assert np.max(runs["tc"]["brake_torque_rear_left_after_traction_control"]) > 100.0
    # the one-sided drive force yaws the open car towards the ice; traction control keeps it straight
    assert abs(runs["tc"]["yaw_angle"][-1]) < 0.3 * abs(runs["open"]["yaw_angle"][-1])
    assert runs["tc"]["longitudinal_velocity"][-1] > 3.5


def test_abs_per_wheel_on_the_full_vehicle():
    from vehdyn.full_vehicle import FullVehicle

    plant = FullVehicle(CAR, friction=lambda X, Y: 0.5 * np.ones_like(np.asarray(X, dtype=float)))
    x0, u0 = plant.trim(20.0)
    abs_ = ABS(CAR, corners=True)
    torque = 1.2 * CAR.mass.mass * G * CAR.tires.rolling_radius / 2
    demand = dict(zip(plant.input_names, u0)) | {f"brake_torque_front_{s}": 0.7 * torque for s in ("left", "right")} \
        | {f"brake_torque_rear_{s}": 0.3 * torque for s in ("left", "right")}
    loop = ClosedLoop(plant, abs_)
    t = np.linspace(0.0, 0.6, 25)
    r = vehdyn.simulate(loop, t, demand, x0=loop.state_vector(dict(zip(plant.state_names, x0))), method="RK45",
                        rtol=1e-4, atol=1e-6, max_step=0.05)
    late = r.time >= 0.3
    for c in abs_.channels:
        slip = abs_.braking_slip(r[f"wheel_speed_{c}"], r["longitudinal_velocity"])
        assert np.all(np.isfinite(slip)) and np.all(slip[late] < abs_.release_slip + 0.05), c
        assert np.all(slip[late] > 0.5 * abs_.apply_slip), c
    decel = -np.mean(r["longitudinal_acceleration"][late])
    # road friction 0.5 relative to the tire's own: below 0.5 times the tire's peak friction
    assert 0.3 * G < decel < 0.65 * G
