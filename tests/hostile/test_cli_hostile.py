"""Hostile command lines: every case ends with one error line naming the bad value, or runs.

An audit found traceback-free but misleading behaviour; here every
bad argument must give exit code 2 (1 for --strict) and a single line
``wheelrail: error: ...`` that names the offending value — no traceback,
no ``np.float64(...)``, no half-written output.
"""

from __future__ import annotations

import json

import pytest
from _helpers import (SOLVE_CASE, assert_clean_failure, assert_clean_warnings, assert_no_debris,
                      run_cli)

GEO = ["geometry", "--no-plots", "--points", "5"]

# (argv after the command prefix, strings the error line must contain)
GEOMETRY_CASES = [
    (["--inclination", "abc"], ["abc"]),
    (["--inclination", "1/0"], ["1/0"]),
    (["--inclination", "inf"], ["inf"]),
    (["--inclination", "nan"], ["nan"]),
    (["--inclination", "0.5"], ["0.5"]),
    (["--inclination=-1/2"], ["-0.5"]),
    (["--y-range", "-50", "50"], ["-50", "mm given"]),
    (["--y-range", "0.01", "-0.01"], ["increasing"]),
    (["--y-range", "nan", "0.01"], ["nan"]),
    (["--y-range", "-0.06", "0.06"], ["0.06"]),
    (["--points", "0"], ["0"]),
    (["--points", "1"], ["1"]),
    (["--points", "-5"], ["-5"]),
    (["--points", "10000000"], ["10000000"]),
    (["--points", "ten"], ["ten"]),
    (["--yaw", "5"], ["5"]),
    (["--yaw", "nan"], ["nan"]),
    (["--gauge", "1435"], ["1435", "mm given"]),
    (["--gauge", "0"], ["0"]),
    (["--gauge", "-1.435"], ["-1.435"]),
    (["--gauge", "nan"], ["nan"]),
    (["--nominal-radius", "460"], ["460", "mm given"]),
    (["--nominal-radius", "0"], ["0"]),
    (["--nominal-radius", "-0.46"], ["-0.46"]),
    (["--flange-back", "1360"], ["1360", "mm given"]),
    (["--flange-back", "0"], ["0"]),
    (["--amplitude", "0"], ["0"]),
    (["--amplitude", "3"], ["3"]),
    (["--wheel", "no_such_profile.prw"], ["no_such_profile.prw"]),
    (["--wheel", "S1003"], ["S1003"]),
    (["--rail", "60E2"], ["60E2"]),
    (["--wheel", "60E1"], ["wheel", "rail"]),
    (["--rail", "S1002"], ["rail", "wheel"]),
    (["--bogus-option"], ["--bogus-option"]),
]


@pytest.mark.parametrize("extra,names", GEOMETRY_CASES, ids=lambda v: " ".join(v) if isinstance(v, list) else None)
def test_geometry_bad_arguments(extra, names, tmp_path, capsys):
    out = tmp_path / "out"
    code, _, err = run_cli([*GEO, "--out", out, *extra], capsys)
    assert_clean_failure(code, err, *names)
    assert_no_debris(out)


def test_geometry_out_is_a_file(tmp_path, capsys):
    f = tmp_path / "afile"
    f.write_text("x")
    code, _, err = run_cli([*GEO, "--out", f], capsys)
    assert_clean_failure(code, err, "afile", "not a directory")


def test_geometry_unwritable_out(tmp_path, capsys):
    code, _, err = run_cli([*GEO, "--out", "/proc/wheelrail-out"], capsys)
    assert_clean_failure(code, err, "/proc")


def test_geometry_wheel_is_a_directory(tmp_path, capsys):
    code, _, err = run_cli([*GEO, "--out", tmp_path / "o", "--wheel", tmp_path], capsys)
    assert_clean_failure(code, err, str(tmp_path))


def test_geometry_strict_flags_derailed_rows(tmp_path, capsys):
    """±50 mm derails; without --strict exit 0 with a summary."""
    argv = [*GEO, "--y-range", "-0.05", "0.05", "--out", tmp_path / "o"]
    code, out, err = run_cli(argv, capsys)
    assert code == 0 and "derailed" in out and not err
    summary = json.loads((tmp_path / "o" / "geometry_summary.json").read_text())
    assert summary["rows"]["counts"]["derailed"] >= 2
    code, out, err = run_cli([*argv, "--strict"], capsys)
    assert code == 1 and len(err) == 1 and err[0].startswith("wheelrail: error: --strict")
    assert "flagged row" in err[0]


