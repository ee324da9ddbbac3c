"""Batched geometry of the wheelset sweep (contact/_strip_batch.py) for the non-Hertzian methods.

Reference: the per-position path (``batch=False``: one ``wr.solve`` per
position), which the batched path must reproduce — only the touching poses
and candidate points are computed for all positions at once. Also: the
load kernel of Kik–Piotrowski (normal/_kp_kernel.py) against the region
construction it replaces, and K − E against SciPy.
"""

import numpy as np
import pytest

import wheelrail as wr


@pytest.fixture(scope="module")
def s1002():
    ws = wr.Wheelset(wheel=wr.profiles.load("S1002"), nominal_radius=0.46, flange_back=1.360)
    tr = wr.Track(rail=wr.profiles.load("60E1"), gauge=1.435, inclination=1 / 40)
    return ws, tr


@pytest.mark.parametrize("normal", ["kik-piotrowski", "stripes"])
def test_batch_equals_per_position(s1002, normal):
    ws, tr = s1002
    y = np.array([-0.006, 0.0, 0.005, 0.0075])          # 0.005: two patches on the right
    m = wr.Motion(speed=20.0, omega=20.0 / 0.46 * 1.001)
    kw = dict(yaw=0.002, vertical_load=70e3, motion=m, mu=0.3, normal=normal, progress=False)
    a = wr.wheelset_sweep(ws, tr, y, **kw)
    b = wr.wheelset_sweep(ws, tr, y, batch=False, **kw)
    assert (a.status.values == b.status.values).all() and (a.status != "error").all()
    assert (a.n_patches.values == b.n_patches.values).all()
    assert a.n_patches.max() >= 2
    for k in ("Fn", "Fx", "Fs", "Mz", "area", "p_max", "xi", "eta", "phi"):
        np.testing.assert_allclose(a[k].values, b[k].values, rtol=1e-6, atol=1e-9, err_msg=k)


def test_batch_records_errors_per_position(s1002):
    """A position beside the rail fails alone, with the per-position message."""
    ws, tr = s1002
    m = wr.Motion(speed=20.0)
    y = np.array([0.0, 0.2])
    kw = dict(roll=0.0, vertical_load=70e3, motion=m, normal="kik-piotrowski", progress=False)
    a = wr.wheelset_sweep(ws, tr, y, **kw)
    b = wr.wheelset_sweep(ws, tr, y, batch=False, **kw)
    assert list(a.status.values) == ["ok", "error"]
    assert a.message.values[1] == b.message.values[1]
    assert "beside its rail" in a.message.values[1]


def test_k_minus_e_against_scipy():
    from scipy.special import ellipe, ellipk

    from wheelrail.normal._kp_kernel import k_minus_e

    for m in (1e-6, 0.1, 0.5, 0.9, 0.999, 1 - 1e-9):
        assert k_minus_e(m) == pytest.approx(float(ellipk(m) - ellipe(m)), rel=1e-12)


def test_kp_line_load_kernel_equals_regions(s1002):
    """The iteration's kernel gives the load of the regions _solve_line builds."""
    from wheelrail.contact.wheelrail import touching_poses, wheel_problem
    from wheelrail.normal._strips import VirtualPenetration

    ws, tr = s1002
    kp = wr.normal.get("kik-piotrowski")
    for y, opt in ((0.0, {"ellipticity_correction": True}),
                   (0.005, {"ellipticity_correction": True}), (0.005, {}),
                   (0.005, {"ellipticity_correction": False, "shape_correction": False})):
        wp = wr.WheelRailPosition(ws, tr, y, yaw=0.002, vertical_load=70e3)
        roll, zs = touching_poses(wp)
        prob = wheel_problem(wp, "right", roll, zs["right"])
        m = kp.replace(**opt)
        opts = m.option_values()
        for line in m._wheel_lines(prob):
            for d in (2e-5, 8e-5):
                fast = m._line_loads(line, d, opts)
                slow = VirtualPenetration._line_loads(m, line, d, opts)
                assert fast == pytest.approx(slow, rel=1e-9)


def test_stripes_line_load_equals_regions(s1002):
    from wheelrail.contact.wheelrail import touching_poses, wheel_problem
    from wheelrail.normal._strips import VirtualPenetration

    ws, tr = s1002
    st = wr.normal.get("stripes")
    wp = wr.WheelRailPosition(ws, tr, 0.005, yaw=0.002, vertical_load=70e3)
    roll, zs = touching_poses(wp)
    prob = wheel_problem(wp, "right", roll, zs["right"])
    opts = st.option_values()
    for line in st._wheel_lines(prob):
        for d in (2e-5, 8e-5):
            assert st._line_loads(line, d, opts) == pytest.approx(
                VirtualPenetration._line_loads(st, line, d, opts), rel=1e-12)


def test_kalker_table_interpolation():
    """The fine table used for patches agrees with kalker_coefficients within 1e-6."""
    from wheelrail.tangential.fastsim import _kalker_scalar
    from wheelrail.tangential.linear import kalker_coefficients

    ab = np.geomspace(0.011, 95.0, 997)
    got = np.array(_kalker_scalar(ab, 0.28))
    ref = np.array(kalker_coefficients(ab, 0.28)[:3], dtype=float)
    assert np.max(np.abs(got / ref - 1)) < 1e-6
    assert _kalker_scalar(1.3, 0.28)[0] == pytest.approx(float(kalker_coefficients(1.3, 0.28)[0]),
                                                         rel=1e-6)


def test_fast_separation_equals_separation_at(s1002):
    """The compiled separation reproduces the reference implementation's (the same samples
    and local cubics) to round-off."""
    from wheelrail.contact.wheelrail import touching_poses, wheel_problem
    from wheelrail.geometry.separation import separation_at
    from wheelrail.normal._fast_separation import separation_fast

    ws, tr = s1002
    for y, yaw, side in ((0.0, 0.002, "right"), (0.005, 0.002, "right"),
                         (0.005, 0.0, "right"), (-0.006, -0.003, "left")):
        wp = wr.WheelRailPosition(ws, tr, y, yaw=yaw, vertical_load=70e3)
        roll, zs = touching_poses(wp)
        prob = wheel_problem(wp, side, roll, zs[side])
        p = prob.pose
        for k, f in enumerate(prob.frames):
            kw = dict(y=p["y"], z=p["z"], roll=p["roll"], yaw=p["yaw"], wheel_y=f.wheel_y,
                      track_y=f.track_y, contact_angle=f.contact_angle, width=0.04, n=1601,
                      point=k)
            a = separation_fast(ws, tr, side, **kw)
            b = separation_at(ws, tr, side, **kw)
            np.testing.assert_array_equal(a.eta, b.eta)
            np.testing.assert_allclose(a.f, b.f, rtol=0, atol=1e-13)
            np.testing.assert_allclose(a.wheel_radius, b.wheel_radius, rtol=1e-13)
            assert (a.cos_factor, a.point) == (b.cos_factor, b.point)
