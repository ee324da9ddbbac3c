"""``wheelrail wear CASE.toml``: wheel profile evolution by wear over a route.

Reads a case file with a ``[model]`` table (as ``wheelrail dynamics``: a
wheelset, a bogie or a whole vehicle, its profiles and suspension), an optional ``[method]``
table, a ``[route]`` with its ``[[route.cases]]``, a ``[wear]`` table and an
optional ``[output]`` table (see :func:`read_wear_case` and
``docs/examples/wear_route.toml``), prints an estimate, runs
:func:`wheelrail.wear.evolve` with one progress line per wear step and a
checkpoint after each (a killed run started again resumes after its last
finished step), and writes to the output directory:

* ``wear.nc`` — the dataset (:attr:`EvolveResult.dataset`: profiles per step,
  Sh, Sd, qR, equivalent conicity, wear rates, rail wear, Tγ);
* ``summary.json`` — settings, steps, mileage, Sd/Sh/qR and conicity at the
  start and at the end, CPU time;
* ``profiles.png`` (overlay of the wheel profile of every step) and
  ``dimensions.png`` (Sd, Sh, qR and the equivalent conicity against km) —
  unless ``--no-figures``;
* ``checkpoint/`` — the steps (kept: remove it to start afresh).
"""

from __future__ import annotations

import math
from collections.abc import Mapping

HELP = "wheel profile evolution by wear over a route of dynamics cases: NetCDF + figures"

_CASE_KEYS = ("name", "weight", "speed", "mu", "radius", "cant", "start", "transition",
              "length", "direction", "distance", "run_in", "irregularity", "initial")
_WEAR_KEYS = ("law", "options", "mileage", "step_depth", "smoothing", "resolution",
              "profiles", "samples", "cells", "conicity", "executor", "workers", "scheduler",
              "max_steps", "update_rail", "rail_passages", "wheelsets")
#: nominal CPU time per simulated second and wheelset (RK4, Kik–Piotrowski + FASTSIM; measured
#: 0.45 s with docs/examples/wear_route.toml, a wheelset, process time at load 12 on 2 cores)
_CPU_PER_SIMULATED_S = 0.5


def add_arguments(p) -> None:
    p.add_argument("case", metavar="CASE.toml", help="case file with [model], [route], [wear]")
    p.add_argument("--out", metavar="DIR", default=None,
                   help="output directory (default: [output] dir of the case, else wear_out): "
                        "wear.nc, summary.json, profiles.png, dimensions.png, checkpoint/")
    p.add_argument("--mileage", type=float, default=None,
                   help="distance to run [m] (overrides [wear] mileage)")
    p.add_argument("--no-figures", action="store_true", help="skip the PNG figures")
    p.add_argument("--no-progress", action="store_true", help="no progress lines")


# --------------------------------------------------------------------------- reading
def _int(r, table, tbl, key, default, lo=1):
    v = tbl.get(key, default)
    if isinstance(v, bool) or not isinstance(v, int) or v < lo:
        r.fail(table, key, f"must be an integer >= {lo}, got {v!r}")
    return v


