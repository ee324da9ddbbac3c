"""Boundary-element normal contact of one wheel on its rail (driver of :class:`~wheelrail.normal.bem.Bem`).

Candidate contact points are grouped by contact plane; each group is solved
on a planar grid in the plane of its reference point, the groups are coupled
through the wheel's vertical approach (see :class:`~wheelrail.normal.bem.Bem`).
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import ConvergenceError, InputError, NoContactError
from ..hertzian import _vertical_approach, hertz_kernel
from ._bem_solver import _elements_for, _patches_of, _solve_enlarging, _square_grid
from ._gap import _scaled, contact_patches

__all__ = ["solve_wheel"]

_SEARCH_X = 0.03      # half-length [m] of the search box along x


def _rigid_box_of(sep, delta, sigma, roller_radius, search):
    """Bounding box (xmin, xmax, ymin, ymax) of {h < δ} in contact-frame coordinates.

    Direct from the separation: laterally where f(η) < δ, along x up to
    √(2 (δ − f) / k) with k = cos_factor / r (+ 1/R on a roller), the
    longitudinal curvature of h (exact to the order of the Hertz gap).
    """
    inside = sep.f < delta
    if not inside.any():
        raise NoContactError(f"no interpenetration at the approach {delta!r} m")
    y = sigma * sep.eta[inside]
    k = sep.cos_factor / sep.wheel_radius[inside]
    if roller_radius is not None:
        k = k + 1.0 / roller_radius
    xmax = float(np.max(np.sqrt(2.0 * (delta - sep.f[inside]) / k)))
    step = float(np.max(np.abs(np.diff(sep.eta))))
    lo, hi = float(y.min()) - step, float(y.max()) + step
    if lo <= search[2] or hi >= search[3]:
        raise InputError(f"the region where the gap is below the approach δ = {delta!r} m "
                         f"reaches the edge of the search box {search} m")
    return (max(-xmax, search[0]), min(xmax, search[1]), lo, hi)


def _gap_function(sep, roller_radius, sigma):
    """h(x, y) in the contact frame (y to the right; the separation's η points to the field
    side, i.e. y = σ η)."""
    eta, f, r, cosf = sep.eta, sep.f, sep.wheel_radius, sep.cos_factor
    if sigma < 0:
        eta, f, r = -eta[::-1], f[::-1], r[::-1]
    R = roller_radius

    def gap(x, y):
        x = np.asarray(x, dtype=float)
        y = np.asarray(y, dtype=float)
        fy = np.interp(y, eta, f, left=1.0, right=1.0)
        ry = np.interp(y, eta, r)
        xx = np.minimum(np.abs(x), 0.999 * ry)
        h = fy + cosf * (ry - np.sqrt(ry * ry - xx * xx))
        if R is not None:
            h = h + (R - np.sqrt(R * R - np.minimum(xx, 0.999 * R) ** 2))
        return h
    return gap


def _setups(problem, pts, sigma, cosg, dz_est, elements, element_size, margin, group_angle,
            width):
    """Grid, gap and contact reference of every group of candidate points that touches."""
    groups = problem.groups(group_angle, width)
    setups = []
    for g in groups:
        r = g[0]
        s0 = problem.separation(r, width)
        delta_est = dz_est * cosg[r]
        pen0 = np.clip(delta_est - s0.f, 0.0, None)
        if not pen0.any():
            continue             # this group does not reach contact at the estimated approach
        # contact reference: interpenetration-weighted centre and mean surface angle of the
        # group's rigid interpenetration (the planar contact approach of CONTACT)
        eta_c = float(np.sum(pen0 * s0.eta) / np.sum(pen0))
        frame = problem.frame_at(r, eta_c, weights=pen0, eta_samples=s0.eta)
        s = problem.separation(frame, width)
        gap = _gap_function(s, problem.roller_radius, sigma)
        c_ref = math.cos(frame.contact_angle)
        delta_est = dz_est * c_ref
        ylim = sorted((sigma * float(s.eta[0]), sigma * float(s.eta[-1])))
        search = (-_SEARCH_X, _SEARCH_X, ylim[0], ylim[1])
        box = _rigid_box_of(s, max(delta_est * 1.3, delta_est + 2e-6), sigma,
                            problem.roller_radius, search)
        bounds = _scaled(box, margin, search)
        if element_size is None:
            n = _elements_for(max(bounds[1] - bounds[0], bounds[3] - bounds[2]), elements, None)
            grid = _square_grid(bounds, max(bounds[1] - bounds[0], bounds[3] - bounds[2]) / n)
        else:
            grid = _square_grid(bounds, element_size)
        setups.append({"ref": r, "members": g, "gap": gap, "grid": grid, "search": search,
                       "cos": c_ref, "sep": s, "frame": frame})
    return setups


def solve_wheel(problem, *, elements, element_size, margin, tol, max_enlarge, cells, group_angle,
                width):
    """Patches of one wheel (see :class:`~wheelrail.normal.bem.Bem`); returns (patches, info)."""
    pts = problem.points
    sigma = 1.0 if problem.side == "right" else -1.0
    pair = problem.materials
    sep = np.asarray(pts.separation, dtype=float)
    cosg = np.cos(np.asarray(pts.contact_angle, dtype=float))
    A = np.asarray(problem.A, dtype=float)
    B = np.asarray(problem.B, dtype=float)
    ok = (A > 0) & (B > 0)
    # Hertz estimate of the vertical approach: sizes the windows
    d1 = np.full(A.shape, np.inf)
    d1[ok] = hertz_kernel(1.0, A[ok], B[ok], pair.E_star)[3]
    if problem.vertical_approach is not None:
        dz_est = float(problem.vertical_approach)
    elif ok.any():
        dz_est = _vertical_approach(float(problem.vertical_load), sep[ok], cosg[ok], d1[ok])
    else:   # conformal everywhere: a rough estimate, the window enlargement corrects it
        dz_est = float(sep.min() / cosg[np.argmin(sep)]) + 5e-5

    key = ("bem_setups", elements, element_size, margin, group_angle, width)
    setups = problem.cache.get(key)
    if setups is None:
        try:
            setups = _setups(problem, pts, sigma, cosg, dz_est, elements, element_size, margin,
                             group_angle, width)
        except InputError as exc:
            if "search box" not in str(exc):
                raise
            what = (f"vertical load {problem.vertical_load!r} N"
                    if problem.vertical_load is not None
                    else f"vertical approach {problem.vertical_approach!r} m")
            raise InputError(f"{problem.side} wheel: with the {what} the interpenetration "
                             f"reaches beyond the {width!r} m of profile around the contact: "
                             "these profiles cannot carry that load (or raise width=)") from None
        # kept for the next pass of the vertical-load loop (same pose): windows, reference
        # points and the last pressure (warm start)
        problem.cache[key] = setups
    if not setups:
        raise NoContactError(f"{problem.side} wheel: no contact at the estimated vertical "
                             f"approach {dz_est!r} m")

    def solve_all(dz=None, load=None):
        sols = []
        for st in setups:
            kw = {"Fn": load / st["cos"]} if load is not None else {"penetration": dz * st["cos"]}
            try:
                sol, grid = _solve_enlarging(st["gap"], st["grid"], pair, st["search"], tol=tol,
                                             max_enlarge=max_enlarge, square=True,
                                             initial=st.get("pressure"), **kw)
                st["grid"] = grid
                st["pressure"] = sol.pressure
            except NoContactError:
                sol = None
            sols.append(sol)
        return sols

    iterations = 1
    if problem.vertical_approach is not None:
        dz = float(problem.vertical_approach)
        sols = solve_all(dz=dz)
    elif len(setups) == 1:
        sols = solve_all(load=float(problem.vertical_load))
        dz = sols[0].penetration / setups[0]["cos"]
    else:
        Q = float(problem.vertical_load)
        dz = dz_est
        for iterations in range(1, 31):
            sols = solve_all(dz=dz)
            F = dF = 0.0
            for st, sol in zip(setups, sols):
                if sol is None:
                    continue
                c = st["cos"]
                hmin = float(np.min(sol.gap + sol.penetration - sol.displacement))
                F += sol.Fn * c
                dF += 1.5 * sol.Fn * c * c / max(sol.penetration - hmin, 1e-12)
            if abs(F - Q) <= 1e-6 * Q:
                break
            if dF <= 0:
                dz *= 1.2
                continue
            step = (Q - F) / dF
            dz = max(dz + step, 0.5 * dz) if step < 0 else dz + step
        else:
            raise ConvergenceError(f"{problem.side} wheel: the vertical load {Q!r} N was not "
                                   f"reached by the boundary-element contact in 30 iterations "
                                   f"(vertical force {F!r} N)")
    patches = []
    for st, sol in zip(setups, sols):
        if sol is None:
            continue

        labels, _ = contact_patches(sol)
        nlab = int(labels.max())
        r = st["ref"]
        found = _patches_of(sol, pair, cells, frames=[st["frame"]] * nlab,
                            origins=[(0.0, 0.0)] * nlab, A=float(A[r]), B=float(B[r]))
        for p in found:
            # where the patch lies: its centre of pressure on the rail (the creepages refer
            # to the group's reference point, the frame, which all patches of a grid share)
            xc, yc = p.centre
            at = problem.frame_at(st["frame"], sigma * yc, angle=st["frame"].contact_angle)
            p.info.update(centre_rail_y=at.rail_y, centre_wheel_y=at.wheel_y,
                          centre_track_y=at.track_y)
        patches.extend(found)
    return tuple(patches), {"vertical_approach": float(dz), "iterations": iterations,
                            "groups": len(setups)}
