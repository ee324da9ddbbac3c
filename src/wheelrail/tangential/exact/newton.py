"""The stepping core of the exact tangential theory: one Newton (or Gauss–Seidel) solve
of the slip equations on a grid with given rigid slip, used by steady rolling,
shift, transient rolling and prescribed-force loops.

See :mod:`wheelrail.tangential.exact` for the equations, the variables and the
preconditioner.
"""

from __future__ import annotations

import numpy as np

from ...halfspace.rolling import _BlockConvolution
from . import _kernels as K
from .krylov import _gmres


# --------------------------------------------------------------------------
# driver
# --------------------------------------------------------------------------
def _sweep_order(contact):
    """Element indices in contact, leading edge (largest x index) first."""
    # row-major order of the rows reversed: x index descending, y index ascending
    ri, jj = np.nonzero(contact[::-1])
    return (contact.shape[0] - 1 - ri).astype(np.int64), jj.astype(np.int64)


def _initial_traction(p0, g, contact):
    """Starting tractions (2, nx, ny) and their magnitude before projection.

    ``p0`` (zeros if None), zero outside the contact, scaled back onto the
    friction disc ``|p| ≤ g`` where it lies outside.
    """
    if p0 is None:
        return np.zeros((2,) + g.shape), np.zeros(g.shape)
    p = np.array(p0, dtype=float)
    norm = np.empty(g.shape)
    K._project_start(p, g, norm)
    return p, norm


def _gauss_seidel(kernel, conv, b, g, p0, tol, maxiter, skip_fraction=1e-3):
    """Solve ``s = b + M p``, Coulomb with bound ``g`` (nx, ny); returns p, s, sweeps, res."""
    contact = g > 0.0
    order_i, order_j = _sweep_order(contact)
    gmax = float(g.max())
    mxx, mxy, myx, myy = (np.ascontiguousarray(kernel[a, c]) for a, c in
                          ((0, 0), (0, 1), (1, 0), (1, 1)))
    p, _ = _initial_traction(p0, g, contact)
    px, py = np.ascontiguousarray(p[0]), np.ascontiguousarray(p[1])
    ii, jj = np.nonzero(contact)
    i0, i1, j0, j1 = int(ii.min()), int(ii.max()) + 1, int(jj.min()), int(jj.max()) + 1
    tol_abs = tol * gmax
    skip = skip_fraction * tol_abs
    res = np.inf
    sweeps = 0
    for sweeps in range(1, maxiter + 1):
        s = b + conv(np.stack((px, py)))
        sx, sy = np.ascontiguousarray(s[0]), np.ascontiguousarray(s[1])
        dp = K._gs_sweep(mxx, mxy, myx, myy, order_i, order_j, g, px, py, sx, sy,
                       i0, i1, j0, j1, skip)
        res = dp / gmax
        if dp <= tol_abs:
            break
    p = np.stack((px, py))
    s = b + conv(p)
    return p, s, sweeps, res


def _newton(kernel, conv, b, g, p0, tol, maxiter, upwind=True, gmres_rtol=0.1,
            gmres_maxiter=400, krylov_conv=None, precondition=None, forcing=None):
    """Active-set semismooth Newton for ``s = b + M p`` with Coulomb bound ``g``.

    :func:`_newton_force` with no force equation; returns its first five values.
    """
    return _newton_force(kernel, conv, b, g, p0, tol, maxiter, upwind, gmres_rtol,
                         gmres_maxiter, krylov_conv, precondition, forcing)[:5]


