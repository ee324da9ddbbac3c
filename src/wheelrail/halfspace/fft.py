"""Matrix-free influence operators by zero-padded FFT convolution.

On a uniform grid the influence matrix is a (block-)Toeplitz matrix: the
displacement of element (a, b) due to element (c, d) depends only on the
offset (a − c, b − d). Its product with a field is a discrete linear
convolution, evaluated exactly (to round-off) with real FFTs of size
≥ (2nx − 1) × (2ny − 1) and the kernel stored in wrap-around order
(no aliasing: every offset has its own slot). Cost O(N log N) per product,
memory O(N), instead of O(N²) for the dense matrix.

References
----------
.. [1] H.M. Stanley, T. Kato, An FFT-based method for rough surface contact,
   J. Tribol. 119 (1997) 481–485.
.. [2] S. Liu, Q. Wang, G. Liu, A versatile method of discrete convolution and
   FFT (DC-FFT) for contact analyses, Wear 243 (2000) 101–111.
"""

from __future__ import annotations

import numpy as np
import scipy.fft as sfft

from ..errors import InputError
from ..materials import as_material_pair
from ._memo import grid_key, memo
from .influence import influence_kernel

__all__ = ["ConvolutionOperator", "InfluenceOperator", "influence_operator"]


def _fft_shape(nx: int, ny: int) -> tuple[int, int]:
    return (sfft.next_fast_len(2 * nx - 1, real=True), sfft.next_fast_len(2 * ny - 1, real=True))


def _kernel_transform(kernel, shape, workers: int = 1) -> np.ndarray:
    """rfft2 over the last two axes of kernel(s) (..., 2nx − 1, 2ny − 1) padded to ``shape``.

    Wrap-around order: the kernel entry of offset ``m`` goes to slot ``m mod N``.
    """
    k = np.asarray(kernel, dtype=float)
    nx, ny = (k.shape[-2] + 1) // 2, (k.shape[-1] + 1) // 2
    wrapped = np.zeros(k.shape[:-2] + tuple(shape))
    ix = np.arange(-(nx - 1), nx) % shape[0]
    iy = np.arange(-(ny - 1), ny) % shape[1]
    wrapped[..., ix[:, None], iy[None, :]] = k
    return sfft.rfft2(wrapped, axes=(-2, -1), workers=workers)


def _padded_rfft2(field, shape, workers: int = 1) -> np.ndarray:
    """``rfft2(field, s=shape)`` over the last two axes, axis by axis (private).

    The field (..., nx, ny) is zero-padded to ``shape``; transforming along y
    first touches only its ``nx`` rows instead of all ``shape[0]``.
    """
    spec = sfft.rfft(field, n=shape[1], axis=-1, workers=workers)
    return sfft.fft(spec, n=shape[0], axis=-2, overwrite_x=True, workers=workers)


def _cropped_irfft2(spectrum, shape, nx, ny, workers: int = 1) -> np.ndarray:
    """``irfft2(spectrum, s=shape)[..., :nx, :ny]``, back-transforming only the kept rows."""
    rows = sfft.ifft(spectrum, n=shape[0], axis=-2, workers=workers)[..., :nx, :]
    return sfft.irfft(rows, n=shape[1], axis=-1, workers=workers)[..., :ny]


