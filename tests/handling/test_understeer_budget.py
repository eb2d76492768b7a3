"""The understeer budget: each term against its closed form, the rows against understeer_gradient_deg_per_g,
and the gradients the rungs measure from their own steady states against the budget.

Gradients from trims are central differences of delta - L r / u at a_y = +-A, extrapolated with
Richardson's (4 K(A) - K(2A)) / 3 from A = 0.1 and 0.2 m/s^2: the odd terms of the steady steer in
a_y (parallel steer, load transfer under load-proportional stiffness) leave 1e-4 relative at one
A = 0.1 m/s^2 and < 1e-5 extrapolated (measured; NOTES of issue 28, B.3).
"""

import numpy as np
import pytest

import vehdyn
from vehdyn import ParameterError
from vehdyn.handling import (LinearBicycle, SteeringSystem, plot_understeer_budget, steady_roll, understeer_budget,
                             understeer_gradient_deg_per_g)
from vehdyn.handling.steering_system import SteeredVehicle, steering_system_parameters
from vehdyn.tire import LinearTire
from vehdyn.units import GRAVITY

DEG = np.rad2deg(1.0)
CARS = ("sedan", "compact", "van")


@pytest.fixture(scope="module")
def sedan():
    return vehdyn.load_vehicle("sedan")


def _everything(vehicle):
    """``vehicle`` with every term of the budget switched on (typical magnitudes, the aligning-moment ones
    5x typical so that their rows are large)."""
    return vehicle.replace(suspension__front_roll_steer=0.08, suspension__rear_roll_steer=-0.04,
                           suspension__front_camber_gain=0.6, suspension__rear_camber_gain=0.4,
                           suspension__front_lateral_force_compliance_steer=-1.0e-6,
                           suspension__rear_lateral_force_compliance_steer=0.5e-6,
                           suspension__front_aligning_moment_compliance_steer=1.0e-4,
                           suspension__rear_aligning_moment_compliance_steer=5.0e-5)


def _linear_tires(vehicle, camber=(0.0, 0.0), trails=(0.0, 0.0)):
    return tuple(LinearTire.from_vehicle(vehicle, axle).replace(camber_stiffness=c, pneumatic_trail=t)
                 for axle, c, t in zip(("front", "rear"), camber, trails))


def test_rows_are_their_formulas(sedan):
    vehicle = _everything(sedan)
    tires = _linear_tires(vehicle, camber=(-1500.0, -1200.0), trails=(0.04, 0.035))
    budget = understeer_budget(vehicle, tires=tires)
    rad = budget["rad_per_g"]
    t = vehicle.tires
    W_f, W_r = vehicle.static_axle_loads()
    C_f, C_r = t.front_cornering_stiffness, t.rear_cornering_stiffness
    assert rad["weight_distribution"] == pytest.approx(W_f / C_f - W_r / C_r, rel=1e-12)
    assert rad["lateral_load_transfer"] == 0.0  # second order in a_y
    assert rad["lateral_force_compliance_steer"] == pytest.approx(1.0e-6 * W_f + 0.5e-6 * W_r, rel=1e-12)
    # M_z = -t F_y of the linear tire: trails 0.04, 0.035 m
    assert rad["aligning_moment_compliance_steer"] == pytest.approx(1.0e-4 * 0.04 * W_f - 5.0e-5 * 0.035 * W_r,
                                                                    rel=1e-9)
    roll = steady_roll(vehicle)
    rg = roll.roll_gradient * GRAVITY
    assert rad["roll_steer"] == pytest.approx((0.08 + 0.04) * rg, rel=1e-12)
    # camber: both wheels gamma = phi + g (T/2) phi_s (SAE, phi < 0 turning right); the SAE camber stiffness
    # of an axle is -2 x the ISO-W one of a tire: +3000, +2400 N/rad
    dgamma = [-(rg + g * T / 2 * ps * GRAVITY) for g, T, ps in
              zip((0.6, 0.4), (vehicle.geometry.front_track, vehicle.geometry.rear_track),
                  roll.suspension_roll_gradient)]
    assert rad["camber_thrust"] == pytest.approx(-3000.0 / C_f * dgamma[0] + 2400.0 / C_r * dgamma[1], rel=1e-6)
    p = steering_system_parameters(vehicle)
    assert rad["steering_system_compliance"] == pytest.approx(
        (p.caster_trail + p.pneumatic_trail) * W_f / (vehicle.steering.ratio**2 * vehicle.steering.column_stiffness),
        rel=1e-12)
    np.testing.assert_allclose(budget["deg_per_g"], DEG * budget["rad_per_g"], rtol=1e-15)
    assert budget.loc["steering_system_compliance", "road_wheel"] == False  # noqa: E712
    assert budget["road_wheel"].sum() == len(budget) - 1
    assert set(budget.columns) >= {"formula", "reference"} and budget["reference"].str.contains("Gillespie").all()


