"""The wheel–rail contact module (wr.solve on a WheelRailPosition, wheelset_sweep).

References:
* Hertz's closed form (Johnson 1985, §4.2) for a conical wheel on a circular
  rail head, where the undeformed gap is quadratic: the boundary-element path
  must converge to it under grid refinement (fitted order);
* CONTACT's published output for the Manchester benchmark A-2.2
  (eve70a/CONTACT, examples/mbench_a22_{left,right}.ref_out at commit
  d431cdbd, CONTACT open-source revision 2707; same 0.2 mm grid), transcribed
  in ``data/contact_mbench_a22.csv`` with its sign conventions;
* mirror symmetry of a centred wheelset, the total vertical force = the
  prescribed load, and continuity of the forces where a second patch appears.
"""

import csv
from pathlib import Path

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.errors import InputError, NoContactError, WheelrailError
from wheelrail.profiles import Profile

DATA = Path(__file__).parent / "data" / "contact_mbench_a22.csv"


@pytest.fixture(scope="module")
def cone_on_circle():
    """A 1:40 conical wheel (r0 = 0.46 m) on an uninclined R = 300 mm rail head: Hertzian."""
    yw = np.linspace(-0.06, 0.06, 601)
    wheel = Profile(yw, yw / 40.0, kind="wheel")
    R = 0.3
    yr = np.linspace(-0.035, 0.035, 701)
    rail = Profile(yr, -(R - np.sqrt(R * R - yr**2)), kind="rail")
    ws = wr.Wheelset(wheel=wheel, nominal_radius=0.46, flange_back=1.360)
    tr = wr.Track(rail=rail, gauge=1.435, inclination=0.0, gauge_height=0.001)
    return ws, tr


@pytest.fixture(scope="module")
def s1002():
    ws = wr.Wheelset(wheel=wr.profiles.load("S1002"), nominal_radius=0.46, flange_back=1.360)
    tr = wr.Track(rail=wr.profiles.load("60E1"), gauge=1.435, inclination=1 / 40)
    return ws, tr


def test_hertzian_gap_bem_path_converges_to_hertz(cone_on_circle):
    """normal='bem' through the wheel-rail path tends to the Hertz path on a quadratic gap."""
    ws, tr = cone_on_circle
    wp = wr.WheelRailPosition(ws, tr, 0.0, vertical_load=10e3)
    m = wr.Motion(speed=10.0, omega=10.0 / 0.46 * 1.001)
    hz = wr.solve(wp, motion=m, mu=0.3, normal="hertz", tangential="fastsim").side("right")[0]
    hc = hz.patch.hertz
    # Hertz for the profile curvatures: A = 1/(2 r), B = 1/(2 R) (cone: no cross curvature)
    ref = wr.hertz(hz.Fn, 0.5 / hz.patch.frame.rolling_radius, 0.5 / 0.3, wr.STEEL)
    assert hc.p0 == pytest.approx(ref.p0, rel=2e-4)
    sizes = np.array([4e-4, 2.8e-4, 2e-4])
    err_p, err_a, err_f = [], [], []
    for h in sizes:
        b = wr.solve(wp, motion=m, mu=0.3, normal="bem", tangential="fastsim",
                     element_size=h).side("right")
        assert len(b) == 1
        b = b[0]
        assert b.Fn == pytest.approx(hz.Fn, rel=1e-3)       # both carry the 10 kN vertical load
        assert b.xi == pytest.approx(hz.xi, rel=1e-6)      # same reference point on a cone
        err_p.append(abs(b.p_max / hc.p0 - 1))
        err_a.append(abs(b.area / hc.area - 1))
        err_f.append(abs(b.Fx - hz.Fx) / (0.3 * hz.Fn))
    assert err_p[-1] < 1e-3 and err_a[-1] < 0.02
    order = np.polyfit(np.log(sizes), np.log(err_p), 1)[0]
    assert order > 1.0, (err_p, order)
    assert err_f[-1] < 0.02                                  # FASTSIM strips on the BEM patch


