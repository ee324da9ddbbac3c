"""Hertz's elliptic contact in closed form, written for the tests independently of wheelrail.

Johnson (1985), *Contact Mechanics*, §3.7 eqs. (3.64)-(3.66) and §4.2: a semi-ellipsoidal
pressure p0 √(1 − x²/a² − y²/b²) on a half-space displaces the surface inside the ellipse by
δ − A x² − B y², with (long semi-axis l, short s, e² = 1 − s²/l², K, E complete elliptic
integrals of parameter e², E* the contact modulus, A_l the curvature along the long axis)::

    A_l = p0 s (K − E) / (E* l² e²),   A_s = p0 s ((l/s)² E − K) / (E* l² e²),
    δ = p0 s K / E*,                   P = 2/3 π l s p0.

Here the axis ratio is found from A_s/A_l by bisection on k' = s/l, then l from the load or
from the approach. Only NumPy/SciPy are used (no wheelrail code).
"""

import math

from scipy.optimize import brentq
from scipy.special import ellipe, ellipk, ellipkm1

__all__ = ["contact_modulus", "hertz_load", "hertz_approach", "hertz_ellipse_load"]


def contact_modulus(E, nu, E2=None, nu2=None):
    """E* [Pa]: 1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2 (identical bodies by default)."""
    E2 = E if E2 is None else E2
    nu2 = nu if nu2 is None else nu2
    return 1.0 / ((1.0 - nu**2) / E + (1.0 - nu2**2) / E2)


def _KE(kp):
    """K, E of parameter m = 1 − k'² (accurate for small k' = s/l through ellipkm1)."""
    m1 = kp * kp
    return ellipkm1(m1), ellipe(1.0 - m1)


def _shape(A, B):
    """(k' = s/l, K, E, curvature along the long axis, long axis along x?) for curvatures A, B."""
    lo_curv, hi_curv = min(A, B), max(A, B)
    target = hi_curv / lo_curv
    if target - 1.0 < 1e-12:
        return 1.0, math.pi / 2, math.pi / 2, lo_curv, True

    def ratio(logkp):                      # A_s / A_l as a function of ln k'
        kp = math.exp(logkp)
        K, E = _KE(kp)
        return (E / (kp * kp) - K) / (K - E) - target

    kp = math.exp(brentq(ratio, math.log(1e-9), math.log(1.0 - 1e-9), xtol=1e-15, rtol=1e-15))
    K, E = _KE(kp)
    return kp, K, E, lo_curv, A <= B


def _result(l, kp, K, E, lo_curv, along_x, Es):
    s = l * kp
    e2 = 1.0 - kp * kp
    kme_over_e2 = (K - E) / e2 if e2 > 1e-12 else math.pi / 4      # circle limit
    p0 = lo_curv * Es * l * l / (s * kme_over_e2)
    P = 2.0 / 3.0 * math.pi * l * s * p0
    delta = p0 * s * K / Es
    a, b = (l, s) if along_x else (s, l)
    return {"a": a, "b": b, "p0": p0, "load": P, "approach": delta, "area": math.pi * a * b}


def hertz_load(P, A, B, Es):
    """Hertz contact under load ``P`` [N]: dict of a (along x), b, p0, load, approach, area."""
    kp, K, E, lo_curv, along_x = _shape(A, B)
    e2 = 1.0 - kp * kp
    kme_over_e2 = (K - E) / e2 if e2 > 1e-12 else math.pi / 4
    l = (3.0 * P * kme_over_e2 / (2.0 * math.pi * lo_curv * Es)) ** (1.0 / 3.0)
    return _result(l, kp, K, E, lo_curv, along_x, Es)


def hertz_approach(delta, A, B, Es):
    """Hertz contact at approach ``delta`` [m]: dict as :func:`hertz_load`."""
    kp, K, E, lo_curv, along_x = _shape(A, B)
    e2 = 1.0 - kp * kp
    kme_over_e2 = (K - E) / e2 if e2 > 1e-12 else math.pi / 4
    l = math.sqrt(delta * kme_over_e2 / (lo_curv * K))
    return _result(l, kp, K, E, lo_curv, along_x, Es)


def hertz_ellipse_load(a, b, delta, Es):
    """Load [N] of the Hertz ellipse with semi-axes a, b [m] at approach δ [m]:
    P = 2π a b E* δ / (3 s K(e)), s = min(a, b) (δ = p0 s K/E*, P = 2/3 π a b p0)."""
    s, l = min(a, b), max(a, b)
    K = ellipk(1.0 - (s / l) ** 2)
    return 2.0 * math.pi * a * b * Es * delta / (3.0 * s * K)
