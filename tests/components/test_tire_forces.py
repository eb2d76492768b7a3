"""The shared tire step (vehdyn.components): the mirror image, the axle of two tires, the road's friction by
similarity, numpy against compiled, the ``friction`` argument and the laws' characteristics."""

import numpy as np
import pytest

import vehdyn
from vehdyn.components import tire_forces as tf
from vehdyn.components import tire_setup
from vehdyn.components.xp import NUMPY
from vehdyn.handling import SingleTrack
from vehdyn.tire import LinearTire, characteristic_values, tire_for_vehicle

SEDAN = vehdyn.load_vehicle("sedan")
MF = tire_for_vehicle(SEDAN, "front")  # mf_185_80R14.tir: TYRESIDE 'LEFT', with ply steer
LINEAR = LinearTire(cornering_stiffness=60e3, slip_stiffness=80e3, nominal_load=3000.0)
RNG = np.random.default_rng(7)
N = 400
FZ, KAPPA, ALPHA = RNG.uniform(800.0, 7000.0, N), RNG.uniform(-0.4, 0.4, N), RNG.uniform(-0.4, 0.4, N)
GAMMA, VX = RNG.uniform(-0.05, 0.05, N), RNG.uniform(3.0, 35.0, N) * RNG.choice([-1.0, 1.0], N)


@pytest.mark.parametrize("tire", [MF, LINEAR], ids=["magic_formula", "linear"])
def test_the_mirror_image_is_the_law_at_opposite_angles_with_its_side_force_negated(tire):
    # MF-Tyre's convention for the tire on the other side of the vehicle: (F_x, -F_y, M_y) at (-alpha, -gamma)
    own = tire.forces(FZ, KAPPA, -ALPHA, -GAMMA, VX)
    fx, fy, my = tf.tire_loads(NUMPY, tire, FZ, KAPPA, ALPHA, GAMMA, VX, True, 1.0, False)
    assert np.array_equal(fx, own.fx) and np.array_equal(fy, -own.fy) and np.array_equal(my, own.my)
    same = tire.forces(FZ, KAPPA, ALPHA, GAMMA, VX)
    fx, fy, my = tf.tire_loads(NUMPY, tire, FZ, KAPPA, ALPHA, GAMMA, VX, False, 1.0, False)
    assert np.array_equal(fx, same.fx) and np.array_equal(fy, same.fy) and np.array_equal(my, same.my)


def test_an_axle_is_two_tires_at_half_its_load_one_the_mirror_image_with_ply_steer():
    ply_steer, _ = tire_setup.tire_characteristics(MF, 3500.0)
    assert ply_steer  # the shipped file's F_y at zero slip is not zero
    fx, fy, my = tf.axle_tire_loads(NUMPY, MF, FZ, KAPPA, ALPHA, VX, True, 1.0, False)
    own, image = MF.forces(FZ / 2, KAPPA, ALPHA, 0.0, VX), MF.forces(FZ / 2, KAPPA, -ALPHA, 0.0, VX)
    assert np.allclose(fx, own.fx + image.fx, rtol=1e-14, atol=0.0)
    assert np.allclose(fy, own.fy - image.fy, rtol=1e-14, atol=1e-12)
    assert np.allclose(my, own.my + image.my, rtol=1e-14, atol=0.0)
    # zero slip: the ply-steer forces of the two tires cancel, so a car with zero steer runs straight
    assert abs(float(tf.axle_tire_loads(NUMPY, MF, 7000.0, 0.0, 0.0, 20.0, True, 1.0, False)[1])) < 1e-9
    assert abs(float(MF.forces(3500.0, 0.0, 0.0, 0.0, 20.0).fy)) > 10.0
    # without ply steer the axle is twice one tire
    fx, fy, my = tf.axle_tire_loads(NUMPY, LINEAR, FZ, KAPPA, ALPHA, VX, False, 1.0, False)
    one = LINEAR.forces(FZ / 2, KAPPA, ALPHA, 0.0, VX)
    assert np.array_equal(fx, 2 * one.fx) and np.array_equal(fy, 2 * one.fy)


