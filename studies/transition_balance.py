"""Vertical balance of transition runs: Σ Fz against the wheel load and the climb's share.

For runs of ``bench_fe_transition.py --results NAME`` (``results/fe_transition/NAME_*``)
prints, over travel windows after the settle, the mean and scatter of the total vertical
contact force against the static wheel load Q, the part the prescribed climb of the axle
needs by the rigid profiles (:func:`wheelrail.fe.transition.analysis.climb_load`: the
unsprung mass's M_u (V sin α)² z″ and the primary suspension), and the remainder. With
``--fe-climb FROM TO DEG`` it also fits a polynomial of degree DEG in time to the FE axle's
own height w over that travel (the 180-220 Hz unsprung-mass mode averaged out) and takes
the climb from it: M_u w″ plus the primary suspension's k (w − w(FROM)) + c w′ (the sprung
mass, ≈ 2 Hz, taken as still). Usage::

    python benchmarks/bench_fe_transition.py --aoa 0.020 --travel 0.09 --clearance 0.007 \\
        --preload 0.001 --results a20_h4_c7_pre
    python studies/transition_balance.py a25_h4_c7_pre a20_h4_c7_pre \\
        a15_h4_c7_pre --out results/fe_transition/balance_c7_pre.txt
    python studies/transition_balance.py a25_h4_c7_t55_hold_pre \\
        --windows 0.03 0.09 0.09 0.15 0.15 0.21 0.21 0.27 0.03 0.27 --fe-climb 0.03 0.272 4
"""

from __future__ import annotations

import argparse
import json
import os

import numpy as np
import xarray as xr

import wheelrail as wr
from wheelrail.fe.transition.analysis import climb_load

RESULTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "benchmarks", "results", "fe_transition")


def one(name, windows, wheel_mass, fe_climb=None):
    h = xr.open_dataset(os.path.join(RESULTS, f"{name}_history.nc")).load()
    with open(os.path.join(RESULTS, f"{name}_info.json")) as f:
        info = json.load(f)
    case = wr.fe.seed004_case(**info["case"])
    Q = info["info"]["load"]
    s, t, fz = h.travel.values, h.time.values, h.Fz_total.values
    lines = [f"{name}: {info['case']}; wheel load {Q / 1e3:.2f} kN"]
    fe = None
    if fe_climb is not None:
        lo, hi, deg = fe_climb
        k = (s >= lo) & (s <= hi) & (t > 0)
        p = np.polyfit(t[k], h.w.values[k], int(deg))
        w_fit = np.polyval(p, t)
        w0 = w_fit[k][0]
        susp = case.suspension
        fe = ((susp.axle_mass + wheel_mass) * np.polyval(np.polyder(p, 2), t)
              + susp.stiffness * (w_fit - w0)
              + susp.damping * np.polyval(np.polyder(p, 1), t))
        rms = np.sqrt(np.mean((h.w.values[k] - w_fit[k]) ** 2))
        lines.append(f"  FE axle climb: w fitted over {lo * 1e3:.0f}-{hi * 1e3:.0f} mm by degree "
                     f"{int(deg)} in time (rms residual {rms * 1e6:.1f} µm; w rises "
                     f"{(w_fit[k][-1] - w0) * 1e6:.0f} µm)")
    for a, b in windows:
        m = (s >= a) & (s <= b) & (t > 0)
        if not m.any():
            continue
        climb = climb_load(case, np.linspace(a, b, 61), wheel_mass=wheel_mass)["total"].mean()
        mean = fz[m].mean()
        lines.append(f"  {a * 1e3:4.0f}-{b * 1e3:4.0f} mm: Σ Fz {mean / 1e3:6.1f} kN "
                     f"({(mean / Q - 1) * 100:+5.1f} %), std {fz[m].std() / 1e3:4.1f} kN; "
                     f"climb (rigid profiles) {climb / Q * 100:+5.1f} %; remainder "
                     f"{(mean - Q - climb) / Q * 100:+5.1f} %"
                     + ("" if fe is None else
                        f"; FE axle climb {fe[m].mean() / Q * 100:+5.1f} %, remainder "
                        f"{(mean - Q - fe[m].mean()) / Q * 100:+5.1f} %"))
    return lines


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("names", nargs="+")
    ap.add_argument("--windows", type=float, nargs="*", default=[0.03, 0.09, 0.04, 0.09,
                                                                   0.06, 0.09])
    ap.add_argument("--wheel-mass", type=float, default=211.0,
                    help="mass of the FE wheel [kg] (4 mm mesh: 211)")
    ap.add_argument("--fe-climb", type=float, nargs=3, metavar=("FROM", "TO", "DEG"),
                    help="the climb from a polynomial fit of the FE axle's height over this "
                         "travel [m]")
    ap.add_argument("--out")
    a = ap.parse_args()
    wins = list(zip(a.windows[::2], a.windows[1::2]))
    text = "\n".join(line for n in a.names for line in one(n, wins, a.wheel_mass, a.fe_climb))
    text += f"\nload average {os.getloadavg()[0]:.1f}\n"
    print(text, end="")
    if a.out:
        with open(a.out, "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
