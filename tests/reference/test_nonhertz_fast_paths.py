"""Fast paths of the strip methods against the general code they replace.

The per-contact timings of Kik–Piotrowski / STRIPES + FASTSIM rest on fused
numba kernels and on values cached on a wheel problem's lines. Each is
checked here against an independent or the general computation:

* NumPy's pairwise summation (``numpy.add.reduce`` of float64), which the
  patch kernel reproduces so that a patch is the same to the last bit;
* the strip patch of a region against the NumPy expressions of the patch
  construction (written out here);
* the vectorised AGM of the Kik–Piotrowski integrals against SciPy's complete
  elliptic integrals (closed form of eqs. 13–15, seed 003 §3.2);
* FASTSIM on a strip patch through one fused kernel (with and without
  fields) against the general path, also for creepages large enough to need it;
* cached line data (penetration factor, load-kernel arguments, STRIPES'
  smoothed curvature per node): a second solve of the same wheel problem with
  other options or another load equals a solve of a fresh problem.
"""

import dataclasses

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.contact.wheelrail import touching_poses, wheel_problem


@pytest.fixture(scope="module")
def s1002():
    ws = wr.Wheelset(wheel=wr.profiles.load("S1002"), nominal_radius=0.46, flange_back=1.360)
    tr = wr.Track(rail=wr.profiles.load("60E1"), gauge=1.435, inclination=1 / 40)
    return ws, tr


def _problem(s1002, y, load=70e3):
    ws, tr = s1002
    wp = wr.WheelRailPosition(ws, tr, y, yaw=0.002, vertical_load=load)
    roll, zs = touching_poses(wp)
    return wheel_problem(wp, "right", roll, zs["right"])


def test_pairwise_sum_is_numpys():
    from wheelrail.normal._patch_kernel import pairwise_sum

    rng = np.random.default_rng(1)
    for n in list(range(1, 140)) + [255, 256, 257, 1000, 1601, 4097]:
        a = rng.standard_normal(n) * rng.uniform(1.0, 1e6, n)
        assert pairwise_sum(a, 0, n, 1) == np.sum(a), n
        m = a.reshape(1, n)
        assert pairwise_sum(a, 0, n, 1) == m.sum(axis=1)[0], n
    b = rng.standard_normal((40, 40))
    assert pairwise_sum(b.ravel(), 3, 40, 40) == np.sum(b[:, 3])


def test_positive_runs_are_runs():
    from wheelrail.normal._patch_kernel import positive_runs
    from wheelrail.normal._strips import runs

    rng = np.random.default_rng(2)
    for n in (1, 2, 3, 17, 1601):
        for _ in range(50):
            g = rng.standard_normal(n)
            assert [tuple(r) for r in positive_runs(g).tolist()] == runs(g > 0)


def _patch_numpy(eta_n, xl_n, pk_n, strips, cells, N, eta_ref, sign):
    """The strip description of a region in NumPy expressions (the construction the
    kernel replaces)."""
    hn = float(eta_n[1] - eta_n[0])
    lo, hi = eta_n[0] - 0.5 * hn, eta_n[-1] + 0.5 * hn
    width = hi - lo
    dy = width / strips
    ys = lo + (np.arange(strips) + 0.5) * dy
    e_ext = np.concatenate(([lo], eta_n, [hi]))
    xl = np.sqrt(np.clip(np.interp(ys, e_ext, np.concatenate(([0.0], xl_n ** 2, [0.0]))),
                         0.0, None))
    pk = np.interp(ys, e_ext, np.concatenate(([0.0], pk_n, [0.0])))
    s = 1.0 - (np.arange(cells) + 0.5) * (2.0 / cells)
    sp = pk[:, None] * np.sqrt(np.clip(1.0 - s * s, 0.0, None))[None, :]
    got = float(np.sum(sp.sum(axis=1) * (2 * xl / cells) * dy))
    sp *= N / got
    y = sign * (ys - eta_ref)
    order = np.argsort(y)
    return y[order], xl[order], sp[order], float(np.sum(2 * xl) * dy), 2 * float(np.max(xl))


