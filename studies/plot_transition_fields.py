"""Maps of the contact's surface fields of a transition run (``bench_fe_transition.py
--fields FROM TO --results NAME``) around the onset of two-point contact.

Usage::

    python studies/plot_transition_fields.py NAME [--out docs/figures/PREFIX]

Writes ``PREFIX_stress.png`` (pressure, shear stress on the rail, adhesion),
``PREFIX_slip.png`` (normal relative velocity, micro-slip) and ``PREFIX_line.png`` (μ·p and
|q| along the rail) for the outputs two before the first flange patch, at it, and 1, 3, 6
and 12 after it; prints the per-patch numbers of every recorded output.
"""

from __future__ import annotations

import argparse
import json
import os

import numpy as np
import xarray as xr

from wheelrail.fe.plots import plot_contact_fields

RESULTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "benchmarks", "results", "fe_transition")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("name")
    ap.add_argument("--out", default=None, help="figure prefix (default results/NAME)")
    a = ap.parse_args()
    f = xr.open_dataset(os.path.join(RESULTS, f"{a.name}_fields.nc"))
    with open(os.path.join(RESULTS, f"{a.name}_info.json")) as fh:
        case = json.load(fh)["case"]
    mu = float(case.get("mu", 0.6))
    lab, st, P = f.patch.values, f.state.values, f.pressure.values
    T = np.stack([f[f"traction_{c}"].values for c in "xyz"], -1)
    V = np.stack([f[f"slip_{c}"].values for c in "xyz"], -1)
    q, v = np.linalg.norm(T, axis=-1), np.linalg.norm(V, axis=-1)
    print("travel [mm], per patch: nodes, adhering nodes, p_max, q_max [MPa], θ [°], Fn [kN]")
    for i in range(f.sizes["time"]):
        row = []
        for p in (1, 2):
            m = lab[i] == p
            if not m.any():
                row.append("-")
                continue
            A = f.area.values[i][m]
            Ft = (T[i][m] * A[:, None]).sum(0)
            th = np.degrees(np.arccos(np.clip(-Ft[0] / np.linalg.norm(Ft), -1, 1)))
            row.append(f"{m.sum()} {int((st[i][m] == 2).sum())} {P[i][m].max() / 1e6:5.0f} "
                       f"{q[i][m].max() / 1e6:4.0f} {th:4.1f} {(P[i][m] * A).sum() / 1e3:5.1f}")
        print(f"{f.travel.values[i] * 1e3:6.1f}  " + " | ".join(row))
    for p in (1, 2):
        m = (st == 1) & (lab == p) & (P > 0)
        cos = (T * V).sum(-1)[m] / np.maximum(q[m] * v[m], 1e-300)
        print(f"patch {p}, slipping nodes with pressure ({m.sum()}): cos(shear on the rail, "
              f"micro-slip) median {np.median(cos):.3f}, q/(μp) median "
              f"{np.median(q[m] / (mu * P[m])):.3f}, |micro-slip| median {np.median(v[m]):.2f} m/s")
    has2 = (lab == 2).any(axis=(1, 2))
    k = int(np.argmax(has2))
    outs = [j for j in (k - 2, k, k + 1, k + 3, k + 6, k + 12) if 0 <= j < f.sizes["time"]]
    prefix = a.out or os.path.join(RESULTS, a.name)
    aoa = float(case.get("angle_of_attack", 0.0)) * 1e3
    for kind in ("stress", "slip", "line"):
        plot_contact_fields(f, outs, kind=kind, mu=mu, path=f"{prefix}_{kind}.png",
                            title=f"{aoa:g} mrad")
    print("outputs", [round(float(x) * 1e3, 1) for x in f.travel.values[outs]], "->", prefix)


if __name__ == "__main__":
    main()
