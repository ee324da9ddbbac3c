"""``wheelrail geometry``: rigid contact table of a wheelset on a track, with figures.

Writes ``contact_table.csv`` and ``contact_table.nc`` (NetCDF-3, scipy engine)
and the figures ``profiles_in_contact.png``, ``delta_r.png``,
``contact_angle.png`` and ``contact_positions.png`` (contact-point positions on
wheel and rail versus the lateral shift, as in fig. 1 of Piotrowski & Chollet
2005). :func:`geometry_demo` does the same with the default S1002/60E1 pair
for ``wheelrail demo``.
"""

from __future__ import annotations

from pathlib import Path

from ._output import esc

HELP = "contact table (delta r, contact angles, contact points) of a wheelset on a track"


def add_arguments(p) -> None:
    p.add_argument("--wheel", default="S1002",
                   help="wheel profile: a built-in name (S1002) or a profile file (default S1002)")
    p.add_argument("--rail", default="60E1",
                   help="rail profile: a built-in name (60E1, 54E1) or a file (default 60E1)")
    p.add_argument("--inclination", default="1/40",
                   help="rail inclination as a slope, e.g. 1/40, 1/20 or 0 (default 1/40)")
    p.add_argument("--canted", action="store_true",
                   help="the rail profile file is already canted (no rotation applied)")
    p.add_argument("--gauge", type=float, default=1.435, help="track gauge [m] (default 1.435)")
    p.add_argument("--flange-back", type=float, default=1.360,
                   help="flange back distance [m] (default 1.360)")
    p.add_argument("--nominal-radius", type=float, default=0.46,
                   help="wheel radius at the tape circle [m] (default 0.46)")
    p.add_argument("--y-range", type=float, nargs=2, default=(-0.01, 0.01), metavar=("YMIN", "YMAX"),
                   help="range of the lateral shift [m] (default -0.01 0.01)")
    p.add_argument("--points", type=int, default=201, help="number of lateral shifts (default 201)")
    p.add_argument("--yaw", type=float, default=0.0, help="yaw angle [rad] (default 0)")
    p.add_argument("--amplitude", type=float, default=0.003,
                   help="amplitude for the equivalent conicity [m] (default 0.003)")
    p.add_argument("--no-plots", action="store_true", help="write the table only")
    p.add_argument("--strict", action="store_true",
                   help="exit with code 1 if any row is flagged (flange climb, derailed, no "
                        "contact, not converged); by default flagged rows are only summarised")
    p.add_argument("--lenient", action="store_true",
                   help="read a profile file of a doubtful shape (gap, wall, head down, flange "
                        "cut off or at +y, columns swapped) with a warning instead of refusing it")
    p.add_argument("--out", metavar="DIR", default="wheelrail-geometry",
                   help="output directory (default ./wheelrail-geometry)")


def parse_slope(text) -> float:
    """'1/40' → 0.025; '0.025' → 0.025 (InputError otherwise)."""
    import math

    from ..errors import InputError

    s = str(text).strip()
    try:
        if "/" in s:
            num, den = s.split("/", 1)
            val = float(num) / float(den)
        else:
            val = float(s)
    except (ValueError, ZeroDivisionError) as exc:
        raise InputError(f"--inclination must be a slope like 1/40 or 0.025, got {text!r}") from exc
    if not math.isfinite(val):
        raise InputError(f"--inclination must be a finite slope like 1/40, got {text!r}")
    return val


def load_profile(spec: str, kind: str, lenient: bool = False):
    """A built-in profile by name or a profile file by path (``lenient``: see profiles.read)."""
    from .. import profiles

    path = Path(spec)
    if path.exists():
        return profiles.read(path, kind=kind, **({"lenient": True} if lenient else {}))
    if any(c in spec for c in "/\\") or path.suffix:
        raise FileNotFoundError(2, "profile file not found", spec)
    return profiles.load(spec)


