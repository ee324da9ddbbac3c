"""Hertz contact of a wheel on a rail: semi-axes, pressure, approach; batch over loads
===================================================================================

Run: ``python hertz_basics.py [OUT_DIR]``   (or set WHEELRAIL_OUT; default: current directory)
"""
import os
import sys
from pathlib import Path

import numpy as np

import wheelrail as wr

out = Path(sys.argv[1] if len(sys.argv) > 1 else os.environ.get("WHEELRAIL_OUT", "."))
out.mkdir(parents=True, exist_ok=True)

# Wheel rolling radius 0.46 m on a rail head of transverse radius 0.30 m, 7.5 kN, steel.
c = wr.hertz_from_radii(7500.0, wheel_rolling_radius=0.46, rail_profile_radius=0.30,
                        material=wr.STEEL)
print(f"A = {c.A:.6g} 1/m, B = {c.B:.6g} 1/m")
print(f"a = {c.a:.6e} m, b = {c.b:.6e} m, p0 = {c.p0:.6e} Pa, delta = {c.penetration:.6e} m")
print(f"area = {c.area:.6e} m2, Fn/area = {c.Fn / c.area:.6e} Pa (= 2/3 p0)")

# Inverse problem: the load that produces this approach.
back = wr.hertz_from_penetration(c.penetration, c.A, c.B, wr.STEEL)
print(f"load_from_penetration = {back.Fn:.6f} N")

# A batch: arrays in, arrays out (a grows like Fn^(1/3)).
batch = wr.hertz(np.array([2500.0, 5000.0, 10000.0, 20000.0]), c.A, c.B, wr.STEEL)
np.savetxt(out / "hertz_batch.csv", np.column_stack([batch.Fn, batch.a, batch.b, batch.p0]),
           delimiter=",", header="load_N,a_m,b_m,p0_Pa")
print("a(20 kN)/a(2.5 kN) =", f"{batch.a[-1] / batch.a[0]:.6f}", "(2 expected)")

# Sphere of radius 0.05 m on a flat: A = B = 1/(2R), a circle.
s = wr.hertz(1000.0, A=0.5 / 0.05, B=0.5 / 0.05, material=wr.STEEL)
print(f"sphere_a = {s.a:.9e} m, sphere_p0 = {s.p0:.9e} Pa, sphere_delta = {s.penetration:.9e} m")
print("wrote", out / "hertz_batch.csv")
