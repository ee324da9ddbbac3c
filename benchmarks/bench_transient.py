"""Benchmark: transient rolling, seed 001 §3.1 "Cattaneo to Carter".

Table 1 of the seed: wheel radius 0.5 m, wheel profile radius 0.409 m
(concave), rail crown radius 0.3 m, steel, μ = 0.4, F3 = 10 kN, F1 = 2 kN
applied at once, V·Δt = 0.05 mm, 30 elements over 2a, 1801 steps (90 mm).

Prints the grid, the wall time (total and per step), solver counts, the final
creepage against the steady exact solver on the same grid (force found by
brentq on ``solve_rolling``), the overshoot of the creepage and the travel
after which it stays within 1 % of its final value. Also the machine load.

Run:  .venv/bin/python benchmarks/bench_transient.py [ELEMENTS] [STEPS]
"""

from __future__ import annotations

import os
import sys
import time

import numpy as np
from scipy.optimize import brentq

import wheelrail as wr
from wheelrail.tangential.exact import newton_step, solve_rolling
from wheelrail.transient.measures import leading_edge_slip
from wheelrail.transient.rolling import step_kernels
from wheelrail.normal.bem import hertz_grid, solve_normal


#: Table 1 of seed 001: E = 210 GPa, nu = 0.3 (wr.STEEL has nu = 0.28).
SEED = wr.Material(2.1e11, 0.3)


def main(elements=30, steps=1801, h=5e-5, scheme="averaged"):
    hc = wr.hertz_from_radii(10e3, 0.5, -0.409, 0.3, material=SEED)
    wr.transient_rolling(hc, travel=4e-4, step=2e-4, mu=0.4, Fx=2000.0,
                         elements=6)  # warm-up (numba cache)
    print(f"load (uptime): {os.getloadavg()}")
    print(f"scheme = {scheme!r}; a = {hc.a * 1e3:.3f} mm, b = {hc.b * 1e3:.3f} mm; elements over 2a = {elements}, "
          f"V*dt = {h * 1e3:.3f} mm, steps = {steps}")
    t0 = time.perf_counter()
    res = wr.transient_rolling(hc, travel=(steps - 1) * h, step=h, mu=0.4,
                               Fx=2000.0, elements=elements, frames=20,
                               scheme=scheme)
    wall = time.perf_counter() - t0
    info = res.info
    print(f"grid {info['nx']}x{info['ny']}, dx = {info['dx'] * 1e3:.4f} mm: total {wall:.2f} s, "
          f"{wall / (steps - 1) * 1e3:.2f} ms/step; tangential solves {info['solves']}, "
          f"Newton {info['newton']}, GMRES {info['krylov']}")
    grid, gap = hertz_grid(hc, elements=elements)
    pn = solve_normal(grid, gap, SEED, Fn=10e3).pressure
    xi_st = brentq(lambda xi: solve_rolling(grid, pn, SEED, (xi, 0, 0), mu=0.4,
                                            tol=1e-10).Fx - 2000.0, -3e-3, -1e-5, xtol=1e-12)
    # steady fixed point of the same time step h (kernel (now − old)/h of the scheme)
    now, old = step_kernels(grid, SEED, h, scheme)
    M = (now - old)[:2, :2] / h

    def fx(xi):
        b = np.zeros((2,) + grid.shape)
        b[0] = xi
        return newton_step(M, b, 0.4 * pn, tol=1e-10)[0][0].sum() * grid.element_area - 2000.0

    xi_h = brentq(fx, -3e-3, -1e-5, xtol=1e-13)
    print(f"steady fixed point with the same V*dt: {xi_h:.6e}: difference "
          f"{100 * (res.xi[-1] / xi_h - 1):+.4f} %")
    xi = res.xi
    final = xi[-1]
    a = float(hc.a)
    body = xi[2:]  # the first step is the Cattaneo shift (xi = shift / h)
    k = int(np.argmax(np.abs(body))) + 2
    outside = np.nonzero(np.abs(xi - final) > 0.01 * abs(final))[0]
    settle = res.x[outside[-1] + 1] if outside.size else 0.0
    print(f"final xi = {final:.6e}; steady exact (same grid, dx = {grid.dx * 1e3:.4f} mm) "
          f"{xi_st:.6e}: difference {100 * (final / xi_st - 1):+.2f} %")
    print(f"peak |xi| after the first step {xi[k]:.6e} at x = {res.x[k] * 1e3:.2f} mm "
          f"(overshoot {100 * (abs(xi[k]) / abs(final) - 1):.2f} %); within 1 % of final from "
          f"x = {settle * 1e3:.2f} mm = {settle / a:.2f} a")
    for n2 in (45, 60):
        g2, gap2 = hertz_grid(hc, elements=n2)
        pn2 = solve_normal(g2, gap2, SEED, Fn=10e3).pressure
        x2 = brentq(lambda xi: solve_rolling(g2, pn2, SEED, (xi, 0, 0), mu=0.4,
                                             tol=1e-10).Fx - 2000.0, -3e-3, -1e-5, xtol=1e-12)
        print(f"steady exact solver on {n2} elements: xi = {x2:.6e} (transient-30 differs "
              f"{100 * (final / x2 - 1):+.2f} %)")
    xi_fs = brentq(lambda xi: float(wr.creep_forces(hc, (xi, 0, 0), 0.4, method="fastsim").Fx)
                   - 2000.0, -3e-3, -1e-6, xtol=1e-12)
    print(f"FASTSIM: xi = {xi_fs:.6e} (transient-30 differs {100 * (final / xi_fs - 1):+.2f} %)")
    print(f"slip elements at the end {int(res.n_slip[-1])} of {int(res.n_contact[-1])}")


