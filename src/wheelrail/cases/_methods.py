"""The configured methods of a case (private)."""

from __future__ import annotations

from types import MappingProxyType

from .. import normal as normal_family
from .. import tangential as tangential_family


def configured_methods(normal, tangential, methods=None):
    """The configured normal and tangential methods of a case (defaults: Hertz, FASTSIM)
    and the mapping name -> method with both added (:mod:`wheelrail.options`)."""
    n = normal_family.get("hertz" if normal is None else normal)
    t = tangential_family.get("fastsim" if tangential is None else tangential)
    out = dict(methods or {})
    out.setdefault(n.name, n)
    out.setdefault(t.name, t)
    return n, t, MappingProxyType(out)
