"""Properties of MagicFormula (hypothesis): friction bound, odd symmetry, scalar = array, no NaN."""

from __future__ import annotations

import functools

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import vehdyn
from vehdyn.tire import MagicFormula, MagicFormulaOutputs, TireForces, TireModel, TirParameters, read_tir
from vehdyn.tire import magic_formula as mf_module

from .conftest import mf_domain

TIRES = ("MagicFormula61_Parameters", "MagicFormula62_Parameters", "MagicFormula52_Parameters", "mf_185_80R14")
PROPERTY_SETTINGS = settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@functools.cache
def tire(name: str) -> MagicFormula:
    return MagicFormula.from_tir(vehdyn.data_path("tires", name + ".tir"))


# Every coefficient that shifts or skews a curve (book eqs. 4.E10-4.E78): with these zero and
# gamma = 0, Fx is odd in kappa, Fy and Mz are odd in alpha.
SHIFT_COEFFICIENTS = (
    "PHX1", "PHX2", "PVX1", "PVX2", "PEX4", "PHY1", "PHY2", "PHY3", "PVY1", "PVY2", "PVY3", "PVY4", "PEY3",
    "PEY4", "RHX1", "RHY1", "RHY2", "RVY1", "RVY2", "RVY3", "RBY3", "QHZ1", "QHZ2", "QHZ3", "QHZ4", "SSZ1",
    "QDZ6", "QDZ7", "QEZ4", "QEZ5",
)


@functools.cache
def shift_free(name: str) -> MagicFormula:
    params = read_tir(vehdyn.data_path("tires", name + ".tir"))
    sections = {s: dict(kv) for s, kv in params.sections.items()}
    sections.setdefault("ZEROED", {})
    for key in SHIFT_COEFFICIENTS:
        for entries in sections.values():
            entries.pop(key, None)
        sections["ZEROED"][key] = 0.0
    return MagicFormula(TirParameters(sections, tables=params.tables))


def domain(name):
    """Strategy for one operating point in the documented domain (limits on)."""
    return mf_domain(name)


@pytest.mark.parametrize("name", TIRES)
@PROPERTY_SETTINGS
@given(data=st.data())
def test_resultant_force_within_friction_limit_with_margin(name, data):
    """|F| <= max(mux, muy)*Fz*1.25: the peak of each curve is D = mu*Fz (book 4.E12, 4.E22);
    the vertical shifts SVx, SVy, SVyk add up to 17 % on the shipped files (measured on 4e5
    random points), hence the margin. Loads within [FZMIN, FZMAX] (above, Fz is clamped)."""
    c = tire(name)._c
    fz = data.draw(st.floats(c.FZMIN, c.FZMAX))
    kappa = data.draw(st.floats(-1.0, 1.0))
    alpha = data.draw(st.floats(-0.6, 0.6))
    gamma = data.draw(st.floats(c.CAMMIN, c.CAMMAX))
    vx = data.draw(st.floats(-40.0, 40.0))
    out = tire(name).evaluate(fz, kappa, alpha, gamma, vx, alpha_star=data.draw(st.booleans()))
    assert np.hypot(out.fx, out.fy) <= 1.25 * max(out.mux, out.muy) * out.fz + 1e-9


@pytest.mark.parametrize("name", ("MagicFormula61_Parameters", "MagicFormula52_Parameters"))
@PROPERTY_SETTINGS
@given(fz=st.floats(500.0, 9000.0), kappa=st.floats(-1.0, 1.0), alpha=st.floats(-0.6, 0.6),
       vx=st.floats(0.5, 40.0), alpha_star=st.booleans())
