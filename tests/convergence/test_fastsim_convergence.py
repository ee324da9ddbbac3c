"""Observed order of FASTSIM's grid convergence (pure longitudinal creepage, partial slip).

Reference: the continuum simplified theory for pure ξ, integrated strip by
strip (Kalker 1982; every strip of the ellipse has adhesion p = k(1 − s) from
the leading edge s = 1 until the traction meets the bound, slip behind it):

* parabolic bound q(1 − s²): s* = k/q − 1,
  F_strip = a_j [k(1 − s*)²/2 + q((s* + 1) − (s*³ + 1)/3)];
* elliptic bound q√(1 − s²): s* = (k² − q²)/(k² + q²),
  F_strip = a_j [k(1 − s*)²/2 + q((s*√(1 − s*²) + asin s*)/2 + π/4)];

with k = ξ a_j/L1, a_j = a√(1 − t²), q = μ p0 (1 − t²) or μ p0 √(1 − t²),
and Fx = −b ∫ F_strip dt over t = y/b ∈ (−1, 1) (scipy.integrate.quad).
The fine grid (640×640) is checked against the same reference.

Expected orders of the element-centred scheme: 2 for the parabolic bound
(smooth integrand, one kink per strip), ≈ 1.5 for the elliptic bound
(√ behaviour of the bound at the trailing edge). Kalker's original node-based
FASTSIM is first order.
"""

import numpy as np
import pytest
from scipy import integrate

import wheelrail as wr
from wheelrail.tangential.fastsim import flexibilities
from wheelrail.tangential.linear import kalker_coefficients

MU = 0.3


@pytest.fixture(scope="module")
def contact():
    return wr.hertz_from_semiaxes(a=6e-3, b=4e-3, Fn=80e3,
                                  material=wr.Material.from_shear(82e9, 0.28))


def _reference_fx(c, xi, bound):
    a, b, Fn = c.a, c.b, c.Fn
    C11, C22, C23, _ = kalker_coefficients(a / b, c.nu)
    L1 = float(flexibilities(a, b, c.G, C11, C22, C23)[0])
    p0 = (2.0 if bound == "parabolic" else 1.5) * Fn / (np.pi * a * b)

    def strip(t):
        h = np.sqrt(1.0 - t * t)
        aj = a * h
        q = MU * p0 * (h * h if bound == "parabolic" else h)
        k = abs(xi) * aj / L1
        if bound == "parabolic":
            s = min(max(k / q - 1.0, -1.0), 1.0)
            return aj * (k * (1 - s) ** 2 / 2 + q * ((s + 1) - (s**3 + 1) / 3))
        s = (k * k - q * q) / (k * k + q * q)
        return aj * (k * (1 - s) ** 2 / 2 + q * ((s * np.sqrt(1 - s * s) + np.arcsin(s)) / 2
                                                 + np.pi / 4))

    val, _ = integrate.quad(strip, -1.0, 1.0, epsabs=0.0, epsrel=1e-13, limit=200)
    return -np.sign(xi) * b * val


@pytest.mark.parametrize("bound, xi, band", [
    ("parabolic", 1e-3, (1.7, 2.5)),
    ("parabolic", 3e-3, (1.7, 2.5)),
    ("elliptic", 1e-3, (1.2, 2.0)),
    ("elliptic", 3e-3, (1.2, 2.2)),
])
def test_observed_order_pure_xi(contact, bound, xi, band):
    ref = _reference_fx(contact, xi, bound)
    # partial slip: well inside the non-linear range
    assert 0.25 < abs(ref) / (MU * contact.Fn) < 0.85
    ns = np.array([10, 20, 40, 80, 160])
    cr = np.array([[xi, 0.0, 0.0]])
    err = []
    for n in ns:
        r = wr.creep_forces(contact, cr, MU, method="fastsim", nx=int(n), ny=int(n), bound=bound)
        err.append(abs(r.Fx[0] - ref) / abs(ref))
    order = np.polyfit(np.log(1.0 / ns), np.log(err), 1)[0]
    assert band[0] < order < band[1], (order, err)
    # the default 20x20 grid is within 1.5 % of the converged simplified theory
    assert err[1] < 1.5e-2


@pytest.mark.parametrize("bound", ["parabolic", "elliptic"])
def test_fine_grid_matches_reference(contact, bound):
    ref = _reference_fx(contact, 2e-3, bound)
    r = wr.creep_forces(contact, (2e-3, 0.0, 0.0), MU, method="fastsim", nx=640, ny=640,
                        bound=bound, fields=False)
    assert r.Fx == pytest.approx(ref, rel=1e-4)
