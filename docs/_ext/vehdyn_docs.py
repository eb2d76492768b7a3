"""Sphinx helpers of the vehdyn documentation: API pages from ``__all__``, the study gallery.

* :func:`write_api_pages` writes one reStructuredText page per layer (grouped as the README's
  table) with an ``autosummary`` table of every public name of ``vehdyn.__all__`` and the
  subpackages' ``__all__``; autosummary then generates one page per name. A name exported by
  several modules (``vehdyn.Vehicle`` is ``vehdyn.params.Vehicle``) gets one page, under its first
  public path, and is listed in every table that exports it.
* The gallery runs the study scripts as they are: ``Study.main(run, __file__)`` takes the output
  folder from ``sys.argv[1]`` (:func:`study_argv`) and quick mode from ``VEHDYN_QUICK``; a study
  saves and closes its figures, so :class:`StudyScraper` collects the PNG files it wrote.
* A study's module docstring is plain text (its first line is the title ``vehdyn report`` shows);
  :func:`_study_page` turns it into a page title and escapes the text so that Sphinx renders it
  literally.
"""

from __future__ import annotations

import atexit
import importlib
import inspect
import re
import shutil
import tempfile
from pathlib import Path

# (page, title, intro, [(module, names or None for its __all__)])
LAYERS = [
    # foundation
    ("parameters", "Parameters",
     "Frozen, validated parameter sets read from TOML; the shipped vehicles and trailers.",
     [("vehdyn", ["Vehicle", "load_vehicle", "shipped_vehicles", "data_path", "Trailer", "load_trailer",
                  "shipped_trailers"]), ("vehdyn.params", None)]),
    ("errors", "Errors and warnings",
     "Every bad input raises one of these, naming the parameter and the value.",
     [("vehdyn", ["VehdynError", "ParameterError", "SimulationError", "TirFileError", "VehdynWarning"])]),
    ("conventions", "Conventions and units",
     "SAE J670 vehicle axes, ISO 8855 and ISO-W tire axes: the one place signs flip; unit helpers.",
     [("vehdyn.conventions", None), ("vehdyn.units", None)]),
    # core
    ("model_contract", "Model contract",
     "Named signals, the ``Model`` base class, exact linear models and their modes.",
     [("vehdyn", ["Signal", "Model", "LinearModel", "Modes"]), ("vehdyn.model", None)]),
    ("simulation", "Simulation and results",
     "``vehdyn.simulate`` and what it returns; the integrators' work-precision; compiled code ahead of time.",
     [("vehdyn", ["simulate", "simulate_many", "PiecewiseSignal", "SimulationResult", "FrequencyResponse",
                  "warm_up"]),
      ("vehdyn.simulation", None)]),
    ("interconnect", "Interconnection",
     "Closed loops of a plant and its controllers, series connection, the Padé delay.",
     [("vehdyn", ["ClosedLoop", "connect_in_series"]), ("vehdyn.interconnect", None)]),
    ("symbolic", "Symbolic forms",
     "A model's own equations as CasADi functions with exact Jacobians (``pip install 'vehdyn[optimal]'``).",
     [("vehdyn.symbolic", None)]),
    # physics
    ("mechanics", "Mechanics", "Rigid-body mechanics in the SAE body frame.", [("vehdyn.mechanics", None)]),
    ("tire", "Tire", "Tire laws, ``.tir`` files, slip, relaxation, fitting and soft soil.",
     [("vehdyn.tire", None), ("vehdyn.tire.fitting", None), ("vehdyn.tire.terramechanics", None)]),
    ("road", "Road", "ISO 8608 spectra and synthesis, road profiles and events, the IRI.", [("vehdyn.road", None)]),
    ("components", "Components", "What several vehicle models share.", [("vehdyn.components", None)]),
    # vehicles
    ("handling", "Handling", "Bicycle, lateral-yaw-roll, single-track and articulated models, steady state.",
     [("vehdyn.handling", None)]),
    ("ride", "Ride", "Quarter car, bounce–pitch, full car; ISO 2631-1 comfort; random vibration; control.",
     [("vehdyn.ride", None)]),
    ("full_vehicle", "Full vehicle", "The 6-DOF body on four corners.", [("vehdyn.full_vehicle", None)]),
    # controllers
    ("driver", "Drivers", "Preview, crossover and optimal-preview drivers; the driver-vehicle loop.",
     [("vehdyn.driver", None)]),
    ("chassis", "Chassis control", "ABS, traction control and ESC.", [("vehdyn.chassis", None)]),
    # procedures
    ("procedures", "Procedures", "Standard tests: ISO 7401, ISO 4138, ISO 3888, ISO 7975, ISO 13674, FMVSS 126.",
     [("vehdyn.procedures", None)]),
    # applications
    ("scene", "Scenes and the fidelity ladder", "The cheapest model that answers a question.",
     [("vehdyn", ["Scene", "plan", "run", "ladder", "plot_ladder"]), ("vehdyn.scene", None)]),
    ("optimal", "Optimal control",
     "Direct multiple shooting with IPOPT: the minimum-time lane change, NMPC path tracking.",
     [("vehdyn.optimal", None)]),
    ("sweep", "Sweeps and sensitivity", "Grids, samples, Monte Carlo and Sobol'/Morris indices.",
     [("vehdyn.sweep", None), ("vehdyn.sweep.metrics", None)]),
    # interfaces
    ("plotting", "Plotting and the command line", "Figures in the textbook's form; the ``vehdyn`` command.",
     [("vehdyn.plotting", None), ("vehdyn.cli", None)]),
]

