"""Benchmark: Kalker's exact theory, steady rolling on a half-space grid.

For several numbers of elements across the Hertz contact (grid sizes printed)
and three creepage cases it prints the time of the normal (boundary-element)
solve, of the tangential (Newton–GMRES) solve and their sum, the Newton and
Krylov (GMRES) iteration counts and the forces. Times are the best of
``--repeat`` runs after a warm-up (numba cache loaded, kernels built), on one
core: the process is limited to one BLAS/FFT thread; wall time ("s") and the
CPU time of the process ("cpu s", less sensitive to other processes) are
printed, the speed-up is the ratio of CPU times of normal + tangential
solve. The Newton and Krylov counts are those of the given grid; with
nested iteration the coarse levels' counts follow the forces as
``nx:newton/krylov`` per level (coarse grid size nx, finest first; a coarse
Krylov iteration costs about a quarter of a finer one). "cf cpu" is the CPU
time of the same case through
``wr.creep_forces(..., method="exact", elements=N)`` (window, normal solve as
the method starts it, tangential solve; its normal-solution cache cleared).
The load average of the machine is printed beside the numbers, since other
processes share the CPU. After the rows of each size a line gives the
normal solve alone (iterations, CPU time): from the solver's default start
and from the analytic Hertz pressure on the exact method's window, as
``creep_forces`` starts it.

``--before SRC`` runs the same measurements with another source tree of the
package (e.g. ``git archive main src | tar -x -C /tmp/main`` then
``--before /tmp/main/src``) in a subprocess, interleaved size by size with
this tree, and prints the before/after ratios: the comparison is made under
the same load.

Run::

    .venv/bin/python benchmarks/bench_exact_rolling.py [N ...] [--repeat R] [--before SRC]

Defaults: N = 40 104 160, R = 3. The peak memory of the tangential solve is
measured in a separate (untimed) run with ``--memory``.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys

# one core: must be set before numpy / scipy load their thread pools
for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

CASES = {
    "small creep": (2e-4, 0.0, 0.0),
    "combined": (1e-3, 5e-4, 1.0),
    "spin": (0.0, 0.0, 3.0),
}
MU = 0.3


def clear_normal_cache() -> bool:
    """Empty ``creep_forces``' cache of normal solutions wherever this version of the package
    keeps it (``wheelrail.tangential.exact.method`` now, the package module before); False if
    none was found (then "cf cpu" may reuse a normal solution of an earlier repeat)."""
    import importlib

    found = False
    for name in ("wheelrail.tangential.exact.method", "wheelrail.tangential.exact"):
        try:
            module = importlib.import_module(name)
        except ImportError:
            continue
        cache = getattr(module, "_NORMAL_CACHE", None)
        if cache is not None:
            cache.clear()
            found = True
    return found


def measure(n: int, repeat: int, memory: bool = False) -> dict:
    """Times, iteration counts and forces of one grid size (in this process's package)."""
    import time
    import tracemalloc

    import wheelrail as wr
    from wheelrail.tangential.exact import solve_rolling
    from wheelrail.normal.bem import hertz_grid, solve_normal

    hc = wr.hertz(1e4, A=1.0, B=2.0, material=wr.STEEL)
    g8, h8 = hertz_grid(hc, elements=8, margin=1.5)
    solve_rolling(g8, solve_normal(g8, h8, wr.STEEL, Fn=1e4).pressure, wr.STEEL,
                  (1e-3, 0, 0), MU)                                   # numba warm-up
    grid, gap = hertz_grid(hc, elements=n, margin=1.1)
    normal = solve_normal(grid, gap, wr.STEEL, Fn=1e4)              # builds the kernels
    tn, cn = [], []
    for _ in range(repeat):
        t0, c0 = time.perf_counter(), time.process_time()
        normal = solve_normal(grid, gap, wr.STEEL, Fn=1e4)
        tn.append(time.perf_counter() - t0)
        cn.append(time.process_time() - c0)
    out = {"n": n, "grid": f"{grid.nx}x{grid.ny}", "normal_s": min(tn), "normal_cpu": min(cn),
           "normal_iterations": normal.iterations, "cases": {}}
    # the normal solve as the exact method starts it: its window (at least 3 elements of
    # margin) and the analytic Hertz pressure as the first iterate
    import numpy as np

    gh, hh = hertz_grid(hc, elements=n, margin=max(1.1, 1.0 + 3.0 / n))
    hz = float(hc.p0) * np.sqrt(np.clip(1.0 - (gh.X / float(hc.a)) ** 2
                                        - (gh.Y / float(hc.b)) ** 2, 0.0, None))
    solve_normal(gh, hh, wr.STEEL, Fn=1e4, initial=hz)
    ch = []
    for _ in range(repeat):
        c0 = time.process_time()
        nh = solve_normal(gh, hh, wr.STEEL, Fn=1e4, initial=hz)
        ch.append(time.process_time() - c0)
    out["normal_hertz_cpu"] = min(ch)
    out["normal_hertz_iterations"] = nh.iterations
    for name, cr in CASES.items():
        s = solve_rolling(grid, normal.pressure, wr.STEEL, cr, MU)
        tt, ct = [], []
        for _ in range(repeat):
            t0, c0 = time.perf_counter(), time.process_time()
            s = solve_rolling(grid, normal.pressure, wr.STEEL, cr, MU)
            tt.append(time.perf_counter() - t0)
            ct.append(time.process_time() - c0)
        row = {"tangential_s": min(tt), "tangential_cpu": min(ct), "newton": s.iterations,
               "krylov": s.info["krylov_iterations"], "Fx": s.Fx, "Fy": s.Fy, "Mz": s.Mz,
               # nested iteration (absent in older versions): per coarse level, finest first
               "coarse": [(c["shape"][0], c["newton"], c["krylov"])
                          for c in s.info.get("coarse", ())]}
        # the same case through the public entry point (window, normal solve from the Hertz
        # start as the method does it, tangential solve); the normal-solution cache is cleared
        cf = []
        for _ in range(repeat):
            row["cache_cleared"] = clear_normal_cache()
            c0 = time.process_time()
            wr.creep_forces(hc, cr, MU, method="exact", elements=n)
            cf.append(time.process_time() - c0)
        row["creep_forces_cpu"] = min(cf)
        if memory:
            tracemalloc.start()
            solve_rolling(grid, normal.pressure, wr.STEEL, cr, MU)
            row["peak_MB"] = tracemalloc.get_traced_memory()[1] / 2**20
            tracemalloc.stop()
        out["cases"][name] = row
    return out


def _measure_in(src: str | None, n: int, repeat: int, memory: bool) -> dict:
    if src is None:
        return measure(n, repeat, memory)
    env = dict(os.environ, PYTHONPATH=os.path.abspath(src))
    cmd = [sys.executable, os.path.abspath(__file__), "--json", str(n), "--repeat", str(repeat)]
    if memory:
        cmd.append("--memory")
    res = subprocess.run(cmd, env=env, capture_output=True, text=True, check=True)
    return json.loads(res.stdout.strip().splitlines()[-1])


def _print_header(compare: bool) -> None:
    cols = (f"{'N':>4} {'grid':>8} {'case':>12} {'normal s':>9} {'tang s':>8} {'total s':>8} "
            f"{'cpu s':>7} {'cf cpu':>7} {'newton':>6} {'krylov':>6}")
    if compare:
        cols += (f" {'before s':>9} {'cpu s':>7} {'cf cpu':>7} {'nwt':>4} {'kry':>4} "
                 f"{'speed-up':>8}")
    cols += f" {'Fx N':>10} {'Fy N':>10} {'Mz Nm':>9}  coarse levels nx:newton/krylov"
    print(cols)


def _print_rows(after: dict, before: dict | None) -> None:
    for name, r in after["cases"].items():
        total = after["normal_s"] + r["tangential_s"]
        cpu = after["normal_cpu"] + r["tangential_cpu"]
        line = (f"{after['n']:>4} {after['grid']:>8} {name:>12} {after['normal_s']:>9.3f} "
                f"{r['tangential_s']:>8.3f} {total:>8.3f} {cpu:>7.3f} "
                f"{r['creep_forces_cpu']:>7.3f} {r['newton']:>6} {r['krylov']:>6}")
        if before is not None:
            b = before["cases"][name]
            tb = before["normal_s"] + b["tangential_s"]
            cb = before["normal_cpu"] + b["tangential_cpu"]
            line += (f" {tb:>9.3f} {cb:>7.3f} {b['creep_forces_cpu']:>7.3f} {b['newton']:>4} "
                     f"{b['krylov']:>4} {cb / cpu:>8.2f}")
        line += f" {r['Fx']:>10.2f} {r['Fy']:>10.2f} {r['Mz']:>9.4f}"
        line += "  " + (" ".join(f"{n}:{a}/{k}" for n, a, k in r.get("coarse", ())) or "-")
        if "peak_MB" in r:
            line += f"  peak {r['peak_MB']:.1f} MB"
        if not r.get("cache_cleared", True):
            line += "  (cf cpu: no normal-solution cache found to clear)"
        print(line, flush=True)


def _print_normal(after: dict, before: dict | None) -> None:
    """Normal solve alone: iterations and CPU time, default start and Hertz start."""
    def part(r):
        txt = f"default start {r['normal_iterations']} it {r['normal_cpu']:.4f} s"
        if "normal_hertz_cpu" in r:
            txt += (f", Hertz start {r['normal_hertz_iterations']} it "
                    f"{r['normal_hertz_cpu']:.4f} s")
        return txt
    line = f"{after['n']:>4} {after['grid']:>8}  normal solve (cpu): {part(after)}"
    if before is not None:
        line += f"  | before: {part(before)}"
    print(line, flush=True)


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("sizes", nargs="*", type=int, default=[40, 104, 160])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--before", default=None, help="source tree (.../src) to compare with")
    ap.add_argument("--memory", action="store_true", help="also measure peak memory (untimed run)")
    ap.add_argument("--json", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.json:
        print(json.dumps(measure(args.sizes[0], args.repeat, args.memory)))
        return
    import wheelrail as wr

    hc = wr.hertz(1e4, A=1.0, B=2.0, material=wr.STEEL)
    print(f"Hertz contact a = {hc.a * 1e3:.3f} mm, b = {hc.b * 1e3:.3f} mm, Fn = 10 kN, "
          f"mu = {MU}, steel; grid window 1.1 semi-axes; tol 1e-6 (default); one thread; "
          f"best of {args.repeat}")
    print("load average before: " + " ".join(f"{v:.2f}" for v in os.getloadavg()))
    _print_header(args.before is not None)
    for n in args.sizes:
        before = None
        if args.before is not None:       # interleaved: before, after, per size
            before = _measure_in(args.before, n, args.repeat, False)
        # with a comparison both versions run in a subprocess of their own (same conditions)
        this = None if args.before is None else os.path.join(_here(), "..", "src")
        after = _measure_in(this, n, args.repeat, args.memory)
        _print_rows(after, before)
        _print_normal(after, before)
    print("load average after: " + " ".join(f"{v:.2f}" for v in os.getloadavg()))


def _here() -> str:
    return os.path.dirname(os.path.abspath(__file__))


if __name__ == "__main__":
    main()
