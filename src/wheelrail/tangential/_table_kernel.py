"""Compiled evaluation of the creep-force table (private kernel of :mod:`.table`).

One pass per point: the table coordinates of the contact and creepages, the
reflection into ξ, η ≥ 0, a tensor-product interpolation (interpolating cubic
B-spline along the axes flagged cubic, linear along the others) of the values stored
in the frame of the full-slip direction, the rotation back and the scaling to
forces. Kalker's C11, C22, C23 come from a fine (ln a/b, ν) lookup built once
by :mod:`.table` from :func:`wheelrail.tangential.linear.kalker_coefficients`.

References
----------
.. [1] C. de Boor, A Practical Guide to Splines, revised ed., Springer, 2001,
   ch. IX (B-splines) and ch. XII (the not-a-knot end condition).
"""

from __future__ import annotations

import numpy as np
from numba import njit

__all__ = ["evaluate", "point_forces"]


@njit(cache=True, inline="always")
def _locate(x, x0, dx, n):
    """Cell index i (0 ≤ i ≤ n − 2) and fraction t of x on a uniform axis of n nodes."""
    u = (x - x0) / dx
    if u < 0.0:
        u = 0.0
    if u > n - 1.0:
        u = n - 1.0
    i = int(u)
    if i > n - 2:
        i = n - 2
    return i, u - i


