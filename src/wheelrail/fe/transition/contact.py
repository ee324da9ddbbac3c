"""General multi-patch node-to-segment contact (penalty, Coulomb) with a bucket search.

The master surface is any set of bilinear quadrilaterals (the rail's running surface,
gauge face included); a slave node (wheel surface) is located through a uniform
bucket grid built once over the masters' reference bounding boxes (the rail moves
little), projected onto every candidate quad by a closest-point Newton iteration,
and paired with the nearest projection that falls inside its quad. Normals are
interpolated from nodal normals (continuous across facet edges). Normal force: penalty
with a C¹ regularisation below an overlap g0 and a dashpot on the relative normal
velocity; friction: incremental penalty stick and return to the Coulomb cone — the
same laws as :func:`wheelrail.fe._kernels.node_to_surface`, whose tensor-grid search
cannot follow a flange onto a gauge face.

Patches are the connected sets of closed slave nodes on the wheel's surface grid
(:func:`patches`); :func:`patch_summary` gives per-patch forces, contact angle,
centre, area, maximum pressure and shear, the adhesion/slip division by the
tolerance definition of Zhao & Li (2011) (a node adheres if μ p − |q| exceeds a
fraction of the patch's largest tangential nodal force) and the shear direction θ.

References
----------
.. [1] P. Wriggers, *Computational Contact Mechanics*, 2nd ed., Springer 2006, §5.2
   (node-to-segment, closest-point projection), §10.3 (bucket search).
.. [2] X. Zhao, Z. Li, "The solution of frictional wheel-rail rolling contact with a 3D
   transient finite element model: validation and error analysis", Wear 271 (2011)
   444-452, §2.3 (adhesion/slip by a tolerance on μ p − q).
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from .._kernels import closest_point_step, coulomb_update

__all__ = ["BucketGrid", "build_buckets", "nodal_normals_quads", "node_to_segment", "patches",
           "split_patches", "patch_summary", "SPLIT_ANGLE"]

#: Contact angle [rad] separating tread (below) from flange (above) contact nodes: the
#: rigid contact of S1002 on 54E1 jumps from < 30° on the flange root to ≈ 70° on the
#: flange, so any angle in between separates the two patches.
SPLIT_ANGLE = float(np.radians(45.0))


class BucketGrid:
    """Uniform bucket grid of master quads (CSR lists), reference configuration."""

    def __init__(self, origin, cell, dims, start, items):
        self.origin = origin
        self.cell = float(cell)
        self.dims = dims
        self.start = start
        self.items = items

    @property
    def record(self):
        """``(origin, cell, dims, start, items)``: the grid as :func:`node_to_segment` takes it."""
        return (self.origin, self.cell, self.dims, self.start, self.items)


def build_buckets(xm: np.ndarray, quads: np.ndarray, cell: float, margin: float) -> BucketGrid:
    """Bucket grid of the quads ``quads`` (nq, 4) over master nodes ``xm`` (nm, 3).

    Every quad is listed in each bucket its bounding box, grown by ``margin`` [m], overlaps.
    """
    p = xm[quads]                                   # (nq, 4, 3)
    lo = p.min(axis=1) - margin
    hi = p.max(axis=1) + margin
    origin = lo.min(axis=0)
    dims = np.maximum(1, np.ceil((hi.max(axis=0) - origin) / cell).astype(np.int64))
    i0 = np.clip(((lo - origin) // cell).astype(np.int64), 0, dims - 1)
    i1 = np.clip(((hi - origin) // cell).astype(np.int64), 0, dims - 1)
    cells, owners = [], []
    for q in range(quads.shape[0]):
        a, b = i0[q], i1[q]
        g = np.stack(np.meshgrid(np.arange(a[0], b[0] + 1), np.arange(a[1], b[1] + 1),
                                 np.arange(a[2], b[2] + 1), indexing="ij"), -1).reshape(-1, 3)
        cells.append((g[:, 0] * dims[1] + g[:, 1]) * dims[2] + g[:, 2])
        owners.append(np.full(g.shape[0], q))
    cells = np.concatenate(cells)
    owners = np.concatenate(owners)
    order = np.argsort(cells, kind="stable")
    nb = int(dims.prod())
    start = np.zeros(nb + 1, np.int64)
    np.add.at(start, cells + 1, 1)
    return BucketGrid(origin.astype(float), cell, dims.astype(np.int64), np.cumsum(start),
                      owners[order].astype(np.int64))


def nodal_normals_quads(xm: np.ndarray, quads: np.ndarray) -> np.ndarray:
    """Unit nodal normals (nm, 3): area-weighted mean of the adjacent quads' normals
    (the quads' node order gives the outward side)."""
    p = xm[quads]
    n = np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 1])       # 2 × area × unit normal
    out = np.zeros_like(xm)
    for c in range(4):
        np.add.at(out, quads[:, c], n)
    nn = np.linalg.norm(out, axis=1, keepdims=True)
    return out / np.where(nn > 0, nn, 1.0)


