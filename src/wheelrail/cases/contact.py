"""The single-contact case: what a ``[contact]`` case file describes, and its solution.

A :class:`Case` holds validated inputs (materials, the Hertzian contact
description, creepages, friction, configured methods, optional prescribed
forces); :func:`solve_case` solves it through :func:`wheelrail.solve` and
:func:`run_case` returns a JSON-ready dictionary in SI units. Case files are
read by :mod:`wheelrail.cases.files` (reading and validating only).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from types import MappingProxyType
from typing import Any, Mapping

import numpy as np

from .. import tangential as tangential_family
from ..api import solve
from ..conventions import CREEPAGE_UNITS, FORCE_UNITS
from ..errors import CaseFileError, InputError
from ..hertzian import hertz, hertz_from_radii, hertz_from_semiaxes
from ..materials import MaterialPair
from ..normal import NormalMethod
from ..prescribed import solve_creepages
from ..results import to_jsonable
from ..tangential import TangentialMethod
from ._methods import configured_methods
from .wheelset import WheelsetCase, solve_wheelset_case

__all__ = ["Case", "ContactSpec", "CaseResult", "run_case", "solve_case", "DEFAULT_CASE", "UNITS",
           "toml_value"]

#: The built-in example: steel, 7500 N, wheel radius 0.46 m on a rail head
#: radius of 0.30 m (A = 0.5/0.46, B = 0.5/0.30 1/m), μ = 0.3, FASTSIM.
DEFAULT_CASE = {
    "material": {"E": 2.1e11, "nu": 0.28},
    "contact": {"Fn": 7500.0, "wheel_rolling_radius": 0.46, "rail_profile_radius": 0.30},
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
    Fn : float
        Normal force [N].
    kind : str
        ``"curvatures"``, ``"semiaxes"`` or ``"radii"``.
    """

    Fn: float
    kind: str
    A: float | None = None
    B: float | None = None
    a: float | None = None
    b: float | None = None
    radii: Mapping[str, float] = field(default_factory=lambda: MappingProxyType({}))

    def hertz(self, material):
        """The :class:`wheelrail.HertzContact` of this description."""

        if self.kind == "curvatures":
            return hertz(self.Fn, self.A, self.B, material)
        if self.kind == "semiaxes":
            return hertz_from_semiaxes(self.a, self.b, self.Fn, material)
        return hertz_from_radii(self.Fn, material=material, **dict(self.radii))

    def to_dict(self) -> dict:
        out = {"Fn": self.Fn}
        if self.kind == "curvatures":
            out.update(A=self.A, B=self.B)
        elif self.kind == "semiaxes":
            out.update(a=self.a, b=self.b)
        else:
            out.update(self.radii)
        return out


