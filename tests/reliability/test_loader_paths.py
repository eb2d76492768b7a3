"""Every parameter loader reports an unreadable path the same way (one helper, ``read_toml``):
a non-UTF-8 file or a folder gives a ParameterError naming the path and why, for vehicles,
trailers and soils alike (the vehicle cases in detail are in test_parameters_input.py)."""

import pytest

from vehdyn import ParameterError, load_trailer, load_vehicle
from vehdyn.tire.terramechanics import load_soil

LOADERS = [load_vehicle, load_trailer, load_soil]


@pytest.mark.parametrize("load", LOADERS, ids=lambda f: f.__name__)
@pytest.mark.parametrize("name", ["latin1.toml", "latin1"])
def test_non_utf8_file(load, tmp_path, name):
    path = tmp_path / name
    path.write_bytes("name = 'Käfer'\n".encode("latin-1"))  # 0xe4 is not UTF-8
    with pytest.raises(ParameterError, match=r"not a UTF-8 text file \(byte 0xe4 at line 1\)") as info:
        load(path)
    assert info.value.key == "path" and str(path) in str(info.value)


@pytest.mark.parametrize("load", LOADERS, ids=lambda f: f.__name__)
@pytest.mark.parametrize("name", ["folder", "folder.toml"])
def test_folder(load, tmp_path, name):
    folder = tmp_path / name
    folder.mkdir()
    with pytest.raises(ParameterError, match="is a folder, not a parameter file") as info:
        load(folder)
    assert info.value.key == "path" and str(folder) in str(info.value)


def test_folder_named_like_a_shipped_soil_does_not_hide_it(tmp_path, monkeypatch):
    expected = load_soil("dry_sand")
    monkeypatch.chdir(tmp_path)
    (tmp_path / "dry_sand").mkdir()
    assert load_soil("dry_sand") == expected
