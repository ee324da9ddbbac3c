"""Invariants of FASTSIM (hypothesis): traction bound, symmetries, odd response."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import wheelrail as wr

MAT = wr.Material.from_shear(80e9, 0.28)
creep = st.floats(-5e-3, 5e-3, allow_nan=False)
spin = st.floats(-2.0, 2.0, allow_nan=False)
aspect = st.floats(0.2, 5.0)
bound = st.sampled_from(["parabolic", "elliptic"])
flex = st.sampled_from(["three", "weighted"])


def _contact(g):
    return wr.hertz_from_semiaxes(a=5e-3 * np.sqrt(g), b=5e-3 / np.sqrt(g), Fn=60e3, material=MAT)


@settings(max_examples=40, deadline=None)
@given(xi=creep, eta=creep, phi=spin, g=aspect, bound=bound, flex=flex,
       mu=st.floats(0.05, 0.6))
def test_traction_within_bound(xi, eta, phi, g, bound, flex, mu):
    r = wr.creep_forces(_contact(g), (xi, eta, phi), mu, method="fastsim", nx=16, ny=12,
                        bound=bound, flexibility=flex)
    f = r.fields
    assert np.all(f.traction <= mu * f.pressure * (1 + 1e-12))
    assert r.Ft <= mu * float(np.sum(f.pressure * f.area)) * (1 + 1e-12)
    # Coulomb: in slip elements the traction is on the bound and opposes the slip
    s = f.slip & (f.pressure > 0)
    assert np.allclose(f.traction[s], mu * f.pressure[s], rtol=1e-12)
    dot = (f.sx * f.px + f.sy * f.py)[s]
    assert np.allclose(dot, -f.slip_speed[s] * f.traction[s], rtol=1e-9, atol=0)
    assert np.all(f.slip_speed[f.adhesion] == 0)


@settings(max_examples=40, deadline=None)
@given(xi=creep, eta=creep, phi=spin, g=aspect, bound=bound, flex=flex)
def test_odd_and_mirror_symmetry(xi, eta, phi, g, bound, flex):
    c = _contact(g)
    cr = np.array([[xi, eta, phi], [-xi, -eta, -phi], [xi, -eta, -phi]])
    r = wr.creep_forces(c, cr, 0.3, method="fastsim", nx=16, ny=16, bound=bound, flexibility=flex)
    scale = 0.3 * c.Fn
    # odd in the creepages
    assert np.allclose([r.Fx[1], r.Fy[1]], [-r.Fx[0], -r.Fy[0]], atol=1e-9 * scale)
    assert np.isclose(r.Mz[1], -r.Mz[0], atol=1e-9 * scale * c.a)
    # mirror y -> -y: (xi, eta, phi) -> (xi, -eta, -phi) gives (Fx, -Fy, -Mz)
    assert np.allclose([r.Fx[2], r.Fy[2]], [r.Fx[0], -r.Fy[0]], atol=1e-9 * scale)
    assert np.isclose(r.Mz[2], -r.Mz[0], atol=1e-9 * scale * c.a)
