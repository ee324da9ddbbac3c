"""The boundary-element normal solver on a half-space grid (private to the ``bem`` method).

Polonsky & Keer's conjugate gradient with the inverse-symbol preconditioner,
the Hertzian window, and the enlarging window of a gap problem; see
:mod:`wheelrail.normal.bem` for the method and its references.
"""


from __future__ import annotations

import math
import warnings

import numpy as np

from .._resources import guard
from .._validation import as_float_array, integer, positive
from ..errors import ConvergenceError, InputError, NoContactError
from ..halfspace._memo import grid_key, memo
from ..halfspace.fft import InfluenceOperator, influence_operator
from ..halfspace.grid import Grid
from ..halfspace.precondition import InverseSymbolPreconditioner
from ..materials import as_material_pair
from ..patch import ContactPatch
from ..results import NormalResult, Status
from ._gap import _enlarged_bounds, _evaluate, contact_patches

__all__ = ["ContactTruncatedWarning", "solve_normal", "hertz_grid", "polonsky_keer"]


class ContactTruncatedWarning(UserWarning):
    """The contact area reaches the edge of the grid: the window is too small."""


def _dot(a, b) -> float:
    """Dot product of two 1-D arrays without BLAS (private).

    ``np.dot`` calls a multi-threaded BLAS ``ddot`` for long vectors, which is
    several times slower than one core when the machine's cores are busy.
    """
    return float(np.multiply(a, b).sum())


def polonsky_keer(apply, h, dA, *, Fn=None, penetration=None, p_init=None, tol=1e-8,
                  maxiter=1000, precondition=None):
    """Bound-constrained (preconditioned) conjugate gradients for the discrete Signorini problem.

    Pure kernel.

    Parameters
    ----------
    apply : callable
        ``apply(p) -> u_n``, the symmetric positive-definite influence operator
        (nx, ny) → (nx, ny) [Pa → m].
    h : ndarray, shape (nx, ny)
        Undeformed separation h0 [m].
    dA : float
        Element area [m²].
    Fn, penetration : float
        Exactly one: total Fn [N] > 0 or approach δ [m].
    p_init : ndarray, optional
        Initial pressure (≥ 0, not all zero); default: proportional to the rigid
        interference.
    tol : float
        Stop when Σ|p_k − p_{k−1}| / Σ p_k < tol.
    maxiter : int
    precondition : callable, optional
        ``precondition(r) -> z`` [m → Pa], a symmetric positive (semi-)definite
        approximate inverse of the influence operator (e.g.
        :class:`~wheelrail.halfspace.precondition.InverseSymbolPreconditioner`),
        applied to the residual restricted to the contact set; its output is
        restricted again and, for Fn control, projected onto zero total Fn.
        None: the plain method of Polonsky & Keer.

    Returns
    -------
    p : ndarray
        Pressure [Pa].
    delta : float
        Approach [m] (the prescribed one, or the mean of h0 + u_n over the
        contact for Fn control).
    iterations : int
    change : float
        Last relative pressure change.

    References
    ----------
    Polonsky & Keer (1999), §3, steps (i)–(x); the preconditioned direction
    ``t = z + (g·z / g_old·z_old) t_old`` with ``z`` the restricted, projected
    preconditioned residual: Vollebregt (2014), §3–4.
    """
    p, delta, it, change, _ = _pk(apply, h, dA, Fn, penetration, p_init, tol, maxiter,
                                  precondition)
    return p, delta, it, change


