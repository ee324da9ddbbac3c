"""Dissimilar materials (K ≠ 0): free rolling of steel on aluminium rollers.

Bentall & Johnson (1967) showed that two elastically dissimilar cylinders
rolling freely (zero tangential force) have a non-zero creepage, because the
pressure induces different tangential surface strains in the two bodies
(Johnson, *Contact Mechanics* 1985, §8.3; Kalker 1990 §1.6: the coupling is
proportional to the difference parameter K). For the line contact the
pressure-induced strain is ∂u_x/∂x = −(2K/G) p(x) (the 3-D kernel −K x/(πG r²)
integrated along y), so the stick condition reads ∂u_x(q)/∂x = ξ + (2K/G)p.
A traction bounded at both edges exists only if ∫ (ξ + 2Kp/G)/√(a² − x²) dx = 0,
i.e. ξ∞ = −4 K p0 / (π G): the free-rolling creep of large friction is of that
size and sign, and it changes sign when the bodies are exchanged.

References: R.H. Bentall, K.L. Johnson, Slip in the rolling contact of two
dissimilar elastic rollers, Int. J. Mech. Sci. 9 (1967) 389–404.
"""

import numpy as np
import pytest
from scipy.optimize import brentq

import wheelrail as wr
from wheelrail.halfspace import Grid
from wheelrail.tangential.exact import solve_rolling
from wheelrail.normal.bem import hertz_grid
from wheelrail.tangential.exact import solve_gap

STEEL = wr.Material(2.1e11, 0.28)
ALU = wr.Material(7.0e10, 0.33)
A = 1e-3
P0 = 3e8


def _free_rolling_creepage(pair, mu):
    grid = Grid.from_bounds(-A, A, -20 * A, 20 * A, 30, 21)
    p = P0 * np.sqrt(np.clip(1 - (grid.X / A) ** 2, 0, None))
    j = grid.ny // 2

    def fx(xi):
        return solve_rolling(grid, p, pair, (xi, 0.0, 0.0), mu).px[:, j].sum()

    scale = 10 * abs(4 * pair.K * P0 / (np.pi * pair.G))
    return brentq(fx, -scale, scale, xtol=1e-12)


@pytest.mark.parametrize("wheel, rail", [(STEEL, ALU), (ALU, STEEL)])
def test_free_rolling_creepage(wheel, rail):
    pair = wr.MaterialPair(wheel, rail)
    assert pair.K != 0
    xi_free = _free_rolling_creepage(pair, 0.3)
    estimate = -4 * pair.K * P0 / (np.pi * pair.G)
    assert np.sign(xi_free) == np.sign(estimate)
    assert 0.85 < xi_free / estimate < 1.05


def test_identical_bodies_roll_freely_at_zero_creepage():
    grid = Grid.from_bounds(-A, A, -20 * A, 20 * A, 30, 21)
    p = P0 * np.sqrt(np.clip(1 - (grid.X / A) ** 2, 0, None))
    sol = solve_rolling(grid, p, STEEL, (0.0, 0.0, 0.0), 0.3)
    assert np.abs(sol.px).max() == 0.0 and sol.Fx == 0.0
    # ... while dissimilar bodies at zero creepage transmit a force
    dis = solve_rolling(grid, p, wr.MaterialPair(STEEL, ALU), (0.0, 0.0, 0.0), 0.3)
    assert abs(dis.Fx) > 1e-3 * 0.3 * p.sum() * grid.element_area


def test_panagiotopoulos_loop_converges_and_changes_pressure():
    pair = wr.MaterialPair(STEEL, ALU)
    hc = wr.hertz(2e3, A=5.0, B=5.0, material=pair)
    grid, gap = hertz_grid(hc, elements=20, margin=1.2)
    sol = solve_gap(grid, gap, pair, Fn=2e3, creepage=(1e-3, 0.0, 0.0), mu=0.3)
    assert sol.outer_iterations >= 2
    assert sol.outer_change <= 1e-5
    assert sol.Fn == pytest.approx(2e3, rel=1e-6)
    # quasi-identical bodies need a single pass (Johnson's process)
    same = solve_gap(grid, gap, STEEL, Fn=2e3, creepage=(1e-3, 0.0, 0.0), mu=0.3)
    assert same.outer_iterations == 1


def test_exact_method_dissimilar_force_at_zero_creepage():
    """3-D Hertz contact through wr.creep_forces: at zero creepage the force has the sign
    of the strip result above (F ≈ −k (ξ − ξ_free), ξ_free ∝ −K)."""
    pair = wr.MaterialPair(STEEL, ALU)          # K < 0 -> ξ_free > 0 -> Fx(0) > 0
    hc = wr.hertz(2e3, A=5.0, B=5.0, material=pair)
    r = wr.creep_forces(hc, (0.0, 0.0, 0.0), 0.3, method="exact", elements=16)
    assert pair.K < 0 and r.Fx > 0
    assert r.info["outer_iterations"] >= 2
    swapped = wr.creep_forces(wr.hertz(2e3, A=5.0, B=5.0, material=wr.MaterialPair(ALU, STEEL)),
                              (0.0, 0.0, 0.0), 0.3, method="exact", elements=16)
    assert swapped.Fx == pytest.approx(-r.Fx, rel=1e-3)