def _route_case(r, i, c, track):
    from .. import dynamics as dyn
    from ..wear import RouteCase
    from .dynamics import _construct

    name = f"route.cases[{i}]"
    if not isinstance(c, Mapping):
        r.fail(name, None, f"must be a table, got {c!r}")
    r.unknown(name, c, _CASE_KEYS)
    curve_keys = ("cant", "start", "transition", "length", "direction")
    if "radius" not in c:
        for k in curve_keys:
            if k in c:
                r.fail(name, k, "belongs to a curve: give its radius too")
    curves = ()
    if "radius" in c:
        vals = {k: r.number(name, c, k, allow_inf=k == "length")
                for k in ("radius", "cant", "start", "transition", "length") if k in c}
        if "direction" in c:
            vals["direction"] = r.string(name, c, "direction", "right")
        curves = (_construct(r, name, lambda: dyn.Curve(**vals)),)
    irr = None
    if "irregularity" in c:
        g = c["irregularity"]
        tname = f"{name}.irregularity"
        if not isinstance(g, Mapping):
            r.fail(tname, None, f"must be a table, got {g!r}")
        kind = r.string(tname, g, "kind", "sine")
        keys = {"sine": ("amplitude", "wavelength", "start", "cycles", "step"),
                "bump": ("amplitude", "length", "start", "step")}
        if kind not in keys:
            r.fail(tname, "kind", f"must be 'sine' or 'bump', got {kind!r}")
        r.unknown(tname, g, ("kind", *keys[kind]))
        gv = {k: r.number(tname, g, k) for k in keys[kind] if k in g}
        make = dyn.Irregularity.sine if kind == "sine" else dyn.Irregularity.bump
        irr = _construct(r, tname, lambda: make(**gv))
    layout = _construct(r, name, lambda: dyn.TrackLayout(track, curves=curves, irregularity=irr))
    kw = {"speed": r.number(name, c, "speed", positive=True),
          "weight": r.number(name, c, "weight", default=1.0, positive=True),
          "mu": r.number(name, c, "mu", default=0.3, positive=True),
          "distance": r.number(name, c, "distance", default=50.0, positive=True),
          "run_in": r.number(name, c, "run_in", default=0.0, lo=0.0),
          "name": r.string(name, c, "name", f"case{i}")}
    if "initial" in c:
        init = c["initial"]
        if not isinstance(init, Mapping):
            r.fail(name, "initial", f"must be a table of state values, got {init!r}")
        kw["initial"] = {k: r.number(f"{name}.initial", init, k) for k in init}
    return _construct(r, name, lambda: RouteCase(layout, **kw))


