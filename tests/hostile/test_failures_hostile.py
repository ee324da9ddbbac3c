"""Clean failure everywhere: every failure ends in one line naming the
file or value, and suggests the next step.

A campaign of hostile inputs found: names with rich markup (``c[/bold].toml``,
``--out 'g[/bold]'``) ending in ``MarkupError`` after the outputs were written;
an unreachable scheduler reported as ``MemoryError: Unable to allocate 3.07 EiB``
followed by a traceback of the Dask client's destructor; about 75 lines of
tracebacks on Ctrl-C during ``sweep --workers 2`` without a hint to
``--resume``; the losing one of two concurrent writers saying ``Cannot create ''``;
``[Errno 28]`` without the file; a FIFO case file hanging for ever and
``/dev/zero`` read until memory ran out.
"""

from __future__ import annotations

import errno
import gc
import os
import signal
import socket
import subprocess
import sys
import threading
import time

import pytest
from _helpers import (SOLVE_CASE, SWEEP_CASE, assert_clean_failure, run_cli, sweep_case,
                      wheelset_case)

CASE = SOLVE_CASE

WHEELSET = wheelset_case()

MARKUP = "c[/bold]"  # a directory "c[" with a file "bold].toml" in it


def _markup_file(tmp_path, text):
    (tmp_path / "c[").mkdir()
    p = tmp_path / f"{MARKUP}.toml"
    p.write_text(text)
    return p


