"""Atomic file writes: a reader sees the old file or the new one, never a torn one.

Every file vehdyn writes (``.tir`` files, report pages, figures, tables, sweep chunks) goes through
:func:`atomic_write`: the content is written to a temporary file in the destination's directory,
flushed and fsync'ed, then moved over the destination with :func:`os.replace`, which POSIX and
Windows make atomic within one file system. An interrupted or failed write (disk full, an exception
in the writer, a signal) removes the temporary file and leaves the old destination untouched.
Concurrent writers to one path: the last ``os.replace`` wins, each reader sees one whole file.
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from pathlib import Path

__all__ = ["atomic_write", "atomic_write_text", "atomic_write_bytes"]


@contextlib.contextmanager
def atomic_write(path, mode: str = "w", *, encoding: str | None = "utf-8", newline: str | None = None):
    """Open a temporary file beside ``path`` and move it over ``path`` when the block succeeds.

    Parameters
    ----------
    path : str or os.PathLike
        Destination file; its directory must exist.
    mode : {"w", "wb"}
        Text or binary.
    encoding, newline : str, optional
        As for :func:`open` in text mode.

    Yields
    ------
    file object
        The open temporary file. For writers that want a path (``matplotlib``'s ``savefig``,
        ``pandas``' ``to_parquet``), use ``handle.name``: the temporary file's path, with the
        destination's suffix so that format inference works.
    """
    if mode not in ("w", "wb"):
        raise ValueError(f"atomic_write: mode must be 'w' or 'wb', got {mode!r}")
    path = Path(path)
    directory = path.parent if str(path.parent) else Path(".")
    fd, tmp_name = tempfile.mkstemp(prefix=f".{path.name}.", suffix=f".tmp{path.suffix}", dir=directory)
    try:
        os.close(fd)  # reopened by name, so that ``handle.name`` is the temporary file's path
        if "b" in mode:
            handle = open(tmp_name, mode)
        else:
            handle = open(tmp_name, mode, encoding=encoding, newline=newline)
        with handle:
            yield handle
            handle.flush()
            os.fsync(handle.fileno())
        keep_permissions(path, tmp_name)
        os.replace(tmp_name, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp_name)
        raise


def keep_permissions(path: Path, tmp_name: str, default: int = 0o666) -> None:
    """Give the new file the old one's mode, or the umask's default for a new file (mkstemp: 0600).

    ``default=0o777`` does the same for a folder made by :func:`tempfile.mkdtemp` (0700).
    """
    try:
        mode = os.stat(path).st_mode & 0o777
    except OSError:
        umask = os.umask(0)
        os.umask(umask)
        mode = default & ~umask
    with contextlib.suppress(OSError):
        os.chmod(tmp_name, mode)


def atomic_write_text(path, text: str, *, encoding: str = "utf-8") -> Path:
    """Write ``text`` to ``path`` atomically; returns the path."""
    with atomic_write(path, "w", encoding=encoding) as handle:
        handle.write(text)
    return Path(path)


def atomic_write_bytes(path, data: bytes) -> Path:
    """Write ``data`` to ``path`` atomically; returns the path."""
    with atomic_write(path, "wb") as handle:
        handle.write(data)
    return Path(path)
