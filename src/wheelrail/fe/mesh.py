"""Structured hexahedral meshes of a wheel segment and a rail segment (SI units, m).

The two bodies are generated from their :class:`~wheelrail.profiles.Profile`
cross-sections as tensor products of three graded 1-D axes:

* **rail** — extruded along ``x`` (rolling direction): node ``(i, j, k)`` sits
  at ``(x_i, y_j, z_r(y_j) - d_k)``, where ``z_r`` is the (inclined) rail
  profile and ``d_k`` the depth below the running surface;
* **wheel** — swept about its axle (parallel to ``y``) with the rolling radius:
  node ``(i, j, k)`` sits at angle ``theta_i`` and radius ``r(y_j) + d_k``, with
  ``r(y) = R - z_w(y - y_w)`` the wheel radius at lateral position ``y``.

Only the part of each body near the running band is kept (the "cut-away"
bodies of Toumi et al. 2016, Fig. 1): a rail block ``depth`` deep and a wheel
rim ``depth`` thick. Each axis is uniform with spacing ``h`` inside its refined
band (the rolling path along ``x``, the contact band laterally, the layer
under the surface in depth) and grows geometrically by ``ratio`` outside it,
up to ``h_max``.

Global frame: ``x`` rolling direction, ``y`` lateral (the profiles' ``y``),
``z`` up. The wheel's axle centre is at ``(0, ·, z_axle)``.

References
----------
.. [1] M. Toumi, H. Chollet, H. Yin, "Finite element analysis of the frictional
   wheel-rail rolling contact using explicit and implicit methods", Wear 366-367
   (2016) 157-166, §2 and Fig. 1.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError

__all__ = ["Body", "graded_axis", "axis_size", "depth_axis", "rail_body", "wheel_body", "check_quality",
           "MeshQualityError"]


class MeshQualityError(InputError):
    """A generated mesh has an inverted or badly shaped element."""


@dataclass(frozen=True, eq=False)
class Body:
    """A structured hex8 mesh of one body.

    Attributes
    ----------
    name : str
        ``"wheel"`` or ``"rail"``.
    nodes : ndarray, shape (n_nodes, 3)
        Reference coordinates [m] in the body's own frame (wheel: relative to
        the axle centre; rail: the rail frame at rest).
    elements : ndarray of int, shape (n_elements, 8)
        Node numbers, hex8 order (bottom face counter-clockwise seen from
        outside, then top face), positive Jacobian.
    shape : tuple of int
        Nodes per axis ``(nx, ny, nz)``; node ``(i, j, k)`` has number
        ``(i * ny + j) * nz + k``; ``k = 0`` is the running surface.
    axes : tuple of ndarray
        The 1-D axes: ``x`` [m] (rail) or ``theta`` [rad] (wheel), the lateral
        ``y`` [m] and the depth ``d`` [m].
    surface : ndarray of int, shape (nx - 1, ny - 1, 4)
        Node numbers of the surface quads (``k = 0``), ordered so that their
        normal points out of the body.
    fixed : ndarray of int
        Nodes clamped in the body frame (rail foot plane, wheel inner rim).
    """

    name: str
    nodes: np.ndarray
    elements: np.ndarray
    shape: tuple
    axes: tuple
    surface: np.ndarray
    fixed: np.ndarray
    meta: dict = field(default_factory=dict)

    @property
    def n_nodes(self) -> int:
        return int(self.nodes.shape[0])

    @property
    def n_elements(self) -> int:
        return int(self.elements.shape[0])

    def node_index(self, i, j, k):
        nx, ny, nz = self.shape
        return (np.asarray(i) * ny + np.asarray(j)) * nz + np.asarray(k)

    @property
    def surface_nodes(self) -> np.ndarray:
        """Node numbers of the running surface, shape (nx, ny)."""
        nx, ny, nz = self.shape
        return self.node_index(np.arange(nx)[:, None], np.arange(ny)[None, :], 0)

    def surface_areas(self) -> np.ndarray:
        """Tributary area [m²] of every surface node, shape (nx, ny) (reference configuration)."""
        nx, ny, _ = self.shape
        q = self.nodes[self.surface]                      # (nx-1, ny-1, 4, 3)
        d1 = q[:, :, 2] - q[:, :, 0]
        d2 = q[:, :, 3] - q[:, :, 1]
        area = 0.5 * np.linalg.norm(np.cross(d1, d2), axis=-1)
        out = np.zeros((nx, ny))
        for di in (0, 1):
            for dj in (0, 1):
                out[di:nx - 1 + di, dj:ny - 1 + dj] += 0.25 * area
        return out


def graded_axis(lo: float, hi: float, fine_lo: float, fine_hi: float, h: float,
                ratio: float = 1.3, h_max: float | None = None) -> np.ndarray:
    """A 1-D axis uniform (spacing ≈ ``h``) on [fine_lo, fine_hi], geometrically graded outside.

    Parameters
    ----------
    lo, hi : float
        Ends of the axis.
    fine_lo, fine_hi : float
        The refined band, clipped to [lo, hi].
    h : float
        Spacing in the band (> 0).
    ratio : float
        Growth factor of consecutive spacings outside the band (>= 1).
    h_max : float, optional
        Largest spacing (default: unbounded).

    Returns
    -------
    ndarray, shape (n,)
        Strictly increasing coordinates from ``lo`` to ``hi``.
    """
    if not (hi > lo) or h <= 0:
        raise InputError(f"graded axis needs hi > lo and h > 0, got lo={lo}, hi={hi}, h={h}")
    fine_lo, fine_hi = max(lo, fine_lo), min(hi, fine_hi)
    if fine_hi <= fine_lo:
        fine_lo = fine_hi = 0.5 * (lo + hi) if not (lo <= fine_lo <= hi) else fine_lo
    n_fine = max(1, int(round((fine_hi - fine_lo) / h))) if fine_hi > fine_lo else 0
    core = np.linspace(fine_lo, fine_hi, n_fine + 1) if n_fine else np.array([fine_lo])

    def grow(length):
        steps, s, dh = [], 0.0, h
        while s < length - 1e-12 * max(1.0, length):
            dh = min(dh * ratio, h_max) if h_max else dh * ratio
            steps.append(dh)
            s += dh
        if not steps:
            return np.zeros(0)
        c = np.cumsum(steps)
        c *= length / c[-1]              # stretch the last layer onto the end
        if len(c) > 1 and (c[-1] - c[-2]) < 0.5 * (c[-2] - (c[-3] if len(c) > 2 else 0.0)):
            c = np.delete(c, -2)         # merge a sliver last layer
        return c

    left = fine_lo - grow(fine_lo - lo)[::-1]
    right = fine_hi + grow(hi - fine_hi)
    return np.concatenate((left, core, right))


def axis_size(lo: float, hi: float, fine_lo: float, fine_hi: float, h: float,
              ratio: float = 1.3, h_max: float | None = None) -> int:
    """Number of nodes :func:`graded_axis` gives for these arguments (±1), counted without
    building the axis (geometric series outside the band)."""
    if not (hi > lo) or h <= 0:
        raise InputError(f"graded axis needs hi > lo and h > 0, got lo={lo}, hi={hi}, h={h}")
    fine_lo, fine_hi = max(lo, fine_lo), min(hi, fine_hi)
    n = 1 + (max(1, int(round((fine_hi - fine_lo) / h))) if fine_hi > fine_lo else 0)

    def grown(length):
        if length <= 0:
            return 0
        if ratio <= 1.0:
            return int(np.ceil(length / (h_max or h)))
        # h (r + r^2 + ... + r^k) >= length, capped at h_max
        k = int(np.ceil(np.log1p(length * (ratio - 1.0) / (h * ratio)) / np.log(ratio)))
        if h_max:
            k_cap = max(0, int(np.floor(np.log(h_max / h) / np.log(ratio))))
            if k > k_cap:
                s_cap = h * ratio * (ratio ** k_cap - 1.0) / (ratio - 1.0)
                k = k_cap + int(np.ceil(max(0.0, length - s_cap) / h_max))
        return k

    return n + grown(fine_lo - lo) + grown(hi - fine_hi)


def depth_axis(depth: float, h: float, fine: float, ratio: float = 1.3,
               h_max: float | None = None) -> np.ndarray:
    """Depths below the surface, from 0: spacing ``h`` down to ``fine``, graded below."""
    return graded_axis(0.0, depth, 0.0, fine, h, ratio, h_max)


def _hex_connectivity(shape):
    nx, ny, nz = shape
    i, j, k = np.meshgrid(np.arange(nx - 1), np.arange(ny - 1), np.arange(nz - 1), indexing="ij")
    i, j, k = i.ravel(), j.ravel(), k.ravel()

    def n(di, dj, dk):
        return ((i + di) * ny + (j + dj)) * nz + (k + dk)

    return np.stack([n(0, 0, 0), n(1, 0, 0), n(1, 1, 0), n(0, 1, 0),
                     n(0, 0, 1), n(1, 0, 1), n(1, 1, 1), n(0, 1, 1)], axis=1)


def _surface_quads(shape, flip):
    nx, ny, nz = shape
    i, j = np.meshgrid(np.arange(nx - 1), np.arange(ny - 1), indexing="ij")

    def n(di, dj):
        return ((i + di) * ny + (j + dj)) * nz

    q = np.stack([n(0, 0), n(1, 0), n(1, 1), n(0, 1)], axis=-1)
    return q[..., ::-1].copy() if flip else q


def _orient(nodes, elements):
    """Make every element's Jacobian positive by mirroring the node order if needed."""
    x = nodes[elements]
    d = np.einsum("ei,ei->e", np.cross(x[:, 1] - x[:, 0], x[:, 3] - x[:, 0]), x[:, 4] - x[:, 0])
    if np.all(d < 0):
        return elements[:, [4, 5, 6, 7, 0, 1, 2, 3]].copy(), True
    return elements, False


