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

import math
import os

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


def _ignore_sigint():
    """Worker initializer: Ctrl-C stops the parent, which stops the workers (no tracebacks)."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)


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
                                         mp_context=multiprocessing.get_context("spawn"),
                                         initializer=_ignore_sigint)
        return self

    def __exit__(self, *exc):
        self._pool.shutdown(wait=True, cancel_futures=True)
        return False

    def run(self, fn, tasks, on_result):
        from concurrent.futures import FIRST_COMPLETED, wait

        def wait_one(pending):
            done, _ = wait(list(pending), return_when=FIRST_COMPLETED)
            return next(iter(done))

        def submit(*a):
            with _sigint_deferred():  # worker processes are started here: they ignore Ctrl-C
                return self._pool.submit(fn, *a)

        _bounded(submit, wait_one, tasks, on_result, 2 * self.workers)


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

        if self.scheduler is not None:
            self._client = _connect(Client, self.scheduler, self.timeout)
            n = len(self._client.scheduler_info().get("workers", {}))
            self.workers = max(n, 1)
        else:
            with _sigint_ignored():  # workers inherit it: Ctrl-C stops this process only
                self._cluster = LocalCluster(n_workers=self.workers, threads_per_worker=1,
                                             processes=self.processes, dashboard_address=":0",
                                             silence_logs=40)
            self._client = Client(self._cluster, set_as_default=False)
        return self

    def __exit__(self, *exc):
        import contextlib
        import logging

        # on an interrupt or a lost scheduler: close without Dask's shutdown warnings
        quiet = exc[0] is not None
        loggers = [logging.getLogger(n) for n in ("distributed", "tornado", "asyncio")]
        levels = [lg.level for lg in loggers]
        if quiet:
            for lg in loggers:
                lg.setLevel(logging.CRITICAL + 1)
        try:
            if self._client is not None:
                with contextlib.suppress(Exception) if quiet else contextlib.nullcontext():
                    self._client.close(timeout=5 if quiet else None)
            if self._cluster is not None:
                with contextlib.suppress(Exception) if quiet else contextlib.nullcontext():
                    self._cluster.close(timeout=5 if quiet else None)
        finally:
            for lg, lv in zip(loggers, levels):
                lg.setLevel(lv)
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


def _probe(address: str, timeout: float) -> None:
    """Open a TCP connection to ``address`` (``tcp://host:port``) within ``timeout`` seconds.

    Raises
    ------
    OSError
        Nobody listens there (refused, unreachable, timed out, unknown host).
    """
    import socket

    hostport = address.split("://", 1)[-1]
    host, _, port = hostport.rpartition(":")
    if not host or not port.isdigit():
        return  # not host:port (e.g. a unix socket or inproc address): let Dask try
    with socket.create_connection((host.strip("[]"), int(port)), timeout=timeout):
        pass


def _connect(client_class, address: str, timeout: float):
    """A Dask client of the scheduler at ``address``, or one InputError naming it.

    A failed connection leaves no half-built client behind whose destructor
    would later print a traceback (it would time out closing a connection
    that never opened).
    """
    import dask

    hint = f"Dask scheduler {address!r}"
    advice = ("is it running and reachable? Nothing was computed; run the command again "
              "when it is (with --resume if the output already holds part of the sweep)")
    try:
        _probe(address, timeout)
    except OSError as exc:
        raise InputError(f"{hint} did not answer within {timeout:g} s "
                         f"({exc.strerror or type(exc).__name__}); {advice}") from None
    client = client_class.__new__(client_class)
    try:
        with dask.config.set({"distributed.comm.timeouts.connect": f"{timeout}s"}):
            client.__init__(address, timeout=f"{timeout}s", set_as_default=False)
    except Exception as exc:  # noqa: BLE001 - anything from the wire: not a Dask scheduler
        import contextlib

        client.status = "closed"  # its destructor has nothing to close
        with contextlib.suppress(Exception):
            client._loop_runner.stop()
        what = (f"did not answer within {timeout:g} s ({type(exc).__name__})"
                if isinstance(exc, (OSError, TimeoutError))
                else "answered, but not in the Dask protocol")
        raise InputError(f"{hint} {what}; {advice}") from None
    return client


class _sigint_ignored:
    """Ignore SIGINT while worker processes are started (they inherit the disposition).

    Ctrl-C then interrupts this process alone, which stops the workers itself,
    instead of every worker printing its own KeyboardInterrupt traceback.
    """

    def __enter__(self):
        import signal
        import threading

        self._saved = None
        if threading.current_thread() is threading.main_thread():
            self._saved = signal.signal(signal.SIGINT, signal.SIG_IGN)
        return self

    def __exit__(self, *exc):
        import signal

        if self._saved is not None:
            signal.signal(signal.SIGINT, self._saved)
        return False


class _sigint_deferred:
    """Hold back SIGINT while worker processes may be started, without losing it.

    ``submit`` starts the pool's worker processes on demand. A process started
    with SIGINT blocked keeps it blocked until its initializer ignores it, so a
    Ctrl-C never reaches a half-started worker; in this process a Ctrl-C that
    arrives meanwhile stays pending and is delivered when the block ends (the
    ``SIG_IGN`` of :class:`_sigint_ignored` would discard it, and the sweep would
    run on). Falls back to :class:`_sigint_ignored` where signals cannot be
    blocked (Windows).
    """

    def __enter__(self):
        import signal

        self._fallback = None
        if hasattr(signal, "pthread_sigmask"):
            self._mask = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
        else:  # pragma: no cover - Windows
            self._fallback = _sigint_ignored().__enter__()
        return self

    def __exit__(self, *exc):
        import signal

        if self._fallback is not None:  # pragma: no cover - Windows
            return self._fallback.__exit__(*exc)
        signal.pthread_sigmask(signal.SIG_SETMASK, self._mask)
        return False


EXECUTORS = ("serial", "processes", "dask")


def _max_workers() -> int:
    """The most local workers accepted: 8 per core, at least 64 (beyond: a cluster)."""
    return max(64, 8 * (os.cpu_count() or 1))


def make_executor(executor=None, workers=None, scheduler=None, timeout=10.0):
    """The executor for the arguments of :func:`wheelrail.sweep` (see there)."""
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int)
                                or workers < 1):
        raise InputError(f"workers must be an integer >= 1, got {workers!r}")
    limit = _max_workers()
    if workers is not None and workers > limit:
        raise InputError(f"workers = {workers} is more than this machine can run "
                         f"({os.cpu_count() or 1} cores; at most {limit} local workers); "
                         "use a cluster (--scheduler) for more")
    if (isinstance(timeout, bool) or not isinstance(timeout, (int, float))
            or not math.isfinite(timeout) or timeout <= 0):
        raise InputError(f"timeout must be a finite number of seconds > 0, got {timeout!r}")
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
