"""Flange dimensions of a wheel profile: flange height Sh, thickness Sd and the qR dimension.

Definitions (EN 15313 / UIC 510-2, with the profile-measuring defaults
L1 = 2 mm, L2 = 70 mm, L3 = 10 mm of MiniProf's "wheel wear" calculation):

* the **tread datum** (running or tape circle) lies L2 = 70 mm from the inner
  face of the wheel (the back of the flange); in the wheel profile frame of
  :mod:`wheelrail.profiles.core` it is y = 0, the back of the flange at
  y = −L2;
* **Sh**, flange height: radial distance from the tread at the tread datum to
  the flange tip, z(0) − min z;
* **Sd**, flange thickness: lateral distance from the back of the flange to
  the flange face at L3 = 10 mm above the tread datum (radially outward,
  towards the flange tip), i.e. where z = z(0) − L3;
* **qR**: lateral distance between that point and the point of the flange
  face L1 = 2 mm from the flange tip (z = min z + L1).

On the new S1002 these give Sh = 28 mm, Sd = 32.5 mm and qR = 10.8 mm, the
nominal values of the profile (EN 13715).

References
----------
.. [1] EN 15313:2016, Railway applications — In-service wheelset operation
   requirements — In-service and off-vehicle wheelset maintenance (Sh, Sd, qR).
.. [2] UIC 510-2 (2004), Trailing stock: wheels and wheelsets (wheel profile
   dimensions).
.. [3] Greenwood Engineering, MiniProf calculations, "Wheel wear: flange
   thickness (Sd), flange height (Sh) and flange gradient (qR); default
   parameters L1 = 2 mm, L2 = 70 mm, L3 = 10 mm",
   https://greenwood.dk/miniprofstandardcalc.php.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from ..errors import InputError, ProfileError
from .core import Profile

__all__ = ["FlangeDimensions", "flange_dimensions"]


@dataclass(frozen=True)
class FlangeDimensions:
    """Sh, Sd, qR of a wheel profile [m] (frozen); ``y_sd``, ``y_qr`` the measuring points."""

    Sh: float
    Sd: float
    qR: float
    y_tip: float
    y_sd: float
    y_qr: float

    def __iter__(self):
        return iter((self.Sh, self.Sd, self.qR))

    def to_dict(self) -> dict:
        return {"Sh": self.Sh, "Sd": self.Sd, "qR": self.qR}


def _crossing(profile, level, lo, hi):
    """First y in (lo, hi] (from lo upward) where z(y) rises through ``level``."""
    ys = np.linspace(lo, hi, 2001)
    d = profile(ys) - level
    ok = np.isfinite(d)
    idx = np.nonzero(ok[:-1] & ok[1:] & (d[:-1] <= 0) & (d[1:] > 0))[0]
    if idx.size == 0:
        return None
    i = idx[0]
    if d[i] == 0:
        return float(ys[i])
    return float(brentq(lambda y: float(profile(y)) - level, ys[i], ys[i + 1], xtol=1e-12))


def flange_dimensions(profile: Profile, *, datum_offset: float | None = None,
                      sd_height: float = 0.010, qr_height: float = 0.002) -> FlangeDimensions:
    """Flange height Sh, flange thickness Sd and qR of a wheel profile (EN 15313).

    Parameters
    ----------
    profile : Profile
        A wheel profile in the wheel profile frame (flange at negative y, z up,
        tread datum at y = 0).
    datum_offset : float, optional
        Distance from the back of the flange (inner face) to the tread datum
        L2 [m]; default ``profile.meta["tape_circle_from_flange_back"]``, else 0.070.
    sd_height, qr_height : float
        L3 = 10 mm and L1 = 2 mm [m] (module docstring).

    Returns
    -------
    FlangeDimensions
        ``Sh``, ``Sd``, ``qR`` [m] (unpacks as ``Sh, Sd, qR = ...``).

    Raises
    ------
    ProfileError
        Not a wheel profile, no tread datum or flange on it, or a flange
        lower than ``sd_height``.
    """
    if not isinstance(profile, Profile):
        raise InputError(f"profile must be a wheelrail.Profile, got {type(profile).__name__}")
    if profile.kind != "wheel":
        raise ProfileError(f"flange dimensions need a wheel profile, got a {profile.kind} profile")
    L2 = float(profile.meta.get("tape_circle_from_flange_back", 0.070)) \
        if datum_offset is None else float(datum_offset)
    if not profile.contains(0.0):
        raise ProfileError("the wheel profile does not reach its tread datum y = 0")
    z0 = float(profile(0.0))
    y = np.linspace(profile.y_min, 0.0, 4001)
    z = profile(y)
    i_tip = int(np.nanargmin(z))
    y_tip = float(y[i_tip])
    lo = max(profile.y_min, y_tip - (y[1] - y[0]))
    hi = min(profile.y_max, y_tip + 2 * (y[1] - y[0]))
    res = minimize_scalar(lambda t: float(profile(t)), bounds=(lo, hi), method="bounded",
                          options={"xatol": 1e-10})
    if res.success and res.fun <= z[i_tip]:
        y_tip, z_tip = float(res.x), float(res.fun)
    else:
        z_tip = float(z[i_tip])
    Sh = z0 - z_tip
    if Sh <= sd_height:
        raise ProfileError(f"flange height {Sh * 1e3:.3f} mm is not above the Sd measuring "
                           f"height {sd_height * 1e3:g} mm: no flange on this profile")
    y_sd = _crossing(profile, z0 - sd_height, y_tip, 0.0)
    y_qr = _crossing(profile, z_tip + qr_height, y_tip, 0.0)
    if y_sd is None or y_qr is None:
        raise ProfileError("the flange face does not cross the Sd/qR measuring heights")
    return FlangeDimensions(Sh=Sh, Sd=y_sd + L2, qR=y_sd - y_qr, y_tip=y_tip, y_sd=y_sd,
                            y_qr=y_qr)
