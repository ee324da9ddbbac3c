"""Carter's two-dimensional theory of tractive rolling, and its ellipse extensions.

Carter (1926) solved the steady rolling of an elastic cylinder on an elastic
plane (a line contact of half-width ``a`` along the rolling direction, Hertz
pressure p(x) = p0 √(1 − x²/a²)) under a longitudinal creepage ξ. The contact
splits into an adhesion (stick) zone of half-width ``c`` touching the
**leading edge** and a slip zone at the trailing edge (Bosso et al. (2013), ch. 2,
§2.2, Fig. 2.3). The traction is the difference of two semi-ellipses
(Johnson 1985, §8.2)::

    q(x) = −sgn(ξ) μ p0 [ √(1 − x²/a²) − (c/a) √(1 − (x − d)²/c²) ]

with the second term only in the stick zone |x − d| ≤ c, d = a − c, and

    c/a = 1 − |ξ|/ξ_s,    ξ_s = 2 (1 − ν) μ p0 / G

(ξ_s = μ a / R for identical cylinders of relative radius R). Integrating,
the force per unit length of the line contact is

    F' = −sgn(ξ) μ P' [1 − (1 − |ξ|/ξ_s)²]  for |ξ| ≤ ξ_s,   −sgn(ξ) μ P' beyond,

P' = π a p0 / 2, with the small-creepage stiffness dF'/dξ = −π a G / (2(1 − ν))
("Carter's coefficient").

Sign convention: Kalker's (:mod:`wheelrail.conventions`): ξ is the
creepage of the wheel relative to the rail, forces act on the wheel, x points
in the rolling direction so that material enters the contact at x = +a.

Elliptic contacts (``Carter`` creep-force law)
----------------------------------------------
Carter's theory is 2D; two customary extensions to the Hertz ellipse (a along
x, b across) are provided (option ``form``):

* ``"global"`` (default): Carter's force–creepage curve applied to the whole
  patch, Fx = −sgn(ξ) μ Fn [k|ξ|/(μFn) − (k ξ)²/(4 μ²Fn²)] for
  |ξ| ≤ 2 μ Fn / k and −sgn(ξ) μ Fn beyond, with the initial slope ``k`` set
  by option ``stiffness``:

  - ``"carter"``: k = π² G a b / (4(1 − ν)), Carter's 2D coefficient summed
    over the strips of the ellipse. It equals Kalker's exact C11 in the limit
    a/b → 0 (Kalker's asymptote C11 = π²/(4(1 − ν))) but underestimates it
    for rounder patches (by 27 % for a circle with ν = 0, and by a factor
    ~4 at a/b = 10), the classical weakness of Carter's stiffness noted in
    Bosso et al. (2013), ch. 2 (eq. 2.9 discussion);
  - ``"kalker"``: k = G a b C11(a/b, ν), Kalker's linear theory (so the
    initial slope is exact; a common engineering choice).

* ``"strip"``: Carter's 2D solution applied on every strip y = const of the
  ellipse (half-width a√(1 − y²/b²), peak pressure p0√(1 − y²/b²)) and
  integrated across — the strip theory of Haines & Ollerton (1963), see
  Johnson (1985) §8.4. With t* = √(1 − u²), u = |ξ|/ξ_s, ξ_s = 2(1 − ν)μp0/G::

      Fx = −sgn(ξ) μ Fn · (3/2) [u asin(t*) + (1 − t*) − (1 − t*³)/3]   (u ≤ 1)

  and −sgn(ξ) μ Fn for u ≥ 1; its initial slope is the ``"carter"`` k above.

Lateral creepage and spin: Carter's theory has none. With ``lateral="error"``
(default) a non-zero η or φ raises :class:`~wheelrail.errors.InputError`;
``lateral="ignore"`` returns Fy = Mz = 0 whatever η and φ are (documented
neglect, for longitudinal-only studies on data that carry small η, φ).

References
----------
.. [1] F.W. Carter, On the action of a locomotive driving wheel, Proc. R.
   Soc. Lond. A 112 (1926) 151–157.
.. [2] K.L. Johnson, *Contact Mechanics*, CUP 1985, §8.2 (eqs. 8.6–8.9 for
   the traction and creep) and §8.4 (strip theory).
.. [3] J.B. Haines, E. Ollerton, Contact stress distributions on elliptical
   contact surfaces subjected to radial and tangential forces, Proc. IMechE
   177 (1963) 95–114.
.. [4] N. Bosso, M. Spiryagin, A. Gugliotta, A. Somà, *Mechatronic Modeling of Real-Time Wheel-Rail Contact*, Springer 2013, ch. 2 (review of wheel–rail contact models), §2.2 and Fig. 2.3.
"""

