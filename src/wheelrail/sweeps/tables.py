"""Building the creep-force table of :class:`wheelrail.tangential.Table` with the exact solver.

The nodes of the table (its axes: :data:`wheelrail.tangential.table.AXES`) are
turned into physical contacts and creepages (:func:`table_nodes`) and computed
by resumable :func:`wheelrail.sweep` runs of the exact theory. The planes
r = 1 (creepage ≫ spin) and s = ±1 (spin → ∞) are full sliding and are
written from the analytic full-slip integrals (:func:`full_slip`). The command
line is ``wheelrail build-table``.

Grid convergence (table version 2)
----------------------------------
The exact solver converges slowly with its element count N (first order,
with a large constant where spin and creepage combine and for elongated
patches: with 36 elements a patch with a/b = 20 is still up to ≈ 4 % of μFn
from its limit, a spin-dominated one with a/b = 1.6 ≈ 2.5 %). The table is
therefore the grid limit of the exact theory. With ``elements = (N₁, N₂, N₃)``:

* every node (r, θ, s, a/b) is computed with N₂ at the first Poisson's ratio;
* on the sub-grid of every ``extrapolation_stride``-th node along r, θ and s
  (every a/b) all resolutions are computed at the first ν and the grid limit
  is the least-squares fit f∞ + C N⁻ᵖ (:func:`grid_limit`, p = :data:`ORDER`
  = 1, the solver's observed order at high resolution); its step f∞ − f_N₂ is
  interpolated (Catmull–Rom cubics) onto every node and added;
* the other Poisson's ratios: N₂ on the sub-grid of stride ``nu_stride``, the
  difference to the first ν interpolated the same way (the effect of ν on the
  discretisation error is below the solver's jitter);
* the plane of the smallest creepages, r = Δr, at the first ν: its own fit to
  :data:`FIRST_PLANE_ELEMENTS` (the slip zone is a few N₁-elements wide there).

The shipped table uses stride 1 for both (every node).

Every resolution is computed by resumable :func:`wheelrail.sweep` runs into
Zarr stores under the work directory; a node already in a store at that
resolution (of this grid, or of another grid sharing the node, e.g. every other
node of a refined axis) is reused, so an interrupted or
refined build computes only what is missing. Dask ``LocalCluster`` workers with
``workers > 1``.

References
----------
.. [1] J.J. Kalker, Book of tables for the Hertzian creep-force law, in:
   I. Zobory (ed.), Proc. 2nd Mini Conf. on Contact Mechanics and Wear of
   Wheel/Rail Systems, Budapest, 1996, 11-20.
.. [2] L.F. Richardson, The deferred approach to the limit, Phil. Trans. R. Soc.
   A 226 (1927) 299-361 (extrapolation); P.J. Roache, Verification and Validation
   in Computational Science and Engineering, Hermosa 1998, ch. 5 (observed order).
"""

from __future__ import annotations

import hashlib
import json
import shutil
from pathlib import Path

import numpy as np

from .._version import __version__
from ..tangential.exact import Exact
from ..tangential.table import (
    AXES,
    DEFAULT_TABLE,
    TABLE_VERSION,
    _coefficients,
    _spin_length,
    full_slip,
)
from .evaluators import STATUS_CODES
from .run import sweep
from .spec import SweepSpec

__all__ = [
    "BUILD_CONTACT",
    "ELEMENTS",
    "EXTRAPOLATION_STRIDE",
    "FIRST_PLANE_ELEMENTS",
    "GRID",
    "NU_STRIDE",
    "ORDER",
    "REFERENCE_ELEMENTS",
    "assemble_table",
    "REFINED_REGIONS",
    "replace_first_plane",
    "build_table",
    "THETA_END_REGIONS",
    "R_START_REGIONS",
    "fit_r_start",
    "fit_theta_end",
    "refine_regions",
    "refine_table",
    "exact_limit",
    "grid_limit",
    "observed_order",
    "sub_grid",
    "table_nodes",
]

