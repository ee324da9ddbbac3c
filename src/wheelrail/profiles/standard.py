"""Standard wheel and rail profiles generated from their geometric definitions.

* ``S1002`` — wheel tread profile of EN 13715 / UIC 510-2 (flange height
  28 mm, flange thickness 32.5 mm, tread 1:15 chamfer on the field side),
  defined by the eight sections A–H: two polynomials (B, C), one straight
  line (E), a straight chamfer (A) and four circular arcs (D, F, G, H).
* ``60E1`` (UIC60) and ``54E1`` (UIC54) — rail heads of EN 13674-1: three
  tangent circular arcs R300 / R80 / R13 on each side, followed by the head
  side inclined 1:20 (head widening downwards).

All profiles are returned in the profile-frame convention of
:mod:`wheelrail.profiles.core` (SI, z up, y towards the field side; rails
uncanted — apply the cant with ``rotated(np.arctan(1/40))``).

Rail head construction
----------------------
With the R1 = 300 mm arc centred on the rail centre line (top of rail at
z = 0) and tangency between consecutive arcs, the head is fixed by the
half-width ``y1`` of the R300 arc, the head half-width ``w`` at the tangent
point of R13 with the side and the side inclination 1:20:

* centre of arc 2: ``C2 = C1 + (R1 - R2) (sin a1, cos a1)``, ``sin a1 = y1/R1``;
* centre of arc 3: ``C3 = C2 + (R2 - R3) (sin a2, cos a2)`` with ``a2`` from
  ``C3_y + R3 cos(atan(1/20)) = w``;
* the side leaves arc 3 at the angle ``a3 = pi/2 - atan(1/20)``.

60E1: ``w = 36 mm`` (head width 72 mm), ``y1 = 10.5 mm``. The value of
``y1`` is not printed in the sources available to us; 10.5 mm reproduces the
R80 arc centres of the Manchester-benchmark UIC60 profile [3]_ to 1 µm (see
``tests/reference/test_standard_profiles.py``). 54E1: ``w = 35 mm`` (head
width 70 mm) with the same radii; ``y1 = 10.5 mm`` is assumed (not verified).

Status of the rail data (public sources searched for this module):

* confirmed — rail height 172 mm (60E1) / 159 mm (54E1), head width 72 / 70
  mm, foot width 150 / 140 mm, web 16.5 / 16 mm: the EN 13674-1 section table
  of the British Steel rail catalogue as tabulated in the open FE code xc
  (github.com/xcfem/xc, ``bs_en_13674-1_rail_sections.json``; RAIL_EN60E1,
  RAIL_EN54E1); heights 172 / 159 mm also in trade literature. These values are
  stored in ``meta`` (``rail_height``, ``foot_width``, ``web_thickness``; the
  generated profile is the head only) and checked in the tests.
* confirmed for 60E1 only, indirectly — radii 300 / 80 / 13 mm, side 1:20,
  ``w = 36 mm``, ``y1 = 10.5 mm``: the whole head agrees with the
  Manchester-benchmark UIC60 profile within 0.05 mm.
* not confirmed for 54E1 — radii 300 / 80 / 13 mm, side 1:20 and
  ``y1 = 10.5 mm`` (no public drawing, data sheet or profile file with the
  54E1 head arcs was found). With these values the head width (70 mm) and
  height are right; the arc layout is an assumption.

References
----------
.. [1] EN 13715:2006+A1:2010, *Railway applications — Wheelsets and bogies —
   Wheels — Tread profile*, annex with the S1002 section equations (the
   same coefficients as in UIC 510-2, annex C).
.. [2] EN 13674-1:2011, *Railway applications — Track — Rail — Part 1:
   Vignole railway rails 46 kg/m and above*, annex A (60E1, 54E1 drawings).
.. [3] Manchester contact benchmark (Shackleton & Iwnicki 2008), profiles
   ``S1002_v3`` and ``UIC60_v3`` as distributed with CONTACT (Vtech CMCC).
"""

from __future__ import annotations

import numpy as np

from ..errors import ProfileError
from .core import Profile

__all__ = ["s1002", "rail_60e1", "rail_54e1", "load", "available", "ALIASES"]

