"""FFT approximate inverse of the normal influence operator (a preconditioner).

The normal influence coefficients of piecewise-constant pressure elements
(size dx × dy) collocated at the element centres are, far from the source,
``a_m ≈ c dx dy / |r_m|`` with ``r_m = (m_x dx, m_y dy)``: the operator is a
discretisation of the single-layer potential ``u = c ∫ p(y) / |x − y| dy``.
On the infinite grid the Toeplitz operator is diagonal in Fourier space with
the symbol (Poisson summation over the aliases ``K_j = 2π (j_x/dx, j_y/dy)``,
``k = (θ_x/dx, θ_y/dy)``, ``θ ∈ [−π, π]²``)::

    Â(θ) = Σ_j  2π c / |k + K_j| · sinc((k + K_j)_x dx/2) · sinc((k + K_j)_y dy/2)

(``sinc(s) = sin s / s``: the transform of one element). Its reciprocal
``1/Â`` behaves like ``|k| / (2π c)``, the symbol of a first-order
differential operator with a rapidly decaying (∝ 1/r³) stencil; applied as a
circulant on a grid only a few elements larger than the field, it is a
spectrally equivalent approximate inverse of the influence matrix. The
alias sum is truncated at ``|j_x|, |j_y| ≤ 1`` (further terms change the
iteration counts of the normal solver by at most one) and the mean (θ = 0)
is mapped to zero; the constant is read off the kernel's far field, so the
approximation follows the operator it is built from (materials, element
shape). Used by the preconditioned bound-constrained conjugate-gradient
solver :func:`wheelrail.normal.bem.polonsky_keer`.

Why not the circulant embedding's own transform: the transform of the
wrapped, zero-padded kernel (the one that makes the convolution exact) is
the symbol truncated to offsets within the grid; at high frequencies it is
small and of either sign (down to −4e-4 of its maximum for elements of
aspect 1.6), and with its reciprocal the iteration stalled (not converged in
500 iterations on 115² and 177² grids).

References
----------
.. [1] E.A.H. Vollebregt, A new solver for the elastic normal contact problem
   using conjugate gradients, deflation, and an FFT-based preconditioner,
   J. Comput. Phys. 257 (2014) 333–351 (the FFT-based approximate inverse
   inside the constrained CG).
.. [2] K.L. Johnson, *Contact Mechanics*, CUP 1985, §3.2 (the point-load
   kernel ∝ 1/r of the half-space).
"""

from __future__ import annotations

import numpy as np
import scipy.fft as sfft

from ..errors import InputError

__all__ = ["InverseSymbolPreconditioner"]

_PAD = 8      # elements of zero padding of the periodic grid on each axis


class InverseSymbolPreconditioner:
    """Apply ``1/Â`` (the FFT approximate inverse of a normal influence operator).

    Parameters
    ----------
    kernel2d : array_like, shape (2nx − 1, 2ny − 1)
        Normal influence kernel [m/Pa] in the layout of
        :func:`~wheelrail.halfspace.influence.influence_kernel` (entry
        ``[nx − 1, ny − 1]`` is the self-influence), > 0 in its far field.
    dx, dy : float
        Element size [m].
    aliases : int, optional
        Alias terms ``|j| ≤ aliases`` per axis in the symbol (default 1).

    Notes
    -----
    :meth:`apply` maps a pressure-like field (nx, ny) [m] to a pressure-like
    field [Pa]: zero padding to a periodic grid of ``fft_shape`` (at least
    ``nx + 8`` × ``ny + 8``), one real FFT pair in single precision, cropping. The operator is
    symmetric positive semi-definite (its null space is the constant of the
    periodic grid). Immutable.
    """

    __slots__ = ("nx", "ny", "fft_shape", "c", "_inv")

    def __init__(self, kernel2d, dx: float, dy: float, *, aliases: int = 1):
        k = np.asarray(kernel2d, dtype=float)
        if k.ndim != 2 or k.shape[0] % 2 == 0 or k.shape[1] % 2 == 0:
            raise InputError(f"kernel2d must have shape (2nx-1, 2ny-1) (odd sizes), got {k.shape}")
        nx, ny = (k.shape[0] + 1) // 2, (k.shape[1] + 1) // 2
        if nx < 2 and ny < 2:
            raise InputError("the preconditioner needs a grid of at least 2 elements")
        self.nx, self.ny = nx, ny
        # far field a_m ≈ c dx dy / r along the longer axis of the window
        if (nx - 1) * dx >= (ny - 1) * dy:
            r, far = (nx - 1) * dx, k[-1, ny - 1]
        else:
            r, far = (ny - 1) * dy, k[nx - 1, -1]
        c = far * r / (dx * dy)
        if not (np.isfinite(c) and c > 0.0):
            raise InputError(f"the kernel's far field must be positive (got c = {c!r})")
        self.c = float(c)
        self.fft_shape = (sfft.next_fast_len(nx + _PAD, real=True),
                          sfft.next_fast_len(ny + _PAD, real=True))
        inv = _inverse_symbol(self.c, dx, dy, self.fft_shape, int(aliases))
        self._inv = inv.astype(np.float32)
        self._inv.setflags(write=False)

    def apply(self, field) -> np.ndarray:
        """``M field`` for a field of shape (nx, ny); same shape out (float32).

        Computed in single precision (float32 FFTs): a preconditioner needs
        no more, and it is about four times faster than double precision.
        """
        spec = sfft.rfft2(np.asarray(field, dtype=np.float32), s=self.fft_shape)
        spec *= self._inv
        return sfft.irfft2(spec, s=self.fft_shape)[:self.nx, :self.ny]

    __call__ = apply


def _inverse_symbol(c, dx, dy, shape, aliases):
    """1/Â on the rfft2 frequencies of a periodic grid ``shape`` (0 at θ = 0)."""
    kx = (2.0 * np.pi / dx) * np.fft.fftfreq(shape[0])[:, None]
    ky = (2.0 * np.pi / dy) * np.fft.rfftfreq(shape[1])[None, :]
    sym = np.zeros((shape[0], shape[1] // 2 + 1))
    for jx in range(-aliases, aliases + 1):
        qx = kx + 2.0 * np.pi * jx / dx
        sx = np.sinc(qx * dx / (2.0 * np.pi))           # numpy's sinc is sin(πs)/(πs)
        for jy in range(-aliases, aliases + 1):
            qy = ky + 2.0 * np.pi * jy / dy
            q = np.hypot(qx, qy)
            with np.errstate(divide="ignore"):
                sym += (2.0 * np.pi * c) / q * sx * np.sinc(qy * dy / (2.0 * np.pi))
    sym[0, 0] = np.inf
    return 1.0 / sym
