"""A wheelset in time: Klingel's oscillation and hunting above the critical speed
===============================================================================

Run: ``python wheelset_dynamics.py [OUT_DIR]``   (or set WHEELRAIL_OUT; default: current directory)
"""
import os
import sys
from pathlib import Path

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import wheelrail as wr

D = wr.dynamics
out = Path(sys.argv[1] if len(sys.argv) > 1 else os.environ.get("WHEELRAIL_OUT", "."))
out.mkdir(parents=True, exist_ok=True)
ws_c, tr_c = D.cone_track(0.2, 0.46, 0.75, crown_radius=0.02)   # conicity, r0, l0 [m]
free = D.WheelsetModel(ws_c, 1813.0, (1120.0, 100.0, 1120.0), spin="fixed")
res = D.simulate(free, tr_c, 5.0, 3.6, "hertz", "linear", initial={"ws0.y": 0.001})
y = res.state("ws0.y")
up = np.flatnonzero((y[:-1] < 0) & (y[1:] >= 0))                   # upward zero crossings
s_up = res.position[up] - y[up] * (res.position[up + 1] - res.position[up]) / (y[up + 1] - y[up])
print(f"wavelength = {np.diff(s_up).mean():.4f} m (Klingel: 2 pi sqrt(r0 l0 / conicity))")
ws, tr = wr.Wheelset(wr.profiles.load("S1002")), wr.Track(wr.profiles.load("60E1"))
model = D.WheelsetModel(ws, 1813.0, (1120.0, 100.0, 1120.0), axle_load=80e3,
                        primary=D.Suspension(kx=1e6, ky=3.884e6, half_spacing=1.0))
V = 1.2 * D.critical_speed(model, tr, "hertz", "fastsim", method="linear").speed
hunt = D.simulate(model, tr, V, 1.5, "kik-piotrowski", "fastsim", initial={"ws0.y": 0.005})
print(f"V = {V:.2f} m/s, real-time factor {hunt.info['real_time_factor']:.1f}")
fig, ax = plt.subplots(2, 1, figsize=(7, 6), layout="tight")
ax[0].plot(res.position, y * 1e3, label="free conical wheelset, 5 m/s")
ax[1].plot(hunt.t, hunt.state("ws0.y") * 1e3, label=f"S1002/60E1, KP + FASTSIM, {V:.0f} m/s")
for a, x in zip(ax, ("distance [m]", "time [s]")):
    a.set(xlabel=x, ylabel="lateral shift y [mm]")
    a.legend()
fig.savefig(out / "wheelset_dynamics.png", dpi=100)