@pytest.mark.parametrize("name", CARS)
@pytest.mark.parametrize("terms", ["file", "everything"])
def test_road_wheel_rows_sum_to_the_understeer_gradient(name, terms):
    vehicle = vehdyn.load_vehicle(name)
    if terms == "everything":
        vehicle = _everything(vehicle)
    budget = understeer_budget(vehicle)
    total = budget.loc[budget["road_wheel"], "deg_per_g"].sum()
    assert total == pytest.approx(understeer_gradient_deg_per_g(vehicle), rel=1e-12)
    assert budget.attrs["road_wheel_total_deg_per_g"] == pytest.approx(total, rel=1e-15)
    assert budget.attrs["hand_wheel_total_deg_per_g"] == pytest.approx(budget["deg_per_g"].sum(), rel=1e-15)
    if terms == "file":  # the shipped cars have no roll steer, camber gain or compliance: row 1 alone
        assert total == pytest.approx(budget.loc["weight_distribution", "deg_per_g"], rel=1e-15)


def _bicycle_gradient(model, speed, wheelbase=None):
    dc = model.D - model.C @ np.linalg.solve(model.A, model.B)
    j = model.index("front_steer_angle", "inputs")
    ay, r = dc[model.index("lateral_acceleration", "outputs"), j], dc[model.index("yaw_rate", "outputs"), j]
    wheelbase = model.bicycle_parameters.wheelbase if wheelbase is None else wheelbase
    return (1.0 - wheelbase * r / speed) / ay * GRAVITY * DEG


@pytest.mark.parametrize("lag", [0.0, 0.4])
def test_linear_bicycle_carries_the_compliance_rows(sedan, lag):
    vehicle = sedan.replace(suspension__front_lateral_force_compliance_steer=-1.0e-6,
                            suspension__rear_lateral_force_compliance_steer=0.5e-6,
                            suspension__front_aligning_moment_compliance_steer=1.0e-4,
                            tires__front_relaxation_length=lag, tires__rear_relaxation_length=lag)
    budget = understeer_budget(vehicle)
    rows = budget["deg_per_g"]
    assert rows["lateral_force_compliance_steer"] > 0.4 and rows["aligning_moment_compliance_steer"] > 0.1
    measured = _bicycle_gradient(LinearBicycle(vehicle, 20.0), 20.0)
    assert measured == pytest.approx(budget.attrs["road_wheel_total_deg_per_g"], rel=1e-10)


def test_steering_system_row_is_the_steered_vehicle_s(sedan):
    """Against the hand-wheel angle / N of SteeredVehicle(LinearBicycle, SteeringSystem): the road-wheel
    gradient plus the steering row."""
    model = SteeredVehicle(LinearBicycle(sedan, 20.0), SteeringSystem(sedan))
    lin = model.linearize(np.zeros(model.n_states), np.zeros(model.n_inputs))
    dc = lin.D - lin.C @ np.linalg.solve(lin.A, lin.B)
    j = lin.index("steering_wheel_angle", "inputs")
    ay, r = dc[lin.index("lateral_acceleration", "outputs"), j], dc[lin.index("yaw_rate", "outputs"), j]
    hand = (1.0 / sedan.steering.ratio - sedan.wheelbase * r / 20.0) / ay * GRAVITY * DEG
    budget = understeer_budget(sedan)
    assert hand == pytest.approx(budget.attrs["hand_wheel_total_deg_per_g"], rel=1e-9)


def _full_vehicle_gradient(model, speed=20.0):
    L = model.vehicle.wheelbase

    def k(A):
        val = []
        for a in (A, -A):
            x0, u0 = model.trim(speed, lateral_acceleration=a)
            delta = u0[model.index("front_steer_angle", "inputs")]
            val.append(delta - L * x0[model.index("yaw_rate")] / x0[model.index("longitudinal_velocity")])
        return (val[0] - val[1]) / (2 * A)

    return (4 * k(0.1) - k(0.2)) / 3 * GRAVITY * DEG