def rail_body(rail, x_axis, y_axis, d_axis) -> Body:
    """Rail block: the profile ``rail`` (z up) extruded along ``x``.

    Parameters
    ----------
    rail : Profile
        Rail profile (already inclined) giving the surface height z_r(y) [m].
    x_axis, y_axis, d_axis : ndarray
        Longitudinal positions, lateral positions and depths [m].
    """
    zs = rail(y_axis)
    if np.any(~np.isfinite(zs)):
        raise InputError(f"the rail mesh spans y = [{y_axis[0]:.4g}, {y_axis[-1]:.4g}] m, outside the "
                         f"rail profile [{rail.y_min:.4g}, {rail.y_max:.4g}] m; reduce the width")
    X, Y, D = np.meshgrid(x_axis, y_axis, d_axis, indexing="ij")
    Z = rail(Y) - D
    nodes = np.stack([X, Y, Z], axis=-1).reshape(-1, 3)
    shape = (len(x_axis), len(y_axis), len(d_axis))
    elements, flipped = _orient(nodes, _hex_connectivity(shape))
    # surface normal (up) from quad order (i, j): x cross y = +z -> keep
    surface = _surface_quads(shape, flip=False)
    nx, ny, nz = shape
    fixed = ((np.arange(nx)[:, None] * ny + np.arange(ny)[None, :]) * nz + nz - 1).ravel()
    body = Body("rail", nodes, elements, shape, (x_axis, y_axis, d_axis), surface, fixed)
    check_quality(body)
    return body


