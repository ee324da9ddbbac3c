"""The whole-vehicle model: car-body modes on the secondary suspension against closed forms.

With the bogies held (the Jacobian of the model's equations restricted to the
car body's states), the car body of Manchester vehicle 1 (Iwnicki 1998) on its
secondary suspension — four spring sets kx, ky, kz at (±a_b, ±b, h − h_b),
rotational yaw stiffness k_r per set — has the undamped frequencies
(Timoshenko's rigid body on springs; Wickens 2003, ch. 6; Iwnicki (ed.) 2006, ch. 5)

* bounce ω² = 4 kz / m,
* pitch ω² = (4 kz a_b² + 4 kx (h − h_b)² − m g (h_b − h)) / I_y (the last term the
  overturning of the body's weight, carried at the springs' height h below its
  centre of mass h_b),
* yaw ω² = 4 (ky a_b² + kx b² + k_r) / I_z,

and the two-axle vehicle's body bounces on its four primary spring sets with
ω² = 4 kz / m.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.dynamics import (BumpStop, CarBody, SecondarySuspension, Suspension, System,
                                VehicleModel, WheelsetModel, manchester_vehicle1)
from wheelrail.errors import InputError


def _undamped(model):
    sec = dataclasses.replace(model.secondary, cx=0.0, cy=0.0, cz=0.0)
    return dataclasses.replace(model, secondary=sec, bogies=model.bogies[0])


def _jacobian(system, x0, cols, h=1e-6):
    J = np.empty((system.asm.n, len(cols)))
    for k, c in enumerate(cols):
        xp, xm = x0.copy(), x0.copy()
        xp[c] += h
        xm[c] -= h
        J[:, k] = (system.rhs(0.0, xp) - system.rhs(0.0, xm)) / (2 * h)
    return J


def _body_frequencies(system, prefix="body"):
    """ω [rad/s] of the body's modes with everything else held (undamped: from the
    position block of the Jacobian)."""
    x0 = system.initial_state()
    pos = [system.asm.index(f"{prefix}.{s}") for s in ("y", "z", "roll", "pitch", "yaw")]
    acc = [system.asm.index(f"{prefix}.{s}") for s in ("vy", "vz", "roll_rate", "pitch_rate",
                                                        "yaw_rate")]
    J = _jacobian(system, x0, pos)[acc]
    return J


@pytest.fixture(scope="module")
def track():
    return wr.Track(wr.profiles.load("60E1"))


def test_manchester_vehicle1_data():
    """Masses and the static axle load of the benchmark (Iwnicki 1998): 32 000 kg body,
    2 × 2615 kg frames, 4 × 1813 kg wheelsets."""
    m = manchester_vehicle1()
    assert m.n_wheelsets == 4 and m.n_frames == 2
    assert m.mass == pytest.approx(32000 + 2 * 2615 + 4 * 1813, rel=1e-12)
    assert m.axle_load == pytest.approx((32000 + 2 * 2615 + 4 * 1813) * 9.81 / 4, rel=1e-12)
    assert m.secondary.bumpstop.clearance == 0.025
    assert m.wheelset.nominal_radius == 0.46


def test_bumpstop_force_table():
    """The Manchester bump stop (Iwnicki 1998): free within 25 mm, the tabulated force
    at the points, linear between, odd in the deflection, last slope beyond 65 mm."""
    bs = manchester_vehicle1().secondary.bumpstop
    assert bs(0.02) == 0.0 and bs(-0.025) == 0.0
    assert bs(0.035) == pytest.approx(1760.0)
    assert bs(-0.0425) == pytest.approx(-(3730.0 + 6870.0) / 2)
    assert bs(0.070) == pytest.approx(230000.0 + (230000.0 - 29200.0))
    with pytest.raises(InputError, match="force"):
        BumpStop((0.01, 0.02), (100.0, 200.0))
    with pytest.raises(InputError, match="displacement"):
        BumpStop((0.02, 0.01), (0.0, 200.0))


def test_vehicle_model_checks_its_input():
    m = manchester_vehicle1()
    with pytest.raises(InputError, match="carbody"):
        VehicleModel(carbody=1.0, bogies=m.bogies, secondary=m.secondary)
    with pytest.raises(InputError, match="secondary"):
        VehicleModel(carbody=m.carbody, bogies=m.bogies, secondary="soft")
    with pytest.raises(InputError, match="semi_wheelbase"):
        VehicleModel(carbody=m.carbody, wheelsets=WheelsetModel(m.wheelset, 1813.0,
                                                                (1120.0, 112.0, 1120.0)))


def test_carbody_bounce_pitch_yaw_frequencies_bogies_held(track):
    """Manchester vehicle 1 without secondary damping: the body's bounce, pitch and yaw
    frequencies (bogies held) within 1 % of the closed forms of the module docstring."""
    model = _undamped(manchester_vehicle1())
    system = System(model, track, 20.0, "hertz", "fastsim")
    J = _body_frequencies(system)
    sec, body = model.secondary, model.carbody
    a_b, b, dh = model.bogie_semi_spacing, sec.half_spacing, sec.height - body.height
    Ix, Iy, Iz = body.inertia
    ref = {"bounce": math.sqrt(4 * sec.kz / body.mass),
           "pitch": math.sqrt((4 * (sec.kz * a_b ** 2 + sec.kx * dh ** 2)
                               + body.mass * 9.81 * dh) / Iy),
           "yaw": math.sqrt(4 * (sec.ky * a_b ** 2 + sec.kx * b ** 2 + sec.yaw_stiffness) / Iz)}
    got = {"bounce": math.sqrt(-J[1, 1]), "pitch": math.sqrt(-J[3, 3]),
           "yaw": math.sqrt(-J[4, 4])}
    # the three are uncoupled from the rest (lateral–roll: the sway modes)
    for k in (1, 3, 4):
        off = np.delete(J[k], k)
        assert np.all(np.abs(off) < 1e-6 * abs(J[k, k]))
    # and the frequencies from the eigenvalues of the whole body block
    w = np.sort(np.sqrt(-np.linalg.eigvals(J).real))
    for name, v in ref.items():
        assert got[name] == pytest.approx(v, rel=0.01), name
        assert np.min(np.abs(w - v)) < 0.01 * v, name
    assert ref["bounce"] / (2 * math.pi) == pytest.approx(1.17, abs=0.01)


def test_two_axle_vehicle_bounce_on_the_primary(track):
    """A two-axle vehicle (body 12 t on four primary sets kz = 0.6 MN/m, wheelsets held):
    bounce ω² = 4 kz/m within 1 %; the wheelsets carry the body's weight."""
    ws = wr.Wheelset(wr.profiles.load("S1002"))
    prim = Suspension(kx=5e6, ky=2e6, kz=0.6e6, half_spacing=1.0)
    model = VehicleModel(carbody=CarBody(12000.0, (1.5e4, 1.2e5, 1.2e5), height=1.4),
                         wheelsets=WheelsetModel(ws, 1300.0, (700.0, 80.0, 700.0), prim,
                                                 spin="fixed"),
                         semi_wheelbase=4.0)
    assert model.axle_load == pytest.approx((12000 + 2 * 1300) * 9.81 / 2)
    system = System(model, track, 10.0, "hertz", "fastsim")
    J = _body_frequencies(system)
    assert math.sqrt(-J[1, 1]) == pytest.approx(math.sqrt(4 * 0.6e6 / 12000.0), rel=0.01)
    # pitch: 4 kz a² + 4 kx (h_axle − h_body)² − m g (h_body − h_axle)
    ky_pitch = 4 * 0.6e6 * 16.0 + 4 * 5e6 * (0.46 - 1.4) ** 2 + 12000.0 * 9.81 * (0.46 - 1.4)
    assert math.sqrt(-J[3, 3]) == pytest.approx(math.sqrt(ky_pitch / 1.2e5), rel=0.01)
