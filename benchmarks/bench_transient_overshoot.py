"""Benchmark: the overshoot of Baeza et al. §3.1 ("Cattaneo to Carter") per scheme and step ratio.

Table 1 of Baeza et al. (E = 210 GPa, ν = 0.3, μ = 0.4, F3 = 10 kN, F1 = 2 kN at once),
90 mm of travel. For each ``N:ratio`` (elements over 2a : dx/h, or ``N:b`` for Baeza et
al.'s V·Δt = 0.05 mm) it prints the final ξ, the overshoot of |ξ| after the first step
(peak / final − 1), where the peak lies, the number of steps before the peak at which |ξ|
decreases, the slipping fraction after 17 steps, the CPU time (``time.process_time``) and
the machine load. CONTACT on the same grids at V·Δt = 0.05 mm: overshoot 8.66 % (30
elements), 10.40 % (60).

Run:  .venv/bin/python benchmarks/bench_transient_overshoot.py [--schemes transport interpolated upwind2] [30:b 60:b 30:1 ...]
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

import wheelrail as wr
from wheelrail.normal.bem import hertz_grid


def run(scheme, spec):
    hc = wr.hertz_from_radii(10e3, 0.5, -0.409, 0.3, material=wr.Material(2.1e11, 0.3))
    n, ratio = spec.split(":")
    n = int(n)
    dx = hertz_grid(hc, elements=n)[0].dx
    h = 5e-5 if ratio == "b" else dx / float(ratio)
    t = time.process_time()
    r = wr.transient_rolling(hc, travel=0.09, step=h, mu=0.4, Fx=2000.0, elements=n, frames=2,
                             scheme=scheme)
    cpu = time.process_time() - t
    xi = np.abs(r.xi)
    k = int(np.argmax(xi[2:])) + 2
    d = np.diff(xi[2:k + 1])
    print(f"{scheme:12s} {n:4d} el. dx/h {dx / h:5.2f}: final xi {r.xi[-1]:.5e}, overshoot "
          f"{100 * (xi[k] / xi[-1] - 1):6.2f} % at x = {r.x[k] * 1e3:.2f} mm, decreasing steps "
          f"before the peak {(d < 0).sum()} (worst {d.min() / xi[-1]:+.1e} of |xi_end|), "
          f"slipping fraction after 17 steps {r.n_slip[17] / max(r.n_contact[17], 1):.3f}, "
          f"CPU {cpu:.2f} s, {r.info['solves']} solves, load {os.getloadavg()[0]:.1f}",
          flush=True)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("specs", nargs="*", default=["30:b", "60:b", "30:1", "60:1"])
    ap.add_argument("--schemes", nargs="+", default=["transport", "interpolated", "upwind2"])
    a = ap.parse_args()
    run("transport", "6:1")                       # numba warm-up
    for spec in a.specs:
        for scheme in a.schemes:
            run(scheme, spec)


if __name__ == "__main__":
    main()
