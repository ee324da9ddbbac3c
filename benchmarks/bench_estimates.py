"""Benchmark: the estimates shown (and enforced) before long jobs against measured runs.

For each kind of long job — a sweep (``wheelrail.sweeps.estimate``: chunks and
points × a measured cost per point), a transient run (``wheelrail.cli.transient.estimate``:
steps × grid cells), a normal BEM solve and an exact-theory solve
(``wheelrail._resources.estimate``: from the grid cells) and an explicit FE
rolling run (``wheelrail.cli.fe``: steps × (fixed + elements × cost), after and
before the mesh is built) — three sizes are run, each in a fresh subprocess
after one warm-up run that compiles the kernels, and the estimate is printed
beside the measured wall time, CPU time and peak resident memory
(``ru_maxrss``), with the problem size and the machine load. The goal is
estimates within a factor 2 of the measured time. The estimates are of the
time on an unloaded core (CPU time, column e/cpu); e/wall compares them with
the wall time, eL/wall the estimate at the current load
(``wheelrail._resources.load_factor``, shown in the estimate line when the
machine is busy) with the wall time.

Run: ``python benchmarks/bench_estimates.py [--only fe exact]`` (about 3 minutes on
2 cores when idle; the FE kernels compile once, about 35 s, if not cached).
"""

import json
import os
import subprocess
import sys

#: The rolling case of tests/fe/test_fe_cli.py (reduced hex8, mass scaling 400, 6 mm), as
#: [fe] keys of a case file (the mesh size is the benchmark's size).
FE_KEYS = {"wheel": "cylinder", "rail": "60E1", "radius": 0.46, "Fn": 7500.0, "mu": 0.2,
           "creepage": [7e-4, 0.0, 0.0], "element": "reduced", "mass_scaling": 400.0,
           "depth": 3.0, "half_width": 3.0, "half_length": 3.0, "travel": 0.006}
FE_CASE = "[fe]\n" + "".join(f"{k} = {json.dumps(v)}\n" for k, v in FE_KEYS.items()) \
    + "mesh_size = {mesh_size}\n"

CHILD = "FE_CASE = " + repr(FE_CASE) + r"""
import json, resource, sys, time
import numpy as np
import wheelrail as wr
from wheelrail import _resources
kind, n = sys.argv[1], int(sys.argv[2])
hc = wr.hertz(7500.0, 0.5 / 0.46, 0.5 / 0.30, wr.Material(2.1e11, 0.28))
factor = _resources.load_factor()  # wall / CPU expected at the current load
with _resources.limit(None), _resources.time_limit_set(None):
    if kind == "sweep":
        from wheelrail.sweeps import SweepSpec
        from wheelrail.sweeps.estimate import estimate_sweep
        spec = SweepSpec.grid(method="fastsim", mu=0.3, Fn=1e4, A=1.087, B=1.667,
                              xi=np.linspace(-3e-3, 3e-3, n // 10), eta=np.linspace(0, 1e-3, 10),
                              options={"nx": 20, "ny": 20}, chunk=1000)
        est = estimate_sweep(spec)          # measures a few points (and warms the kernels)
        size = f"{spec.size} points"
        t, c = time.perf_counter(), time.process_time()
        wr.sweep(spec, progress=False)
        seconds, memory = est.seconds, est.memory
    elif kind == "transient":
        from wheelrail.cases.files import load_transient_case
        from wheelrail.cli.transient import estimate
        text = open(sys.argv[3]).read()
        lines = []
        for ln in text.splitlines():
            key = ln.split("=")[0].strip()
            lines.append({"elements": f"elements = {n}", "travel": "travel = 0.006",
                          "frames": "frames = 10"}.get(key, ln))
        import os, tempfile
        fd, path = tempfile.mkstemp(suffix=".toml")
        with os.fdopen(fd, "w") as fh:
            fh.write("\n".join(lines) + "\n")
        case = load_transient_case(path)
        os.remove(path)
        seconds, memory, cells = estimate(case.hertz_contact, case.settings)
        steps = int(case.settings["travel"] / case.settings["step"] + 1e-9)
        size = f"{steps} steps x {cells} cells"
        t, c = time.perf_counter(), time.process_time()
        case.run(progress=False)
    elif kind == "bem_normal":
        g, h = wr.hertz_grid(hc, n)
        est = _resources.estimate(kind, g.size)
        seconds, memory, size = est.seconds, est.memory, f"{g.nx}x{g.ny} cells"
        t, c = time.perf_counter(), time.process_time()
        wr.solve_normal(g, h, hc.materials, Fn=7500.0)
    elif kind == "fe":
        from wheelrail.cli.fe import _steps_before_build, case_from_toml, estimate, seconds_estimate
        from wheelrail.fe import solve
        from wheelrail.fe.model import build_model
        from wheelrail.fe.model import mesh_size_estimate
        import os, tempfile
        fd, path = tempfile.mkstemp(suffix=".toml")
        with os.fdopen(fd, "w") as fh:
            fh.write(FE_CASE.format(mesh_size=n * 1e-4))
        case, _ = case_from_toml(path)
        os.remove(path)
        pre = mesh_size_estimate(case)
        plastic = getattr(case.material, "yield_stress", None) is not None
        pre_seconds = seconds_estimate(case, pre["n_elements"], _steps_before_build(case, pre),
                                       plastic)
        t, c = time.perf_counter(), time.process_time()
        model = build_model(case)
        steps, seconds = estimate(case, model)
        r = solve(case, progress=False)
        memory = pre["memory"] + 250e6  # the model, and the interpreter with numpy and numba
        size = f"{model.n_elements} el x {steps} steps"
    else:
        m = max(1.1, 1.0 + 3.0 / n)
        g, _ = wr.hertz_grid(hc, n, margin=m)
        est = _resources.estimate(kind, g.size)
        seconds, memory, size = est.seconds, est.memory, f"{g.nx}x{g.ny} cells"
        t, c = time.perf_counter(), time.process_time()
        wr.creep_forces(hc, (-1e-3, 0.0, 0.0), 0.3, method="exact", elements=n)
    wall, cpu = time.perf_counter() - t, time.process_time() - c
extra = {"pre_seconds": pre_seconds} if kind == "fe" else {}
print(json.dumps({**extra, "factor": factor, "size": size, "wall": wall, "cpu": cpu,
                  "est_seconds": seconds, "est_memory": memory,
                  "rss": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024}))
"""

