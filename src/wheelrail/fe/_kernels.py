"""Array-in/array-out numba kernels of the FE engine (private): element geometry, the elastic
stiffness triplets and the node-to-surface contact (the internal forces and the J2 plasticity
are in :mod:`wheelrail.fe._solid`).

Element kernels work on precomputed shape-function gradients (small-strain
kinematics in each body's own frame, so the gradients of the reference
configuration are used throughout); the material enters through the Lamé
constants λ and G (the shear modulus; ``mu`` is reserved for the friction coefficient).
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

# hex8 natural coordinates of the nodes
XI = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
               [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], dtype=float)
# Flanagan-Belytschko hourglass base vectors (4 x 8)
HG = np.array([[1, 1, -1, -1, -1, -1, 1, 1],
               [1, -1, -1, 1, -1, 1, 1, -1],
               [1, -1, 1, -1, 1, -1, 1, -1],
               [-1, 1, -1, 1, 1, -1, 1, -1]], dtype=float)


def shape_gradients(x: np.ndarray, points: np.ndarray, weights: np.ndarray):
    """Gradients dN/dx and weights w·det J at the integration points.

    Parameters
    ----------
    x : ndarray, shape (ne, 8, 3)
        Element node coordinates [m].
    points : ndarray, shape (ng, 3)
        Natural coordinates of the integration points.
    weights : ndarray, shape (ng,)

    Returns
    -------
    dNdx : ndarray, shape (ne, ng, 8, 3) [1/m]
    wdet : ndarray, shape (ne, ng) [m³]
    """
    ne, ng = x.shape[0], points.shape[0]
    dNdx = np.empty((ne, ng, 8, 3))
    wdet = np.empty((ne, ng))
    for g, p in enumerate(points):
        dN = 0.125 * XI * np.stack([(1 + XI[:, 1] * p[1]) * (1 + XI[:, 2] * p[2]),
                                    (1 + XI[:, 0] * p[0]) * (1 + XI[:, 2] * p[2]),
                                    (1 + XI[:, 0] * p[0]) * (1 + XI[:, 1] * p[1])], axis=1)
        J = np.einsum("ai,eaj->eij", dN, x)
        det = np.linalg.det(J)
        Jinv = np.linalg.inv(J)
        dNdx[:, g] = np.einsum("ai,eji->eaj", dN, Jinv)
        wdet[:, g] = weights[g] * det
    return dNdx, wdet


def hourglass_vectors(x: np.ndarray, dNdx0: np.ndarray) -> np.ndarray:
    """Flanagan-Belytschko hourglass shape vectors γ, shape (ne, 4, 8).

    γ_α = ½·(h_α − (h_α · x_j) b_j) orthogonal to the linear fields.
    """
    hx = np.einsum("ka,eaj->ekj", HG, x)                 # (ne, 4, 3)
    return 0.125 * (HG[None] - np.einsum("ekj,eaj->eka", hx, dNdx0))


@njit(cache=True)
def stiffness_triplets(conn, dNdx, wdet, lam, G, gamma, khg, rows, cols, vals):
    """Element stiffness matrices as COO triplets (576 per element), dof = 3·node + i."""
    ne = conn.shape[0]
    ng = dNdx.shape[1]
    has_hg = gamma.shape[0] == ne
    ke = np.empty((24, 24))
    for e in range(ne):
        ke[:, :] = 0.0
        for g in range(ng):
            w = wdet[e, g]
            for a in range(8):
                ax = dNdx[e, g, a, 0]
                ay = dNdx[e, g, a, 1]
                az = dNdx[e, g, a, 2]
                for b in range(8):
                    bx = dNdx[e, g, b, 0]
                    by = dNdx[e, g, b, 1]
                    bz = dNdx[e, g, b, 2]
                    dot = ax * bx + ay * by + az * bz
                    # K_ab,ij = λ a_i b_j + G a_j b_i + G δ_ij (a·b)
                    ka = (ax, ay, az)
                    kb = (bx, by, bz)
                    for i in range(3):
                        for j in range(3):
                            v = lam * ka[i] * kb[j] + G * ka[j] * kb[i]
                            if i == j:
                                v += G * dot
                            ke[3 * a + i, 3 * b + j] += w * v
        if has_hg:
            k = khg[e]
            for m in range(4):
                for a in range(8):
                    for b in range(8):
                        v = k * gamma[e, m, a] * gamma[e, m, b]
                        for i in range(3):
                            ke[3 * a + i, 3 * b + i] += v
        base = e * 576
        c = 0
        for a in range(8):
            for i in range(3):
                for b in range(8):
                    for j in range(3):
                        rows[base + c] = 3 * conn[e, a] + i
                        cols[base + c] = 3 * conn[e, b] + j
                        vals[base + c] = ke[3 * a + i, 3 * b + j]
                        c += 1


@njit(cache=True)
def _bilinear(c, r, t, out):
    for d in range(3):
        out[d] = ((1 - r) * (1 - t) * c[0, d] + r * (1 - t) * c[1, d] + r * t * c[2, d]
                  + (1 - r) * t * c[3, d])


@njit(cache=True, inline="always")
def _bilinear_tangents(c, r, t):
    """Tangents d/dr and d/dt of the bilinear quad ``c`` (4, 3) at (r, t)."""
    tr0 = (1 - t) * (c[1, 0] - c[0, 0]) + t * (c[2, 0] - c[3, 0])
    tr1 = (1 - t) * (c[1, 1] - c[0, 1]) + t * (c[2, 1] - c[3, 1])
    tr2 = (1 - t) * (c[1, 2] - c[0, 2]) + t * (c[2, 2] - c[3, 2])
    tt0 = (1 - r) * (c[3, 0] - c[0, 0]) + r * (c[2, 0] - c[1, 0])
    tt1 = (1 - r) * (c[3, 1] - c[0, 1]) + r * (c[2, 1] - c[1, 1])
    tt2 = (1 - r) * (c[3, 2] - c[0, 2]) + r * (c[2, 2] - c[1, 2])
    return tr0, tr1, tr2, tt0, tt1, tt2


@njit(cache=True, inline="always")
def closest_point_step(c, r, t, x0, x1, x2):
    """One Newton step of the closest-point projection of (x0, x1, x2) on the bilinear quad
    ``c`` (4, 3) from (r, t): the corrections (dr, dt) and the determinant of the 2×2
    system (the Gram matrix of the tangents); (0, 0, det) when det <= 0 (a degenerate
    quad). Both contact searches use it: the tensor-grid search of :func:`node_to_surface`
    and the bucket search of :func:`wheelrail.fe.transition.contact.node_to_segment`.

    References
    ----------
    .. [1] P. Wriggers, *Computational Contact Mechanics*, 2nd ed., Springer 2006, §4.1
       (closest-point projection onto a surface).
    """
    q0 = ((1 - r) * (1 - t) * c[0, 0] + r * (1 - t) * c[1, 0] + r * t * c[2, 0]
          + (1 - r) * t * c[3, 0])
    q1 = ((1 - r) * (1 - t) * c[0, 1] + r * (1 - t) * c[1, 1] + r * t * c[2, 1]
          + (1 - r) * t * c[3, 1])
    q2 = ((1 - r) * (1 - t) * c[0, 2] + r * (1 - t) * c[1, 2] + r * t * c[2, 2]
          + (1 - r) * t * c[3, 2])
    tr0, tr1, tr2, tt0, tt1, tt2 = _bilinear_tangents(c, r, t)
    d0 = x0 - q0
    d1 = x1 - q1
    d2 = x2 - q2
    a11 = tr0 * tr0 + tr1 * tr1 + tr2 * tr2
    a12 = tr0 * tt0 + tr1 * tt1 + tr2 * tt2
    a22 = tt0 * tt0 + tt1 * tt1 + tt2 * tt2
    b1 = tr0 * d0 + tr1 * d1 + tr2 * d2
    b2 = tt0 * d0 + tt1 * d1 + tt2 * d2
    det = a11 * a22 - a12 * a12
    if det <= 0.0:
        return 0.0, 0.0, det
    return (a22 * b1 - a12 * b2) / det, (a11 * b2 - a12 * b1) / det, det


@njit(cache=True, inline="always")
def scatter_to_grid(status, cell, rt, fs, fm):
    """Subtract the slaves' contact forces ``fs`` (ns, 3) [N] from the master grid's
    nodal forces ``fm`` (nx, ny, 3) with the bilinear weights of each active slave's
    cell ``cell`` (ns, 2) and local coordinates ``rt`` (ns, 2) (action and reaction)."""
    for s in range(fs.shape[0]):
        if status[s] > 0:
            i = cell[s, 0]
            j = cell[s, 1]
            r = rt[s, 0]
            t = rt[s, 1]
            w0 = (1 - r) * (1 - t)
            w1 = r * (1 - t)
            w2 = r * t
            w3 = (1 - r) * t
            for d in range(3):
                fm[i, j, d] -= w0 * fs[s, d]
                fm[i + 1, j, d] -= w1 * fs[s, d]
                fm[i + 1, j + 1, d] -= w2 * fs[s, d]
                fm[i, j + 1, d] -= w3 * fs[s, d]


@njit(cache=True, inline="always")
def coulomb_update(s, fn, s0, s1, s2, n0, n1, n2, A, kt, mu, cdamp, inv_dt, ft_old, pn, ft_new,
                   slip, status, fs):
    """Penalty-Coulomb update of contact node ``s`` (shared by the contact searches).

    ``fn`` [N] is the penalty normal force, ``(s0, s1, s2)`` [m] the relative
    displacement increment of the slave against the master point over the step,
    ``(n0, n1, n2)`` the unit contact normal and ``A`` [m²] the node's area. The
    normal force is damped by ``cdamp[s]`` (kept ≥ 0); the previous tangential
    force ``ft_old[s]`` is rotated into the current tangent plane, increased by
    the stick stiffness ``kt[s]·A`` times the tangential increment and returned
    to the Coulomb cone μ·fn (radial return). Writes ``pn[s]``, ``ft_new[s]``,
    ``slip[s]`` (the slip increment [m]), ``status[s]`` (1 stick, 2 slip) and
    ``fs[s]`` (total contact force on the slave, N).

    References
    ----------
    Wriggers, P. (2006). *Computational Contact Mechanics*, 2nd ed., Springer,
    §5.2 (penalty method, return map of the Coulomb law).
    """
    sn = s0 * n0 + s1 * n1 + s2 * n2
    if cdamp[s] > 0.0:
        fn -= cdamp[s] * sn * inv_dt
        if fn < 0.0:
            fn = 0.0
    pn[s] = fn
    s0 -= sn * n0
    s1 -= sn * n1
    s2 -= sn * n2
    # previous tangential force, rotated into the current tangent plane
    f0 = ft_old[s, 0]
    f1 = ft_old[s, 1]
    f2 = ft_old[s, 2]
    fmag = np.sqrt(f0 * f0 + f1 * f1 + f2 * f2)
    fnp = f0 * n0 + f1 * n1 + f2 * n2
    f0 -= fnp * n0
    f1 -= fnp * n1
    f2 -= fnp * n2
    fm2 = np.sqrt(f0 * f0 + f1 * f1 + f2 * f2)
    if fm2 > 0.0:
        f0 *= fmag / fm2
        f1 *= fmag / fm2
        f2 *= fmag / fm2
    k = kt[s] * A
    f0 -= k * s0
    f1 -= k * s1
    f2 -= k * s2
    ftr = np.sqrt(f0 * f0 + f1 * f1 + f2 * f2)
    bound = mu * fn
    if ftr > bound:
        sc = bound / ftr
        slip[s] = (ftr - bound) / k
        f0 *= sc
        f1 *= sc
        f2 *= sc
        status[s] = 2
    else:
        status[s] = 1
    ft_new[s, 0] = f0
    ft_new[s, 1] = f1
    ft_new[s, 2] = f2
    fs[s, 0] = fn * n0 + f0
    fs[s, 1] = fn * n1 + f1
    fs[s, 2] = fn * n2 + f2


@njit(cache=True)
def _slave(s, slaves, master, law, ft_old, out, scratch):
    """Contact of slave ``s`` (the records of :func:`node_to_surface`); ``scratch`` =
    ``(c, q, dq)``: arrays (4, 3), (3,), (3,) of the caller's thread."""
    xs, dxs, area, kn, kt, cdamp = slaves
    xm, nm, dxm, x_ref, y_ref, shift = master
    mu, reach, g0, inv_dt = law
    energy, fs, gap, pn, ft_new, status, cell, rt, normal, slip_rate_num = out
    c, q, dq = scratch
    nx = x_ref.shape[0]
    ny = y_ref.shape[0]
    status[s] = 0
    energy[s] = 0.0
    pn[s] = 0.0
    gap[s] = 1.0
    slip_rate_num[s] = 0.0
    for d in range(3):
        fs[s, d] = 0.0
        ft_new[s, d] = 0.0
    X = xs[s, 0] + shift
    Y = xs[s, 1]
    if X < x_ref[0] or X > x_ref[nx - 1] or Y < y_ref[0] or Y > y_ref[ny - 1]:
        return
    i = np.searchsorted(x_ref, X) - 1
    j = np.searchsorted(y_ref, Y) - 1
    i = min(max(i, 0), nx - 2)
    j = min(max(j, 0), ny - 2)
    if xs[s, 2] - xm[i, j, 2] > reach:
        return
    r = 0.5
    t = 0.5
    found = False
    for hop in range(4):
        c[0] = xm[i, j]
        c[1] = xm[i + 1, j]
        c[2] = xm[i + 1, j + 1]
        c[3] = xm[i, j + 1]
        r = 0.5
        t = 0.5
        for it in range(6):
            drr, dtt, det = closest_point_step(c, r, t, xs[s, 0], xs[s, 1], xs[s, 2])
            r += drr
            t += dtt
            if abs(drr) < 1e-12 and abs(dtt) < 1e-12:
                break
        tol = 1e-6
        moved = False
        if hop == 3:      # oscillating between two cells: on their common edge
            found = True
            break
        if r < -tol and i > 0:
            i -= 1
            moved = True
        elif r > 1 + tol and i < nx - 2:
            i += 1
            moved = True
        if t < -tol and j > 0:
            j -= 1
            moved = True
        elif t > 1 + tol and j < ny - 2:
            j += 1
            moved = True
        if not moved:
            found = True
            break
    if not found:
        return
    r = min(max(r, 0.0), 1.0)
    t = min(max(t, 0.0), 1.0)
    _bilinear(c, r, t, q)
    tr0, tr1, tr2, tt0, tt1, tt2 = _bilinear_tangents(c, r, t)
    # continuous normal: bilinear interpolation of the nodal normals nm
    n0 = ((1 - r) * (1 - t) * nm[i, j, 0] + r * (1 - t) * nm[i + 1, j, 0]
          + r * t * nm[i + 1, j + 1, 0] + (1 - r) * t * nm[i, j + 1, 0])
    n1 = ((1 - r) * (1 - t) * nm[i, j, 1] + r * (1 - t) * nm[i + 1, j, 1]
          + r * t * nm[i + 1, j + 1, 1] + (1 - r) * t * nm[i, j + 1, 1])
    n2 = ((1 - r) * (1 - t) * nm[i, j, 2] + r * (1 - t) * nm[i + 1, j, 2]
          + r * t * nm[i + 1, j + 1, 2] + (1 - r) * t * nm[i, j + 1, 2])
    nn = np.sqrt(n0 * n0 + n1 * n1 + n2 * n2)
    n0 /= nn
    n1 /= nn
    n2 /= nn
    g = (xs[s, 0] - q[0]) * n0 + (xs[s, 1] - q[1]) * n1 + (xs[s, 2] - q[2]) * n2
    gap[s] = g
    cell[s, 0] = i
    cell[s, 1] = j
    rt[s, 0] = r
    rt[s, 1] = t
    normal[s, 0] = n0
    normal[s, 1] = n1
    normal[s, 2] = n2
    if g >= 0.0:
        return
    A = area[s]
    # C1-regularized penalty: quadratic for overlaps below g0, linear beyond
    dlt = -g
    if dlt < g0:
        fn = kn[s] * A * dlt * dlt / (2 * g0)
        energy[s] = kn[s] * A * dlt ** 3 / (6 * g0)
    else:
        fn = kn[s] * A * (dlt - 0.5 * g0)
        energy[s] = kn[s] * A * (0.5 * dlt * dlt - 0.5 * g0 * dlt + g0 * g0 / 6)
    # relative increment of the slave w.r.t. the master point
    wts = ((1 - r) * (1 - t), r * (1 - t), r * t, (1 - r) * t)
    ii = (i, i + 1, i + 1, i)
    jj = (j, j, j + 1, j + 1)
    for d in range(3):
        dq[d] = 0.0
    for m in range(4):
        for d in range(3):
            dq[d] += wts[m] * dxm[ii[m], jj[m], d]
    s0 = dxs[s, 0] - dq[0]
    s1 = dxs[s, 1] - dq[1]
    s2 = dxs[s, 2] - dq[2]
    coulomb_update(s, fn, s0, s1, s2, n0, n1, n2, A, kt, mu, cdamp, inv_dt, ft_old, pn,
                   ft_new, slip_rate_num, status, fs)


