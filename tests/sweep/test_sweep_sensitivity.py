"""Sobol' and Morris indices through SALib against closed forms."""

import numpy as np
import pytest
import scipy.stats as st

import vehdyn

pytest.importorskip("SALib")

B = (-np.pi, np.pi)


@vehdyn.sweep.vectorized
def ishigami(x1, x2, x3, a=7.0, b=0.1):
    return {"y": np.sin(x1) + a * np.sin(x2) ** 2 + b * x3 ** 4 * np.sin(x1)}


def _ishigami_indices(a=7.0, b=0.1):
    """Closed-form Sobol' indices of the Ishigami function (Ishigami & Homma 1990)."""
    v1 = 0.5 * (1 + b * np.pi ** 4 / 5) ** 2
    v2 = a ** 2 / 8
    v13 = b ** 2 * np.pi ** 8 * (1 / 18 - 1 / 50)
    v = v1 + v2 + v13
    return np.array([v1, v2, 0.0]) / v, np.array([v1 + v13, v2, v13]) / v


def test_sobol_indices_of_ishigami_match_the_closed_form():
    frame = vehdyn.sweep.sensitivity(ishigami, {"x1": B, "x2": B, "x3": B}, "y", n=1024, seed=1)
    s1, st_ = _ishigami_indices()
    assert list(frame.index) == ["x1", "x2", "x3"]
    # within the bootstrap intervals (x2.5 for the 95 % interval's own sampling error)
    assert np.all(np.abs(frame["S1"] - s1) <= 2.5 * frame["S1_conf"])
    assert np.all(np.abs(frame["ST"] - st_) <= 2.5 * frame["ST_conf"])
    assert len(frame.attrs["runs"]) == 1024 * 5
    ax = vehdyn.sweep.plot_sensitivity(frame)
    assert len(ax.patches) == 6
    import matplotlib.pyplot as plt

    plt.close("all")


def test_morris_of_a_linear_function_gives_its_slopes():
    def linear(a, b, c):
        return {"y": 3.0 * a - 2.0 * b + 0.0 * c, "z": a}

    frame = vehdyn.sweep.sensitivity(linear, {"a": (0.0, 1.0), "b": (10.0, 12.0), "c": st.norm(0, 1)}, ["y", "z"],
                               method="morris", n=10, seed=0)
    # elementary effect = slope x range (SALib scales the step by the range): 3 x 1, 2 x 2, 0
    np.testing.assert_allclose(frame.loc["y", "mu_star"], [3.0, 4.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(frame.loc["y", "sigma"], 0.0, atol=1e-12)
    np.testing.assert_allclose(frame.loc["z", "mu"], [1.0, 0.0, 0.0], atol=1e-12)


@pytest.mark.parametrize("kwargs, word", [
    (dict(method="fast"), "method"),
    (dict(n=100), "power of 2"),
    (dict(parameters={"x1": (1.0, 1.0)}), "low < high"),
    (dict(parameters={"x1": "wide"}), "bounds"),
    (dict(parameters={}), "non-empty"),
    (dict(confidence=1.5), "confidence"),
])
def test_bad_sensitivity_arguments(kwargs, word):
    args = dict(parameters={"x1": B, "x2": B, "x3": B}, n=64)
    args.update(kwargs)
    with pytest.raises(vehdyn.ParameterError, match=word):
        vehdyn.sweep.sensitivity(ishigami, args.pop("parameters"), "y", **args)


def test_failed_runs_are_reported():
    def fragile(x):
        if x > 0.5:
            raise vehdyn.ParameterError("x too large", key="x", value=x)
        return {"y": x}

    with pytest.raises(vehdyn.SimulationError, match="x too large"):
        vehdyn.sweep.sensitivity(fragile, {"x": (0.0, 1.0)}, "y", n=8)
