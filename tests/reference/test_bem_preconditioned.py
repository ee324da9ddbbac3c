"""The preconditioned normal BEM solver (FFT approximate inverse, Vollebregt 2014).

References: Hertz theory (Johnson, *Contact Mechanics* (1985) eqs. (3.64)–(3.66),
implemented independently in wheelrail.normal.hertz); the plain Polonsky–Keer
iteration (Wear 231 (1999) 206–219) for the same discrete problem; the
iteration-count behaviour claimed by Vollebregt, J. Comput. Phys. 257 (2014)
333–351 (preconditioned counts nearly independent of the grid, plain counts
growing with it).
"""

import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import wheelrail as wr
from wheelrail.halfspace import Grid, InfluenceOperator
from wheelrail.halfspace.precondition import InverseSymbolPreconditioner
from wheelrail.normal.bem import ContactTruncatedWarning, hertz_grid, polonsky_keer, solve_normal

STEEL = wr.Material(2.1e11, 0.28)
LOAD = 10e3


def _both(grid, h0, materials=STEEL, **kw):
    pre = solve_normal(grid, h0, materials, precondition=True, **kw)
    plain = solve_normal(grid, h0, materials, precondition=False, **kw)
    return pre, plain


@pytest.mark.parametrize("aspect", [1.0, 0.4])
def test_preconditioned_equals_plain_load_control(aspect):
    """Same discrete solution to the solver tolerance (rectangular elements included)."""
    hc = wr.hertz_from_semiaxes(3e-3 * aspect, 3e-3, LOAD, STEEL)
    grid, h0 = hertz_grid(hc, elements=24)
    pre, plain = _both(grid, h0, Fn=LOAD, tol=1e-10)
    assert np.max(np.abs(pre.pressure - plain.pressure)) < 1e-7 * plain.p_max
    assert np.array_equal(pre.contact, plain.contact)
    assert pre.penetration == pytest.approx(plain.penetration, rel=1e-8)
    assert pre.Fn == pytest.approx(LOAD, rel=1e-12)


def test_preconditioned_equals_plain_penetration_two_patches():
    """Penetration control, a non-Hertzian gap with two separate contact patches."""
    grid = Grid.from_bounds(-4e-3, 4e-3, -2e-3, 2e-3, 41, 21)
    h0 = 40.0 * (np.abs(grid.X) - 2e-3) ** 2 + 30.0 * grid.Y ** 2 + 1e-6 * np.cos(2e3 * grid.Y)
    pre, plain = _both(grid, h0, penetration=2e-5, tol=1e-10)
    assert pre.contact.sum() > 20
    # two patches: no contact on the centre line x = 0
    assert not pre.contact[20].any()
    assert np.max(np.abs(pre.pressure - plain.pressure)) < 1e-7 * plain.p_max
    assert pre.Fn == pytest.approx(plain.Fn, rel=1e-8)
    assert pre.residual < 1e-8


def test_preconditioned_hertz_closed_form_small_grid():
    """Pressure, area and approach against Hertz on a 20-element grid (discretisation error)."""
    hc = wr.hertz_from_semiaxes(4e-3, 3e-3, LOAD, STEEL)
    grid, h0 = hertz_grid(hc, elements=20)
    sol = solve_normal(grid, h0, STEEL, Fn=LOAD)
    assert sol.p_max == pytest.approx(hc.p0, rel=0.02)
    assert sol.penetration == pytest.approx(hc.penetration, rel=0.02)
    assert sol.area == pytest.approx(hc.area, rel=0.04)
    assert np.max(np.abs(sol.pressure - hc.pressure(grid.X, grid.Y))) < 0.10 * hc.p0   # edge elements (√ behaviour): 0.081 p0
    # the approach of a prescribed-penetration solve gives back the load
    back = solve_normal(grid, h0, STEEL, penetration=sol.penetration)
    assert back.Fn == pytest.approx(LOAD, rel=1e-6)


def test_preconditioned_dissimilar_materials():
    """Dissimilar pair (K ≠ 0; the normal block differs from steel's)."""
    pair = wr.MaterialPair(wr.Material(2.1e11, 0.28), wr.Material(7e10, 0.33))
    hc = wr.hertz(LOAD, A=1.0, B=1.5, material=pair)
    grid, h0 = hertz_grid(hc, elements=20)
    pre, plain = _both(grid, h0, materials=pair, Fn=LOAD, tol=1e-10)
    assert np.max(np.abs(pre.pressure - plain.pressure)) < 1e-7 * plain.p_max
    assert pre.p_max == pytest.approx(float(hc.p0), rel=0.03)


