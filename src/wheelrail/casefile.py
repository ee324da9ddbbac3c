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
from .errors import CaseFileError, InputError, WheelrailError
from .materials import STEEL, Material, MaterialPair
from .results import to_jsonable

try:  # Python >= 3.11
    import tomllib
except ModuleNotFoundError:  # pragma: no cover - Python 3.10
    import tomli as tomllib

__all__ = ["Case", "ContactSpec", "CaseResult", "load_case", "case_from_dict", "run_case",
           "solve_case", "NORMAL_METHODS", "RADII_KEYS", "DEFAULT_CASE"]

#: Normal-contact methods accepted by ``[method] normal``.
NORMAL_METHODS = ("hertz", "bem")
#: Options of the normal methods, with defaults (``[method.<name>]``).
NORMAL_OPTIONS = {"hertz": {}, "bem": {"elements": 100}}
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
        """Options for the normal method, defaults filled in."""
        out = dict(NORMAL_OPTIONS[self.normal])
        out.update(self.options.get(self.normal, {}))
        return out

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
    """

    case: Case
    contact: Any
    forces: Any
    normal: Any
    summary: dict

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
def load_case(path_or_str) -> Case:
    """Read and validate a case file.

    Parameters
    ----------
    path_or_str : str or os.PathLike
        A path to a ``.toml`` file, or the TOML text itself (a string that
        contains a newline or ``=`` is taken as text).

    Returns
    -------
    Case

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
    return case_from_dict(data, source=source)


def case_from_dict(data: Mapping, source: str = "<dict>") -> Case:
    """Validate a parsed case (the dictionary ``tomllib`` returns) into a :class:`Case`."""
    r = _Reader(source)
    if not isinstance(data, Mapping):
        raise CaseFileError(f"{source}: a case must be a table, got {type(data).__name__}")
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
    from .api import METHODS

    option_tables = {k: v for k, v in tbl.items() if isinstance(v, Mapping)}
    scalars = {k: v for k, v in tbl.items() if k not in option_tables}
    r.unknown("method", scalars, ("normal", "tangential"))
    normal = r.string("method", tbl, "normal", "hertz").lower()
    if normal not in NORMAL_METHODS:
        r.fail("method", "normal", f"unknown normal method {normal!r}; choose one of "
               + ", ".join(NORMAL_METHODS))
    tname = r.string("method", tbl, "tangential", "fastsim")
    tangential = _canonical_tangential(tname)
    if tangential is None:
        r.fail("method", "tangential", f"unknown tangential method {tname!r}; choose one of "
               + ", ".join(METHODS))
    options: dict[str, dict] = {}
    for name, opts in option_tables.items():
        key = name.lower() if name.lower() in NORMAL_METHODS else _canonical_tangential(name)
        if key is None:
            r.fail("method", None, f"unknown method table [method.{name}]; methods are "
                   + ", ".join((*NORMAL_METHODS, *METHODS)))
        options[key] = dict(opts)
        _check_option_values(r, name, key, options[key])
    # options of the chosen methods are checked now (typos), the others are kept as given
    if normal == "bem":
        bem = options.get("bem", {})
        r.unknown("method.bem", bem, tuple(NORMAL_OPTIONS["bem"]))
        if "elements" in bem:
            e = bem["elements"]
            if isinstance(e, bool) or not isinstance(e, int) or e < 2:
                r.fail("method.bem", "elements", f"must be an integer >= 2, got {e!r}")
    _check_tangential_options(r, tangential, options.get(tangential, {}))
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


def _check_tangential_options(r: _Reader, name: str, opts: dict) -> None:
    from .api import get_method

    try:
        impl = get_method(name)
    except ImportError:  # the method is not available yet: run_case will say so
        return
    try:
        impl.check_options(opts)
    except InputError as exc:
        r.fail(f"method.{name}", None, str(exc))


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
def _missing(feature: str, module: str, exc: ImportError) -> WheelrailError:
    return WheelrailError(f"{feature} needs {module}, which is not available in this "
                          f"installation ({exc})")


