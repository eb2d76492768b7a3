"""SingleTrack with the quasi-static lateral load transfer against the textbook closed form, the
no-transfer model and the tire law's load sensitivity."""

import numpy as np
import pytest

import vehdyn
from vehdyn.handling import SingleTrack
from vehdyn.procedures import step_steer
from vehdyn.handling.nonlinear_steady_state import steady_state_cornering
from vehdyn.tire import LinearTire

# raised roll centres, so that the geometric part of the transfer acts too (shipped: at the ground)
SEDAN = vehdyn.load_vehicle("sedan").replace(geometry__front_roll_centre_height=0.05,
                                            geometry__rear_roll_centre_height=0.1)
WHEEL_LOADS = ("front_left_normal_load", "front_right_normal_load", "rear_left_normal_load", "rear_right_normal_load")


def textbook_transfer(vehicle, lateral_acceleration):
    """dF_z per axle from a_y in a steady turn (Milliken & Milliken 1995, ch. 18; Gillespie 1992, ch. 6)."""
    m, g = vehicle.mass, vehicle.geometry
    kf, kr = vehicle.front_roll_stiffness, vehicle.rear_roll_stiffness
    zf, zr = g.front_roll_centre_height, g.rear_roll_centre_height
    h1 = m.cg_height - (zf * g.b + zr * g.a) / g.wheelbase
    phi_moment = m.mass * lateral_acceleration * h1 / (kf + kr - m.mass * vehicle_gravity() * h1)
    front = (kf * phi_moment + m.mass * lateral_acceleration * g.b / g.wheelbase * zf) / g.front_track
    rear = (kr * phi_moment + m.mass * lateral_acceleration * g.a / g.wheelbase * zr) / g.rear_track
    return front, rear


def vehicle_gravity():
    return 9.80665


@pytest.fixture(scope="module")
def steady_turn():
    model = SingleTrack(SEDAN, lateral_load_transfer=True)
    return model, steady_state_cornering(model, lateral_acceleration=4.0, speed=20.0)


def test_steady_turn_transfer_equals_the_closed_form(steady_turn):
    model, turn = steady_turn
    y = turn.outputs
    front, rear = textbook_transfer(SEDAN, y["lateral_acceleration"])
    assert y["front_left_normal_load"] - 0.5 * y["front_normal_load"] == pytest.approx(front, rel=1e-3)
    assert y["rear_left_normal_load"] - 0.5 * y["rear_normal_load"] == pytest.approx(rear, rel=1e-3)
    # a right turn (SAE) loads the left (outer) wheels; each axle keeps its load
    assert front > 0 and rear > 0
    for axle in ("front", "rear"):
        total = y[f"{axle}_left_normal_load"] + y[f"{axle}_right_normal_load"]
        assert total == pytest.approx(y[f"{axle}_normal_load"], rel=1e-12)


@pytest.mark.parametrize("nominal_load", [None, 3000.0])
def test_load_insensitive_linear_tires_give_the_no_transfer_forces(nominal_load):
    # a tire linear in its load (or independent of it) makes the same axle force at F_z/2 +- dF_z
    tires = [LinearTire(cornering_stiffness=getattr(SEDAN.tires, f"{axle}_cornering_stiffness") / 2,
                        nominal_load=nominal_load) for axle in ("front", "rear")]
    with_transfer = SingleTrack(SEDAN, *tires, lateral_load_transfer=True)
    without = SingleTrack(SEDAN, *tires)
    rng = np.random.default_rng(3)
    moved = 0.0
    for _ in range(20):
        x = without.straight_running(25.0)
        x[without.index("lateral_velocity")] = rng.uniform(-1.0, 1.0)
        x[without.index("yaw_rate")] = rng.uniform(-0.3, 0.3)
        x[without.index("front_lateral_deflection")] = rng.uniform(-0.01, 0.01)
        x[without.index("rear_lateral_deflection")] = rng.uniform(-0.01, 0.01)
        # no longitudinal force: the friction ellipse of force mode is nonlinear in the load
        u = without.input_vector(front_steer_angle=rng.uniform(-0.05, 0.05))
        assert np.allclose(with_transfer.rhs(0.0, x, u), without.rhs(0.0, x, u), rtol=1e-12, atol=1e-9)
        y = with_transfer.output(0.0, x, u)
        assert np.allclose(y[:without.n_outputs], without.output(0.0, x, u), rtol=1e-12, atol=1e-9)
        shift = y[with_transfer.index("front_left_normal_load", "outputs")] - \
            0.5 * y[with_transfer.index("front_normal_load", "outputs")]
        moved = max(moved, abs(shift))
    assert moved > 300.0  # [N] the load did move


