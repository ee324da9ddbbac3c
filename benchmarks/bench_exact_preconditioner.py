"""Benchmark: two-level (coarse-grid) preconditioners for the exact rolling solver.

An experiment, kept so that the numbers recorded in the docstring of
:mod:`wheelrail.tangential.exact` can be reproduced. The Newton systems of
steady rolling (:func:`wheelrail.tangential.exact.newton_step`) are solved
by GMRES right-preconditioned by a line solve along the rolling direction,
which is local across it: the Krylov iterations grow with the grid. Here the
line solve is combined with a coarse-grid correction on the adhesion area:

* aggregates of ``a × a`` elements lying entirely in adhesion carry a constant
  traction change (prolongation ``P``; restriction ``R = Pᵀ`` sums the slip
  residuals of the aggregate);
* the coarse operator is the Galerkin product ``A_c = R J P`` of the rolling
  kernel, exact for these aggregates: the kernel summed over element pairs,
  ``K_c(D) = Σ_{i∈I, j∈J} M(i − j)`` (triangle weights, sampled at stride
  ``a``), taken densely at the coarse offsets of the aggregates and LU-factored
  once per Newton step;
* combined with the line preconditioner ``L⁻¹`` as

  - ``mult`` (multiplicative: coarse correction, then the line solve on the
    remaining residual) ``B = Q + L⁻¹ (I − J Q)``, ``Q = P A_c⁻¹ R`` — one
    extra FFT product per Krylov iteration;
  - ``add`` (additive) ``B = L⁻¹ + Q``;
  - ``proj`` ``B = Q + L⁻¹ (I − P̄ R)`` (the extra product replaced by the
    aggregate mean of the residual, which ``J Q`` equals after restriction).

For N = 40, 104, 160 elements across a Hertzian contact (a/b from A = 1,
B = 2 /m, 10 kN, steel, μ = 0.3, grid margin 1.1, the contact's bounding box
as in :func:`~wheelrail.halfspace.solve_rolling`) and the three creepage
cases of ``bench_exact_rolling.py`` it prints the Newton and Krylov
iterations, the CPU time of the tangential solve (best of ``--repeat``, one
thread), the size of the dense coarse system at the first Newton step, and
the largest change of the total force against the default preconditioner
(relative to |F|). The load average is printed, since other processes share
the CPU.

Run::

    .venv/bin/python benchmarks/bench_exact_preconditioner.py [N ...] [--config a:mode ...]

Defaults: N = 40 104 160, configurations 4:mult 8:mult 4:add 4:proj.
"""

from __future__ import annotations

import argparse
import os
import time

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

from bench_exact_rolling import CASES, MU  # noqa: E402 - the same cases (script directory)


