"""ISO 2631-1 weightings and metrics against the standard's tables (cases G-Wd, G-Wf, G-OTHER-WEIGHTS,
G-COMFORT-TABLE, and Table 3 Wk in tests/data) and hand results."""

import re
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import vehdyn
from vehdyn.ride import comfort

DATA = Path(__file__).resolve().parents[1] / "data"


def _entries(case, prefix):
    out = []
    for key in case["expected"]:
        m = re.fullmatch(prefix + r"@([0-9.]+)Hz", key)
        if m:
            value, _unit, tol = case["expected"][key]
            out.append((float(m.group(1)), value, tol))
    assert out
    return out


@pytest.mark.parametrize("case_id, name", [("G-Wd", "Wd"), ("G-Wf", "Wf")])
def test_table3_at_nominal_band_centres(cases, case_id, name):
    # pitfall 3: Table 3 is the Annex A filter at the NOMINAL one-third-octave frequencies
    for f, value, tol in _entries(cases[case_id], f"{name}_table"):
        assert comfort.weighting_factor(name, f) == pytest.approx(value, rel=tol), f


@pytest.mark.parametrize("case_id, name", [("G-Wd", "Wd"), ("G-Wf", "Wf")])
def test_annex_a_filter_exact_values(cases, case_id, name):
    for f, value, tol in _entries(cases[case_id], f"{name}_filter_exact"):
        assert comfort.weighting_factor(name, f) == pytest.approx(value, rel=tol), f


@pytest.mark.parametrize("name", ["Wc", "We", "Wj"])
def test_other_weightings(cases, name):
    for f, value, tol in _entries(cases["G-OTHER-WEIGHTS"], f"{name}_filter"):
        assert comfort.weighting_factor(name, f) == pytest.approx(value, rel=tol), f


def test_wk_table3():
    rows = np.loadtxt(DATA / "iso2631_wk_table.csv", delimiter=",", comments="#", skiprows=5)
    f, table = rows[:, 0], rows[:, 1] / 1000.0
    assert f.size == 37
    np.testing.assert_allclose(comfort.weighting_factor("Wk", f), table, rtol=0.005)


def test_filter_parameters_of_annex_a(cases):
    wd = cases["G-Wd"]["inputs"]
    w = comfort.weighting("Wd")
    assert (w.f1, w.f2, w.f3, w.f4, w.q4) == (wd["f1"][0], wd["f2"][0], wd["f3"][0], wd["f4"][0], wd["Q4"][0])
    wf = cases["G-Wf"]["inputs"]
    w = comfort.weighting("wf")  # names are case-insensitive
    assert (w.f1, w.f2, w.f4, w.q4, w.f5, w.q5, w.f6, w.q6) == tuple(
        wf[k][0] for k in ("f1", "f2", "f4", "Q4", "f5", "Q5", "f6", "Q6"))


@pytest.mark.parametrize("name", list(comfort.WEIGHTINGS))
def test_state_space_round_trip(name):
    w = comfort.weighting(name)
    f = np.geomspace(w.f1 / 10, w.f2 * 3, 50)
    fr = w.to_linear_model().frequency_response(2 * np.pi * f)
    np.testing.assert_allclose(np.abs(fr.response[0, 0]), w.factor(f), rtol=1e-8)


@pytest.mark.parametrize("name", ["Wk", "Wd", "We"])
def test_digital_filter_on_sinusoids(name):
    """Steady-state gain of the digital filter on sinusoids against |W(f)|, within the stated accuracy."""
    fs = 1000.0
    w = comfort.weighting(name)
    t = np.arange(0, 40.0, 1 / fs)
    bound = w.digital_error(fs, 0.5, 50.0)
    assert bound < 0.015
    for f in (0.5, 2.0, 8.0, 31.5, 50.0):
        y = w.filter(np.sin(2 * np.pi * f * t), fs)[t >= 20]
        tt = t[t >= 20]
        amp = 2 * np.abs(np.mean(y * np.exp(-2j * np.pi * f * tt)))
        assert amp == pytest.approx(w.factor(f), rel=bound + 1e-4), f


def test_digital_filter_refuses_low_sample_rate():
    with pytest.raises(vehdyn.ParameterError, match="sample_rate"):
        comfort.weighting("Wk").sos(150.0)


def test_unknown_weighting():
    with pytest.raises(vehdyn.ParameterError, match="Wz"):
        comfort.weighting_factor("Wz", 1.0)


@settings(max_examples=50, deadline=None)
@given(st.floats(0.01, 500.0))
def test_scalar_and_array_agree_and_bounded(f):
    for name in comfort.WEIGHTINGS:
        w = comfort.weighting_factor(name, f)
        assert w == pytest.approx(comfort.weighting_factor(name, np.array([f, 2 * f]))[0], rel=1e-14)
        assert 0.0 < w < 1.06  # every weighting is normalized to about 1 on its plateau (Table 3 max 1.054)