from __future__ import annotations

import numpy as np

from .._validation import as_float_array, in_range, positive, scalar_or_array
from ..errors import InputError
from ..options import configured, option
from ..results import CreepForcesResult, Status
from ._base import TangentialMethod
from .linear import kalker_coefficients

__all__ = [
    "carter_saturation_creepage",
    "carter_stick_zone",
    "carter_traction",
    "carter_force_per_length",
    "carter_stiffness_per_length",
    "carter_ellipse_force",
    "Carter",
]


def carter_saturation_creepage(mu, p0, G, nu):
    """Creepage ξ_s = 2 (1 − ν) μ p0 / G at which Carter's stick zone vanishes [-].

    Parameters
    ----------
    mu : array_like
        Friction coefficient [-].
    p0 : array_like
        Peak Hertz pressure of the line contact [Pa].
    G, nu : array_like
        Combined shear modulus [Pa] and Poisson's ratio [-].

    Returns
    -------
    ndarray
        ξ_s (= μ a / R for identical bodies, Johnson 1985 eq. 8.9).
    """
    return 2.0 * (1.0 - np.asarray(nu, float)) * np.asarray(mu, float) * np.asarray(p0, float) / G


def _check(a, mu, p0, G, nu):
    return (positive("a", a), positive("mu", mu), positive("p0", p0), positive("G", G),
            in_range("nu", nu, 0.0, 0.5))


def carter_stick_zone(a, xi, mu, p0, G, nu):
    """Half-width ``c`` and centre ``d`` of Carter's stick zone.

    Parameters
    ----------
    a : array_like
        Half-width of the line contact along the rolling direction [m].
    xi : array_like
        Longitudinal creepage (wheel relative to rail) [-].
    mu, p0, G, nu : array_like
        Friction coefficient [-], peak pressure [Pa], combined shear modulus
        [Pa] and Poisson's ratio [-].

    Returns
    -------
    c, d : ndarray
        c = a (1 − |ξ|/ξ_s) clipped at 0 (full slip), d = a − c [m]: the stick
        zone is [d − c, a], adjacent to the leading edge x = +a.
    """
    a, mu, p0, G, nu = _check(a, mu, p0, G, nu)
    xi = as_float_array("xi", xi)
    xs = carter_saturation_creepage(mu, p0, G, nu)
    c = a * np.clip(1.0 - np.abs(xi) / xs, 0.0, 1.0)
    return c, a - c


def carter_traction(x, a, xi, mu, p0, G, nu):
    """Carter's tangential traction profile q(x) on the wheel [Pa].

    The difference of two semi-ellipses: μ p(x) over the whole contact minus
    a smaller semi-ellipse over the stick zone at the leading edge (Johnson
    1985, §8.2; Bosso et al. (2013), ch. 2 Fig. 2.3).

    Parameters
    ----------
    x : array_like
        Positions along the rolling direction [m]; zero traction for |x| > a.
    a : float or array_like
        Contact half-width along x [m], > 0.
    xi : float or array_like
        Longitudinal creepage of the wheel relative to the rail [-].
    mu : float or array_like
        Coulomb friction coefficient [-], > 0.
    p0 : float or array_like
        Peak Hertz pressure [Pa], > 0.
    G : float
        Combined shear modulus [Pa], > 0.
    nu : float
        Combined Poisson's ratio [-], in [0, 0.5].

    Returns
    -------
    q : ndarray
        Longitudinal traction on the wheel [Pa], broadcast shape of ``x`` and
        the parameters; |q| ≤ μ p everywhere, q = −sgn(ξ) μ p in the slip zone.

    Notes
    -----
    q(x) = −sgn(ξ) μ p0 [√(1 − x²/a²) − (c/a)√(1 − (x − d)²/c²)], with the
    second term for |x − d| < c only; c/a = 1 − |ξ|/ξ_s, d = a − c,
    ξ_s = 2(1 − ν) μ p0/G. In the stick zone the rigid slip ξ is exactly
    cancelled by the elastic strain: ∂u/∂x = ξ.

    References
    ----------
    .. [1] F.W. Carter, Proc. R. Soc. Lond. A 112 (1926) 151–157.
    .. [2] K.L. Johnson, *Contact Mechanics*, CUP 1985, §8.2.
    """
    x = as_float_array("x", x)
    c, d = carter_stick_zone(a, xi, mu, p0, G, nu)
    a = np.asarray(a, float)
    mu = np.asarray(mu, float)
    p0 = np.asarray(p0, float)
    sgn = np.sign(as_float_array("xi", xi))
    full = np.sqrt(np.clip(1.0 - (x / a) ** 2, 0.0, None))
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = np.where(c > 0, (x - d) / np.where(c > 0, c, 1.0), 2.0)
    stick = np.where(c > 0, (c / a) * np.sqrt(np.clip(1.0 - rel**2, 0.0, None)), 0.0)
    return -sgn * mu * p0 * (full - stick)


