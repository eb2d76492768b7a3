"""`vehdyn sweep`: the same table as the library call; user errors as one line, exit 2."""

import numpy as np
import pandas as pd
import pytest
import scipy.stats as st

import vehdyn
from vehdyn.cli import main
from vehdyn.sweep.api import distribution_from_text, grid_from_text

SCENE = """vehicle = "sedan"
manoeuvre = "step_steer"
speed = 25.0
duration = 1.0
outputs = ["yaw_rate"]
[manoeuvre_parameters]
lateral_acceleration = 3.0
"""


@pytest.fixture
def scene_file(tmp_path):
    path = tmp_path / "scene.toml"
    path.write_text(SCENE)
    return path


def test_cli_writes_the_library_table(scene_file, tmp_path, capsys):
    pytest.importorskip("pyarrow")
    out = tmp_path / "r.parquet"
    status = main(["sweep", str(scene_file), "--grid", "speed=20:30:3", "--samples", "2", "--vary",
                   "vehicle.mass.mass=norm:1500:50", "--metric", "understeer_gradient", "--out", str(out)])
    assert status == 0
    assert "6 variants, 0 failed" in capsys.readouterr().out
    written = pd.read_parquet(out).sort_values("variant")
    expected = vehdyn.sweep.run(vehdyn.Scene.from_toml(scene_file), grid={"speed": [20.0, 25.0, 30.0]},
                            samples={"vehicle.mass.mass": st.norm(1500, 50)}, n=2, seed=0,
                            metrics=["understeer_gradient"], progress=False)
    # bitwise: the command runs vehdyn.sweep in this process, with the same draws (seed 0)
    np.testing.assert_array_equal(written["understeer_gradient"], expected["understeer_gradient"])
    np.testing.assert_array_equal(written["vehicle.mass.mass"], expected["vehicle.mass.mass"])


@pytest.mark.parametrize("extra, word", [
    (["--grid", "sped=10:40:4"], "close matches: ['speed'"),
    (["--grid", "speed=10:40"], "START:STOP:COUNT"),
    (["--grid", "speed=a,b"], "numbers"),
    (["--samples", "4"], "go together"),
    (["--samples", "4", "--vary", "speed=gauss:1:2"], "scipy.stats law"),
    (["--grid", "speed=10,20", "--metric", "peak_yaw"], "unknown metric"),
    (["--grid", "speed=10,20", "--method", "Euler"], "solver method 'Euler'"),
])
def test_cli_user_errors_are_one_line(scene_file, capsys, extra, word):
    assert main(["sweep", str(scene_file), *extra]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("vehdyn sweep: ") and word in err[0]


def test_text_specs():
    assert grid_from_text("speed=10:40:7") == ("speed", [10.0, 15.0, 20.0, 25.0, 30.0, 35.0, 40.0])
    assert grid_from_text("vehicle.mass.mass=1400,1600") == ("vehicle.mass.mass", [1400.0, 1600.0])
    name, dist = distribution_from_text("x=uniform:2:3")
    assert name == "x" and dist.ppf(0.0) == 2.0 and dist.ppf(1.0) == 5.0
