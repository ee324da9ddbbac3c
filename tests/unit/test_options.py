"""One declaration per option: the API, case files and the command line build every method
through the same option declarations, and accept and refuse the same values.

For every registered method and every declared option, values on and across its bounds
(and of wrong types) are given to

* the class itself, ``wr.tangential.Fastsim(nx=...)``;
* a case file, ``[method.fastsim] nx = ...`` (:func:`wheelrail.cases.files.case_from_dict`);
* the command line, ``wheelrail solve case.toml`` (reading only: the solve is replaced);

and the three must agree: accepted by all, or refused by all with a message that names the
option and the value (the case file and the CLI also name the file and the table).
"""

from __future__ import annotations

import math
import sys

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.cases.files import case_from_dict
from wheelrail.errors import CaseFileError, InputError, OptionError

sys.path.insert(0, str(__import__("pathlib").Path(__file__).resolve().parents[1] / "hostile"))
from _helpers import run_cli  # noqa: E402

CLASSES = {**wr.normal_methods(), **wr.tangential_methods()}
#: options whose combination is checked (a valid single value may be refused with the
#: defaults of the others, e.g. Polach's A needs B and speed): consistency only
COMBINED = {"polach"}


def _probe_values(decl):
    """(value, declared valid?) pairs on and across the declaration's bounds."""
    out = []
    if decl.kind == "int":
        lo = decl.lo if decl.lo is not None else 0
        out += [(decl.default, True), (int(lo), True), (int(lo) - 1, False), (2.5, False),
                (True, False), ("3", False)]
        if decl.hi is not None:
            out += [(int(decl.hi), True), (int(decl.hi) + 1, False)]
    elif decl.kind == "float":
        if decl.default is not None:
            out.append((decl.default, True))
        if decl.lo is not None:
            out += [(float(decl.lo), not decl.lo_open), (float(decl.lo) - 1.0, False)]
        if decl.hi is not None:
            out += [(float(decl.hi), not decl.hi_open), (float(decl.hi) + 1.0, False)]
        out += [(math.nan, False), ("1", False), (True, False)]
    elif decl.kind == "bool":
        out += [(True, True), (False, True), (1, False), ("yes", False)]
    elif decl.kind == "choice":
        out += [(c, True) for c in decl.choices if c is not None]
        out += [("nonsense", False), (3, False)]
    return out


SPECIAL = {  # options of kind "any": their own checks
    ("kik-piotrowski", "penetration_factor"): [("hertz", True), (0.55, True), (1.0, True),
                                               (0.0, False), (1.5, False), ("half", False)],
    ("multi-hertz", "caf_range"): [([-0.01, 0.01], True), ([0.01, -0.01], False),
                                   ([0.0], False), ("wide", False)],
    ("polach", "speed"): [(20.0, True), (0.0, False), (-1.0, False)],
    ("table", "table"): [("/nonexistent/table.npz", False), (3, False)],
}

CASES = []
for _name, _cls in CLASSES.items():
    for _key, _decl in _cls.option_declarations().items():
        _values = SPECIAL.get((_name, _key)) or _probe_values(_decl)
        CASES += [(_name, _key, v, ok) for v, ok in _values]


def _toml(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        return "nan" if math.isnan(v) else repr(v)
    if isinstance(v, int):
        return str(v)
    if isinstance(v, str):
        return f'"{v}"'
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml(x) for x in v) + "]"
    raise TypeError(v)


def _case_text(name, key, value):
    family = "normal" if name in wr.normal_methods() else "tangential"
    return (f"[contact]\nFn = 7500.0\nA = 1.0\nB = 1.5\n[friction]\nmu = 0.3\n"
            f"[method]\n{family} = \"{name}\"\n[method.\"{name}\"]\n{key} = {_toml(value)}\n")


def _value_text(v):
    return "nan" if isinstance(v, float) and math.isnan(v) else str(v)


def test_every_registered_method_is_probed():
    with_options = {n for n, c in CLASSES.items() if c.option_declarations()}
    assert {c[0] for c in CASES} == with_options and set(CLASSES) - with_options == {"linear"}
    assert len(CASES) > 150


@pytest.mark.parametrize("name,key,value,valid", CASES,
                         ids=[f"{n}.{k}={v!r}" for n, k, v, _ in CASES])
