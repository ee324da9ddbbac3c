"""Standard profiles (S1002, 60E1, 54E1) against their defining dimensions and the
Manchester-benchmark profile files.

Independent references:
* EN 13715 / UIC 510-2: S1002 flange height Sh = 28 mm, flange thickness Sd = 32.5 mm
  measured 10 mm below the tape circle from the flange back (70 mm from the tape circle),
  flange slope qR = 10.8 mm (distance between the Sd point and the flank point 2 mm
  above the flange tip), field-side chamfer 1:15.
* EN 13674-1: 60E1 head radii 300/80/13 mm, side inclination 1:20, head width 72 mm;
  54E1 the same radii and 70 mm.
* Manchester contact benchmark profiles (Shackleton & Iwnicki, Vehicle System Dynamics
  46 (2008)), files MBench_S1002_v3.prw and MBench_UIC60_v3.prr from CONTACT (Vtech CMCC):
  same geometry within 0.05 mm after a least-squares alignment.
"""

import numpy as np
import pytest
from scipy.optimize import brentq, least_squares

import wheelrail as wr
from wheelrail.errors import ProfileError

MM = 1e-3
TOL_MBENCH = 0.05 * MM


@pytest.fixture(scope="module")
def s1002():
    return wr.profiles.load("S1002")


@pytest.fixture(scope="module")
def r60():
    return wr.profiles.load("60E1")


# ----------------------------------------------------------------------------- S1002
def test_s1002_frame_and_flange_height(s1002):
    assert s1002.kind == "wheel"
    assert s1002(0.0) == pytest.approx(0.0, abs=1e-9)               # tape circle
    i = np.argmin(s1002.z)
    assert s1002.y[i] == pytest.approx(-55 * MM, abs=0.3 * MM)      # flange at negative y
    assert s1002.z.min() == pytest.approx(-28 * MM, abs=1e-6 * MM)  # Sh = 28 mm
    assert s1002.meta["nominal_radius"] == 0.46


def test_s1002_flange_thickness_and_qr(s1002):
    # flank points (field side of the flange tip, y in (-55, -26) mm) at given depths
    def flank_at(z):
        return brentq(lambda y: s1002(y) - z, -54.9 * MM, -30 * MM)

    y_sd = flank_at(-10 * MM)
    sd = y_sd - (-70 * MM)          # from the flange back, 70 mm from the tape circle
    assert sd == pytest.approx(32.5 * MM, abs=0.01 * MM)
    qr = y_sd - flank_at(-26 * MM)  # 2 mm above the 28 mm flange tip
    assert qr == pytest.approx(10.8 * MM, abs=0.05 * MM)


def test_s1002_field_side_chamfer_and_continuity(s1002):
    y = np.linspace(33 * MM, 59 * MM, 9)
    np.testing.assert_allclose(s1002.slope(y), 1 / 15, atol=1e-6)
    # the sections join without steps: no jumps in z between dense samples
    yy = np.linspace(s1002.y_min, s1002.y_max, 20001)
    assert np.max(np.abs(np.diff(s1002(yy)))) < 0.1 * MM


def test_s1002_non_nominal_flange_refused():
    with pytest.raises(ProfileError, match="flange"):
        wr.profiles.load("S1002", flange_thickness=0.030)


# ----------------------------------------------------------------------------- rails
@pytest.mark.parametrize("name, half_width", [("60E1", 36.0), ("54E1", 35.0)])
def test_rail_head_radii_width_and_side(name, half_width):
    r = wr.profiles.load(name)
    assert r.kind == "rail" and r(0.0) == pytest.approx(0.0, abs=1e-12)
    np.testing.assert_allclose(r.z, r(-r.y), atol=1e-12)       # symmetric head
    c2 = np.array(r.meta["R80_centre"])
    c3 = np.array(r.meta["R13_centre"])
    # curvature -1/R in the middle of each arc
    assert r.curvature(0.005) == pytest.approx(-1 / 0.300, rel=1e-4)
    a_mid80 = 0.5 * (np.arcsin(0.0105 / 0.3) + np.arcsin((c3[0] - c2[0]) / 0.067))
    assert r.curvature(c2[0] + 0.080 * np.sin(a_mid80)) == pytest.approx(-1 / 0.080, rel=1e-3)
    y13 = c3[0] + 0.013 * np.sin(1.0)
    assert r.curvature(y13) == pytest.approx(-1 / 0.013, rel=1e-3)
    # tangency: centre distances R1-R2, R2-R3
    assert np.hypot(c2[0], c2[1] + 0.300) == pytest.approx(0.220, abs=1e-12)
    assert np.hypot(*(c3 - c2)) == pytest.approx(0.067, abs=1e-12)
    # side 1:20 and head width at the R13/side tangent point
    y_side = np.linspace(half_width * MM + 0.2 * MM, r.y_max - 0.2 * MM, 5)
    np.testing.assert_allclose(r.slope(y_side), -20.0, rtol=1e-6)
    assert c3[0] + 0.013 * np.cos(np.arctan(1 / 20)) == pytest.approx(half_width * MM, abs=1e-12)


def test_load_names_and_aliases():
    assert wr.profiles.load("uic60") == wr.profiles.load("60E1")
    assert wr.profiles.load("UIC54").name == "54E1"
    assert wr.profiles.load("s1002").name == "S1002"
    assert set(wr.profiles.available()) >= {"S1002", "60E1", "54E1", "UIC60", "UIC54"}
    with pytest.raises(ProfileError, match="available"):
        wr.profiles.load("UIC71")