@pytest.mark.parametrize("mirror_left, mirror_right", [(True, False), (False, True), (False, False)])
def test_a_wheel_pair_is_each_tire_at_its_own_load(mirror_left, mirror_right):
    left, right = FZ, 0.6 * FZ
    w = tf.wheel_pair_tire_loads(NUMPY, MF, left, right, KAPPA, ALPHA, 0.0, VX, mirror_left, mirror_right, 1.0,
                                 False)
    for load, mirror, got in ((left, mirror_left, w[:3]), (right, mirror_right, w[3:])):
        expected = tf.tire_loads(NUMPY, MF, load, KAPPA, ALPHA, 0.0, VX, mirror, 1.0, False)
        assert all(np.array_equal(a, b) for a, b in zip(got, expected))


@pytest.mark.parametrize("tire", [MF, LINEAR], ids=["magic_formula", "linear"])
@pytest.mark.parametrize("mu", [0.3, 0.6, 1.2])
def test_friction_by_similarity_scales_the_peaks_and_their_slips_and_keeps_the_stiffnesses(tire, mu):
    """Pacejka 2012, sec. 4.3.2: F(kappa, tan alpha) -> mu F(kappa / mu, tan(alpha) / mu)."""
    load = 3500.0
    kappa = np.linspace(0.0, 1.0, 20001)
    pure = tire.forces(np.full(kappa.size, load), kappa, 0.0 * kappa, 0.0, 20.0).fx
    scaled = tf.tire_loads(NUMPY, tire, load, kappa, 0.0 * kappa, 0.0, 20.0, False, mu, True)[0]
    if tire is MF:  # a peak: mu times the law's, at mu times its slip
        assert np.max(scaled) == pytest.approx(mu * np.max(pure), rel=1e-6)
        kx = kappa[np.argmax(pure)]
        assert kappa[np.argmax(scaled)] == pytest.approx(mu * kx, abs=2e-4)
    h = 1e-7
    for axis in (0, 1):  # the slip stiffnesses at zero slip: dF_x/dkappa, dF_y/dtan(alpha)
        step = (h, 0.0) if axis == 0 else (0.0, np.arctan(h))
        law = [tire.forces(load, s * step[0], s * step[1], 0.0, 20.0) for s in (1.0, -1.0)]
        ours = [tf.tire_loads(NUMPY, tire, load, s * step[0], s * step[1], 0.0, 20.0, False, mu, True) for s in (1, -1)]
        stiffness = (getattr(law[0], "fy" if axis else "fx") - getattr(law[1], "fy" if axis else "fx")) / (2 * h)
        assert (ours[0][axis] - ours[1][axis]) / (2 * h) == pytest.approx(stiffness, rel=1e-5)
    # the rolling-resistance moment is the tire's hysteresis, not the road's grip: unscaled
    assert tf.tire_loads(NUMPY, tire, load, 0.0, 0.0, 0.0, 20.0, False, mu, True)[2] == tire.forces(
        load, 0.0, 0.0, 0.0, 20.0).my


def test_friction_ratio_puts_the_peak_at_the_road_friction():
    load = 0.5 * SEDAN.static_axle_loads()[0]
    for mu in (0.9, 0.5, 0.2):
        ratio = tire_setup.friction_ratio(MF, mu, load)
        kappa = np.linspace(-1.0, 1.0, 4001)
        fx = tf.tire_loads(NUMPY, MF, load, kappa, 0.0 * kappa, 0.0, 20.0, False, ratio, True)[0]
        assert np.max(np.abs(fx)) / load == pytest.approx(mu, rel=2e-3)
    lateral = tire_setup.friction_ratio(MF, 0.5, load, "lateral")
    assert lateral == pytest.approx(0.5 / float(characteristic_values(MF, [load]).iloc[0]["peak_lateral_friction"]))
    for kwargs, key in (({"friction": -0.2}, "friction"), ({"friction": float("nan")}, "friction"),
                        ({"load": 0.0}, "load"), ({"friction": True}, "friction"), ({"direction": "up"}, "direction")):
        args = {"friction": 0.5, "load": load, **kwargs}
        with pytest.raises(vehdyn.ParameterError, match=key) as info:
            tire_setup.friction_ratio(MF, **args)
        assert info.value.key == key


