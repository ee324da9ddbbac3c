"""Benchmark: CPU time of Baeza et al. §3.1 (30 elements, 1801 steps), alternated with another tree.

Table 1 of Baeza et al. (E = 210 GPa, ν = 0.3, μ = 0.4, F3 = 10 kN, F1 = 2 kN at
once), V·Δt = 0.05 mm, 90 mm of travel, default scheme. Each run is a separate
process (``time.process_time`` around the call, after a small warm-up run that
loads the numba caches); with ``--before SRC`` the same script runs with
``PYTHONPATH=SRC`` (e.g. another checkout's ``src``) in alternation, so both see
the same load. Prints CPU time, final ξ and the solver counts of every run and
the load average.

With ``--history`` it also compares the ξ and Fx histories of the last round of
each tree with a run of this tree at 1000× tighter tolerances (``tol`` 1e-11,
``force_tol`` 1e-10): the largest |Δξ| over the history relative to |ξ_end|
and the largest |ΔFx| [N] (the solver tolerance of the default run is
``force_tol·μ·Fn`` = 4e-4 N in Fx).

Run:  .venv/bin/python benchmarks/bench_transient_speed.py [--before /path/to/other/src] [--rounds 2] [--history] [--scheme interpolated]
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np

CODE = r'''
import os, sys, time, numpy as np, wheelrail as wr
SEED = wr.Material(2.1e11, 0.3); H = 5e-5
hc = wr.hertz_from_radii(10e3, 0.5, -0.409, 0.3, material=SEED)
kw = dict(scheme=os.environ["BTS_SCHEME"], tol=float(os.environ["BTS_TOL"]),
          force_tol=float(os.environ["BTS_FTOL"]))
wr.transient_rolling(hc, travel=4e-4, step=2e-4, mu=0.4, Fx=2000.0, elements=6, **kw)
t = time.process_time()
r = wr.transient_rolling(hc, travel=1800 * H, step=H, mu=0.4, Fx=2000.0, elements=30, frames=2,
                         **kw)
print("cpu %.3f s, xi_end %.9e, solves %d, krylov %d" % (time.process_time() - t, r.xi[-1],
      r.info["solves"], r.info["krylov"]))
if os.environ.get("BTS_OUT"):
    np.save(os.environ["BTS_OUT"], np.array([r.xi, r.Fx]))
'''


def _run(src, scheme, tol, ftol, out=None):
    env = dict(os.environ, BTS_SCHEME=scheme, BTS_TOL=str(tol), BTS_FTOL=str(ftol),
               BTS_OUT=out or "")
    if src:
        env["PYTHONPATH"] = src
    res = subprocess.run([sys.executable, "-c", CODE], capture_output=True, text=True, env=env,
                         cwd=os.path.expanduser("~"))
    return res.stdout.strip() or res.stderr.strip()[-300:]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--before", help="src directory of the code to compare with")
    ap.add_argument("--rounds", type=int, default=2)
    ap.add_argument("--scheme", default="interpolated")
    ap.add_argument("--history", action="store_true",
                    help="compare the histories with a run at 1000x tighter tolerances")
    args = ap.parse_args()
    trees = [("this tree", None)] + ([("before", args.before)] if args.before else [])
    tmp = tempfile.mkdtemp()
    print(f"scheme {args.scheme}", flush=True)
    for k in range(args.rounds):
        for j, (name, src) in enumerate(trees):
            out = (os.path.join(tmp, f"tree{j}.npy")
                   if args.history and k == args.rounds - 1 else None)
            print(f"round {k} {name:10s} {_run(src, args.scheme, 1e-8, 1e-7, out)}  "
                  f"load {os.getloadavg()[0]:.1f}", flush=True)
    if args.history:
        ref_path = os.path.join(tmp, "tight.npy")
        print(f"tight      {_run(None, args.scheme, 1e-11, 1e-10, ref_path)}", flush=True)
        ref = np.load(ref_path)
        for j, (name, _) in enumerate(trees):
            h = np.load(os.path.join(tmp, f"tree{j}.npy"))
            dxi = np.abs(h[0] - ref[0])
            print(f"{name:10s} vs tight: max |dxi|/|xi_end| {dxi.max() / abs(ref[0][-1]):.2e} "
                  f"(step {int(dxi.argmax())}), at the end {dxi[-1] / abs(ref[0][-1]):.1e}, "
                  f"max |dFx| {np.abs(h[1] - ref[1]).max():.1e} N")
        if len(trees) == 2:
            a, b = (np.load(os.path.join(tmp, f"tree{j}.npy")) for j in (0, 1))
            d = np.abs(a[0] - b[0])
            print(f"this tree vs before: max |dxi|/|xi_end| {d.max() / abs(b[0][-1]):.2e}, "
                  f"at the end {d[-1] / abs(b[0][-1]):.1e}, "
                  f"max |dFx| {np.abs(a[1] - b[1]).max():.1e} N")


if __name__ == "__main__":
    main()
