"""The tests' own Hertz closed form (``tests/_closed_form.py``) against published values.

* Piotrowski & Chollet (2005), VSD 43, Table 2: Hertz's coefficients m, n/m for
  cos θ = (B − A)/(A + B), with a = m (3P/(4E*(A + B)))^(1/3), b = n (...)^(1/3)
  (Timoshenko & Goodier's form; 4 digits);
* Johnson (1985), eqs. (4.22)–(4.24): the circle, a³ = 3PR/(4E*), δ = a²/R, p0 = 3P/(2πa²).
"""

import math

import pytest
from _closed_form import hertz_approach, hertz_ellipse_load, hertz_load

# theta [deg], n/m, m   (Piotrowski & Chollet 2005, Table 2)
TABLE2 = [(5, 0.0212, 11.238), (10, 0.0470, 6.612), (30, 0.1806, 2.731), (60, 0.4826, 1.486),
          (90, 1.0, 1.0), (120, 2.0720, 0.7171), (150, 5.5380, 0.4931), (170, 21.26, 0.311)]


@pytest.mark.parametrize("theta, n_over_m, m", TABLE2)
def test_semi_axes_match_the_published_coefficients(theta, n_over_m, m):
    c = math.cos(math.radians(theta))
    A, B = 1.0 - c, 1.0 + c                   # A + B = 2 1/m
    P, Es = 1e4, 1.15e11
    r = hertz_load(P, A, B, Es) if theta != 90 else hertz_load(P, 1.0, 1.0, Es)
    unit = (3.0 * P / (4.0 * Es * (A + B))) ** (1.0 / 3.0)
    assert r["a"] / unit == pytest.approx(m, rel=1e-3)
    assert r["b"] / r["a"] == pytest.approx(n_over_m, rel=1e-3)


def test_circle_and_consistency():
    P, A, Es = 1e4, 1.0, 1.15e11
    R = 1.0 / (2.0 * A)
    r = hertz_load(P, A, A, Es)
    a = (3.0 * P * R / (4.0 * Es)) ** (1.0 / 3.0)
    assert r["a"] == pytest.approx(a, rel=1e-12) and r["b"] == pytest.approx(a, rel=1e-12)
    assert r["approach"] == pytest.approx(a * a / R, rel=1e-12)
    assert r["p0"] == pytest.approx(3.0 * P / (2.0 * math.pi * a * a), rel=1e-12)
    # load -> approach -> load, and the ellipse-load relation, for an elongated contact
    e = hertz_load(P, 0.2, 30.0, Es)
    back = hertz_approach(e["approach"], 0.2, 30.0, Es)
    assert back["load"] == pytest.approx(P, rel=1e-10)
    assert hertz_ellipse_load(e["a"], e["b"], e["approach"], Es) == pytest.approx(P, rel=1e-10)