def _newton_force(kernel, conv, b, g, p0, tol, maxiter, upwind=True, gmres_rtol=0.1,
                  gmres_maxiter=400, krylov_conv=None, precondition=None, forcing=None,
                  force=None):
    """Active-set semismooth Newton for ``s = b + M p`` with Coulomb bound ``g``.

    Unknowns are the tractions of the adhesion elements (H) and the traction
    angles θ of the slip elements (S, ``p = g (cos θ, sin θ)``; Zhao, Vollebregt
    & Oosterlee 2014). Equations: ``s_I = 0`` on H, ``t_I · s_I = 0`` on S with
    ``t`` the unit vector normal to ``p``. Each Newton system is solved by
    GMRES with FFT matrix–vector products, right-preconditioned by
    :func:`_precondition`. After each step elements with ``|p| > g`` move to S
    and slip elements whose slip points along their traction move to H.

    ``precondition`` (private, for experiments such as
    ``benchmarks/bench_exact_preconditioner.py``): a factory
    ``(kind, pos, pinv, matvec, n) -> callable`` called once per Newton step
    with the element states (0 out of contact, 1 adhesion, 2 slip), the
    positions of their unknowns, the line preconditioner, the Krylov product
    and the number of unknowns; the callable replaces ``pinv`` as the right
    preconditioner. Default: the line preconditioner.

    ``force`` (optional) ``(weights, target, xi0, force_tol)``: the longitudinal rigid
    slip ξ (added to ``b[0]``, started from ``xi0``) is one more unknown, and one more
    equation asks ``Σ weights·p_x = target`` (the total force Fx, ``weights`` the element
    areas) within ``force_tol``. The Newton system is bordered by the column
    ``∂F/∂ξ`` (1 for the x equation of an adhesion element, ``t_x`` for a slip element)
    and the row ``∂Fx/∂(δp, δθ)``; the right preconditioner is the block elimination
    of the bordered system with the line preconditioner ``P`` (one extra ``P`` per
    Newton step for ``P ∂F/∂ξ``). The force equation is scaled by
    ``tol·max |b| / force_tol``, so that a residual ``≤ tol`` means both the slip
    equations and ``|Fx − target| ≤ force_tol``.

    Returns ``p, s, newton_iterations, residual, gmres_iterations, xi``; the
    residual is the largest equation residual divided by the slip scale
    ``max |b + ξ e_x|`` on the contact (at the current ξ; dimensionless); ``xi`` is
    ``None`` without ``force``.
    """
    contact = g > 0.0
    shape = g.shape
    order_i, order_j = _sweep_order(contact)
    nx, ny = shape
    cx, cy = nx - 1, ny - 1
    d0 = np.ascontiguousarray(kernel[:, :, cx, cy])
    if upwind and nx > 1:
        dup = np.ascontiguousarray(kernel[:, :, cx - 1, cy])
    else:
        dup = np.zeros((2, 2))
    p, norm = _initial_traction(p0, g, contact)
    slip = contact & (norm >= g * (1 - 1e-12)) & (norm > 0)
    xi = None
    if force is not None:
        weights, target, xi, force_tol = force
        xi = float(xi)
        b0 = b
        b = b0.copy()
        b[0] += xi
    s_scale = float(np.max(np.hypot(b[0], b[1])[contact]))
    if s_scale == 0.0:
        if force is not None:  # no slip scale to measure the residual by: not solved here
            return p, b.copy(), 0, np.inf, 0, xi
        return np.zeros((2,) + shape), b.copy(), 0, 0.0, 0, None
    if s_scale < 1e-100 or s_scale > 1e100:
        # the problem is positively homogeneous in (b, g, p): solve it rescaled; a bound
        # that would overflow (rigid slip ~1e-308) is capped: the patch then sticks fully
        with np.errstate(over="ignore"):
            g_scaled = np.minimum(g / s_scale, 1e300)
        scaled = None if force is None else (weights, target / s_scale, xi / s_scale,
                                             force_tol / s_scale)
        p, s, it, res, kry, xs = _newton_force(
            kernel, conv, (b if force is None else b0) / s_scale, g_scaled,
            None if p0 is None else np.asarray(p0) / s_scale, tol, maxiter, upwind, gmres_rtol,
            gmres_maxiter, krylov_conv, precondition, forcing, scaled)
        return p * s_scale, s * s_scale, it, res, kry, (None if xs is None else xs * s_scale)
    total_krylov = 0
    res = np.inf
    it = 0
    n_e = order_i.shape[0]
    # per element, in upwind order: (i, j, kind, position of its unknowns, list index of
    # its upstream neighbour (i + 1, j) or −1) and (t_x, t_y, g, diag, g t_x, g t_y)
    elem = np.empty((5, n_e), dtype=np.int64)
    elem[0], elem[1] = order_i, order_j
    index = np.full(shape, -1, dtype=np.int64)
    index[order_i, order_j] = np.arange(n_e)
    up_e = elem[4]
    up_e[:] = -1
    inside = order_i + 1 < nx
    up_e[inside] = index[order_i[inside] + 1, order_j[inside]]
    kind_e, pos_e = elem[2], elem[3]
    geo = np.empty((6, n_e))
    tx_e, ty_e, g_e, diag_e, gtx_e, gty_e = geo
    g_e[:] = g[order_i, order_j]
    ex_e, ey_e = np.empty(n_e), np.empty(n_e)
    vx = np.zeros(n_e)
    vy = np.zeros(n_e)
    v = np.zeros((2,) + shape)      # Krylov work field: only contact elements are written
    kconv = conv if krylov_conv is None else krylov_conv
    slip_e = np.ascontiguousarray(slip[order_i, order_j])
    F_work = np.empty(2 * n_e + 1)
    if force is not None:
        # the force equation, scaled so that |Fx − target| = force_tol weighs as a slip
        # residual tol·s_scale
        if np.ndim(weights):
            w_e = np.ascontiguousarray(np.asarray(weights, dtype=float)[order_i, order_j])
        else:
            w_e = np.full(n_e, float(weights))
        f_scale = tol * s_scale / force_tol
        c_w = f_scale * w_e
    p = np.ascontiguousarray(p)
    for it in range(1, maxiter + 1):
        s = b + conv(p)
        # --- active-set update
        changed = K._active_set(p, s, g_e, order_i, order_j, slip_e)
        if changed:
            # the Krylov product suffices: a step whose active set changed is never the last
            s = b + kconv(p)
        # --- residual, unknowns in upwind order, element data of the Krylov loop
        n_unknowns, big = K._newton_system(p, s, g_e, order_i, order_j, slip_e, kind_e, pos_e,
                                         ex_e, ey_e, tx_e, ty_e, gtx_e, gty_e, diag_e, F_work)
        if force is not None:
            F_work[n_unknowns] = f_scale * (K._weighted_x_sum(p, order_i, order_j, w_e) - target)
            big = max(big, abs(F_work[n_unknowns]))
        n_all = n_unknowns + (force is not None)
        F = F_work[:n_all]
        res = big / s_scale if n_all else 0.0
        if res <= tol and not changed:
            return p, s, it - 1, res, total_krylov, xi

        if force is None:
            e = c = w = np.zeros(n_unknowns)
            schur = 1.0
        else:
            # the ξ border [[J, e], [cᵀ, 0]]: e = ∂F/∂ξ, cᵀ z the scaled force change; the
            # preconditioner is the block elimination with P ≈ J⁻¹: w = P e,
            # ζ = (cᵀ P r − r_c) / (cᵀ w), z = P r − w ζ (exact when P = J⁻¹)
            e, c, w = np.empty(n_unknowns), np.empty(n_unknowns), np.empty(n_unknowns)
            schur = K._border(elem, geo, c_w, d0, dup, vx, vy, e, c, w)
            if schur == 0.0:
                schur = 1.0  # the force does not depend on ξ through P: ζ from r_c alone
        z_work = np.empty(n_all)

        if precondition is None:
            def op(r):
                """The Newton-system product of the preconditioned vector ``P r``."""
                K._prec_scatter(elem, geo, d0, dup, r, z_work, vx, vy, v, c, w, schur)
                out = np.empty(n_all)
                K._gather_bordered(kconv(v), z_work, elem, geo, out, e, c)
                return out

            def prec(r):
                z = np.empty(n_all)
                K._prec_scatter(elem, geo, d0, dup, r, z, vx, vy, v, c, w, schur)
                return z
        else:  # an experimental preconditioner (no ξ border)
            op, prec = _custom_preconditioner(precondition, shape, elem, geo, d0, dup, vx, vy,
                                              v, kconv, n_unknowns)
        rtol = gmres_rtol
        if forcing is not None:
            # adaptive forcing: loose while the active set moves, then just tight enough
            # to reach tol in one more step (floor: the single-precision products); with
            # ξ unknown the first step starts from the extrapolated state, tight at once
            loose, factor, floor = forcing
            rtol = loose if (changed or (it == 1 and force is None)) else min(
                gmres_rtol, max(factor * tol / res, floor))
        y, count = _gmres(op, -F, rtol, gmres_maxiter)
        total_krylov += count
        dz = prec(y)
        # --- update
        K._newton_update(p, dz, g_e, order_i, order_j, kind_e, pos_e, ex_e, ey_e)
        if force is not None:
            xi += float(dz[n_unknowns])
            b = b0.copy()
            b[0] += xi
            # the slip scale of the current ξ (as a solve at that ξ would measure it)
            s_scale = float(np.max(np.hypot(b[0], b[1])[contact])) or s_scale
            f_scale = tol * s_scale / force_tol
            c_w = f_scale * w_e
    s = b + conv(p)
    return p, s, it, max(res, np.nextafter(tol, np.inf)), total_krylov, xi