#: Node grid of the table (version 2). r = ρ̂/(1 + |φ̂| + ρ̂) (r = 1 analytic), θ,
#: s = φ̂/(1 + |φ̂|) (s = ±1 analytic), ln(a/b) for a/b in [0.05, 20], ν.
GRID = {
    "r": np.linspace(0.0, 1.0, 21),
    "theta": np.linspace(0.0, 0.5 * np.pi, 9),
    "s": np.linspace(-1.0, 1.0, 41),
    "log_ab": np.log(np.geomspace(0.05, 20.0, 17)),
    "nu": np.array([0.25, 0.30]),
}
#: Exact-solver resolutions (elements across the contact): 24 on every node and ν,
#: 16 and 36 on every node at the first ν.
ELEMENTS = (16, 24, 36)
#: Convergence order of the exact solver in its element count (first order: the
#: median observed order of 60 random contacts from 54/81/122 elements is 0.98 for
#: Fx and Fy, benchmarks/bench_contact_table_law.py).
ORDER = 1.0
#: Resolutions of the table law's reference (:func:`exact_limit`).
REFERENCE_ELEMENTS = (36, 54, 81, 122)
#: Strides along r, θ, s of the sub-grids of the grid-limit fit and of the other ν
#: (1: every node; the shipped table).
EXTRAPOLATION_STRIDE = 1
NU_STRIDE = 1
#: Resolutions of the grid-limit fit on the first plane of computed creepages (r = Δr)
#: at the first ν. There the slip zone is a few elements of N₁ wide and the exact
#: solver is not yet in its first-order regime at N₁ … N₃: the 16/24/36 fit is up
#: to 1.7 % of μFn off at r = 0.05, and 0.9 % low in the slope at a/b = 1 (Kalker's
#: C11), where 36/54/81 holds it to 0.4 %.
FIRST_PLANE_ELEMENTS = (36, 54, 81)
#: Regions of nodes recomputed on every ν with the grid-limit fit of
#: :data:`FIRST_PLANE_ELEMENTS` (:func:`refine_regions`): small creepage with large spin
#: on patches wide in y. There the 16/24/36 fit is up to 2 % of μFn from the 36/54/81
#: limit (r = 0.1, s = 0.95, a/b = 0.1; elsewhere within 0.3 %, 300 random nodes); the
#: ranges are inclusive bounds of r, |s| and a/b.
REFINED_REGIONS = ({"r": (0.0, 0.2), "s_abs": (0.75, 0.95), "aspect": (0.05, 0.5)},)
#: Regions where the last θ nodes (nearly lateral creepage, θ ≥ 3π/8) are least-squares
#: fitted (:func:`fit_theta_end`): on slender patches (a/b ≥ 6) with spin and
#: moderate creepage Fy has a narrow peak at θ = π/2 that a spline through the 9
#: θ nodes misses by up to 1.3 % of μFn at the midpoint θ = 15π/32.
THETA_END_REGIONS = ({"r": (0.35, 0.75), "s_abs": (0.3, 0.95), "aspect": (6.0, 20.0)},)
#: Regions whose lines along r are least-squares fitted to the midpoint of the first
#: cell, r = Δr/2 (:func:`fit_r_start`): with large spin on patches wide in y, Fy
#: bends between r = 0 and Δr more than the spline through the nodes follows (1.1 %
#: of μFn at r = 0.017, s = −0.94, a/b = 0.1 with exact nodes).
R_START_REGIONS = ({"s_abs": (0.8, 0.95), "aspect": (0.05, 0.5)},)
#: Parameters of the physical contacts on which the nodes are computed (any
#: values give the same dimensionless result, by similarity).
BUILD_CONTACT = {"E": 2.1e11, "Fn": 1.0e4, "mu": 0.3, "c": 5.0e-3}


def _computed(axis, name):
    """Mask of the computed nodes of an axis (the analytic end planes excluded)."""
    if name == "r":
        return axis < 1.0
    if name == "s":
        return np.abs(axis) < 1.0
    return np.ones(axis.shape, bool)


def _physical(R, T, S, L, N, *, spin_sign_only=False):
    """Physical creepages and semi-axes of table coordinates (arrays of one shape)."""
    ab = np.exp(L)
    C11, C22, C23 = _coefficients(ab, N)
    c, E, load, mu = (BUILD_CONTACT[k] for k in ("c", "E", "Fn", "mu"))
    G = E / (2.0 * (1.0 + N))
    b = c / np.sqrt(ab)
    spin_len = _spin_length(c, b, C11, C23)
    unit = 3.0 * mu * load / G
    if spin_sign_only:  # s = ±1: spin -> infinity, rho_hat/|phi_hat| = r/(1 - r)
        phi_hat = np.sign(S)
        rho = R / (1.0 - R)
    else:
        phi_hat = S / (1.0 - np.abs(S))
        rho = (1.0 + np.abs(phi_hat)) * R / (1.0 - R)
    eta_hat = rho * np.sin(T) - phi_hat * c * C23 / spin_len  # θ: direction of (ξ̂, η̂ + φ̂_y)
    return {"xi": rho * np.cos(T) * unit / (c**2 * C11),
            "eta": eta_hat * unit / (c**2 * C22),
            "phi": phi_hat * unit / (c**2 * spin_len),
            "a": c * np.sqrt(ab), "b": b, "nu": N}


def table_nodes(grid=None) -> dict:
    """Physical inputs of the table's computed nodes (all but the analytic planes).

    Returns
    -------
    dict
        ``shape`` (the grid of computed nodes: r < 1, |s| < 1) and columns
        ``xi, eta`` [-], ``phi`` [1/m], ``a, b`` [m], ``nu`` [-] in C order of
        (r, θ, s, a/b, ν); the contact has ``E``, ``Fn``, ``mu`` of
        :data:`BUILD_CONTACT`.
    """
    g = {k: np.asarray(v, float) for k, v in (GRID if grid is None else grid).items()}
    ax = [g[k][_computed(g[k], k)] for k in AXES]
    R, T, S, L, N = np.meshgrid(*ax, indexing="ij")
    shape = R.shape
    out = _physical(*(v.reshape(-1) for v in (R, T, S, L, N)))
    out["shape"] = shape
    return out


def _analytic_values(grid):
    """Full grid of values with the analytic planes filled (NaN elsewhere)."""
    shape = tuple(len(grid[k]) for k in AXES)
    vals = np.full(shape + (3,), np.nan)
    R, T, S, L, N = np.meshgrid(*(grid[k] for k in AXES), indexing="ij")
    # r = 1: F = -mu Fn along the creepage direction, Mz = 0 (spin negligible)
    C11, C22, _ = _coefficients(np.exp(L), N)
    alpha = np.arctan2(np.sin(T) / C22, np.cos(T) / C11)
    plane = R == 1.0
    vals[plane] = np.stack([-np.cos(alpha), -np.sin(alpha), np.zeros_like(alpha)], -1)[plane]
    # s = ±1 (r < 1): full sliding under the rigid slip of infinite spin with rho/phi fixed
    spin = (np.abs(S) == 1.0) & (R < 1.0)
    if np.any(spin):
        p = _physical(R[spin], T[spin], S[spin], L[spin], N[spin], spin_sign_only=True)
        vals[spin] = np.stack(full_slip(p["a"], p["b"], p["xi"], p["eta"], p["phi"]), -1)
    return vals


