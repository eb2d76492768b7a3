"""FullVehicle: signals, static equilibrium, batch evaluation, bad input, a Magic Formula step steer."""

import numpy as np
import pytest

import vehdyn
from vehdyn.full_vehicle import CORNERS, FullVehicle
from vehdyn.units import GRAVITY


def test_signal_names_are_the_issue_s(sedan, linear_tires):
    model = FullVehicle(sedan, *linear_tires(sedan))
    body = ["longitudinal_velocity", "lateral_velocity", "vertical_velocity", "roll_rate", "pitch_rate", "yaw_rate",
            "roll_angle", "pitch_angle", "yaw_angle", "x", "y", "z"]
    corners = [f"{kind}{sfx}" for kind in ("wheel_speed", "unsprung_displacement", "unsprung_velocity",
                                           "lateral_deflection", "longitudinal_deflection") for sfx in CORNERS]
    assert list(model.state_names) == body + corners
    assert list(FullVehicle(sedan, *linear_tires(sedan), tire_lag=False).state_names) == body + corners[:12]
    inputs = (["front_steer_angle", "rear_steer_angle"]
              + [f"{k}{s}" for k in ("drive_torque", "brake_torque", "road_displacement", "road_velocity")
                 for s in CORNERS] + ["wind_velocity_lateral"])
    assert list(model.input_names) == inputs
    for name in ("longitudinal_acceleration", "lateral_acceleration", "sideslip_angle", "sprung_acceleration",
                 "roll_angle", "pitch_angle", "yaw_rate", "speed", "path_curvature"):
        assert name in model.output_names
    for kind in ("normal_load", "slip_angle", "slip_ratio", "longitudinal_force", "lateral_force",
                 "suspension_travel"):
        assert all(f"{kind}{s}" in model.output_names for s in CORNERS)
    # every phenomenon but the steering system's compliance (SteeringSystem composes with it)
    assert model.phenomena == vehdyn.model.PHENOMENA - {"steering"}
    assert "tire_lag" not in FullVehicle(sedan, *linear_tires(sedan), tire_lag=False).phenomena
    assert isinstance(vehdyn.full_vehicle.FullVehicle(sedan), vehdyn.Model)  # default tires: the file's


@pytest.mark.parametrize("name", ["sedan", "compact", "van"])
def test_static_loads_sum_to_the_weight_and_split_by_the_cg(name, linear_tires):
    vehicle = vehdyn.load_vehicle(name)
    model = FullVehicle(vehicle, *linear_tires(vehicle))
    loads = model.static_loads()
    # the rest state is an equilibrium of the equations (not only of the preloads)
    assert np.max(np.abs(model.rhs(0.0, model.state_vector(), model.input_vector()))) < 1e-12
    weight = vehicle.mass.mass * GRAVITY
    total = sum(loads.values())
    front = loads["normal_load_front_left"] + loads["normal_load_front_right"]
    assert total == pytest.approx(weight, rel=1e-9)
    assert front == pytest.approx(weight * vehicle.geometry.b / vehicle.wheelbase, rel=1e-9)
    assert loads["normal_load_front_left"] == pytest.approx(loads["normal_load_front_right"], rel=1e-12)


def test_magic_formula_rest_state_is_static(sedan):
    # the Magic Formula file has a small force at zero slip and speed: the rest state moves by less than 1e-4
    model = FullVehicle(sedan)
    assert np.max(np.abs(model.rhs(0.0, model.state_vector(), model.input_vector()))) < 1e-4


