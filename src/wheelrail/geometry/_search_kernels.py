"""Numba kernels of the rigid contact search (private; see :mod:`.contact_search`).

Scalar versions of the vectorised search of :mod:`wheelrail.geometry.contact_search`,
with the same arithmetic: the vertical gap of one wheel point
(:func:`~wheelrail.geometry.contact_search._gap`), the parabolic refinement of a
minimum (:func:`~wheelrail.geometry.contact_search._refine`), the refined global
minimum of the gap of one pose (:func:`~wheelrail.geometry.contact_search._global_min`)
and the damped Newton iteration on (z, θ) of the rigid contact constraint
(Bosso et al. (2013), ch. 2, eqs. 2.1–2.3; :func:`~wheelrail.geometry.contact_search.solve_rigid`).
Running them as compiled loops removes the per-iteration array overhead that
dominates a single wheelset position (one ``wr.solve`` per time step of a
vehicle-dynamics simulation).

Splines are passed as ``(u, inv_h, c)``: breakpoints, the inverse of their
spacing (0 for a non-uniform spline: binary search) and the (4, n−1)
coefficients of :class:`~wheelrail.geometry._curves.PiecewiseCubic`.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = []


@njit(cache=True)
def _index(u, inv_h, x):  # pragma: no cover - compiled
    if inv_h > 0.0:
        i = int((x - u[0]) * inv_h)
    else:
        i = np.searchsorted(u, x) - 1
    if i < 0:
        i = 0
    if i > u.size - 2:
        i = u.size - 2
    return i


@njit(cache=True)
def _eval0(u, inv_h, c, x):  # pragma: no cover - compiled
    i = _index(u, inv_h, x)
    dx = x - u[i]
    return ((c[0, i] * dx + c[1, i]) * dx + c[2, i]) * dx + c[3, i]


@njit(cache=True)
def _eval1(u, inv_h, c, x):  # pragma: no cover - compiled
    i = _index(u, inv_h, x)
    dx = x - u[i]
    c0, c1, c2, c3 = c[0, i], c[1, i], c[2, i], c[3, i]
    return ((c0 * dx + c1) * dx + c2) * dx + c3, (3.0 * c0 * dx + 2.0 * c1) * dx + c2


@njit(cache=True)
def _silhouette(s, p, p1, r0, e_tape, sig, y, zc, th, psi):  # pragma: no cover - compiled
    """One point of :func:`~wheelrail.geometry.contact_search.silhouette`: (Y, Z, x_r),
    x_r the point's longitudinal lead in the track frame (0 without yaw)."""
    r = r0 - p
    a = sig * (e_tape + s)
    st, ct = math.sin(th), math.cos(th)
    if psi == 0.0:
        return y + (a * ct + r * st), zc + (a * st - r * ct), 0.0
    sp, cp = math.sin(psi), math.cos(psi)
    r_a = -sig * p1
    Bc = -st * sp
    C = -r_a * ct * sp
    R = math.hypot(cp, Bc)
    q = min(max(C / R, -1.0), 1.0)
    phi = math.asin(q) - math.atan2(Bc, cp)
    sf, cf = math.sin(phi), math.cos(phi)
    xb = r * sf
    yp = a * ct + r * cf * st
    zp = a * st - r * cf * ct
    return y + xb * sp + yp * cp, zc + zp, xb * cp - r * cf * st * sp


@njit(cache=True)
def _gap_point(s, wu, winv, wc, ru, rinv, rc, r0, e_tape, sig, y, zc, th, psi,
               big):  # pragma: no cover - compiled
    """Vertical gap wheel − rail at wheel coordinate ``s`` (as ``contact_search._gap``)."""
    p, p1 = _eval1(wu, winv, wc, s)
    Y, Z, _ = _silhouette(s, p, p1, r0, e_tape, sig, y, zc, th, psi)
    u = sig * Y
    if u < ru[0] or u > ru[-1]:
        return big
    return Z - _eval0(ru, rinv, rc, u)


