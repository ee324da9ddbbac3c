"""The contact patch lies along the right axes: semi-axis a along x (rolling), b along y.

Reference: Hertz's closed form (``tests/_closed_form.py``, Johnson 1985, §3.7 and §4.2,
complete elliptic integrals), independent of wheelrail. With A < B the ellipse is longer in
the rolling direction (a > b); the patch must say so in its semi-axes, in its strips (across
y, each extending ±a √(1 − (y/b)²) along x) and in its pressure (which carries the load).
"""

import numpy as np
import pytest
from _closed_form import contact_modulus, hertz_load

import wheelrail as wr

ES = contact_modulus(2.1e11, 0.28)
LOAD, A, B = 1e4, 0.5, 4.0                      # a/b = 3.9


@pytest.fixture(scope="module")
def ref():
    r = hertz_load(LOAD, A, B, ES)
    assert r["a"] > 3 * r["b"]
    return r


def _patch(normal, **kw):
    c = wr.hertz(LOAD, A=A, B=B, material=wr.STEEL)
    r = wr.solve(c, creepage=(0.0, 0.0, 0.0), mu=0.3, normal=normal, tangential="fastsim", **kw)
    (p,) = r.patches
    return p.patch


def _extent(p):
    """Half-length along x of the longest strip, half-width across y of all strips [m]."""
    length = float(np.max(p.x_lead - p.x_trail)) / 2
    width = float(p.y.max() - p.y.min() + 0.5 * (p.dy[0] + p.dy[-1])) / 2
    return length, width


def test_hertzian_patch_semi_axes_strips_and_pressure(ref):
    p = _patch("hertz")
    assert p.a == pytest.approx(ref["a"], rel=1e-9)
    assert p.b == pytest.approx(ref["b"], rel=1e-9)
    length, width = _extent(p)
    strips = p.y.size
    # the middle strips' centres lie at ±b/strips: their half-length is a √(1 − 1/strips²)
    assert length == pytest.approx(ref["a"] * np.sqrt(1 - 1 / strips**2), rel=1e-9)
    assert width == pytest.approx(ref["b"], rel=1e-9)
    cell = (p.x_lead - p.x_trail) / p.cells
    assert float(np.sum(p.strip_pressure * (cell * p.dy)[:, None])) == pytest.approx(LOAD,
                                                                                      rel=3e-3)
    assert p.p_max == pytest.approx(ref["p0"], rel=1e-9)
    assert p.area == pytest.approx(np.pi * ref["a"] * ref["b"], rel=1e-9)


def test_boundary_element_patch_equivalent_ellipse(ref):
    """The BEM patch of the same contact: its equivalent ellipse (the patch's area and its
    length/width ratio) and its extent are Hertz's to the grid's resolution (30 elements,
    measured 1 % and 3.3 %)."""
    p = _patch("bem", grid_elements=30)
    assert p.a == pytest.approx(ref["a"], rel=0.03)
    assert p.b == pytest.approx(ref["b"], rel=0.03)
    length, width = _extent(p)
    assert length == pytest.approx(ref["a"], rel=0.06)
    assert width == pytest.approx(ref["b"], rel=0.06)
