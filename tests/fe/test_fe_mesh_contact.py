"""Mesh generator and contact kernel checks (closed forms of the geometry and of the penalty law)."""

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.errors import InputError
from wheelrail.fe import RollingCase
from wheelrail.fe.model import build_model
from wheelrail.fe import _kernels as K
from wheelrail.fe.mesh import graded_axis

FLAT_WHEEL = wr.Profile(np.linspace(-0.04, 0.04, 9), np.zeros(9), kind="wheel")


@pytest.fixture(scope="module")
def model():
    case = RollingCase(wheel=FLAT_WHEEL, rail=wr.profiles.load("60E1"), radius=0.46,
                       Fn=7500.0, mesh_size=2e-3, depth=4, half_width=3, half_length=3)
    return build_model(case, rolling=False)


def test_graded_axis_uniform_band_and_bounded_growth():
    x = graded_axis(-0.05, 0.08, -0.01, 0.02, 1e-3, ratio=1.3)
    d = np.diff(x)
    assert x[0] == pytest.approx(-0.05) and x[-1] == pytest.approx(0.08)
    band = (x[:-1] >= -0.01 - 1e-12) & (x[1:] <= 0.02 + 1e-12)
    np.testing.assert_allclose(d[band], 1e-3, rtol=1e-9)
    assert np.all(d > 0)
    assert np.max(d[1:] / d[:-1]) < 1.3 * 1.6 and np.max(d[:-1] / d[1:]) < 1.3 * 1.6


def test_rail_surface_on_profile_and_wheel_surface_on_radius(model):
    rail = wr.profiles.load("60E1")
    top = model.rail.nodes[model.rail.surface_nodes.ravel()]
    np.testing.assert_allclose(top[:, 2], rail(top[:, 1]), atol=1e-12)
    ws = model.wheel.nodes[model.wheel.surface_nodes.ravel()]
    np.testing.assert_allclose(np.hypot(ws[:, 0], ws[:, 2]), 0.46, rtol=1e-12)
    # the bodies touch at the contact point: wheel bottom at the rail crown height
    assert model.z_axle - 0.46 == pytest.approx(float(rail(model.geometry["y_c"])), abs=1e-9)


def test_surface_normals_point_out_of_the_bodies(model):
    for body, sign in ((model.wheel, -1.0), (model.rail, 1.0)):
        q = body.nodes[body.surface]
        n = np.cross(q[..., 1, :] - q[..., 0, :], q[..., 3, :] - q[..., 0, :])
        assert np.all(sign * n[..., 2] > 0)


def test_tributary_areas_sum_to_surface_area(model):
    ax = model.rail.axes
    area = model.rail.surface_areas().sum()
    flat = (ax[0][-1] - ax[0][0]) * (ax[1][-1] - ax[1][0])
    assert area == pytest.approx(flat, rel=2e-3)   # crowned head: slightly more than flat


def test_mesh_larger_than_patch_is_rejected():
    with pytest.raises(InputError, match="mesh_size 0.005"):
        build_model(RollingCase(wheel=FLAT_WHEEL, rail=wr.profiles.load("60E1"), radius=0.46,
                                Fn=7500.0, mesh_size=5e-3), rolling=False)


@pytest.mark.parametrize("kw, match", [({"creepage": (0.0, 0.0, 0.1)}, "phi = 0.1"),
                                       ({"creepage": (0.2, 0.0, 0.0)}, "saturation"),
                                       ({"creepage": (0.0, -0.06, 0.0)}, "eta = -0.06"),
                                       ({"integrator": "implicit-qs", "rayleigh": (10.0, 0.0)},
                                        "alpha = 10.0"),
                                       ({"linear_solver": "lu"}, "linear_solver"),
                                       ({"integrator": "rk4"}, "integrator"),
                                       ({"Fn": -1.0}, "Fn")])
def test_bad_case_input_named(kw, match):
    args = dict(wheel=FLAT_WHEEL, rail=wr.profiles.load("60E1"), radius=0.46, Fn=7500.0)
    args.update(kw)
    with pytest.raises(InputError, match=match):
        RollingCase(**args)


