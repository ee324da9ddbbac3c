"""Hertz's theory of elastic contact between two bodies with quadratic gap (core layer).

The closed forms and :class:`HertzContact` live in the core layer because the
contact patch (:mod:`wheelrail.patch`) and every method read them; the normal
method that applies them to wheel–rail problems is
:class:`wheelrail.normal.Hertz`.

The undeformed gap is h(x, y) = A x² + B y² − δ, with ``A`` the combined
curvature along the rolling direction ``x`` and ``B`` across it (both 1/m,
A = ½(1/R1x + 1/R2x), B = ½(1/R1y + 1/R2y)). The contact patch is an ellipse
with semi-axes ``a`` (along x) and ``b`` (along y).

Kernels in this module are pure array functions (broadcasting over all
arguments); :func:`hertz`, :func:`hertz_from_semiaxes`,
:func:`hertz_from_radii` and :func:`hertz_from_penetration` build the frozen
:class:`HertzContact` from user input.

References
----------
.. [1] K.L. Johnson, *Contact Mechanics*, CUP 1985, §4.2, eqs. (3.64)–(3.66)
   and (4.32)–(4.36).
.. [2] J. Piotrowski, H. Chollet, Wheel–rail contact models for vehicle system
   dynamics including multi-point contact, VSD 43 (2005), Table 2.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ._validation import as_float_array, positive, scalar_or_array
from .errors import InputError
from .materials import MaterialPair, as_material_pair
from .plausibility import check_hertz, check_rolling_radius

__all__ = [
    "HertzContact",
    "hertz",
    "hertz_from_semiaxes",
    "hertz_from_radii",
    "hertz_from_penetration",
    "hertz_line",
    "curvatures_from_radii",
    "shape_ratio",
    "hertz_coefficients",
    "hertz_kernel",
    "RADII_KEYS",
]

_K_MIN = 1e-9  # smallest semi-axis ratio handled before the line-contact limit


def _elliptic(k):
    """K(e), E(e) and (K − E)/e² for e² = 1 − k², accurate for k → 0 and k → 1."""
    from scipy import special  # imported here: keeps ``import wheelrail`` fast

    p = k * k  # complementary parameter 1 - m
    m = 1.0 - p
    K = special.ellipkm1(p)
    E = special.ellipe(m)
    small = m < 1e-5
    with np.errstate(invalid="ignore", divide="ignore"):
        kme = np.where(small, 0.25 * np.pi * (1.0 + 0.375 * m), (K - E) / np.where(small, 1.0, m))
    return K, E, kme


def _curvature_ratio(k):
    """(E/k² − K)/(K − E): ratio of the larger to the smaller curvature for axis ratio k ≤ 1."""
    p = k * k
    m = 1.0 - p
    K, E, kme = _elliptic(k)
    small = m < 1e-5
    with np.errstate(invalid="ignore", divide="ignore"):
        exact = (E / p - K) / (K - E)
    series = (1.0 + 1.125 * m) / (1.0 + 0.375 * m)
    return np.where(small, series, exact)


def shape_ratio(ratio):
    """Semi-axis ratio k = short/long ≤ 1 for a curvature ratio ``ratio`` = large/small ≥ 1.

    Solves (E(e)/k² − K(e)) / (K(e) − E(e)) = ratio, e² = 1 − k², for
    t = log k by the secant method on log(ratio(k)) − log(ratio) (a monotone
    function of t), starting from Greenwood's k ≈ ratio^(−2/3) and kept in the
    bracket [log k_min, 0]; relative accuracy ~1e-14 in 4–8 steps
    (vectorised). A test compares it with bisection.

    Parameters
    ----------
    ratio : array_like
        max(A, B) / min(A, B) ≥ 1.

    Returns
    -------
    k : ndarray
        min(a, b) / max(a, b), same shape as ``ratio``.
    """
    ratio = np.asarray(ratio, dtype=float)
    if ratio.size <= 4 and np.all((ratio >= 1.0) & (ratio < np.inf)):
        # a few ratios (the contact points of one wheel): the same iteration in float
        # arithmetic, point by point (equal to the array iteration to a few ulps)
        k = [_shape_ratio_one(float(v)) for v in ratio.flat]
        return np.float64(k[0]) if ratio.ndim == 0 else np.array(k).reshape(ratio.shape)
    target = np.log(ratio)
    lo = np.log(_K_MIN)

    def F(t):
        return np.log(_curvature_ratio(np.exp(t))) - target

    t0 = np.clip(-(2.0 / 3.0) * target, lo, 0.0)
    t1 = np.clip(t0 - 1e-3, lo, 0.0)
    f0, f1 = F(t0), F(t1)
    for _ in range(40):
        df = f1 - f0
        ok = (df != 0.0) & np.isfinite(df)
        step = np.where(ok, f1 * (t1 - t0) / np.where(ok, df, 1.0), 0.0)
        t0, f0 = t1, f1
        t1 = np.clip(t1 - step, lo, 0.0)
        if np.all(np.abs(t1 - t0) <= 1e-15 * np.maximum(1.0, np.abs(t1))):
            break
        f1 = F(t1)
    return np.exp(t1)


def _shape_ratio_one(ratio: float) -> float:
    """:func:`shape_ratio` of one ratio ≥ 1 (the same secant iteration on Python floats)."""
    from scipy import special

    target = math.log(ratio)
    lo = math.log(_K_MIN)

    def F(t):
        k = math.exp(t)
        p = k * k
        m = 1.0 - p
        if m < 1e-5:
            cr = (1.0 + 1.125 * m) / (1.0 + 0.375 * m)
        else:
            K = float(special.ellipkm1(p))
            E = float(special.ellipe(m))
            cr = (E / p - K) / (K - E)
        return math.log(cr) - target

    t0 = min(max(-(2.0 / 3.0) * target, lo), 0.0)
    t1 = min(max(t0 - 1e-3, lo), 0.0)
    f0, f1 = F(t0), F(t1)
    for _ in range(40):
        df = f1 - f0
        step = f1 * (t1 - t0) / df if (df != 0.0 and math.isfinite(df)) else 0.0
        t0, f0 = t1, f1
        t1 = min(max(t1 - step, lo), 0.0)
        if abs(t1 - t0) <= 1e-15 * max(1.0, abs(t1)):
            break
        f1 = F(t1)
    return math.exp(t1)


def _shape_ratio_bisection(ratio):
    """Reference for tests: bisection in log k (64 steps)."""
    ratio = np.asarray(ratio, dtype=float)
    lo = np.full(ratio.shape, np.log(_K_MIN))
    hi = np.zeros(ratio.shape)
    for _ in range(64):
        mid = 0.5 * (lo + hi)
        too_small = _curvature_ratio(np.exp(mid)) > ratio   # ratio(k) decreases with k
        lo = np.where(too_small, mid, lo)
        hi = np.where(too_small, hi, mid)
    return np.exp(0.5 * (lo + hi))


def hertz_kernel(load, A, B, E_star):
    """Hertz solution for prescribed load (pure array kernel).

    Parameters
    ----------
    load : array_like
        Normal load N [N], > 0.
    A, B : array_like
        Combined curvatures along x and y [1/m], > 0.
    E_star : float or array_like
        Contact modulus [Pa].

    Returns
    -------
    a, b, p0, delta : ndarray
        Semi-axes along x and y [m], maximum pressure [Pa], approach [m].

    Notes
    -----
    With the long semi-axis ``l`` along the direction of the smaller curvature
    ``Cs`` and k = short/long (Johnson 1985, eqs. 3.64–3.66)::

        l³ = 3 N (K − E) / (2 π E* e² Cs),  p0 = 3N / (2π a b),  δ = p0 s K(e) / E*

    where ``s = k l`` is the short semi-axis.
    """
    load, A, B = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (load, A, B)))
    Cs = np.minimum(A, B)
    k = shape_ratio(np.maximum(A, B) / Cs)
    K, E, kme = _elliptic(k)
    long_ = np.cbrt(3.0 * load * kme / (2.0 * np.pi * E_star * Cs))
    short = k * long_
    a = np.where(A <= B, long_, short)
    b = np.where(A <= B, short, long_)
    p0 = 1.5 * load / (np.pi * a * b)
    delta = p0 * short * K / E_star
    return a, b, p0, delta


def curvatures_from_semiaxes(a, b, load, E_star):
    """Curvatures A, B [1/m] that give semi-axes ``a``, ``b`` [m] under ``load`` [N] (Johnson eq. 3.64)."""
    a, b, load = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (a, b, load)))
    long_ = np.maximum(a, b)
    short = np.minimum(a, b)
    k = short / long_
    K, E, kme = _elliptic(k)
    p0 = 1.5 * load / (np.pi * a * b)
    c_small = p0 * short * kme / (E_star * long_**2)          # curvature along the long axis
    c_large = c_small * _curvature_ratio(k)
    A = np.where(a >= b, c_small, c_large)
    B = np.where(a >= b, c_large, c_small)
    return A, B


def curvatures_from_radii(wheel_rolling_radius, wheel_profile_radius=np.inf,
                          rail_profile_radius=np.inf, rail_longitudinal_radius=np.inf):
    """Combined curvatures A (rolling direction) and B (lateral) from principal radii.

    Parameters
    ----------
    wheel_rolling_radius : float
        Wheel rolling radius R1x [m], > 0.
    wheel_profile_radius : float, optional
        Wheel transverse profile radius R1y [m]; concave (e.g. a worn hollow
        tread) is **negative**; ``inf`` (default) for a flat (conical) tread.
    rail_profile_radius : float, optional
        Rail head transverse radius R2y [m]; convex positive; ``inf`` = flat.
    rail_longitudinal_radius : float, optional
        Rail radius along the track R2x [m]; ``inf`` (default) for straight rail.

    Returns
    -------
    A, B : float or ndarray
        A = ½(1/R1x + 1/R2x), B = ½(1/R1y + 1/R2y) [1/m].
    """
    r1x = positive("wheel_rolling_radius", wheel_rolling_radius)
    inv = []
    for name, r in (("wheel_profile_radius", wheel_profile_radius),
                    ("rail_profile_radius", rail_profile_radius),
                    ("rail_longitudinal_radius", rail_longitudinal_radius)):
        r = np.asarray(r, dtype=float)
        bad = np.isnan(r) | (r == 0)
        if np.any(bad):
            raise InputError(f"{name} must be non-zero and not NaN (use inf for flat), "
                             f"got {_first(bad, r)!r}")
        inv.append(1.0 / r)
    A = 0.5 * (1.0 / r1x + inv[2])
    B = 0.5 * (inv[0] + inv[1])
    if np.any(A <= 0) or np.any(B <= 0):
        bad = ("A", _first(A <= 0, A)) if np.any(A <= 0) else ("B", _first(B <= 0, B))
        raise InputError(
            f"the radii give a non-positive combined curvature {bad[0]} = {bad[1]!r} 1/m: "
            "the surfaces do not form a Hertzian (convex) contact; a concave wheel radius must "
            "be larger in magnitude than the rail radius")
    return scalar_or_array(A), scalar_or_array(B)


@dataclass(frozen=True)
class HertzContact:
    """An elliptic Hertzian contact patch (frozen).

    All attributes are floats, or arrays of one common shape for batches.

    Attributes
    ----------
    a, b : float or ndarray
        Semi-axes along the rolling direction x and laterally y [m].
    p0 : float or ndarray
        Maximum pressure [Pa].
    penetration : float or ndarray
        Approach of the two bodies δ [m].
    Fn : float or ndarray
        Normal force [N].
    A, B : float or ndarray
        Combined curvatures [1/m].
    materials : MaterialPair
        Wheel and rail materials.
    """

    a: object
    b: object
    p0: object
    penetration: object
    Fn: object
    A: object
    B: object
    materials: MaterialPair

    # -- derived quantities -------------------------------------------------
    @property
    def area(self):
        """Contact area π a b [m²]."""
        return np.pi * np.asarray(self.a) * self.b

    @property
    def c(self):
        """Mean semi-axis √(ab) [m]."""
        return np.sqrt(np.asarray(self.a) * self.b)

    @property
    def aspect(self):
        """Ratio a/b [-]."""
        return np.asarray(self.a) / self.b

    @property
    def G(self) -> float:
        """Combined shear modulus [Pa]."""
        return self.materials.G

    @property
    def nu(self) -> float:
        """Combined Poisson's ratio [-]."""
        return self.materials.nu

    @property
    def shape(self) -> tuple:
        """Batch shape (``()`` for a single contact)."""
        return np.shape(self.a)

    def pressure(self, x, y):
        """Hertzian pressure p(x, y) = p0 √(1 − (x/a)² − (y/b)²) [Pa], zero outside.

        Only for a single contact (scalar attributes). ``x``, ``y`` in m, broadcast.
        """
        if self.shape != ():
            raise InputError("pressure() needs a single contact, this HertzContact is a batch")
        r2 = (np.asarray(x) / self.a) ** 2 + (np.asarray(y) / self.b) ** 2
        return self.p0 * np.sqrt(np.clip(1.0 - r2, 0.0, None))

    def __getitem__(self, index) -> "HertzContact":
        """One contact (or a sub-batch) of a batch."""
        if self.shape == ():
            raise InputError("a single HertzContact cannot be indexed")
        pick = lambda v: scalar_or_array(np.asarray(v)[index])  # noqa: E731
        return HertzContact(*(pick(getattr(self, f)) for f in
                              ("a", "b", "p0", "penetration", "Fn", "A", "B")), self.materials)

    def to_dict(self) -> dict:
        """JSON-friendly summary in SI units."""
        out = {}
        for key in ("a", "b", "p0", "penetration", "Fn", "A", "B", "area"):
            v = np.asarray(getattr(self, key))
            out[key] = v.tolist() if v.ndim else float(v)
        return out


