"""Invariants every registered creep-force law must satisfy (hypothesis).

For each law in ``wheelrail.api.METHODS``:

* Coulomb bound |F_t| ≤ μ Fn to round-off (not for ``linear``, which is unsaturated;
  FASTSIM included);
* odd symmetry of the steady rolling problem (Kalker 1990, ch. 1–2: reversing all
  creepages reverses the traction; reflecting y → −y maps (ξ, η, φ) to
  (ξ, −η, −φ)), hence Fx(−ξ, η, φ) = −Fx(ξ, η, φ) and
  Fy(ξ, −η, −φ) = −Fy(ξ, η, φ), Mz(ξ, −η, −φ) = −Mz(ξ, η, φ);
* continuity: a change Δ of the creepages changes the forces by at most a
  multiple of Kalker's linear stiffness times |Δ| (Lipschitz bound);
* a batch gives the same numbers as a loop over single cases.

``carter`` is exercised with ξ only (it is a longitudinal theory); ``exact`` runs on a
coarse 10-element grid (the invariants hold on any grid, to the solver tolerance).
"""

import numpy as np
import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

import wheelrail as wr

#: small, fast options per method (only keys the method accepts are passed)
SMALL_OPTIONS = {"fastsim": {"nx": 10, "ny": 10, "fields": False},
                 "exact": {"elements": 10},
                 "table": {"outside": "fastsim"}}  # contacts/spins beyond the table: FASTSIM
#: relative tolerance of the Coulomb bound: every law, FASTSIM included (its sampled
#: traction bound is scaled to carry exactly Fn), must satisfy it to round-off.
BOUND_TOL: dict = {}
#: relative tolerance (of mu Fn) of the symmetry checks: round-off for closed forms and
#: FASTSIM; the iterative exact solver converges to its tolerance tol = 1e-6
SYM_TOL = {"exact": 1e-6}
LIPSCHITZ = 10.0  # multiple of Kalker's largest coefficient allowed for dF/dcreepage

STEEL = wr.Material(E=2.1e11, nu=0.28)
CONTACTS = [
    wr.hertz(7.5e4, A=0.5 / 0.46, B=0.5 / 0.30, material=STEEL),   # a/b > 1 (tread)
    wr.hertz(5.0e4, A=0.5 / 0.46, B=0.5 / 0.015, material=STEEL),  # a/b < 1 (flange root)
]
LAWS = list(wr.tangential_methods())

PROP = settings(max_examples=50, deadline=None,
                suppress_health_check=[HealthCheck.function_scoped_fixture])

creep = st.floats(-0.05, 0.05, allow_subnormal=False)
spin = st.floats(-5.0, 5.0, allow_subnormal=False)
frict = st.floats(0.05, 0.8)
contact_index = st.sampled_from(range(len(CONTACTS)))


def law(name):
    """(implementation, options) for ``name``."""
    impl = wr.tangential.get(name, SMALL_OPTIONS.get(name, {}))
    return impl, {}


def creepage(name, xi, eta, phi):
    return (xi, 0.0, 0.0) if name == "carter" else (xi, eta, phi)


def forces(impl, opts, contact, c, mu):
    r = wr.creep_forces(contact, c, mu=mu, method=impl, **opts)
    return np.array([r.Fx, r.Fy, r.Mz], dtype=float)


def scale(contact, mu):
    return mu * float(contact.Fn)


@pytest.mark.parametrize("name", LAWS)
@PROP
@given(i=contact_index, xi=creep, eta=creep, phi=spin, mu=frict)
def test_coulomb_bound(name, i, xi, eta, phi, mu):
    if name == "linear":
        pytest.skip("Kalker's linear theory is unsaturated")
    impl, opts = law(name)
    contact = CONTACTS[i]
    F = forces(impl, opts, contact, creepage(name, xi, eta, phi), mu)
    tol = BOUND_TOL.get(name, 1e-12)
    assert np.hypot(F[0], F[1]) <= scale(contact, mu) * (1.0 + tol)


