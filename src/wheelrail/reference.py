"""Closed-form reference solutions of contact mechanics (public).

Used by the tests and the documentation to check the numerical methods.
Every function is a pure array function (numpy broadcasting), SI units,
Kalker's sign convention (:mod:`wheelrail.conventions`): tractions and forces
act on the wheel (body 1), displacements/shifts are those of the wheel
relative to the rail.

* Cattaneo–Mindlin: a circular Hertz contact loaded from rest by a tangential
  force Q < μP (no rolling): :func:`cattaneo_stick_radius`,
  :func:`cattaneo_traction`, :func:`cattaneo_shift`.
* Carter: two-dimensional steady rolling of cylinders with longitudinal
  creepage: :func:`carter_traction`, :func:`carter_force_per_length`,
  :func:`carter_stick_zone`, :func:`carter_saturation_creepage` (implemented in
  :mod:`wheelrail.tangential.carter`, re-exported here).

References
----------
.. [1] C. Cattaneo, Sul contatto di due corpi elastici: distribuzione locale
   degli sforzi, Rend. Accad. Naz. Lincei 27 (1938) 342–348, 434–436, 474–478.
.. [2] R.D. Mindlin, Compliance of elastic bodies in contact, J. Appl. Mech.
   16 (1949) 259–268.
.. [3] K.L. Johnson, *Contact Mechanics*, CUP 1985, §7.2, eqs. (7.38)–(7.42),
   and §8.2 (Carter).
.. [4] F.W. Carter, On the action of a locomotive driving wheel, Proc. R. Soc.
   Lond. A 112 (1926) 151–157.
"""

from __future__ import annotations

import numpy as np

from ._validation import as_float_array, positive
from .errors import InputError
from .materials import as_material_pair
from .tangential.carter import (
    carter_force_per_length,
    carter_saturation_creepage,
    carter_stick_zone,
    carter_traction,
)

__all__ = [
    "cattaneo_stick_radius",
    "cattaneo_traction",
    "cattaneo_shift",
    "mindlin_stiffness",
    "carter_traction",
    "carter_force_per_length",
    "carter_stick_zone",
    "carter_saturation_creepage",
]


def _ratio(Q, mu, P):
    Q = as_float_array("Q", Q)
    mu = positive("mu", mu)
    P = positive("P", P)
    r = np.abs(Q) / (mu * P)
    if np.any(r >= 1.0):
        raise InputError(f"|Q| must be < μP (the contact slides), got |Q|/(μP) = "
                         f"{np.max(r)!r}")
    return Q, mu, P, r


def cattaneo_stick_radius(a, Q, mu, P):
    """Radius of the stick zone of the Cattaneo–Mindlin problem [m].

    c = a (1 − |Q|/(μP))^(1/3) (Johnson 1985, eq. 7.39).

    Parameters
    ----------
    a : array_like
        Radius of the circular Hertz contact [m], > 0.
    Q : array_like
        Tangential force [N], |Q| < μP.
    mu : array_like
        Friction coefficient [-], > 0.
    P : array_like
        Normal force [N], > 0.
    """
    a = positive("a", a)
    _, _, _, r = _ratio(Q, mu, P)
    return a * np.cbrt(1.0 - r)


def cattaneo_traction(r, a, Q, mu, P):
    """Tangential traction q(r) of the Cattaneo–Mindlin problem [Pa].

    q(r) = sgn(Q) μ p0 [√(1 − r²/a²) − (c/a) √(1 − r²/c²)] with the second
    term for r < c only, p0 = 3P/(2πa²), c from :func:`cattaneo_stick_radius`
    (Johnson 1985, eqs. 7.38–7.39). The traction is parallel to Q; its sign
    is that of the force Q on the wheel.

    Parameters
    ----------
    r : array_like
        Distance from the contact centre [m].
    a, Q, mu, P : array_like
        As in :func:`cattaneo_stick_radius`.
    """
    r = np.abs(as_float_array("r", r))
    a = positive("a", a)
    Q, mu, P, ratio = _ratio(Q, mu, P)
    c = a * np.cbrt(1.0 - ratio)
    p0 = 1.5 * P / (np.pi * a * a)
    outer = np.sqrt(np.clip(1.0 - (r / a) ** 2, 0.0, None))
    with np.errstate(divide="ignore", invalid="ignore"):
        inner = np.where(c > 0, (c / a) * np.sqrt(np.clip(1.0 - (r / np.where(c > 0, c, 1.0)) ** 2,
                                                          0.0, None)), 0.0)
    return np.sign(Q) * mu * p0 * (outer - inner)


def mindlin_stiffness(a, material):
    """Initial tangential stiffness dQ/dδ of a circular contact [N/m].

    1/k = ((2 − ν1)/G1 + (2 − ν2)/G2) / (8a) (Mindlin 1949; Johnson 1985,
    eq. 7.42 for Q → 0); for identical bodies k = 4 G a / (2 − ν).
    """
    a = positive("a", a)
    pair = as_material_pair(material)
    w, r = pair.wheel, pair.rail
    return 8.0 * a / ((2.0 - w.nu) / w.G + (2.0 - r.nu) / r.G)


def cattaneo_shift(a, Q, mu, P, material):
    """Rigid tangential shift δ of the wheel relative to the rail [m].

    δ = (3μP / 16a) ((2 − ν1)/G1 + (2 − ν2)/G2) [1 − (1 − |Q|/μP)^(2/3)]
    (Johnson 1985, eq. 7.42), the relative displacement of distant points of
    the two bodies. With Kalker's combined constants ((2−ν1)/G1 + (2−ν2)/G2
    = 2(2 − ν)/G) this is 3μP(2 − ν)/(8 G a) [...]; for a *single* elastic
    body on a rigid one it halves to 3μP(2 − ν)/(16 G a) [...].

    The sign is returned positive for Q > 0: the wheel must be shifted
    **against** the force that acts on it, i.e. the shift in Kalker's
    convention is −sgn(Q) δ.

    Parameters
    ----------
    a, Q, mu, P : array_like
        As in :func:`cattaneo_stick_radius`.
    material : Material or MaterialPair
    """
    a = positive("a", a)
    Q, mu, P, ratio = _ratio(Q, mu, P)
    pair = as_material_pair(material)
    w, r = pair.wheel, pair.rail
    comp = (2.0 - w.nu) / w.G + (2.0 - r.nu) / r.G
    return np.sign(Q) * 3.0 * mu * P * comp / (16.0 * a) * (1.0 - (1.0 - ratio) ** (2.0 / 3.0))

