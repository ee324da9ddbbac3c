"""Kalker's linear theory of rolling contact (creep coefficients C11 … C33).

In the limit of vanishing creepage the whole contact ellipse adheres and the
creep forces are linear in the creepages (Kalker 1967; Bosso et al. (2013), ch. 2,
eq. 2.11). With Kalker's sign convention (:mod:`wheelrail.conventions`:
forces on the wheel, creepage of the wheel relative to the rail) and
c = √(ab)::

    Fx = −G c² C11 ξ
    Fy = −G c² (C22 η + c C23 φ)
    Mz =  G c³ (C23 η − c C33 φ)

The coefficients ``Cij`` depend only on the axis ratio a/b and on Poisson's
ratio ν. C11, C22 and C23 are Kalker's published values for g = a/b and
g = b/a = 0.1, 0.2, …, 1 and ν = 0, 0.25, 0.5 (Kalker 1990, Table E.3);
C33 on the same grid is computed by this project (boundary-element solution
of Kalker's linear theory, Richardson-extrapolated; the same computation
reproduces the published C11, C22, C23 to within 1.1 %), because no
checkable copy of the published C33 column was available. Data, sources and
method are in ``_data/kalker_coefficients.csv``. Closed-form asymptotes
exist for very slender ellipses.

Interpolation (:func:`kalker_coefficients`)
-------------------------------------------
* **In a/b** (0.1 ≤ a/b ≤ 10): for each ν column, a monotone piecewise-cubic
  Hermite interpolant (PCHIP, Fritsch–Carlson) of ln C against ln(a/b) over
  the 19 tabulated ratios. It reproduces the tabulated values exactly, is C¹,
  and is monotone wherever the table is monotone (C11, C22, C23 increase with
  a/b, C33 decreases). Working in logarithms turns the power-law growth of the
  coefficients towards slender ellipses (C23 ∝ √g, C33 ∝ 1/g, C11 ∝ 1/(g ln g))
  into gently varying functions.
* **In ν** (0 ≤ ν ≤ 0.5): the quadratic through the three ν columns, applied
  to 1/C for C11, C22, C23 (as in Vollebregt's CONTACT; 1/C is nearly linear
  in ν, exactly so for C11 = π²/(4(1−ν)) as a/b → 0). C33 falls steeply
  with ν for long ellipses, where C itself is the better variable: for C33
  the quadratic in 1/C (a/b ≤ 1/2) and in C (a/b ≥ 2) are blended linearly
  in ln(a/b) in between. Checked against the numerical solution at
  ν = 0.125, 0.28, 0.375 and a/b = 0.3 … 10: error ≤ 0.03 % for C11 … C23,
  ≤ 0.7 % for C33 (a linear interpolation in ν of C itself would be off by
  up to 13 %).
* **Outside the table** (a/b < 0.1 or a/b > 10): Kalker's asymptotic formulas
  (below), multiplied by a correction factor that varies linearly in g from
  the table/asymptote ratio at g = 0.1 to 1 at g = 0. The result is
  continuous at the table edge and tends to the exact asymptote. (C33 for
  a/b > 10: see below.)

Asymptotes (Kalker 1967, 1990; Johnson 1985, Table 8.1), Λ = ln(16/g²)
----------------------------------------------------------------------
a/b → 0 (g = a/b, ellipse narrow in the rolling direction)::

    C11 = π² / (4 (1 − ν))
    C22 = π² / 4
    C23 = π √g / (3 (1 − ν)) · [1 + ν (Λ/2 + ln 4 − 5)]
    C33 = π² / (16 (1 − ν) g)

b/a → 0 (g = b/a, ellipse long in the rolling direction)::

    C11 = 2π / ((Λ − 2ν) g) · [1 + (3 − ln 4) / (Λ − 2ν)]
    C22 = 2π / (((1 − ν) Λ + 2ν) g) · [1 + (1 − ν)(3 − ln 4) / ((1 − ν) Λ + 2ν)]
    C23 = 2π / (3 g^{3/2} ((1 − ν) Λ − 2 + 4ν))

For C33 as b/a → 0 no asymptotic formula was available to us. Beyond
a/b = 10 C33 is continued as a power law of a/b with the slope of the
interpolant at a/b = 10 (so C33 is C¹ there; it decreases slowly, the faster
the larger ν). Checked against the project's numerical solution at a/b = 20
(C33 = 0.774, 0.483, 0.166 for ν = 0, 0.25, 0.5) the continuation is within
2.1 % (``tests/reference/test_linear_coefficients.py``); use it with caution
for much more elongated contacts.

The a/b → 0 limits of C11, C22 and C33 follow from Carter's 2D solution
applied strip by strip (e.g. C33: Mz = −∫ y F'(y) dy with
F'(y) = π a(y) G φ y / (2(1 − ν))); the C11 and C33 limits are checked that
way in ``tests/reference/test_linear_coefficients.py``.

References
----------
.. [1] J.J. Kalker, *On the rolling contact of two elastic bodies in the
   presence of dry friction*, PhD thesis, TH Delft, 1967.
.. [2] J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
   Kluwer, 1990, Table E.3 and §1.7.
.. [3] K.L. Johnson, *Contact Mechanics*, CUP 1985, §8.4 and Table 8.1.
.. [4] N. Bosso, M. Spiryagin, A. Gugliotta, A. Somà, *Mechatronic Modeling of Real-Time Wheel-Rail Contact*, Springer 2013, ch. 2 (review of wheel–rail contact models), eq. (2.11).
"""

