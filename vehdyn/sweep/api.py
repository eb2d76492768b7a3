"""``vehdyn.sweep``: full-factorial grids and Monte Carlo samples of a scene or a function."""

from __future__ import annotations

import itertools
import math
import sys
from typing import Any, Mapping

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.sweep.engines import ChunkTask, run_chunks
from vehdyn.sweep.targets import as_target

__all__ = ["sweep", "variants", "run_table"]

_SAMPLING = ("lhs", "sobol", "random")


def _grid_values(name, values) -> list:
    if isinstance(values, (str, bytes)) or not np.iterable(values):
        raise ParameterError(f"grid[{name!r}] = {values!r}: must be a sequence of values", key=name, value=values)
    values = list(np.asarray(values).tolist()) if isinstance(values, np.ndarray) else list(values)
    if not values:
        raise ParameterError(f"grid[{name!r}] is empty", key=name, value=values)
    return values


def _draw(samples: Mapping[str, Any], n, sampling: str, seed) -> dict[str, np.ndarray]:
    from scipy.stats import qmc

    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ParameterError(f"n = {n!r}: the number of samples must be an integer >= 1", key="n", value=n)
    if sampling not in _SAMPLING:
        raise ParameterError(f"sampling = {sampling!r}: must be one of {list(_SAMPLING)}", key="sampling",
                             value=sampling)
    for name, dist in samples.items():
        if not hasattr(dist, "ppf"):
            raise ParameterError(f"samples[{name!r}] = {dist!r}: must be a frozen scipy.stats distribution "
                                 "(e.g. scipy.stats.norm(1500, 50))", key=name, value=dist)
    d = len(samples)
    rng = np.random.default_rng(seed)
    if sampling == "lhs":
        u = qmc.LatinHypercube(d=d, rng=rng).random(int(n))
    elif sampling == "sobol":
        u = qmc.Sobol(d=d, scramble=True, rng=rng).random(int(n))
    else:
        u = rng.random((int(n), d))
    return {name: np.asarray(dist.ppf(u[:, j]), dtype=float) for j, (name, dist) in enumerate(samples.items())}


def variants(grid: Mapping[str, Any] | None = None, samples: Mapping[str, Any] | None = None, *, n=None,
             sampling: str = "lhs", seed=None):
    """The parameter table of a sweep: one row per variant (index ``variant``).

    Grid points vary slowest (full factorial, the last name fastest); each grid point is combined
    with every sample.

    Parameters
    ----------
    grid : mapping, optional
        Name -> sequence of values.
    samples : mapping, optional
        Name -> frozen ``scipy.stats`` distribution, drawn ``n`` times by ``sampling``
        (``"lhs"`` Latin hypercube, ``"sobol"`` scrambled Sobol', ``"random"``) through
        :mod:`scipy.stats.qmc`; the draws are reproducible with ``seed``.
    n : int
        Number of samples (with ``samples``).

    Returns
    -------
    pandas.DataFrame
    """
    import pandas as pd

    grid, samples = dict(grid or {}), dict(samples or {})
    both = set(grid) & set(samples)
    if both:
        name = sorted(both)[0]
        raise ParameterError(f"parameter {name!r} is in both grid and samples", key=name, value=name)
    if not grid and not samples:
        raise ParameterError("a sweep needs a grid or samples", key="grid", value=None)
    if samples and n is None:
        raise ParameterError("samples need n, the number of draws", key="n", value=None)
    if not samples and n is not None:
        raise ParameterError(f"n = {n!r} without samples: give samples to draw from", key="n", value=n)
    grid_values = {k: _grid_values(k, v) for k, v in grid.items()}
    points = list(itertools.product(*grid_values.values())) if grid else [()]
    draws = _draw(samples, n, sampling, seed) if samples else {}
    m = int(n) if samples else 1
    columns = {}
    for j, name in enumerate(grid_values):
        columns[name] = np.repeat(np.asarray([p[j] for p in points]), m)
    for name, values in draws.items():
        columns[name] = np.tile(values, len(points))
    table = pd.DataFrame(columns)
    table.index.name = "variant"
    return table


def _chunk_size(chunk_size, count: int) -> int:
    if chunk_size is None:
        return max(1, min(1000, math.ceil(count / 8)))
    if isinstance(chunk_size, bool) or not isinstance(chunk_size, (int, np.integer)) or chunk_size < 1:
        raise ParameterError(f"chunk_size = {chunk_size!r}: must be an integer >= 1", key="chunk_size",
                             value=chunk_size)
    return int(chunk_size)


