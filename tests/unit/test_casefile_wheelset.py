"""Wheelset case files ([wheelset], [track], [motion], [position]) and the wr.solve routing
of case files (wheelrail.cases.files: case files are only read and validated there; the
solvers run them)."""

from __future__ import annotations

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.cases.files import load_case, load_contact_case
from wheelrail.cases import Case, WheelsetCase, run_case, solve_case, solve_wheelset_case
from wheelrail.errors import CaseFileError, InputError

WS = """
[wheelset]
profile = "S1002"
nominal_radius = 0.46
flange_back = 1.360

[track]
profile = "60E1"
gauge = 1.435
inclination = "1/40"

[motion]
speed = 20.0

[position]
y = 0.003
yaw = 0.0
vertical_load = 10000.0

[friction]
mu = 0.3

[method]
normal = "hertz"
tangential = "fastsim"
"""


def _edit(text, old, new):
    assert old in text, old
    return text.replace(old, new)


def _error(text, tmp_path=None):
    if tmp_path is not None:
        path = tmp_path / "ws.toml"
        path.write_text(text, encoding="utf-8")
        text = str(path)
    with pytest.raises(CaseFileError) as info:
        load_case(text)
    return str(info.value)


# --------------------------------------------------------------------------- reading
def test_reads_all_tables():
    case = load_case(WS)
    assert isinstance(case, WheelsetCase)
    assert case.track.inclination == pytest.approx(1 / 40)
    assert case.wheelset.nominal_radius == 0.46 and case.track.gauge == 1.435
    assert case.motion.speed == 20.0 and case.motion.omega is None     # free rolling
    assert not case.sweep and case.y.tolist() == [0.003]
    assert case.vertical_load == (10000.0, 10000.0) and case.z is None and case.roll is None
    assert (case.normal, case.tangential, case.mu) == (wr.normal.Hertz(), wr.tangential.Fastsim(), 0.3)


def test_sweep_range_list_yaw_per_y_and_load_per_wheel():
    text = _edit(WS, "y = 0.003\nyaw = 0.0\nvertical_load = 10000.0",
                 "y = {start = -0.004, stop = 0.004, num = 5}\nyaw_per_y = 0.5\n"
                 "vertical_load = [9000.0, 11000.0]\nroll = 0.001")
    case = load_case(text)
    assert case.sweep and np.allclose(case.y, [-0.004, -0.002, 0.0, 0.002, 0.004])
    assert np.allclose(case.yaw, 0.5 * case.y)
    assert case.vertical_load == (9000.0, 11000.0) and case.roll == 0.001
    listed = load_case(_edit(WS, "y = 0.003", "y = [0.001, 0.002]"))
    assert listed.sweep and listed.y.tolist() == [0.001, 0.002]


def test_numeric_inclination_motion_and_z():
    text = _edit(_edit(WS, 'inclination = "1/40"', "inclination = 0.02\ncanted = false"),
                 "speed = 20.0", "speed = 20.0\nomega = 43.0\nyaw_rate = 0.01\nroller_radius = 0.7")
    text = _edit(text, "vertical_load = 10000.0", "z = -1e-4")
    case = load_case(text)
    assert case.track.inclination == 0.02 and not case.track.canted
    assert (case.motion.omega, case.motion.yaw_rate, case.motion.roller_radius) == (43.0, 0.01, 0.7)
    assert case.z == -1e-4 and case.vertical_load is None


def test_profile_from_file_relative_to_case(tmp_path):
    wr.profiles.write(wr.profiles.load("S1002"), tmp_path / "wheel.txt")
    (tmp_path / "ws.toml").write_text(_edit(WS, 'profile = "S1002"', 'profile = "wheel.txt"'),
                                      encoding="utf-8")
    case = load_case(tmp_path / "ws.toml")
    assert case.tables["wheelset"]["profile"] == str(tmp_path / "wheel.txt")
    ref = wr.profiles.load("S1002")
    assert np.allclose(case.wheelset.wheel.z, ref.z, atol=1e-7)


