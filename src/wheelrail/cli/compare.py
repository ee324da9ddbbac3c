"""``wheelrail compare CASE.toml``: every normal method against the exact solver on one position.

Reads a wheelset case file (as ``wheelrail wheelset``), solves the same
wheel–rail position with every normal method and its natural tangential
method (Hertz, the multi-Hertzian variants, Linder, Kik–Piotrowski, STRIPES
with FASTSIM; Kik–Piotrowski with FaStrip) and with the reference, the
boundary-element normal solution with Kalker's exact tangential theory
(``bem`` + ``exact``), and prints one table per wheel: number of patches,
ΣFn, Σ area, largest p_max, ΣFx, ΣFs, ΣMz (contact frames) and the time per
method, with the relative deviation from the reference. ``--sweep`` runs
the case's lateral-shift range (or ``--y START STOP NUM`` in mm) and writes
``compare.csv`` and a figure with each quantity against the shift per method.
SI units in files (N, m², Pa, N·m); the table shows kN, mm², MPa.
"""

from __future__ import annotations

import time
from pathlib import Path

from ._output import esc

HELP = "compare every normal method (and FaStrip) with the exact solver on a wheelset position"

#: (label, normal, tangential, options) — the reference last.
METHODS = (
    ("hertz", "hertz", "fastsim", {}),
    ("multi-hertz/pascal", "multi-hertz", "fastsim", {"variant": "pascal"}),
    ("multi-hertz/sauvage", "multi-hertz", "fastsim", {"variant": "sauvage"}),
    ("multi-hertz/sauvage-half", "multi-hertz", "fastsim", {"variant": "sauvage-half"}),
    ("multi-hertz/ayasse", "multi-hertz", "fastsim", {"variant": "ayasse"}),
    ("linder", "linder", "fastsim", {}),
    ("kik-piotrowski", "kik-piotrowski", "fastsim", {}),
    ("kik-piotrowski/0.55", "kik-piotrowski", "fastsim",
     {"penetration_factor": 0.55, "ellipticity_correction": False,
      "fastsim_flexibility": "weighted"}),
    ("kik-piotrowski+fastrip", "kik-piotrowski", "fastrip", {}),
    ("stripes", "stripes", "fastsim", {}),
    ("bem+exact", "bem", "exact", {}),
)
REFERENCE = "bem+exact"
#: A method whose first call took less than this [s] is timed again (start-up excluded).
REPEAT_BELOW = 2.0
_TIMED: set = set()  # labels timed once in this process (their start-up is paid)
QUANTITIES = ("patches", "Fn", "area", "p_max", "Fx", "Fs", "Mz", "time")


def add_arguments(p) -> None:
    p.add_argument("case", metavar="CASE.toml", help="wheelset case file (as 'wheelrail wheelset')")
    p.add_argument("--sweep", action="store_true",
                   help="run the case's lateral-shift range (or --y) and plot each quantity")
    p.add_argument("--y", nargs=3, type=float, metavar=("START", "STOP", "NUM"), default=None,
                   help="lateral shifts in mm for --sweep (default: the case's [position] y)")
    p.add_argument("--side", choices=("left", "right"), default=None,
                   help="only this wheel (default both)")
    p.add_argument("--methods", default=None,
                   help="comma-separated labels to run (default all; see the table)")
    p.add_argument("--out", metavar="DIR", default="wheelrail-compare",
                   help="output directory of --sweep (default ./wheelrail-compare)")
    p.add_argument("--no-plots", action="store_true", help="write no figure")
    p.add_argument("--patches", action="store_true",
                   help="single position: also write DIR/compare_patches.png, the patches of "
                        "every method on the rail profile with the pressure in colour")


def wheel_quantities(result, side) -> dict:
    """Totals of one wheel of a :class:`WheelRailResult`: patches, Fn, area, p_max, Fx, Fs, Mz (SI)."""
    ps = result.side(side)
    return {"patches": len(ps), "Fn": sum(p.Fn for p in ps), "area": sum(p.area for p in ps),
            "p_max": max((p.p_max for p in ps), default=0.0),
            "Fx": sum(p.Fx for p in ps), "Fs": sum(p.Fs for p in ps),
            "Mz": sum(p.Mz for p in ps)}


