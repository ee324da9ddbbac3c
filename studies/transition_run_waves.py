"""Surface-wave speed from a transition run's own motion (phase spectra of a rail line).

A run of ``bench_fe_transition.py`` with ``--wave TRAVEL TIME LINE --results NAME`` stores
the velocities of one rail surface line (the tread contact's or the flange contact's) every
step in ``results/fe_transition/NAME_wave.npz``. This script cuts that record into windows
of travel, takes the contact patch's position from ``NAME_patches.nc`` as the source, and
measures the phase velocity of the motion travelling away from it over frequency bands
(:func:`wheelrail.fe.transition.phase_velocity`: the slope of the Fourier phase over the stations).
For comparison it measures the same bands on a clean Ricker pulse struck at the same line
of the same mesh (:func:`wheelrail.fe.transition.rail_pulse`) and prints the Rayleigh speed of the
steel. Usage::

    python benchmarks/bench_fe_transition.py --aoa 0.025 --travel 0.13 \
        --wave 0.07 2.65e-3 flange --results a25_h4_wave_flange
    python studies/transition_run_waves.py a25_h4_wave_flange \
        --out results/fe_transition/run_waves_a25_flange.txt --figure ...png
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import os
import time

import numpy as np
import xarray as xr

from wheelrail.errors import InputError
from wheelrail.fe.transition import seed004_case
from wheelrail.fe.transition.analysis import onset_travel
from wheelrail.fe.transition.model import build_transition_model
from wheelrail.fe.transition.wave import elastic_wave_speeds, phase_velocity, rail_pulse

RESULTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "benchmarks", "results", "fe_transition")
BANDS = ((10e3, 20e3), (20e3, 40e3), (40e3, 70e3), (60e3, 100e3))
DISTANCES = {"ahead": (0.015, 0.06), "behind": (0.015, 0.045)}


def load(name):
    with np.load(os.path.join(RESULTS, f"{name}_wave.npz")) as z:
        rec = {k: z[k] for k in z.files}
    patches = xr.open_dataset(os.path.join(RESULTS, f"{name}_patches.nc")).load()
    with open(os.path.join(RESULTS, f"{name}_info.json")) as f:
        info = json.load(f)
    return rec, patches, info


def window(rec, patches, s_from, s_to, patch, case):
    """The record between two travels, with x measured from ``patch``'s centre at the
    window's start (the source) and the source moving on at the rolling speed."""
    t = rec["t"]
    t_a, t_b = s_from / case.speed, s_to / case.speed       # travel = V t
    k = (t >= t_a) & (t < t_b)
    if k.sum() < 100:
        raise InputError(f"the record does not cover {s_from}-{s_to} m")
    # the source: the patch's pressure-weighted centre (global x) at the window's start
    i = int(np.argmin(np.abs(patches.travel.values - s_from)))
    xs = float(patches.x.values[i, patch - 1])
    if not np.isfinite(xs):
        raise InputError(f"patch {patch} is not in contact at {s_from} m")
    # record x is measured from the wheel centre at the record's start (global x of the
    # centre: travel cos(angle of attack))
    x_glob = rec["x"] + float(rec["travel"]) * np.cos(case.angle_of_attack)
    return {"x": x_glob - xs, "t": t[k], "v": rec["v"][k], "normal": rec["normal"],
            "speed": float(rec["speed"])}


def fit(rec, band, side, comp):
    lo, hi = DISTANCES[side]
    try:
        return phase_velocity(rec, band=band, d_min=lo, d_max=hi, side=side, component=comp)
    except InputError:
        return None


def table(rec, label, key, rows, bands):
    """One printed line per side and component: the speed (accepted share) per band."""
    for side in ("ahead", "behind"):
        for comp in ("z", "n"):
            cells = []
            for band in bands:
                r = fit(rec, band, side, comp)
                cells.append("      —      " if r is None else
                             f"{r['speed']:6.0f} ({r['accepted']:.2f})")
                rows.append((*key, side, comp, band, r))
            print(f"  {label}  {side:6s} v_{comp}: " + "  ".join(cells))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("name", help="NAME of results/fe_transition/NAME_wave.npz")
    ap.add_argument("--windows", type=float, nargs="*",
                    help="travel windows FROM TO FROM TO ... [m] (default: 13.3 mm windows "
                         "before and after the onset)")
    ap.add_argument("--bands", type=float, nargs="*",
                    help="frequency bands FROM TO FROM TO ... [kHz] (default 10-20, 20-40, "
                         "40-70, 60-100)")
    ap.add_argument("--out")
    ap.add_argument("--figure")
    a = ap.parse_args()
    a.bands = (tuple((lo * 1e3, hi * 1e3) for lo, hi in zip(a.bands[::2], a.bands[1::2]))
               if a.bands else BANDS)
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf) if a.out else contextlib.nullcontext():
        run(a)
    if a.out:
        text = buf.getvalue()
        print(text, end="")
        with open(a.out, "w") as f:
            f.write(text)


