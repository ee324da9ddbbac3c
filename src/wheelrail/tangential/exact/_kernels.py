"""Numba kernels of the exact tangential solver (pure array functions).

Local problems of Kalker's block Gauss–Seidel, the active set, the Newton
system and update in the variables of Zhao, Vollebregt & Oosterlee (2015),
the line preconditioner along the rolling direction, and the scatter/gather
of the Newton unknowns. See :mod:`wheelrail.tangential.exact` for the
equations and conventions.
"""

from __future__ import annotations

import math

from numba import njit

#: Where the spin's rigid slip φ·x is evaluated inside an element, in element
#: lengths upstream of its centre (Vollebregt's CONTACT, FACPHI = 1/6).
_SPIN_SHIFT = 1.0 / 6.0


# --------------------------------------------------------------------------
# numba kernels
# --------------------------------------------------------------------------
#: numba fast-math flags of the Krylov reductions: reassociation lets the dot
#: products use SIMD (about 2.5 times faster Gram–Schmidt; the sums change at
#: round-off level only); no assumptions about NaN or infinities.
_REASSOC = {"reassoc", "contract"}


@njit(cache=True)
def _local_problem(bx, by, dxx, dxy, dyx, dyy, g):
    """Exact solution of one element's problem ``s = b + D p`` under ``|p| ≤ g``.

    Returns ``(px, py, sx, sy)``; ``s = (0, 0)`` in adhesion.
    """
    det = dxx * dyy - dxy * dyx
    px = -(dyy * bx - dxy * by) / det
    py = -(-dyx * bx + dxx * by) / det
    if px * px + py * py <= g * g:
        return px, py, 0.0, 0.0
    if g <= 0.0:
        return 0.0, 0.0, bx, by
    # slip: p = -(D + lam I)^-1 b with |p| = g, lam >= 0; Newton on 1/|p| - 1/g
    lam = 0.0
    for _ in range(60):
        axx = dxx + lam
        ayy = dyy + lam
        det = axx * ayy - dxy * dyx
        px = -(ayy * bx - dxy * by) / det
        py = -(-dyx * bx + axx * by) / det
        qx = -(ayy * px - dxy * py) / det   # dp/dlam
        qy = -(-dyx * px + axx * py) / det
        n = math.sqrt(px * px + py * py)
        phi = 1.0 / n - 1.0 / g
        dphi = -(px * qx + py * qy) / (n * n * n)
        if dphi <= 0.0:
            break
        new = lam - phi / dphi
        if new < 0.0:
            new = 0.5 * lam
        if abs(new - lam) <= 1e-14 * (new + abs(dxx) + abs(dyy)):
            lam = new
            break
        lam = new
    axx = dxx + lam
    ayy = dyy + lam
    det = axx * ayy - dxy * dyx
    px = -(ayy * bx - dxy * by) / det
    py = -(-dyx * bx + axx * by) / det
    n = math.sqrt(px * px + py * py)
    px *= g / n
    py *= g / n
    sx = bx + dxx * px + dxy * py
    sy = by + dyx * px + dyy * py
    return px, py, sx, sy


@njit(cache=True)
def _gs_sweep(mxx, mxy, myx, myy, order_i, order_j, g, px, py, sx, sy,
              i0, i1, j0, j1, skip):
    """One block Gauss–Seidel sweep (in place); returns the largest traction change.

    ``m..`` are the 2-D kernel blocks (2nx−1, 2ny−1); ``sx, sy`` hold the
    current slip ``b + M p`` on the grid and are kept consistent inside the
    box ``[i0, i1) × [j0, j1)`` (changes smaller than ``skip`` are not
    propagated; the caller resynchronises after the sweep).
    """
    nx, ny = px.shape
    cx = nx - 1
    cy = ny - 1
    dxx = mxx[cx, cy]
    dxy = mxy[cx, cy]
    dyx = myx[cx, cy]
    dyy = myy[cx, cy]
    maxdp = 0.0
    for k in range(order_i.shape[0]):
        i = order_i[k]
        j = order_j[k]
        pxo = px[i, j]
        pyo = py[i, j]
        bx = sx[i, j] - dxx * pxo - dxy * pyo
        by = sy[i, j] - dyx * pxo - dyy * pyo
        pxn, pyn, sxn, syn = _local_problem(bx, by, dxx, dxy, dyx, dyy, g[i, j])
        dpx = pxn - pxo
        dpy = pyn - pyo
        px[i, j] = pxn
        py[i, j] = pyn
        d = max(abs(dpx), abs(dpy))
        if d > maxdp:
            maxdp = d
        if d > skip:
            for a in range(i0, i1):
                ka = a - i + cx
                for c in range(j0, j1):
                    kc = c - j + cy
                    sx[a, c] += mxx[ka, kc] * dpx + mxy[ka, kc] * dpy
                    sy[a, c] += myx[ka, kc] * dpx + myy[ka, kc] * dpy
        else:
            sx[i, j] += dxx * dpx + dxy * dpy
            sy[i, j] += dyx * dpx + dyy * dpy
    return maxdp


