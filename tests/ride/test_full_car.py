"""Full car against E-FULLCAR, and against the half car for symmetric road input."""

import numpy as np
import pytest

import vehdyn
from vehdyn.ride import BouncePitch, FullCar, olley_criteria, road_frequency_response, ride_modes

from .conftest import check, load_case


def reference_car(**changes):
    i = {k: v[0] for k, v in load_case("E-FULLCAR")["inputs"].items()}
    kw = dict(mass=i["ms"], roll_inertia=i["Ix"], pitch_inertia=i["Iy"], a=i["a"], b=i["b"], front_track=i["tf"],
              rear_track=i["tr"], front_spring_rate=i["ksf"], rear_spring_rate=i["ksr"], front_damping=i["csf"],
              rear_damping=i["csr"], front_unsprung_mass=i["mu"], rear_unsprung_mass=i["mu"],
              front_tire_stiffness=i["kt"], rear_tire_stiffness=i["kt"],
              # the case's bar is a spring k_arb [N/m] on the left-right deflection difference: K = k t^2
              front_antiroll_stiffness=i["karbf"] * i["tf"] ** 2, rear_antiroll_stiffness=i["karbr"] * i["tr"] ** 2)
    kw.update(changes)
    return FullCar.from_parameters(**kw)


def test_full_car_case():
    exp = load_case("E-FULLCAR")["expected"]
    fc = reference_car()
    f = fc.modal_analysis().natural_frequency_hz
    for k in range(7):
        check(f[k], exp[f"f{k + 1}_undamped"], f"f{k + 1}")
    check(fc.roll_stiffness, exp["roll_stiffness_suspension_only"], "roll stiffness")
    labels = ride_modes(fc).labels
    assert set(labels[:3]) == {"body bounce", "pitch", "roll"}
    assert all(lab.startswith("wheel") for lab in labels[3:])
    assert sorted(lab.split()[1] for lab in labels[3:]) == ["hop", "hop", "tramp", "tramp"]


def test_roll_stiffness_from_the_model():
    """Static roll moment / roll angle with the wheels held (huge tire rates) = the closed-form roll stiffness."""
    fc = reference_car(front_tire_stiffness=1e13, rear_tire_stiffness=1e13)
    K = fc.stiffness_matrix
    body = [0, 1, 2]  # heave, pitch, roll coordinates; wheels held by the tires
    kphi = K[2, 2] - K[2, :2] @ np.linalg.solve(K[:2, :2], K[:2, 2])  # roll with heave and pitch free
    assert K[2, 2] == pytest.approx(fc.roll_stiffness, rel=1e-12)
    assert kphi == pytest.approx(fc.roll_stiffness, rel=1e-12)  # symmetric car: roll decoupled
    assert body == [fc.second_order[4].index(n) for n in ("sprung_displacement", "pitch_angle", "roll_angle")]


def test_symmetric_input_equals_half_car():
    """Equal left and right roads: the full car responds as the half car with axle (doubled) rates."""
    fc = reference_car()
    p = fc.parameters
    hc = BouncePitch.from_parameters(mass=p.mass, pitch_inertia=p.pitch_inertia, a=p.a, b=p.b,
                                     front_spring_rate=2 * p.front_spring_rate,
                                     rear_spring_rate=2 * p.rear_spring_rate, front_damping=2 * p.front_damping,
                                     rear_damping=2 * p.rear_damping, front_unsprung_mass=2 * p.front_unsprung_mass,
                                     rear_unsprung_mass=2 * p.rear_unsprung_mass,
                                     front_tire_stiffness=2 * p.front_tire_stiffness,
                                     rear_tire_stiffness=2 * p.rear_tire_stiffness)
    w = 2 * np.pi * np.logspace(-1, 1.5, 40)
    full = road_frequency_response(fc, w, speed=15.0, outputs=["sprung_acceleration", "pitch_angle", "roll_angle",
                                                             "dynamic_tire_load_front_left"])
    half = road_frequency_response(hc, w, speed=15.0, outputs=["sprung_acceleration", "pitch_angle",
                                                             "dynamic_tire_load_front"])
    both = full.response.sum(axis=1)  # left and right profiles equal
    np.testing.assert_allclose(both[0], half.response[0, 0], rtol=1e-9)
    np.testing.assert_allclose(both[1], half.response[1, 0], rtol=1e-9)
    np.testing.assert_allclose(np.abs(both[2]), 0.0, atol=1e-12)
    np.testing.assert_allclose(2 * both[3], half.response[2, 0], rtol=1e-9)


def test_antiroll_bar_changes_only_roll_and_warp():
    fc0 = reference_car(front_antiroll_stiffness=0.0)
    fc1 = reference_car()
    m0, m1 = ride_modes(fc0), ride_modes(fc1)
    for lab in ("body bounce", "pitch"):
        assert m0.undamped_frequency_hz[m0.index(lab)] == pytest.approx(m1.undamped_frequency_hz[m1.index(lab)],
                                                                         rel=1e-12)
    assert m1.undamped_frequency_hz[m1.index("roll")] > m0.undamped_frequency_hz[m0.index("roll")]


def test_shipped_vehicles_build_and_olley_uses_roll_mode():
    for name in vehdyn.shipped_vehicles():
        fc = FullCar(vehdyn.load_vehicle(name))
        assert fc.is_stable()
        o = olley_criteria(fc)
        modes = ride_modes(fc)
        assert o.roll_frequency_hz == modes.undamped_frequency_hz[modes.index("roll")]


def test_bad_track():
    with pytest.raises(vehdyn.ParameterError) as err:
        reference_car(front_track=0.0)
    assert err.value.key == "front_track"


@pytest.mark.parametrize("build", ["two_dof", "half", "full"])
def test_tire_loads_balance_the_inertial_forces(build):
    """Newton for the whole car: sum of dynamic tire loads = m z_s'' + sum m_u z_u'' (pitch/roll moments likewise)."""
    v = vehdyn.load_vehicle("van")
    model = {"two_dof": lambda: BouncePitch(v, unsprung=False), "half": lambda: BouncePitch(v),
             "full": lambda: reference_car()}[build]()
    w = np.array([2.0, 9.0, 70.0])
    fr = model.frequency_response(w)
    y = {n: fr.response[k] for k, n in enumerate(fr.output_names)}
    loads = sum(y[f"dynamic_tire_load{s}"] for s in model.corner_suffixes)
    inertia = model.parameters.mass * y["sprung_acceleration"]
    for c in model.corners:
        if c.has_unsprung_mass:
            inertia = inertia + c.unsprung_mass * y[f"unsprung_acceleration{c.suffix}"]
    np.testing.assert_allclose(loads, inertia, rtol=1e-9, atol=1e-9 * np.abs(loads).max())
    # pitch: moment of the tire loads about the sprung CG (x ahead, loads up) = I_y theta'' + sum m_u x z_u''
    moment = sum(c.x * y[f"dynamic_tire_load{c.suffix}"] for c in model.corners)
    inertia = model.parameters.pitch_inertia * y["pitch_acceleration"]
    for c in model.corners:
        if c.has_unsprung_mass:
            inertia = inertia + c.unsprung_mass * c.x * y[f"unsprung_acceleration{c.suffix}"]
    np.testing.assert_allclose(moment, inertia, rtol=1e-9, atol=1e-9 * np.abs(moment).max())
