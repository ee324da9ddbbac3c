"""FASTSIM throughput: batched forces-only solves per second on one core.

Run:  NUMBA_NUM_THREADS=1 python benchmarks/bench_fastsim.py [n_cases]

Prints solves/s for 20×20 and 40×40 grids (elliptic Hertz patch, random
creepages in partial slip, both traction bounds), excluding JIT compilation.
The machine may be shared: take the best of a few repeats.
"""

import os
import sys
import time

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

import numba  # noqa: E402
import numpy as np  # noqa: E402

import wheelrail as wr  # noqa: E402


def main(n=20000, repeats=3):
    numba.set_num_threads(1)
    rng = np.random.default_rng(1)
    c = wr.hertz_from_semiaxes(a=6e-3, b=4e-3, Fn=80e3, material=wr.Material.from_shear(82e9, 0.28))
    cr = np.column_stack([rng.uniform(-3e-3, 3e-3, n), rng.uniform(-3e-3, 3e-3, n),
                          rng.uniform(-1.0, 1.0, n)])
    print(f"FASTSIM batch, {n} cases, a/b = 1.5, one thread (numba {numba.__version__})")
    print(f"machine load (1-min average): {os.getloadavg()[0]:.2f}")
    for bound in ("parabolic", "elliptic"):
        for grid in (20, 40):
            kw = dict(method="fastsim", nx=grid, ny=grid, bound=bound, fields=False)
            wr.creep_forces(c, cr[:10], 0.3, **kw)  # compile / load cache
            best = np.inf
            for _ in range(repeats):
                t0 = time.perf_counter()
                wr.creep_forces(c, cr, 0.3, **kw)
                best = min(best, time.perf_counter() - t0)
            cells = n * grid * grid / best
            print(f"  {bound:9s} {grid}x{grid}: {n / best:10.0f} solves/s "
                  f"({cells / 1e6:6.1f} M cell updates/s, {best * 1e3:7.1f} ms per batch)")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 20000)
