"""S1002 wheels on 60E1 rails inclined 1:40: rigid contact table, jumps, equivalent conicity
=========================================================================================

Run: ``python profiles_and_contact_table.py [OUT_DIR]``   (or set WHEELRAIL_OUT; default: cwd)
"""
import os
import sys
from pathlib import Path

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import wheelrail as wr

out = Path(sys.argv[1] if len(sys.argv) > 1 else os.environ.get("WHEELRAIL_OUT", "."))
out.mkdir(parents=True, exist_ok=True)
wheel, rail = wr.profiles.load("S1002"), wr.profiles.load("60E1")   # profile frames, SI, z up
print(f"S1002: y from {wheel.y_min:.4f} to {wheel.y_max:.4f} m; 60E1: z(0) = {float(rail(0)):.3g} m")
ws = wr.Wheelset(wheel, nominal_radius=0.46, flange_back=1.360)
tr = wr.Track(rail, gauge=1.435, inclination=1 / 40)
table = wr.contact_table(ws, tr, np.linspace(-0.008, 0.008, 33))    # xarray.Dataset, dim y
mid = table.sel(y=0.0)
print(f"delta_r_max = {float(table.delta_r.max()):.6e} m, "
      f"antisymmetry = {float(np.max(np.abs(table.delta_r + table.delta_r[::-1].values))):.3e} m")
print(f"contact_angle_at_0 = {float(mid.contact_angle_right_primary):.6f} rad, "
      f"rolling_radius_at_0 = {float(mid.rolling_radius_right_primary):.6f} m")
print("jumps of the contact point at y [mm]:", np.round(table.jump_y.values * 1e3, 2))
for amp in (0.002, 0.003, 0.004):
    print(f"conicity_{amp * 1e3:.0f}mm = {float(wr.equivalent_conicity(ws, tr, amp)):.4f}, "
          f"regression_{amp * 1e3:.0f}mm = "
          f"{float(wr.equivalent_conicity(ws, tr, amp, method='regression')):.4f}")
fig, ax = plt.subplots()
ax.plot(table.y * 1e3, table.delta_r * 1e3, ".-")
ax.set(xlabel="lateral shift y [mm]", ylabel="r_right - r_left [mm]", title="S1002 / 60E1 1:40")
fig.savefig(out / "delta_r.png", dpi=100)
table.drop_dims("jump").to_dataframe().to_csv(out / "contact_table.csv")
print("wrote", out / "delta_r.png", out / "contact_table.csv")
