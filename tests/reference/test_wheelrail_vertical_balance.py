"""Vertical equilibrium of each wheel, recomputed from the returned patch forces.

With ``vertical="total"`` (the default of ``wr.solve`` on a wheel–rail position) the
prescribed vertical load Q of a wheel is carried by the normal *and* tangential contact
forces together (Vollebregt, CONTACT user guide, wheel–rail module; Shackleton & Iwnicki
2008, the Manchester benchmark's vertical force per wheel). The check is written here from
the conventions alone (:mod:`wheelrail.conventions`, docs/conventions.md): in the track's
(y right, z up) plane a patch with contact angle γ (positive towards the flange) on the side
σ = +1 (right) / −1 (left) has the unit normal on the wheel n = (−σ sin γ, cos γ) — at the
flange the rail pushes the wheel towards the track centre — and the in-plane lateral unit
vector t = (cos γ, σ sin γ) ⟂ n, pointing to +y. So the wheel's vertical force is
Σ (Fn n_z + Fs t_z) = Σ (Fn cos γ + σ Fs sin γ), which must equal Q.
"""

import numpy as np
import pytest

import wheelrail as wr

LOADS = {"left": 9e3, "right": 11e3}


@pytest.fixture(scope="module")
def pair():
    ws = wr.Wheelset(wheel=wr.profiles.load("S1002"), nominal_radius=0.46, flange_back=1.360)
    tr = wr.Track(rail=wr.profiles.load("60E1"), gauge=1.435, inclination=1 / 40)
    return ws, tr


def _unit_vectors(gamma, sigma):
    n = np.array([-sigma * np.sin(gamma), np.cos(gamma)])
    t = np.array([np.cos(gamma), sigma * np.sin(gamma)])
    assert abs(n @ t) < 1e-15 and t[0] > 0
    return n, t


@pytest.mark.parametrize("y, yaw", [(0.0075, 0.004), (-0.0075, -0.004), (0.002, 0.003)])
def test_normal_and_tangential_forces_carry_the_vertical_load(pair, y, yaw):
    ws, tr = pair
    m = wr.Motion(speed=20.0, omega=20.0 / 0.46 * 1.002)
    r = wr.solve(wr.WheelRailPosition(ws, tr, y, yaw=yaw,
                                      vertical_load=(LOADS["left"], LOADS["right"])),
                 motion=m, mu=0.3)
    creep_share = 0.0
    for side, Q in LOADS.items():
        sigma = 1.0 if side == "right" else -1.0
        F = np.zeros(2)
        for p in (p for p in r.patches if p.side == side):
            n, t = _unit_vectors(p.contact_angle, sigma)
            F += p.Fn * n + p.Fs * t
            creep_share = max(creep_share, abs(p.Fs * t[1]) / Q)
        assert F[1] == pytest.approx(Q, rel=2e-5)              # the solver's tolerance: 1e-5 Q
        np.testing.assert_allclose(F, r.force_track[side][1:], rtol=1e-9, atol=1e-6 * Q)
    # the creep forces carry a real share of the load here (so their sign matters)
    assert creep_share > 0.01
    if abs(y) > 0.007:                       # flange contact: the rail pushes the wheel back
        flange_side = "right" if y > 0 else "left"
        assert np.sign(r.force_track[flange_side][1]) == -np.sign(y)