#: Largest number of levels of the parabolic refinement, refining and moving ones together
#: (:func:`_parabolic_point`, ``contact_search._parabolic``).
_REFINE_MAX_ITER = 48
#: Sub-grid points per grid step of the basin scan (:func:`_refine_point`,
#: ``contact_search._refine``).
_BASIN = 8
#: A sub-grid point of the basin scan lower than the refined minimum by more than this [m]
#: holds another minimum.
_BASIN_MARGIN = 1e-12


@njit(cache=True)
def _parabolic_point(s0, h, lo, hi, levels, wu, winv, wc, ru, rinv, rc, r0, e_tape, sig, y, zc,
                     th, psi, big):  # pragma: no cover - compiled
    """Successive parabolic interpolation from ``s0`` (``contact_search._parabolic``): (s, f).

    A level whose centre is not the best point so far does not count: the search moves to
    the best point with the same ``h``.
    """
    s = s0
    best_s = s
    best_f = np.inf
    done = 0
    for _ in range(_REFINE_MAX_ITER):
        if done >= levels:
            break
        sm = max(s - h, lo)
        sp = min(s + h, hi)
        fm = _gap_point(sm, wu, winv, wc, ru, rinv, rc, r0, e_tape, sig, y, zc, th, psi, big)
        f0 = _gap_point(s, wu, winv, wc, ru, rinv, rc, r0, e_tape, sig, y, zc, th, psi, big)
        fp = _gap_point(sp, wu, winv, wc, ru, rinv, rc, r0, e_tape, sig, y, zc, th, psi, big)
        if f0 < best_f:
            best_s, best_f = s, f0
        if fm < best_f:
            best_s, best_f = sm, fm
        if fp < best_f:
            best_s, best_f = sp, fp
        if best_s != s:
            s = best_s       # not bracketed here: continue from the best point, same h
            continue
        den = fm - 2.0 * f0 + fp
        if den > 0.0:
            shift = 0.5 * h * (fm - fp) / den
        elif fm < fp:
            shift = -h
        else:
            shift = h
        shift = min(max(shift, -h), h)
        s = min(max(s + shift, lo), hi)
        h = h / 8.0
        done += 1
    f = _gap_point(s, wu, winv, wc, ru, rinv, rc, r0, e_tape, sig, y, zc, th, psi, big)
    if f <= best_f:
        return s, f
    return best_s, best_f


@njit(cache=True)
def _refine_point(s0, h, lo, hi, levels, wu, winv, wc, ru, rinv, rc, r0, e_tape, sig, y, zc,
                  th, psi, big):  # pragma: no cover - compiled
    """One point of ``contact_search._refine``: the lowest minimum within ``h`` of ``s0``.

    Parabolic refinement from ``s0``, then a scan of ``[s0 − h, s0 + h]`` at ``h/8``: a
    sub-grid point lower than the refined minimum (a second minimum in the grid cell, as
    at a jump of the contact point) is refined from there with ``h/8``.
    """
    s1, f1 = _parabolic_point(s0, h, lo, hi, levels, wu, winv, wc, ru, rinv, rc, r0, e_tape,
                              sig, y, zc, th, psi, big)
    hs = h / _BASIN
    kbest = 0
    fbest = f1 - _BASIN_MARGIN
    for k in range(-_BASIN, _BASIN + 1):
        sk = min(max(s0 + k * hs, lo), hi)
        fk = _gap_point(sk, wu, winv, wc, ru, rinv, rc, r0, e_tape, sig, y, zc, th, psi, big)
        if fk < fbest:
            kbest, fbest = k, fk
    if fbest < f1 - _BASIN_MARGIN:
        s2, f2 = _parabolic_point(min(max(s0 + kbest * hs, lo), hi), hs, lo, hi, levels, wu,
                                  winv, wc, ru, rinv, rc, r0, e_tape, sig, y, zc, th, psi, big)
        if f2 < f1:
            return s2
    return s1


