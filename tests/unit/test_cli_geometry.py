"""``wheelrail geometry`` command and the demo hook."""

import json

import numpy as np
import pytest

from wheelrail.cli.geometry import geometry_demo, parse_slope
from wheelrail.cli.main import main


def test_geometry_command_writes_table(tmp_path, capsys):
    out = tmp_path / "geo"
    code = main(["geometry", "--points", "21", "--y-range", "-0.004", "0.004", "--no-plots",
                 "--out", str(out)])
    assert code == 0
    assert (out / "contact_table.csv").exists() and (out / "contact_table.nc").exists()
    summary = json.loads((out / "geometry_summary.json").read_text())
    assert summary["points"] == 21
    assert 0.1 < summary["equivalent_conicity"] < 0.25
    assert "equivalent conicity" in capsys.readouterr().out


def test_geometry_command_bad_input(tmp_path, capsys):
    assert main(["geometry", "--inclination", "1/x", "--out", str(tmp_path)]) == 2
    assert "inclination" in capsys.readouterr().err
    assert main(["geometry", "--wheel", "nofile.prw", "--out", str(tmp_path)]) == 2
    assert main(["geometry", "--wheel", "XYZ123", "--out", str(tmp_path)]) == 2


def test_parse_slope():
    assert parse_slope("1/40") == pytest.approx(0.025)
    assert parse_slope("0") == 0.0


def test_geometry_demo_writes_figures(tmp_path):
    res = geometry_demo(tmp_path)
    names = {p.name for p, _ in res["files"]}
    assert {"contact_table.csv", "contact_table.nc", "delta_r.png", "contact_angle.png",
            "contact_positions.png", "profiles_in_contact.png"} <= names
    for p, _ in res["files"]:
        assert p.stat().st_size > 0
    assert 0.1 < res["results"]["equivalent_conicity"] < 0.25
    assert np.all(np.abs(res["results"]["jumps_y"]) <= 0.01)
    json.dumps(res["results"])