def _flat_master():
    x = np.linspace(-1e-3, 1e-3, 3)
    y = np.linspace(-1e-3, 1e-3, 3)
    X, Y = np.meshgrid(x, y, indexing="ij")
    xm = np.stack([X, Y, np.zeros_like(X)], -1)
    nm = np.zeros_like(xm)
    nm[..., 2] = 1.0
    return x, y, xm, nm


def _contact(xs, dxs, ft_old, mu, kn=1e15, area=1e-6, g0=1e-9):
    x, y, xm, nm = _flat_master()
    ns = xs.shape[0]
    out = dict(fs=np.zeros((ns, 3)), fm=np.zeros((3, 3, 3)), gap=np.zeros(ns), pn=np.zeros(ns),
               ft=np.zeros((ns, 3)), status=np.zeros(ns, np.int64), cell=np.zeros((ns, 2), np.int64),
               rt=np.zeros((ns, 2)), normal=np.zeros((ns, 3)), slip=np.zeros(ns),
               energy=np.zeros(ns))
    K.node_to_surface((xs, dxs, np.full(ns, area), np.full(ns, kn), np.full(ns, kn), np.zeros(ns)),
                      (xm, nm, np.zeros_like(xm), x, y, 0.0), (mu, 1e-3, g0, 1.0), ft_old,
                      (out["energy"], out["fs"], out["gap"], out["pn"], out["ft"], out["status"],
                       out["cell"], out["rt"], out["normal"], out["slip"]), out["fm"])
    return out


def test_penalty_normal_force_closed_form_and_action_reaction():
    d = 1e-7
    out = _contact(np.array([[2e-4, -3e-4, -d]]), np.zeros((1, 3)), np.zeros((1, 3)), 0.0)
    assert out["gap"][0] == pytest.approx(-d)
    assert out["pn"][0] == pytest.approx(1e15 * 1e-6 * (d - 0.5e-9), rel=1e-12)
    np.testing.assert_allclose(out["fs"].sum(0) + out["fm"].sum((0, 1)), 0.0, atol=1e-9)
    # bilinear distribution: the moment of the master forces about the slave point vanishes
    x, y, xm, _ = _flat_master()
    mom = np.sum(out["fm"][..., 2] * (xm[..., 0] - 2e-4))
    assert abs(mom) < 1e-12 * out["pn"][0]


def test_friction_stick_then_return_to_cone():
    d = 1e-7
    xs = np.array([[0.0, 0.0, -d]])
    fn = 1e15 * 1e-6 * (d - 0.5e-9)
    small = np.array([[1e-9, 0.0, 0.0]])
    out = _contact(xs, small, np.zeros((1, 3)), 0.3)
    assert out["status"][0] == 1
    assert out["ft"][0, 0] == pytest.approx(-1e15 * 1e-6 * 1e-9)     # penalty stick, opposing slip
    big = np.array([[0.0, 1e-6, 0.0]])
    out = _contact(xs, big, np.zeros((1, 3)), 0.3)
    assert out["status"][0] == 2
    assert np.linalg.norm(out["ft"][0]) == pytest.approx(0.3 * fn, rel=1e-12)
    assert out["ft"][0, 1] < 0
    assert out["slip"][0] == pytest.approx((1e9 * 1e-6 - 0.3 * fn) / 1e9, rel=1e-9)


def test_open_node_carries_no_force():
    out = _contact(np.array([[0.0, 0.0, 1e-6]]), np.zeros((1, 3)), np.ones((1, 3)), 0.3)
    assert out["status"][0] == 0 and np.all(out["fs"] == 0) and np.all(out["fm"] == 0)


