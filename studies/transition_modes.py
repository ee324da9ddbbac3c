"""Vertical modes of the transition case's wheel on its track, from a lumped model, and the
frequency of the vertical contact force's oscillation in a run.

The lumped model: the 54E1 rail as an Euler–Bernoulli beam (EI = 4.93 MN m², 54.77 kg/m)
over the model's length, on the railpads (spread over the rail seat) on rigid sleepers on
the ballast springs; the unsprung mass (half-axle + FE wheel) on a linearised Hertz spring
k = 1.5 Q / δ at the wheel's position; the sprung mass on the primary suspension. Printed:
the natural frequencies with the unsprung mass's share of the modal mass, for contact
stiffnesses 1× and 2× the Hertz estimate (the FE's penalty layer stiffens the contact) and
four wheel positions between the sleepers; then the best-fitting single sine of Σ Fz of a
run (``--run NAME`` of ``results/fe_transition``) over a travel window, on a quadratic
trend. Usage::

    python studies/transition_modes.py [--aoa 0.025 --clearance 0.007 --travel 0.33]
        [--run a25_h4_c7 --window 0.06 0.22]
"""

from __future__ import annotations

import argparse
import json
import os

import numpy as np
import scipy.linalg as sla

import wheelrail as wr
from wheelrail.fe.transition.run import _static_approach
from wheelrail.fe.transition.model import build_transition_model

RESULTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "benchmarks", "results", "fe_transition")
EI = 2.1e11 * 2.346e-5          # 54E1, EN 13674-1
RAIL_MASS = 54.77               # kg/m


def lumped_modes(case, x_sleepers, x_wheel, k_contact, unsprung, n_el=110):
    tr, su = case.track, case.suspension
    x = np.linspace(x_sleepers[0] - tr.overhang, x_sleepers[-1] + tr.overhang, n_el + 1)
    nb = 2 * x.size
    ns = len(x_sleepers)
    N = nb + ns + 2
    K = np.zeros((N, N))
    M = np.zeros((N, N))
    for e in range(n_el):
        L = x[e + 1] - x[e]
        k = EI / L ** 3 * np.array([[12, 6 * L, -12, 6 * L], [6 * L, 4 * L * L, -6 * L, 2 * L * L],
                                    [-12, -6 * L, 12, -6 * L], [6 * L, 2 * L * L, -6 * L, 4 * L * L]])
        m = RAIL_MASS * L / 420 * np.array([[156, 22 * L, 54, -13 * L],
                                            [22 * L, 4 * L * L, 13 * L, -3 * L * L],
                                            [54, 13 * L, 156, -22 * L],
                                            [-13 * L, -3 * L * L, -22 * L, 4 * L * L]])
        i = slice(2 * e, 2 * e + 4)
        K[i, i] += k
        M[i, i] += m

    def at(xp):
        e = min(n_el - 1, int(np.searchsorted(x, xp) - 1))
        L = x[e + 1] - x[e]
        z = (xp - x[e]) / L
        v = np.zeros(N)
        v[2 * e:2 * e + 4] = [1 - 3 * z * z + 2 * z ** 3, L * (z - 2 * z * z + z ** 3),
                              3 * z * z - 2 * z ** 3, L * (-z * z + z ** 3)]
        return v

    def spring(d, k):
        K[:] += k * np.outer(d, d)

    unit = np.eye(N)
    m_sl = float(np.prod(tr.sleeper_size)) * tr.sleeper_density
    for j, xj in enumerate(x_sleepers):
        for xp in np.linspace(xj - tr.pad_length / 2, xj + tr.pad_length / 2, 5):
            spring(at(xp) - unit[nb + j], tr.pad_stiffness / 5)
        spring(unit[nb + j], tr.ballast_stiffness)
        M[nb + j, nb + j] = m_sl
    iw = nb + ns
    spring(unit[iw] - at(x_wheel), k_contact)
    M[iw, iw] = unsprung
    spring(unit[iw + 1] - unit[iw], su.stiffness)
    M[iw + 1, iw + 1] = su.sprung_mass
    w2, V = sla.eigh(K, M)
    return np.sqrt(np.maximum(w2, 0.0)) / (2 * np.pi), V[iw] ** 2 * unsprung


def sine_fit(t, y, freqs=np.arange(40.0, 600.0, 1.0)):
    best = None
    for f in freqs:
        A = np.c_[np.ones_like(t), t, t * t, np.sin(2 * np.pi * f * t), np.cos(2 * np.pi * f * t)]
        c, *_ = np.linalg.lstsq(A, y, rcond=None)
        r = float(np.sum((A @ c - y) ** 2))
        if best is None or r < best[0]:
            best = (r, f, float(np.hypot(c[3], c[4])))
    return best[1], best[2]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--aoa", type=float, default=0.025)
    ap.add_argument("--clearance", type=float, default=0.007)
    ap.add_argument("--travel", type=float, default=0.33)
    ap.add_argument("--run", nargs="*", default=[])
    ap.add_argument("--window", type=float, nargs=2, default=(0.06, 0.22))
    a = ap.parse_args()
    case = wr.fe.seed004_case(a.aoa, flange_clearance=a.clearance, travel=a.travel)
    m = build_transition_model(case)
    m_wheel = float(m.mass[:m.n_wheel].sum())
    load = case.suspension.wheel_load(m_wheel)
    delta, _ = _static_approach(case, m.pose, load, m)
    k_h = 1.5 * load / delta
    unsprung = case.suspension.axle_mass + m_wheel
    xs = m.pose["sleepers"]
    print(f"wheel load {load / 1e3:.2f} kN, unsprung mass {unsprung:.0f} kg, sleepers at "
          f"{np.round(xs, 3)} m, Hertz + penalty approach {delta * 1e6:.0f} µm, "
          f"k = 1.5 Q / δ = {k_h / 1e9:.2f} GN/m")
    for kc in (k_h, 2 * k_h):
        for xw in np.linspace(0.0, 0.5 * (xs[0] + xs[-1]), 4):
            f, share = lumped_modes(case, xs, xw, kc, unsprung)
            top = sorted(np.argsort(share)[::-1][:4])
            print(f"  k {kc / 1e9:.2f} GN/m, wheel at x = {xw:.2f} m: " + ", ".join(
                f"{f[i]:.0f} Hz ({share[i]:.2f})" for i in top))
    for name in a.run:
        import xarray as xr

        h = xr.open_dataset(os.path.join(RESULTS, f"{name}_history.nc"))
        with open(os.path.join(RESULTS, f"{name}_info.json")) as fh:
            q = json.load(fh)["info"]["load"]
        s, t, fz = h.travel.values, h.time.values, h.Fz_total.values
        sel = (s >= a.window[0]) & (s < a.window[1])
        f, amp = sine_fit(t[sel] - t[sel][0], fz[sel])
        print(f"{name}, {a.window[0] * 1e3:.0f}-{a.window[1] * 1e3:.0f} mm: Σ Fz mean "
              f"{fz[sel].mean() / 1e3:.1f} kN ({fz[sel].mean() / q - 1:+.1%}), std "
              f"{fz[sel].std() / 1e3:.1f} kN; best single sine {f:.0f} Hz, amplitude "
              f"{amp / 1e3:.1f} kN")


if __name__ == "__main__":
    main()
