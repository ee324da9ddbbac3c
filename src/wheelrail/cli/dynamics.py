"""``wheelrail dynamics CASE.toml --out DIR``: a wheelset, bogie or whole vehicle on a track.

Reads a case file with a ``[model]``, an optional ``[track]``, ``[method]``,
``[friction]`` and ``[simulation]`` table (see :func:`read_dynamics_case`,
``docs/examples/dynamics_wheelset.toml`` and ``docs/examples/dynamics_vehicle.toml``),
runs :func:`wheelrail.dynamics.simulate` with a progress bar, assesses the run
(:func:`wheelrail.dynamics.assess`) and writes to DIR:

* ``result.nc`` — the time histories (``SimulationResult.dataset``: states,
  per-patch forces, creepages, contact angles, Y/Q, wear number); a run of more
  than :data:`STREAM_OUTPUTS` outputs, or any run with ``--store``, writes them
  instead to ``result.zarr`` while it goes (its memory then does not grow with the
  duration; read it with :func:`wheelrail.dynamics.open_result`);
* ``summary.json`` — the settings, maxima of Y/Q and of the lateral force,
  contact-configuration changes, CPU time, real-time factor and the assessment's verdicts;
* ``assessment.nc`` and ``assessment.csv`` — EN 14363 (Y/Q)2m and (ΣY)2m with their
  limits, Y and Q extremes, wear number per wheel; car-body accelerations and
  Sperling's Wz for a vehicle;
* ``lateral.png`` (lateral shift and yaw of every wheelset), ``forces.png``
  (Y/Q and the vertical load of every wheel) and ``contact.png`` (the contact
  points on the wheel profiles over time), ``assessment.png`` and, for a vehicle,
  ``carbody.png`` — unless ``--no-figures``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

from ._vehicle_case import VEHICLE_KEYS, _construct, read_vehicle

HELP = "wheelset / bogie / vehicle dynamics of a [model] case file: NetCDF, assessment, figures"

_MODEL_KEYS = ("kind", "wheel", "rail", "gauge", "inclination", "nominal_radius", "mass",
               "inertia", "axle_load", "spin", "primary", "secondary", "rail_support",
               "frame_mass", "frame_inertia", "semi_wheelbase") + VEHICLE_KEYS
_SUSPENSION_KEYS = ("kx", "ky", "kz", "cx", "cy", "cz", "half_spacing")
_RAIL_KEYS = ("lateral_stiffness", "vertical_stiffness", "lateral_damping", "vertical_damping",
              "mass")
_SIM_KEYS = ("speed", "speed_profile", "duration", "integrator", "step", "output_step",
             "initial", "start", "deceleration", "creep_relaxation")


#: Runs with more outputs than this write their histories to ``result.zarr`` as they go
#: (200 s at the default output step of 1 ms: 0.3–1 GB in memory otherwise).
STREAM_OUTPUTS = 200_000


def add_arguments(p) -> None:
    p.add_argument("case", metavar="CASE.toml", help="case file with a [model] table")
    p.add_argument("--out", metavar="DIR", default="dynamics_out",
                   help="output directory (default dynamics_out): result.nc, summary.json, "
                        "lateral.png, forces.png, contact.png")
    p.add_argument("--duration", type=float, default=None,
                   help="simulated time [s] (overrides [simulation] duration)")
    p.add_argument("--no-figures", action="store_true", help="skip the PNG figures")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    p.add_argument("--store", action="store_true",
                   help="write the histories to result.zarr while the run goes (memory "
                        "independent of the duration; automatic above "
                        f"{STREAM_OUTPUTS:,} outputs)")


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
    from .. import profiles
    from ..geometry import Track, Wheelset

    m = _table(r, data, "model", required=True)
    r.unknown("model", m, _MODEL_KEYS)
    kind = r.string("model", m, "kind", "wheelset")
    if kind not in ("wheelset", "bogie", "vehicle"):
        r.fail("model", "kind", f"must be 'wheelset', 'bogie' or 'vehicle', got {kind!r}")
    if kind != "vehicle":
        for k in VEHICLE_KEYS:
            if k in m:
                r.fail("model", k, "belongs to a vehicle (kind = 'vehicle')")
    rail_support = None
    if "rail_support" in m:
        rs = m["rail_support"]
        if not isinstance(rs, Mapping):
            r.fail("model.rail_support", None, f"must be a table, got {rs!r}")
        r.unknown("model.rail_support", rs, _RAIL_KEYS)
        vals = {k: _numbers(r, "model.rail_support", rs, k, 2) for k in _RAIL_KEYS if k in rs}
        rail_support = _construct(r, "model.rail_support", lambda: dyn.RailSupport(**vals))
    if kind == "vehicle" and "vehicle" in m:          # a built-in vehicle: its own profiles
        model = read_vehicle(r, m, None, rail_support, _numbers)
        track = Track(profiles.load("60E1"), gauge=1.435, inclination=1 / 40)
        return model, track
    wheel = _profile(r, base, m, "wheel", "S1002")
    rail = _profile(r, base, m, "rail", "60E1")
    ws_kw = {"nominal_radius": r.number("model", m, "nominal_radius", positive=True)} if (
        "nominal_radius" in m) else {}
    ws = _construct(r, "model", lambda: Wheelset(wheel, **ws_kw))
    tr_kw = {k: r.number("model", m, k, positive=k == "gauge", lo=None if k == "gauge" else 0.0)
             for k in ("gauge", "inclination") if k in m}
    track = _construct(r, "model", lambda: Track(rail, **tr_kw))

    def common():
        c = {"wheelset": ws, "mass": r.number("model", m, "mass", positive=True),
             "inertia": _numbers(r, "model", m, "inertia", 3),
             "primary": _suspension(r, "model.primary", m.get("primary", {})),
             "spin": r.string("model", m, "spin", "free")}
        if "axle_load" in m:
            c["axle_load"] = r.number("model", m, "axle_load", positive=True)
        if rail_support is not None:
            c["rail"] = rail_support
        return c

    def bogie():
        return dict(common(), frame_mass=r.number("model", m, "frame_mass", positive=True),
                    frame_inertia=_numbers(r, "model", m, "frame_inertia", 3),
                    semi_wheelbase=r.number("model", m, "semi_wheelbase", positive=True))

    if kind == "wheelset":
        for k in ("secondary", "frame_mass", "frame_inertia", "semi_wheelbase"):
            if k in m:
                r.fail("model", k, "belongs to a bogie (kind = 'bogie')")
        return _construct(r, "model", lambda: dyn.WheelsetModel(**common())), track
    if kind == "vehicle":
        if "axle_load" in m:
            r.fail("model", "axle_load", "a vehicle's axle load follows from its masses")
        return read_vehicle(r, m, bogie, rail_support, _numbers), track
    kw = dict(bogie(), secondary=_suspension(r, "model.secondary", m.get("secondary", {})))
    return _construct(r, "model", lambda: dyn.BogieModel(**kw)), track


def _read_layout(r, data, track, base=None):
    from pathlib import Path

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
                "bump": ("amplitude", "length", "start", "step"),
                "file": ("path", "units"),
                "psd": ("spectrum", "length", "seed", "start", "ramp", "step")}
        if kind not in keys:
            r.fail("track.irregularity", "kind",
                   f"must be 'sine', 'bump', 'file' or 'psd', got {kind!r}")
        r.unknown("track.irregularity", g, ("kind", *keys[kind]))
        if kind == "file":          # measured: distance [m], alignment, level, cross level, gauge
            path = Path(r.string("track.irregularity", g, "path", ""))
            if not str(path):
                r.fail("track.irregularity", "path", "missing (required)")
            if not path.is_absolute():
                path = (base or Path.cwd()) / path
            units = r.string("track.irregularity", g, "units", "mm")
            irr = _construct(r, "track.irregularity",
                             lambda: dyn.TrackIrregularity.from_file(path, units=units))
        elif kind == "psd":         # a standard spectrum, reproducibly from the seed
            spec = r.string("track.irregularity", g, "spectrum", "")
            seed = g.get("seed", 0)
            if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
                r.fail("track.irregularity", "seed", f"must be an integer >= 0, got {seed!r}")
            vals = {k: r.number("track.irregularity", g, k) for k in ("start", "ramp", "step")
                    if k in g}
            length = r.number("track.irregularity", g, "length", positive=True)
            irr = _construct(r, "track.irregularity", lambda: dyn.TrackIrregularity.from_psd(
                spec, length, seed, **vals))
        else:
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

        [model]                      # kind = "wheelset" (default), "bogie" or "vehicle"
                                     # vehicle: vehicle = "manchester1" (built in; with
                                     #   spin, rail_support, [model.yaw_damper]) or the
                                     #   bogie keys + [model.carbody] (mass, inertia,
                                     #   height) + [model.secondary] (kx ... cz,
                                     #   half_spacing, height, yaw_stiffness, anti_roll,
                                     #   [..yaw_damper] damping/stiffness/half_spacing,
                                     #   [..bumpstop] displacement/force lists),
                                     #   bogie_semi_spacing, frame_height, primary_height
        wheel = "S1002"              # built-in name or a profile file (relative to the case)
        rail = "60E1"
        mass = 1813.0                # [kg] (each wheelset)
        inertia = [1120.0, 100.0, 1120.0]   # roll, spin, yaw [kg m²]
        axle_load = 100e3            # [N] (optional)
        [model.primary]              # per side: kx, ky, kz [N/m], cx, cy, cz [N s/m], half_spacing [m]
        [model.rail_support]         # optional flexible rails: (k1, k2) pairs, ...
        [track]                      # optional: curves = [{radius, start, length, transition, cant,
                                     #   direction}], irregularity = {kind = "sine", amplitude, ...}
                                     #   or {kind = "psd", spectrum = "erri-low", length, seed}
                                     #   or {kind = "file", path = "track.csv", units = "mm"}
        [method]                     # normal, tangential and [method.<name>] options
        [friction]
        mu = 0.3
        [simulation]
        speed = 30.0                 # [m/s] (0: from rest, with deceleration < 0)
                                     # or speed_profile = {distance = [...] (track position
                                     #   [m]) or time = [...] ([s], from 0), speed = [...]
                                     #   [m/s]}: piecewise linear (instead of speed)
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

    from ..cases.files._reader import Reader, read_friction, read_methods, read_toml
    from ..dynamics import Adaptive, FixedStep

    data, source = read_toml(path_or_str)
    r = Reader(source)
    r.unknown("", data, ("model", "track", "method", "friction", "simulation"))
    base = Path(source).parent if Path(str(source)).exists() else Path.cwd()
    model, track = _read_model(r, data, base)
    layout = _read_layout(r, data, track, base)
    normal, tangential, _ = read_methods(r, _table(r, data, "method"))
    mu = read_friction(r, data)
    s = _table(r, data, "simulation", required=True)
    r.unknown("simulation", s, _SIM_KEYS)
    sim = {"speed": _read_speed(r, s),
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


def _read_speed(r, s):
    """``speed`` [m/s] or ``speed_profile = {distance|time = [...], speed = [...]}`` of the
    [simulation] table: a float or a :class:`~wheelrail.dynamics.SpeedProfile`."""
    from ..dynamics import SpeedProfile
    from ._vehicle_case import _list

    if "speed_profile" not in s:
        return r.number("simulation", s, "speed", lo=0.0)
    for k in ("speed", "deceleration"):
        if k in s:
            r.fail("simulation", k, "given with speed_profile (the profile gives the speed)")
    p = s["speed_profile"]
    table = "simulation.speed_profile"
    if not isinstance(p, Mapping):
        r.fail("simulation", "speed_profile", f"must be a table {{distance = [...], speed = "
                                             f"[...]}} or {{time = [...], speed = [...]}}, "
                                             f"got {p!r}")
    r.unknown(table, p, ("distance", "time", "speed"))
    if ("distance" in p) == ("time" in p):
        r.fail(table, None, "give either distance = [...] (track positions [m]) or time = "
                            "[...] ([s]), with speed = [...] [m/s]")
    key = "distance" if "distance" in p else "time"
    x, v = _list(r, table, p, key), _list(r, table, p, "speed")
    make = SpeedProfile.from_distance if key == "distance" else SpeedProfile.from_time
    return _construct(r, table, lambda: make(x, v))


def _speed_text(speed):
    """The run's speed for the console: ``30 m/s`` or the profile's range."""
    if isinstance(speed, (int, float)):
        return f"V = {speed:g} m/s"
    return (f"V = {min(speed.v):g}–{max(speed.v):g} m/s (profile against "
            f"{speed.kind}, {len(speed.v)} points)")


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


def _vehicle_figures(ds, table, out):
    """``carbody.png`` (the car body's lateral shift, yaw and bounce) when the run has a car
    body, and ``assessment.png`` ((Y/Q)2m and (ΣY)2m along the track against their limits)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    written = []
    if "body_y" in ds:
        t = ds["time"].values
        fig, ax = plt.subplots(3, 1, sharex=True, figsize=(7, 6))
        for a, (v, scale, label) in zip(ax, (("body_y", 1e3, "lateral shift [mm]"),
                                             ("body_yaw", 1e3, "yaw [mrad]"),
                                             ("body_z", 1e3, "bounce [mm]"))):
            a.plot(t, ds[v].values * scale)
            a.set_ylabel(label)
        ax[0].set_title("car body (relative to the track-following frame)")
        ax[-1].set_xlabel("time [s]")
        fig.tight_layout()
        fig.savefig(out / "carbody.png", dpi=120)
        plt.close(fig)
        written.append("carbody.png")
    if table is not None:
        d = table["distance"].values
        fig, ax = plt.subplots(2, 1, sharex=True, figsize=(7, 5.5))
        for i in table["wheelset"].values:
            for side in table["side"].values:
                ax[0].plot(d, table["Y_over_Q_2m"].sel(wheelset=i, side=side),
                           label=f"ws{i} {side}")
            ax[1].plot(d, table["sum_Y_2m"].sel(wheelset=i) * 1e-3, label=f"ws{i}")
        ax[0].axhline(float(table["Y_over_Q_limit"]), color="k", ls="--", lw=1)
        ax[0].axhline(-float(table["Y_over_Q_limit"]), color="k", ls="--", lw=1)
        lim = float(table["sum_Y_limit"].min()) * 1e-3
        ax[1].axhline(lim, color="k", ls="--", lw=1)
        ax[1].axhline(-lim, color="k", ls="--", lw=1)
        ax[0].set_ylabel("(Y/Q) 2 m [-]")
        ax[1].set_ylabel("(ΣY) 2 m [kN]")
        ax[1].set_xlabel("distance [m]")
        ax[0].legend(fontsize="x-small", ncol=4)
        ax[0].set_title("EN 14363 sliding means; dashed: limits (0.8, Prud'homme)")
        fig.tight_layout()
        fig.savefig(out / "assessment.png", dpi=120)
        plt.close(fig)
        written.append("assessment.png")
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
                  f"{_speed_text(sim['speed'])}, {sim['duration']:g} s, {sim['integrator']!r}")
    if not _kernels_cached():
        console.print("first run: compiling the dynamics kernels (about 50 s on a 2-core "
                      "machine, once; later runs load them from the cache)")
    from ..dynamics.simulate import SimulationInterrupted

    interrupted = None
    store = _store_path(args, sim, out, console)
    try:
        res = dyn.simulate(model, case["layout"], sim.pop("speed"), sim.pop("duration"),
                           case["normal"], case["tangential"], mu=case["mu"],
                           progress=not args.no_progress, store=store, **sim)
    except SimulationInterrupted as exc:
        # Ctrl-C: keep what was simulated (a valid result.nc or result.zarr marked
        # interrupted), then 130
        res, interrupted = exc.result, exc
    ds = res.dataset
    ds.attrs["case"] = str(args.case)
    if store is None:
        ds.to_netcdf(out / "result.nc")
        result_name = "result.nc"
    else:
        import zarr

        zarr.open_group(str(store), mode="r+").attrs["case"] = str(args.case)
        result_name = "result.zarr"
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
               "speed_min_m_s": float(np.min(res.speed)),
               "speed_max_m_s": float(np.max(res.speed)),
               "distance_m": float(res.position[-1] - res.position[0]),
               "interrupted": bool(res.info.get("interrupted")),
               "derailment": res.info.get("derailment"),
               "substeps": res.info.get("substeps", 1),
               "units": {"time": "s", "y": "m", "yaw": "rad", "Fn": "N", "Y_over_Q": "1"}}
    written = [result_name, "summary.json"]
    if interrupted is not None:
        from ._output import esc

        (out / "summary.json").write_text(json.dumps(summary, indent=2))
        console.print(f"interrupted at t = {summary['simulated_s']:.4g} s: wrote "
                      f"{result_name} (marked interrupted) and summary.json to {esc(out)}")
        raise KeyboardInterrupt from None
    table = _assessment(res, out, console, summary)
    if table is not None:
        written += ["assessment.nc", "assessment.csv"]
    (out / "summary.json").write_text(json.dumps(summary, indent=2))
    if not args.no_figures:
        written += _figures(ds, out)
        written += _vehicle_figures(ds, table, out)
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