@pytest.mark.parametrize("name", LAWS)
@PROP
@given(i=contact_index, xi=creep, eta=creep, phi=spin, mu=frict)
def test_odd_symmetry(name, i, xi, eta, phi, mu):
    impl, opts = law(name)
    contact = CONTACTS[i]
    c = creepage(name, xi, eta, phi)
    F = forces(impl, opts, contact, c, mu)
    Fxm = forces(impl, opts, contact, (-c[0], c[1], c[2]), mu)
    Fym = forces(impl, opts, contact, (c[0], -c[1], -c[2]), mu)
    atol = SYM_TOL.get(name, 1e-10) * max(scale(contact, mu), np.abs(F[:2]).max())
    matol = atol * float(contact.c)
    np.testing.assert_allclose(Fxm[0], -F[0], rtol=1e-9, atol=atol)
    np.testing.assert_allclose(Fym[1], -F[1], rtol=1e-9, atol=atol)
    np.testing.assert_allclose(Fym[2], -F[2], rtol=1e-9, atol=matol)
    np.testing.assert_allclose(Fym[0], F[0], rtol=1e-9, atol=atol)


@pytest.mark.parametrize("name", LAWS)
@PROP
@given(i=contact_index, xi=creep, eta=creep, phi=spin, mu=frict,
       dxi=st.floats(-1e-6, 1e-6), deta=st.floats(-1e-6, 1e-6), dphi=st.floats(-1e-4, 1e-4))
# regressions: a symmetry plane against a subnormal neighbour. Fx is odd in ξ, so
# Fx(0, η, φ) = 0 and Fx(5e-324, η, φ) must be as small; (Fy, Mz) are odd in (η, φ), so
# Fy(ξ, 0, 0) = 0 and Fy(ξ, 5e-324, 0) likewise (Kalker 1990, ch. 1-2). The table law once
# zeroed the exact symmetry point only: a jump of ~1e-7 μFn to its neighbours.
@example(i=0, xi=0.0, eta=1e-3, phi=1.0, mu=0.3, dxi=5e-324, deta=0.0, dphi=0.0)
@example(i=0, xi=0.0, eta=1e-3, phi=1.0, mu=0.3, dxi=-5e-324, deta=0.0, dphi=0.0)
@example(i=0, xi=1e-3, eta=0.0, phi=0.0, mu=0.3, dxi=0.0, deta=5e-324, dphi=0.0)
@example(i=0, xi=0.0, eta=0.0, phi=0.5, mu=0.3, dxi=5e-324, deta=0.0, dphi=0.0)
def test_continuity(name, i, xi, eta, phi, mu, dxi, deta, dphi):
    impl, opts = law(name)
    contact = CONTACTS[i]
    c0 = np.array(creepage(name, xi, eta, phi))
    c1 = np.array(creepage(name, xi + dxi, eta + deta, phi + dphi))
    F0 = forces(impl, opts, contact, tuple(c0), mu)
    F1 = forces(impl, opts, contact, tuple(c1), mu)
    cc = float(contact.c)
    d = np.abs(c1 - c0)
    # Kalker's linear stiffness: forces G c^2 C, moment G c^3 C; C <= ~6 for these shapes
    k = LIPSCHITZ * 6.0 * contact.G * cc**2 * (d[0] + d[1] + cc * d[2])
    noise = 1e-9 * max(scale(contact, mu), np.abs(F0[:2]).max())
    assert abs(F1[0] - F0[0]) <= k + noise
    assert abs(F1[1] - F0[1]) <= k + noise
    assert abs(F1[2] - F0[2]) <= k * cc + noise * cc


@pytest.mark.parametrize("name", LAWS)
@settings(max_examples=15, deadline=None)
@given(data=st.data())
def test_batch_equals_loop(name, data):
    impl, opts = law(name)
    n = 4
    loads = np.array(data.draw(st.lists(st.floats(1e4, 1.5e5), min_size=n, max_size=n)))
    contact = wr.hertz(loads, A=0.5 / 0.46, B=np.array([1.6, 5.0, 20.0, 1.2]), material=STEEL)
    cr = np.array([creepage(name, *data.draw(st.tuples(creep, creep, spin))) for _ in range(n)])
    mu = np.array(data.draw(st.lists(frict, min_size=n, max_size=n)))
    rb = wr.creep_forces(contact, cr, mu=mu, method=impl, **opts)
    Fb = np.array([rb.Fx, rb.Fy, rb.Mz], dtype=float)
    assert Fb.shape == (3, n)
    for k in range(n):
        Fk = forces(impl, opts, contact[k], tuple(cr[k]), float(mu[k]))
        atol = 1e-10 * max(mu[k] * loads[k], np.abs(Fk[:2]).max())
        np.testing.assert_allclose(Fb[:2, k], Fk[:2], rtol=1e-10, atol=atol)
        np.testing.assert_allclose(Fb[2, k], Fk[2], rtol=1e-10, atol=atol * float(contact.c[k]))
