"""Low speed: the single-track model against the kinematic single-track solution, which is exact there.

Kinematic single track (no tire slip; Rajamani 2012, sec. 2.2; Gillespie 1992, sec. 6.1): the rear
axle moves along the vehicle axis, so with forward speed u and front steer delta::

    r = u tan(delta) / L,      v = b r      (lateral velocity of the CG)

Tire slips scale with a_y = u r, so the dynamic answer tends to it as u -> 0.
"""

import numpy as np
import pytest

import vehdyn
from vehdyn.handling import SingleTrack
from vehdyn.tire import FialaTire

SEDAN = vehdyn.load_vehicle("sedan")


@pytest.fixture(scope="module")
def model():
    return SingleTrack(SEDAN, FialaTire.from_vehicle(SEDAN, "front"), FialaTire.from_vehicle(SEDAN, "rear"))


@pytest.mark.parametrize("speed", [0.3, -0.3, 0.05])
def test_low_speed_turn_is_the_kinematic_turn(model, speed):
    steer = 0.35
    t = np.linspace(0, 30, 61)
    drag = model.parameters.drag_factor * speed * abs(speed)
    r = vehdyn.simulate(model, t, {"front_steer_angle": steer, "rear_longitudinal_force": drag},
                        x0=model.straight_running(speed), method="LSODA", rtol=1e-9, atol=1e-11)
    assert np.all(np.isfinite(r.states))
    u = r["longitudinal_velocity"][-1]
    kinematic_r = u * np.tan(steer) / SEDAN.wheelbase
    # slip angle ~ m a_y / C ~ 1e-3 of delta at 0.3 m/s
    assert r["yaw_rate"][-1] == pytest.approx(kinematic_r, rel=2e-3)
    assert r["lateral_velocity"][-1] == pytest.approx(SEDAN.geometry.b * kinematic_r, rel=2e-3)


def test_standstill_is_an_equilibrium_and_stays_one(model):
    # parked with the wheels turned: nothing moves, nothing chatters
    t = np.linspace(0, 5, 51)
    r = vehdyn.simulate(model, t, {"front_steer_angle": 0.4}, x0=model.straight_running(0.0), method="RK45")
    assert np.max(np.abs(r.states)) == 0.0


def test_through_standstill_forwards_to_reverse(model):
    # a constant rearward force takes the car from 2 m/s forwards through zero to reverse, steering
    t = np.linspace(0, 8, 161)
    r = vehdyn.simulate(model, t, {"front_steer_angle": 0.2, "rear_longitudinal_force": -800.0},
                        x0=model.straight_running(2.0), method="LSODA", rtol=1e-8, atol=1e-10)
    assert np.all(np.isfinite(r.states))
    u, yaw = r["longitudinal_velocity"], r["yaw_rate"]
    assert u[0] > 0 > u[-1]
    # the yaw rate follows the kinematic law through the sign change (no jump, no chatter)
    kinematic = u * np.tan(0.2) / SEDAN.wheelbase
    settled = t > 1.0  # after the first relaxation lengths of the steer step
    assert np.max(np.abs(yaw - kinematic)[settled]) < 0.02 * np.max(np.abs(kinematic))
    assert np.all(np.abs(np.diff(yaw[settled], 2)) < 1e-3)


def test_relaxation_at_speed_is_first_order_with_time_constant_sigma_over_u(model):
    # a lateral-deflection disturbance relaxes as exp(-u t / sigma) when the body is held (v = r = 0):
    # the rhs of the deflection state is -(|u| / sigma) rho (Pacejka 2012, eq. 7.12)
    u = 15.0
    sigma = SEDAN.tires.front_relaxation_length
    x = model.straight_running(u, front_lateral_deflection=1e-3)
    rate = model.rhs(0.0, x, model.input_vector())[model.index("front_lateral_deflection")]
    assert rate == pytest.approx(-u / sigma * 1e-3, rel=1e-12)
