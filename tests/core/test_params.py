"""Vehicle parameters: shipped files load, every ParameterError path names the key and value."""

import dataclasses
import tomllib

import numpy as np
import pytest

import vehdyn
from vehdyn import ParameterError, load_vehicle
from vehdyn.params import Vehicle, dump_toml, load_toml


def shipped_dict(name="sedan"):
    with vehdyn.data_path("vehicles", f"{name}.toml").open("rb") as fh:
        return tomllib.load(fh)


@pytest.mark.parametrize("name", ["sedan", "compact", "van"])
def test_shipped_vehicles_load_and_match_source_table(name):
    v = load_vehicle(name)
    assert v.name == name and v.source
    # the derived quantities of the CommonRoad source table (shared/data/vehicles/README.md)
    expected = {"compact": (2.3927, 322.8, 1555, 0.9174, 1.4753),
                "sedan": (2.5789, 280.1, 1792, 1.1717, 1.4072),
                "van": (2.4719, 617.0, 2492, 1.1601, 1.3118)}[name]
    L, ixx, iyy, lf, lr = expected
    assert v.wheelbase == pytest.approx(L, abs=1e-4)
    assert v.mass.roll_inertia == pytest.approx(ixx, abs=0.1)
    assert v.mass.pitch_inertia == pytest.approx(iyy, abs=1.0)
    assert v.geometry.a == pytest.approx(lf, abs=1e-4) and v.geometry.b == pytest.approx(lr, abs=1e-4)
    front, rear = v.static_axle_loads()
    assert front + rear == pytest.approx(v.mass.mass * 9.81, rel=1e-12)
    assert v.tir_path().is_file()


def test_roll_stiffness_matches_source_table():
    # CommonRoad table: K_phi_f = K_sf T_f^2/2 - K_tsf; sedan 30431 and 20909 N m/rad
    v = load_vehicle("sedan")
    assert v.front_roll_stiffness == pytest.approx(30431, abs=1)
    assert v.rear_roll_stiffness == pytest.approx(20909, abs=1)


def test_toml_round_trip(tmp_path):
    v = load_vehicle("van")
    path = tmp_path / "van_copy.toml"
    path.write_text(dump_toml(v))
    assert load_vehicle(path) == v


def test_replace_validates_and_nests():
    v = load_vehicle("sedan")
    heavy = v.replace(mass__mass=v.mass.mass + 100, mass__yaw_inertia=2000.0)
    assert heavy.mass.mass == v.mass.mass + 100 and heavy.mass.yaw_inertia == 2000.0
    with pytest.raises(ParameterError, match=r"spring_rate must be > 0"):
        v.replace(suspension__front_spring_rate=-1.0)
    with pytest.raises(dataclasses.FrozenInstanceError):
        v.mass.mass = 1.0


def _load(tmp_path, data):
    lines = []
    tables = {k: val for k, val in data.items() if isinstance(val, dict)}
    for k, val in data.items():
        if not isinstance(val, dict):
            lines.append(f"{k} = {_fmt(val)}")
    for t, entries in tables.items():
        lines.append(f"[{t}]")
        lines.extend(f"{k} = {_fmt(val)}" for k, val in entries.items())
    path = tmp_path / "v.toml"
    path.write_text("\n".join(lines))
    return load_vehicle(path)


def _fmt(val):
    if isinstance(val, str):
        return '"' + val + '"'
    if isinstance(val, bool):
        return "true" if val else "false"
    if isinstance(val, float) and not np.isfinite(val):
        return "nan" if np.isnan(val) else ("inf" if val > 0 else "-inf")
    return repr(val)


def test_shipped_dict_loads_through_helper(tmp_path):
    assert _load(tmp_path, shipped_dict()) == load_vehicle("sedan")


