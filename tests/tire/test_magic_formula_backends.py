"""MagicFormula's two backends: numpy and the numba-compiled loop over the same equation functions.

The MFeval reference tests (test_magic_formula_reference.py) run on both backends; here the two
are compared with each other on random inputs across the documented domain (hypothesis), and the
backend switch, its errors and the lazy import are tested.
"""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from vehdyn.simulation import compiled as _compiled_ode
from vehdyn.errors import ParameterError
from vehdyn.tire import magic_formula as mf_module

from .conftest import mf_domain, shipped_tire

TIRES = ("MagicFormula61_Parameters", "MagicFormula62_Parameters", "MagicFormula52_Parameters", "mf_185_80R14")
needs_numba = pytest.mark.skipif(not mf_module.numba_available(), reason="numba is not installed")


tire = shipped_tire


def output_scales(model: MagicFormula) -> dict:
    """The size of each output at nominal conditions, by unit: the yardstick for 'relative' where an
    output crosses zero (Mz, Mx, trail, residual torque), in which case a ratio of the values
    themselves says nothing."""
    c = model._c
    by_unit = {"N": c.FNOMIN, "N*m": c.FNOMIN * c.UNLOADED_RADIUS, "m": c.UNLOADED_RADIUS, "-": 1.0, "rad": 1.0,
               "1/m": 1.0 / c.UNLOADED_RADIUS, "m/s": c.LONGVL, "Pa": c.NOMPRES,
               "rad/s": c.LONGVL / c.UNLOADED_RADIUS, "N/m": c.FNOMIN / c.UNLOADED_RADIUS, "N/rad": c.FNOMIN}
    return {name: by_unit[unit] for name, unit in mf_module.MagicFormulaOutputs.units.items()}


def points(name):
    """Batches of operating points in the documented domain (as the property tests draw them),
    with an inflation pressure each."""
    c = tire(name)._c
    one = st.tuples(mf_domain(name), st.floats(0.8 * c.NOMPRES, 1.2 * c.NOMPRES)).map(lambda p: (*p[0], p[1]))
    return st.lists(one, min_size=1, max_size=40).map(lambda rows: np.array(rows).T)


@pytest.mark.compiled_vs_numpy
@needs_numba
@pytest.mark.parametrize("name", TIRES)
@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_numba_and_numpy_backends_agree_to_1e_12(name, data):
    """Every output of evaluate (and forces) agrees to 1e-12 relative, all three mode switches:
    |numba - numpy| <= 1e-12*(|numpy| + the output's nominal size). The two use different sin/cos
    (libm in the compiled loop, a half-angle tangent in numpy: a few ulps apart)."""
    fz, kappa, alpha, gamma, vx, phit, pressure = data.draw(points(name))
    switches = dict(limits=data.draw(st.booleans()), alpha_star=data.draw(st.booleans()),
                    turn_slip=data.draw(st.booleans()))
    if not switches["limits"]:  # the equations as written: keep to the fitted ranges
        c = tire(name)._c
        fz, vx = np.clip(fz, c.FZMIN + 1.0, c.FZMAX), np.where(np.abs(vx) < 1.0, 1.0, vx)
        kappa, alpha = np.clip(kappa, -0.9, 0.9), np.clip(alpha, -0.6, 0.6)
    model = tire(name)
    scales = output_scales(model)
    ours = model.evaluate(fz, kappa, alpha, gamma, vx, pressure, phit, **switches, backend="numba")
    reference = model.evaluate(fz, kappa, alpha, gamma, vx, pressure, phit, **switches, backend="numpy")
    for field in ours.keys():
        a, b = ours[field], reference[field]
        np.testing.assert_array_equal(np.isnan(a), np.isnan(b), err_msg=field)  # the same branches: NaN where NaN
        both = ~np.isnan(b)
        assert np.all(np.abs(a - b)[both] <= 1e-12 * (np.abs(b[both]) + scales[field])), field
    del switches["turn_slip"]
    f_ours = model.forces(fz, kappa, alpha, gamma, vx, **switches, backend="numba")
    f_ref = model.forces(fz, kappa, alpha, gamma, vx, **switches, backend="numpy")
    for field, a, b in zip(f_ours._fields, f_ours, f_ref):
        assert np.all(np.abs(a - b) <= 1e-12 * (np.abs(b) + scales[field])), field