# the order in which a re-exported object's first public path is chosen (bottom up)
_ORDER = ["vehdyn", "vehdyn.params", "vehdyn.conventions", "vehdyn.units", "vehdyn.symbolic", "vehdyn.model", "vehdyn.simulation",
          "vehdyn.interconnect", "vehdyn.mechanics", "vehdyn.tire", "vehdyn.tire.fitting",
          "vehdyn.tire.terramechanics", "vehdyn.road", "vehdyn.components", "vehdyn.handling", "vehdyn.ride",
          "vehdyn.full_vehicle", "vehdyn.driver", "vehdyn.chassis", "vehdyn.procedures", "vehdyn.scene",
          "vehdyn.optimal", "vehdyn.sweep", "vehdyn.sweep.metrics", "vehdyn.plotting", "vehdyn.cli"]


def public_names() -> dict[str, list[str]]:
    """``{module: __all__}`` for ``vehdyn`` and every subpackage documented here."""
    return {name: list(importlib.import_module(name).__all__) for name in _ORDER}


def _canonical_paths(exports: dict[str, list[str]]) -> dict[tuple[str, str], str]:
    """``(module, name) -> full path`` of the page that documents it (its first public path)."""
    first: dict[int, str] = {}
    paths = {}
    for module in _ORDER:
        mod = importlib.import_module(module)
        for name in exports[module]:
            obj = getattr(mod, name)
            own = f"{module}.{name}"
            if inspect.ismodule(obj) or not (inspect.isclass(obj) or callable(obj)):
                paths[module, name] = own  # modules and data: by their own path
                continue
            paths[module, name] = first.setdefault(id(obj), own)
    return paths


