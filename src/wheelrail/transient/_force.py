"""The creepage ξ of a prescribed force and the steady fixed point of a step (private).

Helpers of :func:`wheelrail.transient.transient_rolling`: the safeguarded secant
iteration on ξ around a frictional solve (the fallback of the force-controlled
step, whose ξ is otherwise an unknown of the Newton iteration:
:func:`wheelrail.tangential.exact.newton_force_step`) and the steady fixed
point of a time step held under constant loads (the jump of ``settle``).
"""

from __future__ import annotations

import math

from ..errors import ConvergenceError
from ..tangential.exact import newton_force_step, newton_step

#: GMRES forcing of each step: relative tolerance while the active set changes, factor of
#: ``tol / residual`` once it has settled, floor (steady rolling uses 0.3 as the factor;
#: 0.6 saves 4 % of the products on Baeza et al. §3.1, 30 elements, same results to 1e-9).
_FORCING = (0.2, 0.6, 1e-4)


def _steady_limit(M, rigid, pn, g, xi0, p0, target, dA, ftol, tol, maxiter, slope, k, x,
                  upwind=True):
    """The steady fixed point ``(xi, p, s)`` of a step with rigid slip ``rigid`` (or None).

    ``target``: the prescribed force F1 (ξ unknown, started from ``xi0``) or None
    (ξ = ``xi0`` given). None when the steady Newton iteration does not converge
    (the run then simply continues stepping).
    """
    Mt, conv_M, conv_Mn = M
    b0 = rigid if conv_Mn is None else rigid + conv_Mn(pn[None])

    def solve(xi, pinit):
        b = b0.copy()
        b[0] += xi
        # from the given tractions, else from rest (the semismooth Newton iteration of the
        # second-order kernel can cycle from a warm start that converges from rest)
        for start in ((pinit, None) if pinit is not None else (None,)):
            pp, ss, its, res, kry = newton_step(Mt, b, g, conv=conv_M, initial=start, tol=tol,
                                                maxiter=maxiter, upwind=upwind,
                                                krylov_conv=conv_M.single, forcing=_FORCING)
            if res <= tol:
                return pp, ss
        raise ConvergenceError("steady limit")

    try:
        if target is None:
            pp, ss = solve(xi0, p0)
            return xi0, pp, ss
        # ξ an unknown of the Newton iteration (from the given tractions, else from rest),
        # the secant iteration around the solve if that fails
        for start in ((p0, None) if p0 is not None else (None,)):
            pp, ss, xi, its, res, kry = newton_force_step(
                Mt, b0, g, weights=dA, Fx=target, xi=xi0, force_tol=ftol, conv=conv_M,
                initial=start, tol=tol, maxiter=maxiter, upwind=upwind,
                krylov_conv=conv_M.single, forcing=_FORCING)
            if res <= tol:
                return xi, pp, ss
        xi, pp, ss, _ = _xi_for_force(solve, target, xi0, slope, p0, dA, ftol, k, x)
        return xi, pp, ss
    except ConvergenceError:
        return None


def _xi_for_force(solve, target, xi0, slope, p0, dA, ftol, k, x, maxit=50):
    """ξ with ``Fx(ξ) = target``: secant steps kept inside a bracket (Illinois)."""
    def F(xi, p_init):
        pp, ss = solve(xi, p_init)
        return float((pp[0] * dA).sum()) - target, pp, ss

    fa, pa, sa = F(xi0, p0)
    if abs(fa) <= ftol:
        return xi0, pa, sa, slope
    xa = xi0
    lo = hi = None  # brackets: (xi, f) with f > 0 (lo: xi too small) and f < 0
    if fa > 0:
        lo = (xa, fa)
    else:
        hi = (xa, fa)
    s = slope if (slope is not None and slope < 0) else None
    best = (xa, fa, pa, sa)
    for _ in range(maxit):
        if s is not None:
            xn = best[0] - best[1] / s
        else:
            xn = best[0] + 1e-6 * math.copysign(1.0, best[1])
        if lo is not None and hi is not None and not (lo[0] < xn < hi[0]):
            xn = (lo[0] * hi[1] - hi[0] * lo[1]) / (hi[1] - lo[1])  # regula falsi
            if not (lo[0] < xn < hi[0]):
                xn = 0.5 * (lo[0] + hi[0])
        fn, pn_, sn = F(xn, best[2])
        if xn != best[0] and fn != best[1]:
            s_new = (fn - best[1]) / (xn - best[0])
            s = s_new if s_new < 0 else s
        if abs(fn) <= ftol:
            return xn, pn_, sn, s
        if fn > 0:
            lo = (xn, fn) if lo is None or xn > lo[0] else lo
        else:
            hi = (xn, fn) if hi is None or xn < hi[0] else hi
        if lo is None or hi is None:
            # still unbracketed: move further in the right direction
            if s is None:
                s = -1.0
        best = (xn, fn, pn_, sn) if abs(fn) < abs(best[1]) or True else best
    raise ConvergenceError(f"step {k} (x = {x!r} m): no creepage found giving "
                           f"Fx = {target!r} N in {maxit} iterations")