def test_iterations_nearly_grid_independent():
    """Preconditioned counts stay small and grow less than the plain ones (20 → 60 elements)."""
    hc = wr.hertz(LOAD, A=1.0, B=2.0, material=STEEL)
    counts = {}
    for n in (20, 60):
        grid, h0 = hertz_grid(hc, elements=n, margin=1.1)
        pre, plain = _both(grid, h0, Fn=LOAD)
        counts[n] = (pre.iterations, plain.iterations)
    (pre20, plain20), (pre60, plain60) = counts[20], counts[60]
    assert pre20 <= 20 and pre60 <= 20
    assert pre60 < 0.6 * plain60
    assert pre60 - pre20 < plain60 - plain20


def test_inverse_symbol_operator_is_symmetric_psd_and_approximates_inverse():
    """M is symmetric positive semi-definite and M A is close to the identity on smooth fields."""
    grid = Grid.from_bounds(-1e-3, 1e-3, -1e-3, 1e-3, 24, 16)
    op = InfluenceOperator(grid, STEEL).block(2, 2)
    m = InverseSymbolPreconditioner(op.kernel, grid.dx, grid.dy)
    rng = np.random.default_rng(1)
    x, y = rng.standard_normal((2,) + grid.shape)
    scale = np.linalg.norm(x) * np.linalg.norm(m(y))        # single-precision FFTs
    assert abs(np.vdot(x, m(y)) - np.vdot(y, m(x))) < 1e-5 * scale
    assert np.vdot(x, m(x)) > 0
    # A smooth bump well inside the grid: M (A p) ≈ p in the interior
    p = np.exp(-((grid.X / 4e-4) ** 2 + (grid.Y / 4e-4) ** 2))
    back = m(op.apply(p))
    assert np.max(np.abs(back - p)[6:-6, 4:-4]) < 0.15


def test_polonsky_keer_kernel_accepts_preconditioner():
    """The pure kernel with and without a preconditioner callable (dense operator)."""
    grid = Grid.from_bounds(-1e-3, 1e-3, -1e-3, 1e-3, 15, 15)
    op = InfluenceOperator(grid, STEEL).block(2, 2)
    dense = op.dense()
    h = 200.0 * (grid.X ** 2 + grid.Y ** 2)
    apply = lambda p: (dense @ p.ravel()).reshape(p.shape)   # noqa: E731
    m = InverseSymbolPreconditioner(op.kernel, grid.dx, grid.dy)
    pa, da, ia, _ = polonsky_keer(apply, h, grid.element_area, Fn=500.0, tol=1e-11)
    pb, db, ib, _ = polonsky_keer(apply, h, grid.element_area, Fn=500.0, tol=1e-11,
                                  precondition=m)
    assert np.max(np.abs(pa - pb)) < 1e-8 * pa.max()
    assert db == pytest.approx(da, rel=1e-9)
    assert ib <= ia


def test_bad_kernel_rejected():
    with pytest.raises(wr.errors.InputError, match="far field"):
        InverseSymbolPreconditioner(-np.ones((5, 5)), 1e-4, 1e-4)
    with pytest.raises(wr.errors.InputError, match="odd"):
        InverseSymbolPreconditioner(np.ones((4, 5)), 1e-4, 1e-4)


def test_single_element_grid():
    """One element: no preconditioner; the pressure is the load over the element area."""
    grid = Grid.from_bounds(-1e-3, 1e-3, -1e-3, 1e-3, 1, 1)
    with pytest.warns(wr.normal.bem.ContactTruncatedWarning):
        sol = solve_normal(grid, np.zeros(grid.shape), STEEL, Fn=100.0)
    assert sol.p_max == pytest.approx(100.0 / grid.element_area, rel=1e-12)


@settings(max_examples=12, deadline=None)
@given(nx=st.integers(5, 25), ny=st.integers(5, 25), ratio=st.floats(0.25, 4.0),
       A=st.floats(0.2, 5.0), B=st.floats(0.2, 5.0), wave=st.floats(0.0, 3e-6),
       seed=st.integers(0, 2**31), load_control=st.booleans())
def test_preconditioned_equals_plain_random_gaps(nx, ny, ratio, A, B, wave, seed,
                                                 load_control):
    """Any grid shape, element aspect and rough quadratic gap: the same discrete solution."""
    rng = np.random.default_rng(seed)
    grid = Grid.from_bounds(-3e-3, 3e-3, -3e-3 * ratio, 3e-3 * ratio, nx, ny)
    kx, ky = rng.uniform(500.0, 5000.0, 2)
    h0 = (A * grid.X ** 2 + B * grid.Y ** 2
          + wave * np.sin(kx * grid.X + rng.uniform(0, 6)) * np.cos(ky * grid.Y))
    h0 = h0 - h0.min()
    kw = {"Fn": 2e3} if load_control else {"penetration": 0.5 * float(np.median(h0)) + 1e-7}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ContactTruncatedWarning)
        pre, plain = _both(grid, h0, tol=1e-11, **kw)
    assert np.max(np.abs(pre.pressure - plain.pressure)) < 1e-6 * plain.p_max
    assert pre.Fn == pytest.approx(plain.Fn, rel=1e-8)
    assert pre.residual < 1e-6
