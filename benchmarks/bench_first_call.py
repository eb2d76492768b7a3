"""Time to the first result (issue 31): per shipped model, in a fresh numba cache, how long the first
``simulate`` takes on ``backend="auto"`` (numpy answering while the compiled code builds in the
background) and on ``backend="compiled"`` (compile, then run), the cold compile, where it goes, and
the warm call.

Run: ``python benchmarks/bench_first_call.py [MODEL ...] [--report]``. Every measurement runs in a
new Python process with an empty ``NUMBA_CACHE_DIR`` (and build folder), so nothing is cached;
the machine's load average is printed beside each row (the machine may be shared: compare CPU
seconds, less disturbed than wall seconds). Per model (:func:`vehdyn.cli.shipped_runs`):

* ``auto 1st``: wall time of the first ``simulate`` on ``"auto"`` (numpy runs; the build starts);
  ``build``: wall and CPU seconds of the background build (niced, cold compile and one short run);
  ``auto next``: the first ``"auto"`` call once built (a cache load, then compiled);
* ``compiled 1st``: wall and CPU time of the first ``simulate`` on ``"compiled"`` (the cold
  compile and the run), split by where numba's compile time goes (exclusive time per compiled
  function, grouped: the integrator loop and its helpers, the model's own rhs/outputs/equations,
  the tire laws, numba's own library functions); ``warm``: the next call (best of 5).

``llvm``: the CPU seconds of the cold compile spent in LLVM (optimisation and machine code, numba's
``numba:llvm_lock`` events); the rest is numba's typing and lowering.

``--shared`` also compiles the models one after another into one fresh cache (each in a new
process): what each further model costs once the code shared across models (the tire laws) is
cached, as in ``vehdyn compile`` or a report run; ``--shared-only`` skips the per-model rows.
``--report`` also times the README's main command, ``vehdyn report --out DIR``, from a fresh cache
(wall and CPU seconds; a fresh clone and venv are not made here), ``--report-quick`` the same with
``--quick``.
"""

from __future__ import annotations

import _timing  # noqa: F401  (first: one BLAS thread)
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

_WORKER = r'''
import json, os, sys, time
start_process = time.perf_counter()
import numpy as np
import vehdyn
from vehdyn.cli import shipped_runs
from vehdyn.simulation import _background
name, backend = sys.argv[1], sys.argv[2]
import_seconds = time.perf_counter() - start_process
groups = {}
if backend == "compiled":
    from numba.core import event

    stack = []

    def group(module):
        if module.startswith("vehdyn.simulation"):
            return "integrator"
        if module.startswith("vehdyn.tire"):
            return "tire laws"
        if module.startswith(("vehdyn.", "vehdyn")):
            return "model"
        return "numba library"

    class Listener(event.Listener):
        def on_start(self, ev):
            stack.append([time.process_time(), 0.0, group(ev.data["dispatcher"].py_func.__module__)])

        def on_end(self, ev):
            t0, child, g = stack.pop()
            spent = time.process_time() - t0
            groups[g] = groups.get(g, 0.0) + spent - child
            if stack:
                stack[-1][1] += spent

    event.register("numba:compile", Listener())
    llvm = [0, 0.0, 0.0]  # depth, start, total

    class LLVMListener(event.Listener):  # LLVM's work (optimisation, machine code) inside the compile
        def on_start(self, ev):
            llvm[0] += 1
            if llvm[0] == 1:
                llvm[1] = time.process_time()

        def on_end(self, ev):
            llvm[0] -= 1
            if llvm[0] == 0:
                llvm[2] += time.process_time() - llvm[1]

    event.register("numba:llvm_lock", LLVMListener())
model, t, inputs, x0 = shipped_runs([name])[name]()
cpu0, wall0 = time.process_time(), time.perf_counter()
first = vehdyn.simulate(model, t, inputs, x0=x0, backend=backend)
out = {"import": import_seconds, "first": time.perf_counter() - wall0, "first_cpu": time.process_time() - cpu0,
       "first_backend": first.backend, "reason": first.backend_reason, "method": first.method, "groups": groups}
if backend == "compiled":
    out["llvm"] = llvm[2]
if backend == "auto":
    key = _background.code_key(model.compiled_rhs(), first.method)
    _background.wait(key)
    out["build"] = _background.record(key)
    wall0 = time.perf_counter()
    after = vehdyn.simulate(model, t, inputs, x0=x0, backend="auto")
    out["next"] = time.perf_counter() - wall0
    out["next_backend"] = after.backend
    out["max_difference"] = float(np.max(np.abs(after.states - first.states)))
else:
    best = float("inf")
    for _ in range(5):
        wall0 = time.perf_counter()
        vehdyn.simulate(model, t, inputs, x0=x0, backend=backend)
        best = min(best, time.perf_counter() - wall0)
    out["warm"] = best
print("RESULT " + json.dumps(out))
'''


def _load() -> str:
    return " ".join(Path("/proc/loadavg").read_text().split()[:3]) if Path("/proc/loadavg").exists() else "?"


