"""Elastic and quasi-elastic wheelset–track contact (load sharing between contact points).

Elastic contact (Bosso et al. (2013), ch. 2, §2.1.2, eq. 2.4)
-------------------------------------------------------------
The wheelset is held at lateral shift ``y`` and yaw ``ψ`` and loaded by a
vertical force ``load`` at its centre (equal axle-box loads: no roll
moment); its height ``z`` and roll ``θ`` are free. Wherever the undeformed
profiles interpenetrate, each local minimum of the distance is a contact
point with normal approach ``δ_i = −separation_i`` and a Hertzian,
load-dependent stiffness (``N_i = (δ_i / δ_1(A_i, B_i))^{3/2}``, with δ_1 the
Hertz approach under unit load for the local curvatures — eq. 2.4 with the
non-linear stiffness of Hertz instead of a constant ``K``). ``z`` and ``θ``
follow from vertical-force and roll-moment equilibrium::

    Σ N_i cos γ_i = load,    Σ [(y_i − y) F_z,i − (z_i − z_c) F_y,i] = 0,

so that the load is shared between tread and flange (two-point contact). The
lateral force needed to hold the wheelset at ``y``, ``H = −Σ F_y,i``, is
returned (applied at the axle centre). With a steep flange contact alone on
the flanging wheel (S1002/60E1: about 6.5–7.5 mm) the flange force passes
above the axle centre and no roll equilibrium of this loading exists (the
wheel climbs); :class:`~wheelrail.errors.ConvergenceError` is raised. The
quasi-elastic variant then returns a negative (tensile) force on the other
wheel — the bilateral-constraint defect noted in Bosso et al. (2013), ch. 2, §2.1.3.

Quasi-elastic contact (Bosso et al. (2013), ch. 2, §2.1.3, eq. 2.5)
-------------------------------------------------------------------
Schupp, Weidemann and Mauer replace ``min d = 0`` by the regularised
(soft-minimum) distance

    D_ε = −ε ln( ∫ exp(−d(s)/ε) ds / ∫ ds ) = 0        (both sides),

over the range where the wheel lies above the rail (Bosso et al. (2013), ch. 2, print the
exponent with the opposite sign convention for d). With (z, θ) from these
two constraints, one equivalent contact per side is formed with the weights
``w(s) ∝ exp(−d(s)/ε)`` (mean position, contact angle, radius); the two normal
forces then follow from the same two equilibrium equations. The contact
point moves continuously through a jump of the rigid contact point.
Here d is the vertical wheel–rail distance on the search grid.

References
----------
.. [1] Review of wheel–rail contact models (Bosso et al. (2013), ch. 2), §2.1.2–2.1.3, eqs. (2.4), (2.5).
.. [2] G. Schupp, C. Weidemann, L. Mauer, Modelling the contact between wheel
   and rail within multibody system simulation, VSD 41 (2004) 349–364.
.. [3] K.L. Johnson, Contact Mechanics, CUP 1985, §4.2 (Hertz approach).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import root

from .._validation import as_float_array, positive
from ..errors import ConvergenceError, InputError
from ..hertzian import hertz_kernel
from ..materials import STEEL, as_material_pair
from ._checks import check_side
from .contact_search import (
    _SIGMA,
    SIDES,
    _gapfun,
    _grid_gap,
    _Pose,
    find_points,
    point_data,
    solve_rigid,
)
from .points import SideContacts, _side_from_row, check_inputs

__all__ = ["ElasticContactResult", "elastic_contact", "METHODS"]

METHODS = ("elastic", "quasi-elastic")


@dataclass(frozen=True)
class ElasticContactResult:
    """Result of :func:`elastic_contact` (frozen, SI).

    Attributes
    ----------
    method : str
    y, yaw, axle_load : float
        Prescribed lateral shift [m], yaw [rad], vertical axle load [N].
    z, roll : float
        Height of the axle centre [m] (as in :func:`contact_points`) and roll [rad].
    left, right : SideContacts
        Contact points (elastic: all penetrating local minima; quasi-elastic:
        the one equivalent point per side).
    Fn_left, Fn_right : ndarray, shape (n,)
        Normal force at each point [N] (compression positive).
    penetration_left, penetration_right : ndarray, shape (n,)
        Normal approach δ at each point [m] (elastic); −D-weighted mean gap (quasi-elastic).
    vertical_force_left, vertical_force_right : float
        Vertical wheel loads Q [N].
    lateral_force_left, lateral_force_right : float
        Lateral contact forces on each wheel in the track frame [N] (y right).
    lateral_force : float
        External lateral force on the axle needed for equilibrium, H = −ΣF_y [N].
    info : dict
        Solver details (``iterations``, ``epsilon`` …).
    """

    method: str
    y: float
    yaw: float
    axle_load: float
    z: float
    roll: float
    left: SideContacts
    right: SideContacts
    Fn_left: np.ndarray
    Fn_right: np.ndarray
    penetration_left: np.ndarray
    penetration_right: np.ndarray
    vertical_force_left: float
    vertical_force_right: float
    lateral_force_left: float
    lateral_force_right: float
    lateral_force: float
    info: dict = field(default_factory=dict)

    def Fn(self, side: str) -> np.ndarray:
        """Normal forces of ``side`` [N]."""
        return getattr(self, f"Fn_{check_side(side)}")


def _unit_approach(A, B, E_star, where):
    A = np.asarray(A, float)
    B = np.asarray(B, float)
    if np.any(A <= 0) or np.any(B <= 0):  # pragma: no cover - B is regularised before
        raise InputError(f"non-positive Hertz curvature (A={A!r}, B={B!r} 1/m) at a loaded contact "
                         f"point ({where}): conformal contact, Hertz does not apply")
    return hertz_kernel(1.0, A, B, E_star)[3]


_B_SPAN = 1.5e-3  # half-width [m] of the parabola fitted to the gap when the local B <= 0


def regularised_B_rows(ws, tr, side, B, wheel_y, contact_angle, y, zc, roll, yaw):
    """Cross curvature from the separation over ±1.5 mm where the point value is ≤ 0.

    At a jump of a profile curvature (e.g. the flange flank / flange root
    transition of S1002 against the R13 gauge corner) the point curvatures
    can give B ≤ 0 although the gap has a minimum; the separation's
    curvature over the scale of a contact patch, ``B = ½ f''`` with
    ``f'' = d''·cos³γ`` for the vertical gap ``d``, is used there instead.

    Parameters
    ----------
    B, wheel_y, contact_angle : ndarray, shape (n, k)
        Points of n poses (NaN-padded): curvature [1/m], wheel coordinate [m], γ [rad].
    y, zc, roll, yaw : ndarray, shape (n,)
        The poses (axle-centre height ``zc`` [m]).

    Returns
    -------
    ndarray, shape (n, k)
    """
    B = np.array(B, dtype=float)
    bad = np.isfinite(B) & (B <= 0)
    if np.any(bad):
        rows, cols = np.nonzero(bad)
        s = wheel_y[rows, cols]
        k = s.size
        tile = lambda v: np.tile(np.asarray(v, float)[rows], 3)  # noqa: E731
        gap = _gapfun(ws, tr, side, tile(y), tile(zc), tile(roll), tile(yaw))
        d = gap(np.concatenate([s - _B_SPAN, s, s + _B_SPAN]))
        d2 = (d[:k] - 2 * d[k:2 * k] + d[2 * k:]) / _B_SPAN ** 2
        B[rows, cols] = 0.5 * d2 * np.cos(contact_angle[rows, cols]) ** 3
    return B


def _regularised_B(ws, tr, side, pts, pose, zc):
    """:func:`regularised_B_rows` for the points ``pts`` of one pose (shape (k,))."""
    one = lambda v: np.atleast_1d(np.asarray(v, float))[:1]  # noqa: E731
    return regularised_B_rows(ws, tr, side, pts.B[None], pts.wheel_y[None],
                              pts.contact_angle[None], one(pose.y), one(zc), one(pose.roll),
                              one(pose.yaw))[0]


def _forces(ws, tr, side, data, count, pose, zc, E_star):
    """Normal forces and force components of the penetrating points of one side (row 0)."""
    pts = _side_from_row(data, count, 0)
    pen = np.clip(-pts.separation, 0.0, None)
    N = np.zeros_like(pen)
    act = pen > 0
    if np.any(act):
        B = _regularised_B(ws, tr, side, pts, pose, zc)
        d1 = _unit_approach(pts.A[act], B[act], E_star, f"{side} wheel")
        N[act] = (pen[act] / d1) ** 1.5
    sig = _SIGMA[side]
    Fy = -sig * np.sin(pts.contact_angle) * N
    Fz = np.cos(pts.contact_angle) * N
    M = (pts.track_y - pose.y[0]) * Fz - (pts.track_z - zc) * Fy
    return pts, pen, N, Fy, Fz, M


def _elastic(ws, tr, y, yaw, load, E_star, step, z0, th0, maxiter=60):
    """Newton iteration on (z, θ) with the Hertzian tangent stiffness of every point.

    The tangent stiffness of a loaded point is dN/dδ = 1.5 N/δ; a side without
    penetration contributes its closest point with the stiffness of a Hertz
    contact under half the load, so that the iteration pulls it into contact.
    Steps are limited to 0.1 mm (trust region) and backtracked on the
    residual, which keeps the iteration monotone.
    """
    psi = np.array([yaw])
    yv = np.array([y])
    pen_guess = hertz_kernel(0.5 * load, 0.5 / ws.nominal_radius, 5.0, E_star)[3]
    k_est = 1.5 * 0.5 * load / pen_guess
    scale = np.array([load, load * ws.e_tape])

    def evaluate(x):
        pose = _Pose(yv, np.array([x[0]]), np.array([x[1]]), psi)
        zc = ws.nominal_radius + x[0]
        out = {}
        for side in SIDES:
            data, count = find_points(ws, tr, side, pose, step=step, tolerance=0.0)
            out[side] = _forces(ws, tr, side, data, count, pose, zc, E_star)
        Fz = sum(float(np.sum(out[s][4])) for s in SIDES)
        M = sum(float(np.sum(out[s][5])) for s in SIDES)
        return out, np.array([Fz - load, M]) / scale, zc

    x = np.array([z0 - pen_guess, th0])
    out, res, zc = evaluate(x)
    nev = 1
    for it in range(maxiter):
        if np.max(np.abs(res)) < 1e-10:
            break
        J = np.zeros((2, 2))
        for side in SIDES:
            pts, pen, N, Fy, Fz, _ = out[side]
            sig = _SIGMA[side]
            g = pts.contact_angle
            k = np.where(pen > 0, 1.5 * N / np.where(pen > 0, pen, 1.0), k_est)
            lever = (pts.track_y - y) + sig * np.tan(g) * (pts.track_z - zc)
            m = (pts.track_y - y) * np.cos(g) + (pts.track_z - zc) * sig * np.sin(g)
            dN = -k * np.cos(g)                       # per unit of (dz + lever dθ)
            J[0, 0] += np.sum(np.cos(g) * dN)
            J[0, 1] += np.sum(np.cos(g) * dN * lever)
            J[1, 0] += np.sum(m * dN)
            J[1, 1] += np.sum(m * dN * lever)
        J /= scale[:, None]
        try:
            dx = -np.linalg.solve(J, res)
        except np.linalg.LinAlgError as exc:  # pragma: no cover
            raise ConvergenceError(f"elastic contact: singular stiffness at y = {y!r} m") from exc
        # trust region: the flange force passes close to the axle centre, so the stiffness
        # matrix is nearly singular in flange contact; steps beyond 0.1 mm are not trusted
        big = max(abs(dx[0]), abs(dx[1]) * ws.e_tape) / 1e-4
        if big > 1.0:
            dx = dx / big
        lam = 1.0
        for _ in range(30):
            out_n, res_n, zc_n = evaluate(x + lam * dx)
            nev += 1
            if np.linalg.norm(res_n) < np.linalg.norm(res):
                break
            lam *= 0.5
        else:
            break
        x, out, res, zc = x + lam * dx, out_n, res_n, zc_n
    if np.max(np.abs(res)) > 1e-6:
        raise ConvergenceError(
            f"elastic contact equilibrium did not converge at y = {y!r} m (relative residual "
            f"{res.tolist()!r}). Either no equilibrium exists — with the lateral force applied "
            "at the axle centre a steep flange force (line of action above the axle centre) "
            "and the other wheel's tread both roll the wheelset the same way (flange climbing) "
            "— or the contact is nearly conformal (flange root against the gauge corner), where "
            "the Hertzian point contact jumps along a flat distance function; use a "
            "non-Hertzian normal solver with separation() there")
    return x, out, {"iterations": it, "evaluations": nev}


def _soft_min(d, eps):
    """−ε ln(mean exp(−d/ε)) over the finite part of d (rows), and the normalised weights."""
    finite = d < 0.5
    a = np.where(finite, -d / eps, -np.inf)
    m = np.max(a, axis=1, keepdims=True)
    w = np.exp(a - m)
    L = np.sum(finite, axis=1)
    D = -eps * (m[:, 0] + np.log(np.sum(w, axis=1) / L))
    return D, w / np.sum(w, axis=1, keepdims=True)


def _quasi_elastic(ws, tr, y, yaw, load, eps, step, z0, th0):
    psi = np.array([yaw])
    yv = np.array([y])

    def constraint(x):
        pose = _Pose(yv, np.array([x[0]]), np.array([x[1]]), psi)
        out = []
        for side in SIDES:
            d, _ = _grid_gap(ws, tr, side, pose, step)
            out.append(_soft_min(d, eps)[0][0])
        return np.array(out)

    def residual(x):
        DL, DR = constraint(x)
        return np.array([(DL + DR) / 2e-3, (DR - DL) / 2e-3])

    sol = root(residual, np.array([z0, th0]), method="hybr", options={"xtol": 1e-13})
    if np.max(np.abs(constraint(sol.x))) > 1e-9:
        raise ConvergenceError(f"quasi-elastic constraint (eq. 2.5) did not converge at y = {y!r} m "
                               f"({sol.message})")
    pose = _Pose(yv, np.array([sol.x[0]]), np.array([sol.x[1]]), psi)
    zc = ws.nominal_radius + sol.x[0]
    sides = {}
    for side in SIDES:
        d, (s, lo, hi, h) = _grid_gap(ws, tr, side, pose, step)
        _, w = _soft_min(d, eps)
        w = w[0]
        sbar = float(np.sum(w * s))
        data = point_data(ws, tr, side, s, _Pose(*(np.broadcast_to(v, s.shape) for v in
                                                  (yv, pose.z, pose.roll, psi))))
        mean = {k: np.array([float(np.sum(w * v))]) for k, v in data.items()}
        mean["wheel_y"] = np.array([sbar])
        pts = SideContacts(**{k: mean[k] for k in SideContacts.__dataclass_fields__})
        sides[side] = pts
    # normal forces from vertical and roll equilibrium with one contact per side
    rows = []
    for side in SIDES:
        p = sides[side]
        g = float(p.contact_angle[0])
        fy, fz = -_SIGMA[side] * np.sin(g), np.cos(g)
        rows.append((fz, (float(p.track_y[0]) - y) * fz - (float(p.track_z[0]) - zc) * fy, fy))
    Mat = np.array([[rows[0][0], rows[1][0]], [rows[0][1], rows[1][1]]])
    NL, NR = np.linalg.solve(Mat, [load, 0.0])
    out = {}
    for side, Nn, r in zip(SIDES, (NL, NR), rows):
        p = sides[side]
        N = np.array([Nn])
        out[side] = (p, -p.gap * np.cos(p.contact_angle), N, N * r[2], N * r[0], None)
    return sol.x, out, {"iterations": int(sol.nfev), "epsilon": eps}


def elastic_contact(wheelset, track, y, axle_load, yaw=0.0, method: str = "elastic", *,
                    material=STEEL, epsilon: float = 5e-5, step: float = 2e-4) -> ElasticContactResult:
    """Normal forces at all contact points of a loaded wheelset (elastic or quasi-elastic).

    Parameters
    ----------
    wheelset : Wheelset
    track : Track
    y : float
        Lateral shift [m] (right positive).
    axle_load : float
        Vertical wheelset load (axle load) [N] (> 0), applied at the axle centre.
    yaw : float
        Yaw angle [rad].
    method : {"elastic", "quasi-elastic"}
        Hertzian penetration at every contact point (eq. 2.4), or the
        regularised distance of Schupp et al. (eq. 2.5).
    material : Material or MaterialPair
        Elastic constants (default steel), used by ``"elastic"``.
    epsilon : float
        Regularisation length ε [m] of ``"quasi-elastic"`` (default 0.05 mm,
        of the order of the Hertzian approach).
    step : float
        Search-grid spacing along the wheel [m].

    Returns
    -------
    ElasticContactResult

    Examples
    --------
    >>> import wheelrail as wr
    >>> ws = wr.Wheelset(wr.profiles.load("S1002"))
    >>> tr = wr.Track(wr.profiles.load("60E1"))
    >>> res = wr.elastic_contact(ws, tr, 0.0, axle_load=1.0e5)
    >>> round(res.vertical_force_left + res.vertical_force_right)
    100000
    """
    yaw, _, step = check_inputs(wheelset, track, yaw, 0.0, step)
    y = as_float_array("y", y)
    if y.ndim != 0:
        raise InputError("elastic_contact takes a scalar y")
    y = float(y)
    axle_load = float(positive("axle_load", axle_load))
    if method not in METHODS:
        raise InputError(f"method must be one of {METHODS}, got {method!r}")
    pair = as_material_pair(material)
    z0, th0, _ = solve_rigid(wheelset, track, np.array([y]), np.array([yaw]), step=step)
    if method == "elastic":
        x, out, info = _elastic(wheelset, track, y, yaw, axle_load, pair.E_star, step,
                                float(z0[0]), float(th0[0]))
    else:
        eps = float(positive("epsilon", epsilon))
        x, out, info = _quasi_elastic(wheelset, track, y, yaw, axle_load, eps, step,
                                      float(z0[0]), float(th0[0]))
    info["rigid_z"] = float(z0[0])
    info["rigid_roll"] = float(th0[0])

    def keep(side):
        pts, pen, N, Fy, Fz, _ = out[side]
        if method == "elastic":
            m = N > 0
            pts = SideContacts(**{k: getattr(pts, k)[m] for k in SideContacts.__dataclass_fields__})
            return pts, pen[m], N[m], Fy[m], Fz[m]
        return pts, pen, N, Fy, Fz

    L, R = keep("left"), keep("right")
    FyL, FyR = float(np.sum(L[3])), float(np.sum(R[3]))
    return ElasticContactResult(method, y, yaw, axle_load, float(x[0]), float(x[1]), L[0], R[0], L[2], R[2],
                          L[1], R[1], float(np.sum(L[4])), float(np.sum(R[4])), FyL, FyR,
                          -(FyL + FyR), info)
