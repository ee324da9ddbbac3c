"""Compiled evaluation of a run's speed profile (the kernel of :mod:`wheelrail.dynamics.speed`).

A profile is a table ``SP`` of shape (5, n) whose column i describes the motion from
the breakpoint time ``SP[0, i]`` to the next one (the last column: to any later time):

* ``SP[1, i]`` speed v_i [m/s] and ``SP[2, i]`` position s_i [m] at t_i;
* ``SP[3, i]`` the rate r_i and ``SP[4, i]`` the kind of the segment:

  - kind 0, speed linear in time: V = v_i + r_i τ, s = s_i + v_i τ + r_i τ²/2,
    dV/dt = r_i (r_i the acceleration [m/s²]);
  - kind 1, speed linear in distance: dV/ds = r_i [1/s], so dV/dt = r_i V and
    V = v_i exp(r_i τ), s = s_i + v_i (exp(r_i τ) − 1)/r_i,

  with τ = t − t_i. Both are the exact solutions of ds/dt = V.
"""

from __future__ import annotations

import math

from numba import njit

__all__ = ["profile_at", "profile_eval", "least_speed", "greatest_speed", "falls_below"]


@njit(cache=True)
def profile_at(SP, t):
    """Speed V [m/s], acceleration dV/dt [m/s²] and position s [m] at time ``t`` [s].

    The segment is found by bisection on the breakpoint times ``SP[0]`` (before the
    first breakpoint the first segment is extended back).
    """
    n = SP.shape[1]
    lo = 0
    hi = n
    while hi - lo > 1:              # largest i with SP[0, i] <= t
        mid = (lo + hi) // 2
        if SP[0, mid] <= t:
            lo = mid
        else:
            hi = mid
    tau = t - SP[0, lo]
    v = SP[1, lo]
    s = SP[2, lo]
    r = SP[3, lo]
    if SP[4, lo] == 0.0 or r == 0.0:
        return v + r * tau, r, s + v * tau + 0.5 * r * tau * tau
    e = math.expm1(r * tau)
    V = v + v * e
    return V, r * V, s + v * e / r


@njit(cache=True)
def profile_eval(SP, t, V, A, S):
    """:func:`profile_at` at every time of ``t`` (n,): into ``V``, ``A``, ``S`` (n,)."""
    for k in range(t.shape[0]):
        V[k], A[k], S[k] = profile_at(SP, t[k])


# --------------------------------------------------------------------------- on a table (Python)
def least_speed(SP, t0, t1):
    """Least speed [m/s] of the table ``SP`` over [t0, t1] (each segment is monotone: the
    least is at an end or a breakpoint)."""
    ts = [t0, t1] + [float(t) for t in SP[0] if t0 < t < t1]
    return min(profile_at(SP, t)[0] for t in ts)


def greatest_speed(SP, t0, t1):
    """Greatest speed [m/s] of the table ``SP`` over [t0, t1]."""
    ts = [t0, t1] + [float(t) for t in SP[0] if t0 < t < t1]
    return max(profile_at(SP, t)[0] for t in ts)


def falls_below(SP, vmin, t1, held=False):
    """The first time in [0, t1) at which the speed falls to ``vmin`` while decreasing
    (with ``held``: or is held at or below it), or None (closed form per segment; 0 for
    a run that starts at or below ``vmin`` and does not accelerate)."""
    n = SP.shape[1]
    for i in range(n):
        ta = float(SP[0, i])
        tb = float(SP[0, i + 1]) if i + 1 < n else math.inf
        if ta >= t1:
            break
        v, r, kind = float(SP[1, i]), float(SP[3, i]), float(SP[4, i])
        if r > 0.0 or (r == 0.0 and not (held and v <= vmin)):
            continue
        if v <= vmin:
            return ta
        tc = ta + (math.log(vmin / v) / r if kind == 1.0 else (v - vmin) / -r)
        if tc < tb and tc < t1:
            return tc
    return None
