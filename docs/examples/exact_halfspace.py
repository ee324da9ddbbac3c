"""Half-space (boundary-element) solution: normal pressure on a grid, then Kalker's exact rolling
==============================================================================================

Run: ``python exact_halfspace.py [OUT_DIR]``   (or set WHEELRAIL_OUT; default: current directory)
"""
import os
import sys
from pathlib import Path

import numpy as np

import wheelrail as wr

out = Path(sys.argv[1] if len(sys.argv) > 1 else os.environ.get("WHEELRAIL_OUT", "."))
out.mkdir(parents=True, exist_ok=True)
contact = wr.hertz(7500.0, A=0.5 / 0.46, B=0.5 / 0.30, material=wr.STEEL)
mu = 0.3

# Normal problem on a 40 x 40-element window around the Hertz ellipse (quadratic gap).
grid, gap = wr.hertz_grid(contact, elements=40)        # wheelrail.normal.bem.hertz_grid
normal = wr.solve_normal(grid, gap, contact.materials, Fn=contact.Fn)
print(f"bem_p_max = {normal.p_max:.6e} Pa (Hertz p0 = {contact.p0:.6e}), "
      f"bem_area = {normal.area:.6e} m2 (Hertz = {float(contact.area):.6e})")
np.save(out / "bem_pressure.npy", normal.pressure)

# Steady rolling with the exact theory (normal + tangential on the grid), one creepage at a time.
for xi in (-1e-4, -1e-3, -1e-2):
    ex = wr.creep_forces(contact, (xi, 0.0, 0.0), mu, method="exact", elements=30)
    fs = wr.creep_forces(contact, (xi, 0.0, 0.0), mu, method="fastsim")
    print(f"xi = {xi:g}: exact Fx = {ex.Fx:.3f} N, fastsim Fx = {fs.Fx:.3f} N, adhesion "
          f"fraction = {ex.info['adhesion_area'] / ex.info['area']:.3f}, status = {ex.status}")
ex = wr.creep_forces(contact, (-1e-3, 0.0, 0.0), mu, method="exact", elements=30)
print("fields:", type(ex.fields).__name__, "on", ex.fields.grid.nx, "x", ex.fields.grid.ny)
wr.plotting.traction_field(ex.fields, mu=mu, contact=contact, path=out / "exact_fields.png",
                           title="exact theory, xi = -1e-3: traction, adhesion/slip")
