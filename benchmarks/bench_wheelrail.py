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

``--single``: only ``wr.solve`` of one position (both wheels, ``vertical="normal"``,
yaw 2 mrad, 10 kN per wheel, μ = 0.3) with Hertz and Kik–Piotrowski + FASTSIM at
y = 0, 5, 6.8 mm, as CPU time per call (mean of ``--calls`` calls, best of
``--repeat``); ``--breakdown`` adds where the time goes: the rigid pose
(``touching_poses``), the candidate points of both wheels (``wheel_problem``),
the normal problem (``from_wheel``) and the rest (creepages, tangential
problem, result). Both run unchanged on an older tree (``PYTHONPATH=...``), for
interleaved before/after pairs::

    python benchmarks/bench_wheelrail.py --single --breakdown
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


def cpu_per_call(fs, calls, repeat):
    """Best over ``repeat`` rounds of the mean CPU time of ``calls`` calls [s] of each function
    of ``fs`` (after one warm-up call each); the functions take turns in every round, so that
    all see the same machine conditions."""
    for f in fs:
        f()
    best_t = [np.inf] * len(fs)
    for _ in range(repeat):
        for i, f in enumerate(fs):
            t0 = time.process_time()
            for _ in range(calls):
                f()
            best_t[i] = min(best_t[i], (time.process_time() - t0) / calls)
    return best_t


def single(ws, tr, m, calls, repeat, breakdown):
    """Per-call CPU time of wr.solve for one position (both wheels), optionally split."""
    from wheelrail.contact.wheelrail import SIDES, touching_poses, wheel_problem

    for normal in ("hertz", "kik-piotrowski"):
        nimpl = wr.normal.get(normal)
        for y in (0.0, 0.005, 0.0068):
            wp = wr.WheelRailPosition(ws, tr, y, yaw=0.002, vertical_load=10e3)
            r = wr.solve(wp, motion=m, mu=0.3, normal=normal, vertical="normal")
            roll, zs = touching_poses(wp)
            fs = [lambda: wr.solve(wp, motion=m, mu=0.3, normal=normal, tangential="fastsim",
                                   vertical="normal")]
            if breakdown:
                fs += [lambda: touching_poses(wp),
                       lambda: [wheel_problem(wp, s, roll, zs[s]) for s in SIDES],
                       lambda: [nimpl.from_wheel(wheel_problem(wp, s, roll, zs[s]))
                                for s in SIDES]]
            t = cpu_per_call(fs, calls, repeat)
            npt = [len(r.side(s)) for s in SIDES]
            line = (f"{normal} + fastsim, one position (2 wheels, patches {npt[0]}+{npt[1]}), "
                    f"y = {y * 1e3:.1f} mm: {t[0] * 1e3:.3f} ms CPU")
            if breakdown:
                t_tot, t_pose, t_pts, t_pn = t
                line += (f" = pose {t_pose * 1e3:.3f} + points {t_pts * 1e3:.3f} + normal "
                         f"{(t_pn - t_pts) * 1e3:.3f} + rest (creepages, tangential, result) "
                         f"{(t_tot - t_pose - t_pn) * 1e3:.3f} ms")
            print(line, flush=True)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--single", action="store_true",
                    help="only wr.solve of one position, CPU time per call")
    ap.add_argument("--breakdown", action="store_true", help="with --single: split the time")
    ap.add_argument("--calls", type=int, default=50, help="calls per timing with --single")
    args = ap.parse_args(argv)
    ws = wr.Wheelset(wheel=wr.profiles.load("S1002"), nominal_radius=0.46, flange_back=1.360)
    tr = wr.Track(rail=wr.profiles.load("60E1"), gauge=1.435, inclination=1 / 40)
    m = wr.Motion(speed=20.0, omega=20.0 / 0.46 * 1.001)
    print(f"load average {os.getloadavg()[0]:.2f}, cores {os.cpu_count()}")
    if args.single:
        single(ws, tr, m, args.calls, args.repeat, args.breakdown)
        return
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
