"""Nonlinear articulated single track: its linearization, the kinematic trailer, snaking, hard cases, bad input."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.signal import find_peaks

import vehdyn
from vehdyn import ParameterError
from vehdyn.handling import ArticulatedSingleTrack, LinearCarTrailer
from vehdyn.tire import LinearTire

COMPACT = vehdyn.load_vehicle("compact")
CARAVAN = vehdyn.load_trailer("caravan")
TRACTOR = vehdyn.load_vehicle("tractor")
SEMITRAILER = vehdyn.load_trailer("semitrailer")


def finite(result):
    return np.all(np.isfinite(result.states)) and np.all(np.isfinite(result.outputs))


def linear_tires(vehicle, trailer):
    return (LinearTire(cornering_stiffness=vehicle.tires.front_cornering_stiffness / 2),
            LinearTire(cornering_stiffness=vehicle.tires.rear_cornering_stiffness / 2),
            LinearTire(cornering_stiffness=trailer.cornering_stiffness / 2))


@pytest.mark.parametrize("vehicle, trailer", [(COMPACT, CARAVAN), (TRACTOR, SEMITRAILER),
                                              (TRACTOR, SEMITRAILER.replace(hitch_behind_rear_axle=-0.4))],
                         ids=["compact_caravan", "tractor_semitrailer", "fifth_wheel_ahead_of_the_axle"])
def test_linearization_equals_linear_car_trailer(vehicle, trailer):
    # constant speed without longitudinal force: no drag (LinearCarTrailer's assumption)
    vehicle = vehicle.replace(aero__drag_coefficient=0.0)
    model = ArticulatedSingleTrack(vehicle, trailer, *linear_tires(vehicle, trailer), tire_lag=False)
    for speed in (4.0, 22.0):
        block, ref = model.lateral_yaw(speed), LinearCarTrailer(vehicle, trailer, speed)
        assert block.state_names == ref.state_names and block.output_names == ref.output_names
        for mine, theirs in ((block.A, ref.A), (block.B, ref.B), (block.C, ref.C), (block.D, ref.D)):
            np.testing.assert_allclose(mine, theirs, rtol=1e-6, atol=1e-6 * np.abs(theirs).max())


def test_linearized_wind_equals_linear_car_trailer_wind_input():
    vehicle = COMPACT.replace(aero__drag_coefficient=0.0)
    assert CARAVAN.frontal_area > 0 and CARAVAN.side_force_coefficient_slope > 0
    model = ArticulatedSingleTrack(vehicle, CARAVAN, *linear_tires(vehicle, CARAVAN), tire_lag=False)
    for speed in (8.0, 25.0):
        block = model.lateral_yaw(speed, crosswind=True)
        ref = LinearCarTrailer(vehicle, CARAVAN, speed, crosswind=True)
        assert block.input_names == ref.input_names == ("front_steer_angle", "wind_velocity_lateral")
        for mine, theirs in ((block.B, ref.B), (block.D, ref.D)):
            np.testing.assert_allclose(mine, theirs, rtol=1e-6, atol=1e-6 * np.abs(theirs).max())


def test_nonlinear_wind_force_on_each_body_is_the_crosswind_law():
    """At rest in the wind's first instant (x'' from forces alone): the hitch carries what Newton says."""
    from vehdyn.components.aero import aero_side_force, trailer_wind_side_force_factor, wind_side_force_factor

    u, w = 20.0, 15.0
    model = ArticulatedSingleTrack(COMPACT.replace(aero__drag_coefficient=0.0), CARAVAN, tire_lag=False)
    x0 = model.straight_running(u)
    calm, windy = model.input_vector(), model.input_vector({"wind_velocity_lateral": w})
    ext = model.input_vector({"external_lateral_force": aero_side_force(np, wind_side_force_factor(COMPACT), u, w),
                              "external_yaw_moment": model.tractor.parameters.centre_of_pressure
                              * aero_side_force(np, wind_side_force_factor(COMPACT), u, w)})
    ft = aero_side_force(np, trailer_wind_side_force_factor(CARAVAN, COMPACT.aero.air_density), u, w)
    ext[model.index("trailer_external_lateral_force", "inputs")] = ft
    ext[model.index("trailer_external_yaw_moment", "inputs")] = -(CARAVAN.centre_of_pressure_behind_hitch
                                                                  - CARAVAN.hitch_to_cg) * ft
    # the wind input acts exactly as the same forces put in through the external-force inputs
    np.testing.assert_allclose(model.rhs(0.0, x0, windy), model.rhs(0.0, x0, ext), rtol=1e-12, atol=1e-12)
    assert not np.allclose(model.rhs(0.0, x0, windy), model.rhs(0.0, x0, calm))


