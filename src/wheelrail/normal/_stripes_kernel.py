"""Numba kernel of the STRIPES load iteration (private; pure array-in/array-out).

:func:`stripes_line_load` is ``Stripes._line_loads`` (:mod:`wheelrail.normal.stripes`)
in one call: with Piotrowski & Chollet (2005) eq. (27) the force of strip i is ½π k_p E* h_i h
(a_i cancels), so the load of a line is a sum over its interpenetration
regions.

References
----------
.. [1] J. Piotrowski, H. Chollet, Wheel–rail contact models for vehicle system
   dynamics including multi-point contact, VSD 43 (2005), §3.3, eqs. (23)–(27).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ._patch_kernel import pairwise_sum

__all__ = ["stripes_line_load", "smooth_nodes", "half_curvature"]


@njit(cache=True)
def stripes_line_load(f, angle, has_angle, d0, c):
    """(Σ N, Σ N cos ᾱ) of one line at the virtual penetration ``d0`` [m] (pure kernel).

    Parameters
    ----------
    f : ndarray, shape (n,)
        Separation [m].
    angle : ndarray, shape (n,)
        Surface angle [rad] (read when ``has_angle``; ᾱ of a region is its
        h-weighted mean).
    d0 : float
        h0 = ε δ [m].
    c : float
        ½π k_p E* h [N/m].
    """
    n = f.shape[0]
    N = 0.0
    Nz = 0.0
    hi = f.copy()
    for i in range(n):
        hi[i] = d0 - f[i]
    i = 0
    while i < n:
        if not hi[i] > 0:
            i += 1
            continue
        i0 = i
        while i < n and hi[i] > 0:
            i += 1
        if i - i0 < 3:
            continue
        s = pairwise_sum(hi, i0, i - i0, 1)
        nn = c * s
        if not nn > 0:
            continue
        N += nn
        if has_angle:
            dot = 0.0
            for k in range(i0, i):
                dot += hi[k] * angle[k]
            Nz += nn * math.cos(dot / s)
        else:
            Nz += nn
    return N, Nz


@njit(cache=True)
def half_curvature(f, h):
    """½ f'' by two central differences, ``numpy.gradient(numpy.gradient(f, h), h) * 0.5``
    (one-sided at the ends, as ``numpy.gradient`` with ``edge_order=1``; the same numbers)."""
    n = f.shape[0]
    d1 = np.empty(n)
    d2 = np.empty(n)
    for g, out in ((f, d1), (d1, d2)):
        out[0] = (g[1] - g[0]) / h
        for i in range(1, n - 1):
            out[i] = (g[i + 1] - g[i - 1]) / (2.0 * h)
        out[n - 1] = (g[n - 1] - g[n - 2]) / h
    for i in range(n):
        d2[i] = d2[i] * 0.5
    return d2


@njit(cache=True, fastmath=True)
def smooth_nodes(d2, krev, idx):
    """``numpy.convolve(numpy.pad(d2, half, mode="edge"), k, "valid")`` at the outputs
    ``idx`` only (pure kernel; ``krev`` = k reversed, 2·half + 1 long).

    Each output is a dot product over a window of ``d2`` (edge values repeated
    beyond the ends), summed in vector lanes (``fastmath``: the order of the
    additions differs from NumPy's, the values agree to round-off).
    """
    m = krev.shape[0]
    half = m // 2
    n = d2.shape[0]
    out = np.empty(idx.shape[0])
    for q in range(idx.shape[0]):
        i0 = idx[q] - half
        acc = 0.0
        if i0 >= 0 and i0 + m <= n:
            for t in range(m):
                acc += d2[i0 + t] * krev[t]
        else:
            for t in range(m):
                j = min(max(i0 + t, 0), n - 1)
                acc += d2[j] * krev[t]
        out[q] = acc
    return out
