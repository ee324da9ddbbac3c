"""Wheelset dynamics against independent references (closed forms and published numbers).

* Klingel's kinematic wavelength 2π √(r0 l0 / λ) (Klingel 1883; Wickens 2003,
  §2.2) from the free, undamped time-domain wheelset;
* the linear critical speed of the classical two-degree-of-freedom wheelset
  (Wickens 2003, ch. 4; Iwnicki (ed.) 2006, ch. 8) from a Routh–Hurwitz closed
  form written out here, and the published 74.04 m/s (kx = 1 MN/m) and
  114.68 m/s (kx = 5 MN/m);
* the pure-rolling offset of a free wheelset in a curve, y = r0 l0/(λR)
  (Wickens 2003, §2.4; Boocock 1969);
* Nadal's limit (tan γ − μ)/(1 + μ tan γ) of Y/Q at wheel lift (Nadal 1896),
  with the 70° flange angle of S1002 (EN 13715);
* the compiled contact of the dynamics against ``wheelrail.solve`` (same normal
  × tangential method) at Manchester-benchmark-like positions of S1002 on 60E1
  (Shackleton & Iwnicki 2008).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.dynamics import Suspension, WheelsetModel, simulate
from wheelrail.dynamics._fastcontact import KMAX, PATCH_FIELDS, WHEEL_FIELDS
from wheelrail.dynamics.contact import FastContact
from wheelrail.dynamics.linear import LinearWheelset
from wheelrail.dynamics.quasistatic import flange_climb, nadal, steady_curving
from wheelrail.dynamics.reference import cone_track, klingel_wavelength
from wheelrail.geometry.touching import touching_heights

R0, L0, LAM = 0.46, 0.75, 0.2


def _zero_crossing_periods(t, y):
    """Intervals [s] between the upward zero crossings of y(t) (linear interpolation)."""
    i = np.flatnonzero((y[:-1] < 0) & (y[1:] >= 0))
    tc = t[i] - y[i] * (t[i + 1] - t[i]) / (y[i + 1] - y[i])
    return np.diff(tc)


def test_klingel_wavelength_from_free_undamped_wheelset():
    """Klingel (1883): a free conical wheelset oscillates with the wavelength
    2π √(r0 l0/λ) = 8.252 m for r0 = 0.46 m, l0 = 0.75 m, λ = 0.2 (kinematic
    motion, valid at low speed where the inertia is negligible: the 2-DOF
    theory moves it by 1e-5 at 5 m/s). The rails of ``cone_track`` are nearly
    knife edges (crown radius 1 mm) so that the contact points stay at ±l0 on the
    rails (a crown R changes the effective conicity by about Rλ/l0: 0.03 %; the
    300 mm crown it once had gave −3.7 %, a 20 mm one −0.25 %).

    The wheelset's roll moves its wheels at rail level by r0 θ; the conicity that
    relates the rolling-radius difference to that lateral shift at rail level is
    exactly λ, and the shift at rail level is what the lateral creepage sees —
    so the time-domain wheelset with roll must give Klingel's wavelength."""
    ws, tr = cone_track(LAM, R0, L0)
    model = WheelsetModel(ws, 1813.0, (1120.0, 100.0, 1120.0), primary=Suspension(),
                          spin="fixed")
    V = 5.0
    res = simulate(model, tr, V, 3.6, "hertz", "linear", initial={"ws0.y": 0.001})
    periods = _zero_crossing_periods(res.t, res.state("ws0.y"))
    assert periods.size >= 1
    wavelength = V * periods
    ref = klingel_wavelength(R0, L0, LAM)
    assert ref == pytest.approx(8.2523, abs=1e-4)
    np.testing.assert_allclose(wavelength, ref, rtol=1e-3)
    # the motion is a kinematic oscillation: no flange contact, amplitude kept (undamped)
    y = res.state("ws0.y")
    assert 0.9e-3 < np.max(np.abs(y[res.t > 1.5])) < 1.2e-3


