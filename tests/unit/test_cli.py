"""The ``wheelrail`` command, run in-process through ``wheelrail.cli.main.main``."""

from __future__ import annotations

import csv
import json

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.cli.main import COMMANDS, main

PNG = b"\x89PNG\r\n\x1a\n"

# circular contact (A = B), nu = 0.25: Kalker's C11 = 4.12 for a/b = 1
# (Kalker 1990, Table E.3; also Johnson, Contact Mechanics, Table 8.1)
SPHERE = """
[material]
E = 2.0e11
nu = 0.25
[contact]
Fn = 10000.0
A = 1.25
B = 1.25
[creepage]
xi = 2.0e-4
[friction]
mu = 0.3
[method]
tangential = "{method}"
"""


def _write(tmp_path, text, name="case.toml"):
    path = tmp_path / name
    path.write_text(text)
    return str(path)


def _one_line_error(capsys) -> str:
    err = capsys.readouterr().err.strip()
    assert err.startswith("wheelrail: error: "), err
    assert "\n" not in err, err
    assert "Traceback" not in err
    return err


def test_commands_table_lists_the_modules():
    assert [name for name, _ in COMMANDS][:3] == ["solve", "creep-curve", "demo"]


def test_version(capsys):
    assert main(["--version"]) == 0
    assert wr.__version__ in capsys.readouterr().out


def test_python_dash_m_is_the_console_script():
    """``python -m wheelrail`` runs the same CLI: version, help and the exit code of bad input."""
    import subprocess
    import sys

    run = lambda *a: subprocess.run([sys.executable, "-m", "wheelrail", *a],  # noqa: E731
                                    capture_output=True, text=True, timeout=120)
    v = run("--version")
    assert v.returncode == 0 and v.stdout.strip() == f"wheelrail {wr.__version__}"
    h = run("--help")
    assert h.returncode == 0 and "creep-curve" in h.stdout
    bad = run("solve", "no-such-file.toml")
    assert bad.returncode == 2 and "no-such-file.toml" in bad.stderr
    from importlib.metadata import version
    assert version("wheelrail") == wr.__version__       # one version source (pyproject reads it)


def test_solve_writes_json_in_si(tmp_path, capsys):
    case = _write(tmp_path, SPHERE.format(method="linear"))
    out = tmp_path / "out.json"
    assert main(["solve", case, "--json", str(out)]) == 0
    assert "Fx" in capsys.readouterr().out  # the table
    res = json.loads(out.read_text())
    for key in ("a", "b", "p0", "penetration", "Fn", "Fx", "Fy", "Mz", "xi", "eta", "phi", "mu",
                "method", "status", "iterations", "area", "p_max"):
        assert key in res, key
    c = wr.hertz(10000.0, 1.25, 1.25, wr.Material(2.0e11, 0.25))
    assert res["a"] == pytest.approx(c.a, rel=1e-12)  # metres, ~4 mm
    assert 1e-3 < res["a"] < 1e-2
    assert res["p0"] == pytest.approx(c.p0, rel=1e-12)  # pascals, ~0.7 GPa
    assert 1e8 < res["p0"] < 1e10
    assert res["Fn"] == 10000.0 and res["mu"] == 0.3 and res["method"] == "linear"
    # linear theory Fx = -G a^2 C11 xi with the published C11 = 4.12 (3 digits)
    G = 2.0e11 / (2 * 1.25)
    assert res["Fx"] == pytest.approx(-G * c.a**2 * 4.12 * 2.0e-4, rel=3e-3)
    assert res["Fy"] == pytest.approx(0.0, abs=1e-9) and res["Mz"] == pytest.approx(0.0, abs=1e-12)
    assert res["units"]["Fx"] == "N"


def test_solve_plot_pressure_for_closed_form_method(tmp_path):
    case = _write(tmp_path, SPHERE.format(method="linear"))
    png = tmp_path / "p.png"
    assert main(["solve", case, "--plot", str(png), "-q"]) == 0
    assert png.read_bytes()[:8] == PNG


def test_solve_plot_fastsim_fields(tmp_path, capsys):
    case = _write(tmp_path, SPHERE.format(method="fastsim") + "[method.fastsim]\nnx = 8\nny = 8\n")
    png = tmp_path / "f.png"
    assert main(["solve", case, "--plot", str(png), "--json", str(tmp_path / "f.json")]) == 0
    assert "traction field" in capsys.readouterr().out
    assert png.read_bytes()[:8] == PNG
    res = json.loads((tmp_path / "f.json").read_text())
    assert 0.0 < res["adhesion_area"] < res["area"]


def test_solve_bem_exact_writes_traction_and_pressure_figures(tmp_path):
    text = (SPHERE.format(method="exact").replace("[method]\n", '[method]\nnormal = "bem"\n')
            + "[method.bem]\ngrid_elements = 21\n")
    assert 'normal = "bem"' in text
    case = _write(tmp_path, text)
    png = tmp_path / "t.png"
    assert main(["solve", case, "--plot", str(png), "--json", str(tmp_path / "t.json"), "-q"]) == 0
    assert png.read_bytes()[:8] == PNG
    assert (tmp_path / "t_pressure.png").read_bytes()[:8] == PNG
    res = json.loads((tmp_path / "t.json").read_text())
    for key in ("area", "p_max", "adhesion_area", "iterations"):
        assert key in res, key


def test_bad_case_file_exit_2_one_line(tmp_path, capsys):
    case = _write(tmp_path, SPHERE.format(method="linear").replace("Fn = 10000.0",
                                                                    "Fn = -5.0"))
    assert main(["solve", case]) == 2
    err = _one_line_error(capsys)
    assert "[contact] Fn" in err and "-5.0" in err and "case.toml" in err


