"""Longitudinal creep curves Fx(xi) of the fast creep-force laws on one Hertz contact
==================================================================================

Run: ``python creep_curves.py [OUT_DIR]``   (or set WHEELRAIL_OUT; default: current directory)
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
contact = wr.hertz(7500.0, A=0.5 / 0.46, B=0.5 / 0.30, material=wr.STEEL)
mu = 0.3
xi = -np.linspace(0.0, 0.01, 101)          # xi < 0: driving wheel, Fx > 0 (forward on the wheel)
creep = np.column_stack([xi, np.zeros_like(xi), np.zeros_like(xi)])   # shape (101, 3)
print(f"a = {contact.a:.6e} m, b = {contact.b:.6e} m, G = {contact.G:.6e} Pa, nu = {contact.nu}")

fig, ax = plt.subplots()
for method in ["linear", "carter", "fastsim", "shen-hedrick-elkins", "polach"]:
    r = wr.creep_forces(contact, creep, mu, method=method)   # one call for all 101 creepages
    ax.plot(-xi * 1e3, r.Fx / (mu * contact.Fn), label=method)
    print(f"{method}: Fx(xi={xi[10]:g}) = {r.Fx[10]:.3f} N, Fx(xi={xi[-1]:g}) = {r.Fx[-1]:.3f} N")
# Small-creepage slope of the linear theory, as Kalker's coefficient C11 = -Fx / (G c^2 xi)
lin = wr.creep_forces(contact, (-1e-6, 0.0, 0.0), mu, method="linear")
print(f"C11_from_linear = {lin.Fx / (contact.G * contact.a * contact.b * 1e-6):.4f}")
ax.set(xlabel="-xi [1e-3]", ylabel="Fx / (mu Fn)", ylim=(0, 1.2), title="creep curves, mu = 0.3")
ax.legend()
fig.savefig(out / "creep_curves.png", dpi=100)
print("wrote", out / "creep_curves.png")