@pytest.mark.compiled_vs_numpy
@needs_numba
def test_numba_backend_broadcasts_given_spin_and_scalar_calls():
    """Broadcast shapes, a given wheel spin and scalar calls on the compiled path give the numpy
    path's values (to 1e-12) and its types."""
    model = tire("MagicFormula61_Parameters")
    fz, alpha = np.array([[2000.0], [4000.0], [6000.0]]), np.linspace(-0.2, 0.2, 5)
    for omega in (None, 60.0):
        a = model.evaluate(fz, 0.05, alpha, 0.02, vx=20.0, omega=omega, backend="numba")
        b = model.evaluate(fz, 0.05, alpha, 0.02, vx=20.0, omega=omega, backend="numpy")
        for field in a.keys():
            assert a[field].shape == (3, 5)
            np.testing.assert_allclose(a[field], b[field], rtol=1e-12, atol=1e-9, err_msg=field)
    f = model.forces(4000.0, 0.05, 0.1, backend="numba")
    g = model.forces(4000.0, 0.05, 0.1, backend="numpy")
    assert all(isinstance(v, float) for v in f)
    np.testing.assert_allclose(f, g, rtol=1e-12)
    assert model.evaluate(4000.0, 0.05, 0.1, backend="numba").fy.shape == ()


def test_backend_switch_and_errors(monkeypatch):
    model = tire("MagicFormula61_Parameters")
    with pytest.raises(ParameterError, match="backend"):
        model.forces(np.ones(20) * 4000.0, 0.0, 0.1, backend="fortran")
    assert mf_module._backend("auto") == "auto"  # resolved per call, by size
    assert mf_module._auto_backend(mf_module.AUTO_NUMBA_MIN_POINTS - 1) == "numpy"
    if mf_module.numba_available():
        assert mf_module._auto_backend(mf_module.AUTO_NUMBA_MIN_POINTS) == "numba"
        # a call of that many points takes the compiled path (its results, to the last bit)
        monkeypatch.setattr(mf_module, "AUTO_NUMBA_MIN_POINTS", 30)
        args = (np.linspace(1000.0, 6000.0, 40), 0.05, np.linspace(-0.2, 0.2, 40))
        for method in ("evaluate", "forces"):
            auto, compiled = (getattr(model, method)(*args, backend=b) for b in ("auto", "numba"))  # one loop
            np.testing.assert_array_equal(auto.fy, compiled.fy)
            np.testing.assert_array_equal(auto.mz, compiled.mz)
        few = (args[0][:20], 0.05, args[2][:20])  # below the threshold "auto" is numpy itself: bitwise
        np.testing.assert_array_equal(model.forces(*few, backend="auto").fy, model.forces(*few, backend="numpy").fy)
    monkeypatch.setattr(_compiled_ode, "_NUMBA_AVAILABLE", False)
    assert mf_module._auto_backend(10 * mf_module.AUTO_NUMBA_MIN_POINTS) == "numpy"
    with pytest.raises(ParameterError, match="numba"):
        model.evaluate(np.ones(20) * 4000.0, 0.0, 0.1, backend="numba")
    monkeypatch.setattr(mf_module, "BACKEND", "numpy")
    assert mf_module._backend(None) == "numpy"
    assert np.isfinite(model.evaluate(np.ones(20) * 4000.0, 0.0, 0.1).fy).all()


def test_import_does_not_import_numba():
    """numba is compiled on first use only: importing vehdyn and vehdyn.tire, building a tire and
    evaluating on the numpy backend leave it unimported."""
    code = ("import sys, numpy as np, vehdyn, vehdyn.tire\n"
            "t = vehdyn.tire.load_tire('MagicFormula61_Parameters')\n"
            "t.forces(np.ones(50) * 4000.0, 0.0, 0.1, backend='numpy'); t.forces(4000.0, 0.0, 0.1)\n"
            "print('numba' in sys.modules)")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert result.stdout.strip() == "False"


@needs_numba
def test_numba_threads_give_the_serial_results(monkeypatch):
    """NUMBA_PARALLEL splits a call into one block per core: same numbers as one block, bit for bit."""
    from vehdyn.tire import _mf_numba

    model = tire("MagicFormula62_Parameters")
    rng = np.random.default_rng(4)
    n = 4 * _mf_numba._PARALLEL_MIN_POINTS + 7
    args = (rng.uniform(0.0, 9000.0, n), rng.uniform(-0.5, 0.5, n), rng.uniform(-0.4, 0.4, n), 0.03,
            rng.uniform(-30.0, 30.0, n))
    serial = model.evaluate(*args, backend="numba")
    monkeypatch.setattr(_mf_numba.os, "cpu_count", lambda: 3)
    monkeypatch.setattr(mf_module, "NUMBA_PARALLEL", True)
    threaded = model.evaluate(*args, backend="numba")
    for field in serial.keys():  # the same compiled loop on other blocks of points: bitwise
        np.testing.assert_array_equal(threaded[field], serial[field], err_msg=field)


