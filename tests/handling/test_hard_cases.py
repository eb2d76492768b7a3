"""Hard cases of the nonlinear single-track model: each ends in a bounded, physically right answer
or a clear vehdyn error, never NaN or silent garbage (issue 7, item 6)."""

import numpy as np
import pytest

import vehdyn
from vehdyn.handling import SingleTrack, critical_speed
from vehdyn.procedures import spin_out_time, step_steer
from vehdyn.tire import FialaTire, LinearTire

SEDAN = vehdyn.load_vehicle("sedan")
G = 9.81


def fiala(vehicle=SEDAN, rear_scale=1.0, rear_mu_scale=1.0):
    return (FialaTire.from_vehicle(vehicle, "front"),
            FialaTire(cornering_stiffness=vehicle.tires.rear_cornering_stiffness / 2 * rear_scale,
                      mu=vehicle.tires.friction_coefficient * rear_mu_scale))


def finite(result):
    return np.all(np.isfinite(result.states)) and np.all(np.isfinite(result.outputs))


def test_braking_to_standstill_with_locked_wheels():
    model = SingleTrack(SEDAN, *fiala(), wheel_spin=True)
    u0 = 20.0
    t = np.linspace(0, 4, 401)
    brakes = {"front_brake_torque": 5000.0, "rear_brake_torque": 4000.0}  # far above mu F_z R_e: locks
    r = vehdyn.simulate(model, t, brakes, x0=model.straight_running(u0), method="LSODA", rtol=1e-6, atol=1e-8)
    assert finite(r)
    u = r["longitudinal_velocity"]
    # locked while sliding: the wheels turn at a few percent of the rolling speed at most
    sliding = (u > 5.0) & (t > 0.2)  # after the wheels' spin-down
    assert np.all(np.abs(r["front_wheel_speed"][sliding] * SEDAN.tires.rolling_radius) < 0.05 * u[sliding])
    # a locked Fiala tire slides at mu F_z: deceleration mu g (drag helps a little)
    mu = SEDAN.tires.friction_coefficient
    distance = r["x"][-1]
    assert 0.9 * u0**2 / (2 * mu * G) < distance <= u0**2 / (2 * mu * G) * 1.01
    # at rest and stays there: no creep, no chatter
    rest = t > 3.0
    assert np.all(np.abs(u[rest]) < 1e-2)
    assert np.ptp(r["x"][rest]) < 5e-3


def test_launch_from_rest_with_wheel_spin():
    model = SingleTrack(SEDAN, *fiala(), wheel_spin=True)
    t = np.linspace(0, 3, 301)
    r = vehdyn.simulate(model, t, {"rear_drive_torque": 3000.0}, x0=model.straight_running(0.0), method="LSODA",
                        rtol=1e-6, atol=1e-8)
    assert finite(r)
    # the rear wheels spin up far faster than the car
    assert np.max(r["rear_slip_ratio"]) > 0.5
    # traction limit of a rear-driven car with load transfer: a_x / g = mu a / (L - mu h)
    # (Gillespie 1992, ch. 2, traction-limited acceleration)
    g = SEDAN.geometry
    mu, h = SEDAN.tires.friction_coefficient, SEDAN.mass.cg_height
    limit = mu * g.a / (g.wheelbase - mu * h) * G
    ax = r["longitudinal_acceleration"]
    assert np.max(ax) <= limit * 1.001
    assert np.mean(ax[t > 0.5]) > 0.9 * limit
    assert r["longitudinal_velocity"][-1] > 0.9 * 2.5 * limit  # moving forward, v ~ a t


def test_reverse_driving_turns_the_right_way():
    model = SingleTrack(SEDAN, *fiala())
    speed, steer = -3.0, 0.15
    t = np.linspace(0, 10, 101)
    drag = model.parameters.drag_factor * speed * abs(speed)
    r = vehdyn.simulate(model, t, {"front_steer_angle": steer, "rear_longitudinal_force": drag},
                        x0=model.straight_running(speed), method="RK45", rtol=1e-8, atol=1e-10)
    assert finite(r)
    u = r["longitudinal_velocity"][-1]
    # reversing with right steer the car yaws left: r = u tan(delta) / L (kinematic, exact at low a_y)
    assert r["yaw_rate"][-1] == pytest.approx(u * np.tan(steer) / SEDAN.wheelbase, rel=1e-2)
    assert r["x"][-1] < 0


def test_above_the_critical_speed_an_oversteer_car_spins_out():
    # rear tires at 45 % of the file's stiffness and 85 % of its grip: an oversteering sedan
    tires = fiala(rear_scale=0.45, rear_mu_scale=0.85)
    bike = vehdyn.handling.LinearBicycle.from_parameters(
        mass=SEDAN.mass.mass, yaw_inertia=SEDAN.mass.yaw_inertia, a=SEDAN.geometry.a, b=SEDAN.geometry.b,
        front_cornering_stiffness=2 * tires[0].cornering_stiffness,
        rear_cornering_stiffness=2 * tires[1].cornering_stiffness, speed=10.0)
    v_crit = critical_speed(bike)
    model = SingleTrack(SEDAN, *tires, tire_lag=False)
    t = np.linspace(0, 8, 401)
    pulse = {"front_steer_angle": lambda tt: 0.005 * ((tt > 0.5) & (tt < 0.7))}
    outcomes = {}
    for factor in (0.7, 1.5):
        speed = factor * v_crit
        drag = model.parameters.drag_factor * speed**2
        r = vehdyn.simulate(model, t, {**pulse, "rear_longitudinal_force": drag}, x0=model.straight_running(speed),
                            method="RK45", rtol=1e-7, atol=1e-9, max_step=0.02)  # do not step over the pulse
        assert finite(r)
        outcomes[factor] = spin_out_time(r)
    assert outcomes[0.7] is None  # below: the pulse dies out
    assert outcomes[1.5] is not None  # above: the divergence grows into a spin, simulated to the end


