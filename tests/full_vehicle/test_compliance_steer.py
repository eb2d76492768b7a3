"""The full vehicle carries compliance steer (issue 28): each wheel steers by 2 c_i F_y + 2 e_i M_z of its
own force and its law's aligning moment (the axle's c_i F_y,i + e_i M_z,i when its wheels share them).

* Its understeer gradient from its own trims equals the budget's road-wheel total
  (:func:`vehdyn.handling.understeer_budget`) for a sedan with every term on (roll steer, camber gains,
  both compliances), linear tires with camber stiffness and pneumatic trail, no drag; with and without
  tire lag. Central differences at a_y = +-0.1 and +-0.2 m/s^2, Richardson-extrapolated (as
  tests/handling/test_understeer_budget.py): the fourth-order term left is ~1e-8 relative; measured
  6.5e-9; 1e-7 allowed.
* The output compliance steer is the closed form of the wheel's final force (M_z = -t F_y of the
  linear law): explicit with tire lag, Newton and secant steps without.
* numpy, compiled and CasADi evaluate the same equations.
"""

import numpy as np
import pytest

from tests._tolerances import ONE_CALL_ULPS, assert_close_ulps
from vehdyn import ParameterError
from vehdyn.full_vehicle import FullVehicle
from vehdyn.full_vehicle.corner import CORNERS
from vehdyn.handling import understeer_budget
from vehdyn.tire import LinearTire
from vehdyn.units import GRAVITY

# the sedan with every term on and its linear tires: those of the single track's test
from tests.handling.test_single_track_understeer_terms import SEDAN, TERMS, TIRES, VEHICLE  # noqa: E402

DEG = np.rad2deg(1.0)
TRAILS = (0.04, 0.035)  # the linear tires' pneumatic trails [m]


def _gradient(model, speed=20.0):
    L = model.vehicle.wheelbase

    def k(A):
        val = []
        for a in (A, -A):
            x0, u0 = model.trim(speed, lateral_acceleration=a)
            val.append(u0[model.index("front_steer_angle", "inputs")]
                       - L * x0[model.index("yaw_rate")] / x0[model.index("longitudinal_velocity")])
        return (val[0] - val[1]) / (2 * A)

    return (4 * k(0.1) - k(0.2)) / 3 * GRAVITY * DEG


@pytest.mark.parametrize("tire_lag", [True, False], ids=["lag", "no_lag"])
def test_gradient_is_the_budget_with_every_term(tire_lag):
    budget = understeer_budget(VEHICLE, tires=TIRES)
    for row in ("roll_steer", "camber_thrust", "lateral_force_compliance_steer", "aligning_moment_compliance_steer"):
        assert abs(budget.loc[row, "deg_per_g"]) > 0.05, row
    measured = _gradient(FullVehicle(VEHICLE, *TIRES, tire_lag=tire_lag))
    assert measured == pytest.approx(budget.attrs["road_wheel_total_deg_per_g"], rel=1e-7)


@pytest.mark.parametrize("tire_lag", [True, False], ids=["lag", "no_lag"])
def test_compliance_steer_output_is_the_wheel_s_closed_form(tire_lag):
    """At a trim at 4 m/s^2: 2 c F_y - 2 e t F_y of each wheel's final force. Measured with lag 1e-8
    (the forces the explicit step took moved only through the load's dependence on the steer), without
    1e-7 (the secant step's second order); 1e-6 allowed."""
    model = FullVehicle(VEHICLE, *TIRES, tire_lag=tire_lag)
    x0, u0 = model.trim(20.0, lateral_acceleration=4.0)
    y = dict(zip(model.output_names, model.output(0.0, x0, u0)))
    s = VEHICLE.suspension
    for sfx in CORNERS:
        axle = sfx.split("_")[1]
        force = y[f"lateral_force{sfx}"]
        expected = 2 * (getattr(s, f"{axle}_lateral_force_compliance_steer")
                        - getattr(s, f"{axle}_aligning_moment_compliance_steer") * TRAILS[axle == "rear"]) * force
        assert abs(expected) > 1e-3, sfx
        assert y[f"compliance_steer_angle{sfx}"] == pytest.approx(expected, rel=1e-6), sfx


