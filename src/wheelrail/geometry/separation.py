"""Separation of the profiles in the contact plane — input of the non-Hertzian normal solvers.

For one contact point of a wheelset in rigid contact, the wheel and rail
cross-sections are expressed in the contact frame: origin at the contact
point on the rail, ``η`` along the common tangent (lateral coordinate of the
contact plane), ``ζ`` along the common normal (positive into the wheel). The
separation of the profiles is ``f(η) = ζ_wheel(η) − ζ_rail(η)`` (Piotrowski & Chollet (2005),
§3: ``f(y) = z1(y) + z2(y)``) and, for a penetration ``δ0``, the
interpenetration function (Piotrowski & Chollet (2005), eq. 4)::

    g(η) = δ0 − f(η)   where f(η) ≤ δ0,   0 elsewhere.

The undeformed distance on a grid of the contact plane adds the wheel's
longitudinal curvature: a wheel circle of radius ``r(η)`` rises by
``r − √(r² − x²)`` along the wheelset's vertical, i.e. by
``cos(γ − σθ) (r − √(r² − x²))`` along the contact normal (θ roll, σ = ±1 for
right/left), the rail being straight::

    h(x, η) = f(η) + cos(γ − σθ) (r(η) − √(r(η)² − x²)).

Near the contact point this is ``A x² + B η²`` with the curvatures of
:func:`~wheelrail.geometry.contact_points` (Hertz). Yaw enters only through
the location of the contact point (the 2-D distance is evaluated in the
plane of the contact; its O(ψ) skew is neglected).

References
----------
.. [1] J. Piotrowski, H. Chollet, Wheel–rail contact models for vehicle system
   dynamics including multi-point contact, VSD 43 (2005), §3, eqs. (4), (5).
.. [2] W. Kik, J. Piotrowski, A fast, approximate method to calculate normal
   load at contact between wheel and rail and creep forces during rolling,
   2nd Mini-Conference on Contact Mechanics, Budapest 1996.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.interpolate import CubicSpline

from .._validation import as_float_array, non_negative, positive
from ..errors import InputError
from ._checks import check_side
from ._local_cubic import local_cubic
from .contact_search import _SIGMA, silhouette
from .points import contact_points

__all__ = ["Separation", "separation", "separation_at", "undeformed_distance", "interpenetration",
           "undeformed_distance_kernel"]


def interpenetration(f, delta):
    """Interpenetration g = δ0 − f where f ≤ δ0, else 0 (Piotrowski & Chollet (2005), eq. 4) (pure kernel).

    Parameters
    ----------
    f : array_like
        Separation of the profiles [m].
    delta : float
        Virtual penetration δ0 [m], ≥ 0.

    Returns
    -------
    ndarray, shape of ``f``
    """
    f = np.asarray(f, dtype=float)
    return np.where(f <= delta, delta - f, 0.0)


def undeformed_distance_kernel(f, r, cos_factor, x):
    """h(x, η) = f(η) + cos_factor·(r(η) − √(r(η)² − x²)) (pure kernel).

    Parameters
    ----------
    f, r : ndarray, shape (ny,)
        Separation [m] and wheel radius [m] at the lateral positions η.
    cos_factor : float
        Cosine of the angle between the contact normal and the wheelset's vertical.
    x : ndarray, shape (nx,)
        Longitudinal positions [m], |x| < min(r).

    Returns
    -------
    ndarray, shape (nx, ny)
    """
    x = np.asarray(x, dtype=float)[:, None]
    r = np.asarray(r, dtype=float)[None, :]
    return np.asarray(f, dtype=float)[None, :] + cos_factor * (r - np.sqrt(r * r - x * x))


@dataclass(frozen=True)
class Separation:
    """Profile separation around one contact point (frozen, SI).

    Attributes
    ----------
    eta : ndarray, shape (n,)
        Lateral coordinate in the contact plane [m], 0 at the contact point,
        positive towards the side's field side along the tangent.
    f : ndarray, shape (n,)
        Separation of the profiles along the contact normal [m].
    wheel_radius : ndarray, shape (n,)
        Radius of the wheel circle at each η [m].
    cos_factor : float
        cos(γ − σθ): projection of the wheelset vertical on the contact normal.
    contact_angle : float
        γ [rad].
    side : str
    y, yaw : float
        Wheelset lateral shift [m] and yaw [rad].
    point : int
        Index of the contact point in ``contact_points(...).<side>``.
    """

    eta: np.ndarray
    f: np.ndarray
    wheel_radius: np.ndarray
    cos_factor: float
    contact_angle: float
    side: str
    y: float
    yaw: float
    point: int

    def interpenetration(self, delta) -> np.ndarray:
        """g(η) for a virtual penetration ``delta`` [m] (Piotrowski & Chollet (2005), eq. 4)."""
        return interpenetration(self.f, float(non_negative("delta", delta)))

    def distance(self, x) -> np.ndarray:
        """Undeformed distance h(x, η), shape (len(x), len(eta)) [m]."""
        x = as_float_array("x", x)
        if np.any(np.abs(x) >= np.min(self.wheel_radius)):
            raise InputError(f"|x| must be smaller than the wheel radius, got {np.max(np.abs(x))!r} m")
        return undeformed_distance_kernel(self.f, self.wheel_radius, self.cos_factor, np.ravel(x))


def _monotone_window(eta, centre_index):
    """Largest run of strictly increasing eta containing ``centre_index``."""
    dec = np.nonzero(np.diff(eta) <= 0)[0]          # a step k -> k+1 that does not increase
    lo = dec[dec < centre_index]
    hi = dec[dec >= centre_index]
    start = int(lo[-1]) + 1 if lo.size else 0
    stop = int(hi[0]) if hi.size else eta.size - 1
    return slice(start, stop + 1)


def separation(wheelset, track, y, yaw=0.0, *, side="right", point=None, width=0.04, n=401,
               step=2e-4) -> Separation:
    """Separation f(η) of wheel and rail around a contact point, in its contact plane.

    Parameters
    ----------
    wheelset : Wheelset
    track : Track
    y : float
        Lateral shift of the wheelset [m].
    yaw : float
        Yaw angle [rad].
    side : {"left", "right"}
    point : int, optional
        Index of the contact point in ``contact_points(...).<side>`` (default:
        the rigid contact point, smallest separation).
    width : float
        Extent of the η grid [m] (default 40 mm, centred on the point; clipped
        where a profile ends or turns past the normal).
    n : int
        Number of η points.

    Returns
    -------
    Separation

    Examples
    --------
    >>> import wheelrail as wr
    >>> ws = wr.Wheelset(wr.profiles.load("S1002"))
    >>> tr = wr.Track(wr.profiles.load("60E1"))
    >>> sep = wr.geometry.separation(ws, tr, 0.0)
    >>> bool(abs(sep.f[len(sep.f) // 2]) < 1e-9)
    True
    """
    check_side(side)
    width = float(positive("width", width))
    if width > 0.2:
        raise InputError(f"width must be <= 0.2 m, got {width!r}")
    n = int(n)
    if n < 3:
        raise InputError(f"n must be >= 3, got {n!r}")
    cp = contact_points(wheelset, track, y, yaw, step=step)
    pts = cp.side(side)
    k = pts.primary if point is None else int(point)
    if not 0 <= k < pts.n:
        raise InputError(f"point must lie in [0, {pts.n - 1}] for the {side} side, got {point!r}")
    return separation_at(wheelset, track, side, y=cp.y, z=cp.z, roll=cp.roll, yaw=cp.yaw,
                         wheel_y=float(pts.wheel_y[k]), track_y=float(pts.track_y[k]),
                         contact_angle=float(pts.contact_angle[k]), width=width, n=n, point=k)


def separation_at(wheelset, track, side, *, y, z, roll, yaw, wheel_y, track_y, contact_angle,
                  width=0.04, n=401, point=-1, samples=2001) -> Separation:
    """Separation around a point of a wheelset at a given pose (kernel of :func:`separation`).

    Parameters
    ----------
    wheelset, track, side
        As in :func:`separation`.
    y, z, roll, yaw : float
        Pose of the wheelset [m, m, rad, rad] (as in :func:`contact_points`:
        ``z`` is the height of the axle centre above r0 over the top of rail).
    wheel_y : float
        Wheel profile coordinate of the reference point [m].
    track_y : float
        Lateral position of the reference point in the track frame [m].
    contact_angle : float
        γ [rad] of the reference point: the contact plane's orientation.
    width, n
        Extent [m] and number of η samples.
    point : int
        Index stored in the result (−1: not a point of ``contact_points``).
    samples : int
        Profile samples of each body on ±``width`` (2001: 0.04 mm for the default
        width), interpolated at the η nodes by the cubic through the four samples
        around each (:func:`wheelrail.geometry._local_cubic.local_cubic`).

    Returns
    -------
    Separation
        ``f`` is measured from the rail surface at the reference point along
        its normal (not shifted to zero).
    """
    sig = _SIGMA[side]
    gam = float(contact_angle)
    t = np.array([np.cos(gam), np.sin(gam)])
    nrm = np.array([-np.sin(gam), np.cos(gam)])
    rc = track.curve(side)
    u_c = sig * float(track_y)
    C = np.array([u_c, float(rc.eval(u_c, 0)[0])])
    # dense samples of both curves around the point (0.04 mm apart for the default width)
    m = int(samples)
    wc = wheelset.curve(side)
    s = np.linspace(max(wc.u_min, wheel_y - width), min(wc.u_max, wheel_y + width), m)
    p, p1 = wc.eval(s, 1)
    one = np.ones_like(s)
    _, Yw, Zw, rw = silhouette(s, p, p1, wheelset.nominal_radius, wheelset.e_tape, sig,
                               y * one, (wheelset.nominal_radius + z) * one, roll * one,
                               yaw * one)
    uw = sig * Yw
    ur = np.linspace(max(rc.u_min, u_c - width), min(rc.u_max, u_c + width), m)
    (zr,) = rc.eval(ur, 0)
    ew, zw = (uw - C[0]) * t[0] + (Zw - C[1]) * t[1], (uw - C[0]) * nrm[0] + (Zw - C[1]) * nrm[1]
    er, zrr = (ur - C[0]) * t[0] + (zr - C[1]) * t[1], (ur - C[0]) * nrm[0] + (zr - C[1]) * nrm[1]
    sw = _monotone_window(ew, int(np.argmin(np.abs(ew))))
    sr = _monotone_window(er, int(np.argmin(np.abs(er))))
    lo = max(-0.5 * width, ew[sw][0], er[sr][0])
    hi = min(0.5 * width, ew[sw][-1], er[sr][-1])
    eta = np.linspace(lo, hi, n)
    W = local_cubic(np.ascontiguousarray(ew[sw]), np.ascontiguousarray(
        np.stack([zw[sw], rw[sw]])), eta)
    fw, r = W[0], W[1]
    fr = local_cubic(np.ascontiguousarray(er[sr]), np.ascontiguousarray(zrr[sr])[None, :],
                     eta)[0]
    cosf = float(np.cos(gam - sig * roll))
    return Separation(eta, fw - fr, r, cosf, gam, side, float(y), float(yaw), int(point))


def undeformed_distance(wheelset, track, y, x, eta=None, yaw=0.0, *, side="right", point=None,
                        width=0.04, n=401, step=2e-4) -> np.ndarray:
    """Undeformed distance h(x, η) on a grid of the contact plane (plain array).

    Parameters
    ----------
    wheelset, track, y, yaw, side, point, width, n
        As in :func:`separation`.
    x : array_like, shape (nx,)
        Longitudinal coordinates [m] (rolling direction, 0 at the contact point).
    eta : array_like, shape (ny,), optional
        Lateral coordinates in the contact plane [m]; default
        ``separation(...).eta``. Values outside the available range raise.

    Returns
    -------
    ndarray, shape (nx, ny)
        h(x, η) [m] = f(η) + cos(γ − σθ)(r(η) − √(r(η)² − x²)).
    """
    sep = separation(wheelset, track, y, yaw, side=side, point=point, width=width, n=n, step=step)
    if eta is None:
        return sep.distance(x)
    eta = np.ravel(as_float_array("eta", eta))
    if eta.min() < sep.eta[0] - 1e-12 or eta.max() > sep.eta[-1] + 1e-12:
        raise InputError(f"eta must lie in [{sep.eta[0]!r}, {sep.eta[-1]!r}] m (the extent of "
                         "the profiles around this contact point)")
    f = CubicSpline(sep.eta, sep.f)(eta)
    r = CubicSpline(sep.eta, sep.wheel_radius)(eta)
    x = np.ravel(as_float_array("x", x))
    if np.any(np.abs(x) >= np.min(r)):
        raise InputError(f"|x| must be smaller than the wheel radius, got {np.max(np.abs(x))!r} m")
    return undeformed_distance_kernel(f, r, sep.cos_factor, x)
