"""FFT operators of the rolling problem on a half-space grid (kernels).

The rolling kernel M(m) = (C(m) − C(m + e_x)) / dx (Kalker 1990, §5.2: the
backward difference of the influence kernel along the rolling direction), the
2 × 2 block convolution of (px, py) with it or with C, and the contact's
bounding box on which steady-rolling products are made. Sign conventions as
in :mod:`wheelrail.halfspace.influence`.

References
----------
.. [1] J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
   Kluwer 1990, §5.2.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..materials import as_material_pair
from ._memo import grid_key, memo
from .fft import _cropped_irfft2, _fft_shape, _kernel_transform, _padded_rfft2
from .grid import Grid
from .influence import influence_kernel


# --------------------------------------------------------------------------
# operators
# --------------------------------------------------------------------------
def _block_multiply(hat, ph, out):
    """``out[a] = Σ_b hat[a, b] · ph[b]`` per frequency (complex; in place).

    The 2 × 2 block (the tangential products of every Krylov iteration) by
    in-place numpy operations, which vectorise; other shapes by a numba loop.
    """
    if hat.shape[:2] != (2, 2):
        _block_multiply_loop(hat, ph, out)
        return
    tmp = np.empty_like(out[0])
    for a in (0, 1):
        np.multiply(hat[a, 0], ph[0], out=out[a])
        np.multiply(hat[a, 1], ph[1], out=tmp)
        out[a] += tmp


@njit(cache=True)
def _block_multiply_loop(hat, ph, out):
    """``out[a] = Σ_b hat[a, b] · ph[b]`` per frequency, any block shape (in place)."""
    m, k = hat.shape[0], hat.shape[1]
    n0, n1 = ph.shape[1], ph.shape[2]
    for i in range(n0):
        for j in range(n1):
            for a in range(m):
                acc = 0j
                for b in range(k):
                    acc += hat[a, b, i, j] * ph[b, i, j]
                out[a, i, j] = acc


class _BlockConvolution:
    """FFT convolution with a block kernel (m, k, 2nx−1, 2ny−1) on an (nx, ny) grid (private).

    Same zero-padded wrap-around layout (and kernel transform) as
    :class:`~wheelrail.halfspace.fft.ConvolutionOperator`, but for a block of
    kernels sharing the forward transforms of the ``k`` input fields. The
    2-D transforms are done axis by axis so that the zero padding rows are
    never transformed along y (forward) and only the ``nx`` rows needed are
    transformed back (the same numbers as ``rfft2``/``irfft2``).
    """

    def __init__(self, kernel):
        self.nx = (np.shape(kernel)[-2] + 1) // 2
        self.ny = (np.shape(kernel)[-1] + 1) // 2
        self.shape = _fft_shape(self.nx, self.ny)
        self.hat = np.ascontiguousarray(_kernel_transform(kernel, self.shape))
        self.hat.setflags(write=False)
        self._hat32 = None

    def __call__(self, p):
        """``u[i] = Σ_j K[i, j] * p[j]`` for ``p`` of shape (k, nx, ny) -> (m, nx, ny)."""
        ph = _padded_rfft2(p, self.shape)
        uh = np.empty((self.hat.shape[0],) + ph.shape[1:], dtype=complex)
        _block_multiply(self.hat, ph, uh)
        return _cropped_irfft2(uh, self.shape, self.nx, self.ny)

    def single(self, p):
        """The product of :meth:`__call__` in single precision (float32 result).

        Relative error about 1e-6 of the largest output: enough for the
        directions of a Krylov method (which only needs a residual reduction
        of 10 per Newton step), about four times cheaper than double precision.
        """
        if self._hat32 is None:
            self._hat32 = self.hat.astype(np.complex64)
        ph = _padded_rfft2(np.asarray(p, dtype=np.float32), self.shape)
        uh = np.empty((self.hat.shape[0],) + ph.shape[1:], dtype=np.complex64)
        _block_multiply(self._hat32, ph, uh)
        return _cropped_irfft2(uh, self.shape, self.nx, self.ny)


def rolling_kernel(grid: Grid, materials) -> np.ndarray:
    """Kernel of the discretised steady-rolling slip, shape (3, 3, 2nx−1, 2ny−1).

    ``M(m) = (C(m) − C(m + e_x)) / dx`` [m/Pa / m = 1/Pa]: the slip
    ``s_I = w_I + Σ_J M(I − J) p_J`` (module docstring). Built from the
    influence kernel of a grid one element longer so that the offset
    ``m + e_x = nx`` is available.
    """
    return _rolling_and_influence_kernels(grid, materials)[0]


def _rolling_and_influence_kernels(grid: Grid, materials):
    """``(M, C)``: :func:`rolling_kernel` and the influence kernel ``C`` of ``grid``.

    Both from one influence kernel of the grid one element longer (``C`` is its
    central part, offsets ``−(nx−1) … nx−1``).
    """
    pair = as_material_pair(materials)

    def build():
        ext = Grid(grid.x0, grid.y0, grid.dx, grid.dy, grid.nx + 1, grid.ny)
        Ce = influence_kernel(ext, pair)
        nx = grid.nx
        C = Ce[:, :, 1:2 * nx, :]
        M = (C - Ce[:, :, 2:2 * nx + 1, :]) / grid.dx
        for a in (M, C):
            a.setflags(write=False)
        return M, C
    return memo(("rolling",) + grid_key(grid, pair), build)


def _contact_box(grid, pair, R, contact):
    """The bounding box of the contact and the rolling kernel / convolution cropped to it.

    Tractions vanish outside the contact and slips are needed only inside it, so
    the steady-rolling products can be made on the box of the contact elements:
    the same products (to round-off) with a smaller FFT (the window around a
    Hertzian contact is about 10 % wider than the contact on each side).
    Returns ``(box, kernel, conv)`` with ``box`` a pair of slices; the full
    grid when cropping does not shrink the transform.
    """
    ii, jj = np.nonzero(contact)
    i0, i1, j0, j1 = int(ii.min()), int(ii.max()) + 1, int(jj.min()), int(jj.max()) + 1
    mx, my = i1 - i0, j1 - j0
    full = (slice(0, grid.nx), slice(0, grid.ny))
    if _fft_shape(mx, my) == _fft_shape(grid.nx, grid.ny):
        return full, R[:2, :2], _block_convolution(grid, pair, "R_tt", R[:2, :2])
    cx, cy = grid.nx - 1, grid.ny - 1
    kernel = R[:2, :2, cx - (mx - 1): cx + mx, cy - (my - 1): cy + my]
    key = ("block-box", mx, my) + grid_key(grid, pair)
    return (slice(i0, i1), slice(j0, j1)), kernel, memo(key, lambda: _BlockConvolution(kernel))


def _block_convolution(grid, pair, which, kernel):
    """The :class:`_BlockConvolution` of a kernel block of ``grid`` (kept for reuse)."""
    return memo(("block", which) + grid_key(grid, pair), lambda: _BlockConvolution(kernel))