def test_full_vehicle_measures_the_budget_with_roll_steer_and_camber(sedan):
    """The full vehicle (linear tires with camber stiffness, drag off) carries the roll-steer and camber
    rows with its own roll: its gradient from its trims is the budget's road-wheel total to 1e-5
    (higher-order terms of the trims; Richardson-extrapolated)."""
    from vehdyn.full_vehicle import FullVehicle

    vehicle = sedan.replace(aero__drag_coefficient=0.0, suspension__front_roll_steer=0.08,
                            suspension__rear_roll_steer=-0.04, suspension__front_camber_gain=0.6,
                            suspension__rear_camber_gain=0.4)
    tires = _linear_tires(vehicle, camber=(-1500.0, -1200.0))
    budget = understeer_budget(vehicle, tires=tires)
    assert budget.loc["roll_steer", "deg_per_g"] > 0.5 and abs(budget.loc["camber_thrust", "deg_per_g"]) > 0.02
    measured = _full_vehicle_gradient(FullVehicle(vehicle, *tires, tire_lag=False))
    assert measured == pytest.approx(budget.attrs["road_wheel_total_deg_per_g"], rel=1e-5)


@pytest.mark.parametrize("name", CARS)
def test_full_vehicle_measures_the_shipped_budget(name):
    """Each shipped car with linear tires and no drag: the budget (row 1 alone) to 1e-5."""
    from vehdyn.full_vehicle import FullVehicle

    vehicle = vehdyn.load_vehicle(name).replace(aero__drag_coefficient=0.0)
    tires = _linear_tires(vehicle)
    measured = _full_vehicle_gradient(FullVehicle(vehicle, *tires, tire_lag=False))
    assert measured == pytest.approx(understeer_budget(vehicle).attrs["road_wheel_total_deg_per_g"], rel=1e-5)


def test_bad_input_is_refused(sedan):
    with pytest.raises(ParameterError, match="speed") as err:
        understeer_budget(sedan, speed=-1.0)
    assert err.value.key == "speed"
    with pytest.raises(ParameterError, match="front_lateral_force_compliance_steer") as err:
        sedan.replace(suspension__front_lateral_force_compliance_steer=2e-5)
    assert err.value.key == "suspension.front_lateral_force_compliance_steer"
    # with the aligning-moment compliance the net compliance c - e t is checked where the trail is known
    vehicle = sedan.replace(suspension__front_aligning_moment_compliance_steer=-1e-2)
    with pytest.raises(ParameterError, match="front_lateral_force_compliance_steer"):
        understeer_budget(vehicle)
    with pytest.raises(ParameterError, match="front_lateral_force_compliance_steer"):
        LinearBicycle(vehicle, 20.0)


def test_plot_understeer_budget(sedan):
    import matplotlib

    matplotlib.use("Agg")
    budget = understeer_budget(sedan)
    ax = plot_understeer_budget(budget, measured={"LinearBicycle": 0.2998})
    assert len(ax.patches) == len(budget)
    widths = [p.get_width() for p in ax.patches]
    np.testing.assert_allclose(sorted(widths), sorted(budget["deg_per_g"]), rtol=1e-12)


def test_lateral_yaw_roll_carries_compliance_and_roll_steer(sedan):
    """LateralYawRoll with compliance and roll steer: its DC gradient is the bicycle's with C_eff plus
    (eps_f - eps_r) times its own roll gradient (Segel's m_s h / (K_phi - m_s g h), not the full
    vehicle's: the budget's roll-steer row differs by that ratio)."""
    from vehdyn.handling import LateralYawRoll

    vehicle = sedan.replace(suspension__front_lateral_force_compliance_steer=-1.0e-6,
                            suspension__rear_lateral_force_compliance_steer=0.5e-6,
                            suspension__front_roll_steer=0.08, suspension__rear_roll_steer=-0.04)
    model = LateralYawRoll(vehicle, 20.0)
    measured = _bicycle_gradient(model, 20.0, vehicle.wheelbase)
    budget = understeer_budget(vehicle)["deg_per_g"]
    own_roll = model.parameters.roll_gradient * GRAVITY * DEG
    expected = (budget["weight_distribution"] + budget["lateral_force_compliance_steer"]
                + (0.08 + 0.04) * own_roll)
    assert measured == pytest.approx(expected, rel=1e-10)
    assert measured == pytest.approx(np.rad2deg(model.understeer_gradient() * GRAVITY), rel=1e-10)