def wheel_body(radius_of_y, theta_axis, y_axis, d_axis) -> Body:
    """Wheel rim segment swept about the axle (the ``y`` axis through the origin).

    Parameters
    ----------
    radius_of_y : callable
        Wheel radius r(y) [m] of the running surface at lateral position y.
    theta_axis : ndarray
        Material angles [rad]; 0 is straight below the axle, positive ahead (+x).
    y_axis, d_axis : ndarray
        Lateral positions [m] and depths into the wheel (radially outward from
        the surface towards the axle... i.e. inward radius ``r - d``) [m].
    """
    r = radius_of_y(y_axis)
    if np.any(~np.isfinite(r)):
        raise InputError(f"the wheel mesh spans y = [{y_axis[0]:.4g}, {y_axis[-1]:.4g}] m, outside "
                         f"the wheel profile; reduce the width")
    T, Y, D = np.meshgrid(theta_axis, y_axis, d_axis, indexing="ij")
    Rr = np.asarray(radius_of_y(Y)) - D
    nodes = np.stack([Rr * np.sin(T), Y, -Rr * np.cos(T)], axis=-1).reshape(-1, 3)
    shape = (len(theta_axis), len(y_axis), len(d_axis))
    elements, _ = _orient(nodes, _hex_connectivity(shape))
    # quad (i, j) order: theta cross y at the bottom = (+x) x (+y) = +z (into the wheel): flip
    surface = _surface_quads(shape, flip=True)
    nx, ny, nz = shape
    fixed = ((np.arange(nx)[:, None] * ny + np.arange(ny)[None, :]) * nz + nz - 1).ravel()
    body = Body("wheel", nodes, elements, shape, (theta_axis, y_axis, d_axis), surface, fixed)
    check_quality(body)
    return body


