"""Steady rolling and shift (Cattaneo–Mindlin) on a half-space grid with a given pressure:
the public solvers of the exact tangential theory.

See :mod:`wheelrail.tangential.exact` for the equations and conventions.
"""

from __future__ import annotations

import math

import numpy as np

from ..._resources import guard
from ..._validation import as_float_array, integer, positive
from ...errors import ConvergenceError, InputError, NoContactError
from ...halfspace.grid import Grid
from ...halfspace.influence import influence_kernel
from ...halfspace.rolling import _block_convolution, _rolling_and_influence_kernels
from ...materials import as_material_pair
from ...results import TangentialResult
from .nested import _rolling_traction
from .newton import _gauss_seidel, _newton


def _check_problem(grid, pressure, mu):
    if not isinstance(grid, Grid):
        raise InputError(f"grid must be a wheelrail.halfspace.Grid, got {type(grid).__name__}")
    pressure = grid.check_field("pressure", pressure)
    if np.any(pressure < 0):
        raise InputError(f"pressure must be >= 0 (compression positive), got {pressure.min()!r} Pa")
    if not np.any(pressure > 0):
        raise NoContactError("the pressure is zero everywhere: there is no contact to solve "
                             "the tangential problem on")
    mu = float(positive("mu", mu))
    return pressure, mu


def _finish(grid, pressure, p, s, u, mu, kind, creepage, sweeps, res, tol, on_fail, info):
    converged = bool(res <= tol)
    if not converged and on_fail == "raise":
        raise ConvergenceError(
            f"the tangential {kind} problem ({info.get('solver', 'newton')} solver) did not "
            f"converge in {sweeps} iterations (residual {res:.2e} > tol={tol:.1e}); increase "
            "maxiter or loosen tol, or pass on_fail='status'")
    contact = pressure > 0.0
    g = mu * pressure
    norm = np.hypot(p[0], p[1])
    slipping = contact & (np.hypot(s[0], s[1]) > 0.0) & (norm >= g * (1 - 1e-9))
    adhesion = contact & ~slipping
    s = np.where(slipping, s, 0.0)
    dA = grid.element_area
    X, Y = grid.X, grid.Y
    Fx = float(p[0].sum() * dA)
    Fy = float(p[1].sum() * dA)
    Mz = float((X * p[1] - Y * p[0]).sum() * dA)
    pressure = np.array(pressure)
    p = np.array(p)
    u = np.array(u)
    for arr in (pressure, p, s, u, adhesion, slipping):
        arr.setflags(write=False)
    return TangentialResult(
        grid=grid, pressure=pressure, px=p[0], py=p[1], sx=s[0], sy=s[1],
        ux=u[0], uy=u[1], adhesion=adhesion, slip=slipping, Fx=Fx, Fy=Fy, Mz=Mz, mu=mu,
        kind=kind, creepage=tuple(float(c) for c in creepage), iterations=int(sweeps),
        converged=converged, residual=float(res), info=dict(info))


def _check_solver_options(tol, maxiter, on_fail):
    tol = float(positive("tol", tol))
    maxiter = integer("maxiter", maxiter)
    if on_fail not in ("raise", "status"):
        raise InputError(f"on_fail must be 'raise' or 'status', got {on_fail!r}")
    return tol, maxiter, on_fail


