"""Benchmark: normal contact on a grid (Polonsky–Keer CG + FFT influence operator).

Circular Hertz contact (steel, 10 kN, A = B = 1 1/m) on an n × n window of
±1.25 a, load prescribed, tol = 1e-8, scipy.fft with one worker.
Prints per grid size: operator set-up time, solve time, iterations, peak traced
memory (tracemalloc, numpy buffers included) and the errors against Hertz.

Run:  .venv/bin/python benchmarks/bench_bem_normal.py [n ...]
"""

from __future__ import annotations

import sys
import time
import tracemalloc

import wheelrail as wr
from wheelrail.halfspace import Grid, InfluenceOperator
from wheelrail.normal.bem import solve_normal


def run(n: int) -> dict:
    hc = wr.hertz(10e3, A=1.0, B=1.0, material=wr.STEEL)
    w = 1.25
    grid = Grid.from_bounds(-w * hc.a, w * hc.a, -w * hc.b, w * hc.b, n, n)
    gap = hc.A * grid.X**2 + hc.B * grid.Y**2
    tracemalloc.start()
    t0 = time.perf_counter()
    op = InfluenceOperator(grid, wr.STEEL)
    t1 = time.perf_counter()
    sol = solve_normal(grid, gap, wr.STEEL, load=10e3, operator=op)
    t2 = time.perf_counter()
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    return {"n": n, "setup": t1 - t0, "solve": t2 - t1, "it": sol.iterations, "peak_MB": peak / 2**20,
            "err_p0": sol.p_max / hc.p0 - 1, "err_delta": sol.penetration / hc.penetration - 1,
            "elements_across": 2 * hc.a / grid.dx}


def main(sizes) -> None:
    import os

    print("load average: " + " ".join(f"{v:.2f}" for v in os.getloadavg()))
    print(f"{'grid':>9} {'across':>7} {'setup[s]':>9} {'solve[s]':>9} {'iter':>5} "
          f"{'peak[MB]':>9} {'err p0':>10} {'err delta':>10}")
    for n in sizes:
        r = run(n)
        print(f"{n:>4}x{n:<4} {r['elements_across']:7.1f} {r['setup']:9.3f} {r['solve']:9.3f} "
              f"{r['it']:5d} {r['peak_MB']:9.1f} {r['err_p0']:10.2e} {r['err_delta']:10.2e}")


if __name__ == "__main__":
    main([int(a) for a in sys.argv[1:]] or [64, 128, 256, 512])
