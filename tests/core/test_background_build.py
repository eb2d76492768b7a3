"""backend="auto" with background builds (vehdyn.simulation._background): numpy answers while the compiled
code builds in another process, the compiled code runs once built (both against the closed form and
each other), a killed build leaves a usable cache and is built again, one builder per code, a build
outlives the script that started it and ends with its record.

The suite runs with background builds off (tests/conftest.py); these tests turn them on with a build
folder of their own, hold a build between compiling and its record where they need it caught there
(``VEHDYN_BUILD_HOLD_WHILE``), and end every builder they started. No timing assertions.
"""

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import vehdyn
from vehdyn.simulation import _background

pytest.importorskip("numba")
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _coast_down import CoastDown  # noqa: E402

V0 = 30.0
T = np.linspace(0.0, 10.0, 101)
INPUTS = {"rear_longitudinal_force": 0.0}
TIMEOUT = 600.0  # [s] a cold compile on a loaded 2-core machine takes up to a minute


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    try:  # a finished child of ours that is not yet reaped
        done, _ = os.waitpid(pid, os.WNOHANG)
        return done == 0
    except ChildProcessError:
        return True


def _wait_gone(pid: int, timeout: float = TIMEOUT) -> None:
    deadline = time.monotonic() + timeout
    while _alive(pid):
        assert time.monotonic() < deadline, f"builder {pid} still running"
        time.sleep(0.05)


@pytest.fixture
def builds(tmp_path, monkeypatch):
    """Background builds on, in a build folder of this test; every builder is ended afterwards."""
    monkeypatch.setenv(_background.ENV, "1")
    monkeypatch.setenv(_background.DIR_ENV, str(tmp_path / "builds"))
    monkeypatch.delenv(_background._HOLD_ENV, raising=False)
    _background._READY.clear()
    _background._CHILDREN.clear()
    pids = []
    yield pids
    for path in (tmp_path / "builds").glob("*.lock"):
        parts = path.read_text().split()
        if parts:
            pids.append(int(parts[0]))
    pids += [child.pid for child in _background._CHILDREN.values()]
    for pid in set(pids):
        if _alive(pid):
            os.kill(pid, signal.SIGKILL)
        _wait_gone(pid)
    for child in _background._CHILDREN.values():
        child.wait()
    _background._READY.clear()
    _background._CHILDREN.clear()


def _hold(tmp_path, monkeypatch) -> Path:
    hold = tmp_path / "hold"
    hold.write_text("")
    monkeypatch.setenv(_background._HOLD_ENV, str(hold))
    return hold


def _run(model, **options):
    return vehdyn.simulate(model, T, INPUTS, x0=[V0, 0.0], method="RK45", rtol=1e-8, atol=1e-8, **options)


def _check_closed_form(model, result):
    v, x = model.closed_form(T, V0)
    np.testing.assert_allclose(result["longitudinal_velocity"], v, rtol=1e-6)
    np.testing.assert_allclose(result["x_position"], x, rtol=1e-6)


def _key(model):
    return _background.code_key(model.compiled_rhs(), "RK45")


def _builder_pid(key, timeout=TIMEOUT):
    """The pid of the process holding key's build lock (waits until one does)."""
    deadline = time.monotonic() + timeout
    while True:
        running = _background.builder(key)
        if running is not None and running[0] and (Path(_background.build_dir()) / f"{key}.lock").read_text():
            return running[0]
        assert time.monotonic() < deadline, "no builder took the lock"
        time.sleep(0.05)


@pytest.mark.compiled_vs_numpy  # within the integrator's tolerance, not ulps
def test_auto_answers_on_numpy_then_runs_the_built_code(builds, tmp_path, monkeypatch):
    """Cold: numpy answers and says why; once the build's record exists, compiled; both equal the
    closed form and each other within the tolerance."""
    hold = _hold(tmp_path, monkeypatch)
    model = CoastDown()
    first = _run(model)
    assert first.backend == "numpy"
    assert "building in the background" in first.backend_reason and "answers sooner" in first.backend_reason
    key = _key(model)
    assert _background.record(key) is None
    hold.unlink()
    assert _background.wait(key, TIMEOUT)
    assert _background.record(key)["label"] == model.compiled_rhs().key
    second = _run(model)
    assert second.backend == "compiled" and "in the cache" in second.backend_reason
    _check_closed_form(model, first)
    _check_closed_form(model, second)
    np.testing.assert_allclose(second.states, first.states, rtol=1e-6, atol=1e-6)
    third = _run(model)
    assert third.backend == "compiled" and "loaded in this process" in third.backend_reason