# ----------------------------------------------------------------------------- MBench
def _normal_deviation(ours, y, z):
    """Distance of the points (y, z) from the curve ours, measured normal to it [m]."""
    return (z - ours(y)) / np.sqrt(1.0 + ours.slope(y) ** 2)


def _aligned_deviation(make, ref, x0, region):
    def residual(p):
        o = make(p)
        m = region(o, ref.y, ref.z)
        return np.nan_to_num(_normal_deviation(o, ref.y[m], ref.z[m]), nan=1.0)

    sol = least_squares(residual, x0, x_scale=np.full(len(x0), 1e-3))
    return sol.x, sol.fun


def test_s1002_matches_mbench(shared_profiles, s1002):
    ref = wr.profiles.read(shared_profiles / "MBench_S1002_v3.prw")
    # tread, flange and flange back down to -65 mm; field-side chamfer up to 58 mm
    shift, dev = _aligned_deviation(lambda p: s1002.shifted(p[0], p[1]), ref, [0.0, 0.0],
                                    lambda o, y, z: (y > -65 * MM) & (y < 58 * MM))
    assert dev.size > 300
    assert np.max(np.abs(dev)) < TOL_MBENCH
    assert np.max(np.abs(shift)) < 0.01 * MM  # same origin: tape circle, flange back at -70


def test_60e1_matches_mbench_after_removing_cant(shared_profiles, r60):
    ref = wr.profiles.read(shared_profiles / "MBench_UIC60_v3.prr")
    cant = np.arctan(1 / 40)
    # head: top, both gauge corners and sides down to 20 mm below the top of rail
    x, dev = _aligned_deviation(lambda p: r60.rotated(p[2]).shifted(p[0], p[1]), ref,
                                [0.0, 0.0, cant],
                                lambda o, y, z: (z > -20 * MM) & (y > o.y_min) & (y < o.y_max))
    assert dev.size > 250
    assert np.max(np.abs(dev)) < TOL_MBENCH
    assert x[2] == pytest.approx(cant, abs=2e-4)  # the benchmark rail is canted +1:40


def test_mbench_miniprof_rail_equals_simpack_rail(shared_profiles):
    prr = wr.profiles.read(shared_profiles / "MBench_UIC60_v3.prr")
    ban = wr.profiles.read(shared_profiles / "MBench_UIC60_v3.ban")
    y = np.linspace(max(prr.y_min, ban.y_min), min(prr.y_max, ban.y_max), 400)[1:-1]
    assert np.max(np.abs(_normal_deviation(prr, y, ban(y)))) < 1e-3 * MM


# ----------------------------------------------------------------------------- published
# EN 13674-1 section table (British Steel rail catalogue, as tabulated in the open FE code
# xc: github.com/xcfem/xc, python_modules/materials/sections/structural_shapes/aux/
# bs_en_13674-1_rail_sections.json, entries RAIL_EN60E1 / RAIL_EN54E1):
#   60E1: height 172 mm, head width 72 mm, foot 150 mm, web 16.5 mm
#   54E1: height 159 mm, head width 70 mm, foot 140 mm, web 16.0 mm
# Crown radius R300 and 1:20 head side: EN 13674-1 60E1 drawing (54E1: assumed, see
# wheelrail.profiles.standard).
PUBLISHED = {"60E1": (172.0, 72.0, 150.0, 16.5), "54E1": (159.0, 70.0, 140.0, 16.0)}


@pytest.mark.parametrize("name", ["60E1", "54E1"])
def test_rail_head_matches_published_section(name):
    height, head_width, foot, web = PUBLISHED[name]
    r = wr.profiles.load(name, step=0.05e-3)
    # head width measured on the generated points: the 1:20 side starts at the R13 tangent
    # (located to ~0.01 mm: the slope is -20 there, and z(y) is steep)
    y = np.linspace(30 * MM, r.y_max - 0.1 * MM, 20001)
    side = y[np.abs(r.slope(y) + 20.0) < 1e-3]
    assert 2 * side.min() == pytest.approx(head_width * MM, abs=0.05 * MM)
    # symmetric: same width on the gauge side
    ym = -y[::-1]
    side_m = ym[np.abs(r.slope(ym) - 20.0) < 1e-3]
    assert -2 * side_m.max() == pytest.approx(head_width * MM, abs=0.05 * MM)
    # crown radius from a least-squares circle through the points |y| <= 8 mm
    m = np.abs(r.y) <= 8 * MM
    yc, zc = r.y[m], r.z[m]
    A = np.c_[yc, zc, np.ones_like(yc)]
    a, b, c = np.linalg.lstsq(A, -(yc**2 + zc**2), rcond=None)[0]
    R = np.sqrt(a * a / 4 + b * b / 4 - c)
    assert R == pytest.approx(0.300, rel=1e-6)
    assert -b / 2 == pytest.approx(-0.300, rel=1e-6)  # centre on the rail axis below the top
    # section data carried in the metadata (the generated profile is the head only)
    assert r.meta["rail_height"] == pytest.approx(height * MM)
    assert r.meta["foot_width"] == pytest.approx(foot * MM)
    assert r.meta["web_thickness"] == pytest.approx(web * MM)
    assert r.meta["head_width"] == pytest.approx(head_width * MM)
