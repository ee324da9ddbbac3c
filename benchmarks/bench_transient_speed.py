"""Benchmark: CPU time of Baeza et al. §3.1 (30 elements, 1801 steps), alternated with another tree.

Table 1 of Baeza et al. (E = 210 GPa, ν = 0.3, μ = 0.4, F3 = 10 kN, F1 = 2 kN at
once), V·Δt = 0.05 mm, 90 mm of travel, default scheme. Each run is a separate
process (``time.process_time`` around the call, after a small warm-up run that
loads the numba caches); with ``--before SRC`` the same script runs with
``PYTHONPATH=SRC`` (e.g. another checkout's ``src``) in alternation, so both see
the same load. Prints CPU time, final ξ and the solver counts of every run and
the load average.

Run:  .venv/bin/python benchmarks/bench_transient_speed.py [--before /path/to/other/src] [--rounds 2]
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys

CODE = r'''
import time, wheelrail as wr
SEED = wr.Material(2.1e11, 0.3); H = 5e-5
hc = wr.hertz_from_radii(10e3, 0.5, -0.409, 0.3, material=SEED)
wr.transient_rolling(hc, travel=4e-4, step=2e-4, mu=0.4, Fx=2000.0, elements=6)
t = time.process_time()
r = wr.transient_rolling(hc, travel=1800 * H, step=H, mu=0.4, Fx=2000.0, elements=30, frames=2)
print("cpu %.3f s, xi_end %.9e, solves %d, krylov %d" % (time.process_time() - t, r.xi[-1],
      r.info["solves"], r.info["krylov"]))
'''


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--before", help="src directory of the code to compare with")
    ap.add_argument("--rounds", type=int, default=2)
    args = ap.parse_args()
    trees = [("this tree", None)] + ([("before", args.before)] if args.before else [])
    for k in range(args.rounds):
        for name, src in trees:
            env = dict(os.environ)
            if src:
                env["PYTHONPATH"] = src
            out = subprocess.run([sys.executable, "-c", CODE], capture_output=True, text=True,
                                 env=env, cwd=os.path.expanduser("~"))
            print(f"round {k} {name:10s} {out.stdout.strip() or out.stderr.strip()[-300:]}  "
                  f"load {os.getloadavg()[0]:.1f}", flush=True)


if __name__ == "__main__":
    main()
