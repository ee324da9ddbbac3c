"""Hertz's theory as a normal method (:class:`Hertz`): one ellipse per contact point.

The closed forms (:func:`~wheelrail.hertzian.hertz`, :class:`~wheelrail.hertzian.HertzContact`)
live in the core module :mod:`wheelrail.hertzian`.

References
----------
.. [1] K.L. Johnson, *Contact Mechanics*, CUP 1985, §4.2.
.. [2] J. Piotrowski, H. Chollet, Wheel–rail contact models for vehicle system
   dynamics including multi-point contact, Vehicle System Dynamics 43 (2005)
   455–483, §2.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..errors import InputError, NoContactError
from ..hertzian import (
    _checked_curvatures,
    _make,
    _vertical_approach,
    hertz,
    hertz_from_penetration,
    hertz_kernel,
)
from ..materials import as_material_pair
from ..options import configured
from ..patch import ContactPatch
from ._base import NormalMethod, PatchDescription
from ._gap import _check_search, _minimum, _principal_curvatures

__all__ = ["Hertz"]


# --------------------------------------------------------------------------- normal method
def _check_on_rail(problem, k, b):
    """The patch of half-width ``b`` around point ``k`` must lie on the rail profile."""
    rail = problem.track.profile(problem.side) if problem.track is not None else None
    if rail is None:
        return
    y = float(problem.points.rail_y[k])
    lo, hi = float(np.min(rail.y)), float(np.max(rail.y))
    if y - b < lo or y + b > hi:
        what = (f"vertical load {problem.vertical_load!r} N" if problem.vertical_load is not None
                else f"vertical approach {problem.vertical_approach!r} m")
        raise InputError(
            f"{problem.side} wheel: the {what} gives a Hertz patch of half-width b = {b:.4g} m "
            f"around y = {y:.4g} m on the rail profile, which spans only [{lo:.4g}, {hi:.4g}] m: "
            "these profiles cannot carry that load")


@configured
class Hertz(NormalMethod, PatchDescription):
    """Hertz's theory as a normal method: one ellipse per contact point.

    * a :class:`HertzContact`: its own ellipse;
    * a gap h(x, y): the ellipse of the principal curvatures of h at its
      minimum (for a prescribed approach, δ is measured from that minimum);
    * a wheel on its rail: one ellipse per candidate contact point with the
      curvatures of the profiles there (A, B of
      :func:`wheelrail.contact_points`); the penetrations follow from the
      wheel's vertical approach dz, δ_k = dz cos γ_k − s_k (s_k the
      undeformed separation), and dz from Σ Fn_k cos γ_k = Q (the vertical
      load) — the multi-point elastic contact of Bosso et al. (2013), ch. 2 eq. 2.4 with
      Hertzian stiffness per point, or Piotrowski & Chollet's independent
      ellipses (Piotrowski & Chollet (2005) §2).

    Other Parameters
    ----------------
    strips, cells : int, default 40, 40
        Strips and cells per strip of the patch description (used by strip
        theories; the closed-form laws and FASTSIM use the ellipse itself).

    References
    ----------
    .. [1] K.L. Johnson, *Contact Mechanics*, CUP 1985, §4.2.
    .. [2] Bosso et al. (2013), ch. 2, §2.1.2, eq. (2.4); Piotrowski & Chollet (2005), §2.
    """

    name = "hertz"
    references = ("H. Hertz, Ueber die Berührung fester elastischer Körper, J. reine angew. "
                  "Math. 92 (1882) 156-171.",
                  "K.L. Johnson, Contact Mechanics, Cambridge University Press, 1985.")

    def from_contact(self, contact):
        strips, cells = self.strips, self.cells

        return (ContactPatch.from_hertz(contact, strips=strips, cells=cells),)

    def from_gap(self, problem):
        strips, cells = self.strips, self.cells

        search = _check_search(problem.search)
        xm, ym, hmin, spacing = _minimum(problem.gap, search)
        hx, hy = spacing
        pair = as_material_pair(problem.materials)
        c = None
        for _ in range(3):      # probe the curvatures at the scale of the patch
            c = _principal_curvatures(problem.gap, xm, ym, hx, hy)
            if not c[0] > 0:
                raise InputError(f"the gap is not convex at its minimum (x, y) = ({xm!r}, {ym!r}) m "
                                 f"(principal curvatures {c.tolist()} 1/m): Hertz cannot "
                                 "represent it; use normal='bem'")
            if problem.Fn is not None:
                hc = hertz(problem.Fn, c[0], c[1], pair)
            else:
                delta = float(problem.penetration) - hmin
                if not delta > 0:
                    raise NoContactError(f"no contact: the penetration {problem.penetration!r} m "
                                         f"does not exceed the smallest gap {hmin!r} m")
                hc = hertz_from_penetration(delta, c[0], c[1], pair)
            hx = hy = 0.5 * float(np.sqrt(hc.a * hc.b))
        patch = ContactPatch.from_hertz(hc, strips=strips, cells=cells)
        info = {"centre": (xm, ym), "gap_minimum": hmin,
                "note": "principal axes of the gap assumed along x and y"}
        return (replace(patch, info=info),)

    def from_wheel(self, problem):
        strips, cells = self.strips, self.cells

        pts = problem.points
        pair = as_material_pair(problem.materials)
        A = np.asarray(problem.A, dtype=float)
        B = np.asarray(problem.B, dtype=float)
        bad = ~((A > 0) & (B > 0))
        cosg = np.cos(pts.contact_angle)
        sep = np.asarray(pts.separation, dtype=float)
        # the unit-load solution of every convex point (kept in the problem's cache: the
        # vertical-load passes of solve_wheelrail re-solve the same points)
        key = ("hertz_unit", pair.E_star, A.tobytes(), B.tobytes())
        cache = getattr(problem, "cache", None)
        unit = cache.get(key) if isinstance(cache, dict) else None
        if unit is None:
            unit = np.full((4,) + A.shape, np.inf)
            unit[:, ~bad] = hertz_kernel(1.0, A[~bad], B[~bad], pair.E_star)
            if isinstance(cache, dict):
                cache[key] = unit
        d1 = unit[3]
        if problem.vertical_approach is not None:
            dz = float(problem.vertical_approach)
        else:
            if np.all(bad):
                raise InputError(f"{problem.side} wheel: no candidate contact point has convex "
                                 f"curvatures (A = {A.tolist()}, B = {B.tolist()} 1/m); Hertz "
                                 "cannot represent this contact, use normal='bem'")
            dz = _vertical_approach(float(problem.vertical_load), sep[~bad], cosg[~bad], d1[~bad])
        pen = np.clip(dz * cosg - sep, 0.0, None)
        patches = []
        for k in np.nonzero(pen > 0)[0]:
            if bad[k]:
                raise InputError(
                    f"{problem.side} wheel: contact point at wheel y = {float(pts.wheel_y[k])!r} m "
                    f"penetrates but is not convex (A = {float(A[k])!r}, B = {float(B[k])!r} 1/m); "
                    "Hertz cannot represent it, use normal='bem'")
            # as hertz_from_penetration, from the unit-load solution above
            delta = float(pen[k])                       # > 0 here
            Ak, Bk = float(A[k]), float(B[k])           # > 0 here (not bad)
            if max(Ak, Bk) / min(Ak, Bk) > 1e12:
                _checked_curvatures(Ak, Bk)             # refuses it, naming the ratio
            s = np.sqrt(delta / unit[3, k])
            hc = _make(unit[0, k] * s, unit[1, k] * s, unit[2, k] * s, delta, s**3, float(A[k]),
                       float(B[k]), pair)
            _check_on_rail(problem, k, float(hc.b))
            patches.append(ContactPatch.from_hertz(hc, strips=strips, cells=cells,
                                                   frame=problem.frames[k]))
        return tuple(patches), {"vertical_approach": dz}

