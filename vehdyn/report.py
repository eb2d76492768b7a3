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

Files are written so that a reader never sees a half-written one (:func:`build_report`): every
figure, table and ``index.html`` goes to a temporary file moved over its destination when complete,
and a report run builds the whole new report in a hidden sibling folder (``.NAME.partial-*``) that
replaces the report folder only after every study has finished and ``index.html`` is written. An
interrupted run (Ctrl-C, a crash, a full disk) leaves the previous complete report as it was;
concurrent runs into one folder each publish a complete report, the last one wins. The hidden
folder of a run killed outright (``kill -9``, power loss) is removed by a later run.
"""

from __future__ import annotations

import contextlib
import errno
import html
import importlib.util
import os
import re
import shutil
import signal
import socket
import sys
import tempfile
import threading
import time
import traceback
import uuid
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

from vehdyn._atomic import keep_permissions, atomic_write, atomic_write_text
from vehdyn.errors import ParameterError, VehdynError

__all__ = ["Study", "StudyOutcome", "discover_studies", "run_study", "write_report", "build_report"]


def _flag_from_env(name: str) -> bool:
    return os.environ.get(name, "").strip() not in ("", "0", "false", "False")


def quick_from_env() -> bool:
    return _flag_from_env("VEHDYN_QUICK")


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
    full : bool
        The heavy series that would take the default report past a few minutes (a complete
        FMVSS 126 series on every car's full vehicle, ...): ``vehdyn report --full`` or ``VEHDYN_FULL=1``.
        Without it such a study runs a representative subset and says so.
    items : list of tuple
        What the study has produced, in order: ``("figure", file name, caption)``,
        ``("table", HTML, caption)``, ``("text", paragraph, "")`` (default empty; filled by
        :meth:`figure`, :meth:`table` and :meth:`text`, read by :func:`write_report`).

    Notes
    -----
    Creating a Study creates ``out_dir`` (and its parents).
    """

    name: str
    out_dir: Path
    quick: bool = False
    items: list = field(default_factory=list)

    @property
    def full(self) -> bool:
        return not self.quick and _flag_from_env("VEHDYN_FULL")

    def __post_init__(self):
        self.out_dir = Path(self.out_dir)
        self.out_dir.mkdir(parents=True, exist_ok=True)

    def figure(self, fig, name: str, caption: str = "") -> Path:
        """Save a matplotlib figure as ``NAME.png`` (atomically) and close it.

        Parameters
        ----------
        fig : matplotlib.figure.Figure
            The figure, saved at 110 dpi with a tight bounding box.
        name : str
            File stem in :attr:`out_dir` (``NAME.png``; an earlier file of that name is replaced).
        caption : str
            Caption under the figure in the report (default none).

        Returns
        -------
        pathlib.Path
            ``out_dir / "NAME.png"``.
        """
        from vehdyn.plotting import save_figure

        path = save_figure(fig, self.out_dir / f"{name}.png", dpi=110)
        self.items.append(("figure", path.name, caption))
        return path

    def table(self, frame, name: str, caption: str = "", floatfmt: str = "{:.6g}") -> Path:
        """Save a pandas DataFrame as ``NAME.csv`` (atomically), show it in the report and print it.

        Parameters
        ----------
        frame : pandas.DataFrame
            The table, written with its index; its ``attrs["units"]`` (``{column: unit}``), if
            any, are listed under it in the report.
        name : str
            File stem in :attr:`out_dir` (``NAME.csv``).
        caption : str
            Heading of the table in the report and in the printout (default: ``name`` in the
            printout, none in the report).
        floatfmt : str
            :meth:`str.format` pattern of the floats in the report's HTML (default ``"{:.6g}"``);
            the CSV keeps full precision.

        Returns
        -------
        pathlib.Path
            ``out_dir / "NAME.csv"``.
        """
        import pandas as pd

        path = self.out_dir / f"{name}.csv"
        with atomic_write(path, "w", newline="") as handle:
            frame.to_csv(handle)
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
        """A paragraph of findings: printed, and shown in the report after what precedes it.

        Parameters
        ----------
        paragraph : str
            Plain text (HTML-escaped in the report).
        """
        print(paragraph)
        self.items.append(("text", paragraph, ""))

    @staticmethod
    def main(run: Callable[["Study"], None], file: str) -> None:
        """Run a study as a script: ``python studies/NAME.py [OUT_DIR]``.

        Selects matplotlib's non-interactive Agg backend and runs ``run`` on a :class:`Study`
        named after the script, in quick mode if ``VEHDYN_QUICK`` is set (not ``0`` or
        ``false``).

        Parameters
        ----------
        run : callable
            The study's ``run(study)``.
        file : str
            The script's path (``__file__``): its stem names the study. The output folder is the
            first command-line argument, else ``out/NAME`` in the current directory.
        """
        name = Path(file).stem
        out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path("out") / name
        import matplotlib

        matplotlib.use("Agg")
        run(Study(name, out, quick=quick_from_env()))
        print(f"wrote {out}")