#: Nested iteration: coarse levels are used while the contact's bounding box
#: is at least this many elements long in both directions on the finer level.
def solve_rolling(grid, pressure, materials, creepage, mu, *, tol=1e-6, maxiter=100,
                  initial=None, on_fail="raise", solver="newton",
                  nested=True) -> TangentialResult:
    """Steady-state rolling with prescribed creepages (Kalker's exact theory).

    Parameters
    ----------
    grid : Grid
        Element grid; the contact must not touch the leading (largest x) edge
        for the rolling difference to be meaningful.
    pressure : ndarray, shape (nx, ny)
        Normal pressure [Pa], ≥ 0; zero marks elements out of contact.
    materials : Material or MaterialPair
        Combined constants; with ``K ≠ 0`` the tangential displacements caused
        by the pressure are included (one step of the Panagiotopoulos process;
        see :func:`wheelrail.contact.solve_gap` for the full loop).
    creepage : sequence of 3 floats
        (ξ [-], η [-], φ [1/m]), wheel relative to rail.
    mu : float
        Friction coefficient [-], > 0.
    tol : float
        Converged when no element changes between adhesion and slip and the
        largest residual of the slip equations is below ``tol · max|w|``
        (``w`` the rigid slip over the contact).
    maxiter : int
        Largest number of Newton iterations.
    initial : ndarray, shape (2, nx, ny), optional
        Starting tractions (e.g. the solution for nearby creepages).
    on_fail : {"raise", "status"}
        Raise :class:`~wheelrail.errors.ConvergenceError` or return the last
        iterate with ``converged=False``.
    solver : {"newton"}
        The preconditioned Newton–GMRES method (module docstring).
    nested : bool
        Without ``initial``: start from the solution of the same problem on
        the grid with 2 × 2 times larger elements (pressure averaged over
        them), itself started that way while the contact is at least 32
        elements long in both directions (nested iteration, module
        docstring). Only the path changes: the converged solution is that of
        this grid to ``tol``.

    Returns
    -------
    TangentialResult
        ``sx, sy`` are dimensionless slip velocities; ``iterations`` counts
        Newton iterations, ``info["krylov_iterations"]`` the GMRES ones (on
        this grid); ``info["coarse"]`` lists the coarse levels (finest first)
        as dicts with ``shape``, ``newton`` and ``krylov`` iteration counts.

    Examples
    --------
    >>> import wheelrail as wr
    >>> from wheelrail.tangential.exact import solve_rolling
    >>> from wheelrail.normal.bem import hertz_grid, solve_normal
    >>> hc = wr.hertz(1e4, A=1.0, B=2.0, material=wr.STEEL)
    >>> grid, gap = hertz_grid(hc, elements=20, margin=1.1)
    >>> pn = solve_normal(grid, gap, wr.STEEL, Fn=1e4).pressure
    >>> sol = solve_rolling(grid, pn, wr.STEEL, (1e-3, 0.0, 0.0), mu=0.3)
    >>> bool(sol.Fx < 0), bool(sol.adhesion.any()), bool(sol.slip.any())
    (True, True, True)

    References
    ----------
    Kalker (1990) eqs. (2.7)–(2.12) and §5.2–5.3.
    """
    pressure, mu = _check_problem(grid, pressure, mu)
    tol, maxiter, on_fail = _check_solver_options(tol, maxiter, on_fail)
    cr = as_float_array("creepage", creepage)
    if cr.shape != (3,):
        raise InputError(f"creepage must be (xi, eta, phi), got shape {cr.shape}")
    xi, eta, phi = (float(v) for v in cr)
    guard("exact", grid.size, f"exact theory on a {grid.nx}x{grid.ny} grid")  # memory/time
    pair = as_material_pair(materials)
    if solver != "newton":
        raise InputError(f"solver must be 'newton' for steady rolling, got {solver!r} "
                         "(Gauss–Seidel is available for the shift problem only)")
    nested = bool(nested)
    coarse = []
    p, s, its, res, krylov = _rolling_traction(grid, pressure, pair, (xi, eta, phi), mu, tol,
                                               maxiter, initial, nested, coarse)
    C = _rolling_and_influence_kernels(grid, pair)[1]
    conv_u = _block_convolution(grid, pair, "C_t", C[:2, :])
    info = {"solver": "newton", "krylov_iterations": krylov, "coarse": coarse}
    u = conv_u(np.concatenate((p, pressure[None])))
    return _finish(grid, pressure, p, s, u, mu, "rolling", (xi, eta, phi), its, res, tol,
                   on_fail, info)


def solve_shift(grid, pressure, materials, mu, *, shift=None, force=None, tol=1e-6,
                maxiter=100, force_tol=1e-6, initial=None, on_fail="raise",
                solver="newton") -> TangentialResult:
    """Shift (Cattaneo–Mindlin) problem: tangential loading from rest at fixed pressure.

    Give either the rigid ``shift`` W = (Wx, Wy) [m] of the wheel relative to
    the rail, or the total tangential ``force`` (Fx, Fy) [N] on the wheel
    (then W is found by an outer secant/Broyden iteration).

    Parameters
    ----------
    grid : Grid
    pressure : ndarray, shape (nx, ny)
        Normal pressure [Pa].
    materials : Material or MaterialPair
    mu : float
        Friction coefficient, > 0.
    shift : sequence of 2 floats, optional
        Rigid shift [m].
    force : sequence of 2 floats, optional
        Prescribed (Fx, Fy) [N]; ``|F| < μ Fn`` is required.
    tol, maxiter, initial, on_fail
        As in :func:`solve_rolling` (for ``solver="gs"``: ``maxiter`` sweeps,
        converged when the largest traction change of a sweep is below
        ``tol · μ max(pn)``).
    solver : {"newton", "gs"}
        Preconditioned Newton–GMRES (default) or block Gauss–Seidel.
    force_tol : float
        Relative tolerance of the total force (outer iteration), relative to μFn.

    Returns
    -------
    TangentialResult
        ``kind="shift"``, ``creepage`` holds the shift (Wx, Wy) [m]; ``sx, sy``
        are slip distances [m].

    References
    ----------
    Kalker (1990) §2.1 and §5.3; Johnson (1985) §7.2 (Cattaneo–Mindlin).
    """
    pressure, mu = _check_problem(grid, pressure, mu)
    tol, maxiter, on_fail = _check_solver_options(tol, maxiter, on_fail)
    if (shift is None) == (force is None):
        raise InputError("give exactly one of shift=(Wx, Wy) [m] or force=(Fx, Fy) [N]")
    pair = as_material_pair(materials)
    C = influence_kernel(grid, pair)
    conv = _block_convolution(grid, pair, "C_tt", C[:2, :2])
    conv_u = _block_convolution(grid, pair, "C_t", C[:2, :])
    base = conv_u(np.concatenate((np.zeros((2,) + grid.shape), pressure[None])))
    g = mu * pressure
    dA = grid.element_area
    Fn = float(pressure.sum() * dA)

    if solver not in ("newton", "gs"):
        raise InputError(f"solver must be 'newton' or 'gs', got {solver!r}")

    def run(W, p0):
        b = base + np.asarray(W, float)[:, None, None]
        if solver == "gs":
            return _gauss_seidel(C[:2, :2], conv, b, g, p0, tol, maxiter)
        p, s, its, res, _ = _newton(C[:2, :2], conv, b, g, p0, tol, maxiter, upwind=False)
        return p, s, its, res

    total_sweeps = 0
    if shift is not None:
        W = as_float_array("shift", shift)
        if W.shape != (2,):
            raise InputError(f"shift must be (Wx, Wy), got shape {W.shape}")
        p, s, total_sweeps, res = run(W, initial)
        outer = 0
    else:
        F = as_float_array("force", force)
        if F.shape != (2,):
            raise InputError(f"force must be (Fx, Fy), got shape {F.shape}")
        Fmag = float(np.hypot(*F))
        if Fmag >= mu * Fn:
            raise InputError(f"|force| = {Fmag!r} N must be < μ·Fn = {mu * Fn!r} N: no shift "
                             "transmits it (the patch slides)")
        W, p, s, total_sweeps, res, outer = _shift_for_force(run, F, Fn, mu, dA, force_tol,
                                                             initial, pair, pressure, grid)
    u = conv_u(np.concatenate((p, pressure[None])))
    return _finish(grid, pressure, p, s, u, mu, "shift", tuple(W), total_sweeps, res, tol,
                   on_fail, {"outer_iterations": outer, "solver": solver})


