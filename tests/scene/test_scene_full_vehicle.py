"""FullVehicle on the fidelity ladder: registered, the top rung, the only one for combined scenes.

The scenes that run the full vehicle are short: its compiled right-hand side (``backend="auto"``)
takes milliseconds per simulated second, but the driver loop and a machine without numba run it
on numpy (seconds per simulated second, tens on a rough road).
"""

import numpy as np
import pytest

import vehdyn
from vehdyn.full_vehicle import FullVehicle
from vehdyn.scene.full_vehicle_rungs import ladder_setup, road_inputs, scene_inputs
from vehdyn.scene import relative_error
from vehdyn.scene.drive import drive_of
from vehdyn.scene.registry import NotAdmissible, rungs
from vehdyn.scene.standard import standard_scenes


@pytest.fixture(scope="module")
def scenes():
    return standard_scenes("sedan")


def test_full_vehicle_is_registered_on_both_ladders():
    by_name = {r.name: r for r in rungs()}
    for name, ladder in (("FullVehicle", "handling"), ("FullVehicle(ride)", "ride")):
        rung = by_name[name]
        assert rung.available and rung.ladder == ladder and rung.model_class() is FullVehicle
        # the highest fidelity of its ladder
        assert rung.fidelity > max(r.fidelity for r in rungs() if r.ladder == ladder and r is not rung)


@pytest.mark.parametrize("name, top", [("gentle_step_steer", "FullVehicle"), ("braking_in_turn", "FullVehicle"),
                                       ("smooth_road_54", "FullVehicle(ride)"),
                                       ("cornering_rough_road", "FullVehicle")])
def test_full_vehicle_is_the_reference_where_admissible(scenes, name, top):
    p = vehdyn.plan(scenes[name])
    assert p.top.rung.name == top
    rows = {r.rung.name: r for r in p.rows}
    # exactly one of the two full-vehicle rungs answers a scene
    other = rows["FullVehicle(ride)" if top == "FullVehicle" else "FullVehicle"]
    assert rows[top].admissible and not other.admissible and "answers" in other.reason


def test_combined_scene_picks_the_full_vehicle(scenes):
    """Cornering on a rough road: the ride rungs ignore the steer (their error is unestimated) and
    the handling rungs have no sprung acceleration, so only the full vehicle answers -- and its
    linearization, whose error (tire saturation without a linear probe, the wheels lifting) is
    unestimated there: never picked."""
    p = vehdyn.plan(scenes["cornering_rough_road"])
    assert p.chosen.rung.name == "FullVehicle" and p.choice is FullVehicle
    rows = {r.rung.name: r for r in p.rows if r.admissible}
    for name in ("QuarterCar", "BouncePitch", "FullCar"):
        assert "front_steer_angle" in rows[name].setup.ignores and np.isnan(rows[name].estimated_error)
    assert np.isnan(rows["FullVehicle(linearized)"].estimated_error)
    assert not any(r.admissible for r in p.rows if r.rung.ladder == "handling"
                   and r.rung.name not in ("FullVehicle", "FullVehicle(linearized)"))


def test_road_under_each_corner_has_the_wheelbase_delay(scenes):
    """The rear wheels meet the front wheels' road a wheelbase later: z_rear(t) = z_front(t - L / V),
    each track on its own profile (the scene's two synthesized class-D tracks differ)."""
    scene = scenes["cornering_rough_road"].replace(duration=1.0)
    drive = drive_of(scene)
    u = road_inputs(drive)
    t, V, L = drive.time, scene.speed, drive.vehicle.geometry.wheelbase
    distance, left, right = drive.road
    for side, profile in (("left", left), ("right", right)):
        np.testing.assert_allclose(u[f"road_displacement_front_{side}"], np.interp(V * t, distance, profile),
                                   atol=1e-12)
        np.testing.assert_allclose(u[f"road_displacement_rear_{side}"], np.interp(V * t - L, distance, profile),
                                   atol=1e-12)
    assert np.max(np.abs(u["road_displacement_front_left"] - u["road_displacement_front_right"])) > 1e-3
    # the steer and the road reach the model together
    model = FullVehicle(drive.vehicle)
    inputs = scene_inputs(drive, model, model.input_vector(), u)
    assert inputs["front_steer_angle"] is drive.steer and inputs["road_velocity_rear_right"] is u[
        "road_velocity_rear_right"]


