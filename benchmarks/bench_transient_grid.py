"""Benchmark: seed 001 §3.1 ("Cattaneo to Carter") under grid refinement, both schemes.

Baeza et al. §3.1, Table 1 (E = 210 GPa, ν = 0.3, μ = 0.4, F3 = 10 kN, F1 = 2 kN
applied at once), V·Δt = 0.05 mm, 90 mm of travel (1801 steps), on 30, 60 and
120 elements over 2a (dx/h = 3.69, 1.84, 0.92). For each scheme
("interpolated", the default, Kalker's first-order rolling difference;
"upwind2", the second-order upwind rolling difference; and "centre", Baeza et
al.'s eq. 2.10 at the centres) prints the final creepage, the slipping fraction at the end, the
largest dip of |ξ| before its peak (a non-monotone history), the counts and
the CPU time; then the grid limit of the final ξ by Richardson extrapolation
with the order fitted from the three grids, and each grid's distance to it.

The steady exact solver (``solve_rolling``, brentq on the force) on 30 … 240
elements gives the grid limit of the interpolated scheme's end state (its
steady fixed point is Kalker's discretisation, tests/reference/
test_transient_step_ratio.py) on finer grids than the transient can afford;
the same with the second-order upwind kernel (the steady fixed point of
"upwind2", solved with ``newton_step``) for the "upwind2" end state.

Run:  .venv/bin/python benchmarks/bench_transient_grid.py [ELEMENTS ...]
"""

from __future__ import annotations

import os
import sys
import time

import numpy as np
from scipy.optimize import brentq

import wheelrail as wr
from wheelrail.normal.bem import hertz_grid, solve_normal
from wheelrail.halfspace.rolling import _BlockConvolution
from wheelrail.tangential.exact import newton_step, solve_rolling
from wheelrail.transient.rolling import step_kernels

SEED = wr.Material(2.1e11, 0.3)
H = 5e-5
STEPS = 1801


def richardson(values, ratio=2.0):
    """Limit and order from three values on grids refined by ``ratio`` (coarse first)."""
    a, b, c = values
    order = np.log(abs((b - a) / (c - b))) / np.log(ratio)
    return c + (c - b) / (ratio ** order - 1), order


def steady_upwind2(hc, n):
    """ξ for F1 = 2 kN of steady rolling with the second-order upwind kernel on n elements."""
    grid, gap = hertz_grid(hc, elements=n)
    pn = solve_normal(grid, gap, SEED, Fn=10e3).pressure
    now, old = step_kernels(grid, SEED, grid.dx, "upwind2")
    M = np.ascontiguousarray(((now - old) / grid.dx)[:2, :2])
    conv = _BlockConvolution(M)
    dA = grid.element_area
    start = [None]

    def force(xi):
        b = np.zeros((2,) + grid.shape)
        b[0] += xi
        for initial in (start[0], None):  # from a warm start, else from rest
            p, _, _, res, _ = newton_step(M, b, 0.4 * pn, conv=conv, initial=initial,
                                          tol=1e-10, maxiter=200, upwind=False)
            if res <= 1e-10:
                break
        start[0] = p
        return float(p[0].sum() * dA) - 2000.0

    return brentq(force, -3e-3, -1e-5, xtol=1e-13)


def main(elements=(30, 60, 120)):
    hc = wr.hertz_from_radii(10e3, 0.5, -0.409, 0.3, material=SEED)
    a = float(hc.a)
    wr.transient_rolling(hc, travel=4e-4, step=2e-4, mu=0.4, Fx=2000.0, elements=6)
    print(f"load (uptime): {os.getloadavg()}; V*dt = {H * 1e3} mm, {STEPS} steps, "
          f"a = {a * 1e3:.4f} mm")
    final = {}
    for scheme in ("interpolated", "upwind2", "centre"):
        for n in elements:
            t0 = time.process_time()
            r = wr.transient_rolling(hc, travel=(STEPS - 1) * H, step=H, mu=0.4, Fx=2000.0,
                                     elements=n, frames=2, scheme=scheme)
            cpu = time.process_time() - t0
            xi = np.abs(r.xi[2:])
            k = int(np.argmax(xi))
            dip = float(np.min(np.diff(xi[: k + 1])) / xi[-1]) if k > 0 else 0.0
            final[scheme, n] = r.xi[-1]
            print(f"{scheme:12s} {n:4d} el (dx/h = {r.info['dx'] / H:.2f}): xi_end = "
                  f"{r.xi[-1]:.6e}, slip fraction {r.n_slip[-1] / r.n_contact[-1]:.3f}, "
                  f"smallest |xi| increment before the peak {dip:+.2e} |xi_end|, "
                  f"solves {r.info['solves']}, steady steps {r.info['steady_steps']}, "
                  f"cpu {cpu:.1f} s", flush=True)
    steady = {}
    for n in (30, 60, 120, 240):
        grid, gap = hertz_grid(hc, elements=n)
        pn = solve_normal(grid, gap, SEED, Fn=10e3).pressure
        steady[n] = brentq(lambda x: solve_rolling(grid, pn, SEED, (x, 0, 0), mu=0.4,
                                                   tol=1e-10).Fx - 2000.0,
                           -3e-3, -1e-5, xtol=1e-13)
        print(f"steady exact solver {n:4d} el: xi = {steady[n]:.6e}", flush=True)
    lim_s, order_s = richardson([steady[n] for n in (60, 120, 240)])
    print(f"steady grid limit (60/120/240, order {order_s:.2f}): {lim_s:.6e}")
    steady2 = {}
    for n in (30, 60, 120, 240):
        steady2[n] = steady_upwind2(hc, n)
        print(f"steady second-order upwind kernel {n:4d} el: xi = {steady2[n]:.6e}", flush=True)
    lim_2, order_2 = richardson([steady2[n] for n in (60, 120, 240)])
    print(f"steady second-order grid limit (60/120/240, order {order_2:.2f}): {lim_2:.6e}")
    if len(elements) == 3:
        for scheme in ("interpolated", "upwind2", "centre"):
            lim, order = richardson([final[scheme, n] for n in elements])
            print(f"{scheme}: grid limit of xi_end ({'/'.join(map(str, elements))}, order "
                  f"{order:.2f}) = {lim:.6e}; distance of each grid from it: " + ", ".join(
                      f"{n}: {100 * (final[scheme, n] / lim - 1):+.2f} %" for n in elements)
                  + f"; from the steady limit: {100 * (lim / lim_s - 1):+.2f} %")
    for (scheme, n), v in final.items():
        print(f"{scheme:12s} {n:4d} el: {100 * (v / lim_s - 1):+.2f} % from the steady "
              f"grid limit")


if __name__ == "__main__":
    main(tuple(int(v) for v in sys.argv[1:]) or (30, 60, 120))
