"""Studies and the HTML report.

A study is a script ``studies/NAME.py`` that uses only vehdyn's public API. Its module docstring's
first line is its title and the rest its description; it defines ``run(study)``, where ``study`` is
a :class:`Study` that collects figures, tables and text::

    \"\"\"Step steer of the linear bicycle model.

    What the study shows, in a paragraph.
    \"\"\"
    from vehdyn.report import Study

    def run(study: Study) -> None:
        speeds = [20, 30] if study.quick else np.linspace(10, 40, 13)
        ...
        study.figure(fig, "yaw_rate", caption="Yaw rate after a 1 deg step steer")
        study.table(df, "metrics", caption="ISO 7401 metrics")
        study.text("Finding: ...")

    if __name__ == "__main__":
        Study.main(run, __file__)

``vehdyn report`` runs every study (``study.quick`` is true with ``--quick`` or ``VEHDYN_QUICK=1``,
for CI: small grids) and writes ``index.html`` with the figures (PNG) and tables; ``vehdyn study
NAME`` runs one.
"""

from __future__ import annotations

import html
import importlib.util
import os
import sys
import time
import traceback
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

__all__ = ["Study", "StudyOutcome", "discover_studies", "run_study", "write_report"]


def _quick_from_env() -> bool:
    return os.environ.get("VEHDYN_QUICK", "").strip() not in ("", "0", "false", "False")


@dataclass
class Study:
    """Collects what one study produces.

    Attributes
    ----------
    name : str
        File stem of the study.
    out_dir : Path
        Folder for its files.
    quick : bool
        Small grids (CI and ``--quick``).
    """

    name: str
    out_dir: Path
    quick: bool = False
    items: list = field(default_factory=list)

    def __post_init__(self):
        self.out_dir = Path(self.out_dir)
        self.out_dir.mkdir(parents=True, exist_ok=True)

    def figure(self, fig, name: str, caption: str = "") -> Path:
        """Save a matplotlib figure as ``NAME.png`` and close it."""
        import matplotlib.pyplot as plt

        path = self.out_dir / f"{name}.png"
        fig.savefig(path, dpi=110, bbox_inches="tight")
        plt.close(fig)
        self.items.append(("figure", path.name, caption))
        return path

    def table(self, frame, name: str, caption: str = "", floatfmt: str = "{:.6g}") -> Path:
        """Save a pandas DataFrame as ``NAME.csv``, show it in the report and print it."""
        import pandas as pd

        path = self.out_dir / f"{name}.csv"
        frame.to_csv(path)
        units = frame.attrs.get("units") if isinstance(frame, pd.DataFrame) else None
        with pd.option_context("display.width", 160, "display.max_columns", 30):
            print(f"\n== {self.name}: {caption or name}\n{frame.to_string()}")
        table_html = frame.to_html(float_format=lambda v: floatfmt.format(v), border=0, classes="table")
        if units:
            table_html += "<p class='units'>units: " + html.escape(
                ", ".join(f"{k} [{v}]" for k, v in units.items() if v)) + "</p>"
        self.items.append(("table", table_html, caption))
        return path

    def text(self, paragraph: str) -> None:
        """A paragraph of findings."""
        print(paragraph)
        self.items.append(("text", paragraph, ""))

    @staticmethod
    def main(run: Callable[["Study"], None], file: str) -> None:
        """Run a study as a script: ``python studies/NAME.py [OUT_DIR]``."""
        name = Path(file).stem
        out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path("out") / name
        import matplotlib

        matplotlib.use("Agg")
        run(Study(name, out, quick=_quick_from_env()))
        print(f"wrote {out}")


@dataclass
class StudyOutcome:
    name: str
    title: str
    description: str
    items: list
    seconds: float
    error: str | None = None


def discover_studies(folder: str | Path | None = None) -> list[Path]:
    """The study scripts ``studies/*.py`` (sorted), from ``folder`` or the project's ``studies/``."""
    if folder is None:
        folder = find_studies_folder()
    return sorted(p for p in Path(folder).glob("*.py") if not p.name.startswith("_"))