def _node_keys(nodes):
    """Keys identifying physical nodes across grids (inputs rounded to 10 relative digits).

    The creepages are rounded relative to the node's largest one (ξ, η, φc), the semi-axes
    and ν to 10 significant digits: the same table node computed on two grids that share it
    (every other node of a refined axis) gets the same key despite round-off in the axes.
    """
    a, b, nu = (np.asarray(nodes[k], float) for k in ("a", "b", "nu"))
    c = np.sqrt(a * b)
    cr = np.stack([np.asarray(nodes["xi"], float), np.asarray(nodes["eta"], float),
                   np.asarray(nodes["phi"], float) * c], axis=-1)
    scale = np.abs(cr).max(-1, keepdims=True)
    rel = np.round(np.divide(cr, scale, out=np.zeros_like(cr), where=scale > 0), 10) + 0.0
    sig = [np.array([float(f"{v:.10g}") for v in col]) for col in (scale[:, 0], a, b, nu)]
    return [tuple(row) for row in np.column_stack([rel] + sig)]


def _stored(work, elements):
    """Finished results at ``elements`` in every Zarr store of ``work``: {key: (fx, fy, mz)}."""
    import xarray as xr

    done = {}
    mu, load = BUILD_CONTACT["mu"], BUILD_CONTACT["Fn"]
    for store in sorted(Path(work).glob(f"*_e{int(elements)}.zarr")):
        try:
            ds = xr.open_zarr(store)
        except (OSError, ValueError, KeyError):  # unreadable (interrupted at creation): recomputed
            continue
        nodes = {k: ds[k].values for k in ("xi", "eta", "phi", "a", "b", "nu")}
        status = ds["status"].values
        ok = (status != STATUS_CODES["pending"]) & (status != STATUS_CODES["failed"])
        cn = np.sqrt(nodes["a"] * nodes["b"])
        vals = np.stack([ds["Fx"].values / (mu * load), ds["Fy"].values / (mu * load),
                         ds["Mz"].values / (mu * load * cn)], axis=-1)
        ds.close()
        for key, v, good in zip(_node_keys(nodes), vals, ok):
            if good:
                done[key] = v
    return done


def _stage_sweep(nodes, elements, work, workers, executor, progress):
    """The exact solution at ``elements`` on ``nodes``: values (n, 3), NaN where failed.

    Results already in a store of the work directory at the same resolution (of this or
    another grid sharing the node) are reused; the missing nodes are computed by a
    resumable :func:`wheelrail.sweep` into the store ``e<hash>_e<elements>.zarr``.
    """
    work = Path(work)
    keys = _node_keys(nodes)
    done = _stored(work, elements)
    seen = set()
    missing = np.zeros(len(keys), bool)
    for i, k in enumerate(keys):  # r = 0: every θ is the same physical node, computed once
        if k not in done and k not in seen:
            missing[i] = True
            seen.add(k)
    n_comp = 0
    if missing.any():
        sel = {k: np.asarray(nodes[k])[missing] for k in ("xi", "eta", "phi", "a", "b", "nu")}
        tag = hashlib.sha256(np.ascontiguousarray(np.column_stack(
            [sel[k] for k in ("xi", "eta", "phi", "a", "b", "nu")])).tobytes()).hexdigest()[:12]
        store = work / f"n{tag}_e{int(elements)}.zarr"
        E, load, mu = (BUILD_CONTACT[k] for k in ("E", "Fn", "mu"))
        spec = SweepSpec.from_points(sel, method="exact", options={"elements": int(elements)},
                                     Fn=load, mu=mu, E=E, chunk=200)
        ds = sweep(spec, store, workers=workers, executor=executor, resume=store.exists(),
                   progress=progress)
        n_comp = int((ds["status"].values == STATUS_CODES["not_converged"]).sum())
        ds.close()
        done = _stored(work, elements)
    vals = np.array([done.get(k, (np.nan,) * 3) for k in keys], float).reshape(-1, 3)
    return vals, n_comp


def observed_order(f1, f2, f3, N, floor=2e-3):
    """Observed convergence order p of f(N) = f∞ − C N⁻ᵖ from three resolutions.

    For every value whose change f₂ − f₁ exceeds ``floor`` (below it the solver
    tolerance and the element-edge jitter dominate) and that converges
    monotonically (|f₂ − f₁| > |f₃ − f₂|, same sign), p solves
    (f₂ − f₁)/(f₃ − f₂) = (N₁⁻ᵖ − N₂⁻ᵖ)/(N₂⁻ᵖ − N₃⁻ᵖ) on p ∈ [0.3, 3]; the
    median is returned with the number of values used ((1.0, n) when fewer
    than 5 qualify).
    """
    d12, d23 = (f2 - f1).ravel(), (f3 - f2).ravel()
    ok = np.isfinite(d12) & np.isfinite(d23) & (np.abs(d12) > floor)
    ok &= (d12 * d23 > 0) & (np.abs(d12) > np.abs(d23))
    if ok.sum() < 5:
        return 1.0, int(ok.sum())
    N1, N2, N3 = (float(n) for n in N)
    ps = np.linspace(0.3, 3.0, 271)
    q = (N1**-ps - N2**-ps) / (N2**-ps - N3**-ps)     # increasing in p
    ratio = d12[ok] / d23[ok]
    p_each = np.interp(ratio, q, ps)                  # clipped to [0.3, 3] at the ends
    return float(np.median(p_each)), int(ok.sum())


