"""Bounce-pitch model and analysis against E-BP-1600, E-OLLEY-1 and E-HALFCAR."""

import numpy as np
import pytest

import vehdyn
from vehdyn.ride import BouncePitch, bounce_pitch_centres, olley_criteria, ride_modes, axle_ride_rates

from .conftest import check, load_case


def two_dof(case_id, kf_key, kr_key):
    inp = load_case(case_id)["inputs"]
    m, k = inp["m"][0], inp["k_pitch_radius"][0]
    return BouncePitch.from_parameters(mass=m, pitch_inertia=m * k**2, a=inp["b_CG_to_front_axle"][0],
                                       b=inp["c_CG_to_rear_axle"][0], front_spring_rate=inp[kf_key][0],
                                       rear_spring_rate=inp[kr_key][0])


def test_bp_1600_frequencies_and_nodes():
    exp = load_case("E-BP-1600")["expected"]
    bp = two_dof("E-BP-1600", "kf_total", "kr_total")
    f = bp.modal_analysis().natural_frequency_hz
    check(f[0], exp["f1"], "f1")
    check(f[1], exp["f2"], "f2")
    c = bounce_pitch_centres(bp)
    check(c.bounce_frequency_hz, exp["f1"], "bounce")
    check(c.bounce_centre, exp["mode1_node_forward_of_CG"], "bounce centre")
    check(c.pitch_centre, exp["mode2_node_forward_of_CG"], "pitch centre")
    check(c.dynamic_index, exp["dynamic_index"], "DI")
    check(-c.spring_centre, exp["spring_centre_behind_CG"], "spring centre")
    check(bp.parameters.a - c.spring_centre, exp["spring_centre_behind_front_axle"], "spring centre / front axle")
    # the node of a mode is where the body does not move: check on the model's own outputs
    ma = bp.modal_analysis()
    for k, x in ((0, c.bounce_centre), (1, c.pitch_centre)):
        z, th = ma.shapes[:, k]
        assert z + x * th == pytest.approx(0.0, abs=1e-12)


def test_olley_case():
    exp = load_case("E-OLLEY-1")["expected"]
    bp = two_dof("E-OLLEY-1", "Kf_total_ride_rate", "Kr_total_ride_rate")
    o = olley_criteria(bp)
    c = o.centres
    check(c.front_frequency_hz, exp["f_front_uncoupled"], "front")
    check(c.rear_frequency_hz, exp["f_rear_uncoupled"], "rear")
    check(o.frequency_ratio, exp["front_to_rear_frequency_ratio"], "ratio")
    check(o.front_rate_lower_by, exp["front_rate_lower_than_rear_by"], "lower by")
    check(c.dynamic_index, exp["dynamic_index"], "DI")
    check(c.bounce_frequency_hz, exp["f_bounce_mode"], "bounce")
    check(c.pitch_frequency_hz, exp["f_pitch_mode"], "pitch")
    check(o.bounce_to_pitch_ratio, exp["bounce_to_pitch_ratio"], "bounce/pitch")
    check(c.bounce_centre, exp["mode1_node_forward_of_CG"], "bounce node")
    check(c.pitch_centre, exp["mode2_node_forward_of_CG"], "pitch node")
    # criteria: spring centre 12 % of L behind the CG (>= 6.5 %), ratio 0.77 < 1.2, pitch 1.35 Hz > 1.3 Hz
    assert o.front_softer and o.frequencies_close and not o.below_limit and o.roll_matched is None
    assert not o.passed
    assert list(o.to_frame()["criterion_met"])[:2] == [True, True]


def test_dynamic_index_one_uncouples_the_axles():
    """DI = 1: each axle's mass m b/L, m a/L oscillates alone with node at the other axle (Gillespie ch. 5)."""
    a, b, m = 1.2, 1.5, 1500.0
    bp = BouncePitch.from_parameters(mass=m, pitch_inertia=m * a * b, a=a, b=b, front_spring_rate=3e4,
                                     rear_spring_rate=4.5e4)
    c = bounce_pitch_centres(bp)
    nodes = sorted([c.bounce_centre, c.pitch_centre])
    np.testing.assert_allclose(nodes, [-b, a], rtol=1e-10)
    np.testing.assert_allclose(sorted([c.bounce_frequency_hz, c.pitch_frequency_hz]),
                               sorted([c.front_frequency_hz, c.rear_frequency_hz]), rtol=1e-10)


