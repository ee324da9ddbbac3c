"""Sweeps never resume into a damaged store; bad sweep arguments and specs get one line.

Each case damages a finished store the way a crash, a full disk or a careless
user would, and checks that ``--resume`` recomputes what it cannot trust (the
values are compared with the linear theory's closed form, Kalker 1967:
``Fx = -G c² C11 ξ`` — here only equality with an undamaged run is needed) or
refuses with one line naming the store.
"""

from __future__ import annotations

import numpy as np
import pytest
from _helpers import assert_clean_failure, run_cli, sweep_case

from wheelrail.sweeps import open_sweep

@pytest.fixture()
def finished(tmp_path, capsys):
    case = sweep_case(tmp_path)
    out = tmp_path / "o.zarr"
    code, _, err = run_cli(["sweep", case, "--out", out, "-q"], capsys)
    assert code == 0, err
    with open_sweep(out) as ds:
        ref = ds.Fx.values.copy()
    assert np.isfinite(ref).all()
    return case, out, ref


def _resume_ok(case, out, ref, capsys):
    code, _, err = run_cli(["sweep", case, "--out", out, "--resume", "-q"], capsys)
    assert code == 0 and not err, err
    with open_sweep(out) as ds:
        np.testing.assert_allclose(ds.Fx.values, ref, rtol=1e-12)
        assert (ds.status.values == 1).all()


def test_corrupt_chunk_is_recomputed(finished, capsys):
    case, out, ref = finished
    (out / "Fx" / "1.0").write_bytes(b"\x00garbage, not a blosc chunk" * 2)
    _resume_ok(case, out, ref, capsys)


def test_marker_without_data_is_recomputed(finished, capsys):
    case, out, ref = finished
    (out / "Fx" / "2.0").unlink()
    (out / "status" / "2.0").unlink()       # the marker stays: it claims data that is gone
    _resume_ok(case, out, ref, capsys)


def test_ok_rows_with_nan_are_recomputed(finished, capsys):
    case, out, ref = finished
    (out / "Fx" / "3.0").unlink()           # status still says ok, Fx reads as NaN
    _resume_ok(case, out, ref, capsys)


def test_deleted_zmetadata_is_rebuilt(finished, capsys):
    case, out, ref = finished
    (out / ".zmetadata").unlink()
    _resume_ok(case, out, ref, capsys)
    assert (out / ".zmetadata").exists()


def test_deleted_attributes_are_one_line(finished, capsys):
    case, out, _ = finished
    (out / ".zattrs").unlink()
    code, _, err = run_cli(["sweep", case, "--out", out, "--resume", "-q"], capsys)
    assert_clean_failure(code, err, "cannot resume", "o.zarr", "sweep description")


def test_unreadable_result_is_one_line(tmp_path, capsys):
    from wheelrail.errors import InputError

    bad = tmp_path / "r.nc"
    bad.write_bytes(b"not a netcdf file")
    with pytest.raises(InputError, match="cannot read the sweep result .*r.nc"):
        open_sweep(bad)


@pytest.mark.parametrize("flag,value,names", [
    ("--timeout", "-1", ["timeout", "-1"]),
    ("--timeout", "nan", ["timeout", "nan"]),
    ("--timeout", "0", ["timeout", "> 0"]),
    ("--workers", "100000", ["workers = 100000", "cores", "--scheduler"]),
])
def test_bad_executor_arguments_are_one_line(tmp_path, capsys, flag, value, names):
    case = sweep_case(tmp_path)
    out = tmp_path / "x.zarr"
    code, _, err = run_cli(["sweep", case, "--out", out, flag, value, "-q"], capsys)
    assert_clean_failure(code, err, *names)
    assert not out.exists()


_BASE = 'Fn = 1e4\nA = 1.0\nB = 1.5\n'


@pytest.mark.parametrize("body,names", [
    ('method = ["linear", 3]\nmu = 0.3\nxi = [0.0]\n', ["method", "mixes names and numbers"]),
    ('method = "linear"\nmu = 0.3\nxi = ["a", "b"]\n', ["xi", "numbers", "'a'"]),
    ('method = "linear"\nmu = 0.3\nxi = [0.0, "b"]\n', ["xi", "mixes names and numbers"]),
    ('method = "linear"\nmu = [0.3, 5.0]\nxi = [0.0]\n', ["mu = 5", "percentage"]),
    ('method = "linear"\nmu = [0.3, -0.1]\nxi = [0.0]\n', ["mu must be > 0", "-0.1"]),
    ('method = "linear"\nmu = 0.3\ninclination = [0.025]\nxi = [0.0]\n',
     ["inclination", "allowed"]),
    ('method = ["linear", "nope"]\nmu = 0.3\nxi = [0.0]\n', ["nope", "fastsim"]),
])
def test_invalid_specs_are_one_line_under_quiet(tmp_path, capsys, body, names):
    case = tmp_path / "bad.toml"
    case.write_text("[sweep]\n" + _BASE + body)
    code, _, err = run_cli(["sweep", case, "--out", tmp_path / "b.zarr", "-q"], capsys)
    assert_clean_failure(code, err, "bad.toml", *names)


def test_geometry_inclination_axis_of_names_is_one_line(tmp_path, capsys):
    case = tmp_path / "g.toml"
    case.write_text('[sweep]\nevaluator = "geometry"\ny = [0.0]\ninclination = ["1/40"]\n')
    code, _, err = run_cli(["sweep", case, "--out", tmp_path / "g.zarr", "-q"], capsys)
    assert_clean_failure(code, err, "inclination", "numbers", "1/40")


def test_modulus_in_gpa_ends_in_an_error_line(tmp_path, capsys):
    case = tmp_path / "e.toml"
    case.write_text("[sweep]\n" + _BASE + 'method = "linear"\nmu = 0.3\nE = 210.0\n'
                    "xi = [0.0, 0.001]\n")
    code, _, err = run_cli(["sweep", case, "--out", tmp_path / "e.zarr", "-q"], capsys)
    assert code == 1
    assert any("GPa" in ln for ln in err if ln.startswith("wheelrail: warning: "))
    errors = [ln for ln in err if ln.startswith("wheelrail: error: ")]
    assert len(errors) == 1 and "2 of 2 points failed" in errors[0], err
    assert "contact patch" in errors[0] and "e.zarr" in errors[0]
    assert "Traceback" not in "\n".join(err)