def _shift_for_force(run, F, Fn, mu, dA, force_tol, initial, pair, pressure, grid):
    """Find the shift W that transmits the force F (|F| < μFn) by secant + Broyden."""
    Fmag = float(np.hypot(*F))
    total = 0
    if Fmag == 0.0:
        W = np.zeros(2)
        p, s, sw, res = run(W, initial)
        return W, p, s, sw, res, 0
    e = F / Fmag
    # stiffness estimate: Mindlin, equivalent circle of the contact area
    area = float(np.count_nonzero(pressure > 0)) * dA
    a_eq = math.sqrt(area / math.pi)
    k = 4.0 * pair.G * a_eq / (2.0 - pair.nu)
    ftol = force_tol * mu * Fn

    def force_of(W, p0):
        nonlocal total
        p, s, sw, res = run(W, p0)
        total += sw
        return np.array([p[0].sum(), p[1].sum()]) * dA, p, s, res

    # scalar bracketing + Illinois along −e (traction opposes the shift), started from
    # Cattaneo–Mindlin's shift of the equivalent circle (Johnson 1985, eq. 7.42)
    ratio = min(Fmag / (mu * Fn), 0.999)
    t = 1.5 * mu * Fn / k * (1.0 - (1.0 - ratio) ** (2.0 / 3.0))
    p = initial
    Fv, p, s, res = force_of(-t * e, p)
    f = float(Fv @ e) - Fmag
    if f < 0:
        t_lo, f_lo = t, f
        while f < 0:
            t_lo, f_lo = t, f
            t *= 1.1
            Fv, p, s, res = force_of(-t * e, p)
            f = float(Fv @ e) - Fmag
        t_hi, f_hi = t, f
    else:
        t_hi, f_hi = t, f
        while f >= 0 and abs(f) > ftol:
            t_hi, f_hi = t, f
            t *= 0.9
            Fv, p, s, res = force_of(-t * e, p)
            f = float(Fv @ e) - Fmag
        t_lo, f_lo = t, f
    outer = 0
    for outer in range(1, 100):
        if abs(f) <= ftol:
            break
        # regula falsi (Illinois) inside the bracket
        t_new = t_hi - f_hi * (t_hi - t_lo) / (f_hi - f_lo)
        Fv, p, s, res = force_of(-t_new * e, p)
        f = float(Fv @ e) - Fmag
        if f < 0:
            t_lo, f_lo = t_new, f
            f_hi *= 0.5
        else:
            t_hi, f_hi = t_new, f
            f_lo *= 0.5
        t = t_new
    W = -t * e
    # Broyden correction for a force component perpendicular to the shift
    J = -k * np.eye(2)
    r = Fv - F
    for _ in range(20):
        if np.hypot(*r) <= ftol:
            break
        dW = -np.linalg.solve(J, r)
        W = W + dW
        Fv, p, s, res = force_of(W, p)
        r_new = Fv - F
        dr = r_new - r
        J = J + np.outer(dr - J @ dW, dW) / (dW @ dW)
        r = r_new
        outer += 1
    if np.hypot(*r) > 10 * ftol:
        raise ConvergenceError(f"the shift for force {F.tolist()} N was not found "
                               f"(residual {np.hypot(*r):.3e} N)")
    return W, p, s, total, res, outer

