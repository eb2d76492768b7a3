"""`vehdyn scene FILE.toml [--verify]`."""

from vehdyn.cli import main

SCENE = """\
vehicle = "sedan"
manoeuvre = "step_steer"
speed = 20.0
duration = 1.5
outputs = ["yaw_rate"]

[manoeuvre_parameters]
lateral_acceleration = 1.0
"""


def test_scene_command_prints_plan_and_headline(tmp_path, capsys):
    path = tmp_path / "step.toml"
    path.write_text(SCENE)
    assert main(["scene", str(path), "--verify"]) == 0
    out = capsys.readouterr().out
    assert "choice:" in out and "yaw_rate" in out and "verified" in out


def test_scene_command_bad_file(tmp_path, capsys):
    path = tmp_path / "bad.toml"
    path.write_text(SCENE.replace("speed = 20.0", "speed = -1.0"))
    assert main(["scene", str(path)]) == 2
    err = capsys.readouterr().err
    assert "speed" in err and "-1.0" in err
    assert main(["scene", str(tmp_path / "missing.toml")]) == 2
