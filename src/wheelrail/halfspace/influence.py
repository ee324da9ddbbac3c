"""Surface influence coefficients of two elastic half-spaces (pure functions).

Sign conventions (the single place where they are written down)
---------------------------------------------------------------
Axes are those of :mod:`wheelrail.conventions`: ``x`` rolling direction,
``y`` lateral, ``z`` normal pointing into the rail. Body 1 is the wheel
(occupying ``z < 0`` locally), body 2 the rail (``z > 0``). Components are
numbered ``0: x, 1: y, 2: n`` where the third ("normal", ``n``) component is
taken along ``n = −z`` (pointing into the wheel), so that both normal
quantities are positive in the physical sense:

* **Tractions** ``p = (px, py, pn)`` act **on the wheel** (Kalker); the rail
  carries ``−p``. ``px``, ``py`` [Pa] are the tangential tractions on the
  wheel along +x, +y; ``pn`` [Pa] is the normal **pressure, positive in
  compression** (the traction on the wheel along −z).
* **Displacements** ``u = u(wheel) − u(rail)`` (displacement difference),
  ``u_x``, ``u_y`` along +x, +y; ``u_n`` is the difference along ``n = −z``,
  i.e. the part of the elastic deformation that **opens the gap**; under
  pressure ``u_n > 0``.
* **Gap.** With ``h0(x, y) ≥ 0`` the undeformed separation of the surfaces and
  ``δ`` the approach (penetration) of the bodies, the deformed gap is::

      e(x, y) = h0(x, y) − δ + u_n(x, y)   with   u_n = Σ_J A_nn(x − x_J) pn_J

  and contact requires ``pn ≥ 0, e ≥ 0, pn·e = 0``.

With these signs the matrix of influence coefficients is symmetric
(reciprocity: ``pn`` is work-conjugate to ``u_n``), and its point-load form
(Kalker 1990 §1.6; Johnson 1985 §3.2, Boussinesq and Cerruti) for the combined bodies
at the surface offset ``(x, y)``, ``r = √(x² + y²)``, is::

              1   ⎡ (1−ν)/r + ν x²/r³     ν x y/r³          −K x/r² ⎤
    A(x,y) = ──── ⎢ ν x y/r³              (1−ν)/r + ν y²/r³ −K y/r² ⎥
              π G ⎣ +K x/r²               +K y/r²            (1−ν)/r ⎦

with ``G``, ``ν``, ``K`` the combined constants of :class:`~wheelrail.materials.MaterialPair`
(``K = 0`` for identical materials: no normal–tangential coupling).
``A[i, j]`` is the displacement difference ``u_i`` due to a unit point force
``j``. Integrating over a rectangle gives Love's (1929) closed forms used here
(Baeza et al., eqs. 2.14–2.18, gives the tangential ones for one body).

References
----------
.. [1] A.E.H. Love, The stress produced in a semi-infinite solid by pressure on
   part of the boundary, Phil. Trans. R. Soc. A 228 (1929) 377–420.
.. [2] K.L. Johnson, *Contact Mechanics*, CUP 1985, §3.2 (point loads) and
   §3.3 (uniform pressure on a rectangle).
.. [3] J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
   Kluwer 1990, §1.6 and §5.
.. [4] L. Baeza, F.J. Fuenmayor, J. Carballeira, A. Roda, Influence of the wheel–rail contact instationary process on contact parameters,
   eqs. (2.13)–(2.18).
"""

from __future__ import annotations

import numpy as np

from ..materials import as_material_pair

__all__ = [
    "COMPONENTS",
    "point_influence",
    "rectangle_influence",
    "influence_kernel",
    "kernel_offsets",
]

#: Names of the components (axis 0 and 1 of an influence kernel).
COMPONENTS = ("x", "y", "n")


# -- antiderivatives F(s, t) with ∂²F/∂s∂t = g(s, t) -------------------------
# Terms depending on s only or on t only are dropped: they cancel in the
# rectangle difference F(s2,t2) − F(s1,t2) − F(s2,t1) + F(s1,t1).

