"""Contact search, contact table and their I/O for S1002 on 60E1 (1:40, 1435/1360)."""

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.errors import InputError, ProfileError


@pytest.fixture(scope="module")
def s1002_60e1():
    return wr.Wheelset(wr.profiles.load("S1002")), wr.Track(wr.profiles.load("60E1"))


@pytest.fixture(scope="module")
def table(s1002_60e1):
    ws, tr = s1002_60e1
    return wr.contact_table(ws, tr, np.linspace(-0.01, 0.01, 201))


def _brute_min_gap(ws, tr, cp, side):
    """Minimum vertical distance of the rolled wheel above the canted rail, sampled densely
    from the original Profile objects (not from the library's internal splines)."""
    sig = 1.0 if side == "right" else -1.0
    w, r = ws.profile(side), tr.profile(side)
    s = np.linspace(w.y_min + 1e-3, w.y_max - 1e-3, 200001)
    rad = ws.nominal_radius - w(s)
    a = sig * (ws.e_tape + s)
    Y = cp.y + a * np.cos(cp.roll) + rad * np.sin(cp.roll)
    Z = ws.nominal_radius + cp.z + a * np.sin(cp.roll) - rad * np.cos(cp.roll)
    pl = tr.placement(side)
    # rail point below: invert the placement (rotation by the cant about the profile origin)
    yr = np.linspace(r.y_min, r.y_max, 200001)
    zr = r(yr)
    c, sn = np.cos(pl.angle), np.sin(pl.angle)
    U, ZR = c * yr - sn * zr + pl.offset, sn * yr + c * zr - pl.z_top
    return float(np.nanmin(Z - np.interp(sig * Y, U, ZR, left=np.nan, right=np.nan)))


@pytest.mark.parametrize("y", [0.0, 0.0021, -0.0047, 0.0075])
def test_rigid_constraint_both_wheels_touch(s1002_60e1, y):
    """Seed 002, eq. 2.3: min distance = 0 on both sides at the returned (z, roll)."""
    ws, tr = s1002_60e1
    cp = wr.contact_points(ws, tr, y)
    for side in ("left", "right"):
        assert abs(_brute_min_gap(ws, tr, cp, side)) < 2e-7
        assert np.min(cp.side(side).separation) == pytest.approx(0.0, abs=1e-9)


def test_centred_wheelset_is_symmetric(s1002_60e1):
    ws, tr = s1002_60e1
    cp = wr.contact_points(ws, tr, 0.0)
    assert cp.roll == 0.0 or abs(cp.roll) < 1e-12
    assert cp.delta_r == pytest.approx(0.0, abs=1e-12)
    np.testing.assert_allclose(cp.left.wheel_y, cp.right.wheel_y, atol=1e-9)
    np.testing.assert_allclose(cp.left.track_y, -cp.right.track_y, atol=1e-9)
    # tread contact near the tape circle, contact angle a little above the 1:40 cant
    p = cp.right.primary
    assert abs(cp.right.wheel_y[p]) < 0.01
    assert 0.0 < cp.right.contact_angle[p] < np.radians(5)


def test_table_antisymmetry(table):
    """Symmetric wheelset and track: Δr(−y) = −Δr(y), roll(−y) = −roll(y), z(−y) = z(y)."""
    dr = table["delta_r"].values
    np.testing.assert_allclose(dr, -dr[::-1], atol=1e-10)
    np.testing.assert_allclose(table["roll"].values, -table["roll"].values[::-1], atol=1e-12)
    np.testing.assert_allclose(table["z"].values, table["z"].values[::-1], atol=1e-10)
    np.testing.assert_allclose(table["contact_angle_left_primary"].values,
                               table["contact_angle_right_primary"].values[::-1], atol=1e-8)


