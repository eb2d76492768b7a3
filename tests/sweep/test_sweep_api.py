"""vehdyn.sweep: variants, names, metrics against direct runs, failed variants."""

import itertools

import numpy as np
import pytest
import scipy.stats as st

import vehdyn
from vehdyn.sweep import run, variants, vectorized


def _sum_product(a, b):
    return {"total": a + b, "product": a * b}


@pytest.fixture(scope="module")
def scene():
    return vehdyn.Scene(vehicle="sedan", manoeuvre="step_steer", speed=25.0, duration=1.5,
                        manoeuvre_parameters={"lateral_acceleration": 3.0}, outputs=("yaw_rate",))


def test_grid_is_full_factorial_in_product_order():
    grid = {"a": [1.0, 2.0, 3.0], "b": [10.0, 20.0]}
    table = run(_sum_product, grid=grid, progress=False)
    expected = list(itertools.product(grid["a"], grid["b"]))
    assert list(zip(table["a"], table["b"])) == expected
    np.testing.assert_array_equal(table["total"], [a + b for a, b in expected])
    np.testing.assert_array_equal(table["product"], [a * b for a, b in expected])
    assert table["error"].isna().all()
    assert list(table.columns) == ["a", "b", "total", "product", "error"]


def test_latin_hypercube_puts_one_draw_in_each_stratum_and_is_reproducible():
    dist = st.norm(1500.0, 50.0)
    t1 = variants(samples={"m": dist, "k": st.uniform(0, 1)}, n=50, seed=3)
    t2 = variants(samples={"m": dist, "k": st.uniform(0, 1)}, n=50, seed=3)
    t3 = variants(samples={"m": dist, "k": st.uniform(0, 1)}, n=50, seed=4)
    pd_equal = t1.equals(t2)
    assert pd_equal and not t1.equals(t3)
    # the defining property of a Latin hypercube: each of the n equal-probability strata once
    strata = np.floor(dist.cdf(t1["m"].to_numpy()) * 50).astype(int)
    assert sorted(strata) == list(range(50))


def test_sobol_draws_are_balanced():
    t = variants(samples={"x": st.uniform(0, 1)}, n=64, sampling="sobol", seed=1)
    # a scrambled Sobol' net of 2^6 points has one point in each interval [k/64, (k+1)/64)
    assert sorted(np.floor(t["x"].to_numpy() * 64).astype(int)) == list(range(64))


def test_grid_times_samples():
    t = variants(grid={"g": [1, 2]}, samples={"x": st.uniform(0, 1)}, n=3, seed=0)
    assert len(t) == 6
    np.testing.assert_array_equal(t["x"].to_numpy()[:3], t["x"].to_numpy()[3:])


def test_scene_metrics_equal_direct_runs(scene):
    table = run(scene, grid={"speed": [20.0, 30.0], "vehicle.mass.mass": [1400.0, 1700.0]},
                  metrics=["peak_yaw_rate", "understeer_gradient", "final_yaw_rate"], model="SingleTrack",
                  progress=False)
    assert table.attrs["units"]["peak_yaw_rate"] == "rad/s"
    assert table.attrs["units"]["vehicle.mass.mass"] == "kg"
    base = scene.load_vehicle()
    for _, row in table.iterrows():
        vehicle = base.replace(mass__mass=row["vehicle.mass.mass"])
        out = vehdyn.run(scene.replace(speed=row["speed"], vehicle=vehicle), model="SingleTrack")
        # bitwise: the sweep's compiled batch integrates each variant as its own compiled run does (the same
        # loop and step control, simulate's docs); the understeer gradient is the same numpy code
        assert row["peak_yaw_rate"] == np.max(np.abs(out.outputs["yaw_rate"]))
        assert row["final_yaw_rate"] == out.outputs["yaw_rate"][-1]
        assert row["understeer_gradient"] == vehdyn.handling.understeer_gradient(vehicle)
    # heavier -> more understeer for this front-heavy sedan's yaw gain (a physical sanity check)
    assert table["peak_yaw_rate"].notna().all()


def test_unknown_parameter_lists_close_matches(scene):
    with pytest.raises(vehdyn.ParameterError, match=r"vehicle\.mass\.mass"):
        run(scene, grid={"vehicle.mass.mas": [1.0]}, progress=False)
    with pytest.raises(vehdyn.ParameterError, match="'speed'"):
        run(scene, grid={"sped": [1.0]}, progress=False)
    with pytest.raises(vehdyn.ParameterError, match="'a'"):
        run(_sum_product, grid={"aa": [1.0], "b": [1.0]}, progress=False)


def test_unknown_metric_lists_close_matches(scene):
    with pytest.raises(vehdyn.ParameterError, match="peak_yaw_rate"):
        run(scene, grid={"speed": [20.0]}, metrics=["peak_yaw_rat"], progress=False)


