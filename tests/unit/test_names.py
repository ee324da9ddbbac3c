"""One name per physical quantity (``wheelrail.conventions.NAMES``): no public entry
function or method takes a retired synonym (``load``, ``normal_force``, ``approach``, ...)."""

from __future__ import annotations

import dataclasses
import inspect

import wheelrail as wr
from wheelrail.conventions import RETIRED_NAMES

ENTRY_POINTS = ["solve", "creep_forces", "hertz", "hertz_from_semiaxes", "hertz_from_radii",
                "hertz_from_penetration", "transient_rolling", "solve_creepages", "solve_normal",
                "solve_gap", "solve_gap_auto", "wheelset_sweep", "contact_table", "contact_points",
                "elastic_contact", "WheelRailPosition", "GapProblem", "HertzContact",
                "ContactPatch", "Motion"]


def _names(obj):
    if dataclasses.is_dataclass(obj):
        return [f.name for f in dataclasses.fields(obj)]
    return list(inspect.signature(obj).parameters)


def test_public_entry_points_use_the_convention_names():
    bad = {name: [p for p in _names(getattr(wr, name)) if p in RETIRED_NAMES]
           for name in ENTRY_POINTS}
    assert {k: v for k, v in bad.items() if v} == {}


def test_methods_options_use_the_convention_names():
    classes = [*wr.normal_methods().values(), *wr.tangential_methods().values()]
    bad = {c.name: [k for k in c.option_declarations() if k in RETIRED_NAMES] for c in classes}
    assert {k: v for k, v in bad.items() if v} == {}


def test_results_use_the_convention_names():
    c = wr.hertz(Fn=1e4, A=1.0, B=2.0, material=wr.STEEL)
    assert c.Fn == 1e4 and not hasattr(c, "load")
    r = wr.creep_forces(c, (1e-4, 0.0, 0.0), 0.3, method="linear")
    assert r.Fn == 1e4


def test_the_checker_sees_a_retired_name():
    def f(contact, load):  # a planted signature
        return contact, load

    assert [p for p in _names(f) if p in RETIRED_NAMES] == ["load"]


def test_fe_rolling_case_takes_Fn_and_the_old_name_with_a_warning():
    """``RollingCase`` names the wheel load ``Fn`` like the rest of the library; the old
    ``load=`` still works for one release, with a DeprecationWarning, and gives the same case."""
    import pytest

    kw = dict(wheel=wr.fe.cone_wheel(0.1), rail=wr.fe.head_arc_rail(0.3), radius=0.46)
    new = wr.fe.RollingCase(Fn=7500.0, **kw)
    assert [p for p in _names(wr.fe.RollingCase) if p in RETIRED_NAMES] == []
    with pytest.warns(DeprecationWarning, match="Fn"):
        old = wr.fe.RollingCase(load=7500.0, **kw)
    assert old.Fn == new.Fn == 7500.0
    with pytest.warns(DeprecationWarning, match="Fn"):
        assert old.load == 7500.0
    with pytest.raises(wr.InputError, match="Fn"):
        wr.fe.RollingCase(Fn=7500.0, load=7500.0, **kw)


def test_no_two_public_classes_share_a_name():
    """One name per concept: a class exported (``__all__``) by any module of the package is
    the only public class of that name (the FE transition's suspension is
    ``WheelSuspension``; ``wr.dynamics.Suspension`` is the vehicle model's)."""
    import importlib
    import pkgutil

    seen = {}
    for info in pkgutil.walk_packages(wr.__path__, "wheelrail."):
        if info.name.rsplit(".", 1)[-1].startswith("_") or ".cli" in info.name:
            continue
        module = importlib.import_module(info.name)
        for name in getattr(module, "__all__", ()):
            obj = getattr(module, name, None)
            if inspect.isclass(obj):
                seen.setdefault(name, set()).add(f"{obj.__module__}.{obj.__qualname__}")
    assert {k: v for k, v in seen.items() if len(v) > 1} == {}


def test_fe_namespace_is_curated_and_old_names_warn():
    import pytest

    assert len(wr.fe.__all__) <= 25 and set(wr.fe.__all__) <= set(dir(wr.fe))
    with pytest.warns(DeprecationWarning, match="WheelSuspension"):
        assert wr.fe.Suspension is wr.fe.WheelSuspension
    with pytest.warns(DeprecationWarning, match="wheelrail.fe.transition"):
        assert wr.fe.rail_pulse is wr.fe.transition.rail_pulse
    with pytest.raises(AttributeError):
        wr.fe.no_such_name  # noqa: B018