@dataclass
class StudyOutcome:
    """What one study run produced (:func:`run_study`), for :func:`write_report`.

    Parameters
    ----------
    name : str
        File stem of the study script (its folder in the report).
    title : str
        First line of the script's docstring without its final period (the stem if there is no
        docstring).
    description : str
        The rest of the docstring (paragraphs separated by blank lines), or "".
    items : list of tuple
        :attr:`Study.items`: the figures, tables and text the study produced before it ended.
    seconds : float
        Wall-clock time of the run [s].
    error : str, optional
        The traceback if the study raised, else None.
    """

    name: str
    title: str
    description: str
    items: list
    seconds: float
    error: str | None = None


def discover_studies(folder: str | Path | None = None) -> list[Path]:
    """The study scripts ``studies/*.py`` (sorted), from ``folder`` or the project's ``studies/``.

    Parameters
    ----------
    folder : str or os.PathLike, optional
        Where the scripts are. Default: ``studies/`` beside the package (a checkout), else in the
        current directory, else the installed package data.

    Returns
    -------
    list of pathlib.Path
        The ``*.py`` files of ``folder`` whose names do not start with an underscore, sorted.
    """
    if folder is None:
        folder = find_studies_folder()
    return sorted(p for p in Path(folder).glob("*.py") if not p.name.startswith("_"))


def find_studies_folder() -> Path:
    """``studies/`` beside the package (checkout) or in the current directory."""
    here = Path(__file__).resolve().parent.parent
    for cand in (here / "studies", Path.cwd() / "studies", here / "vehdyn" / "studies"):
        if cand.is_dir():
            return cand
    from vehdyn.params import data_path

    return data_path("studies")