def _first(mask, values) -> float:
    """The first value where ``mask`` holds, as a Python float (for error messages)."""
    return np.broadcast_to(values, np.shape(mask))[mask].ravel()[0].item()


def _checked_curvatures(A, B):
    A = as_float_array("A", A)
    B = as_float_array("B", B)
    for name, v in (("A", A), ("B", B)):
        if np.any(v < 0):
            raise InputError(f"curvature {name} must be >= 0 for a Hertzian contact, "
                             f"got {_first(v < 0, v)!r} 1/m")
        if np.any(v == 0):
            raise InputError(f"curvature {name} = 0 1/m means a line contact: use hertz_line()")
    ratio = np.maximum(A, B) / np.minimum(A, B)
    if np.any(ratio > 1e12):
        raise InputError(f"curvature ratio {_first(ratio > 1e12, ratio)!r} is beyond the elliptic "
                         "range (1e-12 … 1e12): use hertz_line() for a line contact")
    return A, B


def _make(a, b, p0, delta, load, A, B, pair) -> HertzContact:
    s = scalar_or_array
    contact = HertzContact(s(a), s(b), s(p0), s(delta), s(load), s(A), s(B), pair)
    check_hertz(contact)  # wrong-unit inputs: warn, or refuse a patch larger than the radii
    return contact


