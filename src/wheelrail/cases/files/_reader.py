"""Typed access to parsed TOML tables (private): every message names file, table, key, value."""

from __future__ import annotations

import math
from types import MappingProxyType
from typing import Mapping

from ..contact import ContactSpec
from ...errors import InputError, OptionError
from ...hertzian import RADII_KEYS
from ...materials import STEEL, Material, MaterialPair

__all__ = ["Reader", "read_toml", "read_materials", "read_contact", "read_methods",
           "read_forces", "read_friction", "configure", "check_plausible", "tomllib",
           "RenamedKeyWarning", "renamed_keys", "RENAMED_OPTIONS"]

#: Options of methods renamed for one name per quantity: method -> {old: new}.
RENAMED_OPTIONS = {"bem": {"elements": "grid_elements", "margin": "window_margin",
                           "tol": "pressure_tol"}}

from ... import normal as normal_family
from ... import tangential as tangential_family
from ..._toml import Reader, RenamedKeyWarning, read_toml, renamed_keys, tomllib
from ...plausibility import check_friction, check_semi_axes


def check_plausible(r, table: str, key: str, value, check=check_friction) -> None:
    """Plausibility ``check(value)`` at read time (see :mod:`wheelrail.plausibility`); a
    refusal names the file, the table and the key."""

    try:
        check(value)
    except InputError as exc:
        r.fail(table, key, str(exc))


def read_material(r: Reader, table: str, tbl) -> Material:
    if not isinstance(tbl, Mapping):
        r.fail(table, None, f"must be a table, got {tbl!r}")
    r.unknown(table, tbl, ("E", "nu"))
    E = r.number(table, tbl, "E", positive=True)
    nu = r.number(table, tbl, "nu", lo=0.0, hi=0.5)
    return Material(E, nu)


def read_materials(r: Reader, tbl: Mapping) -> MaterialPair:
    if not tbl:
        return MaterialPair.same(STEEL)
    if "wheel" in tbl or "rail" in tbl:
        r.unknown("material", tbl, ("wheel", "rail"))
        for body in ("wheel", "rail"):
            if body not in tbl:
                r.fail("material", None, f"[material.{body}] is missing (give both "
                       "[material.wheel] and [material.rail], or E and nu in [material])")
        return MaterialPair(read_material(r, "material.wheel", tbl["wheel"]),
                            read_material(r, "material.rail", tbl["rail"]))
    return MaterialPair.same(read_material(r, "material", tbl))


def read_contact(r: Reader, tbl: Mapping) -> ContactSpec:
    allowed = ("Fn", "A", "B", "a", "b", *RADII_KEYS)
    tbl = renamed_keys(r, "contact", tbl, {"load": "Fn"})
    r.unknown("contact", tbl, allowed)
    Fn = r.number("contact", tbl, "Fn", positive=True)
    groups = {"curvatures": [k for k in ("A", "B") if k in tbl],
              "semiaxes": [k for k in ("a", "b") if k in tbl],
              "radii": [k for k in RADII_KEYS if k in tbl]}
    used = [g for g, keys in groups.items() if keys]
    if len(used) != 1:
        given = ", ".join(k for g in used for k in groups[g]) or "none"
        r.fail("contact", None, "give exactly one of: A and B (1/m); a and b (m); or radii "
               f"({', '.join(RADII_KEYS)}) (m); got {given}")
    kind = used[0]
    if kind == "curvatures":
        A = r.number("contact", tbl, "A", positive=True)
        B = r.number("contact", tbl, "B", positive=True)
        return ContactSpec(Fn, kind, A=A, B=B)
    if kind == "semiaxes":
        a = r.number("contact", tbl, "a", positive=True)
        b = r.number("contact", tbl, "b", positive=True)
        check_plausible(r, "contact", "a" if a >= b else "b", None,
                        lambda _: check_semi_axes(a, b))  # mm given as m: refused
        return ContactSpec(Fn, kind, a=a, b=b)
    radii = {"wheel_rolling_radius": r.number("contact", tbl, "wheel_rolling_radius",
                                              positive=True)}
    for k in RADII_KEYS[1:]:
        if k in tbl:
            v = r.number("contact", tbl, k, allow_inf=True)
            if v == 0:
                r.fail("contact", k, f"must be non-zero (omit it for a flat surface), got {v!r}")
            radii[k] = v
    return ContactSpec(Fn, kind, radii=MappingProxyType(radii))