def run_methods(position, motion, mu, methods=METHODS, sides=("left", "right"), keep=None):
    """Solve ``position`` with every method; {label: {side: quantities}} (or an error string).

    ``keep``: a dict that receives {label: WheelRailResult}.
    """
    from ..api import solve

    out = {}
    for label, normal, tangential, opts in methods:
        def once():
            t0 = time.perf_counter()
            r = solve(position, motion=motion, mu=mu, normal=normal, tangential=tangential,
                      vertical="normal", **opts)
            return r, time.perf_counter() - t0

        try:
            r, dt = once()
            if label not in _TIMED and dt < REPEAT_BELOW:
                # the first call pays the start-up (imports, kernel compilation, caches):
                # time a second call, which is what the method costs
                r, dt = once()
        except Exception as exc:       # one failing method must not hide the others
            out[label] = f"{type(exc).__name__}: {exc}"
            continue
        _TIMED.add(label)
        out[label] = {s: dict(wheel_quantities(r, s), time=dt) for s in sides}
        if keep is not None:
            keep[label] = r
    return out


def yaw_at(case, ys):
    """The case's yaw angle at the lateral shifts ``ys`` [m] (``--y`` keeps every setting).

    A single yaw stays the same; ``yaw_per_y`` (yaw proportional to y) is
    applied to the new shifts; a list of yaws is interpolated linearly.
    """
    import numpy as np

    y0, yaw0 = np.asarray(case.y, float), np.asarray(case.yaw, float)
    if np.all(yaw0 == yaw0[0]):
        return np.full_like(ys, yaw0[0])
    nz = y0 != 0
    k = yaw0[nz] / y0[nz]
    if np.allclose(k, k[0], rtol=1e-9, atol=0) and np.allclose(yaw0[~nz], 0.0):
        return k[0] * ys
    order = np.argsort(y0)
    return np.interp(ys, y0[order], yaw0[order])


def _select(labels):
    if labels is None:
        return METHODS
    want = list(dict.fromkeys(s.strip() for s in labels.split(",") if s.strip()))  # once each
    known = {m[0]: m for m in METHODS}
    bad = [w for w in want if w not in known]
    if bad:
        from ..errors import InputError
        raise InputError(f"--methods: unknown label(s) {', '.join(map(repr, bad))}; choose from "
                         + ", ".join(known))
    if not want:
        from ..errors import InputError
        raise InputError(f"--methods is empty (got {labels!r}); give two or more labels to "
                         f"compare, e.g. hertz,bem+exact (choose from {', '.join(known)})")
    if len(want) == 1:
        import warnings

        warnings.warn(f"--methods {want[0]}: one method compares with nothing; add the exact "
                      "reference (e.g. --methods hertz,bem+exact) for a comparison",
                      UserWarning, stacklevel=2)
    return tuple(known[w] for w in want)


#: Columns of the comparison table: (header, quantity, scale from SI, format).
COLUMNS = (("patches", "patches", 1, "d"), ("Fn kN", "Fn", 1e-3, ".2f"),
           ("area mm²", "area", 1e6, ".1f"), ("p_max MPa", "p_max", 1e-6, ".0f"),
           ("Fx kN", "Fx", 1e-3, ".2f"), ("Fs kN", "Fs", 1e-3, ".2f"), ("Mz N·m", "Mz", 1.0, ".2f"),
           ("time ms", "time", 1e3, ".1f"))
#: Below this console width the table is printed in two parts (fits 80 columns).
SPLIT_BELOW = 130