def test_braking_becomes_brake_torques_on_each_wheel(scenes):
    """Straight braking at 6 m/s^2 (65 % front): brake torque F R_e / 2 per wheel, and over 1 s the
    full vehicle decelerates at the commanded rate (drag, rolling resistance and the wheels' spin
    inertia add a few percent)."""
    scene = scenes["braking_in_turn"].replace(manoeuvre="straight_braking", duration=1.2,
                                              manoeuvre_parameters={"deceleration": 6.0, "brake_start": 0.3})
    drive = drive_of(scene)
    setup = ladder_setup(drive)
    model = setup.model
    m, R = drive.vehicle.mass.mass, drive.vehicle.tires.rolling_radius
    inputs = scene_inputs(drive, model, model.input_vector(drive_torque_rear_left=40.0))
    np.testing.assert_allclose(inputs["brake_torque_front_left"](np.array([0.0, 1.0])), [0.0, 0.5 * 0.65 * m * 6 * R])
    np.testing.assert_allclose(inputs["brake_torque_rear_right"](np.array([1.0])), [0.5 * 0.35 * m * 6 * R])
    np.testing.assert_allclose(inputs["drive_torque_rear_left"](np.array([0.2, 0.4])), [40.0, 0.0])
    result = setup.run()
    ax = result["longitudinal_acceleration"][drive.time > 0.8]
    assert np.all(np.abs(ax / -6.0 - 1.0) < 0.06)
    assert abs(result["longitudinal_acceleration"][0]) < 1e-3  # the trim holds the speed before braking
    # the body above the wheels: a rigid body's vertical acceleration is affine in the point's (x, y)
    # (alpha x r and omega x (omega x r) at the CG's height), so the corners interpolate to the CG
    a, b = model.sprung_cg_to_front_axle, model.sprung_cg_to_rear_axle
    front = 0.5 * (result["sprung_acceleration_front_left"] + result["sprung_acceleration_front_right"])
    rear = 0.5 * (result["sprung_acceleration_rear_left"] + result["sprung_acceleration_rear_right"])
    np.testing.assert_allclose((b * front + a * rear) / (a + b), result["sprung_acceleration"], atol=1e-12)
    assert np.max(np.abs(front - rear)) > 0.1  # the body pitches as the brakes come on


def test_an_input_the_full_vehicle_lacks_makes_it_inadmissible(scenes):
    scene = scenes["gentle_step_steer"].replace(manoeuvre={"front_longitudinal_force": -100.0,
                                                           "front_steer_angle": 0.0})
    with pytest.raises(NotAdmissible, match="front_longitudinal_force"):
        ladder_setup(drive_of(scene))
    with pytest.raises(vehdyn.ParameterError, match="ladder"):
        ladder_setup(drive_of(scenes["gentle_step_steer"]), ladder="pitch")