def test_auto_waits_for_a_build_that_ends_before_numpy_would(builds, monkeypatch):
    """A build expected to end sooner than numpy's run is waited for, and the call runs compiled."""
    monkeypatch.setattr(_background, "DEFAULT_BUILD_SECONDS", 1e-6)
    model = CoastDown()
    result = _run(model)
    assert result.backend == "compiled" and "waited" in result.backend_reason
    _check_closed_form(model, result)


def test_a_killed_build_leaves_a_usable_cache_and_is_built_again(builds, tmp_path, monkeypatch):
    _hold(tmp_path, monkeypatch)
    model = CoastDown()
    assert _run(model).backend == "numpy"
    key = _key(model)
    pid = _builder_pid(key)
    os.kill(pid, signal.SIGKILL)
    _wait_gone(pid)
    assert _background.builder(key) is None and _background.record(key) is None  # no stale lock, no record
    monkeypatch.delenv(_background._HOLD_ENV)
    _background._CHILDREN.clear()
    again = _run(model)  # starts a new build
    assert again.backend == "numpy"
    assert _background.wait(key, TIMEOUT)
    assert _background.record(key)["pid"] != pid
    result = _run(model)
    assert result.backend == "compiled"
    _check_closed_form(model, result)


def test_one_builder_per_code(builds, tmp_path, monkeypatch):
    """While one process builds, a second builder of the same code leaves at once, and another
    process's auto call starts none (it answers on numpy)."""
    hold = _hold(tmp_path, monkeypatch)
    model = CoastDown()
    _run(model)
    key = _key(model)
    pid = _builder_pid(key)
    second = subprocess.run([sys.executable, "-c", _background._ENTRY, key], env=dict(os.environ), timeout=TIMEOUT,
                            capture_output=True, text=True)
    assert second.returncode == 0 and "another process builds it" in second.stdout, second.stdout + second.stderr
    script = ("import sys, numpy as np, vehdyn; sys.path[:0] = {path!r}; from _coast_down import CoastDown; "
              "r = vehdyn.simulate(CoastDown(), np.linspace(0, 10, 101), {{'rear_longitudinal_force': 0.0}}, "
              "x0=[30.0, 0.0], method='RK45'); print(r.backend, r.backend_reason)").format(path=sys.path)
    other = subprocess.run([sys.executable, "-c", script], env=dict(os.environ), timeout=TIMEOUT, capture_output=True,
                           text=True)
    assert other.returncode == 0, other.stderr
    assert other.stdout.startswith("numpy") and f"pid {pid}" in other.stdout
    assert _background.builder(key)[0] == pid  # still the one builder
    hold.unlink()
    assert _background.wait(key, TIMEOUT)
    log = (Path(_background.build_dir()) / f"{key}.log").read_text()
    assert log.count("building ") == 1 and log.count("built ") == 1


def test_a_build_outlives_its_script_and_ends_with_its_record(builds, tmp_path, monkeypatch):
    hold = _hold(tmp_path, monkeypatch)
    script = ("import sys, numpy as np, vehdyn; sys.path[:0] = {path!r}; from _coast_down import CoastDown; "
              "r = vehdyn.simulate(CoastDown(), np.linspace(0, 10, 101), {{'rear_longitudinal_force': 0.0}}, "
              "x0=[30.0, 0.0], method='RK45'); print(r.backend)").format(path=sys.path)
    done = subprocess.run([sys.executable, "-c", script], env=dict(os.environ), timeout=TIMEOUT, capture_output=True,
                          text=True)
    assert done.returncode == 0 and done.stdout.strip() == "numpy", done.stderr
    key = _key(CoastDown())
    pid = _builder_pid(key)
    builds.append(pid)
    assert _alive(pid)  # the script has ended; its build goes on
    hold.unlink()
    _wait_gone(pid)  # and ends once its record is written
    assert json.loads((Path(_background.build_dir()) / f"{key}.done").read_text())["pid"] == pid
    assert not (Path(_background.build_dir()) / f"{key}.payload").exists()


def test_background_builds_off_compile_in_the_calling_process(builds, monkeypatch):
    monkeypatch.setenv(_background.ENV, "0")
    model = CoastDown()
    result = _run(model)
    assert result.backend == "compiled" and f"{_background.ENV}=0" in result.backend_reason
    folder = Path(_background.build_dir())
    assert not _background._CHILDREN and not list(folder.glob("*.log")) and not list(folder.glob("*.payload"))
    _check_closed_form(model, result)


def test_a_model_that_cannot_be_pickled_compiles_in_the_calling_process(builds):
    model = CoastDown()
    model.hook = lambda: None  # a lambda cannot be pickled
    result = _run(model)
    assert result.backend == "compiled" and "not picklable" in result.backend_reason
    assert not _background._CHILDREN


