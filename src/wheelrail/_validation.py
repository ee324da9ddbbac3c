"""Small input checks shared by the public API (private).

Each check raises :class:`wheelrail.errors.InputError` naming the argument and
the bad value; none returns NaN silently.
"""

from __future__ import annotations

import numpy as np

from .errors import InputError


def _describe(value) -> str:
    arr = np.asarray(value)
    if arr.ndim == 0:
        return repr(arr.item())
    bad = arr.ravel()
    return f"array of shape {arr.shape} (e.g. {bad[:3].tolist()})"


def as_float_array(name: str, value) -> np.ndarray:
    """Return ``value`` as a float array, rejecting non-numeric, NaN and inf."""
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise InputError(f"{name} must be numeric, got {value!r}") from exc
    if not np.all(np.isfinite(arr)):
        bad = arr[~np.isfinite(arr)]
        raise InputError(f"{name} must be finite, got {bad.ravel()[0].item()!r}"
                         + ("" if arr.ndim == 0 else f" in {_describe(arr)}"))
    return arr


def positive(name: str, value) -> np.ndarray:
    """Finite and strictly positive (e.g. a load, a modulus, a friction coefficient)."""
    arr = as_float_array(name, value)
    if np.any(arr <= 0.0):
        bad = arr[arr <= 0.0].ravel()[0].item()
        raise InputError(f"{name} must be > 0, got {bad!r}")
    return arr


def non_negative(name: str, value) -> np.ndarray:
    """Finite and >= 0."""
    arr = as_float_array(name, value)
    if np.any(arr < 0.0):
        bad = arr[arr < 0.0].ravel()[0].item()
        raise InputError(f"{name} must be >= 0, got {bad!r}")
    return arr


def in_range(name: str, value, lo: float, hi: float, *, lo_open=False, hi_open=False) -> np.ndarray:
    """Finite and inside [lo, hi] (or the open variant)."""
    arr = as_float_array(name, value)
    low_bad = arr <= lo if lo_open else arr < lo
    high_bad = arr >= hi if hi_open else arr > hi
    bad = low_bad | high_bad
    if np.any(bad):
        lb = "(" if lo_open else "["
        hb = ")" if hi_open else "]"
        raise InputError(f"{name} must lie in {lb}{lo}, {hi}{hb}, got {arr[bad].ravel()[0].item()!r}")
    return arr


def integer(name: str, value, lo: int = 1) -> int:
    """A Python/numpy integer (not a bool) >= ``lo`` (e.g. a number of elements), as ``int``."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < lo:
        raise InputError(f"{name} must be an integer >= {lo}, got {value!r}")
    return int(value)


def scalar_or_array(arr: np.ndarray):
    """Return a Python float for 0-d arrays, the array otherwise."""
    return float(arr) if np.ndim(arr) == 0 else arr
