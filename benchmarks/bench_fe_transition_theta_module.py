"""The tread contact's shear direction θ against the traction, from Kalker's exact theory.

With the transition case's kinematics (yaw α, the wheel moving along its heading: no
lateral creepage, spin from the contact angle) the tread contact's lateral force comes from
spin alone, so its direction θ = atan(|F_lat| / |F_long|) depends on where the contact sits
(contact angle) and on how hard the wheel is driven. This script solves the wheel–rail
contact of S1002 on 54E1 1:40 (``solve_wheelrail``, BEM + exact: Kalker's theory on the
half-space) at the wheelset shifts where the rigid tread contact has the given contact
angles, with the angular velocity at which the longitudinal force is traction × Q, and
prints θ — the quasi-static, independent estimate of what the FE run's tread θ can be
before the flange touches. Usage::

    python benchmarks/bench_fe_transition_theta_module.py --angles 8 16 20 24 \
        --traction 0.3 0.4 0.5 --out results/fe_transition/theta_module.txt
"""

from __future__ import annotations

import argparse
import contextlib
import io
import os
import time

import numpy as np

import wheelrail as wr
from wheelrail.contact.wheelrail import WheelRailPosition, solve_wheelrail

S1002 = wr.profiles.load("S1002")
R54 = wr.profiles.load("54E1")


def shift_at_angle(ws, tr, target_deg):
    """Wheelset shift [m] at which the right wheel's rigid primary contact has the given
    contact angle (bisection below the jump onto the flange)."""
    lo, hi = 0.0, 0.012
    for _ in range(40):                       # the jump onto the flange (> 45°)
        m = 0.5 * (lo + hi)
        cp = wr.contact_points(ws, tr, m)
        if np.degrees(cp.right.contact_angle[cp.right.primary]) > 45:
            hi = m
        else:
            lo = m
    jump = hi
    lo, hi = jump - 6e-3, jump - 1e-5
    for _ in range(30):
        m = 0.5 * (lo + hi)
        cp = wr.contact_points(ws, tr, m)
        if np.degrees(cp.right.contact_angle[cp.right.primary]) < target_deg:
            lo = m
        else:
            hi = m
    cp = wr.contact_points(ws, tr, 0.5 * (lo + hi))
    return 0.5 * (lo + hi), float(np.degrees(cp.right.contact_angle[cp.right.primary]))


def solve(case, shift, traction, normal):
    ws = wr.Wheelset(S1002, nominal_radius=case.radius)
    tr = wr.Track(R54, inclination=np.tan(case.inclination))
    alpha, V = case.angle_of_attack, case.speed
    Q = case.suspension.wheel_load(211.0)          # the FE wheel's mass on the 4 mm mesh
    pos = WheelRailPosition(ws, tr, shift, yaw=alpha, roll=0.0, vertical_load=Q)
    goal = traction * Q

    def fx(omega):
        mot = wr.Motion(V, omega=omega, lateral_velocity=V * np.sin(alpha))
        res = solve_wheelrail(pos, mot, case.mu, normal=normal, tangential="exact")
        ps = [p for p in res.side("right") if p.Fn > 1.0]
        return sum(p.Fx for p in ps), ps

    om0 = V / case.radius
    a_, b_ = om0 * (1 + 1e-3), om0 * (1 + 4e-3)
    fa, _ = fx(a_)
    fb, ps = fx(b_)
    for _ in range(12):
        if abs(fb - goal) < 0.002 * abs(goal) + 5.0:
            break
        c_ = b_ + (goal - fb) * (b_ - a_) / (fb - fa)
        a_, fa = b_, fb
        b_, (fb, ps) = c_, fx(c_)
    return Q, b_ / om0 - 1.0, ps


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--aoa", type=float, default=0.025)
    ap.add_argument("--angles", type=float, nargs="+", default=[8.0, 16.0, 20.0, 24.0])
    ap.add_argument("--traction", type=float, nargs="+", default=[0.3, 0.4, 0.5])
    ap.add_argument("--element", type=float, default=2.5e-4, help="BEM element size [m]")
    ap.add_argument("--out")
    a = ap.parse_args()
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf) if a.out else contextlib.nullcontext():
        case = wr.fe.seed004_case(a.aoa)
        ws = wr.Wheelset(S1002, nominal_radius=case.radius)
        tr = wr.Track(R54, inclination=np.tan(case.inclination))
        print(f"S1002 on 54E1 1:{1 / np.tan(case.inclination):.0f}, yaw {a.aoa * 1e3:g} mrad, "
              f"lateral velocity V sin(yaw) (no lateral creepage), mu {case.mu}, BEM "
              f"{a.element * 1e3:g} mm + exact; F_long = traction x Q")
        print("  contact angle  shift [mm]  traction  Fn [kN]  F_long  F_lat [kN]  "
              "theta [deg]  spin [1/m]  CPU [s]")
        for ang in a.angles:
            shift, got = shift_at_angle(ws, tr, ang)
            for trc in a.traction:
                t0 = time.process_time()
                Q, dom, ps = solve(case, shift, trc, wr.normal.Bem(element_size=a.element))
                p = max(ps, key=lambda q: q.Fn)
                th = np.degrees(np.arctan2(abs(p.Fs), abs(p.Fx)))
                print(f"  {got:8.1f}°     {shift * 1e3:7.2f}     {trc:4.2f}   {p.Fn / 1e3:7.1f}"
                      f"  {p.Fx / 1e3:6.1f}  {p.Fs / 1e3:6.1f}      {th:5.1f}"
                      f"       {p.phi:6.3f}   {time.process_time() - t0:5.1f}", flush=True)
        print(f"load average {os.getloadavg()[0]:.1f}")
    if a.out:
        print(buf.getvalue(), end="")
        with open(a.out, "w") as f:
            f.write(buf.getvalue())


if __name__ == "__main__":
    main()
