"""A dynamics run written to a Zarr store while it goes (``simulate(..., store=...)``,
``wheelrail dynamics --store``): the same histories as a run kept in memory, a memory that
does not grow with the duration, Ctrl-C leaving a readable store marked interrupted, and
refusals of a path that is not a result store or a disk too small for the outputs."""

from __future__ import annotations

import importlib
import json
import tracemalloc

import numpy as np
import pytest

pytest.importorskip("zarr")
pytest.importorskip("dask")

import wheelrail as wr  # noqa: E402
from wheelrail import _resources  # noqa: E402
from wheelrail.dynamics import store as STORE  # noqa: E402
from wheelrail.dynamics.reference import cone_track  # noqa: E402

from _dynamics_case import wheelset_case  # noqa: E402

D = wr.dynamics
SIM = importlib.import_module("wheelrail.dynamics.simulate")


@pytest.fixture(scope="module")
def setup():
    ws, tr = cone_track()
    model = D.WheelsetModel(ws, 1813.0, (1120.0, 112.0, 1120.0), spin="fixed",
                            primary=D.Suspension(kx=1e6, ky=3.9e6, kz=1.2e6))
    return model, tr


@pytest.fixture
def small_chunks(monkeypatch):
    """Store chunks of 256 outputs, so that a short run is written in several appends."""
    monkeypatch.setattr(STORE, "BUFFER_BYTES", 1.0)


def _run(setup, duration=0.6, **kw):
    model, tr = setup
    return D.simulate(model, tr, 20.0, duration, "hertz", "fastsim",
                      initial={"ws0.y": 0.002}, **kw)


def test_stored_run_equals_the_run_in_memory(setup, tmp_path, small_chunks):
    mem = _run(setup)
    st = _run(setup, store=tmp_path / "run.zarr")
    assert st.info["store_status"] == "complete"
    assert hasattr(st.states, "dask")                     # read back lazily
    assert mem.t.size == st.t.size == 601                 # 3 appends of 256 rows
    a, b = mem.dataset, st.dataset
    assert set(a.data_vars) == set(b.data_vars)
    for name in a.data_vars:
        np.testing.assert_array_equal(a[name].values, b[name].values, err_msg=name)
    ta, tb = D.assess(mem), D.assess(st)
    for name in ("Y_max", "Q_max", "sum_Y_2m_max", "wear_number_mean"):
        np.testing.assert_array_equal(ta[name].values, tb[name].values, err_msg=name)
    again = D.open_result(tmp_path / "run.zarr")
    np.testing.assert_array_equal(again.t, mem.t)
    assert again.info["normal"] == mem.info["normal"]


def _peak(fn):
    tracemalloc.start()
    try:
        fn()
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def test_memory_of_a_stored_run_does_not_grow_with_its_duration(setup, tmp_path, small_chunks):
    """Kept in memory, the outputs of a 6 s run (6000 outputs of about 1.2 kB) raise the peak
    over that of a 0.5 s run by megabytes; written to a store, only one chunk of 256 outputs
    and the time axis are held, and the peak does not move."""
    _run(setup, 0.05)                                     # compiled and warm
    _run(setup, 0.05, store=tmp_path / "warm.zarr")
    mem_short = _peak(lambda: _run(setup, 0.5))
    mem_long = _peak(lambda: _run(setup, 6.0))
    st_short = _peak(lambda: _run(setup, 0.5, store=tmp_path / "a.zarr"))
    st_long = _peak(lambda: _run(setup, 6.0, store=tmp_path / "b.zarr"))
    assert mem_long - mem_short > 4.0e6
    assert st_long - st_short < 0.5e6


def test_ctrl_c_leaves_a_readable_store_marked_interrupted(setup, tmp_path, small_chunks,
                                                           monkeypatch):
    real = SIM.run_fixed
    calls = {"n": 0}

    def fake(*args):
        calls["n"] += 1
        if calls["n"] > 7:                               # 7 chunks of 50 ms
            raise KeyboardInterrupt
        return real(*args)

    monkeypatch.setattr(SIM, "run_fixed", fake)
    with pytest.raises(SIM.SimulationInterrupted) as err:
        _run(setup, 1.0, store=tmp_path / "run.zarr")
    res = err.value.result
    assert res.info["store_status"] == "interrupted" and res.info["interrupted"] == 1
    back = D.open_result(tmp_path / "run.zarr")
    assert back.t[-1] == pytest.approx(0.35, abs=1e-9) and back.t.size == 351
    assert np.all(np.isfinite(np.asarray(back.states)))


def test_a_path_that_is_not_a_result_store_is_refused_untouched(setup, tmp_path):
    other = tmp_path / "notes"
    other.mkdir()
    (other / "keep.txt").write_text("mine")
    with pytest.raises(wr.InputError, match="not a dynamics result store"):
        _run(setup, 0.05, store=other)
    assert (other / "keep.txt").read_text() == "mine"
    with pytest.raises(wr.InputError, match="not a readable dynamics result store"):
        D.open_result(other)


def test_a_disk_too_small_for_the_outputs_is_refused(setup, tmp_path, monkeypatch):
    import shutil
    from collections import namedtuple

    usage = namedtuple("usage", "total used free")
    monkeypatch.setattr(shutil, "disk_usage", lambda p: usage(1e6, 0.0, 1e5))
    with pytest.raises(_resources.ResourceLimitError, match="free on that disk"):
        _run(setup, 1.0, store=tmp_path / "run.zarr")
    assert not (tmp_path / "run.zarr").exists()


CASE = wheelset_case(0.3)


def test_cli_store_writes_result_zarr_and_the_assessment(tmp_path, capsys):
    from wheelrail.cli.main import main

    case = tmp_path / "case.toml"
    case.write_text(CASE)
    out = tmp_path / "out"
    code = main(["dynamics", str(case), "--out", str(out), "--store", "--no-figures",
                 "--no-progress"])
    text = capsys.readouterr().out
    assert code == 0, text
    assert "result.zarr" in text and not (out / "result.nc").exists()
    res = D.open_result(out / "result.zarr")
    assert res.info["store_status"] == "complete" and res.t[-1] == pytest.approx(0.3)
    summary = json.loads((out / "summary.json").read_text())
    assert summary["simulated_s"] == pytest.approx(0.3)
    assert (out / "assessment.csv").exists()