def test_gentle_handling_scene_cheap_rungs_against_the_full_vehicle(scenes):
    """A short gentle step steer (0.1 g, 1.2 s): every cheap rung whose estimated error is within
    the tolerance is also within it when measured against the full vehicle (no wrong pick), and
    the estimates are within a factor 3 of the measured errors (bench_ladder's calibration goal)."""
    base = scenes["gentle_step_steer"]
    scene = base.replace(duration=1.2, tolerance=0.2,
                         manoeuvre_parameters=dict(base.manoeuvre_parameters, start=0.2))
    frame = vehdyn.ladder(scene)
    assert frame.loc[frame["reference"], "rung"].item() == "FullVehicle"
    cheap = frame[~frame["reference"]]
    within = cheap[cheap["estimated_error"] <= scene.tolerance]
    assert len(within) >= 1 and np.all(within["error"] <= scene.tolerance)
    planned = frame[frame["planned"]].iloc[0]
    assert planned["rung"] != "FullVehicle" and planned["error"] <= scene.tolerance
    ratio = (within["estimated_error"] / within["error"]).to_numpy()
    assert np.all((ratio > 1 / 3) & (ratio < 3)), within[["rung", "estimated_error", "error"]]


def test_a_wheel_lift_rules_out_the_linear_ride_rungs(scenes):
    """In the pothole the linear full car's front-left tire goes into tension (static load plus its
    dynamic load < 0): the full vehicle lifts that wheel instead, which the linear rungs miss, so
    their estimated error exceeds the tolerance. The full car whose tires lift off (with the tires'
    slip and the wheels' spin) misses, at the corner over the pothole, the full vehicle's unsprung
    masses' lateral inertia taken by the tires (issue 28, lambda = 1: 3.2 % off, 1.7 % with
    lambda = 0; estimates ``lift_off_roll_gain``), so the full vehicle itself answers. On the smooth
    road no tire pulls and a linear ride rung is picked."""
    from vehdyn.scene import estimates as est

    p = vehdyn.plan(scenes["pothole"])
    full_car = p.probes["FullCar"]
    static = 0.5 * p.drive.vehicle.static_axle_loads(9.81)[0]
    tension = -np.min(static + full_car["dynamic_tire_load_front_left"]) / static
    assert tension > 0 and est.tire_lift(full_car, p.drive.vehicle) >= tension - 1e-3
    rows = {r.rung.name: r for r in p.rows if r.admissible}
    assert "wheel lift" in rows["FullCar"].reason and rows["FullCar"].estimated_error > p.scene.tolerance
    lift = rows["FullCar+lift"]
    assert lift.errors["sprung_acceleration"] <= p.scene.tolerance  # at the CG it would do
    assert lift.errors["sprung_acceleration_front"] > p.scene.tolerance
    assert p.chosen.rung.name == "FullVehicle(ride)"
    smooth = vehdyn.plan(scenes["smooth_road_54"])
    assert smooth.chosen.rung.ladder == "ride" and smooth.chosen.rung.linear
    assert est.tire_lift(smooth.probes["FullCar"], smooth.drive.vehicle) == 0.0


def test_iso3888_driver_steers_the_full_vehicle_like_the_single_track():
    """ISO 3888-1 with the preview driver, into the first lane change (3 s at 60 km/h): the full
    vehicle in the loop follows the track as the single track does (same driver), its path within
    10 % of the single track's lateral offset and its speed held by the trim's drive torques."""
    scene = vehdyn.Scene(manoeuvre="iso3888_1", speed=16.7, duration=3.0, outputs=("yaw_rate",))
    p = vehdyn.plan(scene)
    assert p.top.rung.name == "FullVehicle"
    full = p.row("FullVehicle").setup.run()
    single = p.row("SingleTrack").setup.run()
    offset = np.max(np.abs(single["y"]))
    assert offset > 0.2  # the driver has started the lane change (0.35 m by 3 s)
    assert np.max(np.abs(full["y"] - single["y"])) < 0.1 * offset
    assert np.all(np.abs(full["longitudinal_velocity"] / 16.7 - 1.0) < 0.01)


