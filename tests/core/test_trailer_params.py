"""Trailer parameters: shipped files load and agree with their sources, every error names the field."""

import math

import pytest

import vehdyn
from vehdyn import ParameterError, Trailer, load_trailer
from vehdyn.params import dump_toml
from vehdyn.tire import MagicFormula


def test_shipped_trailers_load_with_sources():
    assert vehdyn.shipped_trailers() == ["caravan", "semitrailer"]
    for name in vehdyn.shipped_trailers():
        t = load_trailer(name)
        assert t.name == name and t.source
        vehdyn.load_vehicle(t.towing_vehicle)  # its towing vehicle is shipped too


def test_caravan_tongue_load_and_tire_values_follow_their_formulas():
    t = load_trailer("caravan")
    # the file's comment: 751 N, 6.96 % of the weight
    assert t.tongue_load() == pytest.approx(751.0, abs=1.0)
    assert t.tongue_load() / (t.mass * 9.81) == pytest.approx(0.0696, abs=1e-4)
    assert t.tongue_load() + t.static_axle_load() == pytest.approx(t.mass * 9.81, rel=1e-12)
    # [tire]: the cornering stiffness of two mf_185_80R14 tires at half the static axle load,
    # evaluated here through the Magic Formula itself (a central difference at zero slip)
    tire = MagicFormula.from_tir(vehdyn.data_path("tires", "mf_185_80R14.tir"))
    fz, eps = t.static_axle_load() / 2, 1e-6
    dfy = tire.forces(fz, 0.0, eps, 0.0, 20.0).fy - tire.forces(fz, 0.0, -eps, 0.0, 20.0).fy
    assert t.cornering_stiffness == pytest.approx(-2 * float(dfy) / (2 * eps), rel=2e-3)


def test_caravan_wind_numbers_follow_their_comments():
    t = load_trailer("caravan")
    # "body 2.2 m wide x 2.5 m high"; centre of pressure "0.7 m ahead of the axle"
    assert t.frontal_area == pytest.approx(2.2 * 2.5, rel=1e-12)
    assert t.hitch_to_axle - t.centre_of_pressure_behind_hitch == pytest.approx(0.7, abs=1e-12)
    # a trailer without wind numbers feels no wind (the defaults)
    assert load_trailer("semitrailer").frontal_area * load_trailer("semitrailer").side_force_coefficient_slope == 0


def test_semitrailer_sits_on_the_tractor_drive_tandem():
    t, tractor = load_trailer("semitrailer"), vehdyn.load_vehicle("tractor")
    assert t.coupling == "fifth_wheel" and t.hitch_behind_rear_axle == 0.0
    # load-proportional stiffnesses at the coupled static loads (the files' stated coefficients)
    front = tractor.mass.mass * 9.81 * tractor.geometry.b / tractor.wheelbase
    rear = tractor.mass.mass * 9.81 * tractor.geometry.a / tractor.wheelbase + t.tongue_load()
    per_rad = 180 / math.pi
    assert tractor.tires.front_cornering_stiffness == pytest.approx(0.11 * per_rad * front, rel=1e-5)
    assert tractor.tires.rear_cornering_stiffness == pytest.approx(0.12 * per_rad * rear, rel=1e-5)
    assert t.cornering_stiffness == pytest.approx(0.12 * per_rad * t.static_axle_load(), rel=1e-5)


def test_toml_round_trip_and_replace(tmp_path):
    t = load_trailer("caravan")
    path = tmp_path / "my_caravan.toml"
    path.write_text(dump_toml(t))
    assert load_trailer(path) == t
    assert t.replace(mass=1500.0).mass == 1500.0


def test_cg_behind_the_axle_is_accepted():
    t = load_trailer("caravan").replace(hitch_to_cg=4.8, cg_to_axle=-0.2)
    assert t.tongue_load() < 0


@pytest.mark.parametrize("field, value", [("mass", 0.0), ("yaw_inertia", 0.0), ("hitch_to_cg", -1.0),
                                          ("cg_to_axle", -5.0), ("cornering_stiffness", -3.0),
                                          ("relaxation_length", -0.1), ("coupling", "hook"),
                                          ("frontal_area", -1.0), ("side_force_coefficient_slope", -0.5)])
def test_bad_fields_are_named(field, value):
    with pytest.raises(ParameterError) as err:
        load_trailer("caravan").replace(**{field: value})
    assert err.value.key == field and field in str(err.value)


def test_file_errors_name_the_key(tmp_path):
    with pytest.raises(ParameterError, match="unknown trailer"):
        load_trailer("boat")
    with pytest.raises(ParameterError) as err:
        load_trailer(3)
    assert err.value.key == "trailer"
    bad = tmp_path / "bad.toml"
    bad.write_text(dump_toml(load_trailer("caravan")).replace("mass = ", "weight = "))
    with pytest.raises(ParameterError) as err:
        load_trailer(bad)
    assert err.value.key == "weight"
    missing = tmp_path / "missing.toml"
    missing.write_text("\n".join(line for line in dump_toml(load_trailer("caravan")).splitlines()
                                 if not line.startswith("cornering_stiffness")))
    with pytest.raises(ParameterError) as err:
        load_trailer(missing)
    assert err.value.key == "cornering_stiffness"
    with pytest.raises(ParameterError):
        Trailer.from_dict([1, 2])
