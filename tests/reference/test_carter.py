"""Carter's 2D tractive rolling theory and its ellipse extensions.

References used as independent checks
-------------------------------------
* Johnson, *Contact Mechanics* (1985), §8.2: ξ_s = μ a / R for identical
  cylinders (eq. 8.9), Q = μP (1 − c²/a²) (eq. 8.8), Hertz line contact
  a² = 4PR/(πE*), p0 = 2P/(πa) (eq. 4.43-4.45).
* The half-plane surface displacement of a tangential line load (Johnson
  eq. 2.19b): ∂u_x/∂x = (2(1 − ν)/(πG)) PV∫ q(s)/(s − x) ds for the relative
  displacement of two quasi-identical bodies. Evaluated numerically here with
  QUADPACK's Cauchy weight, it must reproduce the stick condition ∂u/∂x = ξ
  in Carter's adhesion zone, and the slip must oppose the traction elsewhere.
* Kalker's asymptote C11 = π²/(4(1 − ν)) for a/b → 0 (Kalker 1990, §1.7):
  Carter's theory summed over the strips of an ellipse must have this slope.
"""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import integrate

import wheelrail as wr
from wheelrail.tangential.carter import (Carter, carter_ellipse_force, carter_force_per_length,
                                         carter_saturation_creepage, carter_stick_zone,
                                         carter_stiffness_per_length, carter_traction)

G = 8.0e10
NU = 0.28
MU = 0.3


@pytest.fixture
def line():
    """A wheel-like line contact: R = 0.46 m, 1e6 N/m, steel (Johnson eq. 4.43)."""
    mat = wr.Material.from_shear(G, NU)
    R = 0.46
    h = wr.hertz_line(1.0e6, R, mat)
    return {"a": h["b"], "p0": h["p0"], "R": R, "P": 1.0e6}


def test_saturation_creepage_is_mu_a_over_R(line):
    # Johnson (1985) eq. (8.9): full slip at |xi| = mu a / R for identical cylinders
    xs = carter_saturation_creepage(MU, line["p0"], G, NU)
    assert xs == pytest.approx(MU * line["a"] / line["R"], rel=1e-12)


def test_force_per_length_johnson_formula(line):
    # Q = mu P (1 - c^2/a^2), c/a = 1 - xi/xi_s  (Johnson eq. 8.8, 8.9)
    a, p0 = line["a"], line["p0"]
    xs = MU * a / line["R"]
    for frac in (0.0, 0.1, 0.5, 0.9, 1.0, 1.5):
        xi = frac * xs
        c_over_a = max(0.0, 1.0 - frac)
        expected = -MU * line["P"] * (1.0 - c_over_a**2)
        assert carter_force_per_length(a, xi, MU, p0, G, NU) == pytest.approx(expected, rel=1e-9,
                                                                              abs=1e-9)
        # odd in xi
        assert carter_force_per_length(a, -xi, MU, p0, G, NU) == pytest.approx(-expected, rel=1e-9,
                                                                               abs=1e-9)


def test_small_creep_slope_is_carter_coefficient(line):
    a, p0 = line["a"], line["p0"]
    h = 1e-9
    slope = (carter_force_per_length(a, h, MU, p0, G, NU)
             - carter_force_per_length(a, -h, MU, p0, G, NU)) / (2 * h)
    # pi a G / (2 (1 - nu)) per unit length
    assert -slope == pytest.approx(carter_stiffness_per_length(a, G, NU), rel=1e-6)
    assert -slope == pytest.approx(np.pi * a * G / (2 * (1 - NU)), rel=1e-6)


