"""Benchmark: the wear loop on a bogie over a route of five curve classes and tangent track.

The Manchester benchmark vehicle's bogie (``wr.dynamics.manchester_bogie()``, Iwnicki
1998) with S1002 wheels on 60E1 rails (1:40) runs the route of a mixed line:

======  ==========  ========  =============  =======
case    radius [m]  cant [mm] speed [m/s]    weight
======  ==========  ========  =============  =======
R300    300         100       17.2           0.05
R500    500         100       22.1           0.10
R800    800         80        26.1           0.10
R1500   1500        50        31.3           0.15
R3000   3000        30        39.6           0.20
tangent —           —         40.0           0.40
======  ==========  ========  =============  =======

(curve speeds for a cant deficiency of 50 mm, v² / R = g (cant + 0.05) / 1.5; 30 m
transitions, curves alternately right and left; tangent track with a 2 mm, 25 m alignment
sine; weights sum to 1). Per wear step each curve case simulates 40 m run-in + 20 m
counted, the tangent 10 m + 100 m, with the dynamics' compiled Kik–Piotrowski + FASTSIM
contact (``contact="auto"``); USFD law, wear step ``--step`` mm, profiles per side.

Prints the problem size, the number of steps, the CPU time of the cases (on the workers)
per step and in total, the CPU time of this process, the wall time, the load, and per case
the CPU time per step. With ``--steps N`` the run stops after N wear steps and the total
for the mileage is extrapolated from the mileage reached (printed as such).

Dask scaling (``--executor dask --workers 1`` and ``--workers 2``, same ``--steps``):
compare the printed wall time per step on an idle machine; the script also prints the
best speed-up the case costs allow on 2 workers (total / longest-processing-time schedule).

Run:  .venv/bin/python benchmarks/bench_wear_loop.py [--km 10000] [--step 0.1]
      [--executor dask|serial] [--workers 1|2] [--steps N] [--samples 50]
"""

from __future__ import annotations

import argparse
import math
import os
import time

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

G = 9.81
#: (radius [m], cant [m], weight, direction) of the five curve classes
CURVES = ((300.0, 0.10, 0.05, "right"), (500.0, 0.10, 0.10, "left"),
          (800.0, 0.08, 0.10, "right"), (1500.0, 0.05, 0.15, "left"),
          (3000.0, 0.03, 0.20, "right"))
TANGENT_WEIGHT = 0.40


def build():
    import wheelrail as wr
    from wheelrail import dynamics as dy

    bogie = dy.manchester_bogie()
    tr = wr.Track(wr.profiles.load("60E1"))
    cases = []
    for R, cant, w, direction in CURVES:
        v = math.sqrt(G * (cant + 0.05) / 1.5 * R)
        lay = dy.TrackLayout(tr, curves=(dy.Curve(R, start=5.0, transition=30.0, cant=cant,
                                                  direction=direction),))
        cases.append(wr.wear.RouteCase(lay, v, weight=w, distance=20.0, run_in=40.0,
                                       name=f"R{int(R)}"))
    irr = dy.Irregularity.sine(0.002, 25.0, start=5.0, cycles=10.0)
    cases.append(wr.wear.RouteCase(dy.TrackLayout(tr, irregularity=irr), 40.0,
                                   weight=TANGENT_WEIGHT, distance=100.0, run_in=10.0,
                                   name="tangent"))
    assert abs(sum(c.weight for c in cases) - 1.0) < 1e-12
    return bogie, wr.wear.Route(tuple(cases))


