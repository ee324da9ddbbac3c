"""Observed order of convergence of the grid normal solver towards Hertz.

Reference: Hertz theory (Johnson 1985, eqs. 3.64–3.66). Piecewise-constant
elements with collocation at the centres: the integral quantities (approach for
a prescribed load, load for a prescribed approach) converge at an order
between 1 and 2 (the √-singular edge of the pressure limits it below 2).
"""

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.normal.bem import hertz_grid, solve_normal

STEEL = wr.Material(2.1e11, 0.28)
LOAD = 10e3
ELEMENTS = (20, 40, 80)


def _order(h, err):
    return np.polyfit(np.log(h), np.log(err), 1)[0]


@pytest.mark.parametrize("aspect", [1.0, 0.5])
def test_order_of_convergence(aspect):
    hc = wr.hertz_from_semiaxes(aspect * 5e-3, 5e-3, LOAD, STEEL)
    h, e_delta, e_load, e_p0 = [], [], [], []
    for n in ELEMENTS:
        grid, h0 = hertz_grid(hc, elements=n)
        by_load = solve_normal(grid, h0, STEEL, Fn=LOAD)
        by_pen = solve_normal(grid, h0, STEEL, penetration=hc.penetration)
        h.append(1.0 / n)
        e_delta.append(abs(by_load.penetration / hc.penetration - 1))
        e_load.append(abs(by_pen.Fn / hc.Fn - 1))
        e_p0.append(abs(by_load.p_max / hc.p0 - 1))
    # errors decrease monotonically
    for e in (e_delta, e_load, e_p0):
        assert e[0] > e[1] > e[2]
    q_delta, q_load, q_p0 = _order(h, e_delta), _order(h, e_load), _order(h, e_p0)
    assert 1.0 < q_delta < 2.5, q_delta
    assert 1.0 < q_load < 2.5, q_load
    assert 1.5 < q_p0 < 3.0, q_p0
    assert e_delta[-1] < 1e-3 and e_load[-1] < 1e-3 and e_p0[-1] < 1e-3