def hertz(Fn, A, B, material) -> HertzContact:
    """Solve the Hertz problem for a prescribed normal force.

    Parameters
    ----------
    Fn : float or array_like
        Normal force Fn [N], > 0. Arrays give a batch.
    A, B : float or array_like
        Combined curvatures along the rolling direction and laterally [1/m], > 0
        (see :func:`curvatures_from_radii`).
    material : Material or MaterialPair

    Returns
    -------
    HertzContact

    Examples
    --------
    >>> import wheelrail as wr
    >>> c = wr.hertz(Fn=7500.0, A=0.5/0.46, B=0.5/0.30, material=wr.Material(2.1e11, 0.28))
    >>> round(c.a * 1e3, 3), round(c.b * 1e3, 3)
    (3.033, 2.281)

    References
    ----------
    .. [1] Johnson, *Contact Mechanics* (1985), eqs. (3.64)–(3.66).
    """
    pair = as_material_pair(material)
    Fn = positive("Fn", Fn)
    A, B = _checked_curvatures(A, B)
    a, b, p0, delta = hertz_kernel(Fn, A, B, pair.E_star)
    Fn, A, B = np.broadcast_arrays(Fn, A, B)
    return _make(a, b, p0, delta, Fn, A, B, pair)


#: Names of the principal radii [m] taken by :func:`hertz_from_radii` (case files, sweeps).
RADII_KEYS = ("wheel_rolling_radius", "wheel_profile_radius", "rail_profile_radius",
              "rail_longitudinal_radius")


