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
observed p ≈ 1.0–1.1, with a large constant where spin and creepage combine
and for elongated patches: with 36 elements a patch with a/b = 20 is still up
to ≈ 4 % of μFn from its limit, a spin-dominated one with a/b = 1.6 ≈ 2.5 %).
The table is therefore built from grid-extrapolated values. With
``elements = (N₁, N₂, N₃)``:

* every node (r, θ, s, a/b) is computed with N₁ at the first Poisson's ratio
  of the grid, and with N₂ at every ν;
* a sub-grid (every ``fine_every``-th node along r, θ, s and a/b, every ν) is
  also computed with N₃;
* the observed order p is fitted from the three resolutions on the sub-grid
  (f₂ − f₁)/(f₃ − f₂) = (N₁⁻ᵖ − N₂⁻ᵖ)/(N₂⁻ᵖ − N₃⁻ᵖ) (:func:`observed_order`;
  per a/b node where at least 50 values resolve it, else pooled);
* every node is Richardson-extrapolated from N₁ and N₂,
  f∞ = f₂ + (f₂ − f₁)/((N₂/N₁)ᵖ − 1), the grid error f₂ − f₁ of the first ν
  standing for the other ν's (the effect of ν on the discretisation error is
  below the solver's jitter).

Every stage is its own Zarr sweep store under the work directory, so an
interrupted build resumes where it stopped (``wheelrail build-table`` again
with the same arguments); Dask ``LocalCluster`` workers with ``workers > 1``.

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

import json
import shutil
from pathlib import Path

import numpy as np

from .._version import __version__
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
    "GRID",
    "assemble_table",
    "build_table",
    "table_nodes",
]

#: Node grid of the table (version 2). r = ρ̂/(1 + |φ̂| + ρ̂) (r = 1 analytic), θ,
#: s = φ̂/(1 + |φ̂|) (s = ±1 analytic), ln(a/b) for a/b in [0.05, 20], ν.
GRID = {
    "r": np.linspace(0.0, 1.0, 11),
    "theta": np.linspace(0.0, 0.5 * np.pi, 5),
    "s": np.linspace(-1.0, 1.0, 11),
    "log_ab": np.log(np.geomspace(0.05, 20.0, 9)),
    "nu": np.array([0.25, 0.30]),
}
#: Exact-solver resolutions: the base (every node) and the finer ones (sub-grid).
ELEMENTS = (16, 24, 36)
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


def _stage_sweep(nodes, elements, work, workers, executor, progress):
    """One resolution over ``nodes`` (resumable Zarr store ``work``); values (n, 3)."""
    E, load, mu = (BUILD_CONTACT[k] for k in ("E", "Fn", "mu"))
    spec = SweepSpec.from_points({k: nodes[k] for k in ("xi", "eta", "phi", "a", "b", "nu")},
                                 method="exact", options={"elements": int(elements)}, Fn=load,
                                 mu=mu, E=E, chunk=200)
    ds = sweep(spec, work, workers=workers, executor=executor, resume=work.exists(),
               progress=progress)
    status = ds["status"].values
    cn = np.sqrt(nodes["a"] * nodes["b"])
    vals = np.stack([ds["Fx"].values / (mu * load), ds["Fy"].values / (mu * load),
                     ds["Mz"].values / (mu * load * cn)], axis=-1)
    bad = (status == STATUS_CODES["pending"]) | (status == STATUS_CODES["failed"])
    vals[bad] = np.nan
    ds.close()
    return vals, status


def _sub_index(n, every, name):
    """Indices of the sub-grid along an axis of n computed nodes (ends included)."""
    if every == 1 or name == "nu" or n <= 2:
        return np.arange(n)
    idx = np.arange(0, n, every)
    if name != "r" and idx[-1] != n - 1:  # keep the far end (r: 0.95 lies next to r = 1)
        idx = np.append(idx, n - 1)
    return idx


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


