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

__all__ = ["Status", "CreepForces", "to_jsonable"]


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
