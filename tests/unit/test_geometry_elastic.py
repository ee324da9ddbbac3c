"""Elastic / quasi-elastic wheelset contact (seed 002, eqs. 2.4, 2.5) and the profile
separation of seed 003, eq. 4."""

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.errors import InputError
from wheelrail.geometry.separation import interpenetration, undeformed_distance_kernel


@pytest.fixture(scope="module")
def pair():
    return wr.Wheelset(wr.profiles.load("S1002")), wr.Track(wr.profiles.load("60E1"))


def _cone_pair():
    s = np.linspace(-0.05, 0.06, 221)
    y = np.linspace(-0.035, 0.035, 281)
    ws = wr.Wheelset(wr.Profile(s, s / 20, kind="wheel"))
    tr = wr.Track(wr.Profile(y, np.sqrt(0.09 - y * y) - 0.3, kind="rail"), gauge_height=0.001)
    return ws, tr


def test_elastic_cone_matches_hertz():
    """One contact per wheel: vertical equilibrium N cos γ = Q/2 and the Hertz approach
    of wr.hertz for the local curvatures (Johnson 1985, eqs. 3.64–3.66)."""
    ws, tr = _cone_pair()
    load = 9.0e4
    res = wr.elastic_contact(ws, tr, 0.0, load)
    for side in ("left", "right"):
        pts = getattr(res, side)
        assert pts.n == 1
        N = res.Fn(side)[0]
        assert N * np.cos(pts.contact_angle[0]) == pytest.approx(load / 2, rel=1e-8)
        hz = wr.hertz(N, pts.A[0], pts.B[0], wr.STEEL)
        assert getattr(res, f"penetration_{side}")[0] == pytest.approx(hz.penetration, rel=1e-6)
    # the wheelset sinks by the approach projected on the vertical
    rigid = wr.contact_points(ws, tr, 0.0)
    g = rigid.right.contact_angle[0]
    assert rigid.z - res.z == pytest.approx(res.penetration_right[0] / np.cos(g), rel=1e-3)
    assert res.lateral_force == pytest.approx(0.0, abs=1e-6 * load)


@pytest.mark.parametrize("y", [0.0, 0.003, 0.005, -0.008])
def test_elastic_equilibrium(pair, y):
    ws, tr = pair
    load = 1.0e5
    res = wr.elastic_contact(ws, tr, y, load)
    assert res.vertical_force_left + res.vertical_force_right == pytest.approx(load, rel=1e-9)
    # roll equilibrium about the axle centre (forces at the contact points)
    zc = ws.nominal_radius + res.z
    M = 0.0
    for side, sig in (("left", -1), ("right", 1)):
        p = getattr(res, side)
        N = res.Fn(side)
        Fy = -sig * np.sin(p.contact_angle) * N
        Fz = np.cos(p.contact_angle) * N
        M += np.sum((p.track_y - y) * Fz - (p.track_z - zc) * Fy)
    assert abs(M) < 1e-8 * load
    assert np.all(res.Fn_left > 0) and np.all(res.Fn_right > 0)
    # the leading (flanging) wheel carries more and the lateral force pushes back
    if y > 0:
        assert res.vertical_force_right > res.vertical_force_left
        assert res.lateral_force > 0


def test_load_sharing_in_two_point_contact(pair):
    """S1002/60E1 at y = 5 mm: tread and flange root both loaded (two-point contact)."""
    ws, tr = pair
    res = wr.elastic_contact(ws, tr, 0.005, 1.0e5)
    assert res.right.n == 2
    assert np.all(res.Fn_right > 0.1 * res.Fn_right.sum())
    # the points lie on separate zones with clearly different contact angles
    assert np.ptp(np.degrees(res.right.contact_angle)) > 5


def test_quasi_elastic_close_to_elastic_on_the_tread(pair):
    ws, tr = pair
    el = wr.elastic_contact(ws, tr, 0.002, 1.0e5)
    qe = wr.elastic_contact(ws, tr, 0.002, 1.0e5, method="quasi-elastic", epsilon=5e-5)
    assert qe.vertical_force_left + qe.vertical_force_right == pytest.approx(1.0e5, rel=1e-9)
    assert qe.vertical_force_right == pytest.approx(el.vertical_force_right, rel=0.05)
    assert qe.roll == pytest.approx(el.roll, rel=0.1)
    assert qe.right.n == 1 and qe.left.n == 1
    # smaller epsilon: the regularised constraint tends to the rigid one
    rigid = wr.contact_points(ws, tr, 0.002)
    qe_small = wr.elastic_contact(ws, tr, 0.002, 1.0e5, method="quasi-elastic", epsilon=2e-6)
    assert abs(qe_small.roll - rigid.roll) < abs(qe.roll - rigid.roll)
    assert abs(qe_small.z - rigid.z) < abs(qe.z - rigid.z)