@njit(cache=True)
def _precondition(up_e, kind_e, pos_e, tx_e, ty_e, g_e, diag_e, d0, dup, r, z, vx, vy):
    """Apply the line preconditioner (in place into ``z``).

    Solves, in upwind order, the part of the Newton system that couples each
    element to itself (``d0 = M(0)``) and to its upstream neighbour
    (``dup = M(−e_x)``): for rolling this is the backward difference along x,
    whose exact inverse is a running sum from the leading edge. The contact
    elements are listed in upwind order: ``up_e`` is the list index of the
    upstream neighbour (−1 if it is out of contact or off the grid),
    ``kind_e`` 1 (adhesion, unknowns δp) or 2 (slip, unknown δθ), ``pos_e``
    the position of the unknowns; ``vx, vy`` (per element) receive the
    traction perturbation of each element.
    """
    det = d0[0, 0] * d0[1, 1] - d0[0, 1] * d0[1, 0]
    for k in range(kind_e.shape[0]):
        ux = 0.0
        uy = 0.0
        u = up_e[k]
        if u >= 0:
            ux = dup[0, 0] * vx[u] + dup[0, 1] * vy[u]
            uy = dup[1, 0] * vx[u] + dup[1, 1] * vy[u]
        q = pos_e[k]
        if kind_e[k] == 1:
            rx = r[q] - ux
            ry = r[q + 1] - uy
            ax = (d0[1, 1] * rx - d0[0, 1] * ry) / det
            ay = (-d0[1, 0] * rx + d0[0, 0] * ry) / det
            z[q] = ax
            z[q + 1] = ay
            vx[k] = ax
            vy[k] = ay
        else:
            t0 = tx_e[k]
            t1 = ty_e[k]
            tdt = (t0 * (d0[0, 0] * t0 + d0[0, 1] * t1) + t1 * (d0[1, 0] * t0 + d0[1, 1] * t1))
            den = tdt * g_e[k] + diag_e[k]
            dth = (r[q] - (t0 * ux + t1 * uy)) / den
            z[q] = dth
            vx[k] = g_e[k] * t0 * dth
            vy[k] = g_e[k] * t1 * dth


@njit(cache=True)
def _active_set(p, s, g_e, ei, ej, slip_e):
    """Active-set update of the Newton iteration on the element list (in place).

    Adhesion elements whose traction exceeds the bound (by more than 1e-10)
    move to slip and are projected onto it; slip elements whose slip points
    along their traction move to adhesion. Returns whether any element changed.
    """
    changed = False
    for k in range(ei.shape[0]):
        i = ei[k]
        j = ej[k]
        px = p[0, i, j]
        py = p[1, i, j]
        norm = math.hypot(px, py)
        if slip_e[k]:
            safe = norm if norm > 0.0 else 1.0
            if (px / safe) * s[0, i, j] + (py / safe) * s[1, i, j] > 0.0:
                slip_e[k] = False
                changed = True
        elif norm > g_e[k] * (1 + 1e-10):
            slip_e[k] = True
            changed = True
            f = g_e[k] / norm
            p[0, i, j] = px * f
            p[1, i, j] = py * f
    return changed