def coarse_kernel(kernel, a):
    """Galerkin kernel of ``a × a`` aggregates, ``K_c(D) = Σ_{i∈I, j∈J} K(i − j)``.

    ``kernel`` (2, 2, 2nx−1, 2ny−1) in the offset layout of
    :func:`wheelrail.halfspace.influence.influence_kernel`; returns
    (2, 2, 2mx−1, 2my−1), ``mx = ⌈nx/a⌉``, same layout.
    """
    import numpy as np

    nx = (kernel.shape[-2] + 1) // 2
    ny = (kernel.shape[-1] + 1) // 2
    mx, my = -(-nx // a), -(-ny // a)
    w = (a - np.abs(np.arange(-(a - 1), a))).astype(float)   # pairs with offset d
    ox, oy = a * mx + a, a * my + a
    K = np.zeros(kernel.shape[:2] + (2 * ox + 1, 2 * oy + 1))
    K[:, :, ox - (nx - 1): ox + nx, oy - (ny - 1): oy + ny] = kernel
    for axis in (2, 3):
        out = np.zeros_like(K)
        n = K.shape[axis]
        for k, wk in enumerate(w):
            d = k - (a - 1)
            dst = [slice(None)] * 4
            src = [slice(None)] * 4
            dst[axis] = slice(max(0, -d), n - max(0, d))
            src[axis] = slice(max(0, d), n - max(0, -d))
            out[tuple(dst)] += wk * K[tuple(src)]
        K = out
    ix = ox + a * np.arange(-(mx - 1), mx)
    iy = oy + a * np.arange(-(my - 1), my)
    return np.ascontiguousarray(K[:, :, ix][:, :, :, iy])


def two_level(a, Kc, mode, sizes):
    """Preconditioner factory for the ``precondition`` hook of ``tangential._newton``."""
    import numpy as np
    import scipy.linalg as sla

    def factory(kind, pos, pinv, matvec, n):
        nx, ny = kind.shape
        mx, my = -(-nx // a), -(-ny // a)
        stick = np.zeros((mx * a, my * a), dtype=bool)
        stick[:nx, :ny] = kind == 1
        ci, cj = np.nonzero(stick.reshape(mx, a, my, a).all(axis=(1, 3)))
        nc = ci.size
        sizes.append(2 * nc)
        if nc == 0:
            return pinv
        di = ci[:, None] - ci[None, :] + mx - 1
        dj = cj[:, None] - cj[None, :] + my - 1
        A = np.empty((2 * nc, 2 * nc))
        for r in (0, 1):
            for c in (0, 1):
                A[r::2, c::2] = Kc[r, c][di, dj]
        lu = sla.lu_factor(A, check_finite=False)
        gi = (ci[:, None, None] * a + np.arange(a)[None, :, None]).repeat(a, 2).reshape(nc, -1)
        gj = (cj[:, None, None] * a + np.arange(a)[None, None, :]).repeat(a, 1).reshape(nc, -1)
        fp = pos[gi, gj]                  # δpx of each aggregate's elements (δpy at +1)

        def restrict(r):
            return np.column_stack((r[fp].sum(axis=1), r[fp + 1].sum(axis=1)))

        def Q(rc):
            ec = sla.lu_solve(lu, rc.ravel(), check_finite=False)
            z = np.zeros(n)
            z[fp] = ec[0::2, None]
            z[fp + 1] = ec[1::2, None]
            return z

        if mode == "mult":
            def apply(r):
                q = Q(restrict(r))
                return q + pinv(r - matvec(q))
        elif mode == "add":
            def apply(r):
                return pinv(r) + Q(restrict(r))
        elif mode == "proj":
            def apply(r):
                rc = restrict(r)
                rr = r.copy()
                rr[fp] -= rc[:, :1] / (a * a)
                rr[fp + 1] -= rc[:, 1:] / (a * a)
                return Q(rc) + pinv(rr)
        else:
            raise ValueError(f"unknown mode {mode!r} (mult, add, proj)")
        return apply
    return factory


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("sizes", nargs="*", type=int, default=[40, 104, 160])
    ap.add_argument("--config", nargs="*", default=["4:mult", "8:mult", "4:add", "4:proj"],
                    help="aggregate size and mode, e.g. 4:mult")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()

    import numpy as np

    import wheelrail as wr
    from wheelrail.halfspace import rolling as R_ops
    from wheelrail.tangential.exact import _kernels as K, newton as N
    from wheelrail.materials import as_material_pair
    from wheelrail.normal.bem import hertz_grid, solve_normal

    print(f"load average (1, 5, 15 min): {os.getloadavg()}")
    print(f"{'N':>4} {'grid':>8} {'box':>8} {'case':>12} {'precond':>8} {'newton':>6} "
          f"{'krylov':>6} {'cpu s':>7} {'coarse n':>8} {'dF/|F|':>8}")
    hc = wr.hertz(1e4, A=1.0, B=2.0, material=wr.STEEL)
    pair = as_material_pair(wr.STEEL)
    for n in args.sizes:
        grid, gap = hertz_grid(hc, elements=n, margin=1.1)
        pn = solve_normal(grid, gap, wr.STEEL, Fn=1e4).pressure
        R, _ = R_ops._rolling_and_influence_kernels(grid, pair)
        g = MU * pn
        box, kernel, conv = R_ops._contact_box(grid, pair, R, g > 0.0)
        gb = g[box]
        shape = f"{gb.shape[0]}x{gb.shape[1]}"
        for name, (xi, eta, phi) in CASES.items():
            b = np.stack((xi - phi * grid.Y, eta + phi * (grid.X + K._SPIN_SHIFT * grid.dx)))
            b = b[(slice(None),) + box]
            ref = None
            for cfg in ["line"] + list(args.config):
                sizes: list = []
                pre = None
                if cfg != "line":
                    a, mode = cfg.split(":")
                    a = int(a)
                    pre = two_level(a, coarse_kernel(kernel, a), mode, sizes)
                times = []
                for _ in range(args.repeat + 1):               # first run: warm-up
                    sizes.clear()
                    c0 = time.process_time()
                    p, _, it, _, kry = N._newton(kernel, conv, b, gb, None, 1e-6, 100,
                                                 krylov_conv=conv.single, precondition=pre)
                    times.append(time.process_time() - c0)
                F = p.sum(axis=(1, 2))
                ref = F if ref is None else ref
                dF = float(np.max(np.abs(F - ref)) / np.max(np.abs(ref)))
                nc = str(sizes[0]) if sizes else "-"
                print(f"{n:>4} {grid.nx}x{grid.ny:<4} {shape:>8} {name:>12} {cfg:>8} {it:>6} "
                      f"{kry:>6} {min(times[1:]):>7.3f} {nc:>8} {dF:>8.1e}", flush=True)
    print(f"load average (1, 5, 15 min): {os.getloadavg()}")


if __name__ == "__main__":
    main()
