"""Kalker's exact theory of steady rolling contact on a half-space grid (creep-force law).

For each Hertzian contact the window around the ellipse is discretised
(:func:`wheelrail.normal.bem.hertz_grid`), the normal problem is solved with
the boundary-element solver (so the pressure is that of the discretised
half-space, not the analytic Hertz one) and then the steady-rolling problem
with Coulomb friction (:mod:`wheelrail.tangential.exact`). For
dissimilar materials (``K ≠ 0``) the two problems are alternated
(Panagiotopoulos' process, :func:`wheelrail.tangential.exact.solve_gap`).

This is the reference method of the library; accuracy is controlled by
``elements`` (elements across the contact in each direction): the creep
forces converge roughly with the first order of the element size.

References
----------
.. [1] J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
   Kluwer 1990, ch. 2 and 5.
.. [2] Bosso et al. (2013), ch. 2, §2.2–2.3; Baeza et al.,
   §2.2–2.4.
"""

from __future__ import annotations

from collections import OrderedDict

import numpy as np

from ..._validation import scalar_or_array
from ...materials import as_material_pair
from ...normal._bem_solver import MIN_ACROSS, check_resolution
from ...normal.bem import hertz_grid, solve_normal
from ...options import configured, option
from ...results import CreepForcesResult, GapResult, Status
from .._base import TangentialMethod
from .coupled import solve_gap
from .steady import solve_rolling

__all__ = ["Exact", "exact_single"]


_NORMAL_CACHE: OrderedDict = OrderedDict()
_NORMAL_CACHE_SIZE = 8


def _normal_solution(grid, gap, pair, load, on_fail, initial=None):
    """Boundary-element pressure of a Hertzian window, kept for the next call (private).

    A creepage iteration (:func:`wheelrail.solve_creepages`) or a creep curve
    solves the same normal problem for every creepage; for quasi-identical
    bodies (``K = 0``) it does not depend on the tangential tractions
    (Johnson's process), so it is solved once per grid, gap, materials and load.
    The solutions are frozen; the ``_NORMAL_CACHE_SIZE`` most recent are kept.
    ``initial`` is the starting pressure of the solver (the analytic Hertz
    pressure: about 30 % fewer iterations than the default start, the same
    solution to the solver's tolerance).
    """

    key = (grid, hash(gap.tobytes()), pair.G, pair.nu, pair.K, float(load), on_fail)
    try:
        normal = _NORMAL_CACHE.pop(key)
    except KeyError:
        normal = solve_normal(grid, gap, pair, Fn=float(load), on_fail=on_fail,
                              initial=initial)
    _NORMAL_CACHE[key] = normal
    while len(_NORMAL_CACHE) > _NORMAL_CACHE_SIZE:
        _NORMAL_CACHE.popitem(last=False)
    return normal


def exact_single(contact, xi, eta, phi, mu, *, elements=40, margin=1.1, tol=1e-6, maxiter=100,
                 on_fail="raise"):
    """Solve one Hertzian contact with the exact theory; returns a :class:`GapResult`.

    Parameters
    ----------
    contact : HertzContact
        A single contact.
    xi, eta, phi : float
        Creepages (ξ, η [-], φ [1/m]).
    mu : float
        Friction coefficient.
    elements, margin, tol, maxiter, on_fail
        See :class:`Exact`.

    Notes
    -----
    For quasi-identical bodies (``K = 0``) the normal solution is reused
    between calls on the same contact (:func:`_normal_solution`); otherwise
    the normal and tangential problems are alternated by
    :func:`wheelrail.contact.solve_gap`.
    """

    # at least one row of elements outside the Hertz ellipse, also on coarse grids where the
    # discrete contact area reaches the ellipse's edge elements
    margin = max(float(margin), 1.0 + 3.0 / elements)
    grid, gap = hertz_grid(contact, elements=elements, margin=margin)
    pair = as_material_pair(contact.materials)
    creepage = (float(xi), float(eta), float(phi))
    a, b = float(contact.a), float(contact.b)
    if pair.K != 0.0:
        res = solve_gap(grid, gap, pair, Fn=float(contact.Fn), creepage=creepage,
                        mu=float(mu), tol=tol, maxiter=maxiter, on_fail=on_fail)
        _check_grid(grid, res.normal, elements, a, b)
        return res
    hertz = float(contact.p0) * np.sqrt(np.clip(1.0 - (grid.X / a) ** 2 - (grid.Y / b) ** 2,
                                                0.0, None))
    normal = _normal_solution(grid, gap, pair, contact.Fn, on_fail, initial=hertz)
    _check_grid(grid, normal, elements, a, b)
    tang = solve_rolling(grid, normal.pressure, pair, creepage, float(mu), tol=tol,
                         maxiter=maxiter, on_fail=on_fail)
    return GapResult(normal, tang, 1, 0.0)