SOLVE_GOOD = SOLVE_CASE


@pytest.fixture
def good_case(tmp_path):
    p = tmp_path / "case.toml"
    p.write_text(SOLVE_GOOD)
    return p


@pytest.mark.parametrize("opt,value,names", [
    ("--json", "out.txt", [".txt"]),
    ("--json", "/proc/x.json", ["/proc"]),
    ("--plot", "fig.xyz", [".xyz"]),
    ("--plot", "fig", ["(none)"]),
    ("--plot", "/proc/fig.png", ["/proc"]),
])
def test_solve_outputs_checked_before_solving(opt, value, names, good_case, tmp_path, capsys,
                                              monkeypatch):
    import wheelrail.cases as cf

    def boom(case):  # the solve must not even start
        raise AssertionError("solved although the output is invalid")

    monkeypatch.setattr(cf, "solve_case", boom)
    monkeypatch.chdir(tmp_path)
    code, _, err = run_cli(["solve", good_case, opt, value], capsys)
    assert_clean_failure(code, err, *names)


@pytest.mark.parametrize("content,names", [
    (None, ["missing.toml"]),
    (b"\x00\x01\x02binary", ["case.toml"]),
    (b"[contact\nload = 1", ["malformed"]),
    (b"", ["contact"]),
])
def test_solve_bad_case_files(content, names, tmp_path, capsys):
    p = tmp_path / ("missing.toml" if content is None else "case.toml")
    if content is not None:
        p.write_bytes(content)
    code, _, err = run_cli(["solve", p], capsys)
    assert_clean_failure(code, err, *names)


def test_solve_case_is_a_directory(tmp_path, capsys):
    code, _, err = run_cli(["solve", tmp_path], capsys)
    assert_clean_failure(code, err, str(tmp_path.name))


CREEP = ["creep-curve", "--points", "5"]


@pytest.mark.parametrize("extra,names", [
    (["--points", "1"], ["1"]),
    (["--points", "0"], ["0"]),
    (["--min", "nan"], ["nan"]),
    (["--max", "inf"], ["inf"]),
    (["--max", "0"], ["0"]),
    (["--methods", "foo"], ["foo"]),
    (["--methods", ",,"], [",,"]),
    (["--component", "zeta"], ["zeta"]),
    (["--component", "eta", "--methods", "carter"], ["carter", "skipped"]),
    (["--out", "curve.xyz"], [".xyz"]),
    (["--csv", "curve.txt"], [".txt"]),
    (["missing_case.toml"], ["missing_case.toml"]),
])
def test_creep_curve_bad_arguments(extra, names, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, _, err = run_cli([*CREEP, *extra], capsys)
    assert_clean_failure(code, err, *names)
    assert "ImportError" not in " ".join(err)
    assert_no_debris(tmp_path)


@pytest.mark.parametrize("value", ["0", "-1GB", "lots", "nan", "5XB"])
def test_bad_memory_limit(value, good_case, capsys):
    code, _, err = run_cli([f"--memory-limit={value}", "solve", good_case], capsys)
    assert_clean_failure(code, err, value)


def test_memory_guard_refuses_with_estimate(tmp_path, capsys):
    """A big BEM solve is refused before allocating, estimate named."""
    p = tmp_path / "big.toml"
    p.write_text(SOLVE_GOOD + '[method]\nnormal = "bem"\ntangential = "fastsim"\n'
                 '[method.bem]\ngrid_elements = 400\n')
    code, _, err = run_cli(["--memory-limit", "200MB", "solve", p], capsys)
    assert_clean_failure(code, err, "memory limit", "MB", "501x501")


def test_warnings_are_one_line_and_piped_output_is_not_wrapped(tmp_path, capsys):
    """No source lines of warnings, no 80-column wrapping in pipes."""
    p = tmp_path / ("a_rather_long_directory_name_" * 3) / "case.toml"
    p.parent.mkdir()
    p.write_text(SOLVE_GOOD.replace("7500.0", "7.5"))
    js = p.parent / "result_with_a_long_name.json"
    code, out, err = run_cli(["solve", p, "--json", js], capsys)
    assert code == 0
    assert_clean_warnings(err)
    assert any("kN meant" in ln for ln in err)
    assert str(js) in out  # the whole path on one line
