"""Numba kernels of Kalker's FASTSIM (private; pure array-in/array-out).

The contact patch is a set of strips parallel to the rolling direction x.
Strip ``j`` lies at lateral position ``y[j]``, has width ``dy[j]`` and runs
from the leading edge ``x_lead[j]`` to the trailing edge ``x_trail[j]``
(``x_lead > x_trail``: the contact moves in +x, material enters at the
leading edge). Each strip is cut into ``nx`` equal elements spanning its own
length; tractions are evaluated at the element centres.

Simplified theory (Kalker 1982; Kalker 1990, chapter on the simplified theory): the surface
displacement difference is ``u = L p`` and the (non-dimensional) slip of the
wheel relative to the rail is ``s = w − ∂u/∂x`` with rigid slip
``w = (ξ − φ y, η + φ x)``. In the adhesion area s = 0, i.e. along a strip
``∂p/∂x = g`` with, for three flexibilities (Piotrowski & Chollet 2005,
Piotrowski & Chollet (2005) eq. 11),

    g_x = ξ/L1 − φ y/L3,      g_y = η/L2 + φ x/L3,

which is ``w/L`` when L1 = L2 = L3 = L. Marching from the leading edge
(p = 0) towards the trailing edge the elastic predictor over a step from
``x_p`` to ``x_c < x_p`` is (exact for the linear ``g``; the spin term is
evaluated at the step mid-point)

    p_H = p(x_p) − (x_p − x_c) g((x_p + x_c)/2).

If ``|p_H|`` exceeds the traction bound ``g = μ p_z(x_c)`` the element slips.
The slip of the element follows from the same discrete equation with the
traction defect, ``s = D (p − p_H)`` with ``D = diag(L1, L2)/(x_p − x_c)``
(u = (L1 p_x, L2 p_y); the spin's flexibility L3 only enters the rigid slip
through ``g``), and Coulomb's law requires ``|p| = g`` and ``p`` opposite to
``s``. With ``p = −g s/|s|`` this is the small per-element problem

    p_i = L_i p_H,i / (L_i + λ),   Σ_i p_i² = g²,   λ ≥ 0,

(``λ = |s|(x_p − x_c)/g``), solved by Newton's method on the convex,
decreasing function ``|p(λ)| − g`` from the left (monotone convergence), see
:func:`saturate`. With one flexibility (L1 = L2, Kalker's FASTSIM) the
solution is the predictor scaled onto the bound; with three flexibilities it
is not, and scaling the predictor would let the traction follow (ξ/L1, η/L2)
instead of opposing the slip: at ξ = η the force of a sliding patch would
point along (C11, C22) instead of at 45° (Vollebregt & Voltr 2023 make the
same point for FASTSIM with three flexibilities).

With ``first_order=True`` the kernels use instead the backward-Euler march of
CONTACT's FASTSIM for steady rolling (Vollebregt, CONTACT user guide, example
``fastsim.inp``; the steady-state discretisation of Kalker 1990 with
δq = δx): ``u_i = u_{i−1} − δx w(x_i)``, i.e. a full step ``δx`` into every
element including the first one (``u = 0`` ahead of it) and the rigid slip at
the element centre,

    p_H = p(x_{i−1}) − δx g(x_i).

This shifts the adhesion traction by half an element downstream and is first
order accurate in δx (kept to reproduce published CONTACT/FASTSIM numbers). Forces follow from the mid-point rule over the
elements; ``Mz = Σ (x p_y − y p_x) dA`` about the coordinate origin.

Sign convention: ``p`` is the traction on the wheel (Kalker's convention,
:mod:`wheelrail.conventions`), so a positive creepage gives negative traction.

References
----------
.. [1] J.J. Kalker, A fast algorithm for the simplified theory of rolling
   contact, Vehicle System Dynamics 11 (1982) 1–13.
.. [2] J. Piotrowski, H. Chollet, Wheel–rail contact models for vehicle system
   dynamics including multi-point contact, VSD 43 (2005), §3.1 eq. (11),
   §3.3 eqs. (24)–(26).
.. [3] E.A.H. Vollebregt, P. Voltr, FASTSIM with three flexibilities (2023):
   the traction in the slip area must oppose the local slip.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = ["saturate", "newton_steps", "march_strip", "fastsim_strips_kernel", "fastsim_hertz_batch"]


@njit(cache=True, fastmath=False, inline="always")
def _newton_step(lam, cx, cy, g2, L1, L2):
    """One Newton step on ψ(λ) = Σ (c_i/(L_i + λ))² − g², kept ≥ 0 (two divisions)."""
    ex = L1 + lam
    ey = L2 + lam
    r = 1.0 / (ex * ey)
    rx = ey * r
    ry = ex * r
    qx = cx * rx
    qy = cy * ry
    d = -2.0 * (qx * qx * rx + qy * qy * ry)
    if d == 0.0:
        return lam
    return max(lam - (qx * qx + qy * qy - g2) / d, 0.0)


@njit(cache=True, fastmath=False)
def newton_steps(L1, L2):
    """Newton steps of the slip rule for the flexibility ratio (see :func:`saturate`)."""
    ratio = L1 / L2 if L1 > L2 else L2 / L1
    if ratio == 1.0:
        return 0
    return 1 if ratio <= 1.2 else (2 if ratio <= 1.5 else (3 if ratio <= 2.0 else 6))


@njit(cache=True, fastmath=False)
def saturate(pxh, pyh, g, L1, L2, steps):
    """Traction of a slipping element: opposite to its slip, on the bound (pure kernel).

    Solves ``p_i = L_i p_H,i/(L_i + λ)``, ``|p| = g``, ``λ ≥ 0`` (module
    docstring) for ``|p_H| > g > 0`` by Newton's method on
    ``ψ(λ) = Σ p_i(λ)² − g²`` (convex and decreasing on λ ≥ 0; iterates are
    kept ≥ 0), starting from the exact solution for one flexibility
    ``L_e = (L1 p_H,x² + L2 p_H,y²)/|p_H|²``, ``λ0 = L_e(|p_H|/g − 1)``
    (exact when L1 = L2; the start error is second order in L1 − L2). The
    number of steps follows the ratio L1/L2 (:func:`newton_steps`: 1 up to
    1.2, 2 up to 1.5, 3 up to 2, else 6; measured direction errors below
    2e-7, 1e-8 and 1e-11 rad; Kalker's flexibilities have L1/L2 in
    0.73–1.11 for a/b = 0.1–10). The result is finally scaled onto
    ``|p| = g`` exactly. The batch kernel inlines the same operations.

    Parameters
    ----------
    pxh, pyh : float
        Elastic predictor [Pa].
    g : float
        Traction bound μ p_z [Pa], > 0.
    L1, L2 : float
        Flexibilities along x and y [m/Pa] (> 0).
    steps : int
        Newton steps (:func:`newton_steps`).

    Returns
    -------
    px, py : float
        Traction [Pa].
    """
    if g <= 0.0:
        return 0.0, 0.0
    # the solution depends on L1 : L2 only (λ scales with them): work with max(L) = 1, so that
    # no flexibility underflows when squared (e.g. E = 1e155 Pa gives L ~ 1e-158 m/Pa)
    lm = max(L1, L2)
    L1 = L1 / lm
    L2 = L2 / lm
    # scaled by the larger predictor component (no overflow for huge creepages)
    m = max(abs(pxh), abs(pyh))
    if m == np.inf:
        ux = np.copysign(1.0, pxh) if abs(pxh) == np.inf else 0.0
        uy = np.copysign(1.0, pyh) if abs(pyh) == np.inf else 0.0
        gm = 0.0
    else:
        ux = pxh / m
        uy = pyh / m
        gm = g / m
    if gm <= 1e-100:       # |p_H| ≫ g: the limit λ → ∞, p ∥ (L1 p_H,x, L2 p_H,y)
        qx = L1 * ux
        qy = L2 * uy
        sc = g / np.sqrt(qx * qx + qy * qy)
        return qx * sc, qy * sc
    u2 = ux * ux + uy * uy
    lam = (L1 * ux * ux + L2 * uy * uy) / u2 * (np.sqrt(u2) / gm - 1.0)
    cx = L1 * ux
    cy = L2 * uy
    for _ in range(steps):
        lam = _newton_step(lam, cx, cy, gm * gm, L1, L2)
    qx = cx / (L1 + lam)
    qy = cy / (L2 + lam)
    sc = g / np.sqrt(qx * qx + qy * qy)
    return qx * sc, qy * sc


@njit(cache=True, fastmath=False)
def march_strip(y, dy, x_lead, x_trail, bound, L1, L2, L3, xi, eta, phi, nx,
                store, out_px, out_py, out_sx, out_sy, out_slip, first_order=False):
    """March along one strip; return its force contributions (Fx, Fy, Mz).

    Parameters
    ----------
    y, dy : float
        Strip position and width [m].
    x_lead, x_trail : float
        Leading and trailing edge [m]; a strip with ``x_lead <= x_trail`` is empty.
    bound : ndarray, shape (nx,)
        Traction bound μ p_z at the element centres [Pa].
    L1, L2, L3 : float
        Flexibilities for ξ, η and φ [m/Pa].
    xi, eta, phi : float
        Creepages [-], [-], [1/m].
    nx : int
        Number of elements.
    store : bool
        Write the fields into ``out_*`` (shape (nx,)); otherwise they are untouched.
    first_order : bool
        Use the first-order backward-Euler march (see the module docstring)
        instead of the element-centred exact predictor.

    Returns
    -------
    fx, fy, mz : float
        Force [N] and moment about the origin [N m] carried by the strip.
    """
    length = x_lead - x_trail
    if length <= 0.0 or dy <= 0.0:
        return 0.0, 0.0, 0.0
    dx = length / nx
    gx = xi / L1 - phi * y / L3
    gy0 = eta / L2
    gs = phi / L3
    steps = newton_steps(L1, L2)
    px = 0.0
    py = 0.0
    sum_px = 0.0
    sum_py = 0.0
    sum_xpy = 0.0
    xp = x_lead
    h = dx if first_order else 0.5 * dx
    for i in range(nx):
        xc = x_lead - (i + 0.5) * dx
        xm = xc if first_order else 0.5 * (xp + xc)
        pxh = px - h * gx
        pyh = py - h * (gy0 + gs * xm)
        g = bound[i]
        t2 = pxh * pxh + pyh * pyh
        if t2 > g * g:
            px, py = saturate(pxh, pyh, g, L1, L2, steps)
            if store:
                out_slip[i] = True
                out_sx[i] = L1 * (px - pxh) / h
                out_sy[i] = L2 * (py - pyh) / h
        else:
            px = pxh
            py = pyh
            if store:
                out_slip[i] = False
                out_sx[i] = 0.0
                out_sy[i] = 0.0
        if store:
            out_px[i] = px
            out_py[i] = py
        sum_px += px
        sum_py += py
        sum_xpy += xc * py
        xp = xc
        h = dx
    area = dx * dy
    return sum_px * area, sum_py * area, (sum_xpy - y * sum_px) * area


@njit(cache=True)
def fastsim_strips_kernel(y, dy, x_lead, x_trail, bound, L1, L2, L3, xi, eta, phi,
                          px, py, sx, sy, slip, first_order=False):
    """FASTSIM on a patch given by strips (one case), storing the fields.

    Parameters
    ----------
    y, dy, x_lead, x_trail : ndarray, shape (ny,)
        Strip positions, widths, leading and trailing edges [m].
    bound : ndarray, shape (ny, nx)
        Traction bound μ p_z at the element centres [Pa].
    L1, L2, L3 : ndarray, shape (ny,)
        Per-strip flexibilities [m/Pa].
    xi, eta, phi : float
        Creepages.
    px, py, sx, sy : ndarray, shape (ny, nx)
        Output tractions [Pa] and slip [-] (written).
    slip : ndarray of bool, shape (ny, nx)
        Output slip flags (written).
    first_order : bool
        First-order backward-Euler march (see the module docstring).

    Returns
    -------
    Fx, Fy, Mz : float
    """
    ny, nx = bound.shape
    Fx = 0.0
    Fy = 0.0
    Mz = 0.0
    for j in range(ny):
        fx, fy, mz = march_strip(y[j], dy[j], x_lead[j], x_trail[j], bound[j], L1[j], L2[j],
                                 L3[j], xi, eta, phi, nx, True,
                                 px[j], py[j], sx[j], sy[j], slip[j], first_order)
        Fx += fx
        Fy += fy
        Mz += mz
    return Fx, Fy, Mz


@njit(cache=True)
def fastsim_hertz_batch(a, b, peak, mu, L1, L2, L3, xi, eta, phi, t, half, strip_peak, shape,
                        first_order=False):
    """Forces-only FASTSIM for a batch of elliptic (Hertzian) patches.

    Strips are uniform in y: ``y_j = b t_j`` with ``t`` the normalised strip
    centres; strip ``j`` spans ``|x| < a half_j``; the traction bound at element
    ``i`` of strip ``j`` is ``μ peak strip_peak_j shape_i``.

    Same discrete equations as :func:`march_strip`, but all strips of a case
    are marched together (loop over elements outside, strips inside, without
    branches) so that the compiler vectorises across the independent strips.

    Parameters
    ----------
    a, b, peak, mu, L1, L2, L3, xi, eta, phi : ndarray, shape (n,)
        Semi-axes [m], peak pressure of the bound distribution [Pa], friction
        coefficient, flexibilities [m/Pa] and creepages, per case.
    t, half, strip_peak : ndarray, shape (ny,)
        Normalised strip centres y/b, half-lengths √(1 − t²) and peak factors.
    shape : ndarray, shape (nx,)
        Pressure profile along a strip at the normalised element centres
        ``1 − (i + ½) 2/nx``.
    first_order : bool
        First-order backward-Euler march (see the module docstring).

    Returns
    -------
    Fx, Fy, Mz : ndarray, shape (n,)
    adhesion : ndarray, shape (n,)
        Area of the sticking elements / area of all elements [-].
    """
    n = a.shape[0]
    ny = t.shape[0]
    nx = shape.shape[0]
    Fx = np.empty(n)
    Fy = np.empty(n)
    Mz = np.empty(n)
    Adh = np.empty(n)
    stick = np.empty(ny)
    xl = np.empty(ny)
    dx = np.empty(ny)
    gx = np.empty(ny)
    bq = np.empty(ny)
    px = np.empty(ny)
    py = np.empty(ny)
    spx = np.empty(ny)
    spy = np.empty(ny)
    sxp = np.empty(ny)
    hx = np.empty(ny)
    hy = np.empty(ny)
    sl = np.zeros(ny, dtype=np.bool_)
    for k in range(n):
        g1 = xi[k] / L1[k]
        gy0 = eta[k] / L2[k]
        gs = phi[k] / L3[k]
        pk = mu[k] * peak[k]
        l1 = L1[k]
        l2 = L2[k]
        equal_flex = l1 == l2
        steps = newton_steps(l1, l2)
        for j in range(ny):
            xl[j] = a[k] * half[j]
            dx[j] = 2.0 * xl[j] / nx
            gx[j] = g1 - gs * b[k] * t[j]
            bq[j] = pk * strip_peak[j]
            px[j] = 0.0
            py[j] = 0.0
            spx[j] = 0.0
            spy[j] = 0.0
            sxp[j] = 0.0
            stick[j] = 0.0
        for i in range(nx):
            # step from the previous centre (leading edge for i = 0) to centre i
            fc = 1.0 - (2.0 * i + 1.0) / nx                          # element centre / xl
            if first_order:  # backward Euler: full step, rigid slip at the centre
                hf = 1.0
                fm = fc
            else:
                hf = 0.5 if i == 0 else 1.0
                fm = 1.0 - 0.5 / nx if i == 0 else 1.0 - 2.0 * i / nx   # step mid-point / xl
            sh = shape[i]
            # pass 1 (vectorises across the strips): predictor and the scaled traction
            for j in range(ny):
                h = hf * dx[j]
                pxh = px[j] - h * gx[j]
                pyh = py[j] - h * (gy0 + gs * xl[j] * fm)
                g = bq[j] * sh
                t2 = pxh * pxh + pyh * pyh
                g2 = g * g
                slide = t2 > g2
                sc = np.sqrt(g2 / t2) if slide else 1.0
                stick[j] += 0.0 if slide else 1.0
                hx[j] = pxh
                hy[j] = pyh
                px[j] = pxh * sc
                py[j] = pyh * sc
                sl[j] = slide
            # pass 2, three flexibilities only: sliding elements oppose their slip
            # (saturate(), the same operations as the strip path)
            if not equal_flex:
                for j in range(ny):
                    if sl[j]:
                        px[j], py[j] = saturate(hx[j], hy[j], bq[j] * sh, l1, l2, steps)
            for j in range(ny):
                spx[j] += px[j]
                spy[j] += py[j]
                sxp[j] += xl[j] * fc * py[j]
        dyk = 2.0 * b[k] / ny
        fx = 0.0
        fy = 0.0
        mz = 0.0
        adh = 0.0
        tot = 0.0
        for j in range(ny):
            area = dx[j] * dyk
            adh += stick[j] * area
            tot += nx * area
            fx += spx[j] * area
            fy += spy[j] * area
            mz += (sxp[j] - b[k] * t[j] * spx[j]) * area
        Fx[k] = fx
        Fy[k] = fy
        Mz[k] = mz
        Adh[k] = adh / tot if tot > 0.0 else 0.0
    return Fx, Fy, Mz, Adh


@njit(cache=True)
def strip_patch_forces(y, dy, x_lead, x_trail, sp, i0, i1, w, parabolic, mu, L1, L2, L3,
                       xi, eta, phi, cap, first_order, store, p_out, px, py, sx, sy, slip):
    """FASTSIM on a strip patch, resampling and centre of pressure fused (fields optional).

    The same discrete equations as ``Fastsim.solve_patch`` on a non-elliptic
    :class:`~wheelrail.patch.ContactPatch` followed by
    :func:`fastsim_strips_kernel` (without fields), in one call: the patch's
    ``m`` cells per strip are resampled to ``nx`` by linear interpolation
    (indices ``i0``, ``i1``, weights ``w``) keeping each strip's force,
    optionally made parabolic along the strip (same force), multiplied by μ
    to give the traction bound, and marched.

    Parameters
    ----------
    y, dy, x_lead, x_trail : ndarray, shape (ny,)
        Strips of the patch [m].
    sp : ndarray, shape (ny, m)
        Pressure of the patch's cells [Pa].
    i0, i1 : ndarray of int, shape (nx,); w : ndarray, shape (nx,)
        Linear resampling from m to nx cell centres.
    parabolic : bool
        Parabolic pressure along every strip (Linder's traction bound).
    mu : float
        Friction coefficient [-].
    L1, L2, L3 : ndarray, shape (ny,)
        Flexibilities [m/Pa].
    xi, eta, phi : float
        Creepages [-], [-], [1/m].
    cap : float
        Largest rigid-slip traction rate [Pa/m] handled here; beyond it (or for
        a non-finite rate) ``ok`` is False and nothing else is meaningful (the
        caller then takes the general path, which scales the creepages).
    first_order : bool
        First-order backward-Euler march (see the module docstring).
    store : bool
        Write the fields: ``p_out`` the resampled pressure, ``px``, ``py``,
        ``sx``, ``sy``, ``slip`` as in :func:`fastsim_strips_kernel` (all
        shape (ny, nx), zero-initialised by the caller); otherwise they are not
        touched (any float / bool arrays).

    Returns
    -------
    ok : bool
    Fx, Fy, Mz : float
        Forces [N] and moment about the coordinate origin [N m].
    Fn : float
        Σ p_z dA of the resampled pressure [N].
    xc, yc : float
        Centre of pressure of the patch's own cells [m].
    """
    ny, m = sp.shape
    nx = i0.shape[0]
    # rigid-slip rate bound (as _tame): the general path handles huge creepages
    reach = 0.0
    my = 0.0
    mdy = 0.0
    L1m = L1[0]
    L2m = L2[0]
    L3m = L3[0]
    for j in range(ny):
        my = max(my, abs(y[j]))
        mdy = max(mdy, dy[j])
        reach = max(reach, abs(x_lead[j]), abs(x_trail[j]))
        L1m = min(L1m, L1[j])
        L2m = min(L2m, L2[j])
        L3m = min(L3m, L3[j])
    reach = max(reach, my + mdy)
    rate = max(abs(xi) / L1m, abs(eta) / L2m, abs(phi) * reach / L3m)
    if not rate <= cap:
        return False, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    par = np.empty(nx)
    parsum = 0.0
    for i in range(nx):
        s = 1.0 - ((i + 0.5) / nx) * 2.0
        par[i] = max(1.0 - s * s, 0.0)
        parsum += par[i]
    p = np.empty(nx)
    bound = np.empty(nx)
    dummy = np.empty(0)
    dummy_b = np.empty(0, dtype=np.bool_)
    Fx = 0.0
    Fy = 0.0
    Mz = 0.0
    Fn = 0.0
    W = 0.0
    WX = 0.0
    WY = 0.0
    for j in range(ny):
        lj = x_lead[j] - x_trail[j]
        wj = dy[j] * lj / m
        ssum = 0.0
        for k in range(m):
            v = sp[j, k]
            ssum += v
            c = v * wj
            W += c
            WX += c * (x_lead[j] - ((k + 0.5) / m) * lj)
            WY += c * y[j]
        got = 0.0
        for i in range(nx):
            p[i] = sp[j, i0[i]] * (1.0 - w[i]) + sp[j, i1[i]] * w[i]
            got += p[i]
        scale = ssum / m
        got = got / nx
        f = scale / got if got > 0 else 0.0
        tot = 0.0
        for i in range(nx):
            p[i] *= f
            tot += p[i]
        if parabolic:
            for i in range(nx):
                p[i] = (tot / parsum) * par[i]
        dxj = max(lj, 0.0) / nx
        dA = dxj * dy[j]
        for i in range(nx):
            bound[i] = p[i] * mu
            Fn += p[i] * dA
        if store:
            for i in range(nx):
                p_out[j, i] = p[i]
            fx, fy, mz = march_strip(y[j], dy[j], x_lead[j], x_trail[j], bound, L1[j], L2[j],
                                     L3[j], xi, eta, phi, nx, True, px[j], py[j], sx[j], sy[j],
                                     slip[j], first_order)
        else:
            fx, fy, mz = march_strip(y[j], dy[j], x_lead[j], x_trail[j], bound, L1[j], L2[j],
                                     L3[j], xi, eta, phi, nx, False, dummy, dummy, dummy, dummy,
                                     dummy_b, first_order)
        Fx += fx
        Fy += fy
        Mz += mz
    return True, Fx, Fy, Mz, Fn, WX / W, WY / W


@njit(cache=True)
def strip_flexibilities(sa, sb, G, x, c11, c22, c23):
    """Kalker's three flexibilities of every strip's virtual ellipse (pure kernel).

    ``Fastsim.solve_patch`` for a patch with per-strip semi-axes ``sa``, ``sb`` [m]:
    C11, C22, C23 interpolated linearly in ln(a/b) in the table ``x``, ``c11``,
    ``c22``, ``c23`` (:func:`wheelrail.tangential.fastsim._kalker_table`), then
    L1 = 8a/(3 G C11), L2 = 8a/(3 G C22), L3 = π a √(a/b)/(4 G C23) [m/Pa]
    (:func:`wheelrail.tangential.fastsim.flexibilities`).

    Returns
    -------
    ok : bool
        False when an a/b lies outside the table's range [0.01, 100] (the caller
        then evaluates Kalker's coefficients directly).
    L1, L2, L3 : ndarray, shape (ny,)
    m1, m2, m3 : float
        Their medians.
    """
    n = sa.shape[0]
    L1 = np.empty(n)
    L2 = np.empty(n)
    L3 = np.empty(n)
    for j in range(n):
        r = sa[j] / sb[j]
        if not (r >= 0.01 and r <= 100.0):
            return False, L1, L2, L3, 0.0, 0.0, 0.0
        v = math.log(r)
        C11 = np.interp(v, x, c11)
        C22 = np.interp(v, x, c22)
        C23 = np.interp(v, x, c23)
        a = sa[j]
        L1[j] = 8.0 * a / (3.0 * G * C11)
        L2[j] = 8.0 * a / (3.0 * G * C22)
        L3[j] = np.pi * a * np.sqrt(a / sb[j]) / (4.0 * G * C23)
    return True, L1, L2, L3, np.median(L1), np.median(L2), np.median(L3)