def test_zero_shifts_make_fx_odd_in_kappa_and_fy_mz_odd_in_alpha(name, fz, kappa, alpha, vx, alpha_star):
    model = shift_free(name)
    base = model.forces(fz, kappa, alpha, 0.0, vx, alpha_star=alpha_star)
    flip_kappa = model.forces(fz, -kappa, alpha, 0.0, vx, alpha_star=alpha_star)
    flip_alpha = model.forces(fz, kappa, -alpha, 0.0, vx, alpha_star=alpha_star)
    tol = dict(rel=1e-9, abs=1e-9)
    assert flip_kappa.fx == pytest.approx(-base.fx, **tol)
    assert flip_alpha.fy == pytest.approx(-base.fy, **tol)
    pure_lateral = model.forces(fz, 0.0, alpha, 0.0, vx, alpha_star=alpha_star)
    pure_lateral_flipped = model.forces(fz, 0.0, -alpha, 0.0, vx, alpha_star=alpha_star)
    assert pure_lateral_flipped.mz == pytest.approx(-pure_lateral.mz, **tol)


def test_zero_shift_model_is_not_trivially_odd():
    """The shipped files are not symmetric (so the test above checks the zeroed coefficients)."""
    model = tire("MagicFormula61_Parameters")
    assert model.forces(4000.0, 0.0, 0.1, 0.0, 20.0).fy != pytest.approx(-model.forces(4000.0, 0.0, -0.1, 0.0, 20.0).fy)


@pytest.mark.compiled_vs_numpy
@pytest.mark.parametrize("name", TIRES)
@PROPERTY_SETTINGS
@given(data=st.data())
def test_scalar_and_array_calls_agree(name, data):
    fz, kappa, alpha, gamma, vx, _ = data.draw(domain(name))
    limits, alpha_star = data.draw(st.booleans()), data.draw(st.booleans())
    model = tire(name)
    scalar = model.forces(fz, kappa, alpha, gamma, vx, limits=limits, alpha_star=alpha_star)
    few = model.forces(*(np.array([v, 0.5 * v]) for v in (fz, kappa, alpha, gamma, vx)),
                       limits=limits, alpha_star=alpha_star)  # point-by-point path
    n = mf_module.SMALL_BATCH + 1  # numpy path
    many = model.forces(*(np.linspace(v, 0.5 * v, n) for v in (fz, kappa, alpha, gamma, vx)),
                        limits=limits, alpha_star=alpha_star)
    full = model.evaluate(fz, kappa, alpha, gamma, vx, limits=limits, alpha_star=alpha_star)
    for field, value in zip(TireForces._fields, scalar):
        assert isinstance(value, float)
        assert value == pytest.approx(getattr(many, field)[0], rel=1e-12, abs=1e-9), field
        assert value == pytest.approx(float(getattr(full, field)), rel=1e-12, abs=1e-9), field
        assert getattr(few, field)[0] == value  # the same point-by-point (math) path: bitwise
        assert getattr(few, field)[1] == pytest.approx(getattr(many, field)[-1], rel=1e-12, abs=1e-9), field


GEOMETRY_FIELDS = ("effective_radius", "deflection", "loaded_radius", "cz", "omega")


@pytest.mark.parametrize("name", TIRES)
@PROPERTY_SETTINGS
@given(data=st.data())
def test_single_point_and_array_evaluate_agree(name, data):
    """Floats (math) and numpy give the same outputs; the iterated geometry may stop one fixed-point
    or secant step apart (steps of < 1e-9 m in Re, < FNOMIN*1e-6 N in the MF 6.2 load), hence
    rel 1e-7 there."""
    fz, kappa, alpha, gamma, vx, phit = data.draw(domain(name))
    switches = dict(limits=data.draw(st.booleans()), alpha_star=data.draw(st.booleans()),
                    turn_slip=data.draw(st.booleans()))
    model = tire(name)
    single = model.evaluate(fz, kappa, alpha, gamma, vx, phit=phit, **switches)
    array = model.evaluate(np.array([fz, fz]), kappa, alpha, gamma, vx, phit=phit, **switches)
    for field in single.keys():
        a, b = float(single[field]), float(array[field][0])
        if np.isnan(b) and field in ("deflection", "loaded_radius", "cz"):
            assert np.isnan(a), field
            continue
        rel = 1e-7 if field in GEOMETRY_FIELDS else 1e-9
        assert a == pytest.approx(b, rel=rel, abs=1e-9), field


