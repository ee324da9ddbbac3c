"""``wheelrail wheelset CASE.toml``: one position, a sweep, outputs and exit codes."""

from __future__ import annotations

import csv
import json

import numpy as np
import pytest

from wheelrail.cli.main import main

PNG = b"\x89PNG\r\n\x1a\n"

CASE = """
[wheelset]
profile = "S1002"
[track]
profile = "60E1"
inclination = "1/40"
[motion]
speed = 20.0
omega = 43.43
[position]
y = {y}
yaw = 0.002
vertical_load = 10000.0
[friction]
mu = 0.3
"""


def _write(tmp_path, text, name="ws.toml"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return str(path)


def _one_line_error(capsys):
    err = capsys.readouterr().err.strip()
    assert err.startswith("wheelrail: error:") and "\n" not in err, err
    return err


def test_registered():
    from wheelrail.cli.main import COMMANDS

    assert ("wheelset", "wheelrail.cli.wheelset") in COMMANDS


def test_single_position_table_json_and_figures(tmp_path, capsys):
    case = _write(tmp_path, CASE.format(y="0.005"))
    out = tmp_path / "out"
    assert main(["wheelset", case, "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "left 1" in text and "right 1" in text and "contact angle" in text
    assert "track frame" in text
    res = json.loads((out / "wheelset.json").read_text())
    assert res["normal"] == "hertz" and res["tangential"] == "fastsim"
    # vertical equilibrium per wheel (total vertical force = prescribed load)
    for side in ("left", "right"):
        assert res["force_track"][side]["Fz"] == pytest.approx(10000.0, rel=1e-3)
    # y = 5 mm to the right: the right wheel runs on its flange root, the left on its tread
    right = [p for p in res["patches"] if p["side"] == "right"]
    left = [p for p in res["patches"] if p["side"] == "left"]
    assert max(p["contact_angle"] for p in right) > 0.2 > max(p["contact_angle"] for p in left)
    assert res["case"]["position"]["vertical_load"] == [10000.0, 10000.0]
    for name in ("contact_profiles.png", "adhesion.png"):
        assert (out / name).read_bytes()[:8] == PNG


def test_sweep_writes_netcdf_csv_and_figure(tmp_path, capsys):
    xr = pytest.importorskip("xarray")
    case = _write(tmp_path, CASE.format(y="{start = -0.002, stop = 0.002, num = 3}"))
    out = tmp_path / "sweep"
    assert main(["wheelset", case, "--out", str(out), "--sweep", "-q"]) == 0
    assert capsys.readouterr().out == ""
    with xr.open_dataset(out / "sweep.nc", engine="scipy") as ds:
        assert np.allclose(ds["y"].values, [-0.002, 0.0, 0.002])
        fz = ds["Fz_track"].values
    assert np.allclose(fz, 10000.0, rtol=1e-3)
    rows = list(csv.DictReader(open(out / "sweep.csv", encoding="utf-8")))
    assert len(rows) == 3 and float(rows[2]["y"]) == pytest.approx(0.002)
    assert float(rows[1]["Fz_track_left"]) == pytest.approx(fz[1, 0])
    assert rows[0]["status"] == "ok"
    assert (out / "sweep_forces.png").read_bytes()[:8] == PNG


def test_sweep_csv_only_no_plots(tmp_path):
    case = _write(tmp_path, CASE.format(y="[0.0, 0.001]"))
    out = tmp_path / "o"
    assert main(["wheelset", case, "--out", str(out), "--csv", "--no-plots", "-q"]) == 0
    assert (out / "sweep.csv").exists()
    assert not (out / "sweep.nc").exists() and not (out / "sweep_forces.png").exists()


def test_sweep_flag_needs_a_range(tmp_path, capsys):
    case = _write(tmp_path, CASE.format(y="0.001"))
    assert main(["wheelset", case, "--sweep", "--out", str(tmp_path / "o")]) == 2
    err = _one_line_error(capsys)
    assert "ws.toml" in err and "[position] y" in err and "0.001" in err


def test_bad_case_exit_2_names_file_table_key_value(tmp_path, capsys):
    case = _write(tmp_path, CASE.format(y="0.001").replace("speed = 20.0", "speed = -20.0"))
    assert main(["wheelset", case, "--out", str(tmp_path / "o")]) == 2
    err = _one_line_error(capsys)
    assert "ws.toml" in err and "[motion] speed" in err and "-20.0" in err


def test_contact_case_refused_and_wheelset_case_refused_by_solve(tmp_path, capsys):
    contact = _write(tmp_path, "[contact]\nFn = 1e4\nA = 1.0\nB = 1.0\n[friction]\nmu = 0.3\n",
                     "c.toml")
    assert main(["wheelset", contact, "--out", str(tmp_path / "o")]) == 2
    assert "not a wheelset case" in _one_line_error(capsys)
    ws = _write(tmp_path, CASE.format(y="0.001"))
    assert main(["solve", ws]) == 2
    assert "wheelrail wheelset" in _one_line_error(capsys)


def test_wheel_lifted_off_exit_2_and_failed_sweep_exit_1(tmp_path, capsys):
    """An axle height that lifts the wheels off their rails is bad input for one position
    (exit 2, the value named); a sweep records it per row and fails (exit 1) only when no
    position could be solved."""
    lifted = CASE.replace("vertical_load = 10000.0", "z = 0.01")
    one = _write(tmp_path, lifted.format(y="0.001"))
    assert main(["wheelset", one, "--out", str(tmp_path / "o")]) == 2
    assert "0.01" in _one_line_error(capsys)
    allbad = _write(tmp_path, lifted.format(y="[0.0, 0.001]"), "bad.toml")
    assert main(["wheelset", allbad, "--out", str(tmp_path / "o2"), "-q"]) == 1
    assert "no position" in _one_line_error(capsys)