def test_small_wind_zone_response_equals_the_linear_combination():
    """crosswind_sensitivity drives the nonlinear combination; a 0.5 m/s zone stays in the linear range."""
    from vehdyn.procedures import crosswind_sensitivity
    from vehdyn.procedures import wind_zone_signal

    vehicle = COMPACT.replace(aero__drag_coefficient=0.0)
    model = ArticulatedSingleTrack(vehicle, CARAVAN, *linear_tires(vehicle, CARAVAN), tire_lag=False)
    u, w, length = 22.0, 0.5, 30.0
    m = crosswind_sensitivity(vehicle, u, wind_speed=w, wind_length=length, duration=3.0, model=model, rtol=1e-9)
    res = m.result
    linear = LinearCarTrailer(vehicle, CARAVAN, u, crosswind=True)
    zone = wind_zone_signal(u, w, length, vehicle.wheelbase)
    ref = vehdyn.simulate(linear, res.time, {"wind_velocity_lateral": zone}, rtol=1e-10, atol=1e-12)
    for name in ("yaw_rate", "articulation_angle", "lateral_acceleration"):
        peak = np.max(np.abs(ref[name]))
        assert np.max(np.abs(res[name] - ref[name])) < 2e-3 * peak, name  # 3e-4 measured (w^2 terms)
    # the caravan turns the compact into the wind (its hitch share acts behind the neutral steer point)
    assert m.peak_yaw_rate < 0 and LinearCarTrailer(vehicle, CARAVAN, u, crosswind=True).dc_gain()[
        linear.index("yaw_rate", "outputs"), 1] < 0


def test_low_speed_articulation_follows_the_kinematic_trailer():
    # hitch over the rear axle: d(theta)/dt = v (tan(delta) / L - sin(theta) / l_t) (theta = car - trailer yaw)
    trailer = CARAVAN.replace(hitch_behind_rear_axle=0.0)
    model = ArticulatedSingleTrack(COMPACT, trailer)
    L, lt, v0 = COMPACT.wheelbase, trailer.hitch_to_axle, 1.0
    t = np.linspace(0.0, 60.0, 1201)

    def steer(time):
        return 0.25 * np.clip(time * v0 / 8.0, 0.0, 1.0)  # ramp over 8 m, then a tight circle

    r = vehdyn.simulate(model, t, {"front_steer_angle": steer(t)}, x0=model.straight_running(v0), method="LSODA",
                        rtol=1e-8, atol=1e-10)
    assert finite(r)
    u = r["longitudinal_velocity"]
    kin = solve_ivp(lambda s, y: [np.interp(s, t, u) * (np.tan(steer(s)) / L - np.sin(y[0]) / lt)], (0, t[-1]), [0.0],
                    t_eval=t, rtol=1e-10, atol=1e-12, max_step=0.05).y[0]
    assert np.max(np.abs(r["articulation_angle"] - kin)) < 0.01 * np.max(np.abs(kin))
    # and the steady state is the kinematic one, sin(theta) = l_t tan(delta) / L
    assert r["articulation_angle"][-1] == pytest.approx(np.arcsin(lt * np.tan(0.25) / L), rel=0.01)


