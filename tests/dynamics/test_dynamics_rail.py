"""Flexible rails (``RailSupport``): the rail head on two serial spring–dampers.

Independent reference: the static deflection of two springs in series under the wheel's
contact force F (Piotrowski & Chollet 2005, §2.3.3): the head moves F (1/k1 + 1/k2), the
intermediate support point F/k2, vertically under Q and laterally under Y (on the rail:
minus the force on the wheel). A steady run on tangent track must settle there. The
lateral creep forces damp the light rail head (100 kg) far more strongly than the
wheelset, so the fixed step is divided for it; before the creep-rate estimate included
the rail heads, RK4 at 1 ms left the lateral head oscillating about its equilibrium at
the rail's natural frequency with an amplitude several times the deflection.
"""

import warnings

import numpy as np
import pytest

import wheelrail as wr

D = wr.dynamics


@pytest.fixture(scope="module")
def settled():
    ws, tr = wr.Wheelset(wr.profiles.load("S1002")), wr.Track(wr.profiles.load("60E1"))
    rail = D.RailSupport()
    model = D.WheelsetModel(ws, 1500.0, (800.0, 100.0, 800.0), axle_load=100e3, rail=rail)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        res = D.simulate(model, tr, 20.0, 0.3, "hertz", "fastsim", output_step=0.01)
    return rail, res, [str(w.message) for w in caught]


def test_rail_heads_settle_at_the_series_spring_deflection(settled):
    rail, res, _ = settled
    ds = res.dataset if hasattr(res, "dataset") else res.to_dataset()
    Q = ds["vertical_load"].isel(time=-1, wheelset=0).values          # (side,)
    Fy = ds["wheel_Fy"].isel(time=-1, wheelset=0).values              # track frame, on the wheel
    Y = ds["lateral_force"].isel(time=-1, wheelset=0).values          # on the rail, outwards
    for d, F in ((1, -Q), (0, -Fy)):                # force on the rail = − force on the wheel
        k1, _, k2, _, _ = rail.direction(d)
        head = ds["rail_head"].isel(time=-1, wheelset=0, direction=d).values
        support = ds["rail_support"].isel(time=-1, wheelset=0, direction=d).values
        np.testing.assert_allclose(head, F * (1 / k1 + 1 / k2), rtol=0.01)
        np.testing.assert_allclose(support, F / k2, rtol=0.01)
    # the gravitational stiffness pushes both rails outwards: a real lateral load
    assert np.all(Y > 100.0)


def test_the_rail_heads_creep_damping_divides_the_step(settled):
    _, res, messages = settled
    assert res.info["substeps"] > 1
    assert any("rail head" in m for m in messages), messages
