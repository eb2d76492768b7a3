"""vehdyn.symbolic: the CasADi forms equal the numpy models (rhs, outputs, Jacobians), the exact
linearization equals the finite-difference one and the bicycle's closed form, bad input is refused."""

import subprocess
import sys

import numpy as np
import pytest

import vehdyn
from vehdyn import Model, ParameterError
from vehdyn.handling import LateralYawRoll, LateralYawRollLag, LinearBicycle, SingleTrack
from vehdyn.tire import BrushTire, DugoffTire, FialaTire, LinearTire, TireModel

ca = pytest.importorskip("casadi")
from vehdyn.symbolic import to_casadi  # noqa: E402

SEDAN = vehdyn.load_vehicle("sedan")
RNG = np.random.default_rng(29)
LINEAR_TIRES = (LinearTire(cornering_stiffness=SEDAN.tires.front_cornering_stiffness / 2),
                LinearTire(cornering_stiffness=SEDAN.tires.rear_cornering_stiffness / 2))
OPTIONS = {
    "force": dict(tire_lag=False),
    "force_lag": dict(),
    "spin": dict(wheel_spin=True, tire_lag=False),
    "spin_lag": dict(wheel_spin=True),
    "transfer": dict(lateral_load_transfer=True),
    "transfer_spin": dict(lateral_load_transfer=True, wheel_spin=True),
    "roll": dict(lateral_load_transfer=True, roll=True),
    "roll_spin_lag": dict(lateral_load_transfer=True, roll=True, wheel_spin=True),
    "friction": dict(friction=0.6, wheel_spin=True),
    "linear_tires": dict(tire_lag=False, tires=LINEAR_TIRES),
    "linear_tires_spin_transfer": dict(wheel_spin=True, lateral_load_transfer=True, tires=LINEAR_TIRES),
    "brush_tires": dict(tire_lag=False, tires=(BrushTire.from_vehicle(SEDAN, "front"),
                                               BrushTire.from_vehicle(SEDAN, "rear"))),
    "fiala_tires_spin_lag": dict(wheel_spin=True, tires=(FialaTire.from_vehicle(SEDAN, "front"),
                                                         FialaTire.from_vehicle(SEDAN, "rear"))),
    "dugoff_tires_spin_transfer": dict(wheel_spin=True, lateral_load_transfer=True, tire_lag=False,
                                       tires=(DugoffTire.from_vehicle(SEDAN, "front"),
                                              DugoffTire.from_vehicle(SEDAN, "rear"))),
}


def single_track(name):
    options = dict(OPTIONS[name])
    tires = options.pop("tires", (None, None))
    return SingleTrack(SEDAN, *tires, **options)


def random_points(model, n=12):
    """States about straight running at 5-35 m/s, perturbed by up to 30 % (slips to the tires' limit),
    and random inputs (steer to 0.1 rad, forces to 3 kN, torques to 600 N m)."""
    points = []
    for _ in range(n):
        x = model.straight_running(RNG.uniform(5.0, 35.0))
        x = x + RNG.uniform(-0.3, 0.3, x.size) * np.maximum(np.abs(x), 0.05)
        scale = np.array([0.1 if "steer" in s else 3000.0 if "force" in s else 600.0 if "torque" in s else 5.0
                          for s in model.input_names])
        points.append((x, RNG.uniform(-1.0, 1.0, model.n_inputs) * scale))
    return points


def assert_equal_within(ours, theirs, rtol=1e-10):
    ours, theirs = np.asarray(ours, float).ravel(), np.asarray(theirs, float).ravel()
    assert np.all(np.isfinite(ours)) and ours.shape == theirs.shape
    np.testing.assert_allclose(ours, theirs, rtol=rtol, atol=1e-3 * rtol * np.max(np.abs(theirs)))


@pytest.fixture(scope="module", params=list(OPTIONS))
def pair(request):
    model = single_track(request.param)
    return model, to_casadi(model)


