"""Structured hex8 meshes of a whole rail and a whole wheel, flange and gauge corner included.

The meshes of :mod:`wheelrail.fe.mesh` extrude the profile as a height field
(``z = profile(y) - depth``), which cannot represent near-vertical surfaces: the
wheel flange and the rail's gauge face. Here a cross-section is meshed in
*layers offset along the inward normal of the profile curve* (parametrised by
arc length, so any steepness is allowed), graded from fine bands (the expected
tread and flange contacts) outwards; below the offset layers the rows are
blended onto straight "core" lines (rail: underside of the head, web, foot;
wheel: inner rim, plate, hub), so that the whole cross-section is one mapped
block of ``n_s × n_rows`` nodes. The section is then extruded along ``x``
(rail) or swept about the axle (wheel; a full revolution is periodic).

Cross-section frames (SI units, m): the profile frames of :mod:`wheelrail.profiles`
(``y`` lateral, positive to the field side, ``z`` up). The rail's section is the
profile rotated by its inclination; the wheel section is the profile frame with
the wheel body *above* the profile curve, mapped to the radius ``ρ = R − z``.

Node ``(i, j, k)`` — ``i`` along ``x``/``θ``, ``j`` along the section curve, ``k``
the row (``k = 0`` is the running surface) — has number ``(i n_s + j) n_rows + k``,
as in :class:`wheelrail.fe.mesh.Body`.

References
----------
.. [1] X. Zhao, Z. Li, "The solution of frictional wheel-rail rolling contact with a 3D
   transient finite element model: validation and error analysis", Wear 271 (2011)
   444-452 (regular 1 mm mesh in a solution zone, graded elsewhere).
.. [2] EN 13674-1:2011 (54E1 rail: 159 mm high, head 70 mm, web 16 mm, foot 140 mm wide).
"""

from __future__ import annotations

import numpy as np

from ...errors import InputError
from ..mesh import Body, MeshQualityError, check_quality

__all__ = ["spacing_axis", "SectionCurve", "section_rows", "rail_section", "wheel_section",
           "block_rows", "rail_web_foot_rows", "wheel_plate_rows", "line_tie",
           "extrude_section", "sweep_section", "section_quality", "MeshQualityError"]


def spacing_axis(lo: float, hi: float, bands, h: float, ratio: float = 1.3,
                 h_max: float | None = None) -> np.ndarray:
    """A 1-D axis with spacing ``h`` inside the ``bands`` and geometric growth away from them.

    Parameters
    ----------
    lo, hi : float
        Ends of the axis (hi > lo).
    bands : sequence of (float, float)
        Refined intervals (clipped to [lo, hi]); several are allowed.
    h : float
        Spacing in the bands (> 0).
    ratio : float
        Growth factor of consecutive spacings away from the bands (>= 1).
    h_max : float, optional
        Largest spacing.

    Returns
    -------
    ndarray, shape (n,)
        Strictly increasing, from ``lo`` to ``hi``.
    """
    if not hi > lo or not h > 0 or not ratio >= 1.0:
        raise InputError(f"spacing axis needs hi > lo, h > 0, ratio >= 1; got lo={lo}, hi={hi}, "
                         f"h={h}, ratio={ratio}")
    bands = [(max(lo, a), min(hi, b)) for a, b in bands if min(hi, b) >= max(lo, a)]
    h_max = h_max or (hi - lo)

    def spacing(s):
        if not bands:
            return h_max
        dist = min(0.0 if a <= s <= b else min(abs(s - a), abs(s - b)) for a, b in bands)
        # geometric growth: the spacing at distance d from a band of spacing h
        return min(h_max, h + (ratio - 1.0) * dist)

    pts = [lo]
    while pts[-1] < hi:
        s = pts[-1]
        d = spacing(s)
        d = min(d, spacing(min(hi, s + d)))       # do not overshoot into a band
        pts.append(s + d)
    pts = np.array(pts)
    if len(pts) > 2 and (hi - pts[-2]) < 0.5 * (pts[-2] - pts[-3]):
        pts = np.delete(pts, -2)                  # merge a sliver last interval
    pts[-1] = hi
    # stretch the overshoot of the last interval evenly
    return lo + (pts - lo) * (hi - lo) / (pts[-1] - lo)


