"""Sweep throughput (serial, Dask with 1 and 2 workers, a scheduler over loopback) and the
table-interpolating creep-force law (speed and error against the exact solver).

Run:  python benchmarks/bench_sweeps.py [--quick] [--only sweeps|table]

Prints, with problem sizes and the machine load (``os.getloadavg``; the machine is shared):

* points/s (workers warmed up first: imports and numba kernels loaded) of a FASTSIM sweep (101 x 101 x 2 = 20 402 points, 20 x 20 cells) and of an
  exact-theory sweep (21 x 25 = 525 points, 40 elements) with the serial executor and a Dask
  LocalCluster of 1 and 2 single-threaded workers, and the 2-worker/1-worker ratio;
* the same exact sweep on a scheduler reached over loopback (``scheduler="tcp://127.0.0.1:..."``,
  a LocalCluster started separately with 2 worker processes: what a user with a cluster does);
* ``method="table"`` evaluations/s in one batch against FASTSIM and the exact solver, and the
  table's maximum error against the exact solver (40 elements, the default) on random points
  NOT in the table, spread uniformly over its domain (in units of mu Fn and mu Fn c).
"""

import argparse
import os
import shutil
import tempfile
import time

import numpy as np

import wheelrail as wr
from wheelrail.sweeps import DaskExecutor, SweepSpec, sweep


def _warm():
    """Import wheelrail and load the numba kernels in a worker (not part of the throughput)."""
    import wheelrail as wr

    c = wr.hertz(1e4, 1.0, 1.5, wr.STEEL)
    wr.creep_forces(c, (-1e-3, 0, 0), 0.3, method="exact", elements=40)
    wr.creep_forces(c, (-1e-3, 0, 0), 0.3, method="fastsim")


class WarmDask(DaskExecutor):
    """A Dask LocalCluster whose workers are warmed up before the sweep starts timing."""

    def __enter__(self):
        super().__enter__()
        self._client.run(_warm)
        return self


def load():
    return "load average %.2f %.2f %.2f" % os.getloadavg()


def timed_sweep(spec, **kw):
    tmp = tempfile.mkdtemp()
    try:
        t0 = time.perf_counter()
        ds, info = sweep(spec, os.path.join(tmp, "s.zarr"), progress=False, summary=True, **kw)
        total = time.perf_counter() - t0
        ok = int((ds.status.values == 1).sum())
        ds.close()
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return info, total, ok


def bench_sweeps(quick, repeats=2, which=("fastsim", "exact")):
    n = 41 if quick else 101
    fast = SweepSpec.grid(method="fastsim", mu=0.3, Fn=1e4, A=1.087, B=1.667,
                          xi={"start": -0.004, "stop": 0.004, "num": n},
                          eta={"start": -0.004, "stop": 0.004, "num": n}, phi=[0.0, 0.5],
                          options={"nx": 20, "ny": 20}, chunk=1000)
    ne = (7, 9) if quick else (21, 25)
    exact = SweepSpec.grid(method="exact", mu=0.3, Fn=1e4, A=1.087, B=1.667,
                           xi={"start": -0.003, "stop": 0.003, "num": ne[0]},
                           eta={"start": -0.003, "stop": 0.003, "num": ne[1]}, phi=[0.3],
                           options={"elements": 40}, chunk=15)
    wr.creep_forces(wr.hertz(1e4, 1.0, 1.5, wr.STEEL), (-1e-3, 0, 0), 0.3, method="exact",
                    elements=40)  # compile / load the numba cache
    for name, spec in (("FASTSIM 20x20", fast), ("exact 40 el.", exact)):
        if name.split()[0].lower() not in which:
            continue
        print(f"\n{name}: {spec.size} points, chunks of {int(np.prod(spec.chunk_shape()))}; {load()}")
        rates = {}
        # 1- and 2-worker runs interleaved, best of `repeats`: the machine is shared
        runs = [("serial", None)] + [("dask 1 worker", 1), ("dask 2 workers", 2)] * repeats
        for label, nw in runs:
            kw = {} if nw is None else dict(executor=WarmDask(nw))
            info, total, ok = timed_sweep(spec, **kw)
            rates[label] = max(rates.get(label, 0.0), info.points_per_second)
            print(f"  {label:15s} {info.points_per_second:9.1f} points/s "
                  f"(sweep {info.seconds:6.2f} s, with cluster start/stop {total:6.2f} s, "
                  f"{ok}/{spec.size} ok); {load()}")
        print(f"  best 2 workers / best 1 worker: "
              f"{rates['dask 2 workers'] / rates['dask 1 worker']:.2f}x")
    from distributed import LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, host="127.0.0.1",
                      dashboard_address=":0", silence_logs=40) as cluster:
        addr = cluster.scheduler_address
        info, total, ok = timed_sweep(exact, scheduler=addr)
        print(f"\nexact on scheduler {addr} (2 worker processes over loopback): "
              f"{info.points_per_second:.1f} points/s ({ok}/{exact.size} ok); {load()}")


