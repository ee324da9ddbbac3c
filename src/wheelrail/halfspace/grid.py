"""Uniform rectangular grid of piecewise-constant boundary elements.

The contact plane is discretised into ``nx × ny`` equal rectangles of size
``dx × dy``. Every field on the grid (pressure, traction, gap, displacement)
is an array of shape ``(nx, ny)`` holding the value at the element centre;
axis 0 is ``x`` (rolling direction), axis 1 is ``y`` (lateral), i.e. the
``indexing="ij"`` layout of :func:`numpy.meshgrid`. All lengths in m.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from .._validation import as_float_array, integer, positive
from ..errors import InputError

__all__ = ["Grid", "contact_outline"]


@dataclass(frozen=True)
class Grid:
    """A uniform grid of ``nx × ny`` rectangular elements (frozen).

    Parameters
    ----------
    x0, y0 : float
        Centre of element (0, 0) [m].
    dx, dy : float
        Element size along x and y [m], > 0.
    nx, ny : int
        Number of elements along x and y, >= 1.

    Examples
    --------
    >>> g = Grid.from_bounds(-1e-3, 1e-3, -2e-3, 2e-3, nx=4, ny=8)
    >>> g.x
    array([-0.00075, -0.00025,  0.00025,  0.00075])
    >>> g.X.shape
    (4, 8)
    """

    x0: float
    y0: float
    dx: float
    dy: float
    nx: int
    ny: int

    def __post_init__(self):
        object.__setattr__(self, "x0", float(as_float_array("x0", self.x0)))
        object.__setattr__(self, "y0", float(as_float_array("y0", self.y0)))
        object.__setattr__(self, "dx", float(positive("dx", self.dx)))
        object.__setattr__(self, "dy", float(positive("dy", self.dy)))
        object.__setattr__(self, "nx", integer("nx", self.nx))
        object.__setattr__(self, "ny", integer("ny", self.ny))

    @classmethod
    def from_bounds(cls, xmin: float, xmax: float, ymin: float, ymax: float,
                    nx: int, ny: int) -> "Grid":
        """Grid covering the rectangle [xmin, xmax] × [ymin, ymax] (element edges) [m]."""
        nx, ny = integer("nx", nx), integer("ny", ny)
        xmin, xmax, ymin, ymax = (float(as_float_array(n, v)) for n, v in
                                  (("xmin", xmin), ("xmax", xmax), ("ymin", ymin), ("ymax", ymax)))
        if not xmax > xmin:
            raise InputError(f"xmax must be > xmin, got xmin={xmin!r}, xmax={xmax!r}")
        if not ymax > ymin:
            raise InputError(f"ymax must be > ymin, got ymin={ymin!r}, ymax={ymax!r}")
        dx = (xmax - xmin) / nx
        dy = (ymax - ymin) / ny
        return cls(xmin + 0.5 * dx, ymin + 0.5 * dy, dx, dy, nx, ny)

    # -- coordinates -------------------------------------------------------
    @property
    def shape(self) -> tuple[int, int]:
        """``(nx, ny)``."""
        return (self.nx, self.ny)

    @property
    def size(self) -> int:
        """Number of elements ``nx * ny``."""
        return self.nx * self.ny

    @cached_property
    def x(self) -> np.ndarray:
        """Element-centre x coordinates, shape (nx,) [m]."""
        return self.x0 + self.dx * np.arange(self.nx)

    @cached_property
    def y(self) -> np.ndarray:
        """Element-centre y coordinates, shape (ny,) [m]."""
        return self.y0 + self.dy * np.arange(self.ny)

    @property
    def X(self) -> np.ndarray:
        """Element-centre x coordinates, shape (nx, ny) [m] (``indexing="ij"``)."""
        return np.broadcast_to(self.x[:, None], self.shape)

    @property
    def Y(self) -> np.ndarray:
        """Element-centre y coordinates, shape (nx, ny) [m] (``indexing="ij"``)."""
        return np.broadcast_to(self.y[None, :], self.shape)

    @property
    def element_area(self) -> float:
        """Area of one element dx·dy [m²]."""
        return self.dx * self.dy

    @property
    def bounds(self) -> tuple[float, float, float, float]:
        """Outer element edges ``(xmin, xmax, ymin, ymax)`` [m]."""
        return (self.x0 - 0.5 * self.dx, self.x0 + (self.nx - 0.5) * self.dx,
                self.y0 - 0.5 * self.dy, self.y0 + (self.ny - 0.5) * self.dy)

    def check_field(self, name: str, field) -> np.ndarray:
        """Return ``field`` as a finite float array of shape (nx, ny) or raise InputError."""
        arr = as_float_array(name, field)
        if arr.shape != self.shape:
            raise InputError(f"{name} must have the grid shape {self.shape}, got {arr.shape}")
        return arr

    def refined(self, factor: int = 2) -> "Grid":
        """The same window with ``factor`` times more elements along each axis."""
        factor = integer("factor", factor)
        return Grid.from_bounds(*self.bounds, self.nx * factor, self.ny * factor)


# --------------------------------------------------------------------------- outline
# crossing edges of a dual cell with corners c0=(i,j), c1=(i+1,j), c2=(i+1,j+1), c3=(i,j+1);
# edge midpoints in doubled index coordinates
def _edge_points(i, j):
    return ((2 * i + 1, 2 * j), (2 * i + 2, 2 * j + 1), (2 * i + 1, 2 * j + 2), (2 * i, 2 * j + 1))


def contact_outline(grid: Grid, mask) -> list[np.ndarray]:
    """Closed outline polygon(s) of a set of elements (marching squares, level ½).

    The outline passes through the midpoints between contact and non-contact
    element centres (resolution one element). Diagonal neighbours are treated as
    separate regions. Contacts touching the grid edge are closed along the edge.

    Parameters
    ----------
    grid : Grid
    mask : array_like of bool, shape (nx, ny)

    Returns
    -------
    list of ndarray, each shape (m, 2)
        Closed polygons (first point repeated last) of (x, y) vertices [m],
        largest first.
    """
    m = np.asarray(mask, dtype=bool)
    if m.shape != grid.shape:
        raise InputError(f"mask must have the grid shape {grid.shape}, got {m.shape}")
    pad = np.zeros((m.shape[0] + 2, m.shape[1] + 2), dtype=bool)
    pad[1:-1, 1:-1] = m
    c0, c1 = pad[:-1, :-1], pad[1:, :-1]
    c2, c3 = pad[1:, 1:], pad[:-1, 1:]
    mixed = ~((c0 == c1) & (c1 == c2) & (c2 == c3))
    neighbours: dict = {}

    def link(a, b):
        neighbours.setdefault(a, []).append(b)
        neighbours.setdefault(b, []).append(a)

    for i, j in zip(*np.nonzero(mixed)):
        corners = (c0[i, j], c1[i, j], c2[i, j], c3[i, j])
        pts = _edge_points(i, j)
        cross = [k for k in range(4) if corners[k] != corners[(k + 1) % 4]]
        if len(cross) == 2:
            link(pts[cross[0]], pts[cross[1]])
        else:  # saddle: cut off the inside corners separately
            if corners[0]:
                link(pts[0], pts[3])
                link(pts[1], pts[2])
            else:
                link(pts[0], pts[1])
                link(pts[2], pts[3])
    polygons = []
    unvisited = set(neighbours)
    while unvisited:
        start = unvisited.pop()
        ring = [start]
        prev, cur = None, start
        while True:
            nxt = [q for q in neighbours[cur] if q != prev]
            nxt = nxt[0] if nxt else neighbours[cur][0]
            if nxt == start:
                break
            ring.append(nxt)
            unvisited.discard(nxt)
            prev, cur = cur, nxt
        ring.append(start)
        idx = np.asarray(ring, dtype=float) / 2.0 - 1.0     # element-index coordinates
        xy = np.column_stack([grid.x0 + idx[:, 0] * grid.dx, grid.y0 + idx[:, 1] * grid.dy])
        polygons.append(xy)

    def _area(poly):
        x, y = poly[:, 0], poly[:, 1]
        return abs(float(np.multiply(x[:-1], y[1:]).sum())
                   - float(np.multiply(x[1:], y[:-1]).sum())) / 2

    polygons.sort(key=_area, reverse=True)
    return polygons
