"""``wheelrail wheelset CASE.toml``: a wheelset on a track, one position or a lateral-shift sweep.

The case file has ``[wheelset]``, ``[track]``, ``[motion]``, ``[position]``,
``[friction]`` and optionally ``[method]`` and ``[material]`` tables
(:mod:`wheelrail.cases.files`). With one lateral shift ``[position] y`` the
command prints a table per patch and the track-frame forces per wheel and
writes ``wheelset.json`` and the figures ``contact_profiles.png`` and
``adhesion.png``; with a range or list of shifts it solves the sweep
(:func:`wheelrail.wheelset_sweep`, with a progress bar) and writes
``sweep.nc`` (NetCDF-3), ``sweep.csv`` and ``sweep_forces.png``.
"""

from __future__ import annotations

from pathlib import Path

from ._output import esc

HELP = "wheelset on a track (real profiles): contact patches and forces, one position or a sweep"


def add_arguments(p) -> None:
    p.add_argument("case", metavar="CASE.toml",
                   help="wheelset case file ([wheelset], [track], [motion], [position], ...)")
    p.add_argument("--out", metavar="DIR", default="wheelrail-wheelset",
                   help="output directory (default ./wheelrail-wheelset)")
    p.add_argument("--sweep", action="store_true",
                   help="require a sweep: [position] y must be a range {start, stop, num} or a "
                        "list (a case with a range is swept also without this flag)")
    p.add_argument("--csv", action="store_true", help="sweep: write only the CSV file "
                   "(default: CSV and NetCDF)")
    p.add_argument("--netcdf", action="store_true", help="sweep: write only the NetCDF file "
                   "(default: CSV and NetCDF)")
    p.add_argument("--no-plots", action="store_true", help="write no figures")
    p.add_argument("--quiet", "-q", action="store_true",
                   help="print nothing on success (no progress bar)")


# --------------------------------------------------------------------------- tables
def patch_table(result, title: str):
    """A rich Table of the patches of a :class:`~wheelrail.contact.WheelRailResult`:
    one column per patch (left wheel first, each from field side to flange), one row
    per quantity (units shown)."""
    import math

    from rich.table import Table

    rows = [
        ("position on rail", "mm", lambda p: f"{p.y_rail * 1e3:.2f}"),
        ("position on wheel", "mm", lambda p: f"{p.y_wheel * 1e3:.2f}"),
        ("contact angle", "deg", lambda p: f"{math.degrees(p.contact_angle):.2f}"),
        ("creepage ξ", "-", lambda p: f"{p.xi + 0.0:.3e}"),
        ("creepage η", "-", lambda p: f"{p.eta + 0.0:.3e}"),
        ("spin φ", "1/m", lambda p: f"{p.phi:.4g}"),
        ("Fn", "N", lambda p: f"{p.Fn:.0f}"),
        ("Fx", "N", lambda p: f"{p.Fx:.0f}"),
        ("Fs", "N", lambda p: f"{p.Fs:.0f}"),
        ("Mz", "N·m", lambda p: f"{p.Mz:.3g}"),
        ("p_max", "MPa", lambda p: f"{p.p_max / 1e6:.0f}"),
        ("area", "mm²", lambda p: f"{p.area * 1e6:.2f}"),
        ("adhesion area", "mm²",
         lambda p: "n/a" if math.isnan(p.adhesion_area) else f"{p.adhesion_area * 1e6:.2f}"),
        ("status", "", lambda p: str(p.status)),
    ]
    t = Table(title=title, title_justify="left")
    t.add_column("quantity")
    t.add_column("unit")
    count = {}
    for p in result.patches:
        count[p.side] = count.get(p.side, 0) + 1
        t.add_column(f"{p.side} {count[p.side]}", justify="right")
    for label, unit, fmt in rows:
        t.add_row(label, unit, *(fmt(p) for p in result.patches))
    return t


def track_table(result):
    """Forces on each wheel in the track frame (x forward, y right, z up) [N]."""
    from rich.table import Table

    t = Table(title="forces on the wheels (track frame)",
              title_justify="left")
    for name in ("wheel", "Fx fwd [N]", "Fy right [N]", "Fz up [N]", "patches"):
        t.add_column(name, justify="right" if "[" in name or name == "patches" else "left")
    for side, (fx, fy, fz) in result.force_track.items():
        t.add_row(side, f"{fx:.0f}", f"{fy:.0f}", f"{fz:.0f}", str(len(result.side(side))))
    return t


