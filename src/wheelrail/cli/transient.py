"""``wheelrail transient CASE.toml --out DIR``: transient rolling of a ``[transient]`` case.

Reads the case with :func:`wheelrail.casefile.load_transient_case`, runs
:func:`wheelrail.transient_rolling` with a progress bar and writes to DIR:

* ``history.nc`` — the scalar histories over the travel (``TransientResult.dataset``);
* ``fields.nc`` — the stored traction fields (``TransientResult.fields``);
* ``summary.json`` — the settings, final values and solver counts;
* ``creepage.png``, ``centreline.png``, ``state.png`` — figures after Baeza et al.
  Figs. 8/9/11, 7 and 10/12 (unless ``--no-figures``).
"""

from __future__ import annotations

HELP = "transient (instationary) rolling of a [transient] case file: NetCDF + figures"


def add_arguments(p) -> None:
    p.add_argument("case", metavar="CASE.toml", help="case file with a [transient] table")
    p.add_argument("--out", metavar="DIR", default="transient_out",
                   help="output directory (default transient_out): history.nc, fields.nc, "
                        "summary.json, creepage.png, centreline.png, state.png")
    p.add_argument("--no-figures", action="store_true", help="skip the PNG figures")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")


def run(args, console) -> int:
    import json
    import time
    from pathlib import Path

    from ..casefile import load_transient_case

    case = load_transient_case(args.case)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    hc = case.hertz_contact
    s = case.settings
    n_steps = int(s["travel"] / s["step"] + 1e-9)
    console.print(f"transient rolling: a = {hc.a * 1e3:.3f} mm, b = {hc.b * 1e3:.3f} mm, "
                  f"{s['elements']} elements over 2a, V·Δt = {s['step'] * 1e3:.4g} mm, "
                  f"{n_steps} steps over {s['travel'] * 1e3:.4g} mm")
    t0 = time.perf_counter()
    res = case.run(progress=not args.no_progress)
    wall = time.perf_counter() - t0
    ds = res.dataset
    ds.attrs["case"] = str(args.case)
    ds.to_netcdf(out / "history.nc")
    res.fields.to_netcdf(out / "fields.nc")
    final = {k: float(v[-1]) for k, v in res.history.items()}
    summary = {"case": str(args.case), "settings": case.describe(), "mu": case.mu,
               "grid": [res.grid.nx, res.grid.ny], "dx": res.grid.dx, "dy": res.grid.dy,
               "steps": len(res.x) - 1, "wall_time_s": wall, "final": final,
               "solver": {k: res.info[k] for k in ("newton", "krylov", "solves")},
               "units": {"x": "m", "xi": "1", "eta": "1", "phi": "1/m", "Fn": "N", "Fx": "N",
                         "Fy": "N", "p_max": "Pa", "penetration": "m"}}
    (out / "summary.json").write_text(json.dumps(summary, indent=2))
    written = ["history.nc", "fields.nc", "summary.json"]
    if not args.no_figures:
        from ..transient.plot import plot_centreline, plot_creepage, plot_state

        plot_creepage(res, path=out / "creepage.png", title="longitudinal creepage")
        import numpy as np

        # like Baeza et al.'s Fig. 7: the build-up over the first semi-axes of travel
        early = res.frame_x[res.frame_x <= 5 * float(hc.a)]
        xs = early[np.unique(np.linspace(0, len(early) - 1, min(6, len(early))).round()
                             .astype(int))] if len(early) >= 3 else None
        plot_centreline(res, xs=xs, path=out / "centreline.png",
                        title="traction along the centre line")
        plot_state(res, float(res.frame_x[-1]), path=out / "state.png",
                   title="adhesion / slip, last step")
        written += ["creepage.png", "centreline.png", "state.png"]
    console.print(f"{len(res.x) - 1} steps in {wall:.2f} s ({wall / max(len(res.x) - 1, 1) * 1e3:.2f}"
                  f" ms/step); final ξ = {final['xi']:.6e}, Fx = {final['Fx']:.6g} N, "
                  f"Fn = {final['Fn']:.6g} N")
    console.print(f"wrote {', '.join(written)} to {out}")
    return 0