def _rh_critical_speed(m, Iz, r0, l0, lam, f11, f22, ky, kpsi):
    """Linear critical speed of the 2-DOF wheelset from the Routh–Hurwitz condition in
    closed form (independent of the library).

    det(M s² + C s/V + K) = a4 s⁴ + a3 s³ + a2 s² + a1 s + a0 with
    a4 = m Iz, a3 = A3 u, a2 = B + D u², a1 = A1 u, a0 = ky kψ + 4 f11 f22 l0 λ/r0,
    u = 1/V, c1 = 2 f22, c2 = 2 f11 l0², A3 = m c2 + Iz c1, A1 = c1 kψ + c2 ky,
    B = m kψ + Iz ky, D = c1 c2. The quartic is Hurwitz-stable while
    Δ3 = a3 a2 a1 − a4 a1² − a3² a0 > 0; Δ3 = u² (A3 A1 D u² + A3 A1 B − a4 A1² − A3² a0),
    whose root gives u² and V = 1/u."""
    c1, c2 = 2 * f22, 2 * f11 * l0 ** 2
    a4 = m * Iz
    a0 = ky * kpsi + 4 * f11 * f22 * l0 * lam / r0
    A3, A1 = m * c2 + Iz * c1, c1 * kpsi + c2 * ky
    B, D = m * kpsi + Iz * ky, c1 * c2
    u2 = (a4 * A1 ** 2 + A3 ** 2 * a0 - A3 * A1 * B) / (A3 * A1 * D)
    return 1.0 / math.sqrt(u2)


@pytest.mark.parametrize("kx, published", [(1e6, 74.04), (5e6, 114.68)])
def test_linear_critical_speed_two_dof_wheelset(kx, published):
    """The 2-DOF wheelset (m = 1813 kg, Iz = 1120 kg m², r0 = 0.46 m, l0 = 0.7465 m,
    λ = 0.2, ky = 2 × 3.884 MN/m, kψ = 2 kx b² with b = 1 m, f11 = 8.229 MN,
    f22 = 7.133 MN, no gravitational stiffness or spin; Wickens 2003, ch. 4;
    Iwnicki (ed.) 2006, ch. 8): critical speeds 74.04 m/s at kx = 1 MN/m and
    114.68 m/s at kx = 5 MN/m per axlebox."""
    args = {"m": 1813.0, "Iz": 1120.0, "r0": 0.46, "l0": 0.7465, "lam": 0.2, "f11": 8.229e6,
            "f22": 7.133e6, "ky": 2 * 3.884e6, "kpsi": 2 * kx * 1.0 ** 2}
    w = LinearWheelset(1813.0, 1120.0, 0.46, 0.7465, 0.2, 8.229e6, 7.133e6,
                       lateral_stiffness=2 * 3.884e6,
                       yaw_stiffness=Suspension(kx=kx, half_spacing=1.0).yaw_stiffness)
    v_eig = w.critical_speed("eigenvalues")
    v_rh = w.critical_speed("routh-hurwitz")
    v_closed = _rh_critical_speed(**args)
    assert v_eig == pytest.approx(v_rh, rel=1e-5)
    assert v_eig == pytest.approx(v_closed, rel=1e-5)
    assert v_eig == pytest.approx(published, abs=0.005)
    # the eigenvalues cross the imaginary axis there: stable just below, unstable above
    assert np.max(w.eigenvalues(0.999 * v_eig).real) < 0 < np.max(w.eigenvalues(1.001 * v_eig).real)