# --------------------------------------------------------------------------- metrics: hand results
def test_rms_vdv_crest_of_a_sinusoid():
    fs, T, a = 1000.0, 8.0, 1.5
    t = np.arange(0, T, 1 / fs)
    x = a * np.sin(2 * np.pi * 2.0 * t)  # whole number of cycles
    assert comfort.rms(x) == pytest.approx(a / np.sqrt(2), rel=1e-12)
    # int_0^T a^4 sin^4 = a^4 3T/8
    assert comfort.vibration_dose_value(x, fs) == pytest.approx(a * (3 * T / 8) ** 0.25, rel=1e-9)
    assert comfort.crest_factor(x) == pytest.approx(np.sqrt(2), rel=1e-6)


def test_crest_factor_and_vdv_of_a_spike():
    fs = 100.0
    x = np.full(1000, 0.2)
    x[500] = 5.0
    rms = np.sqrt((999 * 0.04 + 25) / 1000)
    assert comfort.crest_factor(x) == pytest.approx(5.0 / rms, rel=1e-12)
    assert comfort.vibration_dose_value(x, fs) == pytest.approx(((999 * 0.2**4 + 5.0**4) / fs) ** 0.25, rel=1e-12)


def test_running_rms_and_mtvv_of_a_burst():
    fs = 200.0
    t = np.arange(0, 10, 1 / fs)
    x = np.where((t >= 4) & (t < 5), 2.0 * np.sin(2 * np.pi * 5 * t), 0.0)
    run = comfort.running_rms(x, fs, 1.0)
    assert run.size == t.size - 200 + 1
    assert comfort.mtvv(x, fs, 1.0) == pytest.approx(2.0 / np.sqrt(2), rel=1e-9)
    assert run[0] == 0.0
    assert comfort.mtvv(np.ones(400), fs) == pytest.approx(1.0)


def test_weighted_rms_of_a_sinusoid():
    fs = 1000.0
    t = np.arange(0, 30, 1 / fs)
    aw = comfort.weighted_rms(np.sin(2 * np.pi * 5 * t), fs, "Wk", settle=10.0)
    assert aw == pytest.approx(comfort.weighting_factor("Wk", 5.0) / np.sqrt(2), rel=2e-3)


def test_metric_errors():
    with pytest.raises(vehdyn.ParameterError, match="integration_time"):
        comfort.running_rms(np.ones(10), 100.0, 1.0)
    with pytest.raises(vehdyn.ParameterError, match="non-finite"):
        comfort.rms([1.0, np.nan])
    with pytest.raises(vehdyn.ParameterError, match="sample_rate"):
        comfort.vibration_dose_value(np.ones(10), -1.0)
    with pytest.raises(vehdyn.ParameterError, match="settle"):
        comfort.weighted_rms(np.ones(500), 500.0, settle=2.0)


# --------------------------------------------------------------------------- Annex C
def test_comfort_reaction_ranges(cases):
    exp = {k: v[0] for k, v in cases["G-COMFORT-TABLE"]["expected"].items()}
    table = {name: (lo, hi) for name, lo, hi in comfort.COMFORT_REACTIONS}
    assert table["not uncomfortable"][1] == exp["not_uncomfortable_below"]
    for name in ("a little uncomfortable", "fairly uncomfortable", "uncomfortable", "very uncomfortable"):
        key = name.replace(" ", "_")
        assert table[name] == (exp[key + "_lo"], exp[key + "_hi"])
    assert table["extremely uncomfortable"][0] == exp["extremely_uncomfortable_above"]


def test_comfort_reactions_overlap():
    assert comfort.comfort_reactions(0.2) == ["not uncomfortable"]
    assert comfort.comfort_reactions(0.55) == ["a little uncomfortable", "fairly uncomfortable"]
    assert comfort.comfort_reactions(0.9) == ["fairly uncomfortable", "uncomfortable"]
    assert comfort.comfort_reactions(3.0) == ["extremely uncomfortable"]
    with pytest.raises(vehdyn.ParameterError, match="total_value"):
        comfort.comfort_reactions(-1.0)


def test_comfort_category_single_label():
    got = comfort.comfort_category([0.1, 0.4, 0.55, 0.57, 0.85, 0.95, 1.3, 1.5, 2.1, 2.4, 5.0])
    assert list(got) == ["not uncomfortable", "a little uncomfortable", "a little uncomfortable",
                         "fairly uncomfortable", "fairly uncomfortable", "uncomfortable", "uncomfortable",
                         "very uncomfortable", "very uncomfortable", "extremely uncomfortable",
                         "extremely uncomfortable"]
    assert comfort.comfort_category(0.2) == "not uncomfortable"


def test_vibration_total_value():
    assert comfort.vibration_total_value([0.3, 0.4]) == pytest.approx(0.5)
    assert comfort.vibration_total_value([0.2, 0.2, 0.5], [1.4, 1.4, 1.0]) == pytest.approx(
        np.sqrt(2 * 0.28**2 + 0.25))
    with pytest.raises(vehdyn.ParameterError, match="weighted_rms_values"):
        comfort.vibration_total_value([0.3, -0.1])