def _custom_preconditioner(precondition, shape, elem, geo, d0, dup, vx, vy, v, kconv, n):
    """``(op, prec)`` with an experimental preconditioner factory (see :func:`_newton`)."""
    order_i, order_j, kind_e, pos_e, up_e = elem
    tx_e, ty_e, g_e, diag_e, gtx_e, gty_e = geo

    def matvec(z):
        K._scatter(z, order_i, order_j, kind_e, pos_e, gtx_e, gty_e, v)
        mv = kconv(v)
        out = np.empty(n)
        K._gather(mv, z, order_i, order_j, kind_e, pos_e, tx_e, ty_e, diag_e, out)
        return out

    def pinv(r):
        z = np.empty(n)
        K._precondition(up_e, kind_e, pos_e, tx_e, ty_e, g_e, diag_e, d0, dup, r, z, vx, vy)
        return z

    kind = np.zeros(shape, dtype=np.int64)
    pos = np.zeros(shape, dtype=np.int64)
    kind[order_i, order_j] = kind_e
    pos[order_i, order_j] = pos_e
    prec = precondition(kind, pos, pinv, matvec, n)
    return (lambda r: matvec(prec(r))), prec


def newton_step(kernel, b, g, *, conv=None, initial=None, tol=1e-6, maxiter=100, upwind=True,
                krylov_conv=None, forcing=None):
    """One frictional step on a grid: the shared core of steady and transient rolling.

    Solves the discrete Coulomb problem ``s = b + K p`` with the traction bound
    ``g`` by the active-set semismooth Newton–GMRES method of the module
    docstring. Steady rolling (:func:`solve_rolling`) calls it once with the
    rolling kernel ``M``; the transient stepper
    (:func:`wheelrail.transient.transient_rolling`) calls it once per time step
    with ``K = C / (V Δt)`` and the displacement carried from the previous step
    in ``b`` (Baeza et al., eq. 2.19).

    Parameters
    ----------
    kernel : ndarray, shape (2, 2, 2nx−1, 2ny−1)
        Slip per unit traction [1/Pa] (offset layout of
        :func:`~wheelrail.halfspace.influence.influence_kernel`).
    b : ndarray, shape (2, nx, ny)
        Slip at zero traction (rigid slip plus carried displacement) [-].
    g : ndarray, shape (nx, ny)
        Traction bound μ·pn [Pa]; zero outside the contact.
    conv : callable, optional
        ``p (2, nx, ny) -> K p (2, nx, ny)``; built from ``kernel`` if omitted.
    initial : ndarray, shape (2, nx, ny), optional
        Starting tractions [Pa] (e.g. the previous time step).
    tol : float
        Residual of the slip equations relative to ``max |b|``.
    maxiter : int
        Largest number of Newton iterations.
    upwind : bool
        Precondition with the upstream neighbour (rolling kernels) or the
        element itself only.
    krylov_conv : callable, optional
        A cheaper approximation of ``conv`` (e.g. the single-precision
        product of the FFT convolution) used for the GMRES products only; the
        residual and the returned slip always use ``conv``, so the converged
        solution meets ``tol`` either way. Default: ``conv``.

    Returns
    -------
    p : ndarray, shape (2, nx, ny)
        Tractions on the wheel [Pa].
    s : ndarray, shape (2, nx, ny)
        Slip ``b + K p`` [-].
    iterations : int
        Newton iterations.
    residual : float
        Final scaled residual (``<= tol`` when converged).
    krylov : int
        GMRES iterations in total.

    References
    ----------
    Zhao, Vollebregt & Oosterlee (2015); Baeza et al. eqs. (2.19)–(2.20).
    """
    if conv is None:
        conv = _BlockConvolution(kernel)
    return _newton(kernel, conv, b, g, initial, tol, maxiter, upwind=upwind,
                   krylov_conv=krylov_conv, forcing=forcing)