def run(a):
    rec, patches, info = load(a.name)
    case_kw = info["case"]
    case = seed004_case(**case_kw)
    line = str(rec["line"])
    onset = onset_travel(patches)
    s0 = float(rec["travel"])
    s1 = float(rec["t"][-1]) * case.speed
    if a.windows:
        wins = list(zip(a.windows[::2], a.windows[1::2]))
    else:
        wins = [(max(s0, onset - 0.040), onset - 0.005), (onset, s1)]
    sp = elastic_wave_speeds(case.material.E, case.material.nu, case.material.density)
    print(f"run {a.name}: {case_kw}; {line} line, {rec['x'].size} nodes, record "
          f"{s0 * 1e3:.1f}-{s1 * 1e3:.1f} mm of travel ({rec['t'].size} samples of "
          f"{(rec['t'][1] - rec['t'][0]) * 1e9:.0f} ns); onset {onset * 1e3:.1f} mm; "
          f"c_R {sp['c_R']:.0f}, c_s {sp['c_s']:.0f}, c_p {sp['c_p']:.0f} m/s")
    print("phase velocity [m/s]: 1/(power-weighted mean slowness) over the frequencies "
          "with R^2 >= 0.9 (their share in brackets); stations "
          f"{DISTANCES['ahead'][0] * 1e3:.0f}-{DISTANCES['ahead'][1] * 1e3:.0f} mm ahead of / "
          f"{DISTANCES['behind'][0] * 1e3:.0f}-{DISTANCES['behind'][1] * 1e3:.0f} mm behind "
          "the source patch's centre")
    rows = []
    for s_from, s_to in wins:
        for patch in (1, 2):
            if patch == 2 and s_from < onset:
                continue
            try:
                wrec = window(rec, patches, s_from, s_to, patch, case)
            except InputError as e:
                print(f"  {s_from * 1e3:.1f}-{s_to * 1e3:.1f} mm, patch {patch}: {e}")
                continue
            table(wrec, f"{s_from * 1e3:5.1f}-{s_to * 1e3:5.1f} mm  source patch {patch}",
                  (s_from, s_to, patch), rows, a.bands)
    # the same bands on a clean pulse at the same line of the same mesh
    t0 = time.process_time()
    model = build_transition_model(case)
    pulse = rail_pulse(case, model=model, at=line, frequency=60e3)
    print(f"clean Ricker pulse (60 kHz) at the {line} line, same mesh "
          f"({pulse.info['elements']} elements, {pulse.info['steps']} steps, "
          f"{time.process_time() - t0:.1f} s CPU):")
    table(pulse, "pulse", ("pulse", None, None), rows, a.bands)
    print("bands [kHz]: " + ", ".join(f"{b[0] / 1e3:.0f}-{b[1] / 1e3:.0f}" for b in a.bands))
    print(f"load average {os.getloadavg()[0]:.1f}")
    if a.figure:
        plot(rows, sp, a.figure, a.name, a.bands)


def plot(rows, sp, path, name, bands):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4.2))
    for (s_from, s_to, patch, side, comp, band, r) in rows:
        if r is None or comp != "z":
            continue
        ok = r["r2"] >= 0.9
        if s_from == "pulse":
            ax.plot(r["f"][ok] / 1e3, r["c"][ok], "k.", ms=3,
                    label="clean pulse" if band == bands[0] and side == "ahead" else None)
        else:
            lab = f"{s_from * 1e3:.0f}-{s_to * 1e3:.0f} mm, patch {patch}, {side}"
            ax.plot(r["f"][ok] / 1e3, r["c"][ok], ".", ms=4,
                    label=lab if band == bands[0] else None)
    for key, ls in (("c_R", "-"), ("c_s", "--")):
        ax.axhline(sp[key], color="grey", ls=ls, lw=0.8)
        ax.text(101, sp[key], key, va="center", fontsize=8)
    ax.axhspan(2700, 3300, color="0.9", zorder=0)
    ax.set(xlabel="frequency [kHz]", ylabel="phase velocity [m/s]", ylim=(500, 6500),
           title=f"{name}: rail surface v_z, frequencies with R² ≥ 0.9")
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


if __name__ == "__main__":
    main()
