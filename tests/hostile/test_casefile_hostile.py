"""Hostile case files: each mutation of a valid case is refused at read time with one line
naming file, table, key and value — or solved with a documented PlausibilityWarning.

Failures once found: values in the wrong unit were solved as "converged";
option errors did not name file and table and were only found at solve time; an
exact-theory margin of −1 was silently clamped.
"""

from __future__ import annotations

import math
import warnings

import pytest
from _helpers import assert_clean_failure, run_cli
from hypothesis import given, settings
from hypothesis import strategies as st

import wheelrail as wr
from wheelrail.cases.files import case_from_dict
from wheelrail.cases import solve_case
from wheelrail.errors import CaseFileError, WheelrailError
from wheelrail.plausibility import PlausibilityWarning


def base():
    return {
        "material": {"E": 2.1e11, "nu": 0.28},
        "contact": {"Fn": 7500.0, "wheel_rolling_radius": 0.46, "rail_profile_radius": 0.30},
        "creepage": {"xi": -1e-3, "eta": 0.0, "phi": 0.0},
        "friction": {"mu": 0.3},
        "method": {"normal": "hertz", "tangential": "fastsim", "fastsim": {"nx": 8, "ny": 8}},
    }


def toml_value(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, int):
        return str(v)
    if isinstance(v, str):
        return '"' + v + '"'
    if isinstance(v, list):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    raise TypeError(v)


def to_toml(d, prefix=""):
    lines, tables = [], []
    for k, v in d.items():
        if isinstance(v, dict):
            tables.append((k, v))
        else:
            lines.append(f"{k} = {toml_value(v)}")
    out = ""
    if lines:
        out += (f"[{prefix}]\n" if prefix else "") + "\n".join(lines) + "\n"
    for k, v in tables:
        out += to_toml(v, f"{prefix}.{k}" if prefix else k)
    return out


def mutate(path, value):
    d = base()
    node = d
    for k in path[:-1]:
        node = node.setdefault(k, {})
    if value is DELETE:
        node.pop(path[-1], None)
    else:
        node[path[-1]] = value
    return d


class _Delete:
    def __repr__(self):
        return "<deleted>"


DELETE = _Delete()