@njit(cache=True)
def grid_gap_row(s, p, p1, r0, e_tape, sig, y, zc, th, psi, u0, hu, c, big,
                 out):  # pragma: no cover - compiled
    """Vertical gap on the search grid for one pose, written to ``out`` (shape (n_grid,)).

    The arithmetic of ``contact_search._grid_gap_kernel`` (rail spline ``c`` (4, m)
    on the equidistant grid ``u0 + hu k``).
    """
    m = c.shape[1]
    u1 = u0 + hu * m
    st, ct = np.sin(th), np.cos(th)
    sp, cp = np.sin(psi), np.cos(psi)
    Bc = -st * sp
    R = np.sqrt(cp * cp + Bc * Bc)
    beta = np.arctan2(Bc, cp)
    for j in range(s.size):
        r = r0 - p[j]
        a = sig * (e_tape + s[j])
        if psi == 0.0:
            sf, cf = 0.0, 1.0
        else:
            q = (sig * p1[j]) * ct * sp / R
            q = min(1.0, max(-1.0, q))
            phi = np.arcsin(q) - beta
            sf, cf = np.sin(phi), np.cos(phi)
        xb = r * sf
        yp = a * ct + r * cf * st
        Y = y + xb * sp + yp * cp
        Z = zc + a * st - r * cf * ct
        u = sig * Y
        if u < u0 or u > u1:
            out[j] = big
            continue
        i = int((u - u0) / hu)
        if i > m - 1:
            i = m - 1
        dx = u - (u0 + i * hu)
        zr = ((c[0, i] * dx + c[1, i]) * dx + c[2, i]) * dx + c[3, i]
        out[j] = Z - zr


@njit(cache=True)
def global_min_row(sg, pg, p1g, lo, hi, h, wu, winv, wc, ru, rinv, rc, rh, r0, e_tape, sig,
                   y, zc, th, psi, levels, big, d):  # pragma: no cover - compiled
    """Refined global minimum of the gap of one pose: (s*, d*, lever).

    As ``contact_search._global_min``: the gap on the grid ``sg`` (wheel
    heights ``pg``, slopes ``p1g``), its two lowest local minima (the
    global grid minimum and the lowest interior minimum besides it) refined
    by :func:`_refine_point`, the lower one kept; ``lever`` is the gap's
    sensitivity to the roll angle. ``d`` is a work array of the grid's size.
    Without a second local minimum only the global one is refined (the array
    code refined a grid point picked by ``argpartition`` among equal ``inf``
    entries there, which depends on the CPU's sorting kernel).
    """
    grid_gap_row(sg, pg, p1g, r0, e_tape, sig, y, zc, th, psi, ru[0], rh, rc, big, d)
    n = sg.size
    gi = 0
    for j in range(1, n):
        if d[j] < d[gi]:
            gi = j
    # second candidate: the lowest interior minimum other than the global one
    si = -1
    for j in range(1, n - 1):
        if j == gi:
            continue
        if d[j] < d[j - 1] and d[j] <= d[j + 1] and d[j - 1] < big and d[j + 1] < big:
            if si < 0 or d[j] < d[si]:
                si = j
    if si < 0:
        si = gi
    sa = _refine_point(sg[gi], h, lo, hi, levels, wu, winv, wc, ru, rinv, rc, r0, e_tape, sig,
                       y, zc, th, psi, big)
    da = _gap_point(sa, wu, winv, wc, ru, rinv, rc, r0, e_tape, sig, y, zc, th, psi, big)
    if si != gi:
        sb = _refine_point(sg[si], h, lo, hi, levels, wu, winv, wc, ru, rinv, rc, r0, e_tape,
                           sig, y, zc, th, psi, big)
        db = _gap_point(sb, wu, winv, wc, ru, rinv, rc, r0, e_tape, sig, y, zc, th, psi, big)
    else:
        sb, db = sa, da
    s1 = sb if db < da else sa
    d1 = min(da, db)
    p, p1 = _eval1(wu, winv, wc, s1)
    Y, Z, _ = _silhouette(s1, p, p1, r0, e_tape, sig, y, zc, th, psi)
    _, t = _eval1(ru, rinv, rc, sig * Y)
    lever = (Y - y) + sig * t * (Z - zc)
    return s1, d1, lever