_MM = 1e-3

# --------------------------------------------------------------------------- S1002
# Section equations of EN 13715 / UIC 510-2 (mm, F positive DOWNWARD, s positive towards
# the field side, origin on the tape circle 70 mm from the back of the flange).
_A = (1.364323640, 0.066666667)
_B = (0.0, 3.358537058e-02, 1.565681624e-03, 2.810427944e-05, 5.844240864e-08,
      1.562379023e-08, 5.309217349e-15, 5.957839843e-12, 2.646656573e-13)
_C = (4.320221063e+03, 1.038384026e+03, 1.065501873e+02, 6.051367875, 2.054332446e-01,
      4.169739389e-03, 4.687195829e-05, 2.252755540e-07)
_D = (16.446, 13.0, 26.210665)
_E = (93.576667419, 2.747477419)
_F = (8.834924130, 20.0, 58.558326413)
_G = (16.0, 12.0, 55.0)
_H = (9.519259302, 20.5, 49.5)
#: section limits [mm], from the flange back (H) to the field side (A)
_S1002_BOUNDS = (-70.0, -62.764705882, -49.662510381, -39.764473993, -38.426669071, -35.0,
                 -26.0, 32.15796, 60.0)


def _s1002_F(s: np.ndarray) -> np.ndarray:
    """S1002 section equations: F(s) [mm], positive downward, for s in [-70, 60] mm."""
    s = np.asarray(s, dtype=float)
    b = _S1002_BOUNDS
    sign_b = np.array([1, -1, 1, -1, 1, -1, 1, -1, 1], dtype=float)  # A_B - B_B s + C_B s^2 ...
    fB = np.polynomial.polynomial.polyval(s, np.array(_B) * sign_b)
    fC = -np.polynomial.polynomial.polyval(s, np.array(_C))
    with np.errstate(invalid="ignore"):
        fA = _A[0] - _A[1] * s
        fD = _D[0] - np.sqrt(np.maximum(_D[1] ** 2 - (s + _D[2]) ** 2, 0.0))
        fE = -_E[0] - _E[1] * s
        fF = _F[0] + np.sqrt(np.maximum(_F[1] ** 2 - (s + _F[2]) ** 2, 0.0))
        fG = _G[0] + np.sqrt(np.maximum(_G[1] ** 2 - (s + _G[2]) ** 2, 0.0))
        fH = _H[0] + np.sqrt(np.maximum(_H[1] ** 2 - (s + _H[2]) ** 2, 0.0))
    conds = [s < b[1], s < b[2], s < b[3], s < b[4], s < b[5], s < b[6], s < b[7]]
    return np.select(conds, [fH, fG, fF, fE, fD, fC, fB], default=fA)


def _arclength_points(f, breaks, ds, y_lo, y_hi):
    """Points on z = f(y) spaced ~ds in arc length, including the section breaks."""
    fine = np.linspace(y_lo, y_hi, 20001)
    zf = f(fine)
    s = np.concatenate(([0.0], np.cumsum(np.hypot(np.diff(fine), np.diff(zf)))))
    n = max(int(np.ceil(s[-1] / ds)), 4)
    y = np.interp(np.linspace(0.0, s[-1], n + 1), s, fine)
    extra = [v for v in breaks if y_lo < v < y_hi]
    y = np.unique(np.concatenate((y, extra)))
    keep = np.concatenate(([True], np.diff(y) > 1e-3 * ds))  # drop near-duplicates
    return y[keep]