def hertz_from_radii(Fn, wheel_rolling_radius, wheel_profile_radius=np.inf,
                     rail_profile_radius=np.inf, rail_longitudinal_radius=np.inf,
                     *, material) -> HertzContact:
    """Hertz solution from principal radii (see :func:`curvatures_from_radii`), all in m."""
    check_rolling_radius(wheel_rolling_radius)  # radii in mm are refused (plausibility)
    A, B = curvatures_from_radii(wheel_rolling_radius, wheel_profile_radius,
                                 rail_profile_radius, rail_longitudinal_radius)
    return hertz(Fn, A, B, material)


def hertz_from_semiaxes(a, b, Fn, material) -> HertzContact:
    """Hertzian contact with prescribed semi-axes.

    Users often know ``a`` and ``b`` (from a measurement or another program);
    the curvatures that produce them under ``Fn`` follow from Hertz theory.

    Parameters
    ----------
    a, b : float or array_like
        Semi-axes along x and y [m], > 0, with 1e-9 ≤ a/b ≤ 1e9.
    Fn : float or array_like
        Normal force [N], > 0.
    material : Material or MaterialPair
    """
    pair = as_material_pair(material)
    a = positive("a", a)
    b = positive("b", b)
    Fn = positive("Fn", Fn)
    ratio = a / b
    out = (ratio < _K_MIN) | (ratio > 1 / _K_MIN)
    if np.any(out):
        raise InputError(f"a/b = {_first(out, ratio)!r} is outside the valid range [1e-9, 1e9]")
    A, B = curvatures_from_semiaxes(a, b, Fn, pair.E_star)
    a, b, Fn = np.broadcast_arrays(a, b, Fn)
    short = np.minimum(a, b)
    p0 = 1.5 * Fn / (np.pi * a * b)
    delta = p0 * short * _elliptic(short / np.maximum(a, b))[0] / pair.E_star  # as hertz_kernel
    return _make(a, b, p0, delta, Fn, A, B, pair)


