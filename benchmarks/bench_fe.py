"""FE engine benchmark: element kernel cost, explicit step cost, memory, and problem sizes.

Run:  python benchmarks/bench_fe.py [--mesh 1e-3] [--steps 200]

Prints, with the problem sizes and the machine load (uptime):
* ns per element per internal-force evaluation (hex8 full 2x2x2 and reduced 1-point + hourglass);
* ns per element per complete explicit step (contact, kinematics and bookkeeping included)
  and steps per second, on the seed-000-like rolling mesh;
* memory per element of the precomputed element data;
* the stable time step and the number of steps the default rolling run needs, and the
  resulting time estimate.
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

import wheelrail as wr
from wheelrail.fe import RollingCase, build_model
from wheelrail.fe import _kernels as K
from wheelrail.fe.rolling import _speed_profile, stable_time_step


def load():
    return os.getloadavg()[0]


def kernel_cost(model, repeat=20):
    u = np.random.default_rng(0).normal(size=(model.n_nodes, 3)) * 1e-7
    f = np.zeros_like(u)
    model.internal_force(u, f)               # compile / warm
    t = time.perf_counter()
    for _ in range(repeat):
        f[:] = 0
        model.internal_force(u, f)
    dt = (time.perf_counter() - t) / repeat
    return dt / model.n_elements * 1e9


def step_cost(case, steps):
    """Time a whole explicit run (relaxation + rolling) on a coarser, mass-scaled copy.

    The per-element cost of a step does not depend on the mesh size; the copy (mesh 2 h,
    mass scaling 100, a short travel) keeps the timed run short.
    """
    from wheelrail.fe import solve

    short = case.replace(mesh_size=2 * case.mesh_size, mass_scaling=100.0, travel=0.012)
    t = time.perf_counter()
    r = solve(short, progress=False)
    wall = time.perf_counter() - t
    n = r.info["steps"]
    return wall / n / r.model.n_elements * 1e9, n / wall, r.model.n_elements, n


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--mesh", type=float, default=1e-3)
    ap.add_argument("--steps", type=int, default=0, help=argparse.SUPPRESS)
    args = ap.parse_args()
    wheel = wr.Profile(np.linspace(-0.04, 0.04, 9), np.zeros(9), kind="wheel")
    print(f"load average before: {load():.2f} (2-core machine shared with other agents)")
    for element in ("reduced", "full"):
        case = RollingCase(wheel=wheel, rail=wr.profiles.load("60E1"), radius=0.46, load=7500.0,
                           creepage=(7e-4, 0, 0), mu=0.2, mesh_size=args.mesh, element=element)
        t = time.perf_counter()
        model = build_model(case)
        t_build = time.perf_counter() - t
        ns_el = kernel_cost(model)
        mem = (model.edata_w.nbytes + model.edata_r.nbytes) / model.n_elements
        dt = case.courant * stable_time_step(model)
        _, t_end = _speed_profile(case, model.geometry["travel"])
        n2 = int(np.ceil(t_end / dt))
        print(f"\n[{element}] mesh {args.mesh * 1e3:g} mm: {model.n_elements} elements, "
              f"{model.n_nodes} nodes, travel {model.geometry['travel'] * 1e3:.1f} mm, "
              f"build {t_build:.1f} s")
        print(f"  internal force: {ns_el:.0f} ns/element/evaluation; element data "
              f"{mem:.0f} B/element")
        print(f"  stable step {dt:.3g} s (courant {case.courant}); rolling needs {n2} steps")
        ns_step, sps, ne, n = step_cost(case, args.steps)
        print(f"  explicit loop: {ns_step:.0f} ns/element/step, {sps:.1f} steps/s "
              f"({n} steps timed on {ne} elements)")
        print(f"  estimate for the rolling run ({n2} steps x {model.n_elements} elements): "
              f"{n2 * ns_step * 1e-9 * model.n_elements / 60:.1f} min on one core")
    print(f"\nload average after: {load():.2f}")


if __name__ == "__main__":
    main()
