"""Sphinx configuration of the vehdyn documentation.

Build (README, development): ``python -m sphinx -W --keep-going -b html docs docs/_build/html``.

The API pages are generated from ``__all__`` (``_ext/vehdyn_docs.py``); the gallery runs the study
scripts ``studies/*.py`` — the same files ``vehdyn report`` runs — in quick mode. Environment:

``VEHDYN_DOCS_GALLERY``
    Which studies the gallery executes: unset or ``all`` every study; ``none`` none (their pages
    show the code without output); otherwise a regular expression matched against the file path
    (the docs test in ``tests/docs`` runs a quick subset this way).
``VEHDYN_DOCS_ROOT``
    The checkout whose ``studies/`` the gallery shows (default: the folder above this one).
"""

import os
import sys
import warnings
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = Path(os.environ.get("VEHDYN_DOCS_ROOT", HERE.parent))  # the checkout (tests build a copy of docs/)
sys.path.insert(0, str(HERE / "_ext"))
sys.path.insert(0, str(ROOT))

import vehdyn  # noqa: E402
import vehdyn_docs  # noqa: E402

project = "vehdyn"
author = "vehdyn developers"
copyright = "vehdyn developers, BSD-3-Clause"
release = version = vehdyn.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx.ext.intersphinx",
    "numpydoc",
    "sphinx_gallery.gen_gallery",
    "matplotlib.sphinxext.plot_directive",
    "vehdyn_docs",
]

root_doc = "index"
exclude_patterns = ["_build", "**.ipynb_checkpoints", "gallery/*.md5", "gallery/*.py", "gallery/*.ipynb",
                    "gallery/*.zip", "gallery/*.json"]
default_role = "obj"
nitpicky = False

# API: one page per public name of every __all__, written by vehdyn_docs before autosummary runs.
vehdyn_docs.write_api_pages(HERE / "api")
autosummary_generate = True
autosummary_imported_members = True
autodoc_default_options = {"members": True, "inherited-members": False, "show-inheritance": True}
autodoc_typehints = "none"
autoclass_content = "class"
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
numpydoc_validation_checks = set()

# numpydoc parses the raw docstrings once more for signatures; the "Signals" sections it does not
# know are rendered through vehdyn_docs (moved into the extended summary), so its notice is noise.
warnings.filterwarnings("ignore", message="Unknown section (Signals|States|Inputs|Outputs)", category=UserWarning)

# matplotlib's plot directive (figures in the user guide, run at build time)
plot_include_source = True
plot_html_show_source_link = False
plot_html_show_formats = False
plot_formats = [("png", 90)]
plot_rcparams = {}

# Gallery: the study scripts, executed in quick mode; their figures are collected from the folder
# the study writes to (a study saves and closes its figures through Study.figure).
os.environ.setdefault("VEHDYN_QUICK", "1")
os.environ.setdefault("MPLBACKEND", "Agg")
sphinx_gallery_conf = {
    "examples_dirs": str(ROOT / "studies"),
    "gallery_dirs": "gallery",
    "filename_pattern": vehdyn_docs.gallery_pattern(os.environ.get("VEHDYN_DOCS_GALLERY", "all")),
    "ignore_pattern": r"/_",
    "reset_argv": "vehdyn_docs.study_argv",
    "image_scrapers": ("vehdyn_docs.study_scraper",),
    "download_all_examples": False,
    "remove_config_comments": True,
    "min_reported_time": 1,
    "within_subsection_order": "FileNameSortKey",
    "abort_on_example_error": False,
    "only_warn_on_example_error": False,
    "show_memory": False,
    "plot_gallery": "True",
    "capture_repr": (),
    # a downloaded notebook runs the study as its script would: figures and tables go to out/study
    "first_notebook_cell": ("import sys\n"
                            "sys.argv = sys.argv[:1]  # Study.main takes its output folder from sys.argv[1]\n"
                            "__file__ = 'study.py'  # and its name from __file__"),
}

intersphinx_mapping = {}  # offline builds: no inventories fetched

html_theme = "pydata_sphinx_theme"
html_title = f"vehdyn {version}"
html_theme_options = {
    "navigation_depth": 3,
    "show_toc_level": 2,
    "secondary_sidebar_items": ["page-toc"],
    "footer_start": ["copyright"],
    "footer_end": [],
}
html_context = {"default_mode": "light"}
html_show_sourcelink = False