def newton_force_step(kernel, b, g, *, weights, Fx, xi, force_tol, conv=None, initial=None,
                      tol=1e-6, maxiter=100, upwind=True, krylov_conv=None, forcing=None):
    """One frictional step with the total force Fx prescribed and ξ unknown.

    As :func:`newton_step` for ``s = b + ξ e_x + K p``, with the longitudinal rigid
    slip ξ one more unknown of the same Newton iteration and one more equation,
    ``Σ weights·p_x = Fx`` (the force-controlled transient step: one solve instead of
    an outer secant iteration on ξ around :func:`newton_step`).

    Parameters
    ----------
    kernel, b, g, conv, initial, tol, maxiter, upwind, krylov_conv, forcing
        As :func:`newton_step`; ``b`` (2, nx, ny) is the slip at zero traction and
        ξ = 0 [-].
    weights : float or ndarray, shape (nx, ny)
        Element areas [m²] (``Fx = Σ weights·p_x``).
    Fx : float
        Prescribed total force on the wheel [N].
    xi : float
        Starting creepage ξ [-] (e.g. the previous time step's).
    force_tol : float
        Tolerance of ``|Σ weights·p_x − Fx|`` [N].

    Returns
    -------
    p : ndarray, shape (2, nx, ny)
        Tractions on the wheel [Pa].
    s : ndarray, shape (2, nx, ny)
        Slip ``b + ξ e_x + K p`` [-].
    xi : float
        The creepage ξ [-].
    iterations : int
        Newton iterations.
    residual : float
        Final scaled residual (``<= tol`` when converged: the slip equations to
        ``tol`` and the force to ``force_tol``); ``inf`` when ``b + ξ e_x`` vanishes
        on the contact (no slip scale: the caller must start elsewhere).
    krylov : int
        GMRES iterations in total.

    References
    ----------
    Zhao, Vollebregt & Oosterlee (2015); Baeza et al. eqs. (2.19)–(2.20), §3.1
    (prescribed F1).
    """
    if conv is None:
        conv = _BlockConvolution(kernel)
    p, s, its, res, kry, xi = _newton_force(kernel, conv, b, g, initial, tol, maxiter,
                                            upwind=upwind, krylov_conv=krylov_conv,
                                            forcing=forcing,
                                            force=(weights, float(Fx), xi, float(force_tol)))
    return p, s, xi, its, res, kry