@njit(cache=True)
def global_min_rows(sg, pg, p1g, lo, hi, h, wu, winv, wc, ru, rinv, rc, rh, r0, e_tape, sig,
                    y, zc, th, psi, levels, big):  # pragma: no cover - compiled
    """:func:`global_min_row` for every row of the pose arrays (shape (n,))."""
    n = y.size
    s_out, d_out, l_out = np.empty(n), np.empty(n), np.empty(n)
    d = np.empty(sg.size)
    for k in range(n):
        s_out[k], d_out[k], l_out[k] = global_min_row(
            sg, pg, p1g, lo, hi, h, wu, winv, wc, ru, rinv, rc, rh, r0, e_tape, sig, y[k], zc[k],
            th[k], psi[k], levels, big, d)
    return s_out, d_out, l_out


@njit(cache=True, error_model="numpy")
def newton_rows(gL, gR, y, yaw, z, th, r0, tol, maxiter, max_dth, max_dz,
                big):  # pragma: no cover - compiled
    """Damped Newton iteration on (z, θ) of the rigid constraint for all rows.

    ``gL``, ``gR``: the arguments of :func:`global_min_row` before the pose
    (grid, spline data, r0, e_tape, σ) of the left and right wheel, as tuples.
    Same iteration as ``contact_search._newton`` (the refinement depth is
    shared by the active rows: 3 levels until a row's residual falls below
    ``tol``, then 5 for all). Returns z, θ, wheel coordinates (left, right),
    residual and a code per row (0 converged, 3 a wheel beside its rail, 4
    not converged).
    """
    n = y.size
    code = np.full(n, 4, dtype=np.int8)
    sL_out, sR_out = np.full(n, np.nan), np.full(n, np.nan)
    res_out = np.full(n, np.inf)
    levels = np.full(n, 3, dtype=np.int64)
    active = np.ones(n, dtype=np.bool_)
    z, th = z.copy(), th.copy()
    dL = np.empty(gL[0].size)
    dR = np.empty(gR[0].size)
    sL, lL, gl = np.empty(n), np.empty(n), np.empty(n)
    sR, lR, gr = np.empty(n), np.empty(n), np.empty(n)
    for _ in range(maxiter):
        lev = 0
        nact = 0
        for k in range(n):
            if active[k]:
                nact += 1
                lev = max(lev, levels[k])
        if nact == 0:
            break
        for k in range(n):
            if not active[k]:
                continue
            zc = r0 + z[k]
            sL[k], gl[k], lL[k] = global_min_row(
                gL[0], gL[1], gL[2], gL[3], gL[4], gL[5], gL[6], gL[7], gL[8], gL[9], gL[10],
                gL[11], gL[12], gL[13], gL[14], gL[15], y[k], zc, th[k], yaw[k], lev, big, dL)
            sR[k], gr[k], lR[k] = global_min_row(
                gR[0], gR[1], gR[2], gR[3], gR[4], gR[5], gR[6], gR[7], gR[8], gR[9], gR[10],
                gR[11], gR[12], gR[13], gR[14], gR[15], y[k], zc, th[k], yaw[k], lev, big, dR)
        for k in range(n):
            if not active[k]:
                continue
            beside = gl[k] >= big or gr[k] >= big
            res = max(abs(gl[k]), abs(gr[k]))
            done = (not beside) and res < tol and levels[k] == 5
            if beside:
                code[k] = 3
            if done:
                code[k] = 0
            sL_out[k], sR_out[k] = sL[k], sR[k]
            res_out[k] = np.inf if beside else res
            if (not beside) and res < tol:
                levels[k] = 5
            keep = (not beside) and (not done)
            dth = -(gr[k] - gl[k]) / (lR[k] - lL[k])
            if not np.isfinite(dth):
                dth = 0.0
            dth = min(max(dth, -max_dth), max_dth)
            dz = min(max(-gr[k] - lR[k] * dth, -max_dz), max_dz)
            if keep and res >= tol:
                th[k] += dth
                z[k] += dz
            active[k] = keep
    return z, th, sL_out, sR_out, res_out, code