@pytest.mark.parametrize("sign", [1.0, -1.0])
@pytest.mark.parametrize("n, strips, cells", [(5, 40, 40), (300, 40, 40), (1201, 13, 7)])
def test_strip_patch_kernel_equals_numpy(sign, n, strips, cells):
    from wheelrail.normal._patch_kernel import strip_patch

    rng = np.random.default_rng(n)
    eta = np.linspace(-0.004, 0.007, n)
    xl = 0.006 * np.sqrt(1 - np.linspace(-0.98, 0.98, n) ** 2) * (1 + 0.1 * rng.random(n))
    pk = 1e9 * xl / xl.max()
    ref = _patch_numpy(eta, xl, pk, strips, cells, 3.3e4, 0.001, sign)
    y, x, sp, ys, dy, width, area, L, ok = strip_patch(eta, xl, pk, 1.0, strips, cells,
                                                        3.3e4, 0.001, sign)
    assert ok
    np.testing.assert_array_equal(y, ref[0])
    np.testing.assert_array_equal(x, ref[1])
    np.testing.assert_array_equal(sp, ref[2])
    assert (area, L) == (ref[3], ref[4])


def test_kp_integrals_against_scipy():
    """Vectorised AGM against the SciPy form of the same integrals (K, E from SciPy)."""
    from wheelrail.normal._kp_kernel import kp_integrals_kernel
    from wheelrail.normal._strips import kp_integrals

    rng = np.random.default_rng(3)
    for n in (3, 50, 400, 1200):
        t = np.linspace(-1, 1, n)
        for _ in range(5):
            xl = (rng.uniform(1e-3, 1e-2) * np.sqrt(np.clip(1 - t * t, 0, None))
                  * (1 + 0.3 * np.sin(rng.uniform(1, 9) * t)))
            j0 = int(rng.integers(0, n))
            h = rng.uniform(5e-6, 5e-5)
            a = kp_integrals_kernel(xl, h, j0)
            b = kp_integrals(xl, h, j0)
            assert a[0] == pytest.approx(b[0], rel=1e-14)
            assert a[1] == pytest.approx(b[1], rel=1e-12)


@pytest.mark.parametrize("normal", ["kik-piotrowski", "stripes", "linder"])
@pytest.mark.parametrize("creep", [(1e-3, 1e-3, 0.1), (-2e-3, 5e-4, -1.0), (0.0, 0.0, 0.0),
                                   (3e-2, 0.0, 0.0), (1e240, -1e240, 0.0)])
def test_fastsim_fused_equals_general_path(s1002, normal, creep, monkeypatch):
    """FASTSIM on a strip patch through the fused kernel (with and without fields)
    against the general path (resampling in NumPy, ``_solve_strips``), which the
    fused path replaces; creepages of 1e240 exceed the fused kernel's rate bound
    and take the general path in both (not with Kik–Piotrowski's weighted
    flexibility, whose norm √(ξ² + η² + ...) overflows there on both paths)."""
    from wheelrail.tangential.fastsim import Fastsim

    if normal == "kik-piotrowski" and creep[0] > 1e100:
        creep = (1e140, -1e140, 0.0)
    nm = wr.normal.get(normal)
    tm = wr.tangential.get("fastsim")
    for y in (0.0, 0.005):               # 0.005: two patches on the right wheel
        ps, _ = nm.from_wheel(_problem(s1002, y))
        cr = [creep] * len(ps)
        opt = {"scheme": "euler", "nx": 13} if y else {}     # CONTACT's march, other cells
        a = tm.replace(**{"fields": False, **opt}).solve_patches(ps, cr, 0.3)
        b = tm.replace(**{"fields": True, **opt}).solve_patches(ps, cr, 0.3)
        with monkeypatch.context() as m:
            m.setattr(Fastsim, "_patch_forces", lambda *args: None)
            g = tm.replace(**{"fields": True, **opt}).solve_patches(ps, cr, 0.3)
        for u, v, r in zip(a, b, g):
            assert u.fields is None and v.fields is not None
            s = 0.3 * r.Fn
            for q in (u, v):
                assert abs(q.Fx - r.Fx) <= 1e-12 * s and abs(q.Fy - r.Fy) <= 1e-12 * s
                assert abs(q.Mz - r.Mz) <= 1e-12 * s * 0.01
                assert q.Fn == pytest.approx(r.Fn, rel=1e-13)
                assert q.info["L"] == r.info["L"]
                assert q.info["flexibility"] == r.info["flexibility"]
            assert v.status == r.status
            assert v.info["adhesion_fraction"] == r.info["adhesion_fraction"]
            for k in ("x", "y", "dx", "dy", "mu", "slip"):
                np.testing.assert_array_equal(getattr(v.fields, k), getattr(r.fields, k), k)
            for k in ("pressure", "px", "py", "sx", "sy"):
                np.testing.assert_allclose(getattr(v.fields, k), getattr(r.fields, k),
                                           rtol=1e-12, atol=1e-12 * float(
                                               np.max(np.abs(getattr(r.fields, k))) or 1.0),
                                           err_msg=k)


