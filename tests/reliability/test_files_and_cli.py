"""Files are written whole or not at all, reports are published whole, CLI user errors are one line.

The studies here are tiny fake scripts written into ``tmp_path`` (a table and a paragraph, some a
figure), so that the report machinery is tested in milliseconds; ``tests/core/test_package.py``
runs one real study through ``vehdyn report``. Independent references: the bytes of the previous
file or report (what an interrupted write must leave), the writer's own marker (which run a
published report came from).
"""

import errno
import os
import threading
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import vehdyn
from vehdyn import ParameterError
from vehdyn._atomic import atomic_write
from vehdyn.cli import main
from vehdyn.errors import VehdynError
from vehdyn.plotting import save_figure
from vehdyn.report import Study, StudyOutcome, build_report, discover_studies, write_report

STUDY = '''"""Fake study {tag}.

Writes a table, a paragraph{figure_note}.
"""
import pandas as pd


def run(study):
{body}    study.table(pd.DataFrame({{"writer": ["{tag}"]}}), "who", caption="who wrote this")
    study.text("written by {tag}")
'''

FIGURE = '''    from matplotlib.figure import Figure

    fig = Figure(figsize=(2, 1.5))
    fig.add_subplot().plot([0, 1], [0, 1])
    study.figure(fig, "line", caption="a line")
'''


def _studies(folder: Path, tag: str, *, figure=False, extra: dict | None = None) -> Path:
    """A studies folder with ``alpha`` and ``beta`` (and ``extra``: name -> run body) for ``tag``."""
    folder.mkdir(parents=True, exist_ok=True)
    for name in ("alpha", "beta"):
        (folder / f"{name}.py").write_text(STUDY.format(
            tag=tag, figure_note=" and a figure" if figure else "", body=FIGURE if figure else ""))
    for name, body in (extra or {}).items():
        (folder / f"{name}.py").write_text(f'"""Fake study {name}."""\n\n\ndef run(study):\n    {body}\n')
    return folder


def _tree(folder: Path) -> dict[str, bytes]:
    """Every file under ``folder`` by relative path, with its bytes."""
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def _leftovers(folder: Path) -> list[str]:
    """Hidden temporary files or folders a run left beside or inside ``folder``."""
    beside = [p.name for p in folder.parent.iterdir() if p.name.startswith(f".{folder.name}.")]
    inside = [p.name for p in folder.rglob(".*")] if folder.is_dir() else []
    return beside + inside


def _one_line_error(capsys) -> str:
    err = capsys.readouterr().err
    lines = [line for line in err.replace("\r", "\n").splitlines() if line.strip() and not line.startswith("[")]
    assert len(lines) == 1 and "Traceback" not in err, err
    return lines[0]


# ---------------------------------------------------------------------------- atomic single files


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(old=st.one_of(st.none(), st.binary(max_size=3000)), new=st.binary(min_size=1, max_size=3000),
       chunk=st.integers(1, 700), cut=st.floats(0, 1), failure=st.sampled_from(["exception", "disk full"]))
def test_interrupted_write_leaves_old_file(tmp_path_factory, old, new, chunk, cut, failure):
    """Property: a writer raising at any point leaves the old file byte for byte (or no file)."""
    folder = tmp_path_factory.mktemp("atomic")
    path = folder / "table.csv"
    if old is not None:
        path.write_bytes(old)
    stop = int(cut * len(new))
    with pytest.raises((RuntimeError, OSError)):
        with atomic_write(path, "wb") as handle:
            for start in range(0, len(new), chunk):
                if start >= stop:
                    if failure == "disk full":
                        raise OSError(errno.ENOSPC, "No space left on device")
                    raise RuntimeError("writer interrupted")
                handle.write(new[start:start + chunk])
            raise RuntimeError("interrupted after the last byte, before the move")
    assert (path.read_bytes() if path.exists() else None) == old
    assert [p.name for p in folder.iterdir()] == ([] if old is None else ["table.csv"])