def test_standstill_start_and_stop_stay_finite_and_at_rest():
    model = ArticulatedSingleTrack(COMPACT, CARAVAN)
    t = np.linspace(0.0, 12.0, 601)
    drive = np.where(t < 4.0, 2500.0, 0.0)
    brake = np.where(t > 6.0, -1e5, 0.0)  # beyond mu F_z: the axles lock (an unbraked caravan would roll on)
    r = vehdyn.simulate(model, t, {"front_steer_angle": 0.1 * np.sin(t), "front_longitudinal_force": brake,
                                   "trailer_longitudinal_force": brake, "rear_longitudinal_force": drive},
                        x0=model.straight_running(0.0), method="LSODA", rtol=1e-6, atol=1e-8)
    assert finite(r)
    # a pull of 2500 N for 4 s accelerates both bodies: (m + m_t) a_x = F (no drag at these speeds to speak of)
    u4 = np.interp(4.0, t, r["longitudinal_velocity"])
    assert u4 == pytest.approx(2500.0 * 4.0 / (COMPACT.mass.mass + CARAVAN.mass), rel=0.03)
    # the hitch pulls the trailer along: -m_t a_x on the car
    k = np.searchsorted(t, 2.0)
    ax = r["longitudinal_acceleration"][k]
    assert r["hitch_longitudinal_force"][k] == pytest.approx(-CARAVAN.mass * ax, rel=0.05)
    # the locked axle's demand outlives the motion: the combination stops and stays (no backward push)
    assert np.all(np.abs(r["longitudinal_velocity"][t > 9.0]) < 0.02)
    assert np.ptp(r["x"][t > 9.5]) < 0.01
    # parked: nothing moves
    rest = vehdyn.simulate(model, np.linspace(0, 5, 51), None, x0=model.straight_running(0.0), method="LSODA")
    assert np.max(np.abs(rest.states)) < 1e-9


