"""Resource guards for long jobs: boundary-element and exact grids, sweeps, transient runs
(private).

Before a long job its memory and time are estimated (grids: from the number
of elements; sweeps: points × a measured cost per point; transient runs:
steps × grid cells); a job whose estimate exceeds the memory or the time
limit is refused with the estimate in the message (before any memory is
allocated), and the command line shows the estimate and a spinner for jobs
expected to take more than a few seconds. With :func:`estimating` (the
command-line option ``--estimate-only``) the first estimate ends the job:
:class:`EstimateOnly` carries it, nothing is allocated or written.

Estimates (``benchmarks/bench_estimates.py`` and ``bench_resources.py`` measure them;
CPU time of one solve in a fresh process on one core of the shared 2-core machine,
numba kernels cached; peak resident memory including the interpreter)

============  =============================  ==========================================
solver        memory                          time (fit of CPU time, within ±30 %)
============  =============================  ==========================================
bem_normal    150 MB + 780 B per grid cell    1.92 s · (cells / 2.5e5)^1.1
                                              (5.6e3–1e6 cells: 0.035–9.9 s)
exact         190 MB + 2.3 kB per grid cell   0.5 s + 3.8 µs per cell
                                              + 0.31 s · (cells / 3.1e4)^1.5
                                              (529–436 921 cells: 0.45–18.5 s)
============  =============================  ==========================================

On a loaded machine the wall time is longer than the CPU time (about 3 × at a load
average of 10 on 2 cores); the estimates are of the time on an unloaded core, and the
message adds the time expected at the current load (:func:`load_factor`). The limits
apply to the unloaded estimate.

The memory limit is, in this order: :func:`memory_limit` inside a :func:`limit`
block (the command-line option ``wheelrail --memory-limit``); the environment
variable ``WHEELRAIL_MEMORY_LIMIT`` (``"8GB"``, ``"500MB"``, ``"2e9"`` bytes,
or ``"off"``); else min(4 GiB, half the physical memory). The time limit
likewise: :func:`time_limit_set` (``wheelrail --time-limit 3h``), the
environment variable ``WHEELRAIL_TIME_LIMIT`` (``"90s"``, ``"30min"``,
``"3h"``, seconds, or ``"off"``), else :data:`DEFAULT_TIME_LIMIT`.
"""

from __future__ import annotations

import contextlib
import math
import os
import time
from dataclasses import dataclass

from .errors import InputError

__all__ = ["Estimate", "EstimateOnly", "ResourceLimitError", "estimate", "guard", "check",
           "limit", "memory_limit", "time_limit", "time_limit_set", "parse_size",
           "parse_duration", "estimating", "load_factor", "load_note", "suspended", "reporting", "DEFAULT_TIME_LIMIT"]

#: kind -> (fixed bytes, bytes per cell, fixed seconds, seconds per cell, seconds at the
#: reference cells, reference cells, time exponent): memory = fixed + per cell × cells,
#: time = fixed + per cell × cells + reference seconds × (cells / reference cells) **
#: exponent (see the module docstring)
MODELS = {
    "bem_normal": (150e6, 780.0, 0.0, 0.0, 1.92, 2.5e5, 1.1),
    "exact": (190e6, 2300.0, 0.5, 3.8e-6, 0.31, 3.1e4, 1.5),
}
#: Solves expected to take longer than this [s] show a spinner on the command line.
PROGRESS_AFTER = 3.0
#: Jobs estimated to take longer than this [s] are refused unless the limit is raised.
DEFAULT_TIME_LIMIT = 3600.0

_state: dict = {"limit": [], "time_limit": [], "reporter": None, "notice": None,
                "estimate_only": 0}

_HINT_MEMORY = ("raise the limit (wheelrail --memory-limit 16GB, WHEELRAIL_MEMORY_LIMIT=16GB "
                "or 'off')")
_HINT_TIME = ("raise the limit (wheelrail --time-limit 12h, WHEELRAIL_TIME_LIMIT=12h or "
              "'off')")


class ResourceLimitError(InputError):
    """A job would need more memory or time than the limit (estimate in the message)."""


