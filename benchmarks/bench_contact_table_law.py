"""Benchmark: the table law (``method="table"``) against the grid-converged exact theory, and its speed.

Random points over the table's whole domain (:func:`wheelrail.tangential.table.random_cases`:
a/b log-uniform in [0.05, 20], ν in [0.25, 0.30], loads 2–20 kN, μ 0.1–0.5, scaled
creepage ρ̂ = U(0, 3)², any direction, scaled spin φ̂ = s/(1 − |s|) with s uniform in
(−0.95, 0.95), i.e. |φ̂| up to 19). The reference at each point is the exact solver's
grid limit (:func:`wheelrail.sweeps.tables.exact_limit`): the least-squares fit
f∞ + C/N to 36, 54, 81 and 122 elements (first order, p = 1: the median observed
order of these points from 54/81/122 elements is 0.98 for Fx and Fy). Its
uncertainty is printed: the largest change of f∞ when the fit drops 36 elements or
takes p = 0.9 or 1.1. Errors in units of μFn (forces) and μFn c (Mz, c = √(ab)).

Speed: one call of ``Table.solve`` and of ``Exact.solve`` (40 elements, the
default) on the same contact, and through :func:`wheelrail.creep_forces`; a
batch of 10⁵ points. CPU time (``time.process_time``), with the load average.

    python benchmarks/bench_contact_table_law.py [--points 60] [--quick] [--table FILE.npz]
"""

from __future__ import annotations

import argparse
import os
import time
import warnings

import numpy as np

import wheelrail as wr
from wheelrail.sweeps.tables import REFERENCE_ELEMENTS, exact_limit, grid_limit
from wheelrail.tangential.table import Table, load_table, random_cases


def load():
    one, five, fifteen = os.getloadavg()
    return f"load average {one:.1f} / {five:.1f} / {fifteen:.1f}"


def references(cases, N, cache=None):
    """Grid limits (n, 3), their uncertainty (n, 3) and the CPU time of the exact solutions."""
    if cache and os.path.exists(cache):
        with np.load(cache) as f:
            if "each" in f.files and f["each"].shape[0] == len(cases) and tuple(f["N"]) == tuple(N):
                each, cpu = f["each"], float(f["cpu"])
                return _limits(each, N) + (cpu,)
    t0 = time.process_time()
    each = np.array([exact_limit(c, N)[1] for c in cases])
    cpu = time.process_time() - t0
    if cache:
        np.savez(cache, each=each, N=np.array(N), cpu=cpu)
    return _limits(each, N) + (cpu,)


def _limits(each, N):
    fs = [each[:, k] for k in range(len(N))]
    ref = grid_limit(fs, N)
    alt = [grid_limit(fs, N, 0.9), grid_limit(fs, N, 1.1)]
    if len(N) > 3:
        alt.append(grid_limit(fs[1:], N[1:]))
    unc = np.max([np.abs(a - ref) for a in alt], axis=0)
    return ref, unc, each[:, -1]