def _s_asinh_t_over_s(s, t):
    """s·asinh(t/|s|), → 0 for s → 0."""
    abs_s = np.abs(s)
    safe = np.where(abs_s > 0, abs_s, 1.0)
    return np.where(abs_s > 0, s * np.arcsinh(t / safe), 0.0)


def _s_atan_t_over_s(s, t):
    """s·atan(t/s), → 0 for s → 0."""
    safe = np.where(s != 0, s, 1.0)
    return np.where(s != 0, s * np.arctan(t / safe), 0.0)


def _t_log_r(s, t):
    """t·ln r, → 0 for r → 0."""
    r2 = s * s + t * t
    return np.where(r2 > 0, 0.5 * t * np.log(np.where(r2 > 0, r2, 1.0)), 0.0)


def _antiderivatives(s, t, coupling=True):
    """F for 1/r, s²/r³, t²/r³, st/r³, s/r², t/r² (in this order).

    Without ``coupling`` the last two (only needed for K ≠ 0) are zeros.
    """
    fa = _s_asinh_t_over_s(s, t)      # ∫∫ t²/r³
    fb = _s_asinh_t_over_s(t, s)      # ∫∫ s²/r³
    r = np.hypot(s, t)
    if coupling:
        fs = _s_atan_t_over_s(s, t) + _t_log_r(s, t)   # s/r²
        ft = _s_atan_t_over_s(t, s) + _t_log_r(t, s)   # t/r²
    else:
        fs = ft = np.zeros_like(r)
    return (fa + fb,                                   # 1/r
            fb,                                        # s²/r³
            fa,                                        # t²/r³
            -r,                                        # s t/r³
            fs, ft)


def _assemble(I, G, nu, K):
    """Influence matrix (3, 3, ...) from the six basic integrals."""
    i_r, i_ss, i_tt, i_st, i_s, i_t = I
    c = 1.0 / (np.pi * G)
    zero = np.zeros_like(i_r)
    out = np.empty((3, 3) + np.shape(i_r))
    out[0, 0] = c * ((1 - nu) * i_r + nu * i_ss)
    out[1, 1] = c * ((1 - nu) * i_r + nu * i_tt)
    out[0, 1] = out[1, 0] = c * nu * i_st
    out[2, 2] = c * (1 - nu) * i_r
    if K == 0.0:
        out[0, 2] = out[1, 2] = out[2, 0] = out[2, 1] = zero
    else:
        out[0, 2] = -c * K * i_s
        out[1, 2] = -c * K * i_t
        out[2, 0] = c * K * i_s
        out[2, 1] = c * K * i_t
    return out


def point_influence(x, y, G, nu, K=0.0):
    """Surface displacement difference due to unit point forces (Boussinesq–Cerruti).

    Parameters
    ----------
    x, y : array_like
        Offset of the observation point from the point of application [m],
        broadcast together, not both zero.
    G, nu, K : float
        Combined shear modulus [Pa], Poisson's ratio [-] and difference
        parameter [-] (:class:`~wheelrail.materials.MaterialPair`).

    Returns
    -------
    ndarray, shape (3, 3, *broadcast(x, y).shape)
        ``A[i, j]`` = displacement difference ``u_i`` [m] per unit force ``j``
        [N], components (x, y, n) as in the module docstring.
    """
    x, y = np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float))
    r = np.hypot(x, y)
    I = (1.0 / r, x * x / r**3, y * y / r**3, x * y / r**3, x / r**2, y / r**2)
    return _assemble(I, G, nu, K)


