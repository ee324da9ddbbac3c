"""Reading transient-rolling case files (``[transient]``)."""

from __future__ import annotations

from types import MappingProxyType
from typing import Mapping

from ..transient import TransientCase
from ...errors import CaseFileError, InputError
from ...transient.loads import KINDS, TravelFunction
from ...transient.rolling import SCHEMES
from ._reader import Reader, read_contact, read_friction, read_materials, read_toml, renamed_keys

__all__ = ["load_transient_case"]

# --------------------------------------------------------------------------- transient case
_TRANSIENT_TABLES = ("material", "contact", "friction", "transient")
_TRANSIENT_KEYS = ("travel", "step", "elements", "friction", "epsilon", "scheme", "frames",
                   "margin", "Fn", "penetration", "Fx", "xi", "eta", "phi",
                   "discretisation", "strips")


def _read_travel_function(r: Reader, tbl: Mapping, key: str):
    v = tbl[key]
    if isinstance(v, Mapping):
        spec = dict(v)
        kind = spec.pop("kind", None)
        if kind not in KINDS:
            r.fail("transient", key, f"kind must be one of {', '.join(KINDS)}, got {kind!r}")
        try:
            return TravelFunction.of(kind, **spec)
        except InputError as exc:
            r.fail("transient", key, str(exc))
    r.number("transient", tbl, key)
    return TravelFunction.of("constant", value=float(v))


def load_transient_case(path_or_str) -> TransientCase:
    """Read and validate a transient-rolling case file (``[transient]`` table).

    Tables: ``[material]`` (optional, as for :func:`load_case`), ``[contact]``
    (load and curvatures/radii/semi-axes: the Hertzian contact whose grid is
    used, and the default normal force), ``[friction]`` (``mu``) and::

        [transient]
        travel = 0.09            # rolling distance [m]
        step = 5e-5              # V·Δt [m]
        elements = 30            # elements across 2a
        friction = "exact"       # or "regularised" (then epsilon = ... [-])
        scheme = "transport"  # or "interpolated", "upwind2" (second order in dx), "averaged", "centre"
        discretisation = "uniform"   # "strips" (Paul–Hashemi; strips = 30) or "material"
        frames = 60              # traction fields stored
        Fn = 10000.0             # normal force [N] (default: [contact] Fn), or penetration = δ [m]
        Fx = 2000.0              # longitudinal force [N] (ξ unknown) -- or xi = ..., eta, phi

    Every load or creepage is a number (constant) or an inline table::

        {kind = "step", at = 0.001, before = 0.0, after = 2000.0}
        {kind = "sine", mean = 10000.0, amplitude = 4500.0, wavelength = 0.005, phase = 0.0}
        {kind = "table", x = [0.0, 0.01, 0.02], value = [0.0, 2000.0, 2000.0]}

    Raises
    ------
    CaseFileError
        Naming the file, table, key and bad value.
    """
    data, source = read_toml(path_or_str)
    r = Reader(source)
    r.unknown("", data, _TRANSIENT_TABLES)
    for name in _TRANSIENT_TABLES:
        if name in data and not isinstance(data[name], Mapping):
            raise CaseFileError(f"{source}: '{name}' must be a table [{name}], got {data[name]!r}")
    materials = read_materials(r, data.get("material", {}))
    contact = read_contact(r, r.required_table(data, "contact"))
    mu = read_friction(r, data)
    t = renamed_keys(r, "transient", r.required_table(data, "transient"),
                     {"normal_force": "Fn", "approach": "penetration", "tangential_force": "Fx"})
    r.unknown("transient", t, _TRANSIENT_KEYS)
    s: dict = {"travel": r.number("transient", t, "travel", positive=True),
               "step": r.number("transient", t, "step", positive=True)}
    for key, default in (("elements", 30), ("frames", 60)):
        v = t.get(key, default)
        if isinstance(v, bool) or not isinstance(v, int) or v < 2:
            r.fail("transient", key, f"must be an integer >= 2, got {v!r}")
        s[key] = v
    s["margin"] = r.number("transient", t, "margin", default=1.25)
    if not s["margin"] > 1:
        r.fail("transient", "margin", f"must be > 1, got {s['margin']!r}")
    s["friction"] = r.string("transient", t, "friction", "exact")
    if s["friction"] not in ("exact", "regularised", "regularized"):
        r.fail("transient", "friction", f"must be 'exact' or 'regularised', got "
               f"{s['friction']!r}")
    if s["friction"] != "exact":
        s["epsilon"] = r.number("transient", t, "epsilon", positive=True)
    elif "epsilon" in t:
        r.fail("transient", "epsilon", "only with friction = 'regularised'")
    s["discretisation"] = r.string("transient", t, "discretisation", "uniform")
    if s["discretisation"] not in ("uniform", "strips", "material"):
        r.fail("transient", "discretisation", f"must be 'uniform', 'strips' or 'material', "
               f"got {s['discretisation']!r}")
    if "strips" in t:
        v = t["strips"]
        if isinstance(v, bool) or not isinstance(v, int) or v < 2:
            r.fail("transient", "strips", f"must be an integer >= 2, got {v!r}")
        s["strips"] = v
    s["scheme"] = r.string("transient", t, "scheme", "transport")
    if s["scheme"] not in SCHEMES:
        r.fail("transient", "scheme", f"must be one of {', '.join(map(repr, SCHEMES))}, "
               f"got {s['scheme']!r}")
    if "Fn" in t and "penetration" in t:
        r.fail("transient", "penetration", "give Fn or penetration, not both")
    for key in ("Fn", "penetration", "Fx"):
        if key in t:
            s[key] = _read_travel_function(r, t, key)
    given = [k for k in ("xi", "eta", "phi") if k in t]
    cr = [(_read_travel_function(r, t, k) if k in t else None) for k in ("xi", "eta", "phi")]
    if "Fx" in s:
        if "xi" in t:
            r.fail("transient", "xi", "with Fx the creepage xi is the unknown: "
                   "omit xi")
        if given:
            s["creepage"] = (None, cr[1] or 0.0, cr[2] or 0.0)
    else:
        if not given:
            r.fail("transient", None, "give Fx [N] or creepages xi, eta, "
                   "phi")
        s["creepage"] = tuple(c if c is not None else 0.0 for c in cr)
    case = TransientCase(materials=materials, contact=contact, mu=mu,
                         settings=MappingProxyType(s), source=source)
    try:
        case.hertz_contact
    except InputError as exc:
        raise CaseFileError(f"{source}: [contact]: {exc}") from None
    return case


