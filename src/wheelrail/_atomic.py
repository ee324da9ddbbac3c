"""Crash-safe output files (private): write to a temporary file, then rename.

A reader never sees a half-written file: the data go to a temporary file in
the target directory, which is flushed, synced and then renamed over the
target (``os.replace`` is atomic on POSIX and Windows). On any error — a full
disk, an interrupted run — the temporary file is removed and the target is
left as it was.
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from pathlib import Path

from .errors import InputError

__all__ = ["atomic_path", "atomic_open", "check_output_path"]


def _file_mode(path: Path) -> int:
    """Mode of the file being replaced, else 0o666 less the umask (mkstemp uses 0o600)."""
    try:
        return os.stat(path).st_mode & 0o7777
    except OSError:
        mask = os.umask(0)
        os.umask(mask)
        return 0o666 & ~mask


@contextlib.contextmanager
def atomic_path(path):
    """Yield a temporary path beside ``path``; rename it to ``path`` if the block succeeds.

    For writers that take a file name (matplotlib, xarray). The temporary
    name keeps the suffix, so format detection by extension still works.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=f".tmp{path.suffix}",
                               dir=path.parent)
    os.close(fd)
    try:
        yield Path(tmp)
        os.chmod(tmp, _file_mode(path))
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


@contextlib.contextmanager
def atomic_open(path, mode="w", **kwargs):
    """``open`` a temporary file beside ``path``; on success sync it and rename it to ``path``."""
    with atomic_path(path) as tmp:
        with open(tmp, mode, **kwargs) as fh:
            yield fh
            fh.flush()
            os.fsync(fh.fileno())


def check_output_path(path, *, what="output", suffixes=None) -> Path:
    """Check before a long computation that ``path`` can be written.

    Parameters
    ----------
    path : path-like
    what : str
        Name used in the message (e.g. ``"--json"``).
    suffixes : iterable of str, optional
        Allowed extensions (lower case, with the dot).

    Raises
    ------
    InputError
        The extension is not allowed, the path is a directory, or the
        directory cannot be created or written.
    """

    path = Path(path)
    if suffixes is not None and path.suffix.lower() not in tuple(suffixes):
        raise InputError(f"{what} {str(path)!r}: unsupported file type {path.suffix or '(none)'!r}; "
                         f"use one of {', '.join(sorted(suffixes))}")
    if path.is_dir():
        raise InputError(f"{what} {str(path)!r} is a directory, not a file")
    parent = path.parent
    existing = parent
    while not existing.exists():
        existing = existing.parent
    if not existing.is_dir():
        raise InputError(f"{what} {str(path)!r}: {str(existing)!r} is not a directory")
    try:  # the only reliable test (root, read-only mounts, /proc): create a file there
        fd, probe = tempfile.mkstemp(prefix=".wheelrail-probe.", dir=existing)
    except OSError as exc:
        raise InputError(f"{what} {str(path)!r}: cannot write in directory {str(existing)!r} "
                         f"({exc.strerror or exc})") from None
    os.close(fd)
    with contextlib.suppress(OSError):
        os.unlink(probe)
    return path
