"""A single wheelset position through ``wr.solve``: the compiled contact search.

The rigid search (Newton on roll and height, the refined global minimum of
the gap, the parabolic refinement of every candidate point and the per-point
quantities) runs as numba kernels with the arithmetic of the array code it
replaced. References:

* the array implementation of the same algorithm (``_grid_gap``, ``_gapfun``,
  ``_refine``, ``_point_data_arrays`` of :mod:`wheelrail.geometry.contact_search`,
  still used by :mod:`wheelrail.geometry.elastic`), point by point;
* numbers printed by ``wr.solve`` before the change (main at 0ef094f, the
  array search), to 1e-12 relative: one- and two-point contact, flange
  contact on either wheel, yaw of both signs, Hertz and Kik–Piotrowski, both
  vertical-load modes;
* a cache keyed on the wheel and rail splines must follow a change of profile.
"""

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.geometry import contact_search as cs

OLD = {
    # Hertz cases: Fx, Fs, Mz (and Fn with vertical='total') regenerated when FASTSIM's
    # sliding elements started to oppose the true slip (spin unscaled); the
    # search quantities (pose, y_wheel, Fn with vertical='normal') are unchanged
    ('hertz', 0.0, 0.002, 'normal'): ((0.0, -0.000182174067782704, -0.000182174067782704), [('left', 0.0032612464891195805, 8484.60582116245, 577.762633402141, 2411.775899441752, -0.40585808481756946), ('left', -0.007686728097846419, 1520.9040351379826, 271.28444069234575, 366.5942208097959, -0.007771557898832235), ('right', 0.0032612464891195805, 9207.714548841426, 1447.630385718658, 2346.5520461661413, 0.158256333461198), ('right', -0.007686728097846419, 1798.5580506457507, 389.30420054563604, 373.3385777056906, 0.009328509531389072)]),
    ('hertz', 0.005, -0.004, 'total'): ((0.0003684944243475377, 3.084758929212105e-05, 3.084758929212105e-05), [('left', 0.013167526842829487, 9974.961602509315, 68.06779434309932, -2991.6702078968083, -0.017294425109758964), ('right', -0.01846885860426641, 1116.7192306041861, 247.41661240936165, -225.61460446012788, 0.006420848651969105), ('right', -0.028608162503465366, 10765.507749673327, 2970.777303551824, -1218.9730591440357, 0.6155786160164635)]),
    ('hertz', 0.0068, 0.002, 'normal'): ((0.005740713661017976, 0.0041094575111453304, 0.0041094575111453304), [('left', 0.01818270686573099, 10000.181891324562, -15.004940217743105, 2759.4135728089086, -0.4788895768363724), ('right', -0.040743095592718395, 24479.99944427747, 7166.109202226832, 1018.1738771828152, 4.546589380849945)]),
    # the right patch since the fix of the parabolic refinement of the gap minimum (it
    # continues from its best point instead of losing the minimum); before: y_wheel
    # 0.018141175415075914, Fx 755.6402221283687, Fs 3038.6414227523396, Mz -0.40331829994212864
    # (the two points are 9.4e-13 m apart, their gaps differ by 2e-16 m: round-off)
    ('kik-piotrowski', -0.0068, 0.003, 'normal'): ((-0.00574285305362323, 0.004111077791551907, 0.004111077791551907), [('left', -0.04074555555622661, 22259.686056841758, 6507.073714979333, 885.1703937278862, -4.7038327182622135), ('right', 0.018141175414139336, 11000.210028460391, 755.6402220515554, 3038.6414223557867, -0.4033183006090711)]),
    ('kik-piotrowski', 0.005, 0.0, 'total'): ((0.0003695270279448543, 3.168298574320246e-05, 3.168298574320246e-05), [('left', 0.013085422281712493, 9999.957495157832, 244.0202279831213, -48.58479012242941, -0.07010926442683735), ('right', -0.028618291016855254, 11452.28050707829, 3382.3475815368583, 213.79246645617866, 1.0246668877000242)]),
}


@pytest.fixture(scope="module")
def s1002():
    ws = wr.Wheelset(wheel=wr.profiles.load("S1002"), nominal_radius=0.46, flange_back=1.360)
    tr = wr.Track(rail=wr.profiles.load("60E1"), gauge=1.435, inclination=1 / 40)
    return ws, tr


