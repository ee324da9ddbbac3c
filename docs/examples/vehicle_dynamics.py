"""A whole vehicle through a curve on irregular track, assessed after EN 14363
============================================================================

Manchester vehicle 1 (Iwnicki 1998), 20 m/s, 600 m curve, ERRI B176 low-level irregularities,
KP + FASTSIM; ``assess``: 2 m means of Y/Q and ΣY against 0.8 and 10 kN + P0/3, Sperling's Wz.

Run: ``python vehicle_dynamics.py [OUT_DIR]``   (or set WHEELRAIL_OUT; default: current directory)
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
vehicle = D.manchester_vehicle1()                       # 4 wheelsets, 2 frames, car body
irregular = D.TrackIrregularity.from_psd("erri-low", length=200.0, seed=3)
layout = D.TrackLayout(wr.Track(wr.profiles.load("60E1")), irregularity=irregular, curves=(
    D.Curve(radius=600.0, start=10.0, length=40.0, transition=30.0, cant=0.1),))
res = D.simulate(vehicle, layout, 20.0, 5.0, "kik-piotrowski", "fastsim", output_step=2e-3)
table = D.assess(res)
print(f"axle_load = {vehicle.axle_load:.1f} N, "
      f"Y_over_Q_2m_max = {float(abs(table['Y_over_Q_2m_max']).max()):.3f} (limit 0.8), "
      f"sum_Y_2m_max = {float(abs(table['sum_Y_2m_max']).max()):.0f} N "
      f"(limit {float(table['sum_Y_limit'].min()):.0f} N), "
      f"sperling_lateral = {float(table['sperling_lateral']):.2f}")
fig, ax = plt.subplots(2, 1, figsize=(7, 6), layout="tight")
for i in table["wheelset"].values:
    ax[0].plot(res.position, res.dataset["y"].sel(wheelset=i) * 1e3, label=f"wheelset {i}")
    ax[1].plot(table["distance"], table["Y_over_Q_2m"].sel(wheelset=i, side="left"))
ax[0].set(xlabel="distance [m]", ylabel="lateral shift [mm]"), ax[0].legend(ncol=2)
ax[1].set(xlabel="distance [m]", ylabel="(Y/Q) 2 m, outer wheels [-]")
fig.savefig(out / "vehicle_dynamics.png", dpi=100)
