"""Sensitivity never answers wrongly: non-finite metrics and bad arguments (issue 32, items 3 and 7).

Before: Sobol' indices of the characteristic speed of a box where some variants oversteer (an
infinite characteristic speed) came back as all zeros without a word; Morris gave NaN; ``levels=1``
raised ZeroDivisionError and ``confidence='high'`` TypeError.

Independent references: SALib's own estimators applied in the test to the whole blocks (or
trajectories) whose runs are finite, picked from the run table by the design's block structure; the
closed form of the understeer gradient for which variants oversteer; the slopes of a linear
function for the Morris elementary effects.
"""

import warnings

import numpy as np
import pytest
import scipy.stats as st

import vehdyn
from vehdyn import ParameterError, SimulationError, VehdynWarning
from vehdyn.sweep import sensitivity

pytest.importorskip("SALib")

CF, CR = "vehicle.tires.front_cornering_stiffness", "vehicle.tires.rear_cornering_stiffness"
BOX = {CF: (7.0e4, 9.0e4), CR: (7.0e4, 8.0e4)}  # ~10 % of the box oversteers (K <= 0)


@pytest.fixture(scope="module")
def scene():
    return vehdyn.Scene(vehicle="sedan", manoeuvre="step_steer", speed=25.0, duration=1.0,
                        manoeuvre_parameters={"lateral_acceleration": 3.0}, outputs=("yaw_rate",))


def _problem(names):
    return {"num_vars": len(names), "names": list(names), "bounds": [[0.0, 1.0]] * len(names)}


def test_sobol_of_the_characteristic_speed_drops_whole_blocks_and_warns(scene):
    """The issue's example: some variants oversteer, their characteristic speed is infinite."""
    from SALib.analyze import sobol

    n = 64
    with pytest.warns(VehdynWarning) as record:
        frame = sensitivity(scene, BOX, "characteristic_speed", n=n, seed=3)
    runs = frame.attrs["runs"]
    # which runs oversteer, from the closed form of each variant's understeer gradient
    sedan = scene.load_vehicle()
    k = np.array([vehdyn.handling.understeer_gradient(sedan.replace(tires__front_cornering_stiffness=cf,
                                                                    tires__rear_cornering_stiffness=cr))
                  for cf, cr in zip(runs[CF], runs[CR])])
    y = runs["characteristic_speed"].to_numpy()
    np.testing.assert_array_equal(np.isinf(y), k <= 0)
    blocks = np.isfinite(y).reshape(n, 4).all(axis=1)  # a Saltelli block: A, AB_1, AB_2, B
    assert 0 < (~blocks).sum() < n / 2
    message = str(record[0].message)
    assert f"{int(np.isinf(y).sum())} of {len(y)} runs gave a non-finite value ({int(np.isinf(y).sum())} inf, " \
           "0 NaN" in message
    assert f"the {int((~blocks).sum())} blocks holding one are dropped" in message
    assert f"the other {int(blocks.sum())} of {n} blocks" in message
    assert frame.attrs["kept"] == {"characteristic_speed": (int(blocks.sum()), n)}
    # the indices are SALib's estimators on the whole finite blocks, bit for bit; not zeros
    expected = sobol.analyze(_problem([CF, CR]), y[np.repeat(blocks, 4)], calc_second_order=False, seed=3)
    np.testing.assert_array_equal(frame["S1"], expected["S1"])
    np.testing.assert_array_equal(frame["ST"], expected["ST"])
    np.testing.assert_array_equal(frame["ST_conf"], expected["ST_conf"])
    assert np.all(np.isfinite(frame.to_numpy())) and np.all(frame["ST"] > 0)


def _capped(limit):
    @vehdyn.sweep.vectorized
    def f(a, b):
        a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
        y = a + 2.0 * b
        return {"y": np.where(a > limit, np.inf, y), "nan": np.where(b > limit, np.nan, y), "all": y}

    return f


def test_nan_metrics_are_counted_apart_and_finite_metrics_untouched():
    with pytest.warns(VehdynWarning, match=r"'nan': \d+ of 256 runs gave a non-finite value \(0 inf, \d+ NaN"):
        frame = sensitivity(_capped(0.9), {"a": (0.0, 1.0), "b": (0.0, 1.0)}, ["nan", "all"], n=64, seed=1)
    assert frame.attrs["kept"]["all"] == (64, 64) and frame.attrs["kept"]["nan"][0] < 64
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a finite metric alone: no warning
        alone = sensitivity(_capped(0.9), {"a": (0.0, 1.0), "b": (0.0, 1.0)}, "all", n=64, seed=1)
    np.testing.assert_array_equal(frame.loc["all", "S1"], alone["S1"])


def test_too_few_finite_blocks_are_refused():
    # infinite on 60 % of the box: most blocks hold an infinite run
    with pytest.raises(SimulationError, match=r"'y': .* remain: too few for indices"):
        sensitivity(_capped(0.4), {"a": (0.0, 1.0), "b": (0.0, 1.0)}, "y", n=64, seed=1)
    with pytest.raises(SimulationError, match="too few"):
        sensitivity(_capped(0.4), {"a": (0.0, 1.0), "b": (0.0, 1.0)}, "y", method="morris", n=8, seed=1)


