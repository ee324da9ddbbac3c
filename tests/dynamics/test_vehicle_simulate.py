"""The whole vehicle in the time domain: compiled fixed-step path against the generic path.

Manchester vehicle 1 (Iwnicki 1998), its leading wheelset released 3 mm off
centre on tangent track at 30 m/s: the compiled RK4 loop (contact of all eight
wheels compiled) and the Python RK4 loop with the library's own contact
evaluation (``contact="generic"``) integrate the same equations; with the same
normal × tangential methods (Hertz + FASTSIM) they agree, and the run's
dataset carries the car body's and frames' states.
"""

from __future__ import annotations

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.dynamics import manchester_vehicle1, simulate


@pytest.fixture(scope="module")
def runs():
    model = manchester_vehicle1()
    track = wr.Track(wr.profiles.load("60E1"))
    kw = dict(normal="hertz", tangential=wr.tangential.Fastsim(nx=10), initial={"ws0.y": 0.003})
    fast = simulate(model, track, 30.0, 0.02, **kw)
    generic = simulate(model, track, 30.0, 0.02, contact="generic", **kw)
    return fast, generic


def test_compiled_and_generic_paths_agree(runs):
    fast, generic = runs
    assert fast.info["contact_path"] != generic.info["contact_path"]
    assert fast.states.shape == generic.states.shape
    for name in ("ws0.y", "ws0.yaw", "ws1.y", "frame0.y", "frame0.yaw", "body.y", "body.roll"):
        a, b = fast.state(name), generic.state(name)
        scale = max(np.max(np.abs(a)), 1e-9)
        assert np.max(np.abs(a - b)) < 1e-3 * scale, name
    # the released wheelset moves back towards the centre; the others hardly move
    y0 = fast.state("ws0.y")
    assert y0[-1] < 0.95 * y0[0]


def test_dataset_has_body_and_frame_states(runs):
    ds = runs[0].dataset
    for name in ("body_y", "body_yaw", "frame0_y", "frame1_pitch"):
        assert name in ds and ds[name].dims == ("time",)
    assert ds["vertical_load"].shape[1:] == (4, 2)
    # every wheel carries its share of the vehicle's weight at the start
    m = manchester_vehicle1()
    np.testing.assert_allclose(ds["vertical_load"].isel(time=0).sum(), m.mass * 9.81,
                               rtol=1e-3)


def test_two_axle_vehicle_runs_and_curves():
    """A two-axle vehicle (wheelsets under the body through the primary) runs in the
    compiled path and in a 400 m curve carries M V²/R on its four wheels (Newton's law,
    0.5 %), its body, on the chord between the axles, m V²/R on its primary springs."""
    from wheelrail.dynamics import CarBody, Suspension, VehicleModel, WheelsetModel
    from wheelrail.dynamics._fastcontact import WHEEL_FIELDS
    from wheelrail.dynamics.quasistatic import steady_curving

    ws = wr.Wheelset(wr.profiles.load("S1002"))
    track = wr.Track(wr.profiles.load("60E1"))
    prim = Suspension(kx=5e6, ky=2e6, kz=0.6e6, cy=2e4, cz=2e4, half_spacing=1.0)
    model = VehicleModel(carbody=CarBody(12000.0, (1.5e4, 1.2e5, 1.2e5), height=1.4),
                         wheelsets=WheelsetModel(ws, 1300.0, (700.0, 80.0, 700.0), prim,
                                                 spin="fixed"),
                         semi_wheelbase=4.0)
    run = simulate(model, track, 15.0, 0.2, "hertz", "fastsim", initial={"ws0.y": 0.002})
    assert run.info["contact_path"] == "compiled" and "compiled loop" in run.info["integrator"]
    assert np.all(np.isfinite(run.states))
    radius, speed = 400.0, 15.0
    r = steady_curving(model, track, radius, speed, "hertz", "fastsim")
    W = {n: i for i, n in enumerate(WHEEL_FIELDS)}
    assert r.wheels[..., W["Fy"]].sum() == pytest.approx(model.mass * speed ** 2 / radius,
                                                          rel=5e-3)
    # the body's balance: the primary lateral springs, deflected by the relative shift of
    # axle and body at the axle height (axles on the centre line, the body on the chord:
    # versine a²/(2R)), carry its unbalanced force
    st = {n: r.state[r.names.index(n)] for n in r.names}
    carried = 0.0
    for i, xi in enumerate((4.0, -4.0)):
        body_pt = st["body.y"] + xi * st["body.yaw"] - (0.46 - 1.4) * st["body.roll"]
        carried += 2 * prim.ky * (st[f"ws{i}.y"] + xi ** 2 / (2 * radius) - body_pt)
    assert carried == pytest.approx(12000.0 * speed ** 2 / radius, rel=5e-3)
    assert 0.0 < xi ** 2 / (2 * radius) - st["body.y"] < 0.005