def test_no_wrong_pick_on_the_standard_scenes_against_the_full_vehicle():
    """bench_ladder's first goal on the sedan, with the full vehicle as the reference: the planned
    rung's measured error is within the tolerance on every standard scene, every rung the plan
    counts within the tolerance is so when measured, and the handling rungs' estimates are within
    a factor 3 of their measured errors. Needs the compiled right-hand side (seconds in all)."""
    pytest.importorskip("numba")
    bad = []
    for name, scene in standard_scenes("sedan").items():
        frame = vehdyn.ladder(scene)
        assert frame.loc[frame["reference"], "rung"].item().startswith("FullVehicle"), name
        planned = frame[frame["planned"]].iloc[0]
        assert planned["error"] <= scene.tolerance, (name, planned["rung"], planned["error"])
        others = frame[~frame["reference"]]
        trusted = others[others["estimated_error"] <= scene.tolerance]
        assert np.all(trusted["error"] <= scene.tolerance), (name, trusted[["rung", "error"]])
        if scene.kind == "handling":
            ratio = (others["estimated_error"] / others["error"]).to_numpy()
            bad += [(name, r) for r, q in zip(others["rung"], ratio) if np.isfinite(q) and not 1 / 3 <= q <= 3]
    assert not bad, bad


def test_a_vehicle_the_full_vehicle_refuses_leaves_the_other_rungs_admissible():
    """A vehicle whose masses do not add up (a sweep varying mass.mass alone) cannot build a
    FullVehicle: that rung is inadmissible with the reason, the others still answer."""
    vehicle = vehdyn.load_vehicle("sedan").replace(mass__mass=1400.0)
    with pytest.raises(vehdyn.ParameterError):
        vehdyn.full_vehicle.FullVehicle(vehicle)
    scene = vehdyn.Scene(vehicle=vehicle, manoeuvre="step_steer", speed=20.0, duration=1.0, outputs=("yaw_rate",))
    p = vehdyn.plan(scene)
    rows = p.to_frame()
    full = rows[rows["model"] == "FullVehicle"]
    assert len(full) and not full["admissible"].any()
    assert full["reason"].str.contains("cannot build the model for this vehicle: mass").any()
    assert p.chosen.rung.name != "FullVehicle" and p.chosen.admissible


@pytest.mark.parametrize("name", ["gentle_step_steer", "lane_change_60"])
def test_gentle_handling_picks_the_roll_model_with_tire_lag_against_the_full_vehicle(scenes, name):
    """At 0.1 g the linear lateral-yaw-roll model with tire lag, its parameters from the tire law at
    the running loads (LateralYawRollLag), is within the 2 % tolerance of the full vehicle and the
    plan picks it at a tabled cost below 1/10 of the full vehicle's; its estimate is within a
    factor 3 of the verified error. (The bicycle with the file's stiffnesses is 3-12 % off.)"""
    pytest.importorskip("numba")
    scene = scenes[name]
    out = vehdyn.run(scene, verify=True)
    p = out.plan
    assert out.rung == "LateralYawRoll+lag" and out.reference == "FullVehicle"
    assert max(out.verified_error.values()) <= scene.tolerance
    assert p.chosen.estimated_cost_s <= 0.1 * p.top.estimated_cost_s
    ratio = max(out.estimated_error.values()) / max(out.verified_error.values())
    assert 1 / 3 <= ratio <= 3
    assert p.row("LinearBicycle+lag").estimated_error > scene.tolerance


def test_linearized_full_vehicle_stays_at_its_trim_and_follows_a_gentle_steer(scenes):
    """The full vehicle linearized at the trim: with zero steer its outputs stay at the trim's
    (speed, zero lateral acceleration) to round-off; in a short 0.1 g step steer it is within 1 %
    of the nonlinear full vehicle (simulated by an adaptive solver, an independent route)."""
    from vehdyn.scene.full_vehicle_rungs import linearized_setup

    base = scenes["gentle_step_steer"].replace(duration=1.5)
    still = drive_of(base.replace(manoeuvre={"front_steer_angle": 0.0}))
    res = linearized_setup(still).run()
    assert np.max(np.abs(res["speed"] - base.speed)) < 1e-9 * base.speed
    assert np.max(np.abs(res["lateral_acceleration"])) < 1e-9
    p = vehdyn.plan(base)
    lin, full = p.row("FullVehicle(linearized)").setup.run(), p.row("FullVehicle").setup.run()
    for name in ("yaw_rate", "lateral_acceleration", "roll_angle"):
        assert relative_error(lin[name], full[name]) < 0.01, name
    with pytest.raises(NotAdmissible, match="braking"):
        linearized_setup(drive_of(scenes["braking_in_turn"]))


