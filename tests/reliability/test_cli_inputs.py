"""The ``vehdyn`` command with bad or hard input: one line naming the field and its value, exit 2; a
verified miss said on stderr and escalated (or not, with ``--no-escalate``).

Independent reference for the miss: the library's own ``vehdyn.run`` on the same scene file (the
command must report what the library found, and the same rung).
"""

import warnings

import pytest

import vehdyn
from vehdyn import Scene, VehdynWarning
from vehdyn.cli import main

MISS = """\
vehicle = "sedan"
manoeuvre = "step_steer"
speed = 10.0
duration = 3.0
outputs = ["yaw_rate", "lateral_acceleration"]

[manoeuvre_parameters]
lateral_acceleration = 2.0
"""


@pytest.fixture()
def miss_file(tmp_path):
    path = tmp_path / "miss.toml"
    path.write_text(MISS)
    return path


def test_a_verified_miss_is_said_and_escalated(miss_file, capsys):
    """`vehdyn scene --verify` printed the miss's numbers and nothing else (exit 0)."""
    pytest.importorskip("numba")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", VehdynWarning)
        library = vehdyn.run(Scene.from_toml(miss_file), verify=True)
    assert main(["scene", str(miss_file), "--verify"]) == 0
    captured = capsys.readouterr()
    warning = [line for line in captured.err.splitlines() if line.startswith("vehdyn scene: warning: ")]
    assert len(warning) == 1 and library.escalated_from in warning[0] and "beyond the scene's tolerance" in warning[0]
    assert f"escalated from {library.escalated_from}" in captured.out and f"to {library.rung}" in captured.out


def test_no_escalate_reports_the_miss_on_the_pick(miss_file, capsys):
    pytest.importorskip("numba")
    assert main(["scene", str(miss_file), "--verify", "--no-escalate"]) == 0
    captured = capsys.readouterr()
    assert "BEYOND TOLERANCE" in captured.out and "escalate=True reruns" in captured.err
    assert main(["scene", str(miss_file), "--no-escalate"]) == 2
    assert "--no-escalate goes with --verify" in capsys.readouterr().err


@pytest.mark.parametrize("change, named", [
    (("speed = 10.0", "speed = 1e9"), ["speed", "1000000000.0"]),  # was blamed on front_cornering_stiffness
    (("duration = 3.0", "duration = 1e12"), ["duration", "1000000000000.0"]),  # was a MemoryError
    (("speed = 10.0", "speed = 0.5"), ["manoeuvre_parameters.lateral_acceleration", "0.5 m/s", "rad"]),
    (("lateral_acceleration = 2.0", "rise_time = -1.0"), ["Scene.manoeuvre_parameters.rise_time", "-1.0"]),
    (("duration = 3.0", 'duration = 3.0\ntire = "missing.tir"'), ["Scene.tire", "missing.tir"]),
    (("manoeuvre = \"step_steer\"", 'road = { event = "bump", position = 5.0, length = 1.0, height = 1e9 }'),
     ["road.height", "1000000000.0"]),  # the command never returned
])
def test_a_bad_scene_file_is_one_line_naming_the_field(tmp_path, capsys, change, named):
    text = MISS.replace(*change)
    if "road =" in text:
        text = text.replace('outputs = ["yaw_rate", "lateral_acceleration"]', 'outputs = ["sprung_acceleration"]')
        text = text.split("[manoeuvre_parameters]")[0]
    path = tmp_path / "bad.toml"
    path.write_text(text)
    assert main(["scene", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and err.startswith("vehdyn scene: ")
    for word in named:
        assert word in err, err


def test_soil_curves_with_a_bad_out_print_nothing_before_the_error(tmp_path, capsys):
    """The soil's table was printed, then the folder refused."""
    blocker = tmp_path / "file"
    blocker.write_text("x")
    assert main(["tire", "--soil", "dry_sand", "--out", str(blocker / "sub")]) == 2
    captured = capsys.readouterr()
    assert captured.out == "" and "--out" in captured.err
