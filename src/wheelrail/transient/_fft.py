"""Block FFT convolution of the transient stepper with fewer layers of dispatch (private).

The transient run makes about ten thousand small convolutions (a 2 × 2 block on
the contact's box, ~72 × 72 FFT); half of the time of each went to the
argument handling of :mod:`scipy.fft` around the transforms. This class makes
the same zero-padded transforms as
:class:`wheelrail.halfspace.rolling._BlockConvolution` (same kernel transform,
same numbers to round-off) by calling scipy's pocketfft binding directly with
preallocated padding buffers, and falls back to :mod:`scipy.fft` when that
binding is not available.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..halfspace.rolling import _block_multiply, _BlockConvolution

try:  # scipy's own binding of pocketfft (present since scipy 1.4)
    from scipy.fft._pocketfft import pypocketfft as _pp
except ImportError:  # pragma: no cover - other scipy builds
    _pp = None


@njit(cache=True)
def _multiply_2x2(hat, ph, out):
    """``out[a] = hat[a, 0] ph[0] + hat[a, 1] ph[1]`` per frequency (in place).

    One pass instead of the four products and two sums of numpy calls (the same
    numbers to round-off: numpy's SIMD complex product may round differently).
    """
    for i in range(ph.shape[1]):
        for j in range(ph.shape[2]):
            x = ph[0, i, j]
            y = ph[1, i, j]
            out[0, i, j] = hat[0, 0, i, j] * x + hat[0, 1, i, j] * y
            out[1, i, j] = hat[1, 0, i, j] * x + hat[1, 1, i, j] * y


class FastBlockConvolution:
    """``p (k, nx, ny) -> K p (m, nx, ny)`` like ``_BlockConvolution(kernel)``.

    ``__call__`` in double precision, :meth:`single` in single precision (the
    Krylov products).
    """

    def __init__(self, kernel):
        base = _BlockConvolution(kernel)
        self._base = base
        self.nx, self.ny, self.shape, self.hat = base.nx, base.ny, base.shape, base.hat
        self._hat32 = None
        self._buf = {}

    def _buffers(self, k, m, dtype):
        """Work arrays: padded input, half spectrum (padding rows zero), transform, product."""
        key = (k, m, dtype)
        if key not in self._buf:
            real = np.dtype(dtype)
            cplx = np.result_type(real, np.complex64)
            nxf, nyf = self.shape
            self._buf[key] = (np.zeros((k, self.nx, nyf), real),
                              np.zeros((k, nxf, nyf // 2 + 1), cplx),
                              np.empty((k, nxf, nyf // 2 + 1), cplx),
                              np.empty((m, nxf, nyf // 2 + 1), cplx))
        return self._buf[key]

    def _apply(self, p, hat, dtype):
        if _pp is None:
            return self._base(p) if dtype == np.float64 else self._base.single(p)
        k = np.shape(p)[0]
        xr, xc, ph, uh = self._buffers(k, hat.shape[0], dtype)
        xr[:, :, :self.ny] = p  # the padding columns stay zero
        _pp.r2c(xr, (2,), True, 0, xc[:, :self.nx], 1)  # the padding rows stay zero
        _pp.c2c(xc, (1,), True, 0, ph, 1)
        if hat.shape[:2] == (2, 2):
            _multiply_2x2(hat, ph, uh)
        else:
            _block_multiply(hat, ph, uh)
        _pp.c2c(uh, (1,), False, 2, uh, 1)
        return _pp.c2r(uh[:, :self.nx], (2,), self.shape[1], False, 2, None, 1)[:, :, :self.ny]

    def __call__(self, p):
        """Double-precision product."""
        return self._apply(p, self.hat, np.float64)

    def single(self, p):
        """Single-precision product (float32 result), as ``_BlockConvolution.single``."""
        if self._hat32 is None:
            self._hat32 = self.hat.astype(np.complex64)
        return self._apply(p, self._hat32, np.float32)