def write_api_pages(folder: Path) -> None:
    """Write ``folder/index.rst`` and one page per layer (only files whose text changed)."""
    exports = public_names()
    paths = _canonical_paths(exports)
    covered = {(m, n) for _, _, _, mods in LAYERS for m, names in mods for n in (names or exports[m])}
    missing = sorted(f"{m}.{n}" for m in _ORDER for n in exports[m] if (m, n) not in covered)
    if missing:
        raise RuntimeError(f"public names on no API page: {missing}")
    folder.mkdir(parents=True, exist_ok=True)
    toc = "\n".join(f"   {page}" for page, *_ in LAYERS)
    _write(folder / "index.rst", f""".. _api:

API reference
=============

Every public name of ``vehdyn`` and its subpackages (their ``__all__``), grouped by layer as in
the README. Each page is generated from the docstrings.

.. toctree::
   :maxdepth: 2

{toc}
""")
    for page, title, intro, modules in LAYERS:
        parts = [f".. _api-{page}:\n\n{title}\n{'=' * len(title)}\n\n{intro}\n"]
        for module, names in modules:
            mod = importlib.import_module(module)
            names = names if names is not None else exports[module]
            if module != "vehdyn" and names == exports[module]:
                heading = f"``{module}``"
                parts.append(f"{heading}\n{'-' * len(heading)}\n\n.. automodule:: {module}\n   :no-members:\n")
            rows, modules_listed = [], []  # rows: [module of the page, [names]] runs
            for name in names:
                if inspect.ismodule(getattr(mod, name)):
                    modules_listed.append(f"{module}.{name}")
                    continue
                home, _, short = paths[module, name].rpartition(".")
                if not rows or rows[-1][0] != home:
                    rows.append((home, []))
                rows[-1][1].append(short)
            for home, shorts in rows:
                parts.append(f".. currentmodule:: {home}\n\n.. autosummary::\n   :toctree: generated/\n"
                             "   :nosignatures:\n\n" + "\n".join(f"   {short}" for short in shorts) + "\n")
            if modules_listed:
                parts.append("Subpackages: " + ", ".join(f":mod:`{m}`" for m in modules_listed) + ".\n")
        _write(folder / f"{page}.rst", "\n".join(parts))


def _write(path: Path, text: str) -> None:
    if not path.exists() or path.read_text(encoding="utf-8") != text:
        path.write_text(text, encoding="utf-8")


# --------------------------------------------------------------------------------------------- gallery
_OUT: list[Path] = []


def _out_root() -> Path:
    if not _OUT:
        _OUT.append(Path(tempfile.mkdtemp(prefix="vehdyn-gallery-")))
        atexit.register(shutil.rmtree, _OUT[0], True)
    return _OUT[0]


def gallery_pattern(choice: str) -> str:
    """sphinx-gallery's ``filename_pattern`` for ``VEHDYN_DOCS_GALLERY`` (``all``, ``none`` or a regex)."""
    choice = choice.strip()
    if choice in ("", "all"):
        return r"/[^_][^/]*\.py$"
    if choice == "none":
        return r"^$"
    return choice


def study_argv(gallery_conf, script_vars) -> list[str]:
    """``sys.argv[1:]`` for a study run by the gallery: its output folder (see ``Study.main``).

    sphinx-gallery calls this just before it runs the script, with the script's globals in
    ``script_vars``; a study's last line is ``Study.main(run, __file__)``, so ``__file__`` (which
    sphinx-gallery leaves undefined) is set to the script's path as Python would.
    """
    script_vars["example_globals"]["__file__"] = str(script_vars["src_file"])
    return [str(_out_root() / Path(script_vars["src_file"]).stem)]


class StudyScraper:
    """Collect the figures (PNG) a study wrote to its output folder, in the order it wrote them."""

    def __repr__(self) -> str:  # sphinx-gallery reports the scrapers by repr in its config cache
        return "StudyScraper()"

    def __call__(self, block, block_vars, gallery_conf):
        from sphinx_gallery.scrapers import figure_rst

        folder = _out_root() / Path(block_vars["src_file"]).stem
        if not folder.is_dir():
            return ""
        done = block_vars.setdefault("vehdyn_scraped", set())
        new = sorted((p for p in folder.glob("*.png") if p.name not in done), key=lambda p: p.stat().st_mtime_ns)
        paths = []
        for png, target in zip(new, block_vars["image_path_iterator"]):
            shutil.copyfile(png, target)
            done.add(png.name)
            paths.append(target)
        return figure_rst(paths, gallery_conf["src_dir"])


study_scraper = StudyScraper()


