"""Frozen result objects returned by the solvers.

Results are never stored on a solver: every entry function returns one of
these immutable objects. Scalars are Python floats for a single case and
arrays of the batch shape for batches.
"""

from __future__ import annotations

import enum
import json
from dataclasses import dataclass, field, fields
from typing import Any, Mapping

import numpy as np

from .halfspace.grid import Grid, contact_outline
from .materials import MaterialPair

__all__ = ["Status", "CreepForcesResult", "to_jsonable", "PatchResult", "ContactResult", "PATCH_QUANTITIES",
           "NormalResult", "TangentialResult", "GapResult"]


class Status(enum.Enum):
    """Outcome of a solve."""

    CONVERGED = "converged"          #: tolerance reached (or a closed-form method)
    NOT_CONVERGED = "not_converged"  #: iteration limit hit; the result is the last iterate
    FULL_SLIP = "full_slip"          #: converged, the whole patch slides (|F_t| = μ Fn)

    def __str__(self) -> str:  # pragma: no cover - trivial
        return self.value


def to_jsonable(value: Any):
    """Convert numpy scalars/arrays, enums and nested containers to JSON types."""
    if isinstance(value, enum.Enum):
        return value.value
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, (np.floating, np.integer, np.bool_)):
        return value.item()
    if isinstance(value, Mapping):
        return {str(k): to_jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [to_jsonable(v) for v in value]
    return value


def _short(value, unit: str = "") -> str:
    """A value for a one-line repr: a scalar with 4 significant digits, an array as its
    shape and range (never its elements)."""
    if isinstance(value, enum.Enum):
        return value.name.lower()
    if isinstance(value, str) or value is None or isinstance(value, bool):
        return repr(value)
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        return type(value).__name__
    u = f" {unit}" if unit else ""
    if a.ndim == 0:
        return f"{float(a):.4g}{u}"
    if a.size == 0:
        return f"array{a.shape}"
    return f"array{a.shape} {np.nanmin(a):.4g}..{np.nanmax(a):.4g}{u}"


def short_repr(obj, items) -> str:
    """``Name(key=value, ...)`` of (key, value, unit) items, each value by :func:`_short`."""
    body = ", ".join(f"{k}={_short(v, u)}" for k, v, u in items)
    return f"{type(obj).__name__}({body})"


@dataclass(frozen=True)
class CreepForcesResult:
    """Tangential contact forces on the wheel (Kalker's sign convention).

    Attributes
    ----------
    Fx, Fy : float or ndarray, shape (n,)
        Longitudinal and lateral creep force on the wheel [N].
    Mz : float or ndarray, shape (n,)
        Spin moment on the wheel about the contact normal [N·m].
    Fn : float or ndarray
        Normal force used [N].
    mu : float or ndarray
        Friction coefficient used [-].
    method : str
        Name of the creep-force law.
    status : Status
        Outcome of the solve; iterative methods report ``NOT_CONVERGED`` rather
        than raising when the caller asked for that (``on_fail="status"``).
    iterations : int or ndarray or None
        Iterations used by iterative methods, ``None`` for closed forms.
    fields : object or None
        Method-specific fields (traction and slip grids for FASTSIM and the
        exact theory), ``None`` for closed-form laws.
    info : dict
        Extra method-specific scalars (e.g. adhesion area, effective friction).
    """

    Fx: Any
    Fy: Any
    Mz: Any
    Fn: Any
    mu: Any
    method: str
    status: Status = Status.CONVERGED
    iterations: Any = None
    fields: Any = None
    info: dict = field(default_factory=dict)

    def __repr__(self):
        return short_repr(self, [("method", self.method, ""), ("Fx", self.Fx, "N"),
                                 ("Fy", self.Fy, "N"), ("Mz", self.Mz, "N m"),
                                 ("Fn", self.Fn, "N"), ("mu", self.mu, ""),
                                 ("status", self.status, ""),
                                 ("iterations", self.iterations, "")])

    @property
    def Ft(self):
        """Magnitude of the tangential force √(Fx² + Fy²) [N]."""
        return np.hypot(self.Fx, self.Fy)

    @property
    def utilisation(self):
        """|F_t| / (μ Fn) [-], 1 at full slip."""
        return self.Ft / (np.asarray(self.mu) * self.Fn)

    def to_dict(self) -> dict:
        """JSON-friendly dictionary of the scalar results (fields left out)."""
        out = {f.name: getattr(self, f.name) for f in fields(self) if f.name not in ("fields", "info")}
        out.update(self.info)
        return to_jsonable(out)

    def to_json(self, path) -> None:
        """Write :meth:`to_dict` to ``path`` as JSON."""
        with open(path, "w", encoding="utf-8") as fh:
            json.dump(self.to_dict(), fh, indent=2)


#: Per-patch quantities of :class:`PatchResult` (name: unit).
PATCH_QUANTITIES = {
    "xi": "1", "eta": "1", "phi": "1/m", "Fn": "N", "Fx": "N", "Fs": "N", "Mz": "N m",
    "p_max": "Pa", "area": "m^2", "adhesion_area": "m^2",
}


@dataclass(frozen=True)
class PatchResult:
    """Normal and tangential solution of one contact patch (frozen, SI).

    Attributes
    ----------
    patch : ContactPatch
        The patch from the normal method (strips, pressure, contact frame).
    forces : CreepForcesResult
        The tangential method's result on it (``fields`` for FASTSIM/exact).
    xi, eta, phi : float
        Creepages at the patch's reference point [-], [-], [1/m].
    side : str or None
        ``"left"``/``"right"`` for a wheel–rail patch.
    """

    patch: Any
    forces: Any
    xi: float
    eta: float
    phi: float
    side: str | None = None

    def __repr__(self):
        return short_repr(self, [("side", self.side, ""), ("Fn", self.Fn, "N"),
                                 ("Fx", self.Fx, "N"), ("Fs", self.Fs, "N"),
                                 ("xi", self.xi, ""), ("eta", self.eta, ""),
                                 ("phi", self.phi, "1/m")])

    @property
    def Fn(self) -> float:
        """Normal force [N]."""
        return float(self.patch.Fn)

    @property
    def Fx(self) -> float:
        """Longitudinal creep force on the wheel [N]."""
        return float(self.forces.Fx)

    @property
    def Fs(self) -> float:
        """Lateral creep force on the wheel in the contact plane [N] (contact y, to the right)."""
        return float(self.forces.Fy)

    Fy = Fs

    @property
    def Mz(self) -> float:
        """Spin moment about the patch's centre of pressure [N·m]."""
        return float(self.forces.Mz)

    @property
    def Mz_reference(self) -> float:
        """Spin moment about the patch's reference point (its contact frame / strip origin)
        [N·m]: Mz + x_c Fs − y_c Fx with (x_c, y_c) the centre of pressure."""
        xc, yc = self.patch.centre
        return self.Mz + xc * self.Fs - yc * self.Fx

    @property
    def p_max(self) -> float:
        return self.patch.p_max

    @property
    def area(self) -> float:
        return self.patch.area

    @property
    def adhesion_area(self) -> float:
        """Area of adhesion [m²] (NaN for closed-form laws, which have no fields)."""
        info = self.forces.info or {}
        if "adhesion_area" in info:
            return float(info["adhesion_area"])
        if "adhesion_fraction" in info:
            return float(info["adhesion_fraction"]) * self.area
        return float("nan")

    @property
    def contact_angle(self) -> float:
        return float("nan") if self.patch.frame is None else self.patch.frame.contact_angle

    @property
    def y_rail(self) -> float:
        """Lateral position of the patch on the rail profile [m] (NaN off a wheel–rail problem)."""
        return float("nan") if self.patch.frame is None else self.patch.frame.rail_y

    @property
    def y_rail_centre(self) -> float:
        """Lateral position of the patch's centre of pressure on the rail profile [m].

        Equal to :attr:`y_rail` for a Hertzian patch; a boundary-element patch
        reports the reference point of its grid (where its creepages are
        given, shared by the patches of one grid) as ``y_rail`` and its own
        centre here.
        """
        return float(self.patch.info.get("centre_rail_y", self.y_rail))

    @property
    def y_wheel(self) -> float:
        return float("nan") if self.patch.frame is None else self.patch.frame.wheel_y

    @property
    def status(self):
        return self.forces.status

    def to_dict(self) -> dict:
        out = {"side": self.side, "normal": self.patch.method, "tangential": self.forces.method}
        if self.patch.frame is not None:
            out.update(self.patch.frame.to_dict())
        for k in PATCH_QUANTITIES:
            out[k] = getattr(self, k)
        out["status"] = self.status
        return to_jsonable(out)


@dataclass(frozen=True)
class ContactResult:
    """Result of :func:`wheelrail.solve` for a single contact or a gap (frozen, SI).

    Attributes
    ----------
    patches : tuple of PatchResult
    normal, tangential : str
        Method names.
    info : dict
    """

    patches: tuple
    normal: str
    tangential: str
    info: dict = field(default_factory=dict)

    def _sum(self, name):
        return float(sum(getattr(p, name) for p in self.patches))

    def __repr__(self):
        return short_repr(self, [("normal", self.normal, ""),
                                 ("tangential", self.tangential, ""),
                                 ("patches", len(self.patches), ""), ("Fn", self.Fn, "N"),
                                 ("Fx", self.Fx, "N"), ("Fy", self.Fy, "N"),
                                 ("Mz", self.Mz, "N m"), ("status", self.status, "")])

    @property
    def Fn(self) -> float:
        return self._sum("Fn")

    @property
    def Fx(self) -> float:
        return self._sum("Fx")

    @property
    def Fy(self) -> float:
        return self._sum("Fs")

    @property
    def Mz(self) -> float:
        """Sum of the patches' spin moments (each about its centre of pressure) [N·m]."""
        return self._sum("Mz")

    @property
    def status(self) -> Status:
        st = [p.status for p in self.patches]
        if Status.NOT_CONVERGED in st:
            return Status.NOT_CONVERGED
        return Status.FULL_SLIP if st and all(s is Status.FULL_SLIP for s in st) else Status.CONVERGED

    def to_dict(self) -> dict:
        return to_jsonable({"normal": self.normal, "tangential": self.tangential,
                            "Fn": self.Fn, "Fx": self.Fx, "Fy": self.Fy, "Mz": self.Mz,
                            "status": self.status,
                            "patches": [p.to_dict() for p in self.patches]})


# --------------------------------------------------------------------------- grid solutions
@dataclass(frozen=True)
class NormalResult:
    """Solution of the normal contact problem on a grid (frozen).

    Attributes
    ----------
    grid : Grid
    pressure : ndarray, shape (nx, ny)
        Contact pressure [Pa], ≥ 0, compression positive.
    gap : ndarray, shape (nx, ny)
        Deformed gap e = h0 − δ + u_n [m] (≈ 0 in contact, > 0 outside).
    displacement : ndarray, shape (nx, ny)
        Gap-opening normal displacement difference u_n [m].
    contact : ndarray of bool, shape (nx, ny)
        Elements in contact (p > 0).
    Fn : float
        Normal force Σ p dA [N].
    p_max : float
        Largest element pressure [Pa].
    penetration : float
        Approach δ of the bodies [m] (prescribed, or found for a prescribed load).
    area : float
        Contact area (number of contact elements × dA) [m²].
    iterations : int
    status : Status
        ``CONVERGED`` or ``NOT_CONVERGED`` (only with ``on_fail="status"``).
    residual : float
        Complementarity residual max(max|e| in contact, max(−e) outside) / max(u_n) [-].
    truncated : bool
        True if the contact reaches the outer row/column of the grid (the result
        is then not the solution of the unbounded problem).
    materials : MaterialPair
    info : dict
        Extra scalars (``change``: last relative pressure change).
    """

    grid: Grid
    pressure: np.ndarray
    gap: np.ndarray
    displacement: np.ndarray
    contact: np.ndarray
    Fn: float
    p_max: float
    penetration: float
    area: float
    iterations: int
    status: Status
    residual: float
    truncated: bool
    materials: MaterialPair
    info: dict = field(default_factory=dict)

    def __repr__(self):
        return short_repr(self, [("grid", f"{self.grid.nx}x{self.grid.ny}", ""),
                                 ("Fn", self.Fn, "N"), ("p_max", self.p_max, "Pa"),
                                 ("penetration", self.penetration, "m"),
                                 ("area", self.area, "m^2"), ("iterations", self.iterations, ""),
                                 ("status", self.status, "")])

    @property
    def centroid(self) -> tuple[float, float]:
        """Centre of pressure (x, y) [m]."""
        w = self.pressure.sum()
        return (float((self.pressure * self.grid.X).sum() / w),
                float((self.pressure * self.grid.Y).sum() / w))

    def outline(self) -> list[np.ndarray]:
        """Outline(s) of the contact area, see :func:`contact_outline`."""
        return contact_outline(self.grid, self.contact)

    def to_dict(self) -> dict:
        """JSON-friendly scalars (fields left out)."""
        out = {k: getattr(self, k) for k in ("Fn", "p_max", "penetration", "area", "iterations",
                                             "status", "residual", "truncated")}
        out["grid"] = {"x0": self.grid.x0, "y0": self.grid.y0, "dx": self.grid.dx,
                       "dy": self.grid.dy, "nx": self.grid.nx, "ny": self.grid.ny}
        out.update(self.info)
        return to_jsonable(out)


@dataclass(frozen=True)
class TangentialResult:
    """Tangential tractions and slip on a grid (frozen).

    Attributes
    ----------
    grid : Grid
    pressure : ndarray, shape (nx, ny)
        Normal pressure used [Pa].
    px, py : ndarray, shape (nx, ny)
        Tangential traction on the wheel [Pa].
    sx, sy : ndarray, shape (nx, ny)
        Slip of the wheel relative to the rail: dimensionless slip velocity
        (rolling) or slip distance [m] (shift); zero in adhesion and outside
        the contact.
    ux, uy : ndarray, shape (nx, ny)
        Tangential displacement difference u(wheel) − u(rail) [m].
    adhesion, slip : ndarray of bool, shape (nx, ny)
        Elements in contact that stick / slide.
    Fx, Fy : float
        Tangential force on the wheel [N].
    Mz : float
        Moment of the tangential tractions about the grid origin [N·m].
    mu : float
    kind : str
        ``"rolling"`` or ``"shift"``.
    creepage : tuple
        (ξ, η, φ) for rolling; the rigid shift (Wx, Wy) [m] for shift.
    iterations : int
        Newton iterations (``solver="newton"``; for a prescribed shift force,
        summed over the outer iterations) or Gauss–Seidel sweeps.
    converged : bool
    residual : float
        Newton: largest slip-equation residual / max |rigid slip|;
        Gauss–Seidel: largest traction change of the last sweep / max μ·pn.
    info : dict
        ``solver``, ``krylov_iterations`` and ``coarse`` (rolling: the Newton
        and Krylov counts of the nested-iteration levels), ``outer_iterations``
        (shift).
    """

    grid: Grid
    pressure: np.ndarray
    px: np.ndarray
    py: np.ndarray
    sx: np.ndarray
    sy: np.ndarray
    ux: np.ndarray
    uy: np.ndarray
    adhesion: np.ndarray
    slip: np.ndarray
    Fx: float
    Fy: float
    Mz: float
    mu: float
    kind: str
    creepage: tuple
    iterations: int
    converged: bool
    residual: float
    info: dict = field(default_factory=dict)

    def __repr__(self):
        return short_repr(self, [("kind", self.kind, ""), ("Fx", self.Fx, "N"),
                                 ("Fy", self.Fy, "N"), ("Mz", self.Mz, "N m"),
                                 ("mu", self.mu, ""), ("creepage", self.creepage, ""),
                                 ("iterations", self.iterations, ""),
                                 ("converged", self.converged, "")])

    @property
    def contact(self) -> np.ndarray:
        """Elements with positive pressure, shape (nx, ny)."""
        return self.pressure > 0.0

    @property
    def adhesion_area(self) -> float:
        """Area of the adhesion zone [m²]."""
        return float(np.count_nonzero(self.adhesion)) * self.grid.element_area

    @property
    def Ft(self) -> float:
        """|F_t| = √(Fx² + Fy²) [N]."""
        return float(np.hypot(self.Fx, self.Fy))

    def as_arrays(self) -> dict:
        """Plain arrays on the grid, indexed ``[i_x, i_y]``, for plotting and export.

        Keys as :meth:`wheelrail.results.GapResult.as_arrays`: ``x``, ``y``
        (element centres, m), ``px``, ``py``, ``p`` (Pa), ``adhesion``,
        ``inside`` (bool), ``dA`` (element areas, m²), ``sx``, ``sy``.
        """
        g = self.grid
        return {"x": g.X, "y": g.Y, "px": np.asarray(self.px), "py": np.asarray(self.py),
                "p": np.asarray(self.pressure), "adhesion": np.asarray(self.adhesion, bool),
                "inside": np.asarray(self.contact, bool),
                "dA": np.full(g.shape, g.element_area), "sx": np.asarray(self.sx),
                "sy": np.asarray(self.sy)}


def _tangential_field(name, doc):
    """A field of the tangential solution of a :class:`GapResult` (zeros without one)."""
    return property(lambda self: self._t(name, np.zeros(self.grid.shape)), doc=doc)


def _tangential_force(name, doc):
    """A force of the tangential solution of a :class:`GapResult` (0 without one)."""
    return property(lambda self: float(self._t(name)), doc=doc)


@dataclass(frozen=True)
class GapResult:
    """Normal and tangential solution of one contact on a grid (frozen).

    Attributes
    ----------
    normal : NormalResult
        The (last) normal solution (:func:`wheelrail.normal.bem.solve_normal`).
    tangential : TangentialResult or None
        ``None`` when no tangential problem was asked for.
    outer_iterations : int
        Normal–tangential alternations (1 for quasi-identical bodies,
        Johnson's process; more with ``K ≠ 0``, Panagiotopoulos' process).
    outer_change : float
        Last relative change of the tractions between alternations.
    """

    normal: object
    tangential: object
    outer_iterations: int
    outer_change: float

    def __repr__(self):
        return short_repr(self, [("Fn", self.Fn, "N"), ("Fx", self.Fx, "N"),
                                 ("Fy", self.Fy, "N"), ("Mz", self.Mz, "N m"),
                                 ("outer_iterations", self.outer_iterations, "")])

    # convenient views (grid, pressure, contact, Fn from the normal solution; tractions,
    # slip, adhesion, tangential displacements and forces from the tangential one) ---------
    @property
    def grid(self) -> Grid:
        return self.normal.grid

    @property
    def pressure(self) -> np.ndarray:
        return self.normal.pressure

    @property
    def contact(self) -> np.ndarray:
        return self.normal.contact

    @property
    def Fn(self) -> float:
        return self.normal.Fn

    def _t(self, name, default=0.0):
        return default if self.tangential is None else getattr(self.tangential, name)

    px = _tangential_field("px", "Tangential traction on the wheel along x [Pa].")
    py = _tangential_field("py", "Tangential traction on the wheel along y [Pa].")
    sx = _tangential_field("sx", "Slip along x (zero in adhesion) [-] or [m].")
    sy = _tangential_field("sy", "Slip along y (zero in adhesion) [-] or [m].")
    ux = _tangential_field("ux", "Tangential displacement difference along x [m].")
    uy = _tangential_field("uy", "Tangential displacement difference along y [m].")
    Fx = _tangential_force("Fx", "Tangential force on the wheel along x [N].")
    Fy = _tangential_force("Fy", "Tangential force on the wheel along y [N].")
    Mz = _tangential_force("Mz", "Moment of the tangential tractions about the grid origin [N·m].")

    @property
    def adhesion(self):
        """Elements that stick (all contact elements without a tangential problem)."""
        return self._t("adhesion", self.contact.copy())

    @property
    def un(self):
        """Gap-opening normal displacement difference [m] (of the last normal solve)."""
        return self.normal.displacement

    def as_arrays(self) -> dict:
        """Plain arrays on the grid, indexed ``[i_x, i_y]``, for plotting and export.

        Keys: ``x``, ``y`` (element centres, m), ``px``, ``py``, ``p`` (Pa),
        ``adhesion``, ``inside`` (bool), ``dA`` (element areas, m²), ``sx``, ``sy``
        (slip, m/m).
        """
        if self.tangential is not None:
            return self.tangential.as_arrays()
        g = self.grid
        return {"x": g.X, "y": g.Y, "px": np.asarray(self.px), "py": np.asarray(self.py),
                "p": np.asarray(self.pressure), "adhesion": np.asarray(self.adhesion, bool),
                "inside": np.asarray(self.contact, bool),
                "dA": np.full(g.shape, g.element_area), "sx": np.asarray(self.sx),
                "sy": np.asarray(self.sy)}
