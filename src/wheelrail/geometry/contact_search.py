"""Rigid wheel–rail contact search: wheelset roll and height, all contact points.

Problem (Bosso et al. (2013), ch. 2, §2.1.1, eqs. 2.1–2.3)
----------------------------------------------------------
For a prescribed lateral shift ``y`` and yaw angle ``ψ`` of the wheelset the
rigid contact constraint ``min d = 0`` on **both** sides fixes the roll angle
``θ(y, ψ)`` (eq. 2.1) and the vertical position ``z(y, ψ)`` (eq. 2.2). The
distance ``d`` is evaluated on the whole profile, and *every* local minimum of
``d`` is reported with its separation, so that two- and three-point contact
(Piotrowski & Chollet (2005), fig. 1) is detected: points whose separation is below a tolerance
are potential contact points (they carry load in an elastic model).

Frames and signs (see :mod:`wheelrail.geometry.wheelset`, :mod:`~wheelrail.geometry.track`)
--------------------------------------------------------------------------------------------
Track frame: ``x`` running direction, ``y`` lateral to the right, ``z`` up;
wheelset pose: lateral shift ``y`` [m], height ``z`` [m] of the axle centre
above ``r0`` over the top-of-rail plane (``z = 0`` when a wheel of radius r0
stands on top of rail), roll ``θ`` [rad] positive when the **right wheel is
higher**, yaw ``ψ`` [rad] positive when the wheelset turns clockwise seen from
above (the right wheel moves backwards, the axle's front points to the right).
The orientation is ``R = R_z(ψ) R_x(θ)``. Contact angles ``γ`` are measured in
each side's own profile orientation: positive when the contact normal on the
wheel points towards the field side (flange contact: large positive γ; a
1:40 inclined rail under a 1:40 tread: γ ≈ +0.025).

Yaw — contact locus
-------------------
A wheel is a body of revolution about the axle and the rail a prismatic body
along ``x``; at contact the wheel normal must therefore have no
``x``-component. On the circle of wheel profile coordinate ``s`` (radius
``r(s) = r0 − z_w(s)``, axial position ``a``) with surface normal
``(sin φ, −r'(a), −cos φ)`` in wheelset axes, this gives after the rotation

    sin φ cos ψ − cos φ sin θ sin ψ = −r'(a) cos θ sin ψ,

one angle ``φ(s)`` per circle: the *contact locus* (Wang 1984; Duffek 1982).
Its projection on the (y, z) plane is the silhouette of the yawed wheel seen
along the rail, which is compared with the rail profile. To first order the
contact point lies ``x_c ≈ r sin φ ≈ r tan ψ (θ − r'(a))`` ahead of the
vertical plane through the wheel centre, i.e. ``x_c ≈ −r tan ψ tan γ_a`` with
``tan γ_a = r'(a)`` the slope of the radius along the axle (for zero roll);
for ψ = 0 the contact lies in the plane x = 0 and the problem is exactly 2-D.

Distance and curvatures
-----------------------
``d`` is the vertical distance from each wheel (silhouette) point to the rail
below it; at a local minimum the tangents are parallel and the normal
separation is ``d cos γ`` (reported as ``separation``; exact at contact,
first order in d for secondary points). Principal curvatures at a point:
wheel along the rolling direction ``cos β / r`` (β = atan z_w' the profile
slope; Meusnier), wheel across ``κ_w = z_w''/(1 + z_w'²)^{3/2}`` (convex wheel
positive, a hollow tread or the flange root negative), rail across
``κ_r = −z_r''/(1 + z_r'²)^{3/2}`` (crowned head positive), rail along 0
(straight track). Hertz input: ``A = ½ cos β / r``, ``B = ½(κ_w + κ_r)``.
The wheel's cross curvature is the profile curvature also under yaw (error
O(ψ)).

Profiles are represented by interpolating cubic splines (re-sampled every
0.05 mm), so the distance is smooth and the location of a minimum does not
jump between grid points; minima are located on a grid of step ``step``
along the wheel profile and refined by successive parabolic interpolation.

References
----------
.. [1] Review of wheel–rail contact models (Bosso et al. (2013), ch. 2), §2.1.1, eqs. (2.1)–(2.3).
.. [2] J. Piotrowski, H. Chollet, Wheel–rail contact models for vehicle system
   dynamics including multi-point contact, VSD 43 (2005) 455–483, fig. 1.
.. [3] K. Wang, The track of wheel contact points and the calculation of
   wheel/rail geometric contact parameters, J. Southwest Jiaotong Univ. 1
   (1984) 89–99 (contact locus); W. Kik, J. Piotrowski, A fast approximate
   method to calculate normal load at contact between wheel and rail and
   creep forces during rolling, 2nd Mini-Conf. on Contact Mechanics, 1996.
.. [4] K.L. Johnson, Contact Mechanics, CUP 1985, §4.1 (principal curvatures).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

from ..errors import ConvergenceError, InputError
from ._checks import SIDES
from ._curves import curvature
from ._search_kernels import (
    _BASIN,
    _BASIN_MARGIN,
    _REFINE_MAX_ITER,
    POINT_ROWS,
    global_min_rows,
    grid_gap_row,
    newton_rows,
    order_points,
    point_data_rows,
    refine_rows,
    select_minima,
)
from .track import Track
from .wheelset import Wheelset

__all__ = ["SIDES", "POINT_FIELDS", "STATUS", "ContactWarning", "RigidRows", "solve_rigid",
           "solve_rigid_rows", "classify_rows", "flange_geometry", "find_points", "silhouette"]


class ContactWarning(UserWarning):
    """A contact was found but is flagged: flange climbing or a derailed wheel."""

_SIGMA = {"left": -1.0, "right": 1.0}
_BIG = 1.0          # gap [m] assigned where no rail lies below the wheel
_EDGE = 2e-4        # distance [m] kept from the ends of the wheel profile
_MERGE = 1e-7       # minima separated by a hump lower than this [m] are one minimum
_MAX_YAW = 0.2      # |yaw| limit [rad]

#: Per-point quantities (name, unit, description); arrays of shape (n,) or (n_y, n_point).
POINT_FIELDS = {
    "wheel_y": ("m", "lateral position on the wheel profile (profile frame)"),
    "wheel_z": ("m", "height on the wheel profile (profile frame)"),
    "rail_y": ("m", "lateral position on the rail profile (profile frame, uncanted)"),
    "rail_z": ("m", "height on the rail profile (profile frame, uncanted)"),
    "track_y": ("m", "lateral position of the contact point in the track frame"),
    "track_z": ("m", "height of the wheel contact point in the track frame"),
    "x": ("m", "longitudinal offset of the contact point ahead of the wheel circle centre"),
    "contact_angle": ("rad", "contact angle, positive towards the flange"),
    "rolling_radius": ("m", "wheel radius at the contact point"),
    "wheel_curvature_x": ("1/m", "wheel curvature along the rolling direction cos(beta)/r"),
    "wheel_curvature_y": ("1/m", "wheel profile curvature (convex positive)"),
    "rail_curvature_y": ("1/m", "rail profile curvature (convex positive)"),
    "A": ("1/m", "Hertz combined curvature along x"),
    "B": ("1/m", "Hertz combined curvature along y"),
    "separation": ("m", "undeformed normal separation (0 at the rigid contact point)"),
    "gap": ("m", "vertical distance wheel - rail"),
}


# --------------------------------------------------------------------------- kernels
def silhouette(s, p, p1, r0, e_tape, sigma, y, zc, theta, psi):
    """Wheel contact locus (silhouette seen along x) in the track frame (pure kernel).

    Parameters
    ----------
    s, p, p1 : ndarray
        Wheel profile coordinate [m], profile height z_w(s) [m] and slope.
    r0, e_tape, sigma : float
        Nominal radius [m], tape-circle half distance [m], +1 right / −1 left.
    y, zc, theta, psi : ndarray
        Pose: lateral shift [m], height of the axle centre [m], roll, yaw [rad];
        all arrays broadcast together.

    Returns
    -------
    x_rel, Y, Z, r : ndarray
        Longitudinal offset from the circle centre [m], lateral position and
        height in the track frame [m], radius of the circle [m].
    """
    r = r0 - p
    a = sigma * (e_tape + s)
    st, ct = np.sin(theta), np.cos(theta)
    if np.all(psi == 0.0):
        yp = a * ct + r * st
        zp = a * st - r * ct
        return np.zeros(np.broadcast(yp, zp).shape), y + yp, zc + zp, r
    sp, cp = np.sin(psi), np.cos(psi)
    r_a = -sigma * p1
    Bc = -st * sp
    C = -r_a * ct * sp
    R = np.hypot(cp, Bc)
    phi = np.arcsin(np.clip(C / R, -1.0, 1.0)) - np.arctan2(Bc, cp)
    sf, cf = np.sin(phi), np.cos(phi)
    xb = r * sf
    yp = a * ct + r * cf * st
    zp = a * st - r * cf * ct
    X_rel = xb * cp - r * cf * st * sp
    return X_rel, y + xb * sp + yp * cp, zc + zp, r


def _gap(ws, tr, side, s, y, zc, th, psi):
    """Vertical gap wheel − rail at wheel coordinates ``s`` (arrays broadcast)."""
    wc = ws.curve(side)
    p, p1 = wc.eval(s, 1)
    sig = _SIGMA[side]
    _, Y, Z, _ = silhouette(s, p, p1, ws.nominal_radius, ws.e_tape, sig, y, zc, th, psi)
    rc = tr.curve(side)
    u = sig * Y
    (zr,) = rc.eval(u, 0)
    d = Z - zr
    return np.where((u < rc.u_min) | (u > rc.u_max), _BIG, d)


def _gapfun(ws, tr, side, y, zc, th, psi):
    """Gap as a function of stacked wheel coordinates (length a multiple of the pose length)."""
    n = np.size(y)
    y, zc, th, psi = (np.broadcast_to(np.asarray(v, dtype=float), (n,)) for v in (y, zc, th, psi))

    def fun(s):
        k = s.size // n
        return _gap(ws, tr, side, s, np.tile(y, k), np.tile(zc, k), np.tile(th, k),
                    np.tile(psi, k))
    return fun


def _parabolic(fun, s0, h, lo, hi, levels=5):
    """Successive parabolic interpolation of a minimum of ``fun`` near ``s0`` (vectorised).

    Each level fits a parabola through ``s − h, s, s + h`` (one call of ``fun``
    on the stacked points), moves to its vertex (at most ``h``) and divides
    ``h`` by 8; five levels from the grid step 0.2 mm reach ~0.1 µm. The best
    point evaluated so far is returned, so a kink of the distance (a jump of
    a profile's curvature) cannot make the result worse than the grid point.
    A level whose centre is not the best point so far (the parabola's vertex
    missed the minimum of a strongly asymmetric gap, e.g. at the flange root
    near a jump of the contact point) does not count: the search moves to the
    best point with the same ``h`` (at most :data:`_REFINE_MAX_ITER` levels), so the
    minimum stays within reach instead of being left ``h`` away. Returns (s, f).
    """
    s = np.asarray(s0, dtype=float).copy()
    n = s.size
    h = np.broadcast_to(np.asarray(h, dtype=float), (n,)).copy()
    done = np.zeros(n, dtype=int)
    best_s = s.copy()
    best_f = np.full(n, np.inf)
    for _ in range(_REFINE_MAX_ITER):
        active = done < levels
        if not np.any(active):
            break
        sm, sp = np.maximum(s - h, lo), np.minimum(s + h, hi)
        f = fun(np.concatenate([sm, s, sp]))
        fm, f0, fp = f[:n], f[n:2 * n], f[2 * n:]
        for cand_s, cand_f in ((s, f0), (sm, fm), (sp, fp)):
            better = active & (cand_f < best_f)
            best_s = np.where(better, cand_s, best_s)
            best_f = np.where(better, cand_f, best_f)
        den = fm - 2.0 * f0 + fp
        with np.errstate(divide="ignore", invalid="ignore"):
            shift = np.where(den > 0.0, 0.5 * h * (fm - fp) / den, np.where(fm < fp, -h, h))
        # a centred level moves to the parabola's vertex and refines; otherwise continue
        # from the best point with the same step
        centred = active & (best_s == s)
        s = np.where(centred, np.clip(s + np.clip(shift, -h, h), lo, hi),
                     np.where(active, best_s, s))
        h = np.where(centred, h / 8.0, h)
        done = done + centred
    f = fun(s)
    keep = f <= best_f
    return np.where(keep, s, best_s), np.where(keep, f, best_f)


def _refine(fun, s0, h, lo, hi, levels=5):
    """The lowest minimum of ``fun`` within ``h`` (the grid step) of the grid points ``s0``.

    :func:`_parabolic` from ``s0``, then a scan of ``[s0 − h, s0 + h]`` at ``h/8``
    (:data:`_BASIN`): near a jump of the contact point the gap has two minima in one
    grid cell (0.13 mm apart for S1002/60E1 at y ≈ 6.25 mm), and the parabola finds the
    one nearer its start. A sub-grid point lower than the refined minimum by more than
    :data:`_BASIN_MARGIN` is refined from there with ``h/8``, the lower result kept.
    """
    s0 = np.asarray(s0, dtype=float)
    n = s0.size
    s1, f1 = _parabolic(fun, s0, h, lo, hi, levels)
    hs = h / _BASIN
    k = np.arange(-_BASIN, _BASIN + 1)
    sk = np.clip(s0[None, :] + k[:, None] * hs, lo, hi)           # (2 _BASIN + 1, n)
    fk = fun(sk.reshape(-1)).reshape(sk.shape)
    j = np.argmin(fk, axis=0)
    cols = np.arange(n)
    other = fk[j, cols] < f1 - _BASIN_MARGIN
    if not np.any(other):
        return s1
    s2, f2 = _parabolic(fun, sk[j, cols], hs, lo, hi, levels)
    return np.where(other & (f2 < f1), s2, s1)


def _refine_fast(ws, tr, side, step, s0, y, zc, th, psi, levels=5):
    """:func:`_refine` of the gap of ``side`` from the grid points ``s0`` (one pose each,
    arrays of shape (n,)), compiled (:func:`wheelrail.geometry._search_kernels.refine_rows`)."""

    n = np.size(s0)
    arr = lambda v: np.ascontiguousarray(np.broadcast_to(np.asarray(v, dtype=float), (n,)))  # noqa: E731
    return refine_rows(*_side_args(ws, tr, side, step), arr(s0), arr(y), arr(zc), arr(th),
                       arr(psi), int(levels), _BIG)


def _grid(ws, side, step):
    wc = ws.curve(side)
    lo, hi = wc.u_min + _EDGE, wc.u_max - _EDGE
    n = max(int(np.ceil((hi - lo) / step)) + 1, 16)
    s = np.linspace(lo, hi, n)
    return s, lo, hi, s[1] - s[0]


_GRID_CACHE: dict = {}


def _grid_profile(ws, side, step):
    """Wheel height and slope on the search grid (cached per wheel curve and step)."""
    wc = ws.curve(side)
    key = (id(wc), step)
    hit = _GRID_CACHE.get(key)
    if hit is None or hit[0] is not wc:
        s = _grid(ws, side, step)[0]
        hit = (wc, *wc.eval(s, 1))
        if len(_GRID_CACHE) > 64:
            _GRID_CACHE.clear()
        _GRID_CACHE[key] = hit
    return hit[1], hit[2]


@dataclass(frozen=True)
class _Pose:
    y: np.ndarray
    z: np.ndarray
    roll: np.ndarray
    yaw: np.ndarray

    def zc(self, ws):
        return ws.nominal_radius + self.z


@njit(cache=True)
def _grid_gap_kernel(s, p, p1, r0, e_tape, sig, y, zc, th, psi, u0, hu, c, big):  # pragma: no cover
    """Vertical gap on the search grid for many poses (numba kernel; see :func:`silhouette`).

    ``u0``, ``hu`` and ``c`` (4, m) describe the rail spline on an equidistant grid;
    each row is :func:`wheelrail.geometry._search_kernels.grid_gap_row`.
    """
    out = np.empty((y.size, s.size))
    for k in range(y.size):
        grid_gap_row(s, p, p1, r0, e_tape, sig, y[k], zc[k], th[k], psi[k], u0, hu, c, big,
                     out[k])
    return out


def _grid_gap(ws, tr, side, pose, step):
    """Gap on the search grid, shape (n_rows, n_grid), and the grid (s, lo, hi, h)."""
    args = _side_args(ws, tr, side, step)    # grid, wheel heights and splines (cached)
    s, p, p1, lo, hi, h = args[:6]
    ru, rc, rh = args[9], args[11], args[12]
    n = np.size(pose.y)
    arr = lambda v: np.ascontiguousarray(np.broadcast_to(np.asarray(v, dtype=float), (n,)))  # noqa: E731
    d = _grid_gap_kernel(s, p, p1, ws.nominal_radius, ws.e_tape, _SIGMA[side], arr(pose.y),
                         arr(pose.zc(ws)), arr(pose.roll), arr(pose.yaw), float(ru[0]), rh, rc,
                         _BIG)
    return d, (s, lo, hi, h)


def _interior_minima(d):
    """Mask (n_rows, n_grid − 2) of the interior grid minima of ``d`` off the rail ends."""
    return ((d[:, 1:-1] < d[:, :-2]) & (d[:, 1:-1] <= d[:, 2:])
            & (d[:, :-2] < _BIG) & (d[:, 2:] < _BIG))


def _side_args(ws, tr, side, step):
    """Arguments of the compiled search kernels for one side (cached per wheel/rail curve).

    ``(s, p, p1, lo, hi, h, wheel u, 1/h_w, wheel c, rail u, 1/h_r, rail c, h_r, r0, e_tape, σ)``
    (see :mod:`wheelrail.geometry._search_kernels`).
    """
    wc, rc = ws.curve(side), tr.curve(side)
    key = (id(wc), id(rc), step, ws.nominal_radius, ws.e_tape, side)
    hit = _ARGS_CACHE.get(key)
    if hit is not None and hit[0] is wc and hit[1] is rc:
        return hit[2]
    s, lo, hi, h = _grid(ws, side, step)
    p, p1 = _grid_profile(ws, side, step)
    spline = lambda cv: (np.ascontiguousarray(cv.u, dtype=float),  # noqa: E731
                         1.0 / cv._h if cv._h else 0.0, np.ascontiguousarray(cv.c, dtype=float))
    args = (np.ascontiguousarray(s), np.ascontiguousarray(p), np.ascontiguousarray(p1),
            float(lo), float(hi), float(h), *spline(wc), *spline(rc), float(rc._h),
            float(ws.nominal_radius), float(ws.e_tape), _SIGMA[side])
    if len(_ARGS_CACHE) > 64:
        _ARGS_CACHE.clear()
    _ARGS_CACHE[key] = (wc, rc, args)
    return args


_ARGS_CACHE: dict = {}


def _global_min(ws, tr, side, pose, step, levels=5):
    """Refined global minimum of the gap per row: (s*, d*, lever) (see :func:`solve_rigid`).

    The gap on the search grid, its two lowest local minima (near a jump of
    the contact point the lower grid value may belong to the branch whose
    refined minimum is higher) refined by parabolic interpolation
    (:func:`_refine`), the lower kept; ``lever`` is the sensitivity of the
    gap to the roll angle: the point moves by (−(Z − zc), Y − y) dθ in (y, z)
    and the rail below it rises by its slope times the lateral motion.
    Compiled (:func:`wheelrail.geometry._search_kernels.global_min_rows`).
    """

    n = np.size(pose.y)
    arr = lambda v: np.ascontiguousarray(np.broadcast_to(np.asarray(v, dtype=float), (n,)))  # noqa: E731
    return global_min_rows(*_side_args(ws, tr, side, step), arr(pose.y), arr(pose.zc(ws)),
                           arr(pose.roll), arr(pose.yaw), int(levels), _BIG)


#: Row status codes of :func:`solve_rigid_rows` and of contact tables (``status`` variable).
STATUS = {0: "ok", 1: "flange_climb", 2: "derailed", 3: "no_contact", 4: "not_converged"}
STATUS_CODE = {v: k for k, v in STATUS.items()}
#: Roll bracket [rad] searched by the fall-back solver (±9.7°: far beyond derailment).
_ROLL_BRACKET = 0.17
#: Largest Newton step in roll [rad] and height [m] (damping).
_MAX_DTH, _MAX_DZ = 0.02, 0.01


@dataclass(frozen=True)
class RigidRows:
    """Rigid pose of many rows with a per-row status (frozen; see :func:`solve_rigid_rows`).

    Attributes
    ----------
    z, roll : ndarray, shape (n,)
        Height of the axle centre [m] and roll [rad]; NaN where not solved.
    wheel_y : dict
        ``{"left": s, "right": s}`` wheel coordinates of the rigid contact
        points [m], shape (n,); NaN where not solved.
    status : ndarray of int, shape (n,)
        :data:`STATUS` code: 0 ok, 3 no contact (a wheel lies entirely beside
        its rail), 4 not converged. (Codes 1 and 2 are set by
        :func:`classify_rows`.)
    reason : tuple of str, length n
        Empty for ok rows, else one line naming the row and the cause.
    residual : ndarray, shape (n,)
        Largest |min gap| of the two sides at the returned pose [m].
    """

    z: np.ndarray
    roll: np.ndarray
    wheel_y: dict
    status: np.ndarray
    reason: tuple
    residual: np.ndarray

    @property
    def ok(self) -> np.ndarray:
        """Mask of the solved rows."""
        return self.status < 3


def _newton(ws, tr, y, yaw, z, th, step, tol, maxiter):
    """Damped Newton iteration on (z, θ) for the rows ``y`` (see :func:`solve_rigid`).

    Returns z, θ, wheel coordinates, residual and a code per row (0 converged,
    3 a wheel beside its rail at some iterate, 4 not converged). The gap minima
    are refined on 3 levels until a row's residual falls below ``tol``, then on
    5 (shared by the active rows). Compiled
    (:func:`wheelrail.geometry._search_kernels.newton_rows`).
    """

    c = lambda v: np.ascontiguousarray(v, dtype=float)  # noqa: E731
    return newton_rows(_side_args(ws, tr, "left", step), _side_args(ws, tr, "right", step),
                       c(y), c(yaw), c(z), c(th), float(ws.nominal_radius), float(tol),
                       int(maxiter), _MAX_DTH, _MAX_DZ, _BIG)


def _min_gaps(ws, tr, y, yaw, th, step, levels=5):
    """Refined minimum gaps (left, right) and wheel coordinates at z = 0 for the poses."""
    pose = _Pose(y, np.zeros_like(y), th, yaw)
    sL, gL, _ = _global_min(ws, tr, "left", pose, step, levels)
    sR, gR, _ = _global_min(ws, tr, "right", pose, step, levels)
    return sL, gL, sR, gR


def _bracketed(ws, tr, y, yaw, th0, step, tol):
    """Fall-back solver: root of f(θ) = g_left(θ) − g_right(θ) by bisection (vectorised).

    The vertical gaps of both sides shift equally with the height z, so the
    roll satisfying the constraint is a root of f alone, after which
    ``z = −g_left``. f is continuous (a minimum over the profile) and
    decreases overall with θ (rolling lifts the right wheel); a sign change
    is searched on a grid of roll angles in ±:data:`_ROLL_BRACKET` (the one
    nearest to ``th0``), then bisected. Returns z, θ, wheel coordinates,
    residual and a code per row (0 solved, 3 a wheel beside its rail at every
    roll of the bracket, 5 no sign change: wherever both wheels lie above
    their rails, one of them cannot touch).
    """
    n = y.size
    grid = np.linspace(-_ROLL_BRACKET, _ROLL_BRACKET, 35)
    m = grid.size
    Y, P, T = np.repeat(y, m), np.repeat(yaw, m), np.tile(grid, n)
    _, gL, _, gR = _min_gaps(ws, tr, Y, P, T, step, levels=3)
    valid = ((gL < _BIG) & (gR < _BIG)).reshape(n, m)
    f = (gL - gR).reshape(n, m)
    code = np.full(n, 4, dtype=np.int8)
    lo, hi = np.zeros(n), np.zeros(n)
    for i in range(n):
        cand = np.flatnonzero(valid[i, :-1] & valid[i, 1:] & (np.sign(f[i, :-1]) != np.sign(f[i, 1:])))
        if cand.size == 0:
            code[i] = 3 if not np.any(valid[i]) else 5
            continue
        k = cand[np.argmin(np.abs(0.5 * (grid[cand] + grid[cand + 1]) - th0[i]))]
        lo[i], hi[i] = grid[k], grid[k + 1]
        code[i] = 0
    idx = np.flatnonzero(code == 0)
    z, th = np.full(n, np.nan), np.full(n, np.nan)
    sLo, sRo, res = np.full(n, np.nan), np.full(n, np.nan), np.full(n, np.inf)
    if idx.size:
        a, b = lo[idx], hi[idx]
        _, gLa, _, gRa = _min_gaps(ws, tr, y[idx], yaw[idx], a, step)
        fa = gLa - gRa
        for _ in range(48):
            mid = 0.5 * (a + b)
            _, gLm, _, gRm = _min_gaps(ws, tr, y[idx], yaw[idx], mid, step)
            fm = gLm - gRm
            same = np.sign(fm) == np.sign(fa)
            a, fa = np.where(same, mid, a), np.where(same, fm, fa)
            b = np.where(same, b, mid)
        t = 0.5 * (a + b)
        sL, gL1, sR, gR1 = _min_gaps(ws, tr, y[idx], yaw[idx], t, step)
        bad = (gL1 >= _BIG) | (gR1 >= _BIG)
        th[idx], z[idx] = t, -0.5 * (gL1 + gR1)
        sLo[idx], sRo[idx] = sL, sR
        res[idx] = np.where(bad, np.inf, 0.5 * np.abs(gL1 - gR1))
        code[idx[bad]] = 3
    return z, th, sLo, sRo, res, code


def _edge_hint(ws, tr, y, z, th, psi, s, margin=5e-4):
    """Reason suffix when a contact point lies at the end of a rail profile (an edge)."""
    hints = []
    for side in SIDES:
        if not np.isfinite(s[side]) or not np.isfinite(z) or not np.isfinite(th):
            continue
        p, p1 = ws.curve(side).eval(np.array([s[side]]), 1)
        _, Y, _, _ = silhouette(np.array([s[side]]), p, p1, ws.nominal_radius, ws.e_tape,
                                _SIGMA[side], y, ws.nominal_radius + z, th, psi)
        u = float(_SIGMA[side] * Y[0])
        rc = tr.curve(side)
        if u - rc.u_min < margin or rc.u_max - u < margin:
            hints.append(side)
    if not hints:
        return ""
    return (f"; the {' and '.join(hints)} wheel touches the end of its rail profile (an edge "
            "where the profile data stop: extend the rail profile)")


def solve_rigid_rows(ws: Wheelset, tr: Track, y, yaw, *, step=2e-4, tol=1e-10, maxiter=60,
                     z0=None, roll0=None) -> RigidRows:
    """Roll and height satisfying ``min d = 0`` on both sides, row by row, never raising.

    The same problem as :func:`solve_rigid` (Bosso et al. (2013), ch. 2, eqs. 2.1–2.3); every
    row gets a status instead of one bad row aborting all of them. A damped
    Newton iteration is tried first; rows where it fails are solved by the
    bracketed fall-back (bisection on the roll angle, see :func:`_bracketed`),
    which converges wherever a pose with both wheels on their rails exists
    within ±0.17 rad of roll. Rows whose wheel lies beside its rail at every
    roll get status 3 (``"no_contact"``), rows without a solution status 4
    (``"not_converged"``), both with a reason.

    Parameters
    ----------
    y, yaw : ndarray, shape (n,)
        Lateral shifts [m] and yaw angles [rad].
    z0, roll0 : ndarray, optional
        Starting values [m], [rad] (e.g. from neighbouring rows).

    Returns
    -------
    RigidRows
    """
    y = np.atleast_1d(np.asarray(y, dtype=float))
    yaw = np.ascontiguousarray(np.broadcast_to(np.asarray(yaw, dtype=float), y.shape))
    z = np.zeros_like(y) if z0 is None else np.array(z0, dtype=float).reshape(y.shape)
    th = np.zeros_like(y) if roll0 is None else np.array(roll0, dtype=float).reshape(y.shape)
    z, th, sL, sR, res, code = _newton(ws, tr, y, yaw, z, th, step, tol, maxiter)
    retry = np.flatnonzero(code != 0)
    if retry.size and (z0 is not None or roll0 is not None):
        # a poor starting value (e.g. between two rows on both sides of a jump): restart at zero
        z1, th1, sL1, sR1, res1, code1 = _newton(ws, tr, y[retry], yaw[retry],
                                                 np.zeros(retry.size), np.zeros(retry.size),
                                                 step, tol, maxiter)
        for arr, new in ((z, z1), (th, th1), (sL, sL1), (sR, sR1), (res, res1), (code, code1)):
            arr[retry] = new
        retry = np.flatnonzero(code != 0)
    if retry.size:
        z2, th2, sL2, sR2, res2, code2 = _bracketed(ws, tr, y[retry], yaw[retry],
                                                    np.nan_to_num(th[retry]), step, tol)
        solved = code2 == 0
        # the bisection's residual is limited by the refinement of the gap minimum
        code2 = np.where(solved & (res2 > max(1e3 * tol, 1e-8)), 4, code2)
        for arr, new in ((z, z2), (th, th2), (sL, sL2), (sR, sR2), (res, res2), (code, code2)):
            arr[retry] = new
    reason = []
    for i in range(y.size):
        if code[i] == 0:
            reason.append("")
        elif code[i] == 5:
            code[i] = 3
            reason.append(f"y = {float(y[i]):.6g} m: no contact on both sides — at every roll "
                          f"angle within ±{_ROLL_BRACKET} rad at which both wheels lie above "
                          "their rails, one wheel cannot touch its rail (a wheel beside its "
                          "rail, or a wheel profile origin not on the tape circle?)")
        elif code[i] == 3:
            reason.append(f"y = {float(y[i]):.6g} m: a wheel lies entirely beside its rail "
                          "(lateral shift too large for these profiles)")
        else:
            reason.append(f"y = {float(y[i]):.6g} m: rigid contact constraint did not converge "
                          f"(residual {float(res[i]):.3g} m)"
                          + _edge_hint(ws, tr, y[i], z[i], th[i], yaw[i],
                                       {"left": sL[i], "right": sR[i]}))
    bad = code != 0
    for arr in (z, th, sL, sR):
        arr[bad] = np.nan
    return RigidRows(z, th, {"left": sL, "right": sR}, code.astype(np.int8), tuple(reason), res)


def solve_rigid(ws: Wheelset, tr: Track, y, yaw, *, step=2e-4, tol=1e-10, maxiter=60,
                z0=None, roll0=None):
    """Roll and height satisfying ``min d = 0`` on both sides (Bosso et al. (2013), ch. 2, eqs. 2.1–2.3).

    Newton iteration on (z, θ): raising the wheelset by Δz and rolling it by Δθ
    about its centre moves a wheel point by ``(−(Z − zc)Δθ, Δz + (Y − y)Δθ)``
    in (y, z); the gap to a rail of slope ``t`` changes by
    ``Δz + [(Y − y) + t (Z − zc)]Δθ`` (envelope theorem: the minimising point
    may be held fixed). The steps are damped, and rows where Newton fails are
    solved by bisection on the roll angle (see :func:`solve_rigid_rows`,
    which returns a per-row status instead of raising).

    Parameters
    ----------
    y, yaw : ndarray, shape (n,)

    z0, roll0 : ndarray, optional
        Starting values (e.g. from neighbouring table rows).

    Returns
    -------
    z, roll : ndarray, shape (n,)
    wheel_y : dict
        ``{"left": s, "right": s}``: wheel coordinate [m] of the rigid contact
        point (refined global minimum of the gap) of each side, shape (n,).

    Raises
    ------
    InputError
        A wheel lies entirely beside its rail for some row.
    ConvergenceError
        No pose satisfies the constraint for some row.
    """
    rows = solve_rigid_rows(ws, tr, y, yaw, step=step, tol=tol, maxiter=maxiter, z0=z0,
                            roll0=roll0)
    bad = np.flatnonzero(rows.status != 0)
    if bad.size:
        i = bad[0]
        err = InputError if rows.status[i] == 3 else ConvergenceError
        raise err(rows.reason[i])
    return rows.z, rows.roll, rows.wheel_y


_FLANGE_CACHE: dict = {}


def flange_geometry(ws, side):
    """Flange of the wheel of ``side``: (s_tip, s_steep, z_tip, height, max_angle).

    ``s_tip`` is the lowest point of the profile (the flange tip), ``s_steep``
    the point of the flange flank nearest to the tip whose slope is within 1°
    of the steepest slope of the flank (Nadal's limit is reached there: beyond
    it, towards the tip, the contact angle decreases and the flange climbs),
    ``height`` the depth of the tip below the profile origin (tape circle)
    (all [m], profile frame) and ``max_angle`` the steepest flank slope [°].
    Returns ``None`` for a wheel without a flange (height < 5 mm).
    """
    wc = ws.curve(side)
    hit = _FLANGE_CACHE.get(id(wc))
    if hit is not None and hit[0] is wc:
        return hit[1]
    s = np.linspace(wc.u_min, wc.u_max, 4001)
    z, z1 = wc.eval(s, 1)
    i_tip = int(np.argmin(z))
    height = float(wc.eval(np.array([min(max(0.0, wc.u_min), wc.u_max)]), 0)[0][0] - z[i_tip])
    out = None
    if height >= 5e-3 and i_tip < s.size - 2:
        ang = np.arctan(z1[i_tip:])
        flank = s[i_tip:] <= min(0.0, s[-1])
        if np.any(flank):
            a_max = float(np.max(ang[flank]))
            steep = np.flatnonzero(flank & (ang >= a_max - np.radians(1.0)))
            out = (float(s[i_tip]), float(s[i_tip + steep[0]]), float(z[i_tip]), height,
                   float(np.degrees(a_max)))
    if len(_FLANGE_CACHE) > 64:
        _FLANGE_CACHE.clear()
    _FLANGE_CACHE[id(wc)] = (wc, out)
    return out


def classify_rows(ws, y, z, wheel_y, status, roll=None):
    """Flag rows whose rigid contact lies on the flange beyond Nadal's limit.

    Per side, with the flange geometry of :func:`flange_geometry`: a contact
    point between the flange tip and the steepest point of the flank (by more
    than 0.1 mm) where the profile slope has fallen more than 2° below the
    steepest slope means the flange is climbing the rail: the contact angle
    decreases as the wheel rises (status 1, ``"flange_climb"``); where the profile slope at the contact point is below
    45° (the rounded flange tip, or beyond the tip) the wheel rides on its
    flange tip: derailed (status 2, ``"derailed"``).

    Parameters
    ----------
    y, z : ndarray, shape (n,)
        Lateral shifts and heights of the rows [m].
    wheel_y : dict of ndarray
        Wheel coordinates of the rigid contact points per side [m].
    status : ndarray of int, shape (n,)
        Codes from :func:`solve_rigid_rows` (rows with code ≥ 3 are left alone).
    roll : ndarray, shape (n,), optional
        Roll angles [rad]; used to report the lift of the flagged wheel.

    Returns
    -------
    status : ndarray of int8, shape (n,)
    reasons : list of str
        Empty where a row was not flagged here.
    """
    status = np.array(status, dtype=np.int8)
    reasons = [""] * status.size
    for side in SIDES:
        fg = flange_geometry(ws, side)
        if fg is None:
            continue
        s_tip, s_steep, z_tip, height, a_max = fg
        sc = np.asarray(wheel_y[side], dtype=float)
        ok = (status < 3) & np.isfinite(sc)
        zc, z1 = ws.curve(side).eval(np.where(ok, sc, 0.0), 1)
        ang = np.degrees(np.arctan(np.abs(z1)))
        beyond = ok & (sc < s_steep - 1e-4) & (ang < a_max - 2.0)
        if not np.any(beyond):
            continue
        for i in np.flatnonzero(beyond):
            tip = bool(ang[i] < 45.0 or sc[i] <= s_tip)
            code = 2 if tip else 1
            above = max(0.0, (zc[i] - z_tip) * 1e3)
            what = (f"{side} wheel rides on its flange tip ({above:.1f} mm above the tip, "
                    f"profile slope {ang[i]:.1f}°): derailed" if tip else
                    f"{side} wheel climbs its flange (contact {above:.1f} mm above the flange "
                    f"tip, slope {ang[i]:.1f}° < steepest {a_max:.1f}°)")
            lift = float(z[i]) + (0.0 if roll is None else _SIGMA[side] * float(roll[i]) * ws.e_tape)
            msg = f"y = {float(y[i]):.6g} m: {what}; {side} wheel lifted {lift * 1e3:.1f} mm"
            if code > status[i]:
                status[i] = code
                reasons[i] = msg
            elif code == status[i] and reasons[i]:
                reasons[i] += "; " + what
    return status, reasons


def point_data(ws, tr, side, s, pose: _Pose) -> dict:
    """All per-point quantities of :data:`POINT_FIELDS` at wheel coordinates ``s`` (pure).

    One pose per point (``pose`` arrays of the shape of ``s``, 1-D) runs the compiled
    kernel :func:`wheelrail.geometry._search_kernels.point_data_rows` (the same formulas).
    """
    s_arr = np.asarray(s, dtype=float)
    if s_arr.ndim == 1 and all(np.shape(v) == s_arr.shape for v in
                               (pose.y, pose.z, pose.roll, pose.yaw)):
        args = _side_args(ws, tr, side, step=2e-4)
        pl = tr.placement(side)
        c = lambda v: np.ascontiguousarray(v, dtype=float)  # noqa: E731
        out = point_data_rows(c(s_arr), c(pose.y), c(pose.zc(ws)), c(pose.roll), c(pose.yaw),
                              *args[6:12], *args[13:16], float(pl.offset), float(pl.z_top),
                              float(pl.angle))
        return dict(zip(POINT_ROWS, out))
    return _point_data_arrays(ws, tr, side, s, pose)


def _point_data_arrays(ws, tr, side, s, pose: _Pose) -> dict:
    """:func:`point_data` with array operations (any broadcastable shapes)."""
    sig = _SIGMA[side]
    wc, rc, pl = ws.curve(side), tr.curve(side), tr.placement(side)
    p, p1, p2 = wc.eval(s)
    zc = pose.zc(ws)
    xr, Y, Z, r = silhouette(s, p, p1, ws.nominal_radius, ws.e_tape, sig,
                             pose.y, zc, pose.roll, pose.yaw)
    u = sig * Y
    zr, zr1, zr2 = rc.eval(u)
    gap = Z - zr
    gamma = np.arctan(zr1)
    kwx = 1.0 / (r * np.sqrt(1.0 + p1 * p1))
    kwy = curvature(p1, p2)
    kry = -curvature(zr1, zr2)
    ry, rz = pl.to_profile_frame(u, zr)
    return {
        "wheel_y": s, "wheel_z": p, "rail_y": ry, "rail_z": rz,
        "track_y": Y, "track_z": Z, "x": xr,
        "contact_angle": gamma, "rolling_radius": r,
        "wheel_curvature_x": kwx, "wheel_curvature_y": kwy, "rail_curvature_y": kry,
        "A": 0.5 * kwx, "B": 0.5 * (kwy + kry),
        "separation": gap * np.cos(gamma), "gap": gap,
    }


def find_points(ws, tr, side, pose: _Pose, *, step=2e-4, tolerance=1e-4, max_points=None):
    """All local minima of the gap per row with separation ≤ ``tolerance`` (pure kernel).

    The global minimum of each row is always included. Points are ordered
    from the field side to the flange (decreasing wheel coordinate).

    Returns
    -------
    data : dict of ndarray, shape (n_rows, n_points)
        :data:`POINT_FIELDS`, NaN-padded.
    count : ndarray of int, shape (n_rows,)
    """

    d, (s, lo, hi, h) = _grid_gap(ws, tr, side, pose, step)
    nrow = d.shape[0]
    # interior grid minima off the rail ends and each row's global minimum; the vertical gap
    # of a point with normal separation <= tolerance is at most tolerance/cos(80°); minima
    # separated by a negligible hump are merged
    rows, idx = select_minima(d, 6.0 * tolerance + 1e-9, _MERGE, _BIG)
    sub = _Pose(*(np.asarray(v)[rows] for v in (pose.y, pose.z, pose.roll, pose.yaw)))
    zsub = sub.zc(ws)
    sref = _refine_fast(ws, tr, side, step, s[idx], sub.y, zsub, sub.roll, sub.yaw)
    data = point_data(ws, tr, side, sref, sub)
    # drop duplicates (two grid minima refined to the same point) and distant minima;
    # order by row, then from the field side to the flange
    order = order_points(rows, np.ascontiguousarray(sref, dtype=float),
                         np.ascontiguousarray(data["separation"], dtype=float),
                         float(tolerance), nrow)
    rows_o = rows[order]
    count = np.bincount(rows_o, minlength=nrow)
    npt = int(max(count.max(initial=1), 1))
    if max_points is not None:
        npt = max(npt, int(max_points))
    slot = np.zeros(order.size, dtype=int)
    for k in range(1, order.size):
        slot[k] = slot[k - 1] + 1 if rows_o[k] == rows_o[k - 1] else 0
    # all fields in one array (n_fields, n_rows, n_points), one row of it per field
    vals = np.stack([np.broadcast_to(np.asarray(v, dtype=float), sref.shape)
                     for v in data.values()])
    arr = np.full((len(data), nrow, npt), np.nan)
    arr[:, rows_o, slot] = vals[:, order]
    return dict(zip(data, arr)), count
