"""A wheelset on a track: contact patches and forces with two method pairs, and a sweep
====================================================================================
"""
import sys
from os import environ
from pathlib import Path

import numpy as np

import wheelrail as wr

out = Path(sys.argv[1] if len(sys.argv) > 1 else environ.get("WHEELRAIL_OUT", "."))
ws = wr.Wheelset(wheel=wr.profiles.load("S1002"), nominal_radius=0.46, flange_back=1.360)
tr = wr.Track(rail=wr.profiles.load("60E1"), gauge=1.435, inclination=1 / 40)
motion = wr.Motion(speed=20.0)                       # free rolling at r0, m/s
wp = wr.WheelRailPosition(ws, tr, y=0.0068, yaw=0.003, vertical_load=10e3)   # N per wheel
for normal, tangential, opts in (("hertz", "fastsim", {}),
                                 ("bem", "exact", {"element_size": 4e-4})):
    res = wr.solve(wp, motion=motion, mu=0.3, normal=normal, tangential=tangential, **opts)
    for p in res.patches:
        print(f"{normal}+{tangential} {p.side}: gamma = {np.degrees(p.contact_angle):.2f} deg, "
              f"Fn = {p.Fn:.0f} N, Fx = {p.Fx:.0f} N, Fs = {p.Fs:.0f} N, "
              f"p_max = {p.p_max / 1e6:.0f} MPa")
    print(f"{normal}_Fz_right = {res.force_track['right'][2]:.2f}")
    print(f"{normal}_Fy_right = {res.force_track['right'][1]:.1f}")
wr.plotting.contact_profiles(res, path=out / "wheelset_patches.png", title="BEM + exact patches")
ds = wr.wheelset_sweep(ws, tr, y=np.linspace(-0.008, 0.008, 81), vertical_load=10e3,
                       motion=motion, yaw=0.0)
ds.to_netcdf(out / "wheelset_sweep.nc")
print("sweep_solved =", int((ds.status != "error").sum()))
print("sweep_flange_climb =", int((ds.status == "flange_climb").sum()))  # rows flagged, not errors
print("sweep_max_patches =", int(ds.n_patches.max()))
