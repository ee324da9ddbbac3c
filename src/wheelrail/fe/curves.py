"""Creep curves of the FE model: steady creep forces over a range of creepage.

Each creepage is an independent rolling run (:func:`wheelrail.fe.solve`, both loading
steps, virgin material for a plastic case) whose steady forces are taken over its steady
window. The FE model deforms the bodies, so its rolling radius is not the rigid one of
the prescribed creepage (eq. 1 of Toumi, Chollet & Yin 2016): the curve is shifted by a
creepage offset (their §4.1.3 shifts their FE curves through the origin). The offset and
the initial slope come from a straight-line fit of the points in the linear range.
"""

from __future__ import annotations

import time

import numpy as np

from .._validation import as_float_array
from ..errors import InputError
from .model import contact_geometry
from .run import solve

__all__ = ["creep_curve", "merge_creep_curves"]

_COMPONENTS = {"xi": 0, "eta": 1}


def creep_curve(case, creepages, component: str = "xi", *, linear_fraction: float = 0.5,
                progress: bool = True, path=None):
    """Steady creep forces of ``case`` at several creepages (one FE rolling run each).

    Parameters
    ----------
    case : RollingCase
        The case; its creepage component ``component`` is replaced by each value (the other
        components are kept).
    creepages : array_like, shape (n,)
        Longitudinal ξ or lateral η creepages [-].
    component : {"xi", "eta"}
        Which creepage varies; the force of the curve is Fx for ξ, the lateral force in the
        contact plane Fy_contact for η.
    linear_fraction : float
        Points with |F| <= linear_fraction · μ F_n enter the straight-line fit F = k (c − c0)
        giving the initial slope k and the offset c0.
    progress : bool
        Show a rich progress bar (over points and within each run).
    path : str or Path, optional
        Also write the result to this NetCDF file.

    Returns
    -------
    xarray.Dataset
        Over ``creepage``: Fx, Fy, Fy_contact, Fn [N] (steady means), Fx_std, Fy_std,
        Fy_contact_std [N] and Fx_scatter, Fy_scatter, Fy_contact_scatter [-] (standard
        deviation over the steady window / |mean|), window_start, window_end [m] (the steady
        window of travel, :func:`wheelrail.fe.rolling.steady_window`), steady_steps (the steps
        averaged), cpu_seconds [s]; coordinate
        ``shifted_creepage`` = creepage − offset. Attributes: ``offset`` [-] (the creepage
        of zero force), ``slope`` [N] (initial slope dF/dc), ``fit_points``, ``component``,
        ``force`` (the force of the curve), the case's load, friction and mesh size.

    References
    ----------
    .. [1] M. Toumi, H. Chollet, H. Yin, Wear 366-367 (2016) 157-166, §4.1.3, §4.2.4,
       Figs. 8 and 12.
    """
    import warnings

    import xarray as xr


    if component not in _COMPONENTS:
        raise InputError(f"component must be 'xi' or 'eta', got {component!r}")
    c = as_float_array("creepages", creepages).ravel()
    if c.size < 1:
        raise InputError("creepages must hold at least one value")
    k = _COMPONENTS[component]
    force = "Fx" if component == "xi" else "Fy_contact"
    names = ("Fx", "Fy", "Fy_contact", "Fn", "Fn_contact")
    rows = {n: [] for n in names}
    stds = {n: [] for n in ("Fx", "Fy", "Fy_contact")}
    cpu = []
    window = []
    bar = None
    if progress:
        from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

        bar = Progress(TextColumn("FE creep curve"), BarColumn(), TextColumn("{task.completed}/"
                       "{task.total}"), TimeElapsedColumn(), transient=True)
        bar.start()
        task = bar.add_task("points", total=c.size)
    try:
        for value in c:
            cr = list(case.creepage)
            cr[k] = float(value)
            t0 = time.process_time()
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", UserWarning)   # saturation warnings: expected
                r = solve(case.replace(creepage=tuple(cr)), progress=False)
            cpu.append(time.process_time() - t0)
            for n in names:
                rows[n].append(r.steady[n])
            for n in stds:
                stds[n].append(r.steady[f"{n}_std"])
            window.append((*r.steady["window"], r.steady["n"]))
            if bar is not None:
                bar.update(task, advance=1)
    finally:
        if bar is not None:
            bar.stop()
    ds = xr.Dataset(coords={"creepage": ("creepage", c)})
    for n in names:
        ds[n] = ("creepage", np.array(rows[n]), {"units": "N"})
    for n, v in stds.items():
        ds[f"{n}_std"] = ("creepage", np.array(v), {"units": "N"})
        ds[f"{n}_scatter"] = ("creepage", np.abs(np.array(v) / np.array(rows[n])))
    w = np.array(window, float).reshape(-1, 3)
    ds["window_start"] = ("creepage", w[:, 0], {"units": "m"})
    ds["window_end"] = ("creepage", w[:, 1], {"units": "m"})
    ds["steady_steps"] = ("creepage", w[:, 2].astype(np.int64))
    ds["cpu_seconds"] = ("creepage", np.array(cpu), {"units": "s"})
    ds.attrs.update({"component": component, "force": force, "load": case.Fn,
                     "normal_load": float(contact_geometry(case)["normal_load"]),
                     "mu": case.mu, "mesh_size": case.mesh_size, "integrator": case.integrator,
                     "material": repr(case.material), "linear_fraction": float(linear_fraction)})
    ds = _fit(ds)
    if path is not None:
        ds.to_netcdf(path)
    return ds


