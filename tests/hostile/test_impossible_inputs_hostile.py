"""Impossible geometry and options are refused (or warned) naming the value and the likely unit.

References for the limits: standard wheelsets have a flange back of 1.360 m on a
1.435 m gauge (EN 13715, EN 13848), i.e. 75 mm for both flanges and their play; a
free-rolling wheel turns at ω = V/r0 with r0 of 0.05–2 m; a creepage is a relative
slip (|ξ| ≤ 1 for any rolling contact).
"""

from __future__ import annotations

import warnings

import pytest
from _helpers import assert_clean_failure, run_cli, wheelset_case

import wheelrail as wr
from wheelrail.plausibility import ImplausibleInputError, PlausibilityWarning

GEO = ["geometry", "--no-plots", "--points", "3"]


@pytest.mark.parametrize("argv,names", [
    (["--gauge", "1000"], ["gauge", "1000", "mm given"]),
    (["--flange-back", "1.5"], ["flange_back = 1.5", "not smaller than the gauge 1.435"]),
    (["--flange-back", "1.0"], ["flange_back = 1", "435 mm", "another gauge"]),
])
def test_geometry_refuses_impossible_gauge_and_flange_back(tmp_path, capsys, argv, names):
    code, _, err = run_cli([*GEO, *argv, "--out", tmp_path / "o"], capsys)
    assert_clean_failure(code, err, *names)


def test_geometry_warns_for_a_yaw_of_a_tenth_radian(tmp_path, capsys):
    code, _, err = run_cli([*GEO, "--yaw", "0.1", "--out", tmp_path / "o"], capsys)
    assert code == 0
    warns = [ln for ln in err if "yaw = 0.1 rad" in ln]
    assert warns and "5.73°" in warns[0] and "degrees or mrad" in warns[0], err


def test_api_yaw_and_flange_back():
    ws = wr.Wheelset(wr.profiles.load("S1002"), flange_back=1.0)
    tr = wr.Track(wr.profiles.load("60E1"))
    with pytest.raises(ImplausibleInputError, match="435 mm"):
        wr.contact_points(ws, tr, 0.0)
    ws = wr.Wheelset(wr.profiles.load("S1002"))
    with pytest.warns(PlausibilityWarning, match="degrees or mrad"):
        wr.contact_points(ws, tr, 0.0, yaw=0.1)
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlausibilityWarning)
        wr.contact_points(ws, tr, 0.0, yaw=0.005)         # a normal yaw: silent


def test_wheelset_case_with_flange_back_of_one_metre(tmp_path, capsys):
    p = tmp_path / "c.toml"
    p.write_text(wheelset_case().replace('profile = "S1002"', 'profile = "S1002"\n'
                                         "flange_back = 1.0", 1))
    code, _, err = run_cli(["wheelset", p, "--out", tmp_path / "o"], capsys)
    assert_clean_failure(code, err, "c.toml", "[wheelset]", "flange_back = 1", "another gauge")


def test_wheelset_omega_in_the_wrong_unit(tmp_path, capsys):
    p = tmp_path / "c.toml"
    p.write_text(wheelset_case(motion="omega = 1e6"))
    code, _, err = run_cli(["wheelset", p, "--out", tmp_path / "o"], capsys)
    assert_clean_failure(code, err, "c.toml", "[motion]", "omega = 1e+06", "rpm or deg/s")
    # 415 rpm meant for 43.5 rad/s (20 m/s on r0 = 0.46 m): warned, with the conversion
    with pytest.warns(PlausibilityWarning, match=r"415 rpm = 43.46 rad/s"):
        wr.Motion(speed=20.0, omega=415.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlausibilityWarning)
        wr.Motion(speed=20.0, omega=20.0 / 0.46 * 1.01)  # 1 % braking slip: silent


@pytest.mark.parametrize("argv,names", [
    (["--max", "1e6"], ["--max", "xi = 1e+06", "percentage"]),
    (["--component", "phi", "--max", "1e6"], ["--max", "phi = 1e+06", "1/mm"]),
    (["--min", "-5"], ["--min", "xi = 5"]),
])
def test_creep_curve_refuses_a_range_that_is_no_creepage(tmp_path, capsys, argv, names):
    code, _, err = run_cli(["creep-curve", *argv, "--out", tmp_path / "c.png"], capsys)
    assert_clean_failure(code, err, *names)
    assert not (tmp_path / "c.png").exists()


@pytest.mark.parametrize("methods", ["", ",", " , "])
def test_compare_with_an_empty_method_list(tmp_path, capsys, methods):
    p = tmp_path / "c.toml"
    p.write_text(wheelset_case())
    code, _, err = run_cli(["compare", p, "--methods", methods, "--out", tmp_path / "o",
                            "--no-plots"], capsys)
    assert_clean_failure(code, err, "--methods is empty", "bem+exact")


def test_compare_with_one_method_warns(tmp_path, capsys):
    p = tmp_path / "c.toml"
    p.write_text(wheelset_case())
    code, _, err = run_cli(["compare", p, "--methods", "hertz", "--side", "right",
                            "--out", tmp_path / "o", "--no-plots"], capsys)
    assert code == 0, err
    assert any("one method compares with nothing" in ln for ln in err), err


@pytest.mark.parametrize("steps", ["", ",", " ,, "])
def test_demo_with_an_empty_step_list(tmp_path, capsys, steps):
    code, _, err = run_cli(["demo", "--steps", steps, "--out", tmp_path / "d"], capsys)
    assert_clean_failure(code, err, "--steps is empty", "hertz")
    assert not (tmp_path / "d").exists()


def test_demo_output_path_with_markup(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, out, err = run_cli(["demo", "--steps", "case", "--out", "d[/bold]x"], capsys)
    assert code == 0, err
    assert "d[/bold]x/case.toml" in out
    assert (tmp_path / "d[" / "bold]x" / "case.toml").exists()
