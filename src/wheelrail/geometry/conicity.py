"""Equivalent conicity of a wheelset on a track (EN 15302).

Principle (EN 15302:2008+A1:2010, §4): the equivalent conicity ``tan γ_e``
at amplitude ``ŷ`` is the conicity of the *conical* wheelset whose kinematic
(Klingel) oscillation has the same wavelength as that of the real wheelset
oscillating with lateral amplitude ``ŷ`` (half the peak-to-peak value).

Kinematic oscillation of a wheelset with rolling-radius difference Δr(y)
(Klingel 1883; Δr = r_right − r_left, e half the contact-point distance, r0
the nominal radius)::

    y''(x) = −Δr(y) / (2 e r0).

With ``U(y) = ∫_{y0}^{y} Δr dy'`` (y0 the equilibrium, Δr(y0) = 0) energy
conservation gives ``y'² = (U* − U(y)) / (e r0)``, so the wavelength is
``L = 2 √(e r0) I`` with ``I = ∫_{y_min}^{y_max} dy / √(U* − U(y))``, where
``y_min``, ``y_max`` are the turning points (``U(y_min) = U(y_max) = U*``,
``y_max − y_min = 2ŷ``). Klingel's formula for a cone, ``L = 2π √(e r0 / tan γ_e)``,
then gives

    tan γ_e = π² / I²                           (``method="integration"``)

independent of e and r0 (for a cone, Δr = 2λy, ``I = π/√λ`` and tan γ_e = λ).
This is the method of EN 15302 annex B (integration of the non-linear
differential equation), evaluated here by quadrature of the period instead of
time-stepping (substitution ``y = c + ŷ sin t`` removes the end singularities;
Gauss–Legendre in t).

``method="regression"`` follows annex C (linear regression of the Δr
function): Δr is sampled over one harmonic oscillation ``y = c + ŷ sin t``
equally spaced in phase and fitted by a straight line, ``tan γ_e`` being half
its slope, i.e. the harmonic linearisation
``tan γ_e = ∫ Δr(c + ŷ sin t) sin t dt / (2π ŷ)``. The centre ``c`` is
chosen so that the mean of Δr over the cycle vanishes (a periodic motion has
no mean lateral acceleration); for Δr odd about its zero ``c = y0``. It
coincides with the integration method for a cone and deviates for strongly
non-linear Δr (see below).

Amplitude: ``ŷ`` is the amplitude of the lateral wheelset displacement, i.e.
half the distance between the two turning points (the amplitude that
reproduces the annex E reference results below; 3 mm is the customary value).

What is verified, and against what
----------------------------------
* Principle, annex structure (annex B: Klingel formula / integration of the
  non-linear equation; annex C: linear regression of the Δr function): the
  published scope of EN 15302:2008+A1:2010 (abstract on the CEN national
  catalogues, e.g. ÖNORM EN 15302:2011-02 / SR EN 15302:2008) and UIC 519
  (2004), from which it derives.
* Formula of annex B: the open EN 15302 benchmark program of E. Tamburini
  (github.com/criogenox/B_ECC-Equivalent-Conicity-Calculation, ``Calc.java``)
  integrates ``ψ² = −2/(e r0) (S(y) − C)``, ``S = −∫Δr dy``, ``x = ∫dy/ψ`` and
  sets ``tan γ_e = 2 e r0 (π/λ)²``; this is the same wavelength integral as
  above (e and r0 cancel), evaluated here with Gauss quadrature instead of a
  Riemann sum.
* Numbers: the reference Δr functions of EN 15302 annex E as tabulated in that
  repository (``data/dr_ce_E*.dat``, 0.1 mm grid) with the annex E reference
  results (``data/ben_E*.dat``) were run through
  :func:`conicity_from_delta_r` (not copied into this project). Integration
  method vs. reference, ŷ = 1 / 2 / 3 / 4 / 5 mm:
  E1 (symmetric): 0.1248/0.1548/0.1879/0.2160/0.2543 vs
  0.125/0.155/0.188/0.216/0.254; E4 (Δr ≡ 0 for |y| < 1.65 mm, then a jump):
  0.000 (1, 1.5 mm), 0.0839 (1.8 mm), 0.2925/0.4887/0.4851/0.4747 vs
  0.000, 0.084, 0.293/0.489/0.485/0.475; E5 (wheel diameters 920/918 mm,
  Δr(0) = 1 mm): 0.2764/0.2725/0.2603/0.2701/0.3072 vs
  0.280/0.272/0.261/0.269/0.307 — all within 0.004 (annex F tolerance
  ±min(0.05, 0.5 tan γ_e)). The regression method agrees for E1 (≤ 0.002) and
  E5 (≤ 0.016) but not near the Δr jump of E4 (0.183 vs 0.084 at 1.8 mm), as
  expected of a harmonic linearisation.
* Not found in public material: a published tan γ_e for the nominal S1002 /
  60E1 1:40 / 1435 mm / 1360 mm combination. This library gives 0.368 / 0.229 /
  0.184 at ŷ = 1 / 2 / 3 mm for it (integration; regression 0.185 at 3 mm):
  the contact search finds two contact points per wheel in the centred
  position (an almost flat double minimum of the gap), so Δr jumps near
  y = 0 and the conicity falls with amplitude. The Manchester-benchmark files
  of the same pair (``MBench_S1002_v3.prw`` / ``MBench_UIC60_v3.prr``, shared
  test data) give 0.369 / 0.229 / 0.184, so this is a property of the profile
  pair, not of the generated profiles. EN 15302 case E1 (S1002 on the
  tabulated reference rail A, which is not nominal 60E1 1:40) has a smooth Δr
  and 0.188 at 3 mm.

References
----------
.. [1] EN 15302:2008+A1:2010, *Railway applications — Method for determining
   the equivalent conicity*, §4 and annexes B, C, E, F.
.. [2] UIC Code 519, *Method for determining the equivalent conicity*, 1st ed.,
   2004.
.. [3] J. Klingel, Über den Lauf der Eisenbahnwagen auf gerader Bahn,
   Organ für die Fortschritte des Eisenbahnwesens 38 (1883) 113–123.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import brentq

from .._validation import as_float_array, positive
from ..errors import InputError
from .contact_table import contact_table

__all__ = ["equivalent_conicity", "conicity_from_delta_r", "METHODS"]

METHODS = ("integration", "regression")
_NODES = 256


def _equilibrium(y, dr):
    """Zero crossing of Δr nearest to y = 0 (linear interpolation)."""
    sign = np.sign(dr)
    zero = np.flatnonzero(sign == 0)
    cross = np.flatnonzero(sign[:-1] * sign[1:] < 0)
    cand = list(y[zero])
    for i in cross:
        cand.append(y[i] - dr[i] * (y[i + 1] - y[i]) / (dr[i + 1] - dr[i]))
    if not cand:
        raise InputError("delta_r has no zero crossing in the given range: no equilibrium "
                         "position (widen the y range)")
    cand = np.asarray(cand)
    return float(cand[np.argmin(np.abs(cand))])


def conicity_from_delta_r(y, delta_r, amplitude, method: str = "integration") -> float:
    """Equivalent conicity from a rolling-radius-difference function (pure kernel).

    Parameters
    ----------
    y : array_like, shape (n,)
        Lateral shifts [m], strictly increasing.
    delta_r : array_like, shape (n,)
        Δr = r_right − r_left [m] at ``y`` (linearly interpolated between the
        points, so jumps are resolved to the sampling step).
    amplitude : float
        Amplitude ŷ of the lateral oscillation [m], > 0.
    method : {"integration", "regression"}
        See the module docstring (EN 15302 annexes B and C).
        Both turning points (integration) or the whole harmonic cycle
        (regression) must lie inside ``y``.

    Returns
    -------
    float
        tan γ_e [-].
    """
    y = as_float_array("y", y)
    dr = as_float_array("delta_r", delta_r)
    amp = float(positive("amplitude", amplitude))
    if y.ndim != 1 or y.shape != dr.shape or y.size < 3:
        raise InputError(f"y and delta_r must be 1-D of equal length >= 3, got {y.shape}, {dr.shape}")
    if np.any(np.diff(y) <= 0):
        raise InputError("y must be strictly increasing")
    if method not in METHODS:
        raise InputError(f"method must be one of {METHODS}, got {method!r}")
    y0 = _equilibrium(y, dr)
    t, w = np.polynomial.legendre.leggauss(_NODES)
    if method == "regression":
        s = np.sin(np.pi * (t + 1.0))  # Gauss nodes on (0, 2π), weights w·π
        lo, hi = y[0] + amp, y[-1] - amp
        if lo > hi:
            raise InputError(f"amplitude {amp!r} m exceeds half the range of y "
                             f"[{y[0]!r}, {y[-1]!r}] m")

        def mean_dr(c):  # mean of Δr over one harmonic cycle centred at c
            return float(0.5 * np.sum(w * np.interp(c + amp * s, y, dr)))

        c = min(max(y0, lo), hi)
        m0 = mean_dr(c)
        if m0 != 0.0:
            # centre of the cycle: zero mean Δr (no mean lateral acceleration over a
            # period); equals y0 for a Δr that is odd about y0
            a, b = (c, hi) if m0 < 0 else (lo, c)
            ma, mb = mean_dr(a), mean_dr(b)
            if not (ma <= 0.0 <= mb):
                raise InputError(f"no harmonic cycle of amplitude {amp!r} m with zero mean "
                                 f"delta_r inside the y range [{y[0]!r}, {y[-1]!r}] m "
                                 "(widen the range)")
            c = brentq(mean_dr, a, b, xtol=1e-15, rtol=1e-14) if ma < 0 < mb else \
                (a if ma == 0 else b)
        val = np.interp(c + amp * s, y, dr)
        return float(np.pi * np.sum(w * val * s) / (2.0 * np.pi * amp))
    # integration: U(y) = ∫ Δr dy, exact for piecewise-linear Δr
    U = np.concatenate(([0.0], np.cumsum(0.5 * (dr[1:] + dr[:-1]) * np.diff(y))))
    U = U - np.interp(y0, y, U)

    def Uf(v):
        v = np.asarray(v, dtype=float)
        i = np.clip(np.searchsorted(y, v) - 1, 0, y.size - 2)
        dx = v - y[i]
        slope = (dr[i + 1] - dr[i]) / (y[i + 1] - y[i])
        return U[i] + dr[i] * dx + 0.5 * slope * dx * dx

    g = lambda top: float(Uf(top) - Uf(top - 2 * amp))  # noqa: E731
    # the upper turning point lies in [y0, y0 + 2ŷ]; both turning points inside the data
    lo, hi = max(y0, y[0] + 2 * amp), min(y0 + 2 * amp, y[-1])
    span = (f"the oscillation of amplitude {amp!r} m around the equilibrium {y0!r} m "
            f"leaves the y range [{y[0]!r}, {y[-1]!r}] m (widen the range)")
    if lo > hi:
        raise InputError(span)
    ga, gb = g(lo), g(hi)
    if (ga > 0 and lo > y0) or (gb < 0 and hi < y0 + 2 * amp):
        raise InputError(span)
    if not (ga <= 0 <= gb):
        raise InputError("delta_r does not increase through its equilibrium: the kinematic "
                         "oscillation is unstable and has no conicity")
    top = brentq(g, lo, hi, xtol=1e-15, rtol=1e-14) if ga < 0 < gb else \
        (lo if ga == 0 else hi)
    centre = top - amp
    Ustar = float(Uf(top))
    tt = 0.5 * np.pi * t                      # (−π/2, π/2)
    yy = centre + amp * np.sin(tt)
    gap = Ustar - Uf(yy)
    if np.all(gap <= 0):
        # Δr ≡ 0 over the whole cycle (e.g. cylindrical contact zone): no restoring
        # term, infinite wavelength, tan γ_e = 0 (EN 15302 annex E case E4, ŷ < 1.8 mm)
        return 0.0
    if np.any(gap <= 0):
        raise InputError("delta_r is not monotone enough between the turning points to define "
                         "an oscillation (U has an interior maximum)")
    integrand = amp * np.cos(tt) / np.sqrt(gap)
    integral = 0.5 * np.pi * np.sum(w * integrand)
    return float(np.pi ** 2 / integral ** 2)


def equivalent_conicity(wheelset, track, amplitude=0.003, method: str = "integration", yaw=0.0,
                        *, dy: float = 1e-4, step: float = 2e-4):
    """Equivalent conicity tan γ_e of a wheelset on a track (EN 15302).

    Parameters
    ----------
    wheelset : Wheelset
    track : Track
    amplitude : float or array_like
        Lateral amplitude(s) ŷ [m] (default 3 mm), > 0.
    method : {"integration", "regression"}
        ``"integration"`` (default): wavelength of the non-linear kinematic
        oscillation (EN 15302 §4 / annex B); ``"regression"``: harmonic
        linear regression of Δr (annex C).
    yaw : float
        Yaw angle [rad] of the contact table (0 in EN 15302).
    dy : float
        Spacing of the contact table in y [m] (default 0.1 mm).
    step : float
        Search-grid spacing along the wheel [m], see :func:`contact_table`.

    Returns
    -------
    float or ndarray
        tan γ_e [-] (an array if ``amplitude`` is an array).

    Examples
    --------
    >>> import wheelrail as wr
    >>> ws = wr.Wheelset(wr.profiles.load("S1002"))
    >>> tr = wr.Track(wr.profiles.load("60E1"))
    >>> 0.05 < wr.equivalent_conicity(ws, tr, 0.003) < 0.4
    True
    """

    amp = positive("amplitude", amplitude)
    if method not in METHODS:
        raise InputError(f"method must be one of {METHODS}, got {method!r}")
    dy = float(positive("dy", dy))
    if np.max(amp) > 0.012:
        raise InputError(f"amplitude must be <= 0.012 m, got {np.max(amp)!r}")
    half = 2.0 * float(np.max(amp)) + 2e-3
    n = int(np.ceil(2 * half / dy)) + 1
    ys = np.linspace(-half, half, n)
    tab = contact_table(wheelset, track, ys, yaw, step=step, refine_jumps=0)
    dr = tab["delta_r"].values
    out = np.array([conicity_from_delta_r(ys, dr, a, method) for a in np.ravel(amp)])
    return float(out[0]) if np.ndim(amp) == 0 else out.reshape(np.shape(amp))
