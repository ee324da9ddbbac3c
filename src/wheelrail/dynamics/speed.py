"""A run's speed that varies along the run: :class:`SpeedProfile`.

The speed is piecewise linear either in time (:meth:`SpeedProfile.from_time`) or
in the distance along the track (:meth:`SpeedProfile.from_distance`, the form of a
route's speed restrictions). Both are integrated exactly, ds/dt = V:

* linear in time between (t_i, v_i) and (t_i+1, v_i+1): constant acceleration
  a_i = (v_i+1 − v_i)/(t_i+1 − t_i), s = s_i + v_i τ + a_i τ²/2, τ = t − t_i;
* linear in distance between (s_i, v_i) and (s_i+1, v_i+1): dV/ds = g_i =
  (v_i+1 − v_i)/(s_i+1 − s_i) is constant, so dV/dt = g_i V, V = v_i e^{g_i τ},
  s = s_i + v_i (e^{g_i τ} − 1)/g_i, and the segment takes
  t_i+1 − t_i = ln(v_i+1/v_i)/g_i (= (s_i+1 − s_i)/v_i at equal speeds).

After the last breakpoint the speed is held at its last value (and, for a profile
against distance, before the first one at its first value).
:func:`~wheelrail.dynamics.simulate` takes a profile as its ``speed``; the compiled
equations evaluate it from the table of :meth:`SpeedProfile.table`
(:mod:`wheelrail.dynamics._speed`).

References
----------
.. [1] A.H. Wickens, *Fundamentals of rail vehicle dynamics*, Swets & Zeitlinger
   2003, §2.1 (the wheelset's reference frame moving along the track at the speed
   V(t), s = ∫V dt, and the inertia terms of V̇).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ._speed import profile_eval

__all__ = ["SpeedProfile"]


def _floats(who, name, values):
    try:
        a = np.array(values, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"SpeedProfile.{who}: {name} must be a list of numbers, got "
                         f"{values!r}") from None
    if a.ndim != 1 or a.size < 2:
        raise InputError(f"SpeedProfile.{who}: {name} must be a list of at least 2 numbers, "
                         f"got {values!r}")
    bad = np.flatnonzero(~np.isfinite(a))
    if bad.size:
        i = int(bad[0])
        raise InputError(f"SpeedProfile.{who}: {name}[{i}] = {a[i]!r} is not finite")
    return a


@dataclass(frozen=True, eq=False)
class SpeedProfile:
    """Forward speed of a run, piecewise linear in time or in distance (frozen).

    Build it with :meth:`from_time` or :meth:`from_distance`.

    Parameters
    ----------
    kind : {"time", "distance"}
        What the abscissae are.
    x : ndarray, shape (n,)
        Breakpoints: times [s] from the start of the run (``x[0] = 0``), or
        positions along the track [m] (the coordinate of the track layout and of
        ``simulate(start=...)``), strictly increasing.
    v : ndarray, shape (n,)
        Speeds at the breakpoints [m/s], ≥ 0 against time, > 0 against distance.
    """

    kind: str
    x: np.ndarray
    v: np.ndarray

    def __post_init__(self):
        who = "from_time" if self.kind == "time" else "from_distance"
        if self.kind not in ("time", "distance"):
            raise InputError(f"SpeedProfile: kind must be 'time' or 'distance', got "
                             f"{self.kind!r}")
        name = "t" if self.kind == "time" else "s"
        x = _floats(who, name, self.x)
        v = _floats(who, "v", self.v)
        if x.size != v.size:
            raise InputError(f"SpeedProfile.{who}: {name} and v differ in length "
                             f"({x.size} and {v.size})")
        step = np.flatnonzero(np.diff(x) <= 0)
        if step.size:
            i = int(step[0]) + 1
            raise InputError(f"SpeedProfile.{who}: {name} must increase strictly; "
                             f"{name}[{i}] = {x[i]!r} follows {name}[{i - 1}] = {x[i - 1]!r}")
        if self.kind == "time" and x[0] != 0.0:
            raise InputError(f"SpeedProfile.from_time: t[0] = {x[0]!r} s must be 0 (the start "
                             f"of the run)")
        neg = np.flatnonzero(v < 0) if self.kind == "time" else np.flatnonzero(v <= 0)
        if neg.size:
            i = int(neg[0])
            what = ("must be ≥ 0 m/s" if self.kind == "time" else
                    "must be > 0 m/s (against distance the time to reach or leave rest is "
                    "infinite: give a profile at rest against time, SpeedProfile.from_time)")
            raise InputError(f"SpeedProfile.{who}: v[{i}] = {v[i]!r} {what}")
        x.setflags(write=False)
        v.setflags(write=False)
        object.__setattr__(self, "x", x)
        object.__setattr__(self, "v", v)

    # ---------------------------------------------------------------- construction
    @classmethod
    def from_time(cls, t, v) -> SpeedProfile:
        """Speed ``v`` [m/s] at the times ``t`` [s] (``t[0] = 0``), linear in between.

        Examples
        --------
        >>> import wheelrail as wr
        >>> p = wr.dynamics.SpeedProfile.from_time([0.0, 10.0], [20.0, 10.0])
        >>> float(p.position(10.0))             # (20 + 10)/2 · 10 s
        150.0
        """
        return cls("time", t, v)

    @classmethod
    def from_distance(cls, s, v) -> SpeedProfile:
        """Speed ``v`` [m/s] at the track positions ``s`` [m], linear in s in between.

        Examples
        --------
        >>> import wheelrail as wr
        >>> p = wr.dynamics.SpeedProfile.from_distance([0.0, 100.0], [20.0, 10.0])
        >>> round(float(p.time_at(100.0)), 6)     # ln(20/10) / (10/100 1/s)
        6.931472
        """
        return cls("distance", s, v)

    # ---------------------------------------------------------------- the kernel's table
    def _origin(self, start):
        if start is None:
            return 0.0 if self.kind == "time" else float(self.x[0])
        if not (isinstance(start, (int, float, np.floating)) and math.isfinite(start)):
            raise InputError(f"start must be a finite position [m], got {start!r}")
        return float(start)

    def table(self, start=None) -> np.ndarray:
        """The profile for a run that is at ``start`` [m] at t = 0, shape (5, n).

        Rows: breakpoint time [s], speed [m/s], position [m], rate and kind of the
        segment that follows (:mod:`wheelrail.dynamics._speed`). ``start`` defaults to
        0 (against time) or the first breakpoint (against distance).
        """
        s0 = self._origin(start)
        x, v = self.x, self.v
        if self.kind == "time":
            a = np.diff(v) / np.diff(x)
            ds = 0.5 * (v[:-1] + v[1:]) * np.diff(x)
            s = s0 + np.concatenate(([0.0], np.cumsum(ds)))
            return np.array([x, v, s, np.append(a, 0.0), np.zeros(x.size)])
        cols = []
        if s0 < x[0]:
            cols.append((0.0, float(v[0]), s0, 0.0, 0.0))
        j = int(np.searchsorted(x, s0, side="right")) - 1
        t = (x[0] - s0) / v[0] if s0 < x[0] else 0.0
        if j >= x.size - 1:
            cols.append((0.0, float(v[-1]), s0, 0.0, 0.0))
            return np.array(cols, dtype=float).T
        for i in range(max(j, 0), x.size - 1):
            g = (v[i + 1] - v[i]) / (x[i + 1] - x[i])
            si, vi = float(x[i]), float(v[i])
            if i == j:                              # the segment that holds the start
                si, vi = s0, vi + g * (s0 - x[i])
            if g == 0.0:
                cols.append((t, vi, si, 0.0, 0.0))
                t += (x[i + 1] - si) / vi
            else:
                cols.append((t, vi, si, g, 1.0))
                t += math.log(v[i + 1] / vi) / g
        cols.append((t, float(v[-1]), float(x[-1]), 0.0, 0.0))
        return np.array(cols, dtype=float).T

    # ---------------------------------------------------------------- evaluation
    def _eval(self, t, start):
        SP = self.table(start)
        tt = np.atleast_1d(np.asarray(t, dtype=float))
        if not np.all(np.isfinite(tt)):
            raise InputError(f"t must be finite, got {t!r}")
        V, A, S = (np.empty(tt.shape) for _ in range(3))
        profile_eval(SP, tt.ravel(), V.ravel(), A.ravel(), S.ravel())
        scalar = np.ndim(t) == 0
        return tuple(float(a[0]) if scalar else a.reshape(np.shape(t)) for a in (V, A, S))

    def speed(self, t, start=None):
        """Speed [m/s] at the times ``t`` [s] of a run that is at ``start`` [m] at t = 0."""
        return self._eval(t, start)[0]

    def acceleration(self, t, start=None):
        """dV/dt [m/s²] at the times ``t`` [s] (the segment after a breakpoint at one)."""
        return self._eval(t, start)[1]

    def position(self, t, start=None):
        """Position along the track [m] at the times ``t`` [s]: ``start`` + ∫₀ᵗ V dt,
        exactly. ``start`` defaults to 0 (against time) or the first breakpoint
        (against distance)."""
        return self._eval(t, start)[2]

    def time_at(self, s, start=None):
        """Time [s] at which the run reaches the track position ``s`` [m] (≥ ``start``),
        the inverse of :meth:`position` (closed form per segment)."""
        SP = self.table(start)
        ss = np.atleast_1d(np.asarray(s, dtype=float))
        if not np.all(np.isfinite(ss)) or np.any(ss < SP[2, 0]):
            raise InputError(f"s must be finite positions ≥ the start {SP[2, 0]!r} m, got {s!r}")
        out = np.empty(ss.shape)
        for k, sk in enumerate(ss.ravel()):
            i = max(int(np.searchsorted(SP[2], sk, side="right")) - 1, 0)
            t0, v, s0, r, kind = SP[:, i]
            d = sk - s0
            if kind == 1.0 and r != 0.0:
                tau = math.log1p(r * d / v) / r
            elif r == 0.0:
                if v <= 0.0:
                    raise InputError(f"the run stands still at {s0!r} m and never reaches "
                                     f"{sk!r} m")
                tau = d / v
            else:                                   # v τ + r τ²/2 = d, the root ≥ 0
                disc = v * v + 2.0 * r * d
                if disc < 0.0:
                    raise InputError(f"the run stops before {sk!r} m")
                tau = 2.0 * d / (v + math.sqrt(disc))
            out.ravel()[k] = t0 + tau
        return float(out[0]) if np.ndim(s) == 0 else out.reshape(np.shape(s))

    def __repr__(self):
        return (f"SpeedProfile.from_{self.kind}({self.x.tolist()!r}, {self.v.tolist()!r})")


def _run_table(speed, deceleration, start):
    """(profile or None, its table for a run at ``start`` at t = 0) of ``simulate``'s
    ``speed`` (a SpeedProfile, or a float with a constant ``deceleration``: one segment)."""
    if isinstance(speed, SpeedProfile):
        if deceleration != 0:
            raise InputError(f"deceleration = {deceleration!r} m/s² with a SpeedProfile: the "
                             f"profile gives the speed; put the ramp into it")
        return speed, speed.table(float(start))
    rest = deceleration < 0          # accelerating: may start from rest
    if not (isinstance(speed, (int, float, np.floating)) and math.isfinite(speed)
            and (speed > 0 or (rest and speed == 0))):
        raise InputError(f"speed must be a number > 0 (or 0 with an acceleration, "
                         f"deceleration < 0) or a SpeedProfile, got {speed!r}")
    return None, np.array([[0.0], [float(speed)], [float(start)], [-float(deceleration)],
                           [0.0]])