@njit(cache=True, inline="always")
def _project(xs0, xs1, xs2, c, out):
    """Closest point of (xs) on the bilinear quad c (4, 3): r, t into ``out`` (Newton,
    the step of :func:`~wheelrail.fe._kernels.closest_point_step`)."""
    r = 0.5
    t = 0.5
    for it in range(8):
        drr, dtt, det = closest_point_step(c, r, t, xs0, xs1, xs2)
        if det <= 0.0:
            break
        r += drr
        t += dtt
        if abs(drr) < 1e-10 and abs(dtt) < 1e-10:
            break
    out[0] = r
    out[1] = t


@njit(cache=True, parallel=True)
def node_to_segment(slaves, master, buckets, law, ft_old, out):
    """Penalty node-to-segment contact with Coulomb friction against arbitrary quads.

    The arguments are records (tuples, in this order):

    * ``slaves`` = ``(xs, dxs, area, kn, kt, cdamp)``,
    * ``master`` = ``(xm, dxm, nmn, quads)``,
    * ``buckets`` = ``(b_origin, b_cell, b_dims, b_start, b_items)`` (:attr:`BucketGrid.record`),
    * ``law`` = ``(mu, reach, g0, inv_dt)``,
    * ``ft_old``,
    * ``out`` = ``(fs, gap, pn, ft_new, status, seg, rt, normal, slip)``.

    Parameters
    ----------
    xs, dxs : (ns, 3)
        Slave positions and their increments over the step [m] (global frame).
    area, kn, kt, cdamp : (ns,)
        Tributary areas [m²], normal and tangential penalties [Pa/m], normal dashpots [N s/m].
    mu : float
        Friction coefficient.
    ft_old : (ns, 3)
        Tangential forces of the last step [N].
    xm, dxm, nmn : (nm, 3)
        Master node positions, increments and unit nodal normals.
    quads : (nq, 4) int
        Master quads (indices into ``xm``).
    b_origin, b_cell, b_dims, b_start, b_items
        The bucket grid (:func:`build_buckets`).
    reach : float
        Slaves farther than this from the surface are open [m].
    g0 : float
        Regularisation overlap [m].
    inv_dt : float
        1 / step [1/s].

    Outputs: fs (ns, 3) force on the slaves, gap (ns,), pn (ns,), ft_new (ns, 3), status
    (ns,) 0 open / 1 stick / 2 slip, seg (ns,) quad or −1, rt (ns, 2), normal (ns, 3),
    slip (ns,) slip increment length [m].
    """
    xs, dxs, area, kn, kt, cdamp = slaves
    xm, dxm, nmn, quads = master
    b_origin, b_cell, b_dims, b_start, b_items = buckets
    mu, reach, g0, inv_dt = law
    fs, gap, pn, ft_new, status, seg, rt, normal, slip = out
    ns = xs.shape[0]
    nch = min(64, max(1, ns // 64))
    for ch in prange(nch):
        c = np.empty((4, 3))
        pr = np.empty(2)
        for s in range(ns * ch // nch, ns * (ch + 1) // nch):
            status[s] = 0
            pn[s] = 0.0
            gap[s] = 1.0
            slip[s] = 0.0
            seg[s] = -1
            for d in range(3):
                fs[s, d] = 0.0
                ft_new[s, d] = 0.0
            bi = np.empty(3, np.int64)
            inside_grid = True
            for d in range(3):
                k = int(np.floor((xs[s, d] - b_origin[d]) / b_cell))
                if k < 0 or k >= b_dims[d]:
                    inside_grid = False
                bi[d] = k
            if not inside_grid:
                continue
            b = (bi[0] * b_dims[1] + bi[1]) * b_dims[2] + bi[2]
            best = -1
            best_d = 1e30
            best_r = 0.0
            best_t = 0.0
            for m in range(b_start[b], b_start[b + 1]):
                q = b_items[m]
                # cheap rejection: slave farther than reach from the quad's bounding box
                far = False
                for d in range(3):
                    lo = xm[quads[q, 0], d]
                    hi = lo
                    for a in range(1, 4):
                        vv = xm[quads[q, a], d]
                        lo = min(lo, vv)
                        hi = max(hi, vv)
                    if xs[s, d] < lo - reach or xs[s, d] > hi + reach:
                        far = True
                        break
                if far:
                    continue
                for a in range(4):
                    for d in range(3):
                        c[a, d] = xm[quads[q, a], d]
                _project(xs[s, 0], xs[s, 1], xs[s, 2], c, pr)
                r = pr[0]
                t = pr[1]
                tol = 1e-3
                if r < -tol or r > 1 + tol or t < -tol or t > 1 + tol:
                    continue
                r = min(max(r, 0.0), 1.0)
                t = min(max(t, 0.0), 1.0)
                dd = 0.0
                for d in range(3):
                    qd = ((1 - r) * (1 - t) * c[0, d] + r * (1 - t) * c[1, d] + r * t * c[2, d]
                          + (1 - r) * t * c[3, d])
                    dd += (xs[s, d] - qd) ** 2
                if dd < best_d:
                    best_d = dd
                    best = q
                    best_r = r
                    best_t = t
            if best < 0:
                continue
            r = best_r
            t = best_t
            w0 = (1 - r) * (1 - t)
            w1 = r * (1 - t)
            w2 = r * t
            w3 = (1 - r) * t
            i0 = quads[best, 0]
            i1 = quads[best, 1]
            i2 = quads[best, 2]
            i3 = quads[best, 3]
            n0 = w0 * nmn[i0, 0] + w1 * nmn[i1, 0] + w2 * nmn[i2, 0] + w3 * nmn[i3, 0]
            n1 = w0 * nmn[i0, 1] + w1 * nmn[i1, 1] + w2 * nmn[i2, 1] + w3 * nmn[i3, 1]
            n2 = w0 * nmn[i0, 2] + w1 * nmn[i1, 2] + w2 * nmn[i2, 2] + w3 * nmn[i3, 2]
            nn = np.sqrt(n0 * n0 + n1 * n1 + n2 * n2)
            n0 /= nn
            n1 /= nn
            n2 /= nn
            q0 = w0 * xm[i0, 0] + w1 * xm[i1, 0] + w2 * xm[i2, 0] + w3 * xm[i3, 0]
            q1 = w0 * xm[i0, 1] + w1 * xm[i1, 1] + w2 * xm[i2, 1] + w3 * xm[i3, 1]
            q2 = w0 * xm[i0, 2] + w1 * xm[i1, 2] + w2 * xm[i2, 2] + w3 * xm[i3, 2]
            g = (xs[s, 0] - q0) * n0 + (xs[s, 1] - q1) * n1 + (xs[s, 2] - q2) * n2
            gap[s] = g
            seg[s] = best
            rt[s, 0] = r
            rt[s, 1] = t
            normal[s, 0] = n0
            normal[s, 1] = n1
            normal[s, 2] = n2
            if g >= 0.0 or g < -reach:
                continue
            A = area[s]
            dlt = -g
            if dlt < g0:
                fn = kn[s] * A * dlt * dlt / (2 * g0)
            else:
                fn = kn[s] * A * (dlt - 0.5 * g0)
            s0 = dxs[s, 0] - (w0 * dxm[i0, 0] + w1 * dxm[i1, 0] + w2 * dxm[i2, 0] + w3 * dxm[i3, 0])
            s1 = dxs[s, 1] - (w0 * dxm[i0, 1] + w1 * dxm[i1, 1] + w2 * dxm[i2, 1] + w3 * dxm[i3, 1])
            s2 = dxs[s, 2] - (w0 * dxm[i0, 2] + w1 * dxm[i1, 2] + w2 * dxm[i2, 2] + w3 * dxm[i3, 2])
            coulomb_update(s, fn, s0, s1, s2, n0, n1, n2, A, kt, mu, cdamp, inv_dt, ft_old, pn,
                           ft_new, slip, status, fs)


@njit(cache=True)
def scatter_master(fs, status, seg, rt, quads, fm):
    """Reaction forces on the master nodes (nm, 3) (added, serial: deterministic)."""
    for s in range(fs.shape[0]):
        if status[s] > 0:
            q = seg[s]
            r = rt[s, 0]
            t = rt[s, 1]
            w = ((1 - r) * (1 - t), r * (1 - t), r * t, (1 - r) * t)
            for a in range(4):
                for d in range(3):
                    fm[quads[q, a], d] -= w[a] * fs[s, d]


def patches(status_grid: np.ndarray):
    """Label the closed nodes of a wheel-surface grid (n_a, n_s) into patches.

    Returns
    -------
    labels : ndarray of int (n_a, n_s), 0 open, 1.. patch number (ordered by the mean
    surface index ``j``, i.e. across the profile from the flange side); n : int.
    """
    from scipy import ndimage

    lab, n = ndimage.label(status_grid > 0, structure=np.ones((3, 3)))
    if n == 0:
        return lab, 0
    jj = np.broadcast_to(np.arange(status_grid.shape[1])[None], status_grid.shape)
    mean_j = ndimage.mean(jj, lab, index=np.arange(1, n + 1))
    order = np.argsort(mean_j)
    remap = np.zeros(n + 1, np.int64)
    remap[order + 1] = np.arange(1, n + 1)
    return remap[lab], n


def split_patches(status_grid: np.ndarray, angle_grid: np.ndarray, weight_grid: np.ndarray,
                  split: float = SPLIT_ANGLE):
    """Tread and flange patches by contact angle, robust on coarse meshes.

    On a coarse surface grid the tread contact at the flange root and the flange contact
    are neighbours and merge into one connected set; splitting the closed nodes by their
    contact angle first (the master normal at the projection against the vertical) keeps
    them apart.

    Parameters
    ----------
    status_grid : (n_a, n_s) int
        Contact status of the wheel-surface grid (> 0 closed).
    angle_grid : (n_a, n_s) float
        Contact angle of each node [rad].
    weight_grid : (n_a, n_s) float
        Normal nodal force [N] (ranks the components of a class).
    split : float
        Contact angle [rad] between the classes.

    Returns
    -------
    labels : ndarray of int (n_a, n_s)
        0 open; 1 the tread patch (the connected set below ``split`` carrying the largest
        normal force); 2 the flange patch (likewise above ``split``); 3 every other closed
        node (small separate islands).
    counts : tuple of int
        Number of connected sets below and above ``split``.
    """
    from scipy import ndimage

    closed = status_grid > 0
    out = np.zeros(status_grid.shape, np.int64)
    counts = []
    for cls, sel in ((1, closed & (angle_grid < split)), (2, closed & (angle_grid >= split))):
        lab, n = ndimage.label(sel, structure=np.ones((3, 3)))
        counts.append(int(n))
        if n == 0:
            continue
        f = ndimage.sum(weight_grid, lab, index=np.arange(1, n + 1))
        best = int(np.argmax(f)) + 1
        out[lab == best] = cls
        out[(lab > 0) & (lab != best)] = 3
    return out, tuple(counts)


#: Fraction of the patch's largest tangential nodal force below which μ p − |q| counts as
#: slip (Zhao & Li 2011 use "a percentage"; 2 % here).
ADHESION_TOLERANCE = 0.02


def adhering(p, q, mu, tolerance: float = ADHESION_TOLERANCE) -> np.ndarray:
    """Adhering nodes of one patch by the tolerance definition (Zhao & Li 2011):
    μ p − |q| > ``tolerance`` × the patch's largest |q|.

    Parameters
    ----------
    p, q : ndarray, shape (n,)
        Normal and tangential nodal forces of the patch's closed nodes [N].
    mu : float
        Friction coefficient.

    Returns
    -------
    ndarray of bool, shape (n,)
    """
    eps = tolerance * q.max() if q.size else 0.0
    return (mu * p - q) > eps


def patch_summary(mask, xs, fs, pn, ft, normal, area, status, mu,
                  tolerance: float = ADHESION_TOLERANCE, heading: float = 0.0) -> dict:
    """Per-patch quantities of the slave nodes ``mask`` (forces on the wheel, global frame).

    Returns
    -------
    dict
        ``Fn`` Σ normal forces [N]; ``Fx``, ``Fy``, ``Fz`` global components of the total
        force [N]; ``F_long``, ``F_lat`` tangential force along the rail and along the
        patch's lateral tangent (in the tangent plane, ⟂ x) [N]; ``contact_angle`` of the
        force-weighted mean normal against the vertical [rad]; ``x``, ``y``, ``z`` centre
        (pressure-weighted) [m]; ``area`` [m²]; ``p_max``, ``q_max`` largest nodal pressure
        and shear [Pa]; ``adhesion`` the adhering fraction of the area (μ p − |q| >
        tolerance × max |q|); ``theta`` the angle of the mean shear stress on the *rail*
        against the negative longitudinal axis [rad] (0: pure traction of a driven wheel).
    """
    m = np.asarray(mask, bool) & (status > 0)
    nan = float("nan")
    if not np.any(m) or not pn[m].sum() > 0:  # nothing closed, or closed without pressure
        return dict(Fn=0.0, Fx=0.0, Fy=0.0, Fz=0.0, F_long=0.0, F_lat=0.0, contact_angle=nan,
                    x=nan, y=nan, z=nan, area=0.0, p_max=0.0, q_max=0.0, adhesion=nan,
                    theta=nan, n_nodes=0)
    p = pn[m]
    F = fs[m].sum(axis=0)
    nm = (normal[m] * p[:, None]).sum(axis=0)
    nm /= np.linalg.norm(nm)
    e_long = np.array([1.0, 0.0, 0.0])
    e_lat = np.cross(nm, e_long)
    e_lat /= np.linalg.norm(e_lat)
    if e_lat[1] < 0:
        e_lat = -e_lat
    Ft = ft[m].sum(axis=0)
    q = np.linalg.norm(ft[m], axis=1)
    A = area[m]
    stick = adhering(p, q, mu, tolerance)
    c = (xs[m] * p[:, None]).sum(axis=0) / p.sum()
    # shear on the rail = −(tangential force on the wheel)
    tau = -Ft
    theta = float(np.arccos(np.clip(np.dot(tau, -e_long) / max(np.linalg.norm(tau), 1e-300),
                                    -1.0, 1.0)))
    return dict(Fn=float(p.sum()), Fx=float(F[0]), Fy=float(F[1]), Fz=float(F[2]),
                F_long=float(Ft @ e_long), F_lat=float(Ft @ e_lat),
                contact_angle=float(np.arccos(min(1.0, abs(nm[2])))),
                x=float(c[0]), y=float(c[1]), z=float(c[2]), area=float(A.sum()),
                p_max=float((p / A).max()), q_max=float((q / A).max()),
                adhesion=float(A[stick].sum() / A.sum()), theta=theta, n_nodes=int(m.sum()))
