"""Kalker's exact theory of tangential contact on a half-space grid.

The creep-force law :class:`Exact` (``method="exact"``) and the solvers behind
it, one concern per module:

=====================  ============================================================
:mod:`.method`         :class:`Exact`: Hertzian contacts and patches (any normal method)
:mod:`.steady`         :func:`solve_rolling`, :func:`solve_shift` on a grid, given pressure
:mod:`.newton`         :func:`newton_step`: the one stepping core (steady, shift,
                       transient rolling, prescribed forces); :func:`newton_force_step`
                       the same with ξ unknown and the force Fx prescribed
:mod:`.nested`         nested iteration (coarse grids start the fine solve)
:mod:`.krylov`         restarted GMRES
:mod:`._kernels`       numba kernels (active set, Newton system, line preconditioner)
:mod:`.coupled`        :func:`solve_gap`: normal + tangential (Johnson / Panagiotopoulos)
=====================  ============================================================

The FFT operators of the rolling problem are kernels in :mod:`wheelrail.halfspace.rolling`.

Two problems with a **given** normal pressure ``pn`` on a uniform grid of
``nx × ny`` piecewise-constant elements (:class:`~wheelrail.halfspace.grid.Grid`):

* **steady-state rolling** with prescribed creepages (ξ, η, φ)
  (:func:`solve_rolling`);
* **shift** (static, Cattaneo–Mindlin) with a prescribed rigid shift or total
  tangential force (:func:`solve_shift`).

Sign conventions (those of :mod:`wheelrail.halfspace.influence`)
----------------------------------------------------------------
``p = (px, py)`` is the tangential traction **on the wheel** [Pa];
``u = u(wheel) − u(rail)`` the displacement difference [m]. The contact moves
along +x over the rail, so material particles cross the patch from the leading
edge (largest x) to the trailing edge. In a frame moving with the contact the
material time derivative is ``d/dt = −V ∂/∂x`` and the slip velocity of the
wheel relative to the rail, divided by V, is (Kalker 1990, eq. 2.7)::

    s = w − ∂u/∂x,      w = (ξ − φ y, η + φ x).

Discretisation (Kalker's, 1990 §5.2): ``∂u/∂x`` at element I is the backward
difference towards the element *upstream* of it (``I + e_x``, where the
particle was one element length earlier), i.e. the transient problem with time
step ``dx / V``::

    s_I = w_I + (u_I − u_{I+e_x}) / dx = w_I + Σ_J M(I − J) p_J,
    M(m) = (C(m) − C(m + e_x)) / dx,

with ``C`` the influence kernel. The spin part of the rigid slip is evaluated
a sixth of an element upstream of the element centre::

    w_I = (ξ − φ y_I,  η + φ (x_I + dx/6)),

as in Vollebregt's CONTACT (rolling-step parameter FACPHI, default 1/6; reference [6]).
The backward difference of the displacement is centred half an element
upstream of the element; neither the centre nor that midpoint is the best
place for ``φ x``: measured on a Hertzian contact (a/b = 1.59, μ = 0.3, pure
spin φ = 3 /m), |Fy| is 2.7 % low at 40 elements with the centre, 5.7 % high
with the midpoint and within 0.1 % with the sixth (limit −1030 N for all
three, first order; ``tests/convergence/test_exact_convergence.py``); for
φ = 0.3 and 1 /m: 0.2 % and 0.6 % instead of 2.2 % and 1.7 %. The sixth is
a compromise for partial slip: in the no-slip limit the centre is exactly
reciprocal (C23 from Fy(φ) equals C23 from Mz(η); with the sixth it is 1.3 %
higher at 64 elements), and for very large spin (φ ≥ 10 /m, nearly full
slip) the centre's error is smaller (−4 … −5 % against +4 … +18 % at 40
elements). Without spin nothing changes. For the shift problem the slip is
a displacement [m]: ``s_I = W + u_I`` (rigid shift ``W`` of the wheel relative to the rail,
starting from the unloaded state), ``M = C``.

Coulomb's law with the traction bound ``g = μ pn``::

    |p_I| ≤ g_I;   |p_I| < g_I ⇒ s_I = 0 (adhesion);   s_I ≠ 0 ⇒ p_I = −g_I s_I/|s_I|.

Solvers
-------
``solver="newton"`` (default): an active-set semismooth Newton method in the
variables of Zhao, Vollebregt & Oosterlee (tractions in the adhesion area,
traction *angles* in the slip area, ``p = g (cos θ, sin θ)``). Each Newton
system is solved by restarted GMRES with FFT matrix–vector products
(O(N log N)), right-preconditioned by an exact solve of the strong
nearest-neighbour coupling along the rolling direction (self + upstream
element): for rolling this inverts the backward difference, i.e. a running
sum from the leading edge. The preconditioner is local across the rolling
direction, so the Krylov iterations per decade of the residual still grow
with the grid (about 7, 11, 13 at 40, 104, 160 elements across a Hertzian
contact, small creepage). After each step
elements whose traction exceeds the bound move to the slip area, slip
elements whose slip points along their traction move back to adhesion.
Converged when no element changes state and the largest residual of the slip
equations is below ``tol · max|w|``.

Nested iteration (steady rolling, ``nested=True``, the default without an
``initial`` traction): the same problem is first solved on the grid with
2 × 2 times larger elements on the same window (pressure averaged over the
four elements, so the normal force is kept), itself started that way while
the contact's bounding box is at least 32 elements long in both directions
(160 → 80 → 40 → 20 elements across), to the tolerance 3e-2 (its solution
differs from the fine one by the discretisation error anyway) and with
single-precision products throughout. Its tractions, bilinearly
interpolated between the coarse element centres, start the finer level; fine
elements whose coarse element slips start on the bound ``|p| = g``. This
removes the expensive first, all-adhesion Newton steps: the start is right
except for about one element row along the slip boundary, which the Newton
iteration moves in 2–4 steps. GMRES's relative tolerance (forcing) is 0.2
while the active set changes and then ``0.3 · tol / residual`` (at least
1e-4, the accuracy of the single-precision products), so that the last step
usually reaches ``tol`` at once. Only the path changes: plain and nested
solves agree to the tolerance (``tests/unit/test_exact_nested.py``).
Fine-level counts on the benchmark contact (``benchmarks/bench_exact_rolling.py``;
40, 104, 160 elements; Newton / Krylov, before → after): small creepage
8/59 → 5/41, 10/116 → 5/68, 10/141 → 6/96; combined creepage 8/37 → 4/26,
9/59 → 4/24, 10/73 → 5/31; pure spin 9/36 → 4/16, 10/56 → 5/29, 11/78 → 4/28;
the coarse levels add about a quarter of that in fine-product equivalents.
With combined creepage or spin the fine-level Krylov count is now nearly
independent of the grid; with small creepage (mostly adhesion) it still
grows, because the last decades are limited by the per-decade count of the
local preconditioner (the largest residual sits at the lateral tips of the
contact, where the lines along x are short).

Cost: one FFT convolution pair (x and y components together) per Krylov
iteration plus one or two per Newton iteration (the second, after an
active-set change, in single precision: such a step is never the last).
The products of steady rolling are made on the bounding box of the contact
(a smaller FFT than the window) and, inside GMRES, in single precision (the
Newton residual and the returned slip stay in double precision, so the
tolerance is met as before; forces change by < 1e-8 μFn); the 2-D
transforms skip the zero padding rows. The active-set update, residual and
correction of each Newton step, the scatter/gather of the Newton unknowns,
the line preconditioner (on element lists in upwind order) and GMRES's
Gram–Schmidt, update and back substitution are numba kernels without BLAS
calls (multi-threaded BLAS level-1/2 calls were several times slower than
one core on a loaded machine); the Gram–Schmidt sums are reassociated (SIMD)
and fused with the update of the previous basis vector (2.5 times faster
than plain modified Gram–Schmidt, the same operations up to round-off).

``solver="gs"`` (shift problem only): Kalker's block Gauss–Seidel (ConvexGS
without relaxation) with the exact 2×2 local problem per element (adhesion
trial, else ``p = −(D + λI)⁻¹ b`` with ``|p| = g`` by Newton on λ); O(N²)
per sweep (numba), kept as an independent check of the Newton solver. For
steady rolling the element-wise Gauss–Seidel iteration diverges on fine grids
(the inverse of the backward difference amplifies the lagged downstream
influence), which is why the default is the preconditioned Newton method.

Preconditioners tried and not adopted
-------------------------------------
Measured on the Hertzian benchmark contact (``benchmarks/``; N elements
across, small creepage ξ = 2e-4 unless said otherwise; Krylov iterations of
the whole solve):

* (measured in an earlier revision) an FFT-diagonal inverse of the
  influence operator (its symbol on the periodic grid): the discrete
  kernel's transform is indefinite; the analytic symbol helped
  adhesion-dominated cases (101 → 48 iterations) but slowed slip-heavy ones
  and doubled the FFTs per iteration; Gauss–Seidel with the lateral
  neighbours in the local solve diverges; an adaptive GMRES tolerance gave
  no gain;
* a two-level preconditioner (``benchmarks/bench_exact_preconditioner.py``
  reproduces these numbers): the ``a × a`` aggregates lying entirely in
  adhesion carry a constant traction change, the coarse operator is the
  exact Galerkin product of the rolling kernel (the kernel summed over the
  element pairs of two aggregates), dense and LU-factored per Newton step.
  Combined *multiplicatively* with the line solve (coarse correction, then
  the line solve on the remaining residual; one extra FFT product per Krylov
  iteration) and 4 × 4 aggregates, the iterations become nearly independent
  of the grid for small creepage: 44, 49, 54 at N = 40, 104, 160 (line
  solve alone: 59, 116, 141), but the slip-heavy cases gain little (combined
  creepage 35, 51, 59 against 37, 59, 73; spin 35, 51, 67 against 36, 56,
  78), every iteration costs two products, and the dense coarse system
  (2400 unknowns at N = 160 in the first, all-adhesion Newton step) costs
  more than the whole solve: 2.1 s against 0.26 s at N = 160, 0.24 s
  against 0.085 s at N = 104 (CPU, one thread, load 3.5). With 8 × 8
  aggregates the coarse solve is cheap but the iterations are 56, 77, 85 at
  twice the cost each (0.35 s against 0.26 s at N = 160). *Additive*
  combination (64, 121, 146) and replacing the extra product by the
  aggregate mean of the residual (58, 80, 91) do not help enough. A
  coarse-grid method would pay off only with a cheap (recursive, FFT-based)
  coarse solve *and* a smoother that does not need the extra product; not
  done (the coarse grids are used for the starting tractions instead:
  nested iteration, above).

Other variants measured with the nested start (same benchmark, iteration
counts of the fine level at 104 / 160 elements, small creepage) and dropped:

* adaptive forcing *without* the nested start: 116 → 131 Krylov at 104 (the
  tight solves are spoilt by the active-set changes that follow);
* fine elements start in slip only where the interpolated traction exceeds
  their bound (not by their coarse element): 104 / 138 Krylov instead of
  81 / 122 (fixed forcing 0.1); keeping the prolongated slip area for the
  first fine step: 88 / 131;
* forcing 0.4 while the active set changes: fewer Krylov (72 / 89) but one
  more Newton step and slower; a floor of 2e-5: 72 / 108;
* coarse tolerance 1e-3 or 1e-4 instead of 3e-2: the same fine-level counts,
  more coarse iterations (1e-1: the same as 3e-2);
* row scaling of the Newton equations by ``(max g / g)^α`` (to weight the
  lateral tips, where the largest residual stays): α = 0.5 no gain, α = 1
  twice the iterations;
* an exact (dense, LU-factored) solve of the Newton system restricted to the
  1, 2 or 3 outermost lateral lines of the contact, in place of their line
  solves (the largest residual of the last steps sits there: at 160 the
  second-to-last iterate is within tol everywhere else): 98, 110, 90 Krylov
  at 160 instead of 96, so the slow decay at the tips is not a local defect
  of the preconditioner;
* row weights 2, 3 or 5 on the outermost lateral lines in GMRES (to align its
  2-norm with the max-norm test): no consistent gain over six creepage cases
  (between −12 and +10 Krylov iterations);
* the Newton residual in single precision while it is above 1e3·tol: one
  more Newton step (79 / 112 Krylov), since the tight last solves need the
  right-hand side to ~1e-9 of the slip;
* a fused numba loop for the 2 × 2 spectrum product instead of numpy's
  in-place operations: no gain (memory bound);
* a nested start for the normal (Polonsky–Keer) solve: from the analytic
  Hertz pressure it takes 42 / 47 iterations, and even from the converged
  pressure perturbed by 1e-4 it takes 30 / 34 (the stopping rule, relative
  pressure change < 1e-8, sets the count), so a coarse-grid start cannot
  save much; not done.

References
----------
.. [1] J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
   Kluwer 1990, ch. 2 (eqs. 2.7–2.12) and ch. 5 (discretisation, §5.2;
   algorithm KOMBI, §5.3).
.. [2] E.A.H. Vollebregt, A Gauss–Seidel type solver for special convex
   programs, with application to frictional contact mechanics, J. Optim.
   Theory Appl. 87 (1995) 47–67 (ConvexGS).
.. [3] L. Baeza, F.J. Fuenmayor, J. Carballeira, A. Roda, Influence of the wheel–rail contact instationary process on contact parameters, §2.2–2.4, eqs. (2.9)–(2.20).
.. [4] N. Bosso, M. Spiryagin, A. Gugliotta, A. Somà, *Mechatronic Modeling of Real-Time Wheel-Rail Contact*, Springer 2013, ch. 2 (review of wheel–rail contact models), §2.2 (Johnson
   process; Panagiotopoulos process for K ≠ 0).
.. [5] J. Zhao, E.A.H. Vollebregt, C.W. Oosterlee, A fast nonlinear conjugate
   gradient based method for 3D frictional contact problems, J. Comput. Phys.
   288 (2015) 86–100 (azimuth-angle variables of the slip area).
.. [6] E.A.H. Vollebregt, *User guide for CONTACT, rolling and sliding contact
   with friction*, Vtech CMCC, technical report TR09-03 (rolling step input
   CHI, DQ, VELOC, FACPHI; the open-source CONTACT, Apache-2.0, evaluates the
   spin creepage at ``x + FACPHI·dq`` with default FACPHI = 1/6).
.. [7] Y. Saad, M.H. Schultz, GMRES: a generalized minimal residual algorithm
   for solving nonsymmetric linear systems, SIAM J. Sci. Stat. Comput. 7
   (1986) 856–869.
"""

from __future__ import annotations

from .coupled import solve_gap
from .method import Exact, exact_single
from .newton import newton_force_step, newton_step
from .steady import solve_rolling, solve_shift

__all__ = ["Exact", "exact_single", "solve_rolling", "solve_shift", "newton_step",
           "newton_force_step", "solve_gap"]