@pytest.mark.parametrize("frac", [0.05, 0.3, 0.7, 0.99, 1.3])
@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_traction_integrates_to_force_and_bounded(line, frac, sign):
    a, p0 = line["a"], line["p0"]
    xi = sign * frac * carter_saturation_creepage(MU, p0, G, NU)
    c, d = carter_stick_zone(a, xi, MU, p0, G, NU)
    pts = [float(d - c), float(d + c)] if c > 0 else None
    F, _ = integrate.quad(lambda x: carter_traction(x, a, xi, MU, p0, G, NU), -a, a,
                          points=pts, limit=200, epsabs=0, epsrel=1e-11)
    assert F == pytest.approx(carter_force_per_length(a, xi, MU, p0, G, NU), rel=1e-8)
    x = np.linspace(-1.2 * a, 1.2 * a, 4001)
    q = carter_traction(x, a, xi, MU, p0, G, NU)
    p = p0 * np.sqrt(np.clip(1 - (x / a) ** 2, 0, None))
    assert np.all(np.abs(q) <= MU * p * (1 + 1e-12) + 1e-6)
    assert np.all(q[np.abs(x) >= a] == 0)
    # traction opposes the creepage: q has the sign of -xi
    assert np.all(np.sign(q[q != 0]) == -np.sign(xi))
    # slip zone (trailing side x < d - c): |q| = mu p exactly
    slip = (x < d - c) & (np.abs(x) < a)
    assert np.allclose(np.abs(q[slip]), MU * p[slip], rtol=1e-12)


def _strain(x0, a, xi, p0):
    """du/dx at x0 from the traction by the half-plane Cauchy integral (Johnson eq. 2.19b)."""
    c, d = carter_stick_zone(a, xi, MU, p0, G, NU)
    pts = sorted({float(d - c), float(d + c)} - {-a, a})

    def q(s):
        return float(carter_traction(s, a, xi, MU, p0, G, NU))

    # PV int q(s)/(s - x0) ds, split so that the Cauchy-weight pieces stay smooth
    edges = [-a] + [p for p in pts if -a < p < a] + [a]
    total = 0.0
    for lo, hi in zip(edges[:-1], edges[1:]):
        if lo < x0 < hi:
            v, _ = integrate.quad(q, lo, hi, weight="cauchy", wvar=x0, limit=200)
        else:
            v, _ = integrate.quad(lambda s: q(s) / (s - x0), lo, hi, limit=200)
        total += v
    return 2 * (1 - NU) / (np.pi * G) * total


@pytest.mark.parametrize("frac", [0.2, 0.6])
def test_stick_condition_from_elasticity(line, frac):
    """Independent check of Carter's solution: no slip in the stick zone, slip opposes q."""
    a, p0 = line["a"], line["p0"]
    xi = frac * carter_saturation_creepage(MU, p0, G, NU)
    c, d = carter_stick_zone(a, xi, MU, p0, G, NU)
    for x0 in d + c * np.array([-0.83, -0.31, 0.27, 0.71]):
        assert _strain(x0, a, xi, p0) == pytest.approx(xi, rel=1e-6)
    # slip zone: slip velocity ~ xi - du/dx has the sign of xi, opposite to the traction
    for x0 in np.linspace(-a, d - c, 6)[1:-1]:
        s = xi - _strain(x0, a, xi, p0)
        assert s > 1e-3 * xi


def test_ellipse_slope_equals_kalker_asymptote():
    # Carter summed over the strips: slope pi^2 G a b /(4(1-nu)) = G c^2 C11(a/b -> 0)
    a, b, Fn = 2e-3, 8e-3, 5.0e4
    c11_limit = wr.kalker_coefficients(1e-7, NU)[0]
    assert float(c11_limit) == pytest.approx(np.pi**2 / (4 * (1 - NU)), rel=1e-5)
    h = 1e-10
    for form in ("global", "strip"):
        F, _ = carter_ellipse_force(a, b, G, NU, Fn, MU, h, form=form)
        assert -F / h == pytest.approx(G * a * b * float(c11_limit), rel=1e-4)
    F, _ = carter_ellipse_force(a, b, G, NU, Fn, MU, h, form="global", stiffness="kalker")
    assert -F / h == pytest.approx(G * a * b * float(wr.kalker_coefficients(a / b, NU)[0]),
                                   rel=1e-6)