def grid_limit(fs, elements, order=ORDER):
    """Least-squares fit of f(N) = f∞ + C N⁻ᵖ (p = ``order``) to several resolutions: f∞.

    Parameters
    ----------
    fs : sequence of ndarray
        Values at the resolutions ``elements`` (arrays of one shape).
    elements : sequence of int
        The resolutions N (at least two).
    order : float
        Convergence order p.

    Returns
    -------
    ndarray
        f∞, the shape of ``fs[0]``.
    """
    N = np.asarray(elements, float)
    A = np.stack([np.ones_like(N), N**-order], axis=1)
    Y = np.stack([np.asarray(f, float).reshape(-1) for f in fs])
    coef = np.linalg.pinv(A) @ Y
    return coef[0].reshape(np.shape(fs[0]))


def sub_grid(grid, stride):
    """Every ``stride``-th node of ``grid`` along r, θ and s (a/b and ν unchanged)."""
    g = {k: np.asarray(v, float) for k, v in grid.items()}
    if stride == 1:
        return g
    for k in ("r", "theta", "s"):
        if (len(g[k]) - 1) % stride:
            raise ValueError(f"axis {k!r} of {len(g[k])} nodes has no sub-grid of stride {stride}")
        g[k] = g[k][::stride]
    return g


def _refine(v, axis, odd_r=False):
    """Midpoints of a uniform axis by Catmull–Rom cubics: 2n − 1 nodes from n along ``axis``.

    Ghost nodes are quadratic extrapolations; with ``odd_r`` (axis 0 = r, axis 2 = s
    symmetric) the ghost at r = −Δ is minus the node at +Δ with s reversed (the grid
    error, like the force, is odd in the creepages reversed together).
    """
    v = np.moveaxis(v, axis, 0)
    lo = 3.0 * v[0] - 3.0 * v[1] + v[2] if v.shape[0] >= 3 else 2.0 * v[0] - v[1]
    hi = 3.0 * v[-1] - 3.0 * v[-2] + v[-3] if v.shape[0] >= 3 else 2.0 * v[-1] - v[-2]
    if odd_r:
        lo = -v[1][:, ::-1]
    pad = np.concatenate([lo[None], v, hi[None]])
    mid = (9.0 * (pad[1:-2] + pad[2:-1]) - (pad[:-3] + pad[3:])) / 16.0
    out = np.empty((2 * v.shape[0] - 1,) + v.shape[1:])
    out[0::2] = v
    out[1::2] = mid
    return np.moveaxis(out, 0, axis)


def _to_grid(coarse, stride):
    """A full-grid field (all nodes, analytic planes included) of a sub-grid, refined."""
    out = coarse
    while stride > 1:
        for ax in (0, 1, 2):
            out = _refine(out, ax, odd_r=ax == 0)
        stride //= 2
    return out


def exact_limit(case, elements=REFERENCE_ELEMENTS, order=ORDER):
    """The exact theory's grid limit at one contact: the reference of the table law.

    The exact solver (:class:`wheelrail.tangential.exact.Exact`) at each resolution of
    ``elements``, and the least-squares fit f∞ + C N⁻ᵖ (:func:`grid_limit`).

    Parameters
    ----------
    case : TableCase
        A contact and creepages (:func:`wheelrail.tangential.table.random_cases`).
    elements : sequence of int
        Resolutions (elements across the contact).
    order : float
        Convergence order p.

    Returns
    -------
    limit : ndarray, shape (3,)
        Fx, Fy [N], Mz [N m] extrapolated.
    each : ndarray, shape (len(elements), 3)
        The solutions at each resolution.
    """
    each = []
    for n in elements:
        r = Exact(elements=int(n)).solve(case.contact, *case.creepage, case.mu)
        each.append([float(r.Fx), float(r.Fy), float(r.Mz)])
    each = np.array(each)
    return grid_limit(list(each), elements, order), each


