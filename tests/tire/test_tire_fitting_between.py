"""fit_magic_formula between the measured conditions (issue 27): a tire sampled at three cambers and
four loads, fitted, and compared with the tire itself at a camber and loads it was not sampled at.

The reference is the shipped .tir file the data come from (vehdyn's Magic Formula is validated
against MFeval). Errors are the largest |fit - truth| over a slip sweep, over the peak |Mz| (or |Fy|,
|Fx|) of the noise-free training data. Before this issue's fix (commit 6acf76e), on the MF 6.1 tire
sampled at 2, 4, 6, 8 kN, the aligning moment at camber 1.5 deg was off by 1072 % of that peak in
pure lateral slip and 79 % in combined slip at alpha 4.5 deg (loads 3, 5, 7 kN), while Fy stayed
within 0.01 %: the residual-torque terms in camber and camber*|camber| (QDZ8/QDZ10, QDZ9/QDZ11) are
one direction at |camber| = 3 deg, and the fit sent them to +-1e3 along it.

The validity conditions are checked here without vehdyn.tire.fitting.validity: friction
coefficients, stiffnesses and the trail come from MagicFormula.evaluate; E <= 1 of every curve
(Fx0, Fy0, the trail, Gxa, Gyk) from the forces being the same with the E <= 1 clamp (limits=True)
and without it (limits=False) on a grid spanning the data, where no other limit acts.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from vehdyn.errors import VehdynWarning
from vehdyn.tire import fit_magic_formula
from vehdyn.tire.fitting.synthetic import sample_tire

from .conftest import shipped_tire

CAMBERS = np.radians([-3.0, 0.0, 3.0])
ANGLES = np.radians(np.linspace(-15.0, 15.0, 21))
RATIOS = np.linspace(-0.3, 0.3, 21)
COMBINED = np.radians([-6.0, -3.0, 3.0, 6.0])
FORCE_STAGES = ("pure_longitudinal", "pure_lateral", "aligning", "combined")
TIRES = ("MagicFormula61_Parameters", "MagicFormula52_Parameters")
SWEEP = np.radians(np.linspace(-15.0, 15.0, 61))
BETWEEN_LOADS = (0.6, 1.0, 1.4)  # times FNOMIN; the data are at 0.4, 0.8, 1.2, 1.6
BETWEEN_CAMBERS = np.radians([-1.5, 1.5])


def valid_everywhere(tire, data, n=9):
    """The Magic Formula's validity conditions on a grid spanning ``data`` (loads, cambers, slips),
    checked through the model's outputs: a list of the conditions that fail (empty if all hold)."""
    fz = np.linspace(data["fz"].min(), data["fz"].max(), n)
    gamma = np.union1d(np.linspace(data["gamma"].min(), data["gamma"].max(), n), [0.0])
    alpha = np.union1d(np.linspace(data["alpha"].min(), data["alpha"].max(), 4 * n), [0.0])
    kappa = np.union1d(np.linspace(data["kappa"].min(), data["kappa"].max(), 2 * n), [0.0])
    f, g, a, k = (x.ravel() for x in np.meshgrid(fz, gamma, alpha, kappa, indexing="ij"))
    vx = float(np.median(data["vx"]))
    failed = []
    out = tire.evaluate(f, k, a, g, vx)
    sign_x, sign_y = math.copysign(1.0, tire.params["PKX1"]), math.copysign(1.0, tire.params["PKY1"])
    for name, ok in (("mu_x > 0", out.mux > 0), ("mu_y > 0", out.muy > 0), ("Kxk sign", sign_x * out.kxk > 0),
                     ("Kya sign", sign_y * out.kya > 0),
                     ("trail > 0 at |alpha| <= 2 deg", (out.trail > 0) | (np.abs(a) > math.radians(2.0)) | (k != 0))):
        if not np.all(ok):
            failed.append(name)
    clamped, free = tire.forces(f, k, a, g, vx), tire.forces(f, k, a, g, vx, limits=False)
    for name in ("fx", "fy", "mz"):
        if not np.allclose(getattr(clamped, name), getattr(free, name), rtol=1e-12, atol=1e-9):
            failed.append(f"E <= 1 ({name} differs without the clamp)")
    pure = tire.forces(f, k, 0.0, g, vx).fx  # Fx = Gxa Fx0 (4.E50): the weighting function's sign
    if np.any(clamped.fx * pure < -1e-9 * np.abs(pure).max()):
        failed.append("Gxa > 0")
    return failed


def _error(tire, truth, out, peak, **point):
    """Largest |fit - truth| of ``out`` over the slip-angle sweep at ``point``, over ``peak`` [-]."""
    fz, gamma, kappa = point["fz"], point["gamma"], point.get("kappa", 0.0)
    alpha = point.get("alpha", SWEEP)
    got = getattr(tire.forces(fz, kappa, alpha, gamma), out)
    want = getattr(truth.forces(fz, kappa, alpha, gamma), out)
    return float(np.max(np.abs(got - want))) / peak


@pytest.fixture(scope="module", params=[(name, noise) for name in TIRES for noise in (0.0, 0.03)],
                ids=lambda p: f"{p[0][:16]}-noise{p[1]}")