def test_fastsim_forces_only_rejects_bad_mu(s1002):
    nm = wr.normal.get("kik-piotrowski")
    tm = wr.tangential.get("fastsim")
    ps, _ = nm.from_wheel(_problem(s1002, 0.0))
    with pytest.raises(wr.errors.InputError, match="mu must be > 0, got -0.3"):
        tm.replace(fields=False).solve_patch(ps[0], 1e-3, 0.0, 0.0, -0.3)


def _forces(ps):
    return np.array([[p.Fn, p.area, p.p_max, p.a, p.b, p.frame.contact_angle] for p in ps])


@pytest.mark.parametrize("normal, first, second", [
    ("kik-piotrowski", {}, {"ellipticity_correction": False}),
    ("kik-piotrowski", {"ellipticity_correction": False},
     {"ellipticity_correction": False, "shape_correction": False}),
    ("kik-piotrowski", {"ellipticity_correction": False},
     {"ellipticity_correction": False, "penetration_factor": 0.55}),
    ("stripes", {}, {"smoothing": 0.004}),
    ("stripes", {"strips": 10}, {"strips": 40}),
])
def test_cached_line_data_follow_options(s1002, normal, first, second):
    """A wheel problem solved once keeps line data in its cache; a second solve with
    other options must equal a solve of a fresh problem with those options."""
    nm = wr.normal.get(normal)
    prob = _problem(s1002, 0.005)
    nm.replace(**first).from_wheel(prob)
    again, _ = nm.replace(**second).from_wheel(prob)
    fresh, _ = nm.replace(**second).from_wheel(_problem(s1002, 0.005))
    np.testing.assert_array_equal(_forces(again), _forces(fresh))
    for p, q in zip(again, fresh):
        np.testing.assert_array_equal(p.strip_pressure, q.strip_pressure)
        if "strip_semiaxes" in q.info:
            np.testing.assert_array_equal(p.info["strip_semiaxes"][1],
                                          q.info["strip_semiaxes"][1])


@pytest.mark.parametrize("normal", ["kik-piotrowski", "stripes"])
def test_cached_line_data_follow_the_load(s1002, normal):
    """The load changes the regions (STRIPES then needs its curvature at new nodes):
    the cached problem must give what a fresh one gives."""
    nm = wr.normal.get(normal)
    o = nm
    prob = _problem(s1002, -0.004, load=20e3)
    small, _ = o.from_wheel(prob)
    big, _ = o.from_wheel(dataclasses.replace(prob, vertical_load=120e3))
    fresh, _ = o.from_wheel(_problem(s1002, -0.004, load=120e3))
    assert big[0].area > 2 * small[0].area
    np.testing.assert_array_equal(_forces(big), _forces(fresh))
    if normal == "stripes":
        np.testing.assert_array_equal(big[0].info["strip_semiaxes"][1],
                                      fresh[0].info["strip_semiaxes"][1])


