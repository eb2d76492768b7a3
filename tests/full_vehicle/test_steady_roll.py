"""The full vehicle's steady roll, derived: roll gradient and per-axle load transfer against the closed
form of :func:`vehdyn.handling.steady_roll` (stated in the FullVehicle docstring), term by term.

Gradients are central differences of steady trims at +-0.5 m/s^2 (linear tires, no tire lag, 20 m/s),
which cancel every even-order term; what is left against the linear closed form is of higher order
(the drag's pitch, the yaw rate's gyroscopic terms): <= 0.015 % for the sedan with the roll centres on
the ground, <= 0.06 % with them 0.3-0.4 m high, for the compact and the van as shipped (drag on) and at
other gravities (measured). Each term's size, the difference of two
configurations that switch it, is held to 0.5 % of the term.
"""

import numpy as np
import pytest

import vehdyn
from vehdyn import ParameterError
from vehdyn.full_vehicle import FullVehicle
from vehdyn.handling import steady_roll
from vehdyn.units import GRAVITY

A_Y = 0.5  # [m/s^2]


def _measure(vehicle, linear_tires, gravity=GRAVITY):
    """(roll gradient [rad/(m/s^2)], (front, rear) Delta N / a_y [N/(m/s^2)]) from trims at +-A_Y."""
    model = FullVehicle(vehicle, *linear_tires(vehicle), tire_lag=False, gravity=gravity)
    out = []
    for a in (A_Y, -A_Y):
        x0, u0 = model.trim(20.0, lateral_acceleration=a * gravity / GRAVITY)
        y = dict(zip(model.output_names, model.output(0.0, x0, u0)))
        out.append(np.array([-y["roll_angle"], (y["normal_load_front_left"] - y["normal_load_front_right"]) / 2,
                             (y["normal_load_rear_left"] - y["normal_load_rear_right"]) / 2]))
    d = (out[0] - out[1]) / (2 * A_Y * gravity / GRAVITY)
    return d[0], (d[1], d[2])


def _lam(vehicle, front, rear=None):
    return vehicle.replace(suspension__front_unsprung_transfer_fraction=front,
                           suspension__rear_unsprung_transfer_fraction=front if rear is None else rear)


def _with_unsprung(vehicle, factor):
    """``vehicle`` with its unsprung masses scaled by ``factor``, the sprung mass, its CG and the unsprung
    masses' height kept (total mass, CG position and height follow)."""
    m, G = vehicle.mass, vehicle.geometry
    h_u = (m.mass * m.cg_height - m.sprung_mass * m.sprung_cg_height) / m.unsprung_mass
    muf, mur = factor * m.front_unsprung_mass, factor * m.rear_unsprung_mass
    mass = m.sprung_mass + muf + mur
    L = G.wheelbase
    a = (m.sprung_mass * G.sprung_cg_to_front_axle + mur * L) / mass
    return vehicle.replace(mass__mass=mass, mass__front_unsprung_mass=muf, mass__rear_unsprung_mass=mur,
                           mass__cg_height=(m.sprung_mass * m.sprung_cg_height + (muf + mur) * h_u) / mass,
                           mass__sprung_yaw_inertia=1500.0, geometry__cg_to_front_axle=a,
                           geometry__cg_to_rear_axle=L - a)


_CONFIGURATIONS = {
    "shipped": {},
    "stiff_tires": {"tires__vertical_stiffness": 1.0e3 * 189785.5477234252},
    "unsprung_x3": "unsprung_x3",
    "roll_centres_low": {"geometry__front_roll_centre_height": 0.08, "geometry__rear_roll_centre_height": 0.15},
    "roll_centres_high": {"geometry__front_roll_centre_height": 0.3, "geometry__rear_roll_centre_height": 0.4},
    "bars_off": {"suspension__front_antiroll_stiffness": 0.0, "suspension__rear_antiroll_stiffness": 0.0},
}


def _configured(vehicle, name):
    change = _CONFIGURATIONS[name]
    if change == "unsprung_x3":
        return _with_unsprung(vehicle, 3.0)
    return vehicle.replace(**change)


@pytest.mark.parametrize("lam", [1.0, (0.3, 0.6), 0.0])
@pytest.mark.parametrize("configuration", list(_CONFIGURATIONS))
def test_roll_gradient_and_load_transfer_are_the_closed_form(sedan, linear_tires, configuration, lam):
    vehicle = _configured(_lam(sedan, *np.atleast_1d(lam)), configuration)
    phi, transfer = _measure(vehicle, linear_tires)
    expected = steady_roll(vehicle)
    rtol = 1e-3 if configuration == "roll_centres_high" else 3e-4
    assert phi == pytest.approx(expected.roll_gradient, rel=rtol)
    np.testing.assert_allclose(transfer, expected.load_transfer, rtol=rtol)
    # the transfer is its three parts: elastic, geometric (roll centres), unsprung (direct)
    parts = np.add(np.add(expected.elastic_transfer, expected.geometric_transfer), expected.unsprung_transfer)
    np.testing.assert_allclose(parts, expected.load_transfer, rtol=1e-12)


@pytest.mark.parametrize("name", ["sedan", "compact", "van"])
def test_every_shipped_car_rolls_as_the_closed_form(name, linear_tires):
    vehicle = vehdyn.load_vehicle(name)
    phi, transfer = _measure(vehicle, linear_tires)
    expected = steady_roll(vehicle)
    assert phi == pytest.approx(expected.roll_gradient, rel=1e-3)
    np.testing.assert_allclose(transfer, expected.load_transfer, rtol=1e-3)


