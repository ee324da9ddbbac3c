"""Paul–Hashemi discretisation (seed 001 Fig. 2; Paul & Hashemi 1981) for transient rolling.

Reference: Kalker's steady exact solver (``solve_rolling``) on a fine uniform
grid (60 elements over 2a), Table 1 contact of seed 001, ξ = −5.6e-4; the
strip runs are held at constant creepage until steady (10 semi-axes).
Measured Fx errors 5.5 %, 3.2 %, 2.1 % for 8, 12, 16 elements per strip (as
many strips), fitted order 1.4; the uniform grid gives 3.9 %, 4.0 %, 2.6 %
(not monotone).
"""

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.tangential.exact import solve_rolling
from wheelrail.normal.bem import hertz_grid, solve_normal
from wheelrail.transient.strips import hertz_pressure, strip_grid

XI = -5.6e-4


@pytest.fixture(scope="module")
def hc():
    return wr.hertz_from_radii(10e3, 0.5, -0.409, 0.3, material=wr.STEEL)


def test_strips_cover_the_ellipse_with_equal_counts(hc):
    a, b = float(hc.a), float(hc.b)
    sg = strip_grid(hc, elements=12, strips=30)
    assert sg.shape == (12, 30)
    # each strip spans its chord at the strip centre exactly, in equal elements
    chord = a * np.sqrt(1 - (sg.y / b) ** 2)
    assert np.allclose(sg.X[0] - sg.dx / 2, -chord) and np.allclose(sg.X[-1] + sg.dx / 2, chord)
    # midpoint-rule area of the ellipse (30 strips: within 0.5 %)
    assert float(sg.area.sum()) == pytest.approx(np.pi * a * b, rel=5e-3)
    pn = hertz_pressure(hc, sg, 1e4)
    assert float((pn * sg.area).sum()) == pytest.approx(1e4, rel=1e-12)
    assert pn.max() == pytest.approx(float(hc.p0), rel=0.02)


def test_strips_converge_to_the_steady_exact_solver(hc):
    grid, gap = hertz_grid(hc, elements=60, margin=1.1)
    pn = solve_normal(grid, gap, wr.STEEL, Fn=1e4).pressure
    ref = solve_rolling(grid, pn, wr.STEEL, (XI, 0.0, 0.0), mu=0.4).Fx
    a = float(hc.a)
    ns = np.array([8, 12, 16])
    err = []
    for n in ns:
        r = wr.transient_rolling(hc, travel=10 * a, step=a / n, mu=0.4, creepage=(XI, 0.0, 0.0),
                                 elements=n, discretisation="strips", frames=2)
        assert r.Fn[-1] == pytest.approx(1e4, rel=1e-12)
        err.append(abs(r.Fx[-1] / ref - 1))
    order = np.polyfit(np.log(1.0 / ns), np.log(err), 1)[0]
    assert 1.0 < order < 2.0, (order, err)
    assert err[-1] < 0.025


def test_strips_force_control_and_refusals(hc):
    r = wr.transient_rolling(hc, travel=1e-3, step=2.5e-4, mu=0.4, Fx=2000.0,
                             elements=8, strips=6, discretisation="strips", frames=2)
    assert r.Fx[1:] == pytest.approx(2000.0, rel=1e-6)
    assert r.grid.shape == (8, 6) and r.fields.X.shape == (8, 6)
    from wheelrail.cases.files import load_transient_case
    from wheelrail.transient.plot import plot_centreline, plot_state

    assert plot_state(r, 1e-3).axes and plot_centreline(r).axes
    case = load_transient_case("""
[contact]
Fn = 10000.0
wheel_rolling_radius = 0.5
wheel_profile_radius = -0.409
rail_profile_radius = 0.3
[friction]
mu = 0.4
[transient]
travel = 1e-3
step = 2.5e-4
elements = 8
strips = 6
frames = 2
discretisation = "strips"
Fx = 2000.0
""")
    assert case.run().xi == pytest.approx(r.xi, rel=1e-9)
    with pytest.raises(wr.InputError, match="constant Fn"):
        wr.transient_rolling(hc, travel=1e-3, step=2.5e-4, mu=0.4, Fx=2000.0,
                             elements=8, discretisation="strips",
                             Fn=lambda x: 1e4 + x)
    with pytest.raises(wr.InputError, match="discretisation must be"):
        wr.transient_rolling(hc, travel=1e-3, step=2.5e-4, mu=0.4, Fx=2000.0,
                             elements=8, discretisation="hexagons")
