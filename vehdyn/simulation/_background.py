"""Background builds of compiled code for ``simulate(..., backend="auto")``: the answer soonest.

A model's compiled code (its rhs, outputs and the integrator loop bound to them, numba's on-disk
cache) takes 10-40 s to build the first time and milliseconds to load afterwards. On
``backend="auto"``, :func:`decide` runs a call compiled when that code is already built (in this
process, or in the cache: a *build record* says so); otherwise it starts one build of it in a
detached, niced background process (:func:`start_build`, one per code and build folder, under a
lock) and runs this call on numpy when numpy's estimated run time is below the build's estimated
remaining time, else waits for the build and runs compiled. Every later call, in this process or
another, runs compiled as soon as the build record exists.

The build folder (:func:`build_dir`) holds, per code key (:func:`code_key`):

* ``KEY.lock``: locked (``fcntl.flock``, exclusive) by the one process that builds the code, for
  as long as it builds; its text is ``pid start_time label``. The kernel releases the lock when the
  builder ends, however it ends (a killed build leaves no stale lock);
* ``KEY.done``: the build record (JSON: label, seconds, pid), written atomically (a temporary file
  renamed) after the build ran the code once; numba writes its own cache files the same way (a
  temporary file renamed), index first, and treats an index entry without its data file as a miss,
  so a killed build leaves no corrupt cache, no record, and is built again by the next call;
* ``KEY.payload``: what the builder runs (the caller's ``sys.path``, then the pickled model, two
  instants of the call's grid and inputs, the method), removed when the build ends; ``KEY.log``: the builder's messages.

``VEHDYN_BACKGROUND_COMPILE=0`` turns background builds off (then ``"auto"`` compiles in the
calling process before running, as ``"compiled"`` does); ``VEHDYN_BUILD_DIR`` moves the build
folder. Platforms without ``fcntl`` (Windows) compile in the calling process.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import sys
import time
from pathlib import Path

from vehdyn.simulation.compiled import BACKGROUND_ENV as ENV

DIR_ENV = "VEHDYN_BUILD_DIR"
#: expected duration [s] of a build of code never built before in the build folder (a cold
#: compile of a shipped model on a 2-core machine: 10-40 s)
DEFAULT_BUILD_SECONDS = 30.0
#: the niceness the builder adds to its own
NICENESS = 10
#: rhs calls per simulated second assumed for a model's first numpy run (then learnt per model class)
DEFAULT_CALLS_PER_SECOND = 400.0
#: solve_ivp's own cost per rhs call [s] besides the rhs
STEP_OVERHEAD = 1e-4

_ENTRY = "import sys; from vehdyn.simulation._background import build; sys.exit(build(sys.argv[1]))"
#: (tests) a path: the builder waits while that file exists, after compiling, before writing its record
_HOLD_ENV = "VEHDYN_BUILD_HOLD_WHILE"
_WRITE_RECORDS = True  # False in a builder, which writes its record when its whole build is done
_READY: set = set()
_DTYPES: dict = {}  # numpy dtype -> its description
_KEYS: dict = {}  # (id of a compiled model, method) -> (that compiled model, its code key): the latest 256  # code keys that ran compiled in this process
_CHILDREN: dict = {}  # code key -> Popen of the builds this process started
_CALLS_PER_SECOND: dict = {}  # model class name -> rhs calls per simulated second (learnt)
_HOLDING: set = set()  # code keys whose build lock this process holds


def enabled() -> bool:
    """Whether ``backend="auto"`` builds compiled code in the background (``VEHDYN_BACKGROUND_COMPILE``
    is not ``0``/``false``/``no``/``off``, and the platform has ``fcntl``)."""
    if os.environ.get(ENV, "1").strip().lower() in ("0", "false", "no", "off"):
        return False
    try:
        import fcntl  # noqa: F401
    except ImportError:  # pragma: no cover - Windows
        return False
    return True


def build_dir() -> Path:
    """The folder of the build locks and records: ``VEHDYN_BUILD_DIR``, else ``vehdyn_builds`` in
    numba's cache folder (``NUMBA_CACHE_DIR``), else in vehdyn's ``__pycache__`` where numba caches
    vehdyn's compiled code (or the user's cache folder where that is read-only)."""
    given = os.environ.get(DIR_ENV)
    if given:
        path = Path(given)
    elif os.environ.get("NUMBA_CACHE_DIR"):
        path = Path(os.environ["NUMBA_CACHE_DIR"]) / "vehdyn_builds"
    else:
        path = Path(__file__).resolve().parent.parent / "__pycache__" / "vehdyn_builds"
        if not os.access(path.parent.parent, os.W_OK):
            path = Path.home() / ".cache" / "vehdyn" / "builds"
    path.mkdir(parents=True, exist_ok=True)
    return path


def _signature(value) -> str:
    """What numba's typing of ``value`` depends on, cheaply (microseconds, where ``numba.typeof`` of a
    model's arguments takes milliseconds): tuples (their class and items), arrays (dtype, dimensions,
    layout, writability), and the type of anything else."""
    if isinstance(value, tuple):
        return f"{type(value).__name__}({','.join(_signature(v) for v in value)})"
    if hasattr(value, "dtype") and hasattr(value, "flags"):
        layout = "C" if value.flags.c_contiguous else "F" if value.flags.f_contiguous else "A"
        dtype = _DTYPES.get(value.dtype)
        if dtype is None:
            dtype = _DTYPES[value.dtype] = str(value.dtype.descr)  # slow for a Magic Formula record: once
        return f"a[{dtype},{value.ndim},{layout},{'w' if value.flags.writeable else 'r'}]"
    return type(value).__name__


def code_key(compiled, method: str) -> str:
    """A digest naming one piece of compiled code: the model's compiled key (its sources' stamps),
    the method's loop, the types of the model's arguments, numba's and Python's versions."""
    import numba

    known = _KEYS.get((id(compiled), method))
    if known is not None and known[0] is compiled:  # the model's cached compiled form: its key once
        return known[1]
    text = "|".join((compiled.key, method, _signature(compiled.args), numba.__version__, sys.version))
    key = hashlib.sha256(text.encode()).hexdigest()[:24]
    if len(_KEYS) >= 256:
        _KEYS.pop(next(iter(_KEYS)))
    _KEYS[(id(compiled), method)] = (compiled, key)
    return key


def _paths(key: str):
    folder = build_dir()
    return folder / f"{key}.lock", folder / f"{key}.done", folder / f"{key}.payload", folder / f"{key}.log"


def record(key: str) -> dict | None:
    """The build record of ``key`` (label, seconds, pid), or None when the code is not built."""
    try:
        return json.loads(_paths(key)[1].read_text())
    except (OSError, ValueError):
        return None


def builder(key: str) -> tuple[int, float] | None:
    """(pid, start time [s since the epoch]) of the process building ``key`` now, or None."""
    import fcntl

    lock = _paths(key)[0]
    child = _CHILDREN.get(key)
    try:
        with open(lock, "a+") as f:
            try:
                fcntl.flock(f, fcntl.LOCK_SH | fcntl.LOCK_NB)
            except OSError:  # held: a build runs
                f.seek(0)
                parts = f.read().split()
                if len(parts) >= 2:
                    return int(parts[0]), float(parts[1])
                return (child.pid if child else 0), time.time()
            fcntl.flock(f, fcntl.LOCK_UN)
    except OSError:
        return None
    if child is not None and child.poll() is None:  # started, not yet holding the lock
        return child.pid, time.time()
    return None


def expected_seconds(label: str) -> float:
    """The expected duration [s] of a build of ``label``'s code: the longest recorded build of the
    same label in the build folder, else :data:`DEFAULT_BUILD_SECONDS` times the machine's load per core
    (when above 1)."""
    seconds = []
    for path in build_dir().glob("*.done"):
        try:
            data = json.loads(path.read_text())
        except (OSError, ValueError):
            continue
        if data.get("label") == label:
            seconds.append(float(data.get("seconds", 0.0)))
    if seconds:
        return max(seconds)
    try:  # a loaded machine builds slower (and runs numpy slower: both estimates scale alike)
        load = os.getloadavg()[0] / (os.cpu_count() or 1)
    except OSError:  # pragma: no cover
        load = 1.0
    return DEFAULT_BUILD_SECONDS * max(1.0, load)


def _mapping_proxy(mapping):
    import types

    return types.MappingProxyType(mapping)


def _dumps(obj) -> bytes:
    """``pickle.dumps`` of a model for the builder: read-only mappings (``types.MappingProxyType``, as
    in a parsed .tir file) as dicts, and without an object's cached compiled code (attributes named
    ``_compiled*``: numba dispatchers, rebuilt by the builder)."""
    import io
    import pickle
    import types

    class Pickler(pickle.Pickler):
        def reducer_override(self, item):
            if isinstance(item, types.MappingProxyType):
                return _mapping_proxy, (dict(item),)
            state = getattr(item, "__dict__", None)
            if isinstance(item, type) or not isinstance(state, dict) or not any(
                    name.startswith("_compiled") for name in state):
                return NotImplemented
            reduced = item.__reduce_ex__(pickle.HIGHEST_PROTOCOL)
            kept = {name: value for name, value in reduced[2].items() if not name.startswith("_compiled")}
            return (*reduced[:2], kept, *reduced[3:])

    buffer = io.BytesIO()
    Pickler(buffer, protocol=pickle.HIGHEST_PROTOCOL).dump(obj)
    return buffer.getvalue()


def start_build(key: str, label: str, model, t, u, x0, method: str) -> int | None:
    """Start the background build of ``key`` (unless one runs or the record exists): a detached,
    niced Python process running :func:`build` that runs ``model`` compiled over the first
    two instants of the grid ``t`` with inputs ``u`` (m, n_t) from ``x0``. Returns its pid, or None
    when the model cannot be sent to another process (then the caller compiles itself)."""
    import subprocess

    running = builder(key)
    if running is not None:
        return running[0]
    lock, _, payload, log = _paths(key)
    span = slice(0, min(2, len(t)))
    try:
        data = _dumps(list(sys.path)) + _dumps(
            {"label": label, "model": model, "t": t[span], "u": u[:, span], "x0": x0, "method": method})
    except Exception:  # an unpicklable model (a Python callable inside): no background build
        return None
    temporary = payload.with_suffix(f".payload.{os.getpid()}")
    temporary.write_bytes(data)
    os.replace(temporary, payload)
    root = str(Path(__file__).resolve().parent.parent.parent)
    env = dict(os.environ)
    env[ENV] = "0"  # the builder compiles in its own process
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [root, env.get("PYTHONPATH")]))
    with open(log, "ab") as out:
        child = subprocess.Popen([sys.executable, "-c", _ENTRY, key], cwd=root, env=env,
                                 stdin=subprocess.DEVNULL, stdout=out, stderr=out, start_new_session=True,
                                 close_fds=True)
    _CHILDREN[key] = child
    return child.pid


def wait(key: str, timeout: float | None = None, poll: float = 0.05) -> bool:
    """Wait until ``key``'s build ends; True when its record exists (False: it ended without one,
    or ``timeout`` [s] passed)."""
    deadline = None if timeout is None else time.monotonic() + timeout
    while True:
        if record(key) is not None:
            return True
        if builder(key) is None:
            return record(key) is not None
        if deadline is not None and time.monotonic() > deadline:
            return False
        time.sleep(poll)


def numpy_estimate(model, t, u, x0) -> float:
    """Estimated wall time [s] of the call on numpy: the rhs's cost at the initial point (best of
    three calls) plus solve_ivp's step overhead, times the rhs calls expected over the time span
    (learnt per model class from earlier runs in this process; :data:`DEFAULT_CALLS_PER_SECOND` before)."""
    cost = float("inf")
    for _ in range(3):
        start = time.perf_counter()
        model.rhs(float(t[0]), x0, u[:, 0])
        cost = min(cost, time.perf_counter() - start)
    rate = _CALLS_PER_SECOND.get(type(model).__name__, DEFAULT_CALLS_PER_SECOND)
    calls = max(100.0, rate * float(t[-1] - t[0]))
    return calls * (cost + STEP_OVERHEAD)


def learn(model, t, nfev: int) -> None:
    """Record a finished run's rhs calls per simulated second for :func:`numpy_estimate`."""
    span = float(t[-1] - t[0])
    if span > 0 and nfev > 0:
        _CALLS_PER_SECOND[type(model).__name__] = nfev / span