class _Progress:
    def __init__(self, total: int, enabled: bool, width: int = 30):
        self.total, self.done, self.enabled, self.width = total, 0, enabled and total > 0, width

    def advance(self, k: int) -> None:
        self.done += k
        if self.enabled:
            filled = int(self.width * self.done / self.total)
            sys.stderr.write(f"\rsweep [{'#' * filled}{'.' * (self.width - filled)}] {self.done}/{self.total}")
            if self.done >= self.total:
                sys.stderr.write("\n")
            sys.stderr.flush()


def sweep(target, *, grid=None, samples=None, n=None, sampling: str = "lhs", metrics=None, executor=None,
          chunk_size=None, out=None, resume: bool = False, progress: bool = True, seed=None, model: str = "auto",
          solver=None):
    """Run every variant of ``target`` and reduce each run to named metrics.

    Parameters
    ----------
    target : Scene or callable
        A :class:`~vehdyn.Scene`, varied by dotted names: its fields (``"speed"``, ``"duration"``,
        ``"tire"``), its manoeuvre's parameters (``"manoeuvre_parameters.lateral_acceleration"``),
        an event road's (``"road.height"``) and its vehicle's parameters
        (``"vehicle.mass.mass"``, ``"vehicle.suspension.front_spring_rate"``). Or a function
        ``f(**params) -> mapping`` of scalar metrics (:func:`vectorized` if it takes arrays).
    grid : mapping, optional
        Name -> values, full factorial.
    samples : mapping, optional
        Name -> frozen ``scipy.stats`` distribution, ``n`` draws (see :func:`variants`).
    n : int, optional
        Number of samples.
    sampling : {"lhs", "sobol", "random"}
        Latin hypercube, scrambled Sobol' or plain random draws (:mod:`scipy.stats.qmc`).
    metrics : sequence of str, optional
        Metric names from the registry (:mod:`vehdyn.sweep.metrics`: ``"peak_yaw_rate"``,
        ``"overshoot_yaw_rate"``, ``"rms_sprung_acceleration"``, ``"understeer_gradient"``, ...).
        Default: ``peak_<output>`` of each scene output; for a function, every key it returns
        (or the keys named).
    executor : None, str, Executor or dask.distributed.Client
        Where chunks run (:mod:`vehdyn.sweep.engines`): None in this process, ``"processes"``,
        ``"threads"``, any :class:`concurrent.futures.Executor`, a Dask client or a scheduler
        address. Every engine gives bitwise the same metrics.
    chunk_size : int, optional
        Variants per task (and per file chunk); default ``ceil(n_variants / 8)`` up to 1000.
    out : str or Path, optional
        A Parquet folder written chunk by chunk, each chunk atomically
        (:mod:`vehdyn.sweep.storage`).
    resume : bool
        With ``out``: run only the variants not yet in it.
    progress : bool
        A progress bar on stderr.
    seed : int, optional
        Seed of the draws.
    model : str
        Scene targets: the rung every variant runs on (``"auto"``: the plan of the base scene).
    solver : mapping, optional
        Scene targets: ``{"method": ..., "rtol": ..., "atol": ...}`` (any of them) for every
        variant's :func:`vehdyn.simulate` call instead of the rung's own (the ladder integrates
        tightly, e.g. the single track by RK45 at rtol 1e-8, so that its errors are the model's);
        ``atol`` defaults to ``rtol / 100`` when only ``rtol`` is given. A sweep whose metrics need
        a few digits runs several times faster, e.g. ``{"method": "BDF", "rtol": 1e-5}`` for a
        single track with tire lag at speed (``benchmarks/bench_sweep.py``).

    Returns
    -------
    pandas.DataFrame
        One row per variant (index ``variant``): the parameter columns, the metric columns and
        ``error`` (None, or ``"ParameterError: ..."`` for a variant that failed; its metrics are
        NaN). ``attrs["units"]`` maps columns to units.

    Raises
    ------
    ParameterError
        An unknown parameter name (with the close matches) or metric, malformed grid or samples.

    Examples
    --------
    >>> import vehdyn, scipy.stats as st
    >>> scene = vehdyn.Scene(vehicle="sedan", manoeuvre="step_steer", speed=25.0, duration=3.0,
    ...                      manoeuvre_parameters={"lateral_acceleration": 3.0})
    >>> table = vehdyn.sweep(scene, grid={"speed": [20.0, 30.0]},
    ...                      samples={"vehicle.mass.mass": st.norm(1500, 50)}, n=4,
    ...                      metrics=["peak_yaw_rate", "understeer_gradient"], progress=False, seed=1)
    >>> table.shape
    (8, 5)
    """
    table = variants(grid, samples, n=n, sampling=sampling, seed=seed)
    return run_table(target, table, metrics=metrics, executor=executor, chunk_size=chunk_size, out=out,
                     resume=resume, progress=progress, model=model, solver=solver)


