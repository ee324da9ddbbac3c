"""Benchmark: rigid contact table, S1002 on 60E1 1:40 (gauge 1435, flange back 1360), zero yaw.

Prints the wall time of ``wheelrail.contact_table`` for 201 lateral positions
(−10 … 10 mm; target < 0.5 s), with and without the bisection that locates the
jumps of the contact point, plus single calls of ``contact_points`` and
``equivalent_conicity``. Run: ``python benchmarks/bench_contact_table.py``.
"""

import os
import time

import numpy as np

import wheelrail as wr


def best_of(fn, repeat=5):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return min(times), out


def main():
    t0 = time.perf_counter()
    ws = wr.Wheelset(wr.profiles.load("S1002"))
    tr = wr.Track(wr.profiles.load("60E1"), inclination=1 / 40)
    y = np.linspace(-0.01, 0.01, 201)
    wr.contact_table(ws, tr, y[:3])  # JIT-cache load, spline set-up
    print(f"set-up (profiles, splines, numba cache): {time.perf_counter() - t0:.3f} s")
    grid = int(np.ceil((ws.wheel.y_max - ws.wheel.y_min) / 2e-4))
    print(f"problem: {y.size} lateral positions x 2 wheels, search grid {grid} points / wheel")
    print(f"machine load (1-min average): {os.getloadavg()[0]:.2f}")
    t, tab = best_of(lambda: wr.contact_table(ws, tr, y))
    print(f"contact_table (201 y, jumps bisected 6x): {t:.3f} s   "
          f"[target < 0.5 s]  jumps at {np.round(tab.jump_y.values * 1e3, 3).tolist()} mm")
    t, _ = best_of(lambda: wr.contact_table(ws, tr, y, refine_jumps=0))
    print(f"contact_table (201 y, jumps to +-dy/2):  {t:.3f} s")
    t, _ = best_of(lambda: wr.contact_points(ws, tr, 0.004), repeat=10)
    print(f"contact_points (one position):           {t * 1e3:.1f} ms")
    t, lam = best_of(lambda: wr.equivalent_conicity(ws, tr, 0.003), repeat=3)
    print(f"equivalent_conicity (3 mm, 161 y):       {t:.3f} s   tan(gamma_e) = {lam:.4f}")
    t, _ = best_of(lambda: wr.elastic_contact(ws, tr, 0.005, 1e5), repeat=3)
    print(f"elastic_contact (y = 5 mm, 100 kN):      {t:.3f} s")


if __name__ == "__main__":
    main()
