"""Subsurface stresses of the half-space.

References: Johnson, *Contact Mechanics* (1985): Boussinesq/Cerruti displacement
fields (§3.2, in the form of Landau & Lifshitz, Theory of Elasticity §8), Hertz axis
stresses (§3.4) and the maximum shear 0.31 p0 at z = 0.48 a (ν = 0.3, §4.2).
"""

import numpy as np
import pytest
from scipy import integrate

import wheelrail as wr
from wheelrail.errors import InputError
from wheelrail.halfspace import Grid, subsurface_stresses
from wheelrail.normal.bem import hertz_grid, solve_normal
from wheelrail.halfspace.subsurface import boussinesq_stress, cerruti_stress

NU = 0.3
MAT = wr.Material(2.1e11, NU)


def _u_boussinesq(x, y, z, nu, G=1.0):
    r = np.sqrt(x * x + y * y + z * z)
    c = 1 / (4 * np.pi * G)
    return np.array([c * (x * z / r**3 - (1 - 2 * nu) * x / (r * (r + z))),
                     c * (y * z / r**3 - (1 - 2 * nu) * y / (r * (r + z))),
                     c * (z * z / r**3 + 2 * (1 - nu) / r)])


def _u_cerruti(x, y, z, nu, G=1.0):
    r = np.sqrt(x * x + y * y + z * z)
    c = 1 / (4 * np.pi * G)
    return np.array([
        c * (1 / r + x * x / r**3 + (1 - 2 * nu) * (1 / (r + z) - x * x / (r * (r + z) ** 2))),
        c * (x * y / r**3 - (1 - 2 * nu) * x * y / (r * (r + z) ** 2)),
        c * (x * z / r**3 + (1 - 2 * nu) * x / (r * (r + z)))])


def _stress_from_displacement(u, p, nu, G=1.0, h=1e-6):
    grad = np.zeros((3, 3))
    for k in range(3):
        e = np.zeros(3)
        e[k] = h
        grad[:, k] = (u(*(p + e), nu) - u(*(p - e), nu)) / (2 * h)
    eps = 0.5 * (grad + grad.T)
    lam = 2 * G * nu / (1 - 2 * nu)
    s = 2 * G * eps + lam * np.trace(eps) * np.eye(3)
    return np.array([s[0, 0], s[1, 1], s[2, 2], s[1, 2], s[0, 2], s[0, 1]])


@pytest.mark.parametrize("pt", [(0.3, 0.7, 0.5), (-1.1, 0.4, 0.2), (0.2, -0.3, 1.5)])
def test_point_load_stresses_match_hooke_of_displacement_fields(pt):
    p = np.array(pt)
    for u, s in ((_u_boussinesq, boussinesq_stress), (_u_cerruti, cerruti_stress)):
        ref = _stress_from_displacement(u, p, NU)
        got = s(*p, NU)
        assert np.max(np.abs(got - ref)) < 1e-8 * np.max(np.abs(ref))


def test_point_load_stresses_traction_free_surface():
    for s in (boussinesq_stress, cerruti_stress):
        out = s(0.5, -0.3, 1e-12, NU)
        assert np.all(np.abs(out[2:5]) < 1e-9 * np.abs(out).max())


@pytest.fixture(scope="module")
def hertz_case():
    hc = wr.hertz(10e3, A=1.0, B=1.0, material=MAT)
    grid, h0 = hertz_grid(hc, elements=40)
    sol = solve_normal(grid, h0, MAT, Fn=10e3)
    return hc, grid, sol


def test_hertz_axis_stresses(hertz_case):
    """σz = −p0/(1+z²/a²), σr = p0[−(1+ν)(1 − (z/a) atan(a/z)) + ½/(1+z²/a²)] (Johnson 3.72)."""
    hc, grid, sol = hertz_case
    a, p0 = hc.a, hc.p0
    zr = np.linspace(0.1, 2.0, 20)
    st = subsurface_stresses(grid, None, None, sol.pressure, MAT, zr * a,
                             x=np.array([0.0]), y=np.array([0.0]))
    sz = -p0 / (1 + zr**2)
    sr = p0 * (-(1 + NU) * (1 - zr * np.arctan(1 / zr)) + 0.5 / (1 + zr**2))
    assert np.max(np.abs(st.szz[:, 0] - sz)) < 1e-3 * p0
    assert np.max(np.abs(st.sxx[:, 0] - sr)) < 1e-3 * p0
    assert np.max(np.abs(st.syy[:, 0] - sr)) < 1e-3 * p0
    assert np.max(np.abs(st.sxz[:, 0])) < 1e-6 * p0


