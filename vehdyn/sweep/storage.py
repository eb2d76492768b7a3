"""Chunked, atomic Parquet storage of a sweep and its resume.

``out="results.parquet"`` is a folder (a Parquet dataset that ``pandas.read_parquet`` reads whole)
holding one file per finished chunk, ``part-<first variant>.parquet``, each written atomically
through :func:`vehdyn._atomic.atomic_write`: an interrupted sweep leaves whole chunks only and
loses at most the chunks in flight. Every row carries its ``variant`` number and its parameter
values; ``resume=True`` reads the finished rows, checks that their parameters are the ones this
sweep would give them (else the folder holds another sweep: :class:`~vehdyn.ParameterError`) and
runs only the others.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from vehdyn._atomic import atomic_write
from vehdyn.errors import ParameterError

__all__ = ["ChunkStore"]


def _require_pyarrow():
    try:
        import pyarrow  # noqa: F401
    except ImportError:  # pragma: no cover - pyarrow is in the test extra
        raise ImportError("writing a sweep to Parquet needs pyarrow: pip install pyarrow") from None


class ChunkStore:
    """The folder of chunk files of one sweep.

    Parameters
    ----------
    path : str or Path
        The dataset folder (created if missing; ``ParameterError`` if it is a file).
    """

    def __init__(self, path):
        _require_pyarrow()
        self.path = Path(path)
        if self.path.exists() and not self.path.is_dir():
            raise ParameterError(f"out={str(path)!r} is a file; a sweep writes a folder of Parquet chunks there",
                                 key="out", value=str(path))
        self.path.mkdir(parents=True, exist_ok=True)

    def parts(self) -> list[Path]:
        return sorted(self.path.glob("part-*.parquet"))

    def clear(self) -> None:
        """Remove the chunk files of an earlier sweep (a fresh, not resumed, sweep)."""
        for p in self.parts():
            p.unlink()

    def write(self, frame) -> Path:
        """Write one finished chunk (a DataFrame with a ``variant`` column) atomically."""
        first = int(frame["variant"].iloc[0])
        target = self.path / f"part-{first:09d}.parquet"
        with atomic_write(target, "wb") as handle:
            frame.to_parquet(handle, index=False)
        return target

    def read(self):
        """All finished rows (an empty frame when none), sorted by variant."""
        import pandas as pd

        parts = self.parts()
        if not parts:
            return pd.DataFrame()
        frame = pd.concat([pd.read_parquet(p) for p in parts], ignore_index=True)
        return frame.sort_values("variant", kind="stable").reset_index(drop=True)

    def done(self, table) -> set[int]:
        """Variant numbers already finished, checked against this sweep's parameter ``table``.

        Parameters
        ----------
        table : pandas.DataFrame
            This sweep's parameters, one row per variant (index = variant number).
        """
        finished = self.read()
        if finished.empty:
            return set()
        ids = finished["variant"].to_numpy(dtype=int)
        missing_cols = [c for c in table.columns if c not in finished.columns]
        bad = ids[(ids < 0) | (ids >= len(table))]
        if missing_cols or bad.size:
            raise ParameterError(f"{self.path} holds another sweep (columns {sorted(finished.columns)}, variants "
                                 f"up to {ids.max()}); remove it or choose another out=", key="out", value=str(self.path))
        for col in table.columns:
            mine = table[col].to_numpy()[ids]
            theirs = finished[col].to_numpy()
            same = mine == theirs if mine.dtype.kind not in "fc" else np.isclose(mine, theirs, rtol=0, atol=0,
                                                                                equal_nan=True)
            if not np.all(same):
                k = int(np.flatnonzero(~np.asarray(same))[0])
                raise ParameterError(f"{self.path} holds another sweep: variant {ids[k]} has {col} = {theirs[k]!r}, "
                                     f"this sweep gives {mine[k]!r}; remove it or choose another out=", key="out",
                                     value=str(self.path))
        return set(ids.tolist())
