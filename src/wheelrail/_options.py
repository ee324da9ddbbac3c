"""Validation of method options (private): one table, used by the API and by case files.

Every option of every method has a validator here, so that a bad value is
refused when :func:`wheelrail.creep_forces` is called or when a case file is
read — not half-way through a solve — and never silently clamped. Messages
name the option and the value (``nx must be an integer >= 1, got 0``); case
files add the file and the table.
"""

from __future__ import annotations

import math

from .errors import InputError

__all__ = ["validate", "VALIDATORS"]


def _integer(lo, hi=None):
    def check(name, v):
        if isinstance(v, bool) or not isinstance(v, int) and not _is_np_int(v) or v < lo \
                or (hi is not None and v > hi):
            rng = f">= {lo}" if hi is None else f"in [{lo}, {hi}]"
            raise InputError(f"{name} must be an integer {rng}, got {v!r}")
    return check


def _is_np_int(v) -> bool:
    try:
        import numpy as np
    except ImportError:  # pragma: no cover
        return False
    return isinstance(v, np.integer)


def _number(lo=None, hi=None, *, lo_open=False, hi_open=False, allow_none=False):
    def check(name, v):
        if v is None and allow_none:
            return
        if isinstance(v, bool) or not isinstance(v, (int, float)) and not _is_np_number(v):
            raise InputError(f"{name} must be a number, got {v!r}")
        f = float(v)
        if not math.isfinite(f):
            raise InputError(f"{name} must be finite, got {v!r}")
        if lo is not None and (f <= lo if lo_open else f < lo):
            raise InputError(f"{name} must be {'>' if lo_open else '>='} {lo:g}, got {v!r}")
        if hi is not None and (f >= hi if hi_open else f > hi):
            raise InputError(f"{name} must be {'<' if hi_open else '<='} {hi:g}, got {v!r}")
    return check


def _is_np_number(v) -> bool:
    try:
        import numpy as np
    except ImportError:  # pragma: no cover
        return False
    return isinstance(v, (np.integer, np.floating))


def _positive_array(name, v):
    """None, a positive number or an array of positive numbers (a value per batch case)."""
    if v is None:
        return
    import numpy as np

    try:
        arr = np.asarray(v, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number or an array of numbers, got {v!r}") from None
    if isinstance(v, bool) or not np.all(np.isfinite(arr)) or np.any(arr <= 0.0):
        raise InputError(f"{name} must be finite and > 0, got {v!r}")


def _choice(*choices):
    def check(name, v):
        if isinstance(v, bool) and not any(isinstance(c, bool) for c in choices) \
                or v not in choices:
            raise InputError(f"{name} must be one of {', '.join(map(repr, choices))}, got {v!r}")
    return check


def _polach_conditions(name, v):
    from .tangential.polach import POLACH_2005_PARAMETERS

    if v is not None and v not in POLACH_2005_PARAMETERS:
        raise InputError(f"{name} must be one of {sorted(POLACH_2005_PARAMETERS)} or None, "
                         f"got {v!r}")


def _polach_all(opts):
    from .tangential.polach import _check_extended

    _check_extended(*(opts.get(k) for k in ("kA", "kS", "speed", "A", "B", "conditions")))


def _penetration_factor(name, v):
    if isinstance(v, str):
        if v != "hertz":
            raise InputError(f"{name} must be 'hertz' or a number in (0, 1], got {v!r}")
        return
    if isinstance(v, bool) or not (isinstance(v, (int, float)) or _is_np_number(v)):
        raise InputError(f"{name} must be 'hertz' or a number in (0, 1], got {v!r}")
    if not (math.isfinite(float(v)) and 0.0 < float(v) <= 1.0):
        raise InputError(f"{name} must lie in (0, 1], got {v!r}")


#: method -> (option -> validator(name, value)), and an optional check of the whole set.
VALIDATORS = {
    # normal methods
    "hertz": {"strips": _integer(2, 2000), "cells": _integer(2, 2000)},
    "bem": {
        "elements": _integer(2), "element_size": _number(0.0, lo_open=True, allow_none=True),
        "margin": _number(0.0, 10.0, lo_open=True), "tol": _number(0.0, 1.0, lo_open=True,
                                                                    hi_open=True),
        "max_enlarge": _integer(0), "cells": _integer(2, 2000),
        "group_angle": _number(0.0, 3.2, lo_open=True), "width": _number(0.0, 0.2, lo_open=True),
    },
    "kik-piotrowski": {"penetration_factor": _penetration_factor,
                       "shape_correction": _choice(True, False),
                       "strips": _integer(2, 2000), "cells": _integer(2, 2000)},
    "linder": {"strips": _integer(2, 2000), "cells": _integer(2, 2000)},
    "stripes": {"smoothing": _number(0.0, lo_open=False), "strips": _integer(2, 2000),
                "cells": _integer(2, 2000)},
    "multi-hertz": {"variant": _choice("pascal", "sauvage", "sauvage-half", "ayasse"),
                    "max_ellipses": _integer(1, 20), "strips": _integer(2, 2000),
                    "cells": _integer(2, 2000)},
    # tangential methods
    "fastsim": {
        "nx": _integer(1, 2000), "ny": _integer(1, 2000),  # 4e6 cells: ~100 MB per field
        "bound": _choice("parabolic", "elliptic"),
        "flexibility": _choice("three", "weighted"),
        "scheme": _choice("midpoint", "euler"),
        "fields": _choice(None, True, False),
    },
    "exact": {
        "elements": _integer(4), "margin": _number(1.0, 10.0, lo_open=True),
        "tol": _number(0.0, 1.0, lo_open=True, hi_open=True), "maxiter": _integer(1),
        "on_fail": _choice("raise", "status"), "progress": _choice(None, True, False),
    },
    "carter": {
        "form": _choice("global", "strip"), "stiffness": _choice("carter", "kalker"),
        "lateral": _choice("error", "ignore"),
    },
    "shen-hedrick-elkins": {"spin_moment": _choice("scaled", "linear")},
    "polach": {
        "kA": _number(0.0, 1.0, lo_open=True, allow_none=True),
        "kS": _number(0.0, 1.0, lo_open=True, allow_none=True),
        "speed": _positive_array,
        "A": _number(0.0, 1.0, lo_open=True, allow_none=True),
        "B": _number(0.0, allow_none=True),
        "conditions": _polach_conditions,
    },
    "linear": {},
    "fastrip": {"ny": _integer(2, 2000)},
}
#: method -> check of the combination of its options (after the single values)
COMBINED = {"polach": _polach_all}


def validate(method: str, options: dict, *, complete: bool = True) -> None:
    """Check every value of ``options`` of ``method``; raise InputError naming key and value.

    ``complete=False`` checks only the given values (a case-file table of a
    method that is not used), without the checks of their combination.
    Unknown methods and keys are left to the caller (the registry).
    """
    table = VALIDATORS.get(method)
    if table is None:
        return
    for key, value in options.items():
        check = table.get(key)
        if check is not None:
            check(key, value)
    if complete and method in COMBINED:
        COMBINED[method](options)
