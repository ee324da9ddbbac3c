"""Describe a contact in a TOML case file, load it, solve it, and switch the method
================================================================================

Run: ``python case_file.py [OUT_DIR]``   (or set WHEELRAIL_OUT; default: current directory)
"""
import json, os, sys
from pathlib import Path

import wheelrail as wr

out = Path(sys.argv[1] if len(sys.argv) > 1 else os.environ.get("WHEELRAIL_OUT", "."))
out.mkdir(parents=True, exist_ok=True); path = out / "wheel_on_rail.toml"
path.write_text("""\
[material]            # the same steel for wheel and rail (omit the table: this default)
E = 2.1e11
nu = 0.28
[contact]             # the contact ellipse, given by its semi-axes [m]
Fn = 10000.0
a = 0.006
b = 0.004
[creepage]            # wheel relative to rail (Kalker's convention)
xi = -0.0003
eta = 0.0002
[friction]
mu = 0.3
[method]
tangential = "fastsim"
[method.fastsim]      # options of the method
nx = 30
""", encoding="utf-8")
case = wr.load_case(path)                      # validated, frozen Case
summary = wr.run_case(case)                    # JSON-ready dict, SI units
(out / "wheel_on_rail.json").write_text(json.dumps(summary, indent=2), encoding="utf-8")
print(f"a = {summary['a']:.6e} m, b = {summary['b']:.6e} m, p0 = {summary['p0']:.6e} Pa")
print(f"fastsim: Fx = {summary['Fx']:.3f} N, Fy = {summary['Fy']:.3f} N, "
      f"utilisation = {summary['utilisation']:.6f}, status = {summary['status']}")
polach = wr.run_case(case.replace(tangential="polach"))      # same case, another law
print(f"polach: Fx = {polach['Fx']:.3f} N, Fy = {polach['Fy']:.3f} N")
print("wrote", out / "wheel_on_rail.json")