def read_wear_case(path_or_str) -> dict:
    """Read and validate a wear case file.

    Tables::

        [model]                 # as in `wheelrail dynamics`: kind = "wheelset" / "bogie" /
                                # "vehicle" (vehicle = "manchester1" or bogie keys + carbody),
                                # wheel, rail, mass, inertia, axle_load, [model.primary], ...
        [method]                # optional: normal, tangential and [method.<name>] options
        [[route.cases]]         # one table per case
        name = "R300"
        weight = 0.3            # share of the mileage (normalised over the cases)
        speed = 15.0            # [m/s]
        mu = 0.3
        radius = 300.0          # [m]; no radius: tangent track
        cant = 0.1              # [m]; also start, transition, length [m], direction
        distance = 5.0          # simulated per step after run_in [m]
        run_in = 30.0           # [m], not counted
        irregularity = {kind = "sine", amplitude = 0.002, wavelength = 25.0}
        [wear]
        law = "usfd"            # archard, kth, usfd, energy; [wear.options] its options
        mileage = 10e3          # [m]
        step_depth = 0.05e-3    # largest depth change per step [m]
        smoothing = 2e-3        # [m]
        profiles = "sides"      # or "mean"
        wheelsets = [0]         # optional: whose wear sets the profile (default all)
        executor = "serial"     # or "dask", "processes"; workers, scheduler
        update_rail = false     # true: wear the rails too, with
        rail_passages = 0.01    # passages over each case's rail per metre of mileage [1/m]
        [output]
        dir = "wear_out"

    Returns
    -------
    dict
        ``model``, ``route`` (:class:`wheelrail.wear.Route`), ``evolve`` (keyword
        arguments of :func:`wheelrail.wear.evolve`), ``out`` (the output directory or
        None) and ``source``.
    """
    from pathlib import Path

    from ..cases.files._reader import Reader, read_methods, read_toml
    from ..wear import Route, wear_laws
    from ..wear import get as get_law
    from .dynamics import _construct, _read_model, _table

    data, source = read_toml(path_or_str)
    r = Reader(source)
    r.unknown("", data, ("model", "method", "route", "wear", "output"))
    base = Path(source).parent if Path(str(source)).exists() else Path.cwd()
    model, track = _read_model(r, data, base)
    normal, tangential, _ = read_methods(r, _table(r, data, "method"))
    route_t = _table(r, data, "route", required=True)
    r.unknown("route", route_t, ("cases",))
    cases = route_t.get("cases")
    if not isinstance(cases, list) or not cases:
        r.fail("route", "cases", f"must be a list of one or more case tables "
                                 f"([[route.cases]]), got {cases!r}")
    route = _construct(r, "route", lambda: Route(tuple(
        _route_case(r, i, c, track) for i, c in enumerate(cases))))
    w = _table(r, data, "wear", required=True)
    r.unknown("wear", w, _WEAR_KEYS)
    law_name = r.string("wear", w, "law", "usfd")
    if law_name not in wear_laws():
        r.fail("wear", "law", f"unknown wear law {law_name!r}; known: "
                              + ", ".join(wear_laws()))
    opts = w.get("options", {})
    if not isinstance(opts, Mapping):
        r.fail("wear", "options", f"must be a table of the law's options, got {opts!r}")
    from ..cases.files._reader import configure

    law = configure(r, "wear.options", type(get_law(law_name)), opts)
    kw = {"law": law, "normal": normal, "tangential": tangential,
          "mileage": r.number("wear", w, "mileage", positive=True),
          "step_depth": r.number("wear", w, "step_depth", default=0.1e-3, positive=True),
          "smoothing": r.number("wear", w, "smoothing", default=2e-3, lo=0.0),
          "resolution": r.number("wear", w, "resolution", default=0.25e-3, positive=True),
          "profiles": r.string("wear", w, "profiles", "mean"),
          "samples": _int(r, "wear", w, "samples", 100),
          "cells": _int(r, "wear", w, "cells", 12, lo=2),
          "max_steps": _int(r, "wear", w, "max_steps", 200),
          "executor": r.string("wear", w, "executor", "dask")}
    if kw["profiles"] not in ("mean", "sides"):
        r.fail("wear", "profiles", f"must be 'mean' or 'sides', got {kw['profiles']!r}")
    if kw["executor"] not in ("dask", "processes", "serial"):
        r.fail("wear", "executor",
               f"must be 'dask', 'processes' or 'serial', got {kw['executor']!r}")
    con = w.get("conicity", True)
    if not isinstance(con, bool):
        r.fail("wear", "conicity", f"must be true or false, got {con!r}")
    kw["conicity"] = con
    upd = w.get("update_rail", False)
    if not isinstance(upd, bool):
        r.fail("wear", "update_rail", f"must be true or false, got {upd!r}")
    if upd:
        kw["update_rail"] = True
        kw["rail_passages"] = r.number("wear", w, "rail_passages", positive=True)
    elif "rail_passages" in w:
        r.fail("wear", "rail_passages", "needs update_rail = true")
    if "wheelsets" in w:
        g = w["wheelsets"]
        n = model.n_wheelsets
        if (not isinstance(g, list) or not g or any(isinstance(i, bool) or not isinstance(i, int)
                                                     or not 0 <= i < n for i in g)):
            r.fail("wear", "wheelsets", f"must be a list of wheelset indices 0 … {n - 1} "
                                        f"(0 the leading one), got {g!r}")
        kw["wheelsets"] = tuple(g)
    if "workers" in w:
        kw["workers"] = _int(r, "wear", w, "workers", 1)
    if "scheduler" in w:
        kw["scheduler"] = r.string("wear", w, "scheduler", "")
    o = _table(r, data, "output")
    r.unknown("output", o, ("dir",))
    out = None
    if "dir" in o:
        out = Path(r.string("output", o, "dir", "wear_out"))
        if not out.is_absolute():
            out = base / out
    return {"model": model, "route": route, "evolve": kw, "out": out, "source": source}


