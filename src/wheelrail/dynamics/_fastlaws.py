"""Compiled creep-force laws and helpers of the dynamics' contact path (private).

Scalar versions, for one patch, of what the library's laws do on arrays:
the creepages of a point (:func:`wheelrail.geometry.kinematics.creepage_kernel`),
FASTSIM on an ellipse (:class:`wheelrail.tangential.Fastsim`, with the library's
batch kernel), the march of FASTSIM over strips with one weighted flexibility per
patch (Kik & Piotrowski's choice; Piotrowski & Chollet 2005, §3.2–3.3, eqs.
24–26; the equations of the library's ``march_strip`` with L1 = L2 = L3) and the
table law (:class:`wheelrail.tangential.Table`:
multilinear interpolation in the frame of the full-slip direction).

References
----------
.. [1] J.J. Kalker, A fast algorithm for the simplified theory of rolling
   contact, VSD 11 (1982) 1–13.
.. [2] J. Piotrowski, H. Chollet, Wheel–rail contact models for vehicle system
   dynamics including multi-point contact, VSD 43 (2005) 455–483, §3.
.. [3] J.J. Kalker, Book of tables for the Hertzian creep-force law, Budapest 1996.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..tangential._fastsim_kernel import fastsim_hertz_batch
from ..tangential._table_kernel import point_forces

__all__ = ["creepage", "table_forces", "fastsim_ellipse", "march_strips", "kp_strips",
           "kp_strip_fastsim",
           "linear_forces"]


@njit(cache=True)
def _interp(x, xp, fp):
    """np.interp of one value (xp increasing)."""
    n = xp.shape[0]
    if x <= xp[0]:
        return fp[0]
    if x >= xp[n - 1]:
        return fp[n - 1]
    i = np.searchsorted(xp, x) - 1
    t = (x - xp[i]) / (xp[i + 1] - xp[i])
    return fp[i] + t * (fp[i + 1] - fp[i])


@njit(cache=True)
def _kalker(ab, kx, c11, c22, c23):
    v = math.log(ab)
    return _interp(v, kx, c11), _interp(v, kx, c22), _interp(v, kx, c23)



@njit(cache=True)
def creepage(sig, V, Om, vy, vz, yaw_rate, roll_rate, yaw, roll, dx, dy, dz, g):
    """Creepages (ξ, η, φ) of one point (the scalar arithmetic of ``creepage_kernel``)."""
    cps, sps = math.cos(yaw), math.sin(yaw)
    cth, sth = math.cos(roll), math.sin(roll)
    wX = Om * cth * sps - roll_rate * cps
    wY = Om * cth * cps + roll_rate * sps
    wZ = -Om * sth - yaw_rate
    rX, rY, rZ = dx, -dy, dz
    vX = V + (wY * rZ - wZ * rY)
    vY = -vy + (wZ * rX - wX * rZ)
    vZ = vz + (wX * rY - wY * rX)
    cg, sg = math.cos(g), math.sin(g)
    return vX / V, (-vY * cg + vZ * sig * sg) / V, (-wY * sig * sg - wZ * cg) / V


# --------------------------------------------------------------------------- table law
@njit(cache=True)
def table_forces(a, b, Fn, xi, eta, phi, mu, G, nu, K, values, x0, dx, n, cubic, c_x0, c_dx,
                 c_n, coef):
    """Creep forces of one elliptic contact by the table law (``Table.solve`` for one point).

    The arrays are the table's compiled form (``TableData.kernel``), evaluated by
    the library's own kernel :func:`wheelrail.tangential._table_kernel.point_forces`
    (cubic in the creepage, spin and ln a/b axes), so the compiled path and
    ``wr.creep_forces(..., method="table")`` give the same forces. Returns
    ``(ok, Fx, Fy, Mz)`` [N, N, N m], forces on the wheel (Kalker's sign
    convention); ``ok`` is False outside the table's domain (a/b outside
    0.05–20, ν outside the table, or a conformal contact with K ≠ 0), where the
    caller uses its fallback.
    """
    if abs(K) > 1e-3:
        return False, 0.0, 0.0, 0.0
    flags, Fx, Fy, Mz = point_forces(a, b, G, nu, xi, eta, phi, mu, Fn, values, x0, dx, n,
                                     cubic, c_x0, c_dx, c_n, coef)
    if flags != 0:
        return False, 0.0, 0.0, 0.0
    return True, Fx, Fy, Mz


# --------------------------------------------------------------------------- FASTSIM
@njit(cache=True)
def fastsim_ellipse(a, b, Fn, mu, xi, eta, phi, G, weighted, kx, c11, c22, c23, t, half,
                     strip_peak, s_cells, peak_factor, parabolic, first_order):
    """FASTSIM on a Hertz ellipse (``Fastsim.solve`` without fields, one case)."""
    C11, C22, C23 = _kalker(a / b, kx, c11, c22, c23)
    L1 = 8.0 * a / (3.0 * G * C11)
    L2 = 8.0 * a / (3.0 * G * C22)
    L3 = math.pi * a * math.sqrt(a / b) / (4.0 * G * C23)
    if weighted:
        c = math.sqrt(a * b)
        cphi = c * abs(phi)
        nrm = math.sqrt(xi * xi + eta * eta + cphi * cphi)
        if nrm > 0:
            L1 = L2 = L3 = (L1 * abs(xi) + L2 * abs(eta) + L3 * cphi) / nrm
    if parabolic:
        peak = 2.0 * Fn / (math.pi * a * b)
    else:
        peak = 1.5 * Fn / (math.pi * a * b)
    A1 = np.empty(1)
    arr = np.empty((10, 1))
    arr[0, 0] = a
    arr[1, 0] = b
    arr[2, 0] = peak * peak_factor
    arr[3, 0] = mu
    arr[4, 0] = L1
    arr[5, 0] = L2
    arr[6, 0] = L3
    # very large creepages: scaled together (same full-slip direction), as Fastsim's _tame
    reach = max(a, b)
    rate = max(abs(xi) / L1, abs(eta) / L2, abs(phi) * reach / L3)
    f = 1.0 if rate <= 1e200 else 1e200 / rate
    arr[7, 0] = xi * f
    arr[8, 0] = eta * f
    arr[9, 0] = phi * f
    A1[0] = 0.0
    Fx, Fy, Mz, _ = fastsim_hertz_batch(arr[0], arr[1], arr[2], arr[3], arr[4], arr[5], arr[6],
                                        arr[7], arr[8], arr[9], t, half, strip_peak, s_cells,
                                        first_order)
    return Fx[0], Fy[0], Mz[0]


@njit(cache=True)
def march_strips(y, dy, xl, p, mu, L, xi, eta, phi, first_order):
    """FASTSIM with one flexibility L over strips with cell pressures p (strips, nx).

    The discrete equations of :func:`~wheelrail.tangential._fastsim_kernel.march_strip`
    with L1 = L2 = L3 = L, where the slip rule is the elastic predictor scaled onto
    the traction bound (Kalker 1982; ``saturate``'s exact solution for equal
    flexibilities). Returns (Fx, Fy, Mz about the origin).
    """
    strips, nx = p.shape
    Fx = 0.0
    Fy = 0.0
    Mz = 0.0
    for k in range(strips):
        length = 2.0 * xl[k]
        if length <= 0.0:
            continue
        dx = length / nx
        yk = y[k]
        gx = (xi - phi * yk) / L
        gy0 = eta / L
        gs = phi / L
        px = 0.0
        py = 0.0
        spx = 0.0
        spy = 0.0
        sxpy = 0.0
        xp = xl[k]
        hh = dx if first_order else 0.5 * dx
        for i in range(nx):
            xc = xl[k] - (i + 0.5) * dx
            xm = xc if first_order else 0.5 * (xp + xc)
            pxh = px - hh * gx
            pyh = py - hh * (gy0 + gs * xm)
            g = mu * p[k, i]
            t2 = pxh * pxh + pyh * pyh
            if t2 > g * g:
                sc = g / math.sqrt(t2)
                px = pxh * sc
                py = pyh * sc
            else:
                px = pxh
                py = pyh
            spx += px
            spy += py
            sxpy += xc * py
            xp = xc
            hh = dx
        area = dx * dy
        Fx += spx * area
        Fy += spy * area
        Mz += (sxpy - yk * spx) * area
    return Fx, Fy, Mz


@njit(cache=True)
def linear_forces(a, b, G, xi, eta, phi, kx, c11, c22, c23, c33):
    """Kalker's linear theory on an ellipse (``wheelrail.tangential.linear.linear_forces``):
    Fx = −G c² C11 ξ, Fy = −G c² (C22 η + c C23 φ), Mz = G c³ (C23 η − c C33 φ)."""
    v = math.log(a / b)
    C11 = _interp(v, kx, c11)
    C22 = _interp(v, kx, c22)
    C23 = _interp(v, kx, c23)
    C33 = _interp(v, kx, c33)
    c2 = a * b
    c = math.sqrt(c2)
    return (-G * c2 * C11 * xi, -G * c2 * (C22 * eta + c * C23 * phi),
            G * c2 * c * (C23 * eta - c * C33 * phi))


@njit(cache=True)
def kp_strips(eta_n, xl_n, pk_n, h_line, strips, cells, N, eta_ref, sign):
    """The strips of a Kik–Piotrowski region as
    :func:`~wheelrail.normal._patch_kernel.strip_patch` makes them (x_l² and the peaks
    linear between the nodes and zero half a node beyond the ends, ``strips`` uniform
    strips, a semi-ellipse of ``cells`` cells along each, scaled to the force N), without
    the cell array: every strip's cells are its peak factor ``c`` times the semi-ellipse.

    Returns
    -------
    y, xl, c : ndarray, shape (strips,)
        Strip centres in the patch frame (sorted), half-lengths [m], pressure factors [Pa]
        (cell i of strip k: c_k √(1 − s_i²), s_i = 1 − (2i + 1)/cells).
    dy, width, area, length : float
    """
    n = eta_n.shape[0]
    hn = eta_n[1] - eta_n[0] if n > 1 else h_line
    lo = eta_n[0] - 0.5 * hn
    hi = eta_n[n - 1] + 0.5 * hn
    width = hi - lo
    dy = width / strips
    psum = 0.0
    for i in range(cells):
        s = 1.0 - (i + 0.5) * (2.0 / cells)
        psum += math.sqrt(max(1.0 - s * s, 0.0))
    ys = np.empty(strips)
    xs = np.empty(strips)
    cs_ = np.empty(strips)
    got = 0.0
    area = 0.0
    lmax = 0.0
    j = -1                    # interval of the extended nodes (lo, eta_n…, hi)
    for k in range(strips):
        e = lo + (k + 0.5) * dy
        while j < n - 1 and eta_n[j + 1] <= e:
            j += 1
        if j < 0:
            ea, x2a, pa = lo, 0.0, 0.0
        else:
            ea, x2a, pa = eta_n[j], xl_n[j] * xl_n[j], pk_n[j]
        if j + 1 < n:
            eb, x2b, pb = eta_n[j + 1], xl_n[j + 1] * xl_n[j + 1], pk_n[j + 1]
        else:
            eb, x2b, pb = hi, 0.0, 0.0
        t = (e - ea) / (eb - ea) if eb > ea else 0.0
        xk = math.sqrt(max(x2a + t * (x2b - x2a), 0.0))
        pk = pa + t * (pb - pa)
        ys[k] = e
        xs[k] = xk
        cs_[k] = pk
        got += pk * psum * (2.0 * xk / cells) * dy
        area += 2.0 * xk * dy
        lmax = max(lmax, xk)
    fac = N / got if got > 0 else 0.0
    y = np.empty(strips)
    xl = np.empty(strips)
    c = np.empty(strips)
    for k in range(strips):
        src = k if sign > 0 else strips - 1 - k
        y[k] = sign * (ys[src] - eta_ref)
        xl[k] = xs[src]
        c[k] = cs_[src] * fac
    return y, xl, c, dy, width, area, 2.0 * lmax


@njit(cache=True)
def kp_strip_fastsim(y, dy, xl, c, cells, i0, i1, w, a, b, mu, G, kx, c11, c22, c23, xi, eta,
                   phi, first_order, combined):
    """FASTSIM on a Kik–Piotrowski strip patch as ``Fastsim.solve_patch`` does it: one
    flexibility of the patch's equivalent ellipse (Vollebregt & Voltr's combined one if
    ``combined``, else Kalker's weighted one), each strip's cells resampled
    to FASTSIM's ``nx`` keeping the strip's force (indices ``i0``, ``i1``, weights ``w``;
    with the cells c_k √(1 − s²) the resampled row is c_k times one fixed profile) and
    marched with the one flexibility by :func:`~wheelrail.dynamics._fastlaws.march_strips`
    (the equations of :func:`~wheelrail.tangential._fastsim_kernel.march_strip` with
    L1 = L2 = L3, where its slip rule is the scaling onto the bound; the same numbers to
    round-off, without the per-cell Newton set-up); ``Mz`` about the centre of pressure.
    Returns (Fx, Fy, Mz)."""
    C11, C22, C23 = _kalker(a / b, kx, c11, c22, c23)
    L1 = 8.0 * a / (3.0 * G * C11)
    L2 = 8.0 * a / (3.0 * G * C22)
    L3 = math.pi * a * math.sqrt(a / b) / (4.0 * G * C23)
    if combined:
        # Vollebregt & Voltr's combined flexibility (Fastsim.combined_flexibility)
        s3 = 3.0 * math.pi * a * phi / 32.0
        den = xi * xi / L1 + eta * eta / L2 + s3 * s3 / L3
        L = (xi * xi + eta * eta + s3 * s3) / den if den > 0 else L1
    else:
        cc = math.sqrt(a * b)
        cphi = cc * abs(phi)
        nrm = math.sqrt(xi * xi + eta * eta + cphi * cphi)
        L = (L1 * abs(xi) + L2 * abs(eta) + L3 * cphi) / nrm if nrm > 0 else L1
    ny = y.shape[0]
    nx = i0.shape[0]
    # the resampled profile (strip_patch_forces: linear resampling, the mean kept)
    prof = np.empty(cells)
    msum = 0.0
    for i in range(cells):
        s = 1.0 - (i + 0.5) * (2.0 / cells)
        prof[i] = math.sqrt(max(1.0 - s * s, 0.0))
        msum += prof[i]
    q = np.empty(nx)
    qsum = 0.0
    for i in range(nx):
        q[i] = prof[i0[i]] * (1.0 - w[i]) + prof[i1[i]] * w[i]
        qsum += q[i]
    qf = (msum / cells) / (qsum / nx) if qsum > 0 else 0.0
    reach = 0.0
    for k in range(ny):
        reach = max(reach, abs(y[k]) + dy, xl[k])
    rate = max(abs(xi), abs(eta), abs(phi) * reach) / L
    if not rate <= _RATE_CAP:
        if not (rate > 0 and math.isfinite(rate)):
            return math.nan, math.nan, math.nan
        # huge creepages: scaled together (the same full-slip direction; ``_tame``)
        fac = _RATE_CAP / rate
        xi, eta, phi = xi * fac, eta * fac, phi * fac
    p = np.empty((ny, nx))
    W = 0.0
    WY = 0.0
    for k in range(ny):
        for i in range(nx):
            p[k, i] = c[k] * qf * q[i]
        wk = c[k] * xl[k]
        W += wk
        WY += wk * y[k]
    Fx, Fy, Mz = march_strips(y, dy, xl, p, mu, L, xi, eta, phi, first_order)
    yc = WY / W if W > 0 else 0.0
    return Fx, Fy, Mz + yc * Fx


_RATE_CAP = 1e200