def test_the_friction_argument_is_checked():
    assert tire_setup.road_friction(None) is None and tire_setup.road_friction(1.0) is None
    assert tire_setup.road_friction(0.5) == 0.5 and tire_setup.road_friction(np.float32(2.0)) == 2.0
    for bad in (0.0, -0.5, float("inf"), float("nan"), "wet", True, [0.5]):
        with pytest.raises(vehdyn.ParameterError, match="friction") as info:
            tire_setup.road_friction(bad)
        assert info.value.key == "friction"
    with pytest.raises(vehdyn.ParameterError, match="> 0 under every wheel"):
        tire_setup.friction_at(lambda X, Y: 0.5 - 0.1 * X, np.array([0.0, 10.0]), np.zeros(2))
    for model in (SingleTrack, vehdyn.full_vehicle.FullVehicle):
        with pytest.raises(vehdyn.ParameterError, match="friction"):
            model(SEDAN, friction=-1.0)


def test_the_single_track_on_a_road_of_other_friction_is_the_similar_vehicle():
    """Force mode without tire lag: the axle side forces at lateral velocity v on a road of ratio mu are mu times
    those at v / mu on the law's own road (tan(alpha) = v / u; no longitudinal demand, so the loads are the same);
    the longitudinal demand is clipped at mu times the law's mu F_z; a constant ratio and a callable that returns it
    give the same numbers."""
    mu = 0.4
    own = SingleTrack(SEDAN, tire_lag=False)
    models = {"constant": SingleTrack(SEDAN, tire_lag=False, friction=mu),
              "callable": SingleTrack(SEDAN, tire_lag=False, friction=lambda X, Y: np.full(np.shape(X), mu))}
    v = np.linspace(-4.0, 4.0, 9)
    x = np.zeros((own.n_states, v.size))
    x[own.index("longitudinal_velocity")] = 25.0
    x[own.index("lateral_velocity")] = v
    u = np.zeros((own.n_inputs, v.size))
    scaled_x = x.copy()
    scaled_x[own.index("lateral_velocity")] = v / mu
    reference = own.output(0.0, scaled_x, u)
    outputs = {key: m.output(0.0, x, u) for key, m in models.items()}
    assert np.array_equal(outputs["constant"], outputs["callable"])
    for name in ("front_lateral_force", "rear_lateral_force"):
        i = own.index(name, "outputs")
        assert np.allclose(outputs["constant"][i], mu * reference[i], rtol=1e-12, atol=1e-9)
    # the demand beyond mu mu_law F_z is clipped there (force mode)
    u[own.index("rear_longitudinal_force", "inputs")] = 1e5
    y = models["constant"].output(0.0, x, u)
    limit = mu * SEDAN.tires.friction_coefficient * y[own.index("rear_normal_load", "outputs")]
    assert np.allclose(y[own.index("rear_longitudinal_force", "outputs")], limit, rtol=1e-14)


def test_tire_characteristics_are_remembered_per_law_and_load(monkeypatch):
    # the memo gives what the law gives evaluated afresh, evaluates each law once per load, keeps
    # the most recent loads of a law, and a law that cannot be a weak key is evaluated every time
    module = tire_setup
    car = SEDAN
    tire = MF
    original = module.evaluate_characteristics
    calls = []

    def counted(law, load):
        calls.append(load)
        return original(law, load)

    monkeypatch.setattr(module, "evaluate_characteristics", counted)
    monkeypatch.setattr(module, "_CHARACTERISTICS", module.weakref.WeakKeyDictionary())
    loads = [3000.0, 4321.5]
    first = [module.tire_characteristics(tire, load) for load in loads]
    again = [module.tire_characteristics(tire, load) for load in loads]
    assert calls == loads
    assert first == again == [original(tire, load) for load in loads]

    calls.clear()
    SingleTrack(car)
    built_once = len(calls)
    assert 1 <= built_once <= 2  # the two axles' static loads
    SingleTrack(car)
    assert len(calls) == built_once

    monkeypatch.setattr(module, "CHARACTERISTICS_PER_TIRE", 3)
    module._CHARACTERISTICS.clear()
    calls.clear()
    for load in (1000.0, 2000.0, 3000.0, 1000.0, 4000.0):  # 1000 N used again: 2000 N is the oldest
        module.tire_characteristics(tire, load)
    assert list(module._CHARACTERISTICS[tire]) == [3000.0, 1000.0, 4000.0]
    module.tire_characteristics(tire, 2000.0)  # evicted: evaluated again
    module.tire_characteristics(tire, 4000.0)  # kept
    assert calls == [1000.0, 2000.0, 3000.0, 4000.0, 2000.0]

    class Unhashable:
        __hash__ = None

        def __init__(self, law):
            self.law = law

        def forces(self, *args, **kwargs):
            return self.law.forces(*args, **kwargs)

    calls.clear()
    linear = LinearTire(cornering_stiffness=60_000.0)
    for _ in range(2):
        assert module.tire_characteristics(Unhashable(linear), 4000.0) == original(linear, 4000.0)
    assert calls == [4000.0, 4000.0]