def test_no_side_force_no_change_bitwise():
    # straight braking with wheel spin: no lateral force, no transfer, the same numbers to the bit (both numpy:
    # the transfer adds exact zeros to the same operations)
    vehicle = vehdyn.load_vehicle("sedan")
    off, on = (SingleTrack(vehicle, wheel_spin=True, lateral_load_transfer=llt) for llt in (False, True))
    t = np.linspace(0.0, 1.0, 21)
    inputs = {"front_brake_torque": 900.0, "rear_brake_torque": 400.0}
    a, b = (vehdyn.simulate(m, t, inputs, x0=m.straight_running(20.0), method="RK45", backend="numpy", rtol=1e-6)
            for m in (off, on))
    assert np.array_equal(a.states, b.states)
    assert np.array_equal(a.outputs, b.outputs[:off.n_outputs])


def understeer_gradient(model, speed=20.0):
    """d(steer)/d(a_y) [rad/(m/s^2)] between 1 and 3 m/s^2 of the steady turns."""
    steer = [steady_state_cornering(model, lateral_acceleration=a, speed=speed).steer_angle for a in (1.0, 3.0)]
    return (steer[1] - steer[0]) / 2.0


def axle_force_loss(model, axle, lateral_acceleration=3.0, alpha=0.02):
    """Relative side-force loss of an axle from the transfer at a_y, from the tire law directly."""
    front, rear = textbook_transfer(model.vehicle, lateral_acceleration)
    load = 0.5 * model.parameters.static_axle_loads()[0 if axle == "front" else 1]
    shift = front if axle == "front" else rear
    tire = model.front_tire if axle == "front" else model.rear_tire
    fy = [float(tire.forces(load + d, 0.0, alpha, 0.0, 20.0).fy) for d in (shift, -shift, 0.0)]
    return 1.0 - (fy[0] + fy[1]) / (2.0 * fy[2])


@pytest.mark.parametrize("bars", [(1.0, 1.0), (0.0, 4.0), (4.0, 0.0)])
def test_understeer_moves_toward_the_axle_that_loses_more_side_force(bars):
    # the load sensitivity of the Magic Formula: the axle with the larger relative transfer loses
    # more side force, so the transfer adds understeer when that is the front (oversteer: the rear)
    s = SEDAN.suspension
    vehicle = SEDAN.replace(suspension__front_antiroll_stiffness=bars[0] * (s.front_antiroll_stiffness + 5000.0),
                            suspension__rear_antiroll_stiffness=bars[1] * (s.rear_antiroll_stiffness + 5000.0))
    off, on = (SingleTrack(vehicle, lateral_load_transfer=llt) for llt in (False, True))
    loss_front, loss_rear = axle_force_loss(on, "front"), axle_force_loss(on, "rear")
    change = understeer_gradient(on) - understeer_gradient(off)
    assert loss_front > 0 and loss_rear > 0
    assert np.sign(change) == np.sign(loss_front - loss_rear)
    assert abs(change) > 1e-5  # [rad/(m/s^2)], about 0.06 deg/g


def test_step_steer_limit_falls_and_compiled_equals_numpy():
    model = SingleTrack(SEDAN, lateral_load_transfer=True)
    plain = SingleTrack(SEDAN)
    t = np.linspace(0.0, 2.0, 41)
    inputs = {"front_steer_angle": step_steer(0.04, 0.2), "rear_longitudinal_force": 300.0}
    runs = {backend: vehdyn.simulate(model, t, inputs, x0=model.straight_running(25.0), method="RK45", rtol=1e-9,
                                     atol=1e-12, backend=backend) for backend in ("numpy", "compiled")}
    assert "compiled" in runs["compiled"].method_reason
    for name in ("lateral_acceleration", "yaw_rate") + WHEEL_LOADS:
        scale = np.max(np.abs(runs["numpy"][name]))
        assert np.max(np.abs(runs["compiled"][name] - runs["numpy"][name])) < 1e-6 * scale, name
    reference = vehdyn.simulate(plain, t, inputs, x0=plain.straight_running(25.0), method="RK45", rtol=1e-9,
                                atol=1e-12)
    # near the limit the transfer takes lateral grip: less lateral acceleration than without
    assert runs["numpy"]["lateral_acceleration"][-1] < 0.97 * reference["lateral_acceleration"][-1]


def test_a_body_that_would_roll_over_is_refused():
    soft = SEDAN.replace(suspension__front_spring_rate=1000.0, suspension__rear_spring_rate=1000.0,
                         suspension__front_antiroll_stiffness=0.0, suspension__rear_antiroll_stiffness=0.0)
    with pytest.raises(vehdyn.ParameterError, match="roll over") as info:
        SingleTrack(soft, lateral_load_transfer=True)
    assert info.value.key == "suspension"
    SingleTrack(soft)  # without the transfer the roll stiffness does not enter


