"""Benchmark: the table law (``method="table"``) against the grid-converged exact theory, and its speed.

Random points over the table's whole domain (a/b log-uniform in [0.05, 20], ν in
[0.25, 0.30], loads 2–20 kN, μ 0.1–0.5, scaled creepage ρ̂ = U(0, 3)², any
direction, scaled spin φ̂ = s/(1 − |s|) with s uniform in (−0.95, 0.95), i.e.
|φ̂| up to 19). The reference at each point is the exact solver extrapolated in
the grid: three resolutions N, 1.5 N, 2.25 N (default 24, 36, 54 elements),
observed order p from the three (clipped to [0.5, 2.5]; 1 when the differences
are below 2e-4 μFn or not monotone), f∞ = f₃ + (f₃ − f₂)/(1.5ᵖ − 1). Errors
in units of μFn (forces) and μFn c (Mz, c = √(ab)).

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
from wheelrail.tangential.linear import kalker_coefficients
from wheelrail.tangential.table import Table, load_table


def load():
    one, five, fifteen = os.getloadavg()
    return f"load average {one:.1f} / {five:.1f} / {fifteen:.1f}"


def points(n, seed=2026):
    rng = np.random.default_rng(seed)
    ab = np.exp(rng.uniform(np.log(0.05), np.log(20.0), n))
    nu = rng.uniform(0.25, 0.30, n)
    Fn = rng.uniform(2e3, 2e4, n)
    mu = rng.uniform(0.1, 0.5, n)
    rho = rng.uniform(0.0, 3.0, n) ** 2
    th = rng.uniform(-np.pi, np.pi, n)
    s = rng.uniform(-0.95, 0.95, n)
    return ab, nu, Fn, mu, rho, th, s / (1.0 - np.abs(s))


def physical(ab, nu, Fn, mu, rho, th, ph):
    m = wr.Material(2.1e11, nu)
    c = wr.hertz_from_semiaxes(4e-3 * np.sqrt(ab), 4e-3 / np.sqrt(ab), Fn, m)
    cc = np.sqrt(c.a * c.b)
    C11, C22, C23, _ = kalker_coefficients(ab, nu)
    u = 3 * mu * Fn / m.G
    ell = np.hypot(cc * C23, c.b * C11)  # the table's spin length (tangential/table.py)
    cr = (rho * np.cos(th) * u / (cc**2 * C11),
          (rho * np.sin(th) - ph * cc * C23 / ell) * u / (cc**2 * C22),
          ph * u / (cc**2 * ell))
    return c, cr, cc


def extrapolated(c, cr, mu, N):
    f = []
    for n in N:
        r = wr.creep_forces(c, cr, mu, method="exact", elements=n, on_fail="status",
                            progress=False)
        f.append(np.array([r.Fx, r.Fy, r.Mz]))
    f1, f2, f3 = f
    d12, d23 = f2 - f1, f3 - f2
    out = f3.copy()
    for k in range(3):
        p = 1.0
        if abs(d23[k]) > 0 and d12[k] * d23[k] > 0 and abs(d12[k]) > abs(d23[k]):
            p = float(np.clip(np.log(d12[k] / d23[k]) / np.log(N[1] / N[0]), 0.5, 2.5))
        out[k] = f3[k] + d23[k] / ((N[2] / N[1]) ** p - 1.0)
    return out, f3


def references(n, N, cache=None):
    """Extrapolated exact (Fx, Fy, Mz) and the finest resolution's, shape (n, 3) each."""
    if cache and os.path.exists(cache):
        with np.load(cache) as f:
            if f["ref"].shape[0] == n and tuple(f["N"]) == tuple(N):
                return f["ref"], f["f3"], float(f["cpu"])
    t0 = time.process_time()
    ref, fin = [], []
    for p in zip(*points(n)):
        c, cr, _ = physical(*p)
        r, f3 = extrapolated(c, cr, p[3], N)
        ref.append(r)
        fin.append(f3)
    cpu = time.process_time() - t0
    ref, fin = np.array(ref), np.array(fin)
    if cache:
        np.savez(cache, ref=ref, f3=fin, N=np.array(N), cpu=cpu)
    return ref, fin, cpu


def accuracy(n, N, table, cache=None):
    data = load_table(table)
    print(f"table: nodes {data.values.shape[:-1]} (r, theta, s, a/b, nu), built with "
          f"{data.meta['elements']} elements, meta {data.meta.get('extrapolation', {})}")
    law = Table(table=table) if table else Table()
    errs, errs3 = [], []
    refs, fins, cpu = references(n, N, cache)
    for p, ref, f3 in zip(zip(*points(n)), refs, fins):
        c, cr, cc = physical(*p)
        mu, Fn = p[3], p[2]
        t = law.solve(c, *cr, mu)
        got = np.array([t.Fx, t.Fy, t.Mz])
        s = np.array([mu * Fn, mu * Fn, mu * Fn * cc])
        errs.append(np.abs(got - ref) / s)
        errs3.append(np.abs(f3 - ref) / s)
    errs, errs3 = np.array(errs), np.array(errs3)
    print(f"\n{n} random points, reference: exact extrapolated from {N} elements "
          f"({cpu:.0f} s CPU; {load()})")
    for name, e in (("table", errs), (f"exact {N[-1]} el.", errs3)):
        ft = np.hypot(e[:, 0], e[:, 1])
        print(f"  {name:14s} max |dFx| {e[:, 0].max():.4f}, |dFy| {e[:, 1].max():.4f}, "
              f"|dF_t| {ft.max():.4f} (rms {np.sqrt((ft**2).mean()):.4f}) of mu Fn; "
              f"max |dMz| {e[:, 2].max():.4f} of mu Fn c")
    worst = np.argsort(np.hypot(errs[:, 0], errs[:, 1]))[-5:][::-1]
    pts = np.array(points(n)).T
    print("  worst points (a/b, nu, rho_hat, theta, phi_hat) -> |dF_t|:")
    for i in worst:
        ab, nu, _, _, rho, th, ph = pts[i]
        print(f"    a/b {ab:7.3f} nu {nu:.3f} rho {rho:6.3f} theta {th:+.2f} phi {ph:+7.2f}"
              f" -> {np.hypot(errs[i, 0], errs[i, 1]):.4f}")


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
    ap.add_argument("--quick", action="store_true", help="20 points, reference 16/24/36")
    ap.add_argument("--table", default=None)
    ap.add_argument("--speed-only", action="store_true")
    ap.add_argument("--refs-only", action="store_true", help="only compute the references")
    ap.add_argument("--cache", default=None, help="npz file caching the exact references")
    a = ap.parse_args()
    warnings.simplefilter("ignore")  # plausibility warnings of the extreme patches
    N = (16, 24, 36) if a.quick else (24, 36, 54)
    n = 20 if a.quick else a.points
    if a.refs_only:
        references(n, N, a.cache)
        return
    print("speed:")
    speed(a.table)
    if not a.speed_only:
        accuracy(n, N, a.table, a.cache)


if __name__ == "__main__":
    main()