class SectionCurve:
    """A profile as a parametric curve P(s) in its cross-section plane (arc length s).

    Parameters
    ----------
    y, z : ndarray, shape (n,)
        Points of the curve [m] (any steepness; ordered along the curve).
    body_side : {"below", "above"}
        Side of the body: ``"below"`` for a rail (the profile is the body's upper
        boundary), ``"above"`` for a wheel.
    """

    def __init__(self, y, z, body_side: str):
        from scipy.interpolate import CubicSpline

        y = np.asarray(y, float)
        z = np.asarray(z, float)
        if body_side not in ("below", "above"):
            raise InputError(f"body_side must be 'below' or 'above', got {body_side!r}")
        ds = np.hypot(np.diff(y), np.diff(z))
        keep = np.concatenate(([True], ds > 1e-12))
        y, z = y[keep], z[keep]
        s = np.concatenate(([0.0], np.cumsum(np.hypot(np.diff(y), np.diff(z)))))
        self.length = float(s[-1])
        self._y = CubicSpline(s, y)
        self._z = CubicSpline(s, z)
        self._s_of_points = s
        self._pts = np.stack([y, z], axis=1)
        self.sign = -1.0 if body_side == "below" else 1.0

    def point(self, s):
        s = np.asarray(s, float)
        return np.stack([self._y(s), self._z(s)], axis=-1)

    def inward_normal(self, s):
        """Unit normal into the body at s, shape (..., 2)."""
        s = np.asarray(s, float)
        ty, tz = self._y(s, 1), self._z(s, 1)
        n = np.hypot(ty, tz)
        # the left normal (−t_z, t_y) points above a curve running towards +y
        return self.sign * np.stack([-tz / n, ty / n], axis=-1)

    def s_of_y(self, y):
        """Arc length of the first curve point at lateral position ``y`` (nearest point)."""
        pts = self.point(np.linspace(0.0, self.length, 4001))
        k = np.argmin(np.abs(pts[:, 0][:, None] - np.atleast_1d(y)[None]), axis=0)
        return np.linspace(0.0, self.length, 4001)[k]

    def s_of_point(self, y, z):
        """Arc length of the curve point nearest to (y, z)."""
        ss = np.linspace(0.0, self.length, 8001)
        pts = self.point(ss)
        return float(ss[np.argmin(np.hypot(pts[:, 0] - y, pts[:, 1] - z))])

    def contact_angle(self, s):
        """Angle [rad] of the inward normal against the vertical (0 on a flat top)."""
        n = self.inward_normal(s)
        return np.arctan2(np.abs(n[..., 0]), np.abs(n[..., 1]))


def section_rows(curve: SectionCurve, s_nodes, depths, cores, spread: float = 0.3) -> np.ndarray:
    """Node rows of a mapped cross-section block.

    Parameters
    ----------
    curve : SectionCurve
    s_nodes : ndarray, shape (n_s,)
        Arc lengths of the surface nodes [m].
    depths : ndarray, shape (n_d,)
        Offsets of the first rows along the inward normal [m] (from 0).
    cores : sequence of (y_lo, y_hi, z, n_rows)
        Straight lines the rows are blended onto in turn, ``n_rows`` rows each (the
        last row on the line); the nodes of a line are spread like the lateral
        positions of the row above them; ``None`` for ``y_lo``/``y_hi`` keeps the ends of that row.
    spread : float
        0: a core line's nodes follow the row above laterally; 1: uniform.

    Returns
    -------
    ndarray, shape (n_rows, n_s, 2)
    """
    P = curve.point(s_nodes)
    N = curve.inward_normal(s_nodes)
    rows = [P + d * N for d in depths]
    for y_lo, y_hi, z, n in cores:
        A = rows[-1]
        # spread like the lateral positions of the row above, relaxed towards uniform
        # (no slivers under fine bands, no crossing over steep flanks)
        fy = (A[:, 0] - A[0, 0]) / (A[-1, 0] - A[0, 0])
        if np.any(np.diff(fy) <= 0):
            j = int(np.argmin(np.diff(fy)))
            raise MeshQualityError(f"section row at depth {depths[-1]:.4g} m folds back "
                                   f"laterally at {A[j].round(5)} m; lower the layer depth")
        f = (1 - spread) * fy + spread * np.linspace(0.0, 1.0, fy.size)
        y_lo = A[0, 0] if y_lo is None else y_lo
        y_hi = A[-1, 0] if y_hi is None else y_hi
        T = np.stack([y_lo + f * (y_hi - y_lo), np.full_like(f, z)], axis=1)
        for m in range(1, int(n) + 1):
            w = m / n
            rows.append((1 - w) * A + w * T)
    return np.array(rows)


