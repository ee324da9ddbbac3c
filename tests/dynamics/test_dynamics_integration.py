"""Integration of a hunting wheelset with flange contact: the contact-configuration changes
are located (never stepped over silently) and the fixed-step scheme converges to the
adaptive solution (Hairer & Wanner 1996: restarting at discontinuities keeps the order)."""

from __future__ import annotations

import numpy as np
import pytest

import wheelrail as wr

D = wr.dynamics


@pytest.fixture(scope="module")
def hunting():
    ws = wr.Wheelset(wr.profiles.load("S1002"))
    tr = wr.Track(wr.profiles.load("60E1"))
    model = D.WheelsetModel(ws, 1813.0, (1120.0, 100.0, 1120.0), axle_load=80e3,
                            primary=D.Suspension(kx=1e6, ky=3.884e6, half_spacing=1.0))

    def run(integrator):
        return D.simulate(model, tr, 85.0, 0.3, "hertz", "fastsim", integrator=integrator,
                          initial={"ws0.y": 0.005}, output_step=1e-3)
    return run


def test_fixed_step_converges_to_adaptive_with_contact_events(hunting):
    ref = hunting(D.Adaptive("RK45", rtol=1e-6, atol=1e-9))
    # the flange contact comes and goes: every change is an event the integration restarts at
    assert len(ref.events) >= 4 and ref.info["restarts"] >= len(ref.events) // 2
    assert {e["side"] for e in ref.events} == {"left", "right"}
    y_ref = ref.state("ws0.y")
    errors = []
    for dt in (1e-3, 2.5e-4):
        res = hunting(D.FixedStep(dt=dt))
        assert res.info["rejected_steps"] > 0          # steps across a change were redone
        np.testing.assert_allclose(res.t, ref.t, atol=1e-12)
        errors.append(float(np.max(np.abs(res.state("ws0.y") - y_ref))))
    # 2.5e-4 s: within 20 µm of the adaptive solution (amplitude ~3 mm), and 4x closer than 1 ms
    assert errors[1] < 2e-5
    assert errors[1] < errors[0] / 4
