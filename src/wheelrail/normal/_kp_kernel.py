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

__all__ = ["k_minus_e", "kp_integrals_kernel", "kp_line_load", "kp_line_regions", "kpec_line_load",
           "kpec_line_regions"]


#: smallest height [m] of a hump of the separation (above the lowest node on either side)
#: at which :func:`kpec_line_regions` splits a run of interpenetration into two regions
_HUMP = 1e-8

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


@njit(cache=True)
def kpec_line_regions(f, Ax, eta, h, delta, E_star, lam, la, lb, ld, ln_max):
    """The regions of one line by Vollebregt's KPEC (pure kernel).

    Kik–Piotrowski with ellipticity correction: every run of nodes with real
    interpenetration δ − f > 0 is one region with its own penetration
    δ_r = δ − f_min and an equivalent Hertz ellipse, whose curvatures are the
    longitudinal curvature A at the deepest node and B = (δ_r/2)/w², w the
    half width of the run where f − f_min ≤ δ_r/2 (ends interpolated linearly),
    centred at y_m; a, b are Hertz's semi-axes for A, B at the approach δ_r.
    The virtual penetration then varies across the region (a parabola in y),

        t(y) = A a² − (A a² − B b²) ((y − y_m)/b)²,   clipped to [0, δ_r],

    and the strips are x_l(y) = √((t(y) − f(y) + f_min)/A_x(y)); for a quadratic
    gap this is exactly Hertz's ellipse (x²/a² + y²/b² ≤ 1), with no separate
    shape correction. The pressure is Kik & Piotrowski's (semi-elliptic along
    the strips, one peak, the deflection at the deepest node equal to δ_r):
    N = π E* δ_r I1/I2 as in :func:`kp_line_regions`.

    With s = √(AB) and Hertz's unit table (ln a, ln b, ln δ at load/E* = 1,
    A·B = 1 on the grid ``lam`` of ln(A/B)): A a² = δ_r e^(2 ln a − ln δ + λ/2),
    B b² = δ_r e^(2 ln b − ln δ − λ/2), b² = δ_r e^(2 ln b − ln δ)/s (a, b ∝ √δ_r).
    ln(A/B) is clipped to ±``ln_max``.

    Returns
    -------
    ok : bool
        Always True (the signature of :func:`kp_line_regions`).
    meta : ndarray, shape (k, 8)
        Per region: start, stop (exclusive; the nodes with x_l > 0 and the ones
        between), deepest node (relative), N [N], p0 [Pa], a/b, δ_r [m] and
        t/δ_r at the deepest node (the local penetration factor).
    eta_c, xl_c, peak, g : ndarray, shape (n,)
        η [m] (unchanged), half-lengths [m], strip peaks [Pa] and the virtual
        interpenetration t − f + f_min (positive part) [m] (weights).

    References
    ----------
    .. [1] E.A.H. Vollebregt, User guide for CONTACT, rolling and sliding contact with
       friction, VORtech technical report TR20-01 (open-source version), section "Fast
       or detailed solution": KPEC, Kik–Piotrowski with ellipse correction (variable
       ε(y) from Hertz's theory, exact for elliptic patches; the equivalent ellipse
       from the curvature at the deepest point and the width at ε = 1/2).
    .. [2] J. Piotrowski, W. Kik, VSD 46 (2008) 27–48 (the pressure, eqs. 12–16).
    """
    n = f.shape[0]
    meta = np.empty((n // 2 + 1, 8))
    eta_c = eta.copy()
    xl_c = np.zeros(n)
    peak = np.zeros(n)
    gw = np.zeros(n)
    k = 0
    i = 0
    while i < n:
        if not delta - f[i] > 0:
            i += 1
            continue
        i0 = i
        while i < n and delta - f[i] > 0:
            i += 1
        r1 = i
        # split the run at its humps (local maxima of f more than _HUMP above the lowest
        # node on either side): one region per valley, so that the regions do not change
        # when the approach rises above a hump (the load stays continuous in δ)
        s0 = i0
        while s0 < r1:
            i0 = s0
            i1 = r1
            lo_l = f[i0]
            for q in range(i0 + 1, r1 - 1):
                lo_l = min(lo_l, f[q])
                if f[q] >= f[q - 1] and f[q] > f[q + 1] and f[q] - lo_l > _HUMP:
                    lo_r = f[q + 1]
                    u = q + 1
                    while u < r1 and f[u] <= f[q]:
                        lo_r = min(lo_r, f[u])
                        u += 1
                    if f[q] - lo_r > _HUMP:
                        i1 = q
                        break
            s0 = i1 + 1 if i1 < r1 else r1
            k = _kpec_region(f, Ax, eta, h, delta, E_star, lam, la, lb, ld, ln_max, i0, i1,
                             meta, k, xl_c, peak, gw)
    return True, meta[:k], eta_c, xl_c, peak, gw


@njit(cache=True)
def _kpec_region(f, Ax, eta, h, delta, E_star, lam, la, lb, ld, ln_max, i0, i1, meta, k, xl_c,
                 peak, gw):
    """One KPEC region on the nodes i0 … i1 − 1 (see :func:`kpec_line_regions`); returns
    the new count of regions in ``meta``."""
    if i1 - i0 < 3:
        return k
    j = i0
    for q in range(i0, i1):
        if f[q] < f[j]:
            j = q
    fmin = f[j]
    pen = delta - fmin
    A = Ax[j]
    if not A > 0:
        return k
    thr = fmin + 0.5 * pen
    q = j
    while q > i0 and f[q - 1] <= thr:
        q -= 1
    if q > i0:
        ysta = eta[q] - h * (thr - f[q]) / (f[q - 1] - f[q])
    else:
        ysta = eta[q] - 0.5 * h
    q = j
    while q < i1 - 1 and f[q + 1] <= thr:
        q += 1
    if q < i1 - 1:
        yend = eta[q] + h * (thr - f[q]) / (f[q + 1] - f[q])
    else:
        yend = eta[q] + 0.5 * h
    w = 0.5 * (yend - ysta)
    ym = 0.5 * (ysta + yend)
    B = 0.5 * pen / (w * w)
    lnab = min(max(math.log(A / B), -ln_max), ln_max)
    s = math.sqrt(A * B)
    ia = np.interp(lnab, lam, la)
    ib = np.interp(lnab, lam, lb)
    idd = np.interp(lnab, lam, ld)
    a2 = pen * math.exp(2.0 * ia - idd) / s
    b2 = pen * math.exp(2.0 * ib - idd) / s
    ex = A * a2
    ey = B * b2
    b = math.sqrt(b2)
    b = max(b, 1.1 * abs(eta[j] - ym))
    q0 = -1
    q1 = -1
    for q in range(i0, i1):
        u = (eta[q] - ym) / b
        t = min(max(ex - (ex - ey) * u * u, 0.0), pen)
        g = t - (f[q] - fmin)
        if g > 0 and Ax[q] > 0:
            gw[q] = g
            xl_c[q] = math.sqrt(g / Ax[q])
            if q0 < 0:
                q0 = q
            q1 = q + 1
    if q0 < 0 or q1 - q0 < 3 or not xl_c[j] > 0:
        for q in range(i0, i1):
            gw[q] = 0.0
            xl_c[q] = 0.0
        return k
    jj = j - q0
    I1, I2 = kp_integrals_kernel(xl_c[q0:q1], h, jj)
    N = math.pi * E_star * pen * I1 / I2
    xj = xl_c[j]
    p0 = N * xj / I1
    for q in range(q0, q1):
        peak[q] = p0 * xl_c[q] / xj
    meta[k, 0] = q0
    meta[k, 1] = q1
    meta[k, 2] = jj
    meta[k, 3] = N
    meta[k, 4] = p0
    meta[k, 5] = math.sqrt(a2) / b
    meta[k, 6] = pen
    meta[k, 7] = min(max(ex - (ex - ey) * ((eta[j] - ym) / b) ** 2, 0.0), pen) / pen
    k += 1
    return k


@njit(cache=True)
def kpec_line_load(f, Ax, eta, angle, h, delta, E_star, lam, la, lb, ld, ln_max):
    """Normal load of one line by KPEC (:func:`kpec_line_regions`) at approach ``delta``:
    (Σ N, Σ N cos ᾱ), ᾱ the region's mean surface angle weighted by its virtual
    interpenetration (as :func:`kp_line_load`)."""
    _, meta, _, _, _, g = kpec_line_regions(f, Ax, eta, h, delta, E_star, lam, la, lb, ld, ln_max)
    N_tot = 0.0
    Nz = 0.0
    for r in range(meta.shape[0]):
        q0 = int(meta[r, 0])
        q1 = int(meta[r, 1])
        N = meta[r, 3]
        sw = 0.0
        swa = 0.0
        for q in range(q0, q1):
            sw += g[q]
            swa += g[q] * angle[q]
        N_tot += N
        Nz += N * math.cos(swa / sw)
    return N_tot, Nz