def test_hertz_maximum_shear(hertz_case):
    """τ_max ≈ 0.31 p0 at z ≈ 0.48 a below the centre of a circular contact (ν = 0.3)."""
    hc, grid, sol = hertz_case
    a, p0 = hc.a, hc.p0
    zz = np.linspace(0.40, 0.56, 33) * a
    st = subsurface_stresses(grid, None, None, sol.pressure, MAT, zz,
                             x=np.array([0.0]), y=np.array([0.0]))
    tau, z_at, _, _ = st.max_location("tau_max")
    assert tau == pytest.approx(0.31 * p0, rel=0.01)
    assert z_at == pytest.approx(0.48 * a, abs=0.01 * a)
    # von Mises: first yield at p0 = 1.60 Y (Johnson §6.2, ν = 0.3), i.e. max σ_vM = p0/1.60
    vm, z_vm, _, _ = st.max_location("von_mises")
    assert vm == pytest.approx(p0 / 1.60, rel=0.01)
    assert z_vm == pytest.approx(0.48 * a, abs=0.02 * a)


def test_grid_evaluation_equals_point_evaluation(hertz_case):
    hc, grid, sol = hertz_case
    rng = np.random.default_rng(3)
    px = rng.normal(size=grid.shape) * 1e8 * sol.contact
    py = rng.normal(size=grid.shape) * 1e8 * sol.contact
    z = [0.3 * hc.a, 0.9 * hc.a]
    full = subsurface_stresses(grid, px, py, sol.pressure, MAT, z)
    ix, iy = [3, 20, 31], [17, 20, 5]
    pts = subsurface_stresses(grid, px, py, sol.pressure, MAT, z,
                              x=grid.x[ix], y=grid.y[iy])
    for c in ("sxx", "syy", "szz", "syz", "sxz", "sxy"):
        a, b = getattr(full, c)[:, ix, iy], getattr(pts, c)
        assert np.allclose(a, b, rtol=0, atol=1e-10 * hc.p0)


def test_force_balance_on_a_plane():
    """∫σzz dA = −Fn and ∫σxz dA = +Fx (rail carries −px) over a wide plane at depth z."""
    grid = Grid.from_bounds(-20e-3, 20e-3, -20e-3, 20e-3, 81, 81)
    load = np.zeros(grid.shape)
    load[38:43, 38:43] = 1e8
    z = 0.5e-3
    st = subsurface_stresses(grid, load * 0.3, None, load, MAT, [z], body="rail")
    dA = grid.element_area
    Fn = load.sum() * dA
    assert st.szz.sum() * dA == pytest.approx(-Fn, rel=2e-3)
    # σxz of a tangential force decays only like 1/ρ² on the plane: the part of the
    # force carried inside the finite square window [-L, L]² (point force at the centre)
    L = 20e-3
    inside, _ = integrate.dblquad(
        lambda yy, xx: 3 * xx**2 * z / (2 * np.pi * (xx**2 + yy**2 + z**2) ** 2.5),
        -L, L, -L, L, epsabs=1e-12)
    assert 0.9 < inside < 0.99
    assert st.sxz.sum() * dA == pytest.approx(0.3 * Fn * inside, rel=2e-3)
    wheel = subsurface_stresses(grid, load * 0.3, None, load, MAT, [z], body="wheel")
    assert wheel.sxz.sum() * dA == pytest.approx(-0.3 * Fn * inside, rel=2e-3)
    # the shear contributions have opposite signs in the two bodies, the pressure ones agree
    only_p = subsurface_stresses(grid, None, None, load, MAT, [z], body="rail")
    assert np.allclose(wheel.szz + st.szz, 2 * only_p.szz, rtol=0, atol=1e-9 * 1e8)
    assert not np.allclose(wheel.szz, st.szz, rtol=0, atol=1e-3 * 1e8)


def test_invariants_and_errors(hertz_case):
    hc, grid, sol = hertz_case
    st = subsurface_stresses(grid, None, None, sol.pressure, MAT, [0.5 * hc.a])
    pr = st.principal
    assert np.all(pr[0] >= pr[1]) and np.all(pr[1] >= pr[2])
    trace = st.sxx + st.syy + st.szz
    assert np.allclose(pr.sum(axis=0), trace, atol=1e-6 * hc.p0)
    assert np.all(st.von_mises <= 2 * st.tau_max * (1 + 1e-12))
    assert np.all(st.von_mises >= np.sqrt(3) * st.tau_max * (1 - 1e-12))
    with pytest.raises(InputError, match="z"):
        subsurface_stresses(grid, None, None, sol.pressure, MAT, [0.0])
    with pytest.raises(InputError, match="body"):
        subsurface_stresses(grid, None, None, sol.pressure, MAT, [1e-3], body="axle")
    with pytest.raises(InputError, match="x and y"):
        subsurface_stresses(grid, None, None, sol.pressure, MAT, [1e-3], x=[0.0])