@needs_numba
@pytest.mark.parametrize("name", ["MagicFormula61_Parameters", "MagicFormula52_Parameters"])
def test_numba_zero_camber_loop_agrees_with_the_general_loop(name):
    """Blocks whose inclination is all +0 run a loop compiled with gamma = 0 as a constant; -0 takes
    the general loop. Every output agrees (1e-12 of the output's size), gamma keeps its sign."""
    model = tire(name)
    rng = np.random.default_rng(5)
    n = 3000
    args = (rng.uniform(0.0, 8000.0, n), rng.uniform(-0.3, 0.3, n), rng.uniform(-0.25, 0.25, n))
    vx = rng.uniform(-40.0, 40.0, n)
    scales = output_scales(model)
    for method in ("evaluate", "forces"):
        plus = getattr(model, method)(*args, np.zeros(n), vx, backend="numba")
        minus = getattr(model, method)(*args, np.full(n, -0.0), vx, backend="numba")
        for field in ("fx", "fy", "fz", "mx", "my", "mz") if method == "forces" else plus.keys():
            a, b = getattr(plus, field), getattr(minus, field)
            assert np.all(np.abs(a - b) <= 1e-12 * (np.abs(b) + scales[field])), (method, field)
    assert not np.signbit(plus.fz).any()
    out = model.evaluate(*args, np.full(n, -0.0), vx, backend="numba")
    assert np.signbit(out.gamma).all()


@pytest.mark.compiled_vs_numpy
@needs_numba
@pytest.mark.parametrize("phit", [5e-324, -5e-324, 1e-310, 1e-300, 1e-20])
def test_turn_slip_near_zero_is_its_limit_on_both_backends(phit):
    """The residual torque's zeta_7 = (2/pi) acos(M_zp90 / |D_rp|) (Pacejka 2012, eq. 4.103) is a
    quotient of two terms proportional to phit; hypothesis found phit = 5e-324 (a denormal, one bit
    of precision) where that quotient is noise and the backends disagreed by 0.117 N m of 80 N m
    (MF 6.1, F_z 12367 N, camber 0.125 rad, v_x 1 m/s). Below |x| = 1e-8 the quotient is its limit
    at phit = 0 to the last bit (atan(x) = x (1 - x^2/3)): both backends give the phit = 0 moment."""
    model = tire("MagicFormula61_Parameters")
    scale = output_scales(model)["mz"]
    args = dict(fz=np.array([12367.0, 4000.0]), kappa=np.array([0.0, 0.05]), alpha=np.array([0.0, -0.03]),
                gamma=np.array([0.125, 0.02]), vx=np.array([1.0, 20.0]), pressure=np.full(2, 208000.0))
    switches = dict(limits=False, alpha_star=False, turn_slip=True)
    at_zero = model.evaluate(**args, phit=np.zeros(2), **switches, backend="numpy")["mz"]
    for backend in ("numpy", "numba"):
        got = model.evaluate(**args, phit=np.full(2, phit), **switches, backend=backend)["mz"]
        assert np.all(np.abs(got - at_zero) <= 1e-12 * (np.abs(at_zero) + scale)), (backend, got, at_zero)


def test_turn_slip_limit_joins_the_quotient_continuously():
    """Across the switch to the limit (about |phit| = 1e-8 / (r0 max(|B_drp|, Q_CRP2)), inside the
    range below) the moment stays on its first-order line M_z(0) + phit dM_z/dphit: the slope from
    phit = 0 is the same, to the rounding of M_z, at every phit from 1e-11 to 1e-6 1/m."""
    model = tire("MagicFormula61_Parameters")
    phit = np.r_[0.0, np.geomspace(1e-11, 1e-6, 300)]
    n = phit.size
    out = model.evaluate(fz=np.full(n, 4000.0), kappa=np.zeros(n), alpha=np.zeros(n), gamma=np.full(n, 0.05),
                         vx=np.full(n, 20.0), pressure=np.full(n, model._c.NOMPRES), phit=phit, limits=False,
                         alpha_star=False, turn_slip=True, backend="numpy")["mz"]
    slope = (out[1:] - out[0]) / phit[1:]
    rounding = 4 * np.spacing(abs(out[0])) / phit[1:]  # the slope's error from rounding M_z
    assert np.all(np.abs(slope - slope[-1]) <= 1e-4 * abs(slope[-1]) + rounding)
