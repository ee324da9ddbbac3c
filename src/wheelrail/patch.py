"""The contact patch: the one description every tangential method reads.

A normal method (:mod:`wheelrail.normal`) turns a contact problem into one or
more :class:`ContactPatch` objects; a tangential method
(:mod:`wheelrail.tangential`) turns a patch, creepages and a friction
coefficient into forces. The patch is therefore the contract between the two
families (de Pater's normal and tangential sub-problems):

* **strips** — lateral positions ``y`` (strip centres) and widths ``dy``,
  leading and trailing edges ``x_lead(y)``, ``x_trail(y)`` and the pressure
  along every strip (sampled at ``m`` equal cells between the edges). Strip
  theories (FASTSIM, later Kik–Piotrowski/STRIPES/FaStrip) read these;
* an **equivalent ellipse** (semi-axes ``a``, ``b``, :meth:`ContactPatch.ellipse`)
  for the closed-form creep laws (Carter, linear, Shen–Hedrick–Elkins,
  Polach), which know nothing but an ellipse. A Hertzian patch carries its
  exact :class:`~wheelrail.hertzian.HertzContact`; for a non-elliptic
  patch the ellipse has the patch's area and its length/width ratio;
* optionally a **pressure field on a half-space grid** (``grid``,
  ``pressure``, ``mask``) from the boundary-element solver, which the exact
  theory uses directly;
* its **contact frame** (:class:`ContactFrame`): where the patch lies on the
  wheel and on the rail, its contact angle and rolling radius (wheel–rail
  problems only).

Axes and units: the contact-plane axes of :mod:`wheelrail.conventions`
(x rolling direction, y lateral to the right, z into the rail), SI units.
Strip coordinates are relative to the patch's reference point (the contact
point of a wheel–rail patch, the ellipse centre of a Hertzian patch).

References
----------
.. [1] J. Piotrowski, H. Chollet, Wheel–rail contact models for vehicle system
   dynamics including multi-point contact, VSD 43 (2005), §3 (strips, virtual
   penetration).
.. [2] J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
   Kluwer 1990 (elliptic patches, exact theory on a grid).
"""

from __future__ import annotations

import math
from dataclasses import MISSING, dataclass, field, fields, replace
from typing import Any

import numpy as np

from ._validation import integer
from .errors import InputError
from .hertzian import hertz_from_semiaxes
from .materials import MaterialPair, as_material_pair

__all__ = ["ContactPatch", "ContactFrame", "DEFAULT_STRIPS", "DEFAULT_CELLS"]

#: Strips and cells per strip of a patch built from an ellipse.
DEFAULT_STRIPS = 40
DEFAULT_CELLS = 40


@dataclass(frozen=True)
class ContactFrame:
    """Where a wheel–rail contact patch lies (frozen, SI).

    Attributes
    ----------
    side : {"left", "right"}
        Wheel and rail of the patch.
    wheel_y, rail_y : float
        Lateral position of the patch's reference point on the wheel and rail
        profiles [m] (profile frames, :mod:`wheelrail.profiles.core`).
    track_y, track_z : float
        Position of the reference point in the track frame [m].
    x : float
        Longitudinal offset of the reference point ahead of the wheel circle
        centre [m] (non-zero under yaw).
    contact_angle : float
        Contact angle γ [rad] in the side's profile orientation (positive
        towards the flange, :mod:`wheelrail.geometry.contact_search`).
    rolling_radius : float
        Wheel radius at the reference point [m].
    """

    side: str
    wheel_y: float
    rail_y: float
    track_y: float
    track_z: float
    x: float
    contact_angle: float
    rolling_radius: float

    def to_dict(self) -> dict:
        return {k: getattr(self, k) for k in self.__dataclass_fields__}


def _sample_profile(kind: str, m: int) -> np.ndarray:
    s = 1.0 - (np.arange(m) + 0.5) * (2.0 / m)       # leading edge (s = 1) first
    if kind == "elliptic":
        return np.sqrt(np.clip(1.0 - s * s, 0.0, None))
    return np.clip(1.0 - s * s, 0.0, None)


