"""Sweeps lose nothing and never mix results (issue 32, items 2 and 7).

A results folder records what produced it; ``resume=True`` on another sweep's folder is refused
with what differs; ``out=`` never deletes, overwrites or mixes in files it did not write; names
that would take the table's own columns are refused up front; non-finite grid values are refused
and a variant that draws one fails in its row; numpy float32 numbers are numbers.

Independent references: the vehicle file itself (``load_vehicle``) and the plan of the scene for
what the manifest must record, ``hashlib`` over ``inspect.getsource`` for the function's hash,
``pyarrow``'s reading of the folder (a round trip of the table), direct calls of the swept
function and of the handling closed forms for the metric values, byte-for-byte copies of the
files a sweep must leave alone.
"""

import hashlib
import inspect
import json

import numpy as np
import pandas as pd
import pytest
import scipy.stats as st

import vehdyn
from vehdyn import ParameterError
from vehdyn.cli import main
from vehdyn.sweep import run, variants
from vehdyn.sweep.api import distribution_from_text, grid_from_text, run_table
from vehdyn.sweep.storage import MANIFEST

pytest.importorskip("pyarrow")

GRID = {"x": [0.0, 1.0, 2.0, 3.0], "y": [0.5, 1.5]}


def quadratic(x, y):
    return {"f": x * x + y, "g": x - y}


def other_quadratic(x, y):
    return {"f": x * x + 2 * y, "g": x - y}


def _scaled(k):
    def scaled(x, y):
        return {"f": k * x + y}

    return scaled


@pytest.fixture(scope="module")
def scene():
    return vehdyn.Scene(vehicle="sedan", manoeuvre="step_steer", speed=25.0, duration=1.0,
                        manoeuvre_parameters={"lateral_acceleration": 3.0}, outputs=("yaw_rate",))


def _snapshot(folder):
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


# ------------------------------------------------------------------ the manifest


def test_folder_records_the_scene_vehicle_rung_design_metrics_and_version(tmp_path, scene):
    out = tmp_path / "r.parquet"
    table = run(scene, grid={"speed": [20.0, 30.0]}, samples={"vehicle.mass.mass": st.norm(1500.0, 50.0)}, n=3,
                seed=4, metrics=["yaw_rate_gain", "understeer_gradient"], out=out, progress=False)
    manifest = json.loads((out / MANIFEST).read_text())
    sedan = vehdyn.load_vehicle("sedan")
    assert manifest["vehdyn"] == vehdyn.__version__
    assert manifest["target"]["kind"] == "scene"
    assert manifest["target"]["scene"]["speed"] == 25.0 and manifest["target"]["scene"]["vehicle"] == "sedan"
    assert manifest["target"]["scene"]["manoeuvre_parameters"] == {"lateral_acceleration": 3.0}
    assert manifest["target"]["vehicle"]["mass"]["mass"] == sedan.mass.mass
    assert manifest["target"]["vehicle"]["tires"]["rear_cornering_stiffness"] == sedan.tires.rear_cornering_stiffness
    assert manifest["target"]["rung"] == vehdyn.plan(scene).chosen.rung.name
    assert manifest["design"]["grid"] == {"speed": [20.0, 30.0]}
    assert manifest["design"]["samples"] == {"vehicle.mass.mass": {"law": "norm", "args": [1500.0, 50.0], "kwds": {}}}
    assert manifest["design"]["n"] == 3 and manifest["design"]["seed"] == 4 and manifest["design"]["sampling"] == "lhs"
    assert manifest["metrics"] == ["yaw_rate_gain", "understeer_gradient"]
    assert manifest["parameters"] == ["speed", "vehicle.mass.mass"] and manifest["variants"] == 6
    # every chunk carries the manifest's id; a Parquet reader skips the manifest and reads the rows back
    import pyarrow.parquet as pq

    for part in out.glob("part-*.parquet"):
        assert pq.read_schema(part).metadata[b"vehdyn.sweep"].decode() == manifest["id"]
    back = pd.read_parquet(out).sort_values("variant").set_index("variant")
    pd.testing.assert_frame_equal(back, table, check_like=False)
    # the metric values are the closed forms of the variants' vehicles
    for _, row in table.iterrows():
        vehicle = sedan.replace(mass__mass=row["vehicle.mass.mass"])
        assert row["yaw_rate_gain"] == vehdyn.handling.steady_state_gains(vehicle, row["speed"]).yaw_rate