def _store_path(args, sim, out, console):
    """``out/result.zarr`` when the run streams its outputs (``--store`` or more than
    :data:`STREAM_OUTPUTS` outputs), else None (``result.nc`` at the end)."""
    integ = sim.get("integrator")
    dt = getattr(integ, "dt", 1e-3)
    out_dt = sim.get("output_step") or dt
    n_out = sim["duration"] / out_dt
    if not (getattr(args, "store", False) or n_out > STREAM_OUTPUTS):
        return None
    path = out / "result.zarr"          # an earlier run's store is replaced
    console.print(f"{n_out:,.0f} outputs: the histories go to result.zarr while the run goes "
                  "(read it with wheelrail.dynamics.open_result)")
    return path


def _assessment(res, out, console, summary):
    """EN 14363 / Sperling assessment of the run (:func:`wheelrail.dynamics.assess`): writes
    ``assessment.nc`` and ``assessment.csv`` (one row per wheel), prints the table and adds
    its verdicts to ``summary``; ``None`` (with a note) when the run is too short for it."""
    import numpy as np

    from .. import dynamics as dyn
    from ..errors import InputError
    from ._output import esc

    try:
        table = dyn.assess(res)
    except InputError as exc:
        console.print(f"no assessment: {esc(str(exc))}")
        return None
    table.to_netcdf(out / "assessment.nc")
    rows = ["wheelset,side,Y_over_Q_2m_max,Y_over_Q_limit,sum_Y_2m_max_N,sum_Y_limit_N,"
            "Y_max_N,Q_max_N,Q_min_N,wear_number_mean_N"]
    lines = []
    for i in table["wheelset"].values:
        for side in table["side"].values:
            w = {"wheelset": i}
            ws = {"wheelset": i, "side": side}
            vals = (float(table["Y_over_Q_2m_max"].sel(**ws)), float(table["Y_over_Q_limit"]),
                    float(table["sum_Y_2m_max"].sel(**w)), float(table["sum_Y_limit"].sel(**w)),
                    float(table["Y_max"].sel(**ws)), float(table["Q_max"].sel(**ws)),
                    float(table["Q_min"].sel(**ws)), float(table["wear_number_mean"].sel(**ws)))
            rows.append(f"{i},{side}," + ",".join(f"{v:.6g}" for v in vals))
            lines.append(f"  ws{i} {side:5s}  (Y/Q)2m {vals[0]:6.3f} / {vals[1]:.2f}   "
                         f"(ΣY)2m {vals[2] / 1e3:7.2f} / {vals[3] / 1e3:6.2f} kN   "
                         f"Y max {vals[4] / 1e3:6.2f} kN   Q {vals[6] / 1e3:6.1f}–"
                         f"{vals[5] / 1e3:6.1f} kN   Tγ {vals[7]:6.1f} N")
    (out / "assessment.csv").write_text("\n".join(rows) + "\n")
    ok_yq = bool(np.all(table["Y_over_Q_ok"].values))
    ok_sy = bool(np.all(table["sum_Y_ok"].values))
    summary["assessment"] = {"Y_over_Q_2m_ok": ok_yq, "sum_Y_2m_ok": ok_sy}
    console.print("assessment (EN 14363 2 m sliding means of the low-passed forces; "
                  "limits after the slash):")
    for line in lines:
        console.print(esc(line))
    if "sperling_lateral" in table:
        wl, wv = float(table["sperling_lateral"]), float(table["sperling_vertical"])
        summary["assessment"].update(sperling_lateral=wl, sperling_vertical=wv)
        console.print(f"  car body: Sperling Wz lateral {wl:.2f}, vertical {wv:.2f}; "
                      f"acceleration rms lateral {float(table['body_lateral_acc_rms']):.3f}, "
                      f"vertical {float(table['body_vertical_acc_rms']):.3f} m/s²")
    console.print(f"  running safety: (Y/Q)2m {'within' if ok_yq else 'BEYOND'} the limit, "
                  f"(ΣY)2m {'within' if ok_sy else 'BEYOND'} Prud'homme's limit")
    return table


def _kernels_cached() -> bool:
    """Whether the compiled time loops of the dynamics have a valid numba cache (else the
    first simulation compiles them, about 50 s)."""
    try:
        from .._numba_cache import is_cached
        from ..dynamics import _motion

        loops = [getattr(_motion, name, None) for name in ("run_fixed", "rhs_fast")]
        return all(is_cached(f) for f in loops if f is not None)
    except Exception:  # pragma: no cover - numba internals moved: assume cached
        return True