@njit(cache=True)
def _newton_system(p, s, g_e, ei, ej, slip_e, kind_e, pos_e, ex_e, ey_e, tx_e, ty_e,
                   gtx_e, gty_e, diag_e, F):
    """Unknown layout, residual ``F`` and per-element data of one Newton step (in place).

    Adhesion elements (kind 1) have two unknowns (δp), slip elements (kind 2)
    one (δθ), in upwind order; ``t = (−e_y, e_x)`` is the unit vector normal to
    the traction direction ``e``, ``diag`` the slip elements' ``max(−e·s, 0)``.
    Returns ``(number of unknowns, max |F|)``.
    """
    q = 0
    big = 0.0
    for k in range(ei.shape[0]):
        i = ei[k]
        j = ej[k]
        px = p[0, i, j]
        py = p[1, i, j]
        norm = math.hypot(px, py)
        safe = norm if norm > 0.0 else 1.0
        ex = px / safe
        ey = py / safe
        ex_e[k] = ex
        ey_e[k] = ey
        tx_e[k] = -ey
        ty_e[k] = ex
        gtx_e[k] = g_e[k] * -ey
        gty_e[k] = g_e[k] * ex
        pos_e[k] = q
        sx = s[0, i, j]
        sy = s[1, i, j]
        if slip_e[k]:
            kind_e[k] = 2
            sigma = ex * sx + ey * sy
            diag_e[k] = -sigma if sigma < 0.0 else 0.0
            f = -ey * sx + ex * sy
            F[q] = f
            q += 1
            if abs(f) > big:
                big = abs(f)
        else:
            kind_e[k] = 1
            diag_e[k] = 0.0
            F[q] = sx
            F[q + 1] = sy
            q += 2
            if abs(sx) > big:
                big = abs(sx)
            if abs(sy) > big:
                big = abs(sy)
    return q, big


@njit(cache=True)
def _newton_update(p, dz, g_e, ei, ej, kind_e, pos_e, ex_e, ey_e):
    """Apply the Newton correction ``dz`` to the tractions (in place).

    Adhesion: ``p += δp``; slip: the traction angle turns by δθ (clipped to
    ±π/2) on the bound, ``p = g (e cos δθ + t sin δθ)``.
    """
    half_pi = 0.5 * math.pi
    for k in range(ei.shape[0]):
        i = ei[k]
        j = ej[k]
        q = pos_e[k]
        if kind_e[k] == 1:
            p[0, i, j] += dz[q]
            p[1, i, j] += dz[q + 1]
        else:
            dth = min(max(dz[q], -half_pi), half_pi)
            c = math.cos(dth)
            sn = math.sin(dth)
            ex = ex_e[k]
            ey = ey_e[k]
            p[0, i, j] = g_e[k] * (ex * c - ey * sn)
            p[1, i, j] = g_e[k] * (ey * c + ex * sn)


@njit(cache=True)
def _scatter(z, ei, ej, kind_e, pos_e, gtx_e, gty_e, v):
    """Traction perturbation field ``v`` (2, nx, ny) of the Newton unknowns ``z`` (in place).

    Adhesion elements (kind 1) carry δp, slip elements (kind 2) ``g t δθ``;
    elements out of contact are never written (stay zero).
    """
    for k in range(ei.shape[0]):
        i = ei[k]
        j = ej[k]
        q = pos_e[k]
        if kind_e[k] == 1:
            v[0, i, j] = z[q]
            v[1, i, j] = z[q + 1]
        else:
            v[0, i, j] = gtx_e[k] * z[q]
            v[1, i, j] = gty_e[k] * z[q]


@njit(cache=True)
def _gather(mv, z, ei, ej, kind_e, pos_e, tx_e, ty_e, diag_e, out):
    """Newton-system product from the slip change ``mv = K v`` (2, nx, ny) (in place)."""
    for k in range(ei.shape[0]):
        i = ei[k]
        j = ej[k]
        q = pos_e[k]
        if kind_e[k] == 1:
            out[q] = mv[0, i, j]
            out[q + 1] = mv[1, i, j]
        else:
            out[q] = tx_e[k] * mv[0, i, j] + ty_e[k] * mv[1, i, j] + diag_e[k] * z[q]