def _table(res, side, title, columns=COLUMNS):
    from rich import box
    from rich.table import Table

    t = Table(title=esc(title), box=box.SIMPLE_HEAD, pad_edge=False)
    width = max([len("method"), *(len(label) for label in res)])
    # never cut the method: which row is which
    t.add_column("method", justify="left", no_wrap=True, min_width=width)
    for header, *_ in columns:
        t.add_column(header, justify="right")
    ref = res.get(REFERENCE)
    ref = ref[side] if isinstance(ref, dict) else None
    for label, v in res.items():
        if not isinstance(v, dict):
            t.add_row(label, "[red]failed[/red]", esc(v[:60]), *[""] * (len(columns) - 2))
            continue
        q = v[side]

        def cell(key, scale, fmt):
            if fmt == "d":
                return str(q[key])
            s = format(q[key] * scale, fmt)
            if key != "time" and ref is not None and label != REFERENCE and ref[key] != 0:
                s += f" ({(q[key] - ref[key]) / abs(ref[key]) * 100:+.0f}%)"
            return s
        t.add_row(label, *[cell(key, scale, fmt) for _, key, scale, fmt in columns])
    return t


def print_tables(console, res, side, title) -> None:
    """The comparison of one wheel: one table, or two halves on a narrow console."""
    if getattr(console, "width", 200) >= SPLIT_BELOW:
        console.print(_table(res, side, title))
        return
    half = 4
    console.print(_table(res, side, title + " (1/2)", COLUMNS[:half]))
    console.print(_table(res, side, title + " (2/2)", COLUMNS[half:]))