def test_folder_records_the_function_by_name_and_source_hash(tmp_path):
    out = tmp_path / "r.parquet"
    run(quadratic, grid=GRID, out=out, progress=False)
    target = json.loads((out / MANIFEST).read_text())["target"]
    assert target["kind"] == "function"
    assert target["function"]["function"] == f"{__name__}.quadratic"
    assert target["function"]["source_sha256"] == hashlib.sha256(inspect.getsource(quadratic).encode()).hexdigest()


# ------------------------------------------------------------------ resume of another sweep


def test_resume_with_another_scene_speed_is_refused_naming_it(tmp_path, scene):
    """The issue's example: the same grid, the scene at 25 then 35 m/s; the 25 m/s results must not
    come back as the 35 m/s sweep's."""
    out = tmp_path / "r.parquet"
    args = dict(grid={"vehicle.mass.mass": [1400.0, 1600.0]}, metrics=["yaw_rate_gain"], out=out, progress=False)
    first = run(scene, **args)
    before = _snapshot(out)
    with pytest.raises(ParameterError, match=r"target\.scene\.speed: 25\.0 in the folder, 35\.0 here") as info:
        run(scene.replace(speed=35.0), resume=True, **args)
    assert info.value.key == "out"
    assert _snapshot(out) == before  # nothing written
    # the 35 m/s sweep's own numbers differ from the folder's: mixing them would have been wrong
    fresh = run(scene.replace(speed=35.0), **{**args, "out": None})
    assert not np.allclose(fresh["yaw_rate_gain"], first["yaw_rate_gain"])


@pytest.mark.parametrize("change, key", [
    (dict(scene=lambda s: s.replace(manoeuvre_parameters={"lateral_acceleration": 4.0})),
     "target.scene.manoeuvre_parameters.lateral_acceleration"),
    (dict(scene=lambda s: s.replace(vehicle=s.load_vehicle().replace(tires__front_cornering_stiffness=7.0e4))),
     "target.vehicle.tires.front_cornering_stiffness"),
    (dict(model="LinearBicycle"), "target.rung"),
    (dict(metrics=["yaw_rate_gain", "understeer_gradient"]), "metrics"),
    (dict(grid={"vehicle.mass.mass": [1400.0, 1650.0]}), "design.grid"),
    (dict(grid={"speed": [1400.0, 1600.0]}), "parameters"),
])
def test_resume_of_a_scene_sweep_names_what_differs(tmp_path, scene, change, key):
    out = tmp_path / "r.parquet"
    args = dict(grid={"vehicle.mass.mass": [1400.0, 1600.0]}, metrics=["yaw_rate_gain"], out=out, progress=False)
    run(scene, **args)
    variant = change.pop("scene", lambda s: s)(scene)
    with pytest.raises(ParameterError, match=key.replace(".", r"\.")):
        run(variant, resume=True, **{**args, **change})


def test_resume_of_another_function_or_closure_is_refused(tmp_path):
    out = tmp_path / "r.parquet"
    run(quadratic, grid=GRID, out=out, progress=False)
    with pytest.raises(ParameterError, match=r"target\.function\.function: .*quadratic.* in the folder, "
                                             r".*other_quadratic.* here"):
        run(other_quadratic, grid=GRID, out=out, resume=True, progress=False)
    out2 = tmp_path / "closure.parquet"
    run(_scaled(2.0), grid=GRID, out=out2, progress=False)
    with pytest.raises(ParameterError, match=r"target\.function\.closure\.k: 2\.0 in the folder, 3\.0 here"):
        run(_scaled(3.0), grid=GRID, out=out2, resume=True, progress=False)
    # the same closure resumes
    assert run(_scaled(2.0), grid=GRID, out=out2, resume=True, progress=False)["f"].iloc[-1] == 2.0 * 3.0 + 1.5