@pytest.mark.compiled_vs_numpy
def test_single_track_rhs_and_outputs_equal_numpy_at_random_states(pair):
    model, form = pair
    assert (form.state_names, form.input_names, form.output_names) == (model.state_names, model.input_names,
                                                                      model.output_names)
    for x, u in random_points(model):
        assert_equal_within(form.rhs(x, u), model.rhs(0.0, x, u))
        assert_equal_within(form.output(x, u), model.output(0.0, x, u))


def central_differences(model, x, u):
    """(df/dx, df/du, dg/dx, dg/du) of the numpy model by the four-point central stencil, with steps
    scaled to each variable (1e-4 of its size, at least 1e-7: the deflections are millimetres)."""
    z0 = np.concatenate([x, u])
    columns_f, columns_g = [], []
    for i in range(z0.size):
        h = 1e-4 * max(abs(z0[i]), 1e-3)
        values = []
        for s in (-2.0, -1.0, 1.0, 2.0):
            z = z0.copy()
            z[i] += s * h
            values.append((model.rhs(0.0, z[:x.size], z[x.size:]), model.output(0.0, z[:x.size], z[x.size:])))
        step = (z0[i] + h) - z0[i]
        columns_f.append((values[0][0] - 8 * values[1][0] + 8 * values[2][0] - values[3][0]) / (12 * step))
        columns_g.append((values[0][1] - 8 * values[1][1] + 8 * values[2][1] - values[3][1]) / (12 * step))
    jf, jg = np.array(columns_f).T, np.array(columns_g).T
    return jf[:, :x.size], jf[:, x.size:], jg[:, :x.size], jg[:, x.size:]


def test_single_track_jacobians_equal_central_differences(pair):
    model, form = pair
    for x, u in random_points(model, n=3):
        for ours, theirs, name in zip(form.linear_matrices(x, u), central_differences(model, x, u), "ABCD"):
            # the stencil's error: truncation (h^4) and rounding (eps |f| / h), ~1e-8 of the largest entry
            assert np.allclose(ours, theirs, rtol=1e-6, atol=1e-7 * max(np.max(np.abs(theirs)), 1.0)), name


@pytest.mark.parametrize("model", [LinearBicycle(SEDAN, 20.0, tire_lag=True, crosswind=True),
                                   LateralYawRoll(SEDAN, 25.0), LateralYawRollLag(SEDAN, 25.0)],
                         ids=["bicycle", "lateral_yaw_roll", "lateral_yaw_roll_lag"])
def test_linear_models_equal_numpy(model):
    form = to_casadi(model)
    for _ in range(5):
        x, u = RNG.normal(size=model.n_states), RNG.normal(size=model.n_inputs)
        assert_equal_within(form.rhs(x, u), model.rhs(0.0, x, u), rtol=1e-13)
        assert_equal_within(form.output(x, u), model.output(0.0, x, u), rtol=1e-13)
    for ours, theirs in zip(form.linear_matrices(x, u), (model.A, model.B, model.C, model.D)):
        assert np.array_equal(ours, theirs)


@pytest.mark.parametrize("speed", [5.0, 20.0, 40.0])
def test_exact_linearization_is_the_bicycle_closed_form(speed):
    # with linear tires and no tire lag the lateral-yaw block of the single track is the bicycle model
    # (Rajamani 2012, eq. 2.31): exactly, where the finite-difference one agrees to ~1e-8
    model = SingleTrack(SEDAN, *LINEAR_TIRES, tire_lag=False)
    full = model.linearize(speed=speed, u0=model.input_vector(), method="exact")
    bike = LinearBicycle(SEDAN, speed)
    keep = [model.index("lateral_velocity"), model.index("yaw_rate")]
    inputs = [model.index(n, "inputs") for n in ("front_steer_angle", "rear_steer_angle")]
    outputs = [model.index(n, "outputs") for n in bike.output_names]
    blocks = {"A": full.A[np.ix_(keep, keep)], "B": full.B[np.ix_(keep, inputs)],
              "C": full.C[np.ix_(outputs, keep)], "D": full.D[np.ix_(outputs, inputs)]}
    for name, ours in blocks.items():
        theirs = getattr(bike, name)
        assert np.allclose(ours, theirs, rtol=1e-12, atol=1e-12 * np.max(np.abs(theirs))), name