def assemble_table(grid, elements, base, fine, fine_every=2):
    """Table values from the three resolutions (see the module docstring).

    Parameters
    ----------
    grid : dict
        The node grid (:data:`GRID`).
    elements : sequence of int
        Resolutions (N₁, N₂, N₃) or (N₁,).
    base : ndarray
        (fx, fy, mz) of the computed nodes at N₁ and the first ν, shape
        (n_r, n_θ, n_s, n_ab, 1, 3) (every ν for one resolution).
    fine : list of ndarray
        At N₂ every computed node and ν, shape (n_r, n_θ, n_s, n_ab, n_ν, 3);
        at N₃ the sub-grid's nodes (every ν).
    fine_every : int
        Sub-grid stride of N₃.

    Returns
    -------
    values : ndarray
        The full table (analytic planes included).
    info : dict
        Fitted orders, largest extrapolation step, failed-node count.
    """
    g = {k: np.asarray(v, float) for k, v in grid.items()}
    comp = [_computed(g[k], k) for k in AXES]
    sub = [_sub_index(int(m.sum()), fine_every, k) for m, k in zip(comp, AXES)]
    vals = _analytic_values(g)
    full_idx = np.ix_(*(np.flatnonzero(m) for m in comp))
    info = {"failed_base": int(np.isnan(base).any(-1).sum())}
    if len(elements) == 1 or not fine:
        vals[full_idx] = base
        return vals, info
    f2_all, f3 = fine
    f1 = base[np.ix_(*sub[:4], [0])]
    f2 = f2_all[np.ix_(*sub)]
    orders = []
    pooled, n_pooled = observed_order(f1[..., 0, :], f2[..., 0, :], f3[..., 0, :],
                                      elements[:3])
    info["order_pooled"] = {"p": pooled, "values": n_pooled}
    step = np.empty_like(base)
    for j in range(len(g["log_ab"])):
        js = np.flatnonzero(sub[3] == j)
        p, used = (observed_order(f1[:, :, :, js[0], 0], f2[:, :, :, js[0], 0],
                                  f3[:, :, :, js[0], 0], elements[:3])
                   if js.size else (pooled, 0))
        if used < 50:  # too few values resolve the order at this a/b: the pooled one
            p = pooled
        orders.append({"a/b": float(np.exp(g["log_ab"][j])), "p": p, "values": used})
        ratio = (elements[1] / elements[0]) ** p - 1.0
        step[:, :, :, j] = (f2_all[:, :, :, j, :1] - base[:, :, :, j]) / ratio
    step = np.where(np.isfinite(step), step, 0.0)
    info["orders"] = orders
    info["max_extrapolation_step"] = float(np.abs(step).max())
    vals[full_idx] = f2_all + step  # the first nu's grid error for every nu
    return vals, info


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


def build_table(out=DEFAULT_TABLE, *, elements=ELEMENTS, fine_every=2, workers=2, work=None,
                executor=None, progress=True, grid=None, keep_work=False) -> Path:
    """Compute the table with the exact solver (resumable :func:`wheelrail.sweep` runs) and save it.

    Parameters
    ----------
    out : path
        The ``.npz`` file to write.
    elements : int or sequence of int
        Exact-solver elements across the contact: (N₁, N₂, N₃), N₁ and N₂ on
        every node (N₁ at the first ν), N₃ on the sub-grid for the observed
        order (module docstring); one value: no extrapolation.
    fine_every : int
        Stride of the sub-grid of N₃ along r, θ, s and a/b (1: every node).
    workers : int
        Local workers of the sweeps (Dask ``LocalCluster``).
    work : path, optional
        Directory of the Zarr work stores (default ``<out>.work``); an
        interrupted build resumes from it; deleted when ``out`` is written
        unless ``keep_work``.
    executor : str, optional
        Executor of the sweeps (default: serial for 1 worker, Dask otherwise).
    grid : dict, optional
        Another node grid (tests use small ones); default :data:`GRID`.

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
    if len(elements) not in (1, 3):
        raise ValueError(f"elements must be one resolution or three (base, two finer), "
                         f"got {elements}")
    g_base = dict(grid, nu=grid["nu"] if len(elements) == 1 else grid["nu"][:1])
    nodes = table_nodes(g_base)
    base, st = _stage_sweep(nodes, elements[0], work / f"all_e{elements[0]}.zarr", workers,
                            executor, progress)
    base = base.reshape(*nodes["shape"], 3)
    not_conv = int((st == STATUS_CODES["not_converged"]).sum())
    fine = []
    if len(elements) > 1:
        nodes2 = table_nodes(grid)
        v, s_ = _stage_sweep(nodes2, elements[1], work / f"all_e{elements[1]}.zarr", workers,
                             executor, progress)
        fine.append(v.reshape(*nodes2["shape"], 3))
        not_conv += int((s_ == STATUS_CODES["not_converged"]).sum())
        comp = [_computed(grid[k], k) for k in AXES]
        sub = [_sub_index(int(m.sum()), fine_every, k) for m, k in zip(comp, AXES)]
        gsub = {k: grid[k][np.flatnonzero(m)[s]] for k, m, s in zip(AXES, comp, sub)}
        snodes = table_nodes(gsub)
        v, s_ = _stage_sweep(snodes, elements[2], work / f"sub{fine_every}_e{elements[2]}.zarr",
                             workers, executor, progress)
        fine.append(v.reshape(*snodes["shape"], 3))
        not_conv += int((s_ == STATUS_CODES["not_converged"]).sum())
    vals, info = assemble_table(grid, elements, base, fine, fine_every)
    vals, n_failed = _fill_failed(vals)
    meta = {"version": TABLE_VERSION, "wheelrail_version": __version__,
            "method": "exact", "elements": list(elements), "fine_every": int(fine_every),
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
