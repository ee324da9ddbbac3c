"""FE case files with swapped profiles, implausible values, bad restart intervals and
unknown keys are refused in one line naming the file, the key and the value — before any
mesh is built or any step is run.

References for the limits: wheel–rail friction is 0.05 … 0.6 (Kalker 1990, ch. 1); wheel
and rail steels yield at 300 … 1200 MPa (R900A rail steel: 489 MPa, Toumi, Chollet & Yin,
Wear 366-367 (2016) 157-166, §2); a Simpack profile file says its body in the header
(``type = 0`` rail, ``1`` wheel).
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from _fe_case import INDENT_BASE, indent_case
from _helpers import assert_clean_failure, run_cli

import wheelrail as wr
from wheelrail.cli.fe import case_from_toml
from wheelrail.errors import CaseFileError, InputError
from wheelrail.fe import J2Plastic, RollingCase
from wheelrail.plausibility import ImplausibleInputError, PlausibilityWarning
from wheelrail.profiles.io import declared_kind

#: An indentation case on a coarse mesh (never meshed here: every check comes first).
BASE = INDENT_BASE
STANDARD = indent_case()


@pytest.fixture(autouse=True)
def no_meshing(monkeypatch):
    """Any attempt to build an FE model (rolling or transition) fails the test: the checks
    must come before."""
    import wheelrail.fe.model as M
    import wheelrail.fe.transition as T

    def forbidden(*a, **k):
        raise AssertionError("an FE model was built before the input was refused")

    monkeypatch.setattr(M, "build_model", forbidden)
    monkeypatch.setattr(M, "mesh_size_estimate", forbidden)
    monkeypatch.setattr(T, "build_transition_model", forbidden)


def _fe(tmp_path, capsys, text, *extra, name="c.toml"):
    p = tmp_path / name
    p.write_text(text)
    return run_cli(["fe", p, "--out", tmp_path / "out", *extra], capsys)


def _profile_files(tmp_path):
    """S1002 (EN 13715) and 60E1 (EN 13674-1) as Simpack files (header type 1 / 0) and as
    plain text files that do not say their body."""
    wheel, rail = wr.profiles.load("S1002"), wr.profiles.load("60E1")
    wr.profiles.write(wheel, tmp_path / "w.prw")
    wr.profiles.write(rail, tmp_path / "r.prr")
    for p, name in ((wheel, "w_plain.txt"), (rail, "r_plain.txt")):
        (tmp_path / name).write_text("# units: m\n" + "\n".join(
            f"{a:.7f} {b:.7f}" for a, b in zip(p.y, p.z)) + "\n")


# --------------------------------------------------------------------------- swapped profiles
@pytest.mark.parametrize("wheel,rail,names", [
    ("r.prr", "w.prw", ["wheel = 'r.prr'", "rail profile", "Simpack header type = 0",
                        "rail = 'r.prr'", "swapped"]),
    ("w.prw", "w.prw", ["rail = 'w.prw'", "wheel profile", "Simpack header type = 1",
                        "swapped"]),
    ("60E1", "S1002", ["wheel = '60E1'", "standard rail profile", "swapped"]),
    ("S1002", "S1002", ["rail = 'S1002'", "standard wheel profile", "swapped"]),
    ("r_plain.txt", "w_plain.txt", ["wheel = 'r_plain.txt'", "reads as a rail profile",
                                    "flange is cut off", "swapped"]),
    ("w_plain.txt", "w_plain.txt", ["rail = 'w_plain.txt'", "reads as a wheel profile",
                                    "head points down", "swapped"]),
])
def test_swapped_profiles_are_refused_naming_the_file(tmp_path, capsys, wheel, rail, names):
    _profile_files(tmp_path)
    code, _, err = _fe(tmp_path, capsys, BASE + f'wheel = "{wheel}"\nrail = "{rail}"\n')
    assert_clean_failure(code, err, "c.toml", "[fe]", *names)


def test_profiles_the_right_way_round_still_read(tmp_path):
    _profile_files(tmp_path)
    for wheel, rail in (("w.prw", "r.prr"), ("w_plain.txt", "r_plain.txt")):
        f = tmp_path / "ok.toml"
        f.write_text(BASE + f'wheel = "{wheel}"\nrail = "{rail}"\n')
        case, mode = case_from_toml(f)
        assert (case.wheel.kind, case.rail.kind, mode) == ("wheel", "rail", "indent")
        # the same points as the standard profiles (the files are these profiles)
        ref = wr.profiles.load("S1002")
        assert np.interp(0.0, case.wheel.y, case.wheel.z) == pytest.approx(
            np.interp(0.0, ref.y, ref.z), abs=1e-6)


def test_declared_kind_names_where_it_was_found(tmp_path):
    _profile_files(tmp_path)
    assert declared_kind(tmp_path / "r.prr") == ("rail", "its Simpack header type = 0")
    assert declared_kind(tmp_path / "w.prw") == ("wheel", "its Simpack header type = 1")
    assert declared_kind(tmp_path / "w_plain.txt") == (None, "")
    (tmp_path / "k.txt").write_text("# kind: rail\n0 0\n0.01 0\n0.02 0\n0.03 0\n")
    assert declared_kind(tmp_path / "k.txt") == ("rail", "its '# kind: rail' comment")
    (tmp_path / "e.ban").write_text("0 0\n")
    assert declared_kind(tmp_path / "e.ban") == ("rail", "its extension .ban")


# --------------------------------------------------------------------------- friction
def test_mu_of_five_is_refused_with_the_plausible_range(tmp_path, capsys):
    code, _, err = _fe(tmp_path, capsys, STANDARD + "mu = 5.0\n")
    assert_clean_failure(code, err, "c.toml", "[fe]", "mu = 5", "0.05 … 0.6", "percentage")


def test_mu_in_a_transition_case_is_checked_too(tmp_path, capsys):
    code, _, err = _fe(tmp_path, capsys, '[fe]\ntransition = "reduced"\nmu = 30.0\n')
    assert_clean_failure(code, err, "c.toml", "[fe]", "mu = 30", "0.05 … 0.6")


def test_mu_api_warns_above_one_and_accepts_zero():
    w, r = wr.profiles.load("S1002"), wr.profiles.load("60E1")
    with pytest.warns(PlausibilityWarning, match="mu = 1.5 is above 1"):
        RollingCase(wheel=w, rail=r, radius=0.46, Fn=7500.0, mu=1.5)
    with pytest.raises(ImplausibleInputError, match="mu = 5"):
        RollingCase(wheel=w, rail=r, radius=0.46, Fn=7500.0, mu=5.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlausibilityWarning)
        RollingCase(wheel=w, rail=r, radius=0.46, Fn=7500.0, mu=0.0)   # frictionless
        RollingCase(wheel=w, rail=r, radius=0.46, Fn=7500.0, mu=0.3)


# --------------------------------------------------------------------------- yield stress
@pytest.mark.parametrize("value,names", [
    ("489.0", ["yield_stress = 489 Pa", "MPa given? 489 MPa = 4.89e+08 Pa"]),
    ("489000.0", ["yield_stress = 4.89e+05 Pa", "kPa given? 4.89e+05 kPa = 4.89e+08 Pa"]),
    ("0.489", ["yield_stress = 0.489 Pa", "GPa given? 0.489 GPa = 4.89e+08 Pa"]),
    ("2.1e11", ["yield_stress = 2.1e+11 Pa", "a modulus given?"]),
])
def test_yield_stress_in_the_wrong_unit_is_refused(tmp_path, capsys, value, names):
    code, _, err = _fe(tmp_path, capsys, STANDARD + f"yield_stress = {value}\n")
    assert_clean_failure(code, err, "c.toml", "[fe]", "300 … 1200 MPa", *names)


def test_yield_stress_api():
    # p_max of the 7.5 kN case is 518 MPa (Toumi et al. 2016, Table 1 load): a yield stress
    # of 489 Pa would make every element yield; 489 MPa is the R900A value
    with pytest.raises(ImplausibleInputError, match="MPa given"):
        J2Plastic(2.1e11, 0.28, 489.0)
    with pytest.warns(PlausibilityWarning, match="below 1e\\+08 Pa"):
        J2Plastic(2.1e11, 0.28, 5e7)
    with pytest.warns(PlausibilityWarning, match="GPa or MPa meant"):
        J2Plastic(210.0e3, 0.28, 489e6)       # E in MPa: the modulus check applies here too
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlausibilityWarning)
        assert J2Plastic(2.1e11, 0.28, 489e6).yield_stress == 489e6
    with wr.plausibility.disabled():
        assert J2Plastic(2.1e11, 0.28, 489.0).yield_stress == 489.0


# --------------------------------------------------------------------------- restart interval
@pytest.mark.parametrize("value", ["0", "-1", "-100", "x", "2.5"])
def test_restart_every_must_be_a_positive_step_count(tmp_path, capsys, value):
    code, _, err = _fe(tmp_path, capsys, STANDARD.replace("indent", "roll"),
                       f"--restart-every={value}")
    assert_clean_failure(code, err, "--restart-every", "steps >= 1", value)
    assert not (tmp_path / "out").exists()


def test_restart_every_api_refused_before_any_step():
    case = wr.fe.seed000_case("printed", mesh_size=2e-3)
    for bad in (0, -1, 2.5, True):
        with pytest.raises(InputError, match=r"restart_every must be an integer >= 1"):
            wr.fe.solve(case, restart_every=bad, progress=False)
    tcase = wr.fe.seed004_case()
    with pytest.raises(InputError, match=r"restart_every must be an integer >= 0"):
        wr.fe.transition.run_transition(tcase, restart_every=-1)


@pytest.mark.parametrize("value", ["-1", "0", "nan", "inf"])
def test_stop_travel_must_be_a_positive_length(tmp_path, capsys, value):
    code, _, err = _fe(tmp_path, capsys, '[fe]\ntransition = "reduced"\n',
                       f"--stop-travel={value}")
    assert_clean_failure(code, err, "--stop-travel", "> 0 in metres", value)


# --------------------------------------------------------------------------- unknown keys
@pytest.mark.parametrize("text,table,allowed", [
    ('[fe]\ntransition = "reduced"\n[fe.suspension]\nfoo = 1.0\n', "[fe.suspension]",
     ["sprung_mass", "lateral_stiffness", "roll_stiffness"]),
    ('[fe]\ntransition = "reduced"\n[fe.track]\nsleeper_spaceing = 0.6\n', "[fe.track]",
     ["sleeper_spacing", "n_sleepers"]),
    ('[fe]\ntransition = "reduced"\nangle_of_atack = 0.02\n', "[fe]",
     ["angle_of_attack", "track", "suspension"]),
    (STANDARD + "mesh_sise = 1e-3\n", "[fe]", ["mesh_size", "yield_stress", "wheel_taper"]),
    (STANDARD + "[fe.suspension]\nsprung_mass = 1.0\n", "[fe]", ["mesh_size"]),
])
def test_unknown_key_lists_the_allowed_keys(tmp_path, capsys, text, table, allowed):
    code, _, err = _fe(tmp_path, capsys, text)
    assert_clean_failure(code, err, "c.toml", table, "unknown key", "allowed:", *allowed)
    assert "__init__" not in err[-1] and "unexpected keyword" not in err[-1]


def test_bad_value_in_a_sub_table_names_the_table(tmp_path):
    f = tmp_path / "t.toml"
    f.write_text('[fe]\ntransition = "reduced"\n[fe.track]\nn_sleepers = "two"\n')
    with pytest.raises(CaseFileError, match=r"t\.toml: \[fe\.track\]"):
        case_from_toml(f)


def test_old_load_key_is_a_renamed_key_warning(tmp_path):
    from wheelrail.cases.files._reader import RenamedKeyWarning

    f = tmp_path / "old.toml"
    f.write_text(STANDARD.replace("Fn = 7500.0", "load = 7500.0"))
    with pytest.warns(RenamedKeyWarning, match="'load' is deprecated, use 'Fn'"):
        case, _ = case_from_toml(f)
    assert case.Fn == 7500.0
