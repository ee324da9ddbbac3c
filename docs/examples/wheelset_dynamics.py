"""A wheelset in time: Klingel's oscillation, hunting above the critical speed, flange climb
=========================================================================================

Three uses of ``wr.dynamics`` with the contact of both wheels computed online:

1. a free conical wheelset on nearly knife-edge rails runs Klingel's kinematic
   oscillation, wavelength 2π √(r0 l0/λ) = 8.25 m (Klingel 1883);
2. a suspended S1002 wheelset on 60E1 below and above its linear critical
   speed (Kik–Piotrowski + FASTSIM): the disturbance decays, or grows into a
   hunting limit cycle with flange contact;
3. Pascal's quasi-static flange climb: Y/Q of the flanging wheel against
   Nadal's limit at the flange angle (Nadal 1896).

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

# 1. Klingel: free conical wheelset (r0 = 0.46 m, l0 = 0.75 m, λ = 0.2) at 5 m/s
ws_c, tr_c = D.cone_track(0.2, 0.46, 0.75, crown_radius=0.02)
free = D.WheelsetModel(ws_c, 1813.0, (1120.0, 100.0, 1120.0), spin="fixed")
V = 5.0
res = D.simulate(free, tr_c, V, 3.6, "hertz", "linear", initial={"ws0.y": 0.001})
y = res.state("ws0.y")
up = np.flatnonzero((y[:-1] < 0) & (y[1:] >= 0))
tc = res.t[up] - y[up] * (res.t[up + 1] - res.t[up]) / (y[up + 1] - y[up])
print(f"Klingel: simulated wavelength {V * np.diff(tc).mean():.3f} m, "
      f"closed form {D.klingel_wavelength(0.46, 0.75, 0.2):.3f} m")

# 2. S1002 / 60E1: the linear critical speed, then runs below and above it
ws = wr.Wheelset(wr.profiles.load("S1002"))
tr = wr.Track(wr.profiles.load("60E1"))
model = D.WheelsetModel(ws, 1813.0, (1120.0, 100.0, 1120.0),
                        primary=D.Suspension(kx=1e6, ky=3.884e6, half_spacing=1.0),
                        axle_load=80e3)
lin = D.critical_speed(model, tr, "hertz", "fastsim", method="linear")
print(f"linear critical speed {lin.speed:.1f} m/s, {lin.frequency:.2f} Hz")
runs = {}
for factor in (0.8, 1.2):
    r = D.simulate(model, tr, factor * lin.speed, 1.5, "kik-piotrowski", "fastsim",
                   initial={"ws0.y": 0.005}, output_step=2e-3)
    runs[factor] = r
    print(f"V = {factor * lin.speed:.1f} m/s: max |y| over the last 0.3 s "
          f"{np.abs(r.state('ws0.y')[r.t > 1.2]).max() * 1e3:.2f} mm, "
          f"real-time factor {r.info['real_time_factor']:.1f}")

# 3. flange climb at 20 mrad angle of attack, μ = 0.3
fc = D.flange_climb(D.WheelsetModel(ws, 1500.0, (800.0, 100.0, 800.0), axle_load=100e3), tr,
                    yaw=0.02, normal="hertz", tangential="fastsim", mu=0.3)
g = fc.contact_angle[fc.lift]
print(f"flange climb: Y/Q at wheel lift {fc.Y_over_Q[fc.lift]:.3f}, flange angle "
      f"{np.degrees(g):.1f}°, Nadal {D.nadal(g, 0.3):.3f}")

fig, ax = plt.subplots(3, 1, figsize=(7, 9))
ax[0].plot(res.position, y * 1e3)
ax[0].set(xlabel="distance [m]", ylabel="y [mm]",
          title="free conical wheelset (Klingel: wavelength "
                f"{D.klingel_wavelength(0.46, 0.75, 0.2):.2f} m)")
for factor, r in runs.items():
    ax[1].plot(r.t, r.state("ws0.y") * 1e3, label=f"V = {factor:g} × V_crit,lin")
ax[1].set(xlabel="time [s]", ylabel="y [mm]", title="S1002 / 60E1, Kik–Piotrowski + FASTSIM")
ax[1].legend()
ax[2].plot(fc.y * 1e3, fc.Y_over_Q, label="Y/Q, flanging wheel")
ax[2].axhline(D.nadal(g, 0.3), color="k", ls="--", label="Nadal, μ = 0.3")
ax[2].axvline(fc.y[fc.lift] * 1e3, color="grey", ls=":", label="wheel lift")
ax[2].set(xlabel="lateral shift [mm]", ylabel="Y/Q", title="quasi-static flange climb, 20 mrad")
ax[2].legend()
fig.tight_layout()
fig.savefig(out / "wheelset_dynamics.png", dpi=100)
print("wrote", out / "wheelset_dynamics.png")
