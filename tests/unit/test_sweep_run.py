"""Running sweeps: results, per-point failures, stores, resume, executors, errors."""

import signal
import socket
import subprocess
import sys
import textwrap

import numpy as np
import pytest
import xarray as xr

import wheelrail as wr
from wheelrail.errors import InputError
from wheelrail.sweeps import DaskExecutor, SweepSpec, open_sweep, sweep

BASE = dict(method="linear", mu=0.3, Fn=1e4, A=1.0, B=1.5)
STEEL = wr.Material(2.1e11, 0.28)


def _same_data(a, b):
    """Equal values, coordinates and sweep identity (the 'created' date may differ)."""
    xr.testing.assert_equal(a.load(), b.load())
    assert a.attrs["spec_sha256"] == b.attrs["spec_sha256"]


def test_grid_values_equal_direct_creep_forces():
    spec = SweepSpec.grid(**{**BASE, "method": "fastsim"}, xi=[-2e-3, 0.0, 1e-3],
                          eta=[0.0, 5e-4], phi=[0.3], chunk=2, options={"nx": 12, "ny": 12})
    ds = sweep(spec, progress=False)
    assert ds.Fx.dims == ("xi", "eta", "phi") and ds.Fx.shape == (3, 2, 1)
    assert np.all(ds.status.values == 1) and np.all(ds.message.values == "")
    c = wr.hertz(1e4, 1.0, 1.5, STEEL)
    for i, xi in enumerate([-2e-3, 0.0, 1e-3]):
        for j, eta in enumerate([0.0, 5e-4]):
            r = wr.creep_forces(c, (xi, eta, 0.3), 0.3, method="fastsim", nx=12, ny=12)
            assert ds.Fx.values[i, j, 0] == pytest.approx(r.Fx, rel=1e-12, abs=1e-9)
            assert ds.Mz.values[i, j, 0] == pytest.approx(r.Mz, rel=1e-12, abs=1e-12)
    assert ds.a.values[0, 0, 0] == pytest.approx(c.a) and ds.Fx.attrs["units"] == "N"
    for key in ("wheelrail_version", "method", "options", "spec", "input_sha256", "created"):
        assert key in ds.attrs


def test_a_failing_point_is_recorded_and_does_not_abort():
    spec = SweepSpec.grid(**{**BASE, "Fn": [1e4, -5.0, 2e4]}, xi=[-1e-3, 0.0])
    ds = sweep(spec, progress=False)
    st = ds.status.values
    assert list(st[:, 0]) == [1, 3, 1] and list(st[:, 1]) == [1, 3, 1]
    assert "Fn must be > 0, got -5.0" in str(ds.message.values[1, 0])
    assert np.isnan(ds.Fx.values[1, 0]) and np.isfinite(ds.Fx.values[0, 0])


def test_existing_output_needs_resume_and_is_not_overwritten(tmp_path):
    out = tmp_path / "t.zarr"
    spec = SweepSpec.grid(**BASE, xi=[0.0, 1e-3])
    sweep(spec, out, progress=False)
    stamp = open_sweep(out).attrs["created"]
    with pytest.raises(InputError, match=r"output '.*t\.zarr' exists; pass resume=True"):
        sweep(spec, out)
    other = SweepSpec.grid(**BASE, xi=[0.0, 2e-3])
    with pytest.raises(InputError, match="holds a different sweep"):
        sweep(other, out, resume=True)
    ds, info = sweep(spec, out, resume=True, summary=True)
    assert info.computed == 0 and ds.attrs["created"] == stamp


def test_netcdf_output(tmp_path):
    out = tmp_path / "t.nc"
    spec = SweepSpec.from_points({"xi": [-1e-3, 1e-3], "eta": [0.0, 2e-4]}, **BASE)
    ds = sweep(spec, out, progress=False)
    assert out.exists() and not (tmp_path / "t.nc.partial.zarr").exists()
    assert ds.Fx.dims == ("point",) and ds.Fx.values[0] > 0 > ds.Fx.values[1]
    with pytest.raises(InputError, match="exists"):
        sweep(spec, out)
    again, info = sweep(spec, out, resume=True, summary=True)  # finished: nothing to do
    assert info.computed == 0 and again.Fx.values[0] == ds.Fx.values[0]


