"""``vehdyn.sweep.run``: full-factorial grids and Monte Carlo samples of a scene or a function."""

from __future__ import annotations

import itertools
import math
import sys
from typing import Any, Mapping

import numpy as np

from vehdyn.errors import ParameterError
from vehdyn.sweep.engines import RESERVED_COLUMNS, ChunkTask, _is_real, run_chunks
from vehdyn.sweep.targets import as_target

__all__ = ["run", "variants", "run_table", "grid_from_text", "distribution_from_text"]

_SAMPLING = ("lhs", "sobol", "random")
_MAX_COUNT = 10_000_000  # values of one grid dimension written as START:STOP:COUNT


def _check_name(name, what: str) -> None:
    """A parameter or metric name: non-empty text, not one of the table's own columns."""
    if not isinstance(name, str) or not name:
        raise ParameterError(f"{what} name {name!r}: names are non-empty text", key=what, value=name)
    if name in RESERVED_COLUMNS:
        raise ParameterError(f"{what} name {name!r} is one of the sweep table's own columns {list(RESERVED_COLUMNS)}"
                             f" (the variant number, the failure message); rename the {what}", key=name, value=name)


def _metric_list(metrics, key: str = "metrics") -> list[str]:
    """``metrics`` (a name or a sequence of names) as a checked, non-empty list."""
    names = [metrics] if isinstance(metrics, str) else metrics
    try:
        names = list(names)
    except TypeError:
        raise ParameterError(f"{key} = {metrics!r}: give a metric name or a list of them", key=key,
                             value=metrics) from None
    if not names:
        raise ParameterError(f"{key} is empty", key=key, value=metrics)
    for name in names:
        _check_name(name, "metric")
    if len(set(names)) != len(names):
        twice = sorted({n for n in names if names.count(n) > 1})
        raise ParameterError(f"{key} names {twice} twice", key=key, value=twice[0])
    return names


def _grid_values(name, values) -> list:
    if isinstance(values, (str, bytes)) or not np.iterable(values):
        raise ParameterError(f"grid[{name!r}] = {values!r}: must be a sequence of values", key=name, value=values)
    if isinstance(values, np.ndarray):
        if values.ndim != 1:
            raise ParameterError(f"grid[{name!r}]: a 1-D array of values, got shape {values.shape}", key=name,
                                 value=values.shape)
        values = values.tolist()
    values = list(values)
    if not values:
        raise ParameterError(f"grid[{name!r}] is empty", key=name, value=values)
    for k, v in enumerate(values):
        if (_is_real(v) or isinstance(v, (complex, np.complexfloating))) and not np.isfinite(v):
            raise ParameterError(f"grid[{name!r}][{k}] = {v!r}: grid values must be finite numbers", key=name,
                                 value=v)
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
        median = np.asarray(dist.ppf(0.5), dtype=float)
        if median.ndim or not np.isfinite(median):
            raise ParameterError(f"samples[{name!r}]: its median is {median}, not a finite number: the law's "
                                 "parameters are not finite (or not scalars)", key=name, value=dist)
    _check_seed(seed)
    d = len(samples)
    rng = np.random.default_rng(seed)
    if sampling == "lhs":
        u = qmc.LatinHypercube(d=d, rng=rng).random(int(n))
    elif sampling == "sobol":
        u = qmc.Sobol(d=d, scramble=True, rng=rng).random(int(n))
    else:
        u = rng.random((int(n), d))
    return {name: np.asarray(dist.ppf(u[:, j]), dtype=float) for j, (name, dist) in enumerate(samples.items())}


def _check_seed(seed) -> None:
    if seed is not None and (isinstance(seed, (bool, np.bool_)) or not isinstance(seed, (int, np.integer))
                             or seed < 0):
        raise ParameterError(f"seed = {seed!r}: must be None or an integer >= 0", key="seed", value=seed)


def variants(grid: Mapping[str, Any] | None = None, samples: Mapping[str, Any] | None = None, *, n=None,
             sampling: str = "lhs", seed=None):
    """The parameter table of a sweep: one row per variant (index ``variant``).

    Grid points vary slowest (full factorial, the last name fastest); each grid point is combined
    with every sample.

    Parameters
    ----------
    grid : mapping, optional
        Name -> sequence of values (finite numbers, or any values a Scene field takes).
    samples : mapping, optional
        Name -> frozen ``scipy.stats`` distribution, drawn ``n`` times by ``sampling``
        (``"lhs"`` Latin hypercube, ``"sobol"`` scrambled Sobol', ``"random"``) through
        :mod:`scipy.stats.qmc`; the draws are reproducible with ``seed``.
    n : int, optional
        Number of samples (with ``samples``).
    sampling : {"lhs", "sobol", "random"}
        How the samples' unit-hypercube points are drawn.
    seed : int, optional
        Seed of the draws (None: fresh entropy).

    Returns
    -------
    pandas.DataFrame
        One column per parameter (grid names, then sample names), index ``variant``.

    Raises
    ------
    ParameterError
        A name in both grid and samples or one of the table's own columns (``variant``,
        ``error``); an empty, non-finite or malformed grid; a malformed distribution, ``n``,
        ``sampling`` or ``seed``.
    """
    import pandas as pd

    grid, samples = dict(grid or {}), dict(samples or {})
    for name in [*grid, *samples]:
        _check_name(name, "parameter")
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