def section_quality(rows: np.ndarray, name: str) -> None:
    """Check that every quadrilateral of a section is convex and positively oriented
    (the 2-D precondition of positive hex8 Jacobians after extrusion or sweep).

    Raises
    ------
    MeshQualityError
        Naming the row, the column and the position of the first bad cell.
    """
    a = rows[:-1, :-1]
    b = rows[:-1, 1:]
    c = rows[1:, 1:]
    d = rows[1:, :-1]

    def cross(p, q, r):
        return (q[..., 0] - p[..., 0]) * (r[..., 1] - p[..., 1]) - \
               (q[..., 1] - p[..., 1]) * (r[..., 0] - p[..., 0])

    det = np.stack([cross(a, b, d), cross(b, c, a), cross(c, d, b), cross(d, a, c)])
    sgn = np.sign(np.median(det[0]))
    bad = np.any(det * sgn <= 0, axis=0)
    if np.any(bad):
        k, j = np.argwhere(bad)[0]
        raise MeshQualityError(f"{name} cross-section: cell (row {k}, column {j}) at "
                               f"{a[k, j].round(5)} m is folded or not convex: the offset "
                               f"layers are deeper than the profile's radius of curvature "
                               f"there; lower the layer depth or refine the core lines")


def _wrap(prof_y, prof_z, angle):
    c, s = np.cos(angle), np.sin(angle)
    return c * prof_y - s * prof_z, s * prof_y + c * prof_z


def rail_section(rail, h: float, bands_y, *, inclination: float = 1 / 40, ratio: float = 1.3,
                 h_max: float = 8e-3, fine_depth: float | None = None,
                 layer_depth: float = 8e-3, head_depth: float = 0.040, spread: float = 0.8):
    """Cross-section of a rail head from its profile, gauge face included.

    Parameters
    ----------
    rail : Profile
        Uninclined rail profile (z up, top at z = 0), with its gauge face.
    h : float
        Spacing in the fine bands and the surface layers [m].
    bands_y : sequence of (float, float)
        Lateral intervals of the *inclined* profile to refine (tread and gauge corner) [m].
    inclination : float
        Rail inclination [rad] (1:40 → 0.025) towards the track centre (−y).
    ratio, h_max : float
        Grading of the surface nodes away from the bands.
    fine_depth : float, optional
        Depth of the uniform layers [m] (default 3 h); graded below to ``layer_depth``.
    head_depth : float
        Depth of the head's flat underside below the top [m] (the web block is tied to it).
    spread : float
        Lateral spreading of the core rows towards uniform (:func:`section_rows`); high for
        a rail, whose near-vertical gauge and field faces stack their nodes at one ``y``.

    Returns
    -------
    rows : ndarray (n_rows, n_s, 2); curve : SectionCurve; s_nodes : ndarray (n_s,)
    """
    y, z = _wrap(rail.y, rail.z, inclination)
    curve = SectionCurve(y, z, "below")
    bands_s = [tuple(sorted(curve.s_of_y(np.array(b)))) for b in bands_y]
    s_nodes = spacing_axis(0.0, curve.length, bands_s, h, ratio, h_max)
    fine = fine_depth if fine_depth is not None else 3 * h
    depths = spacing_axis(0.0, layer_depth, [(0.0, fine)], h, ratio, h_max)
    top = float(np.max(z))
    n_core = max(2, int(np.ceil((head_depth - layer_depth) / h_max)))
    rows = section_rows(curve, s_nodes, depths, [(None, None, top - head_depth, n_core)],
                        spread)
    section_quality(rows, "rail head")
    return rows, curve, s_nodes


def block_rows(lines, n_cols: int) -> np.ndarray:
    """Rows of a plain block between straight horizontal lines.

    Parameters
    ----------
    lines : sequence of (y_lo, y_hi, z, n_rows)
        The first entry's ``n_rows`` is ignored (it is the top row); every following
        line is reached in ``n_rows`` rows, linearly.
    n_cols : int
        Nodes per row (uniform along each line).

    Returns
    -------
    ndarray, shape (n_rows, n_cols, 2)
    """
    f = np.linspace(0.0, 1.0, int(n_cols))

    def line(y_lo, y_hi, z):
        return np.stack([y_lo + f * (y_hi - y_lo), np.full_like(f, z)], axis=1)

    rows = [line(*lines[0][:3])]
    for y_lo, y_hi, z, n in lines[1:]:
        A, T = rows[-1], line(y_lo, y_hi, z)
        for m in range(1, int(n) + 1):
            rows.append(A + (m / n) * (T - A))
    return np.array(rows)


