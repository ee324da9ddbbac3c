"""Nested iteration of the steady-rolling solver (halfspace.tangential).

The coarse levels only give the starting tractions: the nested and the plain
solve must converge to the same discrete problem (agreement to the solver
tolerance), and the start must save fine-level Newton and Krylov steps (the
reason it exists; counts measured with ``benchmarks/bench_exact_rolling.py``).
"""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import wheelrail as wr
from wheelrail.halfspace import Grid
from wheelrail.tangential.exact import solve_rolling
from wheelrail.tangential.exact.nested import _coarsened, _prolongated
from wheelrail.normal.bem import hertz_grid, solve_normal

HC = wr.hertz(1e4, A=1.0, B=2.0, material=wr.STEEL)
MU = 0.3
COMBINED = (1e-3, 5e-4, 1.0)
SPIN = (0.0, 0.0, 3.0)


def _problem(elements):
    grid, gap = hertz_grid(HC, elements=elements, margin=1.1)
    return grid, solve_normal(grid, gap, wr.STEEL, Fn=1e4).pressure


@pytest.fixture(scope="module")
def grid36():
    return _problem(36)


@pytest.mark.parametrize("creepage", [(2e-4, 0.0, 0.0), COMBINED, SPIN])
def test_nested_and_plain_agree(grid36, creepage):
    grid, pn = grid36
    mufn = MU * 1e4
    for tol, ftol in ((1e-6, 1e-7), (1e-10, 1e-11)):
        plain = solve_rolling(grid, pn, wr.STEEL, creepage, MU, tol=tol, nested=False)
        nested = solve_rolling(grid, pn, wr.STEEL, creepage, MU, tol=tol)
        assert plain.info["coarse"] == []
        assert [c["shape"] for c in nested.info["coarse"]] == [(21, 21)]
        assert nested.converged and nested.residual <= tol
        # the same discrete problem: forces and tractions agree to the tolerance
        for a, b in ((plain.Fx, nested.Fx), (plain.Fy, nested.Fy)):
            assert abs(a - b) <= ftol * mufn
        if tol < 1e-8:
            dp = max(np.abs(plain.px - nested.px).max(), np.abs(plain.py - nested.py).max())
            assert dp <= 1e-8 * MU * pn.max()
            np.testing.assert_array_equal(plain.adhesion, nested.adhesion)


@pytest.mark.parametrize("creepage", [COMBINED, SPIN])
def test_nested_start_saves_fine_level_steps(creepage):
    grid, pn = _problem(48)
    plain = solve_rolling(grid, pn, wr.STEEL, creepage, MU, nested=False)
    nested = solve_rolling(grid, pn, wr.STEEL, creepage, MU)
    # measured: plain 7-9 Newton / 35-39 Krylov, nested 4-5 / 24-27 (+ the coarse level's)
    assert nested.iterations <= 5 < plain.iterations
    assert nested.info["krylov_iterations"] <= 0.8 * plain.info["krylov_iterations"]


def test_fine_level_krylov_nearly_grid_independent():
    # combined creepage and spin: fine-level GMRES iterations stay below 30 from 40 to 80
    # elements with the nested start (plain start: 36-49, growing with the grid)
    for n in (40, 80):
        grid, pn = _problem(n)
        for cr in (COMBINED, SPIN):
            sol = solve_rolling(grid, pn, wr.STEEL, cr, MU)
            assert len(sol.info["coarse"]) >= 1
            assert sol.info["krylov_iterations"] <= 30, (n, cr, sol.info)


def test_coarsened_keeps_force_and_window():
    grid = Grid(-0.7, -0.35, 0.1, 0.05, 15, 15)
    rng = np.random.default_rng(3)
    p = rng.uniform(0.0, 1e9, grid.shape)
    cgrid, pc = _coarsened(grid, p)
    assert cgrid.shape == (8, 8)
    assert (cgrid.dx, cgrid.dy) == (0.2, 0.1)
    # same lower-left corner; the coarse window is one fine element longer (odd count)
    assert cgrid.bounds[0] == pytest.approx(grid.bounds[0])
    assert cgrid.bounds[2] == pytest.approx(grid.bounds[2])
    assert pc.sum() * cgrid.element_area == pytest.approx(p.sum() * grid.element_area)
    assert pc[0, 0] == pytest.approx(p[:2, :2].mean())


def test_prolongated_interpolates_and_keeps_slip_on_the_bound():
    grid = Grid(-0.7, -0.7, 0.1, 0.1, 15, 15)
    cgrid, _ = _coarsened(grid, np.ones(grid.shape))
    # a linear traction field is reproduced exactly between coarse centres
    pc = np.stack((1.0 + cgrid.X + 2.0 * cgrid.Y, 3.0 - cgrid.Y))
    gc = np.full(cgrid.shape, 100.0)           # far above |p|: everything sticks
    g = np.full(grid.shape, 100.0)
    p = _prolongated(pc, gc, g)
    inner = (slice(1, 14), slice(1, 14))
    np.testing.assert_allclose(p[0][inner], (1.0 + grid.X + 2.0 * grid.Y)[inner], atol=1e-12)
    np.testing.assert_allclose(p[1][inner], (3.0 - grid.Y)[inner], atol=1e-12)
    # coarse elements at the bound (slip): their fine elements start on the fine bound
    gc = np.hypot(pc[0], pc[1])
    g = np.full(grid.shape, 2.5)
    p = _prolongated(pc, gc, g)
    np.testing.assert_allclose(np.hypot(p[0], p[1]), 2.5, rtol=1e-12)


@settings(max_examples=8, deadline=None)
@given(xi=st.floats(-2e-3, 2e-3), eta=st.floats(-2e-3, 2e-3), phi=st.floats(-4.0, 4.0))
def test_nested_and_plain_agree_for_any_creepage(grid36, xi, eta, phi):
    # property: the nested start changes the path only, for any creepage (partial slip to
    # nearly full slip, either sign)
    grid, pn = grid36
    plain = solve_rolling(grid, pn, wr.STEEL, (xi, eta, phi), MU, tol=1e-9, nested=False)
    nested = solve_rolling(grid, pn, wr.STEEL, (xi, eta, phi), MU, tol=1e-9)
    scale = MU * 1e4
    assert abs(plain.Fx - nested.Fx) <= 1e-8 * scale
    assert abs(plain.Fy - nested.Fy) <= 1e-8 * scale
    assert abs(plain.Mz - nested.Mz) <= 1e-8 * scale * grid.dx * grid.nx
