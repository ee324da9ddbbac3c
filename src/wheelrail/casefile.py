"""Case files: a TOML description of one contact problem → validated objects → results.

A case file describes one wheel–rail contact: materials, the normal contact
(load and curvatures, radii or semi-axes), creepages, friction and the methods
to use. :func:`load_case` reads and validates it into a frozen :class:`Case`;
:func:`run_case` solves it and returns a JSON-ready dictionary in SI units.

Schema (SI units; every table except ``[contact]`` and ``[friction]`` is
optional)::

    [material]              # same material for wheel and rail (default: steel
    E = 2.1e11              # E = 2.1e11 Pa, nu = 0.28), or the two tables
    nu = 0.28               # [material.wheel] and [material.rail], each with E, nu

    [contact]
    load = 7500.0           # normal force Fn [N]
    A = 1.0869565           # combined curvatures [1/m] ...
    B = 1.6666667
    # ... or principal radii [m] (concave negative, omitted = flat/straight):
    # wheel_rolling_radius, wheel_profile_radius, rail_profile_radius,
    # rail_longitudinal_radius
    # ... or the semi-axes a, b [m] of the contact ellipse.

    [creepage]              # wheel relative to rail (Kalker's convention)
    xi = -0.0007            # longitudinal [-]
    eta = 0.0               # lateral [-]
    phi = 0.0               # spin [1/m]

    [friction]
    mu = 0.2

    [method]
    normal = "hertz"        # or "bem"
    tangential = "fastsim"  # any name of wheelrail.available_methods()
    [method.fastsim]        # options of a method, [method.<name>]
    nx = 40
    [method.bem]
    elements = 100

    [force]                 # optional: prescribed Fx and/or Fy [N] replace
    Fx = -1000.0            # the creepage xi and/or eta (solved for)

A **wheelset case** (a wheelset on a track with real profiles) has, instead
of ``[contact]``, ``[creepage]`` and ``[force]``, the tables::

    [wheelset]
    profile = "S1002"       # built-in name or a profile file (relative to the case file)
    # profile_right = "worn.prw"
    nominal_radius = 0.46   # [m]
    flange_back = 1.360     # [m]
    tape_circle_offset = 0.070

    [track]
    profile = "60E1"        # built-in name or a file; profile_right optional
    gauge = 1.435           # [m]
    inclination = "1/40"    # slope, a number or "1/n"
    canted = false          # true: the rail profile file is already inclined

    [motion]
    speed = 20.0            # forward speed V [m/s]
    # omega = 43.5          # [rad/s] about the axle; omitted: free rolling V/r0
    # lateral_velocity, vertical_velocity [m/s], yaw_rate, roll_rate [rad/s],
    # roller_radius [m] (a wheel on a roller rig)

    [position]
    y = 0.005               # lateral shift [m], or a list, or a sweep:
    # y = {start = -0.008, stop = 0.008, num = 81}
    yaw = 0.0               # [rad] (or a list, one per y), or yaw_per_y [rad/m]
    # roll = 0.0            # [rad]; omitted: from the rigid contact constraint
    vertical_load = 10e3    # [N] per wheel, or [left, right]; or z [m]

with ``[friction]``, ``[method]`` and ``[material]`` as above. Every solve
goes through :func:`wheelrail.solve` (:func:`solve_case`,
:func:`solve_wheelset_case`); this module only reads and validates.

Unknown tables and keys are errors (they are usually typos). Every error is a
:class:`wheelrail.errors.CaseFileError` whose one-line message names the file,
the table, the key and the bad value.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from types import MappingProxyType
from typing import Any, Mapping

import numpy as np

from .conventions import CREEPAGE_UNITS, FORCE_UNITS
from .errors import CaseFileError, InputError
from .materials import STEEL, Material, MaterialPair
from .results import to_jsonable

try:  # Python >= 3.11
    import tomllib
except ModuleNotFoundError:  # pragma: no cover - Python 3.10
    import tomli as tomllib

__all__ = ["Case", "ContactSpec", "CaseResult", "load_case", "case_from_dict", "run_case",
           "solve_case", "NORMAL_METHODS", "RADII_KEYS", "DEFAULT_CASE"]

#: Normal-contact methods accepted by ``[method] normal`` (see :func:`wheelrail.normal_methods`).
NORMAL_METHODS = ("hertz", "bem")
#: Keys of ``[contact]`` that give principal radii [m].
RADII_KEYS = ("wheel_rolling_radius", "wheel_profile_radius", "rail_profile_radius",
              "rail_longitudinal_radius")

_TOP_TABLES = ("material", "contact", "creepage", "friction", "method", "force")

#: The built-in example: steel, 7500 N, wheel radius 0.46 m on a rail head
#: radius of 0.30 m (A = 0.5/0.46, B = 0.5/0.30 1/m), μ = 0.3, FASTSIM.
DEFAULT_CASE = {
    "material": {"E": 2.1e11, "nu": 0.28},
    "contact": {"load": 7500.0, "wheel_rolling_radius": 0.46, "rail_profile_radius": 0.30},
    "creepage": {"xi": -1.0e-3, "eta": 0.0, "phi": 0.0},
    "friction": {"mu": 0.3},
    "method": {"normal": "hertz", "tangential": "fastsim"},
}

#: Units of the quantities written by :func:`run_case`.
UNITS = {
    "a": "m", "b": "m", "c": "m", "p0": "Pa", "p_max": "Pa", "penetration": "m",
    **FORCE_UNITS, **CREEPAGE_UNITS, "mu": "1",
    "area": "m^2", "adhesion_area": "m^2", "utilisation": "1", "A": "1/m", "B": "1/m",
}


# --------------------------------------------------------------------------- objects
@dataclass(frozen=True)
class ContactSpec:
    """How the normal contact is described in ``[contact]``.

    Exactly one of three descriptions is set: curvatures ``A``, ``B`` [1/m];
    semi-axes ``a``, ``b`` [m]; or principal ``radii`` [m] (a mapping with
    the keys of :data:`RADII_KEYS`, ``wheel_rolling_radius`` required).

    Attributes
    ----------
    load : float
        Normal force Fn [N].
    kind : str
        ``"curvatures"``, ``"semiaxes"`` or ``"radii"``.
    """

    load: float
    kind: str
    A: float | None = None
    B: float | None = None
    a: float | None = None
    b: float | None = None
    radii: Mapping[str, float] = field(default_factory=lambda: MappingProxyType({}))

    def hertz(self, material):
        """The :class:`wheelrail.HertzContact` of this description."""
        from .normal.hertz import hertz, hertz_from_radii, hertz_from_semiaxes

        if self.kind == "curvatures":
            return hertz(self.load, self.A, self.B, material)
        if self.kind == "semiaxes":
            return hertz_from_semiaxes(self.a, self.b, self.load, material)
        return hertz_from_radii(self.load, material=material, **dict(self.radii))

    def to_dict(self) -> dict:
        out = {"load": self.load}
        if self.kind == "curvatures":
            out.update(A=self.A, B=self.B)
        elif self.kind == "semiaxes":
            out.update(a=self.a, b=self.b)
        else:
            out.update(self.radii)
        return out


@dataclass(frozen=True)
class Case:
    """A validated contact case (see the module docstring for the file format).

    Attributes
    ----------
    materials : MaterialPair
    contact : ContactSpec
    creepage : tuple of float
        (ξ [-], η [-], φ [1/m]).
    mu : float
        Friction coefficient [-].
    normal, tangential : str
        Method names (tangential resolved to its registry name).
    options : mapping of str to mapping
        ``[method.<name>]`` tables, by method name.
    forces : mapping of str to float
        Prescribed ``Fx`` and/or ``Fy`` [N] (empty if none).
    source : str
        File name or ``"<string>"`` (used in messages).
    """

    materials: MaterialPair
    contact: ContactSpec
    creepage: tuple
    mu: float
    normal: str = "hertz"
    tangential: str = "fastsim"
    options: Mapping[str, Mapping[str, Any]] = field(default_factory=lambda: MappingProxyType({}))
    forces: Mapping[str, float] = field(default_factory=lambda: MappingProxyType({}))
    source: str = "<case>"

    @property
    def xi(self) -> float:
        return self.creepage[0]

    @property
    def eta(self) -> float:
        return self.creepage[1]

    @property
    def phi(self) -> float:
        return self.creepage[2]

    @property
    def tangential_options(self) -> dict:
        """Options for the tangential method (``[method.<tangential>]``)."""
        return dict(self.options.get(self.tangential, {}))

    @property
    def normal_options(self) -> dict:
        """Options for the normal method (``[method.<normal>]``; the method's defaults apply
        to the others)."""
        return dict(self.options.get(self.normal, {}))

    @cached_property
    def hertz_contact(self):
        """The Hertzian contact of :attr:`contact` (computed once)."""
        return self.contact.hertz(self.materials)

    def to_toml(self) -> str:
        """The case as TOML text; :func:`load_case` of it gives an equal case."""
        w, r = self.materials.wheel, self.materials.rail
        lines = []
        if w == r:
            lines += ["[material]", f"E = {w.E!r}", f"nu = {w.nu!r}", ""]
        else:
            for body, m in (("wheel", w), ("rail", r)):
                lines += [f"[material.{body}]", f"E = {m.E!r}", f"nu = {m.nu!r}", ""]
        lines.append("[contact]")
        lines += [f"{k} = {_toml_value(v)}" for k, v in self.contact.to_dict().items()]
        lines += ["", "[creepage]", *(f"{k} = {v!r}" for k, v in
                                      zip(("xi", "eta", "phi"), self.creepage)),
                  "", "[friction]", f"mu = {self.mu!r}",
                  "", "[method]", f"normal = {_toml_value(self.normal)}",
                  f"tangential = {_toml_value(self.tangential)}"]
        for name, opts in self.options.items():
            lines += ["", f'[method."{name}"]',
                      *(f"{k} = {_toml_value(v)}" for k, v in opts.items())]
        if self.forces:
            lines += ["", "[force]", *(f"{k} = {v!r}" for k, v in self.forces.items())]
        return "\n".join(lines) + "\n"

    def replace(self, **changes) -> "Case":
        """A copy with some attributes changed (``creepage``, ``tangential``, …)."""
        from dataclasses import replace

        return replace(self, **changes)


@dataclass(frozen=True)
class CaseResult:
    """Everything :func:`solve_case` computed.

    Attributes
    ----------
    case : Case
    contact : HertzContact
        The Hertz ellipse used by the tangential method.
    forces : CreepForces
        Creep forces (``fields`` holds traction fields for FASTSIM / exact).
    normal : NormalSolution or None
        The boundary-element normal solution (``normal = "bem"``).
    summary : dict
        The JSON-ready dictionary returned by :func:`run_case`.
    result : ContactResult or None
        What :func:`wheelrail.solve` returned (``None`` for a ``[force]`` case).
    """

    case: Case
    contact: Any
    forces: Any
    normal: Any
    summary: dict
    result: Any = None

    @property
    def grid(self):
        """The grid of :attr:`normal` (None without a boundary-element solution)."""
        return None if self.normal is None else self.normal.grid


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        return "inf" if v == math.inf else "-inf" if v == -math.inf else repr(v)
    if isinstance(v, int):
        return str(v)
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    raise CaseFileError(f"cannot write {v!r} to TOML")


# --------------------------------------------------------------------------- reading
def load_case(path_or_str):
    """Read and validate a case file: a single contact or a wheelset on a track.

    Parameters
    ----------
    path_or_str : str or os.PathLike
        A path to a ``.toml`` file, or the TOML text itself (a string that
        contains a newline or ``=`` is taken as text).

    Returns
    -------
    Case or WheelsetCase
        A :class:`WheelsetCase` when the file has a ``[wheelset]``, ``[track]``,
        ``[motion]`` or ``[position]`` table.

    Raises
    ------
    CaseFileError
        Unreadable file, malformed TOML (with line and column), unknown table
        or key, or an invalid value; the message names file, table, key and
        value.

    Examples
    --------
    >>> case = load_case('''
    ... [contact]
    ... load = 7500.0
    ... A = 1.0869565
    ... B = 1.6666667
    ... [friction]
    ... mu = 0.3
    ... [method]
    ... tangential = "linear"
    ... ''')
    >>> case.mu, case.tangential
    (0.3, 'linear')
    """
    data, source = _read_toml(path_or_str)
    return case_from_dict(data, source=source)



def _read_toml(path_or_str):
    """``(data, source)`` of a case given as a path or as TOML text; CaseFileError if unreadable."""
    if isinstance(path_or_str, str) and ("\n" in path_or_str or "=" in path_or_str):
        text, source = path_or_str, "<string>"
    else:
        path = Path(path_or_str)
        source = str(path)
        try:
            text = path.read_text(encoding="utf-8")
        except FileNotFoundError:
            raise CaseFileError(f"{source}: case file not found") from None
        except (OSError, UnicodeDecodeError) as exc:
            raise CaseFileError(f"{source}: cannot read case file: {exc}") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise CaseFileError(f"{source}: malformed TOML: {exc}") from None
    return data, source

def case_from_dict(data: Mapping, source: str = "<dict>"):
    """Validate a parsed case (the dictionary ``tomllib`` returns).

    Returns a :class:`Case` (a single contact, ``[contact]``) or a
    :class:`WheelsetCase` (``[wheelset]``, ``[track]``, ``[motion]``, ``[position]``).
    """
    r = _Reader(source)
    if not isinstance(data, Mapping):
        raise CaseFileError(f"{source}: a case must be a table, got {type(data).__name__}")
    if _is_wheelset_case(data):
        return _wheelset_case_from_dict(r, data)
    r.unknown("", data, _TOP_TABLES)
    for name in _TOP_TABLES:
        if name in data and not isinstance(data[name], Mapping):
            raise CaseFileError(f"{source}: '{name}' must be a table [{name}], got {data[name]!r}")

    materials = _read_materials(r, data.get("material", {}))
    contact = _read_contact(r, r.required_table(data, "contact"))
    cr = data.get("creepage", {})
    r.unknown("creepage", cr, ("xi", "eta", "phi"))
    creepage = tuple(r.number("creepage", cr, k, default=0.0) for k in ("xi", "eta", "phi"))
    fr = r.required_table(data, "friction")
    r.unknown("friction", fr, ("mu",))
    mu = r.number("friction", fr, "mu", positive=True)
    _check_plausible(r, "friction", "mu", mu)
    normal, tangential, options = _read_methods(r, data.get("method", {}))
    forces = _read_forces(r, data.get("force", {}), contact.load, mu)
    case = Case(materials=materials, contact=contact, creepage=creepage, mu=mu, normal=normal,
                tangential=tangential, options=MappingProxyType(options),
                forces=MappingProxyType(forces), source=source)
    try:  # catch radii that do not form a convex contact etc. now, with the table named
        case.hertz_contact
    except InputError as exc:
        raise CaseFileError(f"{source}: [contact]: {exc}") from None
    return case


def _check_plausible(r, table: str, key: str, value) -> None:
    """Plausibility check of one value at read time (see :mod:`wheelrail.plausibility`)."""
    from .plausibility import check_friction

    try:
        check_friction(value)
    except InputError as exc:
        r.fail(table, key, str(exc))


class _Reader:
    """Typed access to the parsed tables with messages naming file, table, key, value."""

    def __init__(self, source: str):
        self.source = source

    def fail(self, table: str, key: str | None, msg: str):
        where = f"[{table}]" if table else "top level"
        if key is not None:
            where += f" {key}"
        raise CaseFileError(f"{self.source}: {where}: {msg}")

    def unknown(self, table: str, tbl: Mapping, allowed) -> None:
        extra = [k for k in tbl if k not in allowed]
        if extra:
            kind = "table" if not table else "key"
            allowed_s = ", ".join(allowed)
            where = f"[{table}]" if table else "top level"
            raise CaseFileError(f"{self.source}: {where}: unknown {kind}(s) "
                                f"{', '.join(repr(k) for k in extra)}; allowed: {allowed_s}")

    def required_table(self, data: Mapping, name: str) -> Mapping:
        if name not in data:
            raise CaseFileError(f"{self.source}: missing table [{name}]")
        return data[name]

    def number(self, table: str, tbl: Mapping, key: str, *, default=None, positive=False,
               lo=None, hi=None, allow_inf=False) -> float:
        if key not in tbl:
            if default is None:
                self.fail(table, key, "missing (required)")
            return default
        v = tbl[key]
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            self.fail(table, key, f"must be a number, got {v!r}")
        v = float(v)
        if math.isnan(v) or (math.isinf(v) and not allow_inf):
            self.fail(table, key, f"must be finite, got {v!r}")
        if positive and v <= 0:
            self.fail(table, key, f"must be > 0, got {v!r}")
        if lo is not None and v < lo:
            self.fail(table, key, f"must be >= {lo}, got {v!r}")
        if hi is not None and v >= hi:
            self.fail(table, key, f"must be < {hi}, got {v!r}")
        return v

    def string(self, table: str, tbl: Mapping, key: str, default: str) -> str:
        v = tbl.get(key, default)
        if not isinstance(v, str):
            self.fail(table, key, f"must be a string, got {v!r}")
        return v


def _read_material(r: _Reader, table: str, tbl) -> Material:
    if not isinstance(tbl, Mapping):
        r.fail(table, None, f"must be a table, got {tbl!r}")
    r.unknown(table, tbl, ("E", "nu"))
    E = r.number(table, tbl, "E", positive=True)
    nu = r.number(table, tbl, "nu", lo=0.0, hi=0.5)
    return Material(E, nu)


def _read_materials(r: _Reader, tbl: Mapping) -> MaterialPair:
    if not tbl:
        return MaterialPair.same(STEEL)
    if "wheel" in tbl or "rail" in tbl:
        r.unknown("material", tbl, ("wheel", "rail"))
        for body in ("wheel", "rail"):
            if body not in tbl:
                r.fail("material", None, f"[material.{body}] is missing (give both "
                       "[material.wheel] and [material.rail], or E and nu in [material])")
        return MaterialPair(_read_material(r, "material.wheel", tbl["wheel"]),
                            _read_material(r, "material.rail", tbl["rail"]))
    return MaterialPair.same(_read_material(r, "material", tbl))


def _read_contact(r: _Reader, tbl: Mapping) -> ContactSpec:
    allowed = ("load", "A", "B", "a", "b", *RADII_KEYS)
    r.unknown("contact", tbl, allowed)
    load = r.number("contact", tbl, "load", positive=True)
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
        return ContactSpec(load, kind, A=A, B=B)
    if kind == "semiaxes":
        a = r.number("contact", tbl, "a", positive=True)
        b = r.number("contact", tbl, "b", positive=True)
        return ContactSpec(load, kind, a=a, b=b)
    radii = {"wheel_rolling_radius": r.number("contact", tbl, "wheel_rolling_radius",
                                              positive=True)}
    for k in RADII_KEYS[1:]:
        if k in tbl:
            v = r.number("contact", tbl, k, allow_inf=True)
            if v == 0:
                r.fail("contact", k, f"must be non-zero (omit it for a flat surface), got {v!r}")
            radii[k] = v
    return ContactSpec(load, kind, radii=MappingProxyType(radii))


def _canonical_tangential(name: str) -> str | None:
    from .api import method_key

    return method_key(name)


def _read_methods(r: _Reader, tbl: Mapping):
    from .api import METHODS, NORMAL_METHODS as NORMALS, get_method, get_normal_method

    option_tables = {k: v for k, v in tbl.items() if isinstance(v, Mapping)}
    scalars = {k: v for k, v in tbl.items() if k not in option_tables}
    r.unknown("method", scalars, ("normal", "tangential"))
    normal = r.string("method", tbl, "normal", "hertz").lower()
    if normal not in NORMALS:
        r.fail("method", "normal", f"unknown normal method {normal!r}; choose one of "
               + ", ".join(NORMALS))
    tname = r.string("method", tbl, "tangential", "fastsim")
    tangential = _canonical_tangential(tname)
    if tangential is None:
        r.fail("method", "tangential", f"unknown tangential method {tname!r}; choose one of "
               + ", ".join(METHODS))
    options: dict[str, dict] = {}
    for name, opts in option_tables.items():
        key = name.lower() if name.lower() in NORMALS else _canonical_tangential(name)
        if key is None:
            r.fail("method", None, f"unknown method table [method.{name}]; methods are "
                   + ", ".join((*NORMALS, *METHODS)))
        options[key] = dict(opts)
        _check_option_values(r, name, key, options[key])
    # options of the chosen methods are checked now (typos, types), the others kept as given
    _check_method_options(r, normal, get_normal_method(normal), options.get(normal, {}))
    _check_method_options(r, tangential, get_method(tangential), options.get(tangential, {}))
    return normal, tangential, options


def _check_option_values(r: _Reader, table: str, method: str, opts: dict) -> None:
    """Validate every value of a [method.<name>] table now (see :mod:`wheelrail._options`)."""
    from ._options import VALIDATORS

    checks = VALIDATORS.get(method, {})
    for k, v in opts.items():
        if k in checks:
            try:
                checks[k](k, v)
            except InputError as exc:
                r.fail(f"method.{table}", k, str(exc))


#: Integer options that need at least two elements/cells/strips.
_AT_LEAST_TWO = ("elements", "strips", "cells", "nx", "ny")


def _check_method_options(r: _Reader, name: str, impl, opts: dict) -> None:
    table = f"method.{name}"
    try:
        impl.check_options(opts)
    except InputError as exc:
        r.fail(table, None, str(exc))
    for key, v in opts.items():
        default = impl.options[key]
        if isinstance(default, bool):
            if not isinstance(v, bool):
                r.fail(table, key, f"must be true or false, got {v!r}")
        elif isinstance(default, int):
            if isinstance(v, bool) or not isinstance(v, int):
                r.fail(table, key, f"must be an integer, got {v!r}")
            if key in _AT_LEAST_TWO and v < 2:
                r.fail(table, key, f"must be an integer >= 2, got {v!r}")
        elif isinstance(default, float) or (default is None and key.endswith(("size", "tol"))):
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                r.fail(table, key, f"must be a finite number, got {v!r}")
            if v <= 0 and key.endswith(("size", "tol", "margin", "width", "angle")):
                r.fail(table, key, f"must be > 0, got {v!r}")
        elif isinstance(default, str) and not isinstance(v, str):
            r.fail(table, key, f"must be a string, got {v!r}")


def _read_forces(r: _Reader, tbl: Mapping, load: float, mu: float) -> dict:
    r.unknown("force", tbl, ("Fx", "Fy"))
    forces = {k: r.number("force", tbl, k) for k in ("Fx", "Fy") if k in tbl}
    if forces:
        ft = math.hypot(forces.get("Fx", 0.0), forces.get("Fy", 0.0))
        if ft >= mu * load:
            r.fail("force", None, f"|F| = {ft!r} N is not below the friction limit "
                   f"mu * load = {mu * load!r} N: no creepage can produce it")
    return forces


# --------------------------------------------------------------------------- solving
def solve_case(case: Case) -> CaseResult:
    """Solve a :class:`Case` through :func:`wheelrail.solve` and keep its results.

    The case file only chooses: the problem is the Hertzian contact of
    ``[contact]``, solved by ``wr.solve(contact, creepage, mu, normal=...,
    tangential=..., normal_options=[method.<normal>],
    tangential_options=[method.<tangential>])``. With ``normal = "bem"`` the
    boundary-element patch is what the tangential method reads (FASTSIM its
    strips, the exact theory its pressure, closed-form laws its equivalent
    ellipse). A ``[force]`` table prescribes Fx and/or Fy instead:
    :func:`wheelrail.prescribed.solve_creepages` finds the creepages on the
    Hertz ellipse.

    Returns
    -------
    CaseResult
        ``summary`` is the dictionary returned by :func:`run_case`.
    """
    from .api import solve

    if not isinstance(case, Case):
        raise InputError(f"solve_case needs a Case (from load_case), got {type(case).__name__}")
    contact = case.hertz_contact
    xi, eta, phi = case.creepage
    if case.forces:
        from .prescribed import solve_creepages

        forces = solve_creepages(contact, case.mu, Fx=case.forces.get("Fx"),
                                 Fy=case.forces.get("Fy"), creepage=(xi, eta, phi),
                                 method=case.tangential, **case.tangential_options)
        xi = forces.info.get("xi", xi)
        eta = forces.info.get("eta", eta)
        summary = _summary(case, contact, forces, None, None, xi, eta, phi)
        return CaseResult(case, contact, forces, None, summary)
    result = solve(contact, (xi, eta, phi), case.mu, normal=case.normal,
                   tangential=case.tangential, normal_options=case.normal_options,
                   tangential_options=case.tangential_options)
    patch = result.patches[0]
    normal = patch.patch.info.get("normal_solution")
    summary = _summary(case, contact, patch.forces, patch, normal, xi, eta, phi,
                       method=result.tangential, normal_method=result.normal)
    return CaseResult(case, contact, patch.forces, normal, summary, result)


def run_case(case) -> dict:
    """Solve a case and return a JSON-ready dictionary (SI units).

    A :class:`Case` gives the keys ``a, b`` [m], ``p0`` [Pa], ``penetration`` [m],
    ``Fn, Fx, Fy`` [N], ``Mz`` [N·m], ``xi, eta`` [-], ``phi`` [1/m] (the
    creepages used, solved ones for prescribed forces), ``mu``, ``method``
    (tangential), ``normal_method``, ``status``, ``iterations``, ``area`` [m²]
    and, when the methods provide them, ``p_max`` [Pa] and ``adhesion_area``
    [m²]; ``units`` maps each key to its unit.

    A :class:`WheelsetCase` at one position gives
    :meth:`wheelrail.contact.WheelRailResult.to_dict` (per-patch results,
    ``force_track``, ``pose``) with the validated input under ``case``; a
    sweep is solved with :func:`solve_wheelset_case` (an ``xarray.Dataset``).
    """
    if isinstance(case, WheelsetCase):
        if case.sweep:
            raise InputError(f"{case.source}: [position] y is a sweep; solve it with "
                             "solve_wheelset_case (an xarray.Dataset) or 'wheelrail wheelset'")
        out = solve_wheelset_case(case).to_dict()
        out["case"] = case.to_dict()
        return out
    if not isinstance(case, Case):
        raise InputError(f"run_case needs a Case (from load_case), got {type(case).__name__}")
    return solve_case(case).summary


def _scalar(v):
    arr = np.asarray(v)
    return arr.item() if arr.ndim == 0 else arr.tolist()


def _summary(case, contact, forces, patch, normal, xi, eta, phi, method=None,
             normal_method=None) -> dict:
    Fn = contact.load if patch is None else patch.Fn
    Ft = float(np.hypot(forces.Fx, forces.Fy))
    out = {
        "a": contact.a, "b": contact.b, "c": float(contact.c), "A": contact.A, "B": contact.B,
        "p0": contact.p0, "penetration": contact.penetration, "Fn": Fn,
        "area": float(contact.area) if patch is None else patch.area,
        "p_max": contact.p0 if patch is None else patch.p_max,
        "Fx": forces.Fx, "Fy": forces.Fy, "Mz": forces.Mz,
        "xi": xi, "eta": eta, "phi": phi, "mu": case.mu,
        "utilisation": Ft / (case.mu * Fn),
        "method": method or forces.method, "normal_method": normal_method or case.normal,
        "status": forces.status, "iterations": forces.iterations,
    }
    if patch is not None and patch.patch.method == "bem":
        # the boundary-element patch replaces Hertz's numbers; Hertz's are kept beside
        if np.isfinite(patch.patch.penetration):
            out["penetration"] = patch.patch.penetration
        if normal is not None:
            out.update(normal_iterations=normal.iterations, normal_status=normal.status,
                       truncated=bool(normal.truncated))
        out["hertz"] = {"a": contact.a, "b": contact.b, "p0": contact.p0,
                        "penetration": contact.penetration}
    for k, v in (forces.info or {}).items():  # method extras (adhesion_area, ...), scalars only
        if k not in out and np.ndim(v) == 0:
            out[k] = v
    if patch is not None and np.isfinite(patch.adhesion_area):
        out["adhesion_area"] = patch.adhesion_area
    frac = out.get("adhesion_fraction")  # FASTSIM gives the fraction, the exact theory the area
    if "adhesion_area" not in out and frac is not None:
        out["adhesion_area"] = float(frac) * float(out["area"])
    if case.forces:
        out["prescribed"] = dict(case.forces)
    out["source"] = case.source
    out["units"] = {k: u for k, u in UNITS.items() if k in out}
    return {k: (_scalar(v) if isinstance(v, (np.ndarray, np.generic, float, int)) else
                to_jsonable(v)) for k, v in out.items()}


# =========================================================================== wheelset cases
#: Top-level tables of a wheelset case (a wheelset on a track, real profiles).
_WHEELSET_TABLES = ("material", "wheelset", "track", "motion", "position", "friction", "method")
_WHEELSET_KEYS = ("profile", "profile_right", "nominal_radius", "flange_back",
                  "tape_circle_offset")
_TRACK_KEYS = ("profile", "profile_right", "gauge", "inclination", "gauge_height", "canted")
_MOTION_KEYS = ("speed", "omega", "lateral_velocity", "vertical_velocity", "yaw_rate",
                "roll_rate", "roller_radius")
_POSITION_KEYS = ("y", "yaw", "yaw_per_y", "roll", "vertical_load", "z", "tolerance")
#: Largest number of positions of a sweep read from a case file.
MAX_POSITIONS = 100_001


@dataclass(frozen=True, eq=False)
class WheelsetCase:
    """A validated wheelset-on-track case (``[wheelset]``, ``[track]``, ``[motion]``,
    ``[position]``; see the module docstring and ``docs/cli.md``). SI units.

    Attributes
    ----------
    wheelset : Wheelset
    track : Track
    motion : Motion
    y : ndarray, shape (n,)
        Lateral shifts [m] (one for a single position).
    yaw : ndarray, shape (n,)
        Yaw angle at each shift [rad].
    roll : float or None
        Roll angle [rad]; ``None``: from the rigid contact constraint.
    vertical_load : tuple of float or None
        Vertical force on the (left, right) wheel [N] ...
    z : float or None
        ... or the height of the axle centre [m].
    tolerance : float
        Largest separation of a candidate contact point [m].
    sweep : bool
        True when ``[position] y`` is a range or a list (even of one value).
    materials : MaterialPair
    mu : float
    normal, tangential : str
    options : mapping
        ``[method.<name>]`` tables.
    source : str
    tables : mapping
        The tables as read (for the JSON output).
    """

    wheelset: Any
    track: Any
    motion: Any
    y: np.ndarray
    yaw: np.ndarray
    roll: float | None
    vertical_load: tuple | None
    z: float | None
    tolerance: float
    sweep: bool
    materials: MaterialPair
    mu: float
    normal: str = "hertz"
    tangential: str = "fastsim"
    options: Mapping[str, Mapping[str, Any]] = field(default_factory=lambda: MappingProxyType({}))
    source: str = "<case>"
    tables: Mapping[str, Any] = field(default_factory=lambda: MappingProxyType({}))

    @property
    def normal_options(self) -> dict:
        """``[method.<normal>]``."""
        return dict(self.options.get(self.normal, {}))

    @property
    def tangential_options(self) -> dict:
        """``[method.<tangential>]``."""
        return dict(self.options.get(self.tangential, {}))

    def position(self, i: int = 0):
        """The :class:`wheelrail.WheelRailPosition` of shift number ``i``."""
        from .contact.wheelrail import WheelRailPosition

        return WheelRailPosition(self.wheelset, self.track, float(self.y[i]), float(self.yaw[i]),
                                 self.roll, vertical_load=self.vertical_load, z=self.z,
                                 material=self.materials, tolerance=self.tolerance)

    def to_dict(self) -> dict:
        """The validated input (JSON-ready, SI)."""
        return to_jsonable({**{k: dict(v) if isinstance(v, Mapping) else v
                               for k, v in self.tables.items()},
                            "y": self.y, "yaw": self.yaw, "source": self.source})


def _is_wheelset_case(data: Mapping) -> bool:
    return any(k in data for k in ("wheelset", "track", "position", "motion"))


def load_wheelset_case(path_or_str) -> WheelsetCase:
    """Read and validate a wheelset case file (see :func:`load_case`)."""
    case = load_case(path_or_str)
    if not isinstance(case, WheelsetCase):
        raise CaseFileError(f"{case.source}: not a wheelset case: it has no [wheelset], "
                            "[track], [motion] and [position] tables (run it with "
                            "'wheelrail solve')")
    return case


def load_contact_case(path_or_str) -> Case:
    """Read and validate a single-contact case file (``[contact]``; see :func:`load_case`)."""
    case = load_case(path_or_str)
    if isinstance(case, WheelsetCase):
        raise CaseFileError(f"{case.source}: this is a wheelset case ([wheelset], [track], "
                            "[motion], [position]); run it with 'wheelrail wheelset'")
    return case


def _base_dir(source: str) -> Path:
    return Path(source).parent if not source.startswith("<") else Path.cwd()


def _read_profile(r: _Reader, table: str, tbl: Mapping, key: str, kind: str, default):
    from . import profiles
    from .errors import ProfileError

    if key not in tbl and default is None:
        return None, None
    spec = r.string(table, tbl, key, default)
    names = {n.lower() for n in profiles.available()}
    try:
        if spec.lower() in names:
            prof = profiles.load(spec)
            if getattr(prof, "kind", kind) != kind:
                r.fail(table, key, f"{spec!r} is a {prof.kind} profile; a {kind} profile is "
                       "needed here")
            return prof, spec
        path = Path(spec).expanduser()
        if not path.is_absolute():
            path = _base_dir(r.source) / path
        if not path.exists():
            r.fail(table, key, f"{spec!r} is neither a built-in profile ("
                   + ", ".join(profiles.available()) + f") nor an existing file ({path})")
        return profiles.read(path, kind=kind), str(path)
    except (ProfileError, InputError) as exc:
        r.fail(table, key, f"{spec!r}: {' '.join(str(exc).split())}")


def _construct(r: _Reader, table: str, make):
    from .errors import ProfileError

    try:
        return make()
    except (InputError, ProfileError) as exc:
        r.fail(table, None, " ".join(str(exc).split()))


def _read_slope(r: _Reader, table: str, tbl: Mapping, key: str, default: float) -> float:
    if key not in tbl:
        return default
    v = tbl[key]
    if isinstance(v, str):
        s = v.strip()
        try:
            if "/" in s:
                num, den = s.split("/", 1)
                out = float(num) / float(den)
            else:
                out = float(s)
        except (ValueError, ZeroDivisionError):
            r.fail(table, key, f"must be a slope like \"1/40\" or 0.025, got {v!r}")
        if not math.isfinite(out):
            r.fail(table, key, f"must be finite, got {v!r}")
        return out
    return r.number(table, tbl, key)


def _read_y(r: _Reader, tbl: Mapping):
    """``[position] y``: a number, a list, or a range {start, stop, num}; -> (array, sweep)."""
    if "y" not in tbl:
        r.fail("position", "y", "missing (required): a lateral shift [m], a list of shifts or "
               "a range {start = ..., stop = ..., num = ...}")
    v = tbl["y"]
    if isinstance(v, Mapping):
        r.unknown("position.y", v, ("start", "stop", "num"))
        start = r.number("position.y", v, "start")
        stop = r.number("position.y", v, "stop")
        num = v.get("num")
        if isinstance(num, bool) or not isinstance(num, int) or not 1 <= num <= MAX_POSITIONS:
            r.fail("position.y", "num", f"must be an integer in 1..{MAX_POSITIONS}, got {num!r}")
        if num > 1 and stop <= start:
            r.fail("position.y", "stop", f"must be > start = {start!r}, got {stop!r}")
        return np.linspace(start, stop, num), True
    if isinstance(v, list):
        if not v:
            r.fail("position", "y", "the list of lateral shifts is empty")
        vals = [r.number("position", {"y": x}, "y") for x in v]
        return np.array(vals, dtype=float), True
    return np.array([r.number("position", tbl, "y")]), False


def _read_position(r: _Reader, tbl: Mapping):
    r.unknown("position", tbl, _POSITION_KEYS)
    y, sweep = _read_y(r, tbl)
    if np.any(np.abs(y) > 0.05):
        bad = float(y[np.argmax(np.abs(y))])
        r.fail("position", "y", f"lateral shifts are in metres and |y| <= 0.05 m, got {bad!r}")
    if "yaw" in tbl and "yaw_per_y" in tbl:
        r.fail("position", None, "give yaw [rad] or yaw_per_y [rad/m], not both")
    if isinstance(tbl.get("yaw"), list):
        yaw = np.array([r.number("position", {"yaw": x}, "yaw") for x in tbl["yaw"]], float)
        if yaw.shape != y.shape:
            r.fail("position", "yaw", f"a list of yaw angles needs one per lateral shift "
                   f"({y.size}), got {yaw.size}")
    elif "yaw_per_y" in tbl:
        yaw = r.number("position", tbl, "yaw_per_y") * y
    else:
        yaw = np.full(y.shape, r.number("position", tbl, "yaw", default=0.0))
    if np.any(np.abs(yaw) > 0.2):
        bad = float(yaw[np.argmax(np.abs(yaw))])
        r.fail("position", "yaw_per_y" if "yaw_per_y" in tbl else "yaw",
               f"gives a yaw angle of {bad!r} rad; |yaw| must be <= 0.2 rad")
    roll = None
    if "roll" in tbl:
        roll = r.number("position", tbl, "roll")
        if abs(roll) > 0.2:
            r.fail("position", "roll", f"|roll| must be <= 0.2 rad, got {roll!r}")
    if ("vertical_load" in tbl) == ("z" in tbl):
        r.fail("position", None, "give exactly one of vertical_load (N per wheel, or "
               "[left, right]) and z (height of the axle centre, m)")
    load = z = None
    if "vertical_load" in tbl:
        v = tbl["vertical_load"]
        if isinstance(v, list):
            if len(v) != 2:
                r.fail("position", "vertical_load", f"must be one number or [left, right], "
                       f"got {v!r}")
            load = tuple(r.number("position", {"vertical_load": x}, "vertical_load",
                                  positive=True) for x in v)
        else:
            q = r.number("position", tbl, "vertical_load", positive=True)
            load = (q, q)
    else:
        z = r.number("position", tbl, "z")
    tol = r.number("position", tbl, "tolerance", default=5e-4, positive=True)
    return y, sweep, yaw, roll, load, z, tol


def _wheelset_case_from_dict(r: _Reader, data: Mapping) -> WheelsetCase:
    from .geometry import Track, Wheelset
    from .geometry.kinematics import Motion

    for name in ("contact", "creepage", "force"):
        if name in data:
            r.fail(name, None, "a wheelset case ([wheelset], [track], [motion], [position]) "
                   "takes no [contact], [creepage] or [force] table: the contact follows from "
                   "the profiles, the creepages from [motion]")
    r.unknown("", data, _WHEELSET_TABLES)
    for name in _WHEELSET_TABLES:
        if name in data and not isinstance(data[name], Mapping):
            raise CaseFileError(f"{r.source}: '{name}' must be a table [{name}], "
                                f"got {data[name]!r}")
    materials = _read_materials(r, data.get("material", {}))

    wt = data.get("wheelset", {})
    r.unknown("wheelset", wt, _WHEELSET_KEYS)
    wheel, wheel_src = _read_profile(r, "wheelset", wt, "profile", "wheel", "S1002")
    wheel_r, wheel_r_src = _read_profile(r, "wheelset", wt, "profile_right", "wheel", None)
    wkw = {k: r.number("wheelset", wt, k, positive=True) for k in _WHEELSET_KEYS[2:] if k in wt}
    ws = _construct(r, "wheelset", lambda: Wheelset(wheel, wheel_right=wheel_r, **wkw))

    tt = data.get("track", {})
    r.unknown("track", tt, _TRACK_KEYS)
    rail, rail_src = _read_profile(r, "track", tt, "profile", "rail", "60E1")
    rail_r, rail_r_src = _read_profile(r, "track", tt, "profile_right", "rail", None)
    tkw = {k: r.number("track", tt, k, positive=True) for k in ("gauge",) if k in tt}
    if "gauge_height" in tt:
        tkw["gauge_height"] = r.number("track", tt, "gauge_height", lo=0.0)
    tkw["inclination"] = _read_slope(r, "track", tt, "inclination", 1.0 / 40.0)
    if "canted" in tt:
        if not isinstance(tt["canted"], bool):
            r.fail("track", "canted", f"must be true or false, got {tt['canted']!r}")
        tkw["canted"] = tt["canted"]
    tr = _construct(r, "track", lambda: Track(rail, rail_right=rail_r, **tkw))

    mt = r.required_table(data, "motion")
    r.unknown("motion", mt, _MOTION_KEYS)
    mkw = {"speed": r.number("motion", mt, "speed", positive=True)}
    if "omega" in mt:
        mkw["omega"] = r.number("motion", mt, "omega", positive=True)
    for k in ("lateral_velocity", "vertical_velocity", "yaw_rate", "roll_rate"):
        if k in mt:
            mkw[k] = r.number("motion", mt, k)
    if "roller_radius" in mt:
        mkw["roller_radius"] = r.number("motion", mt, "roller_radius", positive=True)
    motion = _construct(r, "motion", lambda: Motion(**mkw))

    y, sweep, yaw, roll, load, z, tol = _read_position(r, r.required_table(data, "position"))
    fr = r.required_table(data, "friction")
    r.unknown("friction", fr, ("mu",))
    mu = r.number("friction", fr, "mu", positive=True)
    normal, tangential, options = _read_methods(r, data.get("method", {}))
    tables = {"wheelset": {"profile": wheel_src, "profile_right": wheel_r_src,
                           "nominal_radius": ws.nominal_radius, "flange_back": ws.flange_back,
                           "tape_circle_offset": ws.tape_circle_offset},
              "track": {"profile": rail_src, "profile_right": rail_r_src, "gauge": tr.gauge,
                        "inclination": tr.inclination, "gauge_height": tr.gauge_height,
                        "canted": tr.canted},
              "motion": motion.to_dict(),
              "position": {"roll": roll, "vertical_load": load, "z": z, "tolerance": tol},
              "friction": {"mu": mu}, "method": {"normal": normal, "tangential": tangential,
                                                 **{k: dict(v) for k, v in options.items()}}}
    case = WheelsetCase(wheelset=ws, track=tr, motion=motion, y=y, yaw=yaw, roll=roll,
                        vertical_load=load, z=z, tolerance=tol, sweep=sweep,
                        materials=materials, mu=mu, normal=normal, tangential=tangential,
                        options=MappingProxyType(options), source=r.source,
                        tables=MappingProxyType(tables))
    _construct(r, "position", lambda: case.position(0))   # the remaining checks of the pose
    return case


def solve_wheelset_case(case: WheelsetCase, progress=None):
    """Solve a :class:`WheelsetCase` through :func:`wheelrail.solve`.

    Returns
    -------
    WheelRailResult
        For a single position (``[position] y`` a number).
    xarray.Dataset
        For a sweep (``y`` a range or list): :func:`wheelrail.wheelset_sweep`.
    """
    from .api import solve

    if not isinstance(case, WheelsetCase):
        raise InputError(f"solve_wheelset_case needs a WheelsetCase (from load_case), got "
                         f"{type(case).__name__}")
    if not case.sweep:
        return solve(case.position(0), motion=case.motion, mu=case.mu, normal=case.normal,
                     tangential=case.tangential, normal_options=case.normal_options,
                     tangential_options=case.tangential_options)
    from .contact.sweep import wheelset_sweep

    ds = wheelset_sweep(case.wheelset, case.track, y=case.y, yaw=case.yaw,
                        roll=case.roll, vertical_load=case.vertical_load, z=case.z,
                        motion=case.motion, mu=case.mu, normal=case.normal,
                        tangential=case.tangential, material=case.materials,
                        progress=progress, normal_options=case.normal_options,
                        tangential_options=case.tangential_options)
    ds.attrs["source"] = case.source
    return ds


__all__ += ["WheelsetCase", "load_wheelset_case", "load_contact_case", "solve_wheelset_case"]


# --------------------------------------------------------------------------- transient case
_TRANSIENT_TABLES = ("material", "contact", "friction", "transient")
_TRANSIENT_KEYS = ("travel", "step", "elements", "friction", "epsilon", "scheme", "frames",
                   "margin", "normal_force", "approach", "tangential_force", "xi", "eta", "phi",
                   "discretisation", "strips")


@dataclass(frozen=True)
class TransientCase:
    """A validated transient-rolling case (``[transient]`` table; issue 8, seed 001).

    Attributes
    ----------
    materials : MaterialPair
    contact : ContactSpec
        The Hertzian contact: surfaces, and the grid (sized on its load).
    mu : float
    settings : Mapping
        Keyword arguments of :func:`wheelrail.transient_rolling` (SI units);
        load and creepage histories are
        :class:`~wheelrail.transient.loads.TravelFunction` objects.
    source : str
    """

    materials: MaterialPair
    contact: ContactSpec
    mu: float
    settings: Mapping[str, Any]
    source: str = "<dict>"

    @cached_property
    def hertz_contact(self):
        return self.contact.hertz(self.materials)

    def run(self, progress=False):
        """Solve with :func:`wheelrail.transient_rolling`; returns its ``TransientResult``."""
        from .transient import transient_rolling

        return transient_rolling(self.hertz_contact, mu=self.mu, progress=progress,
                                 **dict(self.settings))

    def describe(self) -> dict:
        """Plain description (strings and numbers) of the settings, for summaries."""
        out = {}
        for k, v in self.settings.items():
            if k == "creepage":
                for name, f in zip(("xi", "eta", "phi"), v):
                    if f is not None:
                        out[name] = f.describe() if hasattr(f, "describe") else f
            else:
                out[k] = v.describe() if hasattr(v, "describe") else v
        return out


def _read_travel_function(r: _Reader, tbl: Mapping, key: str):
    from .transient.loads import KINDS, TravelFunction

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
        scheme = "averaged"      # or "centre"
        discretisation = "uniform"   # "strips" (Paul–Hashemi; strips = 30) or "material"
        frames = 60              # traction fields stored
        normal_force = 10000.0   # F3 [N] (default: [contact] load), or approach = δ [m]
        tangential_force = 2000.0   # F1 [N] (ξ unknown) -- or xi = ..., eta, phi creepages

    Every load or creepage is a number (constant) or an inline table::

        {kind = "step", at = 0.001, before = 0.0, after = 2000.0}
        {kind = "sine", mean = 10000.0, amplitude = 4500.0, wavelength = 0.005, phase = 0.0}
        {kind = "table", x = [0.0, 0.01, 0.02], value = [0.0, 2000.0, 2000.0]}

    Raises
    ------
    CaseFileError
        Naming the file, table, key and bad value.
    """
    data, source = _read_toml(path_or_str)
    r = _Reader(source)
    r.unknown("", data, _TRANSIENT_TABLES)
    for name in _TRANSIENT_TABLES:
        if name in data and not isinstance(data[name], Mapping):
            raise CaseFileError(f"{source}: '{name}' must be a table [{name}], got {data[name]!r}")
    materials = _read_materials(r, data.get("material", {}))
    contact = _read_contact(r, r.required_table(data, "contact"))
    fr = r.required_table(data, "friction")
    r.unknown("friction", fr, ("mu",))
    mu = r.number("friction", fr, "mu", positive=True)
    _check_plausible(r, "friction", "mu", mu)
    t = r.required_table(data, "transient")
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
    s["scheme"] = r.string("transient", t, "scheme", "averaged")
    if s["scheme"] not in ("averaged", "centre"):
        r.fail("transient", "scheme", f"must be 'averaged' or 'centre', got {s['scheme']!r}")
    if "normal_force" in t and "approach" in t:
        r.fail("transient", "approach", "give normal_force or approach, not both")
    for key in ("normal_force", "approach", "tangential_force"):
        if key in t:
            s[key] = _read_travel_function(r, t, key)
    given = [k for k in ("xi", "eta", "phi") if k in t]
    cr = [(_read_travel_function(r, t, k) if k in t else None) for k in ("xi", "eta", "phi")]
    if "tangential_force" in s:
        if "xi" in t:
            r.fail("transient", "xi", "with tangential_force the creepage xi is the unknown: "
                   "omit xi")
        if given:
            s["creepage"] = (None, cr[1] or 0.0, cr[2] or 0.0)
    else:
        if not given:
            r.fail("transient", None, "give tangential_force (F1 [N]) or creepages xi, eta, "
                   "phi")
        s["creepage"] = tuple(c if c is not None else 0.0 for c in cr)
    case = TransientCase(materials=materials, contact=contact, mu=mu,
                         settings=MappingProxyType(s), source=source)
    try:
        case.hertz_contact
    except InputError as exc:
        raise CaseFileError(f"{source}: [contact]: {exc}") from None
    return case


__all__ += ["TransientCase", "load_transient_case"]
