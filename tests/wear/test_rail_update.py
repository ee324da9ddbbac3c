"""The wear loop with ``update_rail=True``: the rails wear too and the next step runs on them.

Same bogie and 300 m right-hand curve as tests/wear/test_loop.py (tests/wear/_wear_case.py).
Known behaviour (Enblom & Berg, Wear 258 (2005) 1055–1063; Braghin et al., Wear 261
(2006) 1253–1264): the outer (left) rail wears at its gauge corner, the inner one on
the crown and less; material is only removed. The step control takes the
largest depth change of wheels and rails: with a traffic ratio that makes the
rail wear fastest, every full step removes ``step_depth`` at the rail's most-worn
point (its height change is that depth × √(1 + z'²), between 1 and 3 times it).
"""

import numpy as np
import pytest
from _wear_case import KW, r300_case

import wheelrail as wr
from wheelrail.errors import InputError

STEP = 0.05e-3


@pytest.fixture(scope="module")
def case():
    return r300_case()


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
