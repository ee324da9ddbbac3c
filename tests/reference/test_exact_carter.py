"""Kalker's exact theory in the two-dimensional limit against Carter (1926).

A strip of length 40a across the rolling direction carries the Hertz line
pressure p0 √(1 − x²/a²), uniform in y; on its centre line the half-space
problem is plane strain to O((a/L)²). Reference: F.W. Carter, Proc. R. Soc.
A 112 (1926) 151–157; Johnson, *Contact Mechanics* (1985) §8.2, eqs.
(8.5)–(8.9) (:mod:`wheelrail.reference`).
"""

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.halfspace import Grid
from wheelrail.tangential.exact import solve_rolling
from wheelrail.reference import (carter_force_per_length, carter_saturation_creepage,
                                 carter_traction)

A = 1e-3
P0 = 5e8
MU = 0.3
MAT = wr.Material(2.1e11, 0.25)


def _strip(nx, ny=21):
    grid = Grid.from_bounds(-A, A, -20 * A, 20 * A, nx, ny)
    p = P0 * np.sqrt(np.clip(1 - (grid.X / A) ** 2, 0, None))
    return grid, p


@pytest.mark.parametrize("frac", [0.2, 0.5, 0.8, -0.5])
def test_traction_and_force(frac):
    grid, p = _strip(40)
    xi = frac * carter_saturation_creepage(MU, P0, MAT.G, MAT.nu)
    sol = solve_rolling(grid, p, MAT, (xi, 0.0, 0.0), MU)
    j = grid.ny // 2
    q = carter_traction(grid.x, A, xi, MU, P0, MAT.G, MAT.nu)
    rms = np.sqrt(np.mean((sol.px[:, j] - q) ** 2)) / (MU * P0)
    assert rms < 0.02
    F = sol.px[:, j].sum() * grid.dx
    assert F == pytest.approx(carter_force_per_length(A, xi, MU, P0, MAT.G, MAT.nu), rel=0.015)
    # stick zone at the leading edge (x > 0), slip at the trailing edge
    stick_x = grid.x[sol.adhesion[:, j]]
    assert stick_x.max() > 0.9 * A
    assert not sol.adhesion[1, j]


def test_full_slip_beyond_saturation():
    grid, p = _strip(20)
    xi = 1.5 * carter_saturation_creepage(MU, P0, MAT.G, MAT.nu)
    sol = solve_rolling(grid, p, MAT, (xi, 0.0, 0.0), MU)
    assert not sol.adhesion.any()
    # every element at the traction bound; the slip is nearly longitudinal
    np.testing.assert_allclose(np.hypot(sol.px, sol.py), MU * p, rtol=1e-9, atol=1e-9 * P0)
    assert sol.Fx == pytest.approx(-MU * p.sum() * grid.element_area, rel=1e-3)


def test_force_converges_first_order():
    xi = 0.5 * carter_saturation_creepage(MU, P0, MAT.G, MAT.nu)
    ref = carter_force_per_length(A, xi, MU, P0, MAT.G, MAT.nu)
    h, err = [], []
    for nx in (20, 40, 80):
        grid, p = _strip(nx)
        sol = solve_rolling(grid, p, MAT, (xi, 0.0, 0.0), MU)
        h.append(grid.dx)
        err.append(abs(sol.px[:, grid.ny // 2].sum() * grid.dx / ref - 1))
    order = np.polyfit(np.log(h), np.log(err), 1)[0]
    assert 0.7 < order < 1.5, (h, err, order)
