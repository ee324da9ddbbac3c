"""Transient rolling (seed 001) against the steady exact solver and the shift problem.

References: Baeza et al., seed 001 eqs. (2.10), (2.19) and §3.1 ("Cattaneo to
Carter", Table 1: wheel radius 0.5 m, wheel profile radius −0.409 m, rail crown
radius 0.3 m, F3 = 10 kN, F1 = 2 kN, μ = 0.4, steel); Kalker (1990) §5.2: with
V·Δt = dx the transient discretisation held at constant loads is the steady one.
Reduced grids (10–12 elements over 2a) keep the tests fast.
"""

import numpy as np
import pytest
from scipy.optimize import brentq

import wheelrail as wr
from wheelrail.halfspace.influence import influence_kernel
from wheelrail.tangential.exact import newton_step, solve_rolling, solve_shift
from wheelrail.transient.rolling import shifted_influence_kernel
from wheelrail.normal.bem import hertz_grid, solve_normal

MU = 0.4


@pytest.fixture(scope="module")
def table1():
    return wr.hertz_from_radii(10e3, 0.5, -0.409, 0.3, material=wr.STEEL)


def _steady(hc, n, creepage):
    grid, gap = hertz_grid(hc, elements=n)
    pn = solve_normal(grid, gap, wr.STEEL, Fn=float(hc.Fn)).pressure
    return grid, pn, solve_rolling(grid, pn, wr.STEEL, creepage, mu=MU, tol=1e-10)


def test_constant_creepage_ends_on_steady_rolling(table1):
    n = 12
    grid, pn, st = _steady(table1, n, (-5e-4, 0.0, 0.0))
    res = wr.transient_rolling(table1, travel=20 * float(table1.a), step=grid.dx, mu=MU,
                               creepage=(-5e-4, 0.0, 0.0), elements=n)
    # tractions after 20 semi-axes equal the steady solution (measured 1.6e-6)
    err = np.abs(res.px[-1] - st.px).max() / np.abs(st.px).max()
    assert err < 1e-4
    assert res.Fx[-1] == pytest.approx(st.Fx, rel=1e-5)
    assert res.n_slip[-1] == st.slip.sum()


def test_first_step_is_the_cattaneo_shift(table1):
    # first step from rest: h·s = h·w + C p, the shift problem with W = h·(ξ, η)
    n, h, xi, eta = 10, 2e-4, -4e-4, 2e-4
    res = wr.transient_rolling(table1, travel=2 * h, step=h, mu=MU, creepage=(xi, eta, 0.0),
                               elements=n, scheme="centre")
    grid, gap = hertz_grid(table1, elements=n)
    pn = solve_normal(grid, gap, wr.STEEL, Fn=10e3).pressure
    sh = solve_shift(grid, pn, wr.STEEL, MU, shift=(h * xi, h * eta), tol=1e-10)
    fields = res.fields_at(x=h)
    assert np.allclose(fields.px.values, sh.px, atol=1e-6 * np.abs(sh.px).max())
    assert res.Fy[1] == pytest.approx(sh.Fy, rel=1e-6)


def test_cattaneo_to_carter_final_creepage(table1):
    """Seed §3.1 on 10 elements: final ξ within 1 % of the steady exact solver's."""
    n = 10
    grid, gap = hertz_grid(table1, elements=n)
    pn = solve_normal(grid, gap, wr.STEEL, Fn=10e3).pressure

    def fx(xi):
        return solve_rolling(grid, pn, wr.STEEL, (xi, 0.0, 0.0), mu=MU, tol=1e-10).Fx - 2000.0

    xi_steady = brentq(fx, -3e-3, -1e-5, xtol=1e-12)
    res = wr.transient_rolling(table1, travel=16 * float(table1.a), step=grid.dx, mu=MU,
                               Fx=2000.0, elements=n)
    assert np.allclose(res.Fx[1:], 2000.0, rtol=1e-6)
    assert res.xi[-1] == pytest.approx(xi_steady, rel=0.01)
    # Kalker's convention: a positive force on the wheel needs a negative creepage
    assert xi_steady < 0


def test_centre_scheme_ends_on_its_steady_fixed_point(table1):
    """Seed eq. (2.10) at the centres, V·Δt = dx/2: the run ends on the steady problem
    with kernel (C − C_h)/h (measured 4e-6).

    That steady problem is solved independently (``newton_step`` + brentq on
    the force); it differs from ``solve_rolling`` (h = dx) by the O(h)
    discretisation of the time derivative.
    """
    n = 10
    grid, gap = hertz_grid(table1, elements=n)
    h = grid.dx / 2
    pn = solve_normal(grid, gap, wr.STEEL, Fn=10e3).pressure
    M = (influence_kernel(grid, wr.STEEL)[:2, :2]
         - shifted_influence_kernel(grid, wr.STEEL, h)[:2, :2]) / h

    def fx(xi):
        b = np.zeros((2,) + grid.shape)
        b[0] = xi
        p, _, _, res, _ = newton_step(M, b, MU * pn, tol=1e-10)
        assert res <= 1e-10
        return p[0].sum() * grid.element_area - 2000.0

    xi_h = brentq(fx, -3e-3, -1e-5, xtol=1e-13)
    res = wr.transient_rolling(table1, travel=16 * float(table1.a), step=h, mu=MU,
                               Fx=2000.0, elements=n, scheme="centre")
    assert res.xi[-1] == pytest.approx(xi_h, rel=1e-4)


@pytest.mark.parametrize("m", [2, 3, 5])
def test_averaged_step_kernel_telescopes_to_kalkers_rolling_kernel(m):
    """Held steady, (now − old)/h of the averaged scheme is Kalker's M = (C − C_dx)/dx
    (Kalker 1990 §5.2) exactly for integer dx/h: an independent kernel (rolling_kernel)."""
    from wheelrail.halfspace.grid import Grid
    from wheelrail.halfspace.rolling import rolling_kernel
    from wheelrail.transient.rolling import step_kernels

    g = Grid(0.0, 0.0, 2e-4, 3e-4, 7, 5)
    h = g.dx / m
    now, old = step_kernels(g, wr.STEEL, h, "averaged")
    M = rolling_kernel(g, wr.STEEL)
    assert np.allclose((now - old) / h, M, rtol=1e-9, atol=1e-12 * np.abs(M).max())


def test_seed_time_step_ends_on_the_steady_exact_solver(table1):
    """Seed §3.1 with V·Δt/dx as in the seed (0.05 mm on 30 elements: dx/h = 3.70), on
    12 elements: the interpolated scheme ends on solve_rolling's creepage within 1 %
    (measured 0.12 %); the seed's centre scheme ends 4.1 % off on this grid (measured)."""
    n = 12
    grid, gap = hertz_grid(table1, elements=n)
    pn = solve_normal(grid, gap, wr.STEEL, Fn=10e3).pressure
    xi_st = brentq(lambda xi: solve_rolling(grid, pn, wr.STEEL, (xi, 0.0, 0.0), mu=MU,
                                            tol=1e-10).Fx - 2000.0, -3e-3, -1e-5, xtol=1e-12)
    h = grid.dx / 3.7
    kw = dict(travel=12 * float(table1.a), step=h, mu=MU, Fx=2000.0,
              elements=n, frames=2)
    avg = wr.transient_rolling(table1, scheme="interpolated", **kw)
    assert avg.xi[-1] == pytest.approx(xi_st, rel=0.01)
    centre = wr.transient_rolling(table1, scheme="centre", **kw)
    assert abs(centre.xi[-1] / xi_st - 1) > 0.01  # the defect the averaged scheme removes
