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

__all__ = ["profile_at", "profile_eval"]


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
