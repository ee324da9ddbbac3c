"""`wheelrail fe CASE.toml`: indentation run writes its outputs; bad case files give one-line errors."""

import json

from wheelrail.cli.main import main

CASE = """
[fe]
wheel = "cylinder"
rail = "60E1"
radius = 0.46
load = 7500.0
mesh_size = 2e-3
depth = 3.0
half_width = 3.0
half_length = 3.0
mode = "indent"
"""


def test_fe_indent_writes_summary_vtu_and_patch(tmp_path, capsys):
    case = tmp_path / "case.toml"
    case.write_text(CASE)
    out = tmp_path / "out"
    assert main(["fe", str(case), "--out", str(out), "--no-figures"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["mode"] == "indent"
    assert abs(summary["Fn"] - 7500.0) < 10.0
    assert 0.5 < summary["p_max"] / summary["hertz"]["p_max"] < 1.2
    assert (out / "mesh.vtu").stat().st_size > 1000
    assert (out / "patch.nc").is_file()
    import meshio
    m = meshio.read(out / "mesh.vtu")
    assert m.cells[0].type == "hexahedron" and "von_mises" in m.cell_data


def test_fe_estimate_only_prints_steps(tmp_path, capsys):
    case = tmp_path / "case.toml"
    case.write_text(CASE.replace('mode = "indent"', 'mode = "roll"'))
    assert main(["fe", str(case), "--estimate-only"]) == 0
    assert "explicit steps" in capsys.readouterr().out


def test_fe_bad_key_is_a_usage_error(tmp_path, capsys):
    case = tmp_path / "case.toml"
    case.write_text(CASE + "mesh_sise = 1.0\n")
    assert main(["fe", str(case)]) == 2
    assert "mesh_sise" in capsys.readouterr().err


def test_fe_indent_figure(tmp_path):
    case = tmp_path / "case.toml"
    case.write_text(CASE)
    out = tmp_path / "out"
    assert main(["fe", str(case), "--out", str(out)]) == 0
    assert (out / "patch.png").stat().st_size > 10_000