# (path, value, tokens the error must contain)
REFUSED = [
    (("contact", "Fn"), -1.0, ["[contact]", "Fn", "-1.0"]),
    (("contact", "Fn"), 0.0, ["Fn", "0.0"]),
    (("contact", "Fn"), "7500", ["Fn", "7500"]),
    (("contact", "Fn"), True, ["Fn", "True"]),
    (("contact", "Fn"), float("nan"), ["Fn", "nan"]),
    (("contact", "Fn"), float("inf"), ["Fn", "inf"]),
    (("contact", "Fn"), 1e12, ["[contact]", "larger than the bodies' radii"]),
    (("contact", "Fn"), [7500.0], ["Fn"]),
    (("contact", "Fn"), DELETE, ["Fn", "missing"]),
    (("contact", "wheel_rolling_radius"), 460.0, ["wheel_rolling_radius", "460", "mm given"]),
    (("contact", "wheel_rolling_radius"), 0.0, ["wheel_rolling_radius", "0.0"]),
    (("contact", "wheel_rolling_radius"), -0.46, ["wheel_rolling_radius", "-0.46"]),
    (("contact", "rail_profile_radius"), 0.0, ["rail_profile_radius", "0.0"]),
    (("contact", "rail_profile_radius"), "flat", ["rail_profile_radius", "flat"]),
    (("contact", "A"), 1.0, ["exactly one"]),
    (("contact", "rail_radius"), 0.3, ["rail_radius"]),
    (("material", "E"), 210.0, ["[contact]", "larger than the bodies' radii"]),
    (("material", "E"), -2.1e11, ["E", "-210000000000.0"]),
    (("material", "E"), 0.0, ["E", "0.0"]),
    (("material", "E"), "steel", ["E", "steel"]),
    (("material", "nu"), 0.5, ["nu", "0.5"]),
    (("material", "nu"), -0.1, ["nu", "-0.1"]),
    (("material", "nu"), 28.0, ["nu", "28.0"]),
    (("material", "G"), 8e10, ["G"]),
    (("friction", "mu"), 0.0, ["[friction]", "mu", "0.0"]),
    (("friction", "mu"), -0.3, ["mu", "-0.3"]),
    (("friction", "mu"), 50.0, ["[friction]", "mu", "50"]),
    (("friction", "mu"), 30.0, ["mu", "30", "percentage"]),
    (("friction", "mu"), "0.3", ["mu", "0.3"]),
    (("friction", "mu"), float("nan"), ["mu", "nan"]),
    (("friction", "mu"), DELETE, ["friction", "missing"]),
    (("creepage", "xi"), float("nan"), ["xi", "nan"]),
    (("creepage", "xi"), "small", ["xi", "small"]),
    (("creepage", "xi"), float("inf"), ["xi", "inf"]),
    (("creepage", "zeta"), 0.0, ["zeta"]),
    (("method", "tangential"), "foo", ["tangential", "foo"]),
    (("method", "tangential"), 3, ["tangential", "3"]),
    (("method", "normal"), "fem", ["normal", "fem"]),
    (("method", "fastsim", "nx"), 0, ["[method.fastsim]", "nx", "0"]),
    (("method", "fastsim", "nx"), 2.5, ["[method.fastsim]", "nx", "2.5"]),
    (("method", "fastsim", "nx"), -1, ["[method.fastsim]", "nx", "-1"]),
    (("method", "fastsim", "nx"), "20", ["[method.fastsim]", "nx", "20"]),
    (("method", "fastsim", "ny"), True, ["[method.fastsim]", "ny", "True"]),
    (("method", "fastsim", "bound"), "square", ["[method.fastsim]", "bound", "square"]),
    (("method", "fastsim", "nz"), 20, ["nz"]),
    (("method", "exact", "margin"), -1.0, ["[method.exact]", "margin", "-1"]),
    (("method", "exact", "margin"), 1.0, ["[method.exact]", "margin", "1.0"]),
    (("method", "exact", "elements"), 2, ["[method.exact]", "elements", "2"]),
    (("method", "exact", "tol"), 0.0, ["[method.exact]", "tol", "0.0"]),
    (("method", "exact", "maxiter"), 0, ["[method.exact]", "maxiter", "0"]),
    (("method", "exact", "on_fail"), "ignore", ["[method.exact]", "on_fail", "ignore"]),
    (("method", "carter", "form"), "local", ["[method.carter]", "form", "local"]),
    (("method", "polach", "kA"), 2.0, ["[method.polach]", "kA", "2.0"]),
    (("method", "polach", "kS"), 0.0, ["[method.polach]", "kS", "0.0"]),
    (("method", "shen-hedrick-elkins", "spin_moment"), "none",
     ["[method.shen-hedrick-elkins]", "spin_moment", "none"]),
    (("method", "bem", "grid_elements"), 1, ["[method.bem]", "grid_elements", "1"]),
    # [method.bem] elements (the former name of grid_elements) is read with a warning:
    # tests/hostile/test_renamed_keys_hostile.py
    (("method", "fem", "elements"), 10, ["fem"]),
    (("force", "Fx"), -1e6, ["[force]", "friction limit"]),
    (("force", "Fz"), 1.0, ["Fz"]),
    (("extra",), {"a": 1}, ["extra"]),
]


@pytest.mark.parametrize("path,value,names", REFUSED,
                         ids=[f"{'.'.join(p)}={v!r}" for p, v, _ in REFUSED])
def test_refused_at_read_time_naming_file_table_key_value(path, value, names, tmp_path, capsys,
                                                           monkeypatch):
    import wheelrail.cases as cases

    def boom(case):  # everything must be caught when the case is read
        raise AssertionError("the case was solved")

    monkeypatch.setattr(cases, "solve_case", boom)
    p = tmp_path / "hostile.toml"
    p.write_text(to_toml(mutate(path, value)))
    code, _, err = run_cli(["solve", p], capsys)
    assert_clean_failure(code, err, "hostile.toml", *names)