def rail_web_foot_rows(z_top: float, *, y_centre: float = 0.0, height: float = 0.159,
                       web: float = 0.020, foot: float = 0.140, foot_thickness: float = 0.011,
                       n_cols: int = 7, h_max: float = 0.02) -> np.ndarray:
    """Web and foot of a rail as one block below the head (tied to the head's underside).

    ``z_top`` is the head's underside [m]; the rail's top is at 0 (uninclined) and its
    foot at ``-height``. 54E1 defaults (EN 13674-1; web 16 mm at mid-height, 20 mm taken
    as the mean over its height with the fillets).
    """
    z_foot = -height + foot_thickness
    flare = 0.025
    n_web = max(2, int(round((z_top - z_foot - flare) / h_max)))
    return block_rows([(y_centre - web / 2, y_centre + web / 2, z_top, 0),
                       (y_centre - web / 2, y_centre + web / 2, z_foot + flare, n_web),
                       (y_centre - foot / 2, y_centre + foot / 2, z_foot, 2),
                       (y_centre - foot / 2, y_centre + foot / 2, -height, 1)], n_cols)


def wheel_section(wheel, h: float, bands_y, *, ratio: float = 1.3, h_max: float = 8e-3,
                  fine_depth: float | None = None, layer_depth: float = 5e-3,
                  rim: float = 0.035):
    """Cross-section of a wheel rim from its profile (flange included).

    Parameters
    ----------
    wheel : Profile
        Wheel profile (z up, body above the curve; flange at −y).
    h, bands_y, ratio, h_max, fine_depth, layer_depth
        As :func:`rail_section` (bands in the wheel's profile frame).
    rim : float
        Height of the rim's flat inner line above the tape circle [m] (the plate block is
        tied to it).

    Returns
    -------
    rows, curve, s_nodes as :func:`rail_section`.
    """
    curve = SectionCurve(wheel.y, wheel.z, "above")
    bands_s = [tuple(sorted(curve.s_of_y(np.array(b)))) for b in bands_y]
    s_nodes = spacing_axis(0.0, curve.length, bands_s, h, ratio, h_max)
    fine = fine_depth if fine_depth is not None else 3 * h
    depths = spacing_axis(0.0, layer_depth, [(0.0, fine)], h, ratio, h_max)
    n_core = max(2, int(np.ceil((rim - layer_depth) / h_max)))
    rows = section_rows(curve, s_nodes, depths, [(None, None, rim, n_core)])
    section_quality(rows, "wheel rim")
    return rows, curve, s_nodes


def wheel_plate_rows(z_rim: float, *, plate: float = 0.025, plate_centre: float = -0.010,
                     hub: float = 0.30, n_cols: int = 5, h_max: float = 0.03) -> np.ndarray:
    """The wheel plate as a block from the rim's inner line ``z_rim`` to the hub (profile
    frame heights above the tape circle [m]; radius ρ = R − z)."""
    n = max(2, int(round((hub - z_rim) / h_max)))
    return block_rows([(plate_centre - plate / 2, plate_centre + plate / 2, z_rim, 0),
                       (plate_centre - plate / 2, plate_centre + plate / 2, hub, n)], n_cols)


def line_tie(slave_yz: np.ndarray, line_yz: np.ndarray):
    """Weights tying points to a polyline: for each slave point (y, z) the two line nodes
    and their linear interpolation weights (nearest segment by ``y``).

    Returns
    -------
    idx : ndarray of int, shape (n, 2); w : ndarray, shape (n, 2)
    """
    ly = line_yz[:, 0]
    if np.any(np.diff(ly) <= 0):
        raise InputError("tie line must run towards +y")
    y = slave_yz[:, 0]
    if np.any(y < ly[0] - 1e-9) or np.any(y > ly[-1] + 1e-9):
        raise InputError(f"tied points y = [{y.min():.4g}, {y.max():.4g}] m lie beyond the line "
                         f"[{ly[0]:.4g}, {ly[-1]:.4g}] m")
    j = np.clip(np.searchsorted(ly, y) - 1, 0, ly.size - 2)
    t = np.clip((y - ly[j]) / (ly[j + 1] - ly[j]), 0.0, 1.0)
    return np.stack([j, j + 1], axis=1), np.stack([1 - t, t], axis=1)


