"""Numba kernels of Kik & Piotrowski's method (private; pure array-in/array-out).

:func:`kp_line_load` is the load of one lateral line at a given virtual
penetration, the quantity the load iteration of
:class:`wheelrail.normal.kik_piotrowski.KikPiotrowski` evaluates many times:
the same discrete equations as its ``_solve_line`` (regions of positive
interpenetration, shape correction, the integrals of eqs. 13–15), without
building region objects. :func:`k_minus_e` gives K(m) − E(m) by the
arithmetic–geometric mean, so that the integrals need no SciPy call.

References
----------
.. [1] J. Piotrowski, H. Chollet, Wheel–rail contact models for vehicle system
   dynamics including multi-point contact, VSD 43 (2005), §3.2, eqs. (12)–(22).
.. [2] M. Abramowitz, I.A. Stegun, *Handbook of mathematical functions*, 17.6
   (arithmetic–geometric mean for K and E).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = ["k_minus_e", "kp_integrals_kernel", "kp_line_load", "kp_line_regions"]


#: relative size of c at which the AGM of :func:`k_minus_e` has converged
_AGM_TOL = 1e-15


@njit(cache=True)
def k_minus_e(m):
    """K(m) − E(m) for 0 ≤ m < 1 (parameter m = k²), by the AGM (Abramowitz & Stegun 17.6).

    a₀ = 1, b₀ = √(1 − m), c₀ = √m; K = π/(2 a_N); E = K (1 − Σ 2^(n−1) c_n²),
    so K − E = K Σ_n 2^(n−1) c_n² (no cancellation for small m).

    Stops at |c_n| ≤ 1e-15 a_n (a few units in the last place): in floating
    point the AGM may end in a cycle where a and b differ by one unit and c
    never reaches 0; the remaining change of a is below ~5e-16 relative.
    """
    a = 1.0
    b = math.sqrt(1.0 - m)
    s = 0.5 * m
    w = 0.5
    for _ in range(40):
        c = 0.5 * (a - b)
        a_new = 0.5 * (a + b)
        b = math.sqrt(a * b)
        a = a_new
        w *= 2.0
        s += w * c * c
        if abs(c) <= _AGM_TOL * a:
            break
    return 0.5 * math.pi / a * s


#: AGM steps run for every node of :func:`kp_integrals_kernel`: enough for b₀ = √(1 − m) ≳ 0.05
#: (|y| ≳ x_l/20); the few nodes next to the reference point that need more are redone by
#: :func:`k_minus_e`
_AGM_STEPS = 6


@njit(cache=True, error_model="numpy")
def kp_integrals_kernel(xl, h, j0):
    """I1, I2 of eqs. (13)–(15) (see :func:`wheelrail.normal._strips.kp_integrals`).

    K − E of every node by the AGM of :func:`k_minus_e` with a fixed number of
    steps and no branch, so that the compiler vectorises over the nodes (the
    steps after convergence change a, b by at most a unit in the last place
    and the sum not at all). Nodes whose c is not below ``_AGM_TOL`` a after
    ``_AGM_STEPS`` steps are redone with :func:`k_minus_e`; the sum over the
    nodes runs in node order.
    """
    n = xl.shape[0]
    s1 = 0.0
    for i in range(n):
        s1 += xl[i] * xl[i]
    J = np.empty(n)
    C = np.empty(n)
    for i in range(n):             # vectorised: every lane runs _AGM_STEPS steps
        x = xl[i]
        y = (i - j0) * h
        r2 = x * x + y * y
        m = x * x / r2
        a = 1.0
        b = math.sqrt(1.0 - m)
        s = 0.5 * m
        w = 0.5
        c = 0.0
        for _ in range(_AGM_STEPS):
            c = 0.5 * (a - b)
            a_new = 0.5 * (a + b)
            b = math.sqrt(a * b)
            a = a_new
            w *= 2.0
            s += w * c * c
        J[i] = 2.0 * math.sqrt(r2) * (0.5 * math.pi / a * s)
        C[i] = 0.0 if abs(c) <= _AGM_TOL * a else 1.0
    s2 = 0.0
    for i in range(n):
        x = xl[i]
        if x > 0.0 and i != j0:
            if C[i] != 0.0:        # not converged in _AGM_STEPS steps (rare)
                y = (i - j0) * h
                r2 = x * x + y * y
                J[i] = 2.0 * math.sqrt(r2) * k_minus_e(x * x / r2)
            s2 += J[i]
    I1 = 0.5 * math.pi * s1 * h
    I2 = s2 * h
    x0 = xl[j0]
    if x0 > 0.0:
        I2 += 2.0 * x0 * h * math.log(8.0 * x0 / h)
    return I1, I2


@njit(cache=True)
def kp_line_load(f, Ax, angle, h, d0, eps, E_star, correct, lam, la, lb):
    """Normal load of one line at virtual penetration ``d0`` (pure kernel).

    Parameters
    ----------
    f, Ax, angle : ndarray, shape (n,)
        Separation [m], longitudinal curvature [1/m] and surface angle [rad]
        at the uniformly spaced nodes (spacing ``h`` [m]).
    d0 : float
        Virtual penetration ε δ [m].
    eps : float
        Penetration factor ε [-].
    E_star : float
        Contact modulus [Pa].
    correct : bool
        Shape correction (eqs. 17–22).
    lam, la, lb : ndarray
        Hertz table: ln(A/B) grid and ln a, ln b at A·B = 1
        (:func:`wheelrail.normal._strips._hertz_table`).

    Returns
    -------
    N : float
        Σ of the regions' normal forces [N].
    Nz : float
        Σ N cos(ᾱ), ᾱ the region's interpenetration-weighted surface angle [N].
    """
    n = f.shape[0]
    N_tot = 0.0
    Nz = 0.0
    i = 0
    while i < n:
        if d0 - f[i] <= 0.0:
            i += 1
            continue
        i0 = i
        while i < n and d0 - f[i] > 0.0:
            i += 1
        i1 = i
        m = i1 - i0
        if m < 3:
            continue
        xl = np.empty(m)
        j = 0
        gmax = -1.0
        sw = 0.0
        swa = 0.0
        xmax = 0.0
        for k in range(m):
            gk = d0 - f[i0 + k]
            xl[k] = math.sqrt(gk / Ax[i0 + k])
            if gk > gmax:
                gmax = gk
                j = k
            if xl[k] > xmax:
                xmax = xl[k]
            sw += gk
            swa += gk * angle[i0 + k]
        real = gmax / eps
        hh = h
        if correct:
            L = 2.0 * xmax
            W = m * h
            x = math.log((W / L) ** 2)
            alpha = math.exp(np.interp(x, lam, la) - np.interp(x, lam, lb))
            sy = math.sqrt(L / (alpha * W))
            for k in range(m):
                xl[k] = xl[k] / sy
            hh = h * sy
        I1, I2 = kp_integrals_kernel(xl, hh, j)
        N = math.pi * E_star * real * I1 / I2
        N_tot += N
        Nz += N * math.cos(swa / sw)
    return N_tot, Nz


@njit(cache=True)
def kp_line_regions(f, Ax, eta, h, d0, eps, E_star, correct, lam, la, lb, ln_max):
    """The regions of one line at virtual penetration ``d0`` (pure kernel): the
    arithmetic of ``KikPiotrowski._solve_line`` (regions of at least 3 nodes, the
    penetration g_max/ε, the shape correction with Hertz's a/b from the table, the
    integrals, N and the strip peaks).

    Returns
    -------
    ok : bool
        False when a region's ln(A/B) of the shape correction lies beyond the
        table (|ln| > ``ln_max``): the caller then uses the Python path.
    meta : ndarray, shape (k, 6)
        Per region: start, stop (exclusive), deepest node (relative), N [N],
        p0 [Pa], α = L_c/W_c (NaN without correction).
    eta_c, xl_c, peak : ndarray, shape (n,)
        Per region's nodes (at start … stop − 1): stretched η [m], half-lengths [m]
        and strip peaks [Pa].
    """
    n = f.shape[0]
    meta = np.empty((n // 2 + 1, 6))
    eta_c = np.empty(n)
    xl_c = np.empty(n)
    peak = np.empty(n)
    k = 0
    i = 0
    while i < n:
        if not d0 - f[i] > 0:
            i += 1
            continue
        i0 = i
        while i < n and d0 - f[i] > 0:
            i += 1
        i1 = i
        m = i1 - i0
        if m < 3:
            continue
        j = 0
        gmax = d0 - f[i0]
        xmax = 0.0
        for q in range(m):
            g = d0 - f[i0 + q]
            x = math.sqrt(g / Ax[i0 + q])
            xl_c[i0 + q] = x
            if g > gmax:
                gmax = g
                j = q
            if x > xmax:
                xmax = x
        real = gmax / eps
        hh = h
        alpha = np.nan
        if correct:
            L = 2.0 * xmax
            W = m * h
            A = (W / L) ** 2
            lnab = math.log(A / 1.0)
            if abs(lnab) > ln_max:
                return False, meta[:0], eta_c, xl_c, peak
            s = math.sqrt(A * 1.0)
            a = math.exp(np.interp(lnab, lam, la)) / s ** (1 / 3)
            b = math.exp(np.interp(lnab, lam, lb)) / s ** (1 / 3)
            alpha = a / b
            sy = math.sqrt(L / (alpha * W))
            sx = 1.0 / sy
            ej = eta[i0 + j]
            for q in range(m):
                eta_c[i0 + q] = ej + (eta[i0 + q] - ej) * sy
                xl_c[i0 + q] = xl_c[i0 + q] * sx
            hh = h * sy
        else:
            for q in range(m):
                eta_c[i0 + q] = eta[i0 + q]
        I1, I2 = kp_integrals_kernel(xl_c[i0:i1], hh, j)
        N = math.pi * E_star * real * I1 / I2
        xj = xl_c[i0 + j]
        p0 = N * xj / I1
        for q in range(m):
            peak[i0 + q] = p0 * xl_c[i0 + q] / xj
        meta[k, 0] = i0
        meta[k, 1] = i1
        meta[k, 2] = j
        meta[k, 3] = N
        meta[k, 4] = p0
        meta[k, 5] = alpha
        k += 1
    return True, meta[:k], eta_c, xl_c, peak
