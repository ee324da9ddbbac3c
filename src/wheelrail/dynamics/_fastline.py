"""Compiled separation line of Kik–Piotrowski's virtual penetration (private).

The nodes of the library's wheel line (``VirtualPenetration._wheel_lines`` →
:func:`wheelrail.normal._fast_separation.separation_window`): profile samples of wheel
and rail in the contact plane, the monotone runs of their tangential coordinates and
the separation at the nodes by the same local cubics
(:func:`wheelrail.normal._fast_separation.local_cubic`), evaluated only on the nodes of
a window around the interpenetration.

References
----------
.. [1] J. Piotrowski, H. Chollet, Wheel–rail contact models for vehicle system dynamics
   including multi-point contact, VSD 43 (2005) 455–483, §3.2.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ._fastgeom import _locus, _spline, _spline0

#: The library's wheel line (``VirtualPenetration._wheel_lines`` → ``separation_window``):
#: nodes, extent [m], profile samples and their half range [m].
_LINE_WIDTH = 0.04
_SAMPLE_HALF = 0.04
#: samples kept beyond the outer nodes on each side (the cubic needs one)
_MARGIN = 3
_COARSE = 25          # samples per step of the walk along a silhouette (at 2001 samples: 1 mm)


@njit(cache=True, inline="always")
def _sample(wheel, k, gw, gr_, u_c, z_c, t0, t1):
    """Tangential and normal coordinates in the contact plane (and the wheel circle radius)
    of wheel sample ``k`` or rail sample ``k`` (``plane_samples`` of one sample)."""
    if wheel:
        s_lo, dsw, wu, winv, wc, r0, e_tape, sig, y, zc, st, ct, sp, cp, R, ph0 = gw
        s = k * dsw + s_lo
        p, p1, _ = _spline(wu, winv, wc, s)
        Y, Z, _, rr = _locus(s, p, p1, r0, e_tape, sig, y, zc, st, ct, sp, cp, R, ph0)
        u = sig * Y
    else:
        u_lo, dsr, ru, rinv, rc = gr_
        u = k * dsr + u_lo
        Z = _spline0(ru, rinv, rc, u)
        rr = 0.0
    du = u - u_c
    dz = Z - z_c
    return du * t0 + dz * t1, -du * t1 + dz * t0, rr


@njit(cache=True)
def _run_end(wheel, kc, dirn, gw, gr_, u_c, z_c, t0, t1, n_samp, coarse):
    """End of the monotone run of a silhouette's tangential coordinate from sample ``kc`` in
    direction ``dirn`` (``_monotone_bounds``): (its coordinate, its sample) where the run
    ends within the line's half width, else (∓inf, the last sample walked)."""
    lim = 0.5 * _LINE_WIDTH + 1e-4
    e_c, _, _ = _sample(wheel, kc, gw, gr_, u_c, z_c, t0, t1)
    k = kc
    e_k = e_c
    while True:
        k2 = k + dirn * coarse
        if k2 < 0:
            k2 = 0
        elif k2 > n_samp - 1:
            k2 = n_samp - 1
        if k2 == k:
            return e_k, k                         # the end of the samples
        e2, _, _ = _sample(wheel, k2, gw, gr_, u_c, z_c, t0, t1)
        if dirn * (e2 - e_k) <= 0.0:
            break                                 # turned between k − step and k2
        k, e_k = k2, e2
        if dirn * e_k > lim:
            return dirn * math.inf, k
    # sample by sample from one coarse step back towards k2
    j = k - dirn * coarse
    if dirn * (j - kc) < 0:
        j = kc
    e_j, _, _ = _sample(wheel, j, gw, gr_, u_c, z_c, t0, t1)
    while j != k2:
        jn = j + dirn
        e_n, _, _ = _sample(wheel, jn, gw, gr_, u_c, z_c, t0, t1)
        if dirn * (e_n - e_j) <= 0.0:
            return e_j, j
        j, e_j = jn, e_n
    return e_j, j


@njit(cache=True)
def _span(wheel, kc, k_end, dirn, target, margin, gw, gr_, u_c, z_c, t0, t1):
    """Sample index beyond which the silhouette passes ``target`` in direction ``dirn``
    (walked from ``kc``, not past ``k_end``), plus the spline margin."""
    k = kc
    while dirn * (k_end - k) > 0:
        k2 = k + dirn * 8
        if dirn * (k2 - k_end) > 0:
            k2 = k_end
        e2, _, _ = _sample(wheel, k2, gw, gr_, u_c, z_c, t0, t1)
        k = k2
        if dirn * (e2 - target) > 0.0:
            break
    k = k + dirn * margin
    if dirn * (k - k_end) > 0:
        k = k_end
    return k


@njit(cache=True, inline="always")
def _lagrange_den(x, j):
    """Reciprocal denominators of the cubic Lagrange weights through x[j−1 … j+2]."""
    x0, x1, x2, x3 = x[j - 1], x[j], x[j + 1], x[j + 2]
    return (1.0 / ((x0 - x1) * (x0 - x2) * (x0 - x3)), 1.0 / ((x1 - x0) * (x1 - x2) * (x1 - x3)),
            1.0 / ((x2 - x0) * (x2 - x1) * (x2 - x3)), 1.0 / ((x3 - x0) * (x3 - x1) * (x3 - x2)))


