"""The manifest's description of what produced a sweep: equal for equal values in any process,
different when a value differs, plain JSON (no inf, NaN or memory address)."""

import functools
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import scipy.stats as st

import vehdyn
from vehdyn.sweep.manifest import canonical, describe, differences, table_digest

ROOT = Path(__file__).resolve().parents[2]


class Opaque:
    __slots__ = ()


class Node:
    def __init__(self):
        self.weight = 2.0
        self.self_ref = self
        self._cache = object()  # private state beside public state: a cache, left out


def test_plain_json_without_addresses_or_non_finite_numbers():
    value = {"a": np.float32(1.5), "b": [np.inf, -np.inf, np.nan], "c": Opaque(), "d": Node(),
             "e": np.arange(100.0), "f": st.norm(2.0, 3.0), "g": functools.partial(max, 1), "h": (1, "x"),
             "i": pd.DataFrame({"x": [1.0, 2.0]}), "j": {1, 2}, "k": 3 + 4j}
    text = json.dumps(canonical(value), allow_nan=False, sort_keys=True)
    assert "0x" not in text and "_cache" not in text
    out = json.loads(text)
    assert out["a"] == 1.5 and out["b"] == ["inf", "-inf", "nan"] and out["k"] == {"complex": [3.0, 4.0]}
    assert out["d"]["self_ref"] == {"type": f"{__name__}.Node"}  # a cycle is named, not followed
    assert out["e"]["array"] == [100] and len(out["e"]["sha256"]) == 64
    assert out["f"] == {"law": "norm", "args": [2.0, 3.0], "kwds": {}}


def test_a_different_value_gives_a_different_description_and_difference():
    a = canonical({"x": np.arange(100.0), "df": pd.DataFrame({"x": [1.0, 2.0]})})
    b = canonical({"x": np.arange(100.0) + 1e-12 * (np.arange(100) == 50), "df": pd.DataFrame({"x": [1.0, 2.0]})})
    c = canonical({"x": np.arange(100.0), "df": pd.DataFrame({"x": [1.0, 2.5]})})
    assert a != b and a != c
    assert canonical({"x": np.arange(100.0), "df": pd.DataFrame({"x": [1.0, 2.0]})}) == a
    assert differences({"target": a}, {"target": b})[0].startswith("target.x.sha256: ")


def test_the_manifest_is_the_same_in_another_process():
    code = """
import json, vehdyn, numpy as np
from vehdyn.procedures import sine_steer
from vehdyn.sweep import variants
from vehdyn.sweep.manifest import describe
from vehdyn.sweep.targets import as_target
scene = vehdyn.Scene(vehicle="sedan", manoeuvre=sine_steer(0.03, 0.5), speed=25.0, duration=2.0, time_step=0.01)
table = variants(grid={"vehicle.mass.mass": np.linspace(1400.0, 1600.0, 101)})
print(json.dumps(describe(target=as_target(scene, "SingleTrack").identity(), parameters=list(table.columns),
                          metrics=["peak_yaw_rate"], design={"seed": 3}, table=table, version="x")))
"""
    runs = [subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                           env=dict(os.environ, PYTHONPATH=str(ROOT))).stdout for _ in range(2)]
    there = json.loads(runs[0])
    assert json.loads(runs[1]) == there
    from vehdyn.procedures import sine_steer
    from vehdyn.sweep import variants
    from vehdyn.sweep.targets import as_target

    scene = vehdyn.Scene(vehicle="sedan", manoeuvre=sine_steer(0.03, 0.5), speed=25.0, duration=2.0, time_step=0.01)
    grid = variants(grid={"vehicle.mass.mass": np.linspace(1400.0, 1600.0, 101)})
    target = as_target(scene, "SingleTrack")
    here = describe(target=target.identity(), parameters=list(grid.columns), metrics=["peak_yaw_rate"],
                    design={"seed": 3}, table=grid, version="x")
    assert here == there
    assert here["target"]["rung"] == target.rung and target.rung.startswith("SingleTrack")
    assert here["target"]["scene"]["manoeuvre"]["type"] == "vehdyn.piecewise_signal.PiecewiseSignal"
    assert here["target"]["vehicle"]["mass"]["mass"] == vehdyn.load_vehicle("sedan").mass.mass
    table = pd.DataFrame({"vehicle.mass.mass": np.linspace(1400.0, 1600.0, 101)})
    assert here["table_sha256"] == table_digest(table)
    again = describe(target={"kind": "none"}, parameters=["vehicle.mass.mass"], metrics=None, design=None,
                     table=table, version="x")
    assert again["table_sha256"] == here["table_sha256"] and again["id"] != here["id"]