def hertz_from_penetration(penetration, A, B, material) -> HertzContact:
    """Inverse Hertz problem: Fn and patch from the approach δ [m] (δ > 0).

    Uses δ ∝ N^(2/3): the solution for a unit Fn is scaled, so it is exact.
    """
    pair = as_material_pair(material)
    delta = positive("penetration", penetration)
    A, B = _checked_curvatures(A, B)
    a1, b1, p01, d1 = hertz_kernel(1.0, A, B, pair.E_star)
    s = np.sqrt(delta / d1)  # = Fn^(1/3): a, b, p0 scale with it, δ with its square
    delta, A, B = np.broadcast_arrays(delta, A, B)
    return _make(a1 * s, b1 * s, p01 * s, delta, s**3, A, B, pair)


def hertz_line(load_per_length, radius, material):
    """Hertz line (cylinder) contact, the limit B/A → ∞ of the elliptic case.

    Parameters
    ----------
    load_per_length : float
        Load per unit length P' [N/m], > 0.
    radius : float
        Relative radius R = 1/(1/R1 + 1/R2) in the plane of the section [m].
    material : Material or MaterialPair

    Returns
    -------
    dict
        ``b`` half-width [m] = √(4 P' R / (π E*)), ``p0`` [Pa] = 2P'/(π b).
    """
    pair = as_material_pair(material)
    P = positive("load_per_length", load_per_length)
    R = positive("radius", radius)
    b = np.sqrt(4.0 * P * R / (np.pi * pair.E_star))
    return {"b": scalar_or_array(b), "p0": scalar_or_array(2.0 * P / (np.pi * b))}


