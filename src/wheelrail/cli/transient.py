"""``wheelrail transient CASE.toml --out DIR``: transient rolling of a ``[transient]`` case.

Reads the case with :func:`wheelrail.cases.files.load_transient_case`, runs
:func:`wheelrail.transient_rolling` with a progress bar and writes to DIR:

* ``history.nc`` — the scalar histories over the travel (``TransientResult.dataset``);
* ``fields.nc`` — the stored traction fields (``TransientResult.fields``);
* ``summary.json`` — the settings, final values and solver counts;
* ``creepage.png``, ``centreline.png``, ``state.png`` — figures after Baeza et al.
  Figs. 8/9/11, 7 and 10/12 (unless ``--no-figures``).
"""

from __future__ import annotations

from ._output import esc

HELP = "transient (instationary) rolling of a [transient] case file: NetCDF + figures"


def add_arguments(p) -> None:
    p.add_argument("case", metavar="CASE.toml", help="case file with a [transient] table")
    p.add_argument("--out", metavar="DIR", default="transient_out",
                   help="output directory (default transient_out): history.nc, fields.nc, "
                        "summary.json, creepage.png, centreline.png, state.png")
    p.add_argument("--no-figures", action="store_true", help="skip the PNG figures")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")


#: CPU time per time step and grid cell [s] (benchmarks/bench_estimates.py: a fit of
#: STARTUP + steps × cells × STEP_COST to 120 steps at 20–80 elements across 2a, 676–10 201
#: cells, 1.7–11.4 s CPU on one core of the 2-core machine, within ±15 %).
STEP_COST = 8.3e-6
#: Start-up (kernels from the numba cache, influence coefficients) [s].
STARTUP = 0.8


def estimate(hc, settings) -> tuple[float, float, int]:
    """Time [s], memory [bytes] and grid cells of a transient run, before it is set up.

    The grid is square, about 1.25 × the elements across 2a on a side (30
    elements: 39 × 39 cells); each step costs :data:`STEP_COST` per cell; the memory holds
    the stored frames (about 10 fields of 8 bytes per cell), the history
    (about 12 values per step) and the solver's FFT buffers.
    """
    import math

    e = float(settings["elements"])
    nx = int(math.ceil(1.25 * e)) + 1  # 30 elements: 39 x 39, 60: 75 x 75
    cells = nx * nx
    steps = float(settings["travel"]) / float(settings["step"])
    frames = float(settings.get("frames", 60) or 60)
    seconds = STARTUP + steps * cells * STEP_COST
    memory = 200e6 + cells * (frames * 80.0 + 4 * 16 * 8) + steps * 12 * 8
    return seconds, memory, cells


def run(args, console) -> int:
    import time
    from pathlib import Path

    from ..cases.files import load_transient_case

    from .._resources import check

    case = load_transient_case(args.case)
    hc = case.hertz_contact
    s = case.settings
    n_steps = int(s["travel"] / s["step"] + 1e-9)
    seconds, memory, cells = estimate(hc, s)
    check(f"transient run of {n_steps} steps on about {cells} grid cells", seconds, memory,
          f"{STEP_COST * 1e6:.3g} µs per step and grid cell")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    console.print(f"transient rolling: a = {hc.a * 1e3:.3f} mm, b = {hc.b * 1e3:.3f} mm, "
                  f"{s['elements']} elements over 2a, V·Δt = {s['step'] * 1e3:.4g} mm, "
                  f"{n_steps} steps over {s['travel'] * 1e3:.4g} mm")
    t0 = time.perf_counter()
    res = case.run(progress=not args.no_progress)
    wall = time.perf_counter() - t0
    ds = res.dataset
    ds.attrs["case"] = str(args.case)
    from .._atomic import atomic_path

    with atomic_path(out / "history.nc") as tmp:
        ds.to_netcdf(tmp)
    with atomic_path(out / "fields.nc") as tmp:
        res.fields.to_netcdf(tmp)
    final = {k: float(v[-1]) for k, v in res.history.items()}
    summary = {"case": str(args.case), "settings": case.describe(), "mu": case.mu,
               "grid": [res.grid.nx, res.grid.ny], "dx": res.grid.dx, "dy": res.grid.dy,
               "steps": len(res.x) - 1, "wall_time_s": wall, "final": final,
               "solver": {k: res.info[k] for k in ("newton", "krylov", "solves")},
               "units": {"x": "m", "xi": "1", "eta": "1", "phi": "1/m", "Fn": "N", "Fx": "N",
                         "Fy": "N", "p_max": "Pa", "penetration": "m"}}
    from ._output import write_json

    write_json(summary, out / "summary.json")
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
    console.print(f"wrote {', '.join(written)} to {esc(out)}")
    return 0