def mark_ready(key: str, label: str, seconds: float) -> None:
    """Note that ``key``'s code ran compiled in this process, and write its build record if there is
    none (it was compiled here, or loaded from a cache built by ``"compiled"`` calls or
    :func:`vehdyn.warm_up`), so that ``"auto"`` calls in other processes run it from their first."""
    if key in _READY:
        return
    _READY.add(key)
    try:
        if _WRITE_RECORDS and record(key) is None:
            _write_record(key, {"label": label, "seconds": seconds, "pid": os.getpid()})
    except OSError:  # no build folder can be written: other processes build (or load) again
        pass


def _write_record(key: str, data: dict) -> None:
    done = _paths(key)[1]
    temporary = done.with_suffix(f".done.{os.getpid()}")
    try:
        temporary.write_text(json.dumps(data))
        os.replace(temporary, done)
    except OSError:  # a read-only build folder: the next process builds (or loads) again
        pass


@contextlib.contextmanager
def compiling(key: str | None, label: str = ""):
    """Hold ``key``'s build lock while this process compiles its code (``backend="compiled"``,
    :func:`vehdyn.warm_up`, ``"auto"`` without background builds), as a background build holds it.

    A background build of the same code started meanwhile then leaves it to this process, and one
    running already is waited for (its cache then loads here instead of compiling the same code
    twice at once). Nothing is locked when ``key`` is None, its code ran or was built already, this
    process holds the lock (a builder), or the platform or the build folder does not allow it.
    """
    if key is None or key in _READY or key in _HOLDING or record(key) is not None:
        yield
        return
    try:
        import fcntl

        handle = open(_paths(key)[0], "a+")
    except (ImportError, OSError):  # Windows, an unwritable build folder: compile unlocked
        yield
        return
    held = False
    try:
        fcntl.flock(handle, fcntl.LOCK_EX)  # blocks while a build of the same code runs
        held = True
        handle.seek(0)
        handle.truncate()
        handle.write(f"{os.getpid()} {time.time()!r} {label}")
        handle.flush()
        _HOLDING.add(key)
        yield
    finally:
        _HOLDING.discard(key)
        if held:  # the text names the holder while it holds the lock only
            handle.seek(0)
            handle.truncate()
        handle.close()  # releases the lock