def test_the_result_says_which_backend_ran_and_why():
    model = CoastDown()
    numpy_run = _run(model, backend="numpy")
    assert numpy_run.backend == "numpy" and "backend='numpy'" in numpy_run.backend_reason
    compiled_run = _run(model, backend="compiled")
    assert compiled_run.backend == "compiled" and "backend='compiled'" in compiled_run.backend_reason
    lag = vehdyn.LinearModel([[-2.0]], [[2.0]], states=["yaw_rate"], inputs=["front_steer_angle"])
    exact = vehdyn.simulate(lag, T, {"front_steer_angle": 0.01})
    assert exact.backend == "numpy" and "method 'exact'" in exact.backend_reason


def test_a_compiled_run_records_its_build_for_other_processes(builds):
    """After a backend="compiled" run (what vehdyn.warm_up does), an auto call in a new process runs
    compiled from its first call, starting no build."""
    model = CoastDown()
    _run(model, backend="compiled")
    assert _background.record(_key(model)) is not None
    script = ("import sys, numpy as np, vehdyn; sys.path[:0] = {path!r}; from _coast_down import CoastDown; "
              "from vehdyn.simulation import _background; "
              "r = vehdyn.simulate(CoastDown(), np.linspace(0, 10, 101), {{'rear_longitudinal_force': 0.0}}, "
              "x0=[30.0, 0.0], method='RK45'); print(r.backend, len(_background._CHILDREN), r.backend_reason)"
              ).format(path=sys.path)
    other = subprocess.run([sys.executable, "-c", script], env=dict(os.environ), timeout=TIMEOUT, capture_output=True,
                           text=True)
    assert other.returncode == 0, other.stderr
    assert other.stdout.startswith("compiled 0 compiled code in the cache"), other.stdout


def test_an_unwritable_build_folder_compiles_in_the_calling_process(builds, tmp_path, monkeypatch):
    blocker = tmp_path / "a_file"
    blocker.write_text("")
    monkeypatch.setenv(_background.DIR_ENV, str(blocker / "builds"))  # below a file: cannot be created
    model = CoastDown()
    result = _run(model)
    assert result.backend == "compiled" and "no background build" in result.backend_reason
    _check_closed_form(model, result)


@pytest.mark.skipif(not Path("/proc/locks").exists(), reason="reads the kernel's lock table (Linux)")
def test_a_compiled_call_waits_for_the_running_build_of_its_code(builds, tmp_path, monkeypatch):
    """backend="compiled" (and vehdyn compile / warm_up) takes the build lock: while a background build
    of the same code runs, a compiled call in another process waits on the lock (the kernel lists it as
    a blocked waiter) instead of compiling the same code at once, then runs on the built cache."""
    hold = _hold(tmp_path, monkeypatch)
    model = CoastDown()
    assert _run(model).backend == "numpy"  # starts the build, held after compiling, before its record
    key = _key(model)
    pid = _builder_pid(key)
    script = ("import sys, numpy as np, vehdyn; sys.path[:0] = {path!r}; from _coast_down import CoastDown; "
              "from vehdyn.simulation import compiled; m = CoastDown(); print('calling', flush=True); "
              "r = vehdyn.simulate(m, np.linspace(0, 10, 101), {{'rear_longitudinal_force': 0.0}}, "
              "x0=[30.0, 0.0], method='RK45', rtol=1e-8, atol=1e-8, backend='compiled'); "
              "c = m.compiled_rhs(); loop = compiled.integrator(c.rhs, c.key, 'RK45'); "
              "print(r.backend, sum(loop.stats.cache_misses.values()), float(r.states[0, -1]))").format(path=sys.path)
    other = subprocess.Popen([sys.executable, "-c", script], env=dict(os.environ), stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True)
    try:
        assert other.stdout.readline().strip() == "calling"
        deadline = time.monotonic() + TIMEOUT
        while not any(line.split()[1] == "->" and line.split()[5] == str(other.pid)
                      for line in Path("/proc/locks").read_text().splitlines() if len(line.split()) > 5):
            assert other.poll() is None, "the compiled call ended while the build held its lock"
            assert time.monotonic() < deadline, "the compiled call never waited on the build lock"
            time.sleep(0.05)
        assert _background.builder(key)[0] == pid  # the build still holds the lock; the call waits
        hold.unlink()
        out, err = other.communicate(timeout=TIMEOUT)
    finally:
        if other.poll() is None:
            other.kill()
            other.wait()
    assert other.returncode == 0, err
    backend, misses, v_end = out.split()
    assert backend == "compiled" and misses == "0"  # the loop loaded from the build's cache: nothing compiled twice
    assert float(v_end) == pytest.approx(model.closed_form(T, V0)[0][-1], rel=1e-6)
    log = (Path(_background.build_dir()) / f"{key}.log").read_text()
    assert log.count("building ") == 1 and log.count("built ") == 1
