"""Numba kernel of the strip description of a virtual-penetration patch (private).

:func:`strip_patch` turns the nodes of one solved region (lateral positions
η, strip half-lengths x_l, peak pressures) into the ``strips`` × ``cells``
description of :class:`~wheelrail.patch.ContactPatch`: the equations
of ``VirtualPenetration._make_patch`` (:mod:`wheelrail.normal._strips`) in
one call. Sums follow NumPy's pairwise summation (:func:`pairwise_sum`), so
the numbers are those of the NumPy expressions they replace, to the last bit.

References
----------
.. [1] J. Piotrowski, H. Chollet, Wheel–rail contact models for vehicle system
   dynamics including multi-point contact, VSD 43 (2005), §3.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = ["pairwise_sum", "strip_patch", "positive_runs"]


@njit(cache=True)
def _block_sum(a, start, n, stride):
    """NumPy's pairwise summation of n ≤ 128 terms (see :func:`pairwise_sum`)."""
    if n < 8:
        res = -0.0
        for i in range(n):
            res += a[start + i * stride]
        return res
    r0 = a[start]
    r1 = a[start + stride]
    r2 = a[start + 2 * stride]
    r3 = a[start + 3 * stride]
    r4 = a[start + 4 * stride]
    r5 = a[start + 5 * stride]
    r6 = a[start + 6 * stride]
    r7 = a[start + 7 * stride]
    i = 8
    while i < n - (n % 8):
        b = start + i * stride
        r0 += a[b]
        r1 += a[b + stride]
        r2 += a[b + 2 * stride]
        r3 += a[b + 3 * stride]
        r4 += a[b + 4 * stride]
        r5 += a[b + 5 * stride]
        r6 += a[b + 6 * stride]
        r7 += a[b + 7 * stride]
        i += 8
    res = ((r0 + r1) + (r2 + r3)) + ((r4 + r5) + (r6 + r7))
    while i < n:
        res += a[start + i * stride]
        i += 1
    return res


@njit(cache=True)
def pairwise_sum(a, start, n, stride):
    """Σ of ``a[start + k·stride]``, k < n, in NumPy's pairwise order (its float64 ``add.reduce``).

    Below 8 terms a plain loop; up to 128 eight partial sums combined as
    ((r0 + r1) + (r2 + r3)) + ((r4 + r5) + (r6 + r7)) then the rest; beyond,
    the sum of the two halves (the first a multiple of 8 long), each summed
    the same way (an explicit stack: numba's cache does not keep recursive
    functions reliably).
    """
    if n <= 128:
        return _block_sum(a, start, n, stride)
    seg_s = np.empty(128, np.int64)
    seg_n = np.empty(128, np.int64)
    state = np.zeros(128, np.int64)
    vals = np.empty(128)
    top = 0
    nv = 0
    seg_s[0] = start
    seg_n[0] = n
    while top >= 0:
        s0 = seg_s[top]
        n0 = seg_n[top]
        if n0 <= 128:
            vals[nv] = _block_sum(a, s0, n0, stride)
            nv += 1
            top -= 1
            continue
        n2 = n0 // 2
        n2 -= n2 % 8
        if state[top] == 0:            # left half
            state[top] = 1
            top += 1
            seg_s[top] = s0
            seg_n[top] = n2
            state[top] = 0
        elif state[top] == 1:          # right half
            state[top] = 2
            top += 1
            seg_s[top] = s0 + n2 * stride
            seg_n[top] = n0 - n2
            state[top] = 0
        else:                          # both done: combine
            vals[nv - 2] = vals[nv - 2] + vals[nv - 1]
            nv -= 1
            top -= 1
    return vals[0]