def decide(model, compiled, method: str, t, u, x0) -> tuple[bool, str, str]:
    """Whether an ``"auto"`` call runs compiled now: (compiled, code key, why).

    Compiled when the code ran in this process or its build record exists, or when background builds
    are off or cannot take the model (then compiled here first); otherwise a background build is
    started (or found running) and numpy runs when its estimate is below the build's remaining time,
    else this call waits for the build.
    """
    try:
        return _decide(model, compiled, method, t, u, x0)
    except OSError as exc:  # no build folder can be written: compile here, as without background builds
        return True, None, f"no background build ({exc}): compiled in this process first if not cached"


def _decide(model, compiled, method, t, u, x0):
    key = code_key(compiled, method)
    if key in _READY:
        return True, key, "compiled code already loaded in this process"
    if not enabled():
        return True, key, f"background builds off ({ENV}=0): compiled in this process first if not cached"
    done = record(key)
    if done is not None:
        return True, key, f"compiled code in the cache (built in {done.get('seconds', 0.0):.1f} s)"
    label = compiled.key
    pid = start_build(key, label, model, t, u, x0, method)
    if pid is None:
        return True, key, (f"{type(model).__name__} cannot be sent to a background build (not picklable): "
                           "compiled in this process")
    running = builder(key)
    started = running[1] if running else time.time()
    expected = expected_seconds(label)
    remaining = max(expected - (time.time() - started), 0.2 * expected)
    estimate = numpy_estimate(model, t, u, x0)
    if estimate < remaining:
        return False, key, (f"compiled code not in the cache yet: building in the background (pid {pid}, about "
                            f"{remaining:.0f} s left); numpy's estimated {estimate:.2g} s answers sooner")
    start = time.perf_counter()
    if wait(key):
        return True, key, (f"compiled code built in the background (pid {pid}); waited {time.perf_counter() - start:.1f}"
                           f" s for it, numpy's estimate being {estimate:.2g} s")
    return True, key, (f"the background build (pid {pid}) ended without finishing: compiled in this process "
                       "(see the build log in " + str(build_dir()) + ")")


