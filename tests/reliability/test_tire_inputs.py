"""Tire-law inputs that are not finite give NaN at exactly those points, bools are refused.

The policy (vehdyn.tire.base): on every law and both Magic Formula backends a point whose input is
NaN or infinite comes out NaN in every output and no other point changes; a bool or non-numeric
input raises ParameterError naming it. References: the same law at the same points with the bad
values replaced by finite ones (a pointwise law must not let one point change another), the
scalar evaluation of each point, and the existing behaviour at the legitimate edges (lift-off,
standstill, large finite inputs).
"""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import vehdyn
from vehdyn import ParameterError
from vehdyn.tire import BrushTire, DugoffTire, FialaTire, LinearTire, MagicFormula, TireForces
from vehdyn.tire.magic_formula import numba_available
from vehdyn.tire.terramechanics import SoftSoilTire, SoftSoilTireGeometry, load_soil

INPUTS = ("fz", "kappa", "alpha", "gamma", "vx")
NON_FINITE = (math.nan, math.inf, -math.inf)
FIELDS = TireForces._fields
BACKENDS = ["numpy"] + (["numba"] if numba_available() else [])


@functools.cache
def magic_formula(name: str = "MagicFormula61_Parameters") -> MagicFormula:
    return MagicFormula.from_tir(vehdyn.data_path("tires", name + ".tir"))


SIMPLE_LAWS = {
    "linear": LinearTire(cornering_stiffness=80000.0, slip_stiffness=100000.0, camber_stiffness=3000.0,
                         pneumatic_trail=0.03, nominal_load=4000.0),
    "brush": BrushTire(contact_half_length=0.08, tread_stiffness=6e6, mu=1.0, mu_sliding=0.8),
    "fiala": FialaTire(cornering_stiffness=80000.0, mu=1.0, contact_half_length=0.08),
    "dugoff": DugoffTire(cornering_stiffness=80000.0, slip_stiffness=100000.0, mu=1.0, speed_friction_reduction=0.01,
                         pneumatic_trail=0.02),
    "soft_soil": SoftSoilTire(SoftSoilTireGeometry(radius=0.32, width=0.205, inflation_pressure=2.2e5),
                              load_soil("dry_sand")),
}


def forces_function(law: str, backend: str = "numpy"):
    """``forces(fz, kappa, alpha, gamma, vx)`` of one law (and, for the Magic Formula, one backend)."""
    if law in SIMPLE_LAWS:
        return SIMPLE_LAWS[law].forces
    tire = magic_formula()
    return functools.partial(tire.forces, backend=backend)


LAWS = list(SIMPLE_LAWS) + [f"magic_formula-{b}" for b in BACKENDS]


def law_forces(law):
    name, _, backend = law.partition("-")
    return forces_function(name, backend or "numpy")


def point(n=5, seed=0):
    """``n`` finite combined-slip points, both directions of travel, one standstill."""
    rng = np.random.default_rng(seed)
    args = [rng.uniform(500.0, 8000.0, n), rng.uniform(-0.3, 0.3, n), rng.uniform(-0.25, 0.25, n),
            rng.uniform(-0.05, 0.05, n), rng.uniform(-30.0, 30.0, n)]
    args[4][-1] = 0.0
    return args


def assert_nan_exactly_at(out, clean, bad):
    for field in FIELDS:
        value, reference = np.asarray(getattr(out, field)), np.asarray(getattr(clean, field))
        assert np.isnan(value[bad]).all(), (field, value)
        np.testing.assert_allclose(value[~bad], reference[~bad], rtol=1e-13, atol=1e-9, err_msg=field)


# ---------------------------------------------------------------------------------------- the cases
@pytest.mark.parametrize("backend", BACKENDS)
def test_nan_speed_is_not_the_20_m_s_force(backend):
    """Issue 20: mf.forces(fz, 0, 0.05, 0, vx=[20, nan, 20]) gave the 20 m/s force at the NaN point."""
    tire = magic_formula()
    out = tire.forces(4000.0, 0.0, 0.05, 0.0, vx=[20.0, math.nan, 20.0], backend=backend)
    alone = tire.forces(4000.0, 0.0, 0.05, 0.0, vx=20.0)  # the scalar path, point by point
    for field in FIELDS:
        value = getattr(out, field)
        assert math.isnan(value[1]), field
        assert value[0] == pytest.approx(getattr(alone, field), rel=1e-12, abs=1e-12)
        assert value[2] == value[0]  # two equal points of one call: the same operations


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("shape", [(), (3,)])
def test_infinite_load_is_not_clamped_to_fzmax(backend, shape):
    """Issue 20: fz = inf returned the FZMAX force (18.8 kN of Fy for this file)."""
    tire = magic_formula()
    fz = np.full(shape, math.inf) if shape else math.inf
    out = tire.forces(fz, 0.0, 0.05, 0.0, 20.0, backend=backend)
    assert all(np.isnan(getattr(out, f)).all() for f in FIELDS)
    # a finite load above FZMAX is still clamped to FZMAX, as MFeval does
    fzmax = tire.params["FZMAX"]
    assert tire.forces(1e7, 0.0, 0.05, 0.0, 20.0).fy == tire.forces(fzmax, 0.0, 0.05, 0.0, 20.0).fy  # same input