def test_the_full_vehicle_takes_the_same_friction_argument():
    """A constant ratio and a callable that returns it: the same numbers (the callable evaluated under each contact
    point); the similarity law makes the split-mu and uniform cases one mechanism with the single track's."""
    from vehdyn.full_vehicle import FullVehicle

    constant, varying = FullVehicle(SEDAN, friction=0.5), FullVehicle(SEDAN, friction=lambda X, Y: 0.5 + 0.0 * X)
    x0, u0 = FullVehicle(SEDAN).trim(15.0, lateral_acceleration=2.0)
    x = x0[:, None] * (1.0 + 0.02 * RNG.uniform(-1.0, 1.0, (x0.size, 5)))
    u = np.repeat(u0[:, None], 5, axis=1)
    assert np.array_equal(constant.rhs(0.0, x, u), varying.rhs(0.0, x, u))
    assert np.array_equal(constant.output(0.0, x, u), varying.output(0.0, x, u))
    assert not np.allclose(constant.rhs(0.0, x, u), FullVehicle(SEDAN).rhs(0.0, x, u))


def test_aligning_moment_of_a_tire_its_mirror_image_and_a_cambered_pair():
    """tire_aligning_moment is the law's M_z, the mirror image's -M_z(-alpha, -gamma), on another road
    mu M_z(kappa / mu, atan(tan(alpha) / mu)) (as the forces); a wheel pair with an inclination is each
    tire's tire_loads at it (the mirror image at -gamma)."""
    gamma, mu = 0.02, 0.6
    own, image = MF.forces(FZ, KAPPA, ALPHA, gamma, VX), MF.forces(FZ, KAPPA, -ALPHA, -gamma, VX)
    assert np.allclose(tf.tire_aligning_moment(NUMPY, MF, FZ, KAPPA, ALPHA, gamma, VX, False, 1.0, False), own.mz,
                       rtol=1e-14, atol=0.0)
    assert np.allclose(tf.tire_aligning_moment(NUMPY, MF, FZ, KAPPA, ALPHA, gamma, VX, True, 1.0, False), -image.mz,
                       rtol=1e-14, atol=0.0)
    similar = MF.forces(FZ, KAPPA / mu, np.arctan(np.tan(ALPHA) / mu), gamma, VX)
    assert np.allclose(tf.tire_aligning_moment(NUMPY, MF, FZ, KAPPA, ALPHA, gamma, VX, False, mu, True),
                       mu * similar.mz, rtol=1e-14, atol=0.0)
    w = tf.wheel_pair_tire_loads(NUMPY, MF, FZ, 0.6 * FZ, KAPPA, ALPHA, gamma, VX, True, False, 1.0, False)
    for load, mirror, got in ((FZ, True, w[:3]), (0.6 * FZ, False, w[3:])):
        expected = tf.tire_loads(NUMPY, MF, load, KAPPA, ALPHA, gamma, VX, mirror, 1.0, False)
        assert all(np.allclose(a, b, rtol=1e-14, atol=0.0) for a, b in zip(got, expected))
    assert np.max(np.abs(w[1] - tf.wheel_pair_tire_loads(NUMPY, MF, FZ, 0.6 * FZ, KAPPA, ALPHA, 0.0, VX, True, False,
                                                           1.0, False)[1])) > 1.0  # the camber acts