def run(args, console) -> int:
    import numpy as np

    from ..cases.files import load_wheelset_case
    from ..contact.wheelrail import WheelRailPosition

    case = load_wheelset_case(args.case)
    methods = _select(args.methods)
    sides = (args.side,) if args.side else ("left", "right")

    def position(y, yaw):
        return WheelRailPosition(case.wheelset, case.track, float(y), yaw=float(yaw),
                                 roll=case.roll, vertical_load=case.vertical_load, z=case.z,
                                 material=case.materials, tolerance=case.tolerance)

    if not args.sweep:
        y, yaw = float(case.y[0]), float(case.yaw[0])
        kept = {}
        res = run_methods(position(y, yaw), case.motion, case.mu, methods, sides, keep=kept)
        for s in sides:
            print_tables(console, res, s, f"wheelrail compare {args.case}: y = {y * 1e3:g} mm, "
                                          f"{s} wheel, μ = {case.mu:g} (deviation from "
                                          f"{REFERENCE})")
        if args.patches and not args.no_plots and kept:
            out = Path(args.out)
            out.mkdir(parents=True, exist_ok=True)
            path = patch_figure(kept, sides[-1], out / "compare_patches.png",
                                title=f"{args.case}: y = {y * 1e3:g} mm, {sides[-1]} wheel")
            console.print(f"  {esc(path)}  — patches of every method, pressure in colour")
        return 0
    if args.y is not None:
        ys = np.linspace(args.y[0], args.y[1], int(args.y[2])) * 1e-3
        yaws = yaw_at(case, ys)
    else:
        ys, yaws = np.asarray(case.y, float), np.asarray(case.yaw, float)
    from rich.progress import track

    rows = []
    for y, yaw in track(list(zip(ys, yaws)), description="compare sweep", console=console):
        res = run_methods(position(y, yaw), case.motion, case.mu, methods, sides)
        for label, v in res.items():
            for s in sides:
                row = {"y": float(y), "yaw": float(yaw), "method": label, "side": s}
                if isinstance(v, dict):
                    row.update(v[s])
                    row["status"] = "ok"
                else:
                    row.update({k: float("nan") for k in QUANTITIES})
                    row["status"] = v
                rows.append(row)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    import csv

    from .._atomic import atomic_open

    keys = ["y", "yaw", "method", "side", *QUANTITIES, "status"]
    with atomic_open(out / "compare.csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=keys)
        w.writeheader()
        for r in rows:
            w.writerow({k: r.get(k) for k in keys})
    files = [(out / "compare.csv", "every method, every shift (SI units)")]
    if not args.no_plots:
        files.append((_plot(rows, sides, out), "each quantity against the lateral shift"))
    for p, d in files:
        console.print(f"  {esc(p)}  — {d}")
    return 0


def _plot(rows, sides, out):
    """Figure: every quantity against the lateral shift, one line per method."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    qs = ("patches", "Fn", "area", "p_max", "Fx", "Fs", "Mz", "time")
    scale = {"Fn": 1e-3, "area": 1e6, "p_max": 1e-6, "Fx": 1e-3, "Fs": 1e-3, "time": 1e3}
    unit = {"Fn": "kN", "area": "mm²", "p_max": "MPa", "Fx": "kN", "Fs": "kN", "Mz": "N·m",
            "time": "ms", "patches": "-"}
    fig, axes = plt.subplots(len(qs), len(sides), figsize=(6 * len(sides), 2.2 * len(qs)),
                             squeeze=False, sharex=True)
    labels = list(dict.fromkeys(r["method"] for r in rows))
    for j, s in enumerate(sides):
        for i, q in enumerate(qs):
            ax = axes[i, j]
            for lab in labels:
                rr = [r for r in rows if r["method"] == lab and r["side"] == s]
                y = np.array([r["y"] for r in rr]) * 1e3
                v = np.array([r.get(q, np.nan) for r in rr], float) * scale.get(q, 1.0)
                ax.plot(y, v, "k-" if lab == REFERENCE else "-", lw=2 if lab == REFERENCE else 1,
                        label=lab)
            ax.set_ylabel(f"{q} [{unit[q]}]")
            if i == 0:
                ax.set_title(f"{s} wheel")
        axes[-1, j].set_xlabel("lateral shift y [mm]")
    axes[0, 0].legend(fontsize=6, ncol=2)
    fig.tight_layout()
    from .._atomic import atomic_path

    path = out / "compare_sweep.png"
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=110)
    plt.close(fig)
    return path


def patch_figure(results, side, path, title=""):
    """Patches of every method on one rail (Piotrowski & Chollet (2005) figs. 13, 18–22 in kind).

    One row per method: the rail profile of the side (top of rail, lateral
    coordinate of the rail profile frame [mm]) and below it every patch in
    the (lateral, rolling) plane, the pressure in colour (common scale, MPa).
    Strip y is laid along the rail at the patch's rail position (y·cos of the
    contact angle: the plane is tilted by γ).
    """
    import math

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    labels = list(results)
    pmax = max((p.p_max for r in results.values() for p in r.side(side)), default=1.0)
    fig, axes = plt.subplots(len(labels), 1, figsize=(7, 1.6 * len(labels) + 0.8),
                             sharex=True, squeeze=False)
    mappable = None
    for ax, lab in zip(axes[:, 0], labels):
        r = results[lab]
        sig = 1.0 if side == "right" else -1.0
        for p in r.side(side):
            pt = p.patch
            c = math.cos(pt.frame.contact_angle)
            yc = (pt.frame.rail_y + sig * pt.y * c) * 1e3
            x = pt.cell_x() * 1e3
            Y = np.repeat(yc[:, None], x.shape[1], axis=1)
            mappable = ax.scatter(Y.ravel(), x.ravel(), c=pt.strip_pressure.ravel() / 1e6,
                                  s=4, marker="s", cmap="viridis", vmin=0, vmax=pmax / 1e6,
                                  linewidths=0)
        ax.set_ylabel("x [mm]")
        ax.set_title(lab, fontsize=8, loc="left")
        xm = max((float(np.max(np.abs(p.patch.cell_x()))) for p in r.side(side)), default=1e-3)
        ax.set_ylim(-1.1e3 * xm, 1.1e3 * xm)
    axes[-1, 0].set_xlabel(f"lateral position on the {side} rail profile [mm]")
    if mappable is not None:
        fig.colorbar(mappable, ax=axes[:, 0].tolist(), label="pressure [MPa]", shrink=0.6)
    fig.suptitle(title, fontsize=9)
    from .._atomic import atomic_path

    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=110)
    plt.close(fig)
    return path
