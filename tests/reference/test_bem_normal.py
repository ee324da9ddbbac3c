"""Normal contact on a grid (Polonsky–Keer BEM) against Hertz's closed form.

Reference: Hertz theory, Johnson, *Contact Mechanics* (1985) eqs. (3.64)–(3.66)
(implemented independently in wheelrail.normal.hertz, itself checked against
Table 2 of seed 003).
"""

import warnings

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.errors import ConvergenceError, InputError, NoContactError
from wheelrail.normal.bem import ContactTruncatedWarning, hertz_grid, solve_normal
from wheelrail.halfspace import Grid, InfluenceOperator
from wheelrail.results import Status

STEEL = wr.Material(2.1e11, 0.28)
LOAD = 10e3


def semi_axes_from_pressure(sol):
    """Semi-axes from the pressure along the two central lines: p² = p0²(1 − x²/a²) fitted.

    The elliptic edge behaviour p ∝ √(distance) is generic for smooth
    non-conforming contacts; the fit uses only the computed element pressures.
    """
    g, p = sol.grid, sol.pressure
    ix, iy = np.argmin(np.abs(g.x)), np.argmin(np.abs(g.y))

    def fit(coord, prof):
        m = prof > 0
        slope, icpt = np.polyfit(coord[m] ** 2, prof[m] ** 2, 1)
        return np.sqrt(-icpt / slope)

    return fit(g.x, p[:, iy]), fit(g.y, p[ix, :])


@pytest.mark.parametrize("aspect", [1.0, 0.5, 2.0])
def test_hertz_load_control(aspect):
    b = 4e-3
    hc = wr.hertz_from_semiaxes(aspect * b, b, LOAD, STEEL)
    grid, h0 = hertz_grid(hc, elements=60)
    sol = solve_normal(grid, h0, STEEL, Fn=LOAD)
    assert sol.status is Status.CONVERGED and not sol.truncated
    assert sol.Fn == pytest.approx(LOAD, rel=1e-12)
    assert sol.p_max == pytest.approx(hc.p0, rel=0.01)
    assert sol.penetration == pytest.approx(hc.penetration, rel=0.01)
    a, bb = semi_axes_from_pressure(sol)
    assert a == pytest.approx(hc.a, rel=0.01)
    assert bb == pytest.approx(hc.b, rel=0.01)
    assert sol.area == pytest.approx(hc.area, rel=0.015)
    # pressure field close to the Hertz ellipsoid everywhere (relative to p0)
    ref = hc.pressure(grid.X, grid.Y)
    assert np.max(np.abs(sol.pressure - ref)) < 0.05 * hc.p0
    # complementarity
    assert sol.residual < 1e-6
    assert np.all(sol.pressure >= 0)
    assert np.all(sol.gap[~sol.contact] >= -1e-6 * hc.penetration)
    x, y = sol.centroid
    assert abs(x) < 1e-9 and abs(y) < 1e-9


def test_hertz_penetration_control_dissimilar_materials():
    """Prescribed approach, wheel and rail of different steels (Hertz depends on E* only)."""
    pair = wr.MaterialPair(wr.Material(2.1e11, 0.28), wr.Material(1.7e11, 0.30))
    hc = wr.hertz(LOAD, A=1.0 / 0.92, B=1.0 / 0.6, material=pair)
    grid, h0 = hertz_grid(hc, elements=60)
    sol = solve_normal(grid, h0, pair, penetration=hc.penetration)
    assert sol.penetration == hc.penetration
    assert sol.Fn == pytest.approx(LOAD, rel=0.01)
    assert sol.p_max == pytest.approx(hc.p0, rel=0.01)
    # consistency of the two controls on the same grid
    sol2 = solve_normal(grid, h0, pair, Fn=sol.Fn, operator=InfluenceOperator(grid, pair))
    assert sol2.penetration == pytest.approx(hc.penetration, rel=1e-6)
    assert np.max(np.abs(sol2.pressure - sol.pressure)) < 1e-5 * sol.p_max


def test_outline_of_circular_contact():
    hc = wr.hertz(LOAD, A=1.0, B=1.0, material=STEEL)
    grid, h0 = hertz_grid(hc, elements=40)
    sol = solve_normal(grid, h0, STEEL, Fn=LOAD)
    polys = sol.outline()
    assert len(polys) == 1
    poly = polys[0]
    assert np.all(poly[0] == poly[-1])
    r = np.hypot(poly[:, 0], poly[:, 1])
    # the outline runs between contact and free elements: within one element of r = a
    assert np.all(np.abs(r - hc.a) < 1.5 * grid.dx)
    x, y = poly[:, 0], poly[:, 1]
    area = abs(np.dot(x[:-1], y[1:]) - np.dot(x[1:], y[:-1])) / 2
    # marching squares cuts the staircase corners: close to the cell area and to pi a^2
    assert area == pytest.approx(sol.area, rel=0.01)
    assert area == pytest.approx(hc.area, rel=0.03)


