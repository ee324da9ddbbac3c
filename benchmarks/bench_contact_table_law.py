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
        [--seed 2026] [--cache REFS.npz]

``--ab-line K``: the a/b axis's resolution at point K of the 200 (seed 2026): the exact
forces (24/36 elements, extrapolated) on 33 points of ln a/b at the point's other table
coordinates, and the largest error of a not-a-knot spline through 9 and 17 of them.
"""

from __future__ import annotations

import argparse
import os
import time
import warnings

import numpy as np

import wheelrail as wr
from wheelrail.sweeps.tables import BUILD_CONTACT, REFERENCE_ELEMENTS, exact_limit, grid_limit
from wheelrail.tangential.table import Table, load_table, random_cases


def load():
    one, five, fifteen = os.getloadavg()
    return f"load average {one:.1f} / {five:.1f} / {fifteen:.1f}"


def references(cases, N, cache=None, seed=2026):
    """Grid limits (n, 3), their uncertainty (n, 3) and the CPU time of the exact solutions."""
    if cache and os.path.exists(cache):
        with np.load(cache) as f:
            cached_seed = int(f["seed"]) if "seed" in f.files else 2026
            if ("each" in f.files and f["each"].shape[0] == len(cases)
                    and tuple(f["N"]) == tuple(N) and cached_seed == seed):
                each, cpu = f["each"], float(f["cpu"])
                return _limits(each, N) + (cpu,)
    t0 = time.process_time()
    each = np.array([exact_limit(c, N)[1] for c in cases])
    cpu = time.process_time() - t0
    if cache:
        np.savez(cache, each=each, N=np.array(N), cpu=cpu, seed=seed)
    return _limits(each, N) + (cpu,)


def _limits(each, N):
    fs = [each[:, k] for k in range(len(N))]
    ref = grid_limit(fs, N)
    alt = [grid_limit(fs, N, 0.9), grid_limit(fs, N, 1.1)]
    if len(N) > 3:
        alt.append(grid_limit(fs[1:], N[1:]))
    unc = np.max([np.abs(a - ref) for a in alt], axis=0)
    return ref, unc, each[:, -1]


def accuracy(n, N, table, cache=None, seed=2026):
    data = load_table(table)
    print(f"table: nodes {data.values.shape[:-1]} (r, theta, s, a/b, nu), built with "
          f"{data.meta['elements']} elements, meta {data.meta.get('extrapolation', {})}")
    law = Table(table=table) if table else Table()
    cases = random_cases(n, seed=seed)
    refs, unc, fin, cpu = references(cases, N, cache, seed)
    errs, errs3, uncs = [], [], []
    for cs, ref, u, f3 in zip(cases, refs, unc, fin):
        t = law.solve(cs.contact, *cs.creepage, cs.mu)
        got = np.array([t.Fx, t.Fy, t.Mz])
        s = np.array([cs.mu * cs.Fn, cs.mu * cs.Fn, cs.mu * cs.Fn * cs.c])
        errs.append(np.abs(got - ref) / s)
        errs3.append(np.abs(f3 - ref) / s)
        uncs.append(u / s)
    errs, errs3, uncs = np.array(errs), np.array(errs3), np.array(uncs)
    print(f"\n{n} random points (seed {seed}), reference: exact grid limit "
          f"(fit f + C/N to {N} elements; "
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


def ab_line(index, n_points=200, seed=2026):
    """Exact forces along ln a/b through one benchmark point, and spline errors (see --ab-line)."""
    from wheelrail.hertzian import hertz_from_semiaxes
    from wheelrail.sweeps.tables import _physical
    from wheelrail.tangential._table_kernel import _locate, _weights
    from wheelrail.tangential.table import _spline_operator, table_coordinates

    cs = random_cases(n_points, seed=seed)[index]
    G = wr.Material(2.1e11, cs.nu).G
    one = lambda v: np.array([v], float)  # noqa: E731
    co = table_coordinates(one(cs.contact.a), one(cs.contact.b), G, cs.nu,
                           *(one(v) for v in cs.creepage), one(cs.mu), one(cs.Fn))[0][0]
    r, th, s, L0, nu = co
    lines = np.linspace(np.log(0.05), np.log(20.0), 33)
    L = np.append(lines, L0)
    P = _physical(np.full(L.size, r), np.full(L.size, th), np.full(L.size, s), L,
                  np.full(L.size, nu))
    mat = wr.Material(BUILD_CONTACT["E"], nu)
    Fn, mu = BUILD_CONTACT["Fn"], BUILD_CONTACT["mu"]

    def limit(i):
        cont = hertz_from_semiaxes(P["a"][i], P["b"][i], Fn, mat)
        f = []
        for N in (24, 36):
            e = wr.creep_forces(cont, (P["xi"][i], P["eta"][i], P["phi"][i]), mu,
                                method="exact", elements=N, on_fail="status", progress=False)
            f.append(np.array([e.Fx, e.Fy, e.Mz / np.sqrt(P["a"][i] * P["b"][i])]) / (mu * Fn))
        return grid_limit(f, (24, 36), order=1.0)   # first-order grid limit

    t0 = time.process_time()
    f = np.array([limit(i) for i in range(L.size)])
    print(f"point #{index}: a/b {cs.ab:.3f}, rho_hat {cs.rho_hat:.2f}, phi_hat {cs.phi_hat:.2f}; "
          f"table coordinates r {r:.4f}, theta {th:.4f}, s {s:.4f}, nu {nu:.4f}; "
          f"{L.size} x 2 exact solutions, {time.process_time() - t0:.0f} s CPU, {load()}")
    print("  Fy/(mu Fn) along ln a/b:", " ".join(f"{v:+.3f}" for v in f[:33, 1]))

    def spline(nodes, vals, x):
        h = nodes[1] - nodes[0]
        C = _spline_operator(nodes.size) @ vals
        i, t = _locate(x, nodes[0], h, nodes.size)
        w = np.empty(4)
        _weights(t, True, w)
        return w @ C[i:i + 4]

    for step in (4, 2):
        nodes, vals = lines[::step], f[:33][::step]
        worst = max(np.abs(spline(nodes, vals, x) - f[j]).max() for j, x in enumerate(lines))
        at = np.abs(spline(nodes, vals, L0) - f[33])
        print(f"  spline through {nodes.size:2d} nodes: max error on the line {worst:.4f}, at the "
              f"point {at.max():.4f} of mu Fn")


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
    ap.add_argument("--ab-line", type=int, default=None, metavar="K",
                    help="the a/b axis's resolution along ln a/b through point K (see above)")
    ap.add_argument("--seed", type=int, default=2026,
                    help="seed of the random points (2026: the points the table was tuned on; "
                         "another seed gives an independent set)")
    a = ap.parse_args()
    warnings.simplefilter("ignore")  # plausibility warnings of the extreme patches
    N = (24, 36, 54) if a.quick else REFERENCE_ELEMENTS
    n = 20 if a.quick else a.points
    if a.ab_line is not None:
        ab_line(a.ab_line, seed=a.seed)
        return
    if a.refs_only:
        references(random_cases(n, seed=a.seed), N, a.cache, a.seed)
        return
    print("speed:")
    speed(a.table)
    if not a.speed_only:
        accuracy(n, N, a.table, a.cache, a.seed)


if __name__ == "__main__":
    main()
