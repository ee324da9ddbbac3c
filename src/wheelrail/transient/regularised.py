"""Regularised Coulomb law for one transient step (Baeza et al. eqs. 2.21–2.22), dense Newton.

The traction is a smooth function of the slip (dimensionless, slip velocity / V)::

    p(s) = −g (2/π) atan(|s|/ε) s/|s|,      g = μ pn,           (eq. 2.21)

so the step equation ``s = b + K p`` (eq. 2.19 with ``K = C/(VΔt)``) has no
adhesion/slip split. It is solved for the tractions of the contact elements by
Newton–Raphson (eq. 2.22) on the inverse law
``s(p) = −ε tan(π|p|/(2g)) p/|p|``::

    R(p) = s(p) − b − K p = 0,

whose Jacobian ``ds/dp − K`` is minus a positive definite matrix (monotone
law plus elastic flexibility; symmetric for the centre scheme, not for the
element-averaged one, so a general LU solve is used); updates are damped to stay inside the
friction disc ``|p| < g`` (fraction to the boundary 0.99). The Jacobian is dense
over the contact elements (O(n³) per iteration): meant for the modest grids of
the transient runs (≲ 1000 contact elements).

References
----------
Baeza et al. eqs. (2.19), (2.21), (2.22) and Fig. 6.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla

from ..errors import ConvergenceError, InputError

__all__ = ["dense_block", "regularised_step"]

_SMALL = 600  # below this size the dense Newton systems are solved by _lu_solve


def _lu_solve_impl(A, b):
    """Solve ``A x = b`` by Gaussian elimination with partial pivoting (copies A, b).

    Single-threaded on purpose: for the small systems of a regularised step a
    threaded LAPACK ``getrf`` is slower by orders of magnitude when the cores
    are busy (measured 128 ms against 1 ms for n = 200 under load).
    """
    n = A.shape[0]
    M = A.copy()
    x = b.copy()
    for k in range(n):
        piv = k
        big = abs(M[k, k])
        for i in range(k + 1, n):
            if abs(M[i, k]) > big:
                big = abs(M[i, k])
                piv = i
        if piv != k:
            for j in range(n):
                t = M[k, j]
                M[k, j] = M[piv, j]
                M[piv, j] = t
            t = x[k]
            x[k] = x[piv]
            x[piv] = t
        inv = 1.0 / M[k, k]
        for i in range(k + 1, n):
            f = M[i, k] * inv
            if f != 0.0:
                for j in range(k + 1, n):
                    M[i, j] -= f * M[k, j]
                x[i] -= f * x[k]
    for k in range(n - 1, -1, -1):
        acc = x[k]
        for j in range(k + 1, n):
            acc -= M[k, j] * x[j]
        x[k] = acc / M[k, k]
    return x


_lu_jit = None


def _solve(A, b):
    global _lu_jit
    if A.shape[0] > _SMALL:
        return sla.solve(A, b)
    if _lu_jit is None:
        from numba import njit

        _lu_jit = njit(cache=True)(_lu_solve_impl)
    return _lu_jit(np.ascontiguousarray(A), np.ascontiguousarray(b))


def dense_block(kernel, ii, jj):
    """Dense matrix (2n, 2n) of a kernel (2, 2, 2nx−1, 2ny−1) on elements (ii, jj).

    Ordering ``[x-components of the n elements, y-components]``.
    """
    nx = (kernel.shape[-2] + 1) // 2
    ny = (kernel.shape[-1] + 1) // 2
    di = ii[:, None] - ii[None, :] + nx - 1
    dj = jj[:, None] - jj[None, :] + ny - 1
    return np.block([[kernel[0, 0][di, dj], kernel[0, 1][di, dj]],
                     [kernel[1, 0][di, dj], kernel[1, 1][di, dj]]])


def regularised_step(Kd, b, g, epsilon, p0=None, *, tol=1e-10, maxiter=100):
    """Solve ``s = b + Kd p`` with ``p = −g (2/π) atan(|s|/ε) s/|s|`` on n elements.

    Parameters
    ----------
    Kd : ndarray, shape (2n, 2n)
        Slip per unit traction [1/Pa] (:func:`dense_block` of ``C/h``).
    b : ndarray, shape (2, n)
        Slip at zero traction [-].
    g : ndarray, shape (n,)
        Traction bound μ pn [Pa], > 0.
    epsilon : float
        Regularisation slip ε [-] (slip velocity / V), > 0.
    p0 : ndarray, shape (2, n), optional
        Starting tractions [Pa] (pulled inside the disc if needed).
    tol : float
        Converged when ``max |R| <= tol · max(|b|)`` and the last update is small.

    Returns
    -------
    p, s : ndarray, shape (2, n)
        Tractions on the wheel [Pa] and slip [-].
    iterations : int
    """
    if not epsilon > 0:
        raise InputError(f"epsilon must be > 0, got {epsilon!r}")
    n = g.size
    q = np.zeros((2, n)) if p0 is None else np.array(p0, dtype=float)
    norm = np.hypot(q[0], q[1])
    lim = 0.9 * g
    q = np.where(norm > lim, q * (lim / np.where(norm > 0, norm, 1.0)), q)
    scale = max(float(np.max(np.abs(b))), 1e-300)
    c = 0.5 * np.pi / g
    for it in range(1, maxiter + 1):
        norm = np.hypot(q[0], q[1])
        th = np.minimum(c * norm, 0.5 * np.pi * (1 - 1e-15))
        tn = np.tan(th)
        safe = np.where(norm > 0, norm, 1.0)
        ex, ey = np.where(norm > 0, q[0] / safe, 1.0), np.where(norm > 0, q[1] / safe, 0.0)
        mag = epsilon * tn
        sinv = -mag * np.stack((ex, ey))
        s = b + (Kd @ q.ravel()).reshape(2, n)
        R = sinv - s
        res = float(np.max(np.abs(R))) / scale
        # d sinv / dq = −(m' e eᵀ + (m/|q|)(I − e eᵀ)), m' = ε c / cos²θ; m/|q| → ε c at 0
        dm = epsilon * c / np.cos(th) ** 2
        ratio = np.where(norm > 0, mag / safe, epsilon * c)
        axx = dm * ex * ex + ratio * (1 - ex * ex)
        ayy = dm * ey * ey + ratio * (1 - ey * ey)
        axy = (dm - ratio) * ex * ey
        J = -Kd.copy()
        idx = np.arange(n)
        J[idx, idx] -= axx
        J[idx + n, idx + n] -= ayy
        J[idx, idx + n] -= axy
        J[idx + n, idx] -= axy
        dq = _solve(-J, R.ravel()).reshape(2, n)
        # damp: stay strictly inside the friction disc
        alpha = 1.0
        new = q + dq
        nn = np.hypot(new[0], new[1])
        over = nn >= g
        if np.any(over):
            # largest alpha with |q + alpha dq| <= 0.99·(distance to the boundary) per element
            qa = dq[0] ** 2 + dq[1] ** 2
            qb = 2 * (q[0] * dq[0] + q[1] * dq[1])
            target = (norm + 0.99 * (g - norm)) ** 2
            qc = norm ** 2 - target
            root = (-qb + np.sqrt(np.maximum(qb * qb - 4 * qa * qc, 0))) / (2 * np.where(qa > 0, qa, 1))
            alpha = float(min(1.0, np.min(root[over])))
        q = q + alpha * dq
        if res <= tol and alpha == 1.0 and float(np.max(np.abs(dq))) <= 1e-9 * float(g.max()):
            break
    else:
        raise ConvergenceError(f"regularised Newton (epsilon = {epsilon!r}) did not converge in "
                               f"{maxiter} iterations (residual {res:.2e})")
    s = b + (Kd @ q.ravel()).reshape(2, n)
    return q, s, it
