"""``wheelrail dynamics CASE.toml --out DIR``: a wheelset or bogie running along a track.

Reads a case file with a ``[model]``, an optional ``[track]``, ``[method]``,
``[friction]`` and ``[simulation]`` table (see :func:`read_dynamics_case` and
``docs/examples/dynamics_wheelset.toml``), runs
:func:`wheelrail.dynamics.simulate` with a progress bar and writes to DIR:

* ``result.nc`` — the time histories (``SimulationResult.dataset``: states,
  per-patch forces, creepages, contact angles, Y/Q, wear number);
* ``summary.json`` — the settings, maxima of Y/Q and of the lateral force,
  contact-configuration changes, CPU time and real-time factor;
* ``lateral.png`` (lateral shift and yaw of every wheelset), ``forces.png``
  (Y/Q and the vertical load of every wheel) and ``contact.png`` (the contact
  points on the wheel profiles over time) — unless ``--no-figures``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

HELP = "wheelset / bogie dynamics of a [model] case file: NetCDF + figures"

_MODEL_KEYS = ("kind", "wheel", "rail", "gauge", "inclination", "nominal_radius", "mass",
               "inertia", "axle_load", "spin", "primary", "secondary", "rail_support",
               "frame_mass", "frame_inertia", "semi_wheelbase")
_SUSPENSION_KEYS = ("kx", "ky", "kz", "cx", "cy", "cz", "half_spacing")
_RAIL_KEYS = ("lateral_stiffness", "vertical_stiffness", "lateral_damping", "vertical_damping",
              "mass")
_SIM_KEYS = ("speed", "duration", "integrator", "step", "output_step", "initial", "start",
             "deceleration", "creep_relaxation")


def add_arguments(p) -> None:
    p.add_argument("case", metavar="CASE.toml", help="case file with a [model] table")
    p.add_argument("--out", metavar="DIR", default="dynamics_out",
                   help="output directory (default dynamics_out): result.nc, summary.json, "
                        "lateral.png, forces.png, contact.png")
    p.add_argument("--duration", type=float, default=None,
                   help="simulated time [s] (overrides [simulation] duration)")
    p.add_argument("--no-figures", action="store_true", help="skip the PNG figures")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")


# --------------------------------------------------------------------------- reading
def _table(r, data, name, required=False):
    if name not in data:
        if required:
            r.required_table(data, name)
        return {}
    tbl = data[name]
    if not isinstance(tbl, Mapping):
        r.fail(name, None, f"must be a table, got {tbl!r}")
    return tbl


def _construct(r, table, make):
    from ..errors import InputError

    try:
        return make()
    except InputError as exc:
        r.fail(table, None, str(exc))


def _numbers(r, table, tbl, key, n, default=None):
    v = tbl.get(key, default)
    if v is None:
        r.fail(table, key, "missing (required)")
    if (not isinstance(v, (list, tuple)) or len(v) != n
            or any(isinstance(x, bool) or not isinstance(x, (int, float)) for x in v)):
        r.fail(table, key, f"must be a list of {n} numbers, got {v!r}")
    return tuple(float(x) for x in v)


def _profile(r, base, tbl, key, default):
    from pathlib import Path

    from .. import profiles
    from ..errors import WheelrailError

    name = r.string("model", tbl, key, default)
    path = Path(name)
    if not path.is_absolute() and (base / path).exists():
        name = str(base / path)
    try:
        return profiles.load(name)
    except WheelrailError as exc:
        r.fail("model", key, str(exc))


def _suspension(r, table, tbl):
    from ..dynamics import Suspension

    if not isinstance(tbl, Mapping):
        r.fail(table, None, f"must be a table, got {tbl!r}")
    r.unknown(table, tbl, _SUSPENSION_KEYS)
    vals = {k: r.number(table, tbl, k, lo=0.0) for k in _SUSPENSION_KEYS if k in tbl}
    return _construct(r, table, lambda: Suspension(**vals))


def _read_model(r, data, base):
    from .. import dynamics as dyn
    from ..geometry import Track, Wheelset

    m = _table(r, data, "model", required=True)
    r.unknown("model", m, _MODEL_KEYS)
    kind = r.string("model", m, "kind", "wheelset")
    if kind not in ("wheelset", "bogie"):
        r.fail("model", "kind", f"must be 'wheelset' or 'bogie', got {kind!r}")
    wheel = _profile(r, base, m, "wheel", "S1002")
    rail = _profile(r, base, m, "rail", "60E1")
    ws_kw = {"nominal_radius": r.number("model", m, "nominal_radius", positive=True)} if (
        "nominal_radius" in m) else {}
    ws = _construct(r, "model", lambda: Wheelset(wheel, **ws_kw))
    tr_kw = {k: r.number("model", m, k, positive=k == "gauge", lo=None if k == "gauge" else 0.0)
             for k in ("gauge", "inclination") if k in m}
    track = _construct(r, "model", lambda: Track(rail, **tr_kw))
    common = {"wheelset": ws, "mass": r.number("model", m, "mass", positive=True),
              "inertia": _numbers(r, "model", m, "inertia", 3),
              "primary": _suspension(r, "model.primary", m.get("primary", {})),
              "spin": r.string("model", m, "spin", "free")}
    if "axle_load" in m:
        common["axle_load"] = r.number("model", m, "axle_load", positive=True)
    if "rail_support" in m:
        rs = m["rail_support"]
        if not isinstance(rs, Mapping):
            r.fail("model.rail_support", None, f"must be a table, got {rs!r}")
        r.unknown("model.rail_support", rs, _RAIL_KEYS)
        vals = {k: _numbers(r, "model.rail_support", rs, k, 2) for k in _RAIL_KEYS if k in rs}
        common["rail"] = _construct(r, "model.rail_support", lambda: dyn.RailSupport(**vals))
    if kind == "wheelset":
        for k in ("secondary", "frame_mass", "frame_inertia", "semi_wheelbase"):
            if k in m:
                r.fail("model", k, "belongs to a bogie (kind = 'bogie')")
        return _construct(r, "model", lambda: dyn.WheelsetModel(**common)), track
    bogie = dict(common, frame_mass=r.number("model", m, "frame_mass", positive=True),
                 frame_inertia=_numbers(r, "model", m, "frame_inertia", 3),
                 semi_wheelbase=r.number("model", m, "semi_wheelbase", positive=True),
                 secondary=_suspension(r, "model.secondary", m.get("secondary", {})))
    return _construct(r, "model", lambda: dyn.BogieModel(**bogie)), track


def _read_layout(r, data, track):
    from .. import dynamics as dyn

    t = _table(r, data, "track")
    r.unknown("track", t, ("curves", "irregularity", "cant_base"))
    curves = []
    for i, c in enumerate(t.get("curves", [])):
        name = f"track.curves[{i}]"
        if not isinstance(c, Mapping):
            r.fail(name, None, f"must be a table, got {c!r}")
        keys = ("radius", "start", "length", "transition", "cant", "direction")
        r.unknown(name, c, keys)
        vals = {k: r.number(name, c, k, allow_inf=k == "length") for k in keys[:-1] if k in c}
        if "direction" in c:
            vals["direction"] = r.string(name, c, "direction", "right")
        curves.append(_construct(r, name, lambda vals=vals: dyn.Curve(**vals)))
    irr = None
    if "irregularity" in t:
        g = t["irregularity"]
        if not isinstance(g, Mapping):
            r.fail("track.irregularity", None, f"must be a table, got {g!r}")
        kind = r.string("track.irregularity", g, "kind", "sine")
        keys = {"sine": ("amplitude", "wavelength", "start", "cycles", "step"),
                "bump": ("amplitude", "length", "start", "step")}
        if kind not in keys:
            r.fail("track.irregularity", "kind", f"must be 'sine' or 'bump', got {kind!r}")
        r.unknown("track.irregularity", g, ("kind", *keys[kind]))
        vals = {k: r.number("track.irregularity", g, k) for k in keys[kind] if k in g}
        make = dyn.Irregularity.sine if kind == "sine" else dyn.Irregularity.bump
        irr = _construct(r, "track.irregularity", lambda: make(**vals))
    extra = {"cant_base": r.number("track", t, "cant_base", positive=True)} if (
        "cant_base" in t) else {}
    return _construct(r, "track", lambda: dyn.TrackLayout(track, curves=tuple(curves),
                                                           irregularity=irr, **extra))


def read_dynamics_case(path_or_str):
    """Read and validate a dynamics case file.

    Tables::

        [model]                      # kind = "wheelset" (default) or "bogie"
        wheel = "S1002"              # built-in name or a profile file (relative to the case)
        rail = "60E1"
        mass = 1813.0                # [kg] (each wheelset)
        inertia = [1120.0, 100.0, 1120.0]   # roll, spin, yaw [kg m²]
        axle_load = 100e3            # [N] (optional)
        [model.primary]              # per side: kx, ky, kz [N/m], cx, cy, cz [N s/m], half_spacing [m]
        [model.rail_support]         # optional flexible rails: (k1, k2) pairs, ...
        [track]                      # optional: curves = [{radius, start, length, transition, cant,
                                     #   direction}], irregularity = {kind = "sine", amplitude, ...}
        [method]                     # normal, tangential and [method.<name>] options
        [friction]
        mu = 0.3
        [simulation]
        speed = 30.0                 # [m/s] (0: from rest, with deceleration < 0)
        duration = 2.0               # [s]
        integrator = "rk4"           # "rk4" / "heun" (fixed step = step) or a solve_ivp method
        step = 1e-3
        initial = {"ws0.y" = 0.003}

    Returns
    -------
    dict
        ``model``, ``layout``, ``normal``, ``tangential``, ``mu`` and the
        keyword arguments of :func:`wheelrail.dynamics.simulate` (``simulate``).
    """
    from pathlib import Path

    from ..casefile._reader import Reader, read_friction, read_methods, read_toml
    from ..dynamics import Adaptive, FixedStep

    data, source = read_toml(path_or_str)
    r = Reader(source)
    r.unknown("", data, ("model", "track", "method", "friction", "simulation"))
    base = Path(source).parent if Path(str(source)).exists() else Path.cwd()
    model, track = _read_model(r, data, base)
    layout = _read_layout(r, data, track)
    normal, tangential, _ = read_methods(r, _table(r, data, "method"))
    mu = read_friction(r, data)
    s = _table(r, data, "simulation", required=True)
    r.unknown("simulation", s, _SIM_KEYS)
    sim = {"speed": r.number("simulation", s, "speed", lo=0.0),
           "duration": r.number("simulation", s, "duration", positive=True),
           "start": r.number("simulation", s, "start", default=0.0),
           "deceleration": r.number("simulation", s, "deceleration", default=0.0)}
    integ = r.string("simulation", s, "integrator", "rk4")
    step = r.number("simulation", s, "step", default=1e-3, positive=True)
    sim["integrator"] = _construct(r, "simulation", lambda: (
        FixedStep(dt=step, scheme=integ) if integ in ("rk4", "heun") else
        Adaptive(method=integ)))
    if "output_step" in s:
        sim["output_step"] = r.number("simulation", s, "output_step", positive=True)
    if "initial" in s:
        init = s["initial"]
        if not isinstance(init, Mapping):
            r.fail("simulation", "initial", f"must be a table of state values, got {init!r}")
        sim["initial"] = {k: r.number("simulation.initial", init, k) for k in init}
    cr = s.get("creep_relaxation", False)
    if not isinstance(cr, bool) and not (
            isinstance(cr, (int, float)) and math.isfinite(cr) and cr > 0):
        r.fail("simulation", "creep_relaxation",
               f"must be true, false or a relaxation length in semi-axes a (> 0), got {cr!r}")
    sim["creep_relaxation"] = cr
    return {"model": model, "layout": layout, "normal": normal, "tangential": tangential,
            "mu": mu, "simulate": sim, "source": source}


# --------------------------------------------------------------------------- figures
def _figures(ds, out):
    import matplotlib
    import numpy as np

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = ds["time"].values
    written = []
    fig, ax = plt.subplots(2, 1, sharex=True, figsize=(7, 5))
    for i in ds["wheelset"].values:
        ax[0].plot(t, ds["y"].sel(wheelset=i) * 1e3, label=f"wheelset {i}")
        ax[1].plot(t, ds["yaw"].sel(wheelset=i) * 1e3, label=f"wheelset {i}")
    ax[0].set_ylabel("lateral shift y [mm]")
    ax[1].set_ylabel("yaw ψ [mrad]")
    ax[1].set_xlabel("time [s]")
    ax[0].legend()
    fig.tight_layout()
    fig.savefig(out / "lateral.png", dpi=120)
    plt.close(fig)
    written.append("lateral.png")
    fig, ax = plt.subplots(2, 1, sharex=True, figsize=(7, 5))
    for i in ds["wheelset"].values:
        for side in ("left", "right"):
            sel = {"wheelset": i, "side": side}
            ax[0].plot(t, ds["Y_over_Q"].sel(**sel), label=f"ws{i} {side}")
            ax[1].plot(t, ds["vertical_load"].sel(**sel) * 1e-3, label=f"ws{i} {side}")
    ax[0].set_ylabel("Y/Q [-]")
    ax[1].set_ylabel("Q [kN]")
    ax[1].set_xlabel("time [s]")
    ax[0].legend(fontsize="small", ncol=2)
    fig.tight_layout()
    fig.savefig(out / "forces.png", dpi=120)
    plt.close(fig)
    written.append("forces.png")
    fig, ax = plt.subplots(figsize=(7, 3.5))
    Fn = ds["Fn"].sel(wheelset=0)
    for side, marker in (("left", "."), ("right", "x")):
        wy = ds["wheel_y"].sel(wheelset=0, side=side).values
        loaded = Fn.sel(side=side).values > 0
        tt = (t[:, None] * np.ones(wy.shape[1]))[loaded]
        ax.plot(tt, wy[loaded] * 1e3, marker, ms=2, ls="none", label=f"{side} wheel")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("contact point on wheel [mm]")
    ax.set_title("wheelset 0: contact points (every loaded patch)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(out / "contact.png", dpi=120)
    plt.close(fig)
    written.append("contact.png")
    return written


# --------------------------------------------------------------------------- run
def run(args, console) -> int:
    import json
    from pathlib import Path

    import numpy as np

    from .. import dynamics as dyn
    from ..errors import InputError

    case = read_dynamics_case(args.case)
    sim = dict(case["simulate"])
    if args.duration is not None:
        if not args.duration > 0:
            raise InputError(f"--duration must be > 0 s, got {args.duration!r}")
        sim["duration"] = float(args.duration)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    model = case["model"]
    console.print(f"dynamics: {type(model).__name__} ({model.n_wheelsets} wheelset(s)), "
                  f"{case['normal'].name} × {case['tangential'].name}, μ = {case['mu']:g}, "
                  f"V = {sim['speed']:g} m/s, {sim['duration']:g} s, {sim['integrator']!r}")
    from ..dynamics.simulate import SimulationInterrupted

    interrupted = None
    try:
        res = dyn.simulate(model, case["layout"], sim.pop("speed"), sim.pop("duration"),
                           case["normal"], case["tangential"], mu=case["mu"],
                           progress=not args.no_progress, **sim)
    except SimulationInterrupted as exc:
        # Ctrl-C: keep what was simulated (a valid result.nc marked interrupted), then 130
        res, interrupted = exc.result, exc
    ds = res.dataset
    ds.attrs["case"] = str(args.case)
    ds.to_netcdf(out / "result.nc")
    yq = ds["Y_over_Q"]
    summary = {"case": str(args.case), "model": type(model).__name__,
               "normal": res.info["normal"], "tangential": res.info["tangential"],
               "mu": case["mu"], "integrator": res.info["integrator"],
               "simulated_s": float(res.t[-1] - res.t[0]), "cpu_time_s": res.info["cpu_time"],
               "real_time_factor": res.info["real_time_factor"],
               "contact_evaluations": res.info["contact_evaluations"],
               "max_Y_over_Q": float(np.nanmax(np.abs(yq.values))),
               "max_lateral_shift_m": float(np.max(np.abs(ds["y"].values))),
               "contact_changes": len(res.events),
               "interrupted": bool(res.info.get("interrupted")),
               "derailment": res.info.get("derailment"),
               "substeps": res.info.get("substeps", 1),
               "units": {"time": "s", "y": "m", "yaw": "rad", "Fn": "N", "Y_over_Q": "1"}}
    (out / "summary.json").write_text(json.dumps(summary, indent=2))
    written = ["result.nc", "summary.json"]
    if interrupted is not None:
        from ._output import esc

        console.print(f"interrupted at t = {summary['simulated_s']:.4g} s: wrote result.nc "
                      f"(marked interrupted) and summary.json to {esc(out)}")
        raise KeyboardInterrupt from None
    if not args.no_figures:
        written += _figures(ds, out)
    console.print(f"{summary['simulated_s']:.3f} s simulated in {summary['cpu_time_s']:.2f} s "
                  f"CPU (real-time factor {summary['real_time_factor']:.2f}); max |Y/Q| = "
                  f"{summary['max_Y_over_Q']:.3f}, max |y| = "
                  f"{summary['max_lateral_shift_m'] * 1e3:.2f} mm, "
                  f"{summary['contact_changes']} contact-configuration changes")
    d = summary["derailment"]
    if d:
        console.print(f"DERAILMENT: Y/Q = {d['max_Y_over_Q']:.3g} beyond Nadal's limit "
                      f"{d['nadal_limit']:.3g} (wheelset {d['wheelset']}, {d['side']} wheel, "
                      f"from t = {d['t']:.4g} s); the motion after it is not physical",
                      markup=False, highlight=False)
    from ._output import esc

    console.print(f"wrote {', '.join(written)} to {esc(out)}")
    return 0
