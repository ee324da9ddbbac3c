"""The wear loop with ``update_rail=True``: the rails wear too and the next step runs on them.

Same bogie and 300 m right-hand curve as tests/wear/test_loop.py. Known behaviour
(Enblom & Berg, Wear 258 (2005) 1055–1063; Braghin et al., Wear 261 (2006)
1253–1264): the outer (left) rail wears at its gauge corner, the inner one on
the crown and less; material is only removed. The step control takes the
largest depth change of wheels and rails: with a traffic ratio that makes the
rail wear fastest, every full step removes ``step_depth`` at the rail's most-worn
point (its height change is that depth × √(1 + z'²), between 1 and 3 times it).
"""

import numpy as np
import pytest

import wheelrail as wr
from wheelrail import dynamics as dy
from wheelrail.dynamics import BogieModel, Suspension
from wheelrail.errors import InputError

G = 9.81
STEP = 0.05e-3
KW = dict(law="usfd", executor="serial", samples=10, cells=8, conicity=False, profiles="sides")


@pytest.fixture(scope="module")
def case():
    ws = wr.Wheelset(wr.profiles.load("S1002"))
    tr = wr.Track(wr.profiles.load("60E1"))
    prim = Suspension(kx=31.391e6, ky=3.884e6, kz=1.22e6, cx=15e3, cy=2e3, cz=4e3,
                      half_spacing=1.0)
    sec = Suspension(kx=0.16e6, ky=0.16e6, kz=0.43e6, cy=32e3, cz=20e3, half_spacing=1.0)
    bogie = BogieModel(ws, 1813.0, (1120.0, 112.0, 1120.0), prim, 2615.0,
                       (1722.0, 1476.0, 3067.0), 1.28, sec,
                       axle_load=(32000.0 / 4 + 2615.0 / 2 + 1813.0) * G, spin="fixed")
    lay = dy.TrackLayout(tr, curves=(dy.Curve(radius=300.0, start=5.0, transition=20.0,
                                              cant=0.1, direction="right"),))
    route = wr.wear.Route((wr.wear.RouteCase(lay, 15.0, distance=5.0, run_in=30.0,
                                             name="R300"),))
    return bogie, route


@pytest.fixture(scope="module")
def run(case, tmp_path_factory):
    bogie, route = case
    store = tmp_path_factory.mktemp("railwear")
    res = wr.wear.evolve(bogie, route, mileage=3e3, step_depth=STEP, update_rail=True,
                         rail_passages=1.0, store=store, **KW)
    return res, store


def test_rails_wear_at_the_outer_gauge_corner(run):
    d = run[0].dataset
    assert d.sizes["step"] >= 3
    dz = (d.rail_z.isel(step=-1) - d.rail_z.isel(step=0)).values[0]   # (side, y_rail)
    assert np.all(dz <= 1e-15)                                          # only removed
    y = d.y_rail.values
    assert y[np.argmin(dz[0])] < -0.02                  # outer (left) rail: gauge corner
    assert -dz[0].sum() > -dz[1].sum()                  # the inner rail wears less
    assert -dz.min() > 1e-6


def test_rail_controls_the_step(run):
    d = run[0].dataset
    rz = d.rail_z.values[:, 0]                          # (step, side, y_rail)
    wz = d.wheel_z.values
    for k in range(1, d.sizes["step"] - 1):             # full steps (the last: the remainder)
        rail_change = np.max(rz[k - 1] - rz[k])
        assert STEP * (1 - 1e-9) <= rail_change <= 3 * STEP
        assert np.max(wz[k] - wz[k - 1]) < rail_change  # the wheels changed less


def test_resume_with_rails_and_default_keeps_rails(case, run):
    bogie, route = case
    res, store = run
    again = wr.wear.evolve(bogie, route, mileage=3e3, step_depth=STEP, update_rail=True,
                           rail_passages=1.0, store=store, **KW)
    np.testing.assert_array_equal(again.dataset.rail_z.values, res.dataset.rail_z.values)
    with pytest.raises(InputError, match="rail_passages"):
        wr.wear.evolve(bogie, route, mileage=3e3, update_rail=True, **KW)