class EstimateOnly(BaseException):
    """Raised by :func:`check` inside :func:`estimating`: the job stops at its estimate.

    Not an error (the command line prints the estimate and exits with 0);
    ``str()`` is the estimate. A ``BaseException`` like ``KeyboardInterrupt``:
    code that catches every ``Exception`` of one method or one sweep point
    (and records it as failed) lets it through.
    """


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
    for unit, f in (("PB", 1e15), ("TB", 1e12), ("GB", 1e9), ("MB", 1e6), ("kB", 1e3)):
        if n >= f:
            return f"{n / f:.3g} {unit}"
    return f"{n:.0f} B"


def _duration(s: float) -> str:
    if s < 120:
        return f"{s:.2g} s" if s < 10 else f"{s:.0f} s"
    if s < 7200:
        return f"{s / 60:.0f} min"
    if s < 2 * 86400:
        return f"{s / 3600:.1f} h"
    return f"{s / 86400:.3g} days"


def _parse(text, factors: dict, what: str, examples: str) -> float | None:
    """A positive number with an optional unit suffix (``factors``: suffix -> multiplier);
    'off', 'none', 'inf', 'unlimited' → None. ``what`` and ``examples`` for the message."""
    s = str(text).strip().lower().replace(" ", "")
    if s in ("off", "none", "inf", "unlimited"):
        return None
    for suffix in sorted(factors, key=len, reverse=True):
        if s.endswith(suffix):
            num, f = s[:-len(suffix)], factors[suffix]
            break
    else:
        num, f = s, 1.0
    try:
        val = float(num) * f
    except ValueError:
        raise InputError(f"{what} must be {examples} or 'off', got {text!r}") from None
    if not val > 0 or not math.isfinite(val):
        raise InputError(f"{what} must be positive or 'off', got {text!r}")
    return val


def parse_duration(text) -> float | None:
    """'90s' → 90, '30min' → 1800, '3h' → 10800, '3600' → 3600 s; 'off'/'none' → None."""
    return _parse(text, {"d": 86400.0, "h": 3600.0, "min": 60.0, "m": 60.0, "s": 1.0},
                  "time limit", "a duration like 90s, 30min, 3h")


def time_limit() -> float | None:
    """The time limit [s] in force, or None for no limit (see the module docstring)."""
    if _state["time_limit"]:
        return _state["time_limit"][-1]
    env = os.environ.get("WHEELRAIL_TIME_LIMIT")
    if env:
        return parse_duration(env)
    return DEFAULT_TIME_LIMIT


@contextlib.contextmanager
def time_limit_set(duration):
    """Use the time limit ``duration`` (seconds, a string like '3h', or None/'off') in the block."""
    value = (duration if duration is None or isinstance(duration, (int, float))
             else parse_duration(duration))
    _state["time_limit"].append(None if value is None else float(value))
    try:
        yield
    finally:
        _state["time_limit"].pop()


@contextlib.contextmanager
def estimating():
    """Inside the block the first :func:`check` (or :func:`guard`) raises :class:`EstimateOnly`."""
    _state["estimate_only"] += 1
    try:
        yield
    finally:
        _state["estimate_only"] -= 1


@contextlib.contextmanager
def suspended():
    """A measurement in progress: no estimate-only stop, no limits' reports in the block.

    The sweep estimate times a few real points; their solves must run even
    under ``--estimate-only`` and must not print their own estimates.
    """
    saved = _state["estimate_only"], _state["notice"], _state["reporter"]
    _state["estimate_only"], _state["notice"], _state["reporter"] = 0, None, None
    try:
        yield
    finally:
        _state["estimate_only"], _state["notice"], _state["reporter"] = saved


