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
  the start of a long curve, settles at :func:`steady_curving`'s equilibrium;
* Boocock's linear theory of steady curving (Boocock 1969; Wickens 2003, ch. 9)
  for both bogies, extended by the car body's secondary lateral and yaw
  stiffness, at large radius on conical wheels.
"""

from __future__ import annotations

import dataclasses
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


@pytest.mark.slow
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


def _boocock_vehicle(model, lam, f11, f22, radius, speed):
    """Boocock's linear steady curving (Boocock 1969; Wickens 2003, ch. 9) of the whole
    vehicle: the bogie equations of :class:`~wheelrail.dynamics.LinearBogie` written out
    for both bogies, joined to the car body by the secondary suspension — lateral
    2 ky2 (y_f + κ a_b²/2 − y_b − x_j ψ_b) (the body on the chord) and yaw
    (2 kx2 b2² + 2 k_r) (ψ_f + κ x_j − ψ_b) (the bogie turned against the body by the
    curve) — and the apparent centrifugal force m V² κ on every body (no cant); the
    wheelsets' kinematic roll λ y/l0 in the rolling-radius difference. Returns
    (y, ψ) of the four wheelsets, the two frames and the body."""
    bogie = model.bogies[0]
    prim, sec = bogie.primary, model.secondary
    r0, l0 = model.wheelset.nominal_radius, model.wheelset.e_tape
    kx, ky, b = prim.kx, prim.ky, prim.half_spacing
    ky2 = sec.ky
    kyaw2 = 2 * sec.kx * sec.half_spacing ** 2 + 2 * sec.yaw_stiffness
    k = 1.0 / radius
    acc = speed ** 2 * k
    # the wheelset's kinematic roll θ = λ y/l0 on the cone moves its wheels' points at rail
    # level by r0 θ: the rolling-radius difference is 2 λ (y + r0 θ) = 2 λ* y
    lam_roll = lam * (1.0 + r0 * lam / l0)
    n = 14                       # (y, ψ) of ws0..ws3, frame0, frame1, body
    A = np.zeros((n, n))
    rhs = np.zeros(n)
    fy = lambda j: 8 + 2 * j     # noqa: E731
    by, bp = 12, 13
    for j, xj in enumerate((model.bogie_semi_spacing, -model.bogie_semi_spacing)):
        yf, pf = fy(j), fy(j) + 1
        for i, xi in enumerate((bogie.semi_wheelbase, -bogie.semi_wheelbase)):
            jy, jp = 4 * j + 2 * i, 4 * j + 2 * i + 1
            # wheelset lateral: 2 f22 ψ − 2 ky (y + κ x²/2 − yf − x ψf) − m V² κ = 0
            A[jy, jp] += 2 * f22
            A[jy, jy] += -2 * ky
            A[jy, yf] += 2 * ky
            A[jy, pf] += 2 * ky * xi
            rhs[jy] += 2 * ky * k * xi * xi / 2 + bogie.mass * acc
            # wheelset yaw: −2 f11 l0 (λ* y/r0 + l0 κ) − 2 kx b² (ψ + κ x − ψf) = 0
            A[jp, jy] += -2 * f11 * l0 * lam_roll / r0
            A[jp, jp] += -2 * kx * b * b
            A[jp, pf] += 2 * kx * b * b
            rhs[jp] += 2 * f11 * l0 * l0 * k + 2 * kx * b * b * k * xi
            # the reactions on the frame
            A[yf, jy] += 2 * ky
            A[yf, yf] += -2 * ky
            A[yf, pf] += -2 * ky * xi
            rhs[yf] += -2 * ky * k * xi * xi / 2
            A[pf, jy] += 2 * ky * xi
            A[pf, yf] += -2 * ky * xi
            A[pf, pf] += -2 * ky * xi * xi
            rhs[pf] += -2 * ky * xi * k * xi * xi / 2
            A[pf, jp] += 2 * kx * b * b
            A[pf, pf] += -2 * kx * b * b
            rhs[pf] += -2 * kx * b * b * k * xi
        rhs[yf] += bogie.frame_mass * acc
        # secondary lateral: F = −2 ky2 d, d = yf + κ xj²/2 − yb − xj ψb (on the frame)
        d = np.zeros(n)
        d[yf], d[by], d[bp] = 1.0, -1.0, -xj
        d0 = k * xj * xj / 2
        A[yf] += -2 * ky2 * d
        rhs[yf] += 2 * ky2 * d0
        A[by] += 2 * ky2 * d
        rhs[by] += -2 * ky2 * d0
        A[bp] += 2 * ky2 * xj * d
        rhs[bp] += -2 * ky2 * xj * d0
        # secondary yaw: M = −kyaw2 (ψf + κ xj − ψb) (on the frame)
        e = np.zeros(n)
        e[pf], e[bp] = 1.0, -1.0
        A[pf] += -kyaw2 * e
        rhs[pf] += kyaw2 * k * xj
        A[bp] += kyaw2 * e
        rhs[bp] += -kyaw2 * k * xj
    rhs[by] += model.carbody.mass * acc
    return np.linalg.solve(A, rhs)


def test_vehicle_angles_of_attack_against_boocock_extended_by_the_car_body():
    """Large radius (3000 m), tread contact of conical wheels (λ = 0.05) on nearly
    knife-edge rails, linear creep law, 5 m/s: the four wheelsets' angles of attack and
    the frames' yaw of the full nonlinear vehicle against Boocock's linear theory
    extended by the car body (:func:`_boocock_vehicle`), creep coefficients
    f11 = G a b C11, f22 = G a b C22 of the model's own Hertz patch (Kalker 1990,
    Table E.3): angles of attack within 2 %, frames' yaw within 1 %, lateral shifts
    within 1.5 % (the theory leaves out spin creep and the gravitational stiffness)."""
    from wheelrail.dynamics import BogieModel, CarBody, SecondarySuspension, Suspension
    from wheelrail.dynamics import VehicleModel
    from wheelrail.dynamics._fastcontact import PATCH_FIELDS
    from wheelrail.dynamics.reference import cone_track
    from wheelrail.tangential.linear import kalker_coefficients

    lam, r0, l0 = 0.05, 0.46, 0.75
    ws, tr = cone_track(lam, r0, l0, crown_radius=0.02)
    prim = Suspension(kx=2e6, ky=2e6, kz=1e6, cz=1e4, half_spacing=1.0)
    bogie = BogieModel(ws, 1500.0, (800.0, 100.0, 800.0), prim, 2600.0,
                       (1700.0, 1700.0, 3000.0), 1.25, spin="fixed")
    sec = SecondarySuspension(kx=0.3e6, ky=0.2e6, kz=0.4e6, cz=2e4, half_spacing=1.0,
                              height=0.9, yaw_stiffness=2e4)
    model = VehicleModel(carbody=CarBody(9000.0, (2e4, 4e5, 4e5), height=1.6), bogies=bogie,
                         secondary=sec, bogie_semi_spacing=7.0)
    radius, speed = 3000.0, 5.0
    r = steady_curving(model, tr, radius, speed, "hertz", "linear")
    P = {n: i for i, n in enumerate(PATCH_FIELDS)}
    a, b = r.patches[0, 0, 0, P["a"]], r.patches[0, 0, 0, P["b"]]
    mat = wr.STEEL
    Gm = mat.E / (2 * (1 + mat.nu))
    C11, C22, _, _ = kalker_coefficients(a / b, mat.nu)
    f11, f22 = Gm * a * b * float(C11), Gm * a * b * float(C22)
    u = _boocock_vehicle(model, lam, f11, f22, radius, speed)
    yaw_ref = u[[1, 3, 5, 7]]
    frame_yaw = [r.state[r.names.index(f"frame{j}.yaw")] for j in (0, 1)]
    np.testing.assert_allclose(r.yaw, yaw_ref, rtol=0.02)
    np.testing.assert_allclose(frame_yaw, u[[9, 11]], rtol=0.01)
    np.testing.assert_allclose(r.y, u[[0, 2, 4, 6]], rtol=0.015)
    # the car body turns the bogies against the curve: without it (kyaw2 → 0 and
    # ky2 → 0) the frames' yaw would differ by far more than the tolerance
    free = _boocock_vehicle(dataclasses.replace(
        model, secondary=dataclasses.replace(sec, kx=0.0, ky=1.0, yaw_stiffness=0.0)),
        lam, f11, f22, radius, speed)
    assert np.all(np.abs(free[[9, 11]] - u[[9, 11]]) > 0.05 * np.abs(u[[9, 11]]))
