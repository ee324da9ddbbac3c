"""Manchester contact benchmark A-2.2: wheelrail against CONTACT, per case and wheel, with timings.

Runs the 21 load cases (S1002 / UIC60 1:40, 10 kN per wheel, V = 2 m/s,
mu = 0.3) with the exact theory on boundary elements (0.2 mm grid, as
CONTACT's published run) and with Hertz + FASTSIM, and compares with
CONTACT's reference output (tests/reference/data/contact_mbench_a22.csv,
forces converted to Kalker's convention: on the wheel, creepage of the wheel
relative to the rail). Prints a table per method and the time per wheel.

    python benchmarks/bench_manchester.py [--shared ../shared] [--cases 1,11,14] [--out FILE.md]
    python benchmarks/bench_manchester.py --methods kik-piotrowski+fastsim \
        --options fastsim_flexibility=three

``--out`` also writes the printed tables (Markdown) to a file: the project's
copy is docs/validation/manchester_a22.md.
"""

from __future__ import annotations

import argparse
import csv
import os
import time
from pathlib import Path

import numpy as np

import wheelrail as wr
from wheelrail.contact.manchester import manchester_a22

HERE = Path(__file__).resolve().parent
REF = HERE.parent / "tests" / "reference" / "data" / "contact_mbench_a22.csv"


def contact_reference(path=REF):
    """{(case, side): row} of CONTACT's results, converted to Kalker's convention (SI)."""
    out = {}
    with open(path, encoding="utf-8") as fh:
        rows = [r for r in csv.DictReader(line for line in fh if not line.startswith("#"))]
    for r in rows:
        f = lambda k: float(r[k])  # noqa: E731
        out[(int(r["case"]), r["wheel"])] = {
            "xi": -f("xi"), "eta": -f("eta"), "phi": -f("phi_per_mm") * 1e3,
            "Fn": f("Fn_N"), "Fx": -f("Fx_N"), "Fs": -f("Fs_N"), "Mz": -f("Mz_Nmm") * 1e-3,
            "p_max": f("pmax_MPa") * 1e6, "area": f("area_mm2") * 1e-6,
            "adhesion_area": f("adhesion_area_mm2") * 1e-6,
            "Fy_track": -f("FY_TR_N"), "Fx_track": -f("FX_TR_N"),
            "Fz_track": f("FZ_TR_N"),   # CONTACT: z down and on the rail; ours: z up, on the wheel
            "contact_angle": abs(f("deltcp_rad")),
            # CONTACT prints the left side's rail position towards the track centre
            "y_rail": f("y_rail_mm") * 1e-3 * (-1.0 if r["wheel"] == "left" else 1.0),
        }
    return out


def totals(res, side):
    ps = res.side(side)
    Fn = sum(p.Fn for p in ps)
    area = sum(p.area for p in ps)
    adh = sum(p.adhesion_area for p in ps)
    pmax = max(p.p_max for p in ps)
    main = max(ps, key=lambda p: p.Fn)
    return {"n": len(ps), "Fn": Fn, "Fx": sum(p.Fx for p in ps), "Fs": sum(p.Fs for p in ps),
            "Mz": sum(p.Mz_reference for p in ps), "p_max": pmax, "area": area, "adhesion_area": adh,
            "xi": main.xi, "eta": main.eta, "phi": main.phi,
            "contact_angle": main.contact_angle, "y_rail": main.y_rail,
            "Fx_track": res.force_track[side][0], "Fy_track": res.force_track[side][1],
            "Fz_track": res.force_track[side][2]}


def run(cases, normal, tangential, **options):
    rows, times = [], []
    for c in cases:
        t0 = time.perf_counter()
        res = wr.solve(c.position, motion=c.motion, mu=c.mu, normal=normal, tangential=tangential,
                       **options)
        times.append(time.perf_counter() - t0)
        rows.append((c.case, res))
    return rows, np.array(times)