class ConvolutionOperator:
    """Apply one influence kernel to fields on a grid by zero-padded FFT.

    Parameters
    ----------
    kernel2d : array_like, shape (2nx − 1, 2ny − 1)
        ``kernel2d[kx, ky]`` is the response at offset ``(kx − (nx−1), ky − (ny−1))``
        elements from a unit source (layout of
        :func:`~wheelrail.halfspace.influence.influence_kernel`).
    workers : int, optional
        Threads for :mod:`scipy.fft` (default 1).

    Notes
    -----
    ``op(field)[a, b] = Σ_{c,d} kernel2d[a − c + nx − 1, b − d + ny − 1] · field[c, d]``,
    equal to :meth:`dense` ``@ field.ravel()`` to round-off. The kernel
    transform is computed once here; the operator is immutable.
    """

    __slots__ = ("nx", "ny", "fft_shape", "workers", "_kernel", "_kernel_hat")

    def __init__(self, kernel2d, *, workers: int = 1):
        k = np.asarray(kernel2d, dtype=float)
        if k.ndim != 2 or k.shape[0] % 2 == 0 or k.shape[1] % 2 == 0:
            raise InputError(f"kernel2d must have shape (2nx-1, 2ny-1) (odd sizes), got {k.shape}")
        if not np.all(np.isfinite(k)):
            raise InputError("kernel2d must be finite")
        nx, ny = (k.shape[0] + 1) // 2, (k.shape[1] + 1) // 2
        self.nx, self.ny = nx, ny
        self.fft_shape = _fft_shape(nx, ny)
        self.workers = int(workers)
        self._kernel = k
        self._kernel.setflags(write=False)
        self._kernel_hat = _kernel_transform(k, self.fft_shape, self.workers)
        self._kernel_hat.setflags(write=False)

    @property
    def shape(self) -> tuple[int, int]:
        """Field shape ``(nx, ny)``."""
        return (self.nx, self.ny)

    @property
    def kernel(self) -> np.ndarray:
        """The kernel (read-only), shape (2nx − 1, 2ny − 1)."""
        return self._kernel

    def _check(self, field) -> np.ndarray:
        f = np.asarray(field, dtype=float)
        if f.shape[-2:] != self.shape:
            raise InputError(f"field must have trailing shape {self.shape}, got {f.shape}")
        return f

    def forward(self, field) -> np.ndarray:
        """Padded spectrum of ``field`` (shape (..., nx, ny)), for reuse with :meth:`backward`.

        Equal to ``rfft2(field, s=fft_shape)``, computed axis by axis so that
        the zero padding rows are not transformed along y.
        """
        return _padded_rfft2(self._check(field), self.fft_shape, self.workers)

    def backward(self, spectrum) -> np.ndarray:
        """Field (..., nx, ny) from a spectrum already multiplied by a kernel transform.

        Equal to ``irfft2(spectrum, s=fft_shape)[..., :nx, :ny]``; only the
        ``nx`` rows kept are transformed back along y.
        """
        return _cropped_irfft2(spectrum, self.fft_shape, self.nx, self.ny, self.workers)

    def multiply(self, spectrum) -> np.ndarray:
        """Spectrum times the kernel transform."""
        return spectrum * self._kernel_hat

    def apply(self, field) -> np.ndarray:
        """Convolve ``field`` of shape (..., nx, ny) with the kernel; same shape out."""
        return self.backward(self.forward(field) * self._kernel_hat)

    __call__ = apply

    def dense(self) -> np.ndarray:
        """Dense matrix (nx·ny, nx·ny) of the operator (C order, index ``a·ny + b``).

        Reference for small grids and tests; O(N²) memory.
        """
        nx, ny = self.shape
        a = np.arange(nx)
        b = np.arange(ny)
        dxi = a[:, None] - a[None, :] + nx - 1          # (nx, nx)
        dyi = b[:, None] - b[None, :] + ny - 1          # (ny, ny)
        m = self._kernel[dxi[:, None, :, None], dyi[None, :, None, :]]  # (nx, ny, nx, ny)
        return m.reshape(nx * ny, nx * ny)


