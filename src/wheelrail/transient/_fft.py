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

from ..halfspace.rolling import _block_multiply, _BlockConvolution

try:  # scipy's own binding of pocketfft (present since scipy 1.4)
    from scipy.fft._pocketfft import pypocketfft as _pp
except ImportError:  # pragma: no cover - other scipy builds
    _pp = None


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

    def _buffers(self, k, dtype):
        key = (k, dtype)
        if key not in self._buf:
            real = np.dtype(dtype)
            cplx = np.result_type(real, np.complex64)
            nxf, nyf = self.shape
            self._buf[key] = (np.zeros((k, self.nx, nyf), real),
                              np.zeros((k, nxf, nyf // 2 + 1), cplx))
        return self._buf[key]

    def _apply(self, p, hat, dtype):
        if _pp is None:
            return self._base(p) if dtype == np.float64 else self._base.single(p)
        k = p.shape[0]
        xr, xc = self._buffers(k, dtype)
        xr[:, :, :self.ny] = p  # the padding columns stay zero
        spec = _pp.r2c(xr, (2,), True, 0, None, 1)
        xc[:, :self.nx] = spec  # the padding rows stay zero
        ph = _pp.c2c(xc, (1,), True, 0, None, 1)
        uh = np.empty((hat.shape[0],) + ph.shape[1:], dtype=ph.dtype)
        _block_multiply(hat, ph, uh)
        rows = _pp.c2c(uh, (1,), False, 2, None, 1)[:, :self.nx]
        return _pp.c2r(rows, (2,), self.shape[1], False, 2, None, 1)[:, :, :self.ny]

    def __call__(self, p):
        """Double-precision product."""
        return self._apply(np.asarray(p, dtype=float), self.hat, np.float64)

    def single(self, p):
        """Single-precision product (float32 result), as ``_BlockConvolution.single``."""
        if self._hat32 is None:
            self._hat32 = self.hat.astype(np.complex64)
        return self._apply(np.asarray(p, dtype=np.float32), self._hat32, np.float32)
