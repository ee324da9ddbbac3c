"""Property tests of Kalker's exact theory (steady rolling on a half-space grid).

Invariants of Coulomb's law that must hold for any creepage: |p_t| ≤ μ pn on
every element, |F_t| ≤ μ Fn, traction at the bound and opposite to the slip
in the slip area, zero slip in the adhesion area (Kalker 1990, eqs. 2.9–2.12).
"""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import wheelrail as wr
from wheelrail.tangential.exact import solve_rolling

HC = wr.hertz(1e4, A=1.0, B=2.0, material=wr.STEEL)
MU = 0.3


@pytest.fixture(scope="module")
def patch(hertz_patch16):
    return hertz_patch16  # grid and pressure of HC (tests/conftest.py)


@settings(max_examples=15, deadline=None)
@given(xi=st.floats(-3e-3, 3e-3), eta=st.floats(-3e-3, 3e-3), phi=st.floats(-5.0, 5.0))
def test_coulomb_bound_and_slip_direction(patch, xi, eta, phi):
    grid, p = patch
    s = solve_rolling(grid, p, wr.STEEL, (xi, eta, phi), MU)
    g = MU * p
    pt = np.hypot(s.px, s.py)
    assert np.all(pt <= g * (1 + 1e-9) + 1e-9)
    assert s.Ft <= MU * p.sum() * grid.element_area * (1 + 1e-9)
    # in the slip zone the traction is at the bound and opposes the slip
    sl = s.slip
    if sl.any():
        np.testing.assert_allclose(pt[sl], g[sl], rtol=1e-9)
        dot = (s.px * s.sx + s.py * s.sy)[sl]
        norm = (pt * np.hypot(s.sx, s.sy))[sl]
        assert np.all(dot <= -0.999 * norm)
    assert np.all(s.sx[s.adhesion] == 0) and np.all(s.sy[s.adhesion] == 0)
