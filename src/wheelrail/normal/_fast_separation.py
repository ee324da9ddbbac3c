"""Profile separation of a contact plane for the strip methods, with a numba spline (private).

:func:`separation_fast` computes exactly what
:func:`wheelrail.geometry.separation.separation_at` computes (dense samples
of both profiles around the point, rotated into the contact plane, restricted
to the monotone part, interpolated onto a uniform η grid by not-a-knot cubic
splines), but builds the splines in one numba kernel instead of three
``scipy.interpolate.CubicSpline`` objects, which take two thirds of the time
of a separation. The not-a-knot cubic interpolant is unique, so the two agree
to round-off (a test checks it); the strip methods call this per wheel problem
and store the result in the problem's cache, where
:meth:`~wheelrail.contact.wheelrail.WheelProblem.separation` finds it.

References
----------
.. [1] C. de Boor, *A practical guide to splines*, Springer 1978, ch. IV
   (cubic spline interpolation, not-a-knot end condition).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..geometry.contact_search import _SIGMA
from ..geometry.separation import Separation, separation_at

__all__ = ["spline_not_a_knot", "local_cubic", "separation_fast", "plane_samples", "separation_kernel",
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
def local_cubic(x, Y, t):
    """Cubic interpolants of the rows of ``Y`` at increasing ``t``, each through the four
    samples around it (x[j−1] … x[j+2] for x[j] ≤ t < x[j+1]; pure kernel).

    On profile samples 0.04 mm apart it differs from the not-a-knot spline through
    all samples by less than 2 nm (mostly < 0.2 nm; the most next to a jump of a
    profile's curvature; both are exact for cubics), and it is
    what the compiled dynamics evaluates node by node, so both give one line at any
    sample spacing.

    Parameters
    ----------
    x : ndarray, shape (n,)
        Strictly increasing abscissae, n ≥ 4.
    Y : ndarray, shape (k, n)
    t : ndarray, shape (m,)
        Increasing evaluation points.

    Returns
    -------
    ndarray, shape (k, m)
    """
    n = x.shape[0]
    k = Y.shape[0]
    out = np.empty((k, t.shape[0]))
    j = 1
    for i in range(t.shape[0]):
        e = t[i]
        while j < n - 3 and x[j + 1] < e:
            j += 1
        x0, x1, x2, x3 = x[j - 1], x[j], x[j + 1], x[j + 2]
        a0, a1, a2, a3 = e - x0, e - x1, e - x2, e - x3
        w0 = a1 * a2 * a3 / ((x0 - x1) * (x0 - x2) * (x0 - x3))
        w1 = a0 * a2 * a3 / ((x1 - x0) * (x1 - x2) * (x1 - x3))
        w2 = a0 * a1 * a3 / ((x2 - x0) * (x2 - x1) * (x2 - x3))
        w3 = a0 * a1 * a2 / ((x3 - x0) * (x3 - x1) * (x3 - x2))
        for r in range(k):
            out[r, i] = w0 * Y[r, j - 1] + w1 * Y[r, j] + w2 * Y[r, j + 1] + w3 * Y[r, j + 2]
    return out


@njit(cache=True)
def spline_not_a_knot(x, Y, t):
    """Not-a-knot cubic spline interpolants of the rows of ``Y`` at ``t`` (pure kernel).

    Parameters
    ----------
    x : ndarray, shape (n,)
        Strictly increasing abscissae, n ≥ 4.
    Y : ndarray, shape (k, n)
        Ordinates (one interpolant per row).
    t : ndarray, shape (m,)
        Evaluation points, increasing, inside [x[0], x[-1]].

    Returns
    -------
    ndarray, shape (k, m)

    Notes
    -----
    The node slopes s solve the tridiagonal system of C² continuity with the
    not-a-knot end rows (third derivative continuous at x[1] and x[-2]),
    by Gaussian elimination without pivoting (the eliminated diagonal stays
    ≥ its off-diagonal neighbours for the near-uniform spacing of profile
    samples); each interval is then the cubic Hermite polynomial of its end
    values and slopes.
    """
    n = x.shape[0]
    k = Y.shape[0]
    m = t.shape[0]
    dx = np.empty(n - 1)
    idx = np.empty(n - 1)                # 1/dx: multiplications instead of divisions
    for i in range(n - 1):
        dx[i] = x[i + 1] - x[i]
        idx[i] = 1.0 / dx[i]
    # matrix rows: sub[i] s[i-1] + dia[i] s[i] + sup[i] s[i+1] = rhs[i]; the forward
    # elimination factors w, c (and 1/c) are shared by all rows of Y
    sup = np.zeros(n)
    c = np.empty(n)
    w = np.empty(n)
    ic = np.empty(n)
    c[0] = dx[1]
    sup[0] = x[2] - x[0]
    for i in range(1, n - 1):
        sup[i] = dx[i - 1]
    ic[0] = 1.0 / c[0]
    for i in range(1, n):
        if i < n - 1:
            sub = dx[i]
            dia = 2.0 * (dx[i - 1] + dx[i])
        else:
            sub = x[n - 1] - x[n - 3]
            dia = dx[n - 3]
        w[i] = sub * ic[i - 1]
        c[i] = dia - w[i] * sup[i - 1]
        ic[i] = 1.0 / c[i]
    jj = np.empty(m, np.int64)           # interval of each evaluation point (all rows)
    j = 0
    for q in range(m):
        while j < n - 2 and t[q] > x[j + 1]:
            j += 1
        jj[q] = j
    out = np.empty((k, m))
    slope = np.empty((k, n - 1))
    rhs = np.empty((k, n))
    s = np.empty((k, n))
    d0 = x[2] - x[0]
    d1 = x[n - 1] - x[n - 3]
    for r in range(k):
        for i in range(n - 1):
            slope[r, i] = (Y[r, i + 1] - Y[r, i]) * idx[i]
        rhs[r, 0] = ((dx[0] + 2.0 * d0) * dx[1] * slope[r, 0]
                     + dx[0] * dx[0] * slope[r, 1]) / d0
        for i in range(1, n - 1):
            rhs[r, i] = 3.0 * (dx[i] * slope[r, i - 1] + dx[i - 1] * slope[r, i])
        rhs[r, n - 1] = ((dx[n - 2] * dx[n - 2] * slope[r, n - 3]
                          + (2.0 * d1 + dx[n - 2]) * dx[n - 3] * slope[r, n - 2]) / d1)
    # the eliminations are chains along i: the rows run side by side (independent chains
    # overlap in the processor), each row with exactly its own operations
    for i in range(1, n):
        wi = w[i]
        for r in range(k):
            rhs[r, i] -= wi * rhs[r, i - 1]
    for r in range(k):
        s[r, n - 1] = rhs[r, n - 1] * ic[n - 1]
    for i in range(n - 2, -1, -1):
        su = sup[i]
        ci = ic[i]
        for r in range(k):
            s[r, i] = (rhs[r, i] - su * s[r, i + 1]) * ci
    for r in range(k):
        for q in range(m):
            j = jj[q]
            ih = idx[j]
            tt = (s[r, j] + s[r, j + 1] - 2.0 * slope[r, j]) * ih
            c0 = tt * ih
            c1 = (slope[r, j] - s[r, j]) * ih - tt
            u = t[q] - x[j]
            out[r, q] = ((c0 * u + c1) * u + s[r, j]) * u + Y[r, j]
    return out


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
    # the splines on the samples around [lo, hi] only (_SPLINE_MARGIN beyond each end)
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
    """:func:`wheelrail.geometry.separation.separation_at` with the numba spline (same result).

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
                             width=width, n=n, point=point)
    cosf = float(np.cos(gam - sig * roll))
    return Separation(eta, f, radius, cosf, gam, side, float(y), float(yaw), int(point))