# ------------------------------------------------------------------------------------ the builder
def _log(message: str) -> None:
    print(f"{time.strftime('%Y-%m-%dT%H:%M:%S')} pid {os.getpid()}: {message}", flush=True)


def build(key: str) -> int:
    """The builder's work: take the lock (or leave: another builds), build, write the record."""
    import fcntl

    global _WRITE_RECORDS
    _WRITE_RECORDS = False
    lock, done, payload, _ = _paths(key)
    try:
        os.nice(NICENESS)
    except OSError:  # pragma: no cover
        pass
    handle = open(lock, "a+")
    try:
        fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        _log(f"skipped {key}: another process builds it")
        return 0
    handle.seek(0)
    handle.truncate()
    start = time.time()
    handle.write(f"{os.getpid()} {start!r}")
    handle.flush()
    _HOLDING.add(key)
    if done.exists():
        _log(f"skipped {key}: already built")
        return 0
    try:
        data = payload.read_bytes()
    except OSError:
        _log(f"no payload for {key}")
        return 1
    import io
    import pickle

    stream = io.BytesIO(data)
    sys.path.extend(p for p in pickle.load(stream) if p not in sys.path)  # where the model's classes live
    return _run(pickle.load(stream), key, start, payload)


def _run(job, key, start, payload) -> int:
    import numpy as np

    from vehdyn.errors import SimulationError
    from vehdyn.simulation._api import simulate

    model, t, u = job["model"], np.asarray(job["t"], dtype=float), np.asarray(job["u"], dtype=float)
    _log(f"building {key} ({job['label']}, {job['method']})")
    try:
        simulate(model, t, dict(zip(model.input_names, u)), x0=job["x0"], method=job["method"], backend="compiled")
    except SimulationError as exc:  # the code is built; the two instants may leave the domain
        _log(f"(the trial run failed after compiling: {exc})")
    hold = os.environ.get(_HOLD_ENV)
    while hold and os.path.exists(hold):  # the tests' seam: a build caught between compiling and its record
        time.sleep(0.05)
    seconds = time.time() - start
    _write_record(key, {"label": job["label"], "seconds": seconds, "cpu_seconds": time.process_time(),
                        "pid": os.getpid(), "method": job["method"]})
    try:
        payload.unlink()
    except OSError:
        pass
    _log(f"built {key} in {seconds:.1f} s")
    return 0


