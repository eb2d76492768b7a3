"""Shared fixtures of the full-vehicle tests."""

import pytest

import vehdyn


@pytest.fixture(scope="session")
def sedan():
    return vehdyn.load_vehicle("sedan")


@pytest.fixture(scope="session")
def linear_tires():
    """``linear_tires(vehicle)`` -> (front, rear) LinearTire of the vehicle (load-proportional)."""
    from vehdyn.tire import LinearTire

    return lambda vehicle: (LinearTire.from_vehicle(vehicle, "front"), LinearTire.from_vehicle(vehicle, "rear"))


@pytest.fixture(scope="session")
def reduced(sedan):
    """The sedan with the full vehicle's extra physics made negligible: no drag, tires 1000x stiffer
    vertically, unsprung masses 1000x lighter (the total CG kept at the sprung CG), wheels with
    1/1000 of their spin inertia."""
    m, k = sedan.mass, 1e-3
    unsprung_height = 0.3  # [m]
    mass = m.sprung_mass + k * m.unsprung_mass
    return sedan.replace(
        aero__drag_coefficient=0.0, tires__vertical_stiffness=1000 * sedan.tires.vertical_stiffness,
        tires__wheel_spin_inertia=k * sedan.tires.wheel_spin_inertia,
        mass__front_unsprung_mass=k * m.front_unsprung_mass, mass__rear_unsprung_mass=k * m.rear_unsprung_mass,
        mass__mass=mass,
        mass__cg_height=(m.sprung_mass * m.sprung_cg_height + k * m.unsprung_mass * unsprung_height) / mass,
        mass__yaw_inertia=1750.0, geometry__cg_to_front_axle=sedan.geometry.sprung_cg_to_front_axle,
        geometry__cg_to_rear_axle=sedan.geometry.sprung_cg_to_rear_axle)
