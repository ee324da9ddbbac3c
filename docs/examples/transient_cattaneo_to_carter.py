"""Transient rolling: from Cattaneo to Carter when a tangential force is applied at once
=====================================================================================

Baeza et al. §3.1 on a coarse grid: F3 = 10 kN, F1 = 2 kN from the first step, μ = 0.4.
The creepage overshoots, then settles on the steady rolling solution.
Run: ``python transient_cattaneo_to_carter.py [OUT_DIR]``   (or set WHEELRAIL_OUT)
"""
import os
import sys
from pathlib import Path

import wheelrail as wr
from wheelrail.transient.plot import plot_creepage

out = Path(sys.argv[1] if len(sys.argv) > 1 else os.environ.get("WHEELRAIL_OUT", "."))
out.mkdir(parents=True, exist_ok=True)
# wheel radius 0.5 m, concave wheel profile 0.409 m, rail crown 0.3 m (Baeza et al., Table 1)
contact = wr.hertz_from_radii(10e3, wheel_rolling_radius=0.5, rail_profile_radius=0.3,
                              wheel_profile_radius=-0.409, material=wr.Material(2.1e11, 0.3))
a = float(contact.a)
res = wr.transient_rolling(contact, travel=8 * a, step=a / 8, mu=0.4, Fn=10e3,
                           Fx=2000.0, elements=16)
ds = res.dataset                                   # xarray.Dataset over travel x [m]
xi = ds["xi"].values
steady = wr.solve_creepages(contact, 0.4, Fx=2000.0, method="exact", elements=16)
print(f"semi_axis_a = {a:.6e} m, steps = {ds.sizes['x']}")
xs = float(steady.info["xi"])                     # steady exact theory, same load and force
print(f"xi_final = {xi[-1]:.6e}, xi_steady_exact = {xs:.6e}")
print(f"overshoot = {abs(xi[4:]).max() / abs(xs) - 1:.4f} (after the first steps' Cattaneo shift)")
plot_creepage(res, path=out / "transient_creepage.png",
              title="F1 = 2 kN applied at once: creepage over travel (16 elements over 2a)")
ds.to_netcdf(out / "transient.nc")
