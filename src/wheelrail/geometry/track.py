"""The :class:`Track`: two rails at a given gauge and inclination (cant).

Frames
------
Track cross-section: lateral ``y`` positive to the **right** (looking in the
running direction), height ``z`` up, origin on the track centre line at the
height of the top of the rails (both rails at the same height: no superelevation).

Each rail profile is given in the profile frame of
:mod:`wheelrail.profiles.core` (``y`` to the field side, origin on the rail
head centre line, ``z = 0`` top of rail). It is first inclined towards the
track centre by ``atan(inclination)`` (a counter-clockwise rotation about the
profile origin, which makes the running surface rise towards the field side),
unless ``canted=True`` says that the profile file is already given in its
inclined position. Parts of the rotated contour that are hidden from above
(a head side that becomes vertical or overhanging, e.g. the 1:20 side of
60E1 under a 1:20 inclination) are dropped; the gauge point may still lie on
such a part. It is then lifted so that its highest point is at ``z = 0``
and placed laterally so that the gauge — the distance between the gauge
faces measured ``gauge_height`` below the top of rail — equals ``gauge``. The
right rail keeps its profile orientation; the left rail is mirrored.

Internally each side is described in *side-local* coordinates ``u`` (lateral,
positive towards that side's field side, ``u = +y`` on the right and
``u = −y`` on the left) so that left and right use the same formulas.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from .._validation import as_float_array, non_negative, positive
from ..errors import InputError, ProfileError
from ._checks import SIDES, check_profile, check_side
from ._curves import SAMPLE_STEP, PiecewiseCubic, rotate, sample_profile

__all__ = ["Track", "RailPlacement"]


@dataclass(frozen=True)
class RailPlacement:
    """Where one rail sits in the track (side-local coordinates, SI).

    Attributes
    ----------
    angle : float
        Rotation applied to the profile [rad] (0 if ``canted``).
    z_top : float
        Height of the highest point of the rotated profile before lifting [m].
    offset : float
        Side-local lateral position ``u`` of the profile origin [m].
    gauge_point : float
        Side-local ``u`` of the gauge point [m] (= gauge/2 by construction).
    curve : PiecewiseCubic
        Rail surface Z(u) in side-local coordinates.
    """

    angle: float
    z_top: float
    offset: float
    gauge_point: float
    curve: PiecewiseCubic

    def to_profile_frame(self, u, z):
        """Side-local (u, z) → rail profile frame (y, z) (undoes placement and cant)."""
        yr, zr = np.asarray(u) - self.offset, np.asarray(z) + self.z_top
        return rotate(yr, zr, -self.angle)


def _seen_from_above(y, z, max_slope=100.0):
    """Indices of the rail contour points visible from above (sorted, y strictly increasing).

    Walking outwards from the highest point, a point is kept only if it lies
    further out than the last kept point by more than ``1/max_slope`` of the
    drop between them: vertical faces (a 1:20 head side under a 1:20
    inclination), overhangs (a steeper inclination, measured profiles) and
    faces steeper than ``max_slope`` (89.4°), which a wheel coming from above
    cannot touch and which a spline z(y) cannot follow, are dropped.
    """
    top = int(np.argmax(z))
    left = [top]
    for i in range(top - 1, -1, -1):
        j = left[-1]
        if y[j] - y[i] > max(1e-9, abs(z[j] - z[i]) / max_slope):
            left.append(i)
    right = [top]
    for i in range(top + 1, y.size):
        j = right[-1]
        if y[i] - y[j] > max(1e-9, abs(z[j] - z[i]) / max_slope):
            right.append(i)
    return np.array(left[::-1] + right[1:], dtype=int)


def _gauge_point(y, z, depth, polish=True):
    """Innermost (smallest y) point of the rail at height −depth (first crossing from the gauge side)."""
    above = z >= -depth
    if not np.any(above):
        raise ProfileError("rail profile lies entirely below the gauge measuring height")
    i = int(np.flatnonzero(above)[0])
    if i == 0:
        raise ProfileError(
            f"rail profile does not reach {depth * 1e3:.1f} mm below the top of rail on the gauge "
            f"side (lowest gauge-side point z = {z[0] * 1e3:.2f} mm); the gauge cannot be placed "
            "(a flat or shallow profile has no gauge face: use a rail-head profile, or a smaller "
            "gauge_height)")
    t = (-depth - z[i - 1]) / (z[i] - z[i - 1])
    yg = y[i - 1] + t * (y[i] - y[i - 1])
    if not polish:
        return float(yg)
    # polish on the cubic spline through the points (Newton, bracketed by the two samples)
    spline = PiecewiseCubic.through(y, z)
    for _ in range(4):
        f, f1 = spline.eval(yg, 1)
        if f1 <= 0:
            break
        yg = min(max(yg - (f + depth) / f1, y[i - 1]), y[i])
    return float(yg)


@dataclass(frozen=True, eq=False)
class Track:
    """Two rails laid at gauge ``gauge`` with inclination ``inclination``.

    Parameters
    ----------
    rail : Profile
        Rail profile (kind ``"rail"``) of the **left** rail, and of the right
        rail unless ``rail_right`` is given; profile frame (y to the field
        side, uncanted unless ``canted``). Mirrored when placed on the left.
    gauge : float
        Track gauge [m] (default 1.435), measured ``gauge_height`` below the
        top of rail.
    inclination : float
        Rail inclination towards the track centre as a slope (default 1/40;
        0 for vertical rails).
    gauge_height : float
        Depth below the top of rail of the gauge measuring point [m]
        (default 0.014, EN 13848-1).
    rail_right : Profile, optional
        Right rail profile; ``None`` uses ``rail``.
    canted : bool
        True if the profile is already in its inclined (canted) position, e.g.
        a measured profile or the Manchester-benchmark UIC60 file; no rotation
        is then applied and ``inclination`` is informational only.
    """

    rail: object
    gauge: float = 1.435
    inclination: float = 1.0 / 40.0
    gauge_height: float = 0.014
    rail_right: object = None
    canted: bool = False

    def __post_init__(self):
        check_profile("rail", self.rail, "rail")
        if self.rail_right is None:
            object.__setattr__(self, "rail_right", self.rail)
        else:
            check_profile("rail_right", self.rail_right, "rail")
        object.__setattr__(self, "gauge", float(positive("gauge", self.gauge)))
        if not 0.5 < self.gauge < 2.0:
            raise InputError(f"gauge must lie in (0.5, 2.0) m, got {self.gauge!r} (mm given?)")
        inc = float(as_float_array("inclination", self.inclination))
        if abs(inc) > 0.2:
            raise InputError(f"inclination is a slope (e.g. 1/40 = 0.025), got {self.inclination!r}")
        object.__setattr__(self, "inclination", inc)
        gh = float(non_negative("gauge_height", self.gauge_height))
        if gh > 0.05:
            raise InputError(f"gauge_height must be <= 0.05 m, got {self.gauge_height!r}")
        object.__setattr__(self, "gauge_height", gh)
        object.__setattr__(self, "canted", bool(self.canted))
        self._placements  # noqa: B018  (validate the placement now, errors at construction)

    @property
    def rail_left(self):
        """Profile of the left rail (``rail``)."""
        return self.rail

    @property
    def cant_angle(self) -> float:
        """Rotation applied to the rail profiles [rad] (0 when ``canted``)."""
        return 0.0 if self.canted else float(np.arctan(self.inclination))

    def profile(self, side: str):
        """Rail profile of ``side`` ("left" or "right")."""
        return self.rail if check_side(side) == "left" else self.rail_right

    def placement(self, side: str) -> RailPlacement:
        """Placement of the rail of ``side`` (cached)."""
        return self._placements[check_side(side)]

    def curve(self, side: str) -> PiecewiseCubic:
        """Rail surface Z(u) of ``side`` in side-local coordinates."""
        return self.placement(side).curve

    @cached_property
    def _placements(self) -> dict:
        out = {}
        for side in SIDES:
            prof = self.profile(side)
            if side == "right" and prof is self.rail:
                out[side] = out["left"]
                continue
            y, z = sample_profile(prof)
            angle = self.cant_angle
            yr, zr = rotate(y, z, angle)
            z_top = float(np.max(zr))
            zr = zr - z_top
            keep = _seen_from_above(yr, zr)
            if keep.size < 4:
                raise ProfileError(
                    f"rail {getattr(prof, 'name', '')!r}: after the inclination of "
                    f"{self.inclination!r} less than 4 points of the rail are visible from above")
            try:
                try:
                    yg = _gauge_point(yr[keep], zr[keep], self.gauge_height)
                except ProfileError:
                    if keep.size == yr.size:
                        raise
                    # the gauge point lies on a vertical or overhanging part that is hidden
                    # from above: locate it on the whole contour (linear interpolation)
                    yg = _gauge_point(yr, zr, self.gauge_height, polish=False)
            except ProfileError as exc:
                raise ProfileError(f"rail {getattr(prof, 'name', '')!r}: {exc}") from None
            yr, zr = yr[keep], zr[keep]
            offset = 0.5 * self.gauge - yg
            curve = PiecewiseCubic.through(yr + offset, zr, uniform_step=SAMPLE_STEP)
            out[side] = RailPlacement(angle, z_top, offset, 0.5 * self.gauge, curve)
        return out
