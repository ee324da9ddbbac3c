"""Benchmark: normal contact on a grid (Polonsky–Keer CG + FFT influence operator).

Circular Hertz contact (steel, 10 kN, A = B = 1 1/m) on an n × n window of
±1.25 a, load prescribed, tol = 1e-8, scipy.fft with one worker.
Prints per grid size: operator set-up time, solve time (wall, best of
``--repeat``, and the CPU time of the process, less sensitive to other
processes), iterations, peak traced memory (tracemalloc, numpy buffers
included, first solve) and the errors against Hertz. The solve includes the
build of the preconditioner on the first call (memoised); the best of the
repeats is a solve with it built, as in a sweep.

``--plain`` solves without the preconditioner (the plain Polonsky–Keer
iteration). ``--before SRC`` runs the same sizes with another source tree of
the package (e.g. ``git archive main src | tar -x -C /tmp/main`` then
``--before /tmp/main/src``) in a subprocess, interleaved size by size with
this tree, and prints the ratio of CPU times.

Run:  .venv/bin/python benchmarks/bench_bem_normal.py [n ...] [--repeat R] [--plain] [--before SRC]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")


def run(n: int, repeat: int = 3, plain: bool = False) -> dict:
    import inspect
    import time
    import tracemalloc

    import wheelrail as wr
    from wheelrail.halfspace import Grid, InfluenceOperator
    from wheelrail.normal.bem import solve_normal

    kw = {}
    if "precondition" in inspect.signature(solve_normal).parameters:
        kw["precondition"] = not plain
    hc = wr.hertz(10e3, A=1.0, B=1.0, material=wr.STEEL)
    w = 1.25
    grid = Grid.from_bounds(-w * hc.a, w * hc.a, -w * hc.b, w * hc.b, n, n)
    gap = hc.A * grid.X**2 + hc.B * grid.Y**2
    tracemalloc.start()
    t0 = time.perf_counter()
    op = InfluenceOperator(grid, wr.STEEL)
    t1 = time.perf_counter()
    sol = solve_normal(grid, gap, wr.STEEL, Fn=10e3, operator=op, **kw)
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    ts, cs = [], []
    for _ in range(repeat):
        t0s, c0 = time.perf_counter(), time.process_time()
        sol = solve_normal(grid, gap, wr.STEEL, Fn=10e3, operator=op, **kw)
        ts.append(time.perf_counter() - t0s)
        cs.append(time.process_time() - c0)
    return {"n": n, "setup": t1 - t0, "solve": min(ts), "cpu": min(cs), "it": sol.iterations,
            "peak_MB": peak / 2**20, "err_p0": sol.p_max / hc.p0 - 1,
            "err_delta": sol.penetration / hc.penetration - 1,
            "elements_across": 2 * hc.a / grid.dx}


def _run_in(src, n, repeat, plain):
    if src is None:
        return run(n, repeat, plain)
    env = dict(os.environ, PYTHONPATH=os.path.abspath(src))
    cmd = [sys.executable, os.path.abspath(__file__), "--json", str(n), "--repeat", str(repeat)]
    res = subprocess.run(cmd, env=env, capture_output=True, text=True, check=True)
    return json.loads(res.stdout.strip().splitlines()[-1])


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("sizes", nargs="*", type=int, default=[64, 128, 256, 512])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--plain", action="store_true", help="without the preconditioner")
    ap.add_argument("--before", default=None, help="source tree (.../src) to compare with")
    ap.add_argument("--json", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.json:
        print(json.dumps(run(args.sizes[0], args.repeat, args.plain)))
        return
    print("load average before: " + " ".join(f"{v:.2f}" for v in os.getloadavg()))
    head = (f"{'grid':>9} {'across':>7} {'setup[s]':>9} {'solve[s]':>9} {'cpu[s]':>7} {'iter':>5} "
            f"{'peak[MB]':>9} {'err p0':>10} {'err delta':>10}")
    if args.before:
        head += f" {'before s':>9} {'cpu[s]':>7} {'iter':>5} {'speed-up':>8}"
    print(head)
    for n in args.sizes:
        b = _run_in(args.before, n, args.repeat, False) if args.before else None
        r = _run_in(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "src")
                    if args.before else None, n, args.repeat, args.plain)
        line = (f"{n:>4}x{n:<4} {r['elements_across']:7.1f} {r['setup']:9.3f} {r['solve']:9.3f} "
                f"{r['cpu']:7.3f} {r['it']:5d} {r['peak_MB']:9.1f} {r['err_p0']:10.2e} "
                f"{r['err_delta']:10.2e}")
        if b is not None:
            line += f" {b['solve']:9.3f} {b['cpu']:7.3f} {b['it']:5d} {b['cpu'] / r['cpu']:8.2f}"
        print(line, flush=True)
    print("load average after: " + " ".join(f"{v:.2f}" for v in os.getloadavg()))


if __name__ == "__main__":
    main()