class InfluenceOperator:
    """The 3 × 3 block influence operator of a grid for two elastic half-spaces.

    Parameters
    ----------
    grid : Grid
    materials : Material or MaterialPair
    workers : int, optional
        Threads for :mod:`scipy.fft` (default 1).

    Attributes
    ----------
    grid : Grid
    materials : MaterialPair
    kernel : ndarray, shape (3, 3, 2nx − 1, 2ny − 1)
        :func:`~wheelrail.halfspace.influence.influence_kernel` (read-only).
    coupled : bool
        True when the normal–tangential coupling (Kalker's K ≠ 0) is present.

    Notes
    -----
    Components ``0: x, 1: y, 2: n`` with the sign conventions of
    :mod:`wheelrail.halfspace.influence`: tractions act on the wheel,
    ``p[2]`` is the pressure (compression positive), ``u = u(wheel) − u(rail)``
    and ``u[2]`` opens the gap (deformed gap ``e = h0 − δ + u[2]``).
    Blocks that vanish (the coupling blocks when ``K = 0``) are skipped.

    Examples
    --------
    >>> import numpy as np, wheelrail as wr
    >>> from wheelrail.halfspace import Grid, InfluenceOperator
    >>> op = InfluenceOperator(Grid.from_bounds(-1e-3, 1e-3, -1e-3, 1e-3, 8, 8), wr.STEEL)
    >>> u = op.apply(np.ones((3, 8, 8)) * 1e8)
    >>> u.shape
    (3, 8, 8)
    """

    def __init__(self, grid, materials, *, workers: int = 1):
        self.grid = grid
        self.materials = as_material_pair(materials)
        kernel = influence_kernel(grid, self.materials)
        kernel.setflags(write=False)
        self.kernel = kernel
        self.coupled = self.materials.K != 0.0
        self.workers = int(workers)
        self._nonzero = {(i, j) for i in range(3) for j in range(3) if np.any(kernel[i, j] != 0.0)}
        self._cache = {}   # block operators are built (kernel FFT) on first use

    def _op(self, i, j):
        if (i, j) not in self._nonzero:
            return None
        op = self._cache.get((i, j))
        if op is None:
            op = self._cache[i, j] = ConvolutionOperator(self.kernel[i, j], workers=self.workers)
        return op

    @property
    def shape(self) -> tuple[int, int]:
        """Grid shape ``(nx, ny)``."""
        return self.grid.shape

    def block(self, i: int, j: int):
        """The :class:`ConvolutionOperator` of block (i, j), or ``None`` if it is zero."""
        self._check_index(i, j)
        return self._op(i, j)

    @staticmethod
    def _check_index(i, j):
        if i not in (0, 1, 2) or j not in (0, 1, 2):
            raise InputError(f"block indices must be 0 (x), 1 (y) or 2 (n), got ({i!r}, {j!r})")

    def apply_block(self, i: int, j: int, field) -> np.ndarray:
        """Displacement difference ``u_i`` [m] due to traction component ``j`` [Pa].

        ``field`` has shape (..., nx, ny); returns the same shape (zeros for a
        vanishing block).
        """
        self._check_index(i, j)
        op = self._op(i, j)
        f = np.asarray(field, dtype=float)
        if f.shape[-2:] != self.shape:
            raise InputError(f"field must have trailing shape {self.shape}, got {f.shape}")
        if op is None:
            return np.zeros(f.shape)
        return op.apply(f)

    def apply(self, p) -> np.ndarray:
        """Displacement differences (3, nx, ny) [m] of tractions ``p`` (3, nx, ny) [Pa].

        ``p = (px, py, pn)``; ``u[i] = Σ_j A_ij * p[j]``. Each component is
        transformed once.
        """
        p = np.asarray(p, dtype=float)
        if p.shape != (3,) + self.shape:
            raise InputError(f"p must have shape {(3,) + self.shape}, got {p.shape}")
        return self._apply_components(p, range(3), range(3))

    def apply_tangential(self, px, py) -> np.ndarray:
        """``(u_x, u_y)`` (2, nx, ny) [m] of tangential tractions ``px``, ``py`` [Pa] only."""
        p = np.stack([np.asarray(px, float), np.asarray(py, float)])
        if p.shape != (2,) + self.shape:
            raise InputError(f"px, py must have shape {self.shape}, got {p.shape[1:]}")
        return self._apply_components(p, range(2), range(2))

    def apply_normal(self, pn) -> np.ndarray:
        """``u_n`` (nx, ny) [m] (gap-opening) of the pressure ``pn`` [Pa] only."""
        return self.apply_block(2, 2, pn)

    def _apply_components(self, p, rows, cols):
        any_op = self._op(2, 2)
        spectra = {j: any_op.forward(p[k]) for k, j in enumerate(cols)}
        out = np.zeros((len(rows),) + self.shape)
        for r, i in enumerate(rows):
            acc = None
            for j in cols:
                op = self._op(i, j)
                if op is None:
                    continue
                term = op.multiply(spectra[j])
                acc = term if acc is None else acc + term
            if acc is not None:
                out[r] = any_op.backward(acc)
        return out

    def dense_matrix(self, i: int, j: int) -> np.ndarray:
        """Dense block (nx·ny, nx·ny) of A_ij (C order, element index ``a·ny + b``)."""
        self._check_index(i, j)
        op = self._op(i, j)
        if op is None:
            return np.zeros((self.grid.size, self.grid.size))
        return op.dense()

    def __repr__(self) -> str:
        return (f"InfluenceOperator(grid={self.grid.nx}x{self.grid.ny}, G={self.materials.G:.4g}, "
                f"nu={self.materials.nu:.4g}, K={self.materials.K:.4g})")


def influence_operator(grid, materials) -> "InfluenceOperator":
    """The :class:`InfluenceOperator` of ``grid`` (shared: same-sized grids reuse one).

    The operator depends only on element size and counts and the materials;
    it is immutable apart from its lazily built block transforms.
    """

    pair = as_material_pair(materials)
    return memo(("operator",) + grid_key(grid, pair), lambda: InfluenceOperator(grid, pair))
