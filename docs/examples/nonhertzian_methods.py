"""Every normal method on one wheel–rail position, against the boundary-element solution
=======================================================================================

S1002 on 60E1 (1:40) shifted 6 mm (near the flange root): each normal method with FASTSIM (BEM with the exact
theory) at the same creepages; Fn, contact area and p_max of the right wheel.
Run: ``python nonhertzian_methods.py [OUT_DIR]``   (or set WHEELRAIL_OUT)
"""
import os
import sys
from pathlib import Path

import matplotlib.pyplot as plt

import wheelrail as wr

out = Path(sys.argv[1] if len(sys.argv) > 1 else os.environ.get("WHEELRAIL_OUT", "."))
out.mkdir(parents=True, exist_ok=True)
ws = wr.Wheelset(wheel=wr.profiles.load("S1002"), nominal_radius=0.46, flange_back=1.360)
tr = wr.Track(rail=wr.profiles.load("60E1"), gauge=1.435, inclination=1 / 40)
wp = wr.WheelRailPosition(ws, tr, y=0.006, yaw=0.002, vertical_load=10e3)   # m, rad, N
rows = {}
for normal in wr.normal_methods():
    tangential, opts = ("exact", {"element_size": 4e-4}) if normal == "bem" else ("fastsim", {})
    res = wr.solve(wp, motion=wr.Motion(speed=20.0), mu=0.3, normal=normal,
                   tangential=tangential, **opts)
    right = [p for p in res.patches if p.side == "right"]
    rows[normal] = (sum(p.Fn for p in right), sum(p.area for p in right),
                    max(p.p_max for p in right), len(right))
    print(f"{normal}: patches = {len(right)}, Fn = {rows[normal][0]:.0f} N, "
          f"area = {rows[normal][1] * 1e6:.1f} mm2, p_max = {rows[normal][2] / 1e6:.0f} MPa")
fig, axes = plt.subplots(1, 2, figsize=(11, 4), layout="constrained")
for ax, k, label in ((axes[0], 1, "area / BEM"), (axes[1], 2, "p_max / BEM")):
    ax.bar(list(rows), [rows[m][k] / rows["bem"][k] for m in rows], color="tab:blue")
    ax.axhline(1.0, color="k", lw=0.8)
    ax.set_ylabel(label)
    ax.tick_params(axis="x", rotation=30)
fig.savefig(out / "nonhertzian_methods.png", dpi=100)
