"""TOML input with messages that name the file, the table, the key and the value (private).

Shared by the case-file reader (:mod:`wheelrail.cases.files`) and the sweep
specification (:mod:`wheelrail.sweeps.spec`); it knows nothing of wheelrail's
types, only of numbers, strings and tables.
"""

from __future__ import annotations

import math
import warnings
from pathlib import Path
from typing import Mapping

from .errors import CaseFileError

try:  # Python >= 3.11
    import tomllib
except ModuleNotFoundError:  # pragma: no cover - Python 3.10
    import tomli as tomllib

__all__ = ["Reader", "read_toml", "read_input", "tomllib", "MAX_INPUT_BYTES",
           "RenamedKeyWarning", "renamed_keys"]

#: Largest input file read [bytes] (a case with a 100 000-point table is about 10 MB).
MAX_INPUT_BYTES = 64 * 2**20


def read_input(path, what: str = "case file", max_bytes: int | None = None) -> bytes:
    """The bytes of the regular file ``path``; CaseFileError naming it for anything else.

    A FIFO would block for ever, ``/dev/zero`` would be read until memory runs
    out and a directory cannot be read: only regular files of at most
    ``max_bytes`` (default :data:`MAX_INPUT_BYTES`) are accepted, checked with
    ``stat`` before the file is opened.
    """
    import os
    import stat

    if max_bytes is None:
        max_bytes = MAX_INPUT_BYTES
    source = str(path)
    try:
        st = os.stat(path)
    except FileNotFoundError:
        raise CaseFileError(f"{source}: {what} not found") from None
    except OSError as exc:
        raise CaseFileError(f"{source}: cannot read {what}: {exc.strerror or exc}") from None
    if stat.S_ISDIR(st.st_mode):
        raise CaseFileError(f"{source}: is a directory, not a {what}")
    if not stat.S_ISREG(st.st_mode):
        kind = ("a FIFO (named pipe)" if stat.S_ISFIFO(st.st_mode) else
                "a device" if stat.S_ISCHR(st.st_mode) or stat.S_ISBLK(st.st_mode) else
                "a socket" if stat.S_ISSOCK(st.st_mode) else "not a regular file")
        raise CaseFileError(f"{source}: is {kind}; a {what} must be a regular file")
    if st.st_size > max_bytes:
        raise CaseFileError(f"{source}: {st.st_size / 2**20:.0f} MiB is too large for a {what} "
                            f"(at most {max_bytes / 2**20:.0f} MiB)")
    try:
        with open(path, "rb") as fh:
            data = fh.read(max_bytes + 1)
    except OSError as exc:
        raise CaseFileError(f"{source}: cannot read {what}: {exc.strerror or exc}") from None
    if len(data) > max_bytes:  # grew while being read
        raise CaseFileError(f"{source}: too large for a {what} (at most "
                            f"{max_bytes / 2**20:.0f} MiB)")
    return data


def read_toml(path_or_str):
    """``(data, source)`` of a case given as a path or as TOML text; CaseFileError if unreadable."""
    if isinstance(path_or_str, str) and ("\n" in path_or_str or "=" in path_or_str):
        text, source = path_or_str, "<string>"
    else:
        path = Path(path_or_str)
        source = str(path)
        try:
            text = read_input(path).decode("utf-8")
        except UnicodeDecodeError as exc:
            raise CaseFileError(f"{source}: cannot read case file: {exc}") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise CaseFileError(f"{source}: malformed TOML: {exc}") from None
    return data, source

class RenamedKeyWarning(DeprecationWarning):
    """A case file uses a key's former name (read for now; the message names the new key)."""


# shown once per place by default (a DeprecationWarning from a library is hidden otherwise):
# files written before the renaming still read, and their users learn the new name
warnings.filterwarnings("default", category=RenamedKeyWarning)


def renamed_keys(r: "Reader", table: str, tbl: Mapping, renames: Mapping) -> dict:
    """``tbl`` with former key names replaced by the current ones (RenamedKeyWarning each).

    Giving both names of one key is an error naming both.
    """
    out = dict(tbl)
    for old, new in renames.items():
        if old not in out:
            continue
        if new in out:
            r.fail(table, old, f"is the former name of {new!r}, which is given too; keep only "
                   f"{new} = ...")
        warnings.warn(f"{r.source}: [{table}] {old}: this key is now called {new!r}; write "
                      f"{new} = {out[old]!r} (the former name is read for now)",
                      RenamedKeyWarning, stacklevel=4)
        out[new] = out.pop(old)
    return out


class Reader:
    """Typed access to the parsed tables with messages naming file, table, key, value."""

    def __init__(self, source: str):
        self.source = source

    def fail(self, table: str, key: str | None, msg: str):
        where = f"[{table}]" if table else "top level"
        if key is not None:
            where += f" {key}"
        raise CaseFileError(f"{self.source}: {where}: {msg}")

    def unknown(self, table: str, tbl: Mapping, allowed) -> None:
        extra = [k for k in tbl if k not in allowed]
        if extra:
            kind = "table" if not table else "key"
            allowed_s = ", ".join(allowed)
            where = f"[{table}]" if table else "top level"
            raise CaseFileError(f"{self.source}: {where}: unknown {kind}(s) "
                                f"{', '.join(repr(k) for k in extra)}; allowed: {allowed_s}")

    def required_table(self, data: Mapping, name: str) -> Mapping:
        if name not in data:
            raise CaseFileError(f"{self.source}: missing table [{name}]")
        return data[name]

    def number(self, table: str, tbl: Mapping, key: str, *, default=None, positive=False,
               lo=None, hi=None, allow_inf=False) -> float:
        if key not in tbl:
            if default is None:
                self.fail(table, key, "missing (required)")
            return default
        v = tbl[key]
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            self.fail(table, key, f"must be a number, got {v!r}")
        v = float(v)
        if math.isnan(v) or (math.isinf(v) and not allow_inf):
            self.fail(table, key, f"must be finite, got {v!r}")
        if positive and v <= 0:
            self.fail(table, key, f"must be > 0, got {v!r}")
        if lo is not None and v < lo:
            self.fail(table, key, f"must be >= {lo}, got {v!r}")
        if hi is not None and v >= hi:
            self.fail(table, key, f"must be < {hi}, got {v!r}")
        return v

    def string(self, table: str, tbl: Mapping, key: str, default: str) -> str:
        v = tbl.get(key, default)
        if not isinstance(v, str):
            self.fail(table, key, f"must be a string, got {v!r}")
        return v