CASES = (("sweep", (2000, 8000, 32000)), ("transient", (20, 30, 45)),
         ("bem_normal", (100, 200, 300)), ("exact", (30, 50, 80)),
         ("fe", (20, 15, 10)))  # fe: mesh size in 0.1 mm


def _child(kind, n, transient_case):
    out = subprocess.run([sys.executable, "-c", CHILD, kind, str(n), transient_case],
                         capture_output=True, text=True, cwd=os.getcwd())
    if out.returncode:
        return out.stderr.strip().splitlines()[-1]
    return json.loads(out.stdout.strip().splitlines()[-1])


def main(argv=None):
    import argparse

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", nargs="*", default=None, help="job kinds to run (default all)")
    ap.add_argument("--cold", action="store_true",
                    help="no warm-up run (the first size then includes compiling the kernels "
                         "if they are not cached)")
    args = ap.parse_args(argv)
    here = os.path.dirname(os.path.abspath(__file__))
    transient_case = os.path.join(here, "..", "docs", "examples", "transient_cattaneo_carter.toml")
    print(f"load average before: {os.getloadavg()} ({os.cpu_count()} cores)")
    print(f"{'job':10s} {'size':>22s} {'wall':>8s} {'cpu':>8s} {'estimate':>9s} {'e/cpu':>6s} "
          f"{'e/wall':>6s} {'eL/wall':>7s} {'peak RSS':>9s} {'estimate':>9s}")
    for kind, sizes in CASES:
        if args.only and kind not in args.only:
            continue
        if not args.cold:
            _child(kind, sizes[0], transient_case)  # compiles (and caches) the kernels
        for n in sizes:
            r = _child(kind, n, transient_case)
            if isinstance(r, str):
                print(f"{kind:10s} {n:>22d} failed: {r}")
                continue
            e, f = r["est_seconds"], r["factor"]
            print(f"{kind:10s} {r['size']:>22s} {r['wall']:7.2f}s {r['cpu']:7.2f}s "
                  f"{e:8.2f}s {e / max(r['cpu'], 1e-9):6.2f} {e / r['wall']:6.2f} "
                  f"{e * f / r['wall']:7.2f} {r['rss'] / 1e6:7.0f}MB {r['est_memory'] / 1e6:7.0f}MB")
            if "pre_seconds" in r:
                e = r["pre_seconds"]
                print(f"{'':10s} {'before the mesh is built':>22s} {'':8s} {'':8s} "
                      f"{e:8.2f}s {e / max(r['cpu'], 1e-9):6.2f} {e / r['wall']:6.2f} "
                      f"{e * f / r['wall']:7.2f}")
    print(f"load average after: {os.getloadavg()}")


if __name__ == "__main__":
    main()
