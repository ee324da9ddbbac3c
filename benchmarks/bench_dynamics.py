"""Wheelset dynamics: contact time per wheelset position and the real-time factor.

Problem: S1002 on 60E1 (1:40), 80 kN axle load (40 kN per wheel), μ = 0.3,
V = 30 m/s, yaw 1 mrad, lateral shifts −6 … +7 mm (tread and flange contact).

1. **Per-position contact time** (both wheels, including the contact search:
   profile separation, candidate points, normal problem, FASTSIM) of the
   compiled path used by :func:`wheelrail.dynamics.simulate`, for
   Kik–Piotrowski + FASTSIM and Hertz + FASTSIM (and the table law when its
   data are installed): mean CPU time over the positions, best of ``--repeat``
   rounds, after a warm-up (numba cache load). Goals: ≤ 0.1 ms (KP)
   and ≤ 0.05 ms (Hertz).
2. **Real-time factor** (simulated seconds per CPU second) of a suspended
   wheelset with the fixed-step RK4 scheme at a 1 ms step (4 contact
   evaluations of both wheels per step), released 3 mm off centre on tangent
   track; goal ≥ 1.
3. **Steady curving** of the Manchester vehicle 1 bogie in a 300 m curve with
   100 mm cant at 10–25 m/s: CPU time per equilibrium.

CPU time (``time.process_time``) on one core; set ``NUMBA_NUM_THREADS=1``.
The load of the machine (``os.getloadavg``) is printed with the numbers.

    python benchmarks/bench_dynamics.py [--repeat 5] [--duration 2.0] [--contact-only]
        [--line-nodes 201]

Kik–Piotrowski evaluates the library's separation line (``KikPiotrowski.line_nodes``;
the dynamics' default by name: 201 nodes, 0.2 mm; the library's 1601: 0.025 mm) around
each region, so that its forces are those of :func:`wheelrail.solve` with the same
line.
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

import wheelrail as wr
from wheelrail.dynamics._fastcontact import KMAX, PATCH_FIELDS, WHEEL_FIELDS
from wheelrail.dynamics.contact import LINE_NODES, FastContact
from wheelrail.geometry.touching import touching_heights

D = wr.dynamics


def positions(ws, tr, ys, yaw, approach=3e-5):
    """(y, zc, roll) of each position: rigid roll of both wheels touching, then pressed
    ``approach`` [m] into the rails (a loaded wheelset)."""
    from wheelrail.geometry.contact_search import solve_rigid

    _z, roll, _ = solve_rigid(ws, tr, ys, np.full_like(ys, yaw))
    out = []
    for y, th in zip(ys, roll):
        zt, _ = touching_heights(ws, tr, np.array([y]), np.array([th]), np.array([yaw]))
        zc = ws.nominal_radius + min(zt["left"][0], zt["right"][0]) - approach
        out.append((float(y), float(zc), float(th)))
    return out


def contact_time(fc, poses, yaw, V, r0, repeat):
    op = np.zeros((KMAX, len(PATCH_FIELDS)))
    ow = np.zeros(len(WHEEL_FIELDS))

    def one_round():
        for y, zc, th in poses:
            for side in ("left", "right"):
                fc.wheel(side, y, zc, th, yaw, V, V / r0, 0.0, 0.0, 0.0, 0.0, 0.3, op, ow)

    one_round()
    best = np.inf
    for _ in range(repeat):
        t0 = time.process_time()
        for _ in range(10):
            one_round()
        best = min(best, (time.process_time() - t0) / (10 * len(poses)))
    return best


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--duration", type=float, default=2.0, help="simulated time [s]")
    ap.add_argument("--line-nodes", type=int, default=LINE_NODES,
                    help="nodes of Kik-Piotrowski's separation line (40 mm)")
    ap.add_argument("--contact-only", action="store_true",
                    help="only the per-position contact time (section 1)")
    args = ap.parse_args(argv)
    ws = wr.Wheelset(wr.profiles.load("S1002"))
    tr = wr.Track(wr.profiles.load("60E1"))
    V, yaw = 30.0, 1e-3
    ys = np.linspace(-0.006, 0.007, 27)
    poses = positions(ws, tr, ys, yaw)
    print(f"load average {os.getloadavg()[0]:.2f}; NUMBA_NUM_THREADS="
          f"{os.environ.get('NUMBA_NUM_THREADS', 'unset')}")
    print(f"Kik-Piotrowski line: {args.line_nodes} nodes over 40 mm")
    print(f"S1002 / 60E1 1:40, {len(poses)} positions y = {ys[0] * 1e3:g} … {ys[-1] * 1e3:g} mm, "
          f"yaw {yaw * 1e3:g} mrad, approach 30 µm, V = {V:g} m/s, mu = 0.3")
    laws = [("kik-piotrowski", "fastsim"), ("hertz", "fastsim")]
    try:
        from wheelrail.tangential.table import load_table

        load_table(wr.tangential.Table().table)
        laws += [("hertz", wr.tangential.Table(outside="fastsim")),
                 ("kik-piotrowski", wr.tangential.Table(outside="fastsim"))]
    except Exception as exc:  # noqa: BLE001 - the table's data are optional
        print(f"(table law skipped: {exc})")
    print("\nper-position contact time, both wheels incl. contact search (compiled path):")
    print(f"{'normal':>16} {'tangential':>12} {'ms/position':>12} {'patches':>8}")
    for normal, tang in laws:
        opts = {"line_nodes": args.line_nodes} if normal == "kik-piotrowski" else {}
        nm, tm = D.configured_methods(normal, tang, opts)
        fc = FastContact(ws, tr, wr.STEEL, nm, tm)
        t = contact_time(fc, poses, yaw, V, ws.nominal_radius, args.repeat)
        op = np.zeros((KMAX, len(PATCH_FIELDS)))
        ow = np.zeros(len(WHEEL_FIELDS))
        npatch = sum(fc.wheel(s, y, zc, th, yaw, V, V / ws.nominal_radius, 0, 0, 0, 0, 0.3, op,
                              ow) for y, zc, th in poses for s in ("left", "right"))
        print(f"{nm.name:>16} {tm.name:>12} {t * 1e3:12.4f} {npatch / len(poses):8.2f}")
    if args.contact_only:
        print(f"\nload average {os.getloadavg()[0]:.2f}")
        return
    print(f"\nreal-time factor, suspended wheelset (1813 kg, 80 kN axle load), rk4 at 1 ms, "
          f"{args.duration:g} s simulated at {V:g} m/s from y = 3 mm:")
    model = D.WheelsetModel(ws, 1813.0, (1120.0, 100.0, 1120.0),
                            primary=D.Suspension(kx=5e6, ky=3.884e6, kz=1.2e6, cz=2e4,
                                                 half_spacing=1.0), axle_load=80e3)
    print(f"{'normal':>16} {'tangential':>12} {'RTF':>8} {'evals':>8} {'ms/eval':>8}")
    for normal, tang in laws:
        D.simulate(model, tr, V, 0.01, normal, tang, initial={"ws0.y": 0.003})   # warm-up
        res = D.simulate(model, tr, V, args.duration, normal, tang,
                         integrator=D.FixedStep(dt=1e-3), initial={"ws0.y": 0.003},
                         **({"line_nodes": args.line_nodes} if normal == "kik-piotrowski"
                            else {}))
        info = res.info
        print(f"{info['normal']:>16} {info['tangential']:>12} {info['real_time_factor']:8.2f} "
              f"{info['contact_evaluations']:8d} "
              f"{info['cpu_time'] / info['contact_evaluations'] * 1e3:8.4f}")
    print("\nsteady curving, Manchester vehicle 1 bogie (Iwnicki 1998), R = 300 m, 100 mm cant, "
          "Hertz + FASTSIM (CPU per equilibrium, first one with warm-up):")
    bogie = D.manchester_bogie()
    print(f"{'V m/s':>6} {'yaw lead mrad':>14} {'flange Fn kN':>13} {'CPU s':>7}")
    for speed in (10.0, 15.0, 20.0, 25.0):
        t0 = time.process_time()
        r = D.steady_curving(bogie, tr, 300.0, speed, "hertz", "fastsim", cant=0.1)
        fl = r.flange_contact(0)
        print(f"{speed:6.1f} {r.yaw[0] * 1e3:14.3f} {fl['Fn'] / 1e3 if fl else 0.0:13.2f} "
              f"{time.process_time() - t0:7.2f}")
    print(f"\nload average {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