@pytest.mark.parametrize("kwargs, word", [
    (dict(), "grid or samples"),
    (dict(samples={"a": st.norm()}), "n"),
    (dict(grid={"a": [1.0], "b": []}), "empty"),
    (dict(grid={"a": 3.0, "b": [1.0]}), "sequence"),
    (dict(samples={"a": (0, 1)}, n=4), "scipy.stats"),
    (dict(samples={"a": st.norm(), "b": st.norm()}, n=0), "n = 0"),
    (dict(samples={"a": st.norm(), "b": st.norm()}, n=4, sampling="grid"), "sampling"),
    (dict(grid={"a": [1.0], "b": [1.0]}, chunk_size=0), "chunk_size"),
    (dict(grid={"a": [1.0], "b": [1.0]}, resume=True), "resume"),
    (dict(grid={"a": [1.0], "b": [1.0]}, executor="cluster"), "executor"),
])
def test_bad_sweep_arguments(kwargs, word):
    with pytest.raises(vehdyn.ParameterError, match=word):
        run(_sum_product, progress=False, **kwargs)


def test_invalid_variants_fail_in_their_row_the_rest_complete(scene):
    # a wide mass distribution draws negative masses: those rows carry the ParameterError
    table = run(scene, samples={"vehicle.mass.mass": st.norm(1500.0, 1500.0)}, n=12, seed=2,
                  metrics=["understeer_gradient"], progress=False)
    base = scene.load_vehicle()
    expected, messages = [], []
    for m in table["vehicle.mass.mass"]:
        try:
            expected.append(vehdyn.handling.understeer_gradient(base.replace(mass__mass=m)))
            messages.append(None)
        except vehdyn.ParameterError as exc:
            expected.append(np.nan)
            messages.append(f"ParameterError: {exc}")
    bad = np.array([m is not None for m in messages])
    assert bad.any() and (~bad).any() and (table["vehicle.mass.mass"] <= 0).any()
    assert list(table["error"]) == messages
    np.testing.assert_array_equal(table["understeer_gradient"], expected)


@vectorized
def _batched(a, b):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    if np.any(a < 0):
        raise vehdyn.ParameterError(f"a must be >= 0, got {a[a < 0]}", key="a", value=a)
    return {"root": np.sqrt(a) * b, "ratio": b / (1.0 + a)}


def test_vectorized_function_matches_scalar_calls_and_isolates_bad_variants():
    grid = {"a": [4.0, -1.0, 0.25, 9.0], "b": [1.5, 3.0]}
    table = run(_batched, grid=grid, chunk_size=8, progress=False)
    ok = table["a"] >= 0
    assert table.loc[~ok, "error"].str.contains("a must be >= 0").all()
    for _, row in table[ok].iterrows():  # sqrt, * and / are correctly rounded: the same bits on arrays and floats
        assert row["root"] == np.sqrt(row["a"]) * row["b"]
        assert row["ratio"] == row["b"] / (1.0 + row["a"])
    # no bad variant: one batched call gives the same bits as the scalar calls
    good = run(_batched, grid={"a": [4.0, 0.25, 9.0, 2.0], "b": [1.5, 3.0]}, chunk_size=8, progress=False)
    single = run(_batched, grid={"a": [4.0, 0.25, 9.0, 2.0], "b": [1.5, 3.0]}, chunk_size=1, progress=False)
    assert good.equals(single)


def test_function_returning_a_non_mapping_fails_in_the_error_column():
    table = run(lambda a: a, grid={"a": [1.0]}, progress=False)
    assert "must return a mapping" in table["error"].iloc[0]


def test_sweep_is_a_plain_module_whose_names_shadow_no_submodule():
    import importlib
    import pkgutil
    import types

    assert type(vehdyn.sweep) is types.ModuleType and not callable(vehdyn.sweep)
    assert vehdyn.sweep.run is run
    submodules = {m.name for m in pkgutil.iter_modules(vehdyn.sweep.__path__)}
    assert {"api", "indices", "engines", "metrics", "storage", "targets", "manifest"} <= submodules
    for name in submodules:  # importing each submodule leaves every public name as it was
        importlib.import_module(f"vehdyn.sweep.{name}")
    for name in vehdyn.sweep.__all__:
        assert name not in submodules, name
        assert not isinstance(getattr(vehdyn.sweep, name), types.ModuleType), name
    assert callable(vehdyn.sweep.sensitivity) and vehdyn.sweep.sensitivity is vehdyn.sweep.indices.sensitivity
    assert not hasattr(vehdyn, "sensitivity") and "sweep" not in vehdyn.__all__
    table = vehdyn.sweep.run(_sum_product, grid={"a": [1.0], "b": [2.0]}, progress=False)
    assert table["total"].iloc[0] == 3.0