def test_morris_drops_whole_trajectories_and_keeps_the_slopes():
    """A linear function infinite at the top level of ``a``: the kept trajectories' elementary
    effects are still the slopes times the ranges (3 x 1 and 2 x 2), and equal SALib's Morris on them."""
    from SALib.analyze import morris

    @vehdyn.sweep.vectorized
    def linear(a, b):
        a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
        return {"y": np.where(a > 0.99, np.inf, 3.0 * a - 2.0 * b)}

    n = 40
    with pytest.warns(VehdynWarning, match="whole trajectories of d \\+ 1 = 3 runs"):
        frame = sensitivity(linear, {"a": (0.0, 1.0), "b": (10.0, 12.0)}, "y", method="morris", n=n, seed=0)
    np.testing.assert_allclose(frame["mu_star"], [3.0, 4.0], atol=1e-12)
    np.testing.assert_allclose(frame["sigma"], 0.0, atol=1e-12)
    runs = frame.attrs["runs"]
    y = runs["y"].to_numpy()
    keep = np.repeat(np.isfinite(y).reshape(n, 3).all(axis=1), 3)
    u = np.column_stack([runs["a"].to_numpy(), (runs["b"].to_numpy() - 10.0) / 2.0])
    expected = morris.analyze(_problem(["a", "b"]), u[keep], y[keep], num_levels=4, seed=0)
    np.testing.assert_allclose(frame["mu_star"], expected["mu_star"], rtol=1e-12)
    assert frame.attrs["kept"]["y"] == (int(keep.sum()) // 3, n)


def test_failed_runs_still_refuse_the_indices():
    def fragile(x):
        if x > 0.9:
            raise ParameterError("x too large", key="x", value=x)
        return {"y": x}

    with pytest.raises(SimulationError, match="sensitivity runs failed .*x too large"):
        sensitivity(fragile, {"x": (0.0, 1.0)}, "y", n=8)


@vehdyn.sweep.vectorized
def _plane(x1, x2):
    return {"y": np.asarray(x1) + 2 * np.asarray(x2)}


@pytest.mark.parametrize("kwargs, key, word", [
    (dict(method="morris", levels=1), "levels", "even integer >= 2"),
    (dict(method="morris", levels=0), "levels", "levels = 0"),
    (dict(method="morris", levels=3), "levels", "even"),
    (dict(method="morris", levels=2.5), "levels", "levels = 2.5"),
    (dict(method="morris", levels="4"), "levels", "levels = '4'"),
    (dict(method="morris", levels=True), "levels", "levels = True"),
    (dict(confidence="high"), "confidence", "confidence = 'high'"),
    (dict(confidence=0.0), "confidence", "in \\(0, 1\\)"),
    (dict(confidence=1.0), "confidence", "confidence = 1.0"),
    (dict(confidence=float("nan")), "confidence", "confidence = nan"),
    (dict(confidence=True), "confidence", "confidence = True"),
    (dict(n=0), "n", "n = 0"),
    (dict(n=-4), "n", "n = -4"),
    (dict(n=4.0), "n", "n = 4.0"),
    (dict(n=True), "n", "n = True"),
    (dict(n=1, method="morris"), "n", "n = 1"),
    (dict(n=48), "n", "power of 2"),
    (dict(method="fast"), "method", "method = 'fast'"),
    (dict(method=None), "method", "method = None"),
    (dict(seed=-1), "seed", "seed = -1"),
    (dict(seed="a"), "seed", "seed = 'a'"),
    (dict(seed=1.5), "seed", "seed = 1.5"),
    (dict(metric=[]), "metric", "metric is empty"),
    (dict(metric=["y", "y"]), "metric", "twice"),
    (dict(metric="error"), "error", "metric name 'error'"),
    (dict(metric=7), "metric", "give a metric name"),
    (dict(parameters={"x1": (1.0, 0.0)}), "x1", "low < high"),
    (dict(parameters={"x1": ("0", "1")}), "x1", "bounds"),
    (dict(parameters={"x1": (0.0, np.inf)}), "x1", "finite"),
    (dict(parameters=[("x1", (0, 1))]), "parameters", "non-empty mapping"),
])
def test_every_bad_argument_is_a_parameter_error_naming_it(kwargs, key, word):
    args = dict(parameters={"x1": (0.0, 1.0), "x2": (0.0, 1.0)}, metric="y", n=8)
    args.update(kwargs)
    with pytest.raises(ParameterError, match=word) as info:
        sensitivity(_plane, args.pop("parameters"), args.pop("metric"), **args)
    assert info.value.key == key


def test_numpy_numbers_are_numbers():
    frame = sensitivity(_plane, {"x1": (np.float32(0.0), np.float32(1.0)), "x2": st.uniform(0, 1)}, "y",
                        method="morris", n=np.int64(6), levels=np.int32(4), confidence=np.float32(0.9),
                        seed=np.int64(2))
    # x1 by bounds: slope 1 x range 1; x2 a law, at the levels' mid-quantiles (k + 1/2) / 4: a step of
    # Delta = 2/3 (two of the four levels) moves it by 0.5, so 2 x 0.5 / (2/3) = 1.5
    np.testing.assert_allclose(frame["mu"], [1.0, 1.5], rtol=1e-12)