def test_table_contents_and_plausibility(table):
    assert table.sizes["y"] == 201
    for name in ("delta_r", "roll", "z", "n_contact_left", "n_contact_right",
                 "contact_angle_left", "contact_angle_right", "rolling_radius_left", "A_right",
                 "B_left", "separation_right", "wheel_y_left", "rail_y_right", "x_left"):
        assert name in table
    assert table["contact_angle_left"].dims == ("y", "point")
    assert np.all(np.diff(table["delta_r"].values) >= -1e-9)  # Δr increases with y
    # flange contact at the ends: large contact angle on the leading wheel
    assert np.degrees(table["contact_angle_right_primary"].values[-1]) > 40
    assert np.degrees(table["contact_angle_left_primary"].values[0]) > 40
    # NaN exactly where a row has fewer points than the table width
    n = table["n_contact_right"].values
    sep = table["separation_right"].values
    assert np.all(np.isfinite(sep[np.arange(sep.shape[0]), table["primary_right"].values]))
    assert np.all(np.sum(np.isfinite(sep), axis=1) >= n)


def test_two_point_contact_and_jump_location(s1002_60e1, table):
    """Seed 003, fig. 1: two-point contact near flange contact; the jump of the contact point
    is located to within the sampling step, and at the located shift both points touch."""
    ws, tr = s1002_60e1
    jy, js, jsize = table["jump_y"].values, table["jump_side"].values, table["jump_size"].values
    right = jy[(js == 1) & (jy > 0.003)]
    assert right.size >= 1
    dy = 1e-4
    two_point = 0
    for y_j in right:
        # both sides of the jump: primary points on different parts of the wheel
        below = wr.contact_points(ws, tr, y_j - dy / 2)
        above = wr.contact_points(ws, tr, y_j + dy / 2)
        jump = abs(below.right.wheel_y[below.right.primary] - above.right.wheel_y[above.right.primary])
        assert jump > 1e-3
        # at a jump between separate zones the wheel touches at two points (two-point
        # contact); a jump along a nearly conformal zone (flange root against the R13
        # gauge corner) is a fast slide of a single point
        at = wr.contact_points(ws, tr, y_j, tolerance=1e-4)
        if at.right.n >= 2 and np.sort(at.right.separation)[1] < 2e-6:
            two_point += 1
            pts = np.sort(at.right.wheel_y)
            assert np.ptp(pts) > 5e-3  # two distinct zones: tread/flange root
    assert two_point >= 1
    # the coarse table (no refinement) puts the jump within half a sampling step of it
    coarse = wr.contact_table(ws, tr, np.arange(0.003, 0.0071, dy), refine_jumps=0)
    cj = coarse["jump_y"].values[coarse["jump_side"].values == 1]
    for y_j in right:
        assert np.min(np.abs(cj - y_j)) <= dy / 2 + 1e-12
    assert np.all(np.abs(jsize) > 1e-3)


def test_netcdf_and_csv_roundtrip(table, tmp_path):
    import csv

    import xarray as xr

    from wheelrail.geometry.contact_table import write_csv, write_netcdf

    path = write_netcdf(table, tmp_path / "t.nc")
    back = xr.open_dataset(path, engine="scipy")
    np.testing.assert_array_equal(back["delta_r"].values, table["delta_r"].values)
    np.testing.assert_array_equal(back["contact_angle_left"].values,
                                  table["contact_angle_left"].values)
    np.testing.assert_array_equal(back["jump_y"].values, table["jump_y"].values)
    back.close()
    path = write_csv(table, tmp_path / "t.csv")
    with open(path) as fh:
        rows = list(csv.reader(fh))
    header = rows[0]
    assert header[0] == "y" and "delta_r" in header and "contact_angle_right_0" in header
    assert len(rows) == 202
    i = header.index("delta_r")
    assert float(rows[-1][i]) == pytest.approx(float(table["delta_r"].values[-1]), rel=1e-15)