def varying_loads(elements=15):
    """Seed §3.2 (F3 sinusoidal) and §3.3 (F1 sinusoidal), three wavelengths, V·Δt = dx/2."""
    hc = wr.hertz_from_radii(10e3, 0.5, -0.409, 0.3, material=SEED)
    grid, _ = hertz_grid(hc, elements=elements)
    h = grid.dx / 2
    print(f"\n§3.2/§3.3 on {elements} elements over 2a, V*dt = {h * 1e3:.4f} mm, 4 wavelengths; "
          "statistics over the last 3")
    for lam in (12.5e-3, 7.1e-3, 5e-3):
        t0 = time.perf_counter()
        r = wr.transient_rolling(
            hc, travel=4 * lam, step=h, mu=0.4, Fx=2000.0, elements=elements,
            Fn=lambda x: 10e3 + 4.5e3 * np.sin(2 * np.pi * x / lam), frames=10**6)
        m = r.x >= lam
        lead = [(leading_edge_slip(r.state[k]), r.frame_x[k]) for k in range(len(r.frame_x))
                if r.frame_x[k] >= lam]
        (rows, depth), xl = max(lead, key=lambda v: v[0])
        print(f"§3.2 lambda = {lam * 1e3:4.1f} mm: xi in [{r.xi[m].min():.3e}, {r.xi[m].max():.3e}]"
              f"; isolated leading-edge slip: up to {rows} rows, depth {depth} elements "
              f"(at x = {xl * 1e3:.2f} mm); {time.perf_counter() - t0:.1f} s")
        F1 = lambda x: 2000.0 + 1000.0 * np.sin(2 * np.pi * x / lam)  # noqa: E731
        r = wr.transient_rolling(hc, travel=4 * lam, step=h, mu=0.4, Fx=F1,
                                 elements=elements, frames=10**6)
        m = r.x >= lam
        same = np.mean(np.sign(r.xi[m]) == np.sign(F1(r.x[m])))
        rev = max(int(np.sum((r.state[k] == 2) & (r.px[k] < 0))) for k in np.nonzero(
            r.frame_x >= lam)[0])
        print(f"§3.3 lambda = {lam * 1e3:4.1f} mm: xi in [{r.xi[m].min():.3e}, {r.xi[m].max():.3e}]"
              f"; xi and F1 of the same sign over {100 * same:.1f} % of the travel; "
              f"reverse-slip elements (px < 0) up to {rev}")


