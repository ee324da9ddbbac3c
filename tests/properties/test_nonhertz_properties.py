"""Invariants of the virtual-penetration methods (hypothesis).

* Kik–Piotrowski's load grows with the penetration (eq. 15 with a growing
  interpenetration region) and, on a quadratic gap, scales as δ^(3/2) like
  Hertz (Johnson 1985 eq. 3.68: N ∝ δ^(3/2) for fixed curvatures);
* a mirrored gap gives the mirrored patch (same load and area).
"""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import wheelrail as wr
from wheelrail.normal._base import GapProblem


def _gp(A, B, pen, c3=0.0, mirror=False):
    s = -1.0 if mirror else 1.0
    return GapProblem(lambda x, y: A * x**2 + B * y**2 + c3 * (s * y) ** 3, wr.STEEL,
                      penetration=pen, search=(-0.03, 0.03, -0.03, 0.03))


@settings(max_examples=12, deadline=None)
@given(A=st.floats(0.3, 5.0), B=st.floats(0.3, 5.0), pen=st.floats(2e-5, 1.5e-4))
def test_load_scales_as_three_halves(A, B, pen):
    m = wr.normal.get("kik-piotrowski")
    o = m
    (p1,) = o.from_gap(_gp(A, B, pen))
    (p2,) = o.from_gap(_gp(A, B, 2 * pen))
    assert p2.Fn > p1.Fn
    assert np.isclose(p2.Fn / p1.Fn, 2**1.5, rtol=0.02)


@settings(max_examples=8, deadline=None)
@given(c3=st.floats(-60.0, 60.0), name=st.sampled_from(["kik-piotrowski", "linder", "stripes"]))
def test_mirror_symmetry(c3, name):
    m = wr.normal.get(name)
    o = m
    a = o.from_gap(_gp(1.0, 3.0, 8e-5, c3))
    b = o.from_gap(_gp(1.0, 3.0, 8e-5, c3, mirror=True))
    assert np.isclose(sum(p.Fn for p in a), sum(p.Fn for p in b), rtol=1e-3)
    assert np.isclose(sum(p.area for p in a), sum(p.area for p in b), rtol=1e-3)
