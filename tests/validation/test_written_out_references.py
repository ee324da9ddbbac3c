"""The references written out in the validation checks agree with their own known limits.

The closed forms that the checks type in (Carter's strip integral, the strip theory of
FaStrip, Polach's law, the circular rail's placement) and the table law's sampler are the
independent side of their rows; here each is held to a limit derived by hand:

- Carter's strip integral (Johnson 1985 §8.4): initial slope π² G a b / (4(1 − ν)) (Carter's
  per-length stiffness π a G / (2(1 − ν)) integrated over the ellipse), μ Fn beyond the
  largest strip's saturation creepage;
- the strip theory with Kalker's flexibilities: initial slope G a b C11 (Kalker's linear
  theory), μ Fn in full slip;
- Polach (1999): F = Q μ (1/π + 1/2) at ε = 1, and the linear spin force G c³ C23 φ;
- the circular rail head: the gauge point √(R² − (R − h)²) inside the centre (Pythagoras);
- the table-law sampler: a Latin hypercube (one point in each of the n strata of every
  coordinate), inside the table's domain, and not the table's own sampler.
"""

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.validation import checks_other as co
from wheelrail.validation import checks_tangential as ct

G, NU, MU = 8.4e10, 0.25, 0.3


def _contact(ab=0.5, Fn=2e4):
    return wr.hertz_from_semiaxes(5e-3 * np.sqrt(ab), 5e-3 / np.sqrt(ab), Fn,
                                  wr.Material(2.1e11, NU))


def test_carter_strip_integral_limits():
    c = _contact()
    a, b, Fn = float(c.a), float(c.b), float(c.Fn)
    xi = 1e-9
    slope = -ct._carter_strip_reference(a, b, Fn, MU, G, NU, xi) / xi
    assert slope == pytest.approx(np.pi**2 * G * a * b / (4 * (1 - NU)), rel=1e-6)
    p0 = 1.5 * Fn / (np.pi * a * b)
    xs = 2 * (1 - NU) * MU * p0 / G                 # the centre strip saturates last
    assert ct._carter_strip_reference(a, b, Fn, MU, G, NU, -1.01 * xs) == pytest.approx(
        MU * Fn, rel=1e-12)


def test_strip_theory_limits():
    c = _contact()
    c11, c22, _ = ct.KALKER_TABLE[(0.5, 0.25)]
    fx, fy = ct._strip_theory_reference(c, c11, c22, G, MU, 1e-9, 0.0)
    assert -fx / 1e-9 == pytest.approx(G * float(c.a) * float(c.b) * c11, rel=1e-6)
    assert fy == 0.0
    fx, fy = ct._strip_theory_reference(c, c11, c22, G, MU, 0.02, 0.02)
    assert np.hypot(fx, fy) == pytest.approx(MU * float(c.Fn), rel=1e-12)


def test_polach_written_out_limits():
    c = _contact(1.0, Fn=1e5)
    a, b, Q = float(c.a), float(c.b), float(c.Fn)
    c11, c22, c23 = ct.KALKER_TABLE[(1.0, 0.25)]
    xi1 = Q * MU / (0.25 * np.pi * G * a * b * c11)          # eps = 1
    fx, fy = ct._polach_written_out(a, b, G, Q, c11, c22, c23, xi1, 0.0, 0.0, MU)
    assert fx == pytest.approx(-Q * MU * (1 / np.pi + 0.5), rel=1e-14) and fy == 0.0
    phi, eta = 1e-6, 1e-12                                    # linear spin (xi = 0)
    _, fy = ct._polach_written_out(a, b, G, Q, c11, c22, c23, 0.0, eta, phi, MU)
    cc = np.sqrt(a * b)
    assert fy == pytest.approx(-G * cc**2 * (c22 * eta + cc * c23 * phi), rel=1e-5)


def test_circular_rail_centre():
    U, Z = co.circle_rail_centre(gauge=1.435, gauge_height=0.014, R=0.3)
    assert Z == -0.3
    assert (U - 0.7175) ** 2 + (0.3 - 0.014) ** 2 == pytest.approx(0.3**2, rel=1e-14)


def test_table_sampler_is_a_latin_hypercube_in_the_domain():
    from wheelrail.tangential.linear import kalker_coefficients

    n = 12
    pts = ct.table_law_points(n)
    ab = np.array([p[3] for p in pts])
    mu = np.array([p[2] for p in pts])
    assert np.all((ab >= 0.05) & (ab <= 20.0)) and np.all((mu >= 0.1) & (mu <= 0.5))
    strata = np.floor((np.log(ab) - np.log(0.05)) / np.log(400.0) * n).astype(int)
    assert sorted(strata) == list(range(n))                     # one point per stratum
    xh = []
    for c, (xi, _, _), m, r in pts:
        C11 = float(kalker_coefficients(r, float(c.nu))[0])
        xh.append(xi * float(c.G) * float(c.a) * float(c.b) * C11 / (3 * m * float(c.Fn)))
    xh = np.array(xh)
    assert np.all(np.abs(xh) <= 1.5)
    assert sorted(np.floor((xh + 1.5) / 3.0 * n).astype(int)) == list(range(n))
    assert ct.table_law_points(n)[0][1] == pts[0][1]           # fixed seed: reproducible
