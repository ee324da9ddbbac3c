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
from wheelrail.geometry.touching import touching_heights
from wheelrail.errors import InputError
from wheelrail.geometry.contact_search import _Pose, find_points
from wheelrail.normal.caf import (caf_contacts, caf_table, jump_gap, jump_overlap,
                                  profile_jump_gaps)


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
    for kind in ("eq3", "general"):
        tread = table.overlaps(0, d, d, overlap=kind)
        flange = table.overlaps(table.jumps.size - 1, d, d, overlap=kind)
        assert min(tread) > 10 * d / 2
        assert 0.3 * d / 2 < max(flange) < 3 * d / 2
    with pytest.raises(InputError, match="gamma2"):
        jump_overlap(0.1, 0.1, d)
    with pytest.raises(InputError, match="delta1"):
        jump_overlap(0.1, 0.2, -1e-5)
    with pytest.raises(InputError, match="caf_overlap"):
        table.overlaps(0, d, d, overlap="eq. 3")


@pytest.mark.parametrize("g1, g2", [(0.03, 0.06), (0.06, 0.03), (0.3, 0.9), (0.05, 0.05)])
@pytest.mark.parametrize("rate", [-40.0, -5.0, 1e-7, 5.0, 40.0])
def test_generalised_overlap_inverts_the_gap(g1, g2, rate):
    """The small-jump generalisation of eq. 3 (this project's, seed 003 §2.3.3 only cites
    its ref. [42]): the overlap is where the rigid gap of the CAF lines, ∫ tan Δγ dτ / cos γ1
    (checked here against numerical quadrature), reaches δ1/2; it tends to eq. 3 as the
    rate → 0 and stays finite for γ2 = γ1."""
    from scipy.integrate import quad

    d = 1e-4
    t = float(jump_overlap(g1, g2, d, rate))
    c = rate if g2 >= g1 else -rate
    if g2 == g1:
        c = abs(rate)

    def gap(tau):
        a = abs(g2 - g1)
        if c < 0:
            tau = min(tau, a / -c)
        return quad(lambda s: np.tan(a + c * s), 0.0, tau, epsabs=1e-16)[0] / np.cos(g1)

    assert float(jump_gap(g1, g2, t, rate)) == pytest.approx(gap(t), rel=1e-9, abs=1e-15)
    a = abs(g2 - g1)
    if c < 0 and gap(a / -c) < d / 2:             # converging lines cross before the gap opens
        assert t == pytest.approx(a / -c, rel=1e-12)
    else:
        assert gap(t) == pytest.approx(d / 2, rel=1e-7)
    if g1 != g2 and abs(rate) < 1e-6:
        assert t == pytest.approx(np.cos(g1) * d / 2 / np.tan(a), rel=1e-7)      # eq. 3
    if g1 == g2 and rate > 0:
        assert t == pytest.approx(np.sqrt(np.cos(g1) * d / rate), rel=1e-3)     # finite


def test_gap_model_follows_the_profiles(pair, table):
    """The rigid gap of the second contact near a jump, measured on the profiles
    (find_points' candidate on the other branch, S1002/60E1), against the CAF lines'
    gap (jump_gap): straight lines (eq. 3's model) and lines with the CAF slopes (the
    generalisation). Gap increments from the first sample up to 0.45 mm (the jump limit
    is known to ± 25 µm). Measured on the tread and flange-root jumps, both sides: the
    sloped lines 0.4 / 3.9 / 0.9 / 2.4 % off the increments (mean 1.9 %), the straight
    ones 3.5 / 6.2 / 3.6 / 1.2 % (mean 3.6 %)."""
    ws, tr = pair
    err = {"eq3": [], "general": []}
    for k in (0, 1):
        _, g1, g2, _, _, s1, s2 = table._jump_data(k)
        for side in (1, 2):
            tau, gap = profile_jump_gaps(ws, tr, table, k, side,
                                         np.arange(0.05e-3, 0.5e-3, 0.05e-3))
            assert tau.size >= 4
            ga, gb = (g1, g2) if side == 1 else (g2, g1)
            for kind, rate in (("eq3", 0.0), ("general", s1 - s2)):
                model = jump_gap(ga, gb, tau, rate)
                inc, minc = gap[1:] - gap[0], model[1:] - model[0]
                err[kind].append(np.max(np.abs(minc / inc - 1)))
    assert max(err["general"]) < 0.045
    assert np.mean(err["general"]) < 0.6 * np.mean(err["eq3"])   # measured 1.9 vs 3.6 %


