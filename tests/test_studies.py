"""Every study runs in quick mode (as CI and `vehdyn report --quick` do) and produces figures."""

from pathlib import Path

import pytest

from vehdyn.report import discover_studies, run_study

STUDIES = discover_studies(Path(__file__).resolve().parents[1] / "studies")


@pytest.mark.parametrize("path", STUDIES, ids=[p.stem for p in STUDIES])
def test_study_runs_quick(path, tmp_path):
    outcome = run_study(path, tmp_path, quick=True)
    assert outcome.error is None, outcome.error
    figures = [item for item in outcome.items if item[0] == "figure"]
    assert figures, f"{path.stem} produced no figure"
    assert outcome.title and outcome.title != path.stem
