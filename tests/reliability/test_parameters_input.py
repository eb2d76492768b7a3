"""Bad parameter input gets a ParameterError naming the file or the dotted key, never a raw error.

Independent references: the shipped sedan file itself (a BOM-prefixed copy must load to an equal
object), ``dataclasses.replace`` applied group by group (what ``Vehicle.replace`` must equal).
"""

import codecs
import dataclasses

import pytest

from vehdyn import ParameterError, data_path, load_vehicle


@pytest.fixture(scope="module")
def sedan():
    return load_vehicle("sedan")


def _sedan_bytes():
    return data_path("vehicles", "sedan.toml").read_bytes()


# ---------------------------------------------------------------------------- files


@pytest.mark.parametrize("name", ["binary.toml", "binary"])
def test_binary_file_is_named_not_decoded(tmp_path, name):
    path = tmp_path / name
    path.write_bytes(b"mass = 1\n" + bytes(range(0x80, 0x100)))
    with pytest.raises(ParameterError, match=r"not a UTF-8 text file \(byte 0x80 at line 2\)") as info:
        load_vehicle(path)
    assert info.value.key == "path" and str(path) in str(info.value)


@pytest.mark.parametrize("name", ["folder", "folder.toml"])
def test_folder_is_named(tmp_path, name):
    folder = tmp_path / name
    folder.mkdir()
    with pytest.raises(ParameterError, match="is a folder, not a parameter file") as info:
        load_vehicle(folder)
    assert info.value.key == "path"


def test_folder_named_like_a_shipped_vehicle_does_not_hide_it(tmp_path, monkeypatch, sedan):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "sedan").mkdir()
    assert load_vehicle("sedan") == sedan


@pytest.mark.parametrize("bad", [3, 2.5, None, ["sedan"], b"sedan", {"name": "sedan"}])
def test_non_path_object(bad):
    with pytest.raises(ParameterError, match="must be a shipped vehicle's name or a path") as info:
        load_vehicle(bad)
    assert info.value.key == "vehicle" and type(bad).__name__ in str(info.value)


def test_utf8_byte_order_mark_is_accepted(tmp_path, sedan):
    path = tmp_path / "bom.toml"
    path.write_bytes(codecs.BOM_UTF8 + _sedan_bytes())
    assert load_vehicle(path) == sedan


@pytest.mark.parametrize("encoding, name", [("utf-16", "UTF-16"), ("utf-32", "UTF-32")])
def test_utf16_and_utf32_files_are_named(tmp_path, encoding, name):
    path = tmp_path / "wide.toml"
    path.write_bytes(_sedan_bytes().decode("utf-8").encode(encoding))  # Python writes the BOM
    with pytest.raises(ParameterError, match=f"encoded in {name}; TOML files must be UTF-8"):
        load_vehicle(path)


def test_unreadable_file(tmp_path, monkeypatch):
    path = tmp_path / "locked.toml"
    path.write_bytes(_sedan_bytes())

    def refuse(self):
        raise PermissionError(13, "Permission denied", str(self))

    monkeypatch.setattr(type(path), "read_bytes", refuse)  # chmod 0 does not stop root
    with pytest.raises(ParameterError, match="cannot read parameter file .*locked.toml: Permission denied"):
        load_vehicle(path)


# ---------------------------------------------------------------------------- replace


def test_replace_nested_equals_dataclasses_replace(sedan):
    variant = sedan.replace(mass__mass=sedan.mass.mass + 50, suspension__front_spring_rate=30e3,
                            description="heavier")
    expected = dataclasses.replace(
        sedan, description="heavier",
        mass=dataclasses.replace(sedan.mass, mass=sedan.mass.mass + 50),
        suspension=dataclasses.replace(sedan.suspension, front_spring_rate=30e3))
    assert variant == expected
    assert sedan == load_vehicle("sedan")  # the original is unchanged


@pytest.mark.parametrize(
    "changes, key, match",
    [
        ({"mass__unknown": 1.0}, "mass.unknown", r"unknown parameter 'mass.unknown' \(value 1.0\); MassAndInertia takes"),
        ({"colour": "red"}, "colour", r"unknown parameter 'colour' \(value 'red'\); Vehicle takes"),
        ({"engine__power": 1e5}, "engine", r"unknown parameter group 'engine' \(in engine__power=100000.0\)"),
        ({"name__first": "x"}, "name", r"'name' is a parameter, not a group"),
        ({"mass__mass": -1.0}, "mass.mass", r"^mass.mass must be > 0 \[kg\], got -1.0"),
        ({"tires__tir_file": 3}, "tires.tir_file", r"^tires.tir_file must be a string"),
        ({"mass__mass__value": 1.0}, "mass.mass", r"'mass.mass' is a parameter, not a group"),
    ],
)
def test_replace_errors_name_the_dotted_key(sedan, changes, key, match):
    with pytest.raises(ParameterError, match=match) as info:
        sedan.replace(**changes)
    assert info.value.key == key


def test_replace_group_given_twice(sedan):
    with pytest.raises(ParameterError, match="given both whole and by field") as info:
        sedan.replace(mass=sedan.mass, mass__mass=1500.0)
    assert info.value.key == "mass"


def test_replace_on_a_group(sedan):
    heavier = sedan.mass.replace(mass=1500.0)
    assert heavier == dataclasses.replace(sedan.mass, mass=1500.0)
    with pytest.raises(ParameterError, match=r"unknown parameter 'weight'") as info:
        sedan.mass.replace(weight=1500.0)
    assert info.value.key == "weight"