def convergence(travel=20e-3):
    """§3.1 history under grid refinement (30, 45, 60 elements, V·Δt = 0.05 mm) and under
    V·Δt refinement (30 elements: 0.2, 0.1, 0.05 mm against 0.025 mm); errors are the
    largest difference over x in [2a, travel] relative to the final ξ of the reference;
    observed orders by np.polyfit on log h / log error."""
    hc = wr.hertz_from_radii(10e3, 0.5, -0.409, 0.3, material=SEED)
    a = float(hc.a)
    print(f"\nconvergence of the §3.1 history over x in [2a, {travel * 1e3:.0f} mm] "
          f"(load {os.getloadavg()[0]:.1f})")
    h = 5e-5
    runs = {}
    for n in (30, 45, 60):
        t0 = time.perf_counter()
        runs[n] = wr.transient_rolling(hc, travel=travel, step=h, mu=0.4,
                                       Fx=2000.0, elements=n, frames=2)
        print(f"  {n} elements (grid {runs[n].grid.nx}x{runs[n].grid.ny}): final xi "
              f"{runs[n].xi[-1]:.6e}; {time.perf_counter() - t0:.1f} s")
    late = runs[60].x >= 2 * a
    err = np.array([np.max(np.abs(runs[n].xi[late] - runs[60].xi[late])) / abs(runs[60].xi[-1])
                    for n in (30, 45)])
    order = np.log(err[0] / err[1]) / np.log(45 / 30)
    print(f"  grid: errors against 60 elements {100 * err[0]:.2f} % (30), {100 * err[1]:.2f} % "
          f"(45); observed order {order:.2f} (two levels)")
    steps = (2e-4, 1e-4, 5e-5, 2.5e-5)
    runs = {}
    for s in steps:
        runs[s] = wr.transient_rolling(hc, travel=travel, step=s, mu=0.4,
                                       Fx=2000.0, elements=30, frames=2)
    ref = runs[steps[-1]]
    errs = []
    for s in steps[:-1]:
        k = int(round(s / steps[-1]))
        xr, xir = ref.x[::k], ref.xi[::k]
        n = min(len(xr), len(runs[s].xi))
        m = xr[:n] >= 2 * a
        errs.append(np.max(np.abs(runs[s].xi[:n][m] - xir[:n][m])) / abs(ref.xi[-1]))
    order = np.polyfit(np.log(steps[:-1]), np.log(errs), 1)[0]
    print("  V*dt: errors against 0.025 mm " + ", ".join(
        f"{100 * e:.3f} % ({s * 1e3:g} mm)" for s, e in zip(steps, errs))
        + f"; fitted order {order:.2f}")


def strips(elements=30, steps=1801, h=5e-5):
    """§3.1 on the Paul–Hashemi discretisation (30 strips × 30 elements, as the seed's Table 1)."""
    hc = wr.hertz_from_radii(10e3, 0.5, -0.409, 0.3, material=SEED)
    t0 = time.perf_counter()
    res = wr.transient_rolling(hc, travel=(steps - 1) * h, step=h, mu=0.4,
                               Fx=2000.0, elements=elements,
                               discretisation="strips", frames=2)
    wall = time.perf_counter() - t0
    i = res.info
    print(f"\nPaul–Hashemi {elements} strips x {elements} elements, V*dt = {h * 1e3:.3f} mm, "
          f"{steps} steps: {wall:.2f} s ({wall / (steps - 1) * 1e3:.2f} ms/step, load "
          f"{os.getloadavg()[0]:.1f}); solves {i['solves']}, Newton {i['newton']}, GMRES "
          f"{i['krylov']}; final xi = {res.xi[-1]:.6e}")


if __name__ == "__main__":
    args = [int(v) for v in sys.argv[1:]]
    main(*args)
    strips()
    varying_loads()
    convergence()
