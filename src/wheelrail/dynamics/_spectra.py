"""Standard power spectral densities of track irregularities (ERRI B176, FRA classes 1–6).

Every spectrum here is a one-sided spatial PSD S(Ω) [m²/(rad/m)] over the
angular wavenumber Ω = 2π/λ [rad/m] (λ the wavelength), normalised so that the
variance of the irregularity is ∫₀^∞ S(Ω) dΩ; per channel:

* ``alignment`` — lateral position of the track centre line [m];
* ``level`` — vertical position of the track centre line [m];
* ``cross_level`` — height of the right rail over the left one [m];
* ``gauge`` — gauge deviation from nominal [m].

**ERRI B176** (ORE B176, the "low" and "high" level spectra used for European
high-speed lines; also known as the German spectra of low and high
disturbance), with Ωc = 0.8246, Ωr = 0.0206, Ωs = 0.4380 rad/m::

    alignment    S_a(Ω) = A_a Ωc² / ((Ω² + Ωr²)(Ω² + Ωc²))
    level        S_v(Ω) = A_v Ωc² / ((Ω² + Ωr²)(Ω² + Ωc²))
    cross level  S_c(Ω) = (A_v / b²) Ωc² Ω² / ((Ω² + Ωr²)(Ω² + Ωc²)(Ω² + Ωs²))
                 [rad²/(rad/m), the angle between the rails]
    gauge        S_g(Ω) = A_g Ωc² Ω² / ((Ω² + Ωr²)(Ω² + Ωc²)(Ω² + Ωs²))

with A_a = 2.119e-7 (low) / 6.125e-7 (high), A_v = 4.032e-7 / 1.080e-6,
A_g = 5.32e-8 / 1.032e-7 m·rad. The cross level S_c is that of the angle
between the rails over the half distance b of their contact points; as a
height difference 2b·angle it is 4 A_v Ωc² Ω² / (...), independent of b
(this module returns heights). The high-level A_a and A_v reproduce, to
0.01 %, the tabulated ORE B176 high-level PSDs of the GENSYS program
TRC_IPSD (given in m²/(1/m) = 2π S(Ω), at λ = 314, 50, 10, 5 and 0.01 m); the
low-level values and A_g are confirmed only in secondary sources (published
re-implementations of the "German" spectra).

**FRA classes 1–6** (US Federal Railroad Administration track classes, in
the form of Garg & Dukkipati 1984), with k = 0.25 and Ωc = 0.8245 rad/m::

    alignment    S_a(Ω) = k A_a Ωc² / (Ω² (Ω² + Ωc²))
    level        S_v(Ω) = k A_v Ωc² / (Ω² (Ω² + Ωc²))
    cross level  S_c(Ω) = 4 k A_v Ωc² / ((Ω² + Ωc²)(Ω² + Ωs²))
    gauge        S_g(Ω) = 4 k A_v Ωc² / ((Ω² + Ωc²)(Ω² + Ωs²))

(A in cm²·rad/m, S in cm²/(rad/m) in the source; converted to SI here):

=====  ======  ======  =======
class  A_v     A_a     Ωs
=====  ======  ======  =======
1      1.2107  3.3634  0.6046
2      1.0181  1.2107  0.9308
3      0.6816  0.4128  0.8520
4      0.5376  0.3027  1.1312
5      0.2095  0.0762  0.8209
6      0.0339  0.0339  0.4380
=====  ======  ======  =======

A_v, Ωc and k agree with a published re-implementation; A_a, Ωs and the
cross-level/gauge form are the values as reproduced from Garg & Dukkipati,
not confirmed in a source readable while this module was written. The FRA
gauge spectrum is taken of the cross-level form (as in that reproduction).

Wavelength bands (where :meth:`TrackSpectrum.generate` puts the harmonics):
ERRI 3–70 m by default (the D1 and D2 wavelength ranges of EN 13848-1 over
which the ERRI spectra are normally applied); FRA 1.524–304.8 m (5–1000 ft).

References
----------
.. [1] ORE B176, Bogies with steered or steering wheelsets, Report 1,
   Utrecht 1989; ERRI B176/DT 290, 1993 (the spectra).
.. [2] V.K. Garg, R.V. Dukkipati, *Dynamics of railway vehicle systems*,
   Academic Press 1984, ch. 11 (FRA spectra, classes 1–6).
.. [3] GENSYS reference manual, program TRC_IPSD (ORE B176 high level).
.. [4] EN 13848-1:2019, Track geometry quality — characterisation (D1, D2).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError

__all__ = ["TrackSpectrum", "track_spectrum", "CHANNELS", "SPECTRUM_NAMES"]

#: The four irregularity channels, in this order everywhere.
CHANNELS = ("alignment", "level", "cross_level", "gauge")

_ERRI = {"low": (2.119e-7, 4.032e-7, 5.32e-8), "high": (6.125e-7, 1.080e-6, 1.032e-7)}
_FRA = {1: (1.2107, 3.3634, 0.6046), 2: (1.0181, 1.2107, 0.9308), 3: (0.6816, 0.4128, 0.8520),
        4: (0.5376, 0.3027, 1.1312), 5: (0.2095, 0.0762, 0.8209), 6: (0.0339, 0.0339, 0.4380)}
_CM2 = 1e-4                     # cm² → m²

SPECTRUM_NAMES = ("erri-low", "erri-high") + tuple(f"fra-{c}" for c in range(1, 7))


@dataclass(frozen=True)
class TrackSpectrum:
    """A standard track-irregularity spectrum (frozen, SI).

    Parameters
    ----------
    family : {"erri", "fra"}
        ERRI B176 or FRA form (module docstring).
    A_a, A_v, A_g : float
        Alignment, level and gauge constants [m²·rad/m] (A_g unused by FRA).
    omega_c, omega_r, omega_s : float
        Break wavenumbers Ωc, Ωr (ERRI only), Ωs [rad/m].
    k : float
        FRA safety factor (0.25).
    band : tuple of float
        Wavelength band (λ_min, λ_max) [m] of generated irregularities.
    name : str
    """

    family: str
    A_a: float
    A_v: float
    A_g: float = 0.0
    omega_c: float = 0.8246
    omega_r: float = 0.0206
    omega_s: float = 0.4380
    k: float = 0.25
    band: tuple = (3.0, 70.0)
    name: str = ""

    def __post_init__(self):
        if self.family not in ("erri", "fra"):
            raise InputError(f"TrackSpectrum: family must be 'erri' or 'fra', got "
                             f"{self.family!r}")
        for nm in ("A_a", "A_v", "A_g", "omega_c", "omega_r", "omega_s", "k"):
            v = getattr(self, nm)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v >= 0):
                raise InputError(f"TrackSpectrum: {nm} must be a finite number >= 0, got {v!r}")
        try:
            lo, hi = (float(v) for v in self.band)
        except (TypeError, ValueError):
            raise InputError(f"TrackSpectrum: band must be (shortest, longest) wavelength in m, "
                             f"got {self.band!r}") from None
        if not (0 < lo < hi and math.isfinite(hi)):
            raise InputError(f"TrackSpectrum: band must satisfy 0 < shortest < longest < inf "
                             f"[m], got {self.band!r}")
        object.__setattr__(self, "band", (lo, hi))

    @property
    def omega_band(self) -> tuple:
        """(Ω_min, Ω_max) [rad/m] of :attr:`band`."""
        return 2 * math.pi / self.band[1], 2 * math.pi / self.band[0]

    def with_band(self, shortest: float, longest: float) -> TrackSpectrum:
        """The same spectrum over another wavelength band [m]."""
        from dataclasses import replace
        return replace(self, band=(shortest, longest))

    def psd(self, channel: str, omega) -> np.ndarray:
        """One-sided PSD S(Ω) [m²/(rad/m)] of ``channel`` at wavenumbers ``omega`` [rad/m]."""
        if channel not in CHANNELS:
            raise InputError(f"channel must be one of {', '.join(CHANNELS)}, got {channel!r}")
        w2 = np.asarray(omega, dtype=float) ** 2
        c2, r2, s2 = self.omega_c ** 2, self.omega_r ** 2, self.omega_s ** 2
        with np.errstate(divide="ignore", invalid="ignore"):
            if self.family == "erri":
                base = c2 / ((w2 + r2) * (w2 + c2))
                if channel == "alignment":
                    return self.A_a * base
                if channel == "level":
                    return self.A_v * base
                shaped = base * w2 / (w2 + s2)
                return (4.0 * self.A_v if channel == "cross_level" else self.A_g) * shaped
            if channel == "alignment":
                return self.k * self.A_a * c2 / (w2 * (w2 + c2))
            if channel == "level":
                return self.k * self.A_v * c2 / (w2 * (w2 + c2))
            return 4.0 * self.k * self.A_v * c2 / ((w2 + c2) * (w2 + s2))

    def variance(self, channel: str, n: int = 20001) -> float:
        """Variance [m²] of ``channel`` over :attr:`band` (∫ S dΩ, log-spaced trapezoid)."""
        lo, hi = self.omega_band
        w = np.geomspace(lo, hi, n)
        return float(np.trapezoid(self.psd(channel, w), w))


def track_spectrum(spec, band=None) -> TrackSpectrum:
    """A :class:`TrackSpectrum` from a name or a configured object.

    Parameters
    ----------
    spec : str or TrackSpectrum
        ``"erri-low"``, ``"erri-high"`` (ERRI B176 low and high level) or
        ``"fra-1"`` … ``"fra-6"`` (FRA classes; ``"fra-6"`` the best track).
    band : (float, float) or None
        Wavelength band [m] (default: the spectrum's, see the module docstring).
    """
    if isinstance(spec, TrackSpectrum):
        out = spec
    elif isinstance(spec, str):
        key = spec.strip().lower().replace("_", "-").replace(" ", "-")
        if key.startswith("erri-") and key[5:] in _ERRI:
            a, v, g = _ERRI[key[5:]]
            out = TrackSpectrum("erri", a, v, g, name=key)
        elif key.startswith("fra-") and key[4:].isdigit() and int(key[4:]) in _FRA:
            av, aa, ws = _FRA[int(key[4:])]
            out = TrackSpectrum("fra", aa * _CM2, av * _CM2, 0.0, omega_c=0.8245,
                                omega_r=0.0, omega_s=ws, band=(1.524, 304.8), name=key)
        else:
            raise InputError(f"unknown track spectrum {spec!r}; known: "
                             f"{', '.join(SPECTRUM_NAMES)} (or a TrackSpectrum)")
    else:
        raise InputError(f"spectrum must be a name ({', '.join(SPECTRUM_NAMES)}) or a "
                         f"TrackSpectrum, got {type(spec).__name__}")
    if band is not None:
        out = out.with_band(*band)
    return out
