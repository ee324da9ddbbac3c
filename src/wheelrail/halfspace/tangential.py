"""Kalker's exact theory of tangential contact on a half-space grid (kernels).

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
.. [3] L. Baeza et al., seed paper 001, §2.2–2.4, eqs. (2.9)–(2.20).
.. [4] Review of wheel–rail contact models, seed paper 002, §2.2 (Johnson
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

import math
from dataclasses import dataclass, field

import numpy as np
from numba import njit

from .._resources import guard
from .._validation import as_float_array, integer, positive
from ..errors import ConvergenceError, InputError, NoContactError
from ..materials import as_material_pair
from .fft import _cropped_irfft2, _fft_shape, _kernel_transform, _padded_rfft2
from .grid import Grid
from ._memo import grid_key, memo
from .influence import influence_kernel

#: Where the spin's rigid slip φ·x is evaluated inside an element, in element
#: lengths upstream of its centre (Vollebregt's CONTACT, FACPHI = 1/6).
_SPIN_SHIFT = 1.0 / 6.0

__all__ = [
    "TangentialSolution",
    "rolling_kernel",
    "solve_rolling",
    "solve_shift",
    "newton_step",
]


# --------------------------------------------------------------------------
# numba kernels
# --------------------------------------------------------------------------
#: numba fast-math flags of the Krylov reductions: reassociation lets the dot
#: products use SIMD (about 2.5 times faster Gram–Schmidt; the sums change at
#: round-off level only); no assumptions about NaN or infinities.
_REASSOC = {"reassoc", "contract"}


@njit(cache=True)
def _local_problem(bx, by, dxx, dxy, dyx, dyy, g):
    """Exact solution of one element's problem ``s = b + D p`` under ``|p| ≤ g``.

    Returns ``(px, py, sx, sy)``; ``s = (0, 0)`` in adhesion.
    """
    det = dxx * dyy - dxy * dyx
    px = -(dyy * bx - dxy * by) / det
    py = -(-dyx * bx + dxx * by) / det
    if px * px + py * py <= g * g:
        return px, py, 0.0, 0.0
    if g <= 0.0:
        return 0.0, 0.0, bx, by
    # slip: p = -(D + lam I)^-1 b with |p| = g, lam >= 0; Newton on 1/|p| - 1/g
    lam = 0.0
    for _ in range(60):
        axx = dxx + lam
        ayy = dyy + lam
        det = axx * ayy - dxy * dyx
        px = -(ayy * bx - dxy * by) / det
        py = -(-dyx * bx + axx * by) / det
        qx = -(ayy * px - dxy * py) / det   # dp/dlam
        qy = -(-dyx * px + axx * py) / det
        n = math.sqrt(px * px + py * py)
        phi = 1.0 / n - 1.0 / g
        dphi = -(px * qx + py * qy) / (n * n * n)
        if dphi <= 0.0:
            break
        new = lam - phi / dphi
        if new < 0.0:
            new = 0.5 * lam
        if abs(new - lam) <= 1e-14 * (new + abs(dxx) + abs(dyy)):
            lam = new
            break
        lam = new
    axx = dxx + lam
    ayy = dyy + lam
    det = axx * ayy - dxy * dyx
    px = -(ayy * bx - dxy * by) / det
    py = -(-dyx * bx + axx * by) / det
    n = math.sqrt(px * px + py * py)
    px *= g / n
    py *= g / n
    sx = bx + dxx * px + dxy * py
    sy = by + dyx * px + dyy * py
    return px, py, sx, sy


@njit(cache=True)
def _gs_sweep(mxx, mxy, myx, myy, order_i, order_j, g, px, py, sx, sy,
              i0, i1, j0, j1, skip):
    """One block Gauss–Seidel sweep (in place); returns the largest traction change.

    ``m..`` are the 2-D kernel blocks (2nx−1, 2ny−1); ``sx, sy`` hold the
    current slip ``b + M p`` on the grid and are kept consistent inside the
    box ``[i0, i1) × [j0, j1)`` (changes smaller than ``skip`` are not
    propagated; the caller resynchronises after the sweep).
    """
    nx, ny = px.shape
    cx = nx - 1
    cy = ny - 1
    dxx = mxx[cx, cy]
    dxy = mxy[cx, cy]
    dyx = myx[cx, cy]
    dyy = myy[cx, cy]
    maxdp = 0.0
    for k in range(order_i.shape[0]):
        i = order_i[k]
        j = order_j[k]
        pxo = px[i, j]
        pyo = py[i, j]
        bx = sx[i, j] - dxx * pxo - dxy * pyo
        by = sy[i, j] - dyx * pxo - dyy * pyo
        pxn, pyn, sxn, syn = _local_problem(bx, by, dxx, dxy, dyx, dyy, g[i, j])
        dpx = pxn - pxo
        dpy = pyn - pyo
        px[i, j] = pxn
        py[i, j] = pyn
        d = max(abs(dpx), abs(dpy))
        if d > maxdp:
            maxdp = d
        if d > skip:
            for a in range(i0, i1):
                ka = a - i + cx
                for c in range(j0, j1):
                    kc = c - j + cy
                    sx[a, c] += mxx[ka, kc] * dpx + mxy[ka, kc] * dpy
                    sy[a, c] += myx[ka, kc] * dpx + myy[ka, kc] * dpy
        else:
            sx[i, j] += dxx * dpx + dxy * dpy
            sy[i, j] += dyx * dpx + dyy * dpy
    return maxdp


@njit(cache=True)
def _precondition(up_e, kind_e, pos_e, tx_e, ty_e, g_e, diag_e, d0, dup, r, z, vx, vy):
    """Apply the line preconditioner (in place into ``z``).

    Solves, in upwind order, the part of the Newton system that couples each
    element to itself (``d0 = M(0)``) and to its upstream neighbour
    (``dup = M(−e_x)``): for rolling this is the backward difference along x,
    whose exact inverse is a running sum from the leading edge. The contact
    elements are listed in upwind order: ``up_e`` is the list index of the
    upstream neighbour (−1 if it is out of contact or off the grid),
    ``kind_e`` 1 (adhesion, unknowns δp) or 2 (slip, unknown δθ), ``pos_e``
    the position of the unknowns; ``vx, vy`` (per element) receive the
    traction perturbation of each element.
    """
    det = d0[0, 0] * d0[1, 1] - d0[0, 1] * d0[1, 0]
    for k in range(kind_e.shape[0]):
        ux = 0.0
        uy = 0.0
        u = up_e[k]
        if u >= 0:
            ux = dup[0, 0] * vx[u] + dup[0, 1] * vy[u]
            uy = dup[1, 0] * vx[u] + dup[1, 1] * vy[u]
        q = pos_e[k]
        if kind_e[k] == 1:
            rx = r[q] - ux
            ry = r[q + 1] - uy
            ax = (d0[1, 1] * rx - d0[0, 1] * ry) / det
            ay = (-d0[1, 0] * rx + d0[0, 0] * ry) / det
            z[q] = ax
            z[q + 1] = ay
            vx[k] = ax
            vy[k] = ay
        else:
            t0 = tx_e[k]
            t1 = ty_e[k]
            tdt = (t0 * (d0[0, 0] * t0 + d0[0, 1] * t1) + t1 * (d0[1, 0] * t0 + d0[1, 1] * t1))
            den = tdt * g_e[k] + diag_e[k]
            dth = (r[q] - (t0 * ux + t1 * uy)) / den
            z[q] = dth
            vx[k] = g_e[k] * t0 * dth
            vy[k] = g_e[k] * t1 * dth


@njit(cache=True)
def _active_set(p, s, g_e, ei, ej, slip_e):
    """Active-set update of the Newton iteration on the element list (in place).

    Adhesion elements whose traction exceeds the bound (by more than 1e-10)
    move to slip and are projected onto it; slip elements whose slip points
    along their traction move to adhesion. Returns whether any element changed.
    """
    changed = False
    for k in range(ei.shape[0]):
        i = ei[k]
        j = ej[k]
        px = p[0, i, j]
        py = p[1, i, j]
        norm = math.hypot(px, py)
        if slip_e[k]:
            safe = norm if norm > 0.0 else 1.0
            if (px / safe) * s[0, i, j] + (py / safe) * s[1, i, j] > 0.0:
                slip_e[k] = False
                changed = True
        elif norm > g_e[k] * (1 + 1e-10):
            slip_e[k] = True
            changed = True
            f = g_e[k] / norm
            p[0, i, j] = px * f
            p[1, i, j] = py * f
    return changed


@njit(cache=True)
def _newton_system(p, s, g_e, ei, ej, slip_e, kind_e, pos_e, ex_e, ey_e, tx_e, ty_e,
                   gtx_e, gty_e, diag_e, F):
    """Unknown layout, residual ``F`` and per-element data of one Newton step (in place).

    Adhesion elements (kind 1) have two unknowns (δp), slip elements (kind 2)
    one (δθ), in upwind order; ``t = (−e_y, e_x)`` is the unit vector normal to
    the traction direction ``e``, ``diag`` the slip elements' ``max(−e·s, 0)``.
    Returns ``(number of unknowns, max |F|)``.
    """
    q = 0
    big = 0.0
    for k in range(ei.shape[0]):
        i = ei[k]
        j = ej[k]
        px = p[0, i, j]
        py = p[1, i, j]
        norm = math.hypot(px, py)
        safe = norm if norm > 0.0 else 1.0
        ex = px / safe
        ey = py / safe
        ex_e[k] = ex
        ey_e[k] = ey
        tx_e[k] = -ey
        ty_e[k] = ex
        gtx_e[k] = g_e[k] * -ey
        gty_e[k] = g_e[k] * ex
        pos_e[k] = q
        sx = s[0, i, j]
        sy = s[1, i, j]
        if slip_e[k]:
            kind_e[k] = 2
            sigma = ex * sx + ey * sy
            diag_e[k] = -sigma if sigma < 0.0 else 0.0
            f = -ey * sx + ex * sy
            F[q] = f
            q += 1
            if abs(f) > big:
                big = abs(f)
        else:
            kind_e[k] = 1
            diag_e[k] = 0.0
            F[q] = sx
            F[q + 1] = sy
            q += 2
            if abs(sx) > big:
                big = abs(sx)
            if abs(sy) > big:
                big = abs(sy)
    return q, big


@njit(cache=True)
def _newton_update(p, dz, g_e, ei, ej, kind_e, pos_e, ex_e, ey_e):
    """Apply the Newton correction ``dz`` to the tractions (in place).

    Adhesion: ``p += δp``; slip: the traction angle turns by δθ (clipped to
    ±π/2) on the bound, ``p = g (e cos δθ + t sin δθ)``.
    """
    half_pi = 0.5 * math.pi
    for k in range(ei.shape[0]):
        i = ei[k]
        j = ej[k]
        q = pos_e[k]
        if kind_e[k] == 1:
            p[0, i, j] += dz[q]
            p[1, i, j] += dz[q + 1]
        else:
            dth = min(max(dz[q], -half_pi), half_pi)
            c = math.cos(dth)
            sn = math.sin(dth)
            ex = ex_e[k]
            ey = ey_e[k]
            p[0, i, j] = g_e[k] * (ex * c - ey * sn)
            p[1, i, j] = g_e[k] * (ey * c + ex * sn)


@njit(cache=True)
def _scatter(z, ei, ej, kind_e, pos_e, gtx_e, gty_e, v):
    """Traction perturbation field ``v`` (2, nx, ny) of the Newton unknowns ``z`` (in place).

    Adhesion elements (kind 1) carry δp, slip elements (kind 2) ``g t δθ``;
    elements out of contact are never written (stay zero).
    """
    for k in range(ei.shape[0]):
        i = ei[k]
        j = ej[k]
        q = pos_e[k]
        if kind_e[k] == 1:
            v[0, i, j] = z[q]
            v[1, i, j] = z[q + 1]
        else:
            v[0, i, j] = gtx_e[k] * z[q]
            v[1, i, j] = gty_e[k] * z[q]


@njit(cache=True)
def _gather(mv, z, ei, ej, kind_e, pos_e, tx_e, ty_e, diag_e, out):
    """Newton-system product from the slip change ``mv = K v`` (2, nx, ny) (in place)."""
    for k in range(ei.shape[0]):
        i = ei[k]
        j = ej[k]
        q = pos_e[k]
        if kind_e[k] == 1:
            out[q] = mv[0, i, j]
            out[q + 1] = mv[1, i, j]
        else:
            out[q] = tx_e[k] * mv[0, i, j] + ty_e[k] * mv[1, i, j] + diag_e[k] * z[q]


@njit(cache=True, fastmath=_REASSOC)
def _orthogonalise(V, k, w, h):
    """Modified Gram–Schmidt of ``w`` against rows ``V[:k+1]``; fills ``h[:k+2]``."""
    n = w.shape[0]
    acc = 0.0
    for q in range(n):
        acc += V[0, q] * w[q]
    # one pass per basis vector: subtract the projection on V[i] and, with the updated
    # entries, accumulate the projection on V[i + 1] (the same operations as modified
    # Gram–Schmidt, half the passes over w)
    for i in range(k + 1):
        h[i] = acc
        nxt = 0.0
        if i < k:
            for q in range(n):
                wq = w[q] - acc * V[i, q]
                w[q] = wq
                nxt += V[i + 1, q] * wq
        else:
            for q in range(n):
                wq = w[q] - acc * V[i, q]
                w[q] = wq
                nxt += wq * wq
        acc = nxt
    h[k + 1] = math.sqrt(acc)


@njit(cache=True)
def _givens(H, cs, sn, e, k):
    """Apply the previous Givens rotations to column k of H and add a new one."""
    for i in range(k):
        t = cs[i] * H[i, k] + sn[i] * H[i + 1, k]
        H[i + 1, k] = -sn[i] * H[i, k] + cs[i] * H[i + 1, k]
        H[i, k] = t
    den = math.hypot(H[k, k], H[k + 1, k])
    if den == 0.0:
        cs[k] = 1.0
        sn[k] = 0.0
    else:
        cs[k] = H[k, k] / den
        sn[k] = H[k + 1, k] / den
    H[k, k] = den
    H[k + 1, k] = 0.0
    e[k + 1] = -sn[k] * e[k]
    e[k] = cs[k] * e[k]


@njit(cache=True, fastmath=_REASSOC)
def _norm(w):
    """Euclidean norm without BLAS (private; threaded BLAS is slow on a shared machine)."""
    acc = 0.0
    for q in range(w.shape[0]):
        acc += w[q] * w[q]
    return math.sqrt(acc)


@njit(cache=True)
def _gmres_update(V, H, e, k_used, x):
    """``x += V[:k]ᵀ y`` with ``H[:k, :k] y = e[:k]`` (back substitution; in place)."""
    y = np.empty(k_used)
    for i in range(k_used - 1, -1, -1):
        acc = e[i]
        for j in range(i + 1, k_used):
            acc -= H[i, j] * y[j]
        y[i] = acc / H[i, i]
    n = x.shape[0]
    for i in range(k_used):
        yi = y[i]
        for q in range(n):
            x[q] += yi * V[i, q]


def _gmres(matvec, rhs, rtol, maxiter, restart=60):
    """Restarted GMRES for ``A x = rhs`` from x = 0 (private; Saad & Schultz 1986).

    Written out (numba Gram–Schmidt, back substitution and update) because the
    BLAS calls of :func:`scipy.sparse.linalg.gmres` dominate for these small,
    many systems, and multi-threaded BLAS level-1/2 calls are slow when the
    cores are shared. Returns ``x, iterations``.
    """
    n = rhs.shape[0]
    x = np.zeros(n)
    beta0 = _norm(rhs)
    if beta0 == 0.0:
        return x, 0
    total = 0
    r = rhs
    m = min(restart, n)
    V = np.empty((m + 1, n))
    H = np.zeros((m + 1, m))
    cs = np.zeros(m)
    sn = np.zeros(m)
    e = np.zeros(m + 1)
    h = np.zeros(m + 1)
    while total < maxiter:
        beta = _norm(r)
        H[:] = 0.0
        e[:] = 0.0
        e[0] = beta
        np.multiply(r, 1.0 / beta, out=V[0])
        k_used = 0
        for k in range(m):
            w = matvec(V[k])
            _orthogonalise(V, k, w, h)
            total += 1
            H[: k + 2, k] = h[: k + 2]
            if h[k + 1] > 0:
                np.multiply(w, 1.0 / h[k + 1], out=V[k + 1])
            _givens(H, cs, sn, e, k)
            k_used = k + 1
            if abs(e[k + 1]) <= rtol * beta0 or total >= maxiter or h[k + 1] == 0:
                break
        if k_used:
            _gmres_update(V, H, e, k_used, x)
        if abs(e[k_used]) <= rtol * beta0 or total >= maxiter:
            break
        r = rhs - matvec(x)
    return x, total


# --------------------------------------------------------------------------
# operators
# --------------------------------------------------------------------------
def _block_multiply(hat, ph, out):
    """``out[a] = Σ_b hat[a, b] · ph[b]`` per frequency (complex; in place).

    The 2 × 2 block (the tangential products of every Krylov iteration) by
    in-place numpy operations, which vectorise; other shapes by a numba loop.
    """
    if hat.shape[:2] != (2, 2):
        _block_multiply_loop(hat, ph, out)
        return
    tmp = np.empty_like(out[0])
    for a in (0, 1):
        np.multiply(hat[a, 0], ph[0], out=out[a])
        np.multiply(hat[a, 1], ph[1], out=tmp)
        out[a] += tmp


@njit(cache=True)
def _block_multiply_loop(hat, ph, out):
    """``out[a] = Σ_b hat[a, b] · ph[b]`` per frequency, any block shape (in place)."""
    m, k = hat.shape[0], hat.shape[1]
    n0, n1 = ph.shape[1], ph.shape[2]
    for i in range(n0):
        for j in range(n1):
            for a in range(m):
                acc = 0j
                for b in range(k):
                    acc += hat[a, b, i, j] * ph[b, i, j]
                out[a, i, j] = acc


class _BlockConvolution:
    """FFT convolution with a block kernel (m, k, 2nx−1, 2ny−1) on an (nx, ny) grid (private).

    Same zero-padded wrap-around layout (and kernel transform) as
    :class:`~wheelrail.halfspace.fft.ConvolutionOperator`, but for a block of
    kernels sharing the forward transforms of the ``k`` input fields. The
    2-D transforms are done axis by axis so that the zero padding rows are
    never transformed along y (forward) and only the ``nx`` rows needed are
    transformed back (the same numbers as ``rfft2``/``irfft2``).
    """

    def __init__(self, kernel):
        self.nx = (np.shape(kernel)[-2] + 1) // 2
        self.ny = (np.shape(kernel)[-1] + 1) // 2
        self.shape = _fft_shape(self.nx, self.ny)
        self.hat = np.ascontiguousarray(_kernel_transform(kernel, self.shape))
        self.hat.setflags(write=False)
        self._hat32 = None

    def __call__(self, p):
        """``u[i] = Σ_j K[i, j] * p[j]`` for ``p`` of shape (k, nx, ny) -> (m, nx, ny)."""
        ph = _padded_rfft2(p, self.shape)
        uh = np.empty((self.hat.shape[0],) + ph.shape[1:], dtype=complex)
        _block_multiply(self.hat, ph, uh)
        return _cropped_irfft2(uh, self.shape, self.nx, self.ny)

    def single(self, p):
        """The product of :meth:`__call__` in single precision (float32 result).

        Relative error about 1e-6 of the largest output: enough for the
        directions of a Krylov method (which only needs a residual reduction
        of 10 per Newton step), about four times cheaper than double precision.
        """
        if self._hat32 is None:
            self._hat32 = self.hat.astype(np.complex64)
        ph = _padded_rfft2(np.asarray(p, dtype=np.float32), self.shape)
        uh = np.empty((self.hat.shape[0],) + ph.shape[1:], dtype=np.complex64)
        _block_multiply(self._hat32, ph, uh)
        return _cropped_irfft2(uh, self.shape, self.nx, self.ny)


def rolling_kernel(grid: Grid, materials) -> np.ndarray:
    """Kernel of the discretised steady-rolling slip, shape (3, 3, 2nx−1, 2ny−1).

    ``M(m) = (C(m) − C(m + e_x)) / dx`` [m/Pa / m = 1/Pa]: the slip
    ``s_I = w_I + Σ_J M(I − J) p_J`` (module docstring). Built from the
    influence kernel of a grid one element longer so that the offset
    ``m + e_x = nx`` is available.
    """
    return _rolling_and_influence_kernels(grid, materials)[0]


def _rolling_and_influence_kernels(grid: Grid, materials):
    """``(M, C)``: :func:`rolling_kernel` and the influence kernel ``C`` of ``grid``.

    Both from one influence kernel of the grid one element longer (``C`` is its
    central part, offsets ``−(nx−1) … nx−1``).
    """
    pair = as_material_pair(materials)

    def build():
        ext = Grid(grid.x0, grid.y0, grid.dx, grid.dy, grid.nx + 1, grid.ny)
        Ce = influence_kernel(ext, pair)
        nx = grid.nx
        C = Ce[:, :, 1:2 * nx, :]
        M = (C - Ce[:, :, 2:2 * nx + 1, :]) / grid.dx
        for a in (M, C):
            a.setflags(write=False)
        return M, C
    return memo(("rolling",) + grid_key(grid, pair), build)


def _contact_box(grid, pair, R, contact):
    """The bounding box of the contact and the rolling kernel / convolution cropped to it.

    Tractions vanish outside the contact and slips are needed only inside it, so
    the steady-rolling products can be made on the box of the contact elements:
    the same products (to round-off) with a smaller FFT (the window around a
    Hertzian contact is about 10 % wider than the contact on each side).
    Returns ``(box, kernel, conv)`` with ``box`` a pair of slices; the full
    grid when cropping does not shrink the transform.
    """
    ii, jj = np.nonzero(contact)
    i0, i1, j0, j1 = int(ii.min()), int(ii.max()) + 1, int(jj.min()), int(jj.max()) + 1
    mx, my = i1 - i0, j1 - j0
    full = (slice(0, grid.nx), slice(0, grid.ny))
    if _fft_shape(mx, my) == _fft_shape(grid.nx, grid.ny):
        return full, R[:2, :2], _block_convolution(grid, pair, "R_tt", R[:2, :2])
    cx, cy = grid.nx - 1, grid.ny - 1
    kernel = R[:2, :2, cx - (mx - 1): cx + mx, cy - (my - 1): cy + my]
    key = ("block-box", mx, my) + grid_key(grid, pair)
    return (slice(i0, i1), slice(j0, j1)), kernel, memo(key, lambda: _BlockConvolution(kernel))


def _block_convolution(grid, pair, which, kernel):
    """The :class:`_BlockConvolution` of a kernel block of ``grid`` (kept for reuse)."""
    return memo(("block", which) + grid_key(grid, pair), lambda: _BlockConvolution(kernel))


# --------------------------------------------------------------------------
# results
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class TangentialSolution:
    """Tangential tractions and slip on a grid (frozen).

    Attributes
    ----------
    grid : Grid
    pressure : ndarray, shape (nx, ny)
        Normal pressure used [Pa].
    px, py : ndarray, shape (nx, ny)
        Tangential traction on the wheel [Pa].
    sx, sy : ndarray, shape (nx, ny)
        Slip of the wheel relative to the rail: dimensionless slip velocity
        (rolling) or slip distance [m] (shift); zero in adhesion and outside
        the contact.
    ux, uy : ndarray, shape (nx, ny)
        Tangential displacement difference u(wheel) − u(rail) [m].
    adhesion, slip : ndarray of bool, shape (nx, ny)
        Elements in contact that stick / slide.
    Fx, Fy : float
        Tangential force on the wheel [N].
    Mz : float
        Moment of the tangential tractions about the grid origin [N·m].
    mu : float
    kind : str
        ``"rolling"`` or ``"shift"``.
    creepage : tuple
        (ξ, η, φ) for rolling; the rigid shift (Wx, Wy) [m] for shift.
    iterations : int
        Newton iterations (``solver="newton"``; for a prescribed shift force,
        summed over the outer iterations) or Gauss–Seidel sweeps.
    converged : bool
    residual : float
        Newton: largest slip-equation residual / max |rigid slip|;
        Gauss–Seidel: largest traction change of the last sweep / max μ·pn.
    info : dict
        ``solver``, ``krylov_iterations`` and ``coarse`` (rolling: the Newton
        and Krylov counts of the nested-iteration levels), ``outer_iterations``
        (shift).
    """

    grid: Grid
    pressure: np.ndarray
    px: np.ndarray
    py: np.ndarray
    sx: np.ndarray
    sy: np.ndarray
    ux: np.ndarray
    uy: np.ndarray
    adhesion: np.ndarray
    slip: np.ndarray
    Fx: float
    Fy: float
    Mz: float
    mu: float
    kind: str
    creepage: tuple
    iterations: int
    converged: bool
    residual: float
    info: dict = field(default_factory=dict)

    @property
    def contact(self) -> np.ndarray:
        """Elements with positive pressure, shape (nx, ny)."""
        return self.pressure > 0.0

    @property
    def adhesion_area(self) -> float:
        """Area of the adhesion zone [m²]."""
        return float(np.count_nonzero(self.adhesion)) * self.grid.element_area

    @property
    def Ft(self) -> float:
        """|F_t| = √(Fx² + Fy²) [N]."""
        return float(np.hypot(self.Fx, self.Fy))

    def as_arrays(self) -> dict:
        """Plain arrays on the grid, indexed ``[i_x, i_y]``, for plotting and export.

        Keys as :meth:`wheelrail.contact.GapSolution.as_arrays`: ``x``, ``y``
        (element centres, m), ``px``, ``py``, ``p`` (Pa), ``adhesion``,
        ``inside`` (bool), ``dA`` (element areas, m²), ``sx``, ``sy``.
        """
        g = self.grid
        return {"x": g.X, "y": g.Y, "px": np.asarray(self.px), "py": np.asarray(self.py),
                "p": np.asarray(self.pressure), "adhesion": np.asarray(self.adhesion, bool),
                "inside": np.asarray(self.contact, bool),
                "dA": np.full(g.shape, g.element_area), "sx": np.asarray(self.sx),
                "sy": np.asarray(self.sy)}


# --------------------------------------------------------------------------
# driver
# --------------------------------------------------------------------------
def _sweep_order(contact):
    """Element indices in contact, leading edge (largest x index) first."""
    ii, jj = np.nonzero(contact)
    order = np.lexsort((jj, -ii))
    return ii[order].astype(np.int64), jj[order].astype(np.int64)


def _initial_traction(p0, g, contact):
    """Starting tractions (2, nx, ny) and their magnitude before projection.

    ``p0`` (zeros if None), zero outside the contact, scaled back onto the
    friction disc ``|p| ≤ g`` where it lies outside.
    """
    p = np.zeros((2,) + g.shape) if p0 is None else np.array(p0, dtype=float)
    p[:, ~contact] = 0.0
    norm = np.hypot(p[0], p[1])
    return np.where(norm > g, p * (g / np.where(norm > 0, norm, 1.0)), p), norm


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
        dp = _gs_sweep(mxx, mxy, myx, myy, order_i, order_j, g, px, py, sx, sy,
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

    Returns ``p, s, newton_iterations, residual, gmres_iterations``; the
    residual is the largest equation residual divided by the slip scale
    ``max |b|`` (dimensionless).
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
    s_scale = float(np.max(np.hypot(b[0], b[1])[contact]))
    if s_scale == 0.0:
        return np.zeros((2,) + shape), b.copy(), 0, 0.0, 0
    if s_scale < 1e-100 or s_scale > 1e100:
        # the problem is positively homogeneous in (b, g, p): solve it rescaled; a bound
        # that would overflow (rigid slip ~1e-308) is capped: the patch then sticks fully
        with np.errstate(over="ignore"):
            g_scaled = np.minimum(g / s_scale, 1e300)
        p, s, it, res, kry = _newton(kernel, conv, b / s_scale, g_scaled,
                                     None if p0 is None else np.asarray(p0) / s_scale, tol,
                                     maxiter, upwind, gmres_rtol, gmres_maxiter, krylov_conv,
                                     precondition, forcing)
        return p * s_scale, s * s_scale, it, res, kry
    total_krylov = 0
    res = np.inf
    it = 0
    # list index of each contact element's upstream neighbour (i + 1, j), −1 if none
    index = np.full(shape, -1, dtype=np.int64)
    index[order_i, order_j] = np.arange(order_i.shape[0])
    up_e = np.full(order_i.shape[0], -1, dtype=np.int64)
    inside = order_i + 1 < nx
    up_e[inside] = index[order_i[inside] + 1, order_j[inside]]
    g_e = np.ascontiguousarray(g[order_i, order_j])
    vx = np.zeros(order_i.shape[0])
    vy = np.zeros(order_i.shape[0])
    v = np.zeros((2,) + shape)      # Krylov work field: only contact elements are written
    kconv = conv if krylov_conv is None else krylov_conv
    n_e = order_i.shape[0]
    slip_e = np.ascontiguousarray(slip[order_i, order_j])
    kind_e = np.empty(n_e, dtype=np.int64)
    pos_e = np.empty(n_e, dtype=np.int64)
    ex_e, ey_e, tx_e, ty_e, gtx_e, gty_e, diag_e = (np.empty(n_e) for _ in range(7))
    F_work = np.empty(2 * n_e)
    p = np.ascontiguousarray(p)
    for it in range(1, maxiter + 1):
        s = b + conv(p)
        # --- active-set update
        changed = _active_set(p, s, g_e, order_i, order_j, slip_e)
        if changed:
            # the Krylov product suffices: a step whose active set changed is never the last
            s = b + kconv(p)
        # --- residual, unknowns in upwind order, element data of the Krylov loop
        n_unknowns, big = _newton_system(p, s, g_e, order_i, order_j, slip_e, kind_e, pos_e,
                                         ex_e, ey_e, tx_e, ty_e, gtx_e, gty_e, diag_e, F_work)
        F = F_work[:n_unknowns]
        res = big / s_scale if n_unknowns else 0.0
        if res <= tol and not changed:
            return p, s, it - 1, res, total_krylov

        def matvec(z):
            _scatter(z, order_i, order_j, kind_e, pos_e, gtx_e, gty_e, v)
            mv = kconv(v)
            out = np.empty(n_unknowns)
            _gather(mv, z, order_i, order_j, kind_e, pos_e, tx_e, ty_e, diag_e, out)
            return out

        def pinv(r):
            z = np.empty(n_unknowns)
            _precondition(up_e, kind_e, pos_e, tx_e, ty_e, g_e, diag_e, d0, dup, r, z, vx, vy)
            return z

        if precondition is None:
            prec = pinv
        else:
            kind = np.zeros(shape, dtype=np.int64)
            pos = np.zeros(shape, dtype=np.int64)
            kind[order_i, order_j] = kind_e
            pos[order_i, order_j] = pos_e
            prec = precondition(kind, pos, pinv, matvec, n_unknowns)
        rtol = gmres_rtol
        if forcing is not None:
            # adaptive forcing: loose while the active set moves, then just tight enough
            # to reach tol in one more step (floor: the single-precision products)
            loose, factor, floor = forcing
            rtol = loose if (changed or it == 1) else min(gmres_rtol,
                                                          max(factor * tol / res, floor))
        y, count = _gmres(lambda w: matvec(prec(w)), -F, rtol, gmres_maxiter)
        total_krylov += count
        dz = prec(y)
        # --- update
        _newton_update(p, dz, g_e, order_i, order_j, kind_e, pos_e, ex_e, ey_e)
    s = b + conv(p)
    return p, s, it, max(res, np.nextafter(tol, np.inf)), total_krylov


def newton_step(kernel, b, g, *, conv=None, initial=None, tol=1e-6, maxiter=100, upwind=True,
                krylov_conv=None):
    """One frictional step on a grid: the shared core of steady and transient rolling.

    Solves the discrete Coulomb problem ``s = b + K p`` with the traction bound
    ``g`` by the active-set semismooth Newton–GMRES method of the module
    docstring. Steady rolling (:func:`solve_rolling`) calls it once with the
    rolling kernel ``M``; the transient stepper
    (:func:`wheelrail.transient.transient_rolling`) calls it once per time step
    with ``K = C / (V Δt)`` and the displacement carried from the previous step
    in ``b`` (seed 001, eq. 2.19).

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
    Zhao, Vollebregt & Oosterlee (2015); seed 001 eqs. (2.19)–(2.20).
    """
    if conv is None:
        conv = _BlockConvolution(kernel)
    return _newton(kernel, conv, b, g, initial, tol, maxiter, upwind=upwind,
                   krylov_conv=krylov_conv)


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
    return TangentialSolution(
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


def solve_rolling(grid, pressure, materials, creepage, mu, *, tol=1e-6, maxiter=100,
                  initial=None, on_fail="raise", solver="newton",
                  nested=True) -> TangentialSolution:
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
    TangentialSolution
        ``sx, sy`` are dimensionless slip velocities; ``iterations`` counts
        Newton iterations, ``info["krylov_iterations"]`` the GMRES ones (on
        this grid); ``info["coarse"]`` lists the coarse levels (finest first)
        as dicts with ``shape``, ``newton`` and ``krylov`` iteration counts.

    Examples
    --------
    >>> import wheelrail as wr
    >>> from wheelrail.halfspace import solve_rolling
    >>> from wheelrail.normal.bem import hertz_grid, solve_normal
    >>> hc = wr.hertz(1e4, A=1.0, B=2.0, material=wr.STEEL)
    >>> grid, gap = hertz_grid(hc, elements=20, margin=1.1)
    >>> pn = solve_normal(grid, gap, wr.STEEL, load=1e4).pressure
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
                solver="newton") -> TangentialSolution:
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
    TangentialSolution
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
