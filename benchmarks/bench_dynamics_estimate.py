"""Dynamics run estimates against measured CPU time (the guard of ``simulate``).

Before a run, :func:`wheelrail.dynamics.simulate` estimates its CPU time as the
measured cost of one contact evaluation × the evaluations of the scheme (4 per
RK4 step, × the sub-steps of the creep-damping control) and refuses it past the
time limit. This script runs a suspended wheelset and a bogie (S1002 on 60E1,
80 kN axle load) and the Manchester vehicle 1 (``wr.dynamics.manchester_vehicle1``,
4 wheelsets), Kik–Piotrowski + FASTSIM, RK4 at 1 ms, 30 m/s, released 3 mm off
centre, for three durations, and prints estimate / measured CPU time (the
project's goal: within 0.7–1.5). ``--store`` writes every run to a Zarr store
while it goes (``simulate(store=...)``), to show what streaming costs.

CPU time (``time.process_time``) on one core; the load (``os.getloadavg``) is printed.

    python benchmarks/bench_dynamics_estimate.py [--durations 0.5 1 2] [--models vehicle]
                                                 [--store]
"""

from __future__ import annotations

import argparse
import os
import shutil
import tempfile

import wheelrail as wr

D = wr.dynamics


def models():
    ws = wr.Wheelset(wr.profiles.load("S1002"))
    prim = D.Suspension(kx=1e6, ky=3.884e6, kz=1.22e6, cy=2e4, half_spacing=1.0)
    yield "wheelset", D.WheelsetModel(ws, 1813.0, (1120.0, 112.0, 1120.0), primary=prim,
                                      axle_load=80e3)
    yield "bogie", D.BogieModel(ws, 1813.0, (1120.0, 112.0, 1120.0), prim, 2615.0,
                                (1722.0, 1476.0, 3067.0), 1.25,
                                secondary=D.Suspension(kx=1.5e5, ky=1.5e5, kz=4e5, cy=3e4),
                                axle_load=80e3)
    yield "vehicle", D.manchester_vehicle1()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--durations", type=float, nargs="+", default=[0.5, 1.0, 2.0])
    ap.add_argument("--models", nargs="+", default=["wheelset", "bogie", "vehicle"])
    ap.add_argument("--store", action="store_true", help="stream each run to a Zarr store")
    args = ap.parse_args()
    tr = wr.Track(wr.profiles.load("60E1"))
    tmp = tempfile.mkdtemp()
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores; "
          f"NUMBA_NUM_THREADS={os.environ.get('NUMBA_NUM_THREADS', '(unset)')}"
          + ("; outputs streamed to a Zarr store" if args.store else ""))
    print(f"{'model':9s} {'duration':>8s} {'estimate':>9s} {'measured':>9s} {'ratio':>6s}")
    for name, model in models():
        if name not in args.models:
            continue
        D.simulate(model, tr, 30.0, 0.01, "kik-piotrowski", "fastsim")      # warm-up
        for T in args.durations:
            init = {f"ws{i}.y": 0.003 for i in range(model.n_wheelsets)}
            store = os.path.join(tmp, f"{name}_{T}.zarr") if args.store else None
            r = D.simulate(model, tr, 30.0, T, "kik-piotrowski", "fastsim", initial=init,
                           store=store)
            est, cpu = r.info["estimated_cpu_time"], r.info["cpu_time"]
            print(f"{name:9s} {T:8.2f} {est:9.3f} {cpu:9.3f} {est / cpu:6.2f}")
    shutil.rmtree(tmp, ignore_errors=True)
    print(f"load average after {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
