"""The compiled chassis loops (numba) against the numpy ones: trajectories within the integrator's error, stopping
distances; ESC and ABS around the full vehicle (compiled). (The laws at random points, the fallback to numpy:
tests/interconnect/test_compiled_loop.py.)"""

import numpy as np
import pytest

import vehdyn
from vehdyn import ParameterError
from vehdyn.chassis import ABS, ESC
from vehdyn.components.tire_setup import friction_ratio
from vehdyn.interconnect import ClosedLoop
from vehdyn.full_vehicle import FullVehicle
from vehdyn.handling import SingleTrack
from vehdyn.procedures import fmvss126
from vehdyn.tire import tire_for_vehicle

pytest.importorskip("numba")

CAR = vehdyn.load_vehicle("sedan")
G = vehdyn.units.GRAVITY
WHEELS = ("front_left", "front_right", "rear_left", "rear_right")


def _friction(mu):
    """The road friction ratio of a road of peak friction ``mu`` (the front tire at its static load)."""
    return friction_ratio(tire_for_vehicle(CAR, "front"), mu, 0.5 * CAR.static_axle_loads()[0])


def _panic(speed, mu, backend, rtol, duration=1.0):
    plant = SingleTrack(CAR, wheel_spin=True, friction=_friction(mu))
    loop = ClosedLoop(plant, ABS(CAR))
    torque = 1.2 * CAR.mass.mass * G * CAR.tires.rolling_radius
    x0 = loop.state_vector(dict(zip(plant.state_names, plant.straight_running(speed))))
    t = np.linspace(0.0, duration, 41)
    return vehdyn.simulate(loop, t, {"front_brake_torque": 0.7 * torque, "rear_brake_torque": 0.3 * torque}, x0=x0,
                           method="RK45", rtol=rtol, atol=rtol * 1e-2, max_step=0.05, backend=backend)


@pytest.mark.compiled_vs_numpy
@pytest.mark.parametrize("mu", [0.9, 0.5, 0.2])
def test_compiled_abs_braking_equals_solve_ivp_within_the_integration_error(mu):
    # The same RK45 with the same step control on the same rhs: where both take the same steps the states agree
    # to rounding; where one accepts a step the other rejects (error norms equal to rounding), they differ by the
    # local error, which the apply/release cycles amplify (measured at rtol 1e-8: up to 6e-8 in speed, 3e-6 in
    # wheel speed, 3e-5 in brake torque, relative to the peak; 1e-6, 3e-4 and 2e-3 at rtol 1e-6 over 1 s).
    runs = {backend: _panic(20.0, mu, backend, 1e-8, duration=0.6) for backend in ("numpy", "compiled")}
    assert "compiled" in runs["compiled"].method_reason and "compiled" not in runs["numpy"].method_reason
    for name, bound in (("longitudinal_velocity", 1e-6), ("x", 1e-6), ("front_wheel_speed", 1e-4),
                        ("front_abs_brake_torque", 1e-3)):
        reference = runs["numpy"][name]
        assert np.max(np.abs(runs["compiled"][name] - reference)) < bound * np.max(np.abs(reference)), name


@pytest.mark.compiled_vs_numpy
def test_compiled_abs_stopping_distance_equals_numpy():
    # the stopping distance (speed below 2 m/s) from 72 km/h on mu 0.5 at a loose tolerance, both backends
    distances = {}
    for backend in ("numpy", "compiled"):
        r = _panic(20.0, 0.5, backend, 1e-4, duration=4.5)
        k = int(np.argmax(r["longitudinal_velocity"] < 2.0))
        assert k > 0
        distances[backend] = np.interp(2.0, r["longitudinal_velocity"][[k, k - 1]], r["x"][[k, k - 1]])
    # friction-limited: v0^2 / (2 mu g) = 40.8 m to rest
    assert 35.0 < distances["compiled"] < 45.0
    assert distances["compiled"] == pytest.approx(distances["numpy"], rel=2e-3)


def test_fullvehicle_with_esc_passes_fmvss126_where_it_fails_alone():
    # 8 A: within the standard's series (up to 6.5 A or 270 deg at the hand wheel, whichever is larger)
    kwargs = dict(plant="full_vehicle", amplitude_multiples=[8.0], directions=("clockwise",))
    alone = fmvss126(CAR, **kwargs)
    assert not alone.passed and alone.runs[0]["yaw_rate_ratio_1000ms"] > 0.35
    with_esc = fmvss126(CAR, ESC(CAR, corners=True), **kwargs)
    run = with_esc.runs[0]
    assert with_esc.passed, with_esc.failures()
    assert run["yaw_rate_ratio_1000ms"] <= 0.35 and run["yaw_rate_ratio_1750ms"] <= 0.20
    assert run["lateral_displacement"] >= 1.83
    # the ESC of the single track's signals cannot drive the full vehicle: the missing inputs are named
    with pytest.raises(ParameterError, match="front_longitudinal_force") as info:
        fmvss126(CAR, ESC(CAR), **kwargs)
    assert "corners=True" in str(info.value)


def test_fmvss126_bad_plant():
    with pytest.raises(ParameterError, match="plant"):
        fmvss126(CAR, plant="bicycle")


def test_esc_on_the_full_vehicle_brakes_the_outer_front_wheel_when_oversteering():
    esc = ESC(CAR, corners=True)
    assert esc.output_names == tuple(f"brake_torque_{w}" for w in WHEELS)
    # turning right faster than the reference: the outer (left) front channel is commanded
    u = esc.input_vector(front_steer_angle=0.01, longitudinal_velocity=20.0, yaw_rate=0.6,
                         brake_torque_rear_right=100.0)
    rates = esc.rhs(0.0, np.zeros(4), u)
    assert rates[0] > 0 and rates[0] > 100 * np.max(np.abs(rates[1:]))
    out = esc.output(0.0, np.array([300.0, 0.0, 0.0, 0.0]), u)
    np.testing.assert_allclose(out, [300.0, 0.0, 0.0, 100.0])  # ESC torque added to the driver's demand


@pytest.mark.parametrize("mu", [0.9, 0.5, 0.2])
def test_abs_on_the_compiled_full_vehicle_holds_slip_on_every_road(mu):
    plant = FullVehicle(CAR, friction=_friction(mu))
    abs_ = ABS(CAR, corners=True)
    loop = ClosedLoop(plant, abs_)
    x0 = plant.trim(20.0)[0]
    torque = 1.2 * CAR.mass.mass * G * CAR.tires.rolling_radius / 2
    demand = {f"brake_torque_{w}": (0.7 if w.startswith("front") else 0.3) * torque for w in WHEELS}
    t = np.linspace(0.0, 1.0, 41)
    r = vehdyn.simulate(loop, t, demand, x0=loop.state_vector(dict(zip(plant.state_names, x0))), method="RK45",
                        rtol=1e-4, atol=1e-6, max_step=0.05)
    assert "compiled" in r.method_reason
    late = r.time >= 0.3
    for c in abs_.channels:
        slip = abs_.braking_slip(r[f"wheel_speed_{c}"], r["longitudinal_velocity"])
        assert np.all(np.isfinite(slip)), c
        assert np.all(slip[late] > 0.5 * abs_.apply_slip) and np.all(slip[late] < abs_.release_slip + 0.05), c
    decel = -np.mean(r["longitudinal_acceleration"][late])
    assert 0.85 * mu * G < decel < 1.05 * mu * G
