"""The wear loop on the whole vehicle (``wr.dynamics.manchester_vehicle1()``: a car body on
two bogies, four wheelsets; Iwnicki, Vehicle System Dynamics 30 (1998) 295–313).

Known behaviour of curving wear (Jendel, Wear 253 (2002) 89–99; Braghin et al., Wear 261
(2006) 1253–1264): in a tight curve the leading wheelset of each bogie runs with a large
angle of attack against the outer rail, so the outer wheel of the vehicle's leading
wheelset wears most, on its flange side, the trailing wheelsets much less. The case of
tests/wear/_wear_case.py (300 m, 100 mm cant, 15 m/s) with the vehicle instead of a bogie.
"""

import numpy as np
import pytest
from _wear_case import KW, r300_case

import wheelrail as wr
from wheelrail import dynamics as dy
from wheelrail.cli.wear import read_wear_case
from wheelrail.errors import CaseFileError, InputError
from wheelrail.wear import loop


@pytest.fixture(scope="module")
def vehicle():
    return dy.manchester_vehicle1()


@pytest.fixture(scope="module")
def route():
    return r300_case()[1]


@pytest.fixture(scope="module")
def lead(vehicle, route):
    # the leading wheelset's wear sets the profiles (the declared grouping)
    return wr.wear.evolve(vehicle, route, mileage=10e3, step_depth=0.05e-3, wheelsets=(0,),
                          **KW)


def test_leading_outer_wheel_wears_most(lead):
    d = lead.dataset
    assert d.sizes["wheelset"] == 4 and d.sizes["step"] >= 3
    total = d.wear_rate.isel(step=0, case=0).sum("y").values        # (wheelset, side)
    # right-hand curve: the outer wheel is the left one (side 0)
    assert np.unravel_index(np.argmax(total), total.shape) == (0, 0)
    # each bogie's leading wheelset wears more than its trailing one (outer wheels)
    assert total[0, 0] > 2 * total[1, 0] and total[2, 0] > 2 * total[3, 0]
    # on the flange side of the tape circle, and the outer flange thins, the inner much less
    rate = d.wear_rate.isel(step=0, case=0, wheelset=0, side=0).values
    assert d.y.values[np.argmax(rate)] < -0.02
    sd = d.Sd.values
    assert sd[-1, 0] < sd[0, 0] - 1e-6
    assert sd[0, 0] - sd[-1, 0] > 5 * abs(sd[0, 1] - sd[-1, 1])
    # the CPU time of each case, per step, adds up to the step's
    np.testing.assert_allclose(d.cpu_per_case.sum("case"), d.case_cpu, rtol=1e-12)


def test_grouping_selects_the_wear_that_updates_the_profile(vehicle, route, lead):
    # all four wheelsets averaged: the same first-step rates, a smaller flange wear per km
    # (the trailing wheelsets dilute it) -> the left profile's depth is the mean of the four
    both = wr.wear.evolve(vehicle, route, mileage=2e3, step_depth=1.0, **KW)
    d = both.dataset
    rate = d.wear_rate.isel(step=0, case=0).values                   # (wheelset, side, y)
    np.testing.assert_allclose(rate, lead.dataset.wear_rate.isel(step=0, case=0).values,
                               rtol=1e-9, atol=0)
    depth = (d.wheel_z[-1] - d.wheel_z[0]).values[0]
    slope = np.sqrt(1 + vehicle.wheelset.wheel.slope(d.y.values) ** 2)
    expect = loop._smooth(rate.mean(axis=0)[0], 0.25e-3, 2e-3) * 2e3 * slope
    np.testing.assert_allclose(depth, expect, rtol=1e-6, atol=1e-12)
    with pytest.raises(InputError, match="wheelsets"):
        wr.wear.evolve(vehicle, route, mileage=1e3, wheelsets=(4,), **KW)


def test_vehicle_resume(vehicle, route, lead, tmp_path, monkeypatch):
    calls = {"n": 0}
    real = loop._case_wear

    def dying(*args):
        calls["n"] += 1
        if calls["n"] == 2:
            raise KeyboardInterrupt("killed")
        return real(*args)

    kw = dict(KW, mileage=10e3, step_depth=0.05e-3, wheelsets=(0,), store=tmp_path)
    monkeypatch.setattr(loop, "_case_wear", dying)
    with pytest.raises(KeyboardInterrupt):
        wr.wear.evolve(vehicle, route, **kw)
    assert len(list(tmp_path.glob("step_*.npz"))) == 1
    calls["n"] = 0
    monkeypatch.setattr(loop, "_case_wear", lambda *a: (calls.__setitem__("n", calls["n"] + 1),
                                                        real(*a))[1])
    res = wr.wear.evolve(vehicle, route, **kw)
    assert calls["n"] == lead.dataset.sizes["step"] - 1               # nothing repeated
    np.testing.assert_allclose(res.dataset.wheel_z.values, lead.dataset.wheel_z.values,
                               rtol=0, atol=1e-9)
    # the resumed vehicle runs on the worn profiles: every wheelset on the same one
    m = loop._with_profiles(vehicle, res.profiles[-1]["left"], res.profiles[-1]["right"])
    assert isinstance(m, dy.VehicleModel) and m.bogies[0].wheelset is m.bogies[1].wheelset
    assert m.wheelset.wheel is res.profiles[-1]["left"]


CASE = """
[model]
kind = "vehicle"
vehicle = "manchester1"
[[route.cases]]
name = "R300"
speed = 15.0
radius = 300.0
cant = 0.1
run_in = 30.0
distance = 5.0
[wear]
law = "usfd"
mileage = 10e3
profiles = "sides"
wheelsets = [0]
executor = "serial"
"""


def test_case_file_vehicle():
    case = read_wear_case(CASE)
    assert isinstance(case["model"], dy.VehicleModel)
    assert case["model"].n_wheelsets == 4 and case["evolve"]["wheelsets"] == (0,)
    with pytest.raises(CaseFileError, match="wheelsets"):
        read_wear_case(CASE.replace("wheelsets = [0]", "wheelsets = [4]"))