def test_overlap_sides_follow_the_rigid_gaps(pair, table):
    """On side i of a jump limit (contact i the rigid one) the other contact carries load
    while its rigid gap is below δ_i/2: the table's shares against those of the direct form
    (caf="direct", shares from the rigid gaps of the candidate points of the actual pose)
    inside both overlaps, S1002/60E1, 70 kN, roll 0. Measured: within 0.05 of the share at
    the tread jump and 0.035 at the flange-root jump; with the sides of eq. 3 exchanged the
    table was 0.14–0.23 off."""
    ws, tr = pair
    for y, tol in ((-0.175e-3, 0.06), (0.025e-3, 0.06), (0.225e-3, 0.06), (0.425e-3, 0.06),
                   (4.825e-3, 0.035), (5.025e-3, 0.035), (5.225e-3, 0.035)):
        wp = wr.WheelRailPosition(ws, tr, y, roll=0.0, vertical_load=70e3)
        res = {}
        for caf in ("table", "direct"):
            r = wr.solve(wp, motion=MOTION, mu=0.3, normal="multi-hertz", variant="ayasse",
                         caf=caf, vertical="normal")
            ps = sorted(r.side("right"), key=lambda p: p.contact_angle)
            assert len(ps) == 2
            res[caf] = ps[1].Fn / (ps[0].Fn + ps[1].Fn)
        assert res["table"] == pytest.approx(res["direct"], abs=tol)


def test_bad_input_named(pair):
    with pytest.raises(InputError, match="step"):
        caf_table(*pair, "right", (-0.01, 0.01), step=0.0)
    with pytest.raises(InputError, match="range"):
        caf_table(*pair, "right", (0.01, -0.01))


# --------------------------------------------------------------------------- wr.solve with the tables
MOTION = wr.Motion(speed=10.0, omega=10.0 / 0.46 * 1.001)


def test_left_table_mirrors_the_right(pair, table):
    """Mirror symmetry of the track: the left wheel at −t_y is the right one at t_y; the
    wheel radius from the CAF slope (sign reversed for the left wheel) agrees."""
    left = caf_table(*pair, "left", (-0.01, 0.01), tolerance=2e-4)
    np.testing.assert_allclose(np.sort(-left.jumps), np.sort(table.jumps), atol=1e-12)
    y = np.array([-0.008, -0.003, 0.002, 0.0045, 0.0057, 0.009])
    np.testing.assert_allclose(left.contact_angle(-y)[0], table.contact_angle(y)[0], atol=2e-4)
    rl, rr = left.wheel_radius(-y), table.wheel_radius(y)
    fin = np.abs(rr) < 2.5
    # the simplified lines of the two tables differ (Douglas–Peucker runs from the other end):
    # 5 %; the wrong sign of the slope relation gave R_w = −5.2 mm instead of −20.9 mm at −6 mm
    np.testing.assert_allclose(rl[fin], rr[fin], rtol=0.05)


def test_solve_ayasse_table_against_direct(pair):
    """``variant="ayasse"`` from the tables against the per-pose (direct) form, S1002/60E1,
    70 kN, roll 0 (the tables neglect roll, seed 003 §2.3.1), shifts −9.5…9.5 mm outside the
    jump overlaps. Tolerances: the table's lines are within 2e-4 rad of the sampled γ (so the
    contact angle within 3e-4 rad); the wheel radius of a line is its mean over the line
    (CAF slope), the direct one the point curvature regularised over the patch, so b (from
    B) differs up to 12 % (median < 3 %), a (from A = cos γ/2r) < 4 %."""
    ws, tr = pair
    dev = {"Fn": [], "g": [], "a": [], "b": []}
    for y in np.arange(-0.0095, 0.0096, 0.001):
        wp = wr.WheelRailPosition(ws, tr, y, roll=0.0, vertical_load=70e3)
        rt = wr.solve(wp, motion=MOTION, mu=0.3, normal="multi-hertz", variant="ayasse",
                      vertical="normal")
        rd = wr.solve(wp, motion=MOTION, mu=0.3, normal="multi-hertz", variant="ayasse",
                      caf="direct", vertical="normal")
        for s in ("left", "right"):
            if len(rt.side(s)) == 2:    # inside the tread jump's overlap (two contacts by design)
                assert abs(y) < 0.002
                continue
            (p,), (q,) = rt.side(s), rd.side(s)
            assert p.patch.info["caf"] == "table"
            dev["Fn"].append(p.Fn / q.Fn - 1)
            dev["g"].append(p.contact_angle - q.contact_angle)
            dev["a"].append(p.patch.hertz.a / q.patch.hertz.a - 1)
            dev["b"].append(p.patch.hertz.b / q.patch.hertz.b - 1)
    dev = {k: np.abs(v) for k, v in dev.items()}
    assert dev["Fn"].size >= 34
    assert dev["Fn"].max() < 1e-3
    assert dev["g"].max() < 3e-4
    assert dev["a"].max() < 0.04
    assert dev["b"].max() < 0.12 and np.median(dev["b"]) < 0.03