@pytest.mark.parametrize("law", LAWS)
@pytest.mark.parametrize("name", INPUTS)
@pytest.mark.parametrize("bad_value", NON_FINITE)
def test_each_non_finite_input_gives_nan_at_that_point_only(law, name, bad_value):
    forces = law_forces(law)
    args = point()
    clean = forces(*args)
    args[INPUTS.index(name)] = args[INPUTS.index(name)].copy()
    args[INPUTS.index(name)][2] = bad_value
    bad = np.arange(5) == 2
    assert_nan_exactly_at(forces(*args), clean, bad)


@pytest.mark.parametrize("law", LAWS)
@pytest.mark.parametrize("name", INPUTS)
@pytest.mark.parametrize("bad_value", NON_FINITE)
def test_scalar_call_with_a_non_finite_input_is_nan(law, name, bad_value):
    values = [4000.0, 0.05, 0.05, 0.01, 20.0]
    values[INPUTS.index(name)] = bad_value
    out = law_forces(law)(*values)
    assert all(math.isnan(float(getattr(out, f))) for f in FIELDS)


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("name", ["fz", "kappa", "alpha", "gamma", "vx", "pressure", "phit", "omega"])
def test_evaluate_nan_at_the_bad_point_in_every_output(backend, name):
    """MagicFormula.evaluate also takes pressure, turn slip and wheel spin: the same rule for each."""
    tire = magic_formula()
    fz, kappa, alpha, gamma, vx = point(4, seed=3)
    values = dict(fz=fz, kappa=kappa, alpha=alpha, gamma=gamma, vx=vx, pressure=np.full(4, 2.4e5),
                  phit=np.array([0.0, 0.05, -0.1, 0.0]), omega=(1.0 + kappa) * vx / 0.38)
    clean = tire.evaluate(**values, turn_slip=True, backend=backend)
    values[name] = values[name].copy()
    values[name][1] = math.nan
    out = tire.evaluate(**values, turn_slip=True, backend=backend)
    for field in out.keys():
        assert math.isnan(out[field][1]), field
        keep = np.array([True, False, True, True])
        np.testing.assert_allclose(out[field][keep], clean[field][keep], rtol=1e-13, atol=1e-9, err_msg=field)


def test_evaluate_scalar_with_non_finite_pressure_is_nan():
    out = magic_formula().evaluate(4000.0, 0.0, 0.05, pressure=math.inf)
    assert all(np.isnan(out[field]) for field in out.keys())


@pytest.mark.parametrize("law", LAWS)
@pytest.mark.parametrize("name", INPUTS)
def test_bool_inputs_are_refused(law, name):
    forces = law_forces(law)
    for flag in (True, np.bool_(False), np.array([True, False])):
        values = [4000.0, 0.05, 0.05, 0.0, 20.0]
        values[INPUTS.index(name)] = flag
        with pytest.raises(ParameterError, match=name) as info:
            forces(*values)
        assert info.value.key == name


@pytest.mark.parametrize("name", ["pressure", "phit", "omega"])
def test_bool_pressure_turn_slip_and_spin_are_refused(name):
    with pytest.raises(ParameterError, match=name):
        magic_formula().evaluate(4000.0, 0.0, 0.05, **{name: True})


@pytest.mark.parametrize("law", LAWS)
def test_non_numeric_and_unbroadcastable_inputs_are_refused(law):
    forces = law_forces(law)
    with pytest.raises(ParameterError, match="kappa"):
        forces(4000.0, "0.1", 0.05, 0.0, 20.0)
    with pytest.raises(ParameterError, match="alpha"):
        forces(4000.0, 0.0, 0.05 + 1j, 0.0, 20.0)
    with pytest.raises(ParameterError, match="broadcast"):
        forces(np.ones(3), np.ones(4), 0.05, 0.0, 20.0)


