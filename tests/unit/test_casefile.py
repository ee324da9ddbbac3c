"""Case files: schema, validation messages and run_case (wheelrail.cases.files)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.cases.files import case_from_dict, load_case
from wheelrail.cases import Case, run_case, solve_case
from wheelrail.errors import CaseFileError

FULL = """
[material]
E = 2.1e11
nu = 0.28

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
normal = "hertz"
tangential = "linear"
"""

REQUIRED_KEYS = {"a", "b", "p0", "penetration", "Fn", "Fx", "Fy", "Mz", "xi", "eta", "phi",
                 "mu", "method", "status", "iterations", "area"}


def _edit(text, old, new):
    assert old in text
    return text.replace(old, new)


# --------------------------------------------------------------------------- valid cases
def test_full_case_from_file(tmp_path):
    path = tmp_path / "case.toml"
    path.write_text(FULL)
    case = load_case(path)
    assert isinstance(case, Case)
    assert case.source == str(path)
    assert case.materials == wr.MaterialPair.same(wr.Material(2.1e11, 0.28))
    assert case.contact.kind == "curvatures"
    assert (case.contact.Fn, case.contact.A, case.contact.B) == (7500.0, 1.0869565, 1.6666667)
    assert case.creepage == (-0.0007, 0.0002, 0.1)
    assert case.mu == 0.2
    assert (case.normal, case.tangential) == (wr.normal.Hertz(), wr.tangential.Linear())
    assert dict(case.forces) == {}
    with pytest.raises(Exception):  # frozen
        case.mu = 0.3


def test_text_and_path_give_the_same_case(tmp_path):
    path = tmp_path / "case.toml"
    path.write_text(FULL)
    a, b = load_case(path), load_case(FULL)
    assert (a.materials, a.contact, a.creepage, a.mu) == (b.materials, b.contact, b.creepage, b.mu)
    assert load_case(str(path)).source == str(path)


def test_defaults_steel_zero_creepage_fastsim():
    case = load_case("[contact]\nFn = 1000.0\nA = 1.0\nB = 2.0\n[friction]\nmu = 0.3\n")
    assert case.materials.wheel == wr.STEEL
    assert case.creepage == (0.0, 0.0, 0.0)
    assert (case.normal, case.tangential) == (wr.normal.Hertz(), wr.tangential.Fastsim())


def test_alias_resolved_and_options_kept():
    text = _edit(FULL, 'tangential = "linear"', 'tangential = "SHE"\n[method.fastsim]\nnx = 7')
    case = load_case(text)
    assert case.tangential == wr.tangential.ShenHedrickElkins()
    assert case.methods["fastsim"] == wr.tangential.Fastsim(nx=7)
    assert case.with_tangential("fastsim").tangential == wr.tangential.Fastsim(nx=7)


def test_material_pair():
    text = _edit(FULL, "[material]\nE = 2.1e11\nnu = 0.28",
                 "[material.wheel]\nE = 2.1e11\nnu = 0.28\n[material.rail]\nE = 2.0e11\nnu = 0.3")
    case = load_case(text)
    assert case.materials.wheel == wr.Material(2.1e11, 0.28)
    assert case.materials.rail == wr.Material(2.0e11, 0.3)


def test_to_toml_round_trip():
    text = _edit(FULL, "[material]\nE = 2.1e11\nnu = 0.28",
                 "[material.wheel]\nE = 2.1e11\nnu = 0.28\n[material.rail]\nE = 2.0e11\nnu = 0.3")
    text = _edit(text, "A = 1.0869565\nB = 1.6666667",
                 "wheel_rolling_radius = 0.46\nrail_profile_radius = 0.3\nrail_longitudinal_radius = inf")
    text += '[method.fastsim]\nnx = 7\nbound = "elliptic"\n[force]\nFy = 100.0\n'
    case = load_case(text)
    again = load_case(case.to_toml())
    for attr in ("materials", "contact", "creepage", "mu", "normal", "tangential"):
        assert getattr(again, attr) == getattr(case, attr), attr
    assert again.methods["fastsim"] == wr.tangential.Fastsim(nx=7, bound="elliptic")
    assert dict(again.forces) == {"Fy": 100.0}


def test_radii_give_the_curvatures():
    # A = 1/2 (1/R1x + 1/R2x), B = 1/2 (1/R1y + 1/R2y); hollow wheel (R1y < 0)
    text = _edit(FULL, "A = 1.0869565\nB = 1.6666667",
                 "wheel_rolling_radius = 0.46\nwheel_profile_radius = -0.5\n"
                 "rail_profile_radius = 0.3")
    c = load_case(text).hertz_contact
    assert c.A == pytest.approx(0.5 / 0.46, rel=1e-14)
    assert c.B == pytest.approx(0.5 * (1 / 0.3 - 1 / 0.5), rel=1e-14)


def test_semiaxes_are_reproduced():
    text = _edit(FULL, "A = 1.0869565\nB = 1.6666667", "a = 0.006\nb = 0.004")
    out = run_case(load_case(text))
    assert out["a"] == pytest.approx(0.006, rel=1e-9)
    assert out["b"] == pytest.approx(0.004, rel=1e-9)
    assert out["p0"] == pytest.approx(1.5 * 7500.0 / (math.pi * 0.006 * 0.004), rel=1e-9)


def test_run_case_sphere_matches_closed_form():
    """Circular contact: a = (3 N R / 4E*)^(1/3), p0 = 3N/(2πa²), δ = a²/R with R = 1/(2A)
    (Johnson, Contact Mechanics 1985, eqs. 4.22-4.23), E* = E / (2 (1 - ν²))."""
    text = _edit(FULL, "B = 1.6666667", "B = 1.0869565")
    out = run_case(load_case(text))
    R = 1.0 / (2 * 1.0869565)
    E_star = 2.1e11 / (2 * (1 - 0.28**2))
    a = (3 * 7500.0 * R / (4 * E_star)) ** (1 / 3)
    assert out["a"] == pytest.approx(a, rel=1e-9)
    assert out["b"] == pytest.approx(a, rel=1e-9)
    assert out["p0"] == pytest.approx(3 * 7500.0 / (2 * math.pi * a * a), rel=1e-9)
    assert out["penetration"] == pytest.approx(a * a / R, rel=1e-9)


def test_run_case_keys_and_consistency():
    case = load_case(FULL)
    out = run_case(case)
    assert REQUIRED_KEYS <= set(out)
    c = wr.hertz(7500.0, 1.0869565, 1.6666667, wr.Material(2.1e11, 0.28))
    for key in ("a", "b", "p0", "penetration"):
        assert out[key] == pytest.approx(getattr(c, key), rel=1e-12)
    ref = wr.creep_forces(c, (-0.0007, 0.0002, 0.1), 0.2, method="linear")
    assert (out["Fx"], out["Fy"], out["Mz"]) == pytest.approx((ref.Fx, ref.Fy, ref.Mz), rel=1e-12)
    assert out["Fx"] > 0  # Kalker's convention: ξ < 0 gives a positive force on the wheel
    assert out["Fn"] == 7500.0 and out["mu"] == 0.2 and out["method"] == "linear"
    assert out["status"] == "converged"
    assert out["units"]["p0"] == "Pa"
    import json

    json.dumps(out)  # JSON-ready


def test_fastsim_case_reports_adhesion_area():
    text = _edit(FULL, 'tangential = "linear"', 'tangential = "fastsim"\n[method.fastsim]\nnx = 10\nny = 10')
    out = run_case(load_case(text))
    assert 0.0 < out["adhesion_area"] < out["area"] * 1.01
    assert out["Fx"] > 0


# --------------------------------------------------------------------------- errors
def _error(text) -> str:
    with pytest.raises(CaseFileError) as info:
        load_case(text)
    msg = str(info.value)
    assert "\n" not in msg
    return msg


def test_malformed_toml_names_line_and_column():
    msg = _error("[contact]\nFn = 7500.0\nA = \n")
    assert "<string>" in msg and "malformed TOML" in msg
    assert "line 3" in msg and "column" in msg


def test_malformed_toml_in_file_names_the_file(tmp_path):
    path = tmp_path / "broken.toml"
    path.write_text("[contact\nFn = 1\n")
    with pytest.raises(CaseFileError, match="broken.toml.*line 1"):
        load_case(path)


def test_missing_file():
    with pytest.raises(CaseFileError, match="no_such_case.toml: case file not found"):
        load_case("no_such_case.toml")


@pytest.mark.parametrize("old, new, expected", [
    ("Fn = 7500.0", "Fx0 = 7500.0", r"\[contact\]: unknown key\(s\) 'Fx0'"),
    ("[friction]", "[frction]", r"unknown table\(s\) 'frction'"),
    ("mu = 0.2", "mu = 0.2\ntemperature = 20.0", r"\[friction\]: unknown key\(s\) 'temperature'"),
    ('tangential = "linear"', 'tangential = "linear"\nsolver = "x"', r"unknown key\(s\) 'solver'"),
    ('tangential = "linear"', 'tangential = "linear"\n[method.fastsm]\nnx = 3',
     r"unknown method table \[method.fastsm\]"),
    ("[creepage]", "[creepage]\nzeta = 0.1", r"\[creepage\]: unknown key\(s\) 'zeta'"),
])
def test_unknown_names_are_errors(old, new, expected):
    msg = _error(_edit(FULL, old, new))
    assert msg.startswith("<string>: ")
    import re

    assert re.search(expected, msg), msg


@pytest.mark.parametrize("old, new, table_key, value", [
    ("Fn = 7500.0", "Fn = -7500.0", "[contact] Fn", "-7500.0"),
    ("Fn = 7500.0", "Fn = 0.0", "[contact] Fn", "0.0"),
    ("mu = 0.2", "mu = 0.0", "[friction] mu", "0.0"),
    ("mu = 0.2", "mu = -0.1", "[friction] mu", "-0.1"),
    ("xi = -0.0007", "xi = nan", "[creepage] xi", "nan"),
    ("phi = 0.1", "phi = inf", "[creepage] phi", "inf"),
    ("E = 2.1e11", "E = -2.1e11", "[material] E", "-210000000000.0"),
    ("nu = 0.28", "nu = 0.5", "[material] nu", "0.5"),
    ("A = 1.0869565", "A = nan", "[contact] A", "nan"),
    ("mu = 0.2", 'mu = "high"', "[friction] mu", "'high'"),
    ("mu = 0.2", "mu = true", "[friction] mu", "True"),
])
def test_bad_values_name_table_key_and_value(old, new, table_key, value):
    msg = _error(_edit(FULL, old, new))
    assert table_key in msg and value in msg, msg


def test_unknown_methods_name_the_value():
    msg = _error(_edit(FULL, 'tangential = "linear"', 'tangential = "fastsimm"'))
    assert "[method] tangential" in msg and "'fastsimm'" in msg and "fastsim" in msg
    msg = _error(_edit(FULL, 'normal = "hertz"', 'normal = "fem"'))
    assert "[method] normal" in msg and "'fem'" in msg


def test_bad_option_of_chosen_method():
    msg = _error(_edit(FULL, 'tangential = "linear"', 'tangential = "linear"\n[method.linear]\nnx = 3'))
    assert "[method.linear]" in msg and "nx" in msg


def test_bem_elements_checked():
    msg = _error(_edit(FULL, 'normal = "hertz"', 'normal = "bem"') + "[method.bem]\ngrid_elements = 2.5\n")
    assert "[method.bem] grid_elements" in msg and "2.5" in msg


def test_contact_description_must_be_unique():
    msg = _error(_edit(FULL, "B = 1.6666667", "B = 1.6666667\na = 0.003\nb = 0.002"))
    assert "exactly one" in msg and "A, B, a, b" in msg
    msg = _error(_edit(FULL, "A = 1.0869565\nB = 1.6666667\n", ""))
    assert "exactly one" in msg and "got none" in msg


def test_missing_required_values():
    assert "missing table [friction]" in _error(_edit(FULL, "[friction]\nmu = 0.2", ""))
    assert "[contact] Fn: missing" in _error(_edit(FULL, "Fn = 7500.0", ""))
    assert "[material.rail] is missing" in _error(
        _edit(FULL, "[material]\nE = 2.1e11\nnu = 0.28", "[material.wheel]\nE = 2.1e11\nnu = 0.28"))


def test_non_convex_radii_rejected_in_contact_table():
    text = _edit(FULL, "A = 1.0869565\nB = 1.6666667",
                 "wheel_rolling_radius = 0.46\nwheel_profile_radius = -0.2\nrail_profile_radius = 0.3")
    msg = _error(text)
    assert "[contact]" in msg and "non-positive combined curvature" in msg


def test_prescribed_force_beyond_friction_limit():
    msg = _error(FULL + "\n[force]\nFx = 2000.0\n")  # mu Fn = 1500 N
    assert "[force]" in msg and "2000.0" in msg and "1500.0" in msg


def test_case_from_dict_rejects_non_table():
    with pytest.raises(CaseFileError, match="'contact' must be a table"):
        case_from_dict({"contact": 3, "friction": {"mu": 0.3}})


def test_bem_normal_close_to_hertz():
    text = _edit(FULL, 'normal = "hertz"', 'normal = "bem"') + "[method.bem]\ngrid_elements = 40\n"
    out = run_case(load_case(text))
    c = wr.hertz(7500.0, 1.0869565, 1.6666667, wr.Material(2.1e11, 0.28))
    assert out["normal_method"] == "bem"
    assert out["Fn"] == pytest.approx(7500.0, rel=1e-6)
    # a 40-element grid resolves the Hertz pressure peak and area to a few per cent
    assert out["p_max"] == pytest.approx(c.p0, rel=0.05)
    assert out["area"] == pytest.approx(np.pi * c.a * c.b, rel=0.1)
    assert out["hertz"]["p0"] == pytest.approx(c.p0)


def test_prescribed_force_reproduced():
    case = load_case(FULL + "\n[force]\nFx = -500.0\n")
    out = run_case(case)
    assert out["Fx"] == pytest.approx(-500.0, rel=1e-4)
    assert out["xi"] > 0  # a negative force needs a positive creepage
    assert out["prescribed"] == {"Fx": -500.0}


def test_exact_method_runs():
    text = _edit(FULL, 'tangential = "linear"', 'tangential = "exact"\n[method.exact]\nelements = 12')
    res = solve_case(load_case(text))
    assert res.summary["method"] == "exact"
    assert res.summary["Fx"] > 0


def test_bem_with_exact_uses_bem_grid_and_reports_its_normal_solution():
    """Issue 'exact half-space': normal = "bem" + tangential = "exact" with [method.bem] elements.

    The case goes through wr.solve: the BEM normal method's patch (grid size from
    [method.bem]) carries the pressure that the exact theory reads, and the JSON
    reports that BEM normal solution (area, p_max,
    adhesion area, iterations). Reference: Hertz (Johnson 1985, eq. 3.64) for p_max.
    """
    text = (_edit(_edit(FULL, 'normal = "hertz"', 'normal = "bem"'),
                  'tangential = "linear"', 'tangential = "exact"')
            + "[method.bem]\ngrid_elements = 31\n")
    res = solve_case(load_case(text))
    out = res.summary
    sol = res.forces.fields
    # the grid of the exact solve holds 31 elements across the contact (plus its margin)
    assert 31 <= sol.grid.nx <= 40
    # the exact theory reads the pressure of the BEM patch (wr.solve): one grid, one normal solution
    assert res.normal is res.result.patches[0].patch.info["normal_solution"]
    assert res.normal.grid.nx == sol.grid.nx and np.array_equal(res.normal.pressure, sol.pressure)
    c = wr.hertz(7500.0, 1.0869565, 1.6666667, wr.Material(2.1e11, 0.28))
    assert out["p_max"] == pytest.approx(c.p0, rel=0.02)
    assert out["area"] == pytest.approx(np.pi * c.a * c.b, rel=0.05)
    for key in ("adhesion_area", "iterations", "normal_iterations"):
        assert key in out
    assert 0 < out["adhesion_area"] < out["area"]


def test_prescribed_force_with_exact_reports_creepage():
    text = (_edit(FULL, 'tangential = "linear"', 'tangential = "exact"\n[method.exact]\nelements = 16')
            + "\n[force]\nFx = -600.0\n")
    out = run_case(load_case(text))
    assert out["Fx"] == pytest.approx(-600.0, rel=1e-4)
    assert out["xi"] > 0


def test_old_package_name_is_a_deprecated_alias_of_cases_files():
    import importlib

    import wheelrail.cases.files as files

    with pytest.warns(DeprecationWarning, match="wheelrail.cases.files"):
        old = importlib.reload(importlib.import_module("wheelrail.casefile"))
    assert old.load_case is files.load_case
