"""The collocation schemes of one transient time step and their influence kernels.

Where the two displacements of the slip relation of an element are taken
(:func:`step_points`) and the influence kernels of one step built from them
(:func:`step_kernels`); re-exported by :mod:`wheelrail.transient.rolling`,
whose module text describes the schemes.

References
----------
.. [1] L. Baeza, F.J. Fuenmayor, J. Carballeira, A. Roda, Influence of the
   wheel–rail contact instationary process on contact parameters (Baeza et al.),
   eqs. (2.8)–(2.13).
.. [2] J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
   Kluwer 1990, §5.2.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import InputError
from ..halfspace.influence import influence_kernel, kernel_offsets, rectangle_influence
from ..materials import as_material_pair
from ._fft import FastBlockConvolution as _BlockConvolution

__all__ = ["SCHEMES", "shifted_influence_kernel", "step_kernels", "step_points",
           "step_weights", "transport_weights"]


def shifted_influence_kernel(grid, materials, shift) -> np.ndarray:
    """Influence kernel at offsets shifted by ``shift`` along x, shape (3, 3, 2nx−1, 2ny−1).

    ``K[:, :, kx, ky]`` is the displacement difference [m/Pa] at
    ``((kx − nx + 1) dx + shift, (ky − ny + 1) dy)`` from an element carrying a
    unit traction: the displacement of the previous step seen by the particle
    now at element I (Baeza et al. eq. 2.10, ``u_o``).
    """
    pair = as_material_pair(materials)
    ox, oy = kernel_offsets(grid)
    X, Y = np.meshgrid(ox + shift, oy, indexing="ij")
    return rectangle_influence(X, Y, grid.dx / 2, grid.dy / 2, pair.G, pair.nu, pair.K)


def step_weights(dx, step):
    """Collocation offsets [m] and weights of the element-averaged slip (``scheme="averaged"``).

    With ``m = dx / step`` the slip of element I is the weighted mean of the
    slip at the points ``x_I + k·step``, ``k = 0 … ⌈m⌉ − 1``, weights ``1/m``
    except the last, ``(m − ⌈m⌉ + 1)/m`` (they sum to one). Held steady, the
    displacement differences telescope to ``(u(x_I) − ũ(x_I + dx)) / dx``
    with ``ũ`` the linear interpolation of ``u`` between the two last points:
    Kalker's steady discretisation, exactly when ``m`` is an integer. With
    ``step ≥ dx`` a single point (the element centre).

    Returns
    -------
    offsets, weights : ndarray, shape (K,)
    """
    m = dx / step
    K = max(1, int(math.ceil(m - 1e-9)))
    if K == 1:
        return np.zeros(1), np.ones(1)
    w = np.full(K, 1.0 / m)
    w[-1] = (m - (K - 1)) / m
    return np.arange(K) * step, w


SCHEMES = ("transport", "interpolated", "upwind2", "averaged", "centre")


def transport_weights(f):
    """Weights of the cubic Lagrange interpolation at ``x_0 + f dx`` (``0 ≤ f < 1``) from the
    four centres ``x_0 − dx, x_0, x_0 + dx, x_0 + 2 dx`` (they sum to one; ``f = 0``
    gives ``(0, 1, 0, 0)``): the interpolation of the semi-Lagrangian step
    (``scheme="transport"``), exact for cubic fields.

    Returns
    -------
    ndarray, shape (4,)
    """
    return np.array([-f * (f - 1.0) * (f - 2.0) / 6.0, (f + 1.0) * (f - 1.0) * (f - 2.0) / 2.0,
                     -(f + 1.0) * f * (f - 2.0) / 2.0, (f + 1.0) * f * (f - 1.0) / 6.0])


def step_points(dx, step, scheme="transport"):
    """Where the two displacements of the slip relation of one element are taken.

    The slip of element I is ``Σ_k a_k u(x_I + s_k, t) − Σ_k b_k u(x_I + r_k, t − Δt)``
    over ``h``; this returns ``(s, a, r, b)`` (offsets [m] and weights).

    * ``"transport"`` (default): the semi-Lagrangian step. The current displacement
      at the centre, the previous one at the departure point ``x_I + h`` of the
      particle, interpolated by the cubic through the four element centres around
      it (:func:`transport_weights`; ``h = (n + f) dx``: the centres
      ``x_I + (n − 1 … n + 2) dx``). The slip relation is the exact difference
      along the particle path; in adhesion the displacement field is carried
      with an interpolation error O(dx⁴) per step instead of linear
      interpolation's O(dx² f (1 − f)), so the carried field is not diffused at
      steps shorter than an element. ``h = dx`` (whole elements) is the exact
      shift, Kalker's (and CONTACT's) scheme; held steady it ends on
      ``(C − Σ w_k C_{(n−1+k) dx})/h``, which tends to Kalker's kernel as
      ``h → dx`` and to the derivative of the cubic as ``h → 0``.
    * ``"interpolated"``: the current displacement at the centre, the
      previous one at ``x_I + h`` linearly interpolated between the element
      centres ``x_I + n dx`` and ``x_I + (n + 1) dx`` (``h = (n + f) dx``),
      as Vollebregt's CONTACT shifts the previous displacement field by a step
      that is not a whole number of elements (open-source CONTACT, shift of
      the grid functions by the rolled distance ``DQ``). Held steady the carried terms give ``(u(x_I) − u(x_I + dx))/dx``:
      Kalker's steady discretisation for any step ``h ≤ dx``; in adhesion the traction is
      carried by first-order upwind interpolation (Courant number ``h/dx``),
      which never amplifies a traction pattern.
    * ``"upwind2"``: second order in ``dx``. The slip over V is
      ``w − ∂u/∂x + ∂u/∂t / V`` in the frame of the contact; the convective
      derivative is taken at the new time by the second-order upwind difference
      ``−∂u/∂x ≈ (3 u(x_I) − 4 u(x_I + dx) + u(x_I + 2 dx)) / (2 dx)`` and the
      time derivative by ``(u(x_I, t) − u(x_I, t − Δt)) / h``, so the current
      displacement is taken at ``x_I, x_I + dx, x_I + 2 dx`` with weights
      ``1 + 3f/2, −2f, f/2`` (``f = h/dx``) and the previous one at the centre.
      Held steady ``(now − old)/h`` is the second-order upwind rolling kernel
      ``(3 C − 4 C_dx + C_2dx)/(2 dx)`` for any ``h``; the stepping is
      implicit (backward Euler in the frame of the contact), which is
      unconditionally stable for the linear transport in adhesion.
    * ``"averaged"``: the slip averaged over the points of :func:`step_weights`.
    * ``"centre"``: Baeza et al.'s eq. (2.10) at the centre, the previous
      displacement exactly at ``x_I + h``.
    """
    if scheme == "centre":
        return np.zeros(1), np.ones(1), np.array([step]), np.ones(1)
    if scheme == "averaged":
        off, w = step_weights(dx, step)
        return off, w, off + step, w
    if scheme == "upwind2":
        f = step / dx
        return (np.array([0.0, dx, 2 * dx]), np.array([1.0 + 1.5 * f, -2.0 * f, 0.5 * f]),
                np.zeros(1), np.ones(1))
    if scheme == "transport":
        n, f = _whole_and_fraction(step, dx)
        if f == 0.0:
            return np.zeros(1), np.ones(1), np.array([n * dx]), np.ones(1)
        return np.zeros(1), np.ones(1), (n + np.arange(-1, 3)) * dx, transport_weights(f)
    if scheme == "interpolated":
        ratio = step / dx
        n = int(math.floor(ratio + 1e-9))
        f = ratio - n
        if f <= 1e-9:
            return np.zeros(1), np.ones(1), np.array([n * dx]), np.ones(1)
        return (np.zeros(1), np.ones(1), np.array([n * dx, (n + 1) * dx]),
                np.array([1.0 - f, f]))
    raise InputError(f"scheme must be one of {SCHEMES}, got {scheme!r}")


def step_kernels(grid, materials, step, scheme="transport"):
    """Influence kernels of one time step, each of shape (3, 3, 2nx−1, 2ny−1) [m/Pa].

    ``(now, old)``: the displacement difference at the collocation points of
    element I due to a unit traction on element J now (``now``) and, carried
    one step ``h = step`` upstream, at the previous step (``old``)::

        s_I = w_I + Σ_J (now(I − J) p_J − old(I − J) p_old,J) / h

    The points and weights of each scheme are those of :func:`step_points`;
    every kernel is evaluated exactly with Love's rectangle formulae at them.

    ``scheme="interpolated"`` (default): ``now = C``, ``old`` = ``C`` at the
    offsets shifted by ``n dx`` and ``(n + 1) dx`` weighted ``1 − f`` and
    ``f`` (``h = (n + f) dx``): held steady ``(now − old)/h`` is Kalker's
    rolling kernel ``(C − C_dx)/dx`` for any ``h ≤ dx``, and the first step from
    rest is the Cattaneo shift problem.

    ``scheme="upwind2"``: ``now = C + h (3 C − 4 C_dx + C_2dx)/(2 dx)``,
    ``old = C``: held steady ``(now − old)/h`` is the second-order upwind
    rolling kernel for any ``h`` (grid error of Baeza et al. §3.1 in ξ:
    0.03 % on 30 elements where Kalker's first-order kernel leaves 2.5 %).

    ``scheme="centre"``: Baeza et al.'s eq. (2.10) at the element centres,
    ``old = C`` at offsets shifted by ``h`` (:func:`shifted_influence_kernel`).
    Held steady it becomes the steady problem with kernel ``(C − C_h)/h →
    −∂C/∂x`` at the centres, whose self-coefficient vanishes as ``h/dx → 0``:
    a centred difference without diagonal dominance (the Newton iteration
    stops converging for ``dx/h ≳ 4`` on 30 elements) that ends off
    Kalker's steady solution (−1.9 % in ξ at 30 elements, V·Δt = 0.05 mm).

    ``scheme="averaged"``: the slip averaged over the points ``x_I + k h`` of
    :func:`step_weights`. Held steady it ends on Kalker's discretisation
    exactly for integer ``dx/h``, but at a non-integer ratio its collocation
    points straddle the element boundary and the transient shows a false slip
    phase (Baeza et al. §3.1 on 60 elements, ``dx/h = 1.84``: 38 % of the
    contact slipping after 17 steps against 23 % with ``"interpolated"``, a
    non-monotone ξ history).
    """
    now_s, now_w, old_s, old_w = step_points(grid.dx, step, scheme)
    if scheme == "centre" or (len(now_s) == 1 and now_s[0] == 0.0):
        now = influence_kernel(grid, materials)
    else:
        now = sum(w * shifted_influence_kernel(grid, materials, s) for s, w in zip(now_s, now_w))
    if len(old_s) == 1 and old_s[0] == 0.0:
        old = influence_kernel(grid, materials) * old_w[0]
    else:
        old = sum(w * shifted_influence_kernel(grid, materials, s)
                  for s, w in zip(old_s, old_w))
    return now, old


def _whole_and_fraction(step, dx):
    """``(n, f)`` with ``step = (n + f) dx``, ``0 ≤ f < 1`` (f = 0 within 1e-9)."""
    ratio = step / dx
    n = int(math.floor(ratio + 1e-9))
    f = ratio - n
    return n, (0.0 if f <= 1e-9 else f)


def _steady_step_operator(grid, pair, step, scheme):
    """``(M, conv_M, conv_Mn)``: the kernel ``(now − old)/h`` of a step held steady.

    The fixed point of a time step under constant loads solves ``s = w + M (p, pn)``;
    with ``scheme="interpolated"`` ``M`` is Kalker's rolling kernel ``(C − C_dx)/dx``
    (:func:`step_kernels`).
    """
    now, old = step_kernels(grid, pair, step, scheme)
    M = (now - old) / step
    Mt = np.ascontiguousarray(M[:2, :2])
    return Mt, _BlockConvolution(Mt), (_BlockConvolution(M[:2, 2:3]) if pair.K else None)