def _pk(apply, h, dA, Fn, penetration, p_init, tol, maxiter, precondition):
    """:func:`polonsky_keer`, also returning ``u_n = apply(p)`` of the final pressure (private)."""
    if (Fn is None) == (penetration is None):
        raise InputError("give exactly one of Fn= and penetration=")
    load_control = Fn is not None
    if p_init is None:
        p_init = _initial_pressure(apply, h, dA, Fn, penetration)
    p = np.array(p_init, dtype=float)
    if load_control:
        # a start carrying another Fn (e.g. the solution of a nearby Fn) is scaled to
        # this one first: otherwise the iteration can stall on the start's contact area
        p *= Fn / (dA * p.sum())
    # work arrays, allocated once
    t = np.zeros_like(p)
    g = np.empty_like(p)
    gm = np.empty_like(p)
    tmp = np.empty_like(p)
    p_old = np.empty_like(p)
    Ic = np.empty(p.shape, dtype=bool)
    overlap = np.empty(p.shape, dtype=bool)
    G_old = 1.0
    restart = True      # δ = 0 in the paper: steepest descent step
    change = np.inf
    it = 0
    u = apply(p)
    for it in range(1, maxiter + 1):
        np.greater(p, 0.0, out=Ic)
        nI = int(np.count_nonzero(Ic))
        if nI == 0:
            raise NoContactError("the pressure vanished everywhere during the iteration")
        np.add(u, h, out=g)
        if load_control:
            g -= np.sum(g, where=Ic) / nI
        else:
            g -= penetration
        np.multiply(g, Ic, out=gm)               # residual on the contact set, 0 elsewhere
        if precondition is None:
            z = gm
        else:
            z = precondition(gm)
            z *= Ic
            if load_control:                     # keep the Fn: Σ z = 0 on the contact set
                z -= z.sum() / nI
                z *= Ic
        G = _dot(gm, z)
        if restart:
            t[...] = z
        else:
            t *= G / G_old
            t += z
            t *= Ic
        G_old = G
        r_raw = apply(t)
        denom = _dot(r_raw, t)
        if load_control:
            denom -= np.sum(r_raw, where=Ic) / nI * t.sum()
        if G == 0.0 or denom == 0.0:
            change = 0.0
            break
        tau = _dot(gm, t) / denom
        p_old[...] = p
        np.multiply(t, tau, out=tmp)
        p -= tmp
        clipped = bool(p.min() < 0.0)
        np.maximum(p, 0.0, out=p)
        np.equal(p, 0.0, out=overlap)
        overlap &= g < 0.0
        if overlap.any():
            restart = True
            p[overlap] -= tau * g[overlap]
        else:
            restart = False
        scale = 1.0
        if load_control:
            scale = Fn / (dA * p.sum())
            p *= scale
        total = p.sum()
        np.subtract(p, p_old, out=tmp)
        np.abs(tmp, out=tmp)
        change = float(tmp.sum() / total) if total > 0 else np.inf
        if change < tol:
            break
        if clipped or restart or it % 20 == 0:
            u = apply(p)
        else:   # linear step, active set unchanged: A p follows without a convolution
            r_raw *= tau
            u -= r_raw
            u *= scale
    u = apply(p)
    if load_control:
        np.add(u, h, out=g)
        delta = float(np.sum(g, where=p > 0.0) / np.count_nonzero(p > 0.0))
    else:
        delta = float(penetration)
    return p, delta, it, change, u


# --------------------------------------------------------------------------- entry
def _preconditioner(grid, operator):
    """The :class:`InverseSymbolPreconditioner` of ``operator``'s normal block (memoised).

    None for a single element (nothing to precondition).
    """
    if grid.size < 2:
        return None

    key = ("normal-preconditioner",) + grid_key(grid, operator.materials)
    return memo(key, lambda: InverseSymbolPreconditioner(operator.kernel[2, 2], grid.dx, grid.dy))


def _initial_pressure(apply, h, dA, Fn, penetration):
    """Pressure ∝ rigid interference, scaled by one operator application."""
    if Fn is not None:
        # interference of the rigid bodies pressed to a depth covering ~1/4 of the window
        depth = np.quantile(h, 0.25) - h.min()
        if depth <= 0:
            depth = np.ptp(h) if np.ptp(h) > 0 else 1.0
        over = np.maximum(h.min() + depth - h, 0.0)
        if not np.any(over > 0):
            over = np.ones_like(h)
        p = np.sqrt(over)
        return p * (Fn / (dA * p.sum()))
    over = np.maximum(penetration - h, 0.0)
    u = apply(over)
    k = over.max() / u[over > 0].max()
    return over * k