def test_roll_shifts_the_profiles(pair):
    """With the rigid roll θ (flange contact, θ ≈ 9–11 mrad) the profiles' relative
    translation is y + r0 sin θ (seed 003 §2.3.1: a translation, the rotation neglected):
    the table's contact angle then matches the direct form's within 0.01 rad, while the
    wheelset shift alone would give γ ≈ 1.22 instead of 0.95 at y = 8 mm."""
    ws, tr = pair
    for y in (0.008, 0.010):
        wp = wr.WheelRailPosition(ws, tr, y, vertical_load=70e3)
        rt = wr.solve(wp, motion=MOTION, mu=0.3, normal="multi-hertz", variant="ayasse",
                      vertical="normal")
        rd = wr.solve(wp, motion=MOTION, mu=0.3, normal="multi-hertz", variant="ayasse",
                      caf="direct", vertical="normal")
        (p,), (q,) = rt.side("right"), rd.side("right")
        assert abs(p.contact_angle - q.contact_angle) < 0.01
        assert p.Fn == pytest.approx(q.Fn, rel=0.01)


@pytest.mark.parametrize("kind", ["eq3", "general"])
def test_overlap_shares_follow_eq3(pair, table, kind):
    """Across a jump the load moves linearly from contact 1 to contact 2 over
    [t_ylim − Δt_y1, t_ylim + Δt_y2], the widths of eq. (3) (or its generalisation) with
    δ_i the Hertz approach (wr.hertz, independent) of contact i under the whole wheel load
    at the jump limit."""
    Q = 70e3
    for k in range(table.jumps.size):
        t = float(table.jumps[k])
        d = []
        for ln in (table.line(t, k), table.line(t, k + 1)):
            d.append(float(wr.hertz(Q / np.cos(ln["gamma"]), ln["A"], ln["B"],
                                    wr.STEEL).penetration))
        dt1, dt2 = table.overlaps(k, d[0], d[1], overlap=kind)
        lo, hi = t - dt1, t + dt2
        ys = np.linspace(lo, hi, 9)[1:-1]
        w2 = []
        for y in ys:
            c = caf_contacts(table, y, Q, wr.STEEL, overlap=kind)
            assert [br for _, _, br in c] == [k, k + 1]
            assert sum(w for w, _, _ in c) == pytest.approx(1.0)
            w2.append(c[1][0])
        np.testing.assert_allclose(w2, (ys - lo) / (hi - lo), rtol=1e-6)
        # just outside the overlap: one contact, on the branch of the rigid contact point
        for y, br in ((lo - 1e-6, k), (hi + 1e-6, k + 1)):
            (c,) = caf_contacts(table, y, Q, wr.STEEL, overlap=kind)
            assert c[0] == 1.0 and c[2] == br


def test_solve_table_carries_load_and_is_cached(pair):
    from wheelrail.normal.caf import cached_caf_table

    ws, tr = pair
    wp = wr.WheelRailPosition(ws, tr, 0.0002, vertical_load=70e3)
    r = wr.solve(wp, motion=MOTION, mu=0.3, normal="multi-hertz", variant="ayasse",
                 vertical="normal")
    for s in ("left", "right"):
        ps = r.side(s)
        assert len(ps) == 2                 # inside the tread jump's overlap
        Fz = sum(p.Fn * np.cos(p.patch.frame.contact_angle) for p in ps)
        assert Fz == pytest.approx(70e3, rel=1e-9)
    t1 = cached_caf_table(ws, tr, "right", (-0.02, 0.02), tolerance=2e-4)
    assert cached_caf_table(ws, tr, "right", (-0.02, 0.02), tolerance=2e-4) is t1
    with pytest.raises(InputError, match="outside the CAF table range"):
        wr.solve(wr.WheelRailPosition(ws, tr, 0.006, roll=0.0, vertical_load=70e3),
                 motion=MOTION, mu=0.3, normal="multi-hertz", variant="ayasse",
                 caf_range=(-0.005, 0.005))
    with pytest.raises(InputError, match="'tables'"):
        wr.solve(wp, motion=MOTION, mu=0.3, normal="multi-hertz", variant="ayasse",
                 caf="tables")


def test_sweep_with_tables_equals_solve(pair):
    """The sweep's fast path (no candidate-point search for the CAF tables) gives what
    wr.solve gives per position."""
    ws, tr = pair
    y = np.array([-0.006, 0.0003, 0.0052])
    ds = wr.wheelset_sweep(ws, tr, y, yaw=0.002, vertical_load=70e3, motion=MOTION, mu=0.3,
                           normal="multi-hertz", variant="ayasse")
    for i, yi in enumerate(y):
        r = wr.solve(wr.WheelRailPosition(ws, tr, yi, yaw=0.002, vertical_load=70e3),
                     motion=MOTION, mu=0.3, normal="multi-hertz", variant="ayasse")
        for s in ("left", "right"):
            assert float(ds["Fy_track"].sel(side=s)[i]) == pytest.approx(r.force_track[s][1],
                                                                  rel=1e-9, abs=1e-6)