def test_exact_linearization_equals_finite_differences_within_their_error():
    model = SingleTrack(SEDAN, wheel_spin=True, lateral_load_transfer=True)
    x0 = model.straight_running(25.0, yaw_rate=0.2, lateral_velocity=-0.4)
    exact = model.linearize(x0, method="exact")
    numeric = model.linearize(x0)
    for name in "ABCD":
        ours, theirs = getattr(exact, name), getattr(numeric, name)
        # Model.linearize's step is 7e-4 of a unit for every variable: ~5e-6 of the largest entry in the
        # columns of the millimetre-sized tire deflections (1e-9 elsewhere)
        assert np.allclose(ours, theirs, rtol=1e-6, atol=1e-5 * max(np.max(np.abs(theirs)), 1.0)), name
    assert np.allclose(exact.y_op, numeric.y_op, rtol=0, atol=0)
    assert exact.state_names == model.state_names


@pytest.mark.parametrize("options, names", [
    (dict(wheel_spin=True), ("mass", "yaw_inertia", "cg_height", "a", "b", "drag_factor")),
    (dict(lateral_load_transfer=True, roll=True), ("yaw_inertia", "front_lateral_relaxation_length"))],
    ids=["spin", "roll"])
def test_parameters_become_a_third_argument(options, names):
    model = SingleTrack(SEDAN, **options)
    form = to_casadi(model, parameters=names)
    assert form.parameter_names == names
    own = np.array([getattr(model.parameters, n) for n in names])
    assert np.array_equal(form.parameter_values, own)
    changed = own * RNG.uniform(0.8, 1.2, own.size)
    other = model.variants(**dict(zip(names, changed)))
    for x, u in random_points(model, n=4):
        assert_equal_within(form.rhs(x, u, own), model.rhs(0.0, x, u))
        assert_equal_within(form.rhs(x, u, changed), other.rhs(0.0, x, u))
        assert_equal_within(form.output(x, u, changed), other.output(0.0, x, u))


class _Plain(Model):
    def __init__(self):
        self.declare(states=["x"], inputs=["u"], outputs=["x"])

    def rhs(self, t, x, u):
        return -x + u

    def output(self, t, x, u):
        return x


class _Delegating(TireModel):
    """A law of the user's own (here the Fiala law's forces behind it): no kernel over xp."""

    def __init__(self, law):
        self.law = law

    def forces(self, fz, kappa, alpha, gamma=0.0, vx=10.0):
        return self.law.forces(fz, kappa, alpha, gamma, vx)


TIRE_LAWS = {
    "brush": BrushTire.from_vehicle(SEDAN, "front"),
    "brush_sliding_friction": BrushTire(contact_half_length=0.08, tread_stiffness=5e6, mu=1.0, mu_sliding=0.8),
    "fiala": FialaTire.from_vehicle(SEDAN, "front"),
    "fiala_moment_slip_stiffness": FialaTire(cornering_stiffness=6e4, mu=0.9, slip_stiffness=8e4,
                                             contact_half_length=0.07),
    "dugoff": DugoffTire.from_vehicle(SEDAN, "rear"),
    "dugoff_speed_reduction_trail": DugoffTire(cornering_stiffness=6e4, slip_stiffness=9e4, mu=0.9,
                                               speed_friction_reduction=0.01, pneumatic_trail=0.03),
}