from __future__ import annotations

import csv
from functools import lru_cache
from pathlib import Path

import numpy as np
from scipy.interpolate import PchipInterpolator

from .._validation import in_range, positive, scalar_or_array
from ..options import configured
from ..results import CreepForcesResult, Status
from ._base import TangentialMethod

__all__ = [
    "kalker_coefficients",
    "kalker_table",
    "kalker_asymptotes",
    "linear_forces",
    "linear_stiffness",
    "Linear",
    "NU_NODES",
]

#: Poisson's ratios of the tabulated columns.
NU_NODES = (0.0, 0.25, 0.5)
_COEFS = ("C11", "C22", "C23", "C33")
_DATA = Path(__file__).resolve().parent / "_data" / "kalker_coefficients.csv"
_G_EDGE = 0.1  # smallest tabulated g on either side


@lru_cache(maxsize=1)
def kalker_table():
    """Kalker's tabulated creep coefficients as read from the package data file.

    Returns
    -------
    aspect : ndarray, shape (19,)
        a/b of the rows, increasing from 0.1 to 10 (rows ``b/a = g`` are
        converted to a/b = 1/g).
    values : ndarray, shape (4, 19, 3)
        ``values[k, i, j]`` is coefficient k (C11, C22, C23, C33) at
        ``aspect[i]`` and ν = ``NU_NODES[j]``.

    Notes
    -----
    C11, C22, C23: Kalker (1990) Table E.3 / Johnson (1985) Table 8.1. C33:
    computed by this project (Kalker's linear theory solved numerically).
    Details in the header of ``_data/kalker_coefficients.csv``.
    """
    rows = []
    with open(_DATA, encoding="utf-8") as fh:
        lines = [ln for ln in fh if ln.strip() and not ln.lstrip().startswith("#")]
    reader = csv.DictReader(lines)
    for rec in reader:
        g = float(rec["g"])
        aspect = g if rec["side"] == "a/b" else 1.0 / g
        vals = [[float(rec[f"{c}_nu{nu:g}"]) for nu in NU_NODES] for c in _COEFS]
        rows.append((aspect, vals))
    rows.sort(key=lambda r: r[0])
    aspect = np.array([r[0] for r in rows])
    values = np.transpose(np.array([r[1] for r in rows]), (1, 0, 2))
    aspect.setflags(write=False)
    values.setflags(write=False)
    return aspect, values


@lru_cache(maxsize=1)
def _interpolant():
    """One vector-valued PCHIP of ln C against ln(a/b); values shape (..., 4, 3)."""
    aspect, values = kalker_table()
    return PchipInterpolator(np.log(aspect), np.log(np.transpose(values, (1, 0, 2))), axis=0)


