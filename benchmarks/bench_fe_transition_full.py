"""Build the full-size transition case (1 mm) and time a short run on it with 1 and 2
numba threads (run with NUMBA_NUM_THREADS=2): elements, nodes, build CPU/wall, peak
memory, stable step, steps of the full travel, ns per element and step; the load with
every timing. Writes ``results/fe_transition/full_size_build.json`` and
``full_size_runs.jsonl``. Usage::

    NUMBA_NUM_THREADS=2 nice -n 10 python benchmarks/bench_fe_transition_full.py [STEPS]
"""

import os, sys, time, resource, json
t0c, t0w = time.process_time(), time.perf_counter()
import wheelrail as wr
from wheelrail.fe.transition import run_transition, transition_time_estimate
from wheelrail.fe.transition.model import build_transition_model
import numba

RES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "results", "fe_transition")
case = wr.fe.seed004_case(0.025, size="full")
print("case: mesh", case.mesh_size, "travel", case.travel, "sleepers", case.track.n_sleepers, flush=True)
l0 = os.getloadavg()[0]
t1c, t1w = time.process_time(), time.perf_counter()
m = build_transition_model(case)
bc, bw = time.process_time() - t1c, time.perf_counter() - t1w
rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e6
est = transition_time_estimate(m)
out = {"elements": m.n_elements, "nodes": m.n_nodes, "slaves": int(m.slave.size), "quads": int(m.quads.shape[0]),
       "build_cpu_s": bc, "build_wall_s": bw, "maxrss_GB_after_build": rss, "load_build": [l0, os.getloadavg()[0]],
       "time_step": est["time_step"], "steps": est["steps"], "groups": [(g[3].E if hasattr(g[3], 'E') else None, int(g[0].shape[0])) for g in m.groups],
       "added_mass": float(m.meta.get("added_mass", float('nan')))}
print(json.dumps(out, indent=1), flush=True)
json.dump(out, open(os.path.join(RES, "full_size_build.json"), "w"), indent=1)
nsteps = int(sys.argv[1]) if len(sys.argv) > 1 else 200
dt = est["time_step"]
for threads in (1, 2):
    numba.set_num_threads(threads)
    short = case.replace(travel=nsteps * dt * case.speed * 1.0000001, settle=0.5 * nsteps * dt * case.speed)
    l0 = os.getloadavg()[0]
    r = run_transition(short, model=m)
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e6
    res = {"threads": threads, "steps": r.info["steps"], "cpu_s": r.info["cpu_s"], "wall_s": r.info["wall_s"],
           "ns_cpu": r.info["ns_per_element_step"], "ns_wall": r.info["wall_ns_per_element_step"],
           "load": [l0, os.getloadavg()[0]], "maxrss_GB": rss}
    print(json.dumps(res), flush=True)
    with open(os.path.join(RES, "full_size_runs.jsonl"), "a") as f:
        f.write(json.dumps(res) + "\n")