def test_api_case_file_and_cli_agree(name, key, value, valid, tmp_path, capsys, monkeypatch):
    cls = CLASSES[name]
    api_error = None
    try:
        cls(**{key: value})
    except OptionError as exc:
        api_error = exc
    if name not in COMBINED:
        assert (api_error is None) == valid, (name, key, value, api_error)
    if api_error is not None and api_error.option is not None:   # not a combination check
        assert key in str(api_error) and _value_text(value).lower() in str(api_error).lower()

    text = _case_text(name, key, value)
    from wheelrail._toml import tomllib

    case_error = None
    try:
        case_from_dict(tomllib.loads(text), source="probe.toml")
    except CaseFileError as exc:
        case_error = exc
    assert (case_error is None) == (api_error is None), (text, api_error, case_error)
    if case_error is not None:
        msg = str(case_error)
        assert "probe.toml" in msg and f"[method.{name}]" in msg, msg
        assert api_error.option is None or key in msg, msg

    import wheelrail.cases as cases

    monkeypatch.setattr(cases, "solve_case", lambda case: (_ for _ in ()).throw(
        SystemExit(0)))  # reading only: stop before solving
    path = tmp_path / "probe.toml"
    path.write_text(text)
    try:
        code, _, err = run_cli(["solve", path], capsys)
    except SystemExit as exc:
        code, err = int(exc.code or 0), []
    assert (code == 0) == (api_error is None), (code, err)
    if api_error is not None:
        line = [ln for ln in err if ln.startswith("wheelrail: error: ")]
        assert line and f"[method.{name}]" in line[0], err
        assert api_error.option is None or key in line[0], err


def test_unknown_option_is_refused_everywhere_naming_the_options(tmp_path, capsys):
    with pytest.raises(OptionError, match="its options: nx, ny"):
        wr.tangential.Fastsim(nz=3)
    with pytest.raises(OptionError, match="its options: nx, ny"):
        wr.creep_forces(wr.hertz(1e4, 1.0, 2.0, wr.STEEL), (0, 0, 0), 0.3, method="fastsim",
                        nz=3)
    path = tmp_path / "c.toml"
    path.write_text(_case_text("fastsim", "nz", 3))
    code, _, err = run_cli(["solve", path], capsys)
    assert code == 2 and "[method.fastsim] nz" in err[-1]


def test_solve_routes_each_option_to_the_method_that_declares_it():
    c = wr.hertz(7500.0, A=1.087, B=1.667, material=wr.STEEL)
    a = wr.solve(c, creepage=(-7e-4, 0, 0), mu=0.3, normal="bem", tangential="exact",
                 element_size=4e-4, elements=12)
    b = wr.solve(c, creepage=(-7e-4, 0, 0), mu=0.3, normal=wr.normal.Bem(element_size=4e-4),
                 tangential=wr.tangential.Exact(elements=12))
    assert (a.Fx, a.Fy, a.Fn) == (b.Fx, b.Fy, b.Fn)
    assert 3e-4 < a.patches[0].patch.grid.dx <= 4e-4      # element_size: at most 0.4 mm
    r1 = wr.creep_forces(c, (-7e-4, 0, 0), 0.3, method="fastsim", nx=30)
    r2 = wr.creep_forces(c, (-7e-4, 0, 0), 0.3, method=wr.tangential.Fastsim(nx=30))
    assert r1.Fx == r2.Fx
    # an option of neither, or of both, chosen methods is refused naming both
    with pytest.raises(InputError, match="neither.*'hertz'.*'fastsim'"):
        wr.solve(c, creepage=(0, 0, 0), mu=0.3, normal="hertz", tangential="fastsim",
                 elements=10)



def test_an_option_of_both_methods_is_refused_naming_both():
    """No normal method and creep-force law share an option name today (so that every
    option of wr.solve has one owner); the router refuses a shared one."""
    from wheelrail.options import configured, option, split_options

    @configured
    class Shared(wr.tangential.TangentialMethod):   # no ``name``: not registered
        strips: int = option(10, lo=2)

    with pytest.raises(InputError, match="belongs to both.*'hertz'"):
        split_options(wr.normal.Hertz, Shared, {"strips": 10})
    shared = [k for n in wr.normal_methods().values() for k in n.option_declarations()
              if any(k in t.option_declarations() for t in wr.tangential_methods().values())]
    assert shared == []


def test_methods_are_frozen_hashable_and_compare_by_options():
    m = wr.tangential.Fastsim(nx=30)
    with pytest.raises(Exception):
        m.nx = 10
    assert m == wr.tangential.Fastsim(nx=30) != wr.tangential.Fastsim(nx=31)
    assert len({m, wr.tangential.Fastsim(nx=30)}) == 1
    assert m.replace(ny=5) == wr.tangential.Fastsim(nx=30, ny=5)
    assert repr(m) == "Fastsim(nx=30)"
    p = wr.tangential.Polach(speed=np.array([10.0, 20.0]))
    assert p == wr.tangential.Polach(speed=np.array([10.0, 20.0])) and hash(p)


def test_the_methods_page_lists_every_option_with_unit_and_bounds():
    from wheelrail.options import describe

    for cls in CLASSES.values():
        text = describe(cls)
        assert f"`{cls.name}`" in text
        for key, decl in cls.option_declarations().items():
            assert f"| `{key}` |" in text and decl.describe() in text