def assemble_table(grid, elements, main, others, nus, *, extrapolation_stride=1, nu_stride=1,
                   order=ORDER):
    """Table values from the resolutions (see the module docstring).

    Parameters
    ----------
    grid : dict
        The node grid (:data:`GRID`).
    elements : sequence of int
        Resolutions (N₁, …, N_k); ``main`` is at N_m, m = k − 1 (the last but one).
    main : ndarray
        (fx, fy, mz) at N_m on every computed node at the first ν, shape
        (n_r, n_θ, n_s, n_ab, 1, 3).
    others : list of ndarray
        At every resolution N₁ … N_k (N_m included), the first ν, on the computed nodes of
        the sub-grid of stride ``extrapolation_stride`` (:func:`sub_grid`).
    nus : ndarray or None
        At N_m, every ν, on the computed nodes of the sub-grid of stride ``nu_stride``.
    extrapolation_stride, nu_stride : int
        Strides (1, 2, 4, …) of those sub-grids along r, θ, s.
    order : float
        Convergence order p of the fit (:func:`grid_limit`).

    Returns
    -------
    values : ndarray
        The full table (analytic planes included).
    info : dict
        Observed order, largest extrapolation step, failed-node count.
    """
    g = {k: np.asarray(v, float) for k, v in grid.items()}
    comp = [_computed(g[k], k) for k in AXES]
    vals = _analytic_values(g)
    full_idx = np.ix_(*(np.flatnonzero(m) for m in comp))
    n_nu = len(g["nu"])
    info = {"failed": int(np.isnan(main).any(-1).sum())}

    def on_sub(field, stride, nu):
        """A field on the sub-grid's computed nodes -> every computed node of the grid
        (zero on the analytic planes: no grid error there; the ν difference is analytic)."""
        gs = sub_grid(dict(g, nu=nu), stride)
        cs = [_computed(gs[k], k) for k in AXES]
        full = np.zeros(tuple(len(gs[k]) for k in AXES) + (3,))
        full[np.ix_(*(np.flatnonzero(m) for m in cs))] = np.where(np.isfinite(field), field, 0.0)
        return _to_grid(full, stride)[np.ix_(*(np.flatnonzero(m) for m in comp[:4]), [0])]

    value = np.repeat(main, n_nu, axis=4)
    if n_nu > 1 and nus is not None:
        an = _analytic_values(sub_grid(g, nu_stride))
        gs = sub_grid(g, nu_stride)
        cs = [_computed(gs[k], k) for k in AXES]
        full = an - an[..., :1, :]
        diff = nus - nus[..., :1, :]
        full[np.ix_(*(np.flatnonzero(m) for m in cs))] = np.where(np.isfinite(diff), diff, 0.0)
        full = np.where(np.isfinite(full), full, 0.0)
        value = value + _to_grid(full, nu_stride)[full_idx]
        info["max_nu_difference"] = float(np.abs(diff[np.isfinite(diff)]).max())
    if len(elements) > 1:
        m = len(elements) - 2 if len(elements) > 2 else len(elements) - 1
        if len(elements) >= 3:
            p, used = observed_order(*others[-3:], elements[-3:])
            info["observed_order"] = {"p": p, "values": used, "elements": list(elements[-3:])}
        step = grid_limit(others, elements, order) - others[m]
        info["order"] = order
        info["max_extrapolation_step"] = float(np.nanmax(np.abs(step)))
        value = value + on_sub(step, extrapolation_stride, g["nu"][:1])
    vals[full_idx] = value
    return vals, info


def replace_first_plane(vals, grid, limit):
    """``vals`` with the plane r = Δr replaced by ``limit`` at the first ν, the other ν
    shifted by the same change (their difference to the first ν kept).

    ``limit`` has the shape of the plane's computed nodes, (1, n_θ, n_s − 2, n_ab, 1, 3).
    Returns the new values and the largest change (fraction of μFn).
    """
    s_in = np.flatnonzero(_computed(np.asarray(grid["s"], float), "s"))
    s_sl = slice(int(s_in[0]), int(s_in[-1]) + 1)  # |s| < 1: the interior nodes
    vals = np.array(vals, copy=True)
    new = limit[0, :, :, :, 0, :]
    change = np.where(np.isfinite(new), new - vals[1, :, s_sl, :, 0, :], 0.0)
    vals[1, :, s_sl] += change[:, :, :, None, :]
    return vals, float(np.abs(change).max())


def _fill_failed(vals):
    """Failed nodes (NaN) from the mean of their finite neighbours along r (then θ)."""
    bad = np.isnan(vals)
    n = int(bad.any(-1).sum())
    for ax in (0, 1, 2):
        if not np.isnan(vals).any():
            break
        lo = np.roll(vals, 1, axis=ax)
        hi = np.roll(vals, -1, axis=ax)
        fill = np.nanmean(np.stack([lo, hi]), axis=0)
        vals = np.where(np.isnan(vals), fill, vals)
    return vals, n


