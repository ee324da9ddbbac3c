"""Wheel-rail contact module: time per wheelset position, S1002 / 60E1 1:40, 10 kN per wheel.

- Hertz + FASTSIM through ``wr.solve`` (one position per call), and over a
  201-position lateral sweep (``wheelset_sweep``, batched: all positions as
  array operations);
- boundary elements (0.2 mm grid) + the exact theory per wheel (the
  Manchester benchmark's grid; see bench_manchester.py for the comparison
  with CONTACT).

Times are wall-clock on one core (NUMBA_NUM_THREADS=1 recommended), best of
``--repeat``, after a warm-up call (numba cache load, FFT plans).

    python benchmarks/bench_wheelrail.py [--repeat 5]
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

import wheelrail as wr


def best(f, repeat):
    f()
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        f()
        times.append(time.perf_counter() - t0)
    return min(times)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args(argv)
    ws = wr.Wheelset(wheel=wr.profiles.load("S1002"), nominal_radius=0.46, flange_back=1.360)
    tr = wr.Track(rail=wr.profiles.load("60E1"), gauge=1.435, inclination=1 / 40)
    m = wr.Motion(speed=20.0, omega=20.0 / 0.46 * 1.001)
    print(f"load average {os.getloadavg()[0]:.2f}, cores {os.cpu_count()}")
    for y in (0.0, 0.004, 0.0068):
        wp = wr.WheelRailPosition(ws, tr, y, yaw=0.002, vertical_load=10e3)
        t = best(lambda: wr.solve(wp, motion=m, mu=0.3), args.repeat)
        print(f"hertz + fastsim, one position (2 wheels), y = {y * 1e3:.1f} mm: "
              f"{t * 1e3:.2f} ms")
    y = np.linspace(-0.01, 0.01, 201)
    t = best(lambda: wr.wheelset_sweep(ws, tr, y, yaw=0.002, vertical_load=10e3, motion=m),
             args.repeat)
    print(f"hertz + fastsim, sweep of 201 positions (batched): {t:.3f} s = "
          f"{t / 201 * 1e3:.2f} ms per position")
    t = best(lambda: wr.wheelset_sweep(ws, tr, y[::10], yaw=0.002, vertical_load=10e3,
                                       motion=m, batch=False), max(1, args.repeat // 2))
    print(f"hertz + fastsim, 21 positions one by one (batch=False): {t / 21 * 1e3:.2f} ms "
          "per position")
    for y in (0.0, 0.005, 0.0068):
        wp = wr.WheelRailPosition(ws, tr, y, yaw=0.012, vertical_load=10e3)
        t = best(lambda: wr.solve(wp, motion=m, mu=0.3, normal="bem", tangential="exact",
                                  element_size=2e-4), args.repeat)
        r = wr.solve(wp, motion=m, mu=0.3, normal="bem", tangential="exact", element_size=2e-4)
        sizes = sorted({p.patch.grid.shape for p in r.patches})
        print(f"bem (0.2 mm) + exact, y = {y * 1e3:.1f} mm: {t * 1e3 / 2:.1f} ms per wheel "
              f"(grids {sizes}, vertical passes {r.pose['vertical_iterations_left']}/"
              f"{r.pose['vertical_iterations_right']})")


if __name__ == "__main__":
    main()