# --------------------------------------------------------------------------- markup
def test_solve_echoes_markup_names_literally(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    case = _markup_file(tmp_path, CASE)
    code, out, err = run_cli(["solve", case.relative_to(tmp_path), "--json", "j[/bold].json"],
                             capsys)
    assert code == 0, err
    assert "c[/bold].toml" in out and "j[/bold].json" in out


def test_sweep_echoes_markup_names_literally(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    case = _markup_file(tmp_path, SWEEP_CASE)
    (tmp_path / "o[").mkdir()
    code, out, err = run_cli(["sweep", case.relative_to(tmp_path), "--out", "o[/bold].zarr",
                              "-q"], capsys)
    assert code == 0, err
    code, out, err = run_cli(["sweep", case.relative_to(tmp_path), "--out", "o[/x].zarr"],
                             capsys)
    assert code == 0, err
    assert "c[/bold].toml" in out and "o[/x].zarr" in out


def test_geometry_echoes_markup_out_literally(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "g[").mkdir()
    code, out, err = run_cli(["geometry", "--no-plots", "--points", "5", "--out", "g[/bold]"],
                             capsys)
    assert code == 0, err
    assert "g[/bold]/contact_table.csv" in out


def test_wheelset_echoes_markup_names_literally(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    case = _markup_file(tmp_path, WHEELSET)
    (tmp_path / "g[").mkdir()
    code, out, err = run_cli(["wheelset", case.relative_to(tmp_path), "--out", "g[/bold]",
                              "--no-plots"], capsys)
    assert code == 0, err
    assert "c[/bold].toml" in out and "g[/bold]/wheelset.json" in out


# --------------------------------------------------------------------------- odd input files
@pytest.fixture
def fifo(tmp_path):
    if not hasattr(os, "mkfifo"):
        pytest.skip("no FIFOs on this system")
    p = tmp_path / "pipe.toml"
    os.mkfifo(p)
    return p


@pytest.mark.parametrize("command", [["solve"], ["sweep", "--out", "x.zarr"], ["transient"],
                                     ["wheelset", "--out", "o"], ["compare"]])
def test_fifo_case_file_refused_not_waited_for(command, fifo, capsys, monkeypatch, tmp_path):
    monkeypatch.chdir(tmp_path)
    code, _, err = run_cli([command[0], fifo, *command[1:]], capsys)
    assert_clean_failure(code, err, "pipe.toml", "FIFO", "regular file")


@pytest.mark.parametrize("command", [["solve"], ["sweep", "--out", "x.zarr"]])
def test_device_case_file_refused_not_read(command, capsys, monkeypatch, tmp_path):
    monkeypatch.chdir(tmp_path)
    code, _, err = run_cli([command[0], "/dev/zero", *command[1:]], capsys)
    assert_clean_failure(code, err, "/dev/zero", "device")


def test_directory_as_case_file(tmp_path, capsys):
    code, _, err = run_cli(["sweep", tmp_path, "--out", tmp_path / "x.zarr"], capsys)
    assert_clean_failure(code, err, str(tmp_path), "directory")


def test_huge_case_file_refused_by_size(tmp_path, capsys, monkeypatch):
    from wheelrail import _toml

    monkeypatch.setattr(_toml, "MAX_INPUT_BYTES", 1000)
    p = tmp_path / "big.toml"
    p.write_text(CASE + "#" * 2000 + "\n")
    code, _, err = run_cli(["solve", p], capsys)
    assert_clean_failure(code, err, "big.toml", "too large")


def test_fifo_profile_file_refused(fifo, tmp_path, capsys):
    code, _, err = run_cli(["geometry", "--no-plots", "--points", "5", "--out", tmp_path / "o",
                            "--wheel", fifo], capsys)
    assert_clean_failure(code, err, "pipe.toml", "FIFO")


# --------------------------------------------------------------------------- distributed path
def test_refused_scheduler_is_one_line_with_resume(tmp_path, capsys):
    case = sweep_case(tmp_path)
    with socket.socket() as s:  # a free port nobody listens on
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    addr = f"tcp://127.0.0.1:{port}"
    code, _, err = run_cli(["sweep", case, "--out", tmp_path / "o.zarr", "--scheduler", addr,
                            "--timeout", "2"], capsys)
    assert_clean_failure(code, err, addr, "--resume")
    assert not (tmp_path / "o.zarr").exists()


def test_foreign_server_as_scheduler_no_memoryerror_no_destructor_noise(tmp_path, capsys):
    """Something answers on the port, but not in Dask's protocol (the campaign's 3.07 EiB)."""
    srv = socket.socket()
    srv.bind(("127.0.0.1", 0))
    srv.listen(4)
    port = srv.getsockname()[1]
    stop = threading.Event()

    def serve():
        srv.settimeout(0.2)
        while not stop.is_set():
            try:
                conn, _ = srv.accept()
            except OSError:
                continue
            try:
                conn.sendall(b"\xff" * 64)  # a length prefix of about 1.8e19 bytes
                time.sleep(0.5)
            except OSError:
                pass
            conn.close()

    t = threading.Thread(target=serve, daemon=True)
    t.start()
    try:
        case = sweep_case(tmp_path)
        addr = f"tcp://127.0.0.1:{port}"
        code, _, err = run_cli(["sweep", case, "--out", tmp_path / "o.zarr", "--scheduler",
                                addr, "--timeout", "2"], capsys)
        assert_clean_failure(code, err, addr, "Dask", "--resume")
        assert "MemoryError" not in err[-1]
        gc.collect()  # a half-built client's destructor would print here
        time.sleep(0.5)
        _, err2 = capsys.readouterr()
        assert "Traceback" not in err2 and "Exception ignored" not in err2
    finally:
        stop.set()
        t.join()
        srv.close()


def test_interrupt_suggests_resume_and_resume_completes(tmp_path, capsys, monkeypatch):
    from wheelrail.sweeps import executors

    case = sweep_case(tmp_path)
    out = tmp_path / "o.zarr"
    real = executors.SerialExecutor.run

    def interrupted(self, fn, tasks, on_result):
        def first_then_stop(task_id, value):
            on_result(task_id, value)
            raise KeyboardInterrupt

        real(self, fn, tasks, first_then_stop)

    monkeypatch.setattr(executors.SerialExecutor, "run", interrupted)
    code, _, err = run_cli(["sweep", case, "--out", out, "-q"], capsys)
    assert code == 130 and len(err) == 1, err
    assert str(out) in err[0] and "--resume" in err[0]
    # the abandoned Zarr write's never-awaited coroutines warn at garbage collection,
    # after the message (seen in CI as two extra lines): ignored from the interrupt on
    import warnings

    assert any(f[0] == "ignore" and f[1] is not None and f[2] is RuntimeWarning
               and f[1].match("coroutine 'AsyncArray._set_selection' was never awaited")
               for f in warnings.filters)
    monkeypatch.setattr(executors.SerialExecutor, "run", real)
    code, out_text, err = run_cli(["sweep", case, "--out", out, "--resume"], capsys)
    assert code == 0, err
    from wheelrail.sweeps import open_sweep

    with open_sweep(out) as ds:
        assert (ds.status.values == 1).all()


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
def test_ctrl_c_with_worker_processes_is_one_line(tmp_path):
    """SIGINT to the whole process group (what a terminal's Ctrl-C does)."""
    case = sweep_case(tmp_path, SWEEP_CASE.replace("num = 4", "num = 4000")
                      .replace("chunk = 2", "chunk = 50"))
    argv = [sys.executable, "-m", "wheelrail", "sweep", str(case), "--out",
            str(tmp_path / "o.zarr"), "--executor", "processes", "--workers", "2", "-q"]
    p = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         start_new_session=True,
                         preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    deadline = time.monotonic() + 60
    done = tmp_path / "o.zarr" / ".sweep_done"
    while time.monotonic() < deadline and not (done.exists() and any(done.iterdir())):
        time.sleep(0.2)
    os.killpg(p.pid, signal.SIGINT)
    _, err = p.communicate(timeout=60)
    lines = [ln for ln in err.decode().splitlines() if ln.strip()]
    assert p.returncode == 130, lines
    assert len(lines) == 1 and "--resume" in lines[0], lines


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
def test_ctrl_c_while_a_worker_is_submitted_is_not_lost():
    """A Ctrl-C during ``submit`` (where workers start) must still stop the sweep.

    CI lost one: SIGINT was ignored around every submit, and a fast sweep spends
    much of its time there, so a Ctrl-C could vanish and the sweep ran to the end.
    """
    from wheelrail.sweeps.executors import _sigint_deferred

    with pytest.raises(KeyboardInterrupt):
        with _sigint_deferred():
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(0.05)  # held back, not delivered, not discarded
        time.sleep(0.05)  # delivered here


# --------------------------------------------------------------------------- concurrent writers
def test_concurrent_creation_loser_names_the_store(tmp_path):
    from wheelrail.errors import InputError
    from wheelrail.sweeps import load_sweep
    from wheelrail.sweeps.store import SweepStore, provenance

    case = sweep_case(tmp_path)
    spec = load_sweep(case)
    out = tmp_path / "o.zarr"
    SweepStore.create(out, spec, provenance(spec, ["linear"], {}))
    with pytest.raises(InputError, match="o.zarr.*another run"):
        SweepStore.create(out, spec, provenance(spec, ["linear"], {}))
    assert [p.name for p in tmp_path.iterdir() if "creating" in p.name] == []


def test_resume_of_a_store_being_written_is_refused(tmp_path, capsys):
    from wheelrail.sweeps import load_sweep
    from wheelrail.sweeps.store import SweepStore, provenance

    case = sweep_case(tmp_path)
    spec = load_sweep(case)
    out = tmp_path / "o.zarr"
    store = SweepStore.create(out, spec, provenance(spec, ["linear"], {})).lock()
    try:  # flock is per open file: a second open in this process conflicts like a 2nd process
        code, _, err = run_cli(["sweep", case, "--out", out, "--resume"], capsys)
        assert_clean_failure(code, err, "o.zarr", "another wheelrail sweep")
    finally:
        store.close()
    code, _, err = run_cli(["sweep", case, "--out", out, "--resume", "-q"], capsys)
    assert code == 0, err


# --------------------------------------------------------------------------- OSErrors
@pytest.mark.parametrize("err_no", [errno.ENOSPC, errno.EFBIG])
def test_sweep_write_error_names_the_store(err_no, tmp_path, capsys, monkeypatch):
    import zarr

    case = sweep_case(tmp_path)
    real = zarr.open_group
    calls = {"n": 0}

    def failing(*a, **k):
        calls["n"] += 1
        if k.get("mode") == "r+":
            raise OSError(err_no, os.strerror(err_no))
        return real(*a, **k)

    monkeypatch.setattr(zarr, "open_group", failing)
    code, _, err = run_cli(["sweep", case, "--out", tmp_path / "o.zarr", "-q"], capsys)
    assert_clean_failure(code, err, os.strerror(err_no), "o.zarr")


@pytest.mark.parametrize("err_no", [errno.ENOSPC, errno.EFBIG, errno.EACCES])
def test_atomic_write_errors_name_the_file(err_no, tmp_path, capsys, monkeypatch):
    from wheelrail import _atomic

    def failing(*_a, **_k):
        raise OSError(err_no, os.strerror(err_no))

    monkeypatch.setattr(_atomic.os, "fsync", failing)
    p = tmp_path / "case.toml"
    p.write_text(CASE)
    code, _, err = run_cli(["solve", p, "--json", tmp_path / "r.json"], capsys)
    assert_clean_failure(code, err, os.strerror(err_no), "r.json")
    assert list(tmp_path.iterdir()) == [p]


def test_validation_report_is_written_atomically(tmp_path, monkeypatch):
    """report.html, citations.bib, report.json, report.md: a failing write leaves none."""
    from wheelrail import _atomic
    from wheelrail.validation import _report

    def failing(*_a, **_k):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(_atomic.os, "fsync", failing)
    with pytest.raises(OSError, match="No space left"):
        _report.write_text(tmp_path / "report.html", "<html></html>")
    assert list(tmp_path.iterdir()) == []


# --------------------------------------------------------------------------- internal errors
def test_unexpected_error_names_the_command_and_file(tmp_path, capsys, monkeypatch):
    import wheelrail.cases as cases

    def broken(case):
        raise ZeroDivisionError("float division by zero")

    monkeypatch.setattr(cases, "solve_case", broken)
    p = tmp_path / "case.toml"
    p.write_text(CASE)
    code, _, err = run_cli(["solve", p, "--json", tmp_path / "r.json"], capsys)
    assert_clean_failure(code, err, "internal error", "solve", "case.toml", "r.json",
                         "ZeroDivisionError")


def test_multi_hertz_load_closure_is_a_convergence_failure():
    import wheelrail as wr
    from wheelrail.errors import ConvergenceError, InputError
    from wheelrail.materials import as_material_pair
    from wheelrail.normal import multi_hertz
    from wheelrail.patch import ContactPatch

    pair = as_material_pair(wr.STEEL)
    hc = wr.hertz(7500.0, 0.5 / 0.46, 0.5 / 0.30, wr.STEEL)
    patch = ContactPatch.from_hertz(hc)
    with pytest.raises(ConvergenceError, match=r"did not converge.*7500 N.*7575 N") as info:
        multi_hertz._scale_patches([patch], 1.01, pair, target=7575.0)
    assert not isinstance(info.value, InputError)
    assert "kik-piotrowski" in str(info.value)


def test_conicity_without_contact_names_the_position_not_an_array(monkeypatch):
    import numpy as np

    import wheelrail as wr
    from wheelrail.errors import InputError
    from wheelrail.geometry import Track, Wheelset, conicity

    real = conicity.contact_table

    def holed(*a, **k):
        tab = real(*a, **k)
        dr = tab["delta_r"].values.copy()
        dr[3] = np.nan
        return tab.assign(delta_r=("y", dr))

    monkeypatch.setattr(conicity, "contact_table", holed)
    ws = Wheelset(wr.profiles.load("S1002"))
    tr = Track(wr.profiles.load("60E1"), inclination=1 / 40)
    with pytest.raises(InputError) as info:
        conicity.equivalent_conicity(ws, tr, 0.003)
    msg = str(info.value)
    assert "y = " in msg and " mm" in msg and "array" not in msg and "shape" not in msg