@njit(cache=True)
def strip_patch(eta_n, xl_n, pk_n, h_line, strips, cells, N, eta_ref, sign):
    """Strips of one region (pure kernel; ``VirtualPenetration._make_patch``).

    Parameters
    ----------
    eta_n, xl_n, pk_n : ndarray, shape (n,)
        Node positions [m] (uniform), strip half-lengths [m] and peak pressures [Pa].
    h_line : float
        Node spacing of the line [m] (used when n = 1).
    strips, cells : int
        Strips across the patch and cells along each strip.
    N : float
        Normal force of the region [N]; the strip pressures are scaled to it.
    eta_ref : float
        η of the patch's reference point [m]; ``sign`` maps η to the patch y.

    Returns
    -------
    y, xl : ndarray, shape (strips,)
        Strip centres and half-lengths [m], sorted by y.
    sp : ndarray, shape (strips, cells)
        Cell pressures [Pa] (rows in the order of ``y``).
    ys : ndarray, shape (strips,)
        Strip centres in η (unsorted, increasing) [m].
    dy, width, area, L : float
        Strip width, patch width [m], area [m²] and length 2 max x_l [m].
    ok : bool
        All pressures finite and ≥ 0.
    """
    n = eta_n.shape[0]
    hn = eta_n[1] - eta_n[0] if n > 1 else h_line
    lo = eta_n[0] - 0.5 * hn
    hi = eta_n[n - 1] + 0.5 * hn
    width = hi - lo
    dy = width / strips
    ys = np.empty(strips)
    for k in range(strips):
        ys[k] = lo + (k + 0.5) * dy
    e_ext = np.empty(n + 2)
    x2 = np.empty(n + 2)
    pe = np.empty(n + 2)
    e_ext[0] = lo
    e_ext[n + 1] = hi
    x2[0] = 0.0
    x2[n + 1] = 0.0
    pe[0] = 0.0
    pe[n + 1] = 0.0
    for k in range(n):
        e_ext[k + 1] = eta_n[k]
        x2[k + 1] = xl_n[k] ** 2
        pe[k + 1] = pk_n[k]
    xl = np.sqrt(np.maximum(np.interp(ys, e_ext, x2), 0.0))
    pk = np.interp(ys, e_ext, pe)
    prof = np.empty(cells)
    for i in range(cells):
        s = 1.0 - (i + 0.5) * (2.0 / cells)
        prof[i] = math.sqrt(max(1.0 - s * s, 0.0))
    sp = np.empty((strips, cells))
    for k in range(strips):
        for i in range(cells):
            sp[k, i] = pk[k] * prof[i]
    flat = sp.reshape(strips * cells)
    t = np.empty(strips)
    for k in range(strips):
        t[k] = pairwise_sum(flat, k * cells, cells, 1) * (2 * xl[k] / cells) * dy
    got = pairwise_sum(t, 0, strips, 1)
    if got > 0:
        f = N / got
        for k in range(strips):
            for i in range(cells):
                sp[k, i] *= f
    xx = np.empty(strips)
    Lh = 0.0
    for k in range(strips):
        xx[k] = 2 * xl[k]
        Lh = max(Lh, xl[k])
    area = pairwise_sum(xx, 0, strips, 1) * dy
    ok = True
    for k in range(strips):
        for i in range(cells):
            v = sp[k, i]
            if not (v >= 0.0 and v < np.inf):
                ok = False
    y = np.empty(strips)
    xo = np.empty(strips)
    so = np.empty((strips, cells))
    for k in range(strips):
        src = k if sign > 0 else strips - 1 - k
        y[k] = sign * (ys[src] - eta_ref)
        xo[k] = xl[src]
        for i in range(cells):
            so[k, i] = sp[src, i]
    return y, xo, so, ys, dy, width, area, 2.0 * Lh, ok


@njit(cache=True)
def positive_runs(g):
    """Connected runs of g > 0: array (k, 2) of (start, stop), stop exclusive
    (:func:`wheelrail.normal._strips.runs` of ``g > 0``)."""
    n = g.shape[0]
    out = np.empty((n // 2 + 1, 2), np.int64)
    k = 0
    i = 0
    while i < n:
        if g[i] > 0:
            i0 = i
            while i < n and g[i] > 0:
                i += 1
            out[k, 0] = i0
            out[k, 1] = i
            k += 1
        else:
            i += 1
    return out[:k]


@njit(cache=True)
def weighted_means(w, a, b):
    """(Σ w a / Σ w, Σ w b / Σ w) with NumPy's pairwise sums (``np.sum(w * a) / np.sum(w)``
    to the bit), for the surface angle and the lateral position of a region."""
    n = w.shape[0]
    wa = np.empty(n)
    wb = np.empty(n)
    for i in range(n):
        wa[i] = w[i] * a[i]
        wb[i] = w[i] * b[i]
    sw = pairwise_sum(w, 0, n, 1)
    return pairwise_sum(wa, 0, n, 1) / sw, pairwise_sum(wb, 0, n, 1) / sw
