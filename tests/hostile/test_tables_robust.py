"""Contact tables never abort: built-in pairs at every standard inclination and the measured
profiles of ../shared/data/profiles, y = −50 … 50 mm (subsampled here; the full sweep is
``benchmarks/bench_contact_table_sweep.py``).

Failures once found: 60E1/54E1 failed at 1:20; an 11-point table failed at an ordinary
tread position; a wheel on its flange tip at y = −50 mm was reported as normal contact; one
bad row of a measured wheel aborted the whole table.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.geometry.contact_search import STATUS, solve_rigid_rows

INCLINATIONS = [0.0, 1 / 20, 1 / 30, 1 / 40]
Y = np.linspace(-0.05, 0.05, 11)


def _check_table(t):
    st = t.status.values
    assert set(np.unique(st)) <= set(STATUS)
    ok = st < 3
    # every solved row is a contact: both primary points at zero separation
    for side in ("left", "right"):
        sep = t[f"separation_{side}"].values[ok]
        assert np.all(np.nanmin(sep, axis=1) < 1e-8)
        assert np.all(np.isfinite(t[f"contact_angle_{side}_primary"].values[ok]))
    # every flagged row says why, every ok row is silent
    reasons = t.status_reason.values
    assert all(bool(r) == bool(s) for r, s in zip(reasons, st))
    return st


@pytest.mark.parametrize("inc", INCLINATIONS, ids=["0", "1/20", "1/30", "1/40"])
@pytest.mark.parametrize("rail", ["60E1", "54E1"])
def test_builtin_pairs_at_standard_inclinations(rail, inc):
    ws = wr.Wheelset(wr.profiles.load("S1002"))
    tr = wr.Track(wr.profiles.load(rail), inclination=inc)
    t = wr.contact_table(ws, tr, Y)
    st = _check_table(t)
    # tread contact around the centre, the flange rides over at ±50 mm (derailed)
    assert st[5] == 0  # y = 0
    assert st[0] == STATUS_CODE["derailed"] and st[-1] == STATUS_CODE["derailed"]
    assert "left wheel rides on its flange tip" in str(t.status_reason.values[0])
    assert "right wheel" in str(t.status_reason.values[-1])
    # symmetric pair: the table is mirror-symmetric
    np.testing.assert_array_equal(st, st[::-1])


STATUS_CODE = {v: k for k, v in STATUS.items()}


def test_issue_examples_eleven_and_twentyone_points():
    """The 11-point table used to fail at y = −4.69 mm (a jump bisection); 21 points at
    y = −50 mm reported a contact on the flange tip at 1.1° as normal."""
    ws = wr.Wheelset(wr.profiles.load("S1002"))
    tr = wr.Track(wr.profiles.load("60E1"))
    for n in (11, 21):
        t = wr.contact_table(ws, tr, np.linspace(-0.05, 0.05, n))
        st = _check_table(t)
        assert st[0] == STATUS_CODE["derailed"]
        gamma = np.degrees(t.contact_angle_left_primary.values[0])
        assert gamma < 5.0  # on the flange tip, as the audit found (1.1°)
    with pytest.warns(wr.geometry.contact_search.ContactWarning, match="derailed"):
        cp = wr.contact_points(ws, tr, -0.05)
    assert cp.status == "derailed"
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert wr.contact_points(ws, tr, 0.002).status == "ok"


def test_rows_that_cannot_be_solved_are_flagged_not_raised():
    """A shift putting a wheel entirely beside its rail: status no_contact, NaN data."""
    ws = wr.Wheelset(wr.profiles.load("S1002"))
    tr = wr.Track(wr.profiles.load("60E1"), gauge=1.0)   # wheels far outside the rails
    rows = solve_rigid_rows(ws, tr, np.array([-0.01, 0.0, 0.01]), 0.0)
    assert np.all(rows.status == 3) and all("beside" in r or "no contact" in r for r in rows.reason)
    assert np.all(np.isnan(rows.z))
    with pytest.raises(wr.errors.InputError, match="y = 0 m"), wr.plausibility.disabled():
        wr.contact_points(ws, tr, 0.0)
    # checked before solving: a flange back not smaller than the gauge
    with pytest.raises(wr.errors.InputError, match="flange_back = 1.36 m is not smaller"):
        wr.contact_points(ws, tr, 0.0)


def _measured(shared_profiles):
    out = {"wheel": {}, "rail": {}}
    for f in sorted(shared_profiles.iterdir()):
        if f.name == "NOTICE":
            continue
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", wr.profiles.ProfileWarning)
            p = wr.profiles.read(f)
        out[p.kind][f.name] = p
    return out


def test_measured_profiles_never_abort_a_table(shared_profiles):
    """Every measured wheel on 60E1 and S1002 on every measured rail, at 0 and 1/20 (and
    canted files as given), 7 shifts: no exception, every row ok or flagged."""
    prof = _measured(shared_profiles)
    y = np.linspace(-0.05, 0.05, 7)
    s1002, e60 = wr.profiles.load("S1002"), wr.profiles.load("60E1")
    pairs = [(w, e60, wn, "60E1") for wn, w in prof["wheel"].items()]
    pairs += [(s1002, r, "S1002", rn) for rn, r in prof["rail"].items()]
    done = 0
    for w, r, wn, rn in pairs:
        for inc in (0.0, 1 / 20):
            try:
                tr = wr.Track(r, inclination=inc)
            except wr.errors.ProfileError as exc:
                # a flat plane has no gauge face: refused when the track is built, with the cause
                assert rn == "flat_plane.prr" and "no gauge face" in str(exc)
                continue
            t = wr.contact_table(wr.Wheelset(w), tr, y)
            _check_table(t)
            done += 1
    assert done >= 2 * (len(pairs) - 1)


def test_measured_wheel_avg_wheel_full_range(shared_profiles):
    """avg_wheel.whl used to stop the table at y = −10 mm ("did not converge")."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", wr.profiles.ProfileWarning)
        w = wr.profiles.read(shared_profiles / "avg_wheel.whl")
    t = wr.contact_table(wr.Wheelset(w), wr.Track(wr.profiles.load("60E1")),
                         np.linspace(-0.05, 0.05, 21))
    st = _check_table(t)
    assert np.all(st[9:12] == 0)  # |y| <= 5 mm
    assert st[0] == STATUS_CODE["derailed"] and st[-1] == STATUS_CODE["derailed"]


