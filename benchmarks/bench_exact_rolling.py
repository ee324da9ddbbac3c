"""Benchmark: Kalker's exact theory, steady rolling on a half-space grid.

Prints, for several numbers of elements across the contact, the grid size,
the wall time of the normal (BEM) and the tangential (Newton–GMRES) solves,
the iteration counts and the memory (peak of Python/numpy allocations during
the tangential solve, and the process's maximum resident set size).

Run:  .venv/bin/python benchmarks/bench_exact_rolling.py [N ...]
"""

from __future__ import annotations

import resource
import sys
import time
import tracemalloc

import wheelrail as wr
from wheelrail.normal.bem import hertz_grid, solve_normal
from wheelrail.halfspace import solve_rolling

CASES = {
    "small creep": (2e-4, 0.0, 0.0),
    "combined": (1e-3, 5e-4, 1.0),
    "spin": (0.0, 0.0, 3.0),
}


def main(sizes):
    hc = wr.hertz(1e4, A=1.0, B=2.0, material=wr.STEEL)
    mu = 0.3
    # warm up (numba cache load / compile)
    g, h = hertz_grid(hc, elements=8, margin=1.5)
    solve_rolling(g, solve_normal(g, h, wr.STEEL, load=1e4).pressure, wr.STEEL, (1e-3, 0, 0), mu)
    print(f"Hertz contact a = {hc.a * 1e3:.3f} mm, b = {hc.b * 1e3:.3f} mm, Fn = 10 kN, mu = {mu}")
    print(f"{'N':>4} {'grid':>9} {'case':>12} {'normal s':>9} {'tang s':>8} {'newton':>6} "
          f"{'krylov':>6} {'peak MB':>8} {'Fx N':>10} {'Fy N':>10} {'Mz Nm':>9}")
    for n in sizes:
        grid, gap = hertz_grid(hc, elements=n, margin=1.1)
        t0 = time.perf_counter()
        normal = solve_normal(grid, gap, wr.STEEL, load=1e4)
        tn = time.perf_counter() - t0
        for name, cr in CASES.items():
            tracemalloc.start()
            t0 = time.perf_counter()
            s = solve_rolling(grid, normal.pressure, wr.STEEL, cr, mu)
            tt = time.perf_counter() - t0
            peak = tracemalloc.get_traced_memory()[1] / 2**20
            tracemalloc.stop()
            print(f"{n:>4} {grid.nx:>4}x{grid.ny:<4} {name:>12} {tn:>9.3f} {tt:>8.3f} "
                  f"{s.iterations:>6} {s.info['krylov_iterations']:>6} {peak:>8.1f} "
                  f"{s.Fx:>10.2f} {s.Fy:>10.2f} {s.Mz:>9.4f}")
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"max resident set size of the process: {rss:.0f} MB")


if __name__ == "__main__":
    sizes = [int(v) for v in sys.argv[1:]] or [40, 80, 100, 160]
    main(sizes)