def test_bem_exact_equals_hertz_exact_within_discretisation(cone_on_circle):
    ws, tr = cone_on_circle
    wp = wr.WheelRailPosition(ws, tr, 0.0, vertical_load=10e3)
    m = wr.Motion(speed=10.0, omega=10.0 / 0.46 * 1.001)
    hz = wr.solve(wp, motion=m, mu=0.3, normal="hertz", tangential="exact", elements=30)
    bm = wr.solve(wp, motion=m, mu=0.3, normal="bem", tangential="exact", element_size=2.5e-4)
    for a, b in zip(hz.side("right"), bm.side("right")):
        assert b.Fx == pytest.approx(a.Fx, abs=0.02 * 0.3 * a.Fn)
        assert b.Fs == pytest.approx(a.Fs, abs=0.02 * 0.3 * a.Fn)


@pytest.mark.parametrize("normal,tangential,opts", [("hertz", "fastsim", {}),
                                                     ("bem", "exact", {"element_size": 5e-4}),
                                                     ("hertz", "polach", {})])
def test_centred_wheelset_is_mirror_symmetric_and_carries_the_load(s1002, normal, tangential,
                                                                   opts):
    ws, tr = s1002
    wp = wr.WheelRailPosition(ws, tr, 0.0, vertical_load=(10e3, 10e3))
    res = wr.solve(wp, motion=wr.Motion(speed=20.0, omega=20.0 / 0.46 * 1.002), mu=0.3,
                   normal=normal, tangential=tangential, **opts)
    L, R = res.force_track["left"], res.force_track["right"]
    assert L[2] == pytest.approx(10e3, rel=2e-5) and R[2] == pytest.approx(10e3, rel=2e-5)
    # mirror images up to the solvers' tolerances (vertical load 1e-5, BEM pressure 1e-8)
    assert L[0] == pytest.approx(R[0], rel=1e-4, abs=1e-6)
    assert L[1] == pytest.approx(-R[1], rel=1e-4, abs=1e-6)
    for pl, pr in zip(res.side("left"), res.side("right")):
        assert pl.phi == pytest.approx(-pr.phi, rel=1e-9)
        assert pl.Fs == pytest.approx(-pr.Fs, rel=1e-4, abs=1e-6)
        assert pl.Fn == pytest.approx(pr.Fn, rel=1e-4)
    assert res.status in (wr.Status.CONVERGED, wr.Status.FULL_SLIP)


def test_vertical_normal_lets_the_normal_forces_carry_the_load(s1002):
    ws, tr = s1002
    wp = wr.WheelRailPosition(ws, tr, 0.0068, yaw=0.012, vertical_load=10e3)
    m = wr.Motion(speed=20.0)
    tot = wr.solve(wp, motion=m, mu=0.3)
    nor = wr.solve(wp, motion=m, mu=0.3, vertical="normal")
    assert tot.force_track["right"][2] == pytest.approx(10e3, rel=2e-5)
    fz_normal = sum(p.Fn * np.cos(p.contact_angle) for p in nor.side("right"))
    assert fz_normal == pytest.approx(10e3, rel=1e-6)
    # flange contact: the creep forces carry a large share of the vertical load
    assert abs(nor.force_track["right"][2] - 10e3) > 1e3


def test_two_point_contact_appears_without_a_force_jump(s1002):
    """Where the second (flange-root) point starts to carry load the forces are continuous:
    refining the lateral step shrinks the largest step-to-step change proportionally."""
    ws, tr = s1002
    m = wr.Motion(speed=20.0)
    jumps = []
    for n in (21, 81):
        y = np.linspace(0.0040, 0.0056, n)
        ds = wr.wheelset_sweep(ws, tr, y, vertical_load=10e3, motion=m, mu=0.3)
        assert (ds.status == "ok").all()
        npat = ds.n_patches.sel(side="right").values
        assert npat.min() == 1 and npat.max() == 2          # the second patch appears here
        fy = ds.Fy_track.sel(side="right").values
        fn2 = np.nan_to_num(ds.Fn.sel(side="right").isel(patch=1).values)
        first = np.argmax(fn2 > 0)
        assert fn2[first] < 0.05 * 10e3 * 40 / n             # it starts from (almost) zero load
        jumps.append(np.max(np.abs(np.diff(fy))))
    assert jumps[1] < 0.5 * jumps[0]


