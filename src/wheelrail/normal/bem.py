"""The normal contact problem of two elastic half-spaces on a grid (BEM).

Unknown: the pressure ``p`` (nx, ny) [Pa] on a uniform grid of
piecewise-constant elements. With ``h0`` the undeformed separation [m],
``δ`` the approach (penetration) [m] and ``u_n = A_nn * p`` the gap-opening
normal displacement difference of the two bodies (sign conventions of
:mod:`wheelrail.halfspace.influence`), the deformed gap is::

    e = h0 − δ + u_n

and the contact conditions (Signorini) are ``p ≥ 0, e ≥ 0, p·e = 0`` on every
element, with either ``δ`` prescribed or the load ``Fn = Σ p dA`` prescribed
(then ``δ`` is an unknown). The problem is the minimisation of the
complementary energy ½ pᵀA p + pᵀ(h0 − δ) over ``p ≥ 0`` (Kalker 1990 §5;
Kalker's NORM), solved here by the bound-constrained conjugate-gradient method
of Polonsky & Keer, which handles the load constraint directly and uses the
FFT influence operator (one convolution for the search direction per
iteration, plus one for the displacement when the active set changes).

Preconditioning (default): the residual on the contact set is multiplied by an
FFT approximate inverse of the influence matrix,
:class:`~wheelrail.halfspace.precondition.InverseSymbolPreconditioner` (the
reciprocal of the half-space operator's Fourier symbol, ∝ |k|, applied as a
circulant on a grid 8 elements larger than the window, one small real FFT pair
in single precision), restricted to the contact set again and, for load
control, projected onto zero total load (the load constraint is the deflated
direction, as in Vollebregt 2014). The directions are ``t = z + (g·z /
g_old·z_old) t_old``; step, clipping, re-activation and the stopping rule
(relative pressure change < tol) are those of Polonsky & Keer, so the solution
is that of the same discrete problem. Iterations (tol 1e-8, Hertz window 1.1
semi-axes, default start / Hertz start as the exact theory uses it): 40
elements (45²) 39/25 → 16/10, 104 (115²) 56/42 → 20/10, 160 (177²) 64/47 →
21/10; CPU time of the solve at 177² 3.5× (default start) to 5× (Hertz start)
lower (``benchmarks/bench_bem_normal.py``,
``benchmarks/bench_exact_rolling.py``). The work arrays of the loop are
allocated once (the FFTs still allocate their outputs).

Tried and not kept: the transform of the wrapped, zero-padded kernel (the
circulant embedding that makes the convolution exact) as the symbol: it is of
either sign at high frequencies and the iteration stalled (not converged in
500 iterations at 115² and 177², 172 iterations at 45²); more alias terms in
the symbol (|j| ≤ 3 instead of 1): at most one iteration fewer; the
preconditioner on the doubled (padded) FFT grid: the same counts at about 1.5×
the time; single-precision influence products (float32 FFTs, about 4× faster
at 360²) until the pressure change falls below 1e-4 or 1e-5, then double
precision to tol: float32 stalls at a change of about 2e-6, the switch costs a
restart and one more convolution, and from the Hertz start (10 iterations)
nothing was gained at 104 and 160 elements (10–20 % from the default start,
within the noise of a loaded machine). Earlier (plain iteration): a
coarse-grid start leaves 30–34 of 42–47 iterations (the stopping rule sets the
count) and numba versions of the loop were not faster. Not done: updating u_n
through the kernel columns of the elements the clipping or re-activation
changed instead of a convolution; from the Hertz start 4 of the 16
convolutions at 177² are such recomputes, each after 4–120 changed elements,
and beyond about 20 columns the column sum costs more than one FFT product.

Tangential tractions are not fed back into the normal problem (Johnson's
process): exact for quasi-identical materials (``K = 0``), an approximation
otherwise.

References
----------
.. [1] I.A. Polonsky, L.M. Keer, A numerical method for solving rough contact
   problems based on the multi-level multi-summation and conjugate gradient
   techniques, Wear 231 (1999) 206–219, §3.
.. [2] J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
   Kluwer 1990, §5.
.. [3] K.L. Johnson, *Contact Mechanics*, CUP 1985, §3.4 (Hertz reference).
.. [4] E.A.H. Vollebregt, A new solver for the elastic normal contact problem
   using conjugate gradients, deflation, and an FFT-based preconditioner,
   J. Comput. Phys. 257 (2014) 333–351.
"""

from __future__ import annotations

from ..options import configured, option
from ..patch import ContactPatch
from ._base import NormalMethod
from ._bem_solver import (
    ContactTruncatedWarning,
    _elements_for,
    _patches_of,
    _solution_info,
    _solve_enlarging,
    _square_grid,
    hertz_grid,
    polonsky_keer,
    solve_normal,
)
from ._gap import _window
from ._wheel_bem import solve_wheel

__all__ = ["Bem", "ContactTruncatedWarning", "solve_normal", "hertz_grid", "polonsky_keer"]