def test_batch_rhs_equals_point_by_point():
    model = ArticulatedSingleTrack(COMPACT, CARAVAN)
    rng = np.random.default_rng(4)
    x = model.straight_running(15.0)[:, None] + rng.normal(0.0, 0.2, (model.n_states, 5))
    x[model.index("articulation_angle")] = np.linspace(-1.5, 1.5, 5)
    x[model.index("front_lateral_deflection"):] *= 0.05
    u = np.zeros((model.n_inputs, 5))
    u[model.index("front_steer_angle", "inputs")] = np.linspace(-0.2, 0.2, 5)
    batch = model.rhs(0.0, x, u)
    for j in range(5):
        np.testing.assert_allclose(batch[:, j], model.rhs(0.0, x[:, j], u[:, j]), rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("factor", [0.9, 1.1])
def test_snaking_above_critical_speed_grows_at_the_eigenvalue_rate(factor):
    vehicle = COMPACT.replace(aero__drag_coefficient=0.0)
    linear = LinearCarTrailer(vehicle, CARAVAN, 20.0)
    speed = factor * linear.critical_speed()
    model = ArticulatedSingleTrack(vehicle, CARAVAN, *linear_tires(vehicle, CARAVAN), tire_lag=False)
    t = np.linspace(0.0, 25.0, 2501)
    r = vehdyn.simulate(model, t, None, x0=model.straight_running(speed, articulation_rate=0.01), method="LSODA",
                        rtol=1e-9, atol=1e-12)
    assert finite(r)
    theta = r["articulation_angle"]
    peaks, _ = find_peaks(np.abs(theta))
    peaks = peaks[t[peaks] > 3.0]  # after the car's own, faster modes have died away
    rate = np.polyfit(t[peaks], np.log(np.abs(theta[peaks])), 1)[0]
    expected = linear.snaking_mode(speed).eigenvalue.real
    assert np.sign(rate) == np.sign(factor - 1.0)
    assert rate == pytest.approx(expected, rel=0.05, abs=0.005)


def test_jackknife_after_locking_the_tractor_drive_axle_in_a_curve():
    model = ArticulatedSingleTrack(TRACTOR, SEMITRAILER)
    t = np.linspace(0.0, 5.0, 501)
    steer = np.minimum(t / 0.5, 1.0) * 0.02
    locked = np.where(t > 1.0, -1e6, 0.0)
    r = vehdyn.simulate(model, t, {"front_steer_angle": steer, "rear_longitudinal_force": locked},
                        x0=model.straight_running(20.0), method="LSODA", rtol=1e-6, atol=1e-8)
    assert finite(r)
    event = model.articulation_event(r)
    assert event is not None and event.kind == "jackknife" and 1.0 < event.time < 4.0
    # the locked axle slides at its friction limit: |F| = mu F_z (while sliding fast)
    sliding = (t > 1.2) & (t < event.time)
    force = np.hypot(r["rear_longitudinal_force"], r["rear_lateral_force"])[sliding]
    limit = TRACTOR.tires.friction_coefficient * r["rear_normal_load"][sliding]
    np.testing.assert_allclose(force, limit, rtol=2e-3)
    # control run: the same curve without the lock keeps the combination in line
    free = vehdyn.simulate(model, t, {"front_steer_angle": steer}, x0=model.straight_running(20.0), method="LSODA",
                           rtol=1e-6, atol=1e-8)
    assert model.articulation_event(free) is None


def test_trailer_swing_after_locking_the_trailer_axle_in_a_curve():
    model = ArticulatedSingleTrack(TRACTOR, SEMITRAILER)
    t = np.linspace(0.0, 6.0, 601)
    steer = np.minimum(t / 0.5, 1.0) * 0.05
    r = vehdyn.simulate(model, t, {"front_steer_angle": steer, "trailer_longitudinal_force": np.where(t > 1, -1e6, 0)},
                        x0=model.straight_running(25.0), method="LSODA", rtol=1e-6, atol=1e-8)
    assert finite(r)
    event = model.articulation_event(r, threshold=np.radians(20.0))
    assert event is not None and event.kind == "trailer_swing" and event.time > 1.0
    assert event.articulation_angle < 0  # the trailer's tail slides out of the (right-hand) curve
    free = vehdyn.simulate(model, t, {"front_steer_angle": steer}, x0=model.straight_running(25.0), method="LSODA",
                           rtol=1e-6, atol=1e-8)
    assert model.articulation_event(free, threshold=np.radians(20.0)) is None


def test_bad_input_names_the_parameter():
    with pytest.raises(ParameterError) as err:
        ArticulatedSingleTrack(COMPACT, "caravan")
    assert err.value.key == "trailer"
    with pytest.raises(ParameterError) as err:
        ArticulatedSingleTrack(COMPACT, CARAVAN.replace(hitch_behind_rear_axle=-4.0))
    assert err.value.key == "hitch_behind_rear_axle"
    with pytest.raises(ParameterError) as err:
        ArticulatedSingleTrack(COMPACT, CARAVAN.replace(relaxation_length=0.0))
    assert err.value.key == "relaxation_length"
    with pytest.raises(ParameterError) as err:
        ArticulatedSingleTrack(COMPACT, CARAVAN, trailer_tire="fiala")
    assert err.value.key == "trailer_tire"


@pytest.mark.parametrize("name", ["external_lateral_force", "trailer_external_lateral_force"])
def test_external_side_force_accelerates_the_combination_by_newton(name):
    # tires relaxed and straight running: the only lateral force is the external one, so the
    # lateral momentum of both bodies changes at its rate, m a_1y + m_t a_ty = F (theta = 0)
    model = ArticulatedSingleTrack(COMPACT, CARAVAN)
    y = model.output(0.0, model.straight_running(20.0), model.input_vector({name: 1000.0}))
    out = dict(zip(model.output_names, y))
    momentum_rate = COMPACT.mass.mass * out["lateral_acceleration"] + CARAVAN.mass * out["trailer_lateral_acceleration"]
    assert momentum_rate == pytest.approx(1000.0, rel=1e-12)
    # and the hitch carries what the trailer needs: m_t a_ty = F_t - H_y
    applied = 1000.0 if name.startswith("trailer") else 0.0
    assert out["hitch_lateral_force"] == pytest.approx(applied - CARAVAN.mass * out["trailer_lateral_acceleration"],
                                                       rel=1e-12, abs=1e-9)
