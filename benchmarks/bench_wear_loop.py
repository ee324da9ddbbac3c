"""Benchmark: the wear loop on a bogie over a route of five curve classes and tangent track.

The Manchester benchmark vehicle's bogie (``wr.dynamics.manchester_bogie()``) on S1002 / 60E1
runs curves of radius 300, 500, 800, 1500 and 3000 m (cant 100 … 30 mm, speeds
near balance + a cant deficiency of ~50 mm) and tangent track with a sine
alignment, weights 0.05 / 0.1 / 0.1 / 0.15 / 0.2 / 0.4; USFD law, wear step
``--step`` mm, profiles per side. Prints the problem size, the number of
steps, CPU time of this process and of the workers (the cases run on the
executor), wall time, the load average, Sd and conicity at the end; with
``--compare`` the same first steps on Dask with 1 and 2 workers (speed-up of
the wall time of one step).

Run:  .venv/bin/python benchmarks/bench_wear_loop.py [--km 10000] [--step 0.1]
      [--workers 2] [--executor dask] [--compare] [--steps N]
"""

from __future__ import annotations

import argparse
import math
import os
import time

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")


def build():
    import wheelrail as wr
    from wheelrail import dynamics as dy

    G = 9.81
    bogie = dy.manchester_bogie()
    tr = wr.Track(wr.profiles.load("60E1"))
    cases = []
    for R, cant, w, direction in ((300.0, 0.10, 0.05, "right"), (500.0, 0.10, 0.10, "left"),
                                  (800.0, 0.08, 0.10, "right"), (1500.0, 0.05, 0.15, "left"),
                                  (3000.0, 0.03, 0.20, "right")):
        # speed for a cant deficiency of 50 mm: v² / R = g (cant + 0.05) / 1.5
        v = math.sqrt(G * (cant + 0.05) / 1.5 * R)
        lay = dy.TrackLayout(tr, curves=(dy.Curve(R, start=5.0, transition=30.0, cant=cant,
                                                  direction=direction),))
        cases.append(wr.wear.RouteCase(lay, v, weight=w, distance=20.0, run_in=40.0,
                                       name=f"R{int(R)}"))
    irr = dy.Irregularity.sine(0.002, 25.0, start=5.0, cycles=10.0)
    cases.append(wr.wear.RouteCase(dy.TrackLayout(tr, irregularity=irr), 40.0, weight=0.40,
                                   distance=100.0, run_in=10.0, name="tangent"))
    return bogie, wr.wear.Route(tuple(cases))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--km", type=float, default=10000.0)
    ap.add_argument("--step", type=float, default=0.1, help="wear step [mm]")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--executor", default="dask")
    ap.add_argument("--samples", type=int, default=50)
    ap.add_argument("--compare", action="store_true")
    ap.add_argument("--steps", type=int, default=None, help="stop after N steps (max_steps)")
    a = ap.parse_args()

    import wheelrail as wr

    bogie, route = build()
    print(f"route: {len(route.cases)} cases ({', '.join(route.names)}), "
          f"{args_str(a)}; load {os.getloadavg()}")
    if a.compare:
        from wheelrail.sweeps.executors import DaskExecutor
        for n in (1, 2):
            ex = DaskExecutor(workers=n)
            w0 = time.perf_counter()
            wr.wear.evolve(bogie, route, mileage=1.0, law="usfd", executor=ex,
                           samples=a.samples, conicity=False, profiles="sides")
            print(f"dask workers={n}: one step wall {time.perf_counter() - w0:.1f} s, "
                  f"load {os.getloadavg()}", flush=True)
        return
    c0, w0 = time.process_time(), time.perf_counter()
    kw = {} if a.executor == "serial" else {"workers": a.workers}
    res = wr.wear.evolve(bogie, route, mileage=a.km * 1e3, law="usfd", step_depth=a.step * 1e-3,
                         executor=a.executor, samples=a.samples, profiles="sides",
                         progress=True, max_steps=a.steps or 1000, **kw)
    ds = res.dataset
    cpu_self = time.process_time() - c0
    cpu_cases = float(ds.case_cpu.sum())
    print(f"steps = {ds.sizes['step']}  mileage_km = {float(ds.mileage[-1]) / 1e3:.1f}")
    print(f"cpu_cases_s = {cpu_cases:.1f}  cpu_main_s = {cpu_self:.1f}  "
          f"wall_s = {time.perf_counter() - w0:.1f}  (cases on {a.executor})")
    print(f"Sd_left_mm = {float(ds.Sd[-1, 0]) * 1e3:.3f}  Sd_right_mm = "
          f"{float(ds.Sd[-1, 1]) * 1e3:.3f}  conicity = {float(ds.conicity[-1]):.4f}")
    print(f"load {os.getloadavg()}")


def args_str(a):
    return f"{a.km:g} km, step {a.step:g} mm, executor {a.executor}, workers {a.workers}"


if __name__ == "__main__":
    main()