def accuracy(n, N, table, cache=None):
    data = load_table(table)
    print(f"table: nodes {data.values.shape[:-1]} (r, theta, s, a/b, nu), built with "
          f"{data.meta['elements']} elements, meta {data.meta.get('extrapolation', {})}")
    law = Table(table=table) if table else Table()
    cases = random_cases(n)
    refs, unc, fin, cpu = references(cases, N, cache)
    errs, errs3, uncs = [], [], []
    for cs, ref, u, f3 in zip(cases, refs, unc, fin):
        t = law.solve(cs.contact, *cs.creepage, cs.mu)
        got = np.array([t.Fx, t.Fy, t.Mz])
        s = np.array([cs.mu * cs.Fn, cs.mu * cs.Fn, cs.mu * cs.Fn * cs.c])
        errs.append(np.abs(got - ref) / s)
        errs3.append(np.abs(f3 - ref) / s)
        uncs.append(u / s)
    errs, errs3, uncs = np.array(errs), np.array(errs3), np.array(uncs)
    print(f"\n{n} random points, reference: exact grid limit (fit f + C/N to {N} elements; "
          f"{cpu:.0f} s CPU; {load()})")
    for name, e in (("table", errs), (f"exact {N[-1]} el.", errs3), ("ref. uncertainty", uncs)):
        ft = np.hypot(e[:, 0], e[:, 1])
        print(f"  {name:16s} max |dFx| {e[:, 0].max():.4f}, |dFy| {e[:, 1].max():.4f}, "
              f"|dF_t| {ft.max():.4f} (rms {np.sqrt((ft**2).mean()):.4f}) of mu Fn; "
              f"max |dMz| {e[:, 2].max():.4f} of mu Fn c")
    worst = np.argsort(np.hypot(errs[:, 0], errs[:, 1]))[-5:][::-1]
    print("  worst points (a/b, nu, rho_hat, theta, phi_hat) -> |dF_t| (ref. uncertainty):")
    for i in worst:
        c = cases[i]
        print(f"    #{i:<3d} a/b {c.ab:7.3f} nu {c.nu:.3f} rho {c.rho_hat:6.3f} theta "
              f"{c.theta:+.2f} phi {c.phi_hat:+7.2f} -> {np.hypot(errs[i, 0], errs[i, 1]):.4f}"
              f" ({np.hypot(uncs[i, 0], uncs[i, 1]):.4f})")


def speed(table):
    c = wr.hertz(1e4, 1.0, 1.6, wr.Material(2.1e11, 0.28))
    cr = (-3e-4, 2e-4, 0.3)
    law = Table(table=table) if table else Table()
    from wheelrail.tangential.exact import Exact

    ex = Exact()
    res = {}
    for name, fn, n in (("Table.solve", lambda: law.solve(c, *cr, 0.3), 3000),
                        ("Exact.solve (40 el.)", lambda: ex.solve(c, *cr, 0.3), 20),
                        ("creep_forces table", lambda: wr.creep_forces(
                            c, cr, 0.3, method="table", **({"table": table} if table else {})),
                         1000),
                        ("creep_forces exact", lambda: wr.creep_forces(c, cr, 0.3,
                                                                       method="exact"), 20)):
        fn()
        best = np.inf
        for _ in range(3):
            t0 = time.process_time()
            for _ in range(n):
                fn()
            best = min(best, (time.process_time() - t0) / n)
        res[name] = best
        print(f"  {name:22s} {best * 1e3:8.3f} ms per call")
    print(f"  one call: Table.solve is {res['Exact.solve (40 el.)'] / res['Table.solve']:.0f}x "
          f"faster than Exact.solve; through creep_forces "
          f"{res['creep_forces exact'] / res['creep_forces table']:.0f}x; {load()}")
    N = 100_000
    rng = np.random.default_rng(1)
    crs = np.column_stack([rng.uniform(-3e-3, 3e-3, N), rng.uniform(-3e-3, 3e-3, N),
                           rng.uniform(-0.5, 0.5, N)])
    wr.creep_forces(c, crs[:10], 0.3, method="table", **({"table": table} if table else {}))
    t0 = time.process_time()
    wr.creep_forces(c, crs, 0.3, method="table", **({"table": table} if table else {}))
    print(f"  batch of {N}: {N / (time.process_time() - t0):.3g} evaluations/s")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=60)
    ap.add_argument("--quick", action="store_true", help="20 points, reference 24/36/54")
    ap.add_argument("--table", default=None)
    ap.add_argument("--speed-only", action="store_true")
    ap.add_argument("--refs-only", action="store_true", help="only compute the references")
    ap.add_argument("--cache", default=None, help="npz file caching the exact references")
    a = ap.parse_args()
    warnings.simplefilter("ignore")  # plausibility warnings of the extreme patches
    N = (24, 36, 54) if a.quick else REFERENCE_ELEMENTS
    n = 20 if a.quick else a.points
    if a.refs_only:
        references(random_cases(n), N, a.cache)
        return
    print("speed:")
    speed(a.table)
    if not a.speed_only:
        accuracy(n, N, a.table, a.cache)


if __name__ == "__main__":
    main()
