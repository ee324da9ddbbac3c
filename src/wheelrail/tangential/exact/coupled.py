"""Coupled normal + tangential contact of two half-spaces on a grid.

:func:`solve_gap` chains the boundary-element normal solver
(:func:`wheelrail.normal.bem.solve_normal`) and the tangential grid solvers of
:mod:`wheelrail.tangential.exact` (steady rolling, shift): Johnson's
process for quasi-identical bodies, Panagiotopoulos' alternation for
dissimilar ones (``K != 0``). The exact theory of a contact of dissimilar
materials needs it (:class:`~wheelrail.tangential.Exact`), which is why it
lives in the exact theory's package; :mod:`wheelrail.contact.window` chooses
the window of an arbitrary gap around it.

References
----------
.. [1] P.D. Panagiotopoulos, A nonlinear programming approach to the
   unilateral contact- and friction-boundary value problem, Ing.-Arch. 44
   (1975) 421-432.
.. [2] J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
   Kluwer 1990, section 5.3 (KOMBI: alternation of NORM and TANG).
"""

from __future__ import annotations

import numpy as np

from ..._validation import positive
from ...errors import ConvergenceError, InputError
from ...halfspace.fft import InfluenceOperator
from ...halfspace.rolling import _BlockConvolution
from ...materials import as_material_pair
from ...normal.bem import solve_normal
from ...results import GapResult
from .steady import solve_rolling, solve_shift

__all__ = ["solve_gap"]


# --------------------------------------------------------------------------
# normal + tangential (Johnson's process / Panagiotopoulos' process)
# --------------------------------------------------------------------------
def solve_gap(grid, gap, materials, *, Fn=None, penetration=None, creepage=None, mu=None,
              shift=None, force=None, tol=1e-6, maxiter=100, normal_tol=1e-8,
              normal_maxiter=2000, outer_tol=1e-5, outer_maxiter=30, on_fail="raise",
              solver="newton") -> GapResult:
    """Normal and tangential contact of two half-spaces from the undeformed gap.

    The normal problem (:func:`wheelrail.normal.bem.solve_normal`) is solved
    first; then the rolling (``creepage``) or shift (``shift`` / ``force``)
    problem at that pressure. For quasi-identical materials (``K = 0``) the
    two problems are uncoupled and this is Johnson's process. For ``K ≠ 0`` the
    tangential tractions change the normal displacements and vice versa; the
    problems are alternated (Panagiotopoulos' process, Bosso et al. (2013), ch. 2 §2.3: normal
    with the current tangential tractions, tangential with the new pressure)
    until the tractions change by less than ``outer_tol`` (relative).

    Parameters
    ----------
    grid : Grid
    gap : ndarray, shape (nx, ny)
        Undeformed separation h0 [m].
    materials : Material or MaterialPair
    Fn, penetration : float
        Exactly one: normal force [N] or approach [m].
    creepage : sequence of 3 floats, optional
        (ξ, η, φ) for steady rolling.
    mu : float
        Friction coefficient (needed with a tangential problem).
    shift, force : sequence of 2 floats, optional
        Shift problem: rigid shift [m] or total tangential force [N].
    tol, maxiter, solver
        Tangential solver (see :func:`solve_rolling`).
    normal_tol, normal_maxiter
        Normal solver.
    outer_tol, outer_maxiter
        Panagiotopoulos loop (only used when ``K ≠ 0``).
    on_fail : {"raise", "status"}

    Returns
    -------
    GapResult

    References
    ----------
    .. [1] P.D. Panagiotopoulos, A nonlinear programming approach to the
       unilateral contact- and friction-boundary value problem, Ing.-Arch. 44
       (1975) 421–432.
    .. [2] Kalker (1990) §5.3 (KOMBI: alternation of NORM and TANG).
    .. [3] Bosso et al. (2013), ch. 2, §2.3, steps 1–4.
    """
    pair = as_material_pair(materials)
    h0 = grid.check_field("gap", gap)
    tangential = creepage is not None or shift is not None or force is not None
    if not tangential:
        normal = solve_normal(grid, h0, pair, Fn=Fn, penetration=penetration, tol=normal_tol,
                              maxiter=normal_maxiter, on_fail=on_fail)
        return GapResult(normal, None, 1, 0.0)
    if mu is None:
        raise InputError("mu is required for a tangential problem (creepage=, shift= or force=)")
    if creepage is not None and (shift is not None or force is not None):
        raise InputError("give creepage= (rolling) or shift=/force= (shift), not both")
    mu = float(positive("mu", mu))
    opts = dict(tol=tol, maxiter=maxiter, on_fail=on_fail, solver=solver)
    coupled = pair.K != 0.0
    op = InfluenceOperator(grid, pair)      # kernel and its transform: once for all alternations
    conv_nt = _BlockConvolution(op.kernel[2:3, :2]) if coupled else None
    pt = np.zeros((2,) + grid.shape)
    normal = tang = None
    change = 0.0
    outer = 0
    for outer in range(1, (outer_maxiter if coupled else 1) + 1):
        h = h0 if not coupled else h0 + conv_nt(pt)[0]
        normal = solve_normal(grid, h, pair, Fn=Fn, penetration=penetration, tol=normal_tol,
                              maxiter=normal_maxiter, on_fail=on_fail, operator=op)
        init = None if tang is None else np.stack((tang.px, tang.py))
        if creepage is not None:
            tang = solve_rolling(grid, normal.pressure, pair, creepage, mu, initial=init, **opts)
        else:
            tang = solve_shift(grid, normal.pressure, pair, mu, shift=shift, force=force,
                               initial=init, **opts)
        new = np.stack((tang.px, tang.py))
        scale = max(float(np.abs(new).max()), mu * normal.p_max * 1e-12)
        change = float(np.abs(new - pt).max()) / scale if outer > 1 else np.inf
        pt = new
        if not coupled or change <= outer_tol:
            break
    if coupled and change > outer_tol and on_fail == "raise":
        raise ConvergenceError(f"Panagiotopoulos' normal–tangential alternation did not converge "
                               f"in {outer} iterations (relative change {change:.2e} > "
                               f"outer_tol={outer_tol:.1e})")
    return GapResult(normal, tang, outer, 0.0 if not coupled else change)
