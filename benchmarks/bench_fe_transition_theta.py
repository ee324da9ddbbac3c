"""The tread patch's shear direction θ before and after the onset, three ways of averaging.

Reads the surface fields of a run of ``bench_fe_transition.py --fields FROM TO --results
NAME`` (``results/fe_transition/NAME_fields.nc``) and prints, over travel windows before
and after the onset of two-point contact, the medians of the tread patch's θ as the angle
of its mean shear stress (the patch histories' ``theta``), as the area-weighted mean of the
nodes' signed angles and as the mean of their absolute angles
(:func:`wheelrail.fe.transition_analysis.shear_direction`), with the patch's contact angle
and tangential forces. Usage::

    python benchmarks/bench_fe_transition.py --aoa 0.025 --travel 0.13 \
        --fields 0.06 0.125 --results a25_h4_wave_tread
    python benchmarks/bench_fe_transition_theta.py a25_h4_wave_tread a25_h4_t50 \
        --out results/fe_transition/theta_a25.txt
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import os

import numpy as np
import xarray as xr

from wheelrail.fe.transition_analysis import onset_travel, shear_direction

RESULTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "results", "fe_transition")


def windows(onset, start, end):
    w = [(start, onset - 0.030), (onset - 0.030, onset - 0.010), (onset - 0.010, onset),
         (onset, onset + 0.003), (onset + 0.003, onset + 0.010), (onset + 0.010, end)]
    return [(a, b) for a, b in w if b > a + 1e-4 and a >= start - 1e-9]


def one(name):
    fields = xr.open_dataset(os.path.join(RESULTS, f"{name}_fields.nc")).load()
    patches = xr.open_dataset(os.path.join(RESULTS, f"{name}_patches.nc")).load()
    with open(os.path.join(RESULTS, f"{name}_info.json")) as f:
        case = json.load(f)["case"]
    onset = onset_travel(patches)
    sd = shear_direction(fields, patch=1)
    s = sd.travel.values
    k = np.searchsorted(patches.time.values, sd.time.values)
    ang = np.degrees(patches.contact_angle.values[k, 0])
    fl = patches.F_long.values[k, 0] / 1e3
    ft = patches.F_lat.values[k, 0] / 1e3
    fn = patches.Fn.values[k, 0] / 1e3
    print(f"{name}: {case}; onset {onset * 1e3:.1f} mm; fields {s[0] * 1e3:.1f}-"
          f"{s[-1] * 1e3:.1f} mm at {s.size} outputs")
    print("  travel [mm]     outputs  θ mean stress  θ mean angle  θ mean |angle|  "
          "contact angle  Fn [kN]  F_long  F_lat  nodes   (medians)")
    for a, b in windows(onset, s[0], s[-1]):
        m = (s >= a) & (s < b) & np.isfinite(sd.mean_stress.values)
        if not m.any():
            continue
        med = lambda v: float(np.median(v[m]))  # noqa: E731
        print(f"  {a * 1e3:6.1f}-{b * 1e3:6.1f}  {m.sum():6d}   {med(np.abs(sd.mean_stress.values)):8.1f}°"
              f"    {med(sd.mean_angle.values):8.1f}°    {med(sd.mean_abs_angle.values):8.1f}°"
              f"      {med(ang):6.1f}°    {med(fn):6.1f}  {med(fl):6.1f} {med(ft):6.1f}"
              f"  {med(sd.n_nodes.values):5.0f}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("names", nargs="+")
    ap.add_argument("--out")
    a = ap.parse_args()
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf) if a.out else contextlib.nullcontext():
        for name in a.names:
            one(name)
        print(f"load average {os.getloadavg()[0]:.1f}")
    if a.out:
        print(buf.getvalue(), end="")
        with open(a.out, "w") as f:
            f.write(buf.getvalue())


if __name__ == "__main__":
    main()
