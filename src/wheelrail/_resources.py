"""Resource guards for large boundary-element solves (private).

Before a boundary-element solve the memory and time are estimated from the
number of elements of its grid; a solve whose memory estimate exceeds the
limit is refused with the estimate in the message (before any memory is
allocated), and the command line shows a spinner with the estimate and the
elapsed time for solves expected to take more than a few seconds.

Estimates (``benchmarks/bench_resources.py`` measures them; 2-core machine,
numpy/scipy FFT, peak resident memory including ~110 MB for the interpreter)

============  =============================  ======================================
solver        memory                          time (fit, ±50 % with the machine load)
============  =============================  ======================================
bem_normal    150 MB + 740 B per grid cell    9.7 s · (cells / 2.5e5)^1.2
exact         150 MB + 2.3 kB per grid cell   8.4 s · (cells / 3.1e4)^0.85
============  =============================  ======================================

The limit is, in this order: :func:`memory_limit` inside a :func:`limit`
block; the environment variable ``WHEELRAIL_MEMORY_LIMIT`` (``"8GB"``,
``"500MB"``, ``"2e9"`` bytes, or ``"off"``); the command-line option
``wheelrail --memory-limit``; else min(4 GiB, half the physical memory).
"""

from __future__ import annotations

import contextlib
import os
import time
from dataclasses import dataclass

from .errors import InputError

__all__ = ["Estimate", "ResourceLimitError", "estimate", "guard", "limit", "memory_limit",
           "parse_size", "reporting"]

#: kind -> (fixed bytes, bytes per cell, reference seconds, reference cells, time exponent)
MODELS = {
    "bem_normal": (150e6, 740.0, 9.7, 2.5e5, 1.2),
    "exact": (150e6, 2300.0, 8.4, 3.1e4, 0.85),
}
#: Solves expected to take longer than this [s] show a spinner on the command line.
PROGRESS_AFTER = 3.0

_state: dict = {"limit": [], "reporter": None}


class ResourceLimitError(InputError):
    """A solve would need more memory than the limit (estimate in the message)."""


@dataclass(frozen=True)
class Estimate:
    """Estimated peak memory [bytes] and run time [s] of one solve."""

    kind: str
    cells: int
    memory: float
    seconds: float

    def describe(self) -> str:
        return (f"{self.cells} grid cells: about {_human(self.memory)} and "
                f"{_duration(self.seconds)}")


def _human(n: float) -> str:
    for unit, f in (("GB", 1e9), ("MB", 1e6), ("kB", 1e3)):
        if n >= f:
            return f"{n / f:.3g} {unit}"
    return f"{n:.0f} B"


def _duration(s: float) -> str:
    return f"{s:.0f} s" if s < 120 else f"{s / 60:.0f} min"


def parse_size(text) -> float | None:
    """'8GB' → 8e9, '500MB' → 5e8, '2e9' → 2e9 bytes; 'off'/'none' → None (no limit)."""
    s = str(text).strip().lower().replace(" ", "")
    if s in ("off", "none", "inf", "unlimited"):
        return None
    factors = {"tb": 1e12, "gb": 1e9, "mb": 1e6, "kb": 1e3, "gib": 2**30, "mib": 2**20,
               "g": 1e9, "m": 1e6, "k": 1e3, "b": 1.0}
    for suffix in sorted(factors, key=len, reverse=True):
        if s.endswith(suffix):
            num, f = s[:-len(suffix)], factors[suffix]
            break
    else:
        num, f = s, 1.0
    try:
        val = float(num) * f
    except ValueError:
        raise InputError(f"memory limit must be a size like 8GB, 500MB or 'off', got {text!r}"
                         ) from None
    if not val > 0 or val != val or val == float("inf"):
        raise InputError(f"memory limit must be a positive size or 'off', got {text!r}")
    return val


def _physical_memory() -> float:
    try:
        return float(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES"))
    except (ValueError, OSError, AttributeError):  # pragma: no cover - non-POSIX
        return 8e9


def memory_limit() -> float | None:
    """The memory limit [bytes] in force, or None for no limit (see the module docstring)."""
    if _state["limit"]:
        return _state["limit"][-1]
    env = os.environ.get("WHEELRAIL_MEMORY_LIMIT")
    if env:
        return parse_size(env)
    return min(4.0 * 2**30, 0.5 * _physical_memory())


@contextlib.contextmanager
def limit(size):
    """Use the memory limit ``size`` (bytes, a string like '8GB', or None/'off') in the block."""
    value = size if size is None or isinstance(size, (int, float)) else parse_size(size)
    _state["limit"].append(None if value is None else float(value))
    try:
        yield
    finally:
        _state["limit"].pop()


def estimate(kind: str, cells: int) -> Estimate:
    """Memory and time estimate of a solve of ``kind`` ("bem_normal", "exact") on ``cells``."""
    fixed, per_cell, t_ref, c_ref, expo = MODELS[kind]
    cells = int(cells)
    return Estimate(kind, cells, fixed + per_cell * cells, t_ref * (cells / c_ref) ** expo)


def guard(kind: str, cells: int, what: str) -> Estimate:
    """Refuse a solve whose memory estimate exceeds the limit; report long ones.

    Parameters
    ----------
    kind : {"bem_normal", "exact"}
    cells : int
        Number of elements of the grid.
    what : str
        Description for messages (e.g. "normal BEM on a 401x401 grid").

    Raises
    ------
    ResourceLimitError
        With the estimate, the limit and how to override it.
    """
    est = estimate(kind, cells)
    lim = memory_limit()
    if lim is not None and est.memory > lim:
        raise ResourceLimitError(
            f"{what}: {est.describe()} — more than the memory limit of {_human(lim)}; use fewer "
            f"elements, or raise the limit (wheelrail --memory-limit 16GB, "
            f"WHEELRAIL_MEMORY_LIMIT=16GB or 'off')")
    rep = _state["reporter"]
    if rep is not None and est.seconds > PROGRESS_AFTER:
        rep(f"{what}: {est.describe()}", est.seconds)
    return est


@contextlib.contextmanager
def reporting(console):
    """Show a spinner on ``console`` (rich) for every long solve started inside the block.

    The spinner shows the description and estimate of the latest long solve
    and the elapsed time; it disappears when the block ends. Nothing is shown
    when the console is not a terminal.
    """
    status = {"obj": None, "until": 0.0}

    def report(text, seconds):
        if not getattr(console, "is_terminal", False):
            return
        now = time.perf_counter()
        if now + seconds < status["until"]:  # a part of the solve already reported
            return
        status["until"] = now + seconds
        if status["obj"] is None:
            status["obj"] = console.status(text)
            status["obj"].start()
        else:
            status["obj"].update(text)

    prev = _state["reporter"]
    _state["reporter"] = report
    try:
        yield
    finally:
        _state["reporter"] = prev
        if status["obj"] is not None:
            status["obj"].stop()
