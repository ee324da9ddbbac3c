"""Quasi-static cross-check of the transition FE run against the wheel–rail contact module.

At a few travels of a run of :func:`wheelrail.fe.run_transition` the FE state (lateral
position of the wheel, yaw, the total vertical contact force and the wheel's angular
velocity) is given to :func:`wheelrail.contact.wheelrail.solve_wheelrail` (roll 0 as in
the half-wheelset model, lateral velocity V sin α along the yawed heading) with

* BEM + exact (Kalker's theory on the half-space, discretised), and
* Kik–Piotrowski + FASTSIM;

the FE patch forces (mean over ±2 outputs) are printed beside the module's: normal force,
longitudinal and lateral tangential force of the tread and flange patches. Usage::

    python studies/transition_crosscheck.py RUN.pkl [--s 0.03 0.05 0.075]

where RUN.pkl holds ``{"patches", "history", "info", "case_kw"}`` of a run (as written by
``--run``)::

    python studies/transition_crosscheck.py --run RUN.pkl --aoa 0.025 \
        --mesh 4e-3 --travel 0.11
"""

from __future__ import annotations

import argparse
import os
import pickle
import time

import numpy as np

import wheelrail as wr
from wheelrail.contact.wheelrail import WheelRailPosition, solve_wheelrail

S1002 = wr.profiles.load("S1002")
R54 = wr.profiles.load("54E1")


def module_jump_shift(ws, tr):
    """Wheelset shift [m] at which the right wheel's rigid contact jumps to the flange."""
    lo, hi = 0.0, 0.012
    for _ in range(40):
        m = 0.5 * (lo + hi)
        cp = wr.contact_points(ws, tr, m)
        if np.degrees(cp.right.contact_angle[cp.right.primary]) > 45:
            hi = m
        else:
            lo = m
    return hi


def crosscheck(run, s_values):
    case = wr.fe.seed004_case(**run["case_kw"])
    ds, h = run["patches"], run["history"]
    ws = wr.Wheelset(S1002, nominal_radius=case.radius)
    tr = wr.Track(R54, inclination=np.tan(case.inclination))
    yj = module_jump_shift(ws, tr)
    alpha, V = case.angle_of_attack, case.speed
    s_all = h["travel"].values
    rows = []
    for s in s_values:
        k = int(np.argmin(np.abs(s_all - s)))
        sl = slice(max(0, k - 2), k + 3)
        fe = {f: ds[f].isel(time=sl).mean("time").values for f in
              ("Fn", "F_long", "F_lat", "contact_angle")}
        Q = float(h["Fz_total"].isel(time=sl).mean())
        om = float(h["omega"].isel(time=sl).mean())
        tt = h["time"].values
        wdot = float(np.polyfit(tt[sl], h["w"].values[sl], 1)[0])
        # the same pose: the module's wheelset shift at which its rigid tread contact has
        # the FE tread patch's contact angle (the yawed FE wheel's contact leads the axle,
        # so a shift mapped from the axle's lateral position misses the flange root)
        target = float(fe["contact_angle"][0])
        lo, hi = yj - 4e-3, yj - 1e-5
        for _ in range(30):
            mid = 0.5 * (lo + hi)
            cp = wr.contact_points(ws, tr, mid)
            if cp.right.contact_angle[cp.right.primary] < target:
                lo = mid
            else:
                hi = mid
        shift = 0.5 * (lo + hi)
        pos = WheelRailPosition(ws, tr, shift, yaw=alpha, roll=0.0, vertical_load=Q)
        line = {"s": float(s_all[k]), "Q": Q, "shift": shift, "fe": fe, "wdot": wdot}
        for name, nm, tm in (("bem+exact", wr.normal.Bem(element_size=2.5e-4), "exact"),
                             ("kp+fastsim", "kik-piotrowski", "fastsim")):
            t0 = time.process_time()
            # the wheel's angular velocity at which the module's longitudinal force equals
            # the FE tread patch's (the driving torque sets it; the FE's nominal creepage
            # depends on a rolling radius that the two geometries define differently)

            def fx(omega):
                mot = wr.Motion(V, omega=omega, lateral_velocity=V * np.sin(alpha),
                                vertical_velocity=wdot)
                res = solve_wheelrail(pos, mot, case.mu, normal=nm, tangential=tm)
                ps = [p for p in res.side("right") if p.Fn > 1.0]
                return sum(p.Fx for p in ps), ps

            a_, b_ = om * (1 - 2e-3), om * (1 + 2e-3)
            fa, _ = fx(a_)
            fb, ps = fx(b_)
            goal = float(fe["F_long"][0])
            for _ in range(8):
                c_ = b_ + (goal - fb) * (b_ - a_) / (fb - fa)
                a_, fa = b_, fb
                b_ = c_
                fb, ps = fx(b_)
                if abs(fb - goal) < 0.002 * abs(goal) + 5.0:
                    break
            line[name] = [(float(np.degrees(p.contact_angle)), p.Fn, p.Fx, p.Fs, p.xi, p.eta,
                           p.phi) for p in ps]
            line[name + "_cpu"] = time.process_time() - t0
        rows.append(line)
    return rows


