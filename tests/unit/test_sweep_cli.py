"""``wheelrail sweep CASE.toml --out OUT``, run in-process."""

import socket

import numpy as np

import wheelrail as wr
from wheelrail.cli.main import main

CASE = """
[sweep]
method = "linear"
mu = 0.3
Fn = 10000.0
A = 1.087
B = 1.667
xi = {{start = -0.004, stop = 0.004, num = 11}}
eta = {eta}
phi = [0.0, 0.5]
chunk = 8
"""


def _case(tmp_path, eta="[0.0, 0.001]"):
    p = tmp_path / "case.toml"
    p.write_text(CASE.format(eta=eta))
    return str(p)


def test_sweep_writes_zarr_and_prints_a_summary(tmp_path, capsys):
    out = tmp_path / "t.zarr"
    assert main(["sweep", _case(tmp_path), "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "points" in text and "44" in text and "points/s" in text
    ds = wr.open_sweep(out)
    assert ds.Fx.shape == (11, 2, 2) and np.all(ds.status.values == 1)
    # Kalker's linear law: Fx = -G c^2 C11 xi, odd in xi (an independent check of the layout)
    np.testing.assert_allclose(ds.Fx.values[::-1], -ds.Fx.values, atol=1e-9)
    assert ds.attrs["input_file"].endswith("case.toml") and len(ds.attrs["input_sha256"]) == 64


def test_existing_output_without_resume_is_an_error(tmp_path, capsys):
    out = tmp_path / "t.zarr"
    case = _case(tmp_path)
    assert main(["sweep", case, "--out", str(out), "-q"]) == 0
    assert main(["sweep", case, "--out", str(out), "-q"]) == 2
    assert "t.zarr' exists; pass resume=True (--resume)" in capsys.readouterr().err
    assert main(["sweep", case, "--out", str(out), "-q", "--resume"]) == 0


def test_axis_without_values_is_named(tmp_path, capsys):
    assert main(["sweep", _case(tmp_path, eta="[]"), "--out", str(tmp_path / "x.zarr")]) == 2
    err = capsys.readouterr().err
    assert "[sweep] eta: axis 'eta' has no values" in err
    assert not (tmp_path / "x.zarr").exists()


def test_scheduler_that_does_not_answer(tmp_path, capsys):
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    addr = f"tcp://127.0.0.1:{port}"
    rc = main(["sweep", _case(tmp_path), "--out", str(tmp_path / "x.zarr"), "--scheduler", addr,
               "--timeout", "1"])
    assert rc == 2
    assert f"Dask scheduler '{addr}' did not answer within 1 s" in capsys.readouterr().err
    assert not (tmp_path / "x.zarr").exists()  # nothing written


def test_workers_and_scheduler_are_exclusive(tmp_path, capsys):
    rc = main(["sweep", _case(tmp_path), "--out", str(tmp_path / "x.zarr"), "--workers", "2",
               "--scheduler", "tcp://127.0.0.1:1"])
    assert rc == 2 and "not allowed with argument" in capsys.readouterr().err