def test_pure_rolling_offset_in_a_600_m_curve():
    """A free wheelset (no suspension) on the tread of a 600 m curve at low speed
    rolls without longitudinal creep where r_out − r_in = 2 r0 l0/R (to first
    order in l0/R), i.e. where its lateral shift towards the outer rail is
    r0 l0/(λR) = 2.875 mm for a cone (Wickens 2003, §2.4; Boocock 1969).

    As in the Klingel test, the cone's shift is the wheelset's shift at rail level,
    y + r0 θ (the roll θ moves the wheels at the contact by r0 θ; the rolling
    radii follow the cone there with the slope λ exactly)."""
    ws, tr = cone_track(LAM, R0, L0)
    model = WheelsetModel(ws, 1813.0, (1120.0, 100.0, 1120.0), primary=Suspension())
    radius = 600.0
    ref = R0 * L0 / (LAM * radius)
    for direction, outward in (("right", -1.0), ("left", 1.0)):
        r = steady_curving(model, tr, radius, 5.0, "hertz", "fastsim", direction=direction)
        y, roll = float(r.y[0]), float(r.state[r.names.index("ws0.roll")])
        assert outward * (y + R0 * roll) == pytest.approx(ref, rel=2e-3)
        rr = PATCH_FIELDS.index("rolling_radius")
        radii = {s: r.patches[0, k, 0, rr] for k, s in enumerate(("left", "right"))}
        outer, inner = (radii["left"], radii["right"]) if direction == "right" else (
            radii["right"], radii["left"])
        assert outer - inner == pytest.approx(2 * R0 * L0 / radius, rel=0.01)
        # tread contact on both wheels (contact angle ≈ λ, no flange)
        for side in ("left", "right"):
            np.testing.assert_allclose(r.contact_angles(0, side), math.atan(LAM), atol=0.01)


@pytest.fixture(scope="module")
def s1002_60e1():
    return wr.Wheelset(wr.profiles.load("S1002")), wr.Track(wr.profiles.load("60E1"))


@pytest.mark.parametrize("normal", ["hertz", "kik-piotrowski"])
def test_flange_climb_y_over_q_at_lift_is_nadal(s1002_60e1, normal):
    """Pascal's quasi-static wheelset (Piotrowski & Chollet 2005, §2.2) at a 20 mrad
    angle of attack, μ = 0.3: at wheel lift the flanging wheel's Y/Q is within 3 %
    of Nadal's limit (tan γ − μ)/(1 + μ tan γ) (Nadal 1896) for the flange angle
    reached — the 70° of S1002 (EN 13715) — and not below it (the creep force
    on the flange is at most μ Fn)."""
    ws, tr = s1002_60e1
    model = WheelsetModel(ws, 1500.0, (800.0, 100.0, 800.0), axle_load=100e3)
    mu = 0.3
    r = flange_climb(model, tr, 0.02, normal, "fastsim", mu=mu)
    assert r.lift >= 0
    gamma = r.contact_angle[r.lift]
    assert math.degrees(gamma) == pytest.approx(70.0, abs=0.5)
    limit = nadal(gamma, mu)
    assert limit == pytest.approx((math.tan(gamma) - mu) / (1 + mu * math.tan(gamma)))
    assert r.Y_over_Q[r.lift] == pytest.approx(limit, rel=0.03)
    assert r.Y_over_Q[r.lift] >= limit * (1 - 1e-6)
    assert r.tread_load[r.lift] == 0.0 and r.tread_load[0] > 0.0


@pytest.mark.parametrize("normal, tangential, rtol", [
    ("hertz", "fastsim", 1e-4), ("kik-piotrowski", "fastsim", 0.01), ("hertz", wr.tangential.Table(outside="fastsim"), 1e-4)])