def solve_normal(grid: Grid, gap, materials, *, Fn=None, penetration=None, tol: float = 1e-8,
                 maxiter: int = 2000, on_fail: str = "raise", operator=None,
                 initial=None, precondition: bool = True) -> NormalResult:
    """Solve the normal contact problem on a grid (non-Hertzian, half-space).

    Parameters
    ----------
    grid : Grid
        Element grid covering (with some margin) the expected contact area.
    gap : array_like, shape (nx, ny)
        Undeformed separation h0 of the surfaces at the element centres [m]
        (any offset; for ``penetration`` control, contact needs h0 < δ somewhere).
    materials : Material or MaterialPair
    Fn : float, optional
        Prescribed normal force Fn [N], > 0.
    penetration : float, optional
        Prescribed approach δ [m]. Exactly one of ``Fn`` and ``penetration``.
    tol : float, optional
        Relative pressure change Σ|Δp|/Σp at which the iteration stops (1e-8).
    maxiter : int, optional
        Iteration limit (2000).
    on_fail : {"raise", "status"}
        Non-convergence raises :class:`~wheelrail.errors.ConvergenceError`
        ("raise", default) or returns the last iterate with
        ``status = Status.NOT_CONVERGED``.
    operator : InfluenceOperator, optional
        Reuse a prebuilt operator of the same grid (e.g. shared with a
        tangential solver).
    initial : ndarray, shape (nx, ny), optional
        Starting pressure [Pa] (e.g. the solution of a nearby Fn).
    precondition : bool, optional
        Use the FFT approximate inverse of the influence operator as the
        preconditioner of the conjugate gradients (default True; False: the
        plain method of Polonsky & Keer). Both converge to the same discrete
        solution; the preconditioned iteration count hardly grows with the grid.

    Returns
    -------
    NormalResult

    Raises
    ------
    InputError
        Bad arguments (Fn ≤ 0, both or none of Fn/penetration, wrong shape).
    NoContactError
        With prescribed penetration, if h0 − δ > 0 everywhere.
    ConvergenceError
        If the iteration limit is hit and ``on_fail="raise"``.

    Warns
    -----
    ContactTruncatedWarning
        If the contact reaches the grid boundary (``truncated`` is then True).

    Notes
    -----
    Deformed gap e = h0 − δ + u_n, u_n the gap-opening displacement difference
    (:mod:`wheelrail.halfspace.influence`). Algorithm: Polonsky & Keer (1999).

    Examples
    --------
    >>> import wheelrail as wr
    >>> from wheelrail.normal.bem import hertz_grid, solve_normal
    >>> hc = wr.hertz(10e3, A=1.0, B=1.0, material=wr.STEEL)
    >>> grid, h0 = hertz_grid(hc, elements=24)
    >>> sol = solve_normal(grid, h0, wr.STEEL, Fn=10e3)
    >>> abs(sol.p_max / hc.p0 - 1) < 0.03
    True
    """
    if not isinstance(grid, Grid):
        raise InputError(f"grid must be a Grid, got {type(grid).__name__}")
    pair = as_material_pair(materials)
    h = grid.check_field("gap", gap)
    if (Fn is None) == (penetration is None):
        raise InputError("give exactly one of Fn= and penetration= "
                         f"(got Fn={Fn!r}, penetration={penetration!r})")
    if on_fail not in ("raise", "status"):
        raise InputError(f"on_fail must be 'raise' or 'status', got {on_fail!r}")
    tol = float(positive("tol", tol))
    maxiter = integer("maxiter", maxiter)
    if Fn is not None:
        Fn = float(positive("Fn", Fn))
    else:
        penetration = float(as_float_array("penetration", penetration))
        if np.all(h - penetration >= 0.0):
            raise NoContactError(
                f"no contact: the undeformed gap minus the penetration is >= 0 everywhere "
                f"(min(gap) = {h.min()!r} m, penetration = {penetration!r} m)")
    guard("bem_normal", grid.size, f"normal BEM on a {grid.nx}x{grid.ny} grid")  # memory/time
    if operator is None:
        operator = influence_operator(grid, pair)
    elif not isinstance(operator, InfluenceOperator) or operator.grid != grid:
        raise InputError("operator must be an InfluenceOperator built on the same grid")
    block = operator.block(2, 2)
    apply = block.apply
    dA = grid.element_area

    p_init = None if initial is None else np.clip(grid.check_field("initial", initial), 0, None)
    if p_init is not None and not p_init.any():
        p_init = None
    pre = _preconditioner(grid, operator) if precondition else None
    p, delta, iterations, change, u = _pk(apply, h, dA, Fn, penetration, p_init, tol, maxiter,
                                          pre)
    converged = change < tol
    if not converged:
        msg = (f"normal BEM (Polonsky-Keer) did not converge in {iterations} iterations "
               f"(relative pressure change {change:.3g} > tol={tol:g}, grid {grid.nx}x{grid.ny})")
        if on_fail == "raise":
            raise ConvergenceError(msg)

    e = h - delta + u
    contact = p > 0.0
    scale = max(float(np.abs(u).max()), np.finfo(float).tiny)
    viol_in = float(np.abs(e[contact]).max()) if contact.any() else 0.0
    viol_out = float(np.maximum(-e[~contact], 0.0).max()) if (~contact).any() else 0.0
    residual = max(viol_in, viol_out) / scale
    truncated = bool(contact[0].any() or contact[-1].any() or contact[:, 0].any()
                     or contact[:, -1].any())
    if truncated:
        warnings.warn(
            f"the contact area reaches the edge of the {grid.nx}x{grid.ny} grid "
            f"(bounds {tuple(round(b, 9) for b in grid.bounds)} m): enlarge the window; "
            "the result is truncated", ContactTruncatedWarning, stacklevel=2)
    for arr in (p, e, u, contact):
        arr.setflags(write=False)
    return NormalResult(
        grid=grid, pressure=p, gap=e, displacement=u, contact=contact,
        Fn=float(p.sum() * dA), p_max=float(p.max()), penetration=float(delta),
        area=float(contact.sum() * dA), iterations=int(iterations),
        status=Status.CONVERGED if converged else Status.NOT_CONVERGED,
        residual=float(residual), truncated=truncated, materials=pair,
        info={"change": float(change)})


