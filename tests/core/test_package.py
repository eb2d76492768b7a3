"""Packaging promises: light import, shipped data in the wheel, the README's two commands, the CLI."""

import re
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

import vehdyn
from vehdyn.cli import main

ROOT = Path(__file__).resolve().parents[2]


def test_import_is_light():
    code = ("import sys, vehdyn; heavy = [m for m in ('control', 'scipy', 'pandas', 'matplotlib') "
            "if m in sys.modules]; print(heavy)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"


def test_public_api_index():
    for name in vehdyn.__all__:
        assert getattr(vehdyn, name) is not None, name


def test_readme_opens_with_two_commands_and_ci_runs_the_second():
    readme = (ROOT / "README.md").read_text()
    blocks = re.findall(r"```(?:bash|sh|console)?\n(.*?)```", readme, re.S)
    assert len(blocks) >= 2
    first, second = blocks[0].strip(), blocks[1].strip()
    assert "vehdyn report" in first and len(first.splitlines()) == 1
    assert "pytest" in second and len(second.splitlines()) == 1
    assert readme.index(first) < readme.index("## ")  # before the first section
    ci = (ROOT / ".ci" / "run").read_text()
    assert second in ci


@pytest.mark.slow
def test_wheel_ships_data(tmp_path):
    proc = subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(tmp_path), str(ROOT)],
                          capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr[-2000:]
    wheel = next(tmp_path.glob("vehdyn-*.whl"))
    names = zipfile.ZipFile(wheel).namelist()
    assert "vehdyn/data/vehicles/sedan.toml" in names
    assert "vehdyn/data/tires/MagicFormula61_Parameters.tir" in names
    assert "vehdyn/data/vehicles/LICENSE-commonroad.txt" in names
    assert "vehdyn/studies/integrator_work_precision.py" in names


def test_cli_help_and_vehicles(capsys):
    with pytest.raises(SystemExit) as info:
        main(["--help"])
    assert info.value.code == 0
    assert "report" in capsys.readouterr().out
    assert main(["vehicles"]) == 0
    out = capsys.readouterr().out
    assert "sedan" in out and "van" in out


def test_cli_unknown_study(capsys, tmp_path):
    assert main(["study", "no_such_study", "--out", str(tmp_path)]) == 2
    assert "no study named 'no_such_study'" in capsys.readouterr().err


def test_cli_report_runs_one_study(tmp_path):
    assert main(["report", "--quick", "--only", "integrator_work_precision", "--out", str(tmp_path)]) == 0
    html = (tmp_path / "index.html").read_text()
    assert "Integrator work-precision" in html and "work_precision.png" in html
    assert (tmp_path / "integrator_work_precision" / "work_precision.png").stat().st_size > 10_000


def test_cli_tire_describes_file_and_writes_figures(tmp_path, capsys):
    path = vehdyn.data_path("tires", "MagicFormula61_Parameters.tir")
    assert main(["tire", str(path), "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "6.1" in out and "FNOMIN" in out
    assert len(list(tmp_path.glob("*.png"))) >= 5
    assert main(["tire", str(tmp_path / "missing.tir"), "--out", str(tmp_path)]) == 2


def test_readme_quick_start_runs(capsys):
    readme = (ROOT / "README.md").read_text()
    code = re.findall(r"```python\n(.*?)```", readme, re.S)[0]
    exec(compile(code, "README.md quick start", "exec"), {})
    out = capsys.readouterr().out
    assert "rad/s" in out  # the yaw rate with its unit
    assert "choice: " in out and "estimated error" in out  # the ladder's plan and the headline of its run
