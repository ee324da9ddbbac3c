"""Non-Hertzian methods on S1002 / 60E1 1:40 (wheel–rail path).

References: the boundary-element solution of the same position (``bem``,
Kalker's exact normal theory, checked by the lead against CONTACT on the
Manchester cases); the contract Σ Fn cos γ = Q of
:class:`wheelrail.normal.NormalMethod`; mirror symmetry of a centred
wheelset. Tolerances are the method errors measured in
docs/nonhertzian.md (benchmarks/bench_nonhertz.py), not tuned to pass.
"""

import numpy as np
import pytest

import wheelrail as wr

METHODS = [("kik-piotrowski", {}), ("linder", {}), ("stripes", {}),
           ("multi-hertz", {"variant": "pascal"}), ("multi-hertz", {"variant": "sauvage"}),
           ("multi-hertz", {"variant": "ayasse"})]


@pytest.fixture(scope="module")
def s1002():
    ws = wr.Wheelset(wheel=wr.profiles.load("S1002"), nominal_radius=0.46, flange_back=1.360)
    tr = wr.Track(rail=wr.profiles.load("60E1"), gauge=1.435, inclination=1 / 40)
    return ws, tr


MOTION = wr.Motion(speed=10.0, omega=10.0 / 0.46 * 1.001)


def test_registry():
    names = wr.normal_methods()
    for n in ("hertz", "multi-hertz", "linder", "kik-piotrowski", "stripes", "bem"):
        assert n in names


@pytest.mark.parametrize("normal,opts", METHODS)
def test_vertical_load_carried(s1002, normal, opts):
    ws, tr = s1002
    for y in (-0.004, 0.0, 0.005):
        wp = wr.WheelRailPosition(ws, tr, y, vertical_load=70e3)
        r = wr.solve(wp, motion=MOTION, mu=0.3, normal=normal, tangential="fastsim",
                     vertical="normal", **opts)
        for side in ("left", "right"):
            ps = r.side(side)
            Fz = sum(p.Fn * np.cos(p.patch.frame.contact_angle) for p in ps)
            assert Fz == pytest.approx(70e3, rel=1e-6)


def test_centred_wheelset_is_mirror_symmetric(s1002):
    ws, tr = s1002
    wp = wr.WheelRailPosition(ws, tr, 0.0, vertical_load=70e3)
    r = wr.solve(wp, motion=MOTION, mu=0.3, normal="kik-piotrowski", vertical="normal")
    left, right = r.side("left"), r.side("right")
    assert len(left) == len(right)
    for a, b in zip(left, right):
        assert a.Fn == pytest.approx(b.Fn, rel=1e-3)
        assert a.area == pytest.approx(b.area, rel=1e-3)


@pytest.mark.parametrize("normal", ["kik-piotrowski", "stripes"])
def test_close_to_boundary_elements(s1002, normal):
    """Single-patch tread and flange positions: area and p_max within 15 % of bem (40-element grid)."""
    ws, tr = s1002
    for y in (-0.006, 0.004, 0.008):
        wp = wr.WheelRailPosition(ws, tr, y, vertical_load=80e3)
        a = wr.solve(wp, motion=MOTION, mu=0.3, normal=normal, vertical="normal").side("right")
        b = wr.solve(wp, motion=MOTION, mu=0.3, normal="bem", vertical="normal").side("right")
        assert len(a) == len(b) == 1
        assert a[0].area == pytest.approx(b[0].area, rel=0.15)
        assert a[0].p_max == pytest.approx(b[0].p_max, rel=0.15)


def test_prescribed_approach(s1002):
    ws, tr = s1002
    wp = wr.WheelRailPosition(ws, tr, 0.002, vertical_load=70e3)
    r = wr.solve(wp, motion=MOTION, mu=0.3, normal="kik-piotrowski", vertical="normal")
    dz = r.pose["vertical_approach_right"]
    z = r.pose["z_right"] - dz
    wz = wr.WheelRailPosition(ws, tr, 0.002, roll=r.pose["roll"], z=z)
    r2 = wr.solve(wz, motion=MOTION, mu=0.3, normal="kik-piotrowski", vertical="normal")
    Fz = sum(p.Fn * np.cos(p.patch.frame.contact_angle) for p in r2.side("right"))
    assert Fz == pytest.approx(70e3, rel=0.01)