@pytest.mark.compiled_vs_numpy
@pytest.mark.parametrize("name", list(TIRE_LAWS))
def test_brush_fiala_and_dugoff_kernels_on_casadi_equal_their_forces(name):
    # the law's xp_kernel on CasADi symbols against forces() on numpy, at random points from adhesion to full
    # sliding, braking to locked (kappa -1) and driving, both rolling directions
    from vehdyn.symbolic.namespace import casadi_namespace

    law = TIRE_LAWS[name]
    symbols = [ca.SX.sym(n) for n in ("fz", "kappa", "alpha", "vx")]
    fx, fy, mz = law.xp_kernel(casadi_namespace(), symbols[0], symbols[1], symbols[2], 0.0, symbols[3])
    kernel = ca.Function("kernel", symbols, [fx, fy, 0.0 * fy if mz is None else mz])
    rng = np.random.default_rng(7)
    points = np.column_stack([rng.uniform(0.0, 9000.0, 200), rng.uniform(-1.0, 1.5, 200),
                              rng.uniform(-0.6, 0.6, 200), rng.uniform(-30.0, 30.0, 200)])
    points[:20, 1] = 0.0  # pure side slip
    points[20:30, 2] = 0.0  # pure longitudinal slip
    expected = law.forces(points[:, 0], points[:, 1], points[:, 2], 0.0, points[:, 3])
    got = np.array(kernel(*points.T), dtype=float)
    for row, value in zip(got, (expected.fx, expected.fy, expected.mz)):
        np.testing.assert_allclose(row.ravel(), value, rtol=1e-10, atol=1e-10 * np.max(np.abs(value)) + 1e-300)


def test_bad_input_is_refused_with_the_model_and_the_missing_piece():
    with pytest.raises(ParameterError, match="_Plain has no symbolic form.*symbolic_equations"):
        to_casadi(_Plain())
    with pytest.raises(ParameterError, match="front_tire.*_Delegating") as error:
        to_casadi(SingleTrack(SEDAN, _Delegating(FialaTire.from_vehicle(SEDAN, "front")), LINEAR_TIRES[1]))
    assert error.value.key == "front_tire"
    with pytest.raises(ParameterError, match="'wheelbase' is not a SingleTrack parameter"):
        to_casadi(SingleTrack(SEDAN), parameters=("wheelbase",))
    with pytest.raises(ParameterError, match="function of position"):
        to_casadi(SingleTrack(SEDAN, friction=lambda X, Y: 0.8 + 0.0 * X))
    with pytest.raises(ParameterError, match="mass sets the transfer coefficients"):
        to_casadi(SingleTrack(SEDAN, lateral_load_transfer=True), parameters=("mass",))
    with pytest.raises(ParameterError, match="no symbolic parameters"):
        to_casadi(LinearBicycle(SEDAN, 20.0), parameters=("mass",))
    with pytest.raises(ParameterError, match="names"):
        to_casadi(SingleTrack(SEDAN), parameters=(3,))
    with pytest.raises(ParameterError, match="method"):
        SingleTrack(SEDAN).linearize(speed=20.0, method="symbolic")


def test_importing_vehdyn_does_not_import_casadi():
    code = "import sys, vehdyn, vehdyn.symbolic; print('casadi' in sys.modules)"
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert result.stdout.strip() == "False"


@pytest.fixture(scope="module")
def full_vehicle_pair():
    from vehdyn.full_vehicle import FullVehicle

    model = FullVehicle(SEDAN)
    return model, to_casadi(model)


@pytest.mark.compiled_vs_numpy
def test_full_vehicle_rhs_and_outputs_equal_numpy_at_random_states(full_vehicle_pair):
    model, form = full_vehicle_pair
    for speed, ay in ((10.0, 0.0), (20.0, 4.0), (30.0, -6.0)):
        x0, u0 = model.trim(speed, lateral_acceleration=ay)
        for _ in range(3):
            x = x0 + RNG.uniform(-0.05, 0.05, x0.size) * np.maximum(np.abs(x0), 0.05)
            u = u0 + RNG.uniform(-0.05, 0.05, u0.size) * np.maximum(np.abs(u0), 0.01)
            assert_equal_within(form.rhs(x, u), model.rhs(0.0, x, u))
            assert_equal_within(form.output(x, u), model.output(0.0, x, u))


def test_full_vehicle_jacobian_equals_central_differences(full_vehicle_pair):
    model, form = full_vehicle_pair
    x, u = model.trim(20.0, lateral_acceleration=3.0)
    for ours, theirs, name in zip(form.linear_matrices(x, u), central_differences(model, x, u), "ABCD"):
        assert np.allclose(ours, theirs, rtol=1e-6, atol=1e-7 * max(np.max(np.abs(theirs)), 1.0)), name