def main(argv=None):
    lines = []

    def say(text=""):
        print(text)
        lines.append(text)

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--shared", default=os.environ.get("WHEELRAIL_SHARED",
                                                       str(HERE.parent.parent / "shared")))
    ap.add_argument("--cases", default="")
    ap.add_argument("--out", default="", help="also write the Markdown report to this file")
    ap.add_argument("--methods", default="bem+exact,hertz+fastsim",
                    help="comma-separated normal+tangential pairs")
    ap.add_argument("--options", default="",
                    help="extra method options key=value[,key=value] for the non-BEM pairs, "
                         "e.g. fastsim_flexibility=three (Kik-Piotrowski patches)")
    args = ap.parse_args(argv)
    say(f"machine load (1-min average): {os.getloadavg()[0]:.2f}")
    extra = {}
    for kv in filter(None, args.options.split(",")):
        k, v = kv.split("=", 1)
        extra[k.strip()] = v.strip()
    shared = Path(args.shared) / "data"
    cases = manchester_a22(shared / "benchmarks" / "manchester_a22_inputs.csv",
                           shared / "profiles" / "MBench_S1002_v3.prw",
                           shared / "profiles" / "MBench_UIC60_v3.prr")
    if args.cases:
        keep = {int(v) for v in args.cases.split(",")}
        cases = [c for c in cases if c.case in keep]
    ref = contact_reference()
    # warm-up (numba cache load, first FFT plans) outside the timings
    wr.solve(cases[0].position, motion=cases[0].motion, mu=0.3, normal="bem",
             tangential="exact", element_size=2e-4)
    pairs = [m.split("+") for m in args.methods.split(",")]
    for normal, tangential in pairs:
        opts = {"element_size": 2e-4} if normal == "bem" else dict(extra)
        rows, times = run(cases, normal, tangential, **opts)
        say(f"\n## {normal} + {tangential} {opts or ''}: {len(cases)} cases, "
            f"{times.mean() / 2 * 1e3:.1f} ms per wheel (mean), "
            f"{np.median(times) / 2 * 1e3:.1f} ms per wheel (median), one core\n")
        keys = ("Fn", "Fx", "Fs", "Mz", "p_max", "area", "adhesion_area", "Fy_track")
        hdr = "| case | side | patches | " + " | ".join(keys) + " |"
        say("Each cell: wheelrail (CONTACT). N, N·m, Pa, m²; forces on the wheel.\n")
        say(hdr)
        say("|" + "---|" * (3 + len(keys)))
        errs = {k: [] for k in keys}
        for case, res in rows:
            for side in ("left", "right"):
                t = totals(res, side)
                r = ref[(case, side)]
                scale = {"Fx": 0.3 * r["Fn"], "Fs": 0.3 * r["Fn"], "Fy_track": 1e4,
                         "Mz": 0.3 * r["Fn"] * np.sqrt(r["area"] / np.pi)}
                cells = []
                for k in keys:
                    d = t[k] - r[k]
                    rel = d / scale.get(k, abs(r[k]) if r[k] else 1.0)
                    errs[k].append(rel)
                    cells.append(f"{t[k]:.4g} ({r[k]:.4g})")
                say(f"| {case} | {side} | {t['n']} | " + " | ".join(cells) + " |")
        say("\nContact reference point, creepages and track-frame forces (wheelrail (CONTACT); "
            "position on the rail profile, field side positive; the largest patch):\n")
        say("| case | side | y_rail [mm] | gamma [deg] | xi | eta | phi [1/m] | Fx_track [N] | "
            "Fy_track [N] | Fz_track [N] |")
        say("|" + "---|" * 10)
        for case, res in rows:
            for side in ("left", "right"):
                t, r = totals(res, side), ref[(case, side)]
                say(f"| {case} | {side} | {t['y_rail'] * 1e3:.2f} ({r['y_rail'] * 1e3:.2f}) | "
                    f"{np.degrees(t['contact_angle']):.2f} ({np.degrees(r['contact_angle']):.2f})"
                    f" | {t['xi']:.3e} ({r['xi']:.3e}) | {t['eta']:.3e} ({r['eta']:.3e}) | "
                    f"{t['phi']:.4f} ({r['phi']:.4f}) | {t['Fx_track']:.0f} ({r['Fx_track']:.0f})"
                    f" | {t['Fy_track']:.0f} ({r['Fy_track']:.0f}) | {t['Fz_track']:.0f} "
                    f"({r['Fz_track']:.0f}) |")
        say("\nDifferences to CONTACT (Mz about the contact reference point; Fx, Fs scaled by "
            "mu Fn, Mz by mu Fn times the patch radius, Fy_track by 10 kN, the others by "
            "CONTACT's value):\n")
        say("| quantity | max | median | rms |")
        say("|---|---|---|---|")
        for k, v in errs.items():
            a = np.abs(np.array(v))
            a = a[np.isfinite(a)]
            say(f"| {k} | {a.max():.2%} | {np.median(a):.2%} | {np.sqrt(np.mean(a * a)):.2%} |")
    if args.out:
        Path(args.out).parent.mkdir(parents=True, exist_ok=True)
        head = ("# Manchester benchmark A-2.2: wheelrail against CONTACT\n\n"
                "Generated by `python benchmarks/bench_manchester.py --out "
                "docs/validation/manchester_a22.md`; reference: CONTACT's output "
                "(eve70a/CONTACT examples/mbench_a22_{left,right}.ref_out, commit d431cdbd, "
                "revision 2707), tests/reference/data/contact_mbench_a22.csv.\n")
        Path(args.out).write_text(head + "\n".join(lines) + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