def check(what: str, seconds: float, memory: float, detail: str = "") -> str:
    """Refuse a job estimated past the memory or time limit; announce long ones.

    Parameters
    ----------
    what : str
        The job, for messages (e.g. "sweep of 1000000 points").
    seconds, memory : float
        Estimated wall time [s] and peak memory [bytes].
    detail : str
        How the estimate was obtained (e.g. "12 ms per point, measured").

    Returns
    -------
    str
        The estimate as one line.

    Raises
    ------
    EstimateOnly
        Inside :func:`estimating` (before any limit is checked).
    ResourceLimitError
        With the estimate, the limit and how to override it.
    """
    text = (f"{what}: about {_duration(seconds)} and {_human(memory)}"
            + (f" ({detail})" if detail else "") + load_note(seconds))
    if _state["estimate_only"]:
        raise EstimateOnly(text)
    lim = memory_limit()
    if lim is not None and memory > lim:
        raise ResourceLimitError(f"{text} — more than the memory limit of {_human(lim)}; make "
                                 f"the job smaller, or {_HINT_MEMORY}")
    tlim = time_limit()
    if tlim is not None and seconds > tlim:
        raise ResourceLimitError(f"{text} — more than the time limit of {_duration(tlim)}; "
                                 f"make the job smaller, or {_HINT_TIME}")
    note = _state["notice"]
    if note is not None and seconds > PROGRESS_AFTER:
        note(text)
    rep = _state["reporter"]
    if rep is not None and seconds > PROGRESS_AFTER:
        rep(text, seconds)
    return text


def load_factor() -> float:
    """Expected wall time / CPU time at the machine's current load: √((load + 1) / cores),
    at least 1 (measured 2.0–3.0 at a load average of 7–11 on 2 cores with
    ``benchmarks/bench_estimates.py``; 1 on an idle machine)."""
    try:
        load = os.getloadavg()[0]
    except (OSError, AttributeError):  # pragma: no cover - no load average
        return 1.0
    return max(1.0, ((load + 1.0) / (os.cpu_count() or 1)) ** 0.5)


def load_note(seconds: float) -> str:
    """"; about … at the current load …" when the machine is busy (the estimates are of
    the time on an unloaded core), else ""."""
    f = load_factor()
    if f < 1.3 or seconds * f < 1.0:
        return ""
    try:
        load = os.getloadavg()[0]
    except (OSError, AttributeError):  # pragma: no cover
        return ""
    return (f"; about {_duration(seconds * f)} at the current load ({load:.1f} on "
            f"{os.cpu_count()} cores)")


def parse_size(text) -> float | None:
    """'8GB' → 8e9, '500MB' → 5e8, '2e9' → 2e9 bytes; 'off'/'none' → None (no limit)."""
    return _parse(text, {"tb": 1e12, "gb": 1e9, "mb": 1e6, "kb": 1e3, "gib": 2**30,
                         "mib": 2**20, "g": 1e9, "m": 1e6, "k": 1e3, "b": 1.0},
                  "memory limit", "a size like 8GB, 500MB")


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
    fixed, per_cell, t_fixed, t_cell, t_ref, c_ref, expo = MODELS[kind]
    cells = int(cells)
    return Estimate(kind, cells, fixed + per_cell * cells,
                    t_fixed + t_cell * cells + t_ref * (cells / c_ref) ** expo)


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
    text = f"{what}: {est.describe()}{load_note(est.seconds)}"
    if _state["estimate_only"]:
        raise EstimateOnly(text)
    lim = memory_limit()
    if lim is not None and est.memory > lim:
        raise ResourceLimitError(
            f"{text} — more than the memory limit of {_human(lim)}; use fewer "
            f"elements, or {_HINT_MEMORY}")
    tlim = time_limit()
    if tlim is not None and est.seconds > tlim:
        raise ResourceLimitError(f"{text} — more than the time limit of {_duration(tlim)}; use "
                                 f"fewer elements, or {_HINT_TIME}")
    rep = _state["reporter"]
    if rep is not None and est.seconds > PROGRESS_AFTER:
        rep(text, est.seconds)
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

    def notice(text):
        console.print(f"estimate: {text}", markup=False, highlight=False)

    prev, prev_notice = _state["reporter"], _state["notice"]
    _state["reporter"], _state["notice"] = report, notice
    try:
        yield
    finally:
        _state["reporter"], _state["notice"] = prev, prev_notice
        if status["obj"] is not None:
            status["obj"].stop()