def _check_grid(grid, normal, elements, a, b):
    """Resolution of the exact theory's grid: elements across the contact and the area
    against Hertz (:func:`wheelrail.normal._bem_solver.check_resolution`), naming the
    ``elements`` option."""
    check_resolution(grid, normal.contact, f"exact theory with elements = {elements} "
                     f"({grid.nx}x{grid.ny} grid)", hertz_area=np.pi * a * b,
                     advice=f"use more elements (option 'elements' of 'exact', now {elements}; "
                            f"at least {MIN_ACROSS}, default 40)", stacklevel=_outside() + 1)


def _outside() -> int:
    """Stack level (from the caller) of the first frame outside the package: the user's call."""
    import os
    import sys

    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    frame, level = sys._getframe(1), 1
    while frame is not None and frame.f_code.co_filename.startswith(root + os.sep):
        frame, level = frame.f_back, level + 1
    return level


@configured
class Exact(TangentialMethod):
    """Kalker's exact (half-space, boundary-element) theory of steady rolling.

    Other Parameters
    ----------------
    elements : int, default 40
        Elements across the Hertz contact in each direction (≥ 4).
    margin : float, default 1.1
        Half-width of the grid window in semi-axes (> 1); raised to
        1 + 3/elements on coarse grids so that a row of elements lies outside
        the ellipse.
    tol : float, default 1e-6
        Tangential solver tolerance (largest slip residual / largest rigid slip).
    maxiter : int, default 100
        Newton iterations of the tangential solver.
    on_fail : {"raise", "status"}, default "raise"
        Raise :class:`~wheelrail.errors.ConvergenceError`, or return the last
        iterate with ``status=NOT_CONVERGED``.
    progress : bool or None, default None
        Show a progress bar for batches (``None``: only for more than 20 cases).

    Notes
    -----
    ``fields`` is the :class:`~wheelrail.results.GapResult`
    (grid, pressure, px, py, slip sx, sy, adhesion mask, displacements) for a
    single case, a tuple of them for a batch. ``info`` holds ``area``,
    ``p_max``, ``adhesion_area`` [m², Pa, m²], ``normal_iterations``,
    ``tangential_iterations``, ``outer_iterations``; ``iterations`` is the
    number of tangential Newton iterations.
    """

    name = "exact"
    references = (
        "J.J. Kalker, Three-dimensional elastic bodies in rolling contact, Kluwer, 1990 "
        "(exact theory, program CONTACT).",
        "P.D. Panagiotopoulos, A nonlinear programming approach to the unilateral contact- "
        "and friction-boundary value problem, Ing.-Arch. 44 (1975) 421-432.",
        "J. Zhao, E.A.H. Vollebregt, C.W. Oosterlee, A fast nonlinear conjugate gradient based "
        "method for 3D frictional contact problems, J. Comput. Phys. 288 (2015) 86-100.",
    )
    aliases = ("kalker",)
    elements: int = option(40, lo=4, doc="elements across the Hertz contact in each direction")
    margin: float = option(1.1, lo=1.0, hi=10.0, lo_open=True,
                           doc="half-width of the grid window in semi-axes")
    tol: float = option(1e-6, lo=0.0, hi=1.0, lo_open=True, hi_open=True,
                        doc="tangential solver tolerance (slip residual / rigid slip)")
    maxiter: int = option(100, lo=1, doc="Newton iterations of the tangential solver")
    on_fail: str = option("raise", choices=("raise", "status"),
                          doc="not converged: raise ConvergenceError, or return with a status")
    progress: bool | None = option(None, choices=(None, True, False),
                                   doc="progress bar for batches (None: above 20 cases)")

    def solve(self, contact, xi, eta, phi, mu):
        """Creep forces of a (batch of) Hertzian contact(s); see the class docstring."""
        elements, margin, tol, maxiter = self.elements, self.margin, self.tol, self.maxiter
        on_fail, progress = self.on_fail, self.progress
        shape = np.shape(contact.a)
        n = int(np.prod(shape)) if shape else 1
        xs, es, ps, ms = (np.broadcast_to(np.asarray(v, float), shape).reshape(-1)
                          for v in (xi, eta, phi, mu))
        cases = [contact] if not shape else [contact[i] for i in range(n)]
        show = (n > 20) if progress is None else bool(progress)
        sols = []
        iterator = range(n)
        bar = None
        if show:
            from rich.progress import Progress

            bar = Progress(transient=True)
            bar.start()
            task = bar.add_task("exact theory", total=n)
        try:
            for i in iterator:
                sols.append(exact_single(cases[i], xs[i], es[i], ps[i], ms[i], elements=elements,
                                         margin=margin, tol=tol, maxiter=maxiter,
                                         on_fail=on_fail))
                if bar is not None:
                    bar.advance(task)
        finally:
            if bar is not None:
                bar.stop()
        return _to_creep_forces(sols, shape, ms, self.name)

    def solve_patch(self, patch, xi, eta, phi, mu):
        """Exact theory on one patch: the patch's own pressure field if it has one
        (boundary elements; ``elements``/``margin`` then do not apply), else the
        boundary-element solution of its ellipse (as :meth:`solve`)."""
        return _solve_patches_exact(self, (patch,), ((xi, eta, phi),), float(mu))[0]

    def solve_patches(self, patches, creepages, mu, previous=None):
        """Patches on one boundary-element grid are solved together (their interaction
        included), with the creepages of the patch with the largest normal force, at its
        reference point (the rigid slip varies over the grid through the spin)."""
        return _solve_patches_exact(self, patches, creepages, float(mu), previous)