def _fit(ds):
    """Offset and initial slope of a creep curve from its points in the linear range."""
    c = ds.creepage.values
    F = ds[ds.attrs["force"]].values
    lin = np.abs(F) <= ds.attrs["linear_fraction"] * ds.attrs["mu"] * ds.attrs["normal_load"]
    offset = slope = float("nan")
    if lin.sum() >= 2 and np.ptp(c[lin]) > 0:
        slope, intercept = np.polyfit(c[lin], F[lin], 1)
        offset = -intercept / slope
    ds = ds.assign_coords(shifted_creepage=("creepage", c - offset))
    ds.attrs.update({"offset": float(offset), "slope": float(slope),
                     "fit_points": int(lin.sum())})
    return ds


def merge_creep_curves(curves):
    """One creep curve from several :func:`creep_curve` results of the same case.

    Lets the points of a curve run as separate processes (one file each) and be joined
    afterwards; the offset and the initial slope are fitted again over all points.

    Parameters
    ----------
    curves : sequence of xarray.Dataset
        Results of :func:`creep_curve` for the same case and component (the attributes of
        the first are kept); a creepage present twice keeps its first occurrence; a
        variable missing from some (a file written by an older version) is NaN there.

    Returns
    -------
    xarray.Dataset
        As :func:`creep_curve`, over the sorted union of the creepages.
    """
    import xarray as xr

    curves = list(curves)
    if not curves:
        raise InputError("merge_creep_curves needs at least one creep curve")
    first = curves[0].attrs
    for ds in curves[1:]:
        for key in ("component", "load", "mu", "mesh_size", "material"):
            if ds.attrs.get(key) != first.get(key):
                raise InputError(f"creep curves differ in {key!r}: {ds.attrs.get(key)!r} "
                                 f"against {first.get(key)!r}")
    names = {n for d in curves for n in d.data_vars}
    parts = []
    for d in curves:      # curves written before a variable existed: NaN there
        d = d.drop_vars("shifted_creepage")
        for n in names - set(d.data_vars):
            d[n] = ("creepage", np.full(d.sizes["creepage"], np.nan))
        parts.append(d)
    ds = xr.concat(parts, dim="creepage", combine_attrs="override")
    _, keep = np.unique(ds.creepage.values, return_index=True)
    ds = ds.isel(creepage=np.sort(keep)).sortby("creepage")
    ds.attrs = dict(first)
    ds.attrs.setdefault("linear_fraction", 0.5)
    return _fit(ds)
