"""Compiled profile geometry of the dynamics' contact (private): uniform-knot spline
evaluation, the wheel's contact locus (silhouette seen along the rail, Wang 1984; the
formulas of :func:`wheelrail.geometry.contact_search.silhouette`) and the vertical gap to
the rail.

References
----------
.. [1] K. Wang, The track of wheel contact points and the calculation of wheel/rail
   geometric contact parameters, J. Southwest Jiaotong Univ. 1 (1984) 89–99.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

_BIG = 1.0             # gap where the locus is beside the rail [m]


@njit(cache=True, inline="always")
def _idx(u, inv_h, x):
    if inv_h > 0.0:
        i = int((x - u[0]) * inv_h)
    else:
        i = np.searchsorted(u, x) - 1
    if i < 0:
        i = 0
    if i > u.shape[0] - 2:
        i = u.shape[0] - 2
    return i


@njit(cache=True, inline="always")
def _spline(u, inv_h, c, x):
    """Value, slope and second derivative of a PiecewiseCubic at x."""
    i = _idx(u, inv_h, x)
    dx = x - u[i]
    c0, c1, c2, c3 = c[0, i], c[1, i], c[2, i], c[3, i]
    return (((c0 * dx + c1) * dx + c2) * dx + c3, (3.0 * c0 * dx + 2.0 * c1) * dx + c2,
            6.0 * c0 * dx + 2.0 * c1)


@njit(cache=True, inline="always")
def _spline0(u, inv_h, c, x):
    i = _idx(u, inv_h, x)
    dx = x - u[i]
    return ((c[0, i] * dx + c[1, i]) * dx + c[2, i]) * dx + c[3, i]


@njit(cache=True, inline="always")
def _locus(s, p, p1, r0, e_tape, sig, y, zc, st, ct, sp, cp, R, ph0):
    """Contact locus point of wheel coordinate s: (Y, Z, x lead, r) (``silhouette``)."""
    r = r0 - p
    a = sig * (e_tape + s)
    if sp == 0.0:
        return y + (a * ct + r * st), zc + (a * st - r * ct), 0.0, r
    # φ = asin(q) − φ0 with tan φ0 = B/cos ψ; sin φ and cos φ by the angle difference
    # (no trigonometric call: cos φ0 = cos ψ / R, sin φ0 = B / R)
    q = sig * p1 * ct * sp / R
    if q > 1.0:
        q = 1.0
    elif q < -1.0:
        q = -1.0
    cq = math.sqrt(1.0 - q * q)
    c0 = cp / R
    s0 = -st * sp / R
    sf = q * c0 - cq * s0
    cf = cq * c0 + q * s0
    xb = r * sf
    yp = a * ct + r * cf * st
    return y + xb * sp + yp * cp, zc + (a * st - r * cf * ct), xb * cp - r * cf * st * sp, r


@njit(cache=True)
def _gap(s, wu, winv, wc, ru, rinv, rc, r0, e_tape, sig, y, zc, st, ct, sp, cp, R, ph0):
    i = _idx(wu, winv, s)
    dx = s - wu[i]
    c0, c1, c2, c3 = wc[0, i], wc[1, i], wc[2, i], wc[3, i]
    p = ((c0 * dx + c1) * dx + c2) * dx + c3
    p1 = (3.0 * c0 * dx + 2.0 * c1) * dx + c2
    Y, Z, _, _ = _locus(s, p, p1, r0, e_tape, sig, y, zc, st, ct, sp, cp, R, ph0)
    u = sig * Y
    if u < ru[0] or u > ru[ru.shape[0] - 1]:
        return _BIG
    return Z - _spline0(ru, rinv, rc, u)