def test_compiled_contact_matches_wr_solve(s1002_60e1, normal, tangential, rtol):
    """The compiled per-wheel contact of the dynamics (contact search, normal
    problem, FASTSIM) gives the same wheel forces as ``wheelrail.solve`` with the
    same methods at the same pose: S1002 on 60E1 1:40, 10 kN per wheel, yaw 2 mrad,
    lateral shifts 0 … 6.8 mm (Manchester benchmark-like positions, Shackleton &
    Iwnicki 2008), 0.1 % longitudinal creep. Hertz: the same ellipses (1e-4);
    Kik–Piotrowski: the compiled strips, within 1 % of Fn (forces) and of μ Fn.
    The table law: the compiled path evaluates the library's table kernel (1e-4);
    both fall back to FASTSIM where a Hertz patch is outside the table (a/b > 20)."""

    ws, tr = s1002_60e1
    mu, V = 0.3, 20.0
    r0 = ws.nominal_radius
    fc = FastContact(ws, tr, wr.STEEL, wr.normal.get(normal), (wr.tangential.get(tangential) if isinstance(tangential, str)
                                                  else tangential))
    for y, yaw in ((0.0, 0.0), (-0.003, -0.002), (0.004, 0.002), (0.0068, 0.002)):
        motion = wr.Motion(speed=V, omega=1.001 * V / r0)
        pos = wr.WheelRailPosition(ws, tr, y, yaw=yaw, vertical_load=10e3)
        ref = wr.solve(pos, motion=motion, mu=mu, normal=normal, tangential=tangential,
                       vertical="normal")
        roll = ref.pose["roll"]
        zt, _ = touching_heights(ws, tr, np.array([y]), np.array([roll]), np.array([yaw]))
        for side in ("left", "right"):
            out_p = np.zeros((KMAX, len(PATCH_FIELDS)))
            out_w = np.zeros(len(WHEEL_FIELDS))
            zc = r0 + zt[side][0] - ref.pose[f"vertical_approach_{side}"]
            n = fc.wheel(side, y, zc, roll, yaw, V, motion.omega, 0.0, 0.0, 0.0, 0.0, mu,
                         out_p, out_w)
            assert n >= 1
            got = out_p[:n].sum(axis=0)
            patches = ref.side(side)
            Fn = sum(p.Fn for p in patches)
            Fx = sum(p.Fx for p in patches)
            Fs = sum(p.Fy for p in patches)
            if normal == "hertz":
                assert n == len(patches)
            assert got[0] == pytest.approx(Fn, rel=rtol)
            assert abs(got[1] - Fx) <= rtol * mu * Fn
            assert abs(got[2] - Fs) <= rtol * mu * Fn


def test_bogie_steady_curving_against_boocock_linear_theory():
    """A two-axle bogie (semi-wheelbase 1.25 m, primary kx = ky = 2 MN/m per side at
    b = 1 m) on conical wheels (λ = 0.05) in a 3000 m curve: the wheelsets' angles
    of attack and lateral shifts from the full nonlinear model against Boocock's
    linear theory of steady curving (Boocock 1969; Wickens 2003, ch. 9) with the
    creep coefficients f11 = G a b C11, f22 = G a b C22 of the model's own Hertz
    patch (Kalker 1990, Table E.3). The linear theory leaves out spin creep and the
    gravitational stiffness (a few per cent here); the leading wheelset steers out,
    the trailing one in, with nearly equal and opposite angles of attack."""
    from wheelrail.tangential.linear import kalker_coefficients

    lam = 0.05
    ws, tr = cone_track(lam, R0, L0, crown_radius=0.02)
    prim = Suspension(kx=2e6, ky=2e6, kz=1e6, cz=1e4, half_spacing=1.0)
    bogie = wr.dynamics.BogieModel(ws, 1500.0, (800.0, 100.0, 800.0), prim, 2600.0,
                                   (1700.0, 1700.0, 3000.0), 1.25,
                                   Suspension(kz=4e5, cz=1e4), axle_load=50e3, spin="fixed")
    radius = 3000.0
    r = steady_curving(bogie, tr, radius, 5.0, "hertz", "linear")
    P = {n: i for i, n in enumerate(PATCH_FIELDS)}
    a, b = r.patches[0, 0, 0, P["a"]], r.patches[0, 0, 0, P["b"]]
    mat = wr.STEEL
    G = mat.E / (2 * (1 + mat.nu))
    C11, C22, _, _ = kalker_coefficients(a / b, mat.nu)
    f11, f22 = G * a * b * float(C11), G * a * b * float(C22)
    ref = wr.dynamics.LinearBogie(1.25, R0, L0, lam, f11, f22, prim.kx, prim.ky,
                                  1.0).curving(radius)
    # Boocock's closed form for this case: the wheelsets' yaw angles are equal and opposite
    assert ref["yaw"][0] == pytest.approx(-ref["yaw"][1], rel=1e-9)
    np.testing.assert_allclose(r.yaw, ref["yaw"], rtol=0.06)
    roll = np.array([r.state[r.names.index(f"ws{i}.roll")] for i in (0, 1)])
    np.testing.assert_allclose(r.y + R0 * roll, ref["y"], rtol=0.03)
