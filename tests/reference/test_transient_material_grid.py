"""Transient rolling on a grid fixed to the rail (``discretisation="material"``).

References: Kalker's steady exact solver ``solve_rolling`` (Table 1 contact of
seed 001, ξ = −5.6e-4, μ = 0.4). With V·Δt = dx the window moves one element
per step and the material-grid scheme is Kalker's discretisation (measured
Fx 0.06 % from solve_rolling on the same 10-element grid, the normal problem
being re-solved every step). With V·Δt = dx/3.7 the force held steady
oscillates with period dx/h steps (range 9 N) about a mean within 0.1 % of
the steady solver on 60 elements (measured 1961.7 N against 1959.7 N); on
the moving grid the same 10 elements give 2064.9 N (+5.4 %).
"""

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.tangential.exact import solve_rolling
from wheelrail.normal.bem import hertz_grid, solve_normal

XI = -5.6e-4


@pytest.fixture(scope="module")
def hc():
    return wr.hertz_from_radii(10e3, 0.5, -0.409, 0.3, material=wr.STEEL)


def _steady(hc, n, margin=1.25):
    grid, gap = hertz_grid(hc, elements=n, margin=margin)
    pn = solve_normal(grid, gap, wr.STEEL, Fn=1e4).pressure
    return grid, solve_rolling(grid, pn, wr.STEEL, (XI, 0.0, 0.0), mu=0.4).Fx


def test_material_grid_with_step_dx_is_kalkers_scheme(hc):
    grid, ref = _steady(hc, 10)
    r = wr.transient_rolling(hc, travel=10 * float(hc.a), step=grid.dx, mu=0.4,
                             creepage=(XI, 0.0, 0.0), elements=10, discretisation="material",
                             frames=2)
    assert r.Fx[-1] == pytest.approx(ref, rel=2e-3)
    assert r.Fn[1:] == pytest.approx(1e4, rel=1e-6)


def test_material_grid_small_step_oscillates_about_the_fine_steady_solution(hc):
    grid, _ = hertz_grid(hc, elements=10)
    _, fine = _steady(hc, 60, margin=1.1)
    h = grid.dx / 3.7
    r = wr.transient_rolling(hc, travel=10 * float(hc.a), step=h, mu=0.4,
                             creepage=(XI, 0.0, 0.0), elements=10, discretisation="material",
                             frames=2)
    last = r.Fx[-16:]  # four periods of dx/h = 3.7 steps
    assert np.ptp(last) > 0  # the contact moves over the rail-fixed elements
    assert np.ptp(last) < 0.01 * fine
    assert last.mean() == pytest.approx(fine, rel=0.01)