# --------------------------------------------------------------------------- figures
def plot_profiles_in_contact(ws, tr, ys, path, side="right"):
    """Wheel and rail cross-sections of ``side`` with the contact points, one panel per y."""
    import numpy as np

    from ..geometry.contact_search import _SIGMA, silhouette
    from ..geometry.points import contact_points
    from ..plotting._common import finish, new_figure

    n = len(ys)
    ncols = min(n, 2)
    nrows = int(np.ceil(n / ncols))
    fig, axes = new_figure(nrows, ncols, size=(5.0 * ncols, 3.6 * nrows))
    axes = np.atleast_1d(axes).ravel()
    sig = _SIGMA[side]
    wc, rc = ws.curve(side), tr.curve(side)
    s = np.linspace(wc.u_min, wc.u_max, 1500)
    p, p1 = wc.eval(s, 1)
    u_r = np.linspace(rc.u_min, rc.u_max, 800)
    import warnings

    from ..errors import WheelrailError

    for ax, y in zip(axes, ys):
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                cp = contact_points(ws, tr, float(y))
        except WheelrailError as exc:
            ax.set_title(f"y = {y * 1e3:.1f} mm: no contact", fontsize="small")
            ax.text(0.5, 0.5, str(exc), transform=ax.transAxes, ha="center", va="center",
                    fontsize=6, wrap=True)
            continue
        one = np.ones_like(s)
        _, Yw, Zw, _ = silhouette(s, p, p1, ws.nominal_radius, ws.e_tape, sig, cp.y * one,
                                  (ws.nominal_radius + cp.z) * one, cp.roll * one, cp.yaw * one)
        ax.plot(sig * Yw * 1e3, Zw * 1e3, color="tab:blue", lw=1.2, label="wheel")
        ax.plot(u_r * 1e3, rc.eval(u_r, 0)[0] * 1e3, color="k", lw=1.2, label="rail")
        pts = cp.side(side)
        for k in range(pts.n):
            prim = k == pts.primary
            ax.plot(sig * pts.track_y[k] * 1e3, pts.track_z[k] * 1e3, "o" if prim else "s",
                    color="tab:red" if prim else "tab:orange", ms=6 if prim else 4)
            ax.annotate(f"{np.degrees(pts.contact_angle[k]):.1f}°\n{pts.separation[k] * 1e6:.0f} µm",
                        (sig * pts.track_y[k] * 1e3, pts.track_z[k] * 1e3), fontsize=7,
                        xytext=(4, 4), textcoords="offset points")
        ax.set_xlim(rc.u_min * 1e3 - 8, rc.u_max * 1e3 + 5)
        ax.set_ylim(-32, 12)
        ax.set_aspect("equal")
        flag = "" if cp.status == "ok" else f" — {cp.status.upper()}"
        ax.set_title(f"y = {y * 1e3:.1f} mm, Δr = {cp.delta_r * 1e3:.2f} mm{flag}",
                     fontsize="small")
        ax.set_xlabel(f"lateral position, {side} side, towards field side [mm]")
        ax.set_ylabel("height [mm]")
    for ax in axes[len(ys):]:
        ax.set_visible(False)
    axes[0].legend(fontsize="x-small", loc="lower right")
    finish(fig, path, title=f"{side} wheel on rail (red: rigid contact point, orange: secondary)")


def plot_delta_r(table, path):
    """Rolling-radius difference Δr(y) with the jumps of the contact point."""
    from ..plotting._common import finish, new_figure

    fig, ax = new_figure()
    y = table["y"].values * 1e3
    ax.plot(y, table["delta_r"].values * 1e3, color="tab:blue")
    for yj in table["jump_y"].values:
        ax.axvline(yj * 1e3, color="tab:gray", lw=0.7, ls="--")
    ax.set_xlabel("lateral shift y [mm]")
    ax.set_ylabel("Δr = r_right − r_left [mm]")
    ax.grid(alpha=0.3)
    finish(fig, path, title="rolling radius difference (dashed: jumps of the contact point)")