def test_flange_climb_between_flange_contact_and_derailment():
    """S1002/60E1 1:40: tread contact at 5 mm, flange climbing (contact past the steepest
    flank point, contact angle falling) at 9 mm, flange tip at 30 mm; only derailment warns."""
    ws = wr.Wheelset(wr.profiles.load("S1002"))
    tr = wr.Track(wr.profiles.load("60E1"))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert wr.contact_points(ws, tr, 0.005).status == "ok"
        cp = wr.contact_points(ws, tr, 0.009)
    assert cp.status == "flange_climb" and "right wheel climbs its flange" in cp.reason
    fg = wr.geometry.contact_search.flange_geometry(ws, "right")
    gamma = np.degrees(cp.right.contact_angle[cp.right.primary])
    assert 45.0 < gamma < fg[4] - 2.0   # below the 70° of the S1002 flank
    with pytest.warns(wr.geometry.contact_search.ContactWarning):
        assert wr.contact_points(ws, tr, 0.03).status == "derailed"


@pytest.mark.parametrize("rail", ["60E1", "54E1"])
def test_rail_at_1_in_20_keeps_the_part_seen_from_above(rail):
    """At 1:20 the 1:20 head side is vertical: it is dropped, the gauge is still exact."""
    tr = wr.Track(wr.profiles.load(rail), inclination=1 / 20)
    for side in ("left", "right"):
        pl = tr.placement(side)
        assert pl.gauge_point == pytest.approx(tr.gauge / 2)
        u = pl.curve.u
        assert np.all(np.diff(u) > 0)
        # the kept surface is the upper envelope: steepest slope below 100 (89.4°)
        slope = pl.curve.eval(np.linspace(u[0], u[-1], 2001), 1)[1]
        assert np.max(np.abs(slope)) < 150.0