def carter_force_per_length(a, xi, mu, p0, G, nu):
    """Carter's longitudinal force per unit length of a line contact [N/m].

    Parameters
    ----------
    a, xi, mu, p0, G, nu
        As in :func:`carter_traction` (broadcast).

    Returns
    -------
    F : ndarray
        F' = −sgn(ξ) μ P' [1 − (1 − |ξ|/ξ_s)²] for |ξ| ≤ ξ_s, −sgn(ξ) μ P'
        beyond, with P' = π a p0/2 the normal load per unit length.

    References
    ----------
    .. [1] K.L. Johnson, *Contact Mechanics*, CUP 1985, eq. (8.8).
    """
    c, d = carter_stick_zone(a, xi, mu, p0, G, nu)
    a = np.asarray(a, float)
    P = 0.5 * np.pi * a * np.asarray(p0, float)
    return -np.sign(np.asarray(xi, float)) * np.asarray(mu, float) * P * (1.0 - (c / a) ** 2)


def carter_stiffness_per_length(a, G, nu):
    """Carter's creep coefficient −dF'/dξ at ξ = 0 per unit length: π a G / (2(1 − ν)) [N/m]."""
    return np.pi * np.asarray(a, float) * G / (2.0 * (1.0 - np.asarray(nu, float)))


def carter_ellipse_force(a, b, G, nu, Fn, mu, xi, form="global", stiffness="carter"):
    """Longitudinal creep force of Carter's theory extended to a Hertz ellipse (kernel).

    Parameters
    ----------
    a, b : array_like
        Semi-axes along the rolling direction and laterally [m].
    G, nu : float or array_like
        Combined shear modulus [Pa] and Poisson's ratio [-].
    Fn : array_like
        Normal load [N].
    mu : array_like
        Friction coefficient [-].
    xi : array_like
        Longitudinal creepage [-].
    form : {"global", "strip"}
        Whole-patch Carter curve, or Carter applied strip by strip
        (Haines & Ollerton); see the module docstring.
    stiffness : {"carter", "kalker"}
        Initial slope for ``form="global"``: Carter's coefficient summed over
        the strips, π² G a b/(4(1 − ν)), or Kalker's G a b C11(a/b, ν).
        Ignored for ``form="strip"``.

    Returns
    -------
    Fx : ndarray
        Force on the wheel [N]; |Fx| ≤ μ Fn with equality at and beyond
        saturation.
    xi_sat : ndarray
        Creepage magnitude beyond which the whole patch slides [-].
    """
    a, b, Fn, mu, xi = (np.asarray(v, float) for v in (a, b, Fn, mu, xi))
    nu = np.asarray(nu, float)
    sgn = np.sign(xi)
    mf = mu * Fn
    if form == "global":
        if stiffness == "carter":
            k = np.pi**2 * G * a * b / (4.0 * (1.0 - nu))
        elif stiffness == "kalker":
            k = G * a * b * kalker_coefficients(a / b, nu)[0]
        else:
            raise InputError(f"stiffness must be 'carter' or 'kalker', got {stiffness!r}")
        xi_sat = 2.0 * mf / k
        u = np.clip(np.abs(xi) / xi_sat, 0.0, 1.0)
        return -sgn * mf * (1.0 - (1.0 - u) ** 2), xi_sat
    if form == "strip":
        p0 = 1.5 * Fn / (np.pi * a * b)
        xi_sat = carter_saturation_creepage(mu, p0, G, nu)
        u = np.clip(np.abs(xi) / xi_sat, 0.0, 1.0)
        t = np.sqrt(1.0 - u**2)
        J = u * np.arcsin(t) + (1.0 - t) - (1.0 - t**3) / 3.0
        return -sgn * mf * 1.5 * J, xi_sat
    raise InputError(f"form must be 'global' or 'strip', got {form!r}")


