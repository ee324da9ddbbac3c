"""One name per concept: no two different public classes of the package share a name (the
public names are those in the ``__all__`` of every module outside private modules), and
``wr.fe`` stays a curated namespace (at most 25 names)."""

from __future__ import annotations

import collections
import importlib
import inspect
import pkgutil
import warnings

import wheelrail


def clashes(classes_by_module):
    """{name: {qualified names}} of class names bound to more than one class."""
    seen = collections.defaultdict(set)
    for objs in classes_by_module.values():
        for name, cls in objs.items():
            seen[name].add(f"{cls.__module__}.{cls.__qualname__}")
    return {n: q for n, q in seen.items() if len(q) > 1}


def public_classes():
    out = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        for info in pkgutil.walk_packages(wheelrail.__path__, "wheelrail."):
            if any(part.startswith("_") for part in info.name.split(".")[1:]):
                continue
            if info.name == "wheelrail.casefile":        # deprecated alias module
                continue
            mod = importlib.import_module(info.name)
            out[info.name] = {n: o for n in getattr(mod, "__all__", ())
                              if inspect.isclass(o := getattr(mod, n, None))}
    return out


def test_no_two_public_classes_share_a_name():
    assert clashes(public_classes()) == {}


def test_the_check_sees_a_planted_clash():
    class Suspension:                                     # noqa: D401 - a stand-in
        pass

    classes = public_classes()
    planted = dict(classes, planted={"Suspension": Suspension})
    assert "Suspension" in clashes(planted)


def test_fe_namespace_is_curated():
    import wheelrail.fe as fe

    assert len(fe.__all__) <= 25
