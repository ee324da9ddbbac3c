"""Wheel profile evolution by wear: a bogie on a curve and tangent track
=======================================================================

The Manchester benchmark vehicle's bogie (S1002 wheels, 60E1 rails 1:40) runs a
route of a 300 m curve with 100 mm cant (80 % of the mileage) and tangent track
with a 2 mm alignment sine (20 %). :func:`wheelrail.wear.evolve` simulates both
cases with :mod:`wheelrail.dynamics`, wears the wheels with the USFD Tγ/A law
and updates the profiles step by step (largest depth change 0.1 mm per step).
The outer wheels (left: the curve turns right) wear at the flange root and their
flange thickness Sd falls; the tread wear raises the equivalent conicity.
Tiny settings (a few metres simulated per step) keep it to seconds.

Run: ``python wear_evolution.py [OUT_DIR]``   (or set WHEELRAIL_OUT; default: current directory)
"""
import os
import sys
from pathlib import Path

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

import wheelrail as wr

D = wr.dynamics
out = Path(sys.argv[1] if len(sys.argv) > 1 else os.environ.get("WHEELRAIL_OUT", "."))
out.mkdir(parents=True, exist_ok=True)

ws, tr = wr.Wheelset(wr.profiles.load("S1002")), wr.Track(wr.profiles.load("60E1"))
primary = D.Suspension(kx=31.391e6, ky=3.884e6, kz=1.22e6, cx=15e3, cy=2e3, cz=4e3,
                       half_spacing=1.0)
secondary = D.Suspension(kx=0.16e6, ky=0.16e6, kz=0.43e6, cy=32e3, cz=20e3, half_spacing=1.0)
bogie = D.BogieModel(ws, 1813.0, (1120.0, 112.0, 1120.0), primary, 2615.0,
                     (1722.0, 1476.0, 3067.0), 1.28, secondary, axle_load=109.1e3, spin="fixed")
curve = D.TrackLayout(tr, curves=(D.Curve(radius=300.0, start=5.0, transition=20.0, cant=0.1,
                                          direction="right"),))
tangent = D.TrackLayout(tr, irregularity=D.Irregularity.sine(0.002, 25.0, start=2.0,
                                                             cycles=2.0))
route = wr.wear.Route((
    wr.wear.RouteCase(curve, 15.0, weight=0.8, distance=5.0, run_in=30.0, name="R300"),
    wr.wear.RouteCase(tangent, 30.0, weight=0.2, distance=20.0, run_in=2.0, name="tangent"),
))
res = wr.wear.evolve(bogie, route, mileage=50e3, law="usfd", step_depth=0.1e-3,
                     smoothing=2e-3, profiles="sides", samples=10, cells=8,
                     executor="serial")
ds = res.dataset
km = ds.mileage.values / 1e3
print(f"steps = {ds.sizes['step']}, mileage = {km[-1]:.1f} km")
print(f"Sd_outer_loss_mm = {(ds.Sd.values[0, 0] - ds.Sd.values[-1, 0]) * 1e3:.4f}")
print(f"Sd_inner_loss_mm = {(ds.Sd.values[0, 1] - ds.Sd.values[-1, 1]) * 1e3:.4f}")
print(f"conicity_start = {float(ds.conicity[0]):.4f}, conicity_end = "
      f"{float(ds.conicity[-1]):.4f}")

fig, ax = plt.subplots(1, 2, figsize=(10, 4), layout="tight")
y = ds.y.values * 1e3
for k in range(ds.sizes["step"]):
    depth = (ds.wheel_z.isel(step=k) - ds.wheel_z.isel(step=0)).values * 1e3
    color = plt.cm.viridis(k / max(ds.sizes["step"] - 1, 1))
    ax[0].plot(y, depth[0], color=color, label=f"outer, {km[k]:.0f} km")
    ax[0].plot(y, depth[1], color=color, ls="--")
ax[0].set(xlabel="lateral coordinate y on the wheel [mm] (flange at y < -25 mm)",
          ylabel="worn depth [mm]", title="wear of the wheel profile (dashed: inner wheels)")
ax[0].legend(fontsize="small")
prof = ax[0].twinx()
prof.plot(y, ds.wheel_z.isel(step=0, side=0).values * 1e3, color="0.6", lw=0.8)
prof.invert_yaxis()
prof.set_ylabel("new S1002 profile z [mm] (grey)")
ax[1].plot(km, (ds.Sd.sel(side="left") - ds.Sd.sel(side="left")[0]) * 1e3, "o-",
           label="ΔSd outer wheels [mm]")
ax[1].plot(km, (ds.Sd.sel(side="right") - ds.Sd.sel(side="right")[0]) * 1e3, "s-",
           label="ΔSd inner wheels [mm]")
ax[1].set(xlabel="mileage [km]", ylabel="change of flange thickness Sd [mm]")
con = ax[1].twinx()
con.plot(km, ds.conicity, "k^-", label="equivalent conicity")
con.set_ylabel("equivalent conicity [-] (triangles)")
ax[1].legend(loc="lower left", fontsize="small")
fig.savefig(out / "wear_evolution.png", dpi=100)