def test_sweep_batch_equals_per_position_path(s1002):
    ws, tr = s1002
    y = np.linspace(-0.008, 0.008, 9)
    m = wr.Motion(speed=20.0, yaw_rate=0.01)
    a = wr.wheelset_sweep(ws, tr, y, yaw=0.002, vertical_load=10e3, motion=m)
    b = wr.wheelset_sweep(ws, tr, y, yaw=0.002, vertical_load=10e3, motion=m, batch=False)
    # the two paths converge the vertical load to 1e-5 by different iterates
    for k in ("Fn", "Fx", "Fs", "Mz", "xi", "eta", "phi", "area", "adhesion_area"):
        np.testing.assert_allclose(a[k].values, b[k].values, rtol=2e-4, atol=1e-6, err_msg=k)
    np.testing.assert_allclose(a.Fy_track.values, b.Fy_track.values, rtol=2e-4, atol=0.1)


def test_hertz_contact_through_solve_equals_creep_forces():
    c = wr.hertz(Fn=7500.0, A=1.087, B=1.667, material=wr.STEEL)
    for law in ("fastsim", "polach", "linear", "shen-hedrick-elkins"):
        r = wr.solve(c, creepage=(-7e-4, 2e-4, 0.3), mu=0.3, normal="hertz", tangential=law)
        ref = wr.creep_forces(c, (-7e-4, 2e-4, 0.3), 0.3, method=law)
        assert (r.Fx, r.Fy, r.Mz) == (pytest.approx(ref.Fx), pytest.approx(ref.Fy),
                                      pytest.approx(ref.Mz))
    assert set(wr.normal_methods()) >= {"hertz", "bem"}
    assert set(wr.tangential_methods()) >= {"fastsim", "exact"}


def test_bad_wheelrail_input_is_named(s1002):
    ws, tr = s1002
    m = wr.Motion(speed=20.0)
    with pytest.raises(InputError, match="vertical_load"):
        wr.WheelRailPosition(ws, tr, 0.0, vertical_load=-5.0)
    with pytest.raises(InputError, match="exactly one"):
        wr.WheelRailPosition(ws, tr, 0.0)
    with pytest.raises(InputError, match="yaw"):
        wr.WheelRailPosition(ws, tr, 0.0, yaw=0.5, vertical_load=1e4)
    with pytest.raises(InputError, match="beside its rail"):
        wr.solve(wr.WheelRailPosition(ws, tr, 0.2, roll=0.0, vertical_load=1e4), motion=m,
                 mu=0.3)
    with pytest.raises(InputError, match="out of contact"):
        wr.solve(wr.WheelRailPosition(ws, tr, 0.0, z=0.01), motion=m, mu=0.3)
    with pytest.raises(InputError, match="motion"):
        wr.solve(wr.WheelRailPosition(ws, tr, 0.0, vertical_load=1e4), mu=0.3)
    with pytest.raises(InputError, match="frobnicate"):
        wr.solve(wr.WheelRailPosition(ws, tr, 0.0, vertical_load=1e4), motion=m, mu=0.3,
                 frobnicate=1)
    with pytest.raises(InputError, match="unknown normal method"):
        wr.solve(wr.hertz(1e4, 1, 1, wr.STEEL), creepage=(0, 0, 0), mu=0.3, normal="stripes?")
    ds = wr.wheelset_sweep(ws, tr, [0.0, 0.2], roll=[np.nan, 0.0], vertical_load=1e4, motion=m)
    assert list(ds.status.values) == ["ok", "error"] and "beside" in str(ds.message.values[1])
    assert np.isnan(ds.Fn.values[1]).all()


