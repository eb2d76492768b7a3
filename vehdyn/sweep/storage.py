"""Chunked, atomic Parquet storage of a sweep, its manifest and its resume.

``out="results.parquet"`` is a folder (a Parquet dataset that ``pandas.read_parquet`` reads whole)
holding one file per finished chunk, ``part-<first variant>.parquet``, each written atomically
through :func:`vehdyn._atomic.atomic_write`: an interrupted sweep leaves whole chunks only and
loses at most the chunks in flight. Every row carries its ``variant`` number and its parameter
values.

The folder also holds the sweep's manifest, ``_vehdyn_sweep.json`` (:mod:`vehdyn.sweep.manifest`:
what produced the rows; Parquet readers skip names that begin with ``_``), and every chunk file
carries the manifest's ``id`` in its Parquet metadata. So a sweep knows which files it wrote:

* a folder that does not exist or is empty becomes the sweep's;
* a folder holding any file or folder that no vehdyn sweep wrote (a user's Parquet dataset, notes,
  partitions) is refused, resumed or not: a sweep never deletes, overwrites or mixes in files it
  did not write (names beginning with ``.`` - temporary files, the desktop's - are left alone);
* a fresh sweep (``resume=False``) into a folder of a vehdyn sweep replaces its chunk files and
  its manifest;
* ``resume=True`` goes on only when the folder's manifest is this sweep's (else the
  :class:`~vehdyn.ParameterError` names what differs: the scene's speed, the metrics, the seed,
  ...) and its chunk files carry that manifest's id, then runs only the variants not yet in it.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np

from vehdyn._atomic import atomic_write, atomic_write_text
from vehdyn.errors import ParameterError
from vehdyn.sweep.manifest import FORMAT, differences

__all__ = ["ChunkStore", "MANIFEST"]

#: The manifest's file name in a results folder.
MANIFEST = "_vehdyn_sweep.json"
_PART = re.compile(r"part-\d{9}\.parquet")
_KEY = b"vehdyn.sweep"  # the Parquet metadata key holding the manifest id


def _require_pyarrow():
    try:
        import pyarrow  # noqa: F401
    except ImportError:  # pragma: no cover - pyarrow is in the test extra
        raise ImportError("writing a sweep to Parquet needs pyarrow: pip install pyarrow") from None


def _part_id(path: Path) -> str | None:
    """The manifest id in a chunk file's metadata; None for a file no vehdyn sweep wrote."""
    import pyarrow.parquet as pq

    try:
        meta = pq.read_schema(path).metadata or {}
    except Exception:  # not a Parquet file: not ours
        return None
    value = meta.get(_KEY)
    return None if value is None else value.decode()


def _names(paths, limit: int = 4) -> str:
    names = sorted(p.name + ("/" if p.is_dir() else "") for p in paths)
    return ", ".join(names[:limit]) + (f" and {len(names) - limit} more" if len(names) > limit else "")


def _value_difference(finished, table) -> str | None:
    """The first finished variant whose parameter values differ from this sweep's ``table``."""
    if finished.empty:
        return None
    ids = finished["variant"].to_numpy(dtype=int)
    inside = (ids >= 0) & (ids < len(table))
    for col in table.columns:
        if col not in finished.columns:
            continue
        mine = table[col].to_numpy()[ids[inside]]
        theirs = finished[col].to_numpy()[inside]
        same = mine == theirs if mine.dtype.kind not in "fc" else np.isclose(mine, theirs, rtol=0, atol=0,
                                                                            equal_nan=True)
        if not np.all(same):
            k = int(np.flatnonzero(~np.asarray(same))[0])
            return f"variant {ids[inside][k]} has {col} = {theirs[k]!r} in the folder, {mine[k]!r} here"
    return None