def _global_min_arrays(ws, tr, side, pose, step, levels=5):
    """The array version of the refined global gap minimum (the code before the kernels)."""
    d, (s, lo, hi, h) = cs._grid_gap(ws, tr, side, pose, step)
    zc = pose.zc(ws)
    dm = np.full_like(d, np.inf)
    dm[:, 1:-1] = np.where(cs._interior_minima(d), d[:, 1:-1], np.inf)
    rows = np.arange(d.shape[0])
    dm[rows, np.argmin(d, axis=1)] = d[rows, np.argmin(d, axis=1)]
    first = np.argmin(dm, axis=1)
    dm2 = dm.copy()
    dm2[rows, first] = np.inf
    second = np.where(np.isfinite(dm2.min(axis=1)), np.argmin(dm2, axis=1), first)
    n = rows.size
    fun = cs._gapfun(ws, tr, side, pose.y, zc, pose.roll, pose.yaw)
    sab = cs._refine(fun, np.concatenate([s[first], s[second]]), h, lo, hi, levels)
    dab = fun(sab)
    sa, sb, da, db = sab[:n], sab[n:], dab[:n], dab[n:]
    return np.where(db < da, sb, sa), np.minimum(da, db)


# poses (y, yaw) with one- and two-point contact and flange contact on either wheel
POSES = [(0.0, 0.0), (0.0, 0.002), (0.005, -0.004), (0.0068, 0.002), (-0.0068, 0.003),
         (0.0085, -0.01), (-0.009, 0.0)]


@pytest.mark.parametrize("side", ["left", "right"])
def test_compiled_search_equals_array_search(s1002, side):
    ws, tr = s1002
    y = np.array([p[0] for p in POSES])
    yaw = np.array([p[1] for p in POSES])
    z, roll, _ = cs.solve_rigid(ws, tr, y, yaw)
    # at the rigid pose the global minimum of each side is 0; lift the axle a little too
    for dz in (0.0, 3e-4):
        pose = cs._Pose(y, z + dz, roll, yaw)
        s1, d1, _ = cs._global_min(ws, tr, side, pose, 2e-4)
        s_ref, d_ref = _global_min_arrays(ws, tr, side, pose, 2e-4)
        np.testing.assert_allclose(s1, s_ref, rtol=0, atol=1e-12)
        np.testing.assert_allclose(d1, d_ref, rtol=0, atol=1e-15)
    np.testing.assert_allclose(cs._global_min(ws, tr, side, cs._Pose(y, z, roll, yaw),
                                              2e-4)[1], 0.0, atol=1e-10)
    # every candidate point: refinement and per-point quantities
    data, count = cs.find_points(ws, tr, side, cs._Pose(y, z, roll, yaw), tolerance=5e-4)
    assert count.max() == 2 and count.min() == 1          # two-point contact is among them
    rows, cols = np.nonzero(np.isfinite(data["separation"]))
    sub = cs._Pose(y[rows], z[rows], roll[rows], yaw[rows])
    s0 = data["wheel_y"][rows, cols] + 7e-5                # start off the minimum
    fun = cs._gapfun(ws, tr, side, sub.y, sub.zc(ws), sub.roll, sub.yaw)
    h = cs._grid(ws, side, 2e-4)[3]
    lo, hi = cs._grid(ws, side, 2e-4)[1:3]
    np.testing.assert_allclose(
        cs._refine_fast(ws, tr, side, 2e-4, s0, sub.y, sub.zc(ws), sub.roll, sub.yaw),
        cs._refine(fun, s0, h, lo, hi), rtol=0, atol=1e-13)
    fast = cs.point_data(ws, tr, side, data["wheel_y"][rows, cols], sub)
    ref = cs._point_data_arrays(ws, tr, side, data["wheel_y"][rows, cols], sub)
    assert fast.keys() == ref.keys() == cs.POINT_FIELDS.keys()
    for k in ref:
        np.testing.assert_allclose(fast[k], ref[k], rtol=1e-13, atol=1e-16, err_msg=k)