@dataclass(frozen=True, eq=False)
class ContactPatch:
    """One contact patch described by strips, with its normal force (frozen, SI).

    Attributes
    ----------
    y, dy : ndarray, shape (ny,)
        Strip centres and widths [m] (contact-plane y, to the right).
    x_lead, x_trail : ndarray, shape (ny,)
        Leading (larger x) and trailing edge of every strip [m]; an empty
        strip has ``x_lead == x_trail``.
    strip_pressure : ndarray, shape (ny, m)
        Pressure [Pa] at the centres of ``m`` equal cells of every strip,
        leading edge first (cell ``i`` at ``x_lead − (i + ½)(x_lead − x_trail)/m``).
    Fn : float
        Normal force of the patch [N] (compression positive).
    materials : MaterialPair
    a, b : float
        Semi-axes of the equivalent ellipse [m] (exact for a Hertzian patch).
    penetration : float
        Approach of the bodies at the patch [m] (NaN if not defined).
    A, B : float
        Combined curvatures of the undeformed gap at the reference point [1/m]
        (NaN if not defined).
    hertz : HertzContact or None
        The Hertz ellipse of a Hertzian patch.
    grid, pressure, mask : Grid, ndarray (nx, ny), ndarray of bool, or None
        Pressure field on the half-space grid that produced the patch
        (boundary elements); ``mask`` marks the elements of this patch.
    frame : ContactFrame or None
        Position on wheel and rail (wheel–rail problems).
    method : str
        Name of the normal method that made the patch.
    info : dict
        Method-specific extras (iterations, truncation, ...).
    """

    y: np.ndarray
    dy: np.ndarray
    x_lead: np.ndarray
    x_trail: np.ndarray
    strip_pressure: np.ndarray
    Fn: float
    materials: MaterialPair
    a: float
    b: float
    penetration: float = float("nan")
    A: float = float("nan")
    B: float = float("nan")
    hertz: Any = None
    grid: Any = None
    pressure: Any = None
    mask: Any = None
    frame: ContactFrame | None = None
    method: str = ""
    info: dict = field(default_factory=dict)

    def __post_init__(self):
        ny = np.shape(self.y)[0] if np.ndim(self.y) == 1 else -1
        for name in ("y", "dy", "x_lead", "x_trail"):
            v = np.asarray(getattr(self, name), dtype=float)
            if v.shape != (ny,) or ny < 1:
                raise InputError(f"ContactPatch.{name} must have shape (ny,) with ny >= 1, "
                                 f"got {v.shape}")
            object.__setattr__(self, name, v)
        p = np.asarray(self.strip_pressure, dtype=float)
        if p.ndim != 2 or p.shape[0] != ny or p.shape[1] < 1:
            raise InputError(f"ContactPatch.strip_pressure must have shape ({ny}, m), got {p.shape}")
        if np.any(~np.isfinite(p)) or np.any(p < 0):
            raise InputError("ContactPatch.strip_pressure must be finite and >= 0")
        object.__setattr__(self, "strip_pressure", p)
        object.__setattr__(self, "materials", as_material_pair(self.materials))
        for name in ("Fn", "a", "b"):
            v = float(getattr(self, name))
            if not (np.isfinite(v) and v > 0):
                raise InputError(f"ContactPatch.{name} must be > 0, got {v!r}")
            object.__setattr__(self, name, v)

    # ------------------------------------------------------------ constructors
    @classmethod
    def _trusted(cls, **values) -> "ContactPatch":
        """A patch from values the library has built and checked itself (private).

        Skips :meth:`__post_init__`: the caller guarantees what it checks
        (float arrays of shape (ny,), ``strip_pressure`` (ny, m) finite and
        ≥ 0, ``Fn``, ``a``, ``b`` finite floats > 0, ``materials`` a
        :class:`MaterialPair`). User input never comes here.
        """
        obj = object.__new__(cls)
        for f in _PATCH_FIELDS:
            v = values.pop(f.name) if f.name in values else (
                f.default_factory() if f.default_factory is not MISSING else f.default)
            object.__setattr__(obj, f.name, v)
        if values:
            raise TypeError(f"unknown ContactPatch fields {sorted(values)}")
        return obj

    @classmethod
    def from_hertz(cls, contact, *, strips: int = DEFAULT_STRIPS, cells: int = DEFAULT_CELLS,
                   frame: ContactFrame | None = None, method: str = "hertz") -> "ContactPatch":
        """The patch of a single Hertzian contact (semi-elliptic pressure).

        Parameters
        ----------
        contact : HertzContact
            A single contact (not a batch).
        strips, cells : int
            Strips across the ellipse and cells along each strip.
        """
        if np.shape(contact.a) != ():
            raise InputError("ContactPatch.from_hertz needs a single HertzContact, got a batch")
        strips, cells = integer("strips", strips), integer("cells", cells)
        a, b = float(contact.a), float(contact.b)
        t = -1.0 + (np.arange(strips) + 0.5) * (2.0 / strips)
        half = np.sqrt(1.0 - t * t)
        p = float(contact.p0) * half[:, None] * _sample_profile("elliptic", cells)[None, :]
        p0, load = float(contact.p0), float(contact.Fn)
        if (all(math.isfinite(v) and v > 0 for v in (a, b, p0, load))
                and isinstance(contact.materials, MaterialPair)):
            # what __post_init__ would check holds: float arrays (strips,), p finite >= 0
            return cls._trusted(y=b * t, dy=np.full(strips, 2.0 * b / strips), x_lead=a * half,
                                x_trail=-a * half, strip_pressure=p, Fn=load,
                                materials=contact.materials, a=a, b=b,
                                penetration=float(contact.penetration), A=float(contact.A),
                                B=float(contact.B), hertz=contact, frame=frame, method=method)
        return cls(y=b * t, dy=np.full(strips, 2.0 * b / strips), x_lead=a * half,
                   x_trail=-a * half, strip_pressure=p, Fn=float(contact.Fn),
                   materials=contact.materials, a=a, b=b,
                   penetration=float(contact.penetration), A=float(contact.A),
                   B=float(contact.B), hertz=contact, frame=frame, method=method)

    @classmethod
    def from_grid(cls, grid, pressure, mask, materials, *, penetration=float("nan"),
                  A=float("nan"), B=float("nan"), cells: int = DEFAULT_CELLS,
                  frame: ContactFrame | None = None, origin=(0.0, 0.0), method: str = "bem",
                  info: dict | None = None) -> "ContactPatch":
        """The patch of a pressure field on a half-space grid (one connected patch).

        Every grid column (fixed y) with contact elements is a strip; its
        edges are the outer edges of its first and last contact element, and
        its pressure is resampled to ``cells`` equal cells (linear
        interpolation of the element values, zero at the edges).

        Parameters
        ----------
        grid : Grid
        pressure : ndarray, shape (nx, ny)
            Pressure [Pa] on the grid.
        mask : ndarray of bool, shape (nx, ny)
            Elements of this patch.
        materials : Material or MaterialPair
        origin : (float, float)
            Grid coordinates [m] of the patch's reference point; strip
            coordinates are relative to it.
        """
        mask = np.asarray(mask, dtype=bool)
        p = np.where(mask, np.asarray(pressure, dtype=float), 0.0)
        cols = np.nonzero(mask.any(axis=0))[0]
        if cols.size == 0:
            raise InputError("ContactPatch.from_grid: the mask selects no element")
        cols = np.arange(cols[0], cols[-1] + 1)
        x = grid.x - origin[0]
        ys = grid.y[cols] - origin[1]
        xl = np.zeros(cols.size)
        xt = np.zeros(cols.size)
        sp = np.zeros((cols.size, cells))
        frac = (np.arange(cells) + 0.5) / cells
        for k, j in enumerate(cols):
            rows = np.nonzero(mask[:, j])[0]
            if rows.size == 0:
                continue
            lo, hi = rows[0], rows[-1]
            xt[k] = x[lo] - 0.5 * grid.dx
            xl[k] = x[hi] + 0.5 * grid.dx
            xs = xl[k] - frac * (xl[k] - xt[k])
            xp = np.concatenate(([xt[k]], x[lo:hi + 1], [xl[k]]))
            pp = np.concatenate(([0.0], p[lo:hi + 1, j], [0.0]))
            sp[k] = np.interp(xs, xp, pp)
            # keep the strip's force: scale the resampled cells to the element sum
            s_elem = p[lo:hi + 1, j].sum() * grid.dx
            s_cell = sp[k].sum() * (xl[k] - xt[k]) / cells
            if s_cell > 0:
                sp[k] *= s_elem / s_cell
        dA = grid.element_area
        Fn = float(p.sum() * dA)
        area = float(mask.sum() * dA)
        length = float(np.max(xl - xt))
        width = float(cols.size * grid.dy)
        a, b = _equivalent_semiaxes(area, length, width)
        return cls(y=ys, dy=np.full(cols.size, grid.dy), x_lead=xl, x_trail=xt,
                   strip_pressure=sp, Fn=Fn, materials=materials, a=a, b=b,
                   penetration=float(penetration), A=float(A), B=float(B), grid=grid,
                   pressure=p, mask=mask, frame=frame, method=method, info=dict(info or {}))

    # ------------------------------------------------------------ derived
    @property
    def is_hertzian(self) -> bool:
        """True for the patch of a Hertz ellipse."""
        return self.hertz is not None

    @property
    def cells(self) -> int:
        """Cells per strip ``m``."""
        return self.strip_pressure.shape[1]

    @property
    def area(self) -> float:
        """Contact area [m²] (exact ellipse area for a Hertzian patch)."""
        if self.hertz is not None:
            return float(self.hertz.area)
        if self.mask is not None:
            return float(self.mask.sum() * self.grid.element_area)
        return float(np.sum(np.clip(self.x_lead - self.x_trail, 0.0, None) * self.dy))

    @property
    def p_max(self) -> float:
        """Largest pressure [Pa]."""
        if self.hertz is not None:
            return float(self.hertz.p0)
        if self.pressure is not None:
            return float(np.max(self.pressure))
        return float(np.max(self.strip_pressure))

    @property
    def centre(self) -> tuple[float, float]:
        """Centre of pressure (x, y) in patch coordinates [m]."""
        xc = self.cell_x()
        w = self.strip_pressure * (self.dy * (self.x_lead - self.x_trail) / self.cells)[:, None]
        tot = float(w.sum())
        return (float((w * xc).sum() / tot), float((w * self.y[:, None]).sum() / tot))

    def cell_x(self) -> np.ndarray:
        """Cell centres along the strips [m], shape (ny, m), leading edge first."""
        frac = (np.arange(self.cells) + 0.5) / self.cells
        return self.x_lead[:, None] - frac[None, :] * (self.x_lead - self.x_trail)[:, None]

    def ellipse(self):
        """The equivalent :class:`~wheelrail.hertzian.HertzContact` (a, b, Fn).

        The Hertz ellipse itself for a Hertzian patch; otherwise the ellipse
        with the patch's semi-axes ``a``, ``b`` (same area, same
        length/width ratio) carrying ``Fn``. Closed-form creep laws read this.
        """
        if self.hertz is not None:
            return self.hertz

        return hertz_from_semiaxes(self.a, self.b, self.Fn, self.materials)

    def with_frame(self, frame: ContactFrame) -> "ContactPatch":
        """A copy placed at ``frame``."""
        return replace(self, frame=frame)


_PATCH_FIELDS = fields(ContactPatch)


def _equivalent_semiaxes(area: float, length: float, width: float) -> tuple[float, float]:
    """Semi-axes of the ellipse with ``area`` and the length/width ratio of the patch."""
    ratio = length / width if width > 0 else 1.0
    a = float(np.sqrt(area * ratio / np.pi))
    b = float(np.sqrt(area / (ratio * np.pi)))
    return a, b
