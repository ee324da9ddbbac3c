"""Terms of the equations of motion that a sign or factor error would corrupt silently,
each against an independent reference written out here.

* the primary lateral damper: each side's force on the wheelset is −c_y (ẏ_w − ẏ_f)
  (a viscous damper opposes the relative velocity), its reaction on the frame the
  opposite;
* the gyroscopic coupling of the spinning wheelset: Iz ψ̈ = M_z − I_y Ω θ̇,
  I_x θ̈ = M_x + I_y Ω ψ̇ in the library's axes (derivation in the test);
* the frequency of :func:`~wheelrail.dynamics.critical_speed`: the imaginary part / 2π
  of the critical eigenvalue, and the Hopf frequency √(a1/a3) of the classical
  two-degree-of-freedom wheelset's characteristic quartic (Wickens 2003, ch. 4);
* the creep relaxation of the library's (generic) contact path: dq/dt = (F − q) V/L.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.dynamics import BogieModel, Suspension, System, WheelsetModel
from wheelrail.dynamics._fastcontact import PATCH_FIELDS, WHEEL_FIELDS
from wheelrail.dynamics.linear import linearise
from wheelrail.dynamics.reference import cone_track

W = {n: i for i, n in enumerate(WHEEL_FIELDS)}
R0, L0 = 0.46, 0.75


@pytest.fixture(scope="module")
def cone():
    return cone_track(0.2, R0, L0)


@pytest.mark.parametrize("kind", ["wheelset", "bogie"])
def test_primary_lateral_damper_opposes_the_relative_velocity(cone, kind):
    """Two systems that differ only in the primary lateral damping c_y, at the same
    state with a wheelset lateral velocity v: the contact forces are the same, so the
    wheelset's acceleration differs by −2 c_y v / m (two sides) and the frame's by
    +2 c_y v / m_f."""
    ws, tr = cone
    cy, v = 3e4, 0.05
    systems = []
    for c in (0.0, cy):
        prim = Suspension(kx=1e6, ky=3.9e6, kz=1.2e6, cy=c)
        if kind == "wheelset":
            model = WheelsetModel(ws, 1813.0, (1120.0, 112.0, 1120.0), primary=prim,
                                  spin="fixed")
        else:
            model = BogieModel(ws, 1813.0, (1120.0, 112.0, 1120.0), prim, 2615.0,
                               (1722.0, 1476.0, 3067.0), 1.25, spin="fixed")
        systems.append(System(model, tr, 20.0, "hertz", "fastsim"))
    x = systems[0].initial_state()
    j = systems[0].asm.index("ws0.vy")
    x[j] = v
    d0, d1 = (s.rhs(0.0, x).copy() for s in systems)
    assert d1[j] - d0[j] == pytest.approx(-2 * cy * v / 1813.0, rel=1e-9)
    if kind == "bogie":
        jf = systems[0].asm.index("frame.vy")
        assert d1[jf] - d0[jf] == pytest.approx(2 * cy * v / 2615.0, rel=1e-9)
        # and a frame velocity damps the frame, drives the wheelsets
        x[j] = 0.0
        x[jf] = v
        d0, d1 = (s.rhs(0.0, x).copy() for s in systems)
        assert d1[jf] - d0[jf] == pytest.approx(-4 * cy * v / 2615.0, rel=1e-9)
        assert d1[j] - d0[j] == pytest.approx(2 * cy * v / 1813.0, rel=1e-9)


def test_gyroscopic_coupling_of_the_spinning_wheelset(cone):
    """Independent derivation. Right-handed axes X forward, Y left, Z up; the library's
    y (right), roll θ (right side up) and yaw ψ (nose right) are y = −Y, θ = −φ_X,
    ψ = −φ_Z. A wheel rolling forward at V spins about +Y at Ω = V/r0 (v_centre =
    ω × r0 Z = V X), so its angular momentum is H = I_y Ω Y. Rolling and yawing turn H
    at dH/dt = ω × H with ω = −θ̇ X − ψ̇ Z: dH/dt = −I_y Ω θ̇ Z + I_y Ω ψ̇ X. Euler's
    equations M = I φ̈ + dH/dt then give, back in the library's angles,

        I_z ψ̈ = M_ψ − I_y Ω θ̇,      I_x θ̈ = M_θ + I_y Ω ψ̇.

    Two models differing only in I_y (fixed spin, Ω = V/r0, the contact forces the
    same) at the same state with a roll rate θ̇ and a yaw rate ψ̇: the yaw and roll
    accelerations differ by −ΔI_y Ω θ̇ / I_z and +ΔI_y Ω ψ̇ / I_x."""
    ws, tr = cone
    V, Ix, Iz = 20.0, 1120.0, 1000.0
    systems = [System(WheelsetModel(ws, 1813.0, (Ix, Iy, Iz), spin="fixed",
                                    primary=Suspension(kx=1e6, ky=3.9e6, kz=1.2e6)),
                      tr, V, "hertz", "fastsim") for Iy in (100.0, 300.0)]
    x = systems[0].initial_state()
    asm = systems[0].asm
    th_dot, psi_dot = 0.02, 0.01
    x[asm.index("ws0.roll_rate")] = th_dot
    x[asm.index("ws0.yaw_rate")] = psi_dot
    d0, d1 = (s.rhs(0.0, x).copy() for s in systems)
    omega = V / R0
    dyaw = d1[asm.index("ws0.yaw_rate")] - d0[asm.index("ws0.yaw_rate")]
    droll = d1[asm.index("ws0.roll_rate")] - d0[asm.index("ws0.roll_rate")]
    assert dyaw == pytest.approx(-200.0 * omega * th_dot / Iz, rel=1e-9)
    assert droll == pytest.approx(200.0 * omega * psi_dot / Ix, rel=1e-9)


def test_critical_speed_frequency_is_that_of_the_critical_eigenvalue(cone):
    """A suspended wheelset (kx = 1 MN/m at b = 1 m, ky = 3.884 MN/m per side) on a cone
    λ = 0.2 with the linear creep law: ``critical_speed``'s frequency against (1) the
    imaginary part / 2π of the least stable eigenvalue of the model linearised at
    that speed, and (2) the classical 2-DOF wheelset's Hopf frequency √(A1/A3)/2π
    (the characteristic quartic a4 s⁴ + a3 s³ + a2 s² + a1 s + a0 has the root
    s = iω on the boundary with ω² = a1/a3; A1 = c1 kψ + c2 ky, A3 = m c2 + Iz c1,
    c1 = 2 f22, c2 = 2 f11 l0²; Wickens 2003, ch. 4) with f11, f22 of the model's own
    Hertz patch — the 2-DOF model leaves out roll, spin creep and gravitational
    stiffness: 9.14 Hz against 8.52 Hz, so within 10 %; a factor 2 is far outside."""
    from wheelrail.tangential.linear import kalker_coefficients

    ws, tr = cone
    kx, ky, m, Iz = 1e6, 3.884e6, 1813.0, 1120.0
    model = WheelsetModel(ws, m, (1120.0, 112.0, Iz), spin="fixed",
                          primary=Suspension(kx=kx, ky=ky, kz=1.22e6, half_spacing=1.0))
    res = wr.dynamics.critical_speed(model, tr, "hertz", "linear", bracket=(20.0, 150.0))
    Vc, f = res.speed, res.frequency
    A, _, _ = linearise(System(model, tr, Vc, "hertz", "linear"))
    ev = np.linalg.eigvals(A)
    ev = ev[np.abs(ev) > 1e-6]
    crit = ev[np.argmax(ev.real)]
    assert abs(crit.real) < 0.05 * abs(crit.imag)           # on the boundary
    assert f == pytest.approx(abs(crit.imag) / (2 * math.pi), rel=1e-6)
    # the 2-DOF Hopf frequency with the model's creep coefficients
    system = System(model, tr, Vc, "hertz", "linear")
    system.rhs(0.0, system.initial_state())
    P = {n: i for i, n in enumerate(PATCH_FIELDS)}
    a, b = system.OP[0, 0, 0, P["a"]], system.OP[0, 0, 0, P["b"]]
    mat = wr.STEEL
    G = mat.E / (2 * (1 + mat.nu))
    C11, C22, _, _ = kalker_coefficients(a / b, mat.nu)
    f11, f22 = G * a * b * float(C11), G * a * b * float(C22)
    c1, c2 = 2 * f22, 2 * f11 * L0 ** 2
    kpsi = 2 * kx * 1.0 ** 2
    A1, A3 = c1 * kpsi + c2 * 2 * ky, m * c2 + Iz * c1
    assert f == pytest.approx(math.sqrt(A1 / A3) / (2 * math.pi), rel=0.10)


def test_creep_relaxation_of_the_generic_contact_path(cone):
    """The library's contact path (``contact="generic"``) with a relaxation length of
    2 a: at a state whose relaxation states are zero, their rates are F V/(2 a) with F
    the steady creep forces and a the load-weighted semi-axis that the same
    evaluation reports; at the steady values, zero."""
    ws, tr = cone
    model = WheelsetModel(ws, 1813.0, (1120.0, 112.0, 1120.0), spin="free",
                          primary=Suspension(kx=1e6, ky=3.9e6, kz=1.2e6))
    V = 20.0
    system = System(model, tr, V, "hertz", "fastsim", creep_relaxation=2.0, contact="generic")
    assert not system.fast
    x = system.initial_state({"ws0.yaw": 1e-3})
    ox = system.asm.off_relax
    x[ox:] = 0.0
    dx = system.rhs(0.0, x)
    F = system.OW[0, :, W["Qt_y"]:W["Qt_y"] + 5]
    a = system.OW[0, :, W["a_mean"]]
    assert np.max(np.abs(F[:, 0])) > 1e3
    np.testing.assert_allclose(dx[ox:].reshape(2, 5), F * V / (2.0 * a[:, None]),
                               rtol=1e-12, atol=1e-9)
    x[ox:] = F.reshape(-1)
    dx = system.rhs(0.0, x)
    assert np.max(np.abs(dx[ox:])) < 1e-9 * np.max(np.abs(F)) * V / np.min(a)
