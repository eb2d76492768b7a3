"""Tire relaxation: lengths against MFeval 4.3.1, step response against the closed form, linearization."""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import vehdyn
from vehdyn import ParameterError
from vehdyn.tire import TireRelaxation, relaxation_lengths
from vehdyn.tire import MagicFormula
from vehdyn.tire.tir import MFEVAL_DEFAULTS

DATA = Path(__file__).resolve().parent.parent / "data" / "tire_relaxation"
FILES = ["MagicFormula52_Parameters", "mf_185_80R14", "MagicFormula61_Parameters", "MagicFormula62_Parameters"]


def tir_values(stem):
    frame = pd.read_csv(DATA / f"{stem}__params.csv")
    return dict(zip(frame["name"], frame["value"]))


@pytest.mark.parametrize("stem", FILES)
def test_lengths_match_mfeval(stem):
    tir = tir_values(stem)
    ref = pd.read_csv(DATA / f"{stem}__relaxation.csv")
    for limits in (True, False):
        rows = ref[(ref.useMode // 100 == 1) == limits]
        assert len(rows) > 0
        sx, sy = relaxation_lengths(tir, rows.in_Fz.to_numpy(), rows.in_gamma.to_numpy(), rows.in_P.to_numpy(),
                                    limits=limits)
        np.testing.assert_allclose(sx, rows.sigmax, rtol=1e-12)
        np.testing.assert_allclose(sy, rows.sigmay, rtol=1e-12)


def test_unknown_version_names_fittyp():
    tir = tir_values("MagicFormula61_Parameters")
    with pytest.raises(ParameterError, match="FITTYP"):
        relaxation_lengths({**tir, "FITTYP": 7}, 5000.0)
    with pytest.raises(ParameterError, match="tire"):
        relaxation_lengths(3.0, 5000.0)
    with pytest.raises(ParameterError, match="PKY1"):
        relaxation_lengths({**tir, "PKY1": [1.0]}, 5000.0)
    with pytest.raises(ParameterError, match="PKY1"):
        relaxation_lengths({**tir, "PKY1": "one"}, 5000.0)  # neither a number nor a quoted string


def test_grouped_mapping_path_and_model_agree():
    tir = tir_values("MagicFormula61_Parameters")
    grouped = {"MODEL": {"FITTYP": tir["FITTYP"]}, "REST": {k: v for k, v in tir.items() if k != "FITTYP"}}
    assert relaxation_lengths(grouped, 5000.0)[1] == pytest.approx(relaxation_lengths(tir, 5000.0)[1], rel=1e-15)
    path = vehdyn.data_path("tires", "mf_185_80R14.tir")
    from_path = relaxation_lengths(path, [2000.0, 4000.0])
    from_model = relaxation_lengths(MagicFormula.from_tir(path), [2000.0, 4000.0])
    np.testing.assert_array_equal(from_path, from_model)  # the same file values through the same code


def test_missing_keys_take_mfeval_defaults():
    # MFeval's readTIR fills a key a file lacks with its default; so does a mapping here
    tir = tir_values("MagicFormula61_Parameters")
    lacking = {k: v for k, v in tir.items() if k != "LATERAL_STIFFNESS"}
    explicit = {**lacking, "LATERAL_STIFFNESS": MFEVAL_DEFAULTS["LATERAL_STIFFNESS"]}
    assert relaxation_lengths(lacking, 5000.0)[1] == relaxation_lengths(explicit, 5000.0)[1]
    assert relaxation_lengths(lacking, 5000.0)[1] != relaxation_lengths(tir, 5000.0)[1]


def test_step_response_is_first_order_with_time_constant_sigma_over_v():
    # sigma d(q)/dt + |V| q = V_sy: q(t) = (V_sy/|V|)(1 - exp(-|V| t / sigma))
    model = TireRelaxation(longitudinal_relaxation_length=0.25, lateral_relaxation_length=0.6)
    t = np.linspace(0.0, 0.3, 61)
    result = vehdyn.simulate(model, t, inputs={"forward_speed": 15.0, "longitudinal_slip_velocity": -0.3,
                                               "lateral_slip_velocity": 0.9}, method="RK45", rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(result["transient_slip_ratio"], 0.02 * (1 - np.exp(-15.0 * t / 0.25)), atol=1e-8)
    np.testing.assert_allclose(result["transient_slip_angle"],
                               np.arctan(0.06 * (1 - np.exp(-15.0 * t / 0.6))), atol=1e-8)
    assert model.time_constants(15.0) == pytest.approx((0.25 / 15.0, 0.6 / 15.0), rel=1e-15)


def test_reverse_steady_state_is_the_kinematic_slip():
    model = TireRelaxation(longitudinal_relaxation_length=0.3, lateral_relaxation_length=0.5)
    u = np.array([-8.0, -0.4, 0.4])  # V_x < 0, V_sx = -0.4 -> kappa = -V_sx / V_x = -0.05
    x = np.array([-0.05, 0.05])
    np.testing.assert_allclose(model.rhs(0.0, x, u), 0.0, atol=1e-15)


def test_standstill_is_finite_and_builds_deflection():
    model = TireRelaxation(longitudinal_relaxation_length=0.3, lateral_relaxation_length=0.5)
    dx = model.rhs(0.0, np.array([0.0, 0.0]), np.array([0.0, 0.1, 0.2]))
    np.testing.assert_allclose(dx, [-0.1 / 0.3, 0.2 / 0.5], rtol=1e-15)


def test_linearization_poles_and_analytic_jacobian():
    model = TireRelaxation(longitudinal_relaxation_length=0.3, lateral_relaxation_length=0.5, prefix="front_left_")
    x0 = {"front_left_transient_slip_ratio": 0.02, "front_left_transient_lateral_slip": -0.04}
    u0 = {"front_left_forward_speed": 12.0, "front_left_longitudinal_slip_velocity": -0.24,
          "front_left_lateral_slip_velocity": -0.48}
    linear = model.linearize(x0, u0)
    np.testing.assert_allclose(np.sort(np.linalg.eigvals(linear.A).real), [-12.0 / 0.3, -12.0 / 0.5], rtol=1e-14)
    xv, uv = model.state_vector(x0), model.input_vector(u0)
    A, B, C, D = model._finite_difference_jacobian(0.0, xv, uv)
    np.testing.assert_allclose(linear.A, A, rtol=1e-8, atol=1e-9)
    np.testing.assert_allclose(linear.B, B, rtol=1e-8, atol=1e-9)
    np.testing.assert_allclose(linear.C, C, rtol=1e-8, atol=1e-9)
    assert "front_left_transient_slip_angle" in linear.output_names


def test_from_tir_follows_the_load():
    tir = tir_values("mf_185_80R14")
    model = TireRelaxation.from_tir(tir)
    assert model.input_names[-1] == "normal_load"
    sx, sy = relaxation_lengths(tir, 3000.0)
    taus = model.time_constants(10.0, normal_load=3000.0)
    assert taus == pytest.approx((float(sx) / 10.0, float(sy) / 10.0), rel=1e-14)
    # lift-off: the floor keeps the equations finite
    dx = model.rhs(0.0, np.zeros((2, 2)), np.array([[10.0, 10.0], [0.1, 0.1], [0.1, 0.1], [0.0, 3000.0]]))
    assert np.all(np.isfinite(dx)) and dx[0, 0] == pytest.approx(-0.1 / 0.01)
    with pytest.raises(ParameterError, match="normal_load"):
        model.time_constants(10.0)
    assert model.jacobian(0.0, np.zeros(2), np.array([10.0, 0, 0, 3000.0])) is None


@pytest.mark.parametrize("args", [(0.0, 0.5), (0.3, -1.0), (0.3, float("nan")), ("0.3", 0.5)])
def test_bad_lengths_raise(args):
    with pytest.raises(ParameterError):
        TireRelaxation(*args)


def test_phenomena():
    assert TireRelaxation.phenomena == {"tire_lag"}
