"""Nested iteration of steady rolling: coarser grids over the same window start the fine
solve (pressure averaged so that the normal force is kept, tractions prolongated,
elements whose coarse element slips start on the bound).

See :mod:`wheelrail.tangential.exact` for the measured effect.
"""

from __future__ import annotations

import numpy as np

from ...halfspace.grid import Grid
from ...halfspace.rolling import _block_convolution, _contact_box, _rolling_and_influence_kernels
from ._kernels import _SPIN_SHIFT
from .newton import _newton

_NESTED_MIN = 32
#: Tolerance of the coarse-level solves (their solution differs from the fine
#: one by the discretisation error anyway).
_NESTED_TOL = 3e-2
#: GMRES forcing of steady rolling: relative tolerance while the active set
#: changes, factor of ``tol / residual`` once it has settled, floor.
_FORCING = (0.2, 0.3, 1e-4)


def _rolling_traction(grid, pressure, pair, creepage, mu, tol, maxiter, initial, nested,
                      coarse):
    """Tractions and slip (2, nx, ny) of steady rolling on ``grid``; nested-iteration start.

    Returns ``p, s, newton_iterations, residual, krylov_iterations``; the
    iteration counts of the coarse levels are recorded in the list ``coarse``
    (finest coarse level first) as dicts.
    """
    xi, eta, phi = creepage
    R = _rolling_and_influence_kernels(grid, pair)[0]
    X, Y = grid.X, grid.Y
    # spin evaluated a sixth of an element upstream (module docstring; CONTACT's FACPHI)
    b = np.stack((xi - phi * Y, eta + phi * (X + _SPIN_SHIFT * grid.dx)))
    if pair.K:
        b = b + _block_convolution(grid, pair, "R_tn", R[:2, 2:3])(pressure[None])
    g = mu * pressure
    contact = g > 0.0
    box, kernel, conv = _contact_box(grid, pair, R, contact)
    mx, my = box[0].stop - box[0].start, box[1].stop - box[1].start
    if initial is None and nested and min(mx, my) >= _NESTED_MIN:
        cgrid, cpressure = _coarsened(grid, pressure)
        pc, sc, itc, resc, kryc = _rolling_traction(cgrid, cpressure, pair, creepage, mu,
                                                    max(tol, _NESTED_TOL), maxiter, None,
                                                    nested, coarse)
        coarse.insert(0, {"shape": cgrid.shape, "newton": itc, "krylov": kryc})
        if np.all(np.isfinite(pc)):
            initial = _prolongated(pc, mu * cpressure, g)
    p0 = None if initial is None else np.asarray(initial, dtype=float)[(slice(None),) + box]
    # coarse levels (tol >= 1e-3): the single-precision product (relative error ~1e-7)
    # also for the residual
    residual_conv = conv.single if tol >= 1e-3 else conv
    pb, sb, its, res, krylov = _newton(kernel, residual_conv, b[(slice(None),) + box], g[box],
                                       p0, tol, maxiter, krylov_conv=conv.single,
                                       forcing=_FORCING)
    p = np.zeros((2,) + grid.shape)
    s = np.zeros((2,) + grid.shape)
    p[(slice(None),) + box] = pb
    s[(slice(None),) + box] = sb
    return p, s, its, res, krylov


def _coarsened(grid, pressure):
    """The grid with 2 × 2 times larger elements on the same window and the block-mean pressure.

    Coarse element ``(k, l)`` covers the fine elements ``2k, 2k+1`` × ``2l, 2l+1``
    (an odd count is padded by one row of zero pressure at the far side); its
    pressure is the mean of theirs, so the normal force is kept.
    """
    nxc, nyc = (grid.nx + 1) // 2, (grid.ny + 1) // 2
    padded = np.zeros((2 * nxc, 2 * nyc))
    padded[:grid.nx, :grid.ny] = pressure
    pc = padded.reshape(nxc, 2, nyc, 2).mean(axis=(1, 3))
    cgrid = Grid(grid.x0 + 0.5 * grid.dx, grid.y0 + 0.5 * grid.dy, 2.0 * grid.dx, 2.0 * grid.dy,
                 nxc, nyc)
    return cgrid, pc


def _linear_weights(n_fine, n_coarse):
    """Lower coarse index and weight of the upper one for each fine element centre (private).

    Fine centre ``i`` lies at coarse index ``(i − ½) / 2`` (see :func:`_coarsened`);
    clamped to the coarse range (constant extrapolation at the ends).
    """
    t = np.clip((np.arange(n_fine) - 0.5) / 2.0, 0.0, n_coarse - 1.0)
    k = np.minimum(np.floor(t).astype(np.int64), max(n_coarse - 2, 0))
    return k, t - k


def _prolongated(pc, gc, g):
    """Fine starting tractions (2, nx, ny) from a coarse solution (private).

    Tractions by bilinear interpolation between coarse element centres; fine
    elements whose coarse element slips start in slip (``|p| = g`` along the
    interpolated traction), the others with the interpolated traction (the
    Newton iteration moves those above the bound to slip).
    """
    nx, ny = g.shape
    nxc, nyc = gc.shape
    kx, wx = _linear_weights(nx, nxc)
    ky, wy = _linear_weights(ny, nyc)
    kx1 = np.minimum(kx + 1, nxc - 1)
    ky1 = np.minimum(ky + 1, nyc - 1)
    rows = pc[:, kx, :] * (1.0 - wx)[None, :, None] + pc[:, kx1, :] * wx[None, :, None]
    p = rows[:, :, ky] * (1.0 - wy) + rows[:, :, ky1] * wy
    slip_c = (gc > 0.0) & (np.hypot(pc[0], pc[1]) >= gc * (1.0 - 1e-9))
    parent = np.arange(nx) // 2, np.arange(ny) // 2
    slip = slip_c[parent[0][:, None], parent[1][None, :]] & (g > 0.0)
    norm = np.hypot(p[0], p[1])
    scale = np.where(slip & (norm > 0.0), g / np.where(norm > 0.0, norm, 1.0), 1.0)
    return p * scale