def s1002(nominal_radius: float = 0.46, flange_thickness: float = 0.0325,
          flange_height: float = 0.028, *, y_min: float = -0.0699, y_max: float = 0.060,
          step: float = 0.2e-3) -> Profile:
    """S1002 wheel profile (EN 13715) in the wheel profile frame.

    Parameters
    ----------
    nominal_radius : float
        Nominal rolling radius [m] on the tape circle; stored as metadata
        (``meta["nominal_radius"]``), it does not change z(y).
    flange_thickness, flange_height : float
        Flange thickness and height [m]. Only the nominal S1002 values
        32.5 mm / 28 mm are defined by the section equations implemented
        here; other values raise :class:`ProfileError`.
    y_min, y_max : float
        Lateral extent [m] (section equations valid on [-70, 60] mm; the
        flange back at -70 mm is vertical, so the default stops 0.1 mm
        before it to keep z(y) single-valued with finite slope).
    step : float
        Approximate point spacing along the arc length [m].

    Returns
    -------
    Profile
        ``kind="wheel"``, ``name="S1002"``; y positive towards the field
        side, flange at negative y, z up, z = 0 on the tape circle, flange
        tip z = -28 mm at y = -55 mm.

    References
    ----------
    EN 13715 (S1002 section equations A–H); UIC 510-2 annex C.
    """
    if not (np.isfinite(nominal_radius) and nominal_radius > 0):
        raise ProfileError(f"S1002: nominal_radius must be > 0 [m], got {nominal_radius!r}")
    if abs(flange_thickness - 0.0325) > 1e-9 or abs(flange_height - 0.028) > 1e-9:
        raise ProfileError(
            f"S1002: only the nominal flange thickness 0.0325 m and height 0.028 m are "
            f"implemented, got flange_thickness={flange_thickness!r}, "
            f"flange_height={flange_height!r}")
    lo, hi = y_min / _MM, y_max / _MM
    if not (-70.0 <= lo < hi <= 60.0):
        raise ProfileError(f"S1002: need -0.070 <= y_min < y_max <= 0.060 m, got "
                           f"y_min={y_min!r}, y_max={y_max!r}")
    y = _arclength_points(_s1002_F, _S1002_BOUNDS, step / _MM, lo, hi)
    z = -_s1002_F(y)
    meta = {"nominal_radius": float(nominal_radius), "flange_thickness": 0.0325,
            "flange_height": 0.028, "tape_circle_from_flange_back": 0.070,
            "standard": "EN 13715 S1002"}
    return Profile(y * _MM, z * _MM, kind="wheel", name="S1002", meta=meta)


# --------------------------------------------------------------------------- rails
def _rail_head(radii, y1, half_width, side_slope, depth, ds):
    """Right half (y >= 0) of a rail head of three tangent arcs + inclined side [mm], z up."""
    R1, R2, R3 = radii
    a1 = np.arcsin(y1 / R1)
    a3 = np.pi / 2 - np.arctan(side_slope)
    c1 = np.array([0.0, -R1])
    c2 = c1 + (R1 - R2) * np.array([np.sin(a1), np.cos(a1)])
    sin_a2 = (half_width - R3 * np.sin(a3) - c2[0]) / (R2 - R3)
    if not (np.sin(a1) < sin_a2 < np.sin(a3)):
        raise ProfileError("rail head: inconsistent arc parameters (no tangent R80 arc)")
    a2 = np.arcsin(sin_a2)
    c3 = c2 + (R2 - R3) * np.array([np.sin(a2), np.cos(a2)])
    pts = []
    for c, R, lo, hi in ((c1, R1, 0.0, a1), (c2, R2, a1, a2), (c3, R3, a2, a3)):
        n = max(int(np.ceil(R * (hi - lo) / ds)), 2)
        t = np.linspace(lo, hi, n + 1)[:-1]  # the end point starts the next piece
        pts.append(np.c_[c[0] + R * np.sin(t), c[1] + R * np.cos(t)])
    p3 = c3 + R3 * np.array([np.sin(a3), np.cos(a3)])
    # side: from p3 downwards to z = -depth, widening by side_slope per unit depth
    L = (p3[1] + depth) / np.cos(np.arctan(side_slope))
    n = max(int(np.ceil(L / ds)), 2)
    t = np.linspace(0.0, 1.0, n + 1)
    pts.append(np.c_[p3[0] + t * (p3[1] + depth) * side_slope, p3[1] - t * (p3[1] + depth)])
    half = np.concatenate(pts)
    geom = {"R300_half_width": y1, "R80_centre": tuple(c2), "R13_centre": tuple(c3),
            "side_tangent_point": tuple(p3)}
    return half, geom


#: EN 13674-1 section data [mm] (British Steel catalogue, see the module docstring)
_SECTION = {"60E1": {"rail_height": 172.0, "foot_width": 150.0, "web_thickness": 16.5},
            "54E1": {"rail_height": 159.0, "foot_width": 140.0, "web_thickness": 16.0}}