def test_malformed_toml_exit_2(tmp_path, capsys):
    case = _write(tmp_path, "[contact]\nFn = = 3\n")
    assert main(["solve", case]) == 2
    assert "line 2" in _one_line_error(capsys)


def test_missing_file_exit_2(tmp_path, capsys):
    assert main(["solve", str(tmp_path / "nope.toml")]) == 2
    assert "nope.toml" in _one_line_error(capsys)


def test_bad_arguments_exit_2(capsys):
    assert main(["solve"]) == 2
    assert "CASE.toml" in _one_line_error(capsys)
    assert main(["frobnicate"]) == 2
    assert "frobnicate" in _one_line_error(capsys)


def test_runtime_error_exit_1_and_debug_traceback(tmp_path, capsys):
    """A solver that does not converge is a runtime error (exit 1), not a bad input."""
    case = _write(tmp_path, SPHERE.format(method="exact").replace(
        "[method]", "[method.exact]\nmaxiter = 1\nelements = 10\n[method]")
        .replace("xi = 0.0002", "xi = 0.002\neta = 0.001"))
    assert main(["solve", case]) == 1
    assert "converge" in _one_line_error(capsys)
    with pytest.raises(wr.WheelrailError):
        main(["--debug", "solve", case])
    with pytest.raises(wr.WheelrailError):
        main(["solve", case, "--debug"])


def test_creep_curve_png_and_csv(tmp_path, capsys):
    case = _write(tmp_path, SPHERE.format(method="linear"))
    png, table = tmp_path / "c.png", tmp_path / "c.csv"
    assert main(["creep-curve", case, "--component", "xi", "--max", "0.002", "--points", "11",
                 "--methods", "linear", "--out", str(png), "--csv", str(table)]) == 0
    assert png.read_bytes()[:8] == PNG
    rows = list(csv.DictReader(table.open()))
    assert len(rows) == 11
    xi = np.array([float(r["xi"]) for r in rows])
    assert xi[0] == 0.0 and xi[-1] == pytest.approx(0.002)
    # linear: Fx/(mu Fn) = -G a^2 C11 xi / (mu Fn), C11 = 4.12 (Kalker 1990, Table E.3)
    c = wr.hertz(10000.0, 1.25, 1.25, wr.Material(2.0e11, 0.25))
    expect = -(2.0e11 / 2.5) * c.a**2 * 4.12 * xi / (0.3 * 10000.0)
    got = np.array([float(r["linear_Fx_norm"]) for r in rows])
    np.testing.assert_allclose(got, expect, rtol=3e-3, atol=1e-12)


def test_creep_curve_default_case_several_methods(tmp_path, capsys):
    png = tmp_path / "d.png"
    assert main(["creep-curve", "--component", "eta", "--points", "5", "--out", str(png)]) == 0
    out = capsys.readouterr().out
    assert "linear" in out
    assert png.read_bytes()[:8] == PNG


def test_creep_curve_unknown_method_exit_2(tmp_path, capsys):
    assert main(["creep-curve", "--methods", "linear,fastsimm", "--out",
                 str(tmp_path / "x.png")]) == 2
    assert "'fastsimm'" in _one_line_error(capsys)


def test_creep_curve_full_slip_limit(tmp_path):
    """Far beyond saturation every bounded law gives |Fx| -> mu Fn (Coulomb); FASTSIM's
    strip sum of the pressure differs from Fn by O(1/nx^2), hence the tolerance."""
    table = tmp_path / "s.csv"
    assert main(["creep-curve", "--methods", "fastsim", "--min", "0.05", "--max", "0.1",
                 "--points", "3", "--out", str(tmp_path / "s.png"), "--csv", str(table)]) == 0
    rows = list(csv.DictReader(table.open()))
    for r in rows:
        assert float(r["fastsim_Fx_norm"]) == pytest.approx(-1.0, abs=5e-3)


def test_demo_writes_its_files(tmp_path, capsys):
    out = tmp_path / "demo"
    code = main(["demo", "--out", str(out)])
    assert code == 0
    res = json.loads((out / "results.json").read_text())
    assert set(res["steps"].values()) == {"ok"}, res["steps"]  # no step skipped or failed
    c = wr.hertz(7500.0, 0.5 / 0.46, 0.5 / 0.30, wr.Material(2.1e11, 0.28))
    assert res["hertz"]["a"] == pytest.approx(c.a, rel=1e-12)
    assert "linear" in res["creep_forces"]
    assert wr.load_case(out / "case.toml").contact.Fn == 7500.0
    for name in ("results.json", "creep_curves.png", "hertz_table.csv"):
        assert (out / name).is_file(), name
    assert (out / "creep_curves.png").read_bytes()[:8] == PNG
    rows = list(csv.DictReader((out / "hertz_table.csv").open()))
    # Hertz scaling a ∝ N^(1/3) (Johnson 1985, eq. 3.64)
    n0, n1 = (float(rows[i]["load_N"]) for i in (0, -1))
    a0, a1 = (float(rows[i]["a_m"]) for i in (0, -1))
    assert a1 / a0 == pytest.approx((n1 / n0) ** (1 / 3), rel=1e-9)
    assert (out / "fastsim_fields.png").read_bytes()[:8] == PNG
    assert str(out) in capsys.readouterr().out.replace("\n", "")


def test_demo_unknown_step_exit_2(tmp_path, capsys):
    assert main(["demo", "--out", str(tmp_path), "--steps", "hertz,nosuch"]) == 2
    assert "nosuch" in _one_line_error(capsys)