def test_elastic_bad_input(pair):
    ws, tr = pair
    with pytest.raises(InputError, match="load"):
        wr.elastic_contact(ws, tr, 0.0, -1.0)
    with pytest.raises(InputError, match="method"):
        wr.elastic_contact(ws, tr, 0.0, 1e5, method="rigid")
    with pytest.raises(InputError, match="epsilon"):
        wr.elastic_contact(ws, tr, 0.0, 1e5, method="quasi-elastic", epsilon=0.0)


def test_separation_matches_hertz_curvatures(pair):
    """Near the contact point f(η) ≈ B η² and h(x, 0) ≈ A x² (seed 003, §3)."""
    ws, tr = pair
    sep = wr.geometry.separation(ws, tr, 0.002, side="right")
    cp = wr.contact_points(ws, tr, 0.002)
    p = cp.right.primary
    i = int(np.argmin(np.abs(sep.eta)))
    assert abs(sep.eta[i]) < 1e-12 and abs(sep.f[i]) < 1e-9
    assert np.all(sep.f > -1e-9)  # rigid contact: no interpenetration
    eta = sep.eta[i - 3:i + 4]
    B_fit = np.polyfit(eta, sep.f[i - 3:i + 4], 2)[0]
    assert B_fit == pytest.approx(cp.right.B[p], rel=0.02)
    x = np.linspace(-2e-3, 2e-3, 9)
    h = sep.distance(x)
    A_fit = np.polyfit(x, h[:, i], 2)[0]
    assert A_fit == pytest.approx(cp.right.A[p], rel=1e-3)
    h2 = wr.geometry.undeformed_distance(ws, tr, 0.002, x, sep.eta[::50], side="right")
    np.testing.assert_allclose(h2, h[:, ::50], atol=1e-10)


def test_separation_shows_the_secondary_zone(pair):
    """Centred S1002/60E1: the separation has a second valley (8 µm) at the flange-side zone."""
    ws, tr = pair
    sep = wr.geometry.separation(ws, tr, 0.0, side="left")
    valley = (sep.f[1:-1] < sep.f[:-2]) & (sep.f[1:-1] < sep.f[2:])
    mins = sep.f[1:-1][valley]
    assert mins.size >= 2
    assert np.sort(mins)[1] < 2e-5
    # a virtual penetration between the secondary valley and the hump before it: two patches
    k = np.flatnonzero(valley) + 1
    k2 = k[np.argsort(sep.f[k])[1]]
    k1 = k[np.argsort(sep.f[k])[0]]
    lo, hi = sorted((k1, k2))
    hump = np.max(sep.f[lo:hi + 1])
    g = sep.interpenetration(0.5 * (sep.f[k2] + hump))
    assert np.count_nonzero(np.diff((g > 0).astype(int)) == 1) == 2


def test_interpenetration_kernel():
    f = np.array([0.0, 1e-5, 5e-5, 1e-4])
    np.testing.assert_allclose(interpenetration(f, 5e-5), [5e-5, 4e-5, 0.0, 0.0])
    h = undeformed_distance_kernel(np.zeros(3), np.full(3, 0.5), 1.0, np.array([0.0, 0.3]))
    np.testing.assert_allclose(h[1], 0.5 - 0.4)


def test_no_roll_equilibrium_in_steep_flange_contact(pair):
    """At y = 7 mm only the 70° flange touches on the right; its force passes above the axle
    centre, so with the lateral force at the axle no roll equilibrium exists (seed 002, §2.1.3:
    the quasi-elastic bilateral constraint then needs a tensile force on the other wheel)."""
    from wheelrail.errors import ConvergenceError

    ws, tr = pair
    with pytest.raises(ConvergenceError, match="no equilibrium exists"):
        wr.elastic_contact(ws, tr, 0.007, 1.0e5)
    qe = wr.elastic_contact(ws, tr, 0.007, 1.0e5, method="quasi-elastic")
    assert qe.Fn_left[0] < 0