_GAUSS = np.array([-1.0, 1.0]) / np.sqrt(3.0)
_XI = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], dtype=float)


def check_quality(body: Body, max_aspect: float = 50.0) -> dict:
    """Check Jacobians (positive at every Gauss point and corner) and aspect ratios.

    Returns
    -------
    dict
        ``min_jacobian_ratio`` (min/max det J per element, worst element),
        ``max_aspect`` (longest / shortest edge, worst element).

    Raises
    ------
    MeshQualityError
        An element with a non-positive Jacobian or an aspect ratio above ``max_aspect``,
        naming the element and its centre.
    """
    x = body.nodes[body.elements]                          # (ne, 8, 3)
    pts = np.concatenate([_XI, np.array([[a, b, c] for a in _GAUSS for b in _GAUSS
                                         for c in _GAUSS])])
    dets = []
    for p in pts:
        dN = 0.125 * _XI * np.stack([(1 + _XI[:, 1] * p[1]) * (1 + _XI[:, 2] * p[2]),
                                     (1 + _XI[:, 0] * p[0]) * (1 + _XI[:, 2] * p[2]),
                                     (1 + _XI[:, 0] * p[0]) * (1 + _XI[:, 1] * p[1])], axis=1)
        J = np.matmul(dN.T, x)                             # (ne, 3, 3)
        dets.append(J[:, 0, 0] * (J[:, 1, 1] * J[:, 2, 2] - J[:, 1, 2] * J[:, 2, 1])
                    - J[:, 0, 1] * (J[:, 1, 0] * J[:, 2, 2] - J[:, 1, 2] * J[:, 2, 0])
                    + J[:, 0, 2] * (J[:, 1, 0] * J[:, 2, 1] - J[:, 1, 1] * J[:, 2, 0]))
    dets = np.array(dets)
    dmin, dmax = dets.min(axis=0), dets.max(axis=0)
    if np.any(dmin <= 0):
        e = int(np.argmin(dmin))
        raise MeshQualityError(f"{body.name} mesh: element {e} at {x[e].mean(axis=0).round(5)} m "
                               f"has a non-positive Jacobian ({dmin[e]:.3g}); the profile is too "
                               f"curved for the mesh or the depth exceeds the wheel radius")
    edges = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
             (0, 4), (1, 5), (2, 6), (3, 7)]
    L = np.stack([np.linalg.norm(x[:, a] - x[:, b], axis=1) for a, b in edges], axis=1)
    aspect = L.max(axis=1) / L.min(axis=1)
    if np.any(aspect > max_aspect):
        e = int(np.argmax(aspect))
        raise MeshQualityError(f"{body.name} mesh: element {e} at {x[e].mean(axis=0).round(5)} m "
                               f"has aspect ratio {aspect[e]:.3g} > {max_aspect}; lower the grading "
                               f"ratio or h_max")
    return {"min_jacobian_ratio": float((dmin / dmax).min()), "max_aspect": float(aspect.max())}
