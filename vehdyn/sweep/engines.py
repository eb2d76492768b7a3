"""Sweep engines: where the chunks of variants run.

All engines run the same :class:`ChunkTask` on the same chunks, so that they give bitwise the
same metrics; they differ only in where a chunk runs:

``None``
    In this process, chunk after chunk. A :func:`~vehdyn.sweep.vectorized` function gets each
    chunk as one batch of arrays; a Scene's variants in a chunk run their simulations through
    :func:`vehdyn.simulate.simulate_many` (those of one model structure as one compiled batch on
    every core, bitwise their single runs) - in every engine, since all run the same task.
``"processes"``
    A :class:`concurrent.futures.ProcessPoolExecutor` on every core, one chunk per task.
``"threads"``
    A :class:`concurrent.futures.ThreadPoolExecutor` (for targets that release the GIL).
any :class:`concurrent.futures.Executor`
    The caller's executor (left running).
a ``dask.distributed.Client`` (or a scheduler address ``"tcp://host:8786"``)
    Chunks as Dask tasks on the cluster's workers (optional extra ``vehdyn[distributed]``).
"""

from __future__ import annotations

import concurrent.futures as cf
import math
import os
from typing import Any, Callable, Sequence

import numpy as np

from vehdyn.errors import ParameterError

__all__ = ["ChunkTask", "run_chunks", "is_dask_client", "chunk_frame", "RESERVED_COLUMNS"]

#: The sweep table's own columns (the index ``variant`` and ``error``): no parameter or metric may
#: take their names.
RESERVED_COLUMNS = ("variant", "error")


def _is_real(value) -> bool:
    """True for a real number of any kind (Python or numpy, float32 included), False for a bool."""
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, (bool, np.bool_))


def _message(exc: BaseException) -> str:
    return f"{type(exc).__name__}: {exc}"


def _not_finite(names, rows) -> dict[int, str]:
    """Row position -> why, for the rows holding a parameter value that is a non-finite number
    (a NaN or an infinite draw of a distribution): those variants fail in their row, unrun."""
    bad: dict[int, str] = {}
    for j, name in enumerate(names):
        column = [r[j] for r in rows]
        try:
            values = np.asarray(column)
        except ValueError:  # ragged values (sequences of different lengths): none is a number
            continue
        if values.ndim == 1 and values.dtype.kind in "fc":
            flags = ~np.isfinite(values)
        elif values.dtype.kind in "fcO":
            flags = np.array([_is_real(v) and not math.isfinite(v) for v in column], dtype=bool)
        else:
            continue
        for k in np.flatnonzero(flags):
            value = column[k].item() if isinstance(column[k], np.generic) else column[k]
            bad.setdefault(int(k), f"ParameterError: parameter {name!r} = {value!r} is not a finite number (a draw of "
                                   "its distribution?); the variant was not run")
    return bad


def chunk_frame(columns: dict, names, metric_names):
    """A chunk's DataFrame: ``variant``, the parameters, the metrics (float), ``error`` (None or text).

    Parameters
    ----------
    columns : dict
        Column name -> values: ``variant``, the parameters, the metrics and ``error``.
    names : sequence of str
        Parameter names.
    metric_names : sequence of str or None
        Metric names (None: every other column).

    Returns
    -------
    pandas.DataFrame
    """
    import pandas as pd

    frame = pd.DataFrame(columns)
    metric_cols = list(metric_names) if metric_names is not None else \
        [c for c in frame.columns if c not in ("variant", "error", *names)]
    for c in metric_cols:
        frame[c] = frame[c].astype(float) if c in frame.columns else np.nan
    frame["error"] = frame["error"].astype(object).where(frame["error"].notna(), None)
    return frame[["variant", *names, *metric_cols, "error"]]