@pytest.mark.parametrize(
    "mutate, key, match",
    [
        (lambda d: d["suspension"].pop("front_spring_rate"), "suspension.front_spring_rate", "missing parameter"),
        (lambda d: d["mass"].update(wheel_count=4), "mass.wheel_count", "unknown parameter"),
        (lambda d: d.update(colour="red"), "colour", "unknown parameter"),
        (lambda d: d["mass"].update(mass="heavy"), "mass.mass", "must be a number"),
        (lambda d: d["mass"].update(mass=True), "mass.mass", "must be a number"),
        (lambda d: d["tires"].update(tir_file=3), "tires.tir_file", "must be a string"),
        (lambda d: d["geometry"].update(front_track=float("nan")), "geometry.front_track", "must be finite"),
        (lambda d: d["aero"].update(drag_coefficient=float("inf")), "aero.drag_coefficient", "must be finite"),
        (lambda d: d["mass"].update(mass=-1200.0), "mass.mass", "must be > 0"),
        (lambda d: d["suspension"].update(front_damping=-5.0), "suspension.front_damping", "must be >= 0"),
        (lambda d: d["steering"].update(max_road_wheel_angle=2.0), "steering.max_road_wheel_angle", "must be <="),
        (lambda d: d["mass"].update(sprung_mass=5000.0), "mass.sprung_mass", "exceeds mass"),
        (lambda d: d["mass"].update(yaw_inertia=1e5), "mass.yaw_inertia", "triangle inequality"),
        (lambda d: d["mass"].update(roll_yaw_product=1e4), "mass.roll_yaw_product", "indefinite"),
        (lambda d: d["geometry"].update(sprung_cg_to_front_axle=2.0), "geometry.sprung_cg_to_front_axle",
         "inconsistent"),
        (lambda d: d.update(mass=3.0), "mass", "must be a table"),
    ],
)
def test_every_parameter_error_path(tmp_path, mutate, key, match):
    data = shipped_dict()
    mutate(data)
    with pytest.raises(ParameterError, match=match) as info:
        _load(tmp_path, data)
    assert info.value.key == key
    assert key.split(".")[-1] in str(info.value)


def test_unknown_vehicle_and_bad_files(tmp_path):
    with pytest.raises(ParameterError, match="unknown vehicle 'hovercraft'.*sedan"):
        load_vehicle("hovercraft")
    with pytest.raises(ParameterError, match="no such parameter file"):
        load_vehicle(tmp_path / "missing.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text("name = \n")
    with pytest.raises(ParameterError, match="not valid TOML"):
        load_vehicle(bad)


def test_units_metadata():
    units = vehdyn.params.Suspension.units()
    assert units["front_spring_rate"] == "N/m" and units["front_antiroll_stiffness"] == "N*m/rad"


def test_shipped_vehicles_by_category_matches_each_files_field():
    everything = vehdyn.shipped_vehicles()
    cars = vehdyn.shipped_vehicles("passenger_car")
    tractors = vehdyn.shipped_vehicles("truck_tractor")
    assert sorted(cars + tractors) == everything and not set(cars) & set(tractors)
    assert {"sedan", "compact", "van"} <= set(cars) and "tractor" in tractors
    assert all(vehdyn.load_vehicle(name).category == "passenger_car" for name in cars)


def test_shipped_vehicles_unknown_category_is_named():
    with pytest.raises(ParameterError, match="category = 'bus'") as err:
        vehdyn.shipped_vehicles("bus")
    assert err.value.key == "category"


def test_the_mass_group_is_mass_and_inertia_and_its_table_stays_mass(tmp_path):
    """One ``MassProperties`` (a rigid part's, in vehdyn.mechanics); the vehicle's group is
    ``MassAndInertia``, still the ``[mass]`` table of the files, and a rigid part's mass
    properties given in its place are refused by name."""
    from vehdyn.mechanics import InertiaTensor, MassProperties
    from vehdyn.params import MassAndInertia

    sedan = load_vehicle("sedan")
    assert type(sedan.mass) is MassAndInertia
    assert not hasattr(vehdyn.params, "MassProperties")
    text = dump_toml(sedan)
    assert "[mass]" in text.splitlines()
    path = tmp_path / "sedan.toml"
    path.write_text(text)
    assert load_toml(Vehicle, path) == sedan  # a file with a [mass] table loads as before
    part = MassProperties(sedan.mass.mass, (0.0, 0.0, -sedan.mass.cg_height),
                          InertiaTensor.from_matrix(sedan.mass.inertia_matrix))
    with pytest.raises(ParameterError, match=r"^mass must be a MassAndInertia, got MassProperties") as info:
        dataclasses.replace(sedan, mass=part)
    assert info.value.key == "mass"
    with pytest.raises(ParameterError, match=r"unknown parameter 'mass.wheels' \(value 4\); MassAndInertia takes"):
        sedan.replace(mass__wheels=4)