# --------------------------------------------------------------------------- estimate
def estimate_step_cpu(model, route, samples: int) -> float:
    """Nominal CPU time of one wear step [s]: every case's simulated time (run-in +
    distance) / speed × :data:`_CPU_PER_SIMULATED_S` per wheelset, plus the FASTSIM
    post-processing of ``samples`` time points (≈ 2 ms each and wheelset)."""
    n = model.n_wheelsets
    sim = sum((c.run_in + c.distance) / c.speed for c in route.cases)
    return sim * _CPU_PER_SIMULATED_S * n + len(route.cases) * samples * n * 2e-3


# --------------------------------------------------------------------------- figures
def figures(ds, out, profiles=None):
    """``profiles.png`` (the wheel profile of every step) and ``dimensions.png``
    (Sd, Sh, qR and the equivalent conicity against km); returns the file names."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    km = ds["mileage"].values / 1e3
    y = ds["y"].values * 1e3
    cmap = plt.get_cmap("viridis")
    sides = [s for s in ds["side"].values
             if s == "left" or not np.allclose(ds["wheel_z"].sel(side=s),
                                               ds["wheel_z"].sel(side="left"))]
    fig, axes = plt.subplots(len(sides), 1, figsize=(7, 3.2 * len(sides)), squeeze=False)
    n = ds.sizes["step"]
    for ax, side in zip(axes[:, 0], sides):
        z0 = ds["wheel_z"].isel(step=0).sel(side=side).values
        for k in range(n):
            z = ds["wheel_z"].isel(step=k).sel(side=side).values
            ax.plot(y, z * 1e3, color=cmap(k / max(n - 1, 1)), lw=0.8,
                    label=f"{km[k]:.1f} km" if k in (0, n - 1) else None)
        ax.invert_yaxis()
        ax.set_xlabel("lateral coordinate y [mm]")
        ax.set_ylabel("z [mm] (down)")
        ax.set_title(f"wheel profile ({'all wheels' if len(sides) == 1 else side})")
        ax.legend(fontsize="small")
        depth = ax.twinx()
        for k in range(1, n):
            z = ds["wheel_z"].isel(step=k).sel(side=side).values
            depth.plot(y, (z - z0) * 1e3, color=cmap(k / max(n - 1, 1)), lw=0.8, ls="--")
        depth.set_ylabel("worn depth since 0 km [mm] (dashed)")
    fig.tight_layout()
    fig.savefig(out / "profiles.png", dpi=120)
    plt.close(fig)
    fig, ax = plt.subplots(2, 2, sharex=True, figsize=(8, 5.5))
    for var, a in (("Sd", ax[0, 0]), ("Sh", ax[0, 1]), ("qR", ax[1, 0])):
        for side in sides:
            a.plot(km, ds[var].sel(side=side) * 1e3, "o-", ms=3, label=side)
        a.set_ylabel(f"{var} [mm]")
        if len(sides) > 1:
            a.legend(fontsize="small")
    ax[1, 1].plot(km, ds["conicity"], "o-", ms=3, color="k")
    ax[1, 1].set_ylabel("equivalent conicity [-]")
    for a in ax[1]:
        a.set_xlabel("mileage [km]")
    fig.tight_layout()
    fig.savefig(out / "dimensions.png", dpi=120)
    plt.close(fig)
    return ["profiles.png", "dimensions.png"]


# --------------------------------------------------------------------------- run
def run(args, console) -> int:
    import json
    import time
    from pathlib import Path

    from .. import _resources
    from ..errors import InputError
    from ..wear import evolve
    from ._output import esc

    case = read_wear_case(args.case)
    kw = dict(case["evolve"])
    if args.mileage is not None:
        if not (math.isfinite(args.mileage) and args.mileage > 0):
            raise InputError(f"--mileage must be > 0 m, got {args.mileage!r}")
        kw["mileage"] = float(args.mileage)
    out = Path(args.out) if args.out is not None else (case["out"] or Path("wear_out"))
    model, route = case["model"], case["route"]
    law = kw["law"]
    per_step = estimate_step_cpu(model, route, kw["samples"])
    console.print(f"wear: {type(model).__name__} ({model.n_wheelsets} wheelset(s)), "
                  f"{len(route.cases)} case(s) ({', '.join(route.names)}), law {law.name}, "
                  f"{kw['mileage'] / 1e3:g} km, step depth {kw['step_depth'] * 1e3:g} mm",
                  markup=False)
    # steps are known after the first one (they follow from its wear rate): check one step
    # now against the limits, and the whole run when the first step has given the rate
    _resources.check(f"wear step of {len(route.cases)} case(s)", per_step, 200e6,
                     "nominal; the number of steps follows from the first step's wear rate, "
                     f"at most {kw['max_steps']}")
    console.print(f"estimate: about {per_step:.1f} s CPU per step (nominal) × the number of "
                  f"steps (estimated after the first step, at most {kw['max_steps']})",
                  markup=False)
    out.mkdir(parents=True, exist_ok=True)
    state = {"first": True}

    def on_step(info):
        if state["first"]:
            state["first"] = False
            total = info["steps_left"] + 1
            console.print(f"estimate: {info['cpu']:.1f} s CPU per step (measured) × "
                          f"{total} step(s) ≈ {info['cpu'] * total:.0f} s CPU", markup=False)
            _resources.check(f"wear run of {total} steps", info["cpu"] * info["steps_left"],
                             200e6, f"{info['cpu']:.1f} s per step, measured on the first")
        if not args.no_progress:
            pct = 100.0 * info["mileage"] / info["total"]
            console.print(f"step {info['step']}: {info['mileage'] / 1e3:9.2f} km ({pct:5.1f} %)"
                          f"  Sd {info['Sd'][0] * 1e3:.3f} / {info['Sd'][1] * 1e3:.3f} mm"
                          f"  conicity {info['conicity']:.4f}  {info['cpu']:.1f} s CPU"
                          f"  ~{info['steps_left']} step(s) left", markup=False)

    t0 = time.process_time()
    res = evolve(model, route, store=out / "checkpoint", on_step=on_step, **kw)
    ds = res.dataset
    ds.attrs["case"] = str(args.case)
    ds.attrs["law"] = repr(law)
    ds.attrs["weights"] = [float(x) for x in ds.attrs["weights"]]
    ds.to_netcdf(out / "wear.nc")
    first, last = ds.isel(step=0), ds.isel(step=-1)
    summary = {"case": str(args.case), "model": type(model).__name__, "law": repr(law),
               "cases": route.names, "weights": [float(x) for x in route.weights],
               "steps": int(ds.sizes["step"]), "mileage_m": float(last["mileage"]),
               "start": {v: [float(x) for x in first[v].values] for v in ("Sd", "Sh", "qR")},
               "end": {v: [float(x) for x in last[v].values] for v in ("Sd", "Sh", "qR")},
               "conicity": [float(first["conicity"]), float(last["conicity"])],
               "cpu_time_s": time.process_time() - t0,
               "cases_cpu_time_s": float(ds["case_cpu"].sum()),
               "units": {"Sd": "m", "Sh": "m", "qR": "m", "mileage": "m"}}
    (out / "summary.json").write_text(json.dumps(summary, indent=2))
    written = ["wear.nc", "summary.json"]
    if not args.no_figures:
        written += figures(ds, out)
    console.print(f"{summary['steps']} step(s), {summary['mileage_m'] / 1e3:g} km: Sd "
                  f"{first['Sd'].values[0] * 1e3:.3f} → {last['Sd'].values[0] * 1e3:.3f} mm "
                  f"(left), conicity {summary['conicity'][0]:.4f} → "
                  f"{summary['conicity'][1]:.4f}; {summary['cases_cpu_time_s']:.1f} s CPU in "
                  f"the cases", markup=False)
    console.print(f"wrote {', '.join(written)} to {esc(out)}")
    return 0