@njit(cache=True)
def refine_rows(sg, pg, p1g, lo, hi, h, wu, winv, wc, ru, rinv, rc, rh, r0, e_tape, sig,
                s0, y, zc, th, psi, levels, big):  # pragma: no cover - compiled
    """:func:`_refine_point` for every start point ``s0`` with its pose (arrays of shape (n,))."""
    out = np.empty(s0.size)
    for k in range(s0.size):
        out[k] = _refine_point(s0[k], h, lo, hi, levels, wu, winv, wc, ru, rinv, rc, r0, e_tape,
                               sig, y[k], zc[k], th[k], psi[k], big)
    return out


#: Rows of the output of :func:`point_data_rows`, in the order of ``contact_search.POINT_FIELDS``.
POINT_ROWS = ("wheel_y", "wheel_z", "rail_y", "rail_z", "track_y", "track_z", "x",
              "contact_angle", "rolling_radius", "wheel_curvature_x", "wheel_curvature_y",
              "rail_curvature_y", "A", "B", "separation", "gap")


@njit(cache=True)
def point_data_rows(s, y, zc, th, psi, wu, winv, wc, ru, rinv, rc, r0, e_tape, sig, offset,
                    z_top, angle):  # pragma: no cover - compiled
    """Per-point quantities at wheel coordinates ``s`` with their poses (arrays (n,)).

    The formulas of ``contact_search.point_data`` (see :data:`POINT_ROWS`);
    ``offset``, ``z_top``, ``angle``: the rail placement
    (:class:`~wheelrail.geometry.track.RailPlacement`). Returns shape (16, n).
    """
    n = s.size
    out = np.empty((16, n))
    ca, sa = math.cos(-angle), math.sin(-angle)
    for k in range(n):
        i = _index(wu, winv, s[k])
        dx = s[k] - wu[i]
        c0, c1, c2, c3 = wc[0, i], wc[1, i], wc[2, i], wc[3, i]
        p = ((c0 * dx + c1) * dx + c2) * dx + c3
        p1 = (3.0 * c0 * dx + 2.0 * c1) * dx + c2
        p2 = 6.0 * c0 * dx + 2.0 * c1
        r = r0 - p
        Y, Z, xr = _silhouette(s[k], p, p1, r0, e_tape, sig, y[k], zc[k], th[k], psi[k])
        u = sig * Y
        j = _index(ru, rinv, u)
        du = u - ru[j]
        d0, d1, d2, d3 = rc[0, j], rc[1, j], rc[2, j], rc[3, j]
        zr = ((d0 * du + d1) * du + d2) * du + d3
        zr1 = (3.0 * d0 * du + 2.0 * d1) * du + d2
        zr2 = 6.0 * d0 * du + 2.0 * d1
        gap = Z - zr
        gamma = math.atan(zr1)
        kwx = 1.0 / (r * math.sqrt(1.0 + p1 * p1))
        kwy = p2 / (1.0 + p1 * p1) ** 1.5
        kry = -(zr2 / (1.0 + zr1 * zr1) ** 1.5)
        yr, zz = u - offset, zr + z_top
        out[0, k] = s[k]
        out[1, k] = p
        out[2, k] = ca * yr - sa * zz
        out[3, k] = sa * yr + ca * zz
        out[4, k] = Y
        out[5, k] = Z
        out[6, k] = xr
        out[7, k] = gamma
        out[8, k] = r
        out[9, k] = kwx
        out[10, k] = kwy
        out[11, k] = kry
        out[12, k] = 0.5 * kwx
        out[13, k] = 0.5 * (kwy + kry)
        out[14, k] = gap * math.cos(gamma)
        out[15, k] = gap
    return out