def test_left_and_right_profiles_may_differ(s1002_60e1):
    """A higher right rail (shifted down profile = worn) changes the roll, not the symmetry code."""
    ws, tr = s1002_60e1
    rail = wr.profiles.load("60E1")
    tr2 = wr.Track(rail, rail_right=rail.shifted(0.0, -0.002), canted=False)
    cp = wr.contact_points(ws, tr2, 0.0)
    cp0 = wr.contact_points(ws, tr, 0.0)
    # top of rail is re-levelled to z = 0 for each rail: a pure vertical shift changes nothing
    assert cp.roll == pytest.approx(cp0.roll, abs=1e-12)
    wheel = wr.profiles.load("S1002")
    ws2 = wr.Wheelset(wheel, wheel_right=wheel.shifted(0.0, 0.001))  # right wheel 1 mm smaller
    cp2 = wr.contact_points(ws2, tr, 0.0)
    assert cp2.delta_r < -0.0009
    # the wheelset rolls by about −1 mm over the contact-point distance (right wheel lower)
    e_c = 0.5 * (cp2.right.track_y[cp2.right.primary] - cp2.left.track_y[cp2.left.primary])
    assert cp2.roll == pytest.approx(-0.001 / (2 * e_c), rel=0.3)


def test_bad_input_is_rejected(s1002_60e1):
    ws, tr = s1002_60e1
    wheel, rail = wr.profiles.load("S1002"), wr.profiles.load("60E1")
    with pytest.raises(ProfileError, match="wheel profile"):
        wr.Wheelset(rail)
    with pytest.raises(ProfileError, match="rail profile"):
        wr.Track(wheel)
    with pytest.raises(InputError, match="flange_back"):
        wr.Wheelset(wheel, flange_back=1360.0)
    with pytest.raises(InputError, match="gauge"):
        wr.Track(rail, gauge=1435)
    with pytest.raises(InputError, match="inclination"):
        wr.Track(rail, inclination=40)
    with pytest.raises(InputError, match="yaw"):
        wr.contact_points(ws, tr, 0.0, yaw=1.0)
    with pytest.raises(InputError, match="increasing"):
        wr.contact_table(ws, tr, [0.001, 0.0])
    with pytest.raises(InputError, match="y must be finite"):
        wr.contact_points(ws, tr, float("nan"))
    with pytest.raises(InputError, match="mm given"):
        wr.contact_table(ws, tr, [0.0, 10.0])


def test_side_and_scalar_checks_are_shared(s1002_60e1):
    """Every side-taking accessor rejects a bad side; array y or yaw is refused by name."""
    ws, tr = s1002_60e1
    for fn in (ws.profile, ws.curve, tr.profile, tr.placement, tr.curve,
               wr.contact_points(ws, tr, 0.0).side):
        with pytest.raises(InputError, match="side must be 'left' or 'right', got 'lft'"):
            fn("lft")
    with pytest.raises(InputError, match="yaw must be a scalar"):
        wr.contact_table(ws, tr, [0.0, 0.001], yaw=[0.0, 0.0])
    with pytest.raises(InputError, match="yaw must be a scalar"):
        wr.contact_points(ws, tr, 0.0, yaw=[0.0])
    with pytest.raises(InputError, match="elastic_contact takes a scalar y"):
        wr.elastic_contact(ws, tr, [0.0, 0.001], 1e5)
    with pytest.raises(InputError, match="tape_circle_offset"):
        wr.Wheelset(ws.wheel, tape_circle_offset="70mm")


def test_shared_profile_files_make_a_table(shared_profiles):
    """Manchester benchmark S1002 / UIC60 (file already canted 1:40) read from the shared data."""
    wheel = wr.profiles.read(shared_profiles / "MBench_S1002_v3.prw")
    rail = wr.profiles.read(shared_profiles / "MBench_UIC60_v3.prr")
    ws = wr.Wheelset(wheel)
    tr = wr.Track(rail, canted=True)
    t = wr.contact_table(ws, tr, np.linspace(-0.006, 0.006, 25))
    assert np.all(np.isfinite(t["delta_r"].values))
    assert abs(float(t["delta_r"].sel(y=0.0, method="nearest"))) < 2e-4
    # same pair as the built-in profiles: similar equivalent conicity at 3 mm
    ref = wr.equivalent_conicity(wr.Wheelset(wr.profiles.load("S1002")),
                                 wr.Track(wr.profiles.load("60E1")), 0.003)
    assert wr.equivalent_conicity(ws, tr, 0.003) == pytest.approx(ref, abs=0.05)