@pytest.mark.parametrize("name", TIRES)
@PROPERTY_SETTINGS
@given(data=st.data())
def test_no_nan_for_finite_inputs_including_standstill_and_zero_load(name, data):
    """All outputs finite with limits on, in every alpha_star / turn-slip mode, including vx = 0,
    fz = 0, kappa = -1 and loads above FZMAX. Exception: the MF 6.2 deflection, loaded radius and
    vertical stiffness are NaN where the MF 6.2 vertical equation has no root (large lateral
    force, or small loads with camber) - documented in MagicFormula."""
    point = data.draw(domain(name))
    alpha_star, turn_slip = data.draw(st.booleans()), data.draw(st.booleans())
    fz, kappa, alpha, gamma, vx, phit = point
    out = tire(name).evaluate(fz, kappa, alpha, gamma, vx, phit=phit, alpha_star=alpha_star, turn_slip=turn_slip)
    for field in out.keys():
        if name == "MagicFormula62_Parameters" and field in ("deflection", "loaded_radius", "cz"):
            continue
        assert np.isfinite(out[field]), (field, point)


def test_chunked_evaluation_equals_small_calls():
    model = tire("MagicFormula61_Parameters")
    rng = np.random.default_rng(7)
    n = 2 * mf_module.CHUNK_SIZE + 123
    inputs = (rng.uniform(0, 9000, n), rng.uniform(-1, 1, n), rng.uniform(-0.5, 0.5, n), rng.uniform(-0.1, 0.1, n),
              rng.uniform(-30, 30, n))
    whole = model.evaluate(*inputs, phit=rng.uniform(-0.2, 0.2, n), turn_slip=True)
    phit = whole.phit  # reuse the same draws below
    del phit
    rng = np.random.default_rng(7)
    inputs = (rng.uniform(0, 9000, n), rng.uniform(-1, 1, n), rng.uniform(-0.5, 0.5, n), rng.uniform(-0.1, 0.1, n),
              rng.uniform(-30, 30, n))
    phit_in = rng.uniform(-0.2, 0.2, n)
    # bitwise: both numpy, whose kernels give an element the same result whatever the array's length and the
    # element's place in it (SIMD loops treat the tail lanes as the others)
    for part in (slice(0, 50), slice(4000, 4200), slice(n - 30, n)):
        small = model.evaluate(*(a[part] for a in inputs), phit=phit_in[part], turn_slip=True)
        for field in whole.keys():
            np.testing.assert_array_equal(whole[field][part], small[field], err_msg=field)


def test_broadcasting_record_and_frame():
    model = tire("MagicFormula62_Parameters")
    out = model.evaluate(np.array([[2000.0], [4000.0], [6000.0]]), 0.0, np.linspace(-0.2, 0.2, 5), vx=20.0)
    assert isinstance(out, MagicFormulaOutputs)
    for field in out.keys():
        assert out[field].shape == (3, 5), field
    frame = out.to_frame()
    assert len(frame) == 15 and list(frame.columns) == list(out.keys())
    assert frame.attrs["units"]["fy"] == "N" and frame.attrs["units"]["cz"] == "N/m"
    assert out.forces.fy is out.fy
    with pytest.raises(KeyError, match="outputs are"):
        out["instKya"]


def test_defaults_speed_pressure_and_interface():
    model = tire("MagicFormula61_Parameters")
    assert isinstance(model, TireModel) and model.name == "magic_formula"
    default = model.evaluate(5000.0, 0.02, 0.05)
    explicit = model.evaluate(5000.0, 0.02, 0.05, vx=model.params["LONGVL"], pressure=model.params["INFLPRES"])
    for field in default.keys():  # the same scalar path, the defaults spelled out: bitwise
        np.testing.assert_array_equal(default[field], explicit[field])
    assert isinstance(model.forces(5000.0, 0.02, 0.05), TireForces)
    assert "MF 6.1" in repr(model)


