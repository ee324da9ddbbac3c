"""Seed 001 §3.1 creepage history under V·Δt refinement on a fixed 10-element grid.

Reference: the run with V·Δt = dx/16 (self-convergence); the observed order is
fitted with np.polyfit on log h / log error (measured ≈ 1.2: the backward
difference in time of eq. 2.10 is first order).
"""

import numpy as np

import wheelrail as wr
from wheelrail.normal.bem import hertz_grid


def test_creepage_history_converges_in_the_time_step():
    hc = wr.hertz_from_radii(10e3, 0.5, -0.409, 0.3, material=wr.STEEL)
    n = 10
    grid, _ = hertz_grid(hc, elements=n)
    dx = grid.dx
    xi = {}
    for m in (1, 2, 4, 16):
        r = wr.transient_rolling(hc, travel=8 * dx, step=dx / m, mu=0.4,
                                 tangential_force=2000.0, elements=n, frames=2)
        xi[m] = r.xi[::m]  # at x = 0, dx, 2dx, ... (common travels)
    ref = xi[16]
    hs = np.array([dx, dx / 2, dx / 4])
    err = np.array([np.max(np.abs(xi[m][3:] - ref[3:])) / abs(ref[-1]) for m in (1, 2, 4)])
    order = np.polyfit(np.log(hs), np.log(err), 1)[0]
    assert 0.8 < order < 2.0, (order, err)
    assert err[-1] < 0.05