def _measure(name: str, backend: str, cache: str | None = None) -> dict:
    """One worker run in a new process, in ``cache`` (default: a new empty numba cache)."""
    if cache is None:
        with tempfile.TemporaryDirectory(prefix="vehdyn_first_call_") as fresh:
            return _measure(name, backend, fresh)
    env = dict(os.environ, NUMBA_CACHE_DIR=cache, VEHDYN_BACKGROUND_COMPILE="1",
               VEHDYN_BUILD_DIR=str(Path(cache) / "builds"),
               PYTHONPATH=os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")])))
    load = _load()
    done = subprocess.run([sys.executable, "-c", _WORKER, name, backend], env=env, capture_output=True, text=True,
                          timeout=1800)
    lines = [line for line in done.stdout.splitlines() if line.startswith("RESULT ")]
    if done.returncode != 0 or not lines:
        raise RuntimeError(f"{name} {backend}: {done.stderr[-2000:]}")
    result = json.loads(lines[-1][7:])
    result["load"] = load
    return result


def _shared_cache(names) -> None:
    """The models compiled one after another into one cache, each in a new process: what every further
    model costs once the code shared across models (the tire laws) is cached (``vehdyn compile``, a report)."""
    print("\none shared numba cache, the models compiled in this order (each a new process; CPU [s])")
    print(f"{'model':<24} {'compile cpu':>11} {'llvm':>6} {'integrator':>10} {'model':>6} {'tire':>6} {'numba':>6}"
          "  load")
    total = 0.0
    with tempfile.TemporaryDirectory(prefix="vehdyn_first_call_") as cache:
        for name in names:
            r = _measure(name, "compiled", cache)
            g = r["groups"]
            total += r["first_cpu"]
            print(f"{name:<24} {r['first_cpu']:11.1f} {r['llvm']:6.1f} {g.get('integrator', 0):10.1f} "
                  f"{g.get('model', 0):6.1f} {g.get('tire laws', 0):6.1f} {g.get('numba library', 0):6.1f}  "
                  f"{r['load']}", flush=True)
    print(f"{'all':<24} {total:11.1f}")


def _report_command(quick: bool) -> None:
    import resource

    with tempfile.TemporaryDirectory(prefix="vehdyn_first_call_") as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache, VEHDYN_BUILD_DIR=str(Path(cache) / "builds"),
                   PYTHONPATH=os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")])))
        load = _load()
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        command = ["report", *(["--quick"] if quick else []), "--out", str(Path(cache) / "report")]
        done = subprocess.run([sys.executable, "-m", "vehdyn.cli", *command], env=env, capture_output=True, text=True)
        wall = time.perf_counter() - start
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
        print(f"\nvehdyn {' '.join(command[:-2])} from a fresh numba cache: {wall:.0f} s wall, {cpu:.0f} s CPU (exit "
              f"{done.returncode}; load {load} at the start, {_load()} at the end; goal <= 180 s for the README's "
              "main command, its install not included)")


def main(argv) -> None:
    from vehdyn.cli import shipped_runs

    names = [a for a in argv if not a.startswith("--")] or list(shipped_runs())
    print(f"Python {sys.version.split()[0]}, {os.cpu_count()} cores; every row from an empty numba cache; "
          "wall [s] (CPU [s]); goals: auto 1st <= 3 s, cold compile <= 10 s per model")
    header = (f"{'model':<24} {'auto 1st (cpu)':>15} {'build wall (cpu)':>17} {'auto next':>9} {'compiled 1st (cpu)':>19} "
              f"{'llvm':>5} {'integrator':>10} {'model':>6} {'tire':>6} {'numba':>6} {'warm':>8} {'import':>6}  load")
    print(header)
    for name in ([] if "--shared-only" in argv else names):
        auto = _measure(name, "auto")
        compiled = _measure(name, "compiled")
        g = compiled["groups"]
        build = auto.get("build") or {}
        print(f"{name:<24} {auto['first']:7.2f}{'n' if auto['first_backend'] == 'numpy' else 'c'} "
              f"({auto['first_cpu']:5.2f}) "
              f"{build.get('seconds', float('nan')):8.1f} ({build.get('cpu_seconds', float('nan')):5.1f}) "
              f"{auto['next']:9.2f} {compiled['first']:10.1f} ({compiled['first_cpu']:5.1f}) "
              f"{compiled['llvm']:5.1f} {g.get('integrator', 0):10.1f} {g.get('model', 0):6.1f} "
              f"{g.get('tire laws', 0):6.1f} {g.get('numba library', 0):6.1f} {compiled['warm'] * 1e3:6.1f}ms "
              f"{compiled['import']:6.2f}  "
              f"{auto['load']} / {compiled['load']}", flush=True)
    print("(auto 1st: n = numpy answered, c = compiled; compile split: CPU seconds of numba's compile events, "
          "exclusive per compiled function; the rest of 'compiled 1st' is LLVM linking, cache writes and the run)")
    if "--shared" in argv or "--shared-only" in argv:
        _shared_cache(names)
    if "--report" in argv or "--report-quick" in argv:
        _report_command(quick="--report-quick" in argv)


if __name__ == "__main__":
    main(sys.argv[1:])