def report(rows):
    for r in rows:
        fe = r["fe"]
        print(f"s = {r['s'] * 1e3:.1f} mm, vertical load {r['Q'] / 1e3:.1f} kN, "
              f"module shift {r['shift'] * 1e3:.2f} mm, axle vertical velocity "
              f"{r['wdot'] * 1e3:.1f} mm/s")
        for p, nm in ((0, "tread"), (1, "flange")):
            if fe["Fn"][p] > 100:
                print(f"  FE {nm:6s}: angle {np.degrees(fe['contact_angle'][p]):5.1f} deg, "
                      f"Fn {fe['Fn'][p] / 1e3:7.2f} kN, F_long {fe['F_long'][p] / 1e3:7.2f}, "
                      f"F_lat {fe['F_lat'][p] / 1e3:7.2f} kN")
        for name in ("bem+exact", "kp+fastsim"):
            for (ang, fn, fx, fs, xi, eta, phi) in r[name]:
                print(f"  {name:10s}: angle {ang:5.1f} deg, Fn {fn / 1e3:7.2f} kN, "
                      f"Fx {fx / 1e3:7.2f}, Fs {fs / 1e3:7.2f} kN  (xi {xi:.2e}, eta {eta:.2e}, "
                      f"phi {phi:.3f} 1/m)  [{r[name + '_cpu']:.1f} s CPU]")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("pickle", nargs="?")
    ap.add_argument("--run")
    ap.add_argument("--aoa", type=float, default=0.025)
    ap.add_argument("--mesh", type=float, default=4e-3)
    ap.add_argument("--travel", type=float, default=0.11)
    ap.add_argument("--s", type=float, nargs="*", default=None)
    a = ap.parse_args()
    if a.run:
        kw = dict(angle_of_attack=a.aoa, mesh_size=a.mesh, travel=a.travel)
        r = wr.fe.run_transition(wr.fe.seed004_case(**kw), progress=True)
        info = {k: v for k, v in r.info.items() if k != "fields"}
        run = {"patches": r.patches, "history": r.history, "info": info, "case_kw": kw}
        with open(a.run, "wb") as f:
            pickle.dump(run, f)
        print(f"{info['elements']} elements, {info['steps']} steps, {info['cpu_s']:.0f} s CPU, "
              f"load {os.getloadavg()[0]:.1f}")
    else:
        with open(a.pickle, "rb") as f:
            run = pickle.load(f)
    s = a.s or [0.5 * run["info"]["onset_travel"], 0.9 * run["info"]["onset_travel"],
                float(run["history"]["travel"].values[-1]) - 0.002]
    report(crosscheck(run, s))


if __name__ == "__main__":
    main()