def test_soft_soil_evaluate_marks_the_bad_points():
    result = SIMPLE_LAWS["soft_soil"].evaluate([4000.0, math.nan, 4000.0], 0.2, [0.0, 0.0, math.inf])
    assert math.isfinite(result.sinkage[0]) and np.isnan(result.sinkage[1:]).all()
    assert list(result.mode) == ["rigid", "invalid", "invalid"] and not result.stuck[1:].any()


def test_brush_and_fiala_helpers_follow_the_rule():
    brush, fiala = SIMPLE_LAWS["brush"], SIMPLE_LAWS["fiala"]
    trail = brush.pneumatic_trail([4000.0, math.nan, 4000.0], 0.0, 0.02, vx=[20.0, 20.0, math.inf])
    assert math.isfinite(trail[0]) and np.isnan(trail[1:]).all()
    assert np.isnan(brush.full_sliding_slip([math.inf, math.nan])).all()
    assert np.isnan(fiala.sliding_slip_angle(math.inf))  # not atan(inf) = 90 degrees
    assert fiala.sliding_slip_angle(-10.0) == 0.0  # a lifted wheel slides at once, as before


# ------------------------------------------------------------------------------------ legitimate edges
@pytest.mark.parametrize("law", LAWS)
def test_lifted_wheel_standstill_and_large_finite_inputs_still_work(law):
    forces = law_forces(law)
    lifted = forces(np.array([0.0, -500.0]), 0.1, 0.1, 0.0, 20.0)
    for field in ("fx", "fy", "mz"):
        np.testing.assert_array_equal(getattr(lifted, field), 0.0)
    assert np.isfinite(forces(4000.0, 0.0, 0.05, 0.0, 0.0)).all()  # standstill
    # large but finite: far beyond any fitted range, still evaluated (MF: clamped to it)
    big = forces(np.array([1e6, 4000.0]), np.array([50.0, 0.1]), np.array([1.5, 0.05]), 0.0, np.array([-1e3, 20.0]))
    assert all(np.isfinite(getattr(big, f)).all() for f in FIELDS)
    assert big.fy[1] == pytest.approx(forces(4000.0, 0.1, 0.05, 0.0, 20.0).fy, rel=1e-12)


@pytest.mark.parametrize("law", [law for law in SIMPLE_LAWS if law != "soft_soil"])
def test_large_array_calls_use_the_same_rule(law):
    """More points than one evaluation block (8192): the mask spans the blocks."""
    forces = law_forces(law)
    args = point(20_000, seed=5)
    clean = forces(*args)
    bad = np.zeros(20_000, dtype=bool)
    bad[[0, 8191, 8192, 19_999]] = True
    args[0] = np.where(bad, math.inf, args[0])
    assert_nan_exactly_at(forces(*args), clean, bad)


# -------------------------------------------------------------------------------------------- properties
finite = st.floats(-1e3, 1e3, allow_nan=False)
non_finite = st.sampled_from(NON_FINITE)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(law=st.sampled_from(LAWS), n=st.integers(1, 12), data=st.data())
def test_any_non_finite_input_gives_nan_at_that_point_only(law, n, data):
    """Any set of inputs at any points made non-finite: NaN there in every output, nothing else moves."""
    forces = law_forces(law)
    args = point(n, seed=data.draw(st.integers(0, 1000)))
    clean = forces(*args)
    bad = np.zeros(n, dtype=bool)
    for _ in range(data.draw(st.integers(1, 4))):
        i = data.draw(st.integers(0, n - 1))
        which = data.draw(st.sampled_from(INPUTS))
        args[INPUTS.index(which)] = args[INPUTS.index(which)].copy()
        args[INPUTS.index(which)][i] = data.draw(non_finite)
        bad[i] = True
    assert_nan_exactly_at(forces(*args), clean, bad)


@settings(max_examples=60, deadline=None)
@given(law=st.sampled_from(LAWS), values=st.tuples(finite, finite, finite, finite, finite),
       which=st.sampled_from(INPUTS), bad_value=non_finite)
def test_any_scalar_point_with_a_non_finite_input_is_nan(law, values, which, bad_value):
    forces = law_forces(law)
    assert all(math.isfinite(float(v)) for v in forces(*values))  # finite in, finite out
    values = list(values)
    values[INPUTS.index(which)] = bad_value
    assert all(math.isnan(float(v)) for v in forces(*values))
