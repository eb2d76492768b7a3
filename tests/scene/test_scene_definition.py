"""Scene: validation of every field (ParameterError naming field and value) and the TOML round trip."""

import numpy as np
import pytest

import vehdyn
from vehdyn import ParameterError, Scene
from vehdyn.procedures import sine_with_dwell, step_steer
from vehdyn.road import RoadProfile


def test_import_vehdyn_stays_light():
    import subprocess
    import sys

    code = ("import sys, vehdyn; s = vehdyn.Scene; "
            "print(sorted(m for m in ('scipy', 'pandas', 'matplotlib', 'control') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"


@pytest.mark.parametrize("changes, field, value", [
    ({"speed": -3.0}, "speed", -3.0),
    ({"speed": float("nan")}, "speed", "nan"),
    ({"duration": 0.0}, "duration", 0.0),
    ({"tolerance": 1.5}, "tolerance", 1.5),
    ({"tolerance": "small"}, "tolerance", "small"),
    ({"outputs": ()}, "outputs", "()"),
    ({"outputs": ("yaw rate",)}, "outputs", "yaw rate"),
    ({"manoeuvre": "slalom"}, "manoeuvre", "slalom"),
    ({"manoeuvre": 3.0}, "manoeuvre", "3.0"),
    ({"manoeuvre_parameters": {"amplitdue": 0.01}}, "manoeuvre_parameters.amplitdue", "0.01"),
    ({"manoeuvre_parameters": {"amplitude": float("inf")}}, "manoeuvre_parameters.amplitude", "inf"),
    ({"road": "Z"}, "road", "Z"),
    ({"road": {"event": "crater"}}, "road.event", "crater"),
    ({"road": {"event": "pothole", "depth": "deep"}}, "road.depth", "deep"),
    ({"vehicle": 42}, "vehicle", "42"),
    ({"seed": 1.5}, "seed", "1.5"),
    ({"time_step": 5.0}, "time_step", "5.0"),
    ({"manoeuvre": None, "road": None}, "manoeuvre", "None"),
])
def test_bad_fields_name_field_and_value(changes, field, value):
    base = dict(manoeuvre="step_steer", speed=20.0, duration=2.0, outputs=("yaw_rate",))
    base.update(changes)
    with pytest.raises(ParameterError) as info:
        Scene(**base)
    assert info.value.key == field
    assert field in str(info.value) and str(value) in str(info.value)


def test_from_dict_unknown_field():
    with pytest.raises(ParameterError, match="spede") as info:
        Scene.from_dict({"manoeuvre": "step_steer", "spede": 20.0})
    assert info.value.key == "spede"


def test_from_toml_errors(tmp_path):
    with pytest.raises(ParameterError, match="missing.toml"):
        Scene.from_toml(tmp_path / "missing.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text("speed = = 3\n")
    with pytest.raises(ParameterError, match="not valid TOML"):
        Scene.from_toml(bad)


@pytest.mark.parametrize("scene", [
    Scene(vehicle="van", manoeuvre="sine_with_dwell", manoeuvre_parameters={"lateral_acceleration": 5.0},
          speed=22.2, duration=4.5, outputs=("yaw_rate", "lateral_acceleration"), tolerance=0.05),
    Scene(road="c", speed=15.0, duration=1.0, outputs=("sprung_acceleration",), seed=7, time_step=0.005),
    Scene(road={"event": "pothole", "position": 5.0, "length": 0.6, "depth": 0.04, "track": "left"},
          manoeuvre="step_steer", speed=10.0, duration=2.0, outputs=("sprung_acceleration",), tire="mf_185_80R14"),
], ids=["named manoeuvre", "ISO road", "pothole and steer"])
def test_toml_round_trip(scene, tmp_path):
    path = tmp_path / "scene.toml"
    text = scene.to_toml(path)
    assert path.read_text() == text
    assert Scene.from_toml(path) == scene


def test_toml_round_trip_of_signals_and_vehicle(tmp_path):
    vehicle = vehdyn.load_vehicle("sedan").replace(name="my_sedan")
    steer = sine_with_dwell(0.05)
    scene = Scene(vehicle=vehicle, manoeuvre={"front_steer_angle": steer, "rear_steer_angle": 0.001}, speed=20.0,
                  duration=4.0, outputs=("yaw_rate",))
    scene.to_toml(tmp_path / "s.toml")
    back = Scene.from_toml(tmp_path / "s.toml")
    assert back == scene and back != scene.replace(speed=21.0)
    assert back.vehicle == vehicle
    t = np.linspace(0, 4, 401)
    # bitwise: TOML keeps the signal's parameters exactly (shortest repr); the same numpy code evaluates them
    np.testing.assert_array_equal(back.manoeuvre["front_steer_angle"](t), steer(t))
    assert back.manoeuvre["rear_steer_angle"] == 0.001
    # a road profile travels as arrays
    x = np.linspace(0, 50, 101)
    road = RoadProfile(x, 0.01 * np.sin(x))
    Scene(road=road, outputs=("sprung_acceleration",)).to_toml(tmp_path / "r.toml")
    back = Scene.from_toml(tmp_path / "r.toml")
    np.testing.assert_array_equal(back.road.elevation, road.elevation)
    assert back == Scene(road=road, outputs=("sprung_acceleration",))


def test_callable_that_is_not_piecewise_cannot_be_written():
    scene = Scene(manoeuvre=lambda t: 0.01 * np.ones_like(t), outputs=("yaw_rate",))
    with pytest.raises(ParameterError, match="cannot be written to TOML"):
        scene.to_toml()
    assert scene == scene.replace(speed=20.0) and scene != scene.replace(manoeuvre=lambda t: 0.0 * t)


def test_step_signal_given_directly_equals_named_manoeuvre():
    """A steer signal and the named manoeuvre with the same amplitude drive the same steer."""
    from vehdyn.scene.drive import drive_of

    named = drive_of(Scene(manoeuvre="step_steer", manoeuvre_parameters={"amplitude": 0.02}, duration=2.0))
    direct = drive_of(Scene(manoeuvre=step_steer(0.02), duration=2.0))
    t = named.time
    np.testing.assert_array_equal(named.steer(t), direct.steer(t))  # one signal class, equal parameters