def build_table(out=DEFAULT_TABLE, *, elements=ELEMENTS, workers=2, work=None, executor=None,
                progress=True, grid=None, keep_work=False, order=ORDER,
                extrapolation_stride=EXTRAPOLATION_STRIDE, nu_stride=NU_STRIDE,
                first_plane_elements=FIRST_PLANE_ELEMENTS,
                refined_regions=REFINED_REGIONS,
                theta_end_regions=THETA_END_REGIONS,
                r_start_regions=R_START_REGIONS) -> Path:
    """Compute the table with the exact solver (resumable :func:`wheelrail.sweep` runs) and save it.

    Parameters
    ----------
    out : path
        The ``.npz`` file to write.
    elements : int or sequence of int
        Exact-solver elements across the contact (N₁, …, N_k): the last but one on every
        node at the first ν, all of them on a sub-grid for the grid limit (module
        docstring). One value: no extrapolation.
    workers : int
        Local workers of the sweeps (Dask ``LocalCluster``).
    work : path, optional
        Directory of the Zarr work stores (default ``<out>.work``); an
        interrupted build resumes from it, and nodes already computed at a
        resolution by an earlier build (also on another grid) are reused;
        deleted when ``out`` is written unless ``keep_work``.
    executor : str, optional
        Executor of the sweeps (default: serial for 1 worker, Dask otherwise).
    grid : dict, optional
        Another node grid (tests use small ones); default :data:`GRID`.
    order : float
        Convergence order p of the grid-limit fit.
    extrapolation_stride, nu_stride : int
        Strides (1, 2, 4, …) along r, θ, s of the sub-grids of the grid-limit fit and of
        the other Poisson's ratios (1: every node).
    first_plane_elements : sequence of int, optional
        Resolutions of a separate grid-limit fit on the plane r = Δr at the first ν
        (:data:`FIRST_PLANE_ELEMENTS`); the other ν keep their difference to it. Empty
        or None, or a single resolution in ``elements`` (no extrapolation): that plane
        is treated like the others.
    refined_regions : sequence of dict, optional
        Regions recomputed on every ν with the fit to ``first_plane_elements``
        (:func:`refine_regions`; default :data:`REFINED_REGIONS`).
    theta_end_regions : sequence of dict, optional
        Regions whose last θ nodes are fitted (:func:`fit_theta_end`; default
        :data:`THETA_END_REGIONS`).
    r_start_regions : sequence of dict, optional
        Regions whose first r cell is fitted (:func:`fit_r_start`; default
        :data:`R_START_REGIONS`).

    Returns
    -------
    Path
        ``out``.
    """
    grid = {k: np.asarray(v, float) for k, v in (GRID if grid is None else grid).items()}
    elements = tuple(int(e) for e in np.atleast_1d(elements))
    out = Path(out)
    work = Path(work) if work is not None else out.with_name(out.name + ".work")
    work.mkdir(parents=True, exist_ok=True)
    if len(elements) != len(set(elements)):
        raise ValueError(f"elements must be distinct resolutions, got {elements}")
    m = len(elements) - 2 if len(elements) > 2 else len(elements) - 1
    first = dict(grid, nu=grid["nu"][:1])
    not_conv = 0

    def stage(g, n):
        nonlocal not_conv
        nodes = table_nodes(g)
        v, nc = _stage_sweep(nodes, n, work, workers, executor, progress)
        not_conv += nc
        return v.reshape(*nodes["shape"], 3)

    main = stage(first, elements[m])
    nus = stage(sub_grid(grid, nu_stride), elements[m]) if len(grid["nu"]) > 1 else None
    others = ([stage(sub_grid(first, extrapolation_stride), n) for n in elements]
              if len(elements) > 1 else [])
    vals, info = assemble_table(grid, elements, main, others, nus,
                                extrapolation_stride=extrapolation_stride, nu_stride=nu_stride,
                                order=order)
    plane_els = tuple(int(e) for e in (first_plane_elements or ()))
    if plane_els and len(elements) > 1 and len(grid["r"]) > 2:
        plane = dict(grid, r=grid["r"][1:2], nu=grid["nu"][:1])
        fs = [stage(plane, n) for n in plane_els]
        vals, change = replace_first_plane(vals, grid, grid_limit(fs, plane_els, order))
        info["first_plane"] = {"elements": list(plane_els), "max_change": change}
    if plane_els and len(elements) > 1 and refined_regions:
        vals, info["refined_regions"] = refine_regions(
            vals, grid, refined_regions, plane_els, stage=stage, order=order)
    if plane_els and len(elements) > 1 and theta_end_regions:
        vals, info["theta_end_fit"] = fit_theta_end(
            vals, grid, theta_end_regions, plane_els, stage=stage, order=order)
    if plane_els and len(elements) > 1 and r_start_regions:
        vals, info["r_start_fit"] = fit_r_start(
            vals, grid, r_start_regions, plane_els, stage=stage, order=order)
    vals, n_failed = _fill_failed(vals)
    meta = {"version": TABLE_VERSION, "wheelrail_version": __version__,
            "method": "exact", "elements": list(elements), "order": order,
            "extrapolation_stride": int(extrapolation_stride), "nu_stride": int(nu_stride),
            "first_plane_elements": list(plane_els),
            "build_contact": BUILD_CONTACT, "not_converged_nodes": not_conv,
            "failed_nodes_filled": n_failed, "extrapolation": info, "axes": list(AXES),
            "quantities": ["Fx/(mu Fn)", "Fy/(mu Fn)", "Mz/(mu Fn c)"]}
    tmp = out.with_name(out.name + ".tmp.npz")
    np.savez_compressed(tmp, values=vals.astype(np.float32), meta=json.dumps(meta),
                        **{k: grid[k] for k in AXES})
    tmp.replace(out)
    if not keep_work:
        shutil.rmtree(work, ignore_errors=True)
    return out


def _region_index(grid, region):
    """Node indices (r, θ, s, a/b, ν) of the computed nodes of ``region`` (inclusive bounds
    on r, |s| and a/b; every θ and ν)."""
    eps = 1e-9
    r, s, lab = (np.asarray(grid[k], float) for k in ("r", "s", "log_ab"))
    r_lo, r_hi = region.get("r", (0.0, 1.0))
    s_lo, s_hi = region.get("s_abs", (0.0, 1.0))
    ab_lo, ab_hi = region.get("aspect", (np.exp(lab[0]), np.exp(lab[-1])))
    ir = np.flatnonzero((r >= r_lo - eps) & (r <= r_hi + eps) & (r < 1.0))
    i_s = np.flatnonzero((np.abs(s) >= s_lo - eps) & (np.abs(s) <= s_hi + eps)
                         & (np.abs(s) < 1.0))
    il = np.flatnonzero((lab >= np.log(ab_lo) - eps) & (lab <= np.log(ab_hi) + eps))
    return (ir, np.arange(len(grid["theta"])), i_s, il, np.arange(len(grid["nu"])))


