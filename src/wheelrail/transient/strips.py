"""Paul–Hashemi discretisation for transient rolling: strips along x, equal elements per strip.

The Hertzian contact ellipse is cut into ``strips`` strips of equal width
``dy = 2b/strips`` along the rolling direction; strip ``j`` (centre ``y_j``)
covers its chord ``|x| ≤ c_j = a √(1 − (y_j/b)²)`` with the same number
``elements`` of elements of length ``dx_j = 2 c_j / elements`` (Baeza et al.,
Fig. 2; Paul & Hashemi 1981). Every strip then has the same discretisation
error along x, which suits longitudinal creepage.

The elements have different lengths, so the influence operators are dense
matrices (no FFT): Love's rectangle formulae with each source element's own
half-length. The time step uses the element-averaged slip of
:func:`wheelrail.transient.rolling.step_weights` with each target strip's own
``dx_j / h``. The pressure is Hertz's at the element centres, scaled so that
the discrete total equals the normal force (Baeza et al. use the Hertzian normal
contact; a constant normal force only).

References
----------
.. [1] B. Paul, J. Hashemi, Contact pressures in closely conforming elastic
   bodies, J. Appl. Mech. 48 (1981) 543–548.
.. [2] L. Baeza, F.J. Fuenmayor, J. Carballeira, A. Roda, Influence of the wheel–rail contact instationary process on contact parameters, §1 and Fig. 2.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..halfspace.influence import rectangle_influence
from ..materials import as_material_pair

__all__ = ["StripGrid", "strip_grid", "hertz_pressure", "strip_step_operators"]


@dataclass(frozen=True)
class StripGrid:
    """Elements of a Paul–Hashemi discretisation, indexed ``[i (along x), j (strip)]``.

    Attributes
    ----------
    X, Y : ndarray, shape (nx, ny)
        Element centres [m].
    dx : ndarray, shape (ny,)
        Element length of each strip [m].
    dy : float
        Strip width [m].
    """

    X: np.ndarray
    Y: np.ndarray
    dx: np.ndarray
    dy: float

    @property
    def shape(self):
        return self.X.shape

    @property
    def nx(self):
        return self.X.shape[0]

    @property
    def ny(self):
        return self.X.shape[1]

    @property
    def area(self) -> np.ndarray:
        """Element areas [m²], shape (nx, ny)."""
        return np.broadcast_to(self.dx[None, :] * self.dy, self.shape)

    @property
    def x(self) -> np.ndarray:
        """Element index along x (the strips have different x positions; see ``X``)."""
        return np.arange(self.nx, dtype=float)

    @property
    def y(self) -> np.ndarray:
        """Strip centres [m]."""
        return self.Y[0]


def strip_grid(contact, elements=30, strips=30) -> StripGrid:
    """The Paul–Hashemi grid of a Hertzian contact (``elements`` per strip, ``strips`` strips)."""
    a, b = float(contact.a), float(contact.b)
    dy = 2 * b / strips
    y = -b + (np.arange(strips) + 0.5) * dy
    c = a * np.sqrt(1 - (y / b) ** 2)
    dx = 2 * c / elements
    X = -c[None, :] + (np.arange(elements)[:, None] + 0.5) * dx[None, :]
    Y = np.broadcast_to(y[None, :], X.shape).copy()
    return StripGrid(X=X, Y=Y, dx=dx, dy=dy)


def hertz_pressure(contact, sg: StripGrid, load) -> np.ndarray:
    """Hertz's pressure [Pa] at the element centres, scaled to the total ``load`` [N]."""
    a, b = float(contact.a), float(contact.b)
    p = np.sqrt(np.maximum(1 - (sg.X / a) ** 2 - (sg.Y / b) ** 2, 0.0))
    return p * (float(load) / float((p * sg.area).sum()))


def strip_step_operators(sg: StripGrid, materials, step, weights_of):
    """Dense step operators ``(now, old)`` of shapes (2n, 3n) [m/Pa], n = nx·ny.

    Row ``τ n + q`` is the slip component τ (0: x, 1: y) of element q (flat
    index of ``[i, j]``, C order) averaged over its collocation points
    ``weights_of(dx_j, step)``; column ``κ n + r`` the traction κ (x, y, n)
    of element r; ``now`` at the current positions, ``old`` carried one
    step ``h = step`` upstream (:func:`~wheelrail.transient.rolling.step_kernels`).
    """
    pair = as_material_pair(materials)
    X, Y = sg.X.ravel(), sg.Y.ravel()
    n = X.size
    hx = np.broadcast_to(sg.dx[None, :] / 2, sg.shape).ravel()
    strip = np.broadcast_to(np.arange(sg.ny)[None, :], sg.shape).ravel()
    per = [weights_of(float(d), step) for d in sg.dx]
    K = max(len(w) for _, w in per)
    now = np.zeros((2 * n, 3 * n))
    old = np.zeros((2 * n, 3 * n))
    dY = Y[:, None] - Y[None, :]
    for k in range(K):
        w = np.array([ws[k] if k < len(ws) else 0.0 for _, ws in per])[strip]
        s = np.array([off[k] if k < len(off) else 0.0 for off, _ in per])[strip]
        for shift, target in ((0.0, now), (step, old)):
            A = rectangle_influence(X[:, None] + s[:, None] + shift - X[None, :], dY,
                                    hx[None, :], sg.dy / 2, pair.G, pair.nu, pair.K)
            for t in range(2):
                for c in range(3):
                    target[t * n:(t + 1) * n, c * n:(c + 1) * n] += w[:, None] * A[t, c]
    return now, old


class DenseOperator:
    """``p (k, nx, ny) -> M p (2, nx, ny)`` for a dense (2n, k·n) matrix (private helper)."""

    def __init__(self, M, shape):
        self.M = np.ascontiguousarray(M)
        self.shape = shape

    def __call__(self, p):
        out = self.M @ np.asarray(p).reshape(-1)
        return out.reshape((2,) + self.shape)


def preconditioner_kernel(now_t, sg: StripGrid) -> np.ndarray:
    """An offset-layout kernel (2, 2, 2nx−1, 2ny−1) carrying the self and upstream
    coefficients of the middle element (what ``newton_step`` uses to precondition)."""
    nx, ny = sg.shape
    n = nx * ny
    i, j = nx // 2, ny // 2
    q, up = i * ny + j, (i + 1) * ny + j
    ker = np.zeros((2, 2, 2 * nx - 1, 2 * ny - 1))
    for t in range(2):
        for c in range(2):
            ker[t, c, nx - 1, ny - 1] = now_t[t * n + q, c * n + q]
            if i + 1 < nx:
                ker[t, c, nx - 2, ny - 1] = now_t[t * n + q, c * n + up]
    return ker
