"""TOML input with messages that name the file, the table, the key and the value (private).

Shared by the case-file reader (:mod:`wheelrail.casefile`) and the sweep
specification (:mod:`wheelrail.sweeps.spec`); it knows nothing of wheelrail's
types, only of numbers, strings and tables.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Mapping

from .errors import CaseFileError

try:  # Python >= 3.11
    import tomllib
except ModuleNotFoundError:  # pragma: no cover - Python 3.10
    import tomli as tomllib

__all__ = ["Reader", "read_toml", "tomllib"]


def read_toml(path_or_str):
    """``(data, source)`` of a case given as a path or as TOML text; CaseFileError if unreadable."""
    if isinstance(path_or_str, str) and ("\n" in path_or_str or "=" in path_or_str):
        text, source = path_or_str, "<string>"
    else:
        path = Path(path_or_str)
        source = str(path)
        try:
            text = path.read_text(encoding="utf-8")
        except FileNotFoundError:
            raise CaseFileError(f"{source}: case file not found") from None
        except (OSError, UnicodeDecodeError) as exc:
            raise CaseFileError(f"{source}: cannot read case file: {exc}") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise CaseFileError(f"{source}: malformed TOML: {exc}") from None
    return data, source

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