def test_circle_to_the_limit_picks_the_single_track_with_lateral_load_transfer(scenes):
    """The quasi-static lateral load transfer is what the single track misses against the full
    vehicle near the limit (the tire's load sensitivity, 14 % in the sedan's circle to the limit):
    with it the single track is within the 2 % tolerance there and the plan picks it at a tabled
    cost below 1/10 of the full vehicle's; the plan charges it the roll probes, not the transfer."""
    pytest.importorskip("numba")
    scene = scenes["circle_to_limit"]
    out = vehdyn.run(scene, verify=True)
    p = out.plan
    assert out.rung == "SingleTrack+LLT" and out.reference == "FullVehicle"
    assert out.model.lateral_load_transfer
    assert max(out.verified_error.values()) <= scene.tolerance
    assert p.chosen.estimated_cost_s <= 0.1 * p.top.estimated_cost_s
    plain = p.row("SingleTrack")
    assert "lateral load transfer" in plain.reason and "lateral load transfer" not in p.chosen.reason
    assert plain.estimated_error > scene.tolerance


def test_rough_road_picks_the_full_car_with_lift_off_within_tolerance(scenes):
    """The sedan on the class-D road at 54 km/h: the linear ride rungs' tires go into tension
    (their estimate is beyond the tolerance), the full car whose tires lift off is picked, and
    against the full vehicle it is within the tolerance (bench_ladder: 0.45 %) at a tenth of its
    cost or less (the estimated costs, the measured ones in bench_ladder). A vehicle with roll
    centres above the ground is not its (the lateral slip acts at the ground)."""
    pytest.importorskip("numba")
    scene = scenes["rough_road_54"].replace(duration=1.5)
    out = vehdyn.run(scene, verify=True)
    p = out.plan
    assert out.rung == "FullCar+lift" and out.reference == "FullVehicle(ride)"
    assert p.row("FullCar").estimated_error > scene.tolerance
    assert out.verified_error["sprung_acceleration"] <= scene.tolerance
    assert p.chosen.estimated_cost_s <= 0.1 * p.top.estimated_cost_s
    raised = vehdyn.load_vehicle("sedan").replace(geometry__front_roll_centre_height=0.05)
    lift = next(r for r in vehdyn.plan(scene.replace(vehicle=raised)).rows if r.rung.name == "FullCar+lift")
    assert not lift.admissible and "roll centres" in lift.reason


def test_lane_change_at_100_kmh_leaves_the_roll_rung_when_it_may_be_beyond_the_tolerance():
    """At 0.2 g the single track with the roll degree of freedom (SingleTrack+roll) is 2.1 % off
    the full vehicle in the van's lane change at 100 km/h (since every model mirrors the wheel
    opposite the .tir file's TYRESIDE): its estimate must say so (within a factor 3 of the
    measured error, above the tolerance), so the plan does not pick it."""
    pytest.importorskip("numba")
    scene = standard_scenes("van")["lane_change_100"]
    roll = vehdyn.plan(scene).row("SingleTrack+roll")
    assert vehdyn.plan(scene).chosen.rung.name != "SingleTrack+roll"
    out = vehdyn.run(scene, model="SingleTrack+roll", verify=True)
    assert out.reference == "FullVehicle"
    measured, estimated = max(out.verified_error.values()), max(out.estimated_error.values())
    assert roll.estimated_error > scene.tolerance and measured > 0.75 * scene.tolerance
    assert 1 / 3 <= estimated / measured <= 3
