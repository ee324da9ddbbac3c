"""Benchmark of the one- to two-point contact transition model (wheelrail.fe.transition).

Prints the model size, the estimate before the run, the CPU time, the cost per element and
step, the onset of two-point contact and the patch forces at the end, with the load of
the machine. Usage::

    python benchmarks/bench_fe_transition.py [--aoa 0.025] [--mesh 3e-3] [--travel 0.06]
    python benchmarks/bench_fe_transition.py --onset            # 15, 20, 25 mrad
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

import wheelrail as wr


def one(aoa, mesh, travel):
    case = wr.fe.seed004_case(aoa, mesh_size=mesh, travel=travel,
                              settle=min(0.015, 0.25 * travel))
    t0 = time.process_time()
    model = wr.fe.build_transition_model(case)
    t_build = time.process_time() - t0
    r = wr.fe.run_transition(case, model=model, progress=True)
    ds = r.patches
    last = ds.isel(time=-1)
    print(f"aoa {aoa * 1e3:.0f} mrad, h = {mesh * 1e3:g} mm: {r.info['elements']} elements, "
          f"{r.info['steps']} steps of {r.info['time_step'] * 1e9:.1f} ns, build {t_build:.1f} s, "
          f"run {r.info['cpu_s']:.0f} s CPU ({r.info['wall_s']:.0f} s wall), "
          f"{r.info['ns_per_element_step']:.0f} ns/element/step (CPU), "
          f"load {os.getloadavg()[0]:.1f}")
    print(f"  onset of two-point contact at travel {r.info['onset_travel'] * 1e3:.1f} mm; "
          f"wheel load {r.info['load'] / 1e3:.1f} kN")
    for p in ds.patch.values:
        row = last.sel(patch=p)
        if float(row.Fn) > 0:
            print(f"  patch {p}: Fn {float(row.Fn) / 1e3:.1f} kN, Fz {float(row.Fz) / 1e3:.1f} kN, "
                  f"angle {np.degrees(float(row.contact_angle)):.1f} deg, "
                  f"theta {np.degrees(float(row.theta)):.1f} deg, adhesion {float(row.adhesion):.2f}")
    return r


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--aoa", type=float, default=0.025)
    ap.add_argument("--mesh", type=float, default=3e-3)
    ap.add_argument("--travel", type=float, default=0.06)
    ap.add_argument("--onset", action="store_true")
    a = ap.parse_args()
    if a.onset:
        onsets = {aoa: one(aoa, a.mesh, a.travel).info["onset_travel"]
                  for aoa in (0.015, 0.020, 0.025)}
        print("onset [mm]:", {k: round(v * 1e3, 1) for k, v in onsets.items()})
    else:
        one(a.aoa, a.mesh, a.travel)


if __name__ == "__main__":
    main()
