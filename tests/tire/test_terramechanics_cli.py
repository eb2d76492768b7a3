"""``vehdyn tire --soil NAME``: prints the soil and its curves, writes the figure; usage errors."""

import pytest

from vehdyn.cli import main
from vehdyn.tire.terramechanics import RigidWheel, load_soil


def test_cli_soil_prints_curves_and_writes_figure(tmp_path, capsys):
    assert main(["tire", "--soil", "sandy_loam", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "Wong 2008" in out and "phi = 29 [deg]" in out
    row = next(line for line in out.splitlines() if line.split()[:1] == ["0.20"])
    sinkage_mm, pull = float(row.split()[1]), float(row.split()[2])
    r = RigidWheel(radius=0.3, width=0.2, soil=load_soil("sandy_loam")).solve(1500.0, 0.2)
    assert sinkage_mm == pytest.approx(float(r.sinkage) * 1e3, abs=0.006)
    assert pull == pytest.approx(float(r.drawbar_pull), abs=0.06)
    assert (tmp_path / "soil_sandy_loam.png").stat().st_size > 1000


@pytest.mark.parametrize("argv, message", [(["tire", "--soil", "mud"], "no shipped soil 'mud'"),
                                           (["tire"], "give a .tir file or --soil NAME"),
                                           (["tire", "x.tir", "--soil", "snow"], "not both")])
def test_cli_soil_usage_errors(argv, message, tmp_path, capsys):
    assert main(argv + ["--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert message in err and len(err.strip().splitlines()) == 1


def test_cli_user_soil_file(tmp_path, capsys):
    path = tmp_path / "site.toml"
    path.write_text('[pit]\nn = 1.1\nk_c = 0.99\nk_phi = 1528.43\ncohesion = 1.04\nfriction_angle = 28.0\n'
                    'shear_modulus = 2.5\ndensity = 1600.0\n[pit.units]\nk_c = "kN/m^(n+1)"\nk_phi = "kN/m^(n+2)"\n'
                    'cohesion = "kPa"\nfriction_angle = "deg"\nshear_modulus = "cm"\ndensity = "kg/m^3"\n')
    assert main(["tire", "--soil", f"{path}:pit", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "soil pit" in out and "source" not in out
    # the same numbers as the shipped dry sand (same values, different name)
    assert main(["tire", "--soil", "dry_sand", "--out", str(tmp_path)]) == 0
    shipped = capsys.readouterr().out
    rows = lambda text: [line for line in text.splitlines() if line[:6].strip().replace(".", "").lstrip("-").isdigit()]
    assert rows(out) == rows(shipped) and len(rows(out)) == 10