def hertz_grid(contact, elements: int = 64, margin: float = 1.25):
    """Grid and quadratic gap h0 = A x² + B y² around a Hertzian contact.

    Parameters
    ----------
    contact : HertzContact
        A single (non-batch) Hertz contact; its ``A``, ``B``, ``a``, ``b`` are used.
    elements : int
        Elements across the Hertz patch in each direction (2a/dx = 2b/dy), ≥ 2.
    margin : float
        Half-width of the window in units of the semi-axes (> 1): the window is
        [−margin·a, margin·a] × [−margin·b, margin·b], rounded up to a whole,
        odd number of elements so that an element is centred on the origin.

    Returns
    -------
    grid : Grid
    gap : ndarray, shape (nx, ny)
        A x² + B y² at the element centres [m].
    """
    if np.shape(contact.a) != ():
        raise InputError("hertz_grid needs a single HertzContact, got a batch")
    elements = integer("elements", elements, 2)
    margin = float(as_float_array("margin", margin))
    if not margin > 1.0:
        raise InputError(f"margin must be > 1, got {margin!r}")
    a, b = float(contact.a), float(contact.b)
    dx, dy = 2.0 * a / elements, 2.0 * b / elements
    n = math.ceil(2.0 * margin * a / dx - 1e-9)
    n += 1 - n % 2
    grid = Grid(-(n - 1) / 2 * dx, -(n - 1) / 2 * dy, dx, dy, n, n)
    gap = float(contact.A) * grid.X**2 + float(contact.B) * grid.Y**2
    return grid, gap


# --------------------------------------------------------------------------- normal method
#: Fewest elements across the contact patch (each direction) for a converged BEM result.
MIN_ACROSS = 8
#: Largest relative difference of the BEM area from the Hertz area (smooth Hertzian gaps).
AREA_TOLERANCE = 0.25


def check_resolution(grid, contact, what: str, hertz_area: float | None = None,
                     advice: str | None = None, stacklevel: int = 4) -> None:
    """Warn (:class:`~wheelrail.errors.ResolutionWarning`) for a grid too coarse for ``contact``.

    Parameters
    ----------
    grid : Grid
    contact : ndarray of bool, shape (ny, nx) or (nx, ny)
        Elements in contact.
    what : str
        The solve, for the message.
    hertz_area : float, optional
        Area of the Hertz solution of the same gap [m²]: a BEM area off by more
        than :data:`AREA_TOLERANCE` is reported.
    advice : str, optional
        What to change, for the messages (default: the BEM's ``element_size`` /
        ``grid_elements``; the exact theory names its ``elements``).
    stacklevel : int
        Of the warnings (the user's call).
    """
    from ..errors import ResolutionWarning

    c = np.asarray(contact, dtype=bool)
    if not c.any():
        return
    across = [int(c.sum(axis=k).max()) for k in (0, 1)]
    n = min(across)
    if n < MIN_ACROSS:
        fix = advice or (f"use a smaller element_size (about "
                         f"{min(grid.dx, grid.dy) * n / (2 * MIN_ACROSS):.2g} m) or more "
                         f"grid_elements")
        warnings.warn(f"{what}: only {n} element(s) across the contact patch (fewer than "
                      f"{MIN_ACROSS}): the area and pressure are not converged; {fix}",
                      ResolutionWarning, stacklevel=stacklevel)
    if hertz_area is not None and hertz_area > 0:
        area = float(c.sum()) * grid.element_area
        if abs(area / hertz_area - 1.0) > AREA_TOLERANCE:
            warnings.warn(f"{what}: contact area {area * 1e6:.4g} mm² is "
                          f"{(area / hertz_area - 1.0) * 100:+.0f} % from the Hertz area "
                          f"{hertz_area * 1e6:.4g} mm² of the same gap: the grid is too coarse "
                          f"({advice or 'use a smaller element_size or more grid_elements'})",
                          ResolutionWarning, stacklevel=stacklevel)