def test_resume_after_sigkill_gives_the_uninterrupted_dataset(tmp_path):
    """A run SIGKILLed after 3 chunks, between the 4th chunk's data and its marker, resumes
    to exactly the dataset of an uninterrupted run: nothing lost, nothing duplicated."""
    case = tmp_path / "case.toml"
    case.write_text(textwrap.dedent("""
        [sweep]
        method = "fastsim"
        mu = 0.3
        Fn = 10000.0
        A = 1.087
        B = 1.667
        xi = {start = -0.004, stop = 0.004, num = 12}
        eta = [0.0, 0.001]
        chunk = 4
        [sweep.options]
        nx = 8
        ny = 8
    """))
    full = sweep(str(case), tmp_path / "full.zarr", progress=False)
    script = textwrap.dedent(f"""
        import os, signal, sys
        from wheelrail.sweeps import store, sweep
        n = {{"writes": 0}}
        orig = store.SweepStore.write
        kill_after, mode = int(sys.argv[2]), sys.argv[3]
        def write(self, cid, block, out):
            if mode == "mid" and n["writes"] == kill_after:
                import zarr, numpy as np
                g = zarr.open_group(str(self.path), mode="r+")
                shape = tuple(s.stop - s.start for s in block)
                for k, v in out.items():           # data written, marker not yet
                    g[k][block] = np.asarray(v).reshape(shape)
                os.kill(os.getpid(), signal.SIGKILL)
            orig(self, cid, block, out)
            n["writes"] += 1
            if mode == "after" and n["writes"] == kill_after:
                os.kill(os.getpid(), signal.SIGKILL)
        store.SweepStore.write = write
        sweep({str(case)!r}, sys.argv[1], progress=False)
    """)
    for mode in ("mid",):  # "after" (kill after a completed chunk) works the same way
        out = tmp_path / f"{mode}.zarr"
        p = subprocess.run([sys.executable, "-c", script, str(out), "3", mode])
        assert p.returncode == -signal.SIGKILL
        done = len(list((out / ".sweep_done").iterdir()))
        assert done == 3 and len(full.attrs) and done < 6      # killed half-way
        part = open_sweep(out)
        missing = part.status.values == 0                        # points really missing
        assert missing.sum() == 8 and np.isnan(part.Fx.values[missing]).all()
        ds, info = sweep(str(case), out, resume=True, progress=False, summary=True)
        assert info.computed == 12                               # 3 of 6 chunks of 4 points
        _same_data(ds, full)


def test_dask_executor_matches_serial():
    spec = SweepSpec.grid(**BASE, xi=np.linspace(-2e-3, 2e-3, 7), eta=[0.0, 1e-3], chunk=3)
    serial = sweep(spec, progress=False)
    with DaskExecutor(2, processes=False):
        pass  # a cluster starts and stops
    ds, info = sweep(spec, executor=DaskExecutor(2, processes=False), progress=False,
                     summary=True)
    assert info.executor == "dask" and info.workers == 2
    _same_data(ds, serial)


def test_process_executor_matches_serial_and_leaves_no_processes():
    import multiprocessing

    spec = SweepSpec.grid(**BASE, xi=np.linspace(-2e-3, 2e-3, 5), chunk=2)
    ds = sweep(spec, workers=2, executor="processes", progress=False)
    _same_data(ds, sweep(spec, progress=False))
    assert multiprocessing.active_children() == []


def _closed_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_scheduler_that_does_not_answer_is_named():
    addr = f"tcp://127.0.0.1:{_closed_port()}"
    spec = SweepSpec.grid(**BASE, xi=[0.0])
    with pytest.raises(InputError, match=rf"Dask scheduler '{addr}' did not answer within 1 s"):
        sweep(spec, scheduler=addr, timeout=1.0)


@pytest.mark.parametrize("kwargs, match", [
    (dict(workers=0), "workers must be an integer >= 1, got 0"),
    (dict(workers=2, scheduler="tcp://127.0.0.1:1"), "not both"),
    (dict(executor="mpi"), "unknown executor 'mpi'"),
    (dict(scheduler="nowhere"), "scheduler must be an address"),
])
def test_bad_executor_arguments(kwargs, match):
    with pytest.raises(InputError, match=match):
        sweep(SweepSpec.grid(**BASE, xi=[0.0]), **kwargs)


def test_method_axis_with_per_method_options():
    spec = SweepSpec.grid(**{**BASE, "method": ["linear", "fastsim"]}, xi=[-1e-4, -2e-3],
                          options={"fastsim": {"nx": 30, "ny": 30}})
    ds = sweep(spec, progress=False)
    assert list(ds.method.values) == ["linear", "fastsim"]
    c = wr.hertz(1e4, 1.0, 1.5, STEEL)
    f = wr.creep_forces(c, (-2e-3, 0, 0), 0.3, method="fastsim", nx=30, ny=30)
    assert ds.Fx.values[1, 1] == pytest.approx(f.Fx, rel=1e-12)
    # small creepage: FASTSIM tends to the linear theory (Kalker 1982), within a few per cent
    assert ds.Fx.values[1, 0] == pytest.approx(ds.Fx.values[0, 0], rel=0.05)


def test_geometry_evaluator_over_shift_and_rail_profiles():
    """Lateral shift x rail profile: equals wr.contact_table and is antisymmetric in y."""
    y = [-0.006, 0.0, 0.006]
    spec = SweepSpec.grid(evaluator="geometry", wheel="S1002", rail=["60E1", "54E1"], y=y)
    ds = sweep(spec, progress=False)
    assert ds.delta_r.dims == ("rail", "y") and np.all(ds.status.values == 1)
    tab = wr.contact_table(wr.Wheelset(wr.profiles.load("S1002")),
                           wr.Track(wr.profiles.load("60E1")), np.array(y))
    np.testing.assert_allclose(ds.delta_r.values[0], tab.delta_r.values, atol=1e-9)
    np.testing.assert_allclose(ds.delta_r.values[:, ::-1], -ds.delta_r.values, atol=1e-9)
    assert np.all(ds.A_left.values > 0) and abs(ds.delta_r.values[1, 1]) < 1e-9
    with pytest.raises(wr.ProfileError):
        SweepSpec.grid(evaluator="geometry", rail="61E9", y=[0.0])