class ChunkStore:
    """The folder of chunk files of one sweep.

    Parameters
    ----------
    path : str or Path
        The dataset folder (created by :meth:`open` if missing; ``ParameterError`` if it is a
        file).
    """

    def __init__(self, path):
        _require_pyarrow()
        self.path = Path(path)
        if self.path.exists() and not self.path.is_dir():
            raise ParameterError(f"out={str(path)!r} is a file; a sweep writes a folder of Parquet chunks there",
                                 key="out", value=str(path))
        self.id: str | None = None

    def _refuse(self, text: str) -> ParameterError:
        return ParameterError(f"out={str(self.path)!r} {text}", key="out", value=str(self.path))

    @staticmethod
    def recorded_seed(path) -> int | None:
        """The seed of the sample design recorded in the manifest of folder ``path`` (None when
        there is none): what ``resume=True`` redraws an unseeded sweep's samples with.

        Parameters
        ----------
        path : str or Path
            A results folder.

        Returns
        -------
        int or None
        """
        try:
            manifest = json.loads((Path(path) / MANIFEST).read_text(encoding="utf-8"))
            seed = manifest["design"]["seed"]
        except (OSError, ValueError, KeyError, TypeError):
            return None
        return seed if isinstance(seed, int) and not isinstance(seed, bool) else None

    def _survey(self):
        """(manifest or None, [(chunk file, its id)], [foreign entries]) of the folder."""
        if not self.path.exists():
            return None, [], []
        manifest, parts, foreign = None, [], []
        for entry in self.path.iterdir():
            if entry.name.startswith("."):
                continue  # temporary files of atomic writes, the desktop's files: never touched
            if entry.name == MANIFEST and entry.is_file():
                try:
                    manifest = json.loads(entry.read_text(encoding="utf-8"))
                except (OSError, ValueError):
                    manifest = None
                if isinstance(manifest, dict) and manifest.get("written_by") == "vehdyn.sweep":
                    continue
                manifest = None
                foreign.append(entry)
            elif entry.is_file() and _PART.fullmatch(entry.name) and (ident := _part_id(entry)) is not None:
                parts.append((entry, ident))
            else:
                foreign.append(entry)
        return manifest, parts, foreign

    def open(self, manifest: dict, table, resume: bool) -> set[int]:
        """Make the folder this sweep's and return the variants already finished in it.

        Parameters
        ----------
        manifest : dict
            This sweep's manifest (:func:`vehdyn.sweep.manifest.describe`).
        table : pandas.DataFrame
            This sweep's parameters, one row per variant (index = variant number).
        resume : bool
            Keep the finished chunks (after checking they are this sweep's) instead of
            replacing them.

        Returns
        -------
        set of int
            The finished variants (empty for a fresh sweep).

        Raises
        ------
        ParameterError
            The folder holds files no vehdyn sweep wrote, or (``resume``) another sweep's.
        """
        stored, parts, foreign = self._survey()
        if foreign:
            raise self._refuse(f"holds files that no vehdyn sweep wrote ({_names(foreign)}); a sweep writes only into "
                               "a new or empty folder or one it wrote, and never deletes or mixes in other files: "
                               "choose another out=")
        self.id = manifest["id"]
        done: set[int] = set()
        if resume:
            if stored is not None and stored.get("id") != manifest["id"]:
                raise self._refuse(self._another(stored, manifest, table))
            alien = [p for p, ident in parts if ident != manifest["id"]]
            if alien:
                raise self._refuse(f"holds chunk files of another sweep ({_names(alien)}) beside "
                                   f"{'its manifest' if stored else 'no manifest'}; run without resume=True to "
                                   "replace them, or choose another out=")
            done = self.done(table)
        else:
            for p, _ in parts:  # chunk files a vehdyn sweep wrote: a fresh sweep replaces them
                p.unlink()
        self.path.mkdir(parents=True, exist_ok=True)
        if stored != manifest:
            atomic_write_text(self.path / MANIFEST, json.dumps(manifest, indent=1, sort_keys=True) + "\n")
        return done

    def _another(self, stored: dict, manifest: dict, table) -> str:
        lines = differences(stored, manifest)
        if stored.get("format") != FORMAT:
            lines = [f"format: {stored.get('format')!r} in the folder (a vehdyn sweep of another version), "
                     f"{FORMAT} here"]
        metrics_only = [k for k in lines if not k.startswith("metrics")] == []
        if metrics_only:
            return (f"holds this sweep with the metrics {stored.get('metrics')}, not {manifest.get('metrics')}: "
                    "resume=True cannot add metrics to finished variants (their runs would be needed again, "
                    "which is a fresh sweep) nor leave holes; resume with "
                    f"metrics={stored.get('metrics')}, or run without resume=True to replace the folder, or "
                    "choose another out=")
        if [k for k in lines if not k.startswith("table_sha256")] == []:
            lines = [_value_difference(self.read(), table) or "the parameter values differ"]
        return ("holds another sweep: " + "; ".join(lines) + ". Resume it with the same target, parameters, "
                "design and metrics, run without resume=True to replace it, or choose another out=")

    def parts(self) -> list[Path]:
        """The chunk files in the folder, in variant order.

        Returns
        -------
        list of Path
        """
        return sorted(self.path.glob("part-*.parquet")) if self.path.exists() else []

    def write(self, frame) -> Path:
        """Write one finished chunk atomically, tagged with the manifest's id.

        Parameters
        ----------
        frame : pandas.DataFrame
            The chunk's rows, with a ``variant`` column.

        Returns
        -------
        Path
            The chunk file, ``part-<first variant>.parquet``.
        """
        import pyarrow as pa
        import pyarrow.parquet as pq

        first = int(frame["variant"].iloc[0])
        target = self.path / f"part-{first:09d}.parquet"
        data = pa.Table.from_pandas(frame, preserve_index=False)
        data = data.replace_schema_metadata({**(data.schema.metadata or {}), _KEY: (self.id or "").encode()})
        with atomic_write(target, "wb") as handle:
            pq.write_table(data, handle)
        return target

    def read(self):
        """All finished rows (an empty frame when none), sorted by variant.

        Returns
        -------
        pandas.DataFrame
        """
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

        Returns
        -------
        set of int

        Raises
        ------
        ParameterError
            A finished row's variant number or parameter values are not this sweep's, or a
            variant is in two chunk files.
        """
        finished = self.read()
        if finished.empty:
            return set()
        ids = finished["variant"].to_numpy(dtype=int)
        missing_cols = [c for c in table.columns if c not in finished.columns]
        bad = ids[(ids < 0) | (ids >= len(table))]
        if missing_cols or bad.size:
            raise self._refuse(f"holds another sweep (columns {sorted(finished.columns)}, variants up to "
                               f"{ids.max()}); remove it or choose another out=")
        if np.unique(ids).size != ids.size:
            raise self._refuse("holds a variant in two chunk files; remove the folder or choose another out=")
        difference = _value_difference(finished, table)
        if difference is not None:
            raise self._refuse(f"holds another sweep: {difference}; remove it or choose another out=")
        return set(ids.tolist())
