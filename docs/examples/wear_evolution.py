"""Wheel profile evolution by wear: a bogie on a curve and tangent track
=======================================================================

A bogie runs 80 % of 50 km on a 300 m curve, 20 % on tangent track: the outer flanges thin.

Run: ``python wear_evolution.py [OUT_DIR]``   (or set WHEELRAIL_OUT; default: current directory)
"""
import os
import sys
from pathlib import Path

import matplotlib.pyplot as plt

import wheelrail as wr

D, W = wr.dynamics, wr.wear
out = Path(sys.argv[1] if len(sys.argv) > 1 else os.environ.get("WHEELRAIL_OUT", "."))
out.mkdir(parents=True, exist_ok=True)
tr = wr.Track(wr.profiles.load("60E1"))
bogie = D.manchester_bogie()            # the Manchester benchmark vehicle's bogie (Iwnicki 1998)
curve = D.TrackLayout(tr, curves=(D.Curve(300.0, start=5.0, transition=20.0, cant=0.1),))
tangent = D.TrackLayout(tr, irregularity=D.Irregularity.sine(0.002, 25.0, start=2.0, cycles=2))
route = W.Route((W.RouteCase(curve, 15.0, weight=0.8, distance=5.0, run_in=30.0, name="R300"),
                 W.RouteCase(tangent, 30.0, weight=0.2, distance=20.0, run_in=2.0)))
ds = W.evolve(bogie, route, mileage=50e3, law="usfd", step_depth=0.1e-3, profiles="sides",
              samples=10, cells=8, executor="serial").dataset
km, dSd, dcon = ds.mileage / 1e3, (ds.Sd - ds.Sd[0]) * 1e3, ds.conicity - ds.conicity[0]
print(f"Sd_loss_mm = {-float(dSd[-1, 0]):.4f}, conicity_change = {float(dcon[-1]):.4f}")
fig, ax = plt.subplots(1, 2, figsize=(10, 3.8), layout="tight")
for k in range(ds.sizes["step"]):            # both wheels (outer, inner) of step k in colour k
    ax[0].plot(ds.y * 1e3, (ds.wheel_z[k] - ds.wheel_z[0]).T * 1e3, color=f"C{k}")
ax[0].set(xlabel="y on the wheel [mm] (flange: y < -25)", ylabel="worn depth [mm] per step")
ax[1].plot(km, dSd[:, 0], "o-", km, dcon * 100, "^-")
ax[1].set(xlabel="mileage [km]", ylabel="ΔSd outer (o) [mm], Δ conicity (^) [×0.01]")
fig.savefig(out / "wear_evolution.png", dpi=100)