def case(request):
    name, noise = request.param
    truth = shipped_tire(name)
    data = sample_tire(truth, slip_angles=ANGLES, slip_ratios=RATIOS, cambers=CAMBERS, combined_angles=COMBINED,
                       noise=noise, seed=11)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", VehdynWarning)  # no pressure sweep; held coefficients
        fit = fit_magic_formula(data, version=truth.version, stages=FORCE_STAGES, cross_validation=False)
    peaks = {o: float(np.max(np.abs(data.attrs["truth"][o]))) for o in ("fx", "fy", "mz")}
    return truth, data, fit, peaks, noise


def test_aligning_moment_between_cambers_and_loads(case):
    """Mz at camber +-1.5 deg and loads between the measured ones: within 3 % of the peak on clean
    data, 6 % with 3 % noise (the issue's numbers); Fy within 1 % (clean) and 4 % (noise)."""
    truth, _, fit, peaks, noise = case
    limit_mz, limit_fy = (0.03, 0.01) if noise == 0 else (0.06, 0.04)
    for load in BETWEEN_LOADS:
        for gamma in BETWEEN_CAMBERS:
            point = {"fz": load * truth.nominal_load, "gamma": gamma}
            assert _error(fit.tire, truth, "mz", peaks["mz"], **point) < limit_mz, point
            assert _error(fit.tire, truth, "fy", peaks["fy"], **point) < limit_fy, point


def test_combined_slip_between_cambers_and_loads(case):
    """Combined slip at alpha 4.5 deg (between the sweeps at 3 and 6 deg), camber 1.5 deg and loads
    between the measured ones: Mz within 3 % (6 % with noise), Fx and Fy within 3 % (6 %). The
    combined sweeps are at zero camber, so the camber terms of Gxa and Gyk (RBX3, RBY4) and of the
    Fx arm (SSZ3) are not identifiable: they stay at their start values, whose error is part of this."""
    truth, _, fit, peaks, noise = case
    limit = 0.03 if noise == 0 else 0.06
    kappa = np.linspace(-0.3, 0.3, 41)
    for load in BETWEEN_LOADS:
        point = {"fz": load * truth.nominal_load, "gamma": math.radians(1.5), "kappa": kappa,
                 "alpha": math.radians(4.5)}
        for out in ("mz", "fx", "fy"):
            assert _error(fit.tire, truth, out, peaks[out], **point) < limit, (out, point)


def test_validity_conditions_hold_on_a_grid_spanning_the_data(case):
    truth, data, fit, _, _ = case
    assert valid_everywhere(truth, data) == []  # the check itself: the shipped tire passes it
    assert valid_everywhere(fit.tire, data) == []
    assert fit.validity["ok"].all() and len(fit.violations) == 0


def test_unidentifiable_camber_terms_are_held_and_named(case):
    """At cambers -3/0/+3 deg the residual-torque terms in camber*|camber| cannot be told from those
    in camber: the fit holds them (QDZ10, QDZ11 near their start values, 0) and says so."""
    _, _, fit, _, _ = case
    aligning = fit.stages["aligning"]
    assert {"QDZ10", "QDZ11"} <= set(aligning.held)
    # within a tenth of their typical sizes (2 and 5) of the start, 0; before the fix: -1e3 .. 1e3
    assert abs(fit.tire.params["QDZ10"]) < 0.2 and abs(fit.tire.params["QDZ11"]) < 0.5
    assert any("QDZ10" in m and "held at their start values" in m for m in fit.messages)


def test_a_reference_tire_supplies_what_the_data_leave_open():
    """With the tire itself as reference, the held camber*|camber| terms go to its values (QDZ10
    1.03, QDZ11 -4.32) instead of 0, and Mz between the cambers comes closer (0.3 % against 1.5 % of
    the peak, the part of the tire the three cambers cannot show)."""
    truth = shipped_tire("MagicFormula61_Parameters")
    data = sample_tire(truth, loads=[2000.0, 4000.0, 6000.0, 8000.0], slip_angles=np.radians(np.linspace(-15, 15, 13)),
                       slip_ratios=[], cambers=CAMBERS, combined_angles=[])
    peak = float(np.max(np.abs(data["mz"])))
    errors = {}
    for reference in (None, truth):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", VehdynWarning)
            fit = fit_magic_formula(data, stages=("pure_lateral", "aligning"), cross_validation=False,
                                    reference=reference)
        errors[reference is None] = max(_error(fit.tire, truth, "mz", peak, fz=fz, gamma=gamma)
                                        for fz in (3000.0, 5000.0, 7000.0) for gamma in BETWEEN_CAMBERS)
        if reference is not None:
            assert fit.tire.nominal_load == truth.nominal_load  # the reference's FNOMIN: the same dfz
            assert fit.tire.params["QDZ10"] == pytest.approx(truth.params["QDZ10"], abs=0.1)
            assert fit.tire.params["QDZ11"] == pytest.approx(truth.params["QDZ11"], abs=0.3)
            assert any("held at the reference tire's values" in m for m in fit.messages)
    assert errors[False] < 0.01 < errors[True] < 0.03, errors
