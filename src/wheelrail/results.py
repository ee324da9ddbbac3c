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

__all__ = ["Status", "CreepForces", "to_jsonable", "PatchResult", "ContactResult", "PATCH_QUANTITIES"]


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


@dataclass(frozen=True)
class CreepForces:
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
    forces : CreepForces
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
