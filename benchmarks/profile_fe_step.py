"""Where the time of an explicit FE rolling step goes, phase by phase, on 1 or 2 threads.

    python benchmarks/profile_fe_step.py run --threads 1 --material elastic
    python benchmarks/profile_fe_step.py run --threads 2 --material elastic
    python benchmarks/profile_fe_step.py table fe_step_profile/elastic_1.npz fe_step_profile/elastic_2.npz

``run`` solves the 2 mm speed case of ``bench_fe_plastic.py speed`` (Toumi et al.'s case,
11 840 one-point elements, 4 920 steps) with an instrumented copy of the compiled time loop
(``wheelrail.fe._explicit.run_steps`` and ``explicit_step``, generated from their source
text with cycle-counter reads at the phase boundaries and around every task: the
arithmetic is the same, the run prints the same steady Fx) and saves the timestamps;
``table`` prints the median time per step of every phase, the serial parts, and per
thread the tasks, busy time, start latency and idle time at the end of each parallel
region. Timings are wall-clock (the x86 time-stamp counter); state the machine load.
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import os
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent

_HEADER = '''"""Instrumented copy of wheelrail.fe._explicit.run_steps / explicit_step (generated)."""
import numba
import numpy as np
from llvmlite import ir
from numba import njit, prange
from numba.core import cgutils, types
from numba.core.extending import intrinsic

from wheelrail.fe._explicit import (_element_chunk, _take_next, _update_nodes,
                                    contact_to_nodes, master_kinematics, slave_position)
from wheelrail.fe._kernels import _slave, scatter_to_grid


@intrinsic
def rdtsc(typingctx):
    def codegen(context, builder, signature, args):
        fn = cgutils.get_or_insert_function(builder.module, ir.FunctionType(ir.IntType(64), []),
                                            "llvm.readcyclecounter")
        return builder.call(fn, [])
    return types.int64(), codegen


@njit(cache=True)
def tsc():
    return rdtsc()


'''


def _strip_doc(src, start):
    d0 = src.index('    """' + start)
    d1 = src.index('    """\n', d0 + 8) + 8
    return src[:d0] + src[d1:]


def _sub(src, old, new, count=1):
    if src.count(old) < 1:
        raise RuntimeError(f"instrumentation point not found (the kernel changed?): {old!r}")
    return src.replace(old, new, count)


def instrumented_source() -> str:
    """The source of the instrumented copies (from the installed wheelrail)."""
    import wheelrail.fe._explicit as X

    src = Path(X.__file__).read_text()
    es = src[src.index("@njit(cache=True, parallel=True)\ndef explicit_step("):
             src.index("@njit(cache=True)\ndef run_steps(")]
    rs = src[src.index("@njit(cache=True)\ndef run_steps("):]
    es = _strip_doc(es, "One explicit step")
    es = _sub(es, "def explicit_step(", "def explicit_step_t(")
    es = _sub(es, "counter, nthr):", "counter, nthr, T, TA, TB):")
    es = _sub(es, "    ne = conn.shape[0]\n", "    T[0] = rdtsc()\n    ne = conn.shape[0]\n")
    es = _sub(es, "    master_kinematics(ref_m, u, mnodes, shift_x, shift_y, xm, xm_prev, dxm, nm, fm)\n",
              "    master_kinematics(ref_m, u, mnodes, shift_x, shift_y, xm, xm_prev, dxm, nm, fm)\n"
              "    T[1] = rdtsc()\n")
    es = _sub(es, "        while t < n_tasks:\n", "        while t < n_tasks:\n            TA[t, 0] = rdtsc()\n")
    es = _sub(es, "            t = _take_next(counter)\n    scatter_to_grid",
              "            TA[t, 1] = rdtsc()\n            TA[t, 2] = numba.get_thread_id()\n"
              "            t = _take_next(counter)\n    T[2] = rdtsc()\n    scatter_to_grid")
    es = _sub(es, "fcon, sums)\n    counter[0] = 0\n", "fcon, sums)\n    T[3] = rdtsc()\n    counter[0] = 0\n")
    es = _sub(es, "        while g < n_groups:\n", "        while g < n_groups:\n            TB[g, 0] = rdtsc()\n")
    es = _sub(es, "            g = _take_next(counter)\n    e0 = 0.0",
              "            TB[g, 1] = rdtsc()\n            TB[g, 2] = numba.get_thread_id()\n"
              "            g = _take_next(counter)\n    T[4] = rdtsc()\n    e0 = 0.0")
    es += "    T[5] = rdtsc()\n"
    rs = _strip_doc(rs, "Steps ``k0``")
    rs = _sub(rs, "def run_steps(", "def run_steps_t(")
    rs = _sub(rs, "counter, nthr):", "counter, nthr, T, TA, TB, TL):")
    rs = _sub(rs, "gptr, gnodes, partial, totals, counter, nthr)\n",
              "gptr, gnodes, partial, totals, counter, nthr, T[k], TA[k], TB[k])\n")
    rs = _sub(rs, "        explicit_step(", "        TL[k, 0] = rdtsc()\n        explicit_step_t(")
    rs = _sub(rs, "        cur = new\n", "        cur = new\n        TL[k, 1] = rdtsc()\n")
    return _HEADER + es + "\n\n" + rs


