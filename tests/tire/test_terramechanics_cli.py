"""``vehdyn tire --soil NAME``: prints the soil and its curves, writes the figure; usage errors."""

import numpy as np
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