@pytest.mark.parametrize("old, new, where, value", [
    ('inclination = "1/40"', 'inclination = "1/0"', "[track] inclination", "'1/0'"),
    ('inclination = "1/40"', "inclination = 0.5", "[track]", "0.5"),
    ("y = 0.003", "y = 3.0", "[position] y", "3.0"),
    ("y = 0.003", "y = {start = 0.004, stop = -0.004, num = 5}", "[position.y] stop", "-0.004"),
    ("y = 0.003", "y = {start = 0.0, stop = 0.004, num = 2.5}", "[position.y] num", "2.5"),
    ("y = 0.003", "y = []", "[position] y", "empty"),
    ("yaw = 0.0", "yaw = 0.3", "[position] yaw", "0.3"),
    ("yaw = 0.0", "yaw = [0.0, 0.1]", "[position] yaw", "2"),
    ("speed = 20.0", "speed = -3.0", "[motion] speed", "-3.0"),
    ("speed = 20.0", 'speed = "fast"', "[motion] speed", "'fast'"),
    ('profile = "S1002"', 'profile = "S1003"', "[wheelset] profile", "'S1003'"),
    ('profile = "60E1"', 'profile = "S1002"', "[track] profile", "'S1002'"),
    ("gauge = 1.435", "gauge = 1435.0", "[track]", "1435.0"),
    ("gauge = 1.435", "gague = 1.435", "[track]", "'gague'"),
    ("vertical_load = 10000.0", "vertical_load = -5.0", "[position] vertical_load", "-5.0"),
    ("vertical_load = 10000.0", "", "[position]", "vertical_load"),
    ("vertical_load = 10000.0", "vertical_load = [1.0, 2.0, 3.0]", "[position] vertical_load",
     "[1.0, 2.0, 3.0]"),
    ('tangential = "fastsim"', 'tangential = "fastsim"\n[method.fastsim]\nnx = 1.5',
     "[method.fastsim] nx", "1.5"),
    ("[friction]", '[method.bem]\nelement_size = -1e-4\n[friction]',
     "[method.bem] element_size", "-0.0001"),
    ("[friction]\nmu = 0.3", "[friction]\nmu = 0.0", "[friction] mu", "0.0"),
])
def test_bad_values_named_with_file_table_key_value(tmp_path, old, new, where, value):
    text = _edit(WS, 'normal = "hertz"', 'normal = "bem"') if "bem" in where else WS
    msg = _error(_edit(text, old, new), tmp_path)
    assert "ws.toml" in msg and where in msg and value in msg, msg


def test_contact_tables_rejected_in_wheelset_case():
    msg = _error(WS + "\n[contact]\nFn = 1.0\nA = 1.0\nB = 1.0\n")
    assert "[contact]" in msg and "wheelset case" in msg


def test_contact_case_loader_refuses_wheelset_case():
    with pytest.raises(CaseFileError, match="wheelrail wheelset"):
        load_contact_case(WS)


# --------------------------------------------------------------------------- solving
def test_single_position_goes_through_wr_solve_and_carries_the_load():
    case = load_case(WS)
    res = solve_wheelset_case(case)
    ref = wr.solve(case.position(0), motion=case.motion, mu=0.3, normal="hertz",
                   tangential="fastsim")
    assert [p.Fn for p in res.patches] == pytest.approx([p.Fn for p in ref.patches], rel=1e-12)
    # vertical equilibrium of each wheel: the total vertical force is the prescribed load
    for side in ("left", "right"):
        assert res.force_track[side][2] == pytest.approx(10000.0, rel=1e-3)
    out = run_case(case)
    assert {"patches", "force_track", "pose", "case"} <= set(out)
    assert out["case"]["track"]["inclination"] == pytest.approx(0.025)
    assert all({"Fn", "Fx", "Fs", "Mz", "p_max", "area", "adhesion_area", "rail_y",
                "contact_angle"} <= set(p) for p in out["patches"])


def test_centred_symmetric_wheelset_gives_mirror_forces():
    """Symmetric wheelset and track at y = 0, free rolling: the lateral forces of the two
    wheels are equal and opposite (mirror symmetry), the longitudinal ones equal."""
    case = load_case(_edit(WS, "y = 0.003", "y = 0.0"))
    res = solve_wheelset_case(case)
    (fxl, fyl, _), (fxr, fyr, _) = res.force_track["left"], res.force_track["right"]
    assert fyl == pytest.approx(-fyr, rel=1e-6, abs=1e-6)
    assert fxl == pytest.approx(fxr, rel=1e-6, abs=1e-6)


def test_sweep_case_gives_dataset():
    text = _edit(WS, "y = 0.003", "y = {start = 0.0, stop = 0.004, num = 3}")
    case = load_case(text)
    ds = solve_wheelset_case(case, progress=False)
    assert np.allclose(ds["y"].values, [0.0, 0.002, 0.004])
    assert list(ds["status"].values) == ["ok"] * 3
    assert ds.attrs["source"] == "<string>"
    with pytest.raises(InputError, match="sweep"):
        run_case(case)


# --------------------------------------------------------------------------- contact cases
CONTACT = """
[contact]
Fn = 7500.0
A = 1.0869565
B = 1.6666667
[creepage]
xi = -0.0007
eta = 0.0002
phi = 0.1
[friction]
mu = 0.2
[method]
normal = "{normal}"
tangential = "{tangential}"
[method.bem]
grid_elements = 24
"""


@pytest.mark.parametrize("tangential", ["fastsim", "linear", "polach", "exact"])
def test_bem_normal_with_any_tangential_close_to_hertz(tangential):
    """normal = "bem" on a Hertzian gap: the BEM patch read by any tangential method gives
    the forces of the Hertz path within the discretisation error of a 24-element grid."""
    hz = solve_case(load_case(CONTACT.format(normal="hertz", tangential=tangential)))
    bem = solve_case(load_case(CONTACT.format(normal="bem", tangential=tangential)))
    assert isinstance(bem.case, Case) and bem.summary["normal_method"] == "bem"
    assert bem.result.patches[0].patch.method == "bem"
    assert bem.summary["Fx"] == pytest.approx(hz.summary["Fx"], rel=0.08)
    assert bem.summary["Fy"] == pytest.approx(hz.summary["Fy"], rel=0.15, abs=20.0)
    assert bem.summary["p_max"] == pytest.approx(hz.summary["p0"], rel=0.05)
