"""Whole vehicle: real-time factor of Manchester vehicle 1 with the compiled RK4 path.

Problem: Manchester benchmark vehicle 1 (Iwnicki 1998; ``wr.dynamics.manchester_vehicle1``):
car body, two bogie frames, four wheelsets (66 states), S1002 on 60E1 at 1:40,
μ = 0.3, 30 m/s,

* tangent track, the leading wheelset released 3 mm off centre;
* a 600 m curve with 100 mm cant (after 20 m of tangent and a 50 m transition).

Fixed-step classical Runge–Kutta at 1 ms (four evaluations of all eight wheels'
contact per step; steps across a contact-configuration change are halved),
for Kik–Piotrowski + FASTSIM (goal: real-time factor ≥ 1) and Hertz + the
table law (goal ≥ 3; the table is built or loaded first, outside the timing),
and Hertz + FASTSIM for comparison. The real-time factor is simulated time per
CPU second (``time.process_time``, one core: ``NUMBA_NUM_THREADS=1``), after a
warm-up run (numba cache load); the machine's load (``os.getloadavg``) is
printed with the numbers.

    python benchmarks/bench_vehicle_speed.py [--duration 3.0] [--repeat 2]
"""

from __future__ import annotations

import argparse
import math
import os
import time

import wheelrail as wr

D = wr.dynamics


def run(model, track, normal, tangential, duration, repeat, **kw):
    D.simulate(model, track, 30.0, 0.05, normal, tangential, **kw)        # warm-up
    best = None
    for _ in range(repeat):
        cpu = time.process_time()
        r = D.simulate(model, track, 30.0, duration, normal, tangential, output_step=0.01, **kw)
        cpu = time.process_time() - cpu
        if best is None or cpu < best[0]:
            best = (cpu, r)
    return best


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--duration", type=float, default=3.0, help="simulated time [s]")
    ap.add_argument("--repeat", type=int, default=2)
    args = ap.parse_args()
    model = D.manchester_vehicle1()
    section = wr.Track(wr.profiles.load("60E1"))
    curve = D.TrackLayout(section, curves=(D.Curve(600.0, start=20.0, length=math.inf,
                                                   cant=0.1, transition=50.0),))
    n_states = len(D.System(model, section, 30.0, "hertz", "fastsim").asm.names)
    print(f"Manchester vehicle 1: {n_states}"
          f" states, 8 wheels, RK4 1 ms, {args.duration} s simulated, best of {args.repeat}")
    print(f"NUMBA_NUM_THREADS={os.environ.get('NUMBA_NUM_THREADS', '(unset)')}, "
          f"load before: {os.getloadavg()}")
    cases = [("kik-piotrowski", "fastsim", 1.0), ("hertz", "table", 3.0),
             ("hertz", "fastsim", None)]
    for track, name in ((section, "tangent, ws0 3 mm off"), (curve, "600 m curve, 100 mm cant")):
        kw = {"initial": {"ws0.y": 0.003}} if track is section else {}
        for normal, tangential, goal in cases:
            cpu, r = run(model, track, normal, tangential, args.duration, args.repeat, **kw)
            rtf = args.duration / cpu
            n = r.info["contact_evaluations"]
            print(f"{name:26s} {normal:15s} + {tangential:8s}: CPU {cpu:6.2f} s, real-time "
                  f"factor {rtf:5.2f}" + (f" (goal >= {goal:g})" if goal else "")
                  + f", {n} evaluations, {cpu / n * 1e6:6.1f} us each "
                  f"({cpu / n / 8 * 1e6:5.1f} us per wheel), rejected steps "
                  f"{r.info['rejected_steps']}, events {len(r.events)}")
    print(f"load after: {os.getloadavg()}")


if __name__ == "__main__":
    main()
