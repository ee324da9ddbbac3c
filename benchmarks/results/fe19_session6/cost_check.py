"""Measured explicit-run cost of the CLI rolling case (benchmarks/bench_estimates.py FE_KEYS)
at several mesh sizes, one numba thread, against wheelrail.cli.fe.estimate."""
import json, os, sys, tempfile, time
sys.path.insert(0, "/work/wt-fe/benchmarks")
import numba
from bench_estimates import FE_CASE
from wheelrail.cli.fe import case_from_toml, estimate
from wheelrail.fe import build_model, solve

numba.set_num_threads(int(sys.argv[1]))
plastic = len(sys.argv) > 3 and "plastic" in sys.argv[3:]
full = "full" in sys.argv[3:]
for mm in [float(x) for x in sys.argv[2].split(",")]:
    fd, path = tempfile.mkstemp(suffix=".toml")
    with os.fdopen(fd, "w") as fh:
        txt = FE_CASE.format(mesh_size=mm * 1e-3) + ('material = "r900a"\n' if plastic else "")
        fh.write(txt.replace('"reduced"', '"full"') if full else txt)
    case, _ = case_from_toml(path)
    os.remove(path)
    solve(case.replace(travel=0.002), progress=False)       # warm
    t, c = time.perf_counter(), time.process_time()
    model = build_model(case)
    steps, est = estimate(case, model)
    r = solve(case, progress=False)
    wall, cpu = time.perf_counter() - t, time.process_time() - c
    print(json.dumps(dict(mesh_mm=mm, threads=numba.get_num_threads(), plastic=plastic,
                          elements=model.n_elements, steps=steps, run_steps=r.info["steps"],
                          wall=wall, cpu=cpu, loop_wall=r.info["loop_wall"], loop_cpu=r.info["loop_cpu"],
                          estimate=est, load=os.getloadavg()[0])), flush=True)
