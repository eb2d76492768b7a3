"""LateralYawRollLag: the full vehicle's linear lateral-yaw-roll reduction with tire lag."""

import numpy as np
import pytest

import vehdyn
from vehdyn.handling import LateralYawRollLag
from vehdyn.handling.bicycle import BicycleParameters
from vehdyn.handling.lateral_yaw_roll_lag import running_axle_loads, running_slip_ratios
from vehdyn.handling.steady_state import steady_state_gains
from vehdyn.tire import tire_for_vehicle
from vehdyn.units import GRAVITY


def test_without_ply_steer_the_steady_state_is_the_bicycles():
    """Linear tire laws (no force at zero slip) leave no ply-steer term; roll then has no steady
    effect on the yaw (no roll steer), and the steady-state gains are the bicycle's closed forms
    u / (L + K u^2) with the model's own axle stiffnesses (Gillespie 1992, eq. 6-15)."""
    vehicle = vehdyn.load_vehicle("sedan")
    tires = [tire_for_vehicle(vehicle, axle, "linear") for axle in ("front", "rear")]
    model = LateralYawRollLag(vehicle, 20.0, front_tire=tires[0], rear_tire=tires[1])
    assert model.ply_steer_load_coefficient == (0.0, 0.0)
    cf, cr = model.cornering_stiffness
    bicycle = BicycleParameters(mass=vehicle.mass.mass, yaw_inertia=vehicle.mass.yaw_inertia, a=vehicle.geometry.a,
                                b=vehicle.geometry.b, front_cornering_stiffness=cf, rear_cornering_stiffness=cr)
    closed = steady_state_gains(bicycle, 20.0)
    A, B, C, D = model.A, model.B, model.C, model.D
    steady = -C @ np.linalg.solve(A, B[:, 0]) + D[:, 0]
    assert steady[model.index("yaw_rate", "outputs")] == pytest.approx(closed.yaw_rate, rel=1e-9)
    assert steady[model.index("lateral_acceleration", "outputs")] == pytest.approx(closed.lateral_acceleration,
                                                                                   rel=1e-9)


def test_cornering_stiffness_is_the_law_at_the_running_loads():
    """At 30 m/s the drive force that holds the speed against the drag moves h_s F_drag / L from
    the front to the rear axle (moment balance about the ground); the axle stiffness is twice the
    tire law's slope at half that axle load (central difference here, independent of the model)."""
    vehicle = vehdyn.load_vehicle("sedan")
    u = 30.0
    aero = vehicle.aero
    shift = vehicle.mass.sprung_cg_height * 0.5 * aero.air_density * aero.frontal_area * aero.drag_coefficient \
        * u**2 / vehicle.geometry.wheelbase
    static = vehicle.static_axle_loads(GRAVITY)
    loads = running_axle_loads(vehicle, u)
    assert loads == pytest.approx((static[0] - shift, static[1] + shift), rel=1e-12)
    model = LateralYawRollLag(vehicle, u)
    tires = [tire_for_vehicle(vehicle, axle) for axle in ("front", "rear")]
    slips = running_slip_ratios(vehicle, tires, loads, u)
    for k, tire in enumerate(tires):
        h = 1e-5
        slope = (tire.forces(0.5 * loads[k], slips[k], h, 0.0, 20.0).fy
                 - tire.forces(0.5 * loads[k], slips[k], -h, 0.0, 20.0).fy)
        assert model.cornering_stiffness[k] == pytest.approx(abs(float(slope)) / h, rel=1e-5)


@pytest.mark.parametrize("name", ["sedan", "van"])
def test_running_slip_ratios_balance_the_wheels_and_the_drag(name):
    """In steady running every wheel's torque balances, R_e F_x = T + M_y, with the drive torque
    split by the driveline and equal on both sides: the four F_x add up to the drag, and an axle
    without drive torque has F_x = M_y / R_e."""
    vehicle = vehdyn.load_vehicle(name)
    u = 30.0
    tires = [tire_for_vehicle(vehicle, axle) for axle in ("front", "rear")]
    loads = running_axle_loads(vehicle, u)
    slips = running_slip_ratios(vehicle, tires, loads, u)
    out = [t.forces(0.5 * load, k, 0.0, 0.0, u) for t, load, k in zip(tires, loads, slips)]
    fx = np.array([float(o.fx) for o in out])
    my = np.array([float(o.my) for o in out])
    aero = vehicle.aero
    drag = 0.5 * aero.air_density * aero.frontal_area * aero.drag_coefficient * u**2
    assert 2.0 * fx.sum() == pytest.approx(drag, rel=1e-6)
    radius, share = vehicle.tires.rolling_radius, vehicle.driveline.front_drive_fraction
    torque = 2.0 * (radius * fx - my)  # drive torque per axle
    assert torque[0] == pytest.approx(share * torque.sum(), abs=1e-6 * abs(torque.sum()))


