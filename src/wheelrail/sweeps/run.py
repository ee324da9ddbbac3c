"""The sweep driver: spec → chunks → executor → store, with progress and resume."""

from __future__ import annotations

import os
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import InputError, WheelrailError
from .evaluators import STATUS_CODES, get_evaluator
from .executors import make_executor
from .estimate import check_sweep
from .spec import SweepSpec, load_sweep, sweep_from_dict
from .store import SweepStore, _is_netcdf, open_sweep, provenance, to_netcdf

__all__ = ["sweep", "SweepSummary", "SweepInterrupted", "evaluate_chunk"]


class SweepInterrupted(WheelrailError):
    """A sweep stopped before its end (lost workers or scheduler); ``path`` holds its chunks."""

    def __init__(self, message, path=None):
        super().__init__(message)
        self.path = path


@dataclass(frozen=True)
class SweepSummary:
    """What one call of :func:`sweep` did (printed by ``wheelrail sweep``).

    Attributes
    ----------
    points : int
        Points of the sweep.
    computed : int
        Points evaluated by this call (resumed runs skip finished chunks).
    failed, not_converged : int
        Points (of the whole dataset) with status ``failed`` / ``not_converged``.
    seconds : float
        Wall-clock time of this call [s].
    executor : str
    workers : int
    """

    points: int
    computed: int
    failed: int
    not_converged: int
    seconds: float
    executor: str
    workers: int

    @property
    def points_per_second(self) -> float:
        """Points evaluated by this call per second of wall-clock time."""
        return self.computed / self.seconds if self.seconds > 0 else float("inf")


def evaluate_chunk(spec: SweepSpec, block: tuple) -> dict:
    """Evaluate the points of one chunk (runs on the workers)."""
    return get_evaluator(spec.evaluator).evaluate(spec, spec.columns(block))


def _as_spec(spec) -> SweepSpec:
    if isinstance(spec, SweepSpec):
        return spec
    if isinstance(spec, (str, os.PathLike)):
        return load_sweep(spec)
    if isinstance(spec, dict):
        return sweep_from_dict(spec if "sweep" in spec else {"sweep": spec})
    raise InputError(f"spec must be a SweepSpec, a TOML path or a dict, got {type(spec).__name__}")


