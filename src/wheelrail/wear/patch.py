"""Wear on one contact patch: the local law on the traction and slip fields.

:func:`patch_wear` takes any patch solution that carries surface fields
(FASTSIM on an ellipse or on strips, Kalker's exact theory on a grid; the
per-patch results of :func:`wheelrail.solve` and the results of
:func:`wheelrail.creep_forces`) and a wear law (:mod:`wheelrail.wear`), and
returns the wear-depth distribution across the patch per passage.

Definitions (the patch moves over the surfaces in the rolling direction x):

* a surface point (of the wheel or of the rail) rolled through a cell of
  length Δx with the dimensionless slip ‖s‖ slides ‖s‖ Δx; the law gives the
  depth rate dz/dx per cell (:class:`~wheelrail.wear._base.WearLaw`);
* **depth per passage** at the lateral position y of a column of cells:
  d(y) = Σ_x dz/dx · Δx (sum along the rolling direction). Every point of
  the rail at y loses d(y) when one wheel passes; every point of the wheel
  tread at y loses d(y) per wheel revolution, i.e. d(y)/(2π r) per metre
  travelled (r the rolling radius);
* **worn volume per metre rolled** V' = Σ dz/dx ΔA = ∫ d(y) dy [m³/m] — the
  integral of the local law over the patch;
* the wear number Tγ = Σ ‖τ‖‖s‖ ΔA [N] (frictional power per metre rolled).

Both bodies are given the same depth (one law for the wheel and the rail
steel, as in the USFD and KTH data); to wear them differently, call
:func:`patch_wear` with two laws.

For a law stated per patch (USFD with ``application="patch"``) the patch's
Tγ/A gives the worn volume per metre rolled V' = A · K(Tγ/A)/ρ, which is
distributed over the cells in proportion to the local frictional work
‖τ‖‖s‖ (so that the wear concentrates where the patch slides, and the local
and patch applications coincide in the mild, linear regime).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError
from ._base import WearLaw, get

__all__ = ["PatchWear", "patch_wear", "deposit"]


@dataclass(frozen=True)
class PatchWear:
    """Wear of one patch per passage (frozen, SI).

    Attributes
    ----------
    y : ndarray, shape (ny,)
        Lateral positions of the cell columns in the contact plane [m]
        (relative to the patch's reference point, y to the right).
    dy : ndarray, shape (ny,)
        Column widths [m].
    depth : ndarray, shape (ny,)
        Depth removed per passage at ``y`` [m] (normal to the surface).
    rate : ndarray, shape (nx, ny)
        Local depth rate dz/dx per cell [m/m], indexed ``[i_x, i_y]``.
    area : ndarray, shape (nx, ny)
        Cell areas [m²] (zero outside the contact).
    volume_rate : float
        Worn volume per metre rolled Σ rate·area [m³/m].
    Tgamma : float
        Wear number Σ ‖τ‖‖s‖ ΔA [N].
    contact_area : float
        Area of the cells in contact [m²].
    law : str
        Name of the wear law.
    side : str or None
        ``"left"``/``"right"`` for a wheel–rail patch.
    wheel_y, rail_y, contact_angle, rolling_radius : float
        From the patch's contact frame (NaN without one).
    """

    y: np.ndarray
    dy: np.ndarray
    depth: np.ndarray
    rate: np.ndarray
    area: np.ndarray
    volume_rate: float
    Tgamma: float
    contact_area: float
    law: str
    side: str | None = None
    wheel_y: float = math.nan
    rail_y: float = math.nan
    contact_angle: float = math.nan
    rolling_radius: float = math.nan
    info: dict = field(default_factory=dict)

    @property
    def Tgamma_over_A(self) -> float:
        """Tγ/A [N/m² = Pa] (divide by 1e6 for N/mm²)."""
        return self.Tgamma / self.contact_area if self.contact_area > 0 else 0.0

    @property
    def max_depth(self) -> float:
        """Largest depth per passage [m]."""
        return float(self.depth.max()) if self.depth.size else 0.0

    def volume_per_passage(self) -> float:
        """∫ d(y) dy [m³/m] (equal to :attr:`volume_rate`)."""
        return float(np.sum(self.depth * self.dy))

    def wheel_depth_per_metre(self, wheel_radius: float | None = None) -> np.ndarray:
        """Depth removed from the wheel tread per metre travelled, d(y)/(2π r) [m/m].

        ``wheel_radius`` [m] defaults to the patch's rolling radius.
        """
        r = self.rolling_radius if wheel_radius is None else float(wheel_radius)
        if not (np.isfinite(r) and r > 0):
            raise InputError(f"wheel_radius must be a radius > 0 m, got {wheel_radius!r} "
                             "(the patch has no contact frame with a rolling radius)")
        return self.depth / (2.0 * math.pi * r)

    def profile_y(self, body: str = "wheel") -> tuple[np.ndarray, np.ndarray]:
        """Column edges ``(lo, hi)`` in the lateral coordinate of the wheel or rail profile [m].

        A contact-plane offset y maps to the profile offset σ y cos γ (σ = +1
        on the right side, −1 on the left, whose field side is to the left; γ
        the contact angle).
        """
        if body not in ("wheel", "rail"):
            raise InputError(f"body must be 'wheel' or 'rail', got {body!r}")
        ref = self.wheel_y if body == "wheel" else self.rail_y
        if self.side not in ("left", "right") or not np.isfinite(ref):
            raise InputError("this patch has no wheel–rail contact frame; give the profile "
                             "position yourself (PatchWear.y and .dy are contact-plane offsets)")
        sigma = 1.0 if self.side == "right" else -1.0
        c = math.cos(self.contact_angle) if np.isfinite(self.contact_angle) else 1.0
        a = ref + sigma * c * (self.y - 0.5 * self.dy)
        b = ref + sigma * c * (self.y + 0.5 * self.dy)
        return np.minimum(a, b), np.maximum(a, b)

    def on_profile(self, edges, body: str = "wheel") -> np.ndarray:
        """Depth per passage on bins of a profile's lateral coordinate (see :func:`deposit`).

        Parameters
        ----------
        edges : array_like, shape (n + 1,)
            Increasing bin edges in the profile frame [m].
        body : {"wheel", "rail"}

        Returns
        -------
        ndarray, shape (n,)
            Mean normal depth per passage in each bin [m].
        """
        lo, hi = self.profile_y(body)
        return deposit(lo, hi, self.depth, edges)


def deposit(lo, hi, values, edges) -> np.ndarray:
    """Average of piecewise-constant ``values`` on intervals [lo, hi] over bins with ``edges``.

    Conserves the integral: Σ out·Δedge = Σ values·(hi − lo) over the part of
    the intervals inside the bins.
    """
    e = np.asarray(edges, dtype=float)
    if e.ndim != 1 or e.size < 2 or np.any(np.diff(e) <= 0):
        raise InputError("edges must be an increasing 1-D array of at least 2 values")
    lo = np.asarray(lo, dtype=float).ravel()
    hi = np.asarray(hi, dtype=float).ravel()
    v = np.asarray(values, dtype=float).ravel()
    ov = np.clip(np.minimum(hi[:, None], e[None, 1:]) - np.maximum(lo[:, None], e[None, :-1]),
                 0.0, None)
    return (v[:, None] * ov).sum(axis=0) / np.diff(e)


def _unpack(patch_result):
    """(fields, frame) of a patch result, CreepForcesResult or fields object."""
    frame = None
    obj = patch_result
    if hasattr(obj, "patch") and hasattr(obj, "forces"):      # PatchResult of wr.solve
        frame = getattr(obj.patch, "frame", None)
        obj = obj.forces
    if hasattr(obj, "fields") and not hasattr(obj, "as_arrays"):   # CreepForcesResult
        method = getattr(obj, "method", "?")
        obj = obj.fields
        if obj is None:
            raise InputError(f"the creep-force law {method!r} gives no traction and slip "
                             "fields; use a field method (fastsim, exact) for wear")
    if isinstance(obj, tuple):
        raise InputError("patch_wear takes one patch; this result is a batch — pass its "
                         "cases one at a time")
    if not hasattr(obj, "as_arrays"):
        raise InputError(f"patch_wear needs a patch solution with traction and slip fields "
                         f"(FASTSIM, exact theory), got {type(patch_result).__name__}")
    tang = getattr(obj, "tangential", obj)
    if getattr(tang, "kind", "rolling") != "rolling":
        raise InputError("patch_wear needs a rolling solution (its slip is per metre "
                         "rolled); this one is a shift")
    return obj, frame


def patch_wear(patch_result, law="archard", *, speed=None, **options) -> PatchWear:
    """Wear-depth distribution of one patch per passage from its traction and slip fields.

    Parameters
    ----------
    patch_result : PatchResult, CreepForcesResult, FastsimFields, GapResult or TangentialResult
        One patch solved with a field method: a patch of
        :func:`wheelrail.solve` (its contact frame places the wear on the
        profiles), the result of :func:`wheelrail.creep_forces` with
        ``"fastsim"`` or ``"exact"``, or their ``fields``.
    law : str, type or WearLaw
        A wear law by name (``"archard"``, ``"kth"``, ``"usfd"``, ``"energy"``)
        or a configured object (``wr.wear.USFD(application="patch")``).
    speed : float, optional
        Rolling speed [m/s] (needed by the KTH map: sliding velocity = ‖s‖ V).
    **options
        Options of the law when given by name.

    Returns
    -------
    PatchWear
        Depth per passage across the patch, cell rates, worn volume per
        metre rolled, Tγ.

    Raises
    ------
    InputError
        A result without fields (closed-form creep laws), a batch, a shift
        solution, a law that needs ``speed`` without it.

    Examples
    --------
    >>> import wheelrail as wr
    >>> c = wr.hertz(1e4, A=0.5/0.46, B=0.5/0.3, material=wr.STEEL)
    >>> r = wr.creep_forces(c, (-2e-3, 0.0, 0.0), 0.3, "fastsim")
    >>> w = wr.wear.patch_wear(r, wr.wear.Archard(k=1e-4))
    >>> abs(w.volume_per_passage() - w.volume_rate) < 1e-18
    True
    """
    impl = get(law, **options) if not (isinstance(law, WearLaw) and not options) else law
    if impl.needs_speed and speed is None:
        raise InputError(f"wear law {impl.name!r} needs the rolling speed: speed=... [m/s]")
    fields, frame = _unpack(patch_result)
    arr = fields.as_arrays()
    inside = np.asarray(arr["inside"], bool)
    dA = np.where(inside, np.asarray(arr["dA"], dtype=float), 0.0)
    p = np.where(inside, np.asarray(arr["p"], dtype=float), 0.0)
    tau = np.where(inside, np.hypot(arr["px"], arr["py"]), 0.0)
    s = np.where(inside, np.hypot(arr["sx"], arr["sy"]), 0.0)
    work = tau * s
    Tgamma = float(np.sum(work * dA))
    area = float(np.sum(dA))
    if impl.is_per_patch:
        x = Tgamma / area if area > 0 else 0.0
        total = float(impl.patch_rate(x)) * area        # m³ per metre rolled
        rate = total * work / Tgamma if Tgamma > 0 else np.zeros_like(work)
    else:
        rate = np.where(inside, impl.depth_rate(p, tau, s, speed), 0.0)
    if np.any(rate < 0) or not np.all(np.isfinite(rate)):
        raise InputError(f"wear law {impl.name!r} gave a negative or non-finite rate")
    y_col = np.asarray(arr["y"], dtype=float)[0, :]
    if hasattr(fields, "dy") and np.ndim(getattr(fields, "dy")) == 1:
        dy = np.asarray(fields.dy, dtype=float)
    elif hasattr(fields, "grid"):
        dy = np.full(y_col.shape, float(fields.grid.dy))
    else:                                                   # pragma: no cover - generic
        dy = np.gradient(y_col) if y_col.size > 1 else np.ones(1)
    with np.errstate(invalid="ignore", divide="ignore"):
        depth = np.where(dy > 0, np.sum(rate * dA, axis=0) / np.where(dy > 0, dy, 1.0), 0.0)
    kw = {}
    if frame is not None:
        kw = dict(side=frame.side, wheel_y=float(frame.wheel_y), rail_y=float(frame.rail_y),
                  contact_angle=float(frame.contact_angle),
                  rolling_radius=float(frame.rolling_radius))
    return PatchWear(y=y_col, dy=dy, depth=depth, rate=rate, area=dA,
                     volume_rate=float(np.sum(rate * dA)), Tgamma=Tgamma, contact_area=area,
                     law=impl.name, info={"speed": speed}, **kw)