@pytest.mark.parametrize("case", list(OLD))
def test_solve_one_position_equals_old_numbers(s1002, case):
    ws, tr = s1002
    normal, y, yaw, vertical = case
    m = wr.Motion(speed=20.0, omega=20.0 / 0.46 * 1.001, yaw_rate=0.01)
    # the Kik-Piotrowski numbers are the original method's (constant-factor patch with the
    # shape correction, Kalker's weighted flexibility), the defaults when they were printed
    kw = ({"ellipticity_correction": False, "fastsim_flexibility": "weighted"}
          if normal == "kik-piotrowski" else {})
    r = wr.solve(wr.WheelRailPosition(ws, tr, y, yaw=yaw, vertical_load=(10e3, 11e3)), motion=m,
                 mu=0.3, normal=normal, vertical=vertical, **kw)
    pose, patches = OLD[case]
    # Kik-Piotrowski's separation line interpolates the profile samples by local cubics
    # since these numbers were printed (was a not-a-knot spline): forces < 1e-7 relative
    rtol = 2e-7 if normal == "kik-piotrowski" else 1e-12
    np.testing.assert_allclose((r.pose["roll"], r.pose["z_left"], r.pose["z_right"]), pose,
                               rtol=rtol, atol=1e-17)
    assert [p.side for p in r.patches] == [p[0] for p in patches]
    got = np.array([(p.y_wheel, p.Fn, p.Fx, p.Fs, p.Mz) for p in r.patches])
    want = np.array([p[1:] for p in patches])
    for j, name in enumerate(("y_wheel", "Fn", "Fx", "Fs", "Mz")):
        np.testing.assert_allclose(got[:, j], want[:, j], rtol=rtol,
                                   atol=rtol * np.abs(want[:, j]).max(), err_msg=name)


def test_search_cache_follows_the_profiles(s1002):
    """The compiled kernels' arguments are cached per wheel/rail spline: another profile
    (or another wheelset with the same profile but another radius) gives its own answer."""
    ws, tr = s1002
    other = wr.Wheelset(wheel=wr.profiles.load("S1002"), nominal_radius=0.45,
                        flange_back=1.360)
    tr54 = wr.Track(rail=wr.profiles.load("54E1"), gauge=1.435, inclination=1 / 40)
    m = wr.Motion(speed=20.0)

    def run(w, t):
        r = wr.solve(wr.WheelRailPosition(w, t, 0.004, yaw=0.002, vertical_load=1e4),
                     motion=m, mu=0.3, vertical="normal")
        return np.array([r.pose["roll"], r.pose["z_left"]] + [p.Fn for p in r.patches]
                        + [p.y_wheel for p in r.patches])

    cs._ARGS_CACHE.clear()
    first = {k: run(*wt) for k, wt in {"a": (ws, tr), "b": (other, tr), "c": (ws, tr54)}.items()}
    for k, wt in (("c", (ws, tr54)), ("a", (ws, tr)), ("b", (other, tr)), ("a", (ws, tr))):
        again = run(*wt)
        assert again.shape == first[k].shape and np.array_equal(again, first[k]), k
    assert not np.allclose(first["a"][:2], first["b"][:2], rtol=1e-3)
    assert not np.allclose(first["a"][:2], first["c"][:2], rtol=1e-3)
    # entries hold the splines they were built from and are used only for those objects
    for wc, rc, _ in cs._ARGS_CACHE.values():
        assert wc in (ws.curve("left"), other.curve("left")) and rc in (tr.curve("left"),
                                                                      tr54.curve("left"))


def test_shape_ratio_of_one_ratio_equals_the_array_iteration():
    """The float path of shape_ratio (one contact point) runs the same secant iteration as
    the array path: equal to round-off over ratios 1 … 1e7, and both solve the defining
    equation (Johnson 1985, eq. 3.66) as the bisection reference does."""
    from wheelrail.hertzian import _shape_ratio_bisection, shape_ratio

    r = np.geomspace(1.0, 1e7, 301)
    vec = shape_ratio(r)
    one = np.array([shape_ratio(np.array([x]))[0] for x in r])
    np.testing.assert_allclose(one, vec, rtol=1e-13)
    np.testing.assert_allclose(one, _shape_ratio_bisection(r), rtol=1e-12)
    assert np.ndim(shape_ratio(3.0)) == 0 and shape_ratio(np.array([3.0])).shape == (1,)