_RST_SPECIAL = re.compile(r"([\\`*_|\[\]<>])")


def _escape(text: str) -> str:
    return _RST_SPECIAL.sub(r"\\\1", text)


def _study_page(source: str) -> str:
    """Gallery page of a study: its docstring's first line as the title, the rest escaped."""
    marker = ".. GENERATED FROM PYTHON SOURCE LINES"
    label = re.search(r"^\.\. _sphx_glr_\S+:\n", source, re.MULTILINE)
    end = source.find(marker, label.end() if label else 0)
    if not label or end < 0:
        return source
    doc = source[label.end():end].strip()
    if doc.startswith(("=", "-")) or "\n===" in doc.split("\n\n")[0]:
        return source  # already a reStructuredText title
    lines = doc.splitlines()
    title = _escape(lines[0].strip().rstrip("."))
    body = "\n".join(_escape(line) for line in lines[1:]).strip()
    page = f"\n{title}\n{'=' * len(title)}\n\n{body}\n\n"
    return source[:label.end()] + page + source[end:]


def _source_read(app, docname, source):
    gallery = app.config.sphinx_gallery_conf["gallery_dirs"]
    if docname.startswith(f"{gallery}/") and docname != f"{gallery}/index":
        source[0] = _study_page(source[0])


# ------------------------------------------------------------------------------------------ docstrings
# The models' docstrings list their named signals in sections numpydoc does not know ("Signals",
# "States", "Inputs", "Outputs"); numpydoc would drop them, so they are moved, as rubrics, into the
# extended summary. Plain-text absolute values |x| would be read as substitutions: escaped outside
# literals, roles, math and doctests.
_SIGNAL_SECTIONS = ("Signals", "States", "Inputs", "Outputs")
_LITERAL = re.compile(r"(``.+?``|:[a-z:]+:`[^`]*`|`[^`]*`_?)")


def _is_heading(lines: list[str], i: int) -> bool:
    if i + 1 >= len(lines) or not lines[i].strip():
        return False
    underline = lines[i + 1].strip()
    return len(underline) >= 3 and set(underline) == {"-"} and not lines[i].startswith(" ")


def _move_signal_sections(lines: list[str]) -> list[str]:
    headings = [i for i in range(len(lines)) if _is_heading(lines, i)]
    moved, keep, i = [], [], 0
    bounds = headings + [len(lines)]
    if not headings:
        return lines
    keep = lines[:headings[0]]
    for start, end in zip(headings, bounds[1:]):
        block = lines[start:end]
        if block[0].strip() in _SIGNAL_SECTIONS:
            body = block[2:]
            moved += [f".. rubric:: {block[0].strip()}", ""] + body + ([""] if body and body[-1].strip() else [])
        else:
            keep += block
    if not moved:
        return lines
    first = headings[0]
    head = keep[:first]
    if head and head[-1].strip():
        head.append("")
    return head + moved + keep[first:]


def _escape_bars(lines: list[str]) -> list[str]:
    out, literal_indent, in_doctest = [], None, False
    for line in lines:
        stripped = line.lstrip()
        indent = len(line) - len(stripped)
        if literal_indent is not None:
            if not stripped or indent > literal_indent:
                out.append(line)
                continue
            literal_indent = None
        if stripped.startswith((">>>", "...")) or (in_doctest and stripped):
            in_doctest = True
            out.append(line)
            continue
        in_doctest = False
        if stripped.endswith("::"):
            literal_indent = indent
        if "|" in line:
            parts = _LITERAL.split(line)
            line = "".join(part if k % 2 else re.sub(r"(?<!\\)\|", r"\\|", part) for k, part in enumerate(parts))
        out.append(line)
    return out


def _process_docstring(app, what, name, obj, options, lines):
    lines[:] = _escape_bars(_move_signal_sections(list(lines)))


def setup(app):
    app.connect("source-read", _source_read)
    app.connect("autodoc-process-docstring", _process_docstring, priority=400)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