def _to_creep_forces(sols, shape, mu, name):
    def arr(f):
        v = np.array([f(s) for s in sols], dtype=float)
        return scalar_or_array(v.reshape(shape)) if shape else float(v[0])

    def iarr(f):
        v = np.array([f(s) for s in sols], dtype=int)
        return v.reshape(shape) if shape else int(v[0])

    converged = all(s.tangential.converged for s in sols)
    full_slip = all(not s.tangential.adhesion.any() for s in sols)
    status = (Status.NOT_CONVERGED if not converged
              else Status.FULL_SLIP if full_slip else Status.CONVERGED)
    info = {
        "area": arr(lambda s: s.normal.area),
        "p_max": arr(lambda s: s.normal.p_max),
        "adhesion_area": arr(lambda s: s.tangential.adhesion_area),
        "normal_iterations": iarr(lambda s: s.normal.iterations),
        "tangential_iterations": iarr(lambda s: s.tangential.iterations),
        "outer_iterations": iarr(lambda s: s.outer_iterations),
        "converged": (np.array([s.tangential.converged for s in sols]).reshape(shape)
                      if shape else bool(sols[0].tangential.converged)),
    }
    return CreepForcesResult(
        Fx=arr(lambda s: s.Fx), Fy=arr(lambda s: s.Fy), Mz=arr(lambda s: s.Mz),
        Fn=arr(lambda s: s.Fn), mu=scalar_or_array(mu.reshape(shape)) if shape else float(mu[0]),
        method=name, status=status, iterations=iarr(lambda s: s.tangential.iterations),
        fields=tuple(sols) if shape else sols[0], info=info)


def _patch_forces(sol, mask, grid, origin, centre):
    """Fx, Fy, Mz (about ``centre``) and adhesion area of the tractions of ``sol`` on ``mask``."""
    dA = grid.element_area
    px = np.where(mask, sol.px, 0.0)
    py = np.where(mask, sol.py, 0.0)
    X = grid.X - origin[0] - centre[0]
    Y = grid.Y - origin[1] - centre[1]
    Fx, Fy = float(px.sum() * dA), float(py.sum() * dA)
    Mz = float((X * py - Y * px).sum() * dA)
    adh = float(np.count_nonzero(sol.adhesion & mask) * dA)
    return Fx, Fy, Mz, adh


def _solve_patches_exact(method, patches, creepages, mu, previous=None):
    tol, maxiter, on_fail = method.tol, method.maxiter, method.on_fail
    elements, margin = method.elements, method.margin

    out = [None] * len(patches)
    shared = {}
    for i, p in enumerate(patches):
        if p.grid is None:
            r = exact_single(p.ellipse(), *creepages[i], mu, elements=elements, margin=margin,
                             tol=tol, maxiter=maxiter, on_fail=on_fail)
            res = _to_creep_forces([r], (), np.array([mu]), method.name)
            out[i] = res
        else:
            shared.setdefault(id(p.grid), []).append(i)
    for idx in shared.values():
        group = [patches[i] for i in idx]
        grid = group[0].grid
        pressure = sum(np.asarray(p.pressure) for p in group)
        main = max(idx, key=lambda i: patches[i].Fn)      # creepage of the largest patch
        xi, eta, phi = (float(v) for v in creepages[main])
        ox, oy = patches[main].info.get("origin", (0.0, 0.0))
        start = None
        for prev in previous or ():
            f = getattr(prev, "fields", None)
            if getattr(f, "px", None) is not None and f.grid == grid:
                # the last pass's tractions, scaled to the new pressure (exact in full slip)
                with np.errstate(invalid="ignore", divide="ignore"):
                    ratio = np.where(f.pressure > 0, pressure / f.pressure, 0.0)
                start = np.stack((f.px * ratio, f.py * ratio))
                break
        sol = solve_rolling(grid, pressure, group[0].materials, (xi + phi * oy, eta - phi * ox, phi),
                            mu, tol=tol, maxiter=maxiter, on_fail=on_fail, initial=start)
        for i in idx:
            p = patches[i]
            origin = p.info.get("origin", (0.0, 0.0))
            Fx, Fy, Mz, adh = _patch_forces(sol, p.mask, grid, origin, p.centre)
            full_slip = adh == 0.0
            status = (Status.NOT_CONVERGED if not sol.converged
                      else Status.FULL_SLIP if full_slip else Status.CONVERGED)
            out[i] = CreepForcesResult(Fx=Fx, Fy=Fy, Mz=Mz, Fn=p.Fn, mu=float(mu), method=method.name,
                                 status=status, iterations=sol.iterations, fields=sol,
                                 info={"area": p.area, "p_max": p.p_max, "adhesion_area": adh,
                                       "tangential_iterations": sol.iterations,
                                       "shared_grid": len(idx) > 1,
                                       "creepage_used": (xi, eta, phi)})
    return tuple(out)

