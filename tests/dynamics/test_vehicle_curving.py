"""Steady curving of the whole vehicle (Manchester vehicle 1, Iwnicki 1998).

References the checks use:

* Newton's law for the whole vehicle in a circular curve with cant angle φ: the
  wheels' lateral forces (track frame) balance the unbalanced lateral force
  M (V²/R cos φ − g sin φ) and their vertical forces M (g cos φ + V²/R sin φ),
  M the vehicle's total mass (the car body now a free body: no force from
  outside the vehicle);
* the car body's own balance: its unbalanced lateral force carried by the
  secondary springs and bump stops, deflected by the relative displacement of
  frame and body at the secondary height, the frames on the track centre line
  and the rigid body on the chord between them (versine a_b²/(2R), a_b the
  bogie semi-spacing);
* the time-domain model (compiled RK4, 1 ms), released on the static state at
  the start of a long curve, settles at :func:`steady_curving`'s equilibrium.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.dynamics import Curve, TrackLayout, manchester_vehicle1, simulate, steady_curving
from wheelrail.dynamics._fastcontact import WHEEL_FIELDS

_W = {n: i for i, n in enumerate(WHEEL_FIELDS)}
G = 9.81


@pytest.fixture(scope="module")
def case():
    return manchester_vehicle1(), wr.Track(wr.profiles.load("60E1"))


@pytest.mark.parametrize("radius, speed, cant", [(300.0, 15.0, 0.1), (500.0, 25.0, 0.1),
                                                 (1000.0, 30.0, 0.0)])
def test_whole_vehicle_force_balance_in_a_curve(case, radius, speed, cant):
    """Σ of the eight wheels' lateral forces = M (V²/R cos φ − g sin φ) within 0.5 %,
    vertical = M (g cos φ + V²/R sin φ); flange contact at 300 m, the bump stops
    engaged at 500 m (secondary deflection beyond the 25 mm clearance)."""
    model, track = case
    r = steady_curving(model, track, radius, speed, "hertz", "fastsim", cant=cant)
    phi = math.asin(cant / 1.5)
    M = model.mass
    lateral = M * (speed ** 2 / radius * math.cos(phi) - G * math.sin(phi))
    vertical = M * (G * math.cos(phi) + speed ** 2 / radius * math.sin(phi))
    assert r.wheels[..., _W["Fy"]].sum() == pytest.approx(lateral, rel=5e-3)
    assert r.wheels[..., _W["Fz"]].sum() == pytest.approx(vertical, rel=5e-3)
    # the car body's own balance: the secondary springs and bump stops, deflected by the
    # relative lateral displacement of frame and body at the secondary height (the frames
    # on the centre line, the body on the chord: versine a_b²/(2R)), carry its unbalanced
    # force m_b (V²/R cos φ − g sin φ)
    st = {n: r.state[r.names.index(n)] for n in r.names}
    sec, body = model.secondary, model.carbody
    hf, hb, h2 = model.frame_height, body.height, sec.height
    carried = 0.0
    for j, xj in enumerate((model.bogie_semi_spacing, -model.bogie_semi_spacing)):
        frame_pt = st[f"frame{j}.y"] + xj ** 2 / (2 * radius) - (h2 - hf) * st[f"frame{j}.roll"]
        body_pt = st["body.y"] + xj * st["body.yaw"] - (h2 - hb) * st["body.roll"]
        d = frame_pt - body_pt
        carried += 2 * sec.ky * d + float(sec.bumpstop(d))
    unbalanced = body.mass * (speed ** 2 / radius * math.cos(phi) - G * math.sin(phi))
    assert carried == pytest.approx(unbalanced, rel=5e-3)
    # the leading wheelsets of both bogies yaw towards the outer rail, ahead of the trailing
    yaw = r.yaw
    assert yaw[0] < yaw[1] and yaw[2] < yaw[3]


def test_time_domain_run_settles_at_steady_curving(case):
    """R = 500 m, 100 mm cant, 25 m/s (bump stops engaged): after 11 s from the static
    state the compiled RK4 run is within 1 % of the steady-curving equilibrium (same
    methods and contact options) in every body's lateral position and yaw (1 % of the
    largest of each kind: wheelsets' shifts, their yaws, frames', car body's)."""
    model, track = case
    radius, speed, cant = 500.0, 25.0, 0.1
    ref = steady_curving(model, track, radius, speed, "hertz", "fastsim", cant=cant)
    layout = TrackLayout(track, curves=(Curve(radius, start=-1e7, length=math.inf, cant=cant,
                                              direction="right"),))
    run = simulate(model, layout, speed, 11.0, "hertz", "fastsim", output_step=0.1,
                   contact_options={"connected": "shared", "search_step": 1e-4})
    groups = [[f"ws{i}.y" for i in range(4)], [f"ws{i}.yaw" for i in range(4)],
              ["frame0.y", "frame1.y"], ["frame0.yaw", "frame1.yaw"], ["body.y"], ["body.roll"]]
    for group in groups:
        want = np.array([ref.state[ref.names.index(n)] for n in group])
        got = np.array([run.state(n) for n in group])
        # 1 % of the group's largest value (the trailing wheelsets' yaw is 1/20 of the
        # leading ones')
        tol = 0.01 * np.max(np.abs(want))
        np.testing.assert_array_less(np.abs(got[:, -1] - want), tol, err_msg=str(group))
        np.testing.assert_array_less(np.abs(got[:, -5] - want), 2 * tol, err_msg=str(group))
    # and it started far from there: the car body moved inwards by centimetres
    assert abs(run.state("body.y")[0] - ref.state[ref.names.index("body.y")]) > 0.02