def test_study_figure_failure_keeps_old_png(tmp_path, monkeypatch):
    from matplotlib.figure import Figure

    study = Study("s", tmp_path)
    fig = Figure(figsize=(2, 1.5))
    fig.add_subplot().plot([0, 1], [1, 0])
    path = study.figure(fig, "line")
    old = path.read_bytes()
    assert old.startswith(b"\x89PNG\r\n\x1a\n")

    def half_then_full_disk(self, fname, **kwargs):
        fname.write(old[: len(old) // 2])
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(Figure, "savefig", half_then_full_disk)
    with pytest.raises(OSError, match="No space left"):
        study.figure(Figure(), "line")
    assert path.read_bytes() == old and _leftovers(tmp_path) == []


def test_study_table_failure_keeps_old_csv(tmp_path, monkeypatch):
    study = Study("s", tmp_path)
    frame = pd.DataFrame({"speed": [10.0, 20.0]})
    path = study.table(frame, "metrics")
    old = path.read_bytes()
    assert pd.read_csv(path, index_col=0).equals(frame)

    def partial(self, handle, *args, **kwargs):
        handle.write("speed\n0,1")
        raise KeyboardInterrupt

    monkeypatch.setattr(pd.DataFrame, "to_csv", partial)
    with pytest.raises(KeyboardInterrupt):
        study.table(frame * 2, "metrics")
    assert path.read_bytes() == old and _leftovers(tmp_path) == []


def test_index_disk_full_keeps_old_index(tmp_path, monkeypatch):
    outcome = StudyOutcome("s", "A study", "", [("text", "first", "")], 0.1)
    index = write_report([outcome], tmp_path, quick=True)
    old = index.read_bytes()
    assert old.rstrip().endswith(b"</html>") and b"first" in old

    def full(fd):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(os, "fsync", full)
    second = StudyOutcome("s", "A study", "", [("text", "second", "")], 0.1)
    with pytest.raises(OSError, match="No space left"):
        write_report([second], tmp_path, quick=True)
    assert index.read_bytes() == old and _leftovers(tmp_path) == []


def test_save_figure_permissions_and_format(tmp_path):
    from matplotlib.figure import Figure

    fig = Figure(figsize=(2, 1.5))
    png = save_figure(fig, tmp_path / "f.png", close=False)
    svg = save_figure(fig, tmp_path / "f.svg")
    assert png.read_bytes().startswith(b"\x89PNG") and b"<svg" in svg.read_bytes()[:500]
    umask = os.umask(0)
    os.umask(umask)
    assert png.stat().st_mode & 0o777 == 0o666 & ~umask  # not mkstemp's 0600


# ---------------------------------------------------------------------------- report runs


def test_report_replaces_folder_whole(tmp_path):
    out = tmp_path / "report"
    first, outcomes = build_report(discover_studies(_studies(tmp_path / "v1", "one", figure=True)), out)
    assert first == out.resolve() / "index.html" and all(o.error is None for o in outcomes)
    tree = _tree(out)
    assert set(tree) == {"index.html", "alpha/who.csv", "alpha/line.png", "beta/who.csv", "beta/line.png"}
    # a second run without figures: the stale figures of the first run do not survive
    build_report(discover_studies(_studies(tmp_path / "v2", "two")), out)
    assert set(_tree(out)) == {"index.html", "alpha/who.csv", "beta/who.csv"}
    assert b"written by two" in (out / "index.html").read_bytes() and _leftovers(out) == []
    umask = os.umask(0)
    os.umask(umask)
    assert out.stat().st_mode & 0o777 == 0o777 & ~umask  # a normal folder, not mkdtemp's 0700


@pytest.mark.parametrize("interrupt", ["KeyboardInterrupt", "SystemExit", "index"])
def test_interrupted_report_keeps_previous_report(tmp_path, monkeypatch, interrupt):
    out = tmp_path / "report"
    build_report(discover_studies(_studies(tmp_path / "v1", "one", figure=True)), out)
    before = _tree(out)
    if interrupt == "index":  # the page cannot be written: disk full after every study finished
        def full(*args, **kwargs):
            raise OSError(errno.ENOSPC, "No space left on device")
        monkeypatch.setattr("vehdyn.report.write_report", full)
        studies = _studies(tmp_path / "v2", "two")
        with pytest.raises(OSError):
            build_report(discover_studies(studies), out)
    else:  # the second study of three is interrupted after the first has written its files
        studies = _studies(tmp_path / "v2", "two", extra={"gamma": f"raise {interrupt}(1)"})
        with pytest.raises((KeyboardInterrupt, SystemExit)):
            build_report(discover_studies(studies), out)
    assert _tree(out) == before and _leftovers(out) == []


def test_failing_study_is_reported_not_an_interruption(tmp_path, capsys):
    out = tmp_path / "report"
    studies = _studies(tmp_path / "v1", "one", extra={"gamma": "raise ValueError('bad grid')"})
    assert main(["report", "--studies", str(studies), "--out", str(out)]) == 1
    page = (out / "index.html").read_text()
    assert "ValueError: bad grid" in page and page.count("written by one") == 2
    assert "gamma failed" in capsys.readouterr().err


def test_cli_interrupt_exit_130_previous_report_intact(tmp_path, capsys):
    out = tmp_path / "report"
    assert main(["report", "--studies", str(_studies(tmp_path / "v1", "one")), "--out", str(out)]) == 0
    before = _tree(out)
    capsys.readouterr()
    studies = _studies(tmp_path / "v2", "two", extra={"gamma": "raise KeyboardInterrupt"})
    assert main(["report", "--studies", str(studies), "--out", str(out)]) == 130
    assert "previous complete report" in _one_line_error(capsys)
    assert _tree(out) == before and _leftovers(out) == []


def test_publish_failure_restores_old_and_keeps_new(tmp_path, monkeypatch):
    out = tmp_path / "report"
    build_report(discover_studies(_studies(tmp_path / "v1", "one")), out)
    before = _tree(out)
    real_rename = os.rename
    calls = []

    def rename(src, dst):  # the old report moves aside, then the new one cannot move in
        calls.append((Path(src).name, Path(dst).name))
        if len(calls) == 3:
            raise OSError(errno.EIO, "Input/output error", str(dst))
        return real_rename(src, dst)

    monkeypatch.setattr(os, "rename", rename)
    with pytest.raises(VehdynError, match="the new report is complete in .*partial-.* but could not replace") as info:
        build_report(discover_studies(_studies(tmp_path / "v2", "two")), out)
    monkeypatch.undo()
    # tried (the folder exists), moved the old one aside, failed to move in, moved the old one back
    assert [c[1] for c in calls] == ["report", calls[1][1], "report", "report"] and calls[3][0] == calls[1][1]
    assert _tree(out) == before
    kept = Path(str(info.value).split("complete in ")[1].split(" but")[0])
    assert b"written by two" in (kept / "index.html").read_bytes()


@pytest.mark.skipif(os.name != "posix", reason="abandoned folders are found by PID on POSIX only")
def test_folders_of_killed_runs_are_removed_later(tmp_path):
    import subprocess
    import sys

    from vehdyn.report import _run_tag

    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True,
                          text=True, check=True).stdout.strip()
    host = _run_tag().rpartition("-")[0]
    old = os.path.getmtime(tmp_path) - 2 * 3600
    folders = {"dead_idle": (f".report.partial-{host}-{dead}-abc", old),
               "dead_old_swap": (f".report.old-{host}-{dead}-def", old),
               "dead_recent": (f".report.partial-{host}-{dead}-ghi", None),
               "alive_idle": (f".report.partial-{host}-{os.getpid()}-jkl", old),
               "other_host": (f".report.partial-{host}x-{dead}-mno", old),
               "other_report": (f".notes.partial-{host}-{dead}-pqr", old)}
    for name, mtime in folders.values():
        (tmp_path / name / "alpha").mkdir(parents=True)
        (tmp_path / name / "alpha" / "line.png").write_bytes(b"png")
        if mtime is not None:
            for p in (tmp_path / name / "alpha" / "line.png", tmp_path / name / "alpha", tmp_path / name):
                os.utime(p, (mtime, mtime))
    build_report(discover_studies(_studies(tmp_path / "v1", "one")), tmp_path / "report")
    kept = {key for key, (name, _) in folders.items() if (tmp_path / name).exists()}
    assert kept == {"dead_recent", "alive_idle", "other_host", "other_report"}


def test_concurrent_reports_last_writer_wins_no_torn_page(tmp_path):
    """Writers publish into one folder while a reader reads; every read is one writer's whole page."""
    import matplotlib

    matplotlib.use("Agg")  # run_study calls it; do it before the threads start
    out = tmp_path / "report"
    tags = [f"writer{k}" for k in range(4)]
    studies = {t: discover_studies(_studies(tmp_path / t, t)) for t in tags}
    build_report(studies[tags[0]], out)
    barrier = threading.Barrier(len(tags) + 1)
    done = threading.Event()
    errors, reads = [], []

    def writer(tag):
        try:
            barrier.wait()
            for _ in range(3):
                build_report(studies[tag], out)
        except BaseException as exc:  # reported below
            errors.append(exc)

    def reader():
        barrier.wait()
        while not done.is_set():
            try:
                page = (out / "index.html").read_bytes()
            except FileNotFoundError:  # between the two renames of a publish
                continue
            reads.append(page)

    threads = [threading.Thread(target=writer, args=(t,)) for t in tags]
    watcher = threading.Thread(target=reader)
    for t in (*threads, watcher):
        t.start()
    for t in threads:
        t.join()
    done.set()
    watcher.join()
    assert not errors, errors
    assert reads
    for page in reads:
        assert page.rstrip().endswith(b"</html>")
        assert sum(f"written by {t}".encode() in page for t in tags) == 1
    final = _tree(out)
    owners = {t for t in tags if f"written by {t}".encode() in final["index.html"]}
    assert len(owners) == 1
    (owner,) = owners
    assert all(owner.encode() in final[f"{s}/who.csv"] for s in ("alpha", "beta"))
    assert _leftovers(out) == []


# ---------------------------------------------------------------------------- CLI user errors


def _tir():
    return str(vehdyn.data_path("tires", "MagicFormula61_Parameters.tir"))


@pytest.mark.parametrize("command", ["report", "study", "tire"])
@pytest.mark.parametrize("where, expected", [("file", "is not a folder but a file"),
                                             ("under_file", "is not a folder (its parent"),
                                             ("proc", "cannot be created")])
def test_cli_bad_out_is_one_line_exit_2(tmp_path, capsys, command, where, expected):
    if where == "proc" and not Path("/proc/self").is_dir():
        pytest.skip("needs Linux /proc (a folder where nothing can be created)")
    (tmp_path / "a_file").write_text("x")
    out = {"file": tmp_path / "a_file", "under_file": tmp_path / "a_file" / "report",
           "proc": Path("/proc/vehdyn_no/report")}[where]
    studies = str(_studies(tmp_path / "studies", "one"))
    argv = {"report": ["report", "--studies", studies], "study": ["study", "alpha", "--studies", studies],
            "tire": ["tire", _tir()]}[command] + ["--out", str(out)]
    capsys.readouterr()
    assert main(argv) == 2
    line = _one_line_error(capsys)
    assert line.startswith(f"vehdyn {command}: --out {str(out)!r}") and expected in line


@pytest.mark.parametrize("argv, expected", [
    (["report", "--only", "no_such_study"], "no study named ['no_such_study']; studies are"),
    (["study", "no_such_study"], "no study named 'no_such_study'; studies are"),
    (["report", "--studies", "{tmp}/missing"], "no studies found in"),
    (["report", "--out", "{tmp}/notes"], "holds files that are not a vehdyn report"),
    (["tire", "{tmp}/missing.tir"], "missing.tir"),
])
def test_cli_user_errors_are_one_line_exit_2(tmp_path, capsys, argv, expected):
    (tmp_path / "notes").mkdir()
    (tmp_path / "notes" / "thesis.tex").write_text("precious")
    argv = [a.format(tmp=tmp_path) for a in argv]
    if "--out" not in argv:
        argv += ["--out", str(tmp_path / "out")]
    assert main(argv) == 2
    line = _one_line_error(capsys)
    assert line.startswith(f"vehdyn {argv[0]}: ") and expected in line
    assert (tmp_path / "notes" / "thesis.tex").read_text() == "precious"


def test_report_folder_checks_in_the_library(tmp_path):
    (tmp_path / "notes").mkdir()
    (tmp_path / "notes" / "thesis.tex").write_text("precious")
    with pytest.raises(ParameterError, match="not a vehdyn report") as info:
        build_report([], tmp_path / "notes")
    assert info.value.key == "out_dir"
    # an empty folder and a symbolic link to a report are accepted; the link's target is replaced
    (tmp_path / "empty").mkdir()
    index, _ = build_report(discover_studies(_studies(tmp_path / "v1", "one")), tmp_path / "empty")
    assert index.is_file()
    link = tmp_path / "link"
    try:
        link.symlink_to(tmp_path / "empty", target_is_directory=True)
    except (OSError, NotImplementedError):
        pytest.skip("no symbolic links here")
    index, _ = build_report(discover_studies(_studies(tmp_path / "v2", "two")), link)
    assert link.is_symlink() and index == (tmp_path / "empty" / "index.html").resolve()
    assert b"written by two" in (link / "index.html").read_bytes()


def test_study_with_numbers_round_trips_through_report(tmp_path):
    """The CSV a study writes through the atomic path reads back to the same numbers."""
    study = Study("s", tmp_path)
    frame = pd.DataFrame({"speed": np.linspace(10, 40, 7), "gain": np.linspace(10, 40, 7) ** 0.5})
    path = study.table(frame, "gains")
    assert np.array_equal(pd.read_csv(path, index_col=0).to_numpy(), frame.to_numpy())  # shortest repr: exact
    assert b"\r\r\n" not in path.read_bytes()


def test_atomic_write_handle_name_is_the_temporary_path_a_path_writer_can_use(tmp_path):
    """Writers that want a path (savefig, to_parquet) get the temporary file by ``handle.name``."""
    from vehdyn._atomic import atomic_write

    target = tmp_path / "table.csv"
    with atomic_write(target, "w") as handle:
        assert isinstance(handle.name, str) and Path(handle.name).parent == tmp_path
        assert Path(handle.name).suffix == ".csv" and not target.exists()
        Path(handle.name).write_text("a,b\n1,2\n")  # a writer that opens the path itself
    assert target.read_text() == "a,b\n1,2\n" and sorted(p.name for p in tmp_path.iterdir()) == ["table.csv"]


def test_full_flag_reaches_studies_and_quick_wins(tmp_path, monkeypatch):
    """`vehdyn report --full` (or VEHDYN_FULL=1) turns on the heavy series; --quick always wins."""
    from vehdyn.report import Study

    monkeypatch.delenv("VEHDYN_FULL", raising=False)
    assert not Study("s", tmp_path / "a").full
    monkeypatch.setenv("VEHDYN_FULL", "1")
    assert Study("s", tmp_path / "b").full and not Study("s", tmp_path / "c", quick=True).full
    monkeypatch.setenv("VEHDYN_FULL", "0")
    assert not Study("s", tmp_path / "d").full
    monkeypatch.delenv("VEHDYN_FULL")
    from vehdyn.cli import build_parser

    assert build_parser().parse_args(["report", "--full"]).full


def test_report_on_two_processes_equals_the_sequential_report(tmp_path):
    studies = _studies(tmp_path / "v1", "one", figure=True, extra={"gamma": "raise ValueError('bad grid')"})
    paths = discover_studies(studies)
    _, sequential = build_report(paths, tmp_path / "a")
    seen = []
    _, parallel = build_report(paths, tmp_path / "b", jobs=2, progress=lambda i, n, name: seen.append((i, n, name)))
    assert [o.name for o in parallel] == [o.name for o in sequential] == [p.stem for p in paths]
    assert [o.items for o in parallel] == [o.items for o in sequential]
    assert [bool(o.error) for o in parallel] == [bool(o.error) for o in sequential] and "bad grid" in parallel[-1].error
    assert sorted(name for _, _, name in seen) == sorted(p.stem for p in paths) and seen[-1][0] == len(paths)
    assert sorted(f.name for f in (tmp_path / "b").rglob("*")) == sorted(f.name for f in (tmp_path / "a").rglob("*"))
    with pytest.raises(ParameterError, match="jobs"):
        build_report(paths, tmp_path / "c", jobs=0)
    with pytest.raises(SystemExit):
        main(["report", "--studies", str(studies), "--out", str(tmp_path / "d"), "--jobs", "0"])


def record_build(models):
    """A stand-in for vehdyn.cli.warm_up in the report's processes: writes (model, pid, start time) to
    $VEHDYN_TEST_BUILDS; raises for "full_vehicle" after writing (a build that fails)."""
    import os
    import time

    (model,) = models
    with open(os.environ["VEHDYN_TEST_BUILDS"], "a") as f:
        f.write(f"build {model} {os.getpid()} {time.time()!r}\n")
    if model == "full_vehicle":
        raise RuntimeError("no compiler today")


def test_report_builds_the_shared_code_first_and_survives_a_failed_build(tmp_path, monkeypatch):
    """SHARED_CODE: with several processes the models the selected studies share are built before the
    studies start (prebuild, one call per model); a build that raises leaves the studies to compile for
    themselves; one process, or no shared model, builds nothing."""
    from vehdyn.report import SHARED_CODE, shared_code

    log = tmp_path / "log.txt"
    monkeypatch.setenv("VEHDYN_TEST_BUILDS", str(log))
    studies = tmp_path / "studies"
    studies.mkdir()
    body = ('import os, time\n    open(os.environ["VEHDYN_TEST_BUILDS"], "a").write(f"study {study.name} '
            '{os.getpid()} {time.time()!r}\\n")\n    study.text("ran")')
    for name in ("fidelity_ladder", "full_vehicle", "alpha"):
        (studies / f"{name}.py").write_text(f'"""Fake study {name}."""\n\n\ndef run(study):\n    {body}\n')
    paths = discover_studies(studies)
    assert shared_code(paths) == ["single_track", "full_vehicle"] == list(SHARED_CODE)
    assert shared_code([studies / "full_vehicle.py"]) == ["full_vehicle"]
    assert shared_code([studies / "alpha.py"]) == []

    _, outcomes = build_report(paths, tmp_path / "a", jobs=2, prebuild=record_build)
    assert [o.error for o in outcomes] == [None, None, None]
    rows = [line.split() for line in log.read_text().splitlines()]
    builds = {row[1]: float(row[3]) for row in rows if row[0] == "build"}
    starts = [float(row[3]) for row in rows if row[0] == "study"]
    assert sorted(builds) == ["full_vehicle", "single_track"] and len(starts) == 3
    assert min(builds.values()) <= min(starts)  # taken off the queue before any study

    log.unlink()
    build_report([studies / "alpha.py", studies / "fidelity_ladder.py"], tmp_path / "b", jobs=1,
                 prebuild=record_build)
    build_report([studies / "alpha.py"] * 2, tmp_path / "c", jobs=2, prebuild=record_build)
    assert not any(line.startswith("build") for line in log.read_text().splitlines())


def test_report_processes_run_one_library_thread_each(tmp_path, monkeypatch):
    """With several processes every study process starts with one BLAS/OpenMP thread (each variable of
    LIBRARY_THREAD_VARIABLES is 1 there), except where the user set the variable (kept as set); the
    report's own process gets its environment back; one process (the studies run in this one) sets
    nothing."""
    from vehdyn.report import LIBRARY_THREAD_VARIABLES

    for name in LIBRARY_THREAD_VARIABLES:
        monkeypatch.delenv(name, raising=False)
    monkeypatch.setenv("MKL_NUM_THREADS", "3")
    studies = tmp_path / "studies"
    studies.mkdir()
    body = ('import os\n    names = {names!r}\n'
            '    study.text(" ".join(f"{{n}}={{os.environ.get(n, \'-\')}}" for n in names) + f" pid={{os.getpid()}}")')
    for name in ("alpha", "beta"):
        (studies / f"{name}.py").write_text(f'"""Fake study {name}."""\n\n\ndef run(study):\n    '
                                            f'{body.format(names=LIBRARY_THREAD_VARIABLES)}\n')
    paths = discover_studies(studies)
    expected = " ".join(f"{n}={3 if n == 'MKL_NUM_THREADS' else 1}" for n in LIBRARY_THREAD_VARIABLES)
    _, outcomes = build_report(paths, tmp_path / "a", jobs=2)
    texts = [o.items[0][1] for o in outcomes]
    assert [t.rsplit(" pid=", 1)[0] for t in texts] == [expected, expected]
    assert all(int(t.rsplit("pid=", 1)[1]) != os.getpid() for t in texts)
    assert [n for n in LIBRARY_THREAD_VARIABLES if n in os.environ] == ["MKL_NUM_THREADS"]
    assert os.environ["MKL_NUM_THREADS"] == "3"

    _, outcomes = build_report(paths, tmp_path / "b", jobs=1)
    unset = " ".join(f"{n}={3 if n == 'MKL_NUM_THREADS' else '-'}" for n in LIBRARY_THREAD_VARIABLES)
    assert [o.items[0][1] for o in outcomes] == [f"{unset} pid={os.getpid()}"] * 2


def test_report_processes_start_the_longest_studies_first(tmp_path):
    """With several processes the studies of LONGEST_STUDIES start first (in its order), the others
    in their given order; the page keeps the given order (test above)."""
    from vehdyn.report import LONGEST_STUDIES, longest_first

    paths = [tmp_path / f"{name}.py" for name in ("alpha", LONGEST_STUDIES[2], "beta", LONGEST_STUDIES[0], "gamma")]
    assert longest_first(paths) == [paths[3], paths[1], paths[0], paths[2], paths[4]]
    assert longest_first([]) == [] and longest_first(paths[::2]) == paths[::2]