def find_studies_folder() -> Path:
    """``studies/`` beside the package (checkout) or in the current directory."""
    here = Path(__file__).resolve().parent.parent
    for cand in (here / "studies", Path.cwd() / "studies", here / "vehdyn" / "studies"):
        if cand.is_dir():
            return cand
    from .params import data_path

    return data_path("studies")


def _load_module(path: Path):
    spec = importlib.util.spec_from_file_location(f"vehdyn_study_{path.stem}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def run_study(path: str | Path, out_dir: str | Path, quick: bool = False) -> StudyOutcome:
    """Run one study script into ``out_dir/NAME``; errors are caught and reported in the outcome."""
    import matplotlib

    matplotlib.use("Agg")
    path = Path(path)
    study = Study(path.stem, Path(out_dir) / path.stem, quick=quick)
    start = time.perf_counter()
    title, description, error = path.stem, "", None
    try:
        module = _load_module(path)
        doc = (module.__doc__ or "").strip().splitlines()
        if doc:
            title = doc[0].strip().rstrip(".")
            description = "\n".join(doc[1:]).strip()
        if not hasattr(module, "run"):
            raise AttributeError(f"{path.name} defines no run(study) function")
        module.run(study)
    except Exception:  # report the failure, keep going with the other studies
        error = traceback.format_exc()
    return StudyOutcome(path.stem, title, description, study.items, time.perf_counter() - start, error)


_CSS = """
body{font-family:system-ui,sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222}
h1{border-bottom:2px solid #456}h2{margin-top:2.5em;border-bottom:1px solid #ccc}
figure{margin:1em 0}figcaption{font-size:.9em;color:#555}img{max-width:100%}
table.table{border-collapse:collapse;font-size:.85em}table.table td,table.table th{padding:2px 8px;
border-bottom:1px solid #ddd;text-align:right}.units{font-size:.8em;color:#666}
pre.error{background:#fee;padding:1em;overflow:auto}.toc li{margin:.2em 0}
"""


def write_report(outcomes: list[StudyOutcome], out_dir: str | Path, *, quick: bool) -> Path:
    """Write ``out_dir/index.html`` from study outcomes."""
    import vehdyn

    out_dir = Path(out_dir)
    parts = [f"<!doctype html><html><head><meta charset='utf-8'><title>vehdyn report</title>"
             f"<style>{_CSS}</style></head><body>",
             f"<h1>vehdyn {vehdyn.__version__} report</h1>",
             f"<p>{len(outcomes)} studies{' (quick mode: small grids)' if quick else ''}; generated "
             f"{time.strftime('%Y-%m-%d %H:%M:%S')}.</p><ul class='toc'>"]
    for o in outcomes:
        status = "failed" if o.error else f"{o.seconds:.1f} s"
        parts.append(f"<li><a href='#{o.name}'>{html.escape(o.title)}</a> ({status})</li>")
    parts.append("</ul>")
    for o in outcomes:
        parts.append(f"<h2 id='{o.name}'>{html.escape(o.title)}</h2>")
        if o.description:
            parts.extend(f"<p>{html.escape(p)}</p>" for p in o.description.split("\n\n"))
        for kind, payload, caption in o.items:
            if kind == "figure":
                parts.append(f"<figure><img src='{o.name}/{payload}' alt='{html.escape(caption)}'>"
                             f"<figcaption>{html.escape(caption)}</figcaption></figure>")
            elif kind == "table":
                parts.append(f"<h4>{html.escape(caption)}</h4>{payload}")
            else:
                parts.append(f"<p>{html.escape(payload)}</p>")
        if o.error:
            parts.append(f"<pre class='error'>{html.escape(o.error)}</pre>")
        parts.append(f"<p class='units'>study script: studies/{o.name}.py, {o.seconds:.2f} s</p>")
    parts.append("</body></html>")
    index = out_dir / "index.html"
    index.write_text("\n".join(parts), encoding="utf-8")
    return index
