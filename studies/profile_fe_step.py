"""Where the time of an explicit FE rolling step goes, phase by phase, on 1 or 2 threads.

    python studies/profile_fe_step.py run --threads 1 --material elastic
    python studies/profile_fe_step.py run --threads 2 --material elastic
    python studies/profile_fe_step.py table fe_step_profile/elastic_1.npz fe_step_profile/elastic_2.npz

``run`` solves the 2 mm speed case of ``bench_fe_plastic.py speed`` (Toumi et al.'s case,
11 840 one-point elements, 4 920 steps; ``--mesh 1e-3 --travel 0.004``: 47 736 elements,
7 533 steps) with an instrumented copy of the compiled time loop
(``wheelrail.fe._explicit.run_steps``, generated from its source text with cycle-counter
reads at the phase boundaries and around every task: the arithmetic is the same, the run
prints the same steady Fx) and saves the timestamps; ``table`` prints the median time per
step of every phase and serial part, per thread the tasks, busy time, start latency and
idle time at the end of each parallel phase, and where the threads' time goes (in tasks,
before the first task, between tasks, after the last, phases missed). Timings are
wall-clock (the x86 time-stamp counter); state the machine load.
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

_HEADER = '''"""Instrumented copy of wheelrail.fe._explicit.run_steps (generated)."""
import numba
import numpy as np
from llvmlite import ir
from numba import njit, prange
from numba.core import cgutils, types
from numba.core.extending import intrinsic

from wheelrail.fe._explicit import (_CUR, _DONE, _PHASE, _TAKE, _atomic_add, _atomic_load,
                                    _atomic_store, _element_chunk, _step_end, _step_start,
                                    _take_task, _update_nodes, _wait_phase, contact_to_nodes,
                                    slave_position)
from wheelrail.fe._kernels import _slave, scatter_to_grid
import wheelrail.fe._explicit as _X
_open_tasks = getattr(_X, "_open_tasks", None)      # the task ranges (absent in older versions)
MAX_TASKS = getattr(_X, "MAX_TASKS", 0xFFFF)


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
    """The source of the instrumented copy (from the installed wheelrail).

    ``T[k]``: cycle counter when step k's first phase opens, when its last task ends, when
    the second phase opens, when its last task ends and when the next step's first phase
    opens; ``TA[k, t]`` / ``TB[k, g]``: start, end and thread of every task."""
    import wheelrail.fe._explicit as X

    src = Path(X.__file__).read_text()
    rs = src[src.index("@njit(cache=True, parallel=True)\ndef run_steps("):]
    rs = _strip_doc(rs, "Steps ``k0``")
    rs = _sub(rs, "def run_steps(", "def run_steps_t(")
    rs = _sub(rs, "totals, nthr):", "totals, nthr, T, TA, TB):")
    rs = _sub(rs, "    for w in prange(nthr):\n", "    T[k0, 0] = rdtsc()\n    for w in prange(nthr):\n")
    # one task loop for both phases (``first``: the element and contact tasks, TA; else the
    # node groups, TB); T[k] slots 1 and 3 at the phases' last tasks, 2 and 4 when the next
    # phase opens
    body = " " * 16
    loop = "            while t >= 0:\n"
    rs = _sub(rs, loop, loop + body + "if first:\n" + body + "    TA[k, t, 0] = rdtsc()\n"
              + body + "else:\n" + body + "    TB[k, t, 0] = rdtsc()\n")
    last = body + "if _atomic_add(ctl, _DONE, 1) == n_open - 1:"
    rs = _sub(rs, last, body + "R = TA if first else TB\n" + body + "R[k, t, 1] = rdtsc()\n"
              + body + "R[k, t, 2] = numba.get_thread_id()\n" + last)
    branch = body + "    if first:\n"
    i = rs.index(last)
    rs = rs[:i] + _sub(rs[i:], branch, branch + body + "        T[k, 1] = rdtsc()\n")
    other = body + "    else:\n" + body + "        _step_end("
    rs = _sub(rs, other, body + "    else:\n" + body + "        T[k, 3] = rdtsc()\n" + body
              + "        _step_end(")
    pub = body + "        _atomic_store(ctl, _PHASE, p + 1)\n"
    rs = _sub(rs, pub, body + "        T[k, 2] = rdtsc()\n" + pub)      # the first one
    i = rs.index("ctl[_CUR] = new")
    rs = rs[:i] + _sub(rs[i:], pub, body + "        T[k, 4] = rdtsc()\n" + body
                       + "        if k + 1 < k1:\n" + body + "            T[k + 1, 0] = T[k, 4]\n"
                       + pub)
    return _HEADER + rs


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
    try:
        from wheelrail.fe._explicit import phase_one_tasks
    except ImportError:                  # an older version (--baseline-style comparisons)
        from wheelrail.fe._explicit import interleaved_tasks as phase_one_tasks

    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    mod = _load_instrumented(out)
    numba.set_num_threads(a.threads)
    case = seed(a.mesh, plastic=a.material == "plastic", travel=a.travel, mass_scaling=400.0)
    R = {}

    def fresh(n_tasks_a=64, n_tasks_b=64, n=200_000):
        return dict(T=np.zeros((n, 5), np.int64), TA=np.zeros((n, n_tasks_a, 3), np.int64),
                    TB=np.zeros((n, n_tasks_b, 3), np.int64), calls=[], n1=0)

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
        cur = mod.run_steps_t(*args, r["T"][base:], r["TA"][base:], r["TB"][base:])
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
    kinds = phase_one_tasks((nc + 1) // 2, min(64, max(1, ns // 64)))[:, 0]
    info = dict(threads=a.threads, material=a.material, steps=n, elements=res.model.n_elements,
                wall=w1 - w0, cpu=p1 - p0, Fx=res.steady["Fx"], load_before=load0,
                load_after=os.getloadavg()[0], date=time.strftime("%Y-%m-%d %H:%M"))
    print(json.dumps(info))
    path = out / f"{a.material}_{a.threads}.npz"
    np.savez(path, T=r["T"][:n], TA=r["TA"][:n], TB=r["TB"][:n],
             calls=np.array(r["calls"], np.int64), hz=hz, info=json.dumps(info), kinds=kinds,
             run=np.array([c_start, c_end], np.int64))
    print(f"saved {path}")


def table(path):
    d = np.load(path)
    T, TA, TB, calls = d["T"], d["TA"], d["TB"], d["calls"]
    us = 1e6 / float(d["hz"])
    info = json.loads(str(d["info"]))
    kinds = d["kinds"]
    n, ne = T.shape[0], info["elements"]
    run = (d["run"][1] - d["run"][0]) * us
    loop = (calls[-1, 3] - calls[0, 2]) * us
    between = ((calls[1:, 2] - calls[:-1, 3]) * us).sum() / n
    entry = sum((T[c[0], 0] - c[2]) + (c[3] - T[c[1] - 1, 4]) for c in calls) * us / n
    rows = [
        ("model build before the first step and results after the last (serial)", (run - loop) / n),
        ("Python between calls of the compiled loop (averaged over the steps)", between),
        ("entry/exit of the compiled loop (averaged)", entry),
        ("phase 1: even element chunks + contact (parallel)", np.median(T[:, 1] - T[:, 0]) * us),
        ("contact forces scattered and rotated, sums (serial)", np.median(T[:, 2] - T[:, 1]) * us),
        ("phase 2: odd element chunks + node update (parallel)", np.median(T[:, 3] - T[:, 2]) * us),
        ("energy sums, axle, bookkeeping, next step's rail surface (serial)",
         np.median(T[:, 4] - T[:, 3]) * us),
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
    nthr = info["threads"]
    for name, TT, start, end in (("1", TA, T[:, 0], T[:, 1]), ("2", TB, T[:, 2], T[:, 3])):
        txt = []
        wall = (end - start) * us
        tot = dict(tasks=0.0, before=0.0, between=0.0, after=0.0, missed=0.0)
        for tid in range(nthr):
            m = TT[:, :, 2] == tid
            has = m.any(axis=1)
            b = np.where(m, TT[:, :, 1] - TT[:, :, 0], 0).sum(axis=1) * us
            st = np.where(has, (np.where(m, TT[:, :, 0], np.iinfo(np.int64).max).min(axis=1)
                                - start) * us, 0)
            idle = np.where(has, (end - np.where(m, TT[:, :, 1], 0).max(axis=1)) * us, 0)
            txt.append(f"thread {tid}: {np.median(m.sum(1)):.0f} tasks, busy {np.median(b):.0f} us, "
                       f"first task +{np.median(st[has]) if has.any() else 0:.1f} us, idle at the "
                       f"end {np.median(idle[has]) if has.any() else 0:.1f} us (works in "
                       f"{has.mean():.0%} of the steps)")
            tot["tasks"] += b.mean()
            tot["before"] += st.mean()
            tot["after"] += idle.mean()
            tot["between"] += np.where(has, wall - st - idle - b, 0).mean()
            tot["missed"] += np.where(has, 0, wall).mean()
        print(f"  phase {name}: {np.median(wall):.0f} us; " + "; ".join(txt))
        print(f"    thread time, mean per step: {nthr * wall.mean():.0f} us = "
              + ", ".join(f"{k} {v:.0f}" for k, v in tot.items()))


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
