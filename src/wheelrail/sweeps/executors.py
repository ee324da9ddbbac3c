"""Executors: where the chunks of a sweep are evaluated.

===============  =======================================================
name             runs chunks
===============  =======================================================
``"serial"``     in this process, one after the other
``"processes"``  in ``workers`` local processes (``concurrent.futures``)
``"dask"``       on Dask distributed: a ``LocalCluster`` of ``workers``
                 single-threaded worker processes, or the scheduler at
                 ``scheduler="tcp://host:8786"`` (a cluster)
===============  =======================================================

Every executor is a context manager with one method,
``run(fn, tasks, on_result)``: it calls ``fn(*args)`` for each
``(task_id, args)`` of ``tasks`` and ``on_result(task_id, value)`` *in this
process* as results arrive (in any order). At most ``2 × workers`` tasks are
in flight, so memory is bounded by the chunk size, whatever the sweep size.
Workers never write files; the caller does.
"""

from __future__ import annotations

from ..errors import InputError

__all__ = ["SerialExecutor", "ProcessExecutor", "DaskExecutor", "make_executor", "EXECUTORS"]


class SerialExecutor:
    """Evaluate chunks in this process."""

    name = "serial"
    workers = 1

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False

    def run(self, fn, tasks, on_result):
        for task_id, args in tasks:
            on_result(task_id, fn(*args))


def _bounded(submit, wait_one, tasks, on_result, limit):
    """Submit ``tasks`` keeping at most ``limit`` in flight; hand results to ``on_result``."""
    pending = {}
    it = iter(tasks)
    exhausted = False
    while pending or not exhausted:
        while not exhausted and len(pending) < limit:
            try:
                task_id, args = next(it)
            except StopIteration:
                exhausted = True
                break
            pending[submit(*args)] = task_id
        if pending:
            fut = wait_one(pending)
            task_id = pending.pop(fut)
            on_result(task_id, fut.result())


class ProcessExecutor:
    """Evaluate chunks in ``workers`` local processes (spawned, so safe with numba threads)."""

    name = "processes"

    def __init__(self, workers: int):
        self.workers = workers
        self._pool = None

    def __enter__(self):
        import multiprocessing
        from concurrent.futures import ProcessPoolExecutor

        self._pool = ProcessPoolExecutor(max_workers=self.workers,
                                         mp_context=multiprocessing.get_context("spawn"))
        return self

    def __exit__(self, *exc):
        self._pool.shutdown(wait=True, cancel_futures=True)
        return False

    def run(self, fn, tasks, on_result):
        from concurrent.futures import FIRST_COMPLETED, wait

        def wait_one(pending):
            done, _ = wait(list(pending), return_when=FIRST_COMPLETED)
            return next(iter(done))

        _bounded(lambda *a: self._pool.submit(fn, *a), wait_one, tasks, on_result,
                 2 * self.workers)


class DaskExecutor:
    """Evaluate chunks on Dask distributed.

    Parameters
    ----------
    workers : int
        Worker processes of the ``LocalCluster`` started when no scheduler is
        given (one thread each: the solvers are single-threaded numpy/numba).
    scheduler : str, optional
        Address of a running scheduler (``"tcp://host:8786"``); the cluster's
        workers must have wheelrail installed.
    timeout : float
        Seconds to wait for the scheduler to answer.
    processes : bool
        ``LocalCluster`` with worker processes (default) or threads (tests).
    """

    name = "dask"

    def __init__(self, workers: int = 2, scheduler: str | None = None, timeout: float = 10.0,
                 processes: bool = True):
        self.workers = workers
        self.scheduler = scheduler
        self.timeout = timeout
        self.processes = processes
        self._client = self._cluster = None

    def __enter__(self):
        try:
            from distributed import Client, LocalCluster
        except ImportError as exc:  # pragma: no cover - dask is a dependency
            raise InputError("the dask executor needs 'dask[distributed]' "
                             f"(pip install 'dask[distributed]'): {exc}") from None
        import dask

        if self.scheduler is not None:
            try:
                with dask.config.set({"distributed.comm.timeouts.connect": f"{self.timeout}s"}):
                    self._client = Client(self.scheduler, timeout=f"{self.timeout}s",
                                          set_as_default=False)
            except (OSError, TimeoutError) as exc:
                raise InputError(f"Dask scheduler {self.scheduler!r} did not answer within "
                                 f"{self.timeout:g} s ({type(exc).__name__}); is it running "
                                 "and reachable?") from None
            n = len(self._client.scheduler_info().get("workers", {}))
            self.workers = max(n, 1)
        else:
            self._cluster = LocalCluster(n_workers=self.workers, threads_per_worker=1,
                                         processes=self.processes, dashboard_address=":0",
                                         silence_logs=40)
            self._client = Client(self._cluster, set_as_default=False)
        return self

    def __exit__(self, *exc):
        if self._client is not None:
            self._client.close()
        if self._cluster is not None:
            self._cluster.close()
        return False

    def run(self, fn, tasks, on_result):
        from distributed import as_completed

        it = iter(tasks)
        ac = as_completed(loop=self._client.loop)
        pending = {}

        def submit_next() -> bool:
            try:
                task_id, args = next(it)
            except StopIteration:
                return False
            fut = self._client.submit(fn, *args, pure=False)
            pending[fut.key] = task_id
            ac.add(fut)
            return True

        for _ in range(2 * self.workers):
            if not submit_next():
                break
        for fut in ac:
            task_id = pending.pop(fut.key)
            value = fut.result()
            fut.release()
            on_result(task_id, value)
            submit_next()


EXECUTORS = ("serial", "processes", "dask")


def make_executor(executor=None, workers=None, scheduler=None, timeout=10.0):
    """The executor for the arguments of :func:`wheelrail.sweep` (see there)."""
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int)
                                or workers < 1):
        raise InputError(f"workers must be an integer >= 1, got {workers!r}")
    if scheduler is not None:
        if workers is not None:
            raise InputError("give workers (a local cluster) or scheduler (a running "
                             f"cluster), not both: workers={workers!r}, scheduler={scheduler!r}")
        if not isinstance(scheduler, str) or "://" not in scheduler and ":" not in scheduler:
            raise InputError(f"scheduler must be an address such as 'tcp://host:8786', "
                             f"got {scheduler!r}")
        if executor not in (None, "dask"):
            raise InputError(f"scheduler needs executor='dask', got executor={executor!r}")
        return DaskExecutor(scheduler=scheduler, timeout=timeout)
    if executor is None:
        executor = "serial" if (workers or 1) == 1 else "dask"
    if not isinstance(executor, str):
        return executor  # an executor object
    if executor == "serial":
        return SerialExecutor()
    if executor == "processes":
        return ProcessExecutor(workers or 2)
    if executor == "dask":
        return DaskExecutor(workers or 2, timeout=timeout)
    raise InputError(f"unknown executor {executor!r}; choose one of {', '.join(EXECUTORS)}")