def _nu_weights(nu):
    """Lagrange weights of the quadratic through ν = 0, 0.25, 0.5; shape (3, *nu.shape)."""
    n0, n1, n2 = NU_NODES
    return np.stack([(nu - n1) * (nu - n2) / ((n0 - n1) * (n0 - n2)),
                     (nu - n0) * (nu - n2) / ((n1 - n0) * (n1 - n2)),
                     (nu - n0) * (nu - n1) / ((n2 - n0) * (n2 - n1))])


def _table_interp(aspect, nu):
    """Table interpolation for 0.1 ≤ aspect ≤ 10 (clipped), any ν in [0, 0.5]."""
    x = np.log(np.clip(aspect, 0.1, 10.0))
    logc = _interpolant()(x)                    # ln C, shape x.shape + (4, 3)
    w = np.moveaxis(_nu_weights(nu), 0, -1)     # shape nu.shape + (3,)
    out = [1.0 / np.einsum("...j,...j->...", np.exp(-logc[..., k, :]), w) for k in range(4)]
    # C33: 1/C is quadratic-friendly for a/b <= 1/2, C itself for a/b >= 2; blend in between
    lin33 = np.einsum("...j,...j->...", np.exp(logc[..., 3, :]), w)
    t = np.clip((x + np.log(2.0)) / (2.0 * np.log(2.0)), 0.0, 1.0)
    out[3] = (1.0 - t) * out[3] + t * lin33
    return out


def kalker_asymptotes(aspect, nu):
    """Kalker's asymptotic creep coefficients for slender contact ellipses.

    Parameters
    ----------
    aspect : array_like
        a/b [-], > 0. Meaningful for a/b ≪ 1 or a/b ≫ 1 only.
    nu : array_like
        Poisson's ratio [-].

    Returns
    -------
    C11, C22, C23, C33 : ndarray
        For a/b ≤ 1 the a/b → 0 expansions, for a/b > 1 the b/a → 0
        expansions. C33 for b/a → 0 has no closed form here and is returned
        as NaN (:func:`kalker_coefficients` uses a power-law continuation of
        the table instead).

    References
    ----------
    .. [1] Kalker (1967), (1990) §1.7; Johnson (1985) Table 8.1. The same
       formulas are used in Vollebregt's CONTACT (subroutine ``linrol``).
    """
    aspect = np.asarray(aspect, dtype=float)
    nu = np.asarray(nu, dtype=float)
    narrow = aspect <= 1.0  # a/b -> 0
    g = np.where(narrow, aspect, 1.0 / aspect)
    lam = np.log(16.0 / g**2)
    pi = np.pi
    ln4 = np.log(4.0)
    # a/b -> 0
    c11_n = pi**2 / (4.0 * (1.0 - nu)) * np.ones_like(g)
    c22_n = pi**2 / 4.0 * np.ones_like(g)
    c23_n = pi * np.sqrt(g) / (3.0 * (1.0 - nu)) * (1.0 + nu * (0.5 * lam + ln4 - 5.0))
    c33_n = pi**2 / (16.0 * (1.0 - nu) * g)
    # b/a -> 0
    s = lam - 2.0 * nu
    w = (1.0 - nu) * lam + 2.0 * nu
    c11_l = 2.0 * pi / (s * g) * (1.0 + (3.0 - ln4) / s)
    c22_l = 2.0 * pi / (w * g) * (1.0 + (1.0 - nu) * (3.0 - ln4) / w)
    c23_l = 2.0 * pi / (3.0 * g**1.5 * ((1.0 - nu) * lam - 2.0 + 4.0 * nu))
    c33_l = np.full_like(g, np.nan)
    return (np.where(narrow, c11_n, c11_l), np.where(narrow, c22_n, c22_l),
            np.where(narrow, c23_n, c23_l), np.where(narrow, c33_n, c33_l))