@pytest.mark.parametrize("change, key", [
    (dict(seed=6), "design.seed: 5 in the folder, 6 here"),
    (dict(n=5), "design.n: 4 in the folder, 5 here"),
    (dict(sampling="random"), 'design.sampling: "lhs" in the folder, "random" here'),
    (dict(samples={"x": st.norm(0.0, 2.0)}), "design.samples.x.args"),
])
def test_resume_of_another_sample_design_is_refused(tmp_path, change, key):
    out = tmp_path / "r.parquet"
    args = dict(grid={"y": [0.5]}, samples={"x": st.norm(0.0, 1.0)}, n=4, seed=5, out=out, progress=False)
    run(quadratic, **args)
    with pytest.raises(ParameterError, match=key.replace(".", r"\.").replace("(", r"\(")):
        run(quadratic, resume=True, **{**args, **change})


def test_resume_written_by_another_vehdyn_version_is_refused(tmp_path, monkeypatch):
    out = tmp_path / "r.parquet"
    run(quadratic, grid=GRID, out=out, progress=False)
    monkeypatch.setattr(vehdyn, "__version__", "9.9.9")
    with pytest.raises(ParameterError, match=r'vehdyn: "0\.1\.0" in the folder, "9\.9\.9" here'):
        run(quadratic, grid=GRID, out=out, resume=True, progress=False)


class _Stop(BaseException):
    pass


STOP = []


def interrupted(x, y):
    if STOP and x >= STOP[0]:
        raise _Stop
    return {"f": x * x + y}


def test_unseeded_samples_resume_with_the_recorded_seed(tmp_path):
    """seed=None draws fresh samples; the seed is recorded, so an interrupted unseeded sweep resumes
    its own draws (before: the resume was refused or, worse, would have mixed draws)."""
    out = tmp_path / "r.parquet"
    args = dict(samples={"x": st.uniform(0.0, 4.0)}, grid={"y": [0.5, 1.5]}, n=6, chunk_size=2, out=out,
                progress=False)
    STOP.append(2.0)
    try:
        with pytest.raises(_Stop):
            run(interrupted, **args)
    finally:
        STOP.clear()
    seed = json.loads((out / MANIFEST).read_text())["design"]["seed"]
    assert isinstance(seed, int)
    table = run(interrupted, resume=True, **args)
    assert table.attrs["seed"] == seed
    expected = variants(grid={"y": [0.5, 1.5]}, samples={"x": st.uniform(0.0, 4.0)}, n=6, seed=seed)
    np.testing.assert_array_equal(table["x"], expected["x"])
    np.testing.assert_array_equal(table["f"], expected["x"] ** 2 + expected["y"])
    assert table["error"].isna().all()


# ------------------------------------------------------------------ resume with other metrics


def test_resume_with_other_metrics_is_refused_never_nan_holes(tmp_path):
    out = tmp_path / "r.parquet"
    run(quadratic, grid=GRID, metrics=["f"], chunk_size=3, out=out, progress=False)
    before = _snapshot(out)
    for metrics in (["g"], ["f", "g"], None):
        with pytest.raises(ParameterError, match=r"holds this sweep with the metrics \['f'\]") as info:
            run(quadratic, grid=GRID, metrics=metrics, out=out, resume=True, progress=False)
        assert "resume with metrics=['f']" in str(info.value)
    assert _snapshot(out) == before
    table = run(quadratic, grid=GRID, metrics=["f"], out=out, resume=True, progress=False)
    assert table["f"].notna().all() and list(table.columns) == ["x", "y", "f", "error"]


def test_resume_of_a_scene_sweep_with_other_metrics_is_refused(tmp_path, scene):
    out = tmp_path / "r.parquet"
    run(scene, grid={"speed": [20.0, 30.0]}, metrics=["understeer_gradient"], out=out, progress=False)
    with pytest.raises(ParameterError, match="metrics"):
        run(scene, grid={"speed": [20.0, 30.0]}, metrics=["understeer_gradient", "yaw_rate_gain"], out=out,
            resume=True, progress=False)