def lpt_makespan(costs, workers):
    """Longest-processing-time schedule of ``costs`` on ``workers`` (the wall-time bound)."""
    loads = [0.0] * workers
    for c in sorted(costs, reverse=True):
        loads[loads.index(min(loads))] += c
    return max(loads)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--km", type=float, default=10000.0)
    ap.add_argument("--step", type=float, default=0.1, help="wear step [mm]")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--executor", default="dask", choices=("dask", "serial", "processes"))
    ap.add_argument("--samples", type=int, default=50)
    ap.add_argument("--steps", type=int, default=None,
                    help="stop after N wear steps and extrapolate to --km")
    a = ap.parse_args()

    import numpy as np

    import wheelrail as wr

    bogie, route = build()
    sim_s = sum((c.run_in + c.distance) / c.speed for c in route.cases)
    print(f"route: {len(route.cases)} cases ({', '.join(route.names)}), weights "
          f"{', '.join(f'{w:.2f}' for w in route.weights)}; bogie, 2 wheelsets; "
          f"{sim_s:.1f} s simulated per wear step; {a.samples} samples x 12x12 FASTSIM cells "
          f"per case; {a.km:g} km, step {a.step:g} mm, executor {a.executor}, "
          f"workers {a.workers}; load {os.getloadavg()}", flush=True)
    c0, w0 = time.process_time(), time.perf_counter()
    kw = {} if a.executor == "serial" else {"workers": a.workers}
    rows = []
    t_last = [time.perf_counter()]

    class _Stop(Exception):
        pass

    def on_step(info):
        now = time.perf_counter()
        rows.append(dict(info, wall=now - t_last[0]))
        t_last[0] = now
        print(f"  step {info['step']}: {info['mileage'] / 1e3:.1f} km, case CPU "
              f"{info['cpu']:.1f} s, wall {rows[-1]['wall']:.1f} s, "
              f"~{info['steps_left']} steps left, load {os.getloadavg()[0]:.1f}", flush=True)
        if a.steps and len(rows) >= a.steps and info["steps_left"] > 0:
            raise _Stop

    total = a.km * 1e3
    full = True
    try:
        wr.wear.evolve(bogie, route, mileage=total, law="usfd", step_depth=a.step * 1e-3,
                       executor=a.executor, samples=a.samples, profiles="sides",
                       on_step=on_step, max_steps=1000, **kw)
    except _Stop:
        full = False
    wall = time.perf_counter() - w0
    cpu_self = time.process_time() - c0
    n = len(rows)
    reached = rows[-1]["mileage"]
    per_case = np.array([r["cpu_per_case"] for r in rows])      # (step, case)
    cpu_cases = float(per_case.sum())
    step_walls = np.array([r["wall"] for r in rows])
    print(f"steps = {n}  mileage reached = {reached / 1e3:.1f} km")
    later = float(np.mean(step_walls[1:])) if n > 1 else float("nan")
    print(f"case CPU: {cpu_cases:.1f} s total, {cpu_cases / n:.2f} s per step; "
          f"this process {cpu_self:.1f} s; wall {wall:.1f} s (per step: first "
          f"{step_walls[0]:.1f} s incl. start-up, then {later:.1f} s)")
    for j, name in enumerate(route.names):
        print(f"  {name:8s} CPU per step {per_case[:, j].mean():6.2f} s")
    mean_case = per_case.mean(axis=0)
    print(f"2-worker bound on the speed-up from the case costs (LPT schedule): "
          f"{mean_case.sum() / lpt_makespan(list(mean_case), 2):.2f}x")
    if not full:
        # step k+1 starts at rows[k]["mileage"]: the steps after step 0 advanced the
        # mileage; extrapolate the number of steps linearly in mileage
        est = 1 + (n - 1) * total / reached if reached > 0 else float("nan")
        est_left = rows[-1]["steps_left"] + n
        print(f"EXTRAPOLATED to {a.km:g} km (not a full run): ~{est:.0f} steps linearly in "
              f"mileage from {reached / 1e3:.1f} km, ~{est_left} by the loop's own estimate "
              f"(current wear rate); case CPU ~{est * cpu_cases / n / 60:.1f} / "
              f"~{est_left * cpu_cases / n / 60:.1f} min")
    else:
        print(f"FULL RUN {a.km:g} km: case CPU {cpu_cases / 60:.1f} min + this process "
              f"{cpu_self / 60:.1f} min")
    sd = rows[-1]["Sd"]
    print(f"Sd at the last step [mm]: left {sd[0] * 1e3:.3f}, right {sd[1] * 1e3:.3f}; "
          f"conicity {rows[-1]['conicity']:.4f}")
    print(f"load {os.getloadavg()}")


if __name__ == "__main__":
    main()