class ChunkTask:
    """Run one chunk of variants: ``task(ids, rows) -> DataFrame`` (:func:`chunk_frame`).

    A variant whose parameters hold a non-finite number is not run: its row carries the reason.

    Parameters
    ----------
    target : SceneTarget or FunctionTarget
        What each variant runs.
    names : sequence of str
        Parameter names (the order of each row's values).
    metrics : sequence of str or None
        Metric names (None: every key a function returns).
    """

    def __init__(self, target, names: Sequence[str], metrics):
        self.target, self.names, self.metrics = target, list(names), metrics

    def _one(self, variant: int, row) -> dict:
        params = dict(zip(self.names, row))
        record = {"variant": int(variant), **params}
        try:
            record.update(self.target.run(params, self.metrics))
            record["error"] = None
        except Exception as exc:  # one bad variant never loses the sweep
            record["error"] = _message(exc)
        return record

    def _many(self, ids, rows, block: int = 256) -> list[dict]:
        """Records of a chunk whose simulations run batched (blocks of ``block`` variants bound
        the memory of the batched outputs)."""
        records = []
        for k in range(0, len(rows), block):
            params = [dict(zip(self.names, row)) for row in rows[k:k + block]]
            for variant, p, values in zip(ids[k:k + block], params, self.target.run_many(params, self.metrics)):
                record = {"variant": int(variant), **p}
                if isinstance(values, Exception):
                    record["error"] = _message(values)
                else:
                    record.update(values)
                    record["error"] = None
                records.append(record)
        return records

    def __call__(self, ids: Sequence[int], rows: Sequence[tuple]):
        """The chunk's frame (:func:`chunk_frame`), one row per variant in the order given.

        Parameters
        ----------
        ids : sequence of int
            Variant numbers.
        rows : sequence of tuple
            Each variant's parameter values, in the order of ``names``.

        Returns
        -------
        pandas.DataFrame
        """
        import pandas as pd

        bad = _not_finite(self.names, rows)
        if bad:
            keep = [k for k in range(len(rows)) if k not in bad]
            records = pd.DataFrame.from_records([{"variant": int(ids[k]), **dict(zip(self.names, rows[k])),
                                                  "error": why} for k, why in bad.items()])
            frames = [self._run([ids[k] for k in keep], [rows[k] for k in keep])] if keep else []
            frames.append(chunk_frame({c: records[c] for c in records.columns}, self.names, self.metrics))
            frame = pd.concat(frames, ignore_index=True).sort_values("variant", kind="stable")
            return frame[[c for c in frame.columns if c != "error"] + ["error"]].reset_index(drop=True)
        return self._run(ids, rows)

    def _run(self, ids, rows):
        import pandas as pd

        if getattr(self.target, "vectorized", False) and len(rows) > 1:
            columns = {n: np.asarray([r[j] for r in rows]) for j, n in enumerate(self.names)}
            try:
                values = self.target.run_batch(columns, len(rows), self.metrics)
            except Exception:  # find the bad variants one by one
                pass
            else:
                data = {"variant": np.asarray(ids, dtype=np.int64), **columns, **values, "error": [None] * len(rows)}
                return chunk_frame(data, self.names, self.metrics)
        if hasattr(self.target, "run_many") and len(rows) > 1:
            records = pd.DataFrame.from_records(self._many(ids, rows))
        else:
            records = pd.DataFrame.from_records([self._one(i, r) for i, r in zip(ids, rows)])
        return chunk_frame({c: records[c] for c in records.columns}, self.names, self.metrics)


def _run_task(task: ChunkTask, ids, rows):
    """``task(ids, rows)``: a Dask task whose ``task`` argument is scattered to the workers once."""
    return task(ids, rows)


def is_dask_client(executor) -> bool:
    """True for a ``dask.distributed.Client`` (checked without importing dask).

    Parameters
    ----------
    executor : object

    Returns
    -------
    bool
    """
    return type(executor).__module__.startswith("distributed") and hasattr(executor, "scheduler_info")


def _dask_client(address: str):
    try:
        from distributed import Client
    except ImportError:
        raise ParameterError(f"executor={address!r} names a Dask scheduler; install the extra: "
                             "pip install 'vehdyn[distributed]'", key="executor", value=address) from None
    return Client(address)


def run_chunks(task: ChunkTask, chunks: list[tuple[list[int], list[tuple]]], executor: Any,
               on_done: Callable[[Any], None]) -> None:
    """Run ``task`` on every chunk with ``executor`` and call ``on_done(frame)`` as each finishes.

    Finished chunks are handed over in completion order (the caller writes them); an engine failure
    (a worker lost) raises after the chunks finished before it were handed over.

    Parameters
    ----------
    task : ChunkTask
        What each chunk runs.
    chunks : list of (list of int, list of tuple)
        Each chunk's variant numbers and parameter rows.
    executor : None, str, Executor or dask.distributed.Client
        The engine (module docstring).
    on_done : callable
        ``on_done(frame)`` with each finished chunk's frame.

    Returns
    -------
    None
    """
    if not chunks:
        return
    if executor is None:
        for ids, rows in chunks:
            on_done(task(ids, rows))
        return
    owned = None
    if isinstance(executor, str):
        if executor == "processes":
            owned = executor = cf.ProcessPoolExecutor(max_workers=min(len(chunks), os.cpu_count() or 1))
        elif executor == "threads":
            owned = executor = cf.ThreadPoolExecutor(max_workers=min(len(chunks), os.cpu_count() or 1))
        elif "://" in executor:
            owned = executor = _dask_client(executor)
        else:
            raise ParameterError(f"executor={executor!r}: use None, 'processes', 'threads', a scheduler address "
                                 "('tcp://host:8786'), a concurrent.futures.Executor or a dask.distributed.Client",
                                 key="executor", value=executor)
    try:
        if is_dask_client(executor):
            from distributed import as_completed

            # the task (target, base model, metrics) goes to every worker once, not with every chunk
            shared = executor.scatter(task, broadcast=True, hash=False) if len(chunks) > 1 else task
            futures = [executor.submit(_run_task, shared, ids, rows, pure=False) for ids, rows in chunks]
            for future in as_completed(futures):
                on_done(future.result())
        elif isinstance(executor, cf.Executor):
            futures = [executor.submit(task, ids, rows) for ids, rows in chunks]
            try:
                for future in cf.as_completed(futures):
                    on_done(future.result())
            except BaseException:
                for f in futures:
                    f.cancel()
                raise
        else:
            raise ParameterError(f"executor must be None, 'processes', 'threads', a scheduler address, a "
                                 f"concurrent.futures.Executor or a dask.distributed.Client, got "
                                 f"{type(executor).__name__}", key="executor", value=type(executor).__name__)
    finally:
        if owned is not None:
            if is_dask_client(owned):
                owned.close()
            else:
                owned.shutdown(wait=True, cancel_futures=True)
