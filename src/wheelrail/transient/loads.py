"""Load and creepage histories over the travel: constant, step, sine, or a table of points.

A :class:`TravelFunction` is a frozen, callable description ``f(x)`` of a
quantity along the travel ``x`` [m] of the contact (a force [N], a penetration
[m] or a creepage [-] / [1/m]); :func:`transient_rolling` accepts it wherever
it accepts a function. It is what the ``[transient]`` table of a case file
describes (:func:`wheelrail.cases.files.load_transient_case`).

* ``constant``: ``value``;
* ``step``: ``before`` for ``x < at``, ``after`` from ``at`` on;
* ``sine``: ``mean + amplitude·sin(2π x / wavelength + phase)`` (Baeza et al.
  eqs. 3.2, 3.3);
* ``table``: piecewise linear through the points ``(x, value)``, constant
  beyond the first and last point.

References
----------
L. Baeza, F.J. Fuenmayor, J. Carballeira, A. Roda, Influence of the wheel–rail contact instationary process on contact parameters, §3 (eqs. 3.2–3.3: sinusoidal forces).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError

__all__ = ["TravelFunction", "KINDS"]

#: Kinds of travel functions and their parameters.
KINDS = {
    "constant": ("value",),
    "step": ("at", "before", "after"),
    "sine": ("mean", "amplitude", "wavelength", "phase"),
    "table": ("x", "value"),
}


@dataclass(frozen=True)
class TravelFunction:
    """A function of the travel x [m] (frozen; callable on floats and arrays).

    Parameters
    ----------
    kind : {"constant", "step", "sine", "table"}
    params : tuple of (name, value)
        The parameters of :data:`KINDS` for ``kind`` (``phase`` [rad] of a sine
        defaults to 0). ``table`` takes ``x`` [m] (strictly increasing) and
        ``value`` sequences of equal length ≥ 1.
    """

    kind: str
    params: tuple

    def __post_init__(self):
        if self.kind not in KINDS:
            raise InputError(f"kind must be one of {', '.join(KINDS)}, got {self.kind!r}")
        p = dict(self.params)
        allowed = KINDS[self.kind]
        extra = [k for k in p if k not in allowed]
        if extra:
            raise InputError(f"{self.kind} function: unknown parameter(s) {extra}; "
                             f"allowed: {', '.join(allowed)}")
        required = [k for k in allowed if k not in p and not (self.kind == "sine"
                                                             and k == "phase")]
        if required:
            raise InputError(f"{self.kind} function: missing parameter(s) {required}")
        if self.kind == "table":
            x = np.asarray(p["x"], float)
            v = np.asarray(p["value"], float)
            if x.ndim != 1 or x.shape != v.shape or x.size < 1:
                raise InputError(f"table function: x and value must be 1-D of equal length "
                                 f">= 1, got {x.shape} and {v.shape}")
            if not (np.all(np.isfinite(x)) and np.all(np.isfinite(v))):
                raise InputError("table function: x and value must be finite")
            if np.any(np.diff(x) <= 0):
                raise InputError(f"table function: x must be strictly increasing, got "
                                 f"{x.tolist()}")
        else:
            for k, v in p.items():
                if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                    raise InputError(f"{self.kind} function: {k} must be a finite number, "
                                     f"got {v!r}")
            if self.kind == "sine" and not p["wavelength"] > 0:
                raise InputError(f"sine function: wavelength must be > 0 m, got "
                                 f"{p['wavelength']!r}")

    @classmethod
    def of(cls, kind, **params):
        """``TravelFunction.of("sine", mean=1e4, amplitude=4.5e3, wavelength=5e-3)``."""
        return cls(kind, tuple((k, tuple(v) if isinstance(v, (list, np.ndarray)) else v)
                               for k, v in params.items()))

    def __call__(self, x):
        """Value at travel ``x`` [m] (float or array)."""
        p = dict(self.params)
        x = np.asarray(x, float)
        if self.kind == "constant":
            out = np.full(x.shape, float(p["value"]))
        elif self.kind == "step":
            out = np.where(x < p["at"], float(p["before"]), float(p["after"]))
        elif self.kind == "sine":
            out = p["mean"] + p["amplitude"] * np.sin(2 * np.pi * x / p["wavelength"]
                                                      + p.get("phase", 0.0))
        else:
            out = np.interp(x, np.asarray(p["x"], float), np.asarray(p["value"], float))
        return float(out) if out.ndim == 0 else out

    def describe(self) -> str:
        """A one-line description, e.g. ``sine(mean=10000, amplitude=4500, wavelength=0.005)``."""
        p = dict(self.params)
        if self.kind == "table":
            return f"table({len(p['x'])} points)"
        return f"{self.kind}(" + ", ".join(f"{k}={v:g}" for k, v in p.items()) + ")"