def sweep(spec, out=None, *, workers=None, scheduler=None, executor=None, resume=False,
          progress=None, timeout=10.0, summary=False):
    """Run a parameter study and return its results as a labelled dataset.

    Parameters
    ----------
    spec : SweepSpec, str, os.PathLike or dict
        The sweep (a :class:`~wheelrail.sweeps.SweepSpec`, a TOML file with a
        ``[sweep]`` table, or its dictionary); see :mod:`wheelrail.sweeps.spec`.
    out : str or os.PathLike, optional
        Result path: a Zarr directory (default, e.g. ``"table.zarr"``) or a
        NetCDF file (``.nc``: computed into ``<out>.partial.zarr``, converted at
        the end). ``None``: a temporary store, results returned in memory.
    workers : int, optional
        Local workers. 1 or ``None``: serial in this process; more: a Dask
        ``LocalCluster`` of that many single-threaded worker processes (or
        ``executor="processes"`` for a plain process pool).
    scheduler : str, optional
        Address of a running Dask scheduler (``"tcp://host:8786"``) instead of
        local workers.
    executor : {"serial", "processes", "dask"} or executor object, optional
        Overrides the choice above (see :mod:`wheelrail.sweeps.executors`).
    resume : bool
        Continue the sweep stored at ``out`` (finished chunks are kept, the
        others computed). Without it an existing ``out`` is an error: nothing
        is overwritten.
    progress : bool, optional
        Show a progress bar (default: when more than one chunk is computed).
    timeout : float
        Seconds to wait for a scheduler to answer.
    summary : bool
        Return ``(dataset, SweepSummary)`` instead of the dataset.

    Returns
    -------
    xarray.Dataset
        Dimensions: the grid's axes (or ``point``); outputs of the evaluator
        (creep forces ``Fx, Fy`` [N], ``Mz`` [N·m], ``Fn`` [N], ``a, b`` [m],
        ``p0`` [Pa]), ``status`` (int8: 1 ok, 2 not converged, 3 failed; 0 not computed) and
        ``message`` per point; provenance in ``attrs``. Lazily read from
        ``out`` unless ``out`` is ``None``.

    Raises
    ------
    InputError
        An existing ``out`` without ``resume``, a store of another sweep, a
        scheduler that does not answer, bad ``workers``.

    Examples
    --------
    >>> import wheelrail as wr
    >>> from wheelrail.sweeps import SweepSpec
    >>> spec = SweepSpec.grid(method="linear", mu=0.3, Fn=1e4, A=1.0, B=1.5,
    ...                       xi=[-1e-3, 0.0, 1e-3], eta=[0.0, 1e-3])
    >>> ds = wr.sweep(spec)
    >>> ds.Fx.dims, int((ds.status == 1).sum())
    (('xi', 'eta'), 6)
    """
    _require()
    spec = _as_spec(spec)
    ev = get_evaluator(spec.evaluator)
    execu = make_executor(executor, workers, scheduler, timeout)
    tmpdir = None
    if out is None:
        tmpdir = tempfile.TemporaryDirectory(prefix="wheelrail-sweep-")
        out = Path(tmpdir.name) / "sweep.zarr"
    out = Path(out)
    final = out
    if _is_netcdf(out):
        if out.exists():
            if not resume:
                raise InputError(f"output {str(out)!r} exists; pass resume=True (--resume) to "
                                 "continue it, or choose another path (nothing is overwritten)")
            ds = open_sweep(out)
            return _finish(ds, _summary(ds, spec, 0, 0.0, "none", 0), summary)
        out = out.with_name(out.name + ".partial.zarr")
    if out.exists() and not resume:
        raise InputError(f"output {str(out)!r} exists; pass resume=True (--resume) to continue "
                         "it, or choose another path (nothing is overwritten)")
    methods = ev.methods(spec) if hasattr(ev, "methods") else []
    # estimate (a few points measured here) and refuse past the limits: before any store,
    # and before a local cluster starts; a remote scheduler is asked first (its workers)
    done_before = len(list((out / ".sweep_done").glob("[0-9]*"))) if out.exists() else 0
    remaining = max(spec.size - done_before * spec.chunk, 0)
    remote = getattr(execu, "scheduler", None) is not None
    if remaining and not remote:
        check_sweep(spec, remaining, getattr(execu, "workers", 1) or 1, execu.name)
    with execu:  # connect first: an unreachable scheduler leaves no store behind
        if remaining and remote:
            check_sweep(spec, remaining, execu.workers, "remote")
        if out.exists():
            store = SweepStore.open(out, spec).lock()
        else:
            prov = provenance(spec, methods, {m: ev.options_for(spec, m) for m in methods}
                              if methods else dict(spec.options))
            store = SweepStore.create(out, spec, prov).lock()
        blocks = spec.chunks()
        if resume:
            store.validate()  # a chunk is kept only if it reads back complete
        done = store.done()
        todo = [(i, (spec, b)) for i, b in enumerate(blocks) if i not in done]
        n_todo = sum(int(np.prod([s.stop - s.start for s in blocks[i]])) for i, _ in todo)
        show = (len(todo) > 1) if progress is None else bool(progress)
        t0 = time.perf_counter()
        bar = task = None
        if show:
            from rich.progress import (
                BarColumn,
                MofNCompleteColumn,
                Progress,
                TextColumn,
                TimeElapsedColumn,
                TimeRemainingColumn,
            )

            bar = Progress(TextColumn("[bold]sweep[/] {task.description}"), BarColumn(),
                           MofNCompleteColumn(), TextColumn("points"), TimeElapsedColumn(),
                           TimeRemainingColumn())
            bar.start()
            task = bar.add_task(f"{spec.evaluator}/{'+'.join(methods)} "
                                f"({execu.name}, {execu.workers} worker(s))", total=n_todo)

        writing = []  # set while a result is written: such errors are not the executor's

        def on_result(chunk_id, outputs):
            writing.append(chunk_id)
            store.write(chunk_id, blocks[chunk_id], outputs)
            writing.pop()
            if bar is not None:
                bar.advance(task, len(outputs["status"]))

        try:
            execu.run(evaluate_chunk, todo, on_result)
        except (KeyboardInterrupt, WheelrailError):
            raise
        except Exception as exc:  # noqa: BLE001 - the executor (a lost worker or scheduler)
            if writing or execu.name == "serial":
                raise
            raise SweepInterrupted(
                f"sweep stopped by the executor ({execu.name}): {type(exc).__name__}: "
                f"{' '.join(str(exc).split())[:200]}; the finished chunks are kept in "
                f"{str(out)!r}: continue with --resume", out) from exc
        finally:
            store.close()
            if bar is not None:
                bar.stop()
    seconds = time.perf_counter() - t0
    if _is_netcdf(final):
        to_netcdf(out, final)
        out = final
    ds = open_sweep(out)
    if tmpdir is not None:
        ds = ds.load()
        tmpdir.cleanup()
    return _finish(ds, _summary(ds, spec, n_todo, seconds, execu.name, execu.workers), summary)


def _summary(ds, spec, computed, seconds, executor, workers) -> SweepSummary:
    status = np.asarray(ds["status"].values)
    return SweepSummary(points=spec.size, computed=computed,
                        failed=int((status == STATUS_CODES["failed"]).sum()),
                        not_converged=int((status == STATUS_CODES["not_converged"]).sum()),
                        seconds=seconds, executor=executor, workers=workers)


def _require() -> None:
    try:
        import dask  # noqa: F401
        import zarr  # noqa: F401
    except ImportError as exc:
        raise WheelrailError(f"wheelrail.sweep needs zarr and dask[distributed] ({exc}); "
                             "install them with: pip install 'wheelrail[sweep]'") from None


def _finish(ds, info, summary):
    return (ds, info) if summary else ds