def bench_table(quick):
    from wheelrail.tangential import table as T
    from wheelrail.tangential.linear import kalker_coefficients

    data = T.load_table()
    print(f"\ntable: {data.values.shape[:-1]} nodes (r, theta, s, a/b, nu), built with "
          f"{data.meta['elements']} elements; {load()}")
    rng = np.random.default_rng(2026)
    n = 60 if quick else 400
    ab = np.exp(rng.uniform(np.log(0.2), np.log(5.0), n))
    nu = rng.uniform(0.25, 0.30, n)
    Fn = rng.uniform(2e3, 2e4, n)
    mu = rng.uniform(0.1, 0.5, n)
    rho = rng.uniform(0.0, 3.0, n) ** 2  # scaled creepage magnitude (1: linear-theory saturation)
    th = rng.uniform(-np.pi, np.pi, n)
    ph = rng.uniform(-4.0, 4.0, n) * rng.uniform(0, 1, n)  # scaled spin, |phi_hat| <= 4
    errs = []
    t_exact = 0.0
    for i in range(n):  # nu differs per point: one contact each
        m = wr.Material(2.1e11, nu[i])
        c = wr.hertz_from_semiaxes(4e-3 * np.sqrt(ab[i]), 4e-3 / np.sqrt(ab[i]), Fn[i], m)
        cc = np.sqrt(c.a * c.b)
        C11, C22, C23, _ = kalker_coefficients(ab[i], nu[i])
        u = 3 * mu[i] * Fn[i] / m.G
        ell = np.hypot(cc * C23, c.b * C11)  # the table's spin length (see its docstring)
        cr = (rho[i] * np.cos(th[i]) * u / (cc**2 * C11),
              (rho[i] * np.sin(th[i]) - ph[i] * cc * C23 / ell) * u / (cc**2 * C22),
              ph[i] * u / (cc**2 * ell))
        t0 = time.perf_counter()
        e = wr.creep_forces(c, cr, mu[i], method="exact", on_fail="status")
        t_exact += time.perf_counter() - t0
        t = wr.creep_forces(c, cr, mu[i], method="table")
        s = mu[i] * Fn[i]
        errs.append([abs(t.Fx - e.Fx) / s, abs(t.Fy - e.Fy) / s, abs(t.Mz - e.Mz) / (s * cc),
                     np.hypot(t.Fx - e.Fx, t.Fy - e.Fy) / s])
    errs = np.array(errs)
    print(f"  error vs exact (40 el.) on {n} random points off the nodes:")
    print(f"    max |dFx|, |dFy| / (mu Fn) = {errs[:, 0].max():.4f}, {errs[:, 1].max():.4f}; "
          f"max |dFt| / (mu Fn) = {errs[:, 3].max():.4f}; rms = {np.sqrt((errs[:, 3]**2).mean()):.4f}")
    print(f"    max |dMz| / (mu Fn c) = {errs[:, 2].max():.4f}")
    # speed: one batch of N evaluations on one contact
    N = 20_000 if quick else 100_000
    c = wr.hertz(1e4, 1.087, 1.667, wr.STEEL)
    cr = np.column_stack([rng.uniform(-3e-3, 3e-3, N), rng.uniform(-3e-3, 3e-3, N),
                          rng.uniform(-0.5, 0.5, N)])
    wr.creep_forces(c, cr[:10], 0.3, method="table")
    wr.creep_forces(c, cr[:10], 0.3, method="fastsim")
    rates = {}
    for name, kw in (("table", {}), ("fastsim 20x20", dict(nx=20, ny=20, fields=False))):
        best = np.inf
        for _ in range(3):
            t0 = time.perf_counter()
            wr.creep_forces(c, cr, 0.3, method=name.split()[0], **kw)
            best = min(best, time.perf_counter() - t0)
        rates[name] = N / best
        print(f"  {name:15s} {N / best:12.0f} evaluations/s (batch of {N})")
    rates["exact"] = n / t_exact
    print(f"  {'exact 40 el.':15s} {rates['exact']:12.1f} evaluations/s ({n} single solves)")
    print(f"  table / exact = {rates['table'] / rates['exact']:.0f}x, "
          f"table / fastsim = {rates['table'] / rates['fastsim 20x20']:.1f}x; {load()}")


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--only", choices=("sweeps", "table"))
    ap.add_argument("--exact-only", action="store_true", help="sweeps: only the exact solver")
    a = ap.parse_args()
    if a.only in (None, "sweeps"):
        bench_sweeps(a.quick, which=("exact",) if a.exact_only else ("fastsim", "exact"))
    if a.only in (None, "table"):
        bench_table(a.quick)