def test_steer_step_at_the_friction_limit_stays_within_mu():
    model = SingleTrack(SEDAN, *fiala())
    t = np.linspace(0, 3, 301)
    r = vehdyn.simulate(model, t, {"front_steer_angle": step_steer(0.25, start=0.2)},
                        x0=model.straight_running(25.0), method="RK45", rtol=1e-6, atol=1e-9)
    assert finite(r)
    mu = SEDAN.tires.friction_coefficient
    for axle in ("front", "rear"):
        force = np.hypot(r[f"{axle}_lateral_force"], r[f"{axle}_longitudinal_force"])
        assert np.all(force <= mu * r[f"{axle}_normal_load"] * (1 + 1e-9))
    assert np.max(np.abs(r["lateral_acceleration"])) <= mu * G * 1.001
    assert np.max(np.abs(r["lateral_acceleration"])) > 0.8 * mu * G  # it does reach the limit


def test_fixed_step_refuses_an_unstable_step_and_accepts_a_tiny_one():
    model = SingleTrack(SEDAN, *fiala())
    x0 = model.straight_running(20.0)
    with pytest.raises(vehdyn.SimulationError, match="stability limit"):
        vehdyn.simulate(model, np.linspace(0, 5, 11), {"front_steer_angle": 0.01}, x0=x0, method="rk4")
    # low speed makes the tire lag slow, not fast: still refused only by the step size
    t = np.linspace(0, 0.5, 5001)  # 1e-4 s steps
    fine = vehdyn.simulate(model, t, {"front_steer_angle": 0.01}, x0=x0, method="rk4")
    reference = vehdyn.simulate(model, t, {"front_steer_angle": 0.01}, x0=x0, method="DOP853", rtol=1e-11, atol=1e-12)
    assert np.allclose(fine["yaw_rate"], reference["yaw_rate"], rtol=1e-7, atol=1e-10)


def test_zero_normal_load_on_one_axle():
    model = SingleTrack(SEDAN, *fiala())
    x = model.straight_running(10.0)
    weight = SEDAN.mass.mass * G
    # a rear force that would lift the front axle: its load is held at zero, the rear carries all
    u = model.input_vector(rear_longitudinal_force=3 * weight, front_steer_angle=0.1)
    y = dict(zip(model.output_names, model.output(0.0, x, u)))
    lift = model.parameters.front_lift_factor + model.parameters.rear_lift_factor  # zero for the sedan
    assert y["front_normal_load"] == 0.0
    assert y["rear_normal_load"] == pytest.approx(weight - lift * 100.0, rel=1e-12)
    assert y["front_lateral_force"] == 0.0  # an unloaded axle steers nothing
    # the rear force is clipped at mu F_z: the acceleration stays physical
    assert y["longitudinal_acceleration"] <= SEDAN.tires.friction_coefficient * G * (1 + 1e-9)
    f = model.rhs(0.0, x, u)
    assert np.all(np.isfinite(f))
    # a static zero load (CG on an axle) is a parameter error, reported where it enters
    with pytest.raises(vehdyn.ParameterError, match="> 0"):
        model.variants(b=0.0)
    with pytest.raises(vehdyn.ParameterError, match="cg_to_rear_axle"):
        SEDAN.replace(geometry__cg_to_rear_axle=0.0)


def test_non_finite_input_is_reported_not_propagated():
    model = SingleTrack(SEDAN, LinearTire(cornering_stiffness=4e4), LinearTire(cornering_stiffness=4e4))
    with pytest.raises(vehdyn.ParameterError, match="front_steer_angle"):
        vehdyn.simulate(model, np.linspace(0, 1, 11), {"front_steer_angle": np.nan}, x0=model.straight_running(10.0))


from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

_MF_SPIN = SingleTrack(SEDAN, wheel_spin=True)  # the vehicle's Magic Formula tires, every state


@settings(max_examples=60, deadline=None)
@given(u=st.floats(-40, 40), v=st.floats(-20, 20), r=st.floats(-3, 3), psi=st.floats(-10, 10),
       omega=st.floats(-150, 150), rho_y=st.floats(-0.5, 0.5), rho_x=st.floats(-0.5, 0.5),
       steer=st.floats(-0.6, 0.6), torque=st.floats(-3000, 3000), brake=st.floats(0, 5000))
def test_rhs_and_outputs_are_finite_everywhere_on_the_domain(u, v, r, psi, omega, rho_y, rho_x, steer, torque, brake):
    # standstill, reverse, sliding sideways, spinning and locked wheels: never a NaN or an inf
    m = _MF_SPIN
    x = m.state_vector(longitudinal_velocity=u, lateral_velocity=v, yaw_rate=r, yaw_angle=psi,
                       front_wheel_speed=omega, rear_wheel_speed=-omega / 2, front_lateral_deflection=rho_y,
                       rear_lateral_deflection=-rho_y, front_longitudinal_deflection=rho_x,
                       rear_longitudinal_deflection=-rho_x)
    inputs = m.input_vector(front_steer_angle=steer, rear_drive_torque=torque, front_brake_torque=brake)
    assert np.all(np.isfinite(m.rhs(0.0, x, inputs)))
    y = dict(zip(m.output_names, m.output(0.0, x, inputs)))
    assert all(np.isfinite(value) for value in y.values())
    # the tire forces never exceed what friction allows (peak Magic Formula friction, with margin)
    assert abs(y["front_lateral_force"]) <= 1.5 * y["front_normal_load"]