def run(target, *, grid=None, samples=None, n=None, sampling: str = "lhs", metrics=None, executor=None,
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
        A Parquet folder written chunk by chunk, each chunk atomically, beside a manifest of what
        produced it (:mod:`vehdyn.sweep.storage`, :mod:`vehdyn.sweep.manifest`). It must be new,
        empty or a vehdyn sweep's folder (whose chunks a fresh sweep replaces): a folder holding
        other files is refused, never cleared.
    resume : bool
        With ``out``: run only the variants not yet in it, after checking that the folder's
        manifest is this sweep's (the same target, parameters, design, seed, metrics and vehdyn
        version; else a ParameterError names what differs).
    progress : bool
        A progress bar on stderr.
    seed : int, optional
        Seed of the draws (an integer >= 0). None: fresh entropy, recorded in ``out``'s manifest
        and in ``attrs["seed"]``; ``resume=True`` with ``seed=None`` redraws the recorded seed's
        samples.
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
        ``error`` (None, or ``"ParameterError: ..."`` for a variant that failed, a variant that
        drew a non-finite value included; its metrics are NaN). ``attrs["units"]`` maps columns
        to units; ``attrs["seed"]`` is the seed of the samples' draws.

    Raises
    ------
    ParameterError
        An unknown parameter name (with the close matches) or metric; a parameter or metric named
        like one of the table's own columns (``variant``, ``error``) or a metric named like a
        parameter; a malformed or non-finite grid value, a malformed distribution, ``n``,
        ``sampling`` or ``seed``; an ``out`` folder holding files no vehdyn sweep wrote, or
        (``resume``) another sweep's.

    Examples
    --------
    >>> import vehdyn, scipy.stats as st
    >>> scene = vehdyn.Scene(vehicle="sedan", manoeuvre="step_steer", speed=25.0, duration=3.0,
    ...                      manoeuvre_parameters={"lateral_acceleration": 3.0})
    >>> table = vehdyn.sweep.run(scene, grid={"speed": [20.0, 30.0]},
    ...                          samples={"vehicle.mass.mass": st.norm(1500, 50)}, n=4,
    ...                          metrics=["peak_yaw_rate", "understeer_gradient"], progress=False, seed=1)
    >>> table.shape
    (8, 5)
    >>> list(table.columns)
    ['speed', 'vehicle.mass.mass', 'peak_yaw_rate', 'understeer_gradient', 'error']
    >>> bool(table["error"].isna().all())
    True

    A function of named parameters, over a grid:

    >>> def stopping(speed, deceleration):
    ...     return {"distance": speed ** 2 / (2 * deceleration), "time": speed / deceleration}
    >>> table = vehdyn.sweep.run(stopping, grid={"speed": [20.0, 30.0], "deceleration": [8.0]}, progress=False)
    >>> table  # doctest: +NORMALIZE_WHITESPACE
             speed  deceleration  distance  time error
    variant
    0         20.0           8.0     25.00  2.50  None
    1         30.0           8.0     56.25  3.75  None
    """
    if resume and out is None:
        raise ParameterError("resume=True needs out=, the folder to resume", key="resume", value=resume)
    if samples and seed is None:  # a seed recorded, so that the draws can be redrawn by resume=True
        from vehdyn.sweep.storage import ChunkStore

        seed = ChunkStore.recorded_seed(out) if resume else None
        if seed is None:
            seed = int(np.random.SeedSequence().entropy)
    table = variants(grid, samples, n=n, sampling=sampling, seed=seed)
    design = {"grid": dict(grid or {}), "samples": dict(samples or {}), "n": n, "sampling": sampling if samples
              else None, "seed": seed if samples else None}
    frame = run_table(target, table, metrics=metrics, executor=executor, chunk_size=chunk_size, out=out,
                      resume=resume, progress=progress, model=model, solver=solver, design=design)
    if samples:
        frame.attrs["seed"] = seed
    return frame


def run_table(target, table, *, metrics=None, executor=None, chunk_size=None, out=None, resume=False,
              progress=True, model="auto", solver=None, design=None):
    """Run the variants of a parameter ``table`` (one row per variant, a column per parameter).

    The engine of :func:`run` (which builds the table from a grid and samples) and of
    :func:`vehdyn.sweep.sensitivity` (SALib's designs).

    Parameters
    ----------
    target : Scene, callable, SceneTarget or FunctionTarget
        As for :func:`run`.
    table : pandas.DataFrame
        One row per variant, one column per parameter (its index is replaced by 0, 1, ...).
    metrics : str or sequence of str, optional
        As for :func:`run`.
    executor : None, str, Executor or dask.distributed.Client
        As for :func:`run`.
    chunk_size : int, optional
        As for :func:`run`.
    out : str or Path, optional
        As for :func:`run`.
    resume : bool
        As for :func:`run`.
    progress : bool
        As for :func:`run`.
    model : str
        As for :func:`run`.
    solver : mapping, optional
        As for :func:`run`.
    design : mapping, optional
        How ``table`` was made (e.g. ``{"grid": ..., "samples": ..., "n": ..., "seed": ...}``),
        recorded in ``out``'s manifest; the table's own hash is recorded in any case.

    Returns
    -------
    pandas.DataFrame
        As for :func:`run`.

    Raises
    ------
    ParameterError
        As for :func:`run`.
    """
    import pandas as pd

    if resume and out is None:
        raise ParameterError("resume=True needs out=, the folder to resume", key="resume", value=resume)
    t = as_target(target, model, solver)
    table = table.reset_index(drop=True)
    names = list(table.columns)
    for name in names:
        _check_name(name, "parameter")
    units = dict(t.check_names(names))
    metric_names = t.default_metrics() if metrics is None else _metric_list(metrics)
    if metric_names is not None:
        clash = [m for m in metric_names if m in names]
        if clash:
            raise ParameterError(f"metric {clash[0]!r} has a parameter's name: the two would share a column",
                                 key=clash[0], value=clash[0])
        units.update(t.resolve_metrics(metric_names))
    store = None
    todo = np.arange(len(table))
    if out is not None:
        from vehdyn import __version__
        from vehdyn.sweep.manifest import describe
        from vehdyn.sweep.storage import ChunkStore

        store = ChunkStore(out)
        manifest = describe(target=t.identity(), parameters=names, metrics=metric_names, design=design, table=table,
                            version=__version__)
        done = store.open(manifest, table, resume)
        if done:
            todo = todo[~np.isin(todo, np.fromiter(done, dtype=int, count=len(done)))]
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
        values = [float(v) for v in text.split(":" if ":" in text else ",")]
    except ValueError:
        raise ParameterError(f"{what} {spec!r}: values must be numbers", key=what, value=spec) from None
    if not all(math.isfinite(v) for v in values):
        raise ParameterError(f"{what} {spec!r}: values must be finite numbers", key=what, value=spec)
    return values


def grid_from_text(spec: str) -> tuple[str, list]:
    """A grid from the command line's text.

    Parameters
    ----------
    spec : str
        ``"speed=10:40:7"`` (START:STOP:COUNT, linearly spaced) or ``"speed=10,20,40"``.

    Returns
    -------
    tuple
        ``(name, values)``.

    Raises
    ------
    ParameterError
        Malformed text, or values that are not finite numbers.
    """
    name, sep, text = spec.partition("=")
    if not sep or not name.strip() or not text.strip():
        raise ParameterError(f"grid {spec!r}: write NAME=START:STOP:COUNT or NAME=V1,V2,...", key="grid", value=spec)
    if ":" in text:
        parts = _numbers(text, "grid", spec)
        if len(parts) != 3 or not 1 <= parts[2] <= _MAX_COUNT or parts[2] != int(parts[2]):
            raise ParameterError(f"grid {spec!r}: START:STOP:COUNT with an integer COUNT from 1 to {_MAX_COUNT:,}",
                                 key="grid", value=spec)
        return name.strip(), np.linspace(parts[0], parts[1], int(parts[2])).tolist()
    return name.strip(), _numbers(text, "grid", spec)


def distribution_from_text(spec: str):
    """A distribution from the command line's text.

    Parameters
    ----------
    spec : str
        ``"NAME=LAW:ARG:..."``: a ``scipy.stats`` distribution name and its positional parameters
        (shape parameters, loc, scale), e.g. ``"vehicle.mass.mass=norm:1500:50"``.

    Returns
    -------
    tuple
        ``(name, frozen distribution)``, e.g. ``("vehicle.mass.mass", scipy.stats.norm(1500, 50))``.

    Raises
    ------
    ParameterError
        Malformed text, an unknown law, parameters the law refuses or that are not finite.
    """
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