def test_strip_form_matches_quadrature_over_strips():
    """The closed-form strip integral equals summing Carter's 2D force over strips numerically."""
    a, b, Fn = 3e-3, 4e-3, 6.0e4
    p0 = 1.5 * Fn / (np.pi * a * b)
    xs = carter_saturation_creepage(MU, p0, G, NU)
    for frac in (0.1, 0.5, 0.95):
        xi = frac * xs

        def strip(y):
            w = np.sqrt(1 - (y / b) ** 2)
            return float(carter_force_per_length(a * w, xi, MU, p0 * w, G, NU))

        F, _ = integrate.quad(strip, -b * (1 - 1e-14), b * (1 - 1e-14), limit=200, epsrel=1e-11)
        Fs, _ = carter_ellipse_force(a, b, G, NU, Fn, MU, xi, form="strip")
        assert float(Fs) == pytest.approx(F, rel=1e-7)


@settings(max_examples=60, deadline=None)
@given(form=st.sampled_from(["global", "strip"]), stiff=st.sampled_from(["carter", "kalker"]),
       ratio=st.floats(0.05, 20.0), xi1=st.floats(0.0, 0.02), dxi=st.floats(0.0, 0.01))
def test_saturation_and_monotone(form, stiff, ratio, xi1, dxi):
    a = 4e-3 * np.sqrt(ratio)
    b = 4e-3 / np.sqrt(ratio)
    Fn = 5e4
    F1, xs = carter_ellipse_force(a, b, G, NU, Fn, MU, xi1, form=form, stiffness=stiff)
    F2, _ = carter_ellipse_force(a, b, G, NU, Fn, MU, xi1 + dxi, form=form, stiffness=stiff)
    assert abs(F1) <= MU * Fn * (1 + 1e-12)
    assert abs(F2) >= abs(F1) - 1e-9 * MU * Fn
    if xi1 >= xs:
        assert abs(F1) == pytest.approx(MU * Fn, rel=1e-12)
    elif xi1 > 0:
        assert abs(F1) < MU * Fn


def test_creep_forces_api_and_lateral_handling(steel):
    c = wr.hertz(np.array([5e4, 1e5]), A=0.5 / 0.46, B=0.5 / 0.30, material=steel)
    r = wr.creep_forces(c, creepage=[[1e-4, 0, 0], [-2e-2, 0, 0]], mu=MU, method="carter")
    assert r.Fx.shape == (2,) and r.Fx[0] < 0 and r.Fx[1] > 0
    assert r.Fx[1] == pytest.approx(MU * 1e5)
    assert list(r.info["full_slip"]) == [False, True]
    assert np.all(r.Fy == 0) and np.all(r.Mz == 0)
    with pytest.raises(wr.InputError, match="eta"):
        wr.creep_forces(c, creepage=(1e-3, 1e-4, 0.0), mu=MU, method="carter")
    with pytest.raises(wr.InputError, match="phi"):
        wr.creep_forces(c, creepage=(1e-3, 0.0, 0.2), mu=MU, method="carter")
    r2 = wr.creep_forces(c, creepage=(1e-3, 1e-4, 0.2), mu=MU, method="carter", lateral="ignore")
    r3 = wr.creep_forces(c, creepage=(1e-3, 0.0, 0.0), mu=MU, method="carter")
    assert np.allclose(r2.Fx, r3.Fx) and np.all(r2.Fy == 0)
    with pytest.raises(wr.InputError, match="form"):
        wr.creep_forces(c, creepage=(1e-3, 0, 0), mu=MU, method="carter", form="bogus")
    with pytest.raises(wr.InputError):
        wr.creep_forces(c, creepage=(1e-3, 0, 0), mu=MU, method="carter", nx=3)
    single = wr.creep_forces(c[0], creepage=(0.5, 0, 0), mu=MU, method=Carter())
    assert single.status == wr.Status.FULL_SLIP and isinstance(single.Fx, float)


def test_traction_input_errors():
    with pytest.raises(wr.InputError, match="a"):
        carter_traction(0.0, -1e-3, 1e-4, MU, 1e9, G, NU)
    with pytest.raises(wr.InputError, match="mu"):
        carter_traction(0.0, 1e-3, 1e-4, 0.0, 1e9, G, NU)
    with pytest.raises(wr.InputError, match="nu"):
        carter_traction(0.0, 1e-3, 1e-4, MU, 1e9, G, 0.7)
    with pytest.raises(wr.InputError, match="x"):
        carter_traction(np.nan, 1e-3, 1e-4, MU, 1e9, G, NU)