def test_lateral_acceleration_is_the_axle_forces_over_the_mass():
    """a_y of the total CG is Newton's (F_f + F_r) / m at every instant of a step steer (the body's
    roll acceleration makes it differ from dv/dt + u r of the non-rolling frame)."""
    vehicle = vehdyn.load_vehicle("compact")
    model = LateralYawRollLag(vehicle, 20.0)
    t = np.linspace(0.0, 2.0, 401)
    res = vehdyn.simulate(model, t, {"front_steer_angle": vehdyn.procedures.step_steer(0.01, 0.2, 0.1)},
                          method="exact")
    total = (res["front_lateral_force"] + res["rear_lateral_force"]) / vehicle.mass.mass
    assert np.max(np.abs(res["lateral_acceleration"] - total)) < 1e-9 * np.max(np.abs(total))
    frame_rate = np.gradient(res["lateral_velocity"], t) + 20.0 * res["yaw_rate"]
    assert np.max(np.abs(frame_rate - total)) > 0.01 * np.max(np.abs(total))  # the roll acceleration shows


@pytest.mark.parametrize("name", ["sedan", "van"])
def test_steady_turn_matches_the_full_vehicle_trim(name):
    """The full vehicle's steady turn at 0.05 g and 22.2 m/s (FullVehicle.trim, its nonlinear
    equations) needs the steer angle the model's steady-state gain gives, within 1 % (the bicycle
    with the vehicle file's stiffnesses is 3 % off: drag load transfer and ply steer). Measured:
    0.6 % (sedan) and 0.8 % (van) with the right wheels mirrored (the file's TYRESIDE 'LEFT'),
    0.5 % for both with the left ones: the ply steer of the linear model is the law's at zero
    slip only."""
    from vehdyn.full_vehicle import FullVehicle

    vehicle = vehdyn.load_vehicle(name)
    u, a_y = 22.2, 0.05 * GRAVITY
    full = FullVehicle(vehicle)
    _, inputs = full.trim(u, lateral_acceleration=a_y)
    steer = inputs[full.index("front_steer_angle", "inputs")]
    model = LateralYawRollLag(vehicle, u)
    gain = (-model.C @ np.linalg.solve(model.A, model.B[:, 0]) + model.D[:, 0])[model.index("lateral_acceleration",
                                                                                            "outputs")]
    assert a_y / gain == pytest.approx(steer, rel=1e-2)
    bicycle = float(steady_state_gains(vehicle, u).lateral_acceleration)
    assert abs(a_y / bicycle / steer - 1.0) > 0.01


def test_errors():
    with pytest.raises(vehdyn.ParameterError, match="vehicle"):
        LateralYawRollLag("sedan", 20.0)
    with pytest.raises(vehdyn.ParameterError):
        LateralYawRollLag(vehdyn.load_vehicle("sedan"), -1.0)


def _equal_responses(a, b, outputs=("yaw_rate", "lateral_acceleration", "roll_angle", "sideslip_angle")):
    """The two models' frequency responses from both steer inputs to ``outputs`` at 0-5 Hz, as arrays."""
    w = 2 * np.pi * np.array([0.0, 0.2, 0.7, 1.5, 3.0, 5.0])

    def response(model):
        out = [model.index(name, "outputs") for name in outputs]
        rows = []
        for omega in w:
            G = model.C @ np.linalg.solve(1j * omega * np.eye(model.A.shape[0]) - model.A, model.B) + model.D
            rows.append(G[out])
        return np.array(rows)

    return response(a), response(b)