def _elements_for(length, elements, element_size):
    """Elements across ``length`` [m]: from ``element_size`` [m] if given, else ``elements``."""
    if element_size is None:
        n, what = int(elements), f"normal BEM with {int(elements)} elements"
    else:
        n = max(int(math.ceil(length / float(positive("element_size", element_size)) - 1e-9)), 2)
        what = (f"normal BEM with element_size = {float(element_size):g} m ({n} elements across "
                f"{length * 1e3:.3g} mm)")
    if element_size is not None or n > 1000:  # before the grid is built: no MemoryError
        guard("bem_normal", int(min(1.6 * n * n, 1e18)), what)
    return n


def _solution_info(sol) -> dict:
    return {"iterations": sol.iterations, "truncated": sol.truncated, "status": sol.status,
            "normal_solution": sol}


def _square_grid(bounds, element_size) -> Grid:
    """Grid on ``bounds`` with square elements of ``element_size`` (odd counts, centred)."""
    d = float(positive("element_size", element_size))
    cx, cy = 0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3])
    nx = max(int(math.ceil((bounds[1] - bounds[0]) / d)), 5)
    ny = max(int(math.ceil((bounds[3] - bounds[2]) / d)), 5)
    nx += 1 - nx % 2
    ny += 1 - ny % 2
    guard("bem_normal", nx * ny, f"normal BEM with element_size = {d:g} m on a {nx}x{ny} grid")
    return Grid(cx - (nx - 1) / 2 * d, cy - (ny - 1) / 2 * d, d, d, nx, ny)


def _solve_enlarging(gap, grid, materials, search, *, Fn=None, penetration=None, tol=1e-8,
                     max_enlarge=4, square=None, initial=None):
    """Normal solve on ``grid``; move touched window edges out while the contact is truncated.

    ``square``: keep square elements of this size when enlarging (else the element count).
    """

    for it in range(max_enlarge + 1):
        h0 = np.array(_evaluate(gap, grid.X, grid.Y))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ContactTruncatedWarning)
            start = initial if initial is not None and np.shape(initial) == grid.shape else None
            sol = solve_normal(grid, h0, materials, Fn=Fn, penetration=penetration, tol=tol,
                               initial=start)
        c = sol.contact
        if not sol.truncated or it == max_enlarge:
            break
        b = _enlarged_bounds(grid, c, search)
        if b is None:
            break
        grid = (_square_grid(b, grid.dx) if square or grid.dx == grid.dy
                else Grid.from_bounds(*b, nx=grid.nx, ny=grid.ny))
    if sol.truncated:
        warnings.warn(f"the contact still reaches the edge of the window "
                      f"{tuple(round(v, 9) for v in sol.grid.bounds)} m; the result is truncated",
                      ContactTruncatedWarning, stacklevel=3)
    return sol, grid


def _patches_of(sol, materials, cells, frames=None, origins=None, A=float("nan"),
                B=float("nan")):
    """One :class:`ContactPatch` per connected part of the contact of ``sol``."""

    labels, _ = contact_patches(sol)
    out = []
    for k in range(1, int(labels.max()) + 1):
        frame = None if frames is None else frames[k - 1]
        origin = (0.0, 0.0) if origins is None else origins[k - 1]
        info = _solution_info(sol)
        info["origin"] = origin
        out.append(ContactPatch.from_grid(sol.grid, sol.pressure, labels == k, materials,
                                          penetration=sol.penetration, A=A, B=B, cells=cells,
                                          frame=frame, origin=origin, method="bem", info=info))
    return tuple(out)