def test_stripes_read_nodes_cover_the_interpolation():
    """The STRIPES strip ellipses are computed only at the nodes the patch reads:
    NaN elsewhere must not reach the interpolated strip values."""
    from wheelrail.normal.stripes import _read_nodes

    rng = np.random.default_rng(4)
    for n in (30, 85, 300, 1201):
        for strips in (5, 40):
            eta = np.linspace(-0.01, 0.01, n) * rng.uniform(0.5, 2) + rng.uniform(-1e-3, 1e-3)
            full = rng.random(n)
            part = np.full(n, np.nan)
            idx = _read_nodes(eta, strips)
            part[idx] = full[idx]
            hn = eta[1] - eta[0]
            lo = eta[0] - 0.5 * hn
            ys = lo + (np.arange(strips) + 0.5) * ((eta[-1] + 0.5 * hn - lo) / strips)
            np.testing.assert_array_equal(np.interp(ys, eta, part), np.interp(ys, eta, full))


def test_separation_kernel_equals_full_splines(s1002):
    """The separation's local cubics through the 0.04 mm profile samples (the samples around
    the η interval only) give scipy's not-a-knot splines through the full monotone window
    within 2 nm (both are exact for cubics), and are exact for a cubic."""
    from scipy.interpolate import CubicSpline

    from wheelrail.geometry.separation import _monotone_window
    from wheelrail.normal._fast_separation import local_cubic, plane_samples, separation_fast

    ws, tr = s1002
    prob = _problem(s1002, 0.003)
    f = prob.frames[0]
    p = prob.pose
    sep = separation_fast(ws, tr, "right", y=p["y"], z=p["z"], roll=p["roll"], yaw=p["yaw"],
                          wheel_y=f.wheel_y, track_y=f.track_y, contact_angle=f.contact_angle,
                          width=0.04, n=1601)
    wc, rc = ws.curve("right"), tr.curve("right")
    u_c = f.track_y
    s = np.linspace(max(wc.u_min, f.wheel_y - 0.04), min(wc.u_max, f.wheel_y + 0.04), 2001)
    ur = np.linspace(max(rc.u_min, u_c - 0.04), min(rc.u_max, u_c + 0.04), 2001)
    ew, zw, rw, er, zr = plane_samples(s, wc.u, wc.c, wc._h, ur, rc.u, rc.c, rc._h,
                                       ws.nominal_radius, ws.e_tape, 1.0, p["y"],
                                       ws.nominal_radius + p["z"], p["roll"], p["yaw"], u_c,
                                       float(rc.eval(u_c, 0)[0]), f.contact_angle)
    sw = _monotone_window(ew, int(np.argmin(np.abs(ew))))
    sr = _monotone_window(er, int(np.argmin(np.abs(er))))
    assert sw.stop - sw.start > 1500      # the kernel cuts about half of these samples
    W = CubicSpline(ew[sw], np.stack([zw[sw], rw[sw]]).T)(sep.eta).T
    R = CubicSpline(er[sr], zr[sr])(sep.eta)
    np.testing.assert_allclose(sep.f, W[0] - R, rtol=0, atol=2e-9)
    np.testing.assert_allclose(sep.wheel_radius, W[1], rtol=0, atol=2e-9)
    x = np.sort(np.random.default_rng(3).uniform(-1.0, 2.0, 40))
    t = np.linspace(x[1], x[-2], 333)
    cubic = lambda v: 0.3 * v**3 - 1.1 * v**2 + 0.5 * v - 2.0          # noqa: E731
    np.testing.assert_allclose(local_cubic(x, np.stack([cubic(x), 2 * cubic(x)]), t),
                               np.stack([cubic(t), 2 * cubic(t)]), rtol=0, atol=1e-12)


def test_stripes_n_over_m_table_equals_hertz():
    """The n/m table of STRIPES (all grid values at once) against Hertz's b/a per λ."""
    from wheelrail.hertzian import hertz_kernel
    from wheelrail.normal.stripes import _NM_K, _n_over_m, _n_over_m_array, _nm_table

    q = np.arange(-_NM_K, _NM_K + 1) / 50.0
    t = _nm_table()
    np.testing.assert_allclose(t, [_n_over_m(v) for v in np.exp(q)], rtol=1e-15, atol=0)
    for lam in (0.05, 0.3, 1.0, 4.0, 30.0):
        a, b, _, _ = hertz_kernel(1.0, lam, 1.0, 1.0)
        # quantised to 2 % in ln λ: b/a within the change of b/a over 1 % of ln λ
        assert _n_over_m_array(np.array([lam]))[0] == pytest.approx(float(b / a), rel=0.01)