@pytest.mark.parametrize("c, e", [(-1.2e-6, 0.0), (0.0, 2e-4), (-1.2e-6, 2e-4)])
def test_compliance_steer_is_an_effective_stiffness_and_relaxation_length(c, e):
    """Linear laws with a pneumatic trail t: the compliance steer (c - e t) F_i, explicit in the
    lagged force, makes (sigma/u) alpha'' + (1 - (c - e t) C) alpha' = alpha - delta, which is the
    model without compliance with the tire stiffness C / (1 - (c - e t) C) and the relaxation length
    sigma / (1 - (c - e t) C) (Gillespie 1992, Table 6.1, for the steady part): every transfer
    function from the steer to the body's motion is the same."""
    vehicle = vehdyn.load_vehicle("sedan")
    trail = 0.035
    laws = [vehdyn.tire.LinearTire.from_vehicle(vehicle, axle).replace(pneumatic_trail=trail)
            for axle in ("front", "rear")]
    compliant = vehicle.replace(suspension__front_lateral_force_compliance_steer=c,
                                suspension__rear_lateral_force_compliance_steer=-0.5 * c,
                                suspension__front_aligning_moment_compliance_steer=e,
                                suspension__rear_aligning_moment_compliance_steer=0.5 * e)
    model = LateralYawRollLag(compliant, 20.0, front_tire=laws[0], rear_tire=laws[1])
    net = model.compliance_steer
    assert net == pytest.approx((c - e * trail, -0.5 * c - 0.5 * e * trail), rel=1e-6)
    factor = [1.0 - n * C for n, C in zip(net, model.cornering_stiffness)]
    stiff = [law.replace(cornering_stiffness=law.cornering_stiffness / f) for law, f in zip(laws, factor)]
    equivalent = vehicle.replace(tires__front_relaxation_length=vehicle.tires.front_relaxation_length / factor[0],
                                 tires__rear_relaxation_length=vehicle.tires.rear_relaxation_length / factor[1])
    reference = LateralYawRollLag(equivalent, 20.0, front_tire=stiff[0], rear_tire=stiff[1])
    assert reference.cornering_stiffness == pytest.approx([C / f for C, f in zip(model.cornering_stiffness, factor)],
                                                          rel=1e-9)
    got, expected = _equal_responses(model, reference)
    np.testing.assert_allclose(got, expected, rtol=1e-9, atol=1e-12 * np.abs(expected).max())
    # and the compliance is not nothing: the steady yaw gain moved
    rigid = LateralYawRollLag(vehicle, 20.0, front_tire=laws[0], rear_tire=laws[1])
    moved, _ = _equal_responses(model, rigid)
    assert abs(moved[0, 0, 0] - _equal_responses(rigid, rigid)[0][0, 0, 0]) > 1e-3 * abs(moved[0, 0, 0])


def test_compliance_steer_gradient_with_the_shipped_law():
    """Magic Formula tires: the steady understeer gradient moves by the compliance rows of the
    budget evaluated with the model's own running stiffnesses, m/L (b (1/C_f,eff - 1/C_f) -
    a (1/C_r,eff - 1/C_r)) = m/L (-b n_f + a n_r) (Gillespie 1992, Table 6.1), within the ply-steer
    and rolling-resistance couplings of the load transfer (second order in the compliance)."""
    vehicle = vehdyn.load_vehicle("sedan")
    compliant = vehicle.replace(suspension__front_lateral_force_compliance_steer=-1.0e-6,
                                suspension__rear_lateral_force_compliance_steer=0.5e-6,
                                suspension__front_aligning_moment_compliance_steer=5e-5)
    u = 20.0

    def gradient(model):  # K from the steady yaw gain u / (L + K u^2)
        steady = -model.C @ np.linalg.solve(model.A, model.B[:, 0]) + model.D[:, 0]
        return (u / steady[model.index("yaw_rate", "outputs")] - vehicle.wheelbase) / u**2

    rigid, model = LateralYawRollLag(vehicle, u), LateralYawRollLag(compliant, u)
    nf, nr = model.compliance_steer
    assert nf < -1e-6  # the aligning-moment compliance adds to the front's lateral-force compliance
    m, L = vehicle.mass.mass, vehicle.wheelbase
    expected = m / L * (-vehicle.geometry.b * nf + vehicle.geometry.a * nr)
    assert gradient(model) - gradient(rigid) == pytest.approx(expected, rel=0.01)  # 0.4 % measured


def test_compliance_without_an_effective_stiffness_names_the_field():
    """The vehicle file checks c C < 1 with its own stiffness; the trail of the aligning-moment
    compliance and the running stiffness are checked here, (c - e t) C < 1."""
    vehicle = vehdyn.load_vehicle("sedan").replace(suspension__rear_aligning_moment_compliance_steer=-1e-2)
    with pytest.raises(vehdyn.errors.ParameterError, match="rear_lateral_force_compliance_steer") as info:
        LateralYawRollLag(vehicle, 20.0)
    assert info.value.key == "suspension.rear_lateral_force_compliance_steer"
