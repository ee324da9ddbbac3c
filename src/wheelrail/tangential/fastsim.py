"""FASTSIM: Kalker's fast algorithm for the simplified theory of rolling contact.

The simplified theory replaces the elastic half-space by a bed of independent
springs, ``u = L p``; with this relation the steady rolling problem decouples
into strips parallel to the rolling direction, which FASTSIM integrates from
the leading to the trailing edge, scaling the traction back onto the traction
bound μ p_z wherever it would exceed it (slip). See
:mod:`wheelrail.tangential._fastsim_kernel` for the discrete equations.

Choices made here (all documented in the class docstring of :class:`Fastsim`):

* **Strips**: ``ny`` strips of equal width over (−b, b), strip centres
  ``y_j = −b + (j + ½) 2b/ny``; each strip is cut into ``nx`` elements
  spanning its own length 2a√(1 − y_j²/b²) (Kalker's choice), tractions at the
  element centres. The elastic predictor is exact for the linear rigid slip,
  so in full adhesion the scheme is second-order accurate (mid-point rule);
  Kalker's original node-based version is first order.
  ``scheme="euler"`` selects instead the first-order backward-Euler march of
  CONTACT's FASTSIM (full step δx into every element, rigid slip at the
  element centre), which reproduces the numbers CONTACT publishes for its
  FASTSIM example (see :class:`Fastsim`, Notes).
* **Flexibility**: ``flexibility="three"`` (default) uses one flexibility per
  creepage, L1 = 8a/(3 G C11), L2 = 8a/(3 G C22), L3 = π a √(a/b)/(4 G C23)
  (Piotrowski & Chollet 2005, eq. 11; Kalker 1982), so that FASTSIM
  reproduces Kalker's linear theory for pure ξ, pure η and pure φ (forces;
  the spin moment Mz is only approximated, C33 does not enter).
  ``flexibility="weighted"`` uses Kalker's single weighted flexibility
  L = (L1|ξ| + L2|η| + L3 c|φ|)/√(ξ² + η² + c²φ²), c = √(ab)
  (Kalker 1982).
* **Traction bound**: ``bound="parabolic"`` (default) is Kalker's FASTSIM
  bound μ p_z with p_z = 2Fn/(πab) (1 − x²/a² − y²/b²) (the choice of Kalker
  1982 and of CONTACT's FASTSIM, which gives better qualitative agreement with
  the exact theory); ``bound="elliptic"`` uses the Hertzian pressure
  p_z = 3Fn/(2πab) √(1 − x²/a² − y²/b²).

References
----------
.. [1] J.J. Kalker, A fast algorithm for the simplified theory of rolling
   contact, Vehicle System Dynamics 11 (1982) 1–13.
.. [2] J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
   Kluwer 1990 (simplified theory, FASTSIM).
.. [3] J. Piotrowski, H. Chollet, Wheel–rail contact models for vehicle system
   dynamics including multi-point contact, VSD 43 (2005) 455–483, eq. (11),
   eqs. (24)–(26).
.. [4] E.A.H. Vollebregt, *User guide for CONTACT, rolling and sliding contact
   with friction*, Vtech CMCC (TR09-03/20-01), section "The use of the
   FASTSIM algorithm" (example ``fastsim.inp``): the published FASTSIM case
   and CONTACT's first-order march (``scheme="euler"``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from .._validation import as_float_array, integer, positive, scalar_or_array
from ..errors import InputError
from ..options import configured, option
from ..results import CreepForcesResult, Status
from . import _fastsim_kernel as _k
from ._base import TangentialMethod
from .linear import kalker_coefficients

__all__ = [
    "Fastsim",
    "FastsimFields",
    "fastsim_strips",
    "flexibilities",
    "weighted_flexibility",
    "combined_flexibility",
    "hertz_strips",
    "strip_cell_centres",
]

_BOUNDS = ("parabolic", "elliptic")
_FLEXIBILITIES = ("three", "weighted")
_SCHEMES = ("midpoint", "euler")
_KALKER_GRID = 8001


# ---------------------------------------------------------------------------
# fields
# ---------------------------------------------------------------------------
@dataclass(frozen=True)
class FastsimFields:
    """Surface fields of a FASTSIM solution on a strip grid (frozen).

    All arrays have shape (ny, nx): row ``j`` is strip ``j`` (lateral position
    ``y``), column ``i`` the ``i``-th element counted from the leading edge.

    Attributes
    ----------
    x, y : ndarray
        Element centres [m].
    dx, dy : ndarray, shape (ny,)
        Element length and strip width [m] (element area ``dx[j] * dy[j]``).
    pressure : ndarray
        Normal pressure p_z used for the traction bound [Pa].
    px, py : ndarray
        Tangential traction on the wheel [Pa].
    sx, sy : ndarray
        Slip of the wheel relative to the rail divided by the rolling speed
        [-] (zero in adhesion), ``s = diag(L1, L2)(p − p_H)/Δx``; in
        slip ``p`` is exactly opposite to ``s``.
    slip : ndarray of bool
        True where the element slides.
    mu : ndarray, shape (ny,)
        Friction coefficient per strip.
    """

    x: np.ndarray
    y: np.ndarray
    dx: np.ndarray
    dy: np.ndarray
    pressure: np.ndarray
    px: np.ndarray
    py: np.ndarray
    sx: np.ndarray
    sy: np.ndarray
    slip: np.ndarray
    mu: np.ndarray

    @property
    def in_contact(self) -> np.ndarray:
        """True for elements of non-empty strips (shape (ny, nx))."""
        return np.broadcast_to((self.dx > 0)[:, None], self.x.shape)

    @property
    def adhesion(self) -> np.ndarray:
        """True where the element sticks (in contact and not sliding)."""
        return self.in_contact & ~self.slip

    @property
    def area(self) -> np.ndarray:
        """Element areas [m²], shape (ny, nx)."""
        return np.broadcast_to((self.dx * self.dy)[:, None], self.x.shape)

    @property
    def traction(self) -> np.ndarray:
        """|p_t| = √(px² + py²) [Pa]."""
        return np.hypot(self.px, self.py)

    @property
    def slip_speed(self) -> np.ndarray:
        """|s| [-] (slip velocity divided by the rolling speed)."""
        return np.hypot(self.sx, self.sy)

    @property
    def slip_direction(self) -> np.ndarray:
        """Unit vector of the slip, shape (2, ny, nx); zero in adhesion."""
        mag = self.slip_speed
        with np.errstate(invalid="ignore", divide="ignore"):
            d = np.where(mag > 0, np.stack([self.sx, self.sy]) / mag, 0.0)
        return d

    @property
    def adhesion_fraction(self) -> float:
        """Area of adhesion divided by the contact area [-]."""
        area = self.area
        return float(np.sum(area[self.adhesion]) / np.sum(area))

    def as_arrays(self) -> dict:
        """Plain arrays indexed ``[i_x, i_y]`` (the strip arrays transposed), for plotting.

        Keys as :meth:`wheelrail.results.GapResult.as_arrays`: ``x``, ``y`` [m],
        ``px``, ``py``, ``p`` [Pa], ``adhesion``, ``inside`` (bool), ``dA`` [m²],
        ``sx``, ``sy`` [-].
        """
        return {"x": self.x.T, "y": self.y.T, "px": self.px.T, "py": self.py.T,
                "p": self.pressure.T, "adhesion": self.adhesion.T, "inside": self.in_contact.T,
                "dA": self.area.T, "sx": self.sx.T, "sy": self.sy.T}


# ---------------------------------------------------------------------------
# pure helpers
# ---------------------------------------------------------------------------
def flexibilities(a, b, G, C11, C22, C23):
    """Kalker's three flexibilities of the simplified theory.

    Parameters
    ----------
    a, b : array_like
        Semi-axes along x and y [m] (for a strip of a non-elliptic patch: the
        semi-axes of its virtual ellipse §3.1).
    G : float or array_like
        Combined shear modulus [Pa].
    C11, C22, C23 : array_like
        Kalker's creep coefficients for a/b and ν [-].

    Returns
    -------
    L1, L2, L3 : ndarray
        L1 = 8a/(3 G C11), L2 = 8a/(3 G C22), L3 = π a √(a/b)/(4 G C23) [m/Pa].

    References
    ----------
    .. [1] Piotrowski & Chollet (2005), eq. (11); Kalker (1982).
    """
    a, b, G, C11, C22, C23 = (np.asarray(v, dtype=float) for v in (a, b, G, C11, C22, C23))
    L1 = 8.0 * a / (3.0 * G * C11)
    L2 = 8.0 * a / (3.0 * G * C22)
    L3 = np.pi * a * np.sqrt(a / b) / (4.0 * G * C23)
    return L1, L2, L3


def weighted_flexibility(L1, L2, L3, xi, eta, phi, c):
    """Kalker's single weighted flexibility.

    L = (L1|ξ| + L2|η| + L3 c|φ|) / √(ξ² + η² + c²φ²), and L = L1 when all
    creepages vanish (the traction is then zero whatever L).

    Parameters
    ----------
    L1, L2, L3 : array_like
        Flexibilities [m/Pa].
    xi, eta, phi : array_like
        Creepages [-], [-], [1/m].
    c : array_like
        √(ab) [m].

    Returns
    -------
    L : ndarray [m/Pa]

    References
    ----------
    .. [1] Kalker (1982).
    """
    L1, L2, L3, xi, eta, phi, c = (np.asarray(v, dtype=float) for v in (L1, L2, L3, xi, eta, phi, c))
    cphi = c * np.abs(phi)
    norm = np.sqrt(xi * xi + eta * eta + cphi * cphi)
    num = L1 * np.abs(xi) + L2 * np.abs(eta) + L3 * cphi
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(norm > 0, num / np.where(norm > 0, norm, 1.0), L1)


def combined_flexibility(L1, L2, L3, xi, eta, phi, a):
    """Vollebregt & Voltr's single combined flexibility.

    L = (ξ² + η² + s²) / (ξ²/L1 + η²/L2 + s²/L3), s = 3πaφ/32: FASTSIM's
    linear-regime forces on an ellipse are Fx = −(8a²b/3) ξ/L1,
    Fy = −(8a²b/3)(η/L2 + s/L3), so one flexibility L gives the same
    ξ·Fx + η·Fy + s·(spin part of Fy) as the three when the cross term ηs is left
    out. L = L1 when all creepages vanish.

    Parameters
    ----------
    L1, L2, L3 : float
        Flexibilities [m/Pa].
    xi, eta, phi : float
        Creepages [-], [-], [1/m].
    a : float
        Semi-axis along the rolling direction [m].

    Returns
    -------
    L : float [m/Pa]

    References
    ----------
    .. [1] E.A.H. Vollebregt, P. Voltr, Improved accuracy for FASTSIM using one or three
       flexibility values, Vehicle System Dynamics 61 (2023) 309–317 (the combined
       flexibility, CONTACT's L_crss).
    """
    s = 3.0 * math.pi * a * phi / 32.0
    num = xi * xi + eta * eta + s * s
    den = xi * xi / L1 + eta * eta / L2 + s * s / L3
    if not den > 0:
        return float(L1)
    return num / den


def _weighted_scalar(L1, L2, L3, xi, eta, phi, c):
    """:func:`weighted_flexibility` of floats (the same operations in Python arithmetic)."""
    cphi = c * abs(phi)
    norm = math.sqrt(xi * xi + eta * eta + cphi * cphi)
    if not norm > 0:
        return float(L1)
    return (L1 * abs(xi) + L2 * abs(eta) + L3 * cphi) / norm


def hertz_strips(a, b, ny):
    """Strips of an elliptic patch: uniform in y over (−b, b).

    Parameters
    ----------
    a, b : float
        Semi-axes [m].
    ny : int
        Number of strips.

    Returns
    -------
    y, dy, x_lead, x_trail : ndarray, shape (ny,)
        Strip centres y_j = −b + (j + ½) 2b/ny, widths 2b/ny, leading edges
        a√(1 − y_j²/b²) and trailing edges −a√(1 − y_j²/b²) [m].
    """
    t = _strip_t(ny)
    half = np.sqrt(1.0 - t * t)
    return b * t, np.full(ny, 2.0 * b / ny), a * half, -a * half


def strip_cell_centres(x_lead, x_trail, nx):
    """Element centres x [m], shape (ny, nx), of strips cut into ``nx`` equal elements.

    Element ``i`` of strip ``j`` has its centre at
    ``x_lead[j] − (i + ½)(x_lead[j] − x_trail[j])/nx``.
    """
    x_lead = np.atleast_1d(np.asarray(x_lead, dtype=float))
    x_trail = np.atleast_1d(np.asarray(x_trail, dtype=float))
    frac = (np.arange(nx) + 0.5) / nx
    return x_lead[:, None] - frac[None, :] * (x_lead - x_trail)[:, None]


def _strip_t(ny):
    return -1.0 + (np.arange(ny) + 0.5) * (2.0 / ny)


def _profile(kind, s):
    """Pressure profile along a strip at normalised positions s ∈ (−1, 1)."""
    if kind == "elliptic":
        return np.sqrt(np.clip(1.0 - s * s, 0.0, None))
    return np.clip(1.0 - s * s, 0.0, None)


def _check_choice(name, value, choices):
    if value not in choices:
        raise InputError(f"{name} must be one of {', '.join(map(repr, choices))}, got {value!r}")
    return value


# ---------------------------------------------------------------------------
# general strips (non-elliptic patches)
# ---------------------------------------------------------------------------
def fastsim_strips(y, dy, x_lead, x_trail, pressure, L1, L2, L3, xi, eta, phi, mu, nx=None, *,
                   profile=None, fields=True, scheme="midpoint"):
    """FASTSIM on a contact patch described by strips (elliptic or not).

    This is the kernel used by the virtual-penetration methods (Linder,
    Kik–Piotrowski, STRIPES; Piotrowski & Chollet (2005) §3): each strip has its own extent,
    pressure and flexibilities.

    Parameters
    ----------
    y, dy : array_like, shape (ny,)
        Strip centres and widths [m].
    x_lead, x_trail : array_like, shape (ny,)
        Leading (larger x) and trailing edges [m]; strips with
        ``x_lead <= x_trail`` are empty (no contact).
    pressure : array_like, shape (ny, nx) or (ny,)
        Normal pressure [Pa] at the element centres (see
        :func:`strip_cell_centres`), or the peak pressure of each strip
        together with ``profile``.
    L1, L2, L3 : float or array_like, shape (ny,)
        Flexibilities for ξ, η, φ [m/Pa] (e.g. :func:`flexibilities` with the
        strip's virtual ellipse eqs. 11, 25–26). Pass the same value
        three times for a single flexibility.
    xi, eta, phi : float
        Creepages [-], [-], [1/m] (Kalker's convention).
    mu : float or array_like, shape (ny,)
        Friction coefficient [-], > 0.
    nx : int, optional
        Elements per strip; required when ``pressure`` has shape (ny,).
    profile : {"elliptic", "parabolic"}, optional
        Pressure along each strip when ``pressure`` holds peaks:
        ``peak √(1 − s²)`` or ``peak (1 − s²)``, s the position along the
        strip normalised to (−1, 1).
    fields : bool
        Return the fields (:class:`FastsimFields`) in ``.fields``.
    scheme : {"midpoint", "euler"}
        March along the strips: element-centred exact predictor (second
        order, default) or CONTACT's first-order backward Euler (see
        :mod:`wheelrail.tangential._fastsim_kernel`).

    Returns
    -------
    CreepForcesResult
        ``Fx``, ``Fy`` [N] and ``Mz`` [N m] (about the origin of the
        coordinates) on the wheel; ``Fn`` = Σ p_z dA; ``fields`` if requested.

    References
    ----------
    .. [1] Kalker (1982); Piotrowski & Chollet (2005) eqs. (11), (24)–(26).
    """
    _check_choice("scheme", scheme, _SCHEMES)
    y = np.atleast_1d(as_float_array("y", y))
    ny = y.shape[0]
    if y.ndim != 1 or ny == 0:
        raise InputError(f"y must be a non-empty 1-D array of strip centres, got shape {y.shape}")

    def strip_array(name, v, check=None):
        arr = as_float_array(name, v) if check is None else check(name, v)
        try:
            return np.ascontiguousarray(np.broadcast_to(arr, (ny,)), dtype=float)
        except ValueError:
            raise InputError(f"{name} must be a scalar or have shape ({ny},), got shape "
                             f"{np.shape(arr)}") from None

    dy = strip_array("dy", dy)
    if np.any(dy < 0):
        raise InputError(f"dy must be >= 0, got {dy[dy < 0][0]!r}")
    x_lead = strip_array("x_lead", x_lead)
    x_trail = strip_array("x_trail", x_trail)
    L1, L2, L3 = (strip_array(n, v, positive) for n, v in (("L1", L1), ("L2", L2), ("L3", L3)))
    mu_s = strip_array("mu", mu, positive)
    xi, eta, phi = (float(as_float_array(n, v)) for n, v in (("xi", xi), ("eta", eta), ("phi", phi)))

    p = as_float_array("pressure", pressure)
    if p.ndim == 2:
        if p.shape[0] != ny:
            raise InputError(f"pressure must have shape ({ny}, nx), got {p.shape}")
        if nx is not None and integer("nx", nx) != p.shape[1]:
            raise InputError(f"nx={nx!r} does not match pressure.shape[1]={p.shape[1]}")
        nx = p.shape[1]
        if profile is not None:
            raise InputError("profile is only used when pressure holds strip peaks (shape (ny,))")
    else:
        if nx is None or profile is None:
            raise InputError("with strip peak pressures (shape (ny,)) give nx and profile")
        nx = integer("nx", nx)
        _check_choice("profile", profile, _BOUNDS)
        peaks = strip_array("pressure", p)
        s = 1.0 - (np.arange(nx) + 0.5) * (2.0 / nx)
        p = peaks[:, None] * _profile(profile, s)[None, :]
    if np.any(p < 0):
        raise InputError(f"pressure must be >= 0, got {p[p < 0].ravel()[0]!r}")
    p = np.ascontiguousarray(p, dtype=float)
    return _solve_strips(y, dy, x_lead, x_trail, p, L1, L2, L3, xi, eta, phi, mu_s,
                         scalar_or_array(np.asarray(mu, dtype=float)), scheme, fields)


#: rigid-slip traction rate [Pa/m] beyond which every element slides whatever the grid:
#: larger creepages are scaled down together to it (same direction, so the same full-slip
#: tractions to round-off) so that the kernels never overflow to inf or nan
_SLIP_RATE_CAP = 1e200


def _tame(xi, eta, phi, L1, L2, L3, reach):
    """Creepages scaled down together where their rigid-slip rate would overflow.

    ``reach`` [m] bounds |x|, |y| on the patch; arrays broadcast. In full sliding
    FASTSIM's traction depends only on the direction of the rigid slip, which a
    common factor keeps.
    """
    with np.errstate(divide="ignore"):       # in logarithms: no overflow for any float
        log_rate = np.maximum.reduce([np.log(np.abs(xi)) - np.log(L1),
                                      np.log(np.abs(eta)) - np.log(L2),
                                      np.log(np.abs(phi)) + np.log(reach) - np.log(L3)])
    f = np.exp(np.minimum(0.0, np.log(_SLIP_RATE_CAP) - log_rate))
    return xi * f, eta * f, phi * f


def _flags(scheme):
    """Kernel flags of a march (``_fastsim_kernel``): ``"euler"`` is CONTACT's FASTSIM, its
    first-order march (1) and its slip rule with the spin scaled by L/L3 (2)."""
    return 3 if scheme == "euler" else 0


def _solve_strips(y, dy, x_lead, x_trail, p, L1, L2, L3, xi, eta, phi, mu_s, mu_out, scheme,
                  fields):
    """:func:`fastsim_strips` on checked, contiguous float arrays (shapes (ny,), p (ny, nx))."""
    ny, nx = p.shape
    bound = p * mu_s[:, None]
    px = np.zeros((ny, nx))
    py = np.zeros((ny, nx))
    sx = np.zeros((ny, nx))
    sy = np.zeros((ny, nx))
    slip = np.zeros((ny, nx), dtype=bool)
    reach = max(float(np.max(np.abs(y), initial=0.0) + np.max(dy, initial=0.0)),
                float(np.max(np.abs(x_lead), initial=0.0)),
                float(np.max(np.abs(x_trail), initial=0.0)))
    kxi, keta, kphi = _tame(xi, eta, phi, np.min(L1), np.min(L2), np.min(L3), reach)
    Fx, Fy, Mz = _k.fastsim_strips_kernel(y, dy, x_lead, x_trail, bound, L1, L2, L3,
                                          float(kxi), float(keta), float(kphi), px, py, sx, sy,
                                          slip, _flags(scheme))
    scale = max((abs(kv / v) for kv, v in ((kxi, xi), (keta, eta), (kphi, phi)) if v != 0.0),
                default=1.0)
    if scale < 1.0:                       # creepages were tamed: the slip fields scale back
        with np.errstate(over="ignore"):
            sx /= scale
            sy /= scale
    length = np.clip(x_lead - x_trail, 0.0, None)
    dx = length / nx
    Fn = float(np.sum(p * (dx * dy)[:, None]))
    f = None
    if fields:
        empty = length <= 0
        slip[empty] = False
        x = strip_cell_centres(x_lead, x_trail, nx)
        x[empty] = (0.5 * (x_lead + x_trail))[empty, None]
        f = FastsimFields(x=x, y=np.repeat(y[:, None], nx, 1),
                          dx=dx, dy=dy, pressure=p, px=px, py=py, sx=sx, sy=sy, slip=slip, mu=mu_s)
    return CreepForcesResult(Fx=float(Fx), Fy=float(Fy), Mz=float(Mz), Fn=Fn,
                       mu=mu_out, method="fastsim",
                       fields=f, info={"nx": nx, "ny": ny, "scheme": scheme})


@lru_cache(maxsize=16)
def _kalker_table(nu):
    """Kalker's C11, C22, C23 on a fine grid of ln(a/b) ∈ [ln 0.01, ln 100] for one ν."""
    x = np.linspace(np.log(0.01), np.log(100.0), _KALKER_GRID)
    C11, C22, C23, _ = kalker_coefficients(np.exp(x), nu)
    return x, np.asarray(C11, float), np.asarray(C22, float), np.asarray(C23, float)


def _kalker_scalar(aspect, nu):
    """C11, C22, C23 of a patch (or its strips): linear interpolation in ln(a/b) of
    :func:`_kalker_table`.

    The grid step (1.2e-3 in ln(a/b)) keeps the interpolation error below 1e-6
    relative; a scalar :func:`kalker_coefficients` call costs ~0.3 ms, this ~10 µs.
    a/b outside the grid goes to :func:`kalker_coefficients`.
    """
    if isinstance(aspect, float) and 0.01 <= aspect <= 100.0 and isinstance(nu, float):
        x, c11, c22, c23 = _kalker_table(nu)         # one patch: no array checks
        v = math.log(aspect)
        return (float(np.interp(v, x, c11)), float(np.interp(v, x, c22)),
                float(np.interp(v, x, c23)))
    a = np.asarray(aspect, dtype=float)
    if np.ndim(nu) != 0 or not (a.size and np.all(a >= 0.01) and np.all(a <= 100.0)):
        C11, C22, C23, _ = kalker_coefficients(aspect, nu)
        return C11, C22, C23
    x, c11, c22, c23 = _kalker_table(float(nu))
    if a.ndim == 0:
        v = math.log(float(a))
        return (float(np.interp(v, x, c11)), float(np.interp(v, x, c22)),
                float(np.interp(v, x, c23)))
    v = np.log(a)
    return np.interp(v, x, c11), np.interp(v, x, c22), np.interp(v, x, c23)


_EMPTY2 = np.zeros((0, 0))
_EMPTY2B = np.zeros((0, 0), dtype=bool)


def _median(v):
    """float(np.median(v)) of a finite 1-D array (the same value, without np.median's overhead)."""
    s = np.sort(v)
    n = s.shape[0]
    k = n // 2
    return float(s[k]) if n % 2 else float((s[k - 1] + s[k]) / 2.0)


@lru_cache(maxsize=16)
def _resample_weights(m, nx):
    """Indices and weights of linear interpolation from m to nx cell centres on (0, 1)
    (as :func:`numpy.interp`: constant beyond the outer centres)."""
    src = (np.arange(m) + 0.5) / m
    dst = (np.arange(nx) + 0.5) / nx
    i1 = np.clip(np.searchsorted(src, dst), 1, m - 1) if m > 1 else np.zeros(nx, int)
    i0 = np.maximum(i1 - 1, 0)
    if m > 1:
        w = np.clip((dst - src[i0]) / (src[i1] - src[i0]), 0.0, 1.0)
    else:
        w = np.zeros(nx)
    return i0, i1, w


# ---------------------------------------------------------------------------
# the creep-force law
# ---------------------------------------------------------------------------
@configured
class Fastsim(TangentialMethod):
    """Kalker's FASTSIM on the Hertzian ellipse.

    Other Parameters
    ----------------
    nx, ny : int, default 20, 20
        Elements per strip and number of strips. Strips are uniform in y over
        (−b, b); each strip's ``nx`` elements span its own length (Kalker 1982).
        With the element-centred scheme 20×20 gives the forces within about
        0.2 % of the converged simplified theory in the linear range and
        ≈ 1 % in partial slip (see ``tests/convergence/test_fastsim_convergence.py``).
    bound : {"parabolic", "elliptic"}, default "parabolic"
        Traction bound: Kalker's parabolic pressure 2Fn/(πab)(1 − x²/a² − y²/b²)
        (as in Kalker's FASTSIM and CONTACT) or the Hertzian (semi-elliptic)
        pressure.
    flexibility : {"three", "weighted"}, default "three"
        Three flexibilities L1, L2, L3 (reproduces Kalker's linear theory for
        each creepage alone) or Kalker's single weighted flexibility.
    scheme : {"midpoint", "euler"}, default "midpoint"
        March along a strip. ``"midpoint"``: element-centred, exact elastic
        predictor (half a step from the leading edge into the first element,
        spin term at the step mid-point); second order in the element size.
        ``"euler"``: the first-order backward-Euler march of CONTACT's
        FASTSIM (``M=3``) for steady rolling, u_i = u_{i−1} − δx w(x_i)
        (full step into every element, rigid slip at the element centre)
        with CONTACT's slip rule (the spin's rigid slip scaled by L1/L3,
        L2/L3 also in slip elements); use it to reproduce CONTACT's
        published FASTSIM numbers on a given grid. ``"midpoint"`` opposes the
        true slip in slip elements (spin unscaled; module
        :mod:`wheelrail.tangential._fastsim_kernel`): with spin near full slip
        the two differ by the model, not only the discretisation (a = b = 6 mm,
        ξ = η = 1e-3, φ = 0.1 1/m: −0.1 % / +0.6 % from the exact theory
        against −2.1 % / +0.9 %); without spin, or in full adhesion, they
        converge to the same solution.
    fields : bool or None, default None
        Return the surface fields (:class:`FastsimFields`); ``None`` means
        yes for a single case, no for a batch (forces-only fast path, all cases
        in one numba call). For a batch with ``fields=True`` ``.fields`` is a
        tuple with one :class:`FastsimFields` per case.

    Notes
    -----
    Kalker's coefficients C11, C22, C23 come from
    :func:`wheelrail.tangential.linear.kalker_coefficients` for a/b and the
    combined Poisson's ratio. ``Mz`` is the spin moment about the patch centre.

    Slip rule: in a slipping element the traction lies on the bound and
    opposes the element's slip s = diag(L1, L2)(p − p_H)/Δx, a small
    per-element problem solved exactly (:func:`wheelrail.tangential.
    _fastsim_kernel.saturate`; Vollebregt & Voltr 2023, FASTSIM with three
    flexibilities). Scaling the elastic predictor back onto the bound (the
    rule of Kalker's FASTSIM with one flexibility, where both coincide)
    would make the force of a sliding patch point along (C11 ξ, C22 η)
    rather than against (ξ, η) with three flexibilities; it is not offered,
    as no reference supports it for L1 ≠ L2. The weighted flexibility does
    not reproduce the linear theory for combined creepage. The spin moment
    reproduces neither C23 (for η) nor C33 (for φ) of the linear theory.

    Discretisation and published numbers: for CONTACT's FASTSIM example
    (Vollebregt, *User guide for CONTACT*, §"The use of the FASTSIM
    algorithm", input ``fastsim.inp``: a = 8 mm, b = 4 mm, Fn = 82 kN,
    G = 82 GPa, ν = 0.28, μ = 0.3, η = −0.000625, φ = 0.625 1/m) the guide
    quotes Fy/(μFn) ≈ −0.64 (parabolic bound) and −0.60 (elliptic) on
    200×200 grids (−0.59 elliptic in older versions; values quoted to three
    digits elsewhere: −0.636 / −0.596). CONTACT uses the same
    flexibilities L1, L2, L3 and the same Kalker coefficients (1/C quadratic
    in ν) as here, but the first-order march: with ``scheme="euler"`` we get
    −0.639 / −0.5959 at 200×200; the converged simplified theory (both
    schemes) is −0.648 / −0.597, and ``"midpoint"`` gives −0.649 / −0.5973
    at 200×200. The parabolic case is sensitive because the η and φ
    contributions to Fy nearly cancel.
    """

    name = "fastsim"
    references = (
        "J.J. Kalker, A fast algorithm for the simplified theory of rolling contact, "
        "Vehicle System Dynamics 11 (1982) 1-13.",
        "J.J. Kalker, Three-dimensional elastic bodies in rolling contact, Kluwer, 1990.",
        "J. Piotrowski, H. Chollet, Wheel-rail contact models for vehicle system dynamics "
        "including multi-point contact, Vehicle System Dynamics 43 (2005) 455-483.",
    )
    nx: int = option(20, lo=1, hi=2000, doc="elements per strip (along the rolling direction)")
    ny: int = option(20, lo=1, hi=2000, doc="strips across the ellipse (Hertzian patches)")
    bound: str = option("parabolic", choices=_BOUNDS, doc="traction bound along the strips")
    flexibility: str = option("three", choices=_FLEXIBILITIES,
                              doc="three flexibilities L1, L2, L3 or Kalker's weighted one")
    scheme: str = option("midpoint", choices=_SCHEMES,
                         doc="second-order mid-point march, or CONTACT's FASTSIM (first-order "
                             "march, spin scaled in slip)")
    fields: bool | None = option(None, choices=(None, True, False),
                                 doc="return traction fields (None: for single cases only)")

    def solve(self, contact, xi, eta, phi, mu):
        nx, ny, bound, flexibility = self.nx, self.ny, self.bound, self.flexibility
        scheme, fields = self.scheme, self.fields
        first_order = _flags(scheme)
        single = np.shape(contact.a) == ()
        want_fields = single if fields is None else bool(fields)

        a, b, Fn = (np.atleast_1d(np.asarray(v, dtype=float))
                    for v in (contact.a, contact.b, contact.Fn))
        xi, eta, phi, mu = (np.atleast_1d(np.asarray(v, dtype=float)) for v in (xi, eta, phi, mu))
        n = a.shape[0]
        G = float(contact.G)
        C11, C22, C23, _ = kalker_coefficients(a / b, contact.nu)
        L1, L2, L3 = flexibilities(a, b, G, C11, C22, C23)
        if flexibility == "weighted":
            L = weighted_flexibility(L1, L2, L3, xi, eta, phi, np.sqrt(a * b))
            L1 = L2 = L3 = L
        if bound == "parabolic":
            peak = 2.0 * Fn / (np.pi * a * b)
        else:
            peak = 1.5 * Fn / (np.pi * a * b)

        info = {"nx": nx, "ny": ny, "bound": bound, "flexibility": flexibility, "scheme": scheme}
        t = _strip_t(ny)
        half = np.sqrt(1.0 - t * t)
        strip_peak = _profile(bound, t)
        # Scale the sampled traction bound so that the discrete pressure carries exactly Fn;
        # then |F_t| <= mu*Fn holds on every grid, not only in the limit of refinement.
        s_cells = _profile(bound, 1.0 - (np.arange(nx) + 0.5) * (2.0 / nx))
        discrete = (4.0 / (nx * ny)) * np.sum(strip_peak * half) * np.sum(s_cells)
        continuous = np.pi / 2.0 if bound == "parabolic" else 2.0 * np.pi / 3.0
        peak = peak * (continuous / discrete)
        if not want_fields:
            c_ = np.ascontiguousarray
            kxi, keta, kphi = _tame(xi, eta, phi, L1, L2, L3, np.maximum(a, b))
            Fx, Fy, Mz, adh = _k.fastsim_hertz_batch(
                c_(a), c_(b), c_(peak), c_(mu), c_(L1, dtype=float), c_(L2, dtype=float),
                c_(L3, dtype=float), c_(kxi, dtype=float), c_(keta, dtype=float),
                c_(kphi, dtype=float), t, half, strip_peak, s_cells, first_order)
            info["adhesion_fraction"] = adh if not single else float(adh[0])
            f = None
        else:
            Fx, Fy, Mz = (np.empty(n) for _ in range(3))
            flist = []
            for k in range(n):
                ys, dys, xl, xt = hertz_strips(a[k], b[k], ny)
                vals = (float(L1[k]), float(L2[k]), float(L3[k]), float(mu[k]))
                if (all(v > 0 and math.isfinite(v) for v in vals)
                        and all(math.isfinite(v) for v in (xi[k], eta[k], phi[k]))):
                    # checked inputs: fastsim_strips without its argument checks (same numbers)
                    full = lambda v: np.full(ny, v)  # noqa: E731
                    peaks = np.ascontiguousarray(peak[k] * strip_peak, dtype=float)
                    p = np.ascontiguousarray(peaks[:, None] * s_cells[None, :])  # s_cells: _profile
                    r = _solve_strips(
                        np.ascontiguousarray(ys, dtype=float), np.ascontiguousarray(dys, dtype=float),
                        np.ascontiguousarray(xl, dtype=float), np.ascontiguousarray(xt, dtype=float),
                        p, full(vals[0]), full(vals[1]), full(vals[2]), float(xi[k]),
                        float(eta[k]), float(phi[k]), full(vals[3]), vals[3], scheme, True)
                else:
                    r = fastsim_strips(ys, dys, xl, xt, peak[k] * strip_peak, L1[k], L2[k],
                                       L3[k], xi[k], eta[k], phi[k], mu[k], nx, profile=bound,
                                       scheme=scheme)
                Fx[k], Fy[k], Mz[k] = r.Fx, r.Fy, r.Mz
                flist.append(r.fields)
            f = flist[0] if single else tuple(flist)
            if single:
                info["adhesion_fraction"] = f.adhesion_fraction
        status = Status.CONVERGED
        if single and f is not None and not np.any(f.adhesion):
            status = Status.FULL_SLIP
        out = (lambda v: float(v[0])) if single else (lambda v: np.asarray(v))
        return CreepForcesResult(Fx=out(Fx), Fy=out(Fy), Mz=out(Mz), Fn=out(Fn), mu=out(mu),
                           method=self.name, status=status, iterations=None, fields=f, info=info)

    def solve_patch(self, patch, xi, eta, phi, mu):
        """FASTSIM on one :class:`~wheelrail.patch.ContactPatch`.

        A Hertzian patch is solved as its ellipse (:meth:`solve`, options as
        there). A non-elliptic patch is solved strip by strip
        (:func:`fastsim_strips`) on the patch's own strips with its pressure as
        the traction bound (``bound`` and ``ny`` do not apply; ``nx`` cells per
        strip, resampled from the patch), and one set of flexibilities
        L1, L2, L3 from the patch's equivalent ellipse (Kik & Piotrowski's
        choice of one flexibility per patch; Piotrowski & Chollet (2005) §3.2). ``Mz`` is about
        the patch's centre of pressure; ``fields`` are returned for single
        patches unless ``fields=False``.
        """
        if patch.is_hertzian:
            f = np.asarray
            return self.solve(patch.hertz, f(float(xi)), f(float(eta)), f(float(phi)),
                              f(float(mu)))
        nx, flexibility, scheme, fields = self.nx, self.flexibility, self.scheme, self.fields
        # a virtual-penetration patch may prescribe its own flexibilities (Piotrowski & Chollet (2005) §3):
        # one weighted flexibility per patch (Kik-Piotrowski), per-strip virtual ellipses
        # (Linder, STRIPES), a parabolic traction bound along the strips (Linder)
        pinfo = patch.info
        flexibility = pinfo.get("fastsim_flexibility", flexibility)
        a, b = patch.a, patch.b
        axes = pinfo.get("strip_semiaxes")
        if axes is not None:
            sa, sb = (np.ascontiguousarray(v, dtype=float) for v in axes)
            nu = patch.materials.nu
            ok = False
            if flexibility == "three" and isinstance(nu, float) and sa.size:
                # one kernel (the same table look-up and formulas as below)
                ok, L1, L2, L3, *Lrep = _k.strip_flexibilities(
                    sa, sb, float(patch.materials.G), *_kalker_table(nu))
                Lrep = tuple(Lrep)
            if not ok:
                C11, C22, C23 = _kalker_scalar(sa / sb, nu)
                L1, L2, L3 = flexibilities(sa, sb, patch.materials.G, C11, C22, C23)
                if flexibility == "weighted":
                    L1 = L2 = L3 = weighted_flexibility(L1, L2, L3, xi, eta, phi,
                                                        np.sqrt(sa * sb))
                elif flexibility == "combined":
                    L1 = L2 = L3 = np.array([combined_flexibility(*v, float(xi), float(eta),
                                                                  float(phi), ak)
                                             for *v, ak in zip(L1, L2, L3, sa)])
                Lrep = tuple(_median(v) for v in (L1, L2, L3))
        else:
            C11, C22, C23 = _kalker_scalar(a / b, patch.materials.nu)
            G = float(patch.materials.G)
            L1 = 8.0 * a / (3.0 * G * C11)          # as flexibilities(), scalar
            L2 = 8.0 * a / (3.0 * G * C22)
            L3 = math.pi * a * math.sqrt(a / b) / (4.0 * G * C23)
            if flexibility == "weighted":
                L1 = L2 = L3 = _weighted_scalar(L1, L2, L3, float(xi), float(eta), float(phi),
                                                math.sqrt(a * b))
            elif flexibility == "combined":
                L1 = L2 = L3 = combined_flexibility(L1, L2, L3, float(xi), float(eta),
                                                    float(phi), a)
            Lrep = (L1, L2, L3)
        # pressure resampled from the patch's m cells to nx cells per strip
        sp = np.asarray(patch.strip_pressure, dtype=float)
        m = sp.shape[1]
        i0, i1, w = _resample_weights(m, nx)
        r = self._patch_forces(patch, sp, i0, i1, w, pinfo, L1, L2, L3, xi, eta, phi, mu,
                               scheme, flexibility, Lrep, fields is not False)
        if r is not None:
            return r
        p = sp[:, i0] * (1.0 - w) + sp[:, i1] * w
        scale = sp.sum(axis=1) / m
        got = p.sum(axis=1) / nx
        p *= np.where(got > 0, scale / np.where(got > 0, got, 1.0), 0.0)[:, None]
        if pinfo.get("traction_bound") == "parabolic":
            # same force per strip, parabolic along x (Linder: p0' = 3π p0 / 8)
            dst = (np.arange(nx) + 0.5) / nx
            par = _profile("parabolic", 1.0 - dst * 2.0)
            p = (p.sum(axis=1) / par.sum())[:, None] * par[None, :]
        mu = float(positive("mu", mu))
        ny = p.shape[0]
        xi, eta, phi = float(xi), float(eta), float(phi)

        def strip(v):
            return np.ascontiguousarray(np.broadcast_to(np.asarray(v, dtype=float), (ny,)))

        r = _solve_strips(strip(patch.y), strip(patch.dy), strip(patch.x_lead),
                          strip(patch.x_trail), np.ascontiguousarray(p), strip(L1), strip(L2),
                          strip(L3), xi, eta, phi, np.full(ny, mu), mu, scheme,
                          fields is not False)
        xc, yc = patch.centre
        Mz = r.Mz - xc * r.Fy + yc * r.Fx
        info = dict(r.info, flexibility=flexibility, L=Lrep)
        status = Status.CONVERGED
        if r.fields is not None:
            info["adhesion_fraction"] = r.fields.adhesion_fraction
            if not np.any(r.fields.adhesion):
                status = Status.FULL_SLIP
        return CreepForcesResult(Fx=r.Fx, Fy=r.Fy, Mz=float(Mz), Fn=r.Fn, mu=float(mu),
                           method=self.name, status=status, fields=r.fields, info=info)

    def _patch_forces(self, patch, sp, i0, i1, w, pinfo, L1, L2, L3, xi, eta, phi, mu, scheme,
                      flexibility, Lrep, want_fields):
        """:meth:`solve_patch` for a strip patch in one fused kernel
        (:func:`~wheelrail.tangential._fastsim_kernel.strip_patch_forces`): the same
        equations as the general path (sums in another order: equal to round-off), with
        the same fields if wanted. ``None`` when the creepages are so large that the
        general path must scale them."""
        mu_f = float(mu) if isinstance(mu, (float, int)) else math.nan
        mu = mu_f if math.isfinite(mu_f) and mu_f > 0 else float(positive("mu", mu))
        xi, eta, phi = float(xi), float(eta), float(phi)
        ny = sp.shape[0]
        c_ = np.ascontiguousarray

        def strip(v):
            if isinstance(v, np.ndarray) and v.shape == (ny,) and v.dtype == np.float64:
                return c_(v)
            return c_(np.broadcast_to(np.asarray(v, dtype=float), (ny,)))

        if isinstance(L1, float) and isinstance(L2, float) and isinstance(L3, float):
            Ls = np.empty((3, ny))          # one patch flexibility: three constant rows
            Ls[0], Ls[1], Ls[2] = L1, L2, L3
            L1, L2, L3 = Ls

        nx = int(i0.shape[0])
        y, dy, xl, xt = c_(patch.y), c_(patch.dy), c_(patch.x_lead), c_(patch.x_trail)
        if want_fields:
            p, px, py, sx, sy = (np.zeros((ny, nx)) for _ in range(5))
            slip = np.zeros((ny, nx), dtype=bool)
        else:
            p = px = py = sx = sy = _EMPTY2
            slip = _EMPTY2B
        ok, Fx, Fy, Mz, Fn, xc, yc = _k.strip_patch_forces(
            y, dy, xl, xt, c_(sp), i0, i1, w, pinfo.get("traction_bound") == "parabolic", mu,
            strip(L1), strip(L2), strip(L3), xi, eta, phi, _SLIP_RATE_CAP, _flags(scheme),
            want_fields, p, px, py, sx, sy, slip)
        if not ok:
            return None
        info = {"nx": nx, "ny": ny, "scheme": scheme, "flexibility": flexibility, "L": Lrep}
        status = Status.CONVERGED
        f = None
        if want_fields:          # as _solve_strips
            length = np.clip(xl - xt, 0.0, None)
            empty = length <= 0
            x = strip_cell_centres(xl, xt, nx)
            x[empty] = (0.5 * (xl + xt))[empty, None]
            f = FastsimFields(x=x, y=np.repeat(y[:, None], nx, 1), dx=length / nx, dy=dy,
                              pressure=p, px=px, py=py, sx=sx, sy=sy, slip=slip,
                              mu=np.full(ny, mu))
            info["adhesion_fraction"] = f.adhesion_fraction
            if not np.any(f.adhesion):
                status = Status.FULL_SLIP
        return CreepForcesResult(Fx=float(Fx), Fy=float(Fy), Mz=float(Mz - xc * Fy + yc * Fx),
                           Fn=float(Fn), mu=mu, method=self.name, status=status,
                           fields=f, info=info)
