"""Surface-wave speed on the transition model's rail (wheelrail.fe.transition.wave).

A Ricker force pulse strikes the running surface of the one- to two-point transition case's
rail and track mesh (the wheel held and left out); the pulse's arrivals along the surface
line give the speed (cross-correlation with the nearest station, envelope peak, and the
first motion of v_x), compared with the P, S and Rayleigh speeds of the steel. Prints one
line per mesh size and central frequency with the elements, steps, CPU time and load.
Usage::

    python benchmarks/bench_fe_transition_wave.py                  # 4, 3, 2 mm x 70-150 kHz
    python benchmarks/bench_fe_transition_wave.py --mesh 2e-3 --freq 100e3 \
        --figure results/fe_transition/wave_pulse_2mm_100khz.png
    python benchmarks/bench_fe_transition_wave.py --out results/fe_transition/wave_pulse.txt
    # the flange contact position on the gauge corner; a 60 µs half-sine (the time scale of
    # the flange patch's load rise at the onset of two-point contact)
    python benchmarks/bench_fe_transition_wave.py --mesh 4e-3 --at flange --freq 80e3
    python benchmarks/bench_fe_transition_wave.py --mesh 4e-3 --at flange --pulse half-sine \
        --freq 16667 --component n
"""

from __future__ import annotations

import argparse
import os
import sys
import time

import numpy as np

from wheelrail.fe.transition import seed004_case
from wheelrail.fe.transition.model import build_transition_model
from wheelrail.fe.transition.wave import (
    elastic_wave_speeds,
    pulse_arrivals,
    pulse_phase,
    rail_pulse,
)

RANGES = ((0.02, 0.06), (0.03, 0.08), (0.04, 0.09))   # fitted station distances [m]


def fit_or_nan(rec, **kw):
    try:
        return pulse_arrivals(rec, **kw)
    except Exception:                                   # noqa: BLE001 (reported as n/a)
        return None


def one(h, f, travel, figure=None, at="tread", pulse="ricker", comp="z"):
    case = seed004_case(0.025, mesh_size=h, travel=travel)
    t0 = time.process_time()
    model = build_transition_model(case)
    t_build = time.process_time() - t0
    load0 = os.getloadavg()[0]
    rec = rail_pulse(case, model=model, frequency=f, at=at, pulse=pulse)
    i = rec.info
    sp = i["speeds"]
    lines = [f"mesh {h * 1e3:g} mm, {pulse} {f / 1e3:g} kHz at the {at} contact (surface "
             f"normal {i['contact_angle']:.1f}° from vertical; Rayleigh wavelength "
             f"{sp['c_R'] / f * 1e3:.0f} mm = {sp['c_R'] / f / h:.0f} elements): "
             f"{i['elements']} elements (rail and sleepers), {i['steps']} steps of "
             f"{i['time_step'] * 1e9:.0f} ns, {i['cpu_s']:.1f} s CPU "
             f"({i['ns_per_element_step']:.0f} ns/element/step; build {t_build:.1f} s), "
             f"load {load0:.1f}-{os.getloadavg()[0]:.1f}, fine band "
             f"{i['fine_band'][0] * 1e3:.0f} to {i['fine_band'][1] * 1e3:.0f} mm"]
    for lo, hi in RANGES:
        xc = fit_or_nan(rec, d_min=lo, d_max=hi, method="xcorr", component=comp)
        en = fit_or_nan(rec, d_min=lo, d_max=hi, method="envelope", component=comp)
        fx = fit_or_nan(rec, d_min=lo, d_max=hi, component="x", method="first")
        ph = pulse_phase(rec, xc)["phase"] if xc else float("nan")

        def fmt(a):
            return (f"{a['speed']:5.0f} ± {a['speed_se']:3.0f} ({a['d'].size:2d})" if a
                    else "      n/a       ")

        lines.append(f"  {lo * 1e3:.0f}-{hi * 1e3:.0f} mm: xcorr v_{comp} {fmt(xc)}, envelope "
                     f"v_{comp} "
                     f"{fmt(en)}, first v_x {fmt(fx)} m/s; v_x-v_z phase {ph:.0f}°")
    if figure:
        plot(rec, figure)
    return lines


def plot(rec, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    sp = rec.info["speeds"]
    fig, axs = plt.subplots(1, 2, figsize=(11, 6.5), sharey=True)
    sel = np.flatnonzero((rec.x >= 0) & (rec.x <= rec.info["fine_band"][1]))[::2]
    a = pulse_arrivals(rec, method="xcorr")
    t_c = 1.2 / rec.info["frequency"]
    for c, (ax, name) in enumerate(zip(axs, ("v_z (vertical)", "v_x (along the rail)"))):
        k = (2, 0)[c]
        for j in sel:
            tr = rec.v[:, j, k]
            ax.plot(rec.t * 1e6, rec.x[j] * 1e3 + 4.0 * tr / np.abs(tr).max(), "k", lw=0.5)
        tt = np.linspace(0, rec.t[-1], 10)
        for key, col, lab in (("c_p", "r", "P"), ("c_s", "g", "S"), ("c_R", "b", "Rayleigh")):
            ax.plot(tt * 1e6, (tt - t_c) * sp[key] * 1e3, col, lw=0.8,
                    label=f"{lab} {sp[key] / 1e3:.2f} km/s")
        if k == 2:
            ax.plot(a["t_arrival"] * 1e6, a["d"] * 1e3, "o", mfc="none", mec="orange", ms=4,
                    label=f"picked (cross-correlation) {a['speed'] / 1e3:.2f} km/s")
        ax.set_xlabel("time [µs]")
        ax.set_title(name + ", each trace scaled to its peak")
        ax.legend(fontsize=7, loc="lower right")
    axs[0].set_ylabel("distance from the source along the running surface [mm]")
    axs[0].set_ylim(-6, sel.size and rec.x[sel].max() * 1e3 + 6)
    fig.suptitle(f"Ricker {rec.info['frequency'] / 1e3:g} kHz on the rail head, "
                 f"{rec.info['mesh_size'] * 1e3:g} mm mesh")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--mesh", type=float, nargs="*", default=[4e-3, 3e-3, 2e-3])
    ap.add_argument("--freq", type=float, nargs="*", default=[70e3, 100e3, 150e3])
    ap.add_argument("--travel", type=float, default=0.12,
                    help="the case's travel: sets the fine band (about travel + 60 mm)")
    ap.add_argument("--at", default="tread", choices=("tread", "flange"))
    ap.add_argument("--pulse", default="ricker", choices=("ricker", "half-sine"))
    ap.add_argument("--component", default="z", choices=("x", "y", "z", "n"))
    ap.add_argument("--figure")
    ap.add_argument("--out")
    a = ap.parse_args()
    out = [f"python {' '.join(sys.argv)}"]
    case = seed004_case(0.025)
    sp = elastic_wave_speeds(case.material.E, case.material.nu, case.material.density)
    out.append(f"steel E = {case.material.E / 1e9:g} GPa, nu = {case.material.nu:g}, rho = "
               f"{case.material.density:g} kg/m3: c_p {sp['c_p']:.0f}, c_s {sp['c_s']:.0f}, "
               f"c_R {sp['c_R']:.0f} (Viktorov {sp['c_R_viktorov']:.0f}), bar "
               f"{sp['c_bar']:.0f} m/s")
    print("\n".join(out), flush=True)
    for h in a.mesh:
        for f in a.freq:
            for line in one(h, f, a.travel, a.figure, a.at, a.pulse, a.component):
                print(line, flush=True)
                out.append(line)
    if a.out:
        with open(a.out, "w") as fh:
            fh.write("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
