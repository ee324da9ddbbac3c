"""Batched wheel–rail contact with Hertzian patches (the fast path of :func:`wheelset_sweep`).

The same model as :func:`~wheelrail.contact.wheelrail.solve_wheelrail` with
``normal="hertz"`` (candidate points, one ellipse per point, vertical load
carried in total or by the normal forces), evaluated for all positions at
once: the rigid poses, the point search, the vertical approach (Newton, one
row per position), the Hertz ellipses, the creepages and the creep law are
array operations over all positions and patches. A test checks that it
agrees with the per-position path.
"""

from __future__ import annotations

import numpy as np

from ..errors import InputError, WheelrailError
from ..geometry.contact_search import _Pose, find_points, solve_rigid
from ..geometry.elastic import regularised_B_rows
from ..geometry.kinematics import creepage_kernel
from ..geometry.touching import touching_heights
from ..hertzian import _vertical_approach, hertz_from_penetration, hertz_kernel
from ..materials import as_material_pair
from .wheelrail import axle_offset_x

__all__ = ["hertz_sweep"]

_SIDES = ("left", "right")
_SIGMA = {"left": -1.0, "right": 1.0}
_TOL = 1e-5      # relative tolerance on the total vertical force (as solve_wheelrail)


def hertz_sweep(ws, tr, y, yaw, roll, loads, z, motion, mu, tangential, material,
                tolerance, vertical, max_patches):
    """All positions at once; returns the arrays of the sweep dataset (see wheelset_sweep).

    ``tangential`` is a configured creep-force law (its ``solve`` on the batch of
    Hertz contacts of the active points)."""

    pair = as_material_pair(material)
    n = y.size
    status = np.full(n, "ok", dtype=object)
    message = np.full(n, "", dtype=object)
    zs = {s: np.full(n, np.nan) for s in _SIDES}
    th = np.array(roll, dtype=float)
    free = np.isnan(th)
    ok_rows = np.ones(n, dtype=bool)
    if free.any():
        idx = np.nonzero(free)[0]
        try:
            zr, tr_, _ = solve_rigid(ws, tr, y[idx], yaw[idx])
        except WheelrailError:
            # one bad row must not stop the others: solve the rows one by one
            zr, tr_ = np.full(idx.size, np.nan), np.full(idx.size, np.nan)
            for j, i in enumerate(idx):
                try:
                    a, b, _ = solve_rigid(ws, tr, y[i:i + 1], yaw[i:i + 1])
                    zr[j], tr_[j] = a[0], b[0]
                except WheelrailError as exc:
                    status[i], message[i] = "error", f"{type(exc).__name__}: {exc}"
                    ok_rows[i] = False
        th[idx] = tr_
        for s in _SIDES:
            zs[s][idx] = zr
    if (~free).any():
        idx = np.nonzero(~free)[0]
        zt, beside = touching_heights(ws, tr, y[idx], th[idx], yaw[idx])
        for s in _SIDES:
            for i in idx[beside[s]]:
                status[i], message[i] = "error", (f"InputError: y = {y[i]!r} m: the {s} wheel "
                                                  "lies entirely beside its rail")
                ok_rows[i] = False
            zs[s][idx] = zt[s]
    rows = np.nonzero(ok_rows)[0]
    out_patch = {k: np.full((n, 2, max_patches), np.nan) for k in
                 ("y_rail", "y_rail_centre", "y_wheel", "contact_angle", "xi", "eta", "phi", "Fn", "Fx", "Fs",
                  "Mz", "p_max", "area", "adhesion_area")}
    ftrack = np.full((n, 2, 3), np.nan)
    npatches = np.zeros((n, 2), dtype=int)
    if rows.size == 0:
        return out_patch, ftrack, npatches, status, message
    Omega = motion.angular_velocity(ws.nominal_radius)
    R = np.inf if motion.roller_radius is None else motion.roller_radius
    for si, side in enumerate(_SIDES):
        sig = _SIGMA[side]
        yr, zr, thr, psr = y[rows], zs[side][rows], th[rows], yaw[rows]
        pose = _Pose(yr, zr, thr, psr)
        data, count = find_points(ws, tr, side, pose, tolerance=tolerance)
        valid = np.isfinite(data["separation"])
        zc = ws.nominal_radius + zr
        A = data["A"] + (0.0 if not np.isfinite(R) else 0.5 / R)
        B = regularised_B_rows(ws, tr, side, data["B"], data["wheel_y"], data["contact_angle"],
                               yr, zc, thr, psr)
        convex = valid & (A > 0) & (B > 0)
        sep = np.where(valid, data["separation"], np.inf)
        cosg = np.where(valid, np.cos(data["contact_angle"]), 1.0)
        d1 = np.full(A.shape, np.inf)
        d1[convex] = hertz_kernel(1.0, A[convex], B[convex], pair.E_star)[3]
        if z is not None:
            dz = zr - float(z)
            Qn = None
        else:
            Q = float(loads[si])
            Qn = np.full(rows.size, Q)
        # creepages of every candidate point (they do not depend on the load)
        xi, eta, phi = creepage_kernel(
            sig, motion.speed, Omega, motion.lateral_velocity, motion.vertical_velocity,
            motion.yaw_rate, motion.roll_rate, psr[:, None], thr[:, None],
            axle_offset_x(data["x"], data["wheel_y"], sig, ws.e_tape, thr[:, None], psr[:, None]),
            data["track_y"] - yr[:, None], data["track_z"] - zc[:, None], data["contact_angle"],
            R, data["track_z"])
        history = []
        for outer in range(12):
            if Qn is not None:
                dz = _vertical_approach(Qn, sep, cosg, d1, convex)
            pen = np.where(valid, np.clip(dz[:, None] * cosg - sep, 0.0, None), 0.0)
            act = pen > 0
            bad = act & ~convex
            if bad.any():
                for r in np.nonzero(bad.any(axis=1))[0]:
                    i = rows[r]
                    status[i], message[i] = "error", (
                        f"InputError: {side} wheel: a penetrating contact point is not convex "
                        "(Hertz cannot represent it; use normal='bem')")
                act &= ~bad
            for r in np.nonzero(~act.any(axis=1))[0]:
                i = rows[r]
                if status[i] == "ok":
                    what = (f"z = {float(z)!r} m leaves the {side} wheel out of contact (it "
                            f"touches at z = {float(zr[r])!r} m)" if Qn is None else
                            f"no contact on the {side} wheel")
                    status[i], message[i] = "error", f"InputError: {what}"
            if not act.any():          # no row of this side is in contact (all flagged above)
                break
            hc = hertz_from_penetration(pen[act], A[act], B[act], pair)
            last = (Qn is None or vertical == "normal" or outer == 11)
            cf = tangential.solve(hc, xi[act], eta[act], phi[act],
                                  np.full(int(np.count_nonzero(act)), float(mu)))
            Fx, Fs, Mz = (np.zeros(A.shape) for _ in range(3))
            Fx[act], Fs[act], Mz[act] = cf.Fx, cf.Fy, cf.Mz
            Fn = np.zeros(A.shape)
            Fn[act] = hc.Fn
            g = np.where(valid, data["contact_angle"], 0.0)
            Fz = np.sum(sig * Fs * np.sin(g) + Fn * np.cos(g), axis=1)
            if last:
                break
            err = Fz - Q
            if np.all(np.abs(err) <= _TOL * Q):
                break
            history.append((Qn.copy(), Fz))
            if len(history) == 1:
                Qn = np.where(Fz > 0, Qn * Q / np.where(Fz > 0, Fz, 1.0), Qn - err)
            else:
                (q0, f0), (q1, f1) = history[-2:]
                dq = q1 - q0
                slope = np.where(np.abs(dq) > 0, (f1 - f0) / np.where(dq != 0, dq, 1.0), 1.0)
                slope = np.where(slope > 0.05, slope, 1.0)
                Qn = q1 + (Q - f1) / slope
            Qn = np.maximum(Qn, 1e-3 * Q)
        if not act.any():
            continue
        if Qn is not None and vertical == "total":
            bad_rows = np.abs(Fz - Q) > _TOL * Q
            for r in np.nonzero(bad_rows)[0]:
                i = rows[r]
                if status[i] == "ok":
                    status[i], message[i] = "error", (
                        f"ConvergenceError: {side} wheel: the total vertical force {Fz[r]!r} N "
                        f"did not reach {Q!r} N")
        adh = np.full(A.shape, np.nan)
        if "adhesion_fraction" in cf.info:  # FASTSIM's batch kernel counts sticking elements
            adh[act] = np.asarray(cf.info["adhesion_fraction"]) * np.asarray(hc.area)
        Ft = np.stack([Fx.sum(axis=1),
                       np.sum(Fs * np.cos(g) - sig * Fn * np.sin(g), axis=1), Fz], axis=1)
        a_arr, b_arr = np.zeros(A.shape), np.zeros(A.shape)
        a_arr[act], b_arr[act] = hc.a, hc.b
        p0 = np.zeros(A.shape)
        p0[act] = hc.p0
        # active patches first, in the candidates' order (field side to flange), so that a
        # patch keeps its index along a sweep
        order = np.argsort(~act, axis=1, kind="stable")[:, :max_patches]
        take = lambda v: np.take_along_axis(v, order, axis=1)  # noqa: E731
        keep = take(act)
        fields = {"y_rail": data["rail_y"], "y_rail_centre": data["rail_y"],
                  "y_wheel": data["wheel_y"],
                  "contact_angle": data["contact_angle"], "xi": xi, "eta": eta, "phi": phi,
                  "Fn": Fn, "Fx": Fx, "Fs": Fs, "Mz": Mz, "p_max": p0,
                  "area": np.pi * a_arr * b_arr, "adhesion_area": adh}
        m = min(max_patches, order.shape[1])
        for k, v in fields.items():
            vals = np.where(keep, take(np.broadcast_to(v, A.shape)), np.nan)
            out_patch[k][rows, si, :m] = vals[:, :m]
        npatches[rows, si] = act.sum(axis=1)
        ftrack[rows, si] = Ft
    for i in range(n):
        if status[i] != "ok":
            ftrack[i] = np.nan
            npatches[i] = 0
            for v in out_patch.values():
                v[i] = np.nan
    return out_patch, ftrack, npatches, status, message


def check_vertical(vertical):
    if vertical not in ("total", "normal"):
        raise InputError(f"vertical must be 'total' or 'normal', got {vertical!r}")
    return vertical
