"""Parquet chunks written atomically; resume runs only the missing variants."""

import numpy as np
import pandas as pd
import pytest

import vehdyn
from vehdyn.sweep import run

pytest.importorskip("pyarrow")

CALLS = []
STOP = []  # x from which _quadratic is interrupted (the same function, so that its sweep can resume)


class _Interrupt(BaseException):
    pass


def _quadratic(x, y):
    if STOP and x >= STOP[0]:
        raise _Interrupt  # as a Ctrl-C would, mid-sweep
    CALLS.append((x, y))
    return {"f": x * x + y, "g": x - y}


GRID = {"x": [0.0, 1.0, 2.0, 3.0, 4.0], "y": [0.5, 1.5]}


def test_out_writes_chunks_that_read_back_to_the_table(tmp_path):
    out = tmp_path / "results.parquet"
    table = run(_quadratic, grid=GRID, chunk_size=3, out=out, progress=False)
    parts = sorted(out.glob("part-*.parquet"))
    assert len(parts) == 4  # ceil(10 / 3)
    assert not [p for p in out.iterdir() if p.name.startswith(".")]  # no temporary file left
    back = pd.read_parquet(out).sort_values("variant").set_index("variant")  # Parquet stores the doubles' bits
    for c in ("x", "y", "f", "g"):
        np.testing.assert_array_equal(back[c], table[c])
    assert back["error"].isna().all() and list(back.index) == list(table.index)
    np.testing.assert_array_equal(table["f"], [x * x + y for x in GRID["x"] for y in GRID["y"]])


def test_resume_runs_only_the_missing_variants(tmp_path):
    out = tmp_path / "results.parquet"
    STOP.append(3.0)
    try:
        with pytest.raises(_Interrupt):
            run(_quadratic, grid=GRID, chunk_size=2, out=out, progress=False)
    finally:
        STOP.clear()
    # chunks (x=0), (x=1), (x=2) finished before the interruption; only whole chunks are on disk
    finished = pd.read_parquet(out)
    assert sorted(finished["variant"]) == [0, 1, 2, 3, 4, 5]
    CALLS.clear()
    table = run(_quadratic, grid=GRID, chunk_size=2, out=out, resume=True, progress=False)
    assert sorted(CALLS) == [(x, y) for x in (3.0, 4.0) for y in GRID["y"]]
    fresh = run(_quadratic, grid=GRID, progress=False)  # the same Python arithmetic: bitwise
    np.testing.assert_array_equal(table["f"], fresh["f"])
    np.testing.assert_array_equal(table["g"], fresh["g"])
    assert list(table.index) == list(range(10))
    # resuming a finished sweep runs nothing
    CALLS.clear()
    run(_quadratic, grid=GRID, chunk_size=2, out=out, resume=True, progress=False)
    assert CALLS == []


def test_resume_refuses_another_sweeps_folder(tmp_path):
    out = tmp_path / "results.parquet"
    run(_quadratic, grid=GRID, out=out, progress=False)
    with pytest.raises(vehdyn.ParameterError, match="another sweep"):
        run(_quadratic, grid={"x": [9.0, 1.0], "y": [0.5]}, out=out, resume=True, progress=False)


def test_fresh_sweep_replaces_old_chunks(tmp_path):
    out = tmp_path / "results.parquet"
    run(_quadratic, grid=GRID, chunk_size=1, out=out, progress=False)
    table = run(_quadratic, grid={"x": [7.0], "y": [1.0]}, out=out, progress=False)
    assert len(pd.read_parquet(out)) == 1 and table["f"].iloc[0] == 50.0


def test_out_that_is_a_file_is_refused(tmp_path):
    path = tmp_path / "file.parquet"
    path.write_text("x")
    with pytest.raises(vehdyn.ParameterError, match="is a file"):
        run(_quadratic, grid=GRID, out=path, progress=False)


def test_errors_survive_the_round_trip(tmp_path):
    out = tmp_path / "r.parquet"
    table = run(lambda x: {"r": 1.0 / x} if x else {"r": 1.0 / 0}, grid={"x": [0.0, 2.0]}, out=out,
                  progress=False)
    assert table["error"].iloc[0].startswith("ZeroDivisionError") and table["error"].iloc[1] is None
    assert table["r"].iloc[1] == 0.5 and np.isnan(table["r"].iloc[0])