@njit(cache=True)
def select_minima(d, threshold, merge, big):  # pragma: no cover - compiled
    """Candidate grid minima of every row of the gap ``d`` (n_rows, n_grid): (rows, idx).

    As ``contact_search.find_points``: the interior local minima off the rail
    ends with a gap ≤ ``threshold`` and the global minimum of each row, in
    row-major order; neighbouring minima separated by a hump lower than
    ``merge`` are one (the lower kept).
    """
    nrow, ns = d.shape
    rows = np.empty(nrow * ns, dtype=np.int64)
    idx = np.empty(nrow * ns, dtype=np.int64)
    m = 0
    for r in range(nrow):
        g = 0
        for j in range(1, ns):
            if d[r, j] < d[r, g]:
                g = j
        for j in range(ns):
            cand = j == g
            if not cand and 0 < j < ns - 1:
                cand = (d[r, j] < d[r, j - 1] and d[r, j] <= d[r, j + 1] and d[r, j - 1] < big
                        and d[r, j + 1] < big and d[r, j] <= threshold)
            if cand:
                rows[m] = r
                idx[m] = j
                m += 1
    keep = np.ones(m, dtype=np.bool_)
    for k in range(1, m):
        if rows[k] != rows[k - 1]:
            continue
        j = k - 1
        while j >= 0 and not keep[j] and rows[j] == rows[k]:
            j -= 1
        if j < 0 or rows[j] != rows[k]:
            continue
        r, i1, i2 = rows[k], idx[j], idx[k]
        hump = d[r, i1]
        for i in range(i1 + 1, i2 + 1):
            if d[r, i] > hump:
                hump = d[r, i]
        if hump - max(d[r, i1], d[r, i2]) < merge:
            if d[r, i2] < d[r, i1]:
                keep[j] = False
            else:
                keep[k] = False
    n = 0
    for k in range(m):
        if keep[k]:
            rows[n] = rows[k]
            idx[n] = idx[k]
            n += 1
    return rows[:n].copy(), idx[:n].copy()


@njit(cache=True)
def order_points(rows, sref, sep, tolerance, nrow):  # pragma: no cover - compiled
    """Kept refined points, ordered by row and decreasing wheel coordinate (indices).

    As ``contact_search.find_points``: a point is kept if its separation is
    ≤ ``tolerance`` or the smallest of its row, and not within 1 µm of the
    previous kept point of its row (two grid minima refined to one point).
    ``rows`` must be sorted (row-major candidates).
    """
    n = rows.size
    rowmin = np.full(nrow, np.inf)
    for k in range(n):
        if sep[k] < rowmin[rows[k]]:
            rowmin[rows[k]] = sep[k]
    out = np.empty(n, dtype=np.int64)
    m = 0
    start = 0
    while start < n:
        stop = start
        while stop < n and rows[stop] == rows[start]:
            stop += 1
        # stable insertion sort by decreasing wheel coordinate (a few points per row)
        order = np.arange(start, stop)
        for i in range(1, stop - start):
            k = order[i]
            j = i - 1
            while j >= 0 and -sref[order[j]] > -sref[k]:
                order[j + 1] = order[j]
                j -= 1
            order[j + 1] = k
        last_s = np.nan
        first = True
        for k in order:
            if not (sep[k] <= tolerance or sep[k] == rowmin[rows[k]]):
                continue
            if not first and abs(sref[k] - last_s) < 1e-6:
                continue
            first = False
            last_s = sref[k]
            out[m] = k
            m += 1
        start = stop
    return out[:m].copy()
