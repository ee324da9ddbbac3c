"""Rolling-contact-fatigue indices per patch and per wheel.

* **Burstow's damage function** (RSSB whole-life rail model, WLRM): the RCF
  damage per axle passage as a function of the wear number Tγ [N] of a
  wheel: zero below a threshold (no crack initiation), rising linearly to a
  peak, then falling linearly to zero where wear removes the initiated
  cracks faster than they grow. Defaults: threshold 15 N, peak at 65 N,
  zero at 175 N, slope 1e-6 per N (damage 50e-6 per axle at the peak, a
  crack initiated at an accumulated damage of 1). Source status: read only
  in secondary descriptions of the RSSB reports; the threshold is given
  there as 15–20 N and the slope differs between them — every constant is an
  option of :class:`Burstow`.
* **Ekberg's surface fatigue index** FI_surf = μ_t − 2π a b k / (3 Fn) =
  μ_t − k / p0, with μ_t = F_t / Fn the traction coefficient of the patch,
  a, b its semi-axes, k the shear yield stress of the material, p0 =
  3 Fn / (2π a b) the Hertzian peak pressure; surface-initiated fatigue is
  predicted where FI_surf > 0 (beyond the shakedown limit of the surface).
* **Shakedown map** position (μ_t, p0/k) (Johnson's map; the surface limit
  is the hyperbola p0/k = 1/μ_t).

The yield stress in shear k = 300 MPa of the default is a typical value for
wheel steel and is unconfirmed in a readable source: set it for the steel.

References
----------
.. [1] A. Ekberg, E. Kabo, H. Andersson, An engineering model for prediction
   of rolling contact fatigue of railway wheels, Fatigue & Fracture of
   Engineering Materials & Structures 25 (2002) 899–909 (FI_surf).
.. [2] M. Burstow, Whole life rail model application and development for
   RSSB — continued development of an RCF damage parameter, AEATR-ES-2004-880,
   Rail Safety and Standards Board (2004) (damage function of Tγ; secondary).
.. [3] K.L. Johnson, The strength of surfaces in rolling contact, Proc. IMechE
   Part C 203 (1989) 151–163 (shakedown map).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import xarray as xr

from ..errors import InputError
from ..options import Method, configured, option

__all__ = ["Burstow", "RCFResult", "rcf", "surface_fatigue_index"]


@configured
class Burstow(Method):
    """Burstow's RCF damage function of Tγ (whole-life rail model), per axle passage.

    Other Parameters
    ----------------
    threshold : float, default 15.0
        Tγ below which there is no damage [N].
    peak : float, default 65.0
        Tγ of the largest damage [N].
    zero : float, default 175.0
        Tγ where wear removes the damage again [N].
    slope : float, default 1e-6
        Damage per N of Tγ above the threshold [1/N].
    negative : bool, default False
        Continue the falling line below zero beyond ``zero`` (wear removing
        damage accumulated elsewhere) instead of clipping at zero.
    """

    name = "burstow"
    references = ("M. Burstow, Whole life rail model application and development for RSSB - "
                  "continued development of an RCF damage parameter, AEATR-ES-2004-880, "
                  "RSSB (2004).",)

    threshold: float = option(15.0, lo=0.0, unit="N", doc="Tγ below which there is no damage")
    peak: float = option(65.0, lo=0.0, unit="N", doc="Tγ of the largest damage")
    zero: float = option(175.0, lo=0.0, unit="N", doc="Tγ where the damage is zero again")
    slope: float = option(1e-6, lo=0.0, unit="1/N", doc="damage per N above the threshold")
    negative: bool = option(False, doc="continue below zero beyond `zero`")

    def _check(self):
        if not (self.threshold < self.peak < self.zero):
            raise InputError(f"need threshold < peak < zero, got {self.threshold}, "
                             f"{self.peak}, {self.zero}")

    def __call__(self, Tgamma):
        """Damage per axle passage at wear number(s) ``Tgamma`` [N] (negative Tγ as abs(Tγ))."""
        t = np.abs(np.asarray(Tgamma, dtype=float))
        top = self.slope * (self.peak - self.threshold)
        rise = self.slope * (t - self.threshold)
        fall = top * (self.zero - t) / (self.zero - self.peak)
        d = np.where(t < self.threshold, 0.0, np.where(t <= self.peak, rise, fall))
        if not self.negative:
            d = np.clip(d, 0.0, None)
        return d if d.ndim else float(d)


def surface_fatigue_index(Ft, Fn, a, b, yield_shear=300e6):
    """Ekberg's FI_surf = μ_t − 2π a b k / (3 Fn) (arrays broadcast; NaN where Fn ≤ 0).

    Parameters
    ----------
    Ft : array_like
        Tangential force magnitude √(Fx² + Fy²) [N].
    Fn : array_like
        Normal force [N].
    a, b : array_like
        Semi-axes of the (equivalent) contact ellipse [m].
    yield_shear : float
        Yield stress in shear k [Pa].
    """
    Ft, Fn, a, b = (np.asarray(v, dtype=float) for v in (Ft, Fn, a, b))
    with np.errstate(invalid="ignore", divide="ignore"):
        fi = np.where(Fn > 0, np.abs(Ft) / Fn - 2.0 * math.pi * a * b * yield_shear
                      / (3.0 * Fn), np.nan)
    return fi if fi.ndim else float(fi)


@dataclass(frozen=True)
class RCFResult:
    """RCF indices (frozen); arrays of one shape, or an :class:`xarray.Dataset` (``dataset``).

    Attributes
    ----------
    mu_t : traction coefficient F_t / Fn [-]
    p0_over_k : Hertzian peak pressure over the shear yield stress [-]
    FI_surf : Ekberg's surface fatigue index [-] (> 0: surface fatigue predicted)
    Tgamma : wear number [N] (per patch, or per wheel for ``damage``)
    damage : Burstow's damage per axle passage [-]
    """

    mu_t: object
    p0_over_k: object
    FI_surf: object
    Tgamma: object
    damage: object
    yield_shear: float

    @property
    def beyond_shakedown(self):
        """True where the point (μ_t, p0/k) lies beyond the surface shakedown limit."""
        return np.asarray(self.FI_surf) > 0

    def to_dataset(self, dims=("patch",)) -> xr.Dataset:
        """The indices as an :class:`xarray.Dataset` with dimensions ``dims``."""
        data = {}
        for name, unit in (("mu_t", "1"), ("p0_over_k", "1"), ("FI_surf", "1"),
                           ("Tgamma", "N"), ("damage", "1")):
            v = np.asarray(getattr(self, name), dtype=float)
            data[name] = (dims[:v.ndim] if v.ndim else (), v, {"units": unit})
        return xr.Dataset(data, attrs={"yield_shear": self.yield_shear})


def rcf(source=None, *, Fn=None, Ft=None, a=None, b=None, Tgamma=None, yield_shear=300e6,
        damage=None) -> RCFResult:
    """RCF indices of patches: Ekberg's FI_surf, the shakedown-map position and Burstow's damage.

    Parameters
    ----------
    source : PatchResult, xarray.Dataset or None
        A patch of :func:`wheelrail.solve` (forces, ellipse and Tγ =
        −(Fx ξ + Fs η + Mz φ) from it), or the ``dataset`` of a
        :func:`wheelrail.dynamics.simulate` result (per patch ``Fn``, ``Fx``,
        ``Fy``, ``a``, ``b``; Tγ per wheel ``wear_number``, dims time ×
        wheelset × side). Or ``None`` and the quantities below.
    Fn, Ft, a, b : array_like
        Normal force [N], tangential force magnitude [N], semi-axes [m].
    Tgamma : array_like, optional
        Wear number per wheel [N] for Burstow's damage (per patch for a
        single patch).
    yield_shear : float
        Shear yield stress k [Pa] (default 300 MPa, typical wheel steel, unconfirmed).
    damage : Burstow, optional
        The damage function (default :class:`Burstow` with its defaults).

    Returns
    -------
    RCFResult
        For a dynamics dataset the per-patch fields have the dataset's patch
        dims and ``damage`` the per-wheel dims; :meth:`RCFResult.to_dataset`.
    """
    dmg = Burstow() if damage is None else damage
    if not isinstance(dmg, Burstow):
        raise InputError(f"damage must be a wheelrail.wear.Burstow, got {type(dmg).__name__}")
    if not (isinstance(yield_shear, (int, float)) and yield_shear > 0):
        raise InputError(f"yield_shear must be > 0 Pa, got {yield_shear!r}")
    if isinstance(source, xr.Dataset):
        need = ("Fn", "Fx", "Fy", "a", "b", "wear_number")
        missing = [n for n in need if n not in source]
        if missing:
            raise InputError(f"the dataset lacks {', '.join(missing)} (a dynamics result's "
                             "dataset is expected)")
        Fn = source["Fn"].values
        Ft = np.hypot(source["Fx"].values, source["Fy"].values)
        a, b = source["a"].values, source["b"].values
        Tgamma = source["wear_number"].values
    elif source is not None:
        if not (hasattr(source, "patch") and hasattr(source, "forces")):
            raise InputError(f"rcf takes a patch of wheelrail.solve or a dynamics dataset, "
                             f"got {type(source).__name__}")
        Fn, Ft = source.Fn, math.hypot(source.Fx, source.Fs)
        a, b = source.patch.a, source.patch.b
        Tgamma = -(source.Fx * source.xi + source.Fs * source.eta + source.Mz * source.phi)
    if Fn is None or Ft is None or a is None or b is None:
        raise InputError("rcf needs a source or Fn, Ft, a and b")
    Fn, Ft, a, b = (np.asarray(v, dtype=float) for v in (Fn, Ft, a, b))
    with np.errstate(invalid="ignore", divide="ignore"):
        mu_t = np.where(Fn > 0, np.abs(Ft) / np.where(Fn > 0, Fn, 1.0), np.nan)
        p0 = np.where(Fn > 0, 3.0 * Fn / (2.0 * math.pi * a * b), np.nan)
    fi = surface_fatigue_index(Ft, Fn, a, b, yield_shear)
    tg = np.nan if Tgamma is None else np.asarray(Tgamma, dtype=float)
    dm = np.nan if Tgamma is None else dmg(tg)
    return RCFResult(mu_t=mu_t, p0_over_k=p0 / yield_shear, FI_surf=fi, Tgamma=tg, damage=dm,
                     yield_shear=float(yield_shear))