def hertz_coefficients(theta_deg):
    """Hertz coefficients m, n, r versus the angle θ (Piotrowski & Chollet, Table 2).

    cos θ = (B − A)/(A + B); a = m·a0, b = n·a0, δ = r·a0²(A + B), with
    a0 = (3N / (4 E* (A + B)))^(1/3) the radius of the circular contact with the
    same A + B.

    Parameters
    ----------
    theta_deg : array_like
        θ in degrees, 0 < θ < 180.

    Returns
    -------
    m, n, r : ndarray
    """
    theta = np.radians(as_float_array("theta_deg", theta_deg))
    if np.any(theta <= 0) or np.any(theta >= np.pi):
        raise InputError(f"theta_deg must lie in (0, 180), got {theta_deg!r}")
    c = np.cos(theta)
    A = 0.5 * (1.0 - c)
    B = 0.5 * (1.0 + c)  # A + B = 1
    E_star, load = 1.0, 4.0 / 3.0  # a0 = 1
    a, b, p0, delta = hertz_kernel(load, A, B, E_star)
    return a, b, delta


# --------------------------------------------------------------------------- several points
def _vertical_approach(Q, sep, cosg, d1, valid=None):
    """Vertical approach dz with Σ cos γ_k ((dz cos γ_k − s_k)_+ / δ1_k)^{3/2} = Q (pure kernel).

    Newton from above on the convex, increasing left-hand side (monotone
    convergence), started where the point of smallest s_k/cos γ_k alone
    carries Q. ``sep``, ``cosg``, ``d1`` have shape (k,) for one wheel or
    (n, k) for n wheels at once (``Q`` then a scalar or shape (n,), ``valid``
    masking padded points); ``d1`` is the Hertz approach under unit load of
    each point [m/N^(2/3)]. Returns a float, or shape (n,).
    """
    single = np.ndim(sep) == 1
    if single and valid is None and np.size(sep) <= 4 and np.ndim(Q) == 0:
        return _vertical_approach_one(float(Q), [float(v) for v in sep],
                                      [float(v) for v in cosg], [float(v) for v in d1])
    sep, cosg, d1 = (np.atleast_2d(np.asarray(v, dtype=float)) for v in (sep, cosg, d1))
    valid = np.ones(sep.shape, bool) if valid is None else np.atleast_2d(valid)
    Q = np.broadcast_to(np.asarray(Q, dtype=float), sep.shape[:1])
    r = np.arange(sep.shape[0])
    k = np.argmin(np.where(valid, sep / cosg, np.inf), axis=1)
    dz = (sep[r, k] + d1[r, k] * (Q / cosg[r, k]) ** (2.0 / 3.0)) / cosg[r, k]
    for _ in range(100):
        pen = np.where(valid, np.clip(dz[:, None] * cosg - sep, 0.0, None), 0.0)
        F = np.sum((pen / d1) ** 1.5 * cosg, axis=1) - Q
        dF = np.sum(1.5 * np.sqrt(pen / d1) / d1 * cosg * cosg, axis=1)
        dz = dz - np.where(dF > 0, F / np.where(dF > 0, dF, 1.0), 0.0)
        if np.all(np.abs(F) <= 1e-12 * Q):
            break
    return float(dz[0]) if single else dz


def _vertical_approach_one(Q, sep, cosg, d1):
    """:func:`_vertical_approach` of one wheel with a few points (lists of floats): the same
    Newton iteration in float arithmetic."""
    ratios = [s / c for s, c in zip(sep, cosg)]
    k = ratios.index(min(ratios))
    dz = (sep[k] + d1[k] * (Q / cosg[k]) ** (2.0 / 3.0)) / cosg[k]
    for _ in range(100):
        F = dF = 0.0
        for s, c, d in zip(sep, cosg, d1):
            pen = max(dz * c - s, 0.0)
            F += (pen / d) ** 1.5 * c
            dF += 1.5 * math.sqrt(pen / d) / d * c * c
        F -= Q
        dz = dz - (F / dF if dF > 0 else 0.0)
        if abs(F) <= 1e-12 * Q:
            break
    return dz