def _connectivity(n_a, n_s, n_r, periodic):
    m = n_a if periodic else n_a - 1
    i, j, k = np.meshgrid(np.arange(m), np.arange(n_s - 1), np.arange(n_r - 1), indexing="ij")
    i, j, k = i.ravel(), j.ravel(), k.ravel()
    i1 = (i + 1) % n_a

    def n(ii, dj, dk):
        return (ii * n_s + (j + dj)) * n_r + (k + dk)

    return np.stack([n(i, 0, 0), n(i1, 0, 0), n(i1, 1, 0), n(i, 1, 0),
                     n(i, 0, 1), n(i1, 0, 1), n(i1, 1, 1), n(i, 1, 1)], axis=1)


def _finish(name, nodes, shape, axes, periodic, fixed, meta, max_aspect):
    n_a, n_s, n_r = shape
    conn = _connectivity(n_a, n_s, n_r, periodic)
    x = nodes[conn]
    vol = np.einsum("ei,ei->e", np.cross(x[:, 1] - x[:, 0], x[:, 3] - x[:, 0]), x[:, 4] - x[:, 0])
    if np.all(vol < 0):
        conn = conn[:, [4, 5, 6, 7, 0, 1, 2, 3]].copy()
    # surface quads (k = 0), oriented with the normal out of the body (away from row 1)
    m = n_a if periodic else n_a - 1
    i, j = np.meshgrid(np.arange(m), np.arange(n_s - 1), indexing="ij")
    i1 = (i + 1) % n_a
    q = np.stack([(i * n_s + j) * n_r, (i1 * n_s + j) * n_r, (i1 * n_s + j + 1) * n_r,
                  (i * n_s + j + 1) * n_r], axis=-1)
    p = nodes[q]
    nrm = np.cross(p[..., 2, :] - p[..., 0, :], p[..., 3, :] - p[..., 1, :])
    inward = nodes[q[..., 0] + 1] - p[..., 0, :]
    if np.mean(np.einsum("...i,...i", nrm, inward)) > 0:
        q = q[..., ::-1].copy()
    body = Body(name, nodes, conn, shape, axes, q, fixed, dict(meta, periodic=periodic))
    body.meta["quality"] = check_quality(body, max_aspect=max_aspect)
    return body


def extrude_section(rows: np.ndarray, x_axis: np.ndarray, *, name: str = "rail",
                    max_aspect: float = 60.0, meta=None) -> Body:
    """The rail body: the section ``rows`` (n_r, n_s, 2) extruded along ``x_axis``.

    Nodes are in the track frame at rest (x along the rail, y, z). ``fixed`` is empty:
    the rail is held by its supports (:mod:`wheelrail.fe.transition.track`).
    """
    n_r, n_s, _ = rows.shape
    X = np.broadcast_to(x_axis[:, None, None], (x_axis.size, n_s, n_r))
    Y = np.broadcast_to(rows[:, :, 0].T[None], X.shape)
    Z = np.broadcast_to(rows[:, :, 1].T[None], X.shape)
    nodes = np.stack([X, Y, Z], axis=-1).reshape(-1, 3).copy()
    return _finish(name, nodes, (x_axis.size, n_s, n_r), (x_axis, None, None), False,
                   np.zeros(0, np.int64), dict(meta or {}, rows=rows), max_aspect)


def sweep_section(rows: np.ndarray, theta_axis: np.ndarray, radius: float, *,
                  periodic: bool = False, name: str = "wheel", max_aspect: float = 60.0,
                  meta=None) -> Body:
    """The wheel body: the section ``rows`` swept about the axle (the ``y`` axis).

    A section point (y, z) of the profile frame has radius ρ = radius − z; the node at
    material angle θ (0 straight below the axle, positive ahead, +x) sits at
    (ρ sin θ, y, −ρ cos θ) in the wheel frame (axle centre at the origin). ``fixed``: the
    nodes of the last row (the hub), clamped to the axle.
    """
    n_r, n_s, _ = rows.shape
    n_a = theta_axis.size
    T = theta_axis[:, None, None]
    rho = radius - rows[:, :, 1].T[None]
    Y = np.broadcast_to(rows[:, :, 0].T[None], (n_a, n_s, n_r))
    nodes = np.stack([rho * np.sin(T), Y, -rho * np.cos(T)], axis=-1).reshape(-1, 3)
    shape = (n_a, n_s, n_r)
    fixed = ((np.arange(n_a)[:, None] * n_s + np.arange(n_s)[None]) * n_r + n_r - 1).ravel()
    return _finish(name, nodes, shape, (theta_axis, None, None), periodic, fixed,
                   dict(meta or {}, rows=rows, radius=radius), max_aspect)