# ------------------------------------------------------------------ out= and files it did not write


def test_out_on_a_users_parquet_dataset_is_refused_and_nothing_is_touched(tmp_path):
    """The issue's example: out= an existing Parquet dataset folder deleted the user's files."""
    data = tmp_path / "dataset"
    data.mkdir()
    pd.DataFrame({"a": [1.0, 2.0]}).to_parquet(data / "part-000000000.parquet")  # named like a sweep's chunk
    pd.DataFrame({"a": [3.0]}).to_parquet(data / "extra.parquet")
    (data / "_SUCCESS").write_text("")
    before = _snapshot(data)
    for resume in (False, True):
        with pytest.raises(ParameterError, match="no vehdyn sweep wrote") as info:
            run(quadratic, grid=GRID, out=data, resume=resume, progress=False)
        assert info.value.key == "out" and "part-000000000.parquet" in str(info.value)
        assert _snapshot(data) == before
    assert sorted(pd.read_parquet(data)["a"].tolist()) == [1.0, 2.0, 3.0]


@pytest.mark.parametrize("make", [
    lambda d: (d / "notes.txt").write_text("my notes"),
    lambda d: (d / "year=2020").mkdir(),
    lambda d: (d / MANIFEST).write_text("not a manifest"),
    lambda d: (d / MANIFEST).write_text(json.dumps({"written_by": "someone else"})),
])
def test_out_on_a_folder_with_any_foreign_entry_is_refused(tmp_path, make):
    folder = tmp_path / "out"
    folder.mkdir()
    make(folder)
    before = _snapshot(folder)
    with pytest.raises(ParameterError, match="no vehdyn sweep wrote"):
        run(quadratic, grid=GRID, out=folder, progress=False)
    assert _snapshot(folder) == before and len(list(folder.iterdir())) == 1


def test_a_file_added_to_a_sweeps_folder_is_never_deleted(tmp_path):
    out = tmp_path / "r.parquet"
    run(quadratic, grid=GRID, out=out, progress=False)
    pd.DataFrame({"a": [1.0]}).to_parquet(out / "mine.parquet")
    for resume in (False, True):
        with pytest.raises(ParameterError, match=r"no vehdyn sweep wrote \(mine\.parquet\)"):
            run(quadratic, grid=GRID, out=out, resume=resume, progress=False)
    assert (out / "mine.parquet").exists()


def test_hidden_files_are_left_alone(tmp_path):
    folder = tmp_path / "out"
    folder.mkdir()
    (folder / ".DS_Store").write_bytes(b"\x00\x01")
    table = run(quadratic, grid=GRID, out=folder, progress=False)
    assert (folder / ".DS_Store").read_bytes() == b"\x00\x01"
    assert len(table) == 8 and (folder / MANIFEST).is_file()
    run(quadratic, grid={"x": [1.0], "y": [2.0]}, out=folder, progress=False)  # a fresh sweep replaces its own
    assert (folder / ".DS_Store").read_bytes() == b"\x00\x01"
    assert pd.read_parquet(folder)["f"].tolist() == [3.0]


def test_chunks_of_another_sweep_beside_the_manifest_are_refused_on_resume(tmp_path):
    a, b = tmp_path / "a.parquet", tmp_path / "b.parquet"
    run(quadratic, grid=GRID, chunk_size=4, out=a, progress=False)
    run(other_quadratic, grid=GRID, chunk_size=4, out=b, progress=False)
    (a / "part-000000004.parquet").write_bytes((b / "part-000000004.parquet").read_bytes())
    with pytest.raises(ParameterError, match=r"chunk files of another sweep \(part-000000004\.parquet\)"):
        run(quadratic, grid=GRID, out=a, resume=True, progress=False)


# ------------------------------------------------------------------ names taking the table's columns


