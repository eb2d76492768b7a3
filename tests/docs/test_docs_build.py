"""The documentation site builds with warnings as errors, and the docstring examples run.

``test_site_builds`` runs ``sphinx-build -W --keep-going`` on a copy of ``docs/`` (so that the
generated API and gallery pages do not land in the checkout) and checks the result against the
package: one API page for every public name of ``vehdyn.__all__`` and the subpackages' ``__all__``,
a gallery page for every study, the figures of the studies it executed. To stay within the CI
budget the gallery executes a quick subset of the studies (``GALLERY_SUBSET``; every study runs in
quick mode in ``tests/test_studies.py`` anyway); the others are rendered with their code but not
run. ``python -m sphinx -W --keep-going -b html docs docs/_build/html`` (README) runs them all.

``test_docstring_examples`` runs every ``>>>`` example of the package as a doctest.
"""

import importlib
import inspect
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

for _module in ("sphinx", "numpydoc", "sphinx_gallery", "pydata_sphinx_theme"):
    pytest.importorskip(_module, reason='the docs test needs pip install -e ".[test]"')

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"
GALLERY_SUBSET = ("step_steer", "quarter_car", "low_speed")
MODULES = ["vehdyn", "vehdyn.params", "vehdyn.conventions", "vehdyn.units", "vehdyn.model", "vehdyn.simulation",
           "vehdyn.interconnect", "vehdyn.mechanics", "vehdyn.tire", "vehdyn.tire.fitting",
           "vehdyn.tire.terramechanics", "vehdyn.road", "vehdyn.components", "vehdyn.handling", "vehdyn.ride",
           "vehdyn.full_vehicle", "vehdyn.driver", "vehdyn.chassis", "vehdyn.procedures", "vehdyn.scene",
           "vehdyn.sweep", "vehdyn.plotting", "vehdyn.cli"]


def _env(**extra):
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", MPLBACKEND="Agg", PYTHONPATH=str(ROOT), **extra)
    env.pop("VEHDYN_FULL", None)
    return env


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    src = tmp_path_factory.mktemp("docs") / "docs"
    shutil.copytree(DOCS, src, ignore=shutil.ignore_patterns("_build", "api", "gallery"))
    out = src / "_build" / "html"
    pattern = "/(" + "|".join(GALLERY_SUBSET) + r")\.py$"
    proc = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-j", "2", "-b", "html",
                           str(src), str(out)], cwd=src, capture_output=True, text=True, timeout=900,
                          env=_env(VEHDYN_DOCS_ROOT=str(ROOT), VEHDYN_DOCS_GALLERY=pattern))
    return proc, src, out


def test_site_builds_without_warnings(site):
    proc, _, out = site
    assert proc.returncode == 0, proc.stderr[-6000:]
    assert (out / "index.html").is_file()


def test_every_public_name_has_an_api_page(site):
    proc, _, out = site
    assert proc.returncode == 0, proc.stderr[-2000:]
    pages = {p.stem for p in (out / "api" / "generated").glob("*.html")}
    documented = {}
    for module in MODULES:
        mod = importlib.import_module(module)
        for name in mod.__all__:
            obj = getattr(mod, name)
            if inspect.ismodule(obj):
                assert (out / "py-modindex.html").read_text().count(f"{module}.{name}") or \
                    f"{module}.{name}" in {f"{m}" for m in MODULES}, name
                continue
            # a re-exported object has one page, under the first module that exports it
            key = id(obj) if (inspect.isclass(obj) or callable(obj)) else (module, name)
            documented.setdefault(key, f"{module}.{name}")
    missing = sorted(path for path in documented.values() if path not in pages)
    assert not missing, missing


def test_gallery_has_every_study_and_the_figures_of_the_run_ones(site):
    proc, src, out = site
    assert proc.returncode == 0, proc.stderr[-2000:]
    studies = sorted(p.stem for p in (ROOT / "studies").glob("*.py") if not p.name.startswith("_"))
    for stem in studies:
        page = out / "gallery" / f"{stem}.html"
        assert page.is_file(), stem
        title = (ROOT / "studies" / f"{stem}.py").read_text(encoding="utf-8").split('"""')[1].splitlines()[0]
        words = re.findall(r"[A-Za-z]{4,}", title)[:3]
        assert all(word in page.read_text(encoding="utf-8") for word in words), (stem, words)
    for stem in GALLERY_SUBSET:
        images = list((out / "_images").glob(f"sphx_glr_{stem}_*.png"))
        assert images, f"{stem}: no figure collected from the study's output folder"
        assert (src / "gallery" / f"{stem}.ipynb").is_file()
        assert (src / "gallery" / f"{stem}.py").read_bytes() == (ROOT / "studies" / f"{stem}.py").read_bytes()


def test_a_broken_reference_fails_the_build(tmp_path):
    """-W turns an unresolved internal reference into a failed build (a small project, no API)."""
    (tmp_path / "conf.py").write_text("extensions = ['sphinx.ext.autodoc']\n")
    (tmp_path / "index.rst").write_text("Title\n=====\n\nSee :ref:`no-such-label` and :doc:`missing`.\n")
    proc = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html", str(tmp_path),
                           str(tmp_path / "_build")], capture_output=True, text=True, timeout=300, env=_env())
    assert proc.returncode != 0
    assert "no-such-label" in proc.stderr and "missing" in proc.stderr


def test_docstring_examples():
    proc = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "--doctest-modules",
                           "--import-mode=importlib", "-o", "addopts=", "-o", "testpaths=", "vehdyn"],
                          cwd=ROOT, capture_output=True, text=True, timeout=900, env=_env())
    summary = proc.stdout.strip().splitlines()[-1] if proc.stdout.strip() else ""
    assert proc.returncode == 0, proc.stdout[-6000:] + proc.stderr[-2000:]
    assert re.search(r"\d+ passed", summary), summary