@configured
class Bem(NormalMethod):
    """Boundary elements on the elastic half-space (the exact normal problem).

    * a :class:`~wheelrail.hertzian.HertzContact`: the quadratic gap on a
      window around the ellipse (:func:`hertz_grid`), load prescribed;
    * a gap h(x, y): the window from the gap (:mod:`wheelrail.contact.window`),
      enlarged while the contact touches its edge; every connected part of
      the contact area is a patch, interaction included;
    * a wheel on its rail: candidate contact points whose contact planes are
      close (contact angles within ``group_angle``, lateral distance within
      half of ``width``) share one planar grid in the plane of the point
      with the smallest separation, so that their elastic interaction is
      included; the undeformed distance there is the profiles' separation
      along the normal plus the wheel's drop along x
      (:func:`wheelrail.geometry.separation`). Groups far apart (tread and
      flange) have their own grids and interact only through the wheel's
      vertical approach dz (the approach of a group is dz cos γ); dz is
      found by Newton's method so that Σ Fn cos γ = Q. With one group the
      load is prescribed directly (one solve).

    Other Parameters
    ----------------
    grid_elements : int, default 40
        Elements along the longer side of the potential contact area
        (ignored when ``element_size`` is given).
    element_size : float or None
        Element size [m] (square elements), e.g. 2e-4 for a 0.2 mm grid.
    window_margin : float, default 1.2
        Window half-size / half-size of the rigid interpenetration region.
    pressure_tol : float, default 1e-8
        Polonsky–Keer tolerance of the pressure solve.
    max_enlarge : int, default 4
        Window enlargements when the contact reaches the window edge.
    cells : int, default 40
        Cells per strip of the patch description.
    group_angle : float, default 0.2
        Largest contact-angle difference [rad] of points on one grid.
    width : float, default 0.04
        Extent [m] of the lateral separation function around a group.

    References
    ----------
    .. [1] J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
       Kluwer 1990, §5 (NORM, potential contact area).
    .. [2] I.A. Polonsky, L.M. Keer, A numerical method for solving rough
       contact problems based on the multi-level multi-summation and
       conjugate gradient techniques, Wear 231 (1999) 206–219.
    .. [3] E.A.H. Vollebregt, *User guide for CONTACT*, Vtech CMCC, the
       wheel–rail module (planar contact per patch, vertical force prescribed).
    """

    name = "bem"
    references = (
        "J.J. Kalker, Three-dimensional elastic bodies in rolling contact, Kluwer, 1990.",
        "I.A. Polonsky, L.M. Keer, A numerical method for solving rough contact problems based "
        "on the multi-level multi-summation and conjugate gradient techniques, Wear 231 (1999) "
        "206-219.",
    )
    grid_elements: int = option(40, lo=2, doc="elements along the longer side of the potential "
                                "contact area (ignored when element_size is given)")
    element_size: float | None = option(None, kind="float", lo=0.0, lo_open=True, allow_none=True,
                                        unit="m", doc="element size (square elements)")
    window_margin: float = option(1.2, lo=0.0, hi=10.0, lo_open=True,
                                  doc="window half-size / half-size of the rigid "
                                      "interpenetration region")
    pressure_tol: float = option(1e-8, lo=0.0, hi=1.0, lo_open=True, hi_open=True,
                                 doc="Polonsky-Keer tolerance of the pressure solve")
    max_enlarge: int = option(4, lo=0, doc="window enlargements when the contact reaches its edge")
    cells: int = option(40, lo=2, hi=2000, doc="cells per strip of the patch description")
    group_angle: float = option(0.2, lo=0.0, hi=3.2, lo_open=True, unit="rad",
                                doc="largest contact-angle difference of points on one grid")
    width: float = option(0.04, lo=0.0, hi=0.2, lo_open=True, unit="m",
                          doc="extent of the lateral separation function around a group")

    def from_contact(self, contact):
        n = _elements_for(2.0 * max(float(contact.a), float(contact.b)), self.grid_elements,
                          self.element_size)
        grid, gap = hertz_grid(contact, elements=n, margin=max(1.25, 1.0 + 3.0 / n))
        sol = solve_normal(grid, gap, contact.materials, Fn=float(contact.Fn),
                           tol=self.pressure_tol)
        return (ContactPatch.from_grid(grid, sol.pressure, sol.contact, contact.materials,
                                       penetration=sol.penetration, A=float(contact.A),
                                       B=float(contact.B), cells=self.cells, method="bem",
                                       info=_solution_info(sol)),)

    def from_gap(self, problem):
        w = _window(problem.gap, problem.penetration, problem.Fn, problem.materials,
                    self.grid_elements, self.window_margin, problem.search)
        grid = w["grid"]
        if self.element_size is not None:
            grid = _square_grid(grid.bounds, self.element_size)
        sol, grid = _solve_enlarging(problem.gap, grid, problem.materials, w["search"],
                                     Fn=problem.Fn, penetration=problem.penetration,
                                     tol=self.pressure_tol, max_enlarge=self.max_enlarge)
        return _patches_of(sol, problem.materials, self.cells, frames=None)

    def from_wheel(self, problem):
        return solve_wheel(problem, elements=self.grid_elements, element_size=self.element_size,
                           margin=self.window_margin, tol=self.pressure_tol,
                           max_enlarge=self.max_enlarge, cells=self.cells,
                           group_angle=self.group_angle, width=self.width)
