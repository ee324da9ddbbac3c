"""Shen–Hedrick–Elkins creep-force law against closed forms.

References used by the checks:

* Kalker's linear theory (Kalker 1990; conventions in :mod:`wheelrail.conventions`):
  Fx = −G c² C11 ξ, Fy = −G c² (C22 η + c C23 φ), Mz = G c³ (C23 η − c C33 φ).
* Kalker's creep coefficients for a/b = 1, ν = 0.25 (Kalker 1967, reproduced in
  Kalker 1990 Table E.3 and Johnson, *Contact Mechanics*, 1985, Table 8.1):
  C11 = 4.12, C22 = 3.67, C23 = 1.47; C33 = 1.19 is wheelrail's computed value (the
  C33 column of ``kalker_coefficients.csv``; these checks only feed it into closed forms).
* Johnson & Vermeulen (1964) cubic F/(μN) = u − u²/3 + u³/27 (u < 3), 1 beyond,
  as used by Shen, Hedrick & Elkins (1983).
"""

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.tangential.shen_hedrick_elkins import (johnson_vermeulen, she_saturation_ratio,
                                                      shen_hedrick_elkins_forces)

# Kalker 1990 Table E.3 / Johnson 1985 Table 8.1, a/b = 1, nu = 0.25 (C33 computed, see above)
C11, C22, C23, C33 = 4.12, 3.67, 1.47, 1.19
G, A_, B_ = 8.0e10, 6.0e-3, 6.0e-3
FN, MU = 1.0e5, 0.3
C = np.sqrt(A_ * B_)


def she(xi, eta, phi, spin_moment="scaled"):
    return shen_hedrick_elkins_forces(G, A_, B_, C11, C22, C23, C33, np.asarray(xi, float),
                                      np.asarray(eta, float), np.asarray(phi, float), MU, FN,
                                      spin_moment)


def test_cubic_known_points():
    u = np.array([0.0, 1.5, 3.0, 4.0, 100.0])
    # u - u^2/3 + u^3/27: 0; 1.5 - 0.75 + 0.125 = 0.875; 3 - 3 + 1 = 1; saturated beyond
    np.testing.assert_allclose(johnson_vermeulen(u), [0.0, 0.875, 1.0, 1.0, 1.0], rtol=1e-15)
    # slope 1 at the origin and 0 at u = 3 (C1 junction with the plateau)
    h = 1e-6
    assert johnson_vermeulen(h) / h == pytest.approx(1.0, rel=1e-5)
    assert (johnson_vermeulen(3.0) - johnson_vermeulen(3.0 - h)) / h == pytest.approx(0.0, abs=1e-5)
    # the ratio is F/F_lin, finite at 0
    np.testing.assert_allclose(she_saturation_ratio(u[1:]), johnson_vermeulen(u[1:]) / u[1:],
                               rtol=1e-14)
    assert she_saturation_ratio(0.0) == 1.0


def test_cubic_monotone_and_bounded():
    u = np.linspace(0.0, 10.0, 2001)
    f = johnson_vermeulen(u)
    assert np.all(np.diff(f) >= -1e-15)
    assert np.all(f <= 1.0 + 1e-15)


def test_small_creepage_equals_kalker_linear_theory():
    x = 1e-10
    Fx, Fy, Mz, r = she(x, 0.0, 0.0)
    assert Fx == pytest.approx(-G * C**2 * C11 * x, rel=1e-6)
    Fx, Fy, Mz, r = she(0.0, x, 0.0, spin_moment="linear")
    assert Fy == pytest.approx(-G * C**2 * C22 * x, rel=1e-6)
    assert Mz == pytest.approx(G * C**3 * C23 * x, rel=1e-12)
    p = 1e-8  # 1/m
    Fx, Fy, Mz, r = she(0.0, 0.0, p)
    assert Fy == pytest.approx(-G * C**3 * C23 * p, rel=1e-6)
    assert Mz == pytest.approx(-G * C**4 * C33 * p, rel=1e-6)


def test_cubic_points_through_the_law():
    # choose xi so that the linear resultant is 1.5 muN and 3 muN
    xi_unit = MU * FN / (G * C**2 * C11)
    Fx, *_ = she(1.5 * xi_unit, 0.0, 0.0)
    assert Fx == pytest.approx(-0.875 * MU * FN, rel=1e-12)
    Fx, *_ = she(3.0 * xi_unit, 0.0, 0.0)
    assert Fx == pytest.approx(-MU * FN, rel=1e-12)


def test_saturation_keeps_direction():
    xi, eta, phi = 0.02, -0.01, 0.5
    Fx, Fy, Mz, r = she(xi, eta, phi)
    assert np.hypot(Fx, Fy) == pytest.approx(MU * FN, rel=1e-13)
    fx_lin = -G * C**2 * C11 * xi
    fy_lin = -G * C**2 * (C22 * eta + C * C23 * phi)
    assert np.arctan2(Fy, Fx) == pytest.approx(np.arctan2(fy_lin, fx_lin), abs=1e-13)


def test_spin_moment_options():
    xi, eta, phi = 1e-3, 2e-3, 1.0
    mz_lin = G * C**3 * (C23 * eta - C * C33 * phi)
    _, _, Mz_lin, r = she(xi, eta, phi, spin_moment="linear")
    _, _, Mz_sc, r2 = she(xi, eta, phi, spin_moment="scaled")
    assert Mz_lin == pytest.approx(mz_lin, rel=1e-13)
    assert Mz_sc == pytest.approx(r * mz_lin, rel=1e-13)
    assert 0.0 < r < 1.0


def test_sign_convention_positive_creepage_negative_force():
    Fx, Fy, Mz, r = she(1e-3, 1e-3, 0.0)
    assert Fx < 0 and Fy < 0


# ---- through the public API (needs Kalker's coefficients from tangential.linear) ----------
@pytest.fixture
def round_contact():
    return wr.hertz_from_semiaxes(A_, B_, FN, wr.Material(E=2.0 * G * 1.25, nu=0.25))


def test_api_slope_matches_kalker_table(round_contact):
    x = 1e-8
    r = wr.creep_forces(round_contact, (x, 0.0, 0.0), mu=MU, method="shen-hedrick-elkins")
    assert -r.Fx / (G * C**2 * x) == pytest.approx(C11, rel=2e-3)
    r = wr.creep_forces(round_contact, (0.0, x, 0.0), mu=MU, method="she")
    assert -r.Fy / (G * C**2 * x) == pytest.approx(C22, rel=2e-3)


def test_api_full_slip_and_info(round_contact):
    r = wr.creep_forces(round_contact, (0.05, 0.0, 0.0), mu=MU, method="shen-hedrick-elkins")
    assert r.Fx == pytest.approx(-MU * FN, rel=1e-12)
    assert r.info["saturation"] < 1.0
    assert r.method == "shen-hedrick-elkins"


def test_bad_spin_moment_option(round_contact):
    with pytest.raises(wr.InputError, match="spin_moment"):
        wr.creep_forces(round_contact, (1e-3, 0, 0), mu=MU, method="she", spin_moment="zero")
    with pytest.raises(wr.InputError, match="nx"):
        wr.creep_forces(round_contact, (1e-3, 0, 0), mu=MU, method="she", nx=10)