def _contact_reference():
    out = {}
    with open(DATA, encoding="utf-8") as fh:
        for r in csv.DictReader(line for line in fh if not line.startswith("#")):
            out[(int(r["case"]), r["wheel"])] = r
    return out


@pytest.mark.parametrize("case", [1, 2, 14, 21])
def test_manchester_a22_against_contact(case, shared_data):
    """Exact theory on the same 0.2 mm grid as CONTACT's published run (forces converted to
    Kalker's convention: on the wheel, creepage of the wheel relative to the rail)."""
    from wheelrail.contact.manchester import manchester_a22

    cases = manchester_a22(shared_data / "benchmarks" / "manchester_a22_inputs.csv",
                           shared_data / "profiles" / "MBench_S1002_v3.prw",
                           shared_data / "profiles" / "MBench_UIC60_v3.prr")
    c = cases[case - 1]
    res = wr.solve(c.position, motion=c.motion, mu=c.mu, normal="bem", tangential="exact",
                   element_size=2e-4)
    ref = _contact_reference()
    for side in ("left", "right"):
        r = {k: float(v) for k, v in ref[(case, side)].items() if k != "wheel"}
        (p,) = res.side(side)
        fz = 0.3 * r["Fn_N"]
        assert p.Fn == pytest.approx(r["Fn_N"], rel=5e-3)
        flange = abs(r["deltcp_rad"]) > 0.5
        # measured over the 41 single-patch wheels of the 21 cases (benchmarks/
        # bench_manchester.py): Fn within 0.2 %, Fx and Fs within 1.2 % of mu Fn, p_max within
        # 1.25 %; case 11 right, where CONTACT merges two regions into one patch and we keep
        # two, differs by up to 3.6 % of mu Fn (docs/validation/manchester_a22.md). The flange
        # patches (65 deg) are 10 % smaller in area (CONTACT discretises the curved surface,
        # we the contact plane)
        assert p.Fx == pytest.approx(-r["Fx_N"], abs=0.015 * fz)
        assert p.Fs == pytest.approx(-r["Fs_N"], abs=0.015 * fz)
        assert p.p_max == pytest.approx(r["pmax_MPa"] * 1e6, rel=0.015)
        assert p.area == pytest.approx(r["area_mm2"] * 1e-6, rel=0.12 if flange else 0.03)
        if case <= 2:
            continue   # wide conformal tread patches: the reference point (where the creepages
            #            are given) is a convention; CONTACT weights it differently (forces agree)
        # the contact reference point: interpenetration-weighted, as CONTACT's planar approach
        assert abs(p.contact_angle) == pytest.approx(abs(r["deltcp_rad"]), abs=5e-3)
        assert p.xi == pytest.approx(-r["xi"], abs=5e-5 + 0.02 * abs(r["xi"]))
        assert p.eta == pytest.approx(-r["eta"], abs=5e-5 + 0.02 * abs(r["eta"]))
        assert p.phi == pytest.approx(-r["phi_per_mm"] * 1e3,
                                      abs=5e-3 + 0.02 * abs(r["phi_per_mm"]) * 1e3)
    for side in ("left", "right"):
        r = ref[(case, side)]
        # resolved with the reference angle: within 1.5 % of the vertical load (the reference
        # angle of a wide conformal patch differs by up to 0.01 rad from CONTACT's)
        assert res.force_track[side][1] == pytest.approx(-float(r["FY_TR_N"]), abs=150.0)
        assert res.force_track[side][2] == pytest.approx(1e4, rel=2e-5)


def test_no_contact_error_is_clear():
    hc = wr.hertz(1e4, 1, 1, wr.STEEL)
    with pytest.raises(WheelrailError):
        wr.solve(wr.GapProblem(lambda x, y: x**2 + y**2 + 1e-3, wr.STEEL, penetration=1e-4),
                 creepage=(0, 0, 0), mu=0.3, normal="hertz")
    with pytest.raises(NoContactError):
        wr.solve(wr.GapProblem(lambda x, y: x**2 + y**2 + 1e-3, wr.STEEL, penetration=1e-4),
                 creepage=(0, 0, 0), mu=0.3, normal="bem")
    assert hc.p0 > 0


