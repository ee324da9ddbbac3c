"""Benchmark: memory and time of the boundary-element solvers against the estimates of
``wheelrail._resources`` (used to refuse big solves and to show progress).

Runs each solve in a fresh subprocess and reads its peak resident memory
(``ru_maxrss``), for the normal BEM (``solve_normal`` on ``hertz_grid``) and the
exact theory (``creep_forces(method="exact")``) at several grid sizes; prints
measured versus estimated memory and time with the grid sizes and the machine
load (CPU time of the solve). Run: ``python benchmarks/bench_resources.py``.
"""

import json
import os
import subprocess
import sys

CHILD = r"""
import json, resource, sys, time
import wheelrail as wr
kind, n = sys.argv[1], int(sys.argv[2])
hc = wr.hertz(7500.0, 0.5 / 0.46, 0.5 / 0.30, wr.Material(2.1e11, 0.28))
from wheelrail import _resources
with _resources.limit(None):
    t = time.process_time()
    if kind == "bem_normal":
        g, h = wr.hertz_grid(hc, n)
        wr.solve_normal(g, h, hc.materials, load=7500.0)
        cells = g.size
    else:
        wr.creep_forces(hc, (-1e-3, 0.0, 0.0), 0.3, method="exact", elements=n)
        m = max(1.1, 1.0 + 3.0 / n)
        g, _ = wr.hertz_grid(hc, n, margin=m)
        cells = g.size
    dt = time.process_time() - t  # CPU time (the estimates are of an unloaded core)
print(json.dumps({"cells": cells, "seconds": dt,
                  "rss": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024}))
"""


def main():
    from wheelrail._resources import estimate

    print(f"load average before: {os.getloadavg()}")
    print(f"{'solver':11s} {'elements':>8s} {'cells':>9s} {'memory':>9s} {'estimate':>9s} "
          f"{'cpu':>8s} {'estimate':>9s}")
    for kind, sizes in (("bem_normal", (100, 200, 400, 800)), ("exact", (40, 80, 160, 240, 400))):
        for n in sizes:
            out = subprocess.run([sys.executable, "-c", CHILD, kind, str(n)], capture_output=True,
                                 text=True, check=True)
            r = json.loads(out.stdout.strip().splitlines()[-1])
            est = estimate(kind, r["cells"])
            print(f"{kind:11s} {n:8d} {r['cells']:9d} {r['rss'] / 1e6:7.0f}MB {est.memory / 1e6:7.0f}MB "
                  f"{r['seconds']:7.2f}s {est.seconds:8.2f}s")
    print(f"load average after: {os.getloadavg()}")


if __name__ == "__main__":
    main()
