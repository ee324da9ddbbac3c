"""Building the creep-force table of :class:`wheelrail.tangential.Table` with the exact solver.

The nodes of the table (its axes: :data:`wheelrail.tangential.table.AXES`) are
turned into physical contacts and creepages (:func:`table_nodes`), computed
by a resumable :func:`wheelrail.sweep` with the exact theory, scaled back and
written with the analytic full-slip plane r = 1 (:func:`build_table`). The
command line is ``wheelrail build-table``.

References
----------
.. [1] J.J. Kalker, Book of tables for the Hertzian creep-force law, in:
   I. Zobory (ed.), Proc. 2nd Mini Conf. on Contact Mechanics and Wear of
   Wheel/Rail Systems, Budapest, 1996, 11-20.
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np

from .._version import __version__
from ..tangential.table import AXES, DEFAULT_TABLE, TABLE_VERSION, _coefficients, _spin_length
from .evaluators import STATUS_CODES
from .run import sweep
from .spec import SweepSpec

__all__ = ["build_table", "table_nodes", "GRID", "BUILD_CONTACT"]

#: Node grid of the table (version 1). r = ρ̂/(1+ρ̂) (r = 1 analytic), θ, s = φ̂/(1+|φ̂|),
#: ln(a/b), ν.
GRID = {
    "r": np.concatenate([np.linspace(0.0, 0.6, 16), np.linspace(0.64, 0.96, 9), [1.0]]),
    "theta": np.linspace(0.0, 0.5 * np.pi, 11),
    "s": np.linspace(-0.8, 0.8, 21),
    "log_ab": np.log(np.geomspace(0.2, 5.0, 7)),
    "nu": np.array([0.25, 0.30]),
}
#: Parameters of the physical contacts on which the nodes are computed (any
#: values give the same dimensionless result, by similarity).
BUILD_CONTACT = {"E": 2.1e11, "Fn": 1.0e4, "mu": 0.3, "c": 5.0e-3}


def table_nodes(grid=None) -> dict:
    """Physical inputs of the table's computed nodes (all but the analytic r = 1 plane).

    Returns
    -------
    dict
        ``shape`` (the node grid without r = 1) and columns ``xi, eta`` [-],
        ``phi`` [1/m], ``a, b`` [m], ``nu`` [-] in C order of
        (r, θ, s, a/b, ν); the contact has ``E``, ``Fn``, ``mu`` of
        :data:`BUILD_CONTACT`.
    """
    g = dict(GRID if grid is None else grid)
    r = g["r"][g["r"] < 1.0]
    R, T, S, L, N = np.meshgrid(r, g["theta"], g["s"], g["log_ab"], g["nu"], indexing="ij")
    shape = R.shape
    R, T, S, L, N = (v.reshape(-1) for v in (R, T, S, L, N))
    ab = np.exp(L)
    C11, C22, C23 = _coefficients(ab, N)
    c, E, load, mu = (BUILD_CONTACT[k] for k in ("c", "E", "Fn", "mu"))
    G = E / (2.0 * (1.0 + N))
    b = c / np.sqrt(ab)
    spin_len = _spin_length(c, b, C11, C23)
    phi_hat = S / (1.0 - np.abs(S))
    rho = (1.0 + np.abs(phi_hat)) * R / (1.0 - R)
    unit = 3.0 * mu * load / G
    eta_hat = rho * np.sin(T) - phi_hat * c * C23 / spin_len  # θ: direction of (ξ̂, η̂ + φ̂_y)
    return {"shape": shape, "xi": rho * np.cos(T) * unit / (c**2 * C11),
            "eta": eta_hat * unit / (c**2 * C22),
            "phi": phi_hat * unit / (c**2 * spin_len),
            "a": c * np.sqrt(ab), "b": c / np.sqrt(ab), "nu": N}


def _full_slip_plane(grid):
    """fx, fy, mz at r = 1: F = −μFn along the physical creepage direction, Mz = 0."""
    T, S, L, N = np.meshgrid(grid["theta"], grid["s"], grid["log_ab"], grid["nu"], indexing="ij")
    C11, C22, _ = _coefficients(np.exp(L), N)
    alpha = np.arctan2(np.sin(T) / C22, np.cos(T) / C11)
    return np.stack([-np.cos(alpha), -np.sin(alpha), np.zeros_like(alpha)], axis=-1)


def build_table(out=DEFAULT_TABLE, *, elements=40, workers=2, work=None, executor=None,
                progress=True, grid=None) -> Path:
    """Compute the table with the exact solver (a resumable :func:`wheelrail.sweep`) and save it.

    Parameters
    ----------
    out : path
        The ``.npz`` file to write.
    elements : int
        Elements across the contact of the exact solver.
    workers : int
        Local workers of the sweep.
    work : path, optional
        Zarr work store (default ``<out>.zarr``); an interrupted build resumes
        from it; it is deleted when ``out`` is written.
    executor : str, optional
        Executor of the sweep (default: serial for 1 worker, Dask otherwise).
    grid : dict, optional
        Another node grid (tests use small ones); default :data:`GRID`.

    Returns
    -------
    Path
        ``out``.
    """
    grid = {k: np.asarray(v, float) for k, v in (GRID if grid is None else grid).items()}
    out = Path(out)
    work = Path(work) if work is not None else out.with_name(out.name + ".zarr")
    nodes = table_nodes(grid)
    c, E, load, mu = (BUILD_CONTACT[k] for k in ("c", "E", "Fn", "mu"))
    spec = SweepSpec.from_points({k: nodes[k] for k in ("xi", "eta", "phi", "a", "b", "nu")},
                                 method="exact", options={"elements": int(elements)}, Fn=load,
                                 mu=mu, E=E, chunk=200)
    ds = sweep(spec, work, workers=workers, executor=executor, resume=work.exists(),
               progress=progress)
    status = ds["status"].values
    failed = (status == STATUS_CODES["pending"]) | (status == STATUS_CODES["failed"])
    if np.any(failed):
        bad = int(np.argmax(failed))
        raise RuntimeError(f"exact solver failed at table node {bad}: {ds['message'].values[bad]}")
    cn = np.sqrt(nodes["a"] * nodes["b"])
    vals = np.stack([ds["Fx"].values / (mu * load), ds["Fy"].values / (mu * load),
                     ds["Mz"].values / (mu * load * cn)], axis=-1).reshape(*nodes["shape"], 3)
    vals = np.concatenate([vals, _full_slip_plane(grid)[None]], axis=0)
    meta = {"version": TABLE_VERSION, "wheelrail_version": __version__,
            "method": "exact", "elements": int(elements), "build_contact": BUILD_CONTACT,
            "not_converged_nodes": int((status == STATUS_CODES["not_converged"]).sum()),
            "created": ds.attrs.get("created", ""), "axes": list(AXES),
            "quantities": ["Fx/(mu Fn)", "Fy/(mu Fn)", "Mz/(mu Fn c)"]}
    tmp = out.with_name(out.name + ".tmp.npz")
    np.savez_compressed(tmp, values=vals.astype(np.float32), meta=json.dumps(meta),
                        **{k: grid[k] for k in AXES})
    tmp.replace(out)
    ds.close()
    shutil.rmtree(work, ignore_errors=True)
    return out