def refine_regions(vals, grid, regions, elements, *, stage, order=ORDER):
    """``vals`` with the nodes of ``regions`` replaced by the grid limit of ``elements``.

    Parameters
    ----------
    vals : ndarray, shape (n_r, n_θ, n_s, n_ab, n_ν, 3)
        The table's values.
    grid : dict
        Its node axes.
    regions : sequence of dict
        Inclusive bounds ``r``, ``s_abs`` (|s|), ``aspect`` (a/b) of each region; every θ
        and ν of the grid (:data:`REFINED_REGIONS`).
    elements : sequence of int
        Resolutions of the fit (:func:`grid_limit`, order ``order``).
    stage : callable
        ``stage(grid, n)``: the exact solution at ``n`` elements on the computed nodes
        of a sub-grid, shape (…, 3) (the resumable sweeps of :func:`build_table`).

    Returns
    -------
    vals : ndarray
        The new values.
    info : list of dict
        Per region: its bounds, node count and largest change (fraction of μFn).
    """
    vals = np.array(vals, copy=True)
    info = []
    for region in regions:
        idx = _region_index(grid, region)
        if any(len(i) == 0 for i in idx):
            continue
        sub = {k: np.asarray(grid[k], float)[i] for k, i in zip(AXES, idx)}
        lim = grid_limit([stage(sub, n) for n in elements], elements, order)
        sel = np.ix_(*idx)
        change = np.where(np.isfinite(lim), lim - vals[sel], 0.0)
        vals[sel] = vals[sel] + change
        info.append({**{k: list(v) for k, v in region.items()},
                     "nodes": int(np.prod([len(i) for i in idx])),
                     "elements": list(elements), "max_change": float(np.abs(change).max())})
    return vals, info


def refine_table(path=DEFAULT_TABLE, *, regions=REFINED_REGIONS,
                 elements=FIRST_PLANE_ELEMENTS, workers=2, work=None, executor=None,
                 progress=True, keep_work=False, out=None, order=ORDER,
                 theta_end_regions=THETA_END_REGIONS,
                 r_start_regions=R_START_REGIONS) -> Path:
    """Recompute the nodes of ``regions`` of an existing table (:func:`refine_regions`)
    and fit the θ ends of ``theta_end_regions`` (:func:`fit_theta_end`) and the first r
    cell of ``r_start_regions`` (:func:`fit_r_start`).

    The rest of the table is kept as it is; ``meta["extrapolation"]["refined_regions"]``
    records the regions. The sweeps are those of :func:`build_table` (resumable Zarr
    stores in ``work``, default ``<out>.work``).

    Returns
    -------
    Path
        The table written (``out``, default ``path``).
    """
    path = Path(path)
    out = path if out is None else Path(out)
    work = Path(work) if work is not None else out.with_name(out.name + ".work")
    work.mkdir(parents=True, exist_ok=True)
    with np.load(path, allow_pickle=False) as f:
        grid = {k: np.asarray(f[k], float) for k in AXES}
        vals = np.asarray(f["values"], float)
        meta = json.loads(str(f["meta"]))

    def stage(g, n):
        nodes = table_nodes(g)
        v, nc = _stage_sweep(nodes, n, work, workers, executor, progress)
        meta["not_converged_nodes"] = meta.get("not_converged_nodes", 0) + nc
        return v.reshape(*nodes["shape"], 3)

    vals, info = refine_regions(vals, grid, regions, tuple(int(e) for e in elements),
                                stage=stage, order=order)
    meta.setdefault("extrapolation", {})["refined_regions"] = info
    if theta_end_regions:
        vals, info = fit_theta_end(vals, grid, theta_end_regions,
                                   tuple(int(e) for e in elements), stage=stage, order=order)
        meta["extrapolation"]["theta_end_fit"] = info
    if r_start_regions:
        vals, info = fit_r_start(vals, grid, r_start_regions,
                                 tuple(int(e) for e in elements), stage=stage, order=order)
        meta["extrapolation"]["r_start_fit"] = info
    tmp = out.with_name(out.name + ".tmp.npz")
    np.savez_compressed(tmp, values=vals.astype(np.float32), meta=json.dumps(meta),
                        **{k: grid[k] for k in AXES})
    tmp.replace(out)
    if not keep_work:
        shutil.rmtree(work, ignore_errors=True)
    return out


def _bspline_row(t):
    """Weights of the 4 coefficients of a uniform cubic B-spline at fraction t of a cell."""
    u = 1.0 - t
    return np.array([u**3, 3 * t**3 - 6 * t**2 + 4, -3 * t**3 + 3 * t**2 + 3 * t + 1, t**3]) / 6


