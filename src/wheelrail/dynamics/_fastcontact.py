"""Compiled contact of one wheel on its rail for the time integration (private).

One call of :func:`wheel_contact` does for one wheel what
:func:`wheelrail.contact.wheelrail.solve_wheelrail` does with a prescribed
height (``z=``), in one numba function so that a wheelset position costs tens
of microseconds instead of milliseconds:

1. **contact search** — the vertical gap d(s) between the wheel's contact locus
   (its silhouette seen along the rail, Wang 1984; the formulas of
   :func:`wheelrail.geometry.contact_search.silhouette`) and the rail, on a grid
   of the wheel profile coordinate restricted to the part above the rail, its
   local minima refined by successive parabolic interpolation (as
   :func:`~wheelrail.geometry.contact_search._refine`); the point quantities
   (contact angle, curvatures, position) as
   :func:`wheelrail.geometry._search_kernels.point_data_rows`. The vertical
   approach is dz = −min d; a point's penetration is −d_k cos γ_k (the library's
   ``dz cos γ − separation``).
2. **normal problem** — Hertz at every penetrating point (Hertz's unit-load
   solution interpolated in ln(A/B), :func:`wheelrail.normal._strips.hertz_shape`)
   or Kik–Piotrowski's virtual penetration on the profile separation of each
   contact plane (Piotrowski & Chollet 2005, §3.2, eqs. 12–22), on the very
   line of the library (``VirtualPenetration._wheel_lines``: the
   ``KikPiotrowski.line_nodes`` nodes of
   :func:`~wheelrail.normal._fast_separation.separation_window` over the
   monotone part of ±20 mm around the point, the same profile samples and the
   same local cubic interpolation), of which only the nodes around the
   interpenetration are evaluated; the regions, loads
   and strip peaks by the library's kernel
   :func:`~wheelrail.normal._kp_kernel.kp_line_regions`, the patch's contact
   angle and position by :func:`~wheelrail.normal._patch_kernel.weighted_means`,
   the strips as :func:`~wheelrail.normal._patch_kernel.strip_patch` makes them;
   so the patches are those of :func:`wheelrail.solve` at the same vertical
   approach (tests/dynamics/test_dynamics_contact_stack.py: every force within
   1e-4 μQ on Manchester A-2.2 and at flange contacts);
3. **creepages** at each patch from the wheelset's velocities (the formulas of
   :func:`wheelrail.geometry.kinematics.creepage_kernel`) and **creep forces** by
   FASTSIM (Kalker 1982; the library's kernel
   :func:`~wheelrail.tangential._fastsim_kernel.fastsim_hertz_batch` for
   ellipses; on strip patches the resampling and weighted flexibility of
   ``Fastsim.solve_patch`` and the march of
   :func:`~wheelrail.dynamics._fastlaws.march_strips`, the same numbers) or by
   interpolation in the exact-theory table of
   :class:`wheelrail.tangential.Table` (multilinear, in the frame of the
   full-slip direction, as :class:`~wheelrail.tangential.table.TableData`);
4. the forces in the track frame and their **generalised forces** on the
   wheelset (lateral, vertical, roll, yaw, spin), split into the normal and the
   tangential (creep) part.

Frames and signs are those of :mod:`wheelrail.conventions` and
:mod:`wheelrail.geometry.contact_search` (track frame x forward, y right, z up;
roll positive with the right wheel higher, yaw positive with the right wheel
moving backwards; forces on the wheel, Kalker's sign convention).

References
----------
.. [1] J. Piotrowski, H. Chollet, Wheel–rail contact models for vehicle system
   dynamics including multi-point contact, VSD 43 (2005) 455–483, §1, §3.2
   (multiple patches evaluated online during the integration).
.. [2] J.J. Kalker, A fast algorithm for the simplified theory of rolling
   contact, VSD 11 (1982) 1–13.
.. [3] K. Wang, The track of wheel contact points and the calculation of
   wheel/rail geometric contact parameters, J. Southwest Jiaotong Univ. 1
   (1984) 89–99.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..normal._kp_kernel import kp_line_regions, kpec_line_regions
from ..normal._patch_kernel import weighted_means
from ._fastgeom import _BIG, _gap, _locus, _spline, _spline0
from ._fastline import _COARSE, _LINE_WIDTH, _SAMPLE_HALF, _line_nodes, _run_end
from ._fastlaws import (_interp, _kalker, creepage, fastsim_ellipse, kp_strip_fastsim,
                        kp_strips, linear_forces, table_forces)

__all__ = ["wheel_contact", "PATCH_FIELDS", "WHEEL_FIELDS", "KMAX", "MP"]

#: Largest number of patches reported per wheel (more are solved, the smallest dropped).
KMAX = 4
#: Columns of the per-patch output of :func:`wheel_contact`.
PATCH_FIELDS = ("Fn", "Fx", "Fs", "Mz", "contact_angle", "track_y", "track_z", "x", "wheel_y",
                "rail_y", "a", "b", "xi", "eta", "phi", "p_max", "rolling_radius",
                "penetration", "Fy_track", "Fz_track", "fallback")
#: Entries of the per-wheel output of :func:`wheel_contact`.
WHEEL_FIELDS = ("patches", "Qn_y", "Qn_z", "Qn_roll", "Qn_yaw", "Qn_spin", "Qt_y", "Qt_z",
                "Qt_roll", "Qt_yaw", "Qt_spin", "Fx", "Fy", "Fz", "vertical_approach",
                "min_gap", "fallbacks", "a_mean", "candidates")
_NP = len(PATCH_FIELDS)
_KC = 8                # candidate minima kept per wheel
#: Golden-section levels of a minimum's refinement before its parabolic step: the bracket
#: ±0.5 mm shrinks to 8 µm (golden section alone needed 18 levels, 0.2 µm, for a gap
#: smooth enough in the pose for the equilibria's finite-difference Jacobians).
_LEVELS = 10

#: Indices of the method parameters (the float array ``mp``).
MP = {name: i for i, name in enumerate((
    "normal", "tangential", "E_star", "G", "nu", "K", "eps", "shape_correction", "strips",
    "cells", "line_stride", "line_half_width", "group_angle", "tolerance", "nx", "ny",
    "parabolic", "weighted", "first_order", "search_step", "table_fallback", "stop",
    "connected", "line_nodes", "samples", "kpec", "combined"))}


@njit(cache=True)
def _refine(s0, h, lo, hi, levels, wu, winv, wc, ru, rinv, rc, r0, e_tape, sig, y, zc, st, ct,
            sp, cp, R, ph0):
    """Minimum of the gap in [s0 − h, s0 + h]: golden-section search to h·0.618**levels,
    then the vertex of the parabola through the bracket's best three evaluated points
    (the best of it and the golden-section points is returned).

    The golden section is robust where the gap has a kink (a jump of a profile's
    curvature at the contact point), where parabolic interpolation from a coarse grid
    can stall; the final vertex makes the minimum a smooth function of the pose (the
    equilibria's finite-difference Jacobians need it) with fewer evaluations.
    """
    gr = 0.6180339887498949
    a = max(s0 - h, lo)
    b = min(s0 + h, hi)
    fa = math.inf
    fb = math.inf
    c = b - gr * (b - a)
    d = a + gr * (b - a)
    fc = _gap(c, wu, winv, wc, ru, rinv, rc, r0, e_tape, sig, y, zc, st, ct, sp, cp, R, ph0)
    fd = _gap(d, wu, winv, wc, ru, rinv, rc, r0, e_tape, sig, y, zc, st, ct, sp, cp, R, ph0)
    for _ in range(levels):
        if fc < fd:
            b, fb, d, fd = d, fd, c, fc
            c = b - gr * (b - a)
            fc = _gap(c, wu, winv, wc, ru, rinv, rc, r0, e_tape, sig, y, zc, st, ct, sp, cp, R,
                      ph0)
        else:
            a, fa, c, fc = c, fc, d, fd
            d = a + gr * (b - a)
            fd = _gap(d, wu, winv, wc, ru, rinv, rc, r0, e_tape, sig, y, zc, st, ct, sp, cp, R,
                      ph0)
    if fc < fd:
        sb, fbest = c, fc
    else:
        sb, fbest = d, fd
    # the parabola through the three evaluated points around the best one
    if (fc < fd and fa < math.inf) or (fc >= fd and not fb < math.inf):
        x1, f1, x2, f2, x3, f3 = a, fa, c, fc, d, fd
    else:
        x1, f1, x2, f2, x3, f3 = c, fc, d, fd, b, fb
    if f1 < math.inf and f3 < math.inf:
        den = (x2 - x1) * (f2 - f3) - (x2 - x3) * (f2 - f1)
        if den != 0.0:
            xv = x2 - 0.5 * ((x2 - x1) ** 2 * (f2 - f3) - (x2 - x3) ** 2 * (f2 - f1)) / den
            if x1 < xv < x3:
                fv = _gap(xv, wu, winv, wc, ru, rinv, rc, r0, e_tape, sig, y, zc, st, ct, sp,
                          cp, R, ph0)
                if fv < fbest:
                    sb, fbest = xv, fv
    return sb, fbest


# --------------------------------------------------------------------------- the wheel
@njit(cache=True)
def _grid_gap(sg, pg, p1g, i_lo, n, ru, rinv, rc, r0, e_tape, sig, y, zc, st, ct, sp, cp, R,
              ph0):
    """Vertical gap at grid points i_lo … i_lo + n − 1 of the wheel coordinate (``_BIG``
    where the locus is beside the rail): the loci in one branch-free loop the compiler
    vectorises, then the rail spline (uniform knots: ``rinv`` > 0) at each."""
    Ys = np.empty(n)
    d = np.empty(n)
    if sp == 0.0:
        for k in range(n):
            r = r0 - pg[i_lo + k]
            a = sig * (e_tape + sg[i_lo + k])
            Ys[k] = y + (a * ct + r * st)
            d[k] = zc + (a * st - r * ct)
    else:
        c0 = cp / R
        s0 = -st * sp / R
        f = sig * ct * sp / R
        for k in range(n):
            r = r0 - pg[i_lo + k]
            a = sig * (e_tape + sg[i_lo + k])
            q = min(max(f * p1g[i_lo + k], -1.0), 1.0)
            cq = math.sqrt(1.0 - q * q)
            sf = q * c0 - cq * s0
            cf = cq * c0 + q * s0
            Ys[k] = y + r * sf * sp + (a * ct + r * cf * st) * cp
            d[k] = zc + (a * st - r * cf * ct)
    u0 = ru[0]
    u1 = ru[ru.shape[0] - 1]
    last = ru.shape[0] - 2
    for k in range(n):
        u = sig * Ys[k]
        if u < u0 or u > u1:
            d[k] = _BIG
        else:
            if rinv > 0.0:
                i = min(max(int((u - u0) * rinv), 0), last)
            else:
                i = min(max(np.searchsorted(ru, u) - 1, 0), last)
            dx = u - ru[i]
            d[k] -= ((rc[0, i] * dx + rc[1, i]) * dx + rc[2, i]) * dx + rc[3, i]
    return d


@njit(cache=True)
def _depths(d, kk, cd, nc, shared):
    """Depth [m] of each minimum of the vertical gap for the multi-Hertz normal problem.

    ``shared`` false: each minimum k has the depth −d_k, as :func:`wheelrail.solve`
    (``connected="separate"``). ``shared`` true (``connected="shared"``): minima
    whose interpenetration regions are separate (the gap rises above zero between
    them) keep −d_k; minima joined by penetrating saddles (one connected region,
    e.g. flange root and flange at the two-point transition, or the two tread
    points of S1002 on 60E1 near the centre) get their depth below their lower
    neighbouring saddle, b_k, plus a share of the depth −H of the region's highest
    saddle in proportion to b_k, so the common part of the region is counted
    once. The depths are then continuous where a minimum merges with its
    neighbour (b_k → 0: its patch vanishes with zero load; with "separate" it
    carries −d_k to the last instant and drops it, a jump that leaves a steady
    state at the two-point transition without an equilibrium) and where a region
    splits (H → 0: every minimum gets −d_k).

    Parameters
    ----------
    d : ndarray
        Vertical gap on the search grid [m].
    kk : ndarray of int
        Grid index of each minimum, increasing.
    cd : ndarray
        Refined gap of each minimum [m].
    nc : int
        Number of minima.
    shared : bool
    """
    dep = np.empty(nc)
    for q in range(nc):
        dep[q] = -cd[q]
    if nc < 2 or not shared:
        return dep
    hump = np.empty(nc - 1)
    for q in range(nc - 1):
        lo_, hi_ = kk[q], kk[q + 1]
        if hi_ < lo_:
            lo_, hi_ = hi_, lo_
        hmax = d[lo_]
        for j in range(lo_ + 1, hi_ + 1):
            if d[j] > hmax:
                hmax = d[j]
        hump[q] = hmax
    q0 = 0
    while q0 < nc:
        q1 = q0
        while q1 < nc - 1 and hump[q1] < 0.0:
            q1 += 1
        if q1 > q0:
            H = hump[q0]
            for q in range(q0 + 1, q1):
                if hump[q] > H:
                    H = hump[q]
            sb = 0.0
            b = np.empty(q1 - q0 + 1)
            for q in range(q0, q1 + 1):
                Hq = math.inf
                if q > q0:
                    Hq = hump[q - 1]
                if q < q1 and hump[q] < Hq:
                    Hq = hump[q]
                b[q - q0] = max(Hq - cd[q], 0.0)
                sb += b[q - q0]
            if sb > 0.0:
                for q in range(q0, q1 + 1):
                    dep[q] = b[q - q0] - H * b[q - q0] / sb
        q0 = q1 + 1
    return dep


@njit(cache=True, inline="always")
def _closed_law(tangential, a, b, Fn, xi, eta, phi, mu, G, nu, K, kx, c11, c22, c23, c33,
                tk_values, tk_x0, tk_dx, tk_n, tk_cubic, tk_cx0, tk_cdx, tk_cn, tk_coef):
    """Kalker's linear law (``tangential == 2``) or the table law (``1``) on one ellipse.

    Returns (done, Fx, Fs, Mz); ``done`` False (another law, or a point outside the
    table) leaves the patch to the caller's FASTSIM.
    """
    if tangential == 2:
        Fx, Fs, Mz = linear_forces(a, b, G, xi, eta, phi, kx, c11, c22, c23, c33)
        return True, Fx, Fs, Mz
    if tangential == 1:
        return table_forces(a, b, Fn, xi, eta, phi, mu, G, nu, K, tk_values, tk_x0, tk_dx, tk_n,
                            tk_cubic, tk_cx0, tk_cdx, tk_cn, tk_coef)
    return False, 0.0, 0.0, 0.0


@njit(cache=True, inline="always")
def _write_row(row, Fn, Fx, Fs, Mz, angle, y, z, x, s, lateral, a, b, xi, eta, phi, p_max,
               radius, penetration, fell_back):
    """One contact point's row of the output array (columns as documented in wheel_contact)."""
    row[0] = Fn
    row[1] = Fx
    row[2] = Fs
    row[3] = Mz
    row[4] = angle
    row[5] = y
    row[6] = z
    row[7] = x
    row[8] = s
    row[9] = lateral
    row[10] = a
    row[11] = b
    row[12] = xi
    row[13] = eta
    row[14] = phi
    row[15] = p_max
    row[16] = radius
    row[17] = penetration
    row[20] = 1.0 if fell_back else 0.0


@njit(cache=True)
def wheel_contact(sg, pg, p1g, lo, hi, wu, winv, wc, ru, rinv, rc, r0, e_tape, sig,
                  offset, z_top, angle,
                  y, zc, roll, yaw, V, Om, vy, vz, yaw_rate, roll_rate, mu,
                  mp, hz_lam, hz_la, hz_lb, hz_lp, hz_ld, kx, c11, c22, c23, c33,
                  fs_t, fs_half, fs_peak, fs_cells, fs_factor, rs_i0, rs_i1, rs_w,
                  tk_values, tk_x0, tk_dx, tk_n, tk_cubic, tk_cx0, tk_cdx, tk_cn, tk_coef,
                  out_p, out_w):
    """Contact patches and forces of one wheel at a pose (see the module docstring).

    Parameters
    ----------
    sg, pg, p1g : ndarray, shape (m,)
        Search grid of the wheel profile coordinate [m], profile height and slope there.
    lo, hi : float
        Usable range of the wheel profile coordinate [m].
    wu, winv, wc ; ru, rinv, rc
        Wheel and rail profile splines (``PiecewiseCubic``: breakpoints, inverse
        spacing or 0, coefficients (4, n − 1)); the rail in side-local coordinates.
    r0, e_tape, sig : float
        Nominal radius [m], tape-circle half distance [m], +1 right / −1 left.
    offset, z_top, angle : float
        Rail placement (:class:`~wheelrail.geometry.track.RailPlacement`).
    y, zc, roll, yaw : float
        Pose of the wheelset relative to this rail: lateral shift [m], height of
        the axle centre [m] (r0 + z), roll and yaw [rad].
    V, Om, vy, vz, yaw_rate, roll_rate : float
        Forward speed [m/s], angular velocity about the axle [rad/s], lateral and
        vertical velocity relative to the rail [m/s], absolute yaw rate and roll
        rate [rad/s].
    mu : float
        Friction coefficient [-].
    mp : ndarray
        Method parameters (indices :data:`MP`).
    hz_* : ndarray
        Hertz table (``_hertz_table``: ln(A/B) grid, ln a, ln b, ln p0, ln δ).
    kx, c11, c22, c23 : ndarray
        Kalker's coefficients against ln(a/b) for the material's ν.
    fs_* : ndarray, float
        FASTSIM strip data of an ellipse (as ``Fastsim.solve``).
    rs_i0, rs_i1, rs_w : ndarray
        Resampling of a strip patch's cells to FASTSIM's ``nx``.
    ax_*, tab, tab_* : ndarray, float
        The table law's axes, values in the full-slip frame and domain.
    out_p : ndarray, shape (KMAX, len(PATCH_FIELDS))
        Written: the patches (largest normal force first).
    out_w : ndarray, shape (len(WHEEL_FIELDS),)
        Written: per-wheel sums.
    """
    out_p[:, :] = 0.0
    out_w[:] = 0.0
    normal = int(mp[0])
    tangential = int(mp[1])
    E_star = mp[2]
    G = mp[3]
    nu = mp[4]
    K = mp[5]
    st, ct = math.sin(roll), math.cos(roll)
    sp, cp = math.sin(yaw), math.cos(yaw)
    Bc = -st * sp
    R = math.hypot(cp, Bc)
    ph0 = math.atan2(Bc, cp)
    # ------------------------------------------------ search: grid part above the rail
    m = sg.shape[0]
    h = sg[1] - sg[0]
    u_lo = ru[0] - e_tape - sig * y - 0.006
    u_hi = ru[ru.shape[0] - 1] - e_tape - sig * y + 0.006
    i_lo = max(int((u_lo - sg[0]) / h), 0)
    i_hi = min(int((u_hi - sg[0]) / h) + 1, m - 1)
    n = i_hi - i_lo + 1
    if n < 3:
        out_w[15] = _BIG
        return 0
    d = _grid_gap(sg, pg, p1g, i_lo, n, ru, rinv, rc, r0, e_tape, sig, y, zc, st, ct, sp, cp,
                  R, ph0)
    g = 0
    for k in range(1, n):
        if d[k] < d[g]:
            g = k
    tol = mp[13]
    # candidate grid minima: interior local minima within reach, and the global one
    cand = np.empty(_KC, np.int64)
    nc = 0
    for k in range(n):
        ok = k == g
        if not ok and 0 < k < n - 1:
            ok = (d[k] < d[k - 1] and d[k] <= d[k + 1] and d[k - 1] < _BIG and d[k + 1] < _BIG
                  and d[k] - d[g] <= 5.0 * tol + 2e-3)
        if ok:
            # a shallow hump (< 0.1 µm) between this and the last kept minimum: one minimum
            if nc > 0:
                j = cand[nc - 1]
                hump = d[j]
                for q in range(j + 1, k + 1):
                    if d[q] > hump:
                        hump = d[q]
                if hump - max(d[j], d[k]) < 1e-7:
                    if d[k] < d[j]:
                        cand[nc - 1] = k
                    continue
            if nc < _KC:
                cand[nc] = k
                nc += 1
    # refined minima: the global one, then those that can penetrate (grid value minus the
    # grid's error bound below the approach); the others cannot carry load
    cs = np.empty(nc)
    cd = np.empty(nc)
    qg = 0
    for q in range(nc):
        if cand[q] == g:
            qg = q
    cs[qg], cd[qg] = _refine(sg[i_lo + g], h, lo, hi, _LEVELS, wu, winv, wc, ru, rinv, rc, r0,
                             e_tape, sig, y, zc, st, ct, sp, cp, R, ph0)
    dmin = cd[qg]
    kk = np.empty(nc, np.int64)           # grid index of each kept minimum
    m_ok = 0
    for q in range(nc):
        if q == qg:
            cs[m_ok], cd[m_ok] = cs[qg], cd[qg]
            kk[m_ok] = cand[q]
            qg = m_ok
            m_ok += 1
            continue
        # skip a minimum that cannot penetrate: the grid value minus the largest drop a
        # convex gap can have within the neighbouring cells (on a steep flank the gap's
        # curvature is (k_w + k_r)/cos³γ, and a grid value lies far above the minimum)
        k = cand[q]
        drop = 1e-4
        if 0 < k < n - 1:
            drop = max(drop, 1.5 * max(d[k - 1] - d[k], d[k + 1] - d[k]))
        if d[k] - drop >= 0.0:
            continue
        s_r, d_r = _refine(sg[i_lo + cand[q]], h, lo, hi, _LEVELS, wu, winv, wc, ru, rinv, rc, r0,
                           e_tape, sig, y, zc, st, ct, sp, cp, R, ph0)
        cs[m_ok] = s_r
        cd[m_ok] = d_r
        kk[m_ok] = cand[q]
        if d_r < dmin:
            dmin = d_r
        m_ok += 1
    nc = m_ok
    dep = _depths(d, kk, cd, nc, mp[22] > 0)
    out_w[15] = dmin
    out_w[18] = nc
    if dmin >= 0.0 or dmin >= _BIG:
        return 0
    dz = -dmin
    out_w[14] = dz
    zc_t = zc + dz             # touching pose (the library's wheel problem)
    # point data
    PY = np.empty(nc)
    PZ = np.empty(nc)
    PX = np.empty(nc)
    PG = np.empty(nc)
    PR = np.empty(nc)
    PA = np.empty(nc)
    PB = np.empty(nc)
    PU = np.empty(nc)
    keep = np.zeros(nc, np.bool_)
    for q in range(nc):
        s = cs[q]
        p, p1, p2 = _spline(wu, winv, wc, s)
        Y, Z, xr, r = _locus(s, p, p1, r0, e_tape, sig, y, zc_t, st, ct, sp, cp, R, ph0)
        u = sig * Y
        zr, zr1, zr2 = _spline(ru, rinv, rc, u)
        gam = math.atan(zr1)
        kwx = 1.0 / (r * math.sqrt(1.0 + p1 * p1))
        kwy = p2 / (1.0 + p1 * p1) ** 1.5
        kry = -(zr2 / (1.0 + zr1 * zr1) ** 1.5)
        B = 0.5 * (kwy + kry)
        if not B > 0.0:
            # the separation's curvature over ±1.5 mm (regularised_B_rows)
            span = 1.5e-3
            dm = _gap(s - span, wu, winv, wc, ru, rinv, rc, r0, e_tape, sig, y, zc_t, st, ct,
                      sp, cp, R, ph0)
            d0 = _gap(s, wu, winv, wc, ru, rinv, rc, r0, e_tape, sig, y, zc_t, st, ct, sp, cp,
                      R, ph0)
            dp = _gap(s + span, wu, winv, wc, ru, rinv, rc, r0, e_tape, sig, y, zc_t, st, ct,
                      sp, cp, R, ph0)
            B = 0.5 * (dm - 2.0 * d0 + dp) / span ** 2 * math.cos(gam) ** 3
        PY[q] = Y
        PZ[q] = Z
        PX[q] = xr
        PG[q] = gam
        PR[q] = r
        PA[q] = 0.5 * kwx
        PB[q] = B
        PU[q] = u
        keep[q] = (cd[q] - dmin) * math.cos(gam) <= tol
    if mp[21] == 1:
        return 0
    # ------------------------------------------------ normal problem
    npt = 0
    cap = 16
    P = np.zeros((cap, _NP))
    # per patch: strip description for FASTSIM (KP) -> solved right away below
    fallbacks = 0
    if normal == 0:
        for q in range(nc):
            pen = dep[q] * math.cos(PG[q])
            if not pen > 0.0 or npt >= cap:
                continue
            A = PA[q]
            B = PB[q]
            if not (A > 0.0 and B > 0.0):
                continue
            lam = math.log(A / B)
            sab = math.sqrt(A * B)
            la = _interp(lam, hz_lam, hz_la)
            lb = _interp(lam, hz_lam, hz_lb)
            lp = _interp(lam, hz_lam, hz_lp)
            ld = _interp(lam, hz_lam, hz_ld)
            d1 = math.exp(ld) * sab ** (1.0 / 3.0)        # approach at (N/E*) = 1
            load = (pen / d1) ** 1.5                      # N / E*
            Fn = E_star * load
            a = math.exp(la) / sab ** (1.0 / 3.0) * load ** (1.0 / 3.0)
            b = math.exp(lb) / sab ** (1.0 / 3.0) * load ** (1.0 / 3.0)
            p0 = math.exp(lp) * sab ** (2.0 / 3.0) * E_star * load ** (1.0 / 3.0)
            dxa = PX[q] - sig * (e_tape + cs[q]) * ct * sp
            xi, eta, phi = creepage(sig, V, Om, vy, vz, yaw_rate, roll_rate, yaw, roll, dxa,
                                    PY[q] - y, PZ[q] - zc_t, PG[q])
            done, Fx, Fs, Mz = _closed_law(tangential, a, b, Fn, xi, eta, phi, mu, G, nu, K, kx,
                                           c11, c22, c23, c33, tk_values, tk_x0, tk_dx, tk_n,
                                           tk_cubic, tk_cx0, tk_cdx, tk_cn, tk_coef)
            if tangential == 1 and not done:
                fallbacks += 1
            if not done:
                Fx, Fs, Mz = fastsim_ellipse(a, b, Fn, mu, xi, eta, phi, G, mp[17] > 0, kx,
                                              c11, c22, c23, fs_t, fs_half, fs_peak, fs_cells,
                                              fs_factor, mp[16] > 0, mp[18] > 0)
            zr = _spline0(ru, rinv, rc, PU[q])
            ca, sa = math.cos(-angle), math.sin(-angle)
            _write_row(P[npt], Fn, Fx, Fs, Mz, PG[q], PY[q], PZ[q], PX[q], cs[q],
                       ca * (PU[q] - offset) - sa * (zr + z_top), a, b, xi, eta, phi, p0, PR[q],
                       pen, not done and tangential == 1)
            npt += 1
    else:
        npt, fallbacks = _kp_patches(d, i_lo, h, nc, keep, cd, cs, PY, PZ, PX, PG, PR, PA, PB, PU, dz, dmin,
                                     sg, pg, p1g, wu, winv, wc, ru, rinv, rc, r0, e_tape, sig,
                                     offset, z_top, angle, y, zc_t, roll, yaw, st, ct, sp, cp, R,
                                     ph0, V, Om, vy, vz, yaw_rate, roll_rate, mu, mp, hz_lam,
                                     hz_la, hz_lb, hz_ld, kx, c11, c22, c23, c33, rs_i0, rs_i1, rs_w, tk_values,
                                     tk_x0, tk_dx, tk_n, tk_cubic, tk_cx0, tk_cdx, tk_cn,
                                     tk_coef, P)
    # ------------------------------------------------ forces on the wheelset
    order = np.argsort(-P[:npt, 0])
    Fx_t = 0.0
    Fy_t = 0.0
    Fz_t = 0.0
    a_w = 0.0
    Fn_w = 0.0
    for k in range(npt):
        row = P[order[k]]
        Fn, Fx, Fs, Mz, gam = row[0], row[1], row[2], row[3], row[4]
        cg, sgm = math.cos(gam), math.sin(gam)
        # track-frame forces, normal and tangential parts
        Fyn = -sig * Fn * sgm
        Fzn = Fn * cg
        Fyt = Fs * cg
        Fzt = sig * Fs * sgm
        row[18] = Fyn + Fyt
        row[19] = Fzn + Fzt
        ddx = row[7] - sig * (e_tape + row[8]) * ct * sp
        ddy = row[5] - y
        ddz = row[6] - zc_t
        # generalised forces (y, z, roll, yaw, spin), see wheelrail.dynamics.equations
        out_w[1] += Fyn
        out_w[2] += Fzn
        out_w[3] += ddy * Fzn - ddz * Fyn
        out_w[4] += ddx * Fyn
        out_w[5] += -ddx * Fzn
        out_w[6] += Fyt
        out_w[7] += Fzt
        out_w[8] += ddy * Fzt - ddz * Fyt
        out_w[9] += ddx * Fyt - ddy * Fx + cg * Mz
        out_w[10] += ddz * Fx - ddx * Fzt - sig * sgm * Mz
        Fx_t += Fx
        Fy_t += Fyn + Fyt
        Fz_t += Fzn + Fzt
        a_w += Fn * row[10]
        Fn_w += Fn
        if k < out_p.shape[0]:
            out_p[k, :] = row
    out_w[0] = min(npt, out_p.shape[0])
    out_w[11] = Fx_t
    out_w[12] = Fy_t
    out_w[13] = Fz_t
    out_w[16] = fallbacks
    out_w[17] = a_w / Fn_w if Fn_w > 0 else 0.0
    return npt


@njit(cache=True)
def _kp_patches(dgrid, i_lo, hs, nc, keep, cd, cs, PY, PZ, PX, PG, PR, PA, PB, PU, dz, dmin, sg, pg, p1g,
                wu, winv, wc, ru, rinv, rc, r0, e_tape, sig, offset, z_top, angle, y, zc_t, roll,
                yaw, st, ct, sp, cp, R, ph0, V, Om, vy, vz, yaw_rate, roll_rate, mu, mp,
                hz_lam, hz_la, hz_lb, hz_ld, kx, c11, c22, c23, c33, rs_i0, rs_i1, rs_w, tk_values, tk_x0,
                tk_dx, tk_n, tk_cubic, tk_cx0, tk_cdx, tk_cn, tk_coef, P):
    """Kik–Piotrowski patches of one wheel and their creep forces (rows of ``P``)."""
    E_star = mp[2]
    G = mp[3]
    nu = mp[4]
    K = mp[5]
    eps_opt = mp[6]
    correct = mp[7] > 0
    strips = int(mp[8])
    cells = int(mp[9])
    half_min = mp[11]
    group_angle = mp[12]
    tangential = int(mp[1])
    kpec = mp[25] > 0                     # Vollebregt's ellipticity correction (KPEC)
    combined = mp[26] > 0                 # FASTSIM's combined flexibility (else weighted)
    n_nodes = int(mp[23])                 # the library's line (KikPiotrowski.line_nodes)
    n_samp = int(mp[24])                  # and its profile samples per body
    coarse = max(1, int(round(_COARSE * (n_samp - 1) / 2000)))
    # candidate points by increasing gap; groups by contact plane (WheelProblem.groups)
    idx = np.argsort(cd[:nc])
    ref = np.full(nc, -1, np.int64)
    nref = 0
    refs = np.empty(nc, np.int64)
    width = 0.04
    for qq in range(nc):
        q = idx[qq]
        if not keep[q]:
            continue
        joined = False
        for jj in range(nref):
            r = refs[jj]
            if abs(PG[q] - PG[r]) < group_angle and abs(PY[q] - PY[r]) < 0.4 * width:
                ref[q] = r
                joined = True
                break
        if not joined:
            refs[nref] = q
            ref[q] = q
            nref += 1
    npt = 0
    fallbacks = 0
    cap = P.shape[0]
    lam_max = 14.0
    for jj in range(nref):
        r = refs[jj]
        gam = PG[r]
        cosf = math.cos(gam - sig * roll)
        delta = dz * cosf                    # approach along this plane's normal
        A_r, B_r = PA[r], PB[r]
        if kpec:
            eps = 1.0                        # KPEC: the regions of real interpenetration
        elif eps_opt > 0:
            eps = eps_opt
        elif A_r > 0 and B_r > 0:
            # Hertz's area for the curvatures at the point: ε = a b √(AB)/δ (unit load)
            lamr = math.log(A_r / B_r)
            eps = math.exp(_interp(lamr, hz_lam, hz_la) + _interp(lamr, hz_lam, hz_lb)
                           - _interp(lamr, hz_lam, hz_ld))
        else:
            eps = 0.55
        d0 = eps * delta
        sep_r = (cd[r] - dmin) * math.cos(gam)
        if not d0 > sep_r:
            continue
        # line half width: the group's points and the region's extent on the search grid
        # (where the vertical gap stays within the virtual penetration of the point's),
        # widened while a region reaches a line end
        half = half_min
        cg_ = max(abs(math.cos(gam)), 0.2)
        thr = cd[r] + 1.1 * d0 / cg_ + 2e-6
        k0 = int(round((cs[r] - sg[0]) / hs)) - i_lo
        ka = k0
        while ka > 0 and dgrid[ka - 1] < thr:
            ka -= 1
        kb = k0
        while kb < dgrid.shape[0] - 1 and dgrid[kb + 1] < thr:
            kb += 1
        ext_a = (cs[r] - (sg[0] + (i_lo + ka) * hs) + hs) / cg_
        ext_b = ((sg[0] + (i_lo + kb) * hs) - cs[r] + hs) / cg_
        for q in range(nc):
            if ref[q] == r:
                w_q = abs(PY[q] - PY[r]) / max(abs(math.cos(gam)), 0.2) + 0.003
                if w_q > half:
                    half = w_q
        # the library's line of this plane (separation_window: 1601 nodes over the monotone
        # part of ±20 mm), evaluated on the nodes of the window ±half only
        t0g, t1g = math.cos(gam), math.sin(gam)
        z_ref = _spline0(ru, rinv, rc, PU[r])
        s_lo = max(wu[0], cs[r] - _SAMPLE_HALF)
        s_hi = min(wu[wu.shape[0] - 1], cs[r] + _SAMPLE_HALF)
        u_lo = max(ru[0], PU[r] - _SAMPLE_HALF)
        u_hi = min(ru[ru.shape[0] - 1], PU[r] + _SAMPLE_HALF)
        dsw = (s_hi - s_lo) / (n_samp - 1)
        dsr = (u_hi - u_lo) / (n_samp - 1)
        gw = (s_lo, dsw, wu, winv, wc, r0, e_tape, sig, y, zc_t, st, ct, sp, cp, R, ph0)
        gr_ = (u_lo, dsr, ru, rinv, rc)
        kcw = min(max(int(round((cs[r] - s_lo) / dsw)), 0), n_samp - 1)
        kcr = min(max(int(round((PU[r] - u_lo) / dsr)), 0), n_samp - 1)
        lw, kw0 = _run_end(True, kcw, -1, gw, gr_, PU[r], z_ref, t0g, t1g, n_samp,
                           coarse)
        hw, kw1 = _run_end(True, kcw, 1, gw, gr_, PU[r], z_ref, t0g, t1g, n_samp,
                           coarse)
        lr, kr0 = _run_end(False, kcr, -1, gw, gr_, PU[r], z_ref, t0g, t1g, n_samp,
                           coarse)
        hr, kr1 = _run_end(False, kcr, 1, gw, gr_, PU[r], z_ref, t0g, t1g, n_samp,
                           coarse)
        lo_l = max(max(-0.5 * _LINE_WIDTH, lw), lr)
        hi_l = min(min(0.5 * _LINE_WIDTH, hw), hr)
        if not hi_l > lo_l:
            continue
        step = (hi_l - lo_l) / (n_nodes - 1)
        stride = max(int(mp[10]), 1)
        h_l = (stride * step + lo_l) - lo_l
        last = (n_nodes - 1) // stride
        # the window [−w_a, w_b] (the region's extent on the search grid, the group's points)
        w_a = min(max(half, ext_a) + h_l, _LINE_WIDTH)
        w_b = min(max(half, ext_b) + h_l, _LINE_WIDTH)
        ok = False
        for _ in range(6):
            ia = max(int(math.floor((-w_a - lo_l) / (stride * step))), 0)
            ib = min(int(math.ceil((w_b - lo_l) / (stride * step))), last)
            if ib - ia < 4:
                break
            # (KPEC: the surface angles only where the regions are, after them, below)
            eta, f, Ax, ang, rw, ok = _line_nodes(ia, ib, stride, lo_l, hi_l, step, cosf,
                                                  -1.0 if kpec else d0, kcw,
                                                  kw0, kw1,
                                                  kcr, kr0, kr1, gw, gr_, PU[r], z_ref, t0g,
                                                  t1g, n_nodes)
            if not ok:
                break
            nl = eta.shape[0]
            reach_a = ia > 0 and d0 - f[0] > 0.0
            reach_b = ib < last and d0 - f[nl - 1] > 0.0
            if not (reach_a or reach_b):
                break
            if reach_a:
                w_a = min(2.0 * w_a, _LINE_WIDTH)
            if reach_b:
                w_b = min(2.0 * w_b, _LINE_WIDTH)
        if not ok or mp[21] == 2:
            continue
        if kpec:
            okr, meta, eta_c, xl_c, peak, gk = kpec_line_regions(f, Ax, eta, h_l, d0, E_star,
                                                                 hz_lam, hz_la, hz_lb, hz_ld,
                                                                 lam_max)
            for i in range(f.shape[0]):
                if gk[i] > 0.0:
                    _, z1, _ = _spline(ru, rinv, rc, PU[r] + eta[i] * t0g)
                    ang[i] = math.atan(z1)
        else:
            okr, meta, eta_c, xl_c, peak = kp_line_regions(f, Ax, eta, h_l, d0, eps, E_star,
                                                           correct, hz_lam, hz_la, hz_lb,
                                                           lam_max)
            gk = d0 - f
        if not okr or mp[21] == 3:
            continue
        for kr in range(meta.shape[0]):
            if npt >= cap:
                break
            i0 = int(meta[kr, 0])
            i1 = int(meta[kr, 1])
            N = meta[kr, 3]
            if not N > 0:
                continue
            wts = np.empty(i1 - i0)
            for i in range(i0, i1):
                wts[i - i0] = gk[i]
            ang_m, eta_m = weighted_means(wts, ang[i0:i1], eta[i0:i1])
            e0, e1 = eta[i0], eta[i1 - 1]
            tt = (eta_m - e0) / (e1 - e0) if e1 > e0 else 0.0
            eta_ref = eta_c[i0] + tt * (eta_c[i1 - 1] - eta_c[i0]) if i1 - i0 > 1 else eta_c[i0]
            ys_, xl_s, c_s, dy, widthp, area, Lp = kp_strips(
                eta_c[i0:i1], xl_c[i0:i1], peak[i0:i1], h_l, strips, cells, N, eta_ref, sig)
            if not area > 0 or mp[21] == 4:
                continue
            ratio = Lp / widthp
            a = math.sqrt(area * ratio / math.pi)
            b = math.sqrt(area / (ratio * math.pi))
            # the patch frame (WheelProblem.frame_at): rail point at eta_m of the plane
            u_p = PU[r] + eta_m * t0g
            z_p = _spline0(ru, rinv, rc, u_p)
            rad = _interp(eta_m, eta, rw)
            Yp = sig * u_p
            dxa = PX[r] - sig * (e_tape + cs[r] + (u_p - PU[r])) * ct * sp
            xi, eta_cr, phi = creepage(sig, V, Om, vy, vz, yaw_rate, roll_rate, yaw, roll, dxa,
                                       Yp - y, z_p - zc_t, ang_m)
            done, Fx, Fs, Mz = _closed_law(tangential, a, b, N, xi, eta_cr, phi, mu, G, nu, K, kx,
                                           c11, c22, c23, c33, tk_values, tk_x0, tk_dx, tk_n,
                                           tk_cubic, tk_cx0, tk_cdx, tk_cn, tk_coef)
            if tangential == 1 and not done:
                fallbacks += 1
            if not done:
                Fx, Fs, Mz = kp_strip_fastsim(ys_, dy, xl_s, c_s, cells, rs_i0, rs_i1, rs_w, a, b,
                                            mu, G, kx, c11, c22, c23, xi, eta_cr, phi,
                                            mp[18] > 0, combined)
                if not (math.isfinite(Fx) and math.isfinite(Fs) and math.isfinite(Mz)):
                    continue
            pmax = 0.0
            for i in range(i0, i1):
                if peak[i] > pmax:
                    pmax = peak[i]
            ca, sa = math.cos(-angle), math.sin(-angle)
            _write_row(P[npt], N, Fx, Fs, Mz, ang_m, Yp, z_p, PX[r], cs[r] + (u_p - PU[r]),
                       ca * (u_p - offset) - sa * (z_p + z_top), a, b,
                       xi, eta_cr, phi, pmax, rad,
                       d0 / eps - (cd[r] - dmin) * math.cos(gam) if r >= 0 else 0.0,
                       not done and tangential == 1)
            npt += 1
    return npt, fallbacks