def rectangle_influence(x, y, hx, hy, G, nu, K=0.0):
    """Surface displacement difference due to unit uniform tractions on a rectangle.

    Love's (1929) closed forms: the point-load matrix of the module docstring
    integrated over the rectangle ``|ξ| ≤ hx, |η| ≤ hy``.

    Parameters
    ----------
    x, y : array_like
        Observation point relative to the rectangle centre [m] (broadcast).
    hx, hy : float
        Half-widths of the rectangle [m], > 0.
    G, nu, K : float
        Combined constants (see :func:`point_influence`).

    Returns
    -------
    ndarray, shape (3, 3, *broadcast(x, y).shape)
        ``A[i, j]`` = displacement difference ``u_i`` [m] per unit traction
        ``j`` [Pa]; finite everywhere including inside the loaded rectangle.

    Notes
    -----
    With s = x − ξ, t = y − η the basic integrals are
    ∫∫ 1/r = [s asinh(t/|s|) + t asinh(s/|t|)], ∫∫ s²/r³ = [t asinh(s/|t|)],
    ∫∫ s t/r³ = [−r], ∫∫ s/r² = [s atan(t/s) + t ln r], where [F] denotes
    F(x+hx, y+hy) − F(x−hx, y+hy) − F(x+hx, y−hy) + F(x−hx, y−hy); they are
    the L1, L2, L3 of Baeza et al. (eqs. 2.14–2.16) in asinh form.
    """
    x, y = np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float))
    s1, s2 = x - hx, x + hx
    t1, t2 = y - hy, y + hy
    F22, F12 = _antiderivatives(s2, t2), _antiderivatives(s1, t2)
    F21, F11 = _antiderivatives(s2, t1), _antiderivatives(s1, t1)
    I = tuple(a - b - c + d for a, b, c, d in zip(F22, F12, F21, F11))
    return _assemble(I, G, nu, K)


def kernel_offsets(grid):
    """Offsets of the kernel entries: arrays (2nx−1,), (2ny−1,) [m].

    Entry ``k`` along x is the offset ``(k − (nx − 1))·dx`` of the observation
    element from the loaded element.
    """
    ox = (np.arange(2 * grid.nx - 1) - (grid.nx - 1)) * grid.dx
    oy = (np.arange(2 * grid.ny - 1) - (grid.ny - 1)) * grid.dy
    return ox, oy


def influence_kernel(grid, materials) -> np.ndarray:
    """Influence kernel of a uniform grid for the combined bodies.

    Parameters
    ----------
    grid : Grid
        Element grid (``dx``, ``dy``, ``nx``, ``ny`` are used).
    materials : Material or MaterialPair
        Wheel and rail materials (combined ``G``, ``nu``, ``K``).

    Returns
    -------
    ndarray, shape (3, 3, 2nx−1, 2ny−1)
        ``kernel[i, j, kx, ky]`` = displacement difference ``u_i`` [m]
        (wheel minus rail; ``i = 2`` along ``n = −z``, gap-opening positive) at
        the centre of the element offset by ``((kx − (nx−1))·dx,
        (ky − (ny−1))·dy)`` from an element carrying the unit uniform traction
        ``j`` [Pa] (``j = 2``: pressure, positive in compression, acting on the
        wheel). The displacement field of tractions ``p[j]`` (nx, ny) is::

            u[i][a, b] = Σ_j Σ_{c,d} kernel[i, j, a − c + nx − 1, b − d + ny − 1] · p[j][c, d]

        Symmetries: ``kernel[i, j, k] = kernel[j, i, −k]`` (reciprocity), the
        diagonal blocks are even in both offsets, ``[0, 1]`` is odd in both,
        ``[0, 2]``, ``[2, 0]`` odd in x (zero when ``K = 0``).

    References
    ----------
    Love (1929); Kalker (1990) §5; Baeza et al. eqs. (2.13)–(2.18).
    """
    pair = as_material_pair(materials)
    # the antiderivatives are evaluated once on the lattice of element edges
    # (2nx × 2ny points, each shared by four offsets), then differenced
    ex = (np.arange(2 * grid.nx) - grid.nx + 0.5) * grid.dx
    ey = (np.arange(2 * grid.ny) - grid.ny + 0.5) * grid.dy
    S, T = np.meshgrid(ex, ey, indexing="ij")
    F = _antiderivatives(S, T, coupling=pair.K != 0.0)
    I = tuple(f[1:, 1:] - f[:-1, 1:] - f[1:, :-1] + f[:-1, :-1] for f in F)
    return _assemble(I, pair.G, pair.nu, pair.K)