# --------------------------------------------------------------------------- output
def write_sweep_csv(ds, path) -> Path:
    """One row per lateral shift; per-wheel columns ``<name>_<side>``, per-patch columns
    ``<name>_<side>_<patch>`` (SI units, empty where no patch)."""
    import csv

    import numpy as np

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    names, cols = ["y"], [np.asarray(ds["y"].values, float)]
    for name, var in ds.data_vars.items():
        if var.dims == ("y",):
            names.append(name)
            cols.append(np.asarray(var.values))
        elif var.dims == ("y", "side"):
            for s, side in enumerate(ds["side"].values):
                names.append(f"{name}_{side}")
                cols.append(np.asarray(var.values[:, s]))
        elif var.dims == ("y", "side", "patch"):
            for s, side in enumerate(ds["side"].values):
                for k in range(var.shape[2]):
                    names.append(f"{name}_{side}_{k}")
                    cols.append(np.asarray(var.values[:, s, k]))

    def cell(v):
        if isinstance(v, (float, np.floating)):
            return "" if np.isnan(v) else repr(float(v))
        if isinstance(v, (np.integer, int)):
            return str(int(v))
        return str(v)

    from .._atomic import atomic_open

    with atomic_open(path, "w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh)
        w.writerow(names)
        for i in range(cols[0].size):
            w.writerow([cell(c[i]) for c in cols])
    return path


def write_sweep_netcdf(ds, path) -> Path:
    """NetCDF-3 (scipy engine, no netCDF4 library needed)."""
    path = Path(path)
    from .._atomic import atomic_path

    with atomic_path(path) as tmp:
        ds.to_netcdf(tmp, engine="scipy")
    return path


def single_position(case, out: Path, plots: bool = True):
    """Solve one position; returns (result, summary dict, [(path, description)])."""
    from ..cases import solve_wheelset_case
    from ._output import write_json

    result = solve_wheelset_case(case)
    summary = result.to_dict()
    summary["case"] = case.to_dict()
    files = [(write_json(summary, out / "wheelset.json"), "results per patch and wheel (JSON, SI)")]
    if plots:
        from ..plotting.wheelrail import adhesion_maps, contact_profiles

        contact_profiles(result, path=out / "contact_profiles.png")
        files.append((out / "contact_profiles.png", "profiles in contact, patches and pressure"))
        adhesion_maps(result, path=out / "adhesion.png")
        files.append((out / "adhesion.png", "adhesion/slip areas per patch"))
    return result, summary, files


def sweep(case, out: Path, *, plots=True, csv=True, netcdf=True, progress=None):
    """Solve the lateral-shift sweep; returns (dataset, [(path, description)])."""
    from ..cases import solve_wheelset_case

    ds = solve_wheelset_case(case, progress=progress)
    files = []
    if netcdf:
        files.append((write_sweep_netcdf(ds, out / "sweep.nc"), "sweep dataset (NetCDF-3, SI)"))
    if csv:
        files.append((write_sweep_csv(ds, out / "sweep.csv"), "sweep table (CSV, SI)"))
    if plots:
        from ..plotting.wheelrail import sweep_forces

        sweep_forces(ds, path=out / "sweep_forces.png")
        files.append((out / "sweep_forces.png", "forces and patch positions against y"))
    return ds, files


# --------------------------------------------------------------------------- command
def run(args, console) -> int:
    import numpy as np

    from ..cases.files import load_wheelset_case
    from ..errors import CaseFileError

    case = load_wheelset_case(args.case)
    if args.sweep and not case.sweep:
        raise CaseFileError(f"{case.source}: [position] y: --sweep needs a range "
                            "{start = ..., stop = ..., num = ...} or a list, got the single "
                            f"value {float(case.y[0])!r}")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    plots = not args.no_plots
    if not case.sweep:
        result, _, files = single_position(case, out, plots)
        if not args.quiet:
            title = (f"wheelrail wheelset {esc(args.case)}: y = {case.y[0] * 1e3:g} mm, "
                     f"{result.normal} + {result.tangential}, μ = {case.mu:g}")
            console.print(patch_table(result, title))
            console.print(track_table(result))
            for path, desc in files:
                console.print(f"  {esc(path)}  — {desc}")
        return 0
    both = args.csv == args.netcdf
    ds, files = sweep(case, out, plots=plots, csv=both or args.csv, netcdf=both or args.netcdf,
                      progress=not args.quiet)
    status = np.asarray(ds["status"].values)
    failed = int(np.sum(status == "error"))
    flagged = int(np.sum((status != "ok") & (status != "error")))
    if not args.quiet:
        console.print(f"[bold]wheelset sweep[/bold]: {status.size} lateral shifts "
                      f"{case.y[0] * 1e3:g} … {case.y[-1] * 1e3:g} mm, {case.normal.name} + "
                      f"{case.tangential.name}, μ = {case.mu:g}; {status.size - failed} solved"
                      + (f", [yellow]{flagged} flagged[/yellow] (flange climb or derailed)"
                         if flagged else "")
                      + (f", [yellow]{failed} failed[/yellow] (status/message in the files)"
                         if failed else ""))
        for y, msg in zip(ds["y"].values[status != "ok"][:5], ds["message"].values[status != "ok"]):
            console.print(f"  y = {y * 1e3:g} mm: {esc(msg)}")
        for path, desc in files:
            console.print(f"  {esc(path)}  — {desc}")
    if failed == status.size:
        from ..errors import WheelrailError

        raise WheelrailError(f"no position of the sweep could be solved; first error: "
                             f"{ds['message'].values[0]}")
    return 0