@pytest.mark.parametrize("name", ["error", "variant"])
def test_parameters_named_like_the_tables_columns_are_refused(name, scene):
    def f(**kw):
        return {"v": 1.0}

    with pytest.raises(ParameterError, match=f"parameter name '{name}' is one of the sweep table's own") as info:
        run(f, grid={name: [1.0, 2.0]}, progress=False)
    assert info.value.key == name
    with pytest.raises(ParameterError, match=f"'{name}'"):
        run(f, samples={name: st.norm()}, n=2, progress=False)
    with pytest.raises(ParameterError, match=f"'{name}'"):
        run_table(f, pd.DataFrame({name: [1.0]}), progress=False)
    with pytest.raises(ParameterError, match=f"'{name}'"):
        variants(grid={name: [1.0]})
    with pytest.raises(ParameterError, match=f"'{name}'"):
        vehdyn.sweep.sensitivity(f, {name: (0.0, 1.0)}, "v", n=4)


@pytest.mark.parametrize("name", ["error", "variant"])
def test_metrics_named_like_the_tables_columns_are_refused(name):
    def f(x):
        return {name: 2 * x, "ok": x}

    with pytest.raises(ParameterError, match=f"metric name '{name}'"):
        run(f, grid={"x": [1.0]}, metrics=[name], progress=False)
    with pytest.raises(ParameterError, match=f"metric name '{name}'"):
        vehdyn.sweep.register_metric(name, lambda r: 0.0, "-")
    # every key a function returns: the colliding one fails each row with the reason, no column is lost
    table = run(f, grid={"x": [1.0, 2.0]}, progress=False)
    assert list(table.index) == [0, 1] and table["x"].tolist() == [1.0, 2.0]
    assert table["error"].notna().all()
    assert table["error"].str.contains(f"returned a metric named '{name}', which is the table's own column").all()
    # named metrics leave the colliding key aside
    assert run(f, grid={"x": [1.0, 2.0]}, metrics=["ok"], progress=False)["ok"].tolist() == [1.0, 2.0]


def test_a_metric_named_like_a_parameter_is_refused():
    def f(x, y):
        return {"x": x + 100.0, "s": x + y}

    with pytest.raises(ParameterError, match="metric 'x' has a parameter's name"):
        run(f, grid={"x": [1.0], "y": [2.0]}, metrics=["x", "s"], progress=False)
    table = run(f, grid={"x": [1.0, 2.0], "y": [2.0]}, progress=False)
    assert table["x"].tolist() == [1.0, 2.0]  # the parameter's column kept
    assert table["error"].notna().all()
    assert table["error"].str.contains("returned a metric named 'x', which is a parameter's column").all()


@pytest.mark.parametrize("grid, word", [({1: [1.0]}, "non-empty text"), ({"": [1.0]}, "non-empty text")])
def test_parameter_names_must_be_text(grid, word):
    with pytest.raises(ParameterError, match=word):
        run(lambda **kw: {"v": 1.0}, grid=grid, progress=False)


def test_metric_lists_are_checked():
    with pytest.raises(ParameterError, match=r"names \['f'\] twice"):
        run(quadratic, grid=GRID, metrics=["f", "f"], progress=False)
    with pytest.raises(ParameterError, match="metric name 3"):
        run(quadratic, grid=GRID, metrics=[3], progress=False)


# ------------------------------------------------------------------ non-finite values


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf, np.float32("nan"), float("nan")])
def test_non_finite_grid_values_are_refused(bad, scene):
    with pytest.raises(ParameterError, match=r"grid\['x'\]\[1\] = .*: grid values must be finite numbers") as info:
        run(quadratic, grid={"x": [1.0, bad], "y": [0.0]}, progress=False)
    assert info.value.key == "x"
    with pytest.raises(ParameterError, match=r"grid\['speed'\]\[0\]"):
        run(scene, grid={"speed": np.array([bad, 20.0])}, metrics=["yaw_rate_gain"], progress=False)