def test_fastsim_single_ellipse_skips_only_the_checks():
    """FASTSIM on one Hertz ellipse with fields calls the strip solver without re-checking
    its own arguments: the same forces and fields as fastsim_strips (Kalker 1982) on the
    same strips, and bad input is still refused by name."""
    from wheelrail.errors import InputError
    from wheelrail.tangential import fastsim as fs

    hc = wr.hertz(Fn=9e3, A=1.1, B=4.0, material=wr.STEEL)
    law = fs.Fastsim(nx=12, ny=9)
    for xi, eta, phi in ((-4e-4, 2e-4, 0.5), (3e-3, -2e-3, -1.0), (0.0, 0.0, 0.0)):
        r = law.solve(hc, xi, eta, phi, 0.3)
        C11, C22, C23, _ = fs.kalker_coefficients(np.atleast_1d(hc.a / hc.b), hc.nu)
        L1, L2, L3 = fs.flexibilities(np.atleast_1d(hc.a), np.atleast_1d(hc.b), hc.G, C11,
                                      C22, C23)
        t = fs._strip_t(9)
        s = fs._profile("parabolic", 1.0 - (np.arange(12) + 0.5) * (2.0 / 12))
        discrete = (4.0 / (12 * 9)) * np.sum(fs._profile("parabolic", t) * np.sqrt(1 - t * t)) \
            * np.sum(s)
        peak = 2.0 * hc.Fn / (np.pi * hc.a * hc.b) * (np.pi / 2.0 / discrete)
        ref = fs.fastsim_strips(*fs.hertz_strips(hc.a, hc.b, 9),
                                peak * fs._profile("parabolic", t), L1[0], L2[0], L3[0], xi,
                                eta, phi, 0.3, 12, profile="parabolic")
        assert (r.Fx, r.Fy, r.Mz) == (ref.Fx, ref.Fy, ref.Mz)
        for name in ("px", "py", "sx", "sy", "slip", "pressure", "x", "y"):
            np.testing.assert_array_equal(getattr(r.fields, name), getattr(ref.fields, name))
    with pytest.raises(InputError, match="mu"):
        law.solve(hc, 1e-3, 0.0, 0.0, -0.3)
    with pytest.raises(InputError, match="xi"):
        law.solve(hc, np.nan, 0.0, 0.0, 0.3)


def test_vertical_approach_of_one_wheel_equals_the_array_iteration():
    """The float path of the vertical approach (one wheel, up to 4 points) runs the same
    Newton iteration as the array path (rows of many wheels): Σ cos γ (δ/δ1)^{3/2} = Q."""
    from wheelrail.hertzian import _vertical_approach

    rng = np.random.default_rng(3)
    for n in (1, 2, 3, 4):
        for _ in range(20):
            sep = np.sort(rng.uniform(0.0, 2e-4, n))
            cosg = np.cos(rng.uniform(0.0, 1.2, n))
            d1 = rng.uniform(2e-7, 8e-7, n)
            Q = float(rng.uniform(1e3, 1e5))
            one = _vertical_approach(Q, sep, cosg, d1)
            rows = _vertical_approach(np.array([Q, 2 * Q]), np.stack([sep, sep]),
                                      np.stack([cosg, cosg]), np.stack([d1, d1]))
            assert isinstance(one, float)
            assert one == pytest.approx(rows[0], rel=1e-14, abs=1e-18)
            pen = np.clip(one * cosg - sep, 0.0, None)
            assert np.sum((pen / d1) ** 1.5 * cosg) == pytest.approx(Q, rel=1e-11)