def _load_module(path: Path):
    spec = importlib.util.spec_from_file_location(f"vehdyn_study_{path.stem}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def run_study(path: str | Path, out_dir: str | Path, quick: bool = False) -> StudyOutcome:
    """Run one study script into ``out_dir/NAME``; errors are caught and reported in the outcome.

    The study's ``simulate`` calls compile before they run (background builds off, as with
    ``VEHDYN_BACKGROUND_COMPILE=0``): its numbers do not depend on how far a build has come.

    Parameters
    ----------
    path : str or os.PathLike
        The study script (it must define ``run(study)``).
    out_dir : str or os.PathLike
        Report folder; the study writes into ``out_dir/NAME`` (created).
    quick : bool
        Small grids (:attr:`Study.quick`); default False.

    Returns
    -------
    StudyOutcome
        Title and description from the script's docstring, what the study produced, its run time
        [s], and the traceback if loading or running the script raised an ``Exception`` (the
        exception is not propagated; ``KeyboardInterrupt`` and ``SystemExit`` are).
    """
    import os

    from vehdyn.simulation import compiled as compiled_backend

    previous = os.environ.get(compiled_backend.BACKGROUND_ENV)
    os.environ[compiled_backend.BACKGROUND_ENV] = "0"
    try:
        return _run_study(path, out_dir, quick)
    finally:
        if previous is None:
            os.environ.pop(compiled_backend.BACKGROUND_ENV, None)
        else:
            os.environ[compiled_backend.BACKGROUND_ENV] = previous


def _run_study(path, out_dir, quick):
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


_TITLE = "<title>vehdyn report</title>"


def write_report(outcomes: list[StudyOutcome], out_dir: str | Path, *, quick: bool) -> Path:
    """Write ``out_dir/index.html`` from study outcomes (atomically: the old page or the new, whole).

    This writes the page only; :func:`build_report` runs studies and publishes a whole report folder.

    Parameters
    ----------
    outcomes : list of StudyOutcome
        The studies, in the order of the page: a table of contents (with each study's run time or
        "failed"), then per study its description, figures (``NAME/FILE.png``, relative to
        ``out_dir``), tables, text and any traceback.
    out_dir : str or os.PathLike
        Folder of the page; it must exist (the figures are expected in its subfolders).
    quick : bool
        Say on the page that the studies ran in quick mode (keyword only).

    Returns
    -------
    pathlib.Path
        ``out_dir / "index.html"``.
    """
    import vehdyn

    out_dir = Path(out_dir)
    parts = [f"<!doctype html><html><head><meta charset='utf-8'>{_TITLE}"
             f"<meta name='generator' content='vehdyn {vehdyn.__version__}'>"
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
    return atomic_write_text(out_dir / "index.html", "\n".join(parts) + "\n")


#: the shipped studies that take longest, longest first (as measured in ``vehdyn report`` from a fresh
#: numba cache on 2 processes, much of it compiling; the others take a few seconds each); a scheduling hint only
LONGEST_STUDIES = ("fidelity_ladder", "minimum_time_lane_change", "full_vehicle", "monte_carlo", "tire_fitting",
                   "integrator_work_precision", "abs_braking", "rigid_body_tumbling", "active_suspension",
                   "ride_comfort", "on_center", "esc_sine_with_dwell", "off_road", "articulated_vehicles")


def longest_first(paths) -> list:
    """``paths`` in the order to start them on several processes: the studies of :data:`LONGEST_STUDIES`
    first, in its order, then the others in their given order (a long study started last would
    keep one process busy after the others have finished).

    Parameters
    ----------
    paths : sequence of path-like
        Study scripts.

    Returns
    -------
    list
        The same paths, reordered.
    """
    rank = {name: i for i, name in enumerate(LONGEST_STUDIES)}
    order = sorted(range(len(paths)), key=lambda i: (rank.get(Path(paths[i]).stem, len(rank)), i))
    return [paths[i] for i in order]


#: shipped models (:func:`vehdyn.cli.shipped_runs`) whose compiled code (numba's cache key as in that run)
#: several shipped studies run, and those studies; a scheduling hint only (see :func:`shared_code`)
SHARED_CODE = {"single_track": ("fidelity_ladder", "minimum_time_lane_change", "abs_braking", "esc_sine_with_dwell",
                                "crosswind", "sine_with_dwell"),
               "full_vehicle": ("fidelity_ladder", "minimum_time_lane_change", "full_vehicle")}


def shared_code(paths) -> list[str]:
    """The models of :data:`SHARED_CODE` that the studies ``paths`` run compiled.

    With several processes, :func:`build_report` builds their compiled code first, one model per
    process, before the studies start: a study needing code that another process is compiling
    waits for it (numba's cache and the build lock of :mod:`vehdyn.simulation`), and its process
    would sit idle meanwhile (measured in a report from an empty cache: ``minimum_time_lane_change``
    waited 42 s for the single track and the full vehicle that ``fidelity_ladder`` compiled one after
    the other).

    Parameters
    ----------
    paths : sequence of path-like
        Study scripts.

    Returns
    -------
    list of str
        Model names of :func:`vehdyn.cli.shipped_runs`, in the order of :data:`SHARED_CODE`.
    """
    stems = {Path(path).stem for path in paths}
    return [model for model, studies in SHARED_CODE.items() if stems.intersection(studies)]


def _prebuild(build, model: str) -> None:
    """``build([model])`` in a worker. An exception is dropped: the studies that need the code then
    compile it for themselves, and one that cannot reports the error in its own section."""
    try:
        build([model])
    except Exception:  # noqa: BLE001
        pass


#: the environment variables that size the thread pools of the linear-algebra libraries numpy and scipy may
#: be built on (OpenBLAS, MKL, BLIS, Apple Accelerate) and of OpenMP; read once, when the library loads
LIBRARY_THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "BLIS_NUM_THREADS", "VECLIB_MAXIMUM_THREADS",
                            "OMP_NUM_THREADS")


@contextlib.contextmanager
def _one_library_thread_per_process():
    """Set each of :data:`LIBRARY_THREAD_VARIABLES` that is not set to 1 while the block runs (the
    report's worker processes start inside it and inherit them); a variable the user has set is kept.

    Why: BLAS sizes its thread pool to the machine's cores. With one study per core, every BLAS call
    of a study then waits for threads that the other processes' studies hold; the studies that spend
    their time in LAPACK slow down twofold and more (a report from a warm cache on 2 cores:
    ``tire_fitting`` 31.9 -> 12.8 s wall, ``monte_carlo`` 30.3 -> 13.3 s, the report 2:07 -> 1:34).
    The studies' matrices are small: one thread is not slower even with the machine to itself
    (``tire_fitting`` alone: 14.7 s on two threads, 13.3 s on one). And a study's numbers then no
    longer depend on how many cores the machine has, which decides how BLAS splits its sums.

    Yields
    ------
    None
    """
    added = [name for name in LIBRARY_THREAD_VARIABLES if name not in os.environ]
    for name in added:
        os.environ[name] = "1"
    try:
        yield
    finally:
        for name in added:
            os.environ.pop(name, None)


def _run_studies(paths, stage: Path, quick: bool, progress, jobs: int, prebuild=None) -> list[StudyOutcome]:
    """The outcomes of ``paths`` in their order: one after another, or on ``jobs`` processes (the
    shared code built first where ``prebuild`` is given, see :func:`shared_code`)."""
    if jobs <= 1 or len(paths) <= 1:
        outcomes = []
        for i, path in enumerate(paths):
            if progress is not None:
                progress(i, len(paths), Path(path).stem)
            outcomes.append(run_study(path, stage, quick=quick))
        return outcomes
    # spawned workers (no forked copies of the parent's state), one BLAS thread each; each imports vehdyn
    # once and runs whole studies, the longest first (the processes end together); the page keeps the
    # studies' order
    with _one_library_thread_per_process():
        return _run_on_processes(paths, stage, quick, progress, jobs, prebuild)


def _run_on_processes(paths, stage: Path, quick: bool, progress, jobs: int, prebuild) -> list[StudyOutcome]:
    import concurrent.futures
    import multiprocessing

    pool = concurrent.futures.ProcessPoolExecutor(max_workers=min(jobs, len(paths)),
                                                  mp_context=multiprocessing.get_context("spawn"))
    try:
        # submitted first, so taken first: one model per process while the others start on the next
        for model in shared_code(paths) if prebuild is not None else ():
            pool.submit(_prebuild, prebuild, model)
        futures = {path: pool.submit(run_study, path, stage, quick) for path in longest_first(paths)}
        names = {future: Path(path).stem for path, future in futures.items()}
        for done, future in enumerate(concurrent.futures.as_completed(names)):
            if progress is not None:
                progress(done + 1, len(paths), names[future])
        outcomes = [futures[path].result() for path in paths]
    except BaseException:
        pool.shutdown(wait=False, cancel_futures=True)
        raise
    pool.shutdown()
    return outcomes


def build_report(paths, out_dir: str | Path, *, quick: bool = False,
                 progress: Callable[[int, int, str], None] | None = None,
                 jobs: int = 1, prebuild: Callable[[list], object] | None = None) -> tuple[Path, list[StudyOutcome]]:
    """Run studies and publish their report as the folder ``out_dir``, all or nothing.

    The studies run into a hidden sibling folder ``.NAME.partial-*`` (same file system); when every
    study has finished and ``index.html`` is written there, that folder replaces ``out_dir`` by
    renames. Until then ``out_dir`` keeps the previous complete report, readable while the run goes
    on; an interrupted run (an exception, Ctrl-C, a full disk) removes its partial folder and leaves
    the previous report untouched. A study that raises an ordinary exception does not interrupt
    the run: its section shows the traceback (as :func:`run_study` records it). Concurrent runs
    into one folder each publish a complete report; the last to finish wins. Files from an earlier
    run that this run does not produce (a removed figure, a study not selected) do not survive.

    Parameters
    ----------
    paths : sequence of path-like
        Study scripts (see :func:`discover_studies`).
    out_dir : str or os.PathLike
        Report folder. It may be missing, empty, or an earlier vehdyn report; a folder holding
        anything else is refused, because the run replaces the folder as a whole.
    quick : bool
        Small grids.
    progress : callable, optional
        ``progress(i, n, name)`` before study ``i`` of ``n`` starts (with ``jobs`` > 1: after the
        ``i``-th study to finish, ``name``).
    jobs : int
        Processes that run studies at the same time (default 1: one after another in this
        process). Each study runs whole in one process; the page lists them in the given order.
        With ``jobs`` > 1 each process starts with one BLAS/OpenMP thread (the variables of
        :data:`LIBRARY_THREAD_VARIABLES` that the environment does not set are 1 there).
    prebuild : callable, optional
        ``prebuild([model])`` builds a shipped model's compiled code into numba's cache
        (:func:`vehdyn.cli.warm_up`; a module-level function, so that it pickles). With ``jobs`` > 1
        the models the studies share (:func:`shared_code`) are built first, one per process, so
        that no process waits idle for another's compile of the same code. A build that raises is
        left to the studies (each compiles what it needs). Default: none.

    Returns
    -------
    index : pathlib.Path
        ``out_dir/index.html`` (``out_dir`` resolved to an absolute path, symbolic links followed).
    outcomes : list of StudyOutcome

    Raises
    ------
    ParameterError
        If ``out_dir`` is a file, cannot be created, or is a folder that is not a vehdyn report.
    VehdynError
        If the finished report cannot replace ``out_dir`` (the message says where it was kept).
    """
    if isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1:
        raise ParameterError(f"jobs must be a whole number >= 1, got {jobs!r}", key="jobs", value=jobs)
    out = _report_folder(out_dir)
    _remove_abandoned(out)
    try:
        stage = Path(tempfile.mkdtemp(prefix=f".{out.name}.partial-{_run_tag()}-", dir=out.parent))
    except OSError as exc:
        raise ParameterError(f"out_dir {str(out_dir)!r}: cannot create the folder that builds the new report "
                             f"beside it in {str(out.parent)!r} ({exc.strerror or exc})", key="out_dir",
                             value=str(out_dir)) from None
    try:
        keep_permissions(out, stage, default=0o777)  # mkdtemp makes 0700
        outcomes = _run_studies(list(paths), stage, quick, progress, jobs, prebuild)
        write_report(outcomes, stage, quick=quick)
    except BaseException:
        shutil.rmtree(stage, ignore_errors=True)
        raise
    try:
        with _interrupt_deferred():
            _publish(stage, out)
    except OSError as exc:
        raise VehdynError(f"the new report is complete in {stage} but could not replace {out}: "
                          f"{exc.strerror or exc}") from exc
    return out / "index.html", outcomes


def _folder_kind(folder: Path) -> str:
    """What ``folder`` is: ``"missing"``, ``"file"``, ``"empty"``, ``"report"`` (a vehdyn report) or ``"foreign"``.

    Where the system allows, the folder is opened once and looked at through that handle, so that
    a concurrent run swapping another report in cannot mix two folders into one answer.
    """
    if os.open in os.supports_dir_fd and os.listdir in os.supports_fd and hasattr(os, "O_DIRECTORY"):
        for _ in range(100):
            try:
                fd = os.open(folder, os.O_RDONLY | os.O_DIRECTORY)
            except FileNotFoundError:
                return "missing"
            except NotADirectoryError:
                return "file"
            try:
                kind = _open_folder_kind(fd)
                # a folder retired (and being deleted) since it was opened says nothing about ``folder``
                here, there = os.fstat(fd), os.stat(folder)
                if (here.st_dev, here.st_ino) == (there.st_dev, there.st_ino):
                    return kind
            except FileNotFoundError:
                continue
            finally:
                os.close(fd)
    folder = Path(folder)  # Windows: by path
    if not folder.exists():
        return "missing"
    if not folder.is_dir():
        return "file"
    try:
        if not any(folder.iterdir()):
            return "empty"
        with open(folder / "index.html", "rb") as fh:
            return "report" if _TITLE.encode() in fh.read(4096) else "foreign"
    except FileNotFoundError:
        return "missing" if not folder.exists() else "foreign"


def _open_folder_kind(fd: int) -> str:
    if not os.listdir(fd):
        return "empty"
    try:
        page = os.open("index.html", os.O_RDONLY, dir_fd=fd)
    except OSError:
        return "foreign"
    with os.fdopen(page, "rb") as fh:
        return "report" if _TITLE.encode() in fh.read(4096) else "foreign"


def _report_folder(out_dir) -> Path:
    """The absolute report folder, checked: missing, empty or a report; its parent created."""
    out = Path(out_dir).resolve()
    if out.parent == out:
        raise ParameterError(f"out_dir {str(out_dir)!r} is a file-system root", key="out_dir", value=str(out_dir))
    make_folder(out_dir, create=False)
    if _folder_kind(out) == "foreign":
        raise ParameterError(f"out_dir {str(out_dir)!r} holds files that are not a vehdyn report; a report run "
                             "replaces its folder as a whole, so give a new or empty folder or an earlier "
                             "report's folder", key="out_dir", value=str(out_dir))
    make_folder(out.parent, shown=out_dir)
    return out


def make_folder(folder, *, create: bool = True, shown=None) -> Path:
    """Create an output folder and its parents, or say in one line why it cannot be.

    Parameters
    ----------
    folder : str or os.PathLike
    create : bool
        False: only check that neither ``folder`` nor a parent is a file.
    shown : str or os.PathLike, optional
        The path the user gave, for messages (default ``folder``).

    Raises
    ------
    ParameterError
        ``key="out_dir"``: ``folder`` or one of its parents is a file, or the system refuses
        (permissions, a read-only file system); the message names the path and the reason.
    """
    path = Path(folder)
    shown = str(folder if shown is None else shown)
    for part in (path, *path.parents):
        if part.exists() and not part.is_dir():
            which = "" if part == path else f" (its parent {str(part)!r} is a file)"
            raise ParameterError(f"out_dir {shown!r} is not a folder{which or ' but a file'}",
                                 key="out_dir", value=shown)
    if create:
        try:
            path.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            reason = exc.strerror or str(exc)
            raise ParameterError(f"out_dir {shown!r} cannot be created: {reason}"
                                 f"{f' ({exc.filename})' if exc.filename else ''}", key="out_dir",
                                 value=shown) from None
    return path


def _publish(stage: Path, out: Path) -> None:
    """Move the complete folder ``stage`` to ``out``, retiring whatever ``out`` holds.

    Two renames; a concurrent publisher may slip in between, so retire and retry until ``stage``
    lands. Should the move fail, the retired folder goes back if ``out`` is still free.
    """
    retired: list[Path] = []
    try:
        for _ in range(1000):
            try:
                os.rename(stage, out)
                return
            except OSError as exc:
                if not (isinstance(exc, FileExistsError) or exc.errno in (errno.EEXIST, errno.ENOTEMPTY)):
                    raise
            kind = _folder_kind(out)
            if kind == "missing":  # another publisher retired it meanwhile
                continue
            if kind in ("file", "foreign"):  # something else moved in since the run began
                raise OSError(errno.EEXIST, "it now holds files that are not a vehdyn report", str(out))
            aside = out.with_name(f".{out.name}.old-{_run_tag()}-{uuid.uuid4().hex[:12]}")
            try:
                os.rename(out, aside)
            except FileNotFoundError:  # another publisher retired it first
                continue
            retired.append(aside)
        raise OSError(errno.EBUSY, "the folder kept being replaced by other report runs", str(out))
    except BaseException:
        if retired and not out.exists():
            with contextlib.suppress(OSError):
                os.rename(retired.pop(), out)
        raise
    finally:
        for folder in retired:
            shutil.rmtree(folder, ignore_errors=True)


def _run_tag() -> str:
    """``HOST-PID`` of this run, in the names of its temporary folders."""
    host = re.sub(r"[^A-Za-z0-9_]", "_", socket.gethostname())[:40] or "host"
    return f"{host}-{os.getpid()}"


_ABANDONED_AFTER = 3600.0  # [s] without a file written


def _remove_abandoned(out: Path) -> None:
    """Remove temporary folders beside ``out`` left by killed runs (POSIX; this host; idle an hour).

    A run that ends by an exception or Ctrl-C removes its own; one killed outright cannot. A folder
    is abandoned when the process named in it no longer exists on this host and nothing in it has
    been written for :data:`_ABANDONED_AFTER` seconds (the second test guards against a process of
    the same host name in another PID namespace).
    """
    if os.name != "posix":  # os.kill(pid, 0) is not a probe on Windows
        return
    host, _, _ = _run_tag().rpartition("-")
    pattern = re.compile(rf"\.{re.escape(out.name)}\.(?:partial|old)-{re.escape(host)}-(\d+)-")
    now = time.time()
    try:
        entries = list(out.parent.iterdir())
    except OSError:
        return
    for entry in entries:
        match = pattern.match(entry.name)
        if not match or _process_exists(int(match.group(1))):
            continue
        try:
            newest = max([entry.stat().st_mtime, *(p.stat().st_mtime for p in entry.rglob("*"))])
        except OSError:
            continue
        if now - newest > _ABANDONED_AFTER:
            shutil.rmtree(entry, ignore_errors=True)


def _process_exists(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:  # PermissionError: it exists, owned by someone else
        return True
    return True


@contextlib.contextmanager
def _interrupt_deferred():
    """Hold Ctrl-C (SIGINT) back until the block ends, in the main thread; elsewhere do nothing."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    received = []
    try:
        previous = signal.signal(signal.SIGINT, lambda signum, frame: received.append(frame))
    except ValueError:  # not the main interpreter
        yield
        return
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
        if received and callable(previous):
            previous(signal.SIGINT, received[0])