def kalker_coefficients(aspect, nu):
    """Kalker's creep coefficients C11, C22, C23, C33 of the linear theory.

    Parameters
    ----------
    aspect : float or array_like
        Axis ratio a/b of the contact ellipse [-], > 0, with ``a`` the
        semi-axis along the rolling direction x.
    nu : float or array_like
        (Combined) Poisson's ratio [-], 0 ≤ ν ≤ 0.5. Broadcast with ``aspect``.

    Returns
    -------
    C11, C22, C23, C33 : ndarray
        Dimensionless, all positive, of the broadcast shape of the inputs
        (0-d arrays for scalar input).

    Raises
    ------
    InputError
        If ``aspect`` is not finite or ≤ 0, or ``nu`` lies outside [0, 0.5].

    Notes
    -----
    Inside 0.1 ≤ a/b ≤ 10 the table (C11, C22, C23 from Kalker 1990,
    Table E.3; C33 computed by this project, see the module docstring) is
    interpolated: PCHIP of ln C in ln(a/b), quadratic in ν (of 1/C; for C33
    of 1/C or C depending on a/b). Outside it Kalker's slender-ellipse
    asymptotes are blended in (C33 for a/b > 10: power-law continuation).
    Tabulated points are reproduced to rounding error.

    With Kalker's sign convention the linear forces are
    Fx = −G c² C11 ξ, Fy = −G c² (C22 η + c C23 φ),
    Mz = G c³ (C23 η − c C33 φ), c = √(ab): C23 is positive.

    Examples
    --------
    >>> from wheelrail.tangential.linear import kalker_coefficients
    >>> [round(float(c), 2) for c in kalker_coefficients(1.0, 0.25)]
    [4.12, 3.67, 1.47, 1.19]

    References
    ----------
    .. [1] J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
       Kluwer 1990, Table E.3.
    .. [2] K.L. Johnson, *Contact Mechanics*, CUP 1985, Table 8.1.
    """
    aspect, nu = np.broadcast_arrays(positive("aspect (a/b)", aspect), in_range("nu", nu, 0.0, 0.5))
    if aspect.size > 1 and np.all(aspect == aspect.flat[0]) and np.all(nu == nu.flat[0]):
        # one contact, many cases (a batch of creepages): interpolate once
        return tuple(np.full(aspect.shape, c) for c in kalker_coefficients(aspect.flat[0],
                                                                          nu.flat[0]))
    table = _table_interp(aspect, nu)
    low = aspect < _G_EDGE
    high = aspect > 1.0 / _G_EDGE
    if not (np.any(low) or np.any(high)):
        return tuple(table)
    # Outside the table: asymptote * (1 + (r - 1) g/0.1), r = table/asymptote at the edge.
    edge = np.where(low, _G_EDGE, 1.0 / _G_EDGE)
    g = np.where(low, aspect, 1.0 / np.where(high, aspect, 1.0))
    asym = kalker_asymptotes(np.where(low | high, aspect, edge), nu)
    asym_edge = kalker_asymptotes(edge, nu)
    table_edge = _table_interp(edge, nu)
    out = []
    for k in range(4):
        if k == 3:  # C33: no b/a -> 0 asymptote; power law with the table's end slope
            ratio = np.where(low, table_edge[k] / asym_edge[k], 1.0)
            h = 1e-4
            c_in = _table_interp(np.full_like(aspect, 10.0 * np.exp(-h)), nu)[3]
            slope = np.log(table_edge[k] / c_in) / h
            power = table_edge[k] * (np.where(high, aspect, 10.0) / 10.0) ** slope
            blended = np.where(low, asym[k] * (1.0 + (ratio - 1.0) * g / _G_EDGE), power)
        else:
            ratio = table_edge[k] / asym_edge[k]
            blended = asym[k] * (1.0 + (ratio - 1.0) * g / _G_EDGE)
        out.append(np.where(low | high, blended, table[k]))
    return tuple(out)


def linear_stiffness(a, b, G, nu):
    """Linear creep stiffnesses f11, f22, f23, f33 (Kalker's linear theory).

    Parameters
    ----------
    a, b : array_like
        Semi-axes along x and y [m], > 0.
    G : float or array_like
        Combined shear modulus [Pa].
    nu : float or array_like
        Combined Poisson's ratio [-].

    Returns
    -------
    f11, f22 : ndarray
        G c² C11 and G c² C22 [N].
    f23 : ndarray
        G c³ C23 [N·m].
    f33 : ndarray
        G c⁴ C33 [N·m²].
    """
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    c11, c22, c23, c33 = kalker_coefficients(a / b, nu)
    c2 = a * b
    c = np.sqrt(c2)
    return G * c2 * c11, G * c2 * c22, G * c2 * c * c23, G * c2 * c2 * c33