def solve_case(case: Case) -> CaseResult:
    """Solve a :class:`Case` and keep every intermediate result.

    The normal problem is solved with Hertz's theory (``normal = "hertz"``)
    or the boundary-element solver of :mod:`wheelrail.halfspace`
    (``normal = "bem"``, on a grid around the Hertz ellipse); the creep
    forces with the chosen tangential method on the Hertz ellipse, or, with
    a ``[force]`` table, the creepages that produce the prescribed forces
    (:func:`wheelrail.prescribed.solve_creepages`).

    Returns
    -------
    CaseResult
        ``summary`` is the dictionary returned by :func:`run_case`.
    """
    from .api import creep_forces

    contact = case.hertz_contact
    normal = None
    opts = dict(case.tangential_options)
    # The exact theory solves its own boundary-element normal problem: with normal = "bem"
    # it takes the grid size of [method.bem] (unless [method.exact] sets one) and its normal
    # solution is reported, instead of solving the same normal problem twice.
    shared_bem = case.normal == "bem" and case.tangential == "exact"
    if shared_bem:
        opts.setdefault("elements", case.normal_options["elements"])
    elif case.normal == "bem":
        try:
            from .halfspace import hertz_grid, solve_normal
        except ImportError as exc:
            raise _missing('normal = "bem"', "wheelrail.halfspace", exc) from None
        grid, gap = hertz_grid(contact, case.normal_options["elements"])
        normal = solve_normal(grid, gap, case.materials, load=case.contact.load)

    xi, eta, phi = case.creepage
    try:
        if case.forces:
            try:
                from .prescribed import solve_creepages
            except ImportError as exc:
                raise _missing("a [force] table", "wheelrail.prescribed", exc) from None
            forces = solve_creepages(contact, case.mu, Fx=case.forces.get("Fx"),
                                     Fy=case.forces.get("Fy"), creepage=(xi, eta, phi),
                                     method=case.tangential, **opts)
            xi = forces.info.get("xi", xi)
            eta = forces.info.get("eta", eta)
        else:
            forces = creep_forces(contact, (xi, eta, phi), case.mu, method=case.tangential,
                                  **opts)
    except ImportError as exc:
        raise _missing(f"tangential = {case.tangential!r}",
                       f"the module of method {case.tangential!r}", exc) from None

    if shared_bem and forces.fields is not None:
        normal = forces.fields.normal
    summary = _summary(case, contact, forces, normal, xi, eta, phi)
    return CaseResult(case, contact, forces, normal, summary)


def run_case(case: Case) -> dict:
    """Solve a case and return a JSON-ready dictionary (SI units).

    Keys: ``a, b`` [m], ``p0`` [Pa], ``penetration`` [m], ``Fn, Fx, Fy`` [N],
    ``Mz`` [N·m], ``xi, eta`` [-], ``phi`` [1/m] (the creepages used, solved
    ones for prescribed forces), ``mu``, ``method`` (tangential),
    ``normal_method``, ``status``, ``iterations``, ``area`` [m²] and, when
    the methods provide them, ``p_max`` [Pa] and ``adhesion_area`` [m²];
    ``units`` maps each key to its unit.
    """
    if not isinstance(case, Case):
        raise InputError(f"run_case needs a Case (from load_case), got {type(case).__name__}")
    return solve_case(case).summary


def _scalar(v):
    arr = np.asarray(v)
    return arr.item() if arr.ndim == 0 else arr.tolist()


def _summary(case, contact, forces, normal, xi, eta, phi) -> dict:
    out = {
        "a": contact.a, "b": contact.b, "c": float(contact.c), "A": contact.A, "B": contact.B,
        "p0": contact.p0, "penetration": contact.penetration, "Fn": contact.load,
        "area": float(contact.area), "p_max": contact.p0,
        "Fx": forces.Fx, "Fy": forces.Fy, "Mz": forces.Mz,
        "xi": xi, "eta": eta, "phi": phi, "mu": case.mu,
        "utilisation": forces.utilisation,
        "method": forces.method, "normal_method": case.normal,
        "status": forces.status, "iterations": forces.iterations,
    }
    if normal is not None:  # the boundary-element NormalSolution replaces Hertz's numbers
        out.update(p_max=normal.p_max, area=normal.area, Fn=normal.Fn,
                   penetration=normal.penetration, normal_iterations=normal.iterations,
                   normal_status=normal.status, truncated=bool(normal.truncated))
        out["hertz"] = {"a": contact.a, "b": contact.b, "p0": contact.p0,
                        "penetration": contact.penetration}
    for k, v in (forces.info or {}).items():  # method extras (adhesion_area, ...), scalars only
        if k not in out and np.ndim(v) == 0:
            out[k] = v
    frac = out.get("adhesion_fraction")  # FASTSIM gives the fraction, the exact theory the area
    if "adhesion_area" not in out and frac is not None:
        out["adhesion_area"] = float(frac) * float(contact.area)
    if case.forces:
        out["prescribed"] = dict(case.forces)
    out["source"] = case.source
    out["units"] = {k: u for k, u in UNITS.items() if k in out}
    return {k: (_scalar(v) if isinstance(v, (np.ndarray, np.generic, float, int)) else
                to_jsonable(v)) for k, v in out.items()}