@njit(cache=True)
def _line_nodes(ia, ib, stride, lo, hi, step, cosf, d0, kcw, kw0, kw1, kcr, kr0, kr1, gw, gr_, u_c,
                z_c, t0, t1, n_nodes):
    """Nodes ia … ib of the library's separation line (``separation_kernel``): η [m], the
    separation f [m], the longitudinal curvature cos/(2r) [1/m], the rail's surface angle
    [rad] at u_c + η cos γ (where f < ``d0``; 0 elsewhere) and the wheel circle radius [m].

    The library interpolates the profile samples (0.04 mm apart) by not-a-knot splines;
    here the cubic through the four samples around each node, which differs from it by
    far less than a nanometre on profile splines (both are exact for cubics; the samples
    and the nodes are the library's)."""
    n = ib - ia + 1
    eta = np.empty(n)
    for i in range(n):
        eta[i] = ((ia + i) * stride) * step + lo
    if ib * stride == n_nodes - 1:
        eta[n - 1] = hi
    f = np.empty(n)
    Ax = np.empty(n)
    ang = np.zeros(n)
    rw = np.empty(n)
    # samples around [eta_0, eta_n-1] inside the monotone runs
    a_w = _span(True, kcw, kw0, -1, eta[0], _MARGIN * stride, gw, gr_, u_c, z_c, t0, t1)
    b_w = _span(True, kcw, kw1, 1, eta[n - 1], _MARGIN * stride, gw, gr_, u_c, z_c, t0, t1)
    a_r = _span(False, kcr, kr0, -1, eta[0], _MARGIN * stride, gw, gr_, u_c, z_c, t0, t1)
    b_r = _span(False, kcr, kr1, 1, eta[n - 1], _MARGIN * stride, gw, gr_, u_c, z_c, t0, t1)
    mw = (b_w - a_w) // stride + 1
    mr = (b_r - a_r) // stride + 1
    if mw < 4 or mr < 4:
        return eta, f, Ax, ang, rw, False
    ew = np.empty(mw)
    zw = np.empty(mw)
    rr = np.empty(mw)
    s_lo, dsw, wu, winv, wc, r0, e_tape, sig, y, zc, st, ct, sp, cp, R, ph0 = gw
    u_lo, dsr, ru, rinv, rc = gr_
    for k in range(mw):             # (the arithmetic of _sample, arrays unpacked once)
        s = (a_w + k * stride) * dsw + s_lo
        p, p1, _ = _spline(wu, winv, wc, s)
        Y, Z, _, rk = _locus(s, p, p1, r0, e_tape, sig, y, zc, st, ct, sp, cp, R, ph0)
        du = sig * Y - u_c
        dz = Z - z_c
        ew[k] = du * t0 + dz * t1
        zw[k] = -du * t1 + dz * t0
        rr[k] = rk
    er = np.empty(mr)
    zr = np.empty(mr)
    for k in range(mr):
        u = (a_r + k * stride) * dsr + u_lo
        du = u - u_c
        dz = _spline0(ru, rinv, rc, u) - z_c
        er[k] = du * t0 + dz * t1
        zr[k] = -du * t1 + dz * t0
    if ew[0] > eta[0] or ew[mw - 1] < eta[n - 1] or er[0] > eta[0] or er[mr - 1] < eta[n - 1]:
        return eta, f, Ax, ang, rw, False
    jw = 1
    jr = 1
    dw0, dw1, dw2, dw3 = _lagrange_den(ew, jw)
    dr0, dr1, dr2, dr3 = _lagrange_den(er, jr)
    for i in range(n):
        e = eta[i]
        if jw < mw - 3 and ew[jw + 1] < e:
            while jw < mw - 3 and ew[jw + 1] < e:
                jw += 1
            dw0, dw1, dw2, dw3 = _lagrange_den(ew, jw)
        if jr < mr - 3 and er[jr + 1] < e:
            while jr < mr - 3 and er[jr + 1] < e:
                jr += 1
            dr0, dr1, dr2, dr3 = _lagrange_den(er, jr)
        a0, a1, a2, a3 = e - ew[jw - 1], e - ew[jw], e - ew[jw + 1], e - ew[jw + 2]
        b0, b1, b2, b3 = e - er[jr - 1], e - er[jr], e - er[jr + 1], e - er[jr + 2]
        w0 = a1 * a2 * a3 * dw0
        w1 = a0 * a2 * a3 * dw1
        w2 = a0 * a1 * a3 * dw2
        w3 = a0 * a1 * a2 * dw3
        f[i] = (w0 * zw[jw - 1] + w1 * zw[jw] + w2 * zw[jw + 1] + w3 * zw[jw + 2]
                - (b1 * b2 * b3 * dr0 * zr[jr - 1] + b0 * b2 * b3 * dr1 * zr[jr]
                   + b0 * b1 * b3 * dr2 * zr[jr + 1] + b0 * b1 * b2 * dr3 * zr[jr + 2]))
        rw[i] = w0 * rr[jw - 1] + w1 * rr[jw] + w2 * rr[jw + 1] + w3 * rr[jw + 2]
        Ax[i] = cosf / (2.0 * rw[i])
        if d0 - f[i] > 0.0:
            _, z1, _ = _spline(ru, rinv, rc, u_c + e * t0)
            ang[i] = math.atan(z1)
    return eta, f, Ax, ang, rw, True