def test_real_profiles_s1002_on_inclined_60e1_mesh():
    """S1002 on 60E1 at 1:40: contact point where the gap between the profiles is smallest."""
    rail = wr.profiles.load("60E1").rotated(np.arctan(1 / 40))
    wheel = wr.profiles.load("S1002")
    case = RollingCase(wheel=wheel, rail=wr.profiles.load("60E1"), radius=0.46, Fn=7500.0,
                       inclination=np.arctan(1 / 40), mesh_size=1.5e-3, depth=4, half_width=4,
                       half_length=4)
    m = build_model(case, rolling=False)
    y = np.linspace(-0.03, 0.03, 60001)
    gap = wheel(y) - rail(y)
    assert m.geometry["y_c"] == pytest.approx(y[np.nanargmin(gap)], abs=2e-5)
    top = m.rail.nodes[m.rail.surface_nodes.ravel()]
    np.testing.assert_allclose(top[:, 2], rail(top[:, 1]), atol=1e-12)
    ws = m.wheel.nodes[m.wheel.surface_nodes.ravel()]
    np.testing.assert_allclose(np.hypot(ws[:, 0], ws[:, 2]), 0.46 - wheel(ws[:, 1]), atol=1e-12)
    assert m.geometry["hertz"] is not None and m.geometry["hertz"].a > m.geometry["hertz"].b


def test_saturation_creepage_closed_form_and_warning():
    """Full sliding beyond 3 μ Fn / (G c² C11) (Vermeulen & Johnson's cubic law on Kalker's
    linear theory): the run warns naming the creepage; the bad explicit step then stops it."""
    from wheelrail.fe import solve
    from wheelrail.fe.rolling import saturation_creepage
    from wheelrail.tangential.linear import kalker_coefficients

    case = RollingCase(wheel=FLAT_WHEEL, rail=wr.profiles.load("60E1"), radius=0.46,
                       Fn=7500.0, mu=0.2, creepage=(0.01, 0.0, 0.0), mesh_size=2e-3,
                       element="reduced", depth=3, half_width=3, half_length=3, time_step=1.0)
    hz = build_model(case, rolling=False).geometry["hertz"]
    G = 2.1e11 / (2 * 1.28)
    c11 = float(kalker_coefficients(hz.a / hz.b, 0.28)[0])
    sat = saturation_creepage(case)
    assert sat == pytest.approx(3 * 0.2 * 7500.0 / (G * hz.a * hz.b * c11), rel=1e-12)
    assert 1e-3 < sat < 3e-3                        # the exact curve saturates near 2e-3 here
    assert saturation_creepage(case.replace(creepage=(1e-3, 0.0, 0.0))) == pytest.approx(sat)
    with pytest.warns(UserWarning, match=r"\(0.01, 0.0\) is past saturation"):
        with pytest.raises(InputError, match="time_step 1.0"):
            solve(case, progress=False)


def test_implicit_step_too_long_warns_naming_it(tmp_path):
    from wheelrail.fe import solve

    case = RollingCase(wheel=FLAT_WHEEL, rail=wr.profiles.load("60E1"), radius=0.46,
                       Fn=7500.0, mu=0.2, creepage=(1e-3, 0.0, 0.0), mesh_size=2e-3,
                       element="reduced", depth=3, half_width=3, half_length=3,
                       integrator="implicit-qs", time_step=4e-4)
    with pytest.warns(UserWarning, match="time_step 0.0004 s"):
        with pytest.raises(InputError, match="does not exist"):
            solve(case, progress=False, restart=tmp_path / "none.npz")


def test_solve_in_indent_mode_is_the_static_indentation():
    """``wr.fe.solve(case, mode="indent")`` is ``wr.fe.indent(case)`` (one entry for every
    FE case); a bad mode is refused by name."""
    case = RollingCase(wheel=FLAT_WHEEL, rail=wr.profiles.load("60E1"), radius=0.46,
                       Fn=7500.0, mesh_size=2e-3, depth=3, half_width=3, half_length=3)
    a = wr.fe.solve(case, mode="indent")
    b = wr.fe.indent(case)
    assert type(a).__name__ == "IndentResult" and a.p_max == b.p_max and a.a == b.a
    with pytest.raises(InputError, match="mode"):
        wr.fe.solve(case, mode="rolling")
