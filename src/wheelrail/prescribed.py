"""Creep forces with prescribed total tangential forces (creepages as unknowns).

In a vehicle simulation with a prescribed traction or braking effort, the
longitudinal (and/or lateral) force is known and the creepage that produces
it is sought. :func:`solve_creepages` wraps any registered creep-force law
(:func:`wheelrail.creep_forces`) in an outer root-finding iteration:

* one prescribed component (``Fx`` or ``Fy``): the force decreases
  monotonically with its own creepage (Kalker's sign convention), so the root
  is bracketed and found by the Illinois variant of regula falsi (robust up to
  the saturation plateau);
* both components: Broyden's method on (ξ, η) started with the linear
  theory's stiffness (Kalker's C11, C22), with backtracking.

References
----------
.. [1] J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
   Kluwer 1990, §5.3 (total force prescribed, creepage unknown).
.. [2] M. Dowell, P. Jarratt, A modified regula falsi method for computing
   the root of an equation, BIT 11 (1971) 168–174 (Illinois method).
.. [3] C.G. Broyden, A class of methods for solving nonlinear simultaneous
   equations, Math. Comp. 19 (1965) 577–593.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from . import tangential as _tangential
from ._validation import as_float_array, positive
from .api import creep_forces
from .errors import ConvergenceError, InputError
from .results import CreepForcesResult
from .tangential import as_creepage
from .tangential import broadcast_contact as _broadcast_contact
from .tangential.linear import linear_stiffness

__all__ = ["solve_creepages"]


def solve_creepages(contact, mu, Fx=None, Fy=None, creepage=(0.0, 0.0, 0.0), method="fastsim",
                    *, force_tol=1e-6, maxiter=60, **options) -> CreepForcesResult:
    """Creepages that produce prescribed tangential forces, and the resulting creep forces.

    Parameters
    ----------
    contact : HertzContact
        A single contact or a batch (solved case by case).
    mu : float or array_like
        Friction coefficient [-], > 0.
    Fx, Fy : float or array_like, optional
        Prescribed longitudinal / lateral force on the wheel [N] (Kalker's
        convention: a braking wheel, ξ < 0, has Fx > 0). At least one.
        The prescribed resultant must be below μ Fn.
    creepage : sequence of 3 floats
        (ξ, η, φ): φ [1/m] is always kept; ξ (η) is kept when ``Fx`` (``Fy``)
        is not prescribed and is the starting value otherwise.
    method : str or TangentialMethod
        Any creep-force law accepted by :func:`wheelrail.creep_forces`
        (the same default, ``"fastsim"``; ``"exact"`` for the reference solution).
    force_tol : float
        Stop when the force residual is below ``force_tol · μ Fn``.
    maxiter : int
        Largest number of outer iterations.
    **options
        Options of the creep-force law (as for :func:`wheelrail.creep_forces`).

    Returns
    -------
    CreepForcesResult
        The forces at the creepages found; ``info["xi"]``, ``info["eta"]``,
        ``info["phi"]`` hold the creepages, ``info["outer_iterations"]`` the
        number of creep-force evaluations.

    Raises
    ------
    InputError
        If neither force is given, a value is not finite, or |F| ≥ μ Fn (no
        creepage transmits it).
    ConvergenceError
        If the outer iteration fails.

    Examples
    --------
    >>> import wheelrail as wr
    >>> c = wr.hertz(1e4, A=1.0, B=2.0, material=wr.STEEL)
    >>> r = wr.solve_creepages(c, 0.3, Fx=1000.0, method="fastsim")
    >>> abs(r.Fx - 1000.0) < 1e-2, r.info["xi"] < 0
    (True, True)
    """
    if Fx is None and Fy is None:
        raise InputError("give at least one prescribed force, Fx= or Fy= [N]")
    impl = _tangential.get(method, options, argname="method")
    xi0, eta0, phi0 = as_creepage(creepage)
    if np.ndim(xi0) != 0:
        raise InputError("creepage must be a single (xi, eta, phi); batches follow the contact")
    mu = positive("mu", mu)
    force_tol = float(positive("force_tol", force_tol))
    shape = np.shape(contact.a)
    fx = None if Fx is None else as_float_array("Fx", Fx)
    fy = None if Fy is None else as_float_array("Fy", Fy)
    bshape = np.broadcast_shapes(shape, mu.shape, () if fx is None else fx.shape,
                                 () if fy is None else fy.shape)
    if len(bshape) > 1:
        raise InputError(f"batch inputs must be one-dimensional, got shape {bshape}")
    if bshape != ():
        return _batch(contact, mu, fx, fy, (float(xi0), float(eta0), float(phi0)), impl,
                      bshape, force_tol, maxiter, options)
    return _single(contact, float(mu), None if fx is None else float(fx),
                   None if fy is None else float(fy), (float(xi0), float(eta0), float(phi0)),
                   impl, force_tol, maxiter, options)


def _batch(contact, mu, fx, fy, creepage, impl, shape, force_tol, maxiter, options):
    n = shape[0]
    if np.shape(contact.a) != shape:
        contact = _broadcast_contact(contact, shape)
    mu = np.broadcast_to(mu, shape)
    fxs = None if fx is None else np.broadcast_to(fx, shape)
    fys = None if fy is None else np.broadcast_to(fy, shape)
    res = [_single(contact[i], float(mu[i]), None if fxs is None else float(fxs[i]),
                   None if fys is None else float(fys[i]), creepage, impl, force_tol, maxiter,
                   options) for i in range(n)]
    stack = lambda name: np.array([getattr(r, name) for r in res], dtype=float)  # noqa: E731
    info = {k: np.array([r.info.get(k, np.nan) for r in res], dtype=float)
            for k in ("xi", "eta", "phi", "outer_iterations")}
    return CreepForcesResult(Fx=stack("Fx"), Fy=stack("Fy"), Mz=stack("Mz"), Fn=stack("Fn"),
                       mu=np.asarray(mu, float), method=res[0].method, status=res[0].status,
                       iterations=info["outer_iterations"], fields=tuple(r.fields for r in res),
                       info=info)


def _single(contact, mu, Fx, Fy, creepage, impl, force_tol, maxiter, options):
    Fn = float(contact.Fn)
    limit = mu * Fn
    Ft = float(np.hypot(Fx or 0.0, Fy or 0.0))
    if Ft >= limit:
        raise InputError(f"prescribed tangential force |F| = {Ft!r} N must be < "
                         f"μ·Fn = {limit!r} N: no creepage transmits it (the contact slides)")
    xi, eta, phi = creepage
    ftol = force_tol * limit
    evals = [0]

    def evaluate(x, e):
        evals[0] += 1
        return creep_forces(contact, (x, e, phi), mu, method=impl)

    # linear-theory stiffnesses -dFx/dxi, -dFy/deta [N] start the iteration
    k11, k22 = (float(k) for k in linear_stiffness(contact.a, contact.b, contact.G, contact.nu)[:2])
    if Fx is not None and Fy is not None:
        r, xi, eta = _broyden(evaluate, Fx, Fy, xi, eta, k11, k22, ftol, maxiter)
    elif Fx is not None:
        r, xi = _illinois(lambda x: evaluate(x, eta), lambda r: r.Fx, Fx, xi, k11, ftol,
                          maxiter)
    else:
        r, eta = _illinois(lambda e: evaluate(xi, e), lambda r: r.Fy, Fy, eta, k22, ftol,
                           maxiter)
    info = dict(r.info)
    info.update({"xi": float(xi), "eta": float(eta), "phi": float(phi),
                 "outer_iterations": evals[0]})
    return replace(r, info=info)


def _illinois(evaluate, component, target, x0, k, ftol, maxiter):
    """Root of the decreasing function F(x) − target by bracketing + Illinois."""
    def g(x):
        r = evaluate(x)
        return r, float(component(r)) - target

    r, g0 = g(x0)
    if abs(g0) <= ftol:
        return r, x0
    step = max(abs(g0) / k, 1e-12)
    # F decreases with x: g > 0 -> move to larger x
    direction = 1.0 if g0 > 0 else -1.0
    xa, ga, ra = x0, g0, r
    xb = x0 + direction * step
    rb, gb = g(xb)
    n = 2
    while np.sign(gb) == np.sign(ga):
        if n >= maxiter:
            raise ConvergenceError(f"could not bracket the creepage for the prescribed force "
                                   f"{target!r} N (last creepage {xb!r})")
        xa, ga, ra = xb, gb, rb
        step *= 2.0
        xb = xb + direction * step
        rb, gb = g(xb)
        n += 1
    side = 0
    while n < maxiter:
        if abs(gb) <= ftol:
            return rb, xb
        if abs(ga) <= ftol:
            return ra, xa
        xc = xb - gb * (xb - xa) / (gb - ga)
        rc, gc = g(xc)
        n += 1
        if np.sign(gc) == np.sign(gb):
            xb, gb, rb = xc, gc, rc
            if side == -1:
                ga *= 0.5
            side = -1
        else:
            xa, ga, ra = xb, gb, rb
            xb, gb, rb = xc, gc, rc
            side = 1
        if abs(xb - xa) <= 1e-15 * max(abs(xa), abs(xb), 1e-300):
            break
    best = (rb, xb) if abs(gb) <= abs(ga) else (ra, xa)
    if min(abs(ga), abs(gb)) <= 10 * ftol:
        return best
    raise ConvergenceError(f"the creepage for the prescribed force {target!r} N was not found in "
                           f"{maxiter} evaluations (residual {min(abs(ga), abs(gb)):.3e} N)")


def _broyden(evaluate, Fx, Fy, xi, eta, k11, k22, ftol, maxiter):
    """Solve F(ξ, η) = (Fx, Fy) by Broyden's method with backtracking."""
    target = np.array([Fx, Fy])
    x = np.array([xi, eta], dtype=float)
    r = evaluate(*x)
    res = np.array([r.Fx, r.Fy]) - target
    J = np.diag([-k11, -k22])
    n = 1
    while np.hypot(*res) > ftol:
        if n >= maxiter:
            raise ConvergenceError(f"the creepages for the prescribed forces ({Fx!r}, {Fy!r}) N "
                                   f"were not found in {maxiter} evaluations "
                                   f"(residual {np.hypot(*res):.3e} N)")
        dx = -np.linalg.solve(J, res)
        t = 1.0
        while True:
            x_new = x + t * dx
            r_new = evaluate(*x_new)
            n += 1
            res_new = np.array([r_new.Fx, r_new.Fy]) - target
            if np.hypot(*res_new) < np.hypot(*res) or t < 1e-3 or n >= maxiter:
                break
            t *= 0.5
        step = x_new - x
        dres = res_new - res
        if step @ step > 0:
            J = J + np.outer(dres - J @ step, step) / (step @ step)
        x, r, res = x_new, r_new, res_new
    return r, x[0], x[1]
