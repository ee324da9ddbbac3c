"""A whole vehicle through a curve on irregular track, assessed after EN 14363
============================================================================

The Manchester benchmark vehicle 1 (Iwnicki 1998: a coach on two bogies, secondary
yaw stiffness, anti-roll bar and lateral bump stops) runs at 20 m/s into a 600 m curve
with 100 mm cant and clothoid transitions, on track with ERRI B176 low-level
irregularities in alignment, level, cross level and gauge generated from a seed.
Kik–Piotrowski + FASTSIM at every wheel, RK4 at 1 ms. :func:`wheelrail.dynamics.assess`
then gives the running-safety quantities of EN 14363 — (Y/Q) and (ΣY) as 2 m sliding
means against 0.8 and Prud'homme's 10 kN + P0/3 — and Sperling's ride index of the car
body.

Run: ``python vehicle_dynamics.py [OUT_DIR]``   (or set WHEELRAIL_OUT; default: current directory)
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

vehicle = D.manchester_vehicle1()                       # 4 wheelsets, 2 frames, car body
track = wr.Track(wr.profiles.load("60E1"), gauge=1.435, inclination=1 / 40)
irregular = D.TrackIrregularity.from_psd("erri-low", length=200.0, seed=3)
layout = D.TrackLayout(track, curves=(D.Curve(radius=600.0, start=10.0, length=60.0,
                                              transition=30.0, cant=0.1),),
                       irregularity=irregular)
res = D.simulate(vehicle, layout, 20.0, 6.0, "kik-piotrowski", "fastsim", mu=0.3,
                 output_step=2e-3)
print(f"{vehicle.n_wheelsets} wheelsets, axle load {vehicle.axle_load / 1e3:.1f} kN; "
      f"real-time factor {res.info['real_time_factor']:.2f} (CPU)")

table = D.assess(res)
for i in table["wheelset"].values:
    yq = table["Y_over_Q_2m_max"].sel(wheelset=i).values
    print(f"wheelset {i}: (Y/Q)2m max {np.max(np.abs(yq)):.3f} (limit 0.8), "
          f"(SumY)2m max {float(table['sum_Y_2m_max'].sel(wheelset=i)) / 1e3:.1f} kN "
          f"(limit {float(table['sum_Y_limit'].sel(wheelset=i)) / 1e3:.1f} kN)")
print(f"car body: Sperling Wz lateral {float(table['sperling_lateral']):.2f}, "
      f"vertical {float(table['sperling_vertical']):.2f}")

ds = res.dataset
# The car body's centre lies on the chord between its bogie centres, inside the curve's
# centre line by about kappa a_b^2 / 2 (75 mm at 600 m): shown relative to that chord.
s = ds["position"].values
kappa = layout.at(s)[0]
a_b = vehicle.bogie_semi_spacing
k_mean = 0.25 * (layout.at(s - a_b)[0] + 2 * kappa + layout.at(s + a_b)[0])
chord = 0.5 * a_b ** 2 * k_mean                     # y to the right, kappa > 0 to the right
fig, ax = plt.subplots(3, 1, figsize=(7, 8), layout="tight")
for i in ds["wheelset"].values:
    ax[0].plot(ds["position"], ds["y"].sel(wheelset=i) * 1e3, label=f"wheelset {i}")
ax[0].plot(s, (ds["body_y"] - chord) * 1e3, "k--", label="car body − chord offset")
ax[0].set(xlabel="distance [m]", ylabel="lateral shift [mm]")
ax[0].legend(fontsize="small", ncol=3)
for i in table["wheelset"].values:
    ax[1].plot(table["distance"], table["Y_over_Q_2m"].sel(wheelset=i, side="left"),
               label=f"ws{i} left")
ax[1].axhline(0.8, color="k", ls="--", lw=1)
ax[1].set(xlabel="distance [m]", ylabel="(Y/Q) 2 m [-]", ylim=(-0.1, 0.9))
ax[1].legend(fontsize="small", ncol=4)
ax[2].plot(ds["position"], irregular.at(ds["position"].values)["alignment"] * 1e3)
ax[2].set(xlabel="distance [m]", ylabel="alignment [mm]")
fig.savefig(out / "vehicle_dynamics.png", dpi=100)