def test_bad_inputs_are_parameter_errors():
    model = tire("MagicFormula61_Parameters")
    with pytest.raises(vehdyn.ParameterError, match="kappa"):
        model.evaluate(4000.0, "slip", 0.0)
    with pytest.raises(vehdyn.ParameterError, match="broadcast"):
        model.evaluate(np.ones(3), np.ones(4), 0.0)


def test_given_wheel_spin_is_used():
    """With omega given, Re follows it (MFeval adds eps): free rolling omega reproduces the estimate."""
    model = tire("MagicFormula61_Parameters")
    estimated = model.evaluate(4000.0, 0.0, 0.0, vx=20.0)
    given_ = model.evaluate(4000.0, 0.0, 0.0, vx=20.0, omega=estimated.omega)
    assert given_.effective_radius == pytest.approx(estimated.effective_radius, rel=1e-9)
    faster = model.evaluate(4000.0, 0.0, 0.0, vx=20.0, omega=2 * estimated.omega)
    assert faster.effective_radius > estimated.effective_radius  # centrifugal growth, Q_V1 > 0


def test_load_tire_by_path_or_shipped_name():
    from vehdyn.tire import load_tire

    by_name = load_tire("MagicFormula52_Parameters")
    by_path = load_tire(vehdyn.data_path("tires", "MagicFormula52_Parameters.tir"))
    assert by_name.version == by_path.version == "5.2"
    assert by_name.params == by_path.params
    with pytest.raises(vehdyn.TirFileError, match="cannot read"):
        load_tire("no_such_tire")


def test_empty_and_zero_dimensional_inputs():
    model = tire("MagicFormula61_Parameters")
    assert model.evaluate(np.array([]), 0.0, 0.0).cz.shape == (0,)
    assert model.forces(np.zeros((0, 3)), 0.0, 0.0).fx.shape == (0, 3)
    out = model.evaluate(np.float64(3000.0), np.array(0.1), 0.0)
    assert out.fx.shape == () and np.isfinite(out.fx)
    few = model.forces([[3000.0], [4000.0]], [0.0, 0.1, 0.2], 0.05)
    assert few.fy.shape == (2, 3)
    few.fy[0, 0] = 0.0  # outputs are writable arrays


@pytest.mark.parametrize("name", TIRES)
def test_lateral_force_kernel_is_the_combined_fy_at_zero_longitudinal_slip(name):
    """The lean kernel (pure-slip Fy0, what a vehicle model in force mode takes) equals the full
    kernel's combined-slip Fy at kappa = 0, gamma = 0 (Gyk = 1, SVyk = 0 there: 4.E58-4.E66)
    bitwise, across loads up to beyond FZMAX, slip angles beyond the limits, reverse and low speed."""
    from vehdyn.tire._mf_ops import NumpyOps

    c = tire(name)._c
    fz, alpha, vx = (a.ravel() for a in np.meshgrid(
        np.linspace(0.0, 1.5 * c.FZMAX, 7), np.linspace(-1.5, 1.5, 13),
        [-30.0, -c.VXLOW, -0.3 * c.VXLOW, 0.0, 0.3 * c.VXLOW, 2 * c.VXLOW, 30.0], indexing="ij"))
    with np.errstate(all="ignore"):
        full = mf_module.forces_kernel(NumpyOps, c, fz, 0.0 * fz, alpha, 0.0, vx, c.INFLPRES, True, False)[1]
        lean = mf_module.lateral_force_kernel(NumpyOps, c, fz, alpha, vx, c.INFLPRES)
    assert np.all(np.isfinite(full)) and np.any(full != 0)
    # bitwise on any CPU: the same NumpyOps calls on both sides; Gyk = Gyk0 / Gyk0 = 1 and SVyk = DVyk sin(0) = 0
    # exactly (x / x and sin(0) are exact in every library)
    np.testing.assert_array_equal(lean, full)