def _rail(name, half_width_mm, y1_mm=10.5, *, depth=0.030, step=0.2e-3, aliases=()):
    radii = (300.0, 80.0, 13.0)
    if not (np.isfinite(depth) and 0.016 < depth < 0.045):
        raise ProfileError(f"{name}: depth must lie in (0.016, 0.045) m, got {depth!r}")
    half, geom = _rail_head(radii, y1_mm, half_width_mm, 1.0 / 20.0, depth / _MM, step / _MM)
    y = np.concatenate((-half[::-1, 0], half[1:, 0]))
    z = np.concatenate((half[::-1, 1], half[1:, 1]))
    meta = {"standard": f"EN 13674-1 {name}", "radii": tuple(r * _MM for r in radii),
            "head_width": 2 * half_width_mm * _MM, "side_inclination": 1.0 / 20.0,
            "R300_half_width": y1_mm * _MM,
            "R80_centre": tuple(v * _MM for v in geom["R80_centre"]),
            "R13_centre": tuple(v * _MM for v in geom["R13_centre"]), "aliases": aliases}
    meta.update({k: v * _MM for k, v in _SECTION.get(name, {}).items()})
    return Profile(y * _MM, z * _MM, kind="rail", name=name, meta=meta)


def rail_60e1(*, depth: float = 0.030, step: float = 0.2e-3) -> Profile:
    """60E1 (UIC60) rail head, uncanted, in the rail profile frame.

    Parameters
    ----------
    depth : float
        Depth [m] below the top of rail down to which the 1:20 head sides are
        included (default 30 mm, deeper than the 28 mm S1002 flange).
    step : float
        Approximate point spacing along the arc length [m].

    Returns
    -------
    Profile
        ``kind="rail"``, ``name="60E1"``, symmetric, top of rail at (0, 0),
        head width 72 mm; metadata lists the radii and arc centres and the
        section data (``rail_height`` 0.172 m, ``foot_width``, ``web_thickness``).

    References
    ----------
    EN 13674-1, 60E1 (R300/R80/R13, 1:20, width 72 mm); see the module docstring.
    """
    return _rail("60E1", 36.0, depth=depth, step=step, aliases=("UIC60",))


def rail_54e1(*, depth: float = 0.030, step: float = 0.2e-3) -> Profile:
    """54E1 (UIC54) rail head, uncanted (R300/R80/R13, 1:20, head width 70 mm).

    Same construction and parameters as :func:`rail_60e1`. Head width 70 mm
    and rail height 159 mm (``meta["rail_height"]``) are confirmed by the
    EN 13674-1 section table; the radii 300 / 80 / 13 mm, the 1:20 side and
    the R300 half-width of 10.5 mm are taken over from 60E1 and are not
    confirmed by a public 54E1 drawing (see the module docstring).
    """
    return _rail("54E1", 35.0, depth=depth, step=step, aliases=("UIC54",))


_GENERATORS = {"s1002": s1002, "60e1": rail_60e1, "54e1": rail_54e1}
#: alias (lower case) -> canonical name
ALIASES = {"s1002": "s1002", "60e1": "60e1", "uic60": "60e1", "uic 60": "60e1",
           "54e1": "54e1", "uic54": "54e1", "uic 54": "54e1"}


def available() -> list[str]:
    """Canonical names and aliases accepted by :func:`load`."""
    return ["S1002", "60E1", "54E1", "UIC60", "UIC54"]


def load(name: str, **options) -> Profile:
    """Standard profile by name (case-insensitive; "UIC60"/"UIC54" are aliases).

    ``options`` are passed to the generator (:func:`s1002`, :func:`rail_60e1`,
    :func:`rail_54e1`).

    Raises
    ------
    ProfileError
        Unknown name (the message lists :func:`available`).
    """
    key = str(name).strip().lower().replace("_", "").replace("-", "")
    if key not in ALIASES:
        raise ProfileError(f"unknown standard profile {name!r}; available: {available()}")
    return _GENERATORS[ALIASES[key]](**options)
