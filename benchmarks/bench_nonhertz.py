"""Non-Hertzian methods: accuracy against Hertz and the exact solver, and timings.

1. Hertzian gap, a/b = 0.2 … 5 (Hertz load 100 kN, steel): area, p_max and
   the load at Hertz's approach of every normal method, relative to Hertz.
2. S1002 / 60E1 1:40, lateral shifts −10 … 10 mm (yaw 2 mrad, 70 kN per
   wheel, V = 20 m/s, μ = 0.3): every method (with its tangential method)
   against ``bem`` + ``exact`` (40 elements per window): ΣFn cos γ at the
   reference's approach, area, p_max at the prescribed load; Fx, Fs, Mz at the
   creepages of the position. Error statistics per method (max, median, RMS).
3. Manchester A-2.2 (21 cases, both wheels) against CONTACT's published output
   (tests/reference/data/contact_mbench_a22.csv): area, p_max, Fx, Fs, Mz.
4. Timings: Kik–Piotrowski + FASTSIM and STRIPES + FASTSIM per wheel–rail
   contact (normal + tangential of one wheel, profile separation cached /
   not cached); a 201-position sweep with Kik–Piotrowski.
5. Ayasse's CAF method (``--parts 5``): the table build (both sides) and a
   201-position sweep with the tables against the direct form, interleaved.

Relative errors: Fn, area, p_max |q − q_ref|/q_ref; Fx, Fs |ΔF|/(μ Fn_ref);
Mz |ΔMz|/(μ Fn_ref √(area_ref/π)).

    python benchmarks/bench_nonhertz.py [--shared ../shared] [--out docs/nonhertzian_tables.md]
    python benchmarks/bench_nonhertz.py --parts 4 --clock cpu --pairs /path/to/main/src
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import sys
import time
from pathlib import Path

import numpy as np

import wheelrail as wr
from wheelrail.cli.compare import METHODS
from wheelrail.normal._base import GapProblem

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
LINES = []


def say(text=""):
    print(text, flush=True)
    LINES.append(text)


def hertzian_gap():
    say("\n## 1. Hertzian gap: ratio to Hertz (load 100 kN, steel)\n")
    orig = {"ellipticity_correction": False}
    cols = [("kik-piotrowski", {"ellipticity_correction": True}), ("kik-piotrowski", orig),
            ("kik-piotrowski", {**orig, "shape_correction": False}),
            ("kik-piotrowski", {**orig, "penetration_factor": 0.55}),
            ("kik-piotrowski", {**orig, "penetration_factor": 0.55, "shape_correction": False}),
            ("linder", {}), ("stripes", {}), ("multi-hertz", {"variant": "pascal"})]
    say("| method | a/b | area | p_max | Fn at Hertz δ | L/W (Hertz a/b) |")
    say("|---|---|---|---|---|---|")
    for name, opts in cols:
        m = wr.normal.get(name, opts)
        for ab in (0.2, 0.5, 1.0, 2.0, 5.0):
            b = 5e-3 / np.sqrt(ab)
            c0 = wr.hertz_from_semiaxes(ab * b, b, 1e5, wr.STEEL)
            c = wr.hertz(1e5, float(c0.A), float(c0.B), wr.STEEL)
            A, B = float(c.A), float(c.B)
            L = 4 * max(float(c.a), float(c.b))
            gp = GapProblem(lambda x, y: A * x**2 + B * y**2, wr.STEEL,
                            penetration=float(c.penetration), search=(-L, L, -L, L))
            (p,) = m.from_contact(c)
            q = m.from_gap(gp)
            lw = p.a / p.b if p.is_hertzian else p.info["L_W"][0] / p.info["L_W"][1]
            say(f"| {name} {opts or ''} | {ab:g} | {p.area / float(c.area):.3f} | "
                f"{p.p_max / float(c.p0):.3f} | {sum(x.Fn for x in q) / 1e5:.3f} | "
                f"{lw:.2f} ({ab:g}) |")


def stats_table(errs, title, keys):
    say(f"\n{title}\n")
    say("| method | " + " | ".join(f"{k} max / med / RMS %" for k in keys) + " |")
    say("|---|" + "---|" * len(keys))
    for label, e in errs.items():
        cells = []
        for k in keys:
            v = np.abs(np.array(e[k], float)) * 100
            v = v[np.isfinite(v)]
            cells.append("n/a" if v.size == 0 else
                         f"{v.max():.1f} / {np.median(v):.1f} / {np.sqrt(np.mean(v**2)):.1f}")
        say(f"| {label} | " + " | ".join(cells) + " |")


def _tot(res, side):
    ps = res.side(side)
    return {"Fn": sum(p.Fn for p in ps), "area": sum(p.area for p in ps),
            "p_max": max(p.p_max for p in ps), "Fx": sum(p.Fx for p in ps),
            "Fs": sum(p.Fs for p in ps), "Mz": sum(p.Mz_reference for p in ps), "n": len(ps)}


def _err(t, r, mu):
    s = mu * r["Fn"]
    return {"area": t["area"] / r["area"] - 1, "p_max": t["p_max"] / r["p_max"] - 1,
            "Fx": (t["Fx"] - r["Fx"]) / s, "Fs": (t["Fs"] - r["Fs"]) / s,
            "Mz": (t["Mz"] - r["Mz"]) / (s * np.sqrt(r["area"] / np.pi))}


def s1002_sweep(ys):
    from wheelrail.contact.wheelrail import touching_poses, wheel_problem

    ws = wr.Wheelset(wheel=wr.profiles.load("S1002"), nominal_radius=0.46, flange_back=1.360)
    tr = wr.Track(rail=wr.profiles.load("60E1"), gauge=1.435, inclination=1 / 40)
    motion = wr.Motion(speed=20.0, omega=20.0 / 0.46)
    say(f"\n## 2. S1002 / 60E1 1:40 against bem + exact: {len(ys)} shifts "
        f"{ys[0] * 1e3:g} … {ys[-1] * 1e3:g} mm, yaw 2 mrad, 70 kN per wheel, μ = 0.3\n")
    errs = {m[0]: {k: [] for k in ("Fn@δ", "area", "p_max", "Fx", "Fs", "Mz")}
            for m in METHODS if m[0] != "bem+exact"}
    times = {m[0]: [] for m in METHODS}
    npatch = {m[0]: [] for m in METHODS}
    for y in ys:
        wp = wr.WheelRailPosition(ws, tr, float(y), yaw=0.002, vertical_load=70e3)
        res = {}
        for label, normal, tangential, opts in METHODS:
            t0 = time.perf_counter()
            try:
                res[label] = wr.solve(wp, motion=motion, mu=0.3, normal=normal,
                                      tangential=tangential, vertical="normal", **opts)
            except Exception as exc:
                res[label] = exc
            times[label].append(time.perf_counter() - t0)
        ref = res["bem+exact"]
        roll, zs = touching_poses(wp)
        for side in ("left", "right"):
            r = _tot(ref, side)
            npatch["bem+exact"].append(r["n"])
            dz = ref.pose[f"approach_{side}"]
            prob0 = wheel_problem(wp, side, roll, zs[side])
            Qref = sum(p.Fn * np.cos(p.patch.frame.contact_angle) for p in ref.side(side))
            for label, normal, tangential, opts in METHODS:
                if label == "bem+exact":
                    continue
                v = res[label]
                if isinstance(v, Exception):
                    for k in errs[label]:
                        errs[label][k].append(np.nan)
                    continue
                t = _tot(v, side)
                npatch[label].append(t["n"])
                e = _err(t, r, 0.3)
                for k in e:
                    errs[label][k].append(e[k])
                nm = wr.normal.get_class(normal)
                try:
                    prob = dataclasses.replace(prob0, vertical_load=None, vertical_approach=dz, cache={})
                    decl = nm.option_declarations()
                    ps, _ = nm(**{k: w for k, w in opts.items() if k in decl}).from_wheel(prob)
                    Fz = sum(p.Fn * np.cos(p.frame.contact_angle) for p in ps)
                    errs[label]["Fn@δ"].append(Fz / Qref - 1)
                except Exception:
                    errs[label]["Fn@δ"].append(np.nan)
    stats_table(errs, "Relative errors (%) over both wheels and all shifts; Fn@δ: vertical "
                "force at the reference's approach.", ("Fn@δ", "area", "p_max", "Fx", "Fs", "Mz"))
    say("\n| method | mean time per position (both wheels, geometry included) ms | "
        "patches per wheel (min–max) |")
    say("|---|---|---|")
    for label in times:
        n = npatch[label]
        say(f"| {label} | {np.mean(times[label]) * 1e3:.1f} | "
            f"{min(n) if n else '-'}–{max(n) if n else '-'} |")


def manchester(shared):
    from bench_manchester import contact_reference

    from wheelrail.contact.manchester import manchester_a22

    d = Path(shared) / "data"
    inp = d / "benchmarks" / "manchester_a22_inputs.csv"
    if not inp.exists():
        say(f"\n## 3. Manchester A-2.2: skipped ({inp} not found)\n")
        return
    cases = manchester_a22(inp, d / "profiles" / "MBench_S1002_v3.prw",
                           d / "profiles" / "MBench_UIC60_v3.prr")
    ref = contact_reference()
    say("\n## 3. Manchester A-2.2 against CONTACT (21 cases × 2 wheels, 10 kN, μ = 0.3)\n")
    errs = {}
    for label, normal, tangential, opts in METHODS:
        if label == "bem+exact":
            continue
        errs[label] = {k: [] for k in ("area", "p_max", "Fx", "Fs", "Mz")}
        for c in cases:
            try:
                res = wr.solve(c.position, motion=c.motion, mu=c.mu, normal=normal,
                               tangential=tangential, **opts)
            except Exception:
                for k in errs[label]:
                    errs[label][k].append(np.nan)
                continue
            for side in ("left", "right"):
                e = _err(_tot(res, side), ref[(c.case, side)], c.mu)
                for k in e:
                    errs[label][k].append(e[k])
    stats_table(errs, "Relative errors (%) against CONTACT (prescribed vertical load, total).",
                ("area", "p_max", "Fx", "Fs", "Mz"))


def timings(clock=time.perf_counter, record=None):
    from wheelrail.contact.wheelrail import touching_poses, wheel_problem

    ws = wr.Wheelset(wheel=wr.profiles.load("S1002"), nominal_radius=0.46, flange_back=1.360)
    tr = wr.Track(rail=wr.profiles.load("60E1"), gauge=1.435, inclination=1 / 40)
    kind = "CPU time" if clock is time.process_time else "wall time"
    say(f"\n## 4. Timings (one core, {kind}; load {os.getloadavg()[0]:.1f})\n")
    say("| normal + tangential | per contact, separation cached (ms) | per contact, cold "
        "(ms) | full wr.solve per position, both wheels (ms) |")
    say("|---|---|---|---|")
    motion = wr.Motion(speed=20.0, omega=20.0 / 0.46)
    ys = np.linspace(-0.008, 0.008, 9)
    for normal, tangential in (("kik-piotrowski", "fastsim"), ("stripes", "fastsim"),
                               ("linder", "fastsim"), ("kik-piotrowski", "fastrip"),
                               ("hertz", "fastsim")):
        nm = wr.normal.get(normal)
        tm = wr.tangential.get(tangential, {"fields": False} if tangential == "fastsim" else {})
        warm, cold, full = [], [], []
        for y in ys:
            wp = wr.WheelRailPosition(ws, tr, float(y), yaw=0.002, vertical_load=70e3)
            roll, zs = touching_poses(wp)
            prob = wheel_problem(wp, "right", roll, zs["right"])
            t0 = clock()
            ps, _ = nm.from_wheel(prob)
            tm.solve_patches(ps, [(1e-3, 1e-3, 0.1)] * len(ps), 0.3)
            cold.append((clock() - t0) / len(ps))
            for _ in range(5):
                t0 = clock()
                ps, _ = nm.from_wheel(prob)
                tm.solve_patches(ps, [(1e-3, 1e-3, 0.1)] * len(ps), 0.3)
                warm.append((clock() - t0) / len(ps))
            t0 = clock()
            wr.solve(wp, motion=motion, mu=0.3, normal=normal, tangential=tangential,
                     vertical="normal")
            full.append(clock() - t0)
        say(f"| {normal} + {tangential} | {np.median(warm) * 1e3:.2f} | "
            f"{np.median(cold) * 1e3:.2f} | {np.median(full) * 1e3:.1f} |")
        if record is not None:
            record[f"{normal}+{tangential}"] = (float(np.median(warm)) * 1e3,
                                                float(np.median(cold)) * 1e3)
    y = np.linspace(-0.01, 0.01, 201)
    for normal in ("kik-piotrowski", "stripes"):
        kw = dict(yaw=0.0, vertical_load=70e3, motion=motion, mu=0.3, normal=normal,
                  tangential="fastsim", progress=False, vertical="normal")
        t0 = clock()
        wr.wheelset_sweep(ws, tr, y[:5], **kw)       # first call: numba cache loads, tables
        first = clock() - t0
        t0 = clock()
        wr.wheelset_sweep(ws, tr, y, **kw)
        t = clock() - t0
        say(f"\n201-position wheelset sweep (y = −10 … 10 mm, both wheels, 70 kN per wheel) "
            f"with {normal} + fastsim: {t:.2f} s ({t / 201 * 1e3:.1f} ms per position; "
            f"a first 5-position call before it took {first:.2f} s)")
        if record is not None:
            record[f"sweep {normal}"] = t


def caf_timings(clock=time.perf_counter, rounds=2):
    """Ayasse's CAF method: table build once per profile pair, then a 201-position
    sweep with the tables against the direct (per-pose candidate points) form."""
    from wheelrail.normal import caf

    ws = wr.Wheelset(wheel=wr.profiles.load("S1002"), nominal_radius=0.46, flange_back=1.360)
    tr = wr.Track(rail=wr.profiles.load("60E1"), gauge=1.435, inclination=1 / 40)
    motion = wr.Motion(speed=20.0, omega=20.0 / 0.46)
    kind = "CPU time" if clock is time.process_time else "wall time"
    say(f"\n## 5. Ayasse CAF tables (S1002/60E1 1:40, 70 kN per wheel, yaw 2 mrad; {kind})\n")
    caf._CACHE.clear()
    t0 = clock()
    for side in ("left", "right"):
        t = caf.cached_caf_table(ws, tr, side, (-0.02, 0.02), tolerance=2e-4)
    tb = clock() - t0
    say(f"table build, both sides (t_y = −20 … 20 mm, {t.samples} samples, "
        f"{t.y.size} breakpoints right): {tb:.2f} s (load {os.getloadavg()[0]:.1f})\n")
    say("| round | caf | load | 201-position sweep (s) | ms per position |")
    say("|---|---|---|---|---|")
    y = np.linspace(-0.01, 0.01, 201)
    for mode in ("table", "direct"):            # warm-up (imports, numba caches)
        wr.wheelset_sweep(ws, tr, y[::40], yaw=0.002, vertical_load=70e3, motion=motion,
                          mu=0.3, normal="multi-hertz", progress=False, variant="ayasse",
                          caf=mode)
    for r in range(rounds):
        for mode in ("table", "direct"):
            load = os.getloadavg()[0]
            t0 = clock()
            wr.wheelset_sweep(ws, tr, y, yaw=0.002, vertical_load=70e3, motion=motion, mu=0.3,
                              normal="multi-hertz", tangential="fastsim", progress=False,
                              variant="ayasse", caf=mode)
            t = clock() - t0
            say(f"| {r} | {mode} | {load:.1f} | {t:.2f} | {t / 201 * 1e3:.1f} |")


def pairs(base_src, rounds):
    """Interleaved before/after timings: this tree and ``base_src`` (a checkout's src/)
    alternately in fresh processes, CPU time, with the load beside each run."""
    import json
    import subprocess

    rows = []
    for r in range(rounds):
        for label, path in (("before", base_src), ("after", str(HERE.parent / "src"))):
            env = dict(os.environ, PYTHONPATH=path)
            out = subprocess.run([sys.executable, __file__, "--json-timings"], env=env,
                                 capture_output=True, text=True, check=True).stdout
            rec = json.loads(out.strip().splitlines()[-1])
            rows.append((r, label, rec))
    keys = [k for k in rows[0][2] if k not in ("load", "src")]
    say("\n## 4b. Interleaved before/after pairs (CPU time, one process each)\n")
    say("| round | tree | load | " + " | ".join(keys) + " |")
    say("|---|---|---|" + "---|" * len(keys))
    for r, label, rec in rows:
        cells = []
        for k in keys:
            v = rec[k]
            cells.append(f"{v:.2f} s" if k.startswith("sweep") else
                         f"{v[0]:.2f} / {v[1]:.2f} ms")
        say(f"| {r} | {label} | {rec['load']:.1f} | " + " | ".join(cells) + " |")
    say("\n(per contact: separation cached / cold)")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--shared", default=os.environ.get("WHEELRAIL_SHARED",
                                                       str(HERE.parent.parent / "shared")))
    ap.add_argument("--out", default="")
    ap.add_argument("--step", type=float, default=1.0, help="shift step [mm] of part 2")
    ap.add_argument("--parts", default="1,2,3,4")
    ap.add_argument("--clock", choices=("wall", "cpu"), default="wall",
                    help="timings of part 4: wall-clock or CPU time of this process")
    ap.add_argument("--pairs", default="", metavar="BASE_SRC",
                    help="also time the src/ of another checkout (e.g. main before a change) "
                         "interleaved with this tree, CPU time")
    ap.add_argument("--rounds", type=int, default=2)
    ap.add_argument("--json-timings", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.json_timings:
        import contextlib
        import io
        import json

        rec = {"load": os.getloadavg()[0], "src": wr.__file__}
        c = wr.hertz(1e5, 1.0, 2.0, wr.STEEL)
        for n in ("kik-piotrowski", "stripes", "linder"):
            wr.solve(c, creepage=(1e-3, 0, 0), mu=0.3, normal=n)
        with contextlib.redirect_stdout(io.StringIO()):
            timings(time.process_time, rec)
        print(json.dumps(rec))
        return
    parts = {int(v) for v in args.parts.split(",")}
    say(f"load: {os.getloadavg()}")
    # warm-up outside the timings (numba caches, FFT plans)
    c = wr.hertz(1e5, 1.0, 2.0, wr.STEEL)
    for n in ("kik-piotrowski", "stripes", "linder"):
        wr.solve(c, creepage=(1e-3, 0, 0), mu=0.3, normal=n)
    if 1 in parts:
        hertzian_gap()
    if 4 in parts:
        timings(time.process_time if args.clock == "cpu" else time.perf_counter)
    if args.pairs:
        pairs(args.pairs, args.rounds)
    if 5 in parts:
        caf_timings(time.process_time if args.clock == "cpu" else time.perf_counter,
                    args.rounds)
    if 2 in parts:
        s1002_sweep(np.arange(-10.0, 10.0 + 1e-9, args.step) * 1e-3)
    if 3 in parts:
        manchester(args.shared)
    say(f"\nload after: {os.getloadavg()}")
    if args.out:
        Path(args.out).write_text("\n".join(LINES) + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
