"""Wheelset sweep with any patch-based normal method: the geometry of all positions at once.

The fast path of :func:`~wheelrail.contact.sweep.wheelset_sweep` for the
normal methods that work on a :class:`~wheelrail.contact.wheelrail.WheelProblem`
(Kik–Piotrowski, Linder, STRIPES, multi-Hertz, BEM). A position's solution
is the same as :func:`wheelrail.solve` with that method; what is shared
across positions is the geometry, which dominates the time of the fast
methods:

* the rigid touching poses (Newton on (z, θ), Bosso et al. (2013), ch. 2 eqs. 2.1–2.3) of all
  positions in one vectorised call, as the Hertz fast path does;
* the candidate contact points of every position and side in one
  vectorised :func:`~wheelrail.geometry.contact_search.find_points` call and
  the regularised cross curvatures in one
  :func:`~wheelrail.geometry.elastic.regularised_B_rows` call.

The normal and tangential problems are then solved position by position
(``_solve_sides`` of :mod:`wheelrail.contact.wheelrail`, the code of
:func:`wheelrail.solve`). A position whose batched geometry fails is solved
by :func:`wheelrail.solve` alone, so that its error message is the usual one.
A test checks that the sweep agrees with the per-position path.

Multi-Hertz ``variant="ayasse"`` with its CAF tables (the default) reads its
contacts from the tables, not from the candidate points, so the candidate
point search is skipped for it (its wheel problems carry no points).
"""

from __future__ import annotations

import numpy as np

from ..errors import InputError, WheelrailError
from ..geometry.contact_search import _Pose, find_points, solve_rigid
from ..geometry.points import _side_from_row
from ..geometry.elastic import regularised_B_rows
from ..geometry.touching import touching_heights
from ..patch import ContactFrame
from ..plausibility import check_friction, disabled
from .wheelrail import SIDES, WheelProblem, WheelRailPosition, _solve_sides, solve_wheelrail

__all__ = ["strip_sweep"]


def _batched_geometry(ws, tr, y, yaw, roll, tolerance, roller_radius, points=True):
    """Touching poses and per-side candidate points of all rows.

    Returns ``ok`` (bool, shape (n,)), ``roll``, ``{side: z}`` and
    ``{side: (data, count, A, B)}`` for the rows in ``ok`` (arrays over all
    rows; rows not ok hold NaN), or None when the batch cannot be formed.
    """

    n = y.size
    th = np.array(roll, dtype=float)
    zs = {s: np.full(n, np.nan) for s in SIDES}
    ok = np.ones(n, dtype=bool)
    free = np.isnan(th)
    if free.any():
        idx = np.nonzero(free)[0]
        try:
            zr, tr_, _ = solve_rigid(ws, tr, y[idx], yaw[idx])
        except WheelrailError:
            ok[idx] = False        # these rows go through wheelrail.solve (its own message)
        else:
            th[idx] = tr_
            for s in SIDES:
                zs[s][idx] = zr
    if (~free).any():
        idx = np.nonzero(~free)[0]
        zt, beside = touching_heights(ws, tr, y[idx], th[idx], yaw[idx])
        for s in SIDES:
            zs[s][idx] = zt[s]
            ok[idx[beside[s]]] = False
    rows = np.nonzero(ok)[0]
    pts = {}
    if rows.size and points:
        for side in SIDES:
            yr, zr, thr, psr = y[rows], zs[side][rows], th[rows], yaw[rows]
            data, count = find_points(ws, tr, side, _Pose(yr, zr, thr, psr),
                                      tolerance=tolerance)
            zc = ws.nominal_radius + zr
            B = regularised_B_rows(ws, tr, side, data["B"], data["wheel_y"],
                                   data["contact_angle"], yr, zc, thr, psr)
            A = np.array(data["A"], dtype=float)
            if roller_radius is not None:
                A = A + 0.5 / roller_radius
            pts[side] = (data, count, A, B)
    return ok, rows, th, zs, pts


def _problem(position, side, roll, z, data, count, r, A, B, roller_radius):
    """The :class:`WheelProblem` of one side of one position from the batched rows
    (what :func:`~wheelrail.contact.wheelrail.wheel_problem` computes for one pose)."""

    if data is None:        # a method that reads no candidate points (CAF tables)
        pts, k, A, B = None, 0, np.zeros((r + 1, 0)), np.zeros((r + 1, 0))
    else:
        pts = _side_from_row(data, count, r)
        k = pts.n
    frames = tuple(ContactFrame(side, float(pts.wheel_y[i]), float(pts.rail_y[i]),
                                float(pts.track_y[i]), float(pts.track_z[i]), float(pts.x[i]),
                                float(pts.contact_angle[i]), float(pts.rolling_radius[i]))
                   for i in range(k))
    approach = None if position.z is None else z - position.z
    if approach is not None and approach <= 0:
        raise InputError(f"z = {position.z!r} m leaves the {side} wheel out of contact (it "
                         f"touches at z = {z!r} m)")
    return WheelProblem(side, pts, np.array(A[r, :k]), np.array(B[r, :k]), frames,
                        position.material, position.load(side), approach, roller_radius,
                        {"y": position.y, "z": z, "roll": roll, "yaw": position.yaw},
                        position.wheelset, position.track)


def strip_sweep(wheelset, track, y, yaw, roll, vertical_load, z, motion, mu, nimpl, timpl,
                material, tolerance, vertical, record, advance=None):
    """Solve every position; ``record(i, result)`` or ``record(i, exception)`` per position.

    Parameters are those of :func:`~wheelrail.contact.sweep.wheelset_sweep`
    (``nimpl``, ``timpl`` configured method objects).
    """

    n = y.size
    R = motion.roller_radius
    try:
        uses = getattr(nimpl, "_uses_tables", None)
        points = not (uses is not None and uses(nimpl.option_values()))
        ok, rows, th, zs, pts = _batched_geometry(wheelset, track, y, yaw, roll, tolerance, R,
                                                  points)
        if not points:
            pts = {s: (None, None, None, None) for s in SIDES}
    except WheelrailError:
        ok = np.zeros(n, dtype=bool)
        rows = np.zeros(0, dtype=int)
    where = np.full(n, -1)
    where[rows] = np.arange(rows.size)
    mu = float(mu)
    check_friction(mu)
    Omega = motion.angular_velocity(wheelset.nominal_radius)
    for i in range(n):
        try:
            pos = WheelRailPosition(wheelset, track, y[i], yaw[i],
                                    None if np.isnan(roll[i]) else roll[i],
                                    vertical_load=vertical_load, z=z, material=material,
                                    tolerance=tolerance)
            if ok[i]:
                r = int(where[i])
                zsi = {s: float(zs[s][i]) for s in SIDES}
                probs = {s: _problem(pos, s, float(th[i]), zsi[s], *pts[s][:2], r,
                                     *pts[s][2:], R) for s in SIDES}
                with disabled():
                    res = _solve_sides(pos, motion, mu, nimpl, timpl, vertical,
                                       float(th[i]), zsi, Omega, R, problems=probs)
            else:
                res = solve_wheelrail(pos, motion, mu, nimpl, timpl, vertical)
        except WheelrailError as exc:
            record(i, exc)
        else:
            record(i, res)
        if advance is not None:
            advance()