def test_half_car_case():
    c = load_case("E-HALFCAR")
    i, exp = {k: v[0] for k, v in c["inputs"].items()}, c["expected"]
    hc = BouncePitch.from_parameters(mass=i["ms"], pitch_inertia=i["Iy"], a=i["a"], b=i["b"],
                                     front_spring_rate=i["ksf"], rear_spring_rate=i["ksr"], front_damping=i["csf"],
                                     rear_damping=i["csr"], front_unsprung_mass=i["muf"], rear_unsprung_mass=i["mur"],
                                     front_tire_stiffness=i["ktf"], rear_tire_stiffness=i["ktr"])
    modes = ride_modes(hc)
    for k in range(4):
        check(modes.undamped_frequency_hz[k], exp[f"f{k + 1}_undamped"], f"f{k + 1}")
    # the reference sorts the damped modes by |lambda|
    order = np.argsort(modes.natural_frequency_hz)
    for k, j in enumerate(order):
        check(modes.natural_frequency_hz[j], exp[f"mode{k + 1}_f_undamped_damped_model"], f"mode{k + 1}")
        check(modes.damping_ratio[j], exp[f"mode{k + 1}_zeta"], f"zeta{k + 1}")
    assert set(modes.labels[:2]) == {"body bounce", "pitch"}
    assert set(modes.labels[2:]) == {"wheel hop front", "wheel hop rear"}


def test_half_car_with_stiff_light_wheels_tends_to_two_dof():
    """Unsprung masses -> 0 and tires -> rigid: the 4-DOF body modes tend to the 2-DOF model's."""
    two = two_dof("E-BP-1600", "kf_total", "kr_total")
    p = two.parameters
    four = BouncePitch.from_parameters(mass=p.mass, pitch_inertia=p.pitch_inertia, a=p.a, b=p.b,
                                       front_spring_rate=38e3, rear_spring_rate=34e3, front_unsprung_mass=1e-2,
                                       rear_unsprung_mass=1e-2, front_tire_stiffness=1e10, rear_tire_stiffness=1e10)
    np.testing.assert_allclose(four.modal_analysis().natural_frequency_hz[:2],
                               two.modal_analysis().natural_frequency_hz, rtol=1e-5)


def test_a_vehicle_two_dof_uses_ride_rates():
    v = vehdyn.load_vehicle("compact")
    bp2 = BouncePitch(v, unsprung=False)
    bp4 = BouncePitch(v)
    np.testing.assert_allclose(axle_ride_rates(bp2), axle_ride_rates(bp4), rtol=1e-12)
    ks, kt = 2 * v.suspension.front_spring_rate, 2 * v.tires.vertical_stiffness
    assert axle_ride_rates(bp2)[0] == pytest.approx(ks * kt / (ks + kt), rel=1e-12)
    assert bp4.n_states == 8 and bp2.n_states == 4
    # body modes of the 4-DOF car are close to (slightly below) the 2-DOF ones
    f2 = bp2.modal_analysis().natural_frequency_hz
    f4 = bp4.modal_analysis().natural_frequency_hz[:2]
    assert np.all(f4 < f2) and np.all(f4 > 0.97 * f2)


def test_static_load_from_road_step_at_front_wheel():
    """A static front road lift h (rigid tires): heave and pitch from statics."""
    bp = two_dof("E-BP-1600", "kf_total", "kr_total")
    p = bp.parameters
    h = 0.01
    dc = bp.dc_gain()[:, bp.index("road_displacement_front", "inputs")] * h
    # the rear stays, the front rises by h: z + a th = h, z - b th = 0 (springs see no deflection)
    th = h / (p.a + p.b)
    assert dc[bp.index("pitch_angle", "outputs")] == pytest.approx(th, rel=1e-10)
    assert dc[bp.index("sprung_displacement", "outputs")] == pytest.approx(p.b * th, rel=1e-10)
    assert dc[bp.index("dynamic_tire_load_front", "outputs")] == pytest.approx(0.0, abs=1e-8)


@pytest.mark.parametrize("changes,key", [
    (dict(front_unsprung_mass=40.0), "front_tire_stiffness"),
    (dict(rear_tire_stiffness=2e5), "rear_tire_stiffness"),
    (dict(a=-1.0), "a"),
    (dict(pitch_inertia=0.0), "pitch_inertia"),
])
def test_bad_parameters(changes, key):
    kw = dict(mass=1000.0, pitch_inertia=1500.0, a=1.2, b=1.4, front_spring_rate=3e4, rear_spring_rate=3e4)
    kw.update(changes)
    with pytest.raises(vehdyn.ParameterError) as err:
        BouncePitch.from_parameters(**kw)
    assert err.value.key == key


def test_centres_need_pitch():
    from vehdyn.ride import QuarterCar

    qc = QuarterCar.from_parameters(sprung_mass=300.0, unsprung_mass=40.0, spring_rate=2e4, tire_stiffness=2e5)
    with pytest.raises(vehdyn.ParameterError):
        bounce_pitch_centres(qc)
    with pytest.raises(vehdyn.ParameterError):
        ride_modes(vehdyn.LinearModel([[-1.0]], [[1.0]], states=["x"], inputs=["u"]))