def run_table(target, table, *, metrics=None, executor=None, chunk_size=None, out=None, resume=False,
              progress=True, model="auto", solver=None):
    """Run the variants of a parameter ``table`` (one row per variant, a column per parameter);
    the engine of :func:`sweep` (which builds the table from a grid and samples) and of
    :func:`~vehdyn.sweep.sensitivity.sensitivity` (SALib's designs). Arguments as :func:`sweep`."""
    import pandas as pd

    if resume and out is None:
        raise ParameterError("resume=True needs out=, the folder to resume", key="resume", value=resume)
    t = as_target(target, model, solver)
    table = table.reset_index(drop=True)
    names = list(table.columns)
    units = dict(t.check_names(names))
    if metrics is None:
        metric_names = t.default_metrics()
    else:
        metric_names = [metrics] if isinstance(metrics, str) else list(metrics)
        if not metric_names:
            raise ParameterError("metrics is empty", key="metrics", value=metrics)
    if metric_names is not None:
        units.update(t.resolve_metrics(metric_names))
    store = None
    todo = np.arange(len(table))
    if out is not None:
        from vehdyn.sweep.storage import ChunkStore

        store = ChunkStore(out)
        if resume:
            done = store.done(table)
            todo = np.array([i for i in todo if i not in done], dtype=int)
        else:
            store.clear()
    size = _chunk_size(chunk_size, len(todo))
    rows = list(table.itertuples(index=False, name=None))
    chunks = [(todo[k:k + size].tolist(), [rows[i] for i in todo[k:k + size]]) for k in range(0, len(todo), size)]
    frames = []
    bar = _Progress(len(todo), progress)

    def finished(frame):
        if store is not None:
            store.write(frame)
        else:
            frames.append(frame)
        bar.advance(len(frame))

    run_chunks(ChunkTask(t, names, metric_names), chunks, executor, finished)
    if store is not None:
        frame = store.read()
    else:
        frame = pd.concat(frames, ignore_index=True) if frames else pd.DataFrame(columns=["variant", *names])
        frame = frame.sort_values("variant", kind="stable").reset_index(drop=True)
    if "error" in frame.columns:  # chunks of a function may differ in their metrics: error last
        frame = frame[[c for c in frame.columns if c != "error"] + ["error"]]
    frame = frame.set_index("variant")
    frame.attrs["units"] = {k: v for k, v in units.items() if k in frame.columns}
    return frame


def _numbers(text: str, what: str, spec: str) -> list[float]:
    try:
        return [float(v) for v in text.split(":" if ":" in text else ",")]
    except ValueError:
        raise ParameterError(f"{what} {spec!r}: values must be numbers", key=what, value=spec) from None


def grid_from_text(spec: str) -> tuple[str, list]:
    """``"speed=10:40:7"`` (start:stop:count, linearly spaced) or ``"speed=10,20,40"`` -> (name, values)."""
    name, sep, text = spec.partition("=")
    if not sep or not name.strip() or not text.strip():
        raise ParameterError(f"grid {spec!r}: write NAME=START:STOP:COUNT or NAME=V1,V2,...", key="grid", value=spec)
    if ":" in text:
        parts = _numbers(text, "grid", spec)
        if len(parts) != 3 or parts[2] < 1 or parts[2] != int(parts[2]):
            raise ParameterError(f"grid {spec!r}: START:STOP:COUNT with an integer COUNT >= 1", key="grid",
                                 value=spec)
        return name.strip(), np.linspace(parts[0], parts[1], int(parts[2])).tolist()
    return name.strip(), _numbers(text, "grid", spec)


def distribution_from_text(spec: str):
    """``"vehicle.mass.mass=norm:1500:50"`` -> (name, scipy.stats.norm(1500, 50)): a scipy.stats
    distribution name and its positional parameters (shape parameters, loc, scale)."""
    import scipy.stats

    name, sep, text = spec.partition("=")
    law, _, args = text.partition(":")
    dist = getattr(scipy.stats, law.strip(), None)
    if not sep or not name.strip() or not hasattr(dist, "freeze"):
        raise ParameterError(f"distribution {spec!r}: write NAME=LAW:ARG:... with a scipy.stats law "
                             "(norm:LOC:SCALE, uniform:LOW:WIDTH, truncnorm:A:B:LOC:SCALE)", key="samples", value=spec)
    values = _numbers(args, "samples", spec) if args else []
    try:
        frozen = dist(*values)
        frozen.ppf(0.5)
    except (TypeError, ValueError) as exc:
        raise ParameterError(f"distribution {spec!r}: {exc}", key="samples", value=spec) from None
    return name.strip(), frozen