def read_friction(r: Reader, data: Mapping) -> float:
    """``[friction] mu`` (required, > 0, plausible: a percentage or a typo is refused)."""
    fr = r.required_table(data, "friction")
    r.unknown("friction", fr, ("mu",))
    mu = r.number("friction", fr, "mu", positive=True)
    check_plausible(r, "friction", "mu", mu)
    return mu


def read_methods(r: Reader, tbl: Mapping):
    """``[method]``: the two chosen methods, configured from their ``[method.<name>]`` tables.

    Every ``[method.<name>]`` table is turned into a configured method object
    through its class's option declarations (:mod:`wheelrail.options`) — the
    same checks as ``wr.tangential.Fastsim(nx=...)`` in Python and as the
    command line — so a bad value is refused with the file, the table, the key
    and the value, whether or not that method is the one chosen.

    Returns
    -------
    normal : NormalMethod
    tangential : TangentialMethod
    methods : dict
        Registry name -> configured method, for every ``[method.<name>]``
        table and the two chosen methods.
    """

    option_tables = {k: v for k, v in tbl.items() if isinstance(v, Mapping)}
    scalars = {k: v for k, v in tbl.items() if k not in option_tables}
    r.unknown("method", scalars, ("normal", "tangential"))
    classes = {}
    for key, family in (("normal", normal_family), ("tangential", tangential_family)):
        name = r.string("method", tbl, key, "hertz" if key == "normal" else "fastsim")
        try:
            classes[key] = family.get_class(name, argname=key)
        except InputError as exc:
            r.fail("method", key, str(exc))
    methods: dict = {}
    for name, opts in option_tables.items():
        cls = None
        for family in (normal_family, tangential_family):
            try:
                cls = family.get_class(name)
                break
            except InputError:
                continue
        if cls is None:
            r.fail("method", None, f"unknown method table [method.{name}]; methods are "
                   + ", ".join((*normal_family.registry(), *tangential_family.registry())))
        methods[cls.name] = configure(r, f"method.{name}", cls, opts)
    for key, cls in classes.items():
        methods.setdefault(cls.name, configure(r, f"method.{cls.name}", cls, {}))
    return methods[classes["normal"].name], methods[classes["tangential"].name], methods


def configure(r: Reader, table: str, cls, opts: Mapping):
    """``cls`` configured from a case-file table; a bad key or value fails naming both."""
    opts = renamed_keys(r, table, opts, RENAMED_OPTIONS.get(getattr(cls, "name", ""), {}))
    try:
        return cls.from_options(dict(opts))
    except OptionError as exc:
        r.fail(table, exc.option, exc.reason)
    except InputError as exc:   # pragma: no cover - every option error is an OptionError
        r.fail(table, None, str(exc))


def read_forces(r: Reader, tbl: Mapping, Fn: float, mu: float) -> dict:
    r.unknown("force", tbl, ("Fx", "Fy"))
    forces = {k: r.number("force", tbl, k) for k in ("Fx", "Fy") if k in tbl}
    if forces:
        ft = math.hypot(forces.get("Fx", 0.0), forces.get("Fy", 0.0))
        if ft >= mu * Fn:
            r.fail("force", None, f"|F| = {ft!r} N is not below the friction limit "
                   f"mu * Fn = {mu * Fn!r} N: no creepage can produce it")
    return forces


