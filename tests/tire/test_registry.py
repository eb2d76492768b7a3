"""Tire-law registry: names, lazy Magic Formula, tires built from a vehicle file."""

import importlib.util
import math

import pytest

import vehdyn
from vehdyn import ParameterError
from vehdyn.tire import (BrushTire, DugoffTire, FialaTire, LinearTire, TireModel, register_tire_law,
                         tire_for_vehicle, tire_law, tire_law_names)
from vehdyn.tire.registry import vehicle_tire_data


def test_names_and_classes():
    assert {"linear", "brush", "fiala", "dugoff", "magic_formula"} <= set(tire_law_names())
    assert tire_law("brush") is BrushTire
    assert tire_law("fiala") is FialaTire
    assert tire_law("linear") is LinearTire
    assert tire_law("dugoff") is DugoffTire
    for name in ("linear", "brush", "fiala", "dugoff"):
        assert tire_law(name).name == name


def test_unknown_law_names_the_choices():
    with pytest.raises(ParameterError, match="unknown tire law 'bristle'.*brush") as info:
        tire_law("bristle")
    assert info.value.key == "tires.model"


def test_magic_formula_resolves_lazily():
    if importlib.util.find_spec("vehdyn.tire.magic_formula") is None:
        with pytest.raises(ParameterError, match="magic_formula"):
            tire_law("magic_formula")
    else:
        assert tire_law("magic_formula").__name__ == "MagicFormula"


@pytest.mark.parametrize("name", ["linear", "brush", "fiala", "dugoff"])
@pytest.mark.parametrize("axle", ["front", "rear"])
def test_tire_for_vehicle_reproduces_the_vehicle_cornering_stiffness(name, axle):
    vehicle = vehdyn.load_vehicle("sedan").replace(tires__model=name)
    tire = tire_for_vehicle(vehicle, axle)
    assert isinstance(tire, tire_law(name))
    axle_stiffness = getattr(vehicle.tires, f"{axle}_cornering_stiffness")
    load = vehicle.static_axle_loads()[0 if axle == "front" else 1] / 2
    h = 1e-7
    per_tire = -(tire.forces(load, 0.0, h).fy - tire.forces(load, 0.0, -h).fy) / (2 * h)
    assert 2 * per_tire == pytest.approx(axle_stiffness, rel=1e-6)


def test_vehicle_tire_data_contact_length_is_the_chord_at_static_deflection():
    vehicle = vehdyn.load_vehicle("sedan")
    data = vehicle_tire_data(vehicle, "rear")
    delta = data.static_load / vehicle.tires.vertical_stiffness
    radius = vehicle.tires.rolling_radius
    assert (radius - delta) ** 2 + data.contact_half_length**2 == pytest.approx(radius**2, rel=1e-14)
    with pytest.raises(ParameterError, match="axle"):
        vehicle_tire_data(vehicle, "middle")


def test_register_a_law():
    class Slick(TireModel):
        name = "slick_for_test"

        def forces(self, fz, kappa, alpha, gamma=0.0, vx=10.0):
            raise NotImplementedError

    register_tire_law("slick_for_test", Slick)
    assert tire_law("slick_for_test") is Slick
    register_tire_law("slick_for_test", Slick)  # the same law again is fine
    with pytest.raises(ParameterError, match="already registered"):
        register_tire_law("slick_for_test", BrushTire)
    with pytest.raises(ParameterError, match="snake_case"):
        register_tire_law("Bad Name", Slick)
    with pytest.raises(ParameterError, match="TireModel"):
        register_tire_law("not_a_law", int)
    vehicle = vehdyn.load_vehicle("sedan").replace(tires__model="slick_for_test")
    with pytest.raises(ParameterError, match="neither"):
        tire_for_vehicle(vehicle)
    assert math.isfinite(1.0)


def test_magic_formula_of_a_vehicle_is_read_once_per_version_of_its_file(tmp_path):
    """A sweep builds a model per variant: the .tir file is parsed once and its law shared, until
    the file changes (then the new values are read)."""
    sedan = vehdyn.load_vehicle("sedan")
    path = tmp_path / "copy.tir"
    text = sedan.tir_path().read_text()
    path.write_text(text)
    vehicle = sedan.replace(tires__tir_file=str(path))
    first = tire_for_vehicle(vehicle, "front")
    assert tire_for_vehicle(vehicle.replace(mass__mass=1.1 * sedan.mass.mass), "rear") is first
    lines = [line for line in text.splitlines() if line.strip().upper().startswith("FNOMIN")]
    assert len(lines) == 1 and math.isclose(first._c.FNOMIN, float(lines[0].split("=")[1].split("$")[0]))
    path.write_text(text.replace(lines[0], "FNOMIN = 1234.5 $ changed"))
    second = tire_for_vehicle(vehicle, "front")
    assert second is not first and second._c.FNOMIN == 1234.5