def test_two_separate_contacts_give_two_outlines():
    grid = Grid.from_bounds(-4e-3, 4e-3, -2e-3, 2e-3, 64, 32)
    X, Y = grid.X, grid.Y
    h0 = np.minimum((X - 2e-3) ** 2 + Y**2, (X + 2e-3) ** 2 + Y**2) * 1.0
    sol = solve_normal(grid, h0, STEEL, Fn=2e3)
    assert len(sol.outline()) == 2
    # symmetric problem: equal halves
    left = sol.pressure[: 32].sum()
    right = sol.pressure[32:].sum()
    assert left == pytest.approx(right, rel=1e-6)


# --------------------------------------------------------------------------- errors
def test_no_contact_raises():
    hc = wr.hertz(LOAD, A=1.0, B=1.0, material=STEEL)
    grid, h0 = hertz_grid(hc, elements=10)
    with pytest.raises(NoContactError, match="penetration"):
        solve_normal(grid, h0 + 1e-6, STEEL, penetration=0.0)


@pytest.mark.parametrize("load", [0.0, -5.0, np.nan])
def test_bad_load_raises(load):
    grid, h0 = hertz_grid(wr.hertz(LOAD, 1.0, 1.0, STEEL), elements=10)
    with pytest.raises(InputError, match="Fn"):
        solve_normal(grid, h0, STEEL, Fn=load)


def test_argument_errors():
    grid, h0 = hertz_grid(wr.hertz(LOAD, 1.0, 1.0, STEEL), elements=10)
    with pytest.raises(InputError, match="exactly one"):
        solve_normal(grid, h0, STEEL)
    with pytest.raises(InputError, match="exactly one"):
        solve_normal(grid, h0, STEEL, Fn=1.0, penetration=1e-5)
    with pytest.raises(InputError, match="shape"):
        solve_normal(grid, h0[:-1], STEEL, Fn=LOAD)
    with pytest.raises(InputError, match="on_fail"):
        solve_normal(grid, h0, STEEL, Fn=LOAD, on_fail="ignore")


def test_window_too_small_warns_and_flags():
    hc = wr.hertz(LOAD, A=1.0, B=1.0, material=STEEL)
    grid = Grid.from_bounds(-0.8 * hc.a, 0.8 * hc.a, -0.8 * hc.b, 0.8 * hc.b, 30, 30)
    h0 = grid.X**2 + grid.Y**2
    with pytest.warns(ContactTruncatedWarning, match="edge"):
        sol = solve_normal(grid, h0, STEEL, Fn=LOAD)
    assert sol.truncated
    # a proper window does not warn
    grid, h0 = hertz_grid(hc, elements=20)
    with warnings.catch_warnings():
        warnings.simplefilter("error", ContactTruncatedWarning)
        assert not solve_normal(grid, h0, STEEL, Fn=LOAD).truncated


def test_non_convergence():
    grid, h0 = hertz_grid(wr.hertz(LOAD, 1.0, 2.0, STEEL), elements=30)
    with pytest.raises(ConvergenceError, match="did not converge"):
        solve_normal(grid, h0, STEEL, Fn=LOAD, maxiter=3)
    sol = solve_normal(grid, h0, STEEL, Fn=LOAD, maxiter=3, on_fail="status")
    assert sol.status is Status.NOT_CONVERGED and sol.iterations == 3
    assert sol.info["change"] > 1e-8
    assert sol.Fn == pytest.approx(LOAD)


def test_hertz_grid_layout():
    hc = wr.hertz_from_semiaxes(6e-3, 3e-3, LOAD, STEEL)
    grid, h0 = hertz_grid(hc, elements=20, margin=1.25)
    assert grid.dx == pytest.approx(2 * hc.a / 20) and grid.dy == pytest.approx(2 * hc.b / 20)
    assert grid.nx == grid.ny == 25 and grid.x[12] == pytest.approx(0.0, abs=1e-15)
    assert grid.bounds[1] >= 1.25 * hc.a
    assert np.allclose(h0, hc.A * grid.X**2 + hc.B * grid.Y**2)
    with pytest.raises(InputError, match="margin"):
        hertz_grid(hc, margin=0.9)
    with pytest.raises(InputError, match="elements"):
        hertz_grid(hc, elements=1)


@pytest.mark.parametrize("factor", [0.9, 0.98, 1.02, 1.3])
def test_warm_start_from_another_load_gives_the_same_solution(factor):
    """A start pressure carrying another load (a previous pass of a load iteration) must not
    change the solution: the discrete Signorini problem has one solution."""
    hc = wr.hertz(1e4, 1.0, 2.0, wr.STEEL)
    grid, gap = hertz_grid(hc, elements=30)
    first = solve_normal(grid, gap, wr.STEEL, Fn=1e4)
    cold = solve_normal(grid, gap, wr.STEEL, Fn=1e4 * factor)
    warm = solve_normal(grid, gap, wr.STEEL, Fn=1e4 * factor, initial=first.pressure)
    assert np.array_equal(cold.contact, warm.contact)
    np.testing.assert_allclose(warm.pressure, cold.pressure, rtol=0, atol=1e-6 * cold.p_max)
