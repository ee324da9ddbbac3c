"""Ayasse's contact-angle-function tables (normal/caf.py) against seed 003 §2.3.

References: the seed's relations — the CAF as a few lines with jump limits
(§2.3.2), the wheel radius recovered from its slope, R_rx + R_wx =
−1/(cos γ dγ/dt_y) (§2.3.2), and the overlap of eq. (3), "large on the tread,
of the order δ/2 when flanging" (§2.3.3); the profile curvatures computed
independently by the contact search (find_points), and the nominal head radii
of 60E1 (R300, R80, R13; EN 13674-1).
"""

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.contact.wheelrail import touching_heights
from wheelrail.errors import InputError
from wheelrail.geometry.contact_search import _Pose, find_points
from wheelrail.normal.caf import caf_table, jump_overlap


@pytest.fixture(scope="module")
def pair():
    ws = wr.Wheelset(wheel=wr.profiles.load("S1002"), nominal_radius=0.46, flange_back=1.360)
    tr = wr.Track(rail=wr.profiles.load("60E1"), gauge=1.435, inclination=1 / 40)
    return ws, tr


@pytest.fixture(scope="module")
def table(pair):
    return caf_table(*pair, "right", (-0.01, 0.01), tolerance=2e-4)


def _rigid(pair, y):
    ws, tr = pair
    zero = np.zeros(y.size)
    z, _ = touching_heights(ws, tr, y, zero, zero)
    d, _ = find_points(ws, tr, "right", _Pose(y, z["right"], zero, zero), tolerance=1e-9)
    k = np.nanargmin(d["separation"], axis=1)
    r = np.arange(y.size)
    return {f: d[f][r, k] for f in ("contact_angle", "wheel_y", "wheel_curvature_y")}


def test_few_lines_reproduce_the_caf(pair, table):
    """Off the sampled shifts the lines stay within the tolerance (+ sampling error)."""
    y = np.arange(-0.01, 0.01, 5e-5)[:-1] + 2.5e-5            # midway between samples
    ref = _rigid(pair, y)
    near = np.min(np.abs(y[:, None] - table.jumps[None, :]), axis=1) < 1e-4
    g, _ = table.contact_angle(y)
    # tread (before the flange root, where γ changes by up to 0.08 rad per 0.05 mm sample
    # and the error between samples is the sampling's, not the lines')
    tread = ~near & (y < 0.0048)
    assert np.max(np.abs(g - ref["contact_angle"])[tread]) < 3 * table.tolerance
    # at the sampled shifts: within the tolerance everywhere (the simplification's bound)
    ys = np.arange(table.samples) * 5e-5 - 0.01
    on = np.min(np.abs(ys[:, None] - table.jumps[None, :]), axis=1) > 5e-5
    gs, _ = table.contact_angle(ys[on])
    assert np.max(np.abs(gs - _rigid(pair, ys[on])["contact_angle"])) <= table.tolerance * 1.0001
    assert table.y.size < 80                                  # "only a few lines"
    # jumps where the contact point jumps (wheel coordinate), within the sampling step
    wj = y[np.nonzero(np.abs(np.diff(ref["wheel_y"])) > 1e-3)[0]] + 2.5e-5
    assert wj.size == table.jumps.size
    np.testing.assert_allclose(table.jumps, wj, atol=5e-5)


def test_rail_radii_are_the_60E1_head_radii(table):
    radii = np.unique(np.round(table.rail_radius * 1e3))
    for r in (300.0, 80.0, 13.0):
        assert np.min(np.abs(radii - r)) <= 0.5


def test_wheel_radius_from_the_caf_slope(pair, table):
    """R_rx + R_wx = −1/(cos γ dγ/dt_y) recovers the wheel profile radius."""
    same = (table.branch[:-1] == table.branch[1:]) & (np.diff(table.y) > 2e-4)
    mid = (0.5 * (table.y[:-1] + table.y[1:]))[same]
    prof = 1.0 / _rigid(pair, mid)["wheel_curvature_y"]
    caf = table.wheel_radius(mid)
    use = np.abs(prof) < 2.5
    assert use.sum() >= 10
    np.testing.assert_allclose(caf[use], prof[use], rtol=0.03)
    flange = mid > 0.008
    np.testing.assert_allclose(caf[flange], 0.020, rtol=0.01)   # S1002 flange R20


def test_overlap_eq3(table):
    g1, g2, d = 0.03, 0.06, 1e-4
    assert jump_overlap(g1, g2, d) == pytest.approx(np.cos(g1) * d / 2 / np.tan(g2 - g1))
    # on the tread (small angle jump) the overlap is large; flanging it is of order δ/2
    tread = table.overlaps(0, d, d)
    flange = table.overlaps(table.jumps.size - 1, d, d)
    assert min(tread) > 10 * d / 2
    assert 0.3 * d / 2 < max(flange) < 3 * d / 2
    with pytest.raises(InputError, match="gamma2"):
        jump_overlap(0.1, 0.1, d)
    with pytest.raises(InputError, match="delta1"):
        jump_overlap(0.1, 0.2, -1e-5)


def test_bad_input_named(pair):
    with pytest.raises(InputError, match="step"):
        caf_table(*pair, "right", (-0.01, 0.01), step=0.0)
    with pytest.raises(InputError, match="range"):
        caf_table(*pair, "right", (0.01, -0.01))