@dataclass(frozen=True)
class Case:
    """A validated contact case (the file format: :mod:`wheelrail.cases.files`).

    Attributes
    ----------
    materials : MaterialPair
    contact : ContactSpec
    creepage : tuple of float
        (ξ [-], η [-], φ [1/m]).
    mu : float
        Friction coefficient [-].
    normal : NormalMethod
        The configured normal method (``wr.normal.Hertz()`` by default).
    tangential : TangentialMethod
        The configured creep-force law (``wr.tangential.Fastsim()`` by default).
    methods : mapping of str to method
        Every configured method of the case by registry name (the
        ``[method.<name>]`` tables and the two chosen ones): what
        :meth:`with_tangential` switches to.
    forces : mapping of str to float
        Prescribed ``Fx`` and/or ``Fy`` [N] (empty if none).
    source : str
        File name or ``"<string>"`` (used in messages).
    """

    materials: MaterialPair
    contact: ContactSpec
    creepage: tuple
    mu: float
    normal: NormalMethod = None
    tangential: TangentialMethod = None
    methods: Mapping[str, Any] = field(default_factory=lambda: MappingProxyType({}))
    forces: Mapping[str, float] = field(default_factory=lambda: MappingProxyType({}))
    source: str = "<case>"

    def __post_init__(self):
        n, t, methods = configured_methods(self.normal, self.tangential, self.methods)
        object.__setattr__(self, "normal", n)
        object.__setattr__(self, "tangential", t)
        object.__setattr__(self, "methods", methods)

    def with_tangential(self, name) -> "Case":
        """The case with another creep-force law: its configured object from
        :attr:`methods` (the case file's ``[method.<name>]``), else its defaults."""
        cls = tangential_family.get_class(name)
        return self.replace(tangential=self.methods.get(cls.name, cls()))

    @property
    def xi(self) -> float:
        return self.creepage[0]

    @property
    def eta(self) -> float:
        return self.creepage[1]

    @property
    def phi(self) -> float:
        return self.creepage[2]

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
        lines += [f"{k} = {toml_value(v)}" for k, v in self.contact.to_dict().items()]
        lines += ["", "[creepage]", *(f"{k} = {v!r}" for k, v in
                                      zip(("xi", "eta", "phi"), self.creepage)),
                  "", "[friction]", f"mu = {self.mu!r}",
                  "", "[method]", f"normal = {toml_value(self.normal.name)}",
                  f"tangential = {toml_value(self.tangential.name)}"]
        for name, m in self.methods.items():
            changed = {k: v for k, v in m.option_values().items()
                       if v is not None and v != m.option_declarations()[k].default}
            if changed:
                lines += ["", f'[method."{name}"]',
                          *(f"{k} = {toml_value(v)}" for k, v in changed.items())]
        if self.forces:
            lines += ["", "[force]", *(f"{k} = {v!r}" for k, v in self.forces.items())]
        return "\n".join(lines) + "\n"

    def replace(self, **changes) -> "Case":
        """A copy with some attributes changed (``creepage``, ``tangential``, …); a method
        given by name is configured from :attr:`methods` (see :meth:`with_tangential`)."""
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
    forces : CreepForcesResult
        Creep forces (``fields`` holds traction fields for FASTSIM / exact).
    normal : NormalResult or None
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


def toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        return "inf" if v == math.inf else "-inf" if v == -math.inf else repr(v)
    if isinstance(v, int):
        return str(v)
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    raise CaseFileError(f"cannot write {v!r} to TOML")


# --------------------------------------------------------------------------- solving
def solve_case(case: Case) -> CaseResult:
    """Solve a :class:`Case` through :func:`wheelrail.solve` and keep its results.

    The case file only chooses: the problem is the Hertzian contact of
    ``[contact]``, solved by ``wr.solve(contact, creepage, mu, normal=case.normal,
    tangential=case.tangential)`` (the configured methods). With ``normal = "bem"`` the
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

    if not isinstance(case, Case):
        raise InputError(f"solve_case needs a Case (from load_case), got {type(case).__name__}")
    contact = case.hertz_contact
    xi, eta, phi = case.creepage
    if case.forces:
        forces = solve_creepages(contact, case.mu, Fx=case.forces.get("Fx"),
                                 Fy=case.forces.get("Fy"), creepage=(xi, eta, phi),
                                 method=case.tangential)
        xi = forces.info.get("xi", xi)
        eta = forces.info.get("eta", eta)
        summary = _summary(case, contact, forces, None, None, xi, eta, phi)
        return CaseResult(case, contact, forces, None, summary)
    result = solve(contact, (xi, eta, phi), case.mu, normal=case.normal,
                   tangential=case.tangential)
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
    Fn = contact.Fn if patch is None else patch.Fn
    Ft = float(np.hypot(forces.Fx, forces.Fy))
    out = {
        "a": contact.a, "b": contact.b, "c": float(contact.c), "A": contact.A, "B": contact.B,
        "p0": contact.p0, "penetration": contact.penetration, "Fn": Fn,
        "area": float(contact.area) if patch is None else patch.area,
        "p_max": contact.p0 if patch is None else patch.p_max,
        "Fx": forces.Fx, "Fy": forces.Fy, "Mz": forces.Mz,
        "xi": xi, "eta": eta, "phi": phi, "mu": case.mu,
        "utilisation": Ft / (case.mu * Fn),
        "method": method or forces.method, "normal_method": normal_method or case.normal.name,
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


