"""Time and memory estimate of a sweep before it starts: points × a measured cost per point.

The cost of one point depends on the method, its options (grid size) and the
inputs (a large spin slides more cells), so it is *measured*: a few points of
the sweep's first chunk are evaluated in this process — one first (it
includes the one-time compilation of numba kernels), then blocks of 1, 4, 16, …
points until about 0.3 s of CPU time have been spent — and the cost of a call
is fitted as (overhead per call) + points × (cost per point) on the last two
blocks. The sweep's time is

    seconds ≈ startup + [chunks × (CHUNK_COST + overhead) + points × cost per point]
              / (0.9 × workers)

(0.9: the parallel efficiency measured with 2 Dask workers on a 2-core
machine; startup about 4 s for a Dask cluster, 2 s for a process pool, plus
about 1 s to import the store's libraries the first time; CHUNK_COST the
bookkeeping and the store write of one chunk, 30 ms measured). The memory is
the chunks in flight (2 per worker) and the interpreter; the store's size on
disk (uncompressed upper bound) is given as information. Times are CPU times
(on a loaded machine the wall time is longer by about the load per core).

``benchmarks/bench_estimates.py`` compares the estimate with measured runs.
"""

from __future__ import annotations

import math
import sys
import time
from dataclasses import dataclass

from .._resources import _human, check, suspended
from .evaluators import MESSAGE_LENGTH, get_evaluator

__all__ = ["SweepEstimate", "estimate_sweep", "check_sweep"]

#: Parallel efficiency of the executors (2 workers on a 2-core machine).
EFFICIENCY = 0.9
#: Start-up time [s] of the executors (local Dask cluster, process pool, serial).
STARTUP = {"dask": 4.0, "processes": 2.0, "serial": 0.0}
#: CPU time [s] spent measuring the cost per point (after the first point).
PROBE_SECONDS = 0.3
#: Bookkeeping and store write of one chunk [s] (fastsim sweeps of 1000–32 000 points in
#: chunks of 250–8000: 36 ms per chunk, CPU, at a load of 11 on 2 cores).
CHUNK_COST = 0.03
#: First import of the store's libraries (zarr, xarray) in this process [s].
IMPORT_COST = 1.0
#: Interpreter, numpy, xarray, zarr [bytes].
BASE_MEMORY = 250e6  # measured 259–283 MB peak (bench_estimates.py)


@dataclass(frozen=True)
class SweepEstimate:
    """Estimated time [s] and memory [bytes] of a sweep (see the module docstring)."""

    points: int
    per_point: float
    first_point: float
    seconds: float
    memory: float
    disk: float
    workers: int

    def describe(self) -> str:
        return (f"{self.per_point * 1e3:.3g} ms per point measured on {self.workers} "
                f"worker(s); store up to {_human(self.disk)} on disk")


def _probe_block(spec, k: int) -> tuple:
    """Index slices of (at most) the first ``k`` points of the first chunk, in C order:
    whole trailing axes, a slab of the next one, one index of the leading ones."""
    cs = list(spec.chunk_shape())
    if not cs:
        return ()
    block = [slice(0, c) for c in cs]
    trailing = 1
    for j in range(len(cs) - 1, -1, -1):
        if trailing * cs[j] <= k:
            trailing *= cs[j]
            continue
        block[j] = slice(0, max(1, k // trailing))
        for i in range(j):
            block[i] = slice(0, 1)
        break
    return tuple(block)


def _points(block) -> int:
    return math.prod(s.stop - s.start for s in block) if block else 1


def _bytes_per_point(spec) -> float:
    ev = get_evaluator(spec.evaluator)
    size = 0.0
    for name in ev.output_names(spec):
        dtype = ev.outputs[name][0]
        try:
            import numpy as np

            size += np.dtype(dtype).itemsize
        except TypeError:  # pragma: no cover - object outputs
            size += 8
    return size + 1 + 4 * MESSAGE_LENGTH  # status (int8) and the message (UTF-32)


def estimate_sweep(spec, points: int | None = None, workers: int = 1,
                   executor: str = "serial") -> SweepEstimate:
    """Measure the cost per point of ``spec`` and estimate the whole sweep.

    Parameters
    ----------
    spec : SweepSpec
    points : int, optional
        Points still to compute (default: all of ``spec``).
    workers : int
    executor : str
        ``"serial"``, ``"processes"`` or ``"dask"`` (start-up time).

    Returns
    -------
    SweepEstimate
    """
    ev = get_evaluator(spec.evaluator)

    def evaluate_chunk(spec, block):  # as sweeps.run.evaluate_chunk (no import cycle)
        with suspended():  # real solves, also under --estimate-only; their guards stay quiet
            return ev.evaluate(spec, spec.columns(block))

    points = spec.size if points is None else int(points)
    t0 = time.process_time()
    evaluate_chunk(spec, _probe_block(spec, 1))  # includes compiling kernels the first time
    first = time.process_time() - t0
    per_point, overhead = first, 0.0
    chunk_points = _points(_probe_block(spec, spec.chunk))
    if first * points > 1.0:  # else cheap: the first point bounds the sweep
        samples, spent, k = [], 0.0, 1
        while spent < PROBE_SECONDS:
            block = _probe_block(spec, k)
            n = _points(block)
            if samples and n <= samples[-1][0]:
                break
            t0 = time.process_time()
            evaluate_chunk(spec, block)
            dt = time.process_time() - t0
            samples.append((n, dt))
            spent += dt
            if n >= min(points, chunk_points):
                break
            k *= 4
        (n_a, t_a), (n_b, t_b) = samples[-2:] if len(samples) > 1 else (samples[0],) * 2
        slope = (t_b - t_a) / (n_b - n_a) if n_b > n_a else 0.0
        if 0.0 < slope <= t_b / n_b:
            per_point, overhead = slope, t_b - slope * n_b
        else:  # noise, or a single block: no separate overhead
            per_point = t_b / n_b
    workers = max(int(workers), 1)
    chunks = math.ceil(points / max(chunk_points, 1))
    startup = STARTUP.get(executor, 0.0) if workers > 1 or executor != "serial" else 0.0
    startup += IMPORT_COST if "zarr" not in sys.modules else 0.0
    work = chunks * (CHUNK_COST + overhead) + points * per_point
    seconds = startup + work / (EFFICIENCY * workers if workers > 1 else 1.0)
    bpp = _bytes_per_point(spec)
    in_flight = min(points, 2 * workers * max(spec.chunk, 1))
    memory = BASE_MEMORY + 3.0 * in_flight * bpp
    return SweepEstimate(points, per_point, first, seconds, memory, points * bpp, workers)


def check_sweep(spec, points=None, workers=1, executor="serial") -> SweepEstimate:
    """:func:`estimate_sweep`, then refuse it past the time or memory limit.

    Raises
    ------
    wheelrail._resources.ResourceLimitError
        Estimate past a limit (the message says how to raise it).
    wheelrail._resources.EstimateOnly
        Inside ``wheelrail._resources.estimating()`` (``--estimate-only``).
    """
    est = estimate_sweep(spec, points, workers, executor)
    methods = "+".join(get_evaluator(spec.evaluator).methods(spec)) \
        if hasattr(get_evaluator(spec.evaluator), "methods") else spec.evaluator
    check(f"sweep of {est.points} points ({spec.evaluator}/{methods})", est.seconds, est.memory,
          est.describe())
    return est