def test_batch_axis_matches_single_evaluations(sedan, linear_tires):
    model = FullVehicle(sedan, *linear_tires(sedan))
    x0, u0 = model.trim(20.0, lateral_acceleration=2.0)
    rng = np.random.default_rng(1)
    X = x0[:, None] + 1e-3 * rng.standard_normal((x0.size, 3)) * np.maximum(np.abs(x0), 1.0)[:, None]
    U = np.repeat(u0[:, None], 3, axis=1)
    F, G = model.rhs(0.0, X, U), model.output(0.0, X, U)
    for j in range(3):
        np.testing.assert_allclose(F[:, j], model.rhs(0.0, X[:, j], U[:, j]), rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(G[:, j], model.output(0.0, X[:, j], U[:, j]), rtol=1e-12, atol=1e-9)


def test_lifted_wheel_carries_nothing_and_makes_no_force(sedan):
    model = FullVehicle(sedan)
    x = model.state_vector(longitudinal_velocity=20.0, lateral_velocity=1.0,
                           **{f"wheel_speed{s}": 20.0 / sedan.tires.rolling_radius for s in CORNERS},
                           unsprung_displacement_front_left=0.05)  # 5 cm up: beyond the 1.8 cm static deflection
    y = dict(zip(model.output_names, model.output(0.0, x, model.input_vector())))
    assert y["normal_load_front_left"] == 0.0
    assert y["lateral_force_front_left"] == 0.0 and y["longitudinal_force_front_left"] == 0.0
    assert y["normal_load_front_right"] > 0 and abs(y["lateral_force_front_right"]) > 0


def test_brake_cannot_drive_a_wheel_backwards(sedan):
    # a wheel at rest under a brake torque alone gets no torque from the brake (sat(0) = 0)
    model = FullVehicle(sedan)
    i = model.index("wheel_speed_front_left")
    x = model.state_vector()
    u = model.input_vector(brake_torque_front_left=2000.0)
    assert model.rhs(0.0, x, u)[i] == pytest.approx(0.0, abs=1e-4)
    x[i] = 1.0  # spinning forwards: the brake decelerates it
    assert model.rhs(0.0, x, u)[i] < -100.0
    x[i] = -1.0
    assert model.rhs(0.0, x, u)[i] > 100.0


def test_ackermann_split(sedan, linear_tires):
    full = sedan.replace(steering__ackermann_fraction=1.0)
    model = FullVehicle(full, *linear_tires(full))
    x = model.state_vector(longitudinal_velocity=10.0)
    y = dict(zip(model.output_names, model.output(0.0, x, model.input_vector(front_steer_angle=0.1))))
    L, half = full.wheelbase, full.geometry.front_track / 2
    # both wheel axes through the turn centre on the rear axle line (turning right: the right wheel inside)
    assert y["steer_angle_front_right"] == pytest.approx(np.arctan(L / (L / np.tan(0.1) - half)), rel=1e-12)
    assert y["steer_angle_front_left"] == pytest.approx(np.arctan(L / (L / np.tan(0.1) + half)), rel=1e-12)
    parallel = FullVehicle(sedan, *linear_tires(sedan))
    y = dict(zip(parallel.output_names, parallel.output(0.0, x, parallel.input_vector(front_steer_angle=0.1))))
    assert y["steer_angle_front_left"] == y["steer_angle_front_right"] == 0.1


def test_bad_input(sedan):
    from vehdyn.tire import FialaTire, TireModel

    with pytest.raises(vehdyn.ParameterError, match="vehicle"):
        FullVehicle("sedan")
    with pytest.raises(vehdyn.ParameterError, match="front_tire"):
        FullVehicle(sedan, front_tire="magic")
    with pytest.raises(vehdyn.ParameterError, match="road"):
        FullVehicle(sedan, road=3.0)
    with pytest.raises(vehdyn.ParameterError, match="brake_regularization_speed"):
        FullVehicle(sedan, brake_regularization_speed=0.0)

    class LateralOnly(TireModel):
        """A law that ignores the slip ratio: no longitudinal force."""

        def forces(self, fz, kappa, alpha, gamma=0.0, vx=10.0):
            fy = -50000.0 * np.asarray(alpha) * np.asarray(fz) / 3000.0
            return vehdyn.conventions.TireForces(0.0 * fy, fy, fz, 0.0 * fy, 0.0 * fy, 0.0 * fy)

    with pytest.raises(vehdyn.ParameterError, match="rear_tire.*cannot take combined slip"):
        FullVehicle(sedan, rear_tire=LateralOnly())

    class Declared(FialaTire):
        combined_slip = False

    with pytest.raises(vehdyn.ParameterError, match="front_tire.*combined_slip = False"):
        FullVehicle(sedan, front_tire=Declared(cornering_stiffness=40000.0, mu=1.0))
    with pytest.raises(vehdyn.ParameterError, match="tires.front_relaxation_length"):
        FullVehicle(sedan.replace(tires__front_relaxation_length=0.0))
    with pytest.raises(vehdyn.ParameterError, match="mass.sprung_mass"):
        FullVehicle(sedan.replace(mass__sprung_mass=800.0))
    with pytest.raises(vehdyn.ParameterError, match="mass.cg_height"):
        FullVehicle(sedan.replace(mass__cg_height=0.7))
    # a vehicle without unsprung masses is valid for the handling models, not for wheel hop
    with pytest.raises(vehdyn.ParameterError, match="mass.front_unsprung_mass"):
        FullVehicle(sedan.replace(mass__front_unsprung_mass=0.0, mass__rear_unsprung_mass=0.0,
                                  mass__sprung_mass=sedan.mass.mass))


def test_trim_bad_input(sedan, linear_tires):
    model = FullVehicle(sedan, *linear_tires(sedan))
    with pytest.raises(vehdyn.ParameterError, match="speed"):
        model.trim(0.0)
    with pytest.raises(vehdyn.ParameterError, match="radius"):
        model.trim(20.0, radius=0.0)
    with pytest.raises(vehdyn.ParameterError, match="lateral_acceleration"):
        model.trim(20.0, lateral_acceleration=float("nan"))
    with pytest.raises(vehdyn.ParameterError, match="friction limit"):
        model.trim(20.0, lateral_acceleration=12.0)
    with pytest.raises(vehdyn.ParameterError, match="not both"):
        model.trim(20.0, lateral_acceleration=2.0, longitudinal_acceleration=-2.0)
    x0, u0 = model.trim(20.0)
    with pytest.raises(vehdyn.ParameterError, match="guess must be finite"):
        model.trim(20.0, guess=(np.where(np.arange(x0.size) == 3, np.nan, x0), u0))
    with pytest.raises(vehdyn.ParameterError, match="guess must be"):
        model.trim(20.0, guess=(x0[:-1], u0))


@pytest.mark.parametrize("name, lag, speed, ay, ax", [("sedan", True, 20.0, 4.0, 0.0), ("compact", False, 30.0, 6.0, 0.0),
                                                      ("compact", False, 20.0, 0.0, -4.0)])
def test_trim_converges_from_perturbed_and_neighbouring_guesses(name, lag, speed, ay, ax):
    """Every start lands on the operating point trimmed from the closed-form start (the same
    equilibrium, to 1e-6 of each state's scale): guesses with 10 % noise on every state and input
    (wheel speeds 10 % off make large slips; before the fallback to the closed-form start most of
    these failed, some at 5e-9 against the 1e-9 tolerance), and the operating point 2 m/s slower and
    1 m/s^2 lower (continuation: the guess is carried to the new speed)."""
    model = FullVehicle(vehdyn.load_vehicle(name), tire_lag=lag)
    reference = model.trim(speed, lateral_acceleration=ay, longitudinal_acceleration=ax)
    rng = np.random.default_rng(7)
    neighbour = model.trim(speed - 2.0, lateral_acceleration=max(ay - 1.0, 0.0), longitudinal_acceleration=ax)
    guesses = [neighbour] + [tuple(g * (1 + 0.1 * rng.standard_normal(g.size)) for g in reference) for _ in range(2)]
    scale = np.maximum(np.abs(reference[0]), 1e-3)
    for guess in guesses:
        x, u = model.trim(speed, lateral_acceleration=ay, longitudinal_acceleration=ax, guess=guess)
        np.testing.assert_allclose(x / scale, reference[0] / scale, atol=1e-6)
        np.testing.assert_allclose(u, reference[1], rtol=1e-6, atol=1e-6 * np.max(np.abs(reference[1])))


def test_magic_formula_step_steer_is_finite_and_sensible(sedan):
    """Step steer at 20 m/s with the file's Magic Formula tires: the response settles near the trim
    of the same steer, the body rolls out of the turn and the outer wheels carry more load."""
    from vehdyn.procedures import step_steer

    model = FullVehicle(sedan)
    x0, u0 = model.trim(20.0)
    x_turn, u_turn = model.trim(20.0, lateral_acceleration=3.0)
    inputs = {name: float(value) for name, value in zip(model.input_names, u0)}
    inputs["front_steer_angle"] = step_steer(float(u_turn[0]), start=0.2, rise_time=0.15)
    inputs.update({f"drive_torque{s}": float(u_turn[model.index(f'drive_torque{s}', 'inputs')]) for s in CORNERS})
    t = np.linspace(0.0, 4.0, 401)
    result = vehdyn.simulate(model, t, inputs, x0=x0, method="RK45", rtol=1e-6, atol=1e-8)
    ay = result["lateral_acceleration"]
    assert np.all(np.isfinite(result.states))
    steady = dict(zip(model.output_names, model.output(0.0, x_turn, u_turn)))
    assert ay[-1] == pytest.approx(steady["lateral_acceleration"], rel=0.02)
    assert result["yaw_rate"][-1] == pytest.approx(steady["yaw_rate"], rel=0.02)
    assert result["roll_angle"][-1] < 0  # turning right, the body rolls left (SAE)
    loads = {s: result[f"normal_load{s}"][-1] for s in CORNERS}
    assert loads["_front_left"] > loads["_front_right"] and loads["_rear_left"] > loads["_rear_right"]
    assert np.all(np.array([result[f"normal_load{s}"] for s in CORNERS]) >= 0)


def test_road_profile_adds_to_the_road_inputs(sedan, linear_tires):
    """A RoadProfile is sampled under each contact point: a 5 cm plateau under the front axle equals
    the same displacement given as inputs."""
    from vehdyn.road import RoadProfile

    front_x = sedan.geometry.sprung_cg_to_front_axle
    distance = np.linspace(-10.0, 10.0, 2001)
    profile = RoadProfile(distance, np.where(distance > 0.5 * front_x, 0.05, 0.0))
    with_road = FullVehicle(sedan, *linear_tires(sedan), road=profile)
    flat = FullVehicle(sedan, *linear_tires(sedan))
    x = flat.state_vector(longitudinal_velocity=10.0,
                          **{f"wheel_speed{s}": 10.0 / sedan.tires.rolling_radius for s in CORNERS})
    u = flat.input_vector(road_displacement_front_left=0.05, road_displacement_front_right=0.05)
    np.testing.assert_allclose(with_road.rhs(0.0, x, with_road.input_vector()), flat.rhs(0.0, x, u), rtol=1e-12,
                               atol=1e-12)

    def ramp(X, Y):  # a 1 % upward slope along X: road velocity = 0.01 * dX/dt under every wheel
        return 0.01 * X, 0.01 + 0.0 * X, 0.0 * X

    sloped = FullVehicle(sedan, *linear_tires(sedan), road=ramp)
    y = dict(zip(sloped.output_names, sloped.output(0.0, x, sloped.input_vector())))
    y0 = dict(zip(flat.output_names, flat.output(0.0, x, flat.input_vector(
        **{f"road_displacement{s}": 0.01 * X for s, X in zip(CORNERS, with_road.corner_x)},
        **{f"road_velocity{s}": 0.1 for s in CORNERS}))))
    for s in CORNERS:
        assert y[f"normal_load{s}"] == pytest.approx(y0[f"normal_load{s}"], rel=1e-12)


def test_lateral_wind_pushes_the_vehicle_downwind_at_the_centre_of_pressure(sedan, linear_tires):
    """The crosswind law of the handling models: F = 0.5 rho A C_Y' (u^2 + w^2) atan(w / u) at the
    centre of pressure, f_p L behind the front axle (Hucho 1998, sec. 4.4); from rest in the air
    (all other forces in equilibrium) it accelerates the total mass sideways (the unsprung masses
    ride along in y) and yaws the body by the force's moment about the sprung CG."""
    model = FullVehicle(sedan, *linear_tires(sedan))
    a = sedan.aero
    u, w = 20.0, 10.0
    x = model.state_vector(longitudinal_velocity=u, **{f"wheel_speed{s}": u / sedan.tires.rolling_radius
                                                      for s in CORNERS})
    calm = model.rhs(0.0, x, model.input_vector())
    windy = model.rhs(0.0, x, model.input_vector(wind_velocity_lateral=w))
    force = 0.5 * a.air_density * a.frontal_area * a.side_force_coefficient_slope * (u * u + w * w) * np.arctan(w / u)
    lever = model.corner_x[0] - a.centre_of_pressure_from_front_axle * sedan.wheelbase  # ahead of the sprung CG
    change = windy - calm
    # the projection P of the body's added masses maps the sprung body's accelerations to the total's
    alpha0 = np.linalg.solve(model.sprung_inertia, [0.0, 0.0, lever * force])
    P = np.asarray(model.constants().projection)
    expected = P @ np.concatenate([[0.0, force / model.sprung_mass, 0.0], alpha0])
    assert change[model.index("lateral_velocity")] == pytest.approx(expected[1], rel=1e-9)
    assert change[model.index("yaw_rate")] == pytest.approx(expected[5], rel=1e-9)
    assert change[model.index("lateral_velocity")] == pytest.approx(force / sedan.mass.mass, rel=0.02)
    assert lever > 0 and change[model.index("yaw_rate")] > 0  # ahead of the CG: the nose turns downwind
    assert calm[model.index("lateral_velocity")] == 0.0


def test_camber_follows_roll_and_travel(sedan, linear_tires):
    gain = -0.5  # [rad/m]: bump travel tilts the wheel top inwards
    vehicle = sedan.replace(suspension__front_camber_gain=gain, suspension__rear_camber_gain=gain)
    model = FullVehicle(vehicle, *linear_tires(vehicle))
    x = model.state_vector(roll_angle=0.02)
    y = dict(zip(model.output_names, model.output(0.0, x, model.input_vector())))
    for s, side in zip(CORNERS, (-1.0, 1.0, -1.0, 1.0)):
        travel = y[f"suspension_travel{s}"]
        # rotation about x: the roll itself, plus the outward camber change of the bump travel -travel
        assert y[f"camber_angle{s}"] == pytest.approx(0.02 + side * gain * (-travel), rel=1e-12)
    # roll 0.02 right side down: the right wheel in bump leans in, the left in rebound leans out, so
    # both lean less than the body (the purpose of camber gain), by about the same amount
    assert 0.0 < y["camber_angle_front_right"] < 0.02
    assert y["camber_angle_front_left"] == pytest.approx(y["camber_angle_front_right"], rel=0.01)  # (2nd order)
    upright = FullVehicle(sedan, *linear_tires(sedan))
    y = dict(zip(upright.output_names, upright.output(0.0, x, upright.input_vector())))
    assert all(y[f"camber_angle{s}"] == 0.0 for s in CORNERS)


@pytest.mark.parametrize("backend", ["numpy", "compiled"])
def test_coast_down_decelerates_by_the_rolling_resistance_moment(backend):
    # As tests/handling/test_single_track.py: MF 5.2 with QSY2 = QSY3 = QSY4 = 0 gives
    # M_y = -R0 F_z LMY QSY1 per tire, so without drag and lift the four wheels decelerate the car by
    #   du/dt = -g QSY1 LMY (R0 / R_e) m / (m + 4 I_w / R_e^2)
    # whatever the load transfer (the closed form; the pitch settles within the first second);
    # the moment's fade at standstill, tanh(omega / omega_b), is 1 to the last bit here.
    if backend == "compiled":
        pytest.importorskip("numba")
    from vehdyn.tire import MagicFormula

    tire = MagicFormula.from_tir(vehdyn.data_path("tires", "MagicFormula52_Parameters.tir"))
    c = tire._c
    assert (c.QSY2, c.QSY3, c.QSY4, c.QSY1) == (0.0, 0.0, 0.0, 0.01) and c.is_mf52
    sedan = vehdyn.load_vehicle("sedan")
    vehicle = sedan.replace(aero__drag_coefficient=0.0, aero__front_lift_coefficient=0.0,
                            aero__rear_lift_coefficient=0.0)
    model = FullVehicle(vehicle, tire, tire, tire_lag=False)
    x0, u0 = model.trim(20.0)
    inputs = {name: (0.0 if name.startswith("drive_torque") else value) for name, value in zip(model.input_names, u0)}
    t = np.linspace(0.0, 3.0, 31)
    r = vehdyn.simulate(model, t, inputs, x0=x0, method="DOP853", rtol=1e-10, atol=1e-10, backend=backend)
    radius, inertia, mass = vehicle.tires.rolling_radius, vehicle.tires.wheel_spin_inertia, vehicle.mass.mass
    expected = -GRAVITY * c.QSY1 * c.LMY * c.UNLOADED_RADIUS / radius * mass / (mass + 4.0 * inertia / radius**2)
    assert np.allclose(r["longitudinal_acceleration"][15:], expected, rtol=3e-4)
