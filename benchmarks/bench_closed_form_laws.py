"""Throughput of the closed-form creep-force laws and of the batch Hertz solve.

Prints evaluations per second (best of ``--repeat`` runs) for

* Polach (1999, and the 2005 extension with slip-velocity dependent friction),
* Shen–Hedrick–Elkins,

through the public API ``wr.creep_forces`` on a batch of ``n`` contacts (includes
input validation and Kalker-coefficient interpolation), and through the array
kernels alone; and Hertz solves per second through ``wr.hertz`` on a batch.

Usage::

    python benchmarks/bench_closed_form_laws.py [--n 100000] [--repeat 5]
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

import wheelrail as wr
from wheelrail.tangential.linear import kalker_coefficients
from wheelrail.tangential.polach import polach_forces
from wheelrail.tangential.shen_hedrick_elkins import shen_hedrick_elkins_forces


def best_time(fn, repeat):
    fn()  # warm-up
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=100_000, help="batch size")
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args(argv)
    n, rep = args.n, args.repeat

    rng = np.random.default_rng(0)
    steel = wr.Material(E=2.1e11, nu=0.28)
    load = rng.uniform(2e4, 1.2e5, n)
    A = np.full(n, 0.5 / 0.46)
    B = rng.uniform(0.8, 30.0, n)
    creep = np.column_stack([rng.uniform(-0.02, 0.02, n), rng.uniform(-0.02, 0.02, n),
                             rng.uniform(-3.0, 3.0, n)])
    mu = 0.3

    t_hertz = best_time(lambda: wr.hertz(load, A, B, steel), rep)
    contact = wr.hertz(load, A, B, steel)
    a, b = np.asarray(contact.a), np.asarray(contact.b)
    C11, C22, C23, C33 = (np.asarray(v) for v in kalker_coefficients(a / b, contact.nu))
    xi, eta, phi = creep.T.copy()

    rows = [
        ("hertz (wr.hertz, batch)", t_hertz),
        ("polach 1999 (wr.creep_forces)",
         best_time(lambda: wr.creep_forces(contact, creep, mu, method="polach"), rep)),
        ("polach 2005 dry, V=20 m/s (wr.creep_forces)",
         best_time(lambda: wr.creep_forces(contact, creep, 0.55, method="polach",
                                           conditions="dry", speed=20.0), rep)),
        ("shen-hedrick-elkins (wr.creep_forces)",
         best_time(lambda: wr.creep_forces(contact, creep, mu, method="shen-hedrick-elkins"),
                   rep)),
        ("polach 1999 (kernel polach_forces)",
         best_time(lambda: polach_forces(contact.G, a, b, C11, C22, C23, xi, eta, phi, mu, load),
                   rep)),
        ("shen-hedrick-elkins (kernel)",
         best_time(lambda: shen_hedrick_elkins_forces(contact.G, a, b, C11, C22, C23, C33, xi,
                                                      eta, phi, mu, load), rep)),
        ("kalker_coefficients (interpolation only)",
         best_time(lambda: kalker_coefficients(a / b, contact.nu), rep)),
    ]
    print(f"batch size n = {n}, best of {rep} runs, numpy {np.__version__}")
    print(f"machine load (1-min average): {os.getloadavg()[0]:.2f}")
    print(f"{'what':48s} {'time [ms]':>10s} {'evaluations/s':>15s}")
    for what, t in rows:
        print(f"{what:48s} {1e3 * t:10.2f} {n / t:15.3e}")


if __name__ == "__main__":
    main()
