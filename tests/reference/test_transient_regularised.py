"""Regularised Coulomb law (seed 001 eqs. 2.21–2.22) converging to the exact law as ε → 0.

Reference: the exact-Coulomb transient solution (active set) of the same run;
the observed order of the force error in ε is fitted (np.polyfit on log ε /
log error; measured 0.87 on this case: 2.6 %, 1.0 %, 0.36 %, 0.13 %).
"""

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.transient.regularised import dense_block, regularised_step


@pytest.fixture(scope="module")
def hc():
    return wr.hertz_from_radii(10e3, 0.5, -0.409, 0.3, material=wr.STEEL)


def test_regularised_converges_to_exact(hc):
    kw = dict(travel=2.5e-3, step=2.5e-4, mu=0.4, creepage=(-5e-4, 0.0, 0.0), elements=10)
    exact = wr.transient_rolling(hc, **kw)
    eps = np.array([3e-5, 1e-5, 3e-6, 1e-6])
    err = []
    for e in eps:
        r = wr.transient_rolling(hc, friction="regularised", epsilon=e, **kw)
        # the regularised traction lies strictly inside the Coulomb disc
        assert np.all(np.hypot(r.px[-1], r.py[-1]) < 0.4 * r.pn[-1] + 1e-9)
        err.append(abs(r.Fx[-1] - exact.Fx[-1]) / abs(exact.Fx[-1]))
    order = np.polyfit(np.log(eps), np.log(err), 1)[0]
    assert 0.6 < order < 1.3
    assert err[-1] < 3e-3
    assert np.all(np.diff(err) < 0)


def test_regularised_force_control(hc):
    r = wr.transient_rolling(hc, travel=1e-3, step=2.5e-4, mu=0.4, Fx=2000.0,
                             friction="regularised", epsilon=1e-5, elements=8)
    assert r.Fx[1:] == pytest.approx(2000.0, rel=1e-6)
    assert np.all(r.xi[1:] < 0)


def test_regularised_step_satisfies_the_law():
    # a tiny diagonal-dominant system: the returned (p, s) satisfy eq. (2.21) and s = b + K p
    rng = np.random.default_rng(1)
    A = rng.normal(size=(6, 6))
    Kd = A @ A.T + 6 * np.eye(6)
    b = rng.normal(size=(2, 3))
    g = np.array([1.0, 2.0, 0.5])
    p, s, _ = regularised_step(Kd, b, g, 0.1, tol=1e-13)
    ns = np.hypot(s[0], s[1])
    law = -g * (2 / np.pi) * np.arctan(ns / 0.1) * s / ns
    assert np.allclose(p, law, atol=1e-10)
    assert np.allclose(s, b + (Kd @ p.ravel()).reshape(2, 3), atol=1e-12)
    with pytest.raises(wr.InputError, match="epsilon must be > 0, got -1"):
        regularised_step(Kd, b, g, -1.0)
    assert dense_block(np.zeros((2, 2, 3, 3)), np.array([0, 1]), np.array([0, 0])).shape == (4, 4)
