"""Hertz theory against closed forms and Piotrowski & Chollet (2005), Table 2 (seed 003)."""

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.hertzian import hertz_coefficients

# Seed 003 (Piotrowski & Chollet, VSD 43, 2005), Table 2: theta [deg], n/m, m, r
TABLE2 = np.array([
    [5, 0.0212, 11.238, 0.2969],
    [10, 0.0470, 6.612, 0.4280],
    [30, 0.1806, 2.731, 0.7263],
    [60, 0.4826, 1.486, 0.9376],
    [90, 1.0, 1.0, 1.0],
    [120, 2.0720, 0.7171, 0.9376],
    [150, 5.5380, 0.4931, 0.7263],
    [170, 21.26, 0.311, 0.4280],
    [175, 47.20, 0.2381, 0.2969],
])


def test_table2_of_seed_003_within_0p1_percent():
    theta, n_over_m, m_ref, r_ref = TABLE2.T
    m, n, r = hertz_coefficients(theta)
    np.testing.assert_allclose(m, m_ref, rtol=1e-3)
    np.testing.assert_allclose(n / m, n_over_m, rtol=1e-3)
    np.testing.assert_allclose(r, r_ref, rtol=1e-3)


def test_sphere_closed_form(steel):
    # two equal spheres of radius R: relative radius R/2, A = B = 1/R
    R, N = 0.05, 1000.0
    c = wr.hertz(N, A=1 / R, B=1 / R, material=steel)
    Estar = steel.E / (2 * (1 - steel.nu**2))
    Rrel = R / 2
    a_ref = (3 * N * Rrel / (4 * Estar)) ** (1 / 3)
    assert c.a == pytest.approx(a_ref, rel=1e-10)
    assert c.b == pytest.approx(a_ref, rel=1e-10)
    assert c.penetration == pytest.approx(a_ref**2 / Rrel, rel=1e-10)
    assert c.p0 == pytest.approx(3 * N / (2 * np.pi * a_ref**2), rel=1e-10)


@pytest.mark.parametrize("A,B", [(1.0, 4.0), (4.0, 1.0), (0.3, 50.0), (2.0, 2.0000001)])
def test_load_is_integral_of_pressure_and_axes_orientation(steel, A, B):
    c = wr.hertz(10e3, A=A, B=B, material=steel)
    assert c.p0 * 2 / 3 * c.area == pytest.approx(10e3, rel=1e-10)
    # longer semi-axis along the direction of smaller curvature
    assert (c.a >= c.b) == (A <= B)


def test_swap_of_curvatures_swaps_axes(steel):
    c1 = wr.hertz(5e3, 1.0, 3.0, steel)
    c2 = wr.hertz(5e3, 3.0, 1.0, steel)
    assert c1.a == pytest.approx(c2.b, rel=1e-12)
    assert c1.penetration == pytest.approx(c2.penetration, rel=1e-12)


def test_inverse_problems_roundtrip(steel):
    c = wr.hertz(82e3, 0.8, 2.4, steel)
    back = wr.hertz_from_penetration(c.penetration, 0.8, 2.4, steel)
    assert back.Fn == pytest.approx(82e3, rel=1e-9)
    c2 = wr.hertz_from_semiaxes(c.a, c.b, 82e3, steel)
    assert c2.A == pytest.approx(0.8, rel=1e-8)
    assert c2.B == pytest.approx(2.4, rel=1e-8)


def test_radii_helper_concave_wheel(steel):
    A, B = wr.curvatures_from_radii(0.46, -0.5, 0.3)
    assert A == pytest.approx(0.5 / 0.46)
    assert B == pytest.approx(0.5 * (1 / 0.3 - 1 / 0.5))
    with pytest.raises(wr.InputError, match="concave"):
        wr.curvatures_from_radii(0.46, -0.2, 0.3)


def test_line_contact_limit(steel):
    # A very elongated ellipse is locally a line contact: its centre section carries
    # P' = pi p0 b / 2 per unit length and must have the 2D half-width (Johnson eq. 4.43)
    # for the relative radius R = 1/(2B).
    c = wr.hertz(1e4, A=1e-7, B=2.0, material=steel)
    assert c.a / c.b > 1e3
    Pl = np.pi * c.p0 * c.b / 2
    line = wr.hertz_line(Pl, 1 / (2 * c.B), steel)
    assert line["b"] == pytest.approx(c.b, rel=1e-3)
    assert line["p0"] == pytest.approx(c.p0, rel=1e-3)


@pytest.mark.parametrize("kwargs,match", [
    (dict(Fn=-1.0, A=1.0, B=1.0), "Fn"),
    (dict(Fn=0.0, A=1.0, B=1.0), "Fn"),
    (dict(Fn=np.nan, A=1.0, B=1.0), "Fn"),
    (dict(Fn=1.0, A=-1.0, B=1.0), "curvature A"),
    (dict(Fn=1.0, A=0.0, B=1.0), "line contact"),
])
def test_bad_input(steel, kwargs, match):
    with pytest.raises(wr.InputError, match=match):
        wr.hertz(material=steel, **kwargs)


def test_batch(steel):
    loads = np.array([1e3, 1e4, 1e5])
    c = wr.hertz(loads, 1.0, 2.0, steel)
    assert c.a.shape == (3,)
    np.testing.assert_allclose(c.a[1] / c.a[0], 10 ** (1 / 3), rtol=1e-12)
    assert c[2].Fn == 1e5


def test_shape_ratio_secant_equals_bisection():
    """The secant solve of the Hertz shape equation agrees with plain bisection (1e-12)."""
    from wheelrail.hertzian import _shape_ratio_bisection, shape_ratio

    r = np.concatenate([[1.0, 1 + 1e-12, 1 + 1e-6, 1.001], np.logspace(0, 12, 500)])
    # near k = 1 the shape equation is flat: both agree to its own round-off (~2e-13)
    np.testing.assert_allclose(shape_ratio(r), _shape_ratio_bisection(r), rtol=1e-12)