WARNED = [
    (("contact", "Fn"), 7.5, "kN meant"),
    (("contact", "Fn"), 50.0, "below 100 N"),
    (("contact", "Fn"), 2e6, "more than any wheel load"),
    (("friction", "mu"), 1.5, "above 1"),
    (("material", "E"), 5e8, "GPa or MPa meant"),
    (("contact", "wheel_rolling_radius"), 0.03, "unusually small for a wheel"),
]


@pytest.mark.parametrize("path,value,text", WARNED, ids=[f"{'.'.join(p)}={v!r}" for p, v, _ in WARNED])
def test_unusual_values_are_solved_with_a_warning(path, value, text, tmp_path, capsys):
    p = tmp_path / "odd.toml"
    p.write_text(to_toml(mutate(path, value)))
    code, out, err = run_cli(["solve", p, "--json", tmp_path / "r.json"], capsys)
    assert code == 0, err
    assert any(text in ln for ln in err), err
    assert all(ln.startswith("wheelrail: warning: ") for ln in err), err


@pytest.mark.parametrize("path,value", [(("friction", "mu"), 50.0), (("contact", "Fn"), 1e12)])
def test_refusals_can_be_overridden(path, value, tmp_path, capsys):
    p = tmp_path / "forced.toml"
    p.write_text(to_toml(mutate(path, value)))
    code, _, err = run_cli(["--no-plausibility-checks", "solve", p], capsys)
    assert code == 0, err
    with wr.plausibility.disabled():
        solve_case(case_from_dict(mutate(path, value)))


def test_api_refuses_the_same_values():
    """API, case files and CLI give the same answer (the same checks)."""
    with pytest.raises(wr.plausibility.ImplausibleInputError, match="larger than the bodies"):
        wr.hertz_from_radii(1e12, 0.46, rail_profile_radius=0.3, material=wr.STEEL)
    with pytest.raises(wr.plausibility.ImplausibleInputError, match="mm given"):
        wr.hertz_from_radii(7500.0, 460.0, rail_profile_radius=300.0, material=wr.STEEL)
    c = wr.hertz(7500.0, 1.0, 1.5, wr.STEEL)
    with pytest.raises(wr.plausibility.ImplausibleInputError, match="mu = 50"):
        wr.creep_forces(c, (0.0, 0.0, 0.0), 50.0)
    with pytest.raises(wr.errors.InputError, match=r"margin must be a number in \(1, 10\], got -1"):
        wr.creep_forces(c, (0.0, 0.0, 0.0), 0.3, method="exact", margin=-1.0)
    with pytest.warns(PlausibilityWarning, match="kN meant"):
        wr.hertz(7.5, 1.0, 1.5, wr.STEEL)
    with pytest.raises(wr.plausibility.ImplausibleInputError, match="mm given"):
        wr.Wheelset(wr.profiles.load("S1002"), nominal_radius=460.0)


KEYS = [("contact", "Fn"), ("friction", "mu"), ("material", "E"), ("material", "nu"),
        ("creepage", "xi"), ("creepage", "eta"), ("creepage", "phi"),
        ("contact", "wheel_rolling_radius"), ("contact", "rail_profile_radius")]


@settings(max_examples=60, deadline=None)
@given(key=st.sampled_from(KEYS),
       value=st.one_of(st.floats(allow_nan=True, allow_infinity=True),
                       st.floats(min_value=-1e3, max_value=1e3),
                       st.integers(min_value=-10**6, max_value=10**6)))
def test_any_number_in_any_field_is_refused_warned_or_solved_finite(key, value):
    """Property: no traceback, no non-finite result; errors name the key."""
    data = mutate(key, value)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            res = solve_case(case_from_dict(data, source="gen.toml"))
        except CaseFileError as exc:
            assert key[-1] in str(exc) or f"[{key[0]}]" in str(exc), str(exc)
            assert "\n" not in str(exc)
            return
        except WheelrailError as exc:  # e.g. a creepage too large for a method's validity
            assert "\n" not in str(exc) and str(exc)
            return
    for w in caught:
        assert issubclass(w.category, (PlausibilityWarning, wr.profiles.ProfileWarning,
                                       UserWarning)), w
    for name in ("Fx", "Fy", "Mz"):
        assert math.isfinite(res.summary[name])
