"""Benchmark / robustness sweep: contact tables over y = −50 … 50 mm for every pair.

Every built-in wheel/rail pair (S1002 on 60E1 and 54E1) and every measured
profile in ``../shared/data/profiles`` (every wheel on every rail), at the inclinations 0, 1/20, 1/30 and 1/40 (canted
files are rotated as well: the sweep tests robustness, not track design), 101
lateral shifts each. Prints per table the wall time and the number of rows per
status (ok, flange_climb, derailed, no_contact, not_converged); a table that
raises is reported as ABORTED (none may, except a rail without a
gauge face, which is refused when the track is built). Machine load is printed
(other processes share the CPU).

Run: ``python benchmarks/bench_contact_table_sweep.py [points]``.
"""

import os
import sys
import time
import warnings
from pathlib import Path

import numpy as np

import wheelrail as wr
from wheelrail.geometry.contact_search import STATUS

PROFILES = Path(__file__).resolve().parents[1].parent / "shared" / "data" / "profiles"
INCLINATIONS = {"0": 0.0, "1/20": 1 / 20, "1/30": 1 / 30, "1/40": 1 / 40}


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 101
    print(f"load average before: {os.getloadavg()}")
    wheels = {"S1002": wr.profiles.load("S1002")}
    rails = {"60E1": wr.profiles.load("60E1"), "54E1": wr.profiles.load("54E1")}
    if PROFILES.is_dir():
        for f in sorted(PROFILES.iterdir()):
            if f.name == "NOTICE":
                continue
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", wr.profiles.ProfileWarning)
                p = wr.profiles.read(f)
            (wheels if p.kind == "wheel" else rails)[f.name] = p
    else:
        print(f"{PROFILES} not present: built-in profiles only")
    y = np.linspace(-0.05, 0.05, n)
    wr.contact_table(wr.Wheelset(wheels["S1002"]), wr.Track(rails["60E1"]), y[:3])  # JIT
    pairs = [(w, r) for w in wheels for r in rails]  # every wheel on every rail
    total = {k: 0 for k in STATUS.values()}
    aborted, refused, tables, t_all = [], [], 0, 0.0
    print(f"problem: {len(pairs)} wheel/rail pairs x {len(INCLINATIONS)} inclinations x {n} "
          f"lateral shifts (-50 ... 50 mm)")
    for w, r in pairs:
        for name, inc in INCLINATIONS.items():
            try:
                tr = wr.Track(rails[r], inclination=inc)
            except wr.errors.ProfileError as exc:
                refused.append((w, r, name, str(exc)))
                continue
            t0 = time.perf_counter()
            try:
                t = wr.contact_table(wr.Wheelset(wheels[w]), tr, y)
            except Exception as exc:  # noqa: BLE001 - the sweep reports every failure
                aborted.append((w, r, name, f"{type(exc).__name__}: {exc}"))
                continue
            dt = time.perf_counter() - t0
            t_all += dt
            tables += 1
            st = t.status.values
            counts = {STATUS[k]: int(np.sum(st == k)) for k in STATUS if np.any(st == k)}
            for k, v in counts.items():
                total[k] += v
            print(f"{w:24s} {r:22s} {name:5s} {dt:6.2f} s  {counts}")
    print(f"\n{tables} tables ({tables * n} rows) in {t_all:.1f} s "
          f"({t_all / max(tables, 1):.2f} s per table of {n} rows); rows per status: {total}")
    for w, r, name, msg in refused:
        print(f"REFUSED (track): {r} at {name}: {msg}")
    for w, r, name, msg in aborted:
        print(f"ABORTED: {w} on {r} at {name}: {msg}")
    print(f"aborted tables: {len(aborted)}; load average after: {os.getloadavg()}")


if __name__ == "__main__":
    main()
