"""Numba kernel of the STRIPES load iteration (private; pure array-in/array-out).

:func:`stripes_line_load` is ``Stripes._line_loads`` (:mod:`wheelrail.normal.stripes`)
in one call: with seed 003 eq. (27) the force of strip i is ½π k_p E* h_i h
(a_i cancels), so the load of a line is a sum over its interpenetration
regions.

References
----------
.. [1] J. Piotrowski, H. Chollet, Wheel–rail contact models for vehicle system
   dynamics including multi-point contact, VSD 43 (2005), §3.3, eqs. (23)–(27) (seed 003).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ._patch_kernel import pairwise_sum

__all__ = ["stripes_line_load", "smooth_nodes"]


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


@njit(cache=True, fastmath=True)
def smooth_nodes(pad, k, idx):
    """``numpy.convolve(pad, k, "valid")`` at the outputs ``idx`` only (pure kernel).

    Each output is a dot product of ``k`` reversed with a window of ``pad``,
    summed in vector lanes (``fastmath``: the order of the additions differs from
    NumPy's, the values agree to round-off).
    """
    m = k.shape[0]
    out = np.empty(idx.shape[0])
    for q in range(idx.shape[0]):
        i = idx[q]
        acc = 0.0
        for t in range(m):
            acc += pad[i + t] * k[m - 1 - t]
        out[q] = acc
    return out
