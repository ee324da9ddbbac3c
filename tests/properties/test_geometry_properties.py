"""Invariants of the rigid contact geometry (hypothesis)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import wheelrail as wr


_PAIR = {}


def _pair():
    if not _PAIR:
        _PAIR["p"] = (wr.Wheelset(wr.profiles.load("S1002")), wr.Track(wr.profiles.load("60E1")))
    return _PAIR["p"]


@settings(max_examples=12, deadline=None)
@given(y=st.floats(-0.009, 0.009), yaw=st.floats(-0.01, 0.01))
def test_mirror_symmetry(y, yaw):
    """Symmetric wheelset and track: the mirrored position (−y, −ψ) has Δr → −Δr, roll → −roll,
    the same height, and left/right contact points exchanged."""
    ws, tr = _pair()
    a = wr.contact_points(ws, tr, y, yaw)
    b = wr.contact_points(ws, tr, -y, -yaw)
    assert b.delta_r == pytest.approx(-a.delta_r, abs=1e-9)
    assert b.roll == pytest.approx(-a.roll, abs=1e-11)
    assert b.z == pytest.approx(a.z, abs=1e-10)
    pa, pb = a.right.primary, b.left.primary
    assert b.left.wheel_y[pb] == pytest.approx(a.right.wheel_y[pa], abs=1e-6)
    assert b.left.contact_angle[pb] == pytest.approx(a.right.contact_angle[pa], abs=1e-6)
    # the mirror (y -> -y) keeps the longitudinal position of the contact point
    assert b.left.x[pb] == pytest.approx(a.right.x[pa], abs=1e-8)


@settings(max_examples=10, deadline=None)
@given(y=st.floats(-0.008, 0.008))
def test_all_reported_points_are_local_minima(y):
    """Every reported point has non-negative separation (rigid) and a gap that grows nearby."""
    from wheelrail.geometry.contact_search import _gap

    ws, tr = _pair()
    cp = wr.contact_points(ws, tr, y)
    zc = ws.nominal_radius + cp.z
    for side in ("left", "right"):
        p = cp.side(side)
        assert np.all(p.separation > -1e-9)
        assert np.min(p.separation) < 1e-9
        for s in p.wheel_y:
            d = _gap(ws, tr, side, np.array([s - 1e-4, s, s + 1e-4]), np.full(3, y), np.full(3, zc),
                     np.full(3, cp.roll), np.zeros(3))
            assert d[1] <= d[0] + 1e-12 and d[1] <= d[2] + 1e-12
