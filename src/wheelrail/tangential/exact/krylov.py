"""Restarted GMRES (Saad & Schultz 1986) with numba Gram–Schmidt, Givens rotations and
back substitution, for the Newton systems of the exact tangential solver.

References
----------
.. [1] Y. Saad, M.H. Schultz, GMRES: a generalized minimal residual algorithm
   for solving nonsymmetric linear systems, SIAM J. Sci. Stat. Comput. 7
   (1986) 856–869.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ._kernels import _REASSOC


@njit(cache=True, fastmath=_REASSOC)
def _orthogonalise(V, k, w, h):
    """Modified Gram–Schmidt of ``w`` against rows ``V[:k+1]``; fills ``h[:k+2]``."""
    n = w.shape[0]
    acc = 0.0
    for q in range(n):
        acc += V[0, q] * w[q]
    # one pass per basis vector: subtract the projection on V[i] and, with the updated
    # entries, accumulate the projection on V[i + 1] (the same operations as modified
    # Gram–Schmidt, half the passes over w)
    for i in range(k + 1):
        h[i] = acc
        nxt = 0.0
        if i < k:
            for q in range(n):
                wq = w[q] - acc * V[i, q]
                w[q] = wq
                nxt += V[i + 1, q] * wq
        else:
            for q in range(n):
                wq = w[q] - acc * V[i, q]
                w[q] = wq
                nxt += wq * wq
        acc = nxt
    h[k + 1] = math.sqrt(acc)


@njit(cache=True)
def _givens(H, cs, sn, e, k):
    """Apply the previous Givens rotations to column k of H and add a new one."""
    for i in range(k):
        t = cs[i] * H[i, k] + sn[i] * H[i + 1, k]
        H[i + 1, k] = -sn[i] * H[i, k] + cs[i] * H[i + 1, k]
        H[i, k] = t
    den = math.hypot(H[k, k], H[k + 1, k])
    if den == 0.0:
        cs[k] = 1.0
        sn[k] = 0.0
    else:
        cs[k] = H[k, k] / den
        sn[k] = H[k + 1, k] / den
    H[k, k] = den
    H[k + 1, k] = 0.0
    e[k + 1] = -sn[k] * e[k]
    e[k] = cs[k] * e[k]


@njit(cache=True, fastmath=_REASSOC)
def _norm(w):
    """Euclidean norm without BLAS (private; threaded BLAS is slow on a shared machine)."""
    acc = 0.0
    for q in range(w.shape[0]):
        acc += w[q] * w[q]
    return math.sqrt(acc)


@njit(cache=True)
def _arnoldi(V, k, w, H, h, cs, sn, e):
    """One Arnoldi step in place: orthogonalise ``w`` (:func:`_orthogonalise`), column k of
    ``H``, ``V[k + 1] = w / h[k + 1]`` and the Givens rotation (:func:`_givens`).

    One call instead of five (the same operations); returns ``h[k + 1]``.
    """
    _orthogonalise(V, k, w, h)
    for i in range(k + 2):
        H[i, k] = h[i]
    hk = h[k + 1]
    if hk > 0:
        inv = 1.0 / hk
        for q in range(w.shape[0]):
            V[k + 1, q] = w[q] * inv
    _givens(H, cs, sn, e, k)
    return hk


@njit(cache=True)
def _gmres_update(V, H, e, k_used, x):
    """``x += V[:k]ᵀ y`` with ``H[:k, :k] y = e[:k]`` (back substitution; in place)."""
    y = np.empty(k_used)
    for i in range(k_used - 1, -1, -1):
        acc = e[i]
        for j in range(i + 1, k_used):
            acc -= H[i, j] * y[j]
        y[i] = acc / H[i, i]
    n = x.shape[0]
    for i in range(k_used):
        yi = y[i]
        for q in range(n):
            x[q] += yi * V[i, q]


def _gmres(matvec, rhs, rtol, maxiter, restart=60):
    """Restarted GMRES for ``A x = rhs`` from x = 0 (private; Saad & Schultz 1986).

    Written out (numba Gram–Schmidt, back substitution and update) because the
    BLAS calls of :func:`scipy.sparse.linalg.gmres` dominate for these small,
    many systems, and multi-threaded BLAS level-1/2 calls are slow when the
    cores are shared. Returns ``x, iterations``.
    """
    n = rhs.shape[0]
    x = np.zeros(n)
    beta0 = _norm(rhs)
    if beta0 == 0.0:
        return x, 0
    total = 0
    r = rhs
    m = min(restart, n)
    V = np.empty((m + 1, n))
    H = np.zeros((m + 1, m))
    cs = np.zeros(m)
    sn = np.zeros(m)
    e = np.zeros(m + 1)
    h = np.zeros(m + 1)
    while total < maxiter:
        beta = _norm(r)
        H[:] = 0.0
        e[:] = 0.0
        e[0] = beta
        np.multiply(r, 1.0 / beta, out=V[0])
        k_used = 0
        for k in range(m):
            hk = _arnoldi(V, k, matvec(V[k]), H, h, cs, sn, e)
            total += 1
            k_used = k + 1
            if abs(e[k + 1]) <= rtol * beta0 or total >= maxiter or hk == 0:
                break
        if k_used:
            _gmres_update(V, H, e, k_used, x)
        if abs(e[k_used]) <= rtol * beta0 or total >= maxiter:
            break
        r = rhs - matvec(x)
    return x, total