def _load_instrumented(out: Path):
    path = out / "_fe_step_instrumented.py"
    text = instrumented_source()
    if not path.exists() or path.read_text() != text:
        path.write_text(text)
    spec = importlib.util.spec_from_file_location("_fe_step_instrumented", path)
    mod = importlib.util.module_from_spec(spec)
    sys.modules["_fe_step_instrumented"] = mod          # numba's cache imports it by name
    spec.loader.exec_module(mod)
    return mod


def cmd_run(a):
    import numba

    sys.path.insert(0, str(HERE))
    from bench_fe_plastic import seed

    import wheelrail.fe.explicit as EX
    from wheelrail.fe import solve
    from wheelrail.fe._explicit import interleaved_tasks

    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    mod = _load_instrumented(out)
    numba.set_num_threads(a.threads)
    case = seed(a.mesh, plastic=a.material == "plastic", travel=a.travel, mass_scaling=400.0)
    R = {}

    def fresh(n_tasks_a=64, n_tasks_b=64, n=200_000):
        return dict(T=np.zeros((n, 6), np.int64), TA=np.zeros((n, n_tasks_a, 3), np.int64),
                    TB=np.zeros((n, n_tasks_b, 3), np.int64), TL=np.zeros((n, 2), np.int64),
                    calls=[], n1=0)

    def run_steps(*args):
        r = R["r"]
        k0, k1, relax = args[0], args[1], args[2]
        if relax:
            base = 0
            r["n1"] = max(r["n1"], k1)
        else:
            base = r["n1"]
        n_a, n_b = args[i_tasks].shape[0], args[i_gptr].shape[0] - 1    # tasks, node groups
        if r["TA"].shape[1] != n_a or r["TB"].shape[1] != n_b:
            r.update({k: v for k, v in fresh(n_a, n_b, r["T"].shape[0]).items() if k in ("TA", "TB")})
        c0 = mod.tsc()
        cur = mod.run_steps_t(*args, r["T"][base:], r["TA"][base:], r["TB"][base:],
                              r["TL"][base:])
        r["calls"].append((base + k0, base + k1, c0, mod.tsc()))
        return cur

    import inspect

    names = list(inspect.signature(EX.run_steps.py_func).parameters)
    i_tasks, i_gptr = names.index("tasks"), names.index("gptr")
    EX.run_steps = run_steps
    R["r"] = fresh(n=20_000)
    solve(case.replace(travel=0.3 * a.travel), progress=False)             # compile, warm
    R["r"] = fresh(n=20_000)
    mod.tsc()
    t0, c0 = time.perf_counter(), mod.tsc()
    time.sleep(1.0)
    hz = (mod.tsc() - c0) / (time.perf_counter() - t0)
    load0 = os.getloadavg()[0]
    w0, p0, c_start = time.perf_counter(), time.process_time(), mod.tsc()
    res = solve(case, progress=False)
    c_end, w1, p1 = mod.tsc(), time.perf_counter(), time.process_time()
    r = R["r"]
    n = r["calls"][-1][1]
    ns = res.model.slave.size
    nc = res.model.chunks.size - 1
    kinds = interleaved_tasks((nc + 1) // 2, min(64, max(1, ns // 64)))[:, 0]
    info = dict(threads=a.threads, material=a.material, steps=n, elements=res.model.n_elements,
                wall=w1 - w0, cpu=p1 - p0, Fx=res.steady["Fx"], load_before=load0,
                load_after=os.getloadavg()[0], date=time.strftime("%Y-%m-%d %H:%M"))
    print(json.dumps(info))
    path = out / f"{a.material}_{a.threads}.npz"
    np.savez(path, T=r["T"][:n], TA=r["TA"][:n], TB=r["TB"][:n], TL=r["TL"][:n],
             calls=np.array(r["calls"], np.int64), hz=hz, info=json.dumps(info), kinds=kinds,
             run=np.array([c_start, c_end], np.int64))
    print(f"saved {path}")


def table(path):
    d = np.load(path)
    T, TA, TB, TL, calls = d["T"], d["TA"], d["TB"], d["TL"], d["calls"]
    us = 1e6 / float(d["hz"])
    info = json.loads(str(d["info"]))
    kinds = d["kinds"]
    n, ne = T.shape[0], info["elements"]
    run = (d["run"][1] - d["run"][0]) * us
    loop = (calls[-1, 3] - calls[0, 2]) * us
    first = np.zeros(n, bool)
    first[calls[:, 0]] = True
    book = ((TL[1:, 0] - TL[:-1, 1]) * us)[~first[1:]]
    between = ((calls[1:, 2] - calls[:-1, 3]) * us).sum() / n
    entry = sum((TL[c[0], 0] - c[2]) + (c[3] - TL[c[1] - 1, 1]) for c in calls) * us / n
    rows = [
        ("model build before the first step and results after the last (serial)", (run - loop) / n),
        ("Python between calls of the compiled loop (averaged over the steps)", between),
        ("entry/exit of the compiled loop (averaged)", entry),
        ("axle and energy bookkeeping in the loop (serial)", np.median(book)),
        ("entry/exit of explicit_step", np.median((T[:, 0] - TL[:, 0]) + (TL[:, 1] - T[:, 5])) * us),
        ("rail surface positions and normals (serial)", np.median(T[:, 1] - T[:, 0]) * us),
        ("region 1: even element chunks + contact (parallel)", np.median(T[:, 2] - T[:, 1]) * us),
        ("contact forces scattered and rotated, sums (serial)", np.median(T[:, 3] - T[:, 2]) * us),
        ("region 2: odd element chunks + node update (parallel)", np.median(T[:, 4] - T[:, 3]) * us),
        ("energy and work sums (serial)", np.median(T[:, 5] - T[:, 4]) * us),
    ]
    print(f"{path}: {info}")
    print(f"  {n} steps x {ne} elements: whole solve {run / n:.0f} us/step "
          f"({run / n / ne * 1e3:.0f} ns/element/step), time loop {loop / n:.0f} us/step "
          f"({loop / n / ne * 1e3:.0f} ns/element/step)")
    print("  | phase | us per step (median) |\n  |---|---|")
    for name, v in rows:
        print(f"  | {name} | {v:.1f} |")
    dA = (TA[:, :, 1] - TA[:, :, 0]) * us
    dB = (TB[:, :, 1] - TB[:, :, 0]) * us
    print(f"  work in tasks, summed over threads (medians): even element chunks "
          f"{np.median(dA[:, kinds == 0].sum(1)):.0f} us, contact {np.median(dA[:, kinds == 1].sum(1)):.0f}"
          f" us, odd element chunks + node update {np.median(dB.sum(1)):.0f} us")
    both = np.ones(n, bool)
    for name, TT, start, end in (("1", TA, T[:, 1], T[:, 2]), ("2", TB, T[:, 3], T[:, 4])):
        txt = []
        for tid in np.unique(TT[:, :, 2]):
            m = TT[:, :, 2] == tid
            has = m.any(axis=1)
            both &= has
            b = np.where(m, TT[:, :, 1] - TT[:, :, 0], 0).sum(axis=1) * us
            st = (np.where(m, TT[:, :, 0], np.iinfo(np.int64).max).min(axis=1) - start) * us
            idle = (end - np.where(m, TT[:, :, 1], 0).max(axis=1)) * us
            txt.append(f"thread {tid}: {np.median(m.sum(1)):.0f} tasks, busy {np.median(b):.0f} us, "
                       f"first task +{np.median(st[has]):.1f} us, idle at the end "
                       f"{np.median(idle[has]):.1f} us (works in {has.mean():.0%} of the steps)")
        print(f"  region {name}: {np.median((end - start) * us):.0f} us; " + "; ".join(txt))
    if info["threads"] > 1:
        s = (T[:, 5] - T[:, 0]) * us
        print(f"  steps in which every thread works in both regions: {both.mean():.0%}; their "
              f"explicit_step {np.median(s[both]):.0f} us (all steps {np.median(s):.0f} us); task "
              f"work in them {np.median(dA[both].sum(1) + dB[both].sum(1)):.0f} us")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("part", choices=["run", "table"])
    ap.add_argument("files", nargs="*")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--material", choices=["elastic", "plastic"], default="elastic")
    ap.add_argument("--mesh", type=float, default=2e-3)
    ap.add_argument("--travel", type=float, default=0.02)
    ap.add_argument("--out", default="fe_step_profile")
    a = ap.parse_args()
    if a.part == "run":
        cmd_run(a)
    else:
        for f in a.files:
            table(f)


if __name__ == "__main__":
    main()