def plot_contact_angle(table, path):
    """Contact angles of all points (primary points as lines) versus y."""
    import numpy as np

    from ..plotting._common import finish, new_figure

    fig, ax = new_figure()
    y = table["y"].values * 1e3
    for side, color in (("left", "tab:blue"), ("right", "tab:red")):
        ax.plot(y, np.degrees(table[f"contact_angle_{side}_primary"].values), color=color,
                label=f"{side} (rigid contact point)")
        ga = np.degrees(table[f"contact_angle_{side}"].values)
        yy = np.broadcast_to(y[:, None], ga.shape)
        ax.scatter(yy, ga, s=4, color=color, alpha=0.4)
    ax.set_xlabel("lateral shift y [mm]")
    ax.set_ylabel("contact angle γ [°]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize="small")
    finish(fig, path, title="contact angles (dots: all points within the tolerance)")


def plot_contact_positions(table, path):
    """Contact-point positions on wheel and rail versus y (cf. Piotrowski & Chollet (2005), fig. 1)."""
    import numpy as np

    from ..plotting._common import finish, new_figure

    fig, axes = new_figure(2, 2, size=(10, 7), sharex=True)
    y = table["y"].values * 1e3
    for j, side in enumerate(("left", "right")):
        for i, (body, label) in enumerate((("wheel_y", "on the wheel"), ("rail_y", "on the rail"))):
            ax = axes[i, j]
            v = table[f"{body}_{side}"].values * 1e3
            sep = table[f"separation_{side}"].values
            yy = np.broadcast_to(y[:, None], v.shape)
            ok = np.isfinite(v)
            sc = ax.scatter(yy[ok], v[ok], c=np.clip(sep[ok] * 1e6, 0, None), s=5,
                            cmap="viridis_r", vmin=0, vmax=table.attrs.get("tolerance", 1e-4) * 1e6)
            ax.plot(y, table[f"{body}_{side}_primary"].values * 1e3, color="tab:red", lw=0.8)
            ax.set_title(f"{side}: contact position {label}", fontsize="small")
            ax.set_ylabel("profile y [mm] (field side +)")
            ax.grid(alpha=0.3)
            if i == 1:
                ax.set_xlabel("lateral shift y [mm]")
    fig.colorbar(sc, ax=axes, label="separation [µm]", shrink=0.6)
    finish(fig, path, title="contact points versus lateral shift (red: rigid contact point)")


# --------------------------------------------------------------------------- work
def _plot(fn, path, *args):
    """Draw one figure to a temporary file and rename it (crash-safe)."""
    from .._atomic import atomic_path

    with atomic_path(path) as tmp:
        fn(*args, tmp)
    return path


def row_summary(table) -> dict:
    """Counts per row status and the flagged rows [(y, status, reason)] of a contact table."""
    import numpy as np

    from ..geometry.contact_search import STATUS

    st = np.asarray(table["status"].values)
    counts = {name: int(np.count_nonzero(st == code)) for code, name in STATUS.items()}
    flagged = [{"y": float(table["y"].values[i]), "status": STATUS[int(st[i])],
                "reason": str(table["status_reason"].values[i])}
               for i in np.flatnonzero(st)]
    return {"counts": counts, "flagged": flagged}


def compute(ws, tr, ys, out: Path, *, yaw=0.0, amplitude=0.003, plots=True, figure_ys=None):
    """Contact table, conicity and figures; returns (table, summary dict, [(path, description)])."""
    import numpy as np

    from ..errors import WheelrailError
    from ..geometry import contact_table, equivalent_conicity
    from ..geometry.contact_table import write_csv, write_netcdf

    out.mkdir(parents=True, exist_ok=True)
    table = contact_table(ws, tr, ys, yaw)
    files = [(write_csv(table, out / "contact_table.csv"), "contact table (CSV, SI units)"),
             (write_netcdf(table, out / "contact_table.nc"), "contact table (NetCDF-3)")]
    conicity = None
    try:
        conicity = equivalent_conicity(ws, tr, amplitude, yaw=yaw)
    except WheelrailError as exc:  # e.g. flange contact within the amplitude: report why
        conicity = f"not available: {exc}"
    ok = np.asarray(table["status"].values) < 3
    dr = table["delta_r"].values
    summary = {
        "points": int(table.sizes["y"]),
        "y_range": [float(ys[0]), float(ys[-1])],
        "delta_r_at_ends": [float(dr[0]) if ok[0] else None, float(dr[-1]) if ok[-1] else None],
        "jumps_y": [float(v) for v in table["jump_y"].values],
        "jumps_side": [("left" if s < 0 else "right") for s in table["jump_side"].values],
        "max_points_per_side": int(table.sizes["point"]),
        "equivalent_conicity": conicity,
        "amplitude": amplitude,
        "rows": row_summary(table),
    }
    if plots:
        if figure_ys is None:
            lim = float(np.max(np.abs(ys)))
            figure_ys = [0.0, 0.3 * lim, 0.6 * lim, 0.9 * lim]
        _plot(lambda p: plot_profiles_in_contact(ws, tr, figure_ys, p),
              out / "profiles_in_contact.png")
        files.append((out / "profiles_in_contact.png", "wheel on rail with contact points"))
        _plot(plot_delta_r, out / "delta_r.png", table)
        files.append((out / "delta_r.png", "rolling radius difference"))
        _plot(plot_contact_angle, out / "contact_angle.png", table)
        files.append((out / "contact_angle.png", "contact angles"))
        _plot(plot_contact_positions, out / "contact_positions.png", table)
        files.append((out / "contact_positions.png", "contact-point positions vs y"))
    return table, summary, files


def print_row_summary(console, rows: dict, limit: int = 8) -> int:
    """Print the flagged rows of a table (at most ``limit`` reasons); return their number."""
    flagged = rows["flagged"]
    if not flagged:
        return 0
    counts = ", ".join(f"{n} {name.replace('_', ' ')}" for name, n in rows["counts"].items()
                       if n and name != "ok")
    console.print(f"[yellow]{len(flagged)} of {sum(rows['counts'].values())} rows flagged: "
                  f"{counts}[/yellow]")
    for row in flagged[:limit]:
        console.print(f"  {row['status']}: {esc(row['reason'])}")
    if len(flagged) > limit:
        console.print(f"  … {len(flagged) - limit} more (column status_reason of the table)")
    return len(flagged)


def geometry_demo(out_dir) -> dict:
    """Geometry part of ``wheelrail demo``: S1002 on 60E1 1:40, gauge 1435, flange back 1360.

    Writes the contact table (CSV, NetCDF) and four figures into ``out_dir``.

    Returns
    -------
    dict
        ``results`` (JSON-ready summary, SI), ``files`` (list of (Path,
        description)) and ``note`` (one line for the console).
    """
    import numpy as np

    from ..geometry import Track, Wheelset
    from ..profiles import load

    ws = Wheelset(load("S1002"))
    tr = Track(load("60E1"), inclination=1 / 40)
    ys = np.linspace(-0.01, 0.01, 201)
    _, summary, files = compute(ws, tr, ys, Path(out_dir), figure_ys=[0.0, 0.003, 0.005, 0.008])
    con = summary["equivalent_conicity"]
    con_txt = f"{con:.3f}" if isinstance(con, float) else str(con)
    note = (f"S1002/60E1 1:40: equivalent conicity at 3 mm = {con_txt}, "
            f"{len(summary['jumps_y'])} contact-point jumps")
    return {"results": summary, "files": files, "note": note}


def check_arguments(args):
    """Validate the arguments that need no profile (before any work); returns the y values."""
    import numpy as np

    from .._atomic import check_output_path
    from ..errors import InputError

    if args.points < 2:
        raise InputError(f"--points must be >= 2, got {args.points}")
    if args.points > 100_000:
        raise InputError(f"--points must be <= 100000, got {args.points}")
    lo, hi = args.y_range
    if not (np.isfinite(lo) and np.isfinite(hi)):
        raise InputError(f"--y-range must be finite, got {lo:g} {hi:g}")
    if not hi > lo:
        raise InputError(f"--y-range must be increasing, got {lo:g} {hi:g}")
    if max(abs(lo), abs(hi)) > 0.05:
        raise InputError(f"--y-range is in metres and |y| must be <= 0.05 m, got {lo:g} {hi:g}"
                         + (" (mm given?)" if max(abs(lo), abs(hi)) >= 1.0 else ""))
    if not (np.isfinite(args.yaw) and abs(args.yaw) <= 0.2):
        raise InputError(f"--yaw is in rad and must lie in [-0.2, 0.2], got {args.yaw:g}")
    if not (np.isfinite(args.amplitude) and 0.0 < args.amplitude <= 0.012):
        raise InputError(f"--amplitude is in metres and must lie in (0, 0.012], got "
                         f"{args.amplitude:g}")
    out = Path(args.out)
    if out.exists() and not out.is_dir():
        raise InputError(f"--out {str(out)!r} exists and is not a directory")
    check_output_path(out / "contact_table.csv", what="--out")
    return np.linspace(lo, hi, args.points)


def run(args, console) -> int:
    from ..geometry import Track, Wheelset
    from ._output import write_json

    ys = check_arguments(args)
    lo, hi = float(ys[0]), float(ys[-1])
    lenient = getattr(args, "lenient", False)
    ws = Wheelset(load_profile(args.wheel, "wheel", lenient), nominal_radius=args.nominal_radius,
                  flange_back=args.flange_back)
    tr = Track(load_profile(args.rail, "rail", lenient), gauge=args.gauge,
               inclination=parse_slope(args.inclination), canted=args.canted)
    out = Path(args.out)
    import contextlib

    # about 1 ms per lateral shift: show a spinner for long tables (terminal only)
    busy = (console.status(f"contact table: {len(ys)} lateral shifts (about {len(ys) // 1000} s)")
            if len(ys) > 3000 and console.is_terminal else contextlib.nullcontext())
    with busy:
        table, summary, files = compute(ws, tr, ys, out, yaw=args.yaw, amplitude=args.amplitude,
                                        plots=not args.no_plots)
    files.append((write_json(summary, out / "geometry_summary.json"), "summary (JSON, SI)"))
    con = summary["equivalent_conicity"]
    con_txt = f"{con:.4f}" if isinstance(con, float) else con
    console.print(f"[bold]contact table[/bold]: {len(ys)} lateral shifts "
                  f"{lo * 1e3:g} … {hi * 1e3:g} mm; equivalent conicity "
                  f"(ŷ = {args.amplitude * 1e3:g} mm) = {con_txt}")
    if summary["jumps_y"]:
        console.print("jumps of the contact point at y = " + ", ".join(
            f"{v * 1e3:.3f} mm ({s})" for v, s in zip(summary["jumps_y"], summary["jumps_side"])))
    for path, desc in files:
        console.print(f"  {esc(path)}  — {desc}")
    n_flagged = print_row_summary(console, summary["rows"])
    if n_flagged and args.strict:
        import sys

        print(f"wheelrail: error: --strict: {n_flagged} flagged row(s) (flange climb, derailed, "
              "no contact or not converged; see the table above)", file=sys.stderr)
        return 1
    return 0