@njit(cache=True, inline="always")
def _weights(t, cubic, w):
    """Weights of the 4 coefficients i−1 … i+2 of a uniform cubic B-spline, or of the
    nodes i, i+1 (linear, others 0)."""
    if cubic:
        u = 1.0 - t
        t2 = t * t
        t3 = t2 * t
        w[0] = u * u * u / 6.0
        w[1] = (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0
        w[2] = (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0
        w[3] = t3 / 6.0
    else:
        w[0] = 0.0
        w[1] = 1.0 - t
        w[2] = t
        w[3] = 0.0


@njit(cache=True)
def point_forces(a, b, G, nu, xi, eta, phi, mu, Fn, values, x0, dx, n, cubic, c_x0, c_dx, c_n,
                 coef):
    """Creep forces of one contact from the table (see the module docstring).

    Parameters
    ----------
    a, b, G, nu, xi, eta, phi, mu, Fn : float
        Semi-axes [m], shear modulus [Pa], Poisson's ratio, creepages
        [-, -, 1/m], friction, normal force [N].
    values : ndarray, shape (n_r+2, n_θ+2, n_s+2, n_ab+2, n_ν+2, 3)
        Along the cubic axes the B-spline coefficients c₋₁ … c_n of the table
        values (along, across the full-slip direction, mz), along the linear
        axes the values padded by one unused ghost node at each end.
    x0, dx : ndarray, shape (5,)
        First node and spacing of each (uniform) axis; ``n`` node counts (int64).
    cubic : ndarray of bool, shape (5,)
        Axes interpolated with cubic B-splines.
    c_x0, c_dx, c_n : ndarray, shape (2,)
        The (ln a/b, ν) lookup grid of ``coef`` (shape (c_n0, c_n1, 3): C11, C22, C23).

    Returns
    -------
    flags : int
        0 inside the table; bit 1: |φ̂| beyond it, bit 2: a/b outside, bit 4: ν outside
        (the forces are then those of the clipped coordinates).
    Fx, Fy, Mz : float
        Forces on the wheel [N], [N], [N m].
    """
    ab = a / b
    lab = np.log(ab)
    fl = 0
    if lab < x0[3] - 1e-12 or lab > x0[3] + (n[3] - 1) * dx[3] + 1e-12:
        fl |= 2
    if nu < x0[4] - 1e-12 or nu > x0[4] + (n[4] - 1) * dx[4] + 1e-12:
        fl |= 4
    # Kalker's coefficients: bilinear in the (ln a/b, nu) lookup
    i0, t0 = _locate(lab, c_x0[0], c_dx[0], c_n[0])
    i1, t1 = _locate(nu, c_x0[1], c_dx[1], c_n[1])
    C11 = ((1 - t0) * ((1 - t1) * coef[i0, i1, 0] + t1 * coef[i0, i1 + 1, 0])
           + t0 * ((1 - t1) * coef[i0 + 1, i1, 0] + t1 * coef[i0 + 1, i1 + 1, 0]))
    C22 = ((1 - t0) * ((1 - t1) * coef[i0, i1, 1] + t1 * coef[i0, i1 + 1, 1])
           + t0 * ((1 - t1) * coef[i0 + 1, i1, 1] + t1 * coef[i0 + 1, i1 + 1, 1]))
    C23 = ((1 - t0) * ((1 - t1) * coef[i0, i1, 2] + t1 * coef[i0, i1 + 1, 2])
           + t0 * ((1 - t1) * coef[i0 + 1, i1, 2] + t1 * coef[i0 + 1, i1 + 1, 2]))
    c2 = a * b
    c = np.sqrt(c2)
    unit = G / (3.0 * mu * Fn)
    ell = np.hypot(c * C23, b * C11)
    xh = unit * c2 * C11 * xi
    ph = unit * c2 * ell * phi
    eh = unit * c2 * C22 * eta + unit * c2 * c * C23 * phi
    sx = -1.0 if xh < 0 else 1.0
    sy = -1.0 if eh < 0 else 1.0
    xh = abs(xh)
    eh = abs(eh)
    ph = ph * sy
    rho = np.hypot(xh, eh)
    theta = np.arctan2(eh, xh)
    s = ph / (1.0 + abs(ph))
    if abs(s) > x0[2] + (n[2] - 1) * dx[2] + 1e-12:
        fl |= 1
    i_r, t_r = _locate(rho / (1.0 + abs(ph) + rho), x0[0], dx[0], n[0])
    i_t, t_t = _locate(theta, x0[1], dx[1], n[1])
    i_s, t_s = _locate(s, x0[2], dx[2], n[2])
    i_l, t_l = _locate(lab, x0[3], dx[3], n[3])
    i_n, t_n = _locate(nu, x0[4], dx[4], n[4])
    w_r = np.empty(4)
    w_t = np.empty(4)
    w_s = np.empty(4)
    w_l = np.empty(4)
    w_n = np.empty(4)
    _weights(t_r, cubic[0], w_r)
    _weights(t_t, cubic[1], w_t)
    _weights(t_s, cubic[2], w_s)
    _weights(t_l, cubic[3], w_l)
    _weights(t_n, cubic[4], w_n)
    fa = 0.0
    fc = 0.0
    fm = 0.0
    for j0 in range(4):
        w0 = w_r[j0]
        if w0 == 0.0:
            continue
        for j1 in range(4):
            w1 = w0 * w_t[j1]
            if w1 == 0.0:
                continue
            for j2 in range(4):
                w2 = w1 * w_s[j2]
                if w2 == 0.0:
                    continue
                for j3 in range(4):
                    w3 = w2 * w_l[j3]
                    if w3 == 0.0:
                        continue
                    for j4 in range(4):
                        w4 = w3 * w_n[j4]
                        if w4 == 0.0:
                            continue
                        v = values[i_r + j0, i_t + j1, i_s + j2, i_l + j3, i_n + j4]
                        fa += w4 * v[0]
                        fc += w4 * v[1]
                        fm += w4 * v[2]
    alpha = np.arctan2(np.sin(theta) / C22, np.cos(theta) / C11)
    ca = np.cos(alpha)
    sa = np.sin(alpha)
    fx = fa * ca - fc * sa
    fy = fa * sa + fc * ca
    ft = np.hypot(fx, fy)
    if ft > 1.0:  # |F| <= mu Fn (a cubic may overshoot the full-slip bound slightly)
        fx /= ft
        fy /= ft
    scale = mu * Fn
    Fx = sx * fx * scale
    Fy = sy * fy * scale
    Mz = sy * fm * scale * c
    # symmetry: Fx odd in xi, (Fy, Mz) odd in (eta, phi)
    if xi == 0.0:
        Fx = 0.0
    if eta == 0.0 and phi == 0.0:
        Fy = 0.0
        Mz = 0.0
    return fl, Fx, Fy, Mz


@njit(cache=True)
def evaluate(a, b, G, nu, xi, eta, phi, mu, Fn, values, x0, dx, n, cubic, c_x0, c_dx, c_n,
             coef, out, flags):
    """:func:`point_forces` of m points (arrays of shape (m,)); writes ``out`` (m, 3), ``flags``."""
    for p in range(a.shape[0]):
        fl, Fx, Fy, Mz = point_forces(a[p], b[p], G[p], nu[p], xi[p], eta[p], phi[p], mu[p],
                                      Fn[p], values, x0, dx, n, cubic, c_x0, c_dx, c_n, coef)
        flags[p] = fl
        out[p, 0] = Fx
        out[p, 1] = Fy
        out[p, 2] = Mz
