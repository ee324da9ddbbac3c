"""The transient stepper's block convolution gives the products of the halfspace one."""

import numpy as np
import pytest

from wheelrail.halfspace.rolling import _BlockConvolution
from wheelrail.transient._fft import FastBlockConvolution


@pytest.mark.parametrize("m, k, nx, ny", [(2, 2, 36, 33), (2, 1, 9, 7), (2, 3, 12, 20)])
def test_same_products_as_the_halfspace_convolution(m, k, nx, ny):
    rng = np.random.default_rng(1)
    K = rng.standard_normal((m, k, 2 * nx - 1, 2 * ny - 1))
    p = rng.standard_normal((k, nx, ny))
    ref, fast = _BlockConvolution(K), FastBlockConvolution(K)
    # direct sum for one output element (independent of any FFT)
    i, j = nx // 2, ny // 3
    direct = sum(K[0, b, i - c + nx - 1, j - d + ny - 1] * p[b, c, d]
                 for b in range(k) for c in range(nx) for d in range(ny))
    assert fast(p)[0, i, j] == pytest.approx(direct, rel=1e-10, abs=1e-10)
    # the same transforms; the 2 × 2 frequency products are a numba loop (numpy's SIMD
    # complex multiply may round differently): equal to round-off
    scale = np.abs(ref(p)).max()
    assert np.allclose(fast(p), ref(p), rtol=0, atol=1e-14 * scale)
    assert fast.single(p).dtype == np.float32
    assert np.allclose(fast.single(p), ref.single(p), rtol=0, atol=1e-6 * np.abs(ref(p)).max())