def test_patch_from_hertz_without_rechecks_equals_the_checked_patch():
    """ContactPatch.from_hertz skips __post_init__ for a sound ellipse: the patch equals the
    one the checked constructor builds from the same fields (semi-elliptic pressure, Johnson
    1985 eq. 3.63), and a bad ellipse is still refused by name."""
    import dataclasses

    from wheelrail.patch import ContactPatch
    from wheelrail.errors import InputError

    hc = wr.hertz(Fn=9e3, A=1.1, B=4.0, material=wr.STEEL)
    fast = ContactPatch.from_hertz(hc, strips=12, cells=9)
    checked = dataclasses.replace(fast)            # runs __init__ and __post_init__
    for f in dataclasses.fields(ContactPatch):
        a, b = getattr(fast, f.name), getattr(checked, f.name)
        if isinstance(a, np.ndarray):
            assert a.dtype == b.dtype and a.shape == b.shape
            np.testing.assert_array_equal(a, b)
        else:
            assert a is b or a == b or (a != a and b != b), f.name
    assert fast.Fn == pytest.approx(np.sum(fast.strip_pressure * (2 * fast.x_lead / 9)[:, None]
                                           * fast.dy[:, None]), rel=0.02)
    with pytest.raises(InputError, match="Fn"):
        ContactPatch.from_hertz(dataclasses.replace(hc, Fn=-1.0))


def _find_points_arrays(ws, tr, side, pose, tolerance, step=2e-4):
    """The array version of find_points (the code before the kernels): reference."""
    d, (s, lo, hi, h) = cs._grid_gap(ws, tr, side, pose, step)
    nrow = d.shape[0]
    gmin = np.argmin(d, axis=1)
    interior = np.zeros_like(d, dtype=bool)
    interior[:, 1:-1] = cs._interior_minima(d)
    interior &= d <= 6.0 * tolerance + 1e-9
    interior[np.arange(nrow), gmin] = True
    rows, idx = np.nonzero(interior)
    keep = np.ones(rows.size, dtype=bool)
    for k in range(1, rows.size):
        if rows[k] != rows[k - 1]:
            continue
        j = k - 1
        while j >= 0 and not keep[j] and rows[j] == rows[k]:
            j -= 1
        if j < 0 or rows[j] != rows[k]:
            continue
        i1, i2 = idx[j], idx[k]
        if np.max(d[rows[k], i1:i2 + 1]) - max(d[rows[k], i1], d[rows[k], i2]) < cs._MERGE:
            keep[j if d[rows[k], i2] < d[rows[k], i1] else k] = False
    rows, idx = rows[keep], idx[keep]
    sub = cs._Pose(*(np.asarray(v)[rows] for v in (pose.y, pose.z, pose.roll, pose.yaw)))
    fun = cs._gapfun(ws, tr, side, sub.y, sub.zc(ws), sub.roll, sub.yaw)
    sref = cs._refine(fun, s[idx], h, lo, hi)
    data = cs._point_data_arrays(ws, tr, side, sref, sub)
    sep = data["separation"]
    rowmin = np.full(nrow, np.inf)
    np.minimum.at(rowmin, rows, sep)
    ok = (sep <= tolerance) | (sep == rowmin[rows])
    order = np.lexsort((-sref, rows))
    last_row, last_s = -1, np.nan
    for k in order:
        if not ok[k]:
            continue
        if rows[k] == last_row and abs(sref[k] - last_s) < 1e-6:
            ok[k] = False
            continue
        last_row, last_s = rows[k], sref[k]
    order = order[ok[order]]
    return {k: np.asarray(v)[order] for k, v in data.items()}, rows[order]


@pytest.mark.parametrize("side", ["left", "right"])
def test_find_points_equals_array_search_over_a_sweep(s1002, side):
    """Candidate points over y = −10 … 10 mm (one, two and flange points), also 0.3 mm
    above the touching pose and with a large tolerance (distant minima kept)."""
    ws, tr = s1002
    y = np.linspace(-0.01, 0.01, 41)
    yaw = np.full(y.size, -0.003)
    z, roll, _ = cs.solve_rigid(ws, tr, y, yaw)
    for dz, tol in ((0.0, 5e-4), (3e-4, 2e-3)):
        pose = cs._Pose(y, z + dz, roll, yaw)
        data, count = cs.find_points(ws, tr, side, pose, tolerance=tol)
        ref, rows = _find_points_arrays(ws, tr, side, pose, tol)
        np.testing.assert_array_equal(count, np.bincount(rows, minlength=y.size))
        assert count.max() >= 2
        got = np.isfinite(data["separation"])
        for k in cs.POINT_FIELDS:
            np.testing.assert_allclose(data[k][got], ref[k], rtol=1e-12, atol=1e-15, err_msg=k)
