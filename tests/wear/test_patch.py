"""Wear on a patch: worn volume = integral of the local law; twin-disc rates; properties.

The independent references are written here: the law evaluated by hand on the
cell fields, the wear number μ Fn |ξ| of a patch in full slip, and the USFD
twin-disc rates K(Tγ/A) (Braghin et al., Wear 261 (2006) 1253–1264; twin-disc
method of Lewis & Dwyer-Joyce, Proc. IMechE J 218 (2004) 467–478).
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import wheelrail as wr
from wheelrail.errors import InputError


@pytest.fixture(scope="module")
def fastsim_patch():
    c = wr.hertz(1e4, A=0.5 / 0.46, B=0.5 / 0.30, material=wr.STEEL)
    return c, wr.creep_forces(c, (-2e-3, 1e-3, 0.5), 0.3, wr.tangential.Fastsim(nx=16, ny=16))


def _by_hand(fields, k, H):
    a = fields.as_arrays()
    s = np.hypot(a["sx"], a["sy"])
    return float(np.sum(np.where(a["inside"], k * a["p"] * s / H * a["dA"], 0.0)))


@pytest.mark.parametrize("law", ["archard", "usfd", "energy", "usfd-patch", "kth"])
def test_volume_equals_integral_of_law(fastsim_patch, law):
    c, r = fastsim_patch
    impl = wr.wear.USFD(application="patch") if law == "usfd-patch" else law
    w = wr.wear.patch_wear(r, impl, speed=30.0)
    # ∫ d(y) dy over the patch = Σ rate ΔA
    assert w.volume_per_passage() == pytest.approx(w.volume_rate, rel=1e-9)
    if law == "archard":
        ref = _by_hand(r.fields, 1e-4, 2.6e9)
        assert abs(w.volume_rate - ref) <= 1e-6 * ref
    # the depth profile across the patch, deposited on a profile grid, keeps the volume
    lo = w.y - w.dy / 2
    hi = w.y + w.dy / 2
    edges = np.linspace(lo.min() - 1e-3, hi.max() + 1e-3, 57)
    binned = wr.wear.deposit(lo, hi, w.depth, edges)
    assert abs(np.sum(binned * np.diff(edges)) - w.volume_rate) <= 1e-6 * w.volume_rate


def test_exact_theory_fields(fastsim_patch):
    c, _ = fastsim_patch
    r = wr.creep_forces(c, (-2e-3, 0.0, 0.0), 0.3, wr.tangential.Exact(elements=16))
    w = wr.wear.patch_wear(r, "archard")
    ref = _by_hand(r.fields, 1e-4, 2.6e9)
    assert abs(w.volume_rate - ref) <= 1e-6 * ref
    assert w.volume_per_passage() == pytest.approx(w.volume_rate, rel=1e-9)


def _twin_disc(p0, xi, mu=0.3):
    """Two steel discs of radius 23.5 mm with a slight crown (b ≈ 4 a), rolling at creepage ξ."""
    R = 0.0235
    A, B = 1.0 / R, 1.0 / (20 * R)          # 0.5(1/R + 1/R), a crown of 10 R on each disc
    probe = wr.hertz(1e3, A=A, B=B, material=wr.STEEL)
    Fn = 1e3 * (p0 / probe.p0) ** 3        # p0 ∝ Fn^(1/3)
    c = wr.hertz(Fn, A=A, B=B, material=wr.STEEL)
    r = wr.creep_forces(c, (xi, 0.0, 0.0), mu, wr.tangential.Fastsim(nx=30, ny=30))
    return c, r


def test_twin_disc_mild_regime_rate():
    # p0 = 1500 MPa, 1 % slip, μ = 0.3: full slip, local τ|s| ≤ 0.3·1500·0.01 + … < 10.4 N/mm²,
    # so K = 5.3 Tγ/A on every cell and the patch loses 5.3 · Tγ µg per metre rolled,
    # Tγ ≈ μ Fn |ξ| (full slip: the slip equals the creepage up to the elastic part).
    c, r = _twin_disc(1.5e9, -0.01)
    w = wr.wear.patch_wear(r, "usfd")
    mass_ug_per_m = w.volume_rate * 7850.0 * 1e9                 # kg → µg
    area_mm2 = math.pi * c.a * c.b * 1e6
    TgA = 0.3 * c.Fn * 0.01 / area_mm2                           # N/mm², independent
    assert TgA < 10.4
    assert mass_ug_per_m / area_mm2 == pytest.approx(5.3 * TgA, rel=0.05)
    # and exactly the law at the patch's own (field) Tγ/A, the law being linear there
    a = r.fields.as_arrays()
    assert np.max(np.hypot(a["px"], a["py"]) * np.hypot(a["sx"], a["sy"])) < 10.4e6
    assert mass_ug_per_m / (w.contact_area * 1e6) == pytest.approx(
        wr.wear.usfd_rate(w.Tgamma_over_A * 1e-6), rel=1e-9)


def test_twin_disc_severe_regime_rate():
    # 5 % slip: Tγ/A ≈ 0.3·p_mean·0.05 ≈ 15 N/mm² (severe plateau, 55 µg/(m·mm²)).
    c, r = _twin_disc(1.5e9, -0.05)
    w = wr.wear.patch_wear(r, wr.wear.USFD(application="patch"))
    area_mm2 = math.pi * c.a * c.b * 1e6
    TgA = 0.3 * c.Fn * 0.05 / area_mm2
    assert 10.4 < TgA < 77.2
    rate = w.volume_rate * 7850.0 * 1e9 / (w.contact_area * 1e6)
    assert rate == pytest.approx(55.0, rel=1e-9)
    # locally, the edges of the patch (low pressure) are in the mild regime: less wear
    local = wr.wear.patch_wear(r, "usfd")
    assert local.volume_rate < w.volume_rate


def test_errors():
    c = wr.hertz(1e4, A=1.0, B=2.0, material=wr.STEEL)
    with pytest.raises(InputError, match="fields"):
        wr.wear.patch_wear(wr.creep_forces(c, (1e-3, 0, 0), 0.3, "carter"), "archard")
    r = wr.creep_forces(c, (1e-3, 0, 0), 0.3, wr.tangential.Fastsim(nx=8, ny=8))
    with pytest.raises(InputError, match="speed"):
        wr.wear.patch_wear(r, "kth")
    with pytest.raises(InputError, match="contact frame"):
        wr.wear.patch_wear(r, "archard").profile_y("wheel")


_C = wr.hertz(1e4, A=0.5 / 0.46, B=0.5 / 0.30, material=wr.STEEL)


@settings(max_examples=20, deadline=None)
@given(xi=st.floats(-0.02, 0.02), eta=st.floats(-0.02, 0.02), phi=st.floats(-2.0, 2.0),
       law=st.sampled_from(["archard", "usfd", "energy", "kth"]))
def test_nonnegative_and_zero_slip(xi, eta, phi, law):
    r = wr.creep_forces(_C, (xi, eta, phi), 0.3, wr.tangential.Fastsim(nx=8, ny=8))
    w = wr.wear.patch_wear(r, law, speed=20.0)
    assert np.all(w.rate >= 0) and np.all(w.depth >= 0) and w.volume_rate >= 0
    # no slip anywhere (pure rolling) → no wear
    r0 = wr.creep_forces(_C, (0.0, 0.0, 0.0), 0.3, wr.tangential.Fastsim(nx=8, ny=8))
    assert wr.wear.patch_wear(r0, law, speed=20.0).volume_rate == 0.0
    # the depth per passage is zero where the fields say adhesion in a whole column
    a = r.fields.as_arrays()
    stick = ~np.any(a["inside"] & (np.hypot(a["sx"], a["sy"]) > 0), axis=0)
    assert np.all(w.depth[stick] == 0.0)


def test_wheelrail_patch_on_profiles():
    # a wheelset displaced towards the right flange: the patches of wr.solve carry their
    # contact frames; the wear lands around the contact points, volume conserved (cos γ)
    ws = wr.Wheelset(wheel=wr.profiles.load("S1002"), nominal_radius=0.46, flange_back=1.360)
    tr = wr.Track(rail=wr.profiles.load("60E1"), gauge=1.435, inclination=1 / 40)
    wp = wr.WheelRailPosition(ws, tr, 0.003, yaw=0.004, vertical_load=50e3)
    res = wr.solve(wp, motion=wr.Motion(speed=20.0), mu=0.3, normal="hertz",
                   tangential=wr.tangential.Fastsim(nx=12, ny=12))
    for p in res.patches:
        w = wr.wear.patch_wear(p, "archard")
        assert w.side == p.side and w.wheel_y == pytest.approx(p.y_wheel)
        for body, ref in (("wheel", w.wheel_y), ("rail", w.rail_y)):
            lo, hi = w.profile_y(body)
            assert lo.min() < ref < hi.max()
            edges = np.linspace(ref - 0.02, ref + 0.02, 201)
            binned = w.on_profile(edges, body)
            got = np.sum(binned * np.diff(edges))
            assert got == pytest.approx(w.volume_rate * math.cos(w.contact_angle), rel=1e-9)
        per_m = w.wheel_depth_per_metre()
        assert np.allclose(per_m, w.depth / (2 * math.pi * p.patch.frame.rolling_radius))