@njit(cache=True)
def _prec_scatter(elem, geo, d0, dup, r, z, vx, vy, v, c, w, schur):
    """Right preconditioner and traction field of one Krylov product (in place).

    ``z = P r`` by :func:`_precondition` (``elem`` rows: i, j, kind, position,
    upstream neighbour; ``geo`` rows: t_x, t_y, g, diag, g t_x, g t_y), then
    ``v`` = the traction field of ``z`` as :func:`_scatter`. With the ξ border
    (``r`` one longer than the Newton unknowns, ``c`` and ``w = P e`` of length
    n): the block elimination ``ζ = (c·P r − r_n) / schur``, ``z = P r − w ζ``,
    ``z_n = ζ`` first.
    """
    _precondition(elem[4], elem[2], elem[3], geo[0], geo[1], geo[2], geo[3], d0, dup, r, z,
                  vx, vy)
    n = c.shape[0]
    if r.shape[0] > n:
        acc = 0.0
        for q in range(n):
            acc += c[q] * z[q]
        zeta = (acc - r[n]) / schur
        for q in range(n):
            z[q] -= w[q] * zeta
        z[n] = zeta
    _scatter(z, elem[0], elem[1], elem[2], elem[3], geo[4], geo[5], v)


@njit(cache=True)
def _gather_bordered(mv, z, elem, geo, out, e, c):
    """Newton-system product from ``mv = K v`` as :func:`_gather` (in place), plus the ξ
    border when ``out`` is one longer than the unknowns: ``out += z_n e``,
    ``out_n = c·z``."""
    _gather(mv, z, elem[0], elem[1], elem[2], elem[3], geo[0], geo[1], geo[3], out)
    n = c.shape[0]
    if out.shape[0] > n:
        zeta = z[n]
        acc = 0.0
        for q in range(n):
            out[q] += zeta * e[q]
            acc += c[q] * z[q]
        out[n] = acc


@njit(cache=True)
def _border(elem, geo, c_e, d0, dup, vx, vy, e, c, w):
    """The ξ border of the Newton system and ``P e`` (in place); returns ``cᵀ P e``.

    ``e = ∂F/∂ξ``: 1 on the x equation of an adhesion element (0 on its y equation),
    ``t_x`` on a slip element's equation; ``c``: the force change per unknown,
    ``c_e`` (element weight) times δp_x on adhesion or times ``g t_x`` δθ on slip;
    ``w = P e`` by :func:`_precondition`.
    """
    kind_e = elem[2]
    pos_e = elem[3]
    for k in range(kind_e.shape[0]):
        q = pos_e[k]
        if kind_e[k] == 1:
            e[q] = 1.0
            e[q + 1] = 0.0
            c[q] = c_e[k]
            c[q + 1] = 0.0
        else:
            e[q] = geo[0, k]
            c[q] = c_e[k] * geo[4, k]
    _precondition(elem[4], kind_e, pos_e, geo[0], geo[1], geo[2], geo[3], d0, dup, e, w,
                  vx, vy)
    acc = 0.0
    for q in range(c.shape[0]):
        acc += c[q] * w[q]
    return acc


@njit(cache=True)
def _weighted_x_sum(p, ei, ej, w_e):
    """``Σ_k w_e[k] p[0, ei[k], ej[k]]`` (the force Fx of the contact elements)."""
    acc = 0.0
    for k in range(ei.shape[0]):
        acc += w_e[k] * p[0, ei[k], ej[k]]
    return acc


@njit(cache=True)
def _project_start(p, g, norm):
    """Starting tractions in place: zero where ``g`` is not positive (out of contact),
    scaled back onto the friction disc ``|p| ≤ g`` where they lie outside; ``norm``
    receives ``|p|`` before the projection."""
    for i in range(g.shape[0]):
        for j in range(g.shape[1]):
            if not g[i, j] > 0.0:
                p[0, i, j] = 0.0
                p[1, i, j] = 0.0
            n = math.hypot(p[0, i, j], p[1, i, j])
            norm[i, j] = n
            if n > g[i, j]:
                f = g[i, j] / n
                p[0, i, j] *= f
                p[1, i, j] *= f