def linear_forces(a, b, G, nu, xi, eta, phi):
    """Creep forces of Kalker's linear theory (pure kernel, no saturation).

    Parameters
    ----------
    a, b : array_like
        Semi-axes along the rolling direction and laterally [m], > 0.
    G : float or array_like
        Combined shear modulus [Pa].
    nu : float or array_like
        Combined Poisson's ratio [-], in [0, 0.5].
    xi, eta : array_like
        Longitudinal and lateral creepage [-].
    phi : array_like
        Spin creepage [1/m].

    Returns
    -------
    Fx, Fy : ndarray
        Creep forces on the wheel [N], broadcast shape of the inputs.
    Mz : ndarray
        Spin moment on the wheel [N·m].

    Notes
    -----
    Fx = −G c² C11 ξ, Fy = −G c² (C22 η + c C23 φ), Mz = G c³ (C23 η − c C33 φ),
    c = √(ab) (Kalker 1967; Bosso et al. (2013), ch. 2 eq. 2.11 with the sign convention of
    :mod:`wheelrail.conventions`). Valid only for creepages small enough that
    the forces are well below μ Fn: the forces grow without bound.
    """
    f11, f22, f23, f33 = linear_stiffness(a, b, G, nu)
    xi, eta, phi = (np.asarray(v, dtype=float) for v in (xi, eta, phi))
    Fx = -f11 * xi
    Fy = -(f22 * eta + f23 * phi)
    Mz = f23 * eta - f33 * phi
    return Fx, Fy, Mz


@configured
class Linear(TangentialMethod):
    """Kalker's linear theory: creep forces proportional to the creepages.

    On a :class:`~wheelrail.patch.ContactPatch` (``wr.solve``) this law
    uses the patch's equivalent ellipse (:meth:`ContactPatch.ellipse`: the Hertz
    ellipse of a Hertzian patch, otherwise the ellipse of equal area and
    length/width ratio).

    **No saturation.** The forces are the small-creepage tangent of the
    creep-force law and grow without bound; they exceed the Coulomb limit μ Fn
    beyond |ξ| = (2π/3) μ p0 / (G C11) (≈ 2e-3 for steel, p0 = 1 GPa, μ = 0.3).
    ``mu`` is not used except
    to report ``info["utilisation"] = |F_t| / (μ Fn)``, which tells how far
    outside its range of validity a result is (valid for utilisation ≪ 1).
    Use ``"fastsim"``, ``"polach"``, ``"shen-hedrick-elkins"`` or ``"exact"``
    for finite creepages.

    Options: none.

    References
    ----------
    .. [1] J.J. Kalker, PhD thesis, Delft 1967; *Three-dimensional elastic
       bodies in rolling contact*, Kluwer 1990, Table E.3.
    .. [2] N. Bosso, M. Spiryagin, A. Gugliotta, A. Somà, *Mechatronic Modeling of Real-Time Wheel-Rail Contact*, Springer 2013, ch. 2 (review of wheel–rail contact models), eq. (2.11).
    """

    name = "linear"
    references = (
        "J.J. Kalker, On the rolling contact of two elastic bodies in the presence of dry "
        "friction, PhD thesis, Delft University of Technology, 1967.",
        "J.J. Kalker, Three-dimensional elastic bodies in rolling contact, Kluwer, 1990 "
        "(Table E.3: creep coefficients).",
    )
    aliases = ("kalker-linear",)

    def solve(self, contact, xi, eta, phi, mu):
        """Linear creep forces for a (batch of) Hertzian contact(s); see the class docstring."""
        Fx, Fy, Mz = linear_forces(contact.a, contact.b, contact.G, contact.nu, xi, eta, phi)
        Fn = np.asarray(contact.Fn, dtype=float)
        util = np.hypot(Fx, Fy) / (np.asarray(mu, dtype=float) * Fn)
        s = scalar_or_array
        return CreepForcesResult(Fx=s(Fx), Fy=s(Fy), Mz=s(Mz), Fn=s(Fn), mu=s(np.asarray(mu, float)),
                           method=self.name, status=Status.CONVERGED, iterations=None,
                           fields=None, info={"utilisation": s(util)})