def test_gravity_moment_is_the_closed_form(sedan, linear_tires):
    """The gravity moment g M (the body-y component of the weight of what leans) at two gravities."""
    for gravity in (4.0, 20.0):
        phi, transfer = _measure(sedan, linear_tires, gravity=gravity)
        expected = steady_roll(sedan, gravity=gravity)
        assert phi == pytest.approx(expected.roll_gradient, rel=1e-3)
        np.testing.assert_allclose(transfer, expected.load_transfer, rtol=1e-3)


def _term(measured_pair, closed_pair):
    return measured_pair[0] - measured_pair[1], closed_pair[0] - closed_pair[1]


@pytest.mark.parametrize("term", ["unsprung_masses", "tire_compliance", "roll_centres", "gravity_moment",
                                  "sprung_moment"])
def test_each_term_of_the_roll_is_the_closed_form_s(sedan, linear_tires, term):
    """Each term's size, the difference of two configurations that switch it on and off, within 0.5 %
    of the closed form's difference (roll gradient and both axles' transfers)."""
    base = sedan.replace(aero__drag_coefficient=0.0)
    gravities = (GRAVITY, GRAVITY)
    if term == "unsprung_masses":  # through the springs (lambda = 0) against through the tires (lambda = 1)
        pair = (_lam(base, 0.0), _lam(base, 1.0))
    elif term == "tire_compliance":
        pair = (base, base.replace(tires__vertical_stiffness=1e3 * base.tires.vertical_stiffness))
    elif term == "roll_centres":
        pair = (base, base.replace(geometry__front_roll_centre_height=0.08, geometry__rear_roll_centre_height=0.15))
    elif term == "gravity_moment":
        pair, gravities = (base, base), (20.0, 4.0)
    else:  # the sprung moment: a heavier sprung mass at the same CG (unsprung masses and inertias kept)
        m = base.mass
        heavier = base.replace(mass__mass=m.mass + 100.0, mass__sprung_mass=m.sprung_mass + 100.0,
                               mass__cg_height=(m.mass * m.cg_height + 100.0 * m.sprung_cg_height) / (m.mass + 100.0))
        pair = (heavier, base)
    measured = [_measure(v, linear_tires, gravity=g) for v, g in zip(pair, gravities)]
    closed = [steady_roll(v, gravity=g) for v, g in zip(pair, gravities)]
    d_phi, d_phi_closed = _term([x[0] for x in measured], [c.roll_gradient for c in closed])
    assert abs(d_phi_closed) > 2e-4  # the term is there (>= 1.3 % of the roll)
    assert d_phi == pytest.approx(d_phi_closed, rel=5e-3)
    for i in range(2):
        d_n, d_n_closed = _term([x[1][i] for x in measured], [c.load_transfer[i] for c in closed])
        if abs(d_n_closed) > 1e-2 * closed[1].load_transfer[i]:
            assert d_n == pytest.approx(d_n_closed, rel=5e-3)


def test_sedan_rolls_as_commonroad_multibody_model(sedan, linear_tires):
    """CommonRoad's multi-body model (vehicle 2, the shipped sedan; Althoff et al., CommonRoad vehicle
    models, 2020) rolls 0.01580 rad/(m/s^2) in a steady turn (the issue's simulation). The issue asks for
    5 %; the textbook treatment (lambda = 1) reaches 0.1 %; the parallel-link treatment (lambda = 0)
    is 6 % off."""
    phi, _ = _measure(sedan, linear_tires)
    assert phi == pytest.approx(0.01580, rel=0.01)
    phi0, _ = _measure(_lam(sedan, 0.0), linear_tires)
    assert phi0 / 0.01580 - 1 > 0.05


def test_textbook_limit_is_the_familiar_formula(sedan):
    """lambda = 1, rigid tires: m_s h' / (K_phi - m_s g h') with h' the sprung CG over the roll axis."""
    v = sedan.replace(geometry__front_roll_centre_height=0.08, geometry__rear_roll_centre_height=0.15)
    r = steady_roll(v, tire_compliance=False)
    m, G = v.mass, v.geometry
    m_f = m.mass * G.b / G.wheelbase - m.front_unsprung_mass
    m_r = m.mass * G.a / G.wheelbase - m.rear_unsprung_mass
    moment = m_f * (m.sprung_cg_height - 0.08) + m_r * (m.sprung_cg_height - 0.15)
    K = v.front_roll_stiffness + v.rear_roll_stiffness
    # the unsprung masses' direct transfer and the geometric one roll nothing on rigid tires (u_i = 0)
    assert r.tire_roll_moment == 0.0 and r.unsprung_spring_moment == 0.0
    assert r.roll_gradient == pytest.approx(moment / (K - GRAVITY * moment), rel=1e-12)


def test_unsprung_transfer_fraction_is_checked(sedan):
    with pytest.raises(ParameterError, match="suspension.front_unsprung_transfer_fraction") as err:
        sedan.replace(suspension__front_unsprung_transfer_fraction=1.5)
    assert err.value.key == "suspension.front_unsprung_transfer_fraction"
    with pytest.raises(ParameterError, match="rear_unsprung_transfer_fraction"):
        sedan.replace(suspension__rear_unsprung_transfer_fraction=-0.1)


def test_steady_roll_refuses_a_vehicle_that_rolls_over(sedan):
    soft = sedan.replace(suspension__front_spring_rate=100.0, suspension__rear_spring_rate=100.0,
                         suspension__front_antiroll_stiffness=0.0, suspension__rear_antiroll_stiffness=0.0)
    with pytest.raises(ParameterError, match="no steady roll") as err:
        steady_roll(soft)
    assert err.value.key == "suspension.front_spring_rate"
