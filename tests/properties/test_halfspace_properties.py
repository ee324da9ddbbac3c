"""Invariants of the half-space influence operator and the grid normal solver (hypothesis)."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import wheelrail as wr
from wheelrail.halfspace import Grid, InfluenceOperator
from wheelrail.normal.bem import solve_normal

materials = st.sampled_from([
    wr.MaterialPair.same(wr.Material(2.1e11, 0.28)),
    wr.MaterialPair(wr.Material(2.1e11, 0.28), wr.Material(1.2e11, 0.33)),
    wr.MaterialPair.same(wr.Material(1e9, 0.0)),
])


@settings(max_examples=25, deadline=None)
@given(nx=st.integers(1, 7), ny=st.integers(1, 7), dx=st.floats(1e-5, 1e-2),
       ratio=st.floats(0.2, 5.0), mat=materials, seed=st.integers(0, 2**31))
def test_operator_symmetric_positive_and_exact(nx, ny, dx, ratio, mat, seed):
    g = Grid(0.0, 0.0, dx, dx * ratio, nx, ny)
    op = InfluenceOperator(g, mat)
    rng = np.random.default_rng(seed)
    p, q = rng.normal(size=(2, 3, nx, ny))
    up, uq = op.apply(p), op.apply(q)
    # reciprocity <q, A p> = <p, A q> and positive elastic energy <p, A p> > 0
    scale = np.abs(up).max() * np.abs(q).max() * p.size
    assert abs(np.sum(q * up) - np.sum(p * uq)) <= 1e-12 * scale
    assert np.sum(p * up) > 0
    D = np.block([[op.dense_matrix(i, j) for j in range(3)] for i in range(3)])
    assert np.allclose(D @ p.ravel(), up.ravel(), rtol=0, atol=1e-12 * np.abs(up).max())


@settings(max_examples=10, deadline=None)
@given(load=st.floats(1e2, 1e5), A=st.floats(0.3, 3.0), B=st.floats(0.3, 3.0))
def test_normal_solution_is_complementary_and_scales_like_hertz(load, A, B):
    """p ≥ 0, gap ≥ 0, p·gap = 0; Fn balanced; and δ ∝ Fn^(2/3) on a self-similar grid."""
    mat = wr.Material(2.1e11, 0.28)
    hc = wr.hertz(load, A, B, mat)
    w = 1.3
    g = Grid.from_bounds(-w * hc.a, w * hc.a, -w * hc.b, w * hc.b, 24, 24)
    h0 = A * g.X**2 + B * g.Y**2
    sol = solve_normal(g, h0, mat, Fn=load)
    assert np.all(sol.pressure >= 0)
    assert abs(sol.Fn / load - 1) < 1e-12
    assert sol.residual < 1e-6
    assert np.all(sol.gap[~sol.contact] > -1e-6 * sol.penetration)
    # Hertz similarity: 8x the load on a 2x wider grid gives 4x the approach and 2x the pressure
    g2 = Grid.from_bounds(-2 * w * hc.a, 2 * w * hc.a, -2 * w * hc.b, 2 * w * hc.b, 24, 24)
    sol2 = solve_normal(g2, A * g2.X**2 + B * g2.Y**2, mat, Fn=8 * load)
    assert abs(sol2.penetration / (4 * sol.penetration) - 1) < 1e-6
    assert np.allclose(sol2.pressure, 2 * sol.pressure, rtol=0, atol=1e-6 * sol2.p_max)