def test_gap_problem_two_bumps_bem_gives_two_patches_hertz_one():
    """A gap with two separated minima: BEM finds both patches (interaction included), Hertz
    only the ellipse at the global minimum (its documented limitation)."""
    L = 0.012

    def gap(x, y):
        return np.minimum(x**2 + 2 * (y - L)**2, x**2 + 2 * (y + L)**2 + 2e-6)

    prob = wr.GapProblem(gap, wr.STEEL, penetration=2.5e-5, search=(-0.02, 0.02, -0.03, 0.03))
    b = wr.solve(prob, creepage=(-1e-3, 0, 0), mu=0.3, normal="bem", tangential="fastsim",
                 grid_elements=120)
    assert len(b.patches) == 2
    big, small = sorted(b.patches, key=lambda p: -p.Fn)
    # reference: two Hertz contacts, each lowered by the far-field (Boussinesq) displacement
    # of the other's load, u = F / (pi E* d) (Johnson 1985, eq. 3.20)
    E_star, d = wr.MaterialPair.same(wr.STEEL).E_star, 2 * L
    F = [0.0, 0.0]
    for _ in range(50):
        F = [float(wr.hertz_from_penetration(delta - F[1 - i] / (np.pi * E_star * d), 1.0, 2.0,
                                             wr.STEEL).Fn)
             for i, delta in enumerate((2.5e-5, 2.3e-5))]
    assert big.Fn == pytest.approx(F[0], rel=0.02)
    assert small.Fn == pytest.approx(F[1], rel=0.02)
    # without the interaction the loads would be 6-7 % higher: the test sees it
    assert big.Fn < 0.96 * float(wr.hertz_from_penetration(2.5e-5, 1.0, 2.0, wr.STEEL).Fn)
    h = wr.solve(prob, creepage=(-1e-3, 0, 0), mu=0.3, normal="hertz", tangential="fastsim")
    ref = wr.hertz_from_penetration(2.5e-5, 1.0, 2.0, wr.STEEL)
    assert len(h.patches) == 1 and h.Fn == pytest.approx(float(ref.Fn), rel=1e-3)


@pytest.mark.parametrize("normal", ["hertz", "bem"])
def test_a_load_the_profiles_cannot_carry_is_named(s1002, normal):
    ws, tr = s1002
    with pytest.warns(wr.plausibility.PlausibilityWarning):
        wp = wr.WheelRailPosition(ws, tr, 0.0, vertical_load=3e7)
    with pytest.raises(InputError, match="30000000.0 N.*cannot carry"):
        wr.solve(wp, motion=wr.Motion(speed=10.0), mu=0.3, normal=normal)


def test_bem_second_patch_grows_from_zero(s1002):
    """Boundary elements (0.5 mm) where the flange-root patch appears (y = 4.70…4.80 mm): it
    starts with a small load and grows continuously; the total stays the vertical load."""
    ws, tr = s1002
    ds = wr.wheelset_sweep(ws, tr, np.linspace(0.0047, 0.0048, 6), vertical_load=10e3,
                           motion=wr.Motion(speed=20.0), normal="bem", tangential="fastsim",
                           element_size=5e-4)
    assert (ds.status == "ok").all()
    second = np.nan_to_num(ds.Fn.sel(side="right").isel(patch=1).values)
    first = np.argmax(second > 0)
    assert 0 < first and second[first] < 300.0
    assert np.all(np.diff(second[first:]) > 0) and np.max(np.diff(second)) < 800.0
    # its centre lies at the flange root, 10.5 mm from the tread patch (Hertz: 10.6 mm)
    c = ds.y_rail_centre.sel(side="right").values[-1]
    assert c[0] - c[1] == pytest.approx(0.0106, abs=1e-3)