def test_batch_of_variants_equals_single_runs():
    # the transfer coefficients follow the varied mass and CG height (numpy batch axis)
    base = SingleTrack(SEDAN, lateral_load_transfer=True)
    batch = base.variants(mass=[1000.0, 1300.0], cg_height=[0.5, 0.6])
    t = np.linspace(0.0, 1.0, 51)
    steer = {"front_steer_angle": lambda tt: 0.04 * np.sin(2 * np.pi * tt)}
    x0 = np.repeat(base.straight_running(20.0)[:, None], 2, axis=1)
    together = vehdyn.simulate(batch, t, steer, x0=x0, method="rk4")
    for k, (mass, height) in enumerate(((1000.0, 0.5), (1300.0, 0.6))):
        alone = vehdyn.simulate(base.variants(mass=mass, cg_height=height), t, steer, x0=x0[:, k], method="rk4")
        assert np.allclose(together.states[:, :, k], alone.states, rtol=1e-12, atol=1e-12)
        assert np.allclose(together.outputs[:, :, k], alone.outputs, rtol=1e-12, atol=1e-9)


@pytest.fixture(scope="module")
def tires_by_side(tmp_path_factory):
    """The shipped mf_185_80R14.tir (TYRESIDE 'LEFT', with ply steer) and the same law marked 'RIGHT'."""
    from vehdyn.tire import MagicFormula

    path = vehdyn.data_path("tires", "mf_185_80R14.tir")
    text = open(path, encoding="utf-8").read()
    marked = "TYRESIDE                 = 'LEFT'"
    assert text.count(marked) == 1
    right = tmp_path_factory.mktemp("tir") / "right.tir"
    right.write_text(text.replace(marked, "TYRESIDE                 = 'RIGHT'"), encoding="utf-8")
    return {"LEFT": MagicFormula.from_tir(path), "RIGHT": MagicFormula.from_tir(right)}


def test_tyreside_names_the_unmirrored_wheel_and_the_ply_steer_sign_follows(tires_by_side):
    # TYRESIDE names the side the law was measured on: that wheel is the law's own, the other one
    # its mirror image (F_x, -F_y, M_y at -alpha, -gamma); reference: the law evaluated directly
    from vehdyn.full_vehicle import FullVehicle
    from vehdyn.handling import LateralYawRollLag
    from vehdyn.handling import single_track_equations as equations

    fz, shift, vx, alpha, gamma = 8000.0, 800.0, 20.0, 0.01, 0.02
    ply = {}
    for side, tire in tires_by_side.items():
        own = 0 if side == "LEFT" else 1  # the corner (FL 0, FR 1) that is the law's own
        car = FullVehicle(SEDAN, tire, tire)
        law = tire.forces(3500.0, 0.05, alpha, gamma, vx)
        image = tire.forces(3500.0, 0.05, -alpha, -gamma, vx)
        f = car.corner_law_loads(own, 3500.0, 0.05, alpha, gamma, vx)
        g = car.corner_law_loads(1 - own, 3500.0, 0.05, alpha, gamma, vx)
        assert (f[0], f[1], f[2]) == (law.fx, law.fy, law.my)  # the same scalar path of the law: bitwise
        assert (g[0], g[1], g[2]) == (image.fx, -image.fy, image.my)
        # the single track's axle at zero slip under a load transfer onto the left wheel: SAE y is
        # -ISO y, the sum of the law's own force at one wheel's load and the image's at the other's
        model = SingleTrack(SEDAN, tire, tire, lateral_load_transfer=True)
        k = model._constants()
        axle = equations.wheel_pair_loads(equations.NUMPY, (tire, tire), 0, k, fz, shift, vx, 0.0,
                                          vx / k.rolling_radius, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.2, 0.2, 0.0, 1.0, 0.0)
        f_left, f_right = (float(tire.forces(fz / 2 + d, 0.0, 0.0, 0.0, vx).fy) for d in (shift, -shift))
        iso = f_left - f_right if side == "LEFT" else f_right - f_left
        assert abs(iso) > 10.0  # the ply steer of this law is not small against the check
        assert float(axle[1]) == pytest.approx(-iso, rel=1e-12)
        ply[side] = LateralYawRollLag(SEDAN, 20.0, front_tire=tire, rear_tire=tire).ply_steer_load_coefficient
    assert ply["LEFT"] == pytest.approx(tuple(-k for k in ply["RIGHT"]), rel=1e-12)
    assert ply["LEFT"][0] != 0.0
    # a law without ply steer: no wheel is mirrored
    linear = LinearTire(cornering_stiffness=50e3)
    assert SingleTrack._mirrored_wheel(linear, SingleTrack._needs_mirror(linear, 3000.0)) is None
    assert SingleTrack(SEDAN, linear, linear)._mirrored == {"front": False, "rear": False}