def test_non_finite_text_specs_are_refused(tmp_path, capsys):
    with pytest.raises(ParameterError, match="finite"):
        grid_from_text("speed=nan,20")
    with pytest.raises(ParameterError, match="finite"):
        grid_from_text("speed=10:inf:3")
    with pytest.raises(ParameterError, match="finite"):
        distribution_from_text("vehicle.mass.mass=norm:nan:50")
    scene_file = tmp_path / "scene.toml"
    scene_file.write_text('vehicle = "sedan"\nmanoeuvre = "step_steer"\nspeed = 25.0\nduration = 1.0\n'
                          '[manoeuvre_parameters]\nlateral_acceleration = 3.0\n')
    assert main(["sweep", str(scene_file), "--grid", "speed=nan,20"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "finite" in err[0]


@pytest.mark.parametrize("spec", ["speed=0:1:1e10", "speed=0:1:0", "speed=0:1:2.5"])
def test_a_grid_count_that_cannot_be_a_sweep_is_refused(spec):
    with pytest.raises(ParameterError, match="COUNT from 1 to 10,000,000") as info:
        grid_from_text(spec)  # 1e10 was a MemoryError (an 80 GB linspace)
    assert info.value.key == "grid"


class Gappy:
    """A law whose quantile function is NaN below its first quartile."""

    def ppf(self, u):
        u = np.asarray(u, dtype=float)
        return np.where(u < 0.25, np.nan, 1.0 + u)


@pytest.mark.parametrize("vectorized", [False, True])
def test_a_variant_drawing_a_non_finite_value_fails_in_its_row(vectorized):
    f = vehdyn.sweep.vectorized(lambda x, y: {"f": x * x + y}) if vectorized else quadratic
    table = run(f, grid={"y": [0.5]}, samples={"x": Gappy()}, n=16, seed=3, progress=False)
    bad = table["x"].isna()
    assert 0 < bad.sum() < len(table)
    assert table.loc[bad, "error"].notna().all()
    assert table.loc[bad, "error"].str.contains(r"parameter 'x' = nan is not a finite number").all()
    assert table.loc[bad, "f"].isna().all()
    assert table.loc[~bad, "error"].isna().all()
    np.testing.assert_array_equal(table.loc[~bad, "f"], table.loc[~bad, "x"] ** 2 + 0.5)


def test_a_law_without_a_finite_median_is_refused():
    with pytest.raises(ParameterError, match=r"samples\['x'\]: its median is nan"):
        run(quadratic, grid={"y": [0.5]}, samples={"x": st.norm(np.nan, 1.0)}, n=4, progress=False)


# ------------------------------------------------------------------ numbers of any numpy kind


def test_float32_numbers_are_numbers(scene):
    a = run(scene, grid={"vehicle.mass.mass": [1450.0]}, metrics=["peak_yaw_rate"], model="SingleTrack",
            progress=False, solver={"method": "BDF", "rtol": np.float32(1e-5)})
    b = run(scene, grid={"vehicle.mass.mass": [1450.0]}, metrics=["peak_yaw_rate"], model="SingleTrack",
            progress=False, solver={"method": "BDF", "rtol": float(np.float32(1e-5))})
    assert a["peak_yaw_rate"].iloc[0] == b["peak_yaw_rate"].iloc[0] and a["error"].isna().all()
    c = run(scene, grid={"speed": np.array([20.0, 30.0], dtype=np.float32), "vehicle.mass.mass": [np.float32(1450)]},
            metrics=["yaw_rate_gain"], progress=False)
    sedan = scene.load_vehicle().replace(mass__mass=1450.0)
    np.testing.assert_array_equal(c["yaw_rate_gain"], [vehdyn.handling.steady_state_gains(sedan, u).yaw_rate
                                                       for u in (20.0, 30.0)])


@pytest.mark.parametrize("seed", [-1, 1.5, "a", True])
def test_bad_seed_is_named(seed):
    with pytest.raises(ParameterError, match="seed") as info:
        run(quadratic, grid={"y": [0.5]}, samples={"x": st.norm()}, n=2, seed=seed, progress=False)
    assert info.value.key == "seed"