def fit_theta_end(vals, grid, regions, elements, *, stage, order=ORDER):
    """``vals`` with the last three θ nodes of ``regions`` least-squares fitted.

    On each line along θ of a region (every r, s, a/b node of it, first ν) the
    exact grid limit of ``elements`` is computed at the last three θ nodes and at the
    midpoint of the last cell; the line's nine values (in the frame of the full-slip
    direction, as the table law interpolates them) are then the least-squares fit
    of the table's not-a-knot cubic spline to the nine nodes (the new exact values
    at the last three) and the midpoint. The other ν is shifted by the same change.

    Parameters and returns as :func:`refine_regions`.
    """
    from ..tangential.table import _spline_operator

    vals = np.array(vals, copy=True)
    g = {k: np.asarray(v, float) for k, v in grid.items()}
    th = g["theta"]
    n = len(th)
    mid = 0.5 * (th[-2] + th[-1])
    op = _spline_operator(n)
    M = np.zeros((n + 1, n + 2))
    for i in range(n):
        M[i, i:i + 3] = (1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0)
    M[n, n - 2:n + 2] = _bspline_row(0.5)
    A = M @ op
    info = []
    for region in regions:
        ir, _, i_s, il, _ = _region_index(g, region)
        if len(ir) == 0 or len(i_s) == 0 or len(il) == 0:
            continue
        t_new = np.array([th[-3], th[-2], mid, th[-1]])
        sub = {"r": g["r"][ir], "theta": t_new, "s": g["s"][i_s], "log_ab": g["log_ab"][il],
               "nu": g["nu"][:1]}
        lim = grid_limit([stage(sub, e) for e in elements], elements, order)[..., 0, :]
        # targets (nr, nθ + 1, ns, nab, 3), global frame
        old = vals[np.ix_(ir, np.arange(n), i_s, il, [0])][..., 0, :]
        tgt = np.concatenate([old, lim[:, 2:3]], axis=1)
        tgt[:, n - 3:n] = np.where(np.isfinite(lim[:, [0, 1, 3]]), lim[:, [0, 1, 3]],
                                   old[:, n - 3:n])
        if not np.all(np.isfinite(tgt[:, n])):
            tgt[:, n] = np.where(np.isfinite(tgt[:, n]), tgt[:, n], np.nan)
        T = np.concatenate([th, [mid]])
        C11, C22, _ = _coefficients(np.exp(g["log_ab"][il]), g["nu"][0])
        al = np.arctan2(np.sin(T)[:, None] / C22[None, :], np.cos(T)[:, None] / C11[None, :])
        ca, sa = np.cos(al)[None, :, None, :], np.sin(al)[None, :, None, :]
        loc = np.stack([tgt[..., 0] * ca + tgt[..., 1] * sa, -tgt[..., 0] * sa + tgt[..., 1] * ca,
                        tgt[..., 2]], axis=-1)
        Y = np.moveaxis(loc, 1, 0).reshape(n + 1, -1)
        ok = np.all(np.isfinite(Y), axis=0)
        fit = np.moveaxis(loc[:, :n], 1, 0).reshape(n, -1).copy()
        fit[:, ok] = np.linalg.lstsq(A, Y[:, ok], rcond=None)[0]
        fit = np.moveaxis(fit.reshape((n,) + loc.shape[:1] + loc.shape[2:]), 0, 1)
        c0, s0 = ca[:, :n], sa[:, :n]
        new = np.stack([fit[..., 0] * c0 - fit[..., 1] * s0, fit[..., 0] * s0 + fit[..., 1] * c0,
                        fit[..., 2]], axis=-1)
        change = new - old
        sel = np.ix_(ir, np.arange(n), i_s, il, np.arange(len(g["nu"])))
        vals[sel] = vals[sel] + change[:, :, :, :, None, :]
        info.append({**{k: list(v) for k, v in region.items()}, "lines": int(ok.sum()) // 3,
                     "elements": list(elements), "max_change": float(np.abs(change).max())})
    return vals, info


def fit_r_start(vals, grid, regions, elements, *, stage, order=ORDER):
    """``vals`` with the lines along r of ``regions`` fitted to the first cell's midpoint.

    On each line along r (every θ and the region's s and a/b nodes, first ν) the exact
    grid limit of ``elements`` is computed at r = Δr/2; the line's values at
    0 < r < 1 become the least-squares fit of the table's not-a-knot cubic spline to the
    line's nodes and that midpoint (r = 0, the same contact for every θ, and the
    analytic r = 1 are kept). The direction of the full-slip force does not change along
    r, so the fit is done on (fx, fy, mz) directly. The other ν is shifted by the same
    change.

    Parameters and returns as :func:`refine_regions`.
    """
    from ..tangential.table import _spline_operator

    vals = np.array(vals, copy=True)
    g = {k: np.asarray(v, float) for k, v in grid.items()}
    r = g["r"]
    n = len(r)
    op = _spline_operator(n)
    M = np.zeros((n + 1, n + 2))
    for i in range(n):
        M[i, i:i + 3] = (1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0)
    M[n, 0:4] = _bspline_row(0.5)
    A = M @ op
    free = np.flatnonzero((r > 0.0) & (r < 1.0))
    fixed = np.flatnonzero(~((r > 0.0) & (r < 1.0)))
    info = []
    for region in regions:
        _, _, i_s, il, _ = _region_index(g, dict(region, r=(0.0, 1.0)))
        if len(i_s) == 0 or len(il) == 0:
            continue
        sub = {"r": np.array([0.5 * r[1]]), "theta": g["theta"], "s": g["s"][i_s],
               "log_ab": g["log_ab"][il], "nu": g["nu"][:1]}
        lim = grid_limit([stage(sub, e) for e in elements], elements, order)[0, ..., 0, :]
        sel0 = np.ix_(np.arange(n), np.arange(len(g["theta"])), i_s, il, [0])
        old = vals[sel0][..., 0, :]                       # (n, θ, s, ab, 3)
        Y = np.concatenate([old, lim[None]], axis=0).reshape(n + 1, -1)
        ok = np.all(np.isfinite(Y), axis=0)
        fit = old.reshape(n, -1).copy()
        rhs = Y[:, ok] - A[:, fixed] @ fit[fixed][:, ok]
        fit[np.ix_(free, np.flatnonzero(ok))] = np.linalg.lstsq(A[:, free], rhs, rcond=None)[0]
        change = fit.reshape(old.shape) - old
        sel = np.ix_(np.arange(n), np.arange(len(g["theta"])), i_s, il,
                     np.arange(len(g["nu"])))
        vals[sel] = vals[sel] + change[:, :, :, :, None, :]
        info.append({**{k: list(v) for k, v in region.items()}, "lines": int(ok.sum()) // 3,
                     "elements": list(elements), "max_change": float(np.abs(change).max())})
    return vals, info