@pytest.mark.compiled_vs_numpy
@pytest.mark.parametrize("tires", ["magic_formula", "linear"])
@pytest.mark.parametrize("tire_lag", [True, False], ids=["lag", "no_lag"])
def test_compiled_equals_numpy(tires, tire_lag):
    """Points about trims at 0, 4 and -6 m/s^2: the compiled rhs and outputs equal numpy's. Both run the
    same equations, numpy's transcendental ufuncs against the C library: ONE_CALL_ULPS per value, or
    1e-12 of the largest value for the sums of larger terms the tire law's chains feed (as
    tests/full_vehicle/test_full_vehicle_compiled.py)."""
    model = FullVehicle(SEDAN.replace(**TERMS), *(TIRES if tires == "linear" else (None, None)), tire_lag=tire_lag)
    compiled = model.compiled_rhs()
    rng = np.random.default_rng(28)
    for speed, ay in ((10.0, 0.0), (20.0, 4.0), (30.0, -6.0)):
        x0, u0 = model.trim(speed, lateral_acceleration=ay)
        for _ in range(2):
            x = x0 + rng.uniform(-0.05, 0.05, x0.size) * np.maximum(np.abs(x0), 0.05)
            u = u0 + rng.uniform(-0.05, 0.05, u0.size) * np.maximum(np.abs(u0), 0.01)
            dxdt, y = np.empty(model.n_states), np.empty(model.n_outputs)
            compiled.rhs(0.0, x, u, compiled.args, dxdt)
            compiled.output(0.0, x, u, compiled.args, y)
            assert_close_ulps(dxdt, model.rhs(0.0, x, u), ulps=ONE_CALL_ULPS, rtol=1e-12, what="compiled vs numpy rhs")
            assert_close_ulps(y, model.output(0.0, x, u), ulps=ONE_CALL_ULPS, rtol=1e-12,
                              what="compiled vs numpy outputs")


@pytest.mark.parametrize("tire_lag", [True, False], ids=["lag", "no_lag"])
def test_casadi_equals_numpy(tire_lag):
    pytest.importorskip("casadi")
    from vehdyn.symbolic import to_casadi

    model = FullVehicle(SEDAN.replace(**TERMS), tire_lag=tire_lag)
    form = to_casadi(model)
    assert form.output_names == model.output_names
    rng = np.random.default_rng(29)
    for speed, ay in ((20.0, 4.0), (30.0, -6.0)):
        x0, u0 = model.trim(speed, lateral_acceleration=ay)
        x = x0 + rng.uniform(-0.05, 0.05, x0.size) * np.maximum(np.abs(x0), 0.05)
        u = u0 + rng.uniform(-0.05, 0.05, u0.size) * np.maximum(np.abs(u0), 0.01)
        for ours, theirs in ((form.rhs(x, u), model.rhs(0.0, x, u)), (form.output(x, u), model.output(0.0, x, u))):
            ours, theirs = np.ravel(ours), np.ravel(theirs)
            np.testing.assert_allclose(ours, theirs, rtol=1e-10, atol=1e-13 * np.max(np.abs(theirs)))


def test_shipped_car_has_no_compliance_outputs():
    model = FullVehicle(SEDAN)
    assert model.constants().compliance_on == 0.0
    assert not any(name.startswith("compliance_steer_angle") for name in model.output_names)


def test_a_compliance_the_law_cannot_carry_is_refused():
    """(c - e t) C >= 1 with the model's law (stiffer than the file's, which the Vehicle checks)."""
    vehicle = SEDAN.replace(suspension__front_lateral_force_compliance_steer=5e-6)
    stiff = LinearTire.from_vehicle(vehicle, "front").replace(cornering_stiffness=1.5e5)
    with pytest.raises(ParameterError, match="front_lateral_force_compliance_steer") as err:
        FullVehicle(vehicle, stiff, None)
    assert err.value.key == "suspension.front_lateral_force_compliance_steer" and err.value.value == 5e-6
