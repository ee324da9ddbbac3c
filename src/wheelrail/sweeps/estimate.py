"""Time and memory estimate of a sweep before it starts: points × a measured cost per point.

The cost of one point depends on the method, its options (grid size) and the
inputs (a large spin slides more cells), so it is *measured*: a few points of
the sweep's first chunk are evaluated in this process — one first (it
includes the one-time compilation of numba kernels), then 2, 4, … points
until about 0.3 s have been spent — and the sweep's time is

    seconds ≈ startup + points × (cost per point) / (0.9 × workers)

(0.9: the parallel efficiency measured with 2 Dask workers on a 2-core
machine; startup about 4 s for a Dask cluster, 2 s for a process pool).
The memory is the chunks in flight (2 per worker) and the interpreter; the
store's size on disk (uncompressed upper bound) is given as information.

``benchmarks/bench_estimates.py`` compares the estimate with measured runs.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

from .._resources import check, suspended
from .evaluators import MESSAGE_LENGTH, get_evaluator

__all__ = ["SweepEstimate", "estimate_sweep", "check_sweep"]

#: Parallel efficiency of the executors (2 workers on a 2-core machine).
EFFICIENCY = 0.9
#: Start-up time [s] of the executors (local Dask cluster, process pool, serial).
STARTUP = {"dask": 4.0, "processes": 2.0, "serial": 0.0}
#: Time [s] spent measuring the cost per point (after the first point).
PROBE_SECONDS = 0.3
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
                f"worker(s); store up to {_size(self.disk)} on disk")


def _size(n: float) -> str:
    for unit, f in (("TB", 1e12), ("GB", 1e9), ("MB", 1e6), ("kB", 1e3)):
        if n >= f:
            return f"{n / f:.3g} {unit}"
    return f"{n:.0f} B"


def _probe_block(spec, k: int) -> tuple:
    """Index slices of (at most) the first ``k`` points of the first chunk."""
    cs = list(spec.chunk_shape())
    if not cs:
        return ()
    block = [slice(0, c) for c in cs]
    for i in range(len(block)):
        if math.prod(s.stop for s in block) <= k:
            break
        if i < len(block) - 1:
            block[i] = slice(0, 1)
        else:
            block[i] = slice(0, max(1, k))
    return tuple(block)


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
    t0 = time.perf_counter()
    evaluate_chunk(spec, _probe_block(spec, 1))  # includes compiling kernels the first time
    first = time.perf_counter() - t0
    per_point, k = first, 1
    spent = 0.0 if first * points > 1.0 else PROBE_SECONDS  # cheap: the first point bounds it
    while spent < PROBE_SECONDS and k < min(points, 64):
        k = min(2 * k, points, 64)
        block = _probe_block(spec, k)
        n = math.prod(s.stop - s.start for s in block) if block else 1
        t0 = time.perf_counter()
        evaluate_chunk(spec, block)
        dt = time.perf_counter() - t0
        spent += dt
        per_point = dt / max(n, 1)
        if n < k:  # the first chunk is smaller than k points
            break
    workers = max(int(workers), 1)
    seconds = (STARTUP.get(executor, 0.0) if workers > 1 or executor != "serial" else 0.0) \
        + points * per_point / (EFFICIENCY * workers if workers > 1 else 1.0)
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
