"""Kalker's exact theory (tangential.exact, halfspace.tangential): invariants and errors."""

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.errors import ConvergenceError, InputError, NoContactError
from wheelrail.halfspace import Grid
from wheelrail.tangential.exact import solve_rolling, solve_shift
from wheelrail.results import Status

HC = wr.hertz(1e4, A=1.0, B=2.0, material=wr.STEEL)
MU = 0.3


@pytest.fixture(scope="module")
def patch(hertz_patch16):
    return hertz_patch16  # grid and pressure of HC (tests/conftest.py)


def test_full_sliding_gives_mu_fn():
    r = wr.creep_forces(HC, (0.05, 0.0, 0.0), MU, method="exact", elements=16)
    assert r.status is Status.FULL_SLIP
    # every element at the bound; slip directions nearly parallel
    f = r.fields
    np.testing.assert_allclose(np.hypot(f.px, f.py), MU * f.pressure, rtol=1e-9)
    assert r.Ft == pytest.approx(MU * r.Fn, rel=1e-5)
    assert r.Ft <= MU * r.Fn * (1 + 1e-12)
    assert r.Fx < 0
    assert r.info["adhesion_area"] == 0.0


def test_symmetries(patch):
    grid, p = patch
    a = solve_rolling(grid, p, wr.STEEL, (1e-4, 5e-4, 0.8), MU)
    b = solve_rolling(grid, p, wr.STEEL, (1e-4, -5e-4, -0.8), MU)
    # η → −η, φ → −φ mirrors the problem in y: Fx unchanged, Fy and Mz change sign
    assert b.Fx == pytest.approx(a.Fx, rel=1e-5)
    assert b.Fy == pytest.approx(-a.Fy, rel=1e-5)
    assert b.Mz == pytest.approx(-a.Mz, rel=1e-5)
    c = solve_rolling(grid, p, wr.STEEL, (-1e-4, -5e-4, -0.8), MU)
    # reversing all creepages reverses all forces
    assert (c.Fx, c.Fy, c.Mz) == pytest.approx((-a.Fx, -a.Fy, -a.Mz), rel=1e-5)


def test_creep_forces_batch_and_info():
    hc = wr.hertz([8e3, 1.2e4], A=1.0, B=2.0, material=wr.STEEL)
    r = wr.creep_forces(hc, [(-1e-3, 0, 0), (0, 1e-3, 0)], MU, method="exact", elements=12)
    assert np.shape(r.Fx) == (2,)
    assert r.Fx[0] > 0 and r.Fy[1] < 0
    assert len(r.fields) == 2
    for key in ("area", "p_max", "adhesion_area", "normal_iterations", "tangential_iterations"):
        assert np.shape(r.info[key]) == (2,)
    single = wr.creep_forces(hc[0], (-1e-3, 0, 0), MU, method="exact", elements=12)
    assert single.Fx == pytest.approx(r.Fx[0], rel=1e-9)
    f = single.fields
    assert f.px.shape == f.grid.shape and f.adhesion.dtype == bool


def test_non_convergence_reported(patch):
    grid, p = patch
    with pytest.raises(ConvergenceError, match="maxiter"):
        solve_rolling(grid, p, wr.STEEL, (1e-3, 1e-3, 2.0), MU, maxiter=1)
    s = solve_rolling(grid, p, wr.STEEL, (1e-3, 1e-3, 2.0), MU, maxiter=1, on_fail="status")
    assert not s.converged
    r = wr.creep_forces(HC, (1e-3, 1e-3, 2.0), MU, method="exact", elements=12, maxiter=1,
                        on_fail="status")
    assert r.status is Status.NOT_CONVERGED


def test_errors(patch):
    grid, p = patch
    with pytest.raises(NoContactError):
        solve_rolling(grid, np.zeros(grid.shape), wr.STEEL, (1e-3, 0, 0), MU)
    with pytest.raises(InputError, match="pressure"):
        solve_rolling(grid, -p, wr.STEEL, (1e-3, 0, 0), MU)
    with pytest.raises(InputError, match="mu"):
        solve_rolling(grid, p, wr.STEEL, (1e-3, 0, 0), 0.0)
    with pytest.raises(InputError, match="creepage"):
        solve_rolling(grid, p, wr.STEEL, (1e-3, 0), MU)
    with pytest.raises(InputError, match="shape"):
        solve_rolling(grid, p[:-1], wr.STEEL, (1e-3, 0, 0), MU)
    with pytest.raises(InputError, match="exactly one"):
        solve_shift(grid, p, wr.STEEL, MU)
    with pytest.raises(InputError, match="μ·Fn"):
        solve_shift(grid, p, wr.STEEL, MU, force=(1e6, 0.0))
    with pytest.raises(InputError, match="elements"):
        wr.creep_forces(HC, (1e-3, 0, 0), MU, method="exact", elements=2)
    with pytest.raises(InputError, match="does not accept"):
        wr.creep_forces(HC, (1e-3, 0, 0), MU, method="exact", nx=10)


def test_solve_gap_no_contact():
    grid = Grid.from_bounds(-1e-3, 1e-3, -1e-3, 1e-3, 8, 8)
    with pytest.raises(NoContactError):
        wr.solve_gap(grid, np.full(grid.shape, 1e-3), wr.STEEL, penetration=1e-6,
                     creepage=(1e-3, 0, 0), mu=MU)
    with pytest.raises(InputError, match="mu"):
        wr.solve_gap(grid, np.zeros(grid.shape), wr.STEEL, penetration=1e-6, creepage=(1e-3, 0, 0))


def test_gs_and_newton_agree_on_shift(patch):
    grid, p = patch
    a = solve_shift(grid, p, wr.STEEL, MU, shift=(-2e-7, 1e-7), solver="gs", tol=1e-9,
                    maxiter=5000)
    b = solve_shift(grid, p, wr.STEEL, MU, shift=(-2e-7, 1e-7), tol=1e-9)
    assert (a.Fx, a.Fy) == pytest.approx((b.Fx, b.Fy), rel=1e-6)
    np.testing.assert_array_equal(a.adhesion, b.adhesion)