def test_stripes_smoothing_kernels_equal_numpy():
    """½ f'' (two ``numpy.gradient``) to the bit, and the Gaussian smoothing at chosen
    nodes (edges included) against ``numpy.convolve`` of the edge-padded curvature."""
    from wheelrail.normal._stripes_kernel import half_curvature, smooth_nodes
    from wheelrail.normal.stripes import _smoothing

    rng = np.random.default_rng(5)
    eta = np.linspace(-0.02, 0.02, 1601)
    f = 3 * eta ** 2 + 1e-3 * np.sin(300 * eta) + 1e-7 * rng.random(eta.size)
    h = eta[1] - eta[0]
    np.testing.assert_array_equal(half_curvature(f, h), np.gradient(np.gradient(f, h), h) * 0.5)
    d2, krev = _smoothing(eta, f, 0.002)
    half = krev.size // 2
    ref = np.convolve(np.pad(d2, half, mode="edge"), krev[::-1], mode="valid")
    idx = np.array([0, 1, half - 1, half, 700, 701, 1601 - half, 1599, 1600])
    np.testing.assert_allclose(smooth_nodes(d2, krev, idx), ref[idx], rtol=1e-14)


@pytest.mark.parametrize("opts", [{"ellipticity_correction": False},
                                  {"ellipticity_correction": False, "shape_correction": False},
                                  {"ellipticity_correction": False, "penetration_factor": 0.55}])
def test_kp_region_kernel_equals_python_loop(s1002, opts, monkeypatch):
    """Kik–Piotrowski's regions from one kernel against the Python loop it replaces
    (still used beyond the Hertz table), on a wheel with two patches and a Hertzian gap."""
    from wheelrail.normal import _kp_kernel

    nm = wr.normal.get("kik-piotrowski")
    o = nm.replace(**opts)
    c = wr.hertz(1e5, 1.0, 4.0, wr.STEEL)

    def solve():
        w, _ = o.from_wheel(_problem(s1002, 0.005))
        return w + o.from_contact(c)

    fast = solve()
    with monkeypatch.context() as m:
        m.setattr(_kp_kernel, "kp_line_regions",
                  lambda *a: (False, np.zeros((0, 6)), None, None, None))
        slow = solve()
    assert len(fast) == len(slow) == 3
    for p, q in zip(fast, slow):
        np.testing.assert_allclose(_forces([p]) if p.frame else [[p.Fn, p.area, p.p_max]],
                                   _forces([q]) if q.frame else [[q.Fn, q.area, q.p_max]],
                                   rtol=1e-14)
        np.testing.assert_allclose(p.strip_pressure, q.strip_pressure, rtol=1e-13,
                                   atol=1e-13 * q.p_max)
        if q.info["alpha"] is None:
            assert p.info["alpha"] is None
        else:
            assert p.info["alpha"] == pytest.approx(q.info["alpha"], rel=1e-15)


def test_strip_flexibilities_kernel_equals_numpy():
    """Per-strip flexibilities of STRIPES/Linder patches: kernel against
    ``flexibilities`` with the interpolated Kalker coefficients; a/b beyond the
    table is refused (the caller then evaluates Kalker's coefficients directly)."""
    from wheelrail.tangential._fastsim_kernel import strip_flexibilities
    from wheelrail.tangential.fastsim import _kalker_scalar, _kalker_table, flexibilities

    rng = np.random.default_rng(6)
    sa = rng.uniform(1e-3, 8e-3, 40)
    sb = sa / rng.uniform(0.05, 20.0, 40)
    G, nu = wr.STEEL.G, wr.STEEL.nu
    ok, L1, L2, L3, m1, m2, m3 = strip_flexibilities(sa, sb, G, *_kalker_table(nu))
    assert ok
    ref = flexibilities(sa, sb, G, *_kalker_scalar(sa / sb, nu))
    for v, r, m in zip((L1, L2, L3), ref, (m1, m2, m3)):
        np.testing.assert_allclose(v, r, rtol=1e-14)
        assert m == pytest.approx(float(np.median(r)), rel=1e-14)
    sb[3] = sa[3] / 150.0
    assert not strip_flexibilities(sa, sb, G, *_kalker_table(nu))[0]