@njit(cache=True, parallel=True)
def node_to_surface(slaves, master, law, ft_old, out, fm):
    """Penalty node-to-surface contact with Coulomb friction (return mapping).

    Slave nodes (wheel surface) against a structured master surface (rail,
    bilinear quads over a reference grid ``x_ref`` x ``y_ref``). The arguments are
    records (tuples, in this order):

    * ``slaves`` = ``(xs, dxs, area, kn, kt, cdamp)``,
    * ``master`` = ``(xm, nm, dxm, x_ref, y_ref, shift)``,
    * ``law`` = ``(mu, reach, g0, inv_dt)``,
    * ``ft_old``,
    * ``out`` = ``(energy, fs, gap, pn, ft_new, status, cell, rt, normal, slip_rate_num)``,
    * ``fm``.

    Parameters
    ----------
    xs, dxs : (ns, 3)
        Current slave positions and their increments over the step [m].
    area, kn, kt : (ns,)
        Tributary areas [m²] and normal / tangential penalties [Pa/m].
    mu : float
        Coulomb friction coefficient [-].
    ft_old : (ns, 3)
        Tangential forces of the last converged step [N] (global frame).
    xm, dxm : (nx, ny, 3)
        Current master surface node positions and increments [m].
    nm : (nx, ny, 3)
        Unit nodal normals of the master surface (interpolated bilinearly, so
        that the normal is continuous across facet edges).
    x_ref, y_ref : (nx,), (ny,)
        Reference axes of the master grid; a point at current ``x`` is
        searched at reference ``x + shift``.
    reach : float
        Slaves farther than this above the master surface are skipped [m].
    g0 : float
        Regularization overlap [m]: the normal force is kn A δ²/(2 g0) for an
        overlap δ < g0 and kn A (δ − g0/2) beyond (continuous tangent, so that
        Newton converges).
    cdamp : (ns,)
        Normal contact damping [N s/m]: a dashpot −c v_n on the relative normal velocity
        v_n = (normal increment) · inv_dt of a closed pair (the normal force stays >= 0);
        zeros for none.
    inv_dt : float
        1 / time step [1/s] (for the dashpot).
    energy : (ns,)
        Output: penalty energy of each slave [J].

    Outputs (filled): fs (ns, 3) force on the slaves, fm (nx, ny, 3) forces on
    the master nodes, gap (ns,), pn (ns,) normal force, ft_new (ns, 3), status
    (ns,) 0 open / 1 stick / 2 slip, cell (ns, 2), rt (ns, 2), normal (ns, 3),
    slip_rate_num (ns,) the slip increment length [m] (trial excess / kt A).

    Parallel over the slaves (chunks); the master forces are scattered afterwards in
    slave order, so the result does not depend on the number of threads.
    """
    ns = slaves[0].shape[0]
    status, cell, rt, fs = out[5], out[6], out[7], out[1]
    nch = min(64, max(1, ns // 64))
    for ch in prange(nch):
        scratch = (np.empty((4, 3)), np.empty(3), np.empty(3))
        for s in range(ns * ch // nch, ns * (ch + 1) // nch):
            _slave(s, slaves, master, law, ft_old, out, scratch)
    scatter_to_grid(status, cell, rt, fs, fm)
