"""Crash-safe outputs: a full disk or a crash while writing leaves no half-written file.

Once, with the disk full, ``--json`` left a 0-byte invalid file. Every writer
goes through a temporary file that is renamed only when complete; here the write or the
sync fails (ENOSPC) and the target must be absent (or unchanged) with no temporary left.
"""

from __future__ import annotations

import errno
import json
import os

import numpy as np
import pytest
from _helpers import assert_clean_failure, assert_no_debris, run_cli

import wheelrail as wr
from wheelrail import _atomic


def _disk_full(*_a, **_k):
    raise OSError(errno.ENOSPC, "No space left on device")


@pytest.fixture
def full_disk(monkeypatch):
    monkeypatch.setattr(_atomic.os, "fsync", _disk_full)


def test_json_on_full_disk_leaves_nothing(tmp_path, full_disk):
    from wheelrail.cli._output import write_json

    target = tmp_path / "r.json"
    with pytest.raises(OSError):
        write_json({"a": 1.0}, target)
    assert not target.exists()
    assert list(tmp_path.iterdir()) == []


def test_existing_file_is_kept_on_failure(tmp_path, full_disk):
    from wheelrail.cli._output import write_json

    target = tmp_path / "r.json"
    target.write_text('{"old": true}\n')
    with pytest.raises(OSError):
        write_json({"new": 1.0}, target)
    assert json.loads(target.read_text()) == {"old": True}
    assert [p.name for p in tmp_path.iterdir()] == ["r.json"]


def test_nan_is_written_as_null_not_as_invalid_json(tmp_path):
    from wheelrail.cli._output import write_json

    write_json({"a": float("nan"), "b": [1.0, float("inf")], "c": {"d": 2.0}}, tmp_path / "r.json")
    assert json.loads((tmp_path / "r.json").read_text()) == {"a": None, "b": [1.0, None],
                                                             "c": {"d": 2.0}}


@pytest.mark.parametrize("writer", ["csv", "netcdf", "figure", "profile-text", "profile-simpack"])
def test_every_writer_is_atomic(writer, tmp_path, full_disk, monkeypatch):
    if writer == "csv":
        from wheelrail.geometry.contact_table import write_csv

        ws = wr.Wheelset(wr.profiles.load("S1002"))
        t = wr.contact_table(ws, wr.Track(wr.profiles.load("60E1")), np.linspace(-1e-3, 1e-3, 3))
        call = lambda p: write_csv(t, p)  # noqa: E731
        name = "t.csv"
    elif writer == "netcdf":
        from wheelrail.geometry.contact_table import write_netcdf

        ws = wr.Wheelset(wr.profiles.load("S1002"))
        t = wr.contact_table(ws, wr.Track(wr.profiles.load("60E1")), np.linspace(-1e-3, 1e-3, 3))
        monkeypatch.setattr(_atomic.os, "replace", _disk_full)  # to_netcdf does not fsync
        call = lambda p: write_netcdf(t, p)  # noqa: E731
        name = "t.nc"
    elif writer == "figure":
        from wheelrail.plotting._common import finish, new_figure

        monkeypatch.setattr(_atomic.os, "replace", _disk_full)
        fig, ax = new_figure()
        call = lambda p: finish(fig, p)  # noqa: E731
        name = "f.png"
    else:
        prof = wr.profiles.load("60E1")
        name = "p.txt" if writer == "profile-text" else "p.prr"
        call = lambda p: wr.profiles.write(prof, p)  # noqa: E731
    with pytest.raises(OSError):
        call(tmp_path / name)
    assert list(tmp_path.iterdir()) == []


def test_cli_full_disk_is_one_error_line(tmp_path, capsys, full_disk):
    p = tmp_path / "case.toml"
    p.write_text("[contact]\nFn = 7500.0\nA = 1.0\nB = 1.5\n[friction]\nmu = 0.3\n")
    out = tmp_path / "res"
    out.mkdir()
    code, _, err = run_cli(["solve", p, "--json", out / "r.json"], capsys)
    assert_clean_failure(code, err, "No space left")
    assert list(out.iterdir()) == []


def test_geometry_outputs_complete_and_mode_kept(tmp_path, capsys):
    out = tmp_path / "geo"
    code, _, err = run_cli(["geometry", "--points", "5", "--out", out], capsys)
    assert code == 0, err
    assert_no_debris(out)
    names = sorted(p.name for p in out.iterdir())
    assert names == sorted(["contact_table.csv", "contact_table.nc", "geometry_summary.json",
                            "profiles_in_contact.png", "delta_r.png", "contact_angle.png",
                            "contact_positions.png"])
    mask = os.umask(0)
    os.umask(mask)
    assert (out / "contact_table.csv").stat().st_mode & 0o777 == 0o666 & ~mask
