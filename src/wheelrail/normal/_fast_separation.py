"""Profile separation of a contact plane for the strip methods, compiled (private).

:func:`separation_fast` computes exactly what
:func:`wheelrail.geometry.separation.separation_at` computes (dense samples
of both profiles around the point, rotated into the contact plane, restricted
to the monotone part, interpolated onto a uniform η grid by the cubic through
the four samples around each node,
:func:`~wheelrail.geometry._local_cubic.local_cubic`) in one numba kernel; the
two agree to round-off (a test checks it). The strip methods call this per wheel
problem and store the result in the problem's cache, where
:meth:`~wheelrail.contact.wheelrail.WheelProblem.separation` finds it.

References
----------
.. [1] C. de Boor, *A practical guide to splines*, Springer 1978, ch. I
   (polynomial interpolation).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..geometry._local_cubic import local_cubic

from ..geometry.contact_search import _SIGMA
from ..geometry.separation import Separation, separation_at

__all__ = ["local_cubic", "separation_fast", "plane_samples", "separation_kernel",
           "separation_window", "rail_slopes"]


@njit(cache=True)
def _cubic_eval(u, c, h, x, order):
    """Value (and slope) of the piecewise cubic (u, c) at x, as ``PiecewiseCubic.eval``
    (uniform breakpoints when h > 0, else a search; end cubics extrapolated)."""
    n = u.shape[0]
    m = x.shape[0]
    f = np.empty(m)
    f1 = np.empty(m)
    for q in range(m):
        if h > 0.0:
            i = int((x[q] - u[0]) * (1.0 / h))
        else:
            i = np.searchsorted(u, x[q]) - 1
        if i < 0:
            i = 0
        elif i > n - 2:
            i = n - 2
        dx = x[q] - u[i]
        c0, c1, c2, c3 = c[0, i], c[1, i], c[2, i], c[3, i]
        f[q] = ((c0 * dx + c1) * dx + c2) * dx + c3
        if order > 0:
            f1[q] = (3.0 * c0 * dx + 2.0 * c1) * dx + c2
    return f, f1


@njit(cache=True)
def plane_samples(s, wu, wc, wh, ur, ru, rc, rh, r0, e_tape, sig, y, zc, theta, psi,
                  C0, C1, gam):
    """Wheel and rail samples in the contact plane of angle ``gam`` through (C0, C1)
    (pure kernel; the sampling part of ``separation_at``).

    Parameters
    ----------
    s : ndarray, shape (m,)
        Wheel profile coordinates [m].
    wu, wc, wh
        Wheel profile curve: breakpoints [m], cubic coefficients (4, n−1), uniform step
        [m] (0: not uniform).
    ur : ndarray, shape (m,)
        Rail profile coordinates [m].
    ru, rc, rh
        Rail profile curve, as for the wheel.
    r0, e_tape, sig : float
        Nominal radius [m], tape-circle half distance [m], +1 right / −1 left.
    y, zc, theta, psi : float
        Pose: lateral shift [m], axle-centre height [m], roll, yaw [rad].
    C0, C1 : float
        Origin of the plane (rail point, side frame) [m].
    gam : float
        Contact angle [rad].

    Returns
    -------
    ew, zw, rw, er, zr : ndarray, shape (m,)
        Tangential and normal coordinates of the wheel silhouette (of
        :func:`~wheelrail.geometry.contact_search.silhouette`) and its circle
        radius, and of the rail samples [m].
    """
    t0, t1 = np.cos(gam), np.sin(gam)
    n0, n1 = -np.sin(gam), np.cos(gam)
    p, p1 = _cubic_eval(wu, wc, wh, s, 1)
    m = s.shape[0]
    ew = np.empty(m)
    zw = np.empty(m)
    rw = np.empty(m)
    st, ct = np.sin(theta), np.cos(theta)
    sp, cp = np.sin(psi), np.cos(psi)
    Bc = -st * sp
    R = np.hypot(cp, Bc)
    ph0 = np.arctan2(Bc, cp)
    for q in range(m):
        r = r0 - p[q]
        a = sig * (e_tape + s[q])
        if psi == 0.0:
            Y = y + (a * ct + r * st)
            Z = zc + (a * st - r * ct)
        else:
            C = -(-sig * p1[q]) * ct * sp
            v = C / R
            v = -1.0 if v < -1.0 else (1.0 if v > 1.0 else v)
            phi = np.arcsin(v) - ph0
            sf, cf = np.sin(phi), np.cos(phi)
            xb = r * sf
            yp = a * ct + r * cf * st
            Y = y + xb * sp + yp * cp
            Z = zc + (a * st - r * cf * ct)
        uw = sig * Y
        ew[q] = (uw - C0) * t0 + (Z - C1) * t1
        zw[q] = (uw - C0) * n0 + (Z - C1) * n1
        rw[q] = r
    zr, _ = _cubic_eval(ru, rc, rh, ur, 0)
    er = (ur - C0) * t0 + (zr - C1) * t1
    zrr = (ur - C0) * n0 + (zr - C1) * n1
    return ew, zw, rw, er, zrr


@njit(cache=True)
def _monotone_bounds(e, c):
    """(start, stop) of the largest run of strictly increasing ``e`` containing index ``c``
    (stop inclusive; :func:`wheelrail.geometry.separation._monotone_window`)."""
    n = e.shape[0]
    start = 0
    for k in range(c - 1, -1, -1):
        if e[k + 1] - e[k] <= 0:
            start = k + 1
            break
    stop = n - 1
    for k in range(c, n - 1):
        if e[k + 1] - e[k] <= 0:
            stop = k
            break
    return start, stop


@njit(cache=True)
def _abs_argmin(e):
    j = 0
    v = abs(e[0])
    for k in range(1, e.shape[0]):
        if abs(e[k]) < v:
            v = abs(e[k])
            j = k
    return j


#: samples kept beyond the evaluation interval on each side of a spline: the influence of a
#: sample (and of the not-a-knot end condition) on the interpolant decays by a factor
#: ≤ 1/2 per sample (2 − √3 ≈ 0.27 on uniform samples), so 64 samples put the effect of
#: cutting the rest below 1e-19 relative, under round-off
_SPLINE_MARGIN = 64


@njit(cache=True)
def _knot_range(e, k0, k1, lo, hi):
    """Sub-range of the increasing samples ``e[k0..k1]`` covering [lo, hi] with
    ``_SPLINE_MARGIN`` samples beyond each end (clipped)."""
    a = k0
    while a < k1 and e[a + 1] <= lo:
        a += 1
    b = k1
    while b > k0 and e[b - 1] >= hi:
        b -= 1
    return max(k0, a - _SPLINE_MARGIN), min(k1, b + _SPLINE_MARGIN)


@njit(cache=True)
def _linspace(a, b, n):
    """``numpy.linspace(a, b, n)`` (the same numbers)."""
    out = np.empty(n)
    step = (b - a) / (n - 1)
    for i in range(n):
        out[i] = i * step + a
    out[n - 1] = b
    return out


@njit(cache=True)
def separation_window(wu, wc, wh, ru, rc, rh, r0, e_tape, sig, y, zc, theta, psi, gam,
                      wheel_y, u_c, width, n, m):
    """:func:`separation_kernel` with its sampling grids: ``m`` wheel samples on
    ``wheel_y ± width`` and ``m`` rail samples on ``u_c ± width`` (clipped to the
    profiles), the plane through the rail point at ``u_c`` (pure kernel)."""
    s = _linspace(max(wu[0], wheel_y - width), min(wu[wu.shape[0] - 1], wheel_y + width), m)
    ur = _linspace(max(ru[0], u_c - width), min(ru[ru.shape[0] - 1], u_c + width), m)
    x = np.empty(1)
    x[0] = u_c
    C1 = _cubic_eval(ru, rc, rh, x, 0)[0][0]
    return separation_kernel(s, wu, wc, wh, ur, ru, rc, rh, r0, e_tape, sig, y, zc, theta,
                             psi, u_c, C1, gam, width, n)


@njit(cache=True)
def rail_slopes(ru, rc, rh, u):
    """Slope dZ/du of the rail curve at ``u`` (``PiecewiseCubic.eval(u, 1)[1]``, same numbers)."""
    return _cubic_eval(ru, rc, rh, u, 1)[1]


@njit(cache=True)
def separation_kernel(s, wu, wc, wh, ur, ru, rc, rh, r0, e_tape, sig, y, zc, theta, psi,
                      C0, C1, gam, width, n):
    """The whole of :func:`separation_fast` after the sampling grids (pure kernel).

    :func:`plane_samples`, the monotone windows of both silhouettes around the
    plane origin, the uniform η grid (as ``numpy.linspace``) and the
    local cubic interpolants (:func:`local_cubic`) of the wheel's distance and radius
    and of the rail.

    Returns
    -------
    ok : bool
        False when a window has fewer than 4 samples (the caller then uses the
        reference implementation).
    eta, f, wheel_radius : ndarray, shape (n,)
    """
    ew, zw, rw, er, zrr = plane_samples(s, wu, wc, wh, ur, ru, rc, rh, r0, e_tape, sig, y, zc,
                                        theta, psi, C0, C1, gam)
    w0, w1 = _monotone_bounds(ew, _abs_argmin(ew))
    r0_, r1_ = _monotone_bounds(er, _abs_argmin(er))
    empty = np.empty(0)
    if w1 - w0 + 1 < 4 or r1_ - r0_ + 1 < 4:
        return False, empty, empty, empty
    lo = max(max(-0.5 * width, ew[w0]), er[r0_])
    hi = min(min(0.5 * width, ew[w1]), er[r1_])
    eta = np.empty(n)
    step = (hi - lo) / (n - 1)
    for i in range(n):
        eta[i] = i * step + lo
    eta[n - 1] = hi
    # the interpolation on the samples around [lo, hi] only (_SPLINE_MARGIN beyond each end)
    w0, w1 = _knot_range(ew, w0, w1, lo, hi)
    r0_, r1_ = _knot_range(er, r0_, r1_, lo, hi)
    nw = w1 - w0 + 1
    Y = np.empty((2, nw))
    for k in range(nw):
        Y[0, k] = zw[w0 + k]
        Y[1, k] = rw[w0 + k]
    W = local_cubic(ew[w0:w1 + 1], Y, eta)
    Z = np.empty((1, r1_ - r0_ + 1))
    for k in range(r1_ - r0_ + 1):
        Z[0, k] = zrr[r0_ + k]
    R = local_cubic(er[r0_:r1_ + 1], Z, eta)
    f = np.empty(n)
    for i in range(n):
        f[i] = W[0, i] - R[0, i]
    return True, eta, f, W[1].copy()


def separation_fast(wheelset, track, side, *, y, z, roll, yaw, wheel_y, track_y, contact_angle,
                    width=0.04, n=401, point=-1, samples=2001):
    """:func:`wheelrail.geometry.separation.separation_at` compiled (same result).

    Parameters and return value as there (SI units: m, rad); ``samples`` profile
    samples of each body on ±2·``width`` (the reference implementation's 2001: 0.04 mm
    on a 40 mm line).
    """

    sig = _SIGMA[side]
    gam = float(contact_angle)
    rc = track.curve(side)
    u_c = sig * float(track_y)
    wc = wheelset.curve(side)
    ok, eta, f, radius = separation_window(
        wc.u, wc.c, wc._h, rc.u, rc.c, rc._h, float(wheelset.nominal_radius),
        float(wheelset.e_tape), sig, float(y), float(wheelset.nominal_radius + z), float(roll),
        float(yaw), gam, float(wheel_y), u_c, float(width), int(n), int(samples))
    if not ok:                           # degenerate window: the reference implementation

        return separation_at(wheelset, track, side, y=y, z=z, roll=roll, yaw=yaw,
                             wheel_y=wheel_y, track_y=track_y, contact_angle=contact_angle,
                             width=width, n=n, point=point, samples=samples)
    cosf = float(np.cos(gam - sig * roll))
    return Separation(eta, f, radius, cosf, gam, side, float(y), float(yaw), int(point))