@configured
class Carter(TangentialMethod):
    """Carter's theory of tractive rolling (longitudinal creep only).

    On a :class:`~wheelrail.patch.ContactPatch` (``wr.solve``) this law
    uses the patch's equivalent ellipse (:meth:`ContactPatch.ellipse`: the Hertz
    ellipse of a Hertzian patch, otherwise the ellipse of equal area and
    length/width ratio).

    Other Parameters
    ----------------
    form : {"global", "strip"}, default "global"
        Carter's force–creepage curve for the whole ellipse, or applied strip
        by strip (Haines & Ollerton); see :mod:`wheelrail.tangential.carter`.
    stiffness : {"carter", "kalker"}, default "carter"
        Initial slope of the ``"global"`` curve.
    lateral : {"error", "ignore"}, default "error"
        What to do with non-zero η or φ, which Carter's theory cannot
        represent: raise :class:`~wheelrail.errors.InputError`, or ignore them
        and return Fy = Mz = 0.

    The result's ``info`` holds ``xi_saturation`` (creepage magnitude beyond
    which the whole patch slides) and ``full_slip`` (bool); ``status`` is
    ``FULL_SLIP`` when every case of the batch is saturated.

    References
    ----------
    .. [1] F.W. Carter, Proc. R. Soc. Lond. A 112 (1926) 151–157.
    .. [2] K.L. Johnson, *Contact Mechanics*, CUP 1985, §8.2, §8.4.
    """

    name = "carter"
    references = (
        "F.W. Carter, On the action of a locomotive driving wheel, Proc. R. Soc. Lond. A 112 "
        "(1926) 151-157.",
        "J.B. Haines, E. Ollerton, Contact stress distributions on elliptical contact surfaces "
        "subjected to radial and tangential forces, Proc. IMechE 177 (1963) 95-114.",
        "K.L. Johnson, Contact Mechanics, Cambridge University Press, 1985, sections 8.2, 8.4.",
    )
    form: str = option("global", choices=("global", "strip"),
                       doc="Carter's curve for the whole ellipse, or strip by strip")
    stiffness: str = option("carter", choices=("carter", "kalker"),
                            doc="initial slope of the global curve")
    lateral: str = option("error", choices=("error", "ignore"),
                          doc="non-zero eta or phi: refuse, or ignore (Fy = Mz = 0)")

    def solve(self, contact, xi, eta, phi, mu):
        """Carter creep force for a (batch of) Hertzian contact(s); see the class docstring."""
        form, stiffness, lateral = self.form, self.stiffness, self.lateral
        eta = np.asarray(eta, float)
        phi = np.asarray(phi, float)
        if lateral == "error":
            for name, v, unit in (("eta", eta, ""), ("phi", phi, " 1/m")):
                if np.any(v != 0.0):
                    bad = v[v != 0.0].ravel()[0]
                    raise InputError(
                        f"Carter's theory has no lateral creepage or spin, got {name} = {bad!r}"
                        f"{unit}; use method 'fastsim'/'polach'/'exact', or pass "
                        "lateral='ignore' to drop eta and phi")
        Fx, xi_sat = carter_ellipse_force(contact.a, contact.b, contact.G, contact.nu,
                                          contact.Fn, mu, xi, form=form, stiffness=stiffness)
        full = np.abs(np.asarray(xi, float)) >= xi_sat
        zero = np.zeros_like(Fx)
        s = scalar_or_array
        status = Status.FULL_SLIP if np.all(full) else Status.CONVERGED
        return CreepForcesResult(Fx=s(Fx), Fy=s(zero), Mz=s(zero.copy()),
                           Fn=s(np.asarray(contact.Fn, float)), mu=s(np.asarray(mu, float)),
                           method=self.name, status=status, iterations=None, fields=None,
                           info={"xi_saturation": s(xi_sat),
                                 "full_slip": full.item() if full.ndim == 0 else full})
