"""Table-interpolating creep-force law built from Kalker's exact theory ("book of tables").

Vehicle-dynamics codes do not call an exact contact solver at every time step:
they interpolate a table of exact results computed once (with the package's
own exact solver, :mod:`wheelrail.tangential.exact`, by
:mod:`wheelrail.sweeps.tables`). This law interpolates it, vectorised.

Similarity (what the table is a function of)
--------------------------------------------
For quasi-identical bodies (difference parameter K = 0) on an elliptic Hertz
contact, the steady-rolling problem scaled by the traction bound μp₀, the
semi-axes and G depends only on the axis ratio a/b, Poisson's ratio ν and the
creepages scaled by μp₀/G (Kalker 1990, §2.x; Kalker's "book of tables").
The table therefore stores

    fx = Fx/(μFn),  fy = Fy/(μFn),  mz = Mz/(μFn c),   c = √(ab),

as functions of five dimensionless inputs:

* the creepages in units of the linear theory's saturation (Kalker's C11, C22,
  C23 of :func:`~wheelrail.tangential.linear.kalker_coefficients`):
  ξ̂ = G c² C11 ξ/(3μFn), η̂ = G c² C22 η/(3μFn), and the spin's lateral effect
  φ̂_y = G c³ C23 φ/(3μFn) (linear theory: Fy ∝ η̂ + φ̂_y);
* spin: φ̂ = G c² ℓ φ/(3μFn) with ℓ = √((c C23)² + (b C11)²) (b C11 measures the
  longitudinal slip −φy across the half-width b, which saturates Fx of patches wide in y);
  axis s = φ̂/(1 + |φ̂|) ∈ [−1, 1]: *every* spin is inside, s = ±1 being full
  sliding under the rigid slip of infinite spin (:func:`full_slip`);
* ρ̂ = |(ξ̂, η̂ + φ̂_y)| and its direction θ ∈ [0, π/2]; axis r = ρ̂/(1 + |φ̂| + ρ̂)
  ∈ [0, 1], r = 1 being the full-slip limit (F = −μFn along the creepage, Mz = 0),
  so *every* creepage magnitude is inside;
* a/b ∈ [0.05, 20] (log axis; flange contacts give such patches) and ν ∈ [0.25, 0.30].

The symmetries of the problem, F(−ξ, η, φ) = (−Fx, Fy, Mz) and
F(ξ, −η, −φ) = (Fx, −Fy, −Mz), reduce the creepage directions to the quadrant
ξ, η ≥ 0 (θ ∈ [0, π/2]); both follow from the oddness of the traction problem
in the creepages and its mirror symmetry in y, and are checked against the
exact solver in ``tests/reference/test_table_law.py``.

Interpolation is a tensor product of interpolating cubic B-splines in
(r, θ, s, ln a/b) and linear in ν (a compiled kernel,
:mod:`wheelrail.tangential._table_kernel`), for the tangential force in the
frame of the full-slip direction (components along and across it), so that
|F| = μFn is kept in full slip; |F| ≤ μFn is enforced (the cubic may
overshoot the bound by a little). The spline coefficients are computed once
when the table is loaded, with not-a-knot ends (de Boor 2001) on every cubic
axis, r = 0 included (an odd extension through r = 0 was tried and not kept:
F is odd in the creepages but not smooth through 0, and the table's slope
there, Kalker's C11, came out 1.4 % low with it). A global spline rather than
local (Catmull–Rom) cubics: on the 60 benchmark points its largest error is
about a fifth smaller (benchmarks/bench_contact_table_law.py).

Accuracy
--------
See ``benchmarks/bench_contact_table_law.py`` and docs/sweeps.md: random points
over the whole domain (:func:`random_cases`: a/b 0.05–20, |φ̂| up to 19) against
the exact theory's grid limit (least-squares f∞ + C/N to 36–122 elements,
uncertainty ≤ 0.28 % of μFn). The shipped table (21 × 9 × 41 × 17 × 2 nodes,
the grid limit fitted to 16/24/36 elements on every node, 36/54/81 on the
smallest creepages and in the refined regions of
:func:`wheelrail.sweeps.tables.refine_table`): on 200 points max |ΔF_t| = 0.59 %
of μFn, rms 0.12 %, max |ΔMz| = 0.82 % of μFn c; on 100 independent points
(seed 7) max 0.34 %, rms 0.10 % (the exact solver itself with 122 elements: max
1.29 % and 0.76 %); on the validation row's two Latin hypercubes of 80 points
(moderate creepage with spin on slender patches as likely as anywhere) max
0.69 % and 0.39 %.

Speed: one call of :meth:`Table.solve` takes about 0.035 ms on an idle core (the
exact solver with 40 elements: 15–19 ms), see the benchmark.

Outside the domain (a/b outside [0.05, 20], ν outside [0.25, 0.30], or
dissimilar materials K ≠ 0) the law raises :class:`~wheelrail.errors.InputError`
naming the value, unless ``outside="exact"`` or ``outside="fastsim"``: then
those points are computed by that method (documented fallback).

Building the table
------------------
``wheelrail build-table --workers 2`` (:func:`wheelrail.sweeps.tables.build_table`)
recomputes the shipped file ``_data/creep_table_v2.npz`` with resumable
:func:`wheelrail.sweep` runs (Zarr work stores, kept until the file is
written). This module only reads and interpolates tables.

References
----------
.. [1] J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
   Kluwer 1990, ch. 2 (similarity) and ch. 5 (exact theory, CONTACT).
.. [2] J.J. Kalker, Book of tables for the Hertzian creep-force law, in:
   I. Zobory (ed.), Proc. 2nd Mini Conf. on Contact Mechanics and Wear of
   Wheel/Rail Systems, Budapest, 1996, 11-20.
.. [3] C. de Boor, *A Practical Guide to Splines*, revised ed., Springer 2001,
   ch. IX (B-splines) and ch. XII (the not-a-knot end condition).
"""

from __future__ import annotations

import json
import math
from functools import lru_cache
from pathlib import Path
from typing import NamedTuple

import numpy as np

from ..errors import InputError
from ..hertzian import hertz_from_semiaxes
from ..materials import Material
from ..options import configured, option
from ..plausibility import check_friction
from ..results import CreepForcesResult, Status
from ._base import TangentialMethod, get
from ._table_kernel import evaluate
from .linear import kalker_coefficients

__all__ = [
    "AXES",
    "DEFAULT_TABLE",
    "TABLE_VERSION",
    "Table",
    "TableData",
    "full_slip",
    "load_table",
    "random_cases",
    "table_coordinates",
]

#: The shipped table.
DEFAULT_TABLE = Path(__file__).with_name("_data") / "creep_table_v2.npz"
TABLE_VERSION = 2

#: The table's axes: r = ρ̂/(1 + |φ̂| + ρ̂) (r = 1 analytic), θ, s = φ̂/(1 + |φ̂|), ln(a/b), ν.
AXES = ("r", "theta", "s", "log_ab", "nu")
_K_TOL = 1e-3  # |K| below which the bodies count as quasi-identical

def _coefficients(ab, nu):
    C11, C22, C23, _ = kalker_coefficients(ab, nu)
    return C11, C22, C23


def _spin_length(c, b, C11, C23):
    """Length scaling the spin: √((c C23)² + (b C11)²) [m].

    c C23 measures the lateral force of spin (linear theory, Fy = −G c³ C23 φ); b C11 the
    longitudinal slip −φ y it causes across the half-width b, which saturates Fx of patches
    wide in y (a/b < 1) at small spin. With both, the spin axis resolves all a/b alike.
    """
    return np.hypot(c * C23, b * C11)


def full_slip(a, b, xi, eta, phi, n_radial=96, n_angle=192):
    """Creep forces in full sliding on a Hertz ellipse (the table's analytic planes).

    Every element slides against its rigid slip w = (ξ − φy, η + φx) (the elastic
    part of the slip is negligible when the creepages are large):
    τ = −μ p w/|w| with Hertz's pressure p = p₀√(1 − x²/a² − y²/b²).

    Parameters
    ----------
    a, b : ndarray, shape (n,)
        Semi-axes [m].
    xi, eta, phi : ndarray, shape (n,)
        Creepages [-, -, 1/m] (only their direction matters).
    n_radial, n_angle : int
        Gauss–Legendre points in ρ = sin u, u ∈ [0, π/2], and midpoints in the angle.

    Returns
    -------
    fx, fy, mz : ndarray, shape (n,)
        Fx/(μFn), Fy/(μFn), Mz/(μFn c), c = √(ab).

    References
    ----------
    .. [1] J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
       Kluwer 1990, §1.3 (full sliding: traction opposite to the rigid slip).
    """
    a, b, xi, eta, phi = np.broadcast_arrays(*(np.asarray(v, float).reshape(-1)
                                               for v in (a, b, xi, eta, phi)))
    u, wu = np.polynomial.legendre.leggauss(n_radial)
    u = 0.25 * np.pi * (u + 1.0)
    wu = 0.25 * np.pi * wu
    rho = np.sin(u)
    w_r = wu * np.cos(u) ** 2 * rho  # sqrt(1 - rho^2) rho d rho = cos u sin u cos u du
    t = (np.arange(n_angle) + 0.5) * (2.0 * np.pi / n_angle)
    X = (rho[:, None] * np.cos(t)[None, :]).reshape(-1)
    Y = (rho[:, None] * np.sin(t)[None, :]).reshape(-1)
    W = (w_r[:, None] * np.full(n_angle, 2.0 * np.pi / n_angle)[None, :]).reshape(-1)
    W = W * 3.0 / (2.0 * np.pi)  # p dA / Fn on the unit disc
    out = np.empty((a.size, 3))
    for i0 in range(0, a.size, 256):
        sl = slice(i0, i0 + 256)
        x = a[sl, None] * X[None, :]
        y = b[sl, None] * Y[None, :]
        wx = xi[sl, None] - phi[sl, None] * y
        wy = eta[sl, None] + phi[sl, None] * x
        norm = np.hypot(wx, wy)
        norm = np.where(norm > 0.0, norm, np.inf)
        tx, ty = -wx / norm, -wy / norm
        c = np.sqrt(a[sl] * b[sl])
        out[sl, 0] = tx @ W
        out[sl, 1] = ty @ W
        out[sl, 2] = ((x * ty - y * tx) @ W) / c
    return out[:, 0], out[:, 1], out[:, 2]


#: Axes interpolated with cubic B-splines (the others linearly): r, θ, s, ln a/b; ν linear.
CUBIC = (True, True, True, True, False)


def _ghosts(v, axis):
    """Pad ``v`` by one node at each end of ``axis`` (linear extrapolation; the kernel
    gives these nodes weight 0 on a linear axis)."""
    v = np.moveaxis(v, axis, 0)
    lo = 2.0 * v[0] - v[1]
    hi = 2.0 * v[-1] - v[-2]
    return np.moveaxis(np.concatenate([lo[None], v, hi[None]]), 0, axis)


def _spline_operator(n):
    """(n + 2, n) matrix from node values to the coefficients c₋₁ … c_n of the
    interpolating uniform cubic B-spline with not-a-knot ends (de Boor 2001, ch. XII):
    (c_{i−1} + 4 c_i + c_{i+1}) / 6 = f_i, and no jump of the third derivative at the
    second and the last-but-one node (Δ⁴c = 0 there). Axes of 2 or 3 nodes (small test
    tables) get natural ends (no curvature at the end nodes: Δ²c = 0)."""
    if n < 2:
        raise InputError(f"a creep-table axis needs >= 2 nodes, got {n}")
    A = np.zeros((n + 2, n + 2))
    for i in range(n):
        A[i, i:i + 3] = (1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0)
    if n >= 4:
        A[n, 0:5] = (1.0, -4.0, 6.0, -4.0, 1.0)
        A[n + 1, n - 3:n + 2] = (1.0, -4.0, 6.0, -4.0, 1.0)
    else:
        A[n, 0:3] = (1.0, -2.0, 1.0)
        A[n + 1, n - 1:n + 2] = (1.0, -2.0, 1.0)
    return np.linalg.solve(A, np.eye(n + 2)[:, :n])


def _spline_coefficients(v, axis):
    """B-spline coefficients of ``v`` along ``axis`` (:func:`_spline_operator`)."""
    c = np.tensordot(_spline_operator(v.shape[axis]), np.moveaxis(v, axis, 0), axes=(1, 0))
    return np.moveaxis(c, 0, axis)


class TableData:
    """A loaded table: node axes, values and metadata (see :func:`load_table`).

    ``kernel`` holds the arrays of the compiled evaluation
    (:func:`wheelrail.tangential._table_kernel.point_forces`): the cubic
    B-spline coefficients of the values in the frame of the full-slip direction
    (one extra coefficient at each end of every cubic axis), the axes'
    first node, spacing and count, the cubic flags and a (ln a/b, ν) lookup of
    Kalker's C11, C22, C23. ``_interp`` is the multilinear interpolant of the
    same frame values on the nodes (``_interp.values``: shape (n_r, n_θ, n_s,
    n_ab, n_ν, 3)).
    """

    def __init__(self, axes: dict, values: np.ndarray, meta: dict):
        from scipy.interpolate import RegularGridInterpolator

        # Symmetry planes hold the exact solver's round-off (up to ~1e-7 mu Fn), not zero: Fx
        # is odd in xi (zero where xi_hat = 0: theta = pi/2 or r = 0), (Fy, Mz) odd in
        # (eta, phi) (zero where theta = 0 and s = 0). Left in, the interpolant is not odd and
        # jumps at xi = 0 (the reflection sx flips the round-off); set to the exact zero.
        values = np.array(values, dtype=float, copy=True)
        fx, fyz = values[..., 0], values[..., 1:]
        fx[:, np.isclose(axes["theta"], 0.5 * np.pi, rtol=0.0, atol=1e-12)] = 0.0
        fx[axes["r"] == 0.0] = 0.0
        t0, s0 = np.flatnonzero(axes["theta"] == 0.0), np.flatnonzero(axes["s"] == 0.0)
        fyz[:, t0[:, None], s0[None, :]] = 0.0
        self.axes = axes
        self.values = values
        self.meta = meta
        # The tangential force is interpolated in the frame of the creepage direction alpha
        # (components along and across it): full slip then stays at |F| = mu Fn between the
        # direction nodes instead of cutting the chord (a 0.3 % deficit at 9 degrees).
        T, L, N = np.meshgrid(axes["theta"], axes["log_ab"], axes["nu"], indexing="ij")
        C11, C22, _ = _coefficients(np.exp(L), N)
        alpha = np.arctan2(np.sin(T) / C22, np.cos(T) / C11)[None, :, None]  # (1, θ, 1, ab, ν)
        ca, sa = np.cos(alpha), np.sin(alpha)
        v = values
        local = np.stack([v[..., 0] * ca + v[..., 1] * sa, -v[..., 0] * sa + v[..., 1] * ca,
                          v[..., 2]], axis=-1)
        self._interp = RegularGridInterpolator(tuple(axes[k] for k in AXES), local,
                                               method="linear", bounds_error=False,
                                               fill_value=None)
        self.kernel = self._kernel_arrays(axes, local)

    @staticmethod
    def _kernel_arrays(axes, local):
        x0, dx, n = [], [], []
        for k in AXES:
            ax = np.asarray(axes[k], float)
            step = np.diff(ax)
            if ax.size < 2 or not np.allclose(step, step[0], rtol=1e-9, atol=1e-12):
                raise InputError(f"creep table axis {k!r} must be uniform with >= 2 nodes")
            x0.append(ax[0])
            dx.append(step[0])
            n.append(ax.size)
        padded = local
        for d in range(5):
            padded = _spline_coefficients(padded, d) if CUBIC[d] else _ghosts(padded, d)
        ab_lo, ab_hi = axes["log_ab"][0], axes["log_ab"][-1]
        nu_lo, nu_hi = axes["nu"][0], axes["nu"][-1]
        lab = np.linspace(ab_lo, ab_hi, 801)
        nus = np.linspace(nu_lo, nu_hi, 6) if nu_hi > nu_lo else np.array([nu_lo, nu_lo + 1e-9])
        Lg, Ng = np.meshgrid(lab, nus, indexing="ij")
        coef = np.stack(_coefficients(np.exp(Lg), Ng), axis=-1)
        c_x0 = np.array([lab[0], nus[0]])
        c_dx = np.array([lab[1] - lab[0], nus[1] - nus[0]])
        c_n = np.array([lab.size, nus.size], np.int64)
        return (np.ascontiguousarray(padded), np.array(x0), np.array(dx),
                np.array(n, np.int64), np.array(CUBIC, np.bool_), c_x0, c_dx, c_n,
                np.ascontiguousarray(coef))

    def kernel_at(self, nu):
        """``kernel`` for one Poisson's ratio ``nu`` (a material fixed over many calls).

        The ν axis (linear) is collapsed to the interpolated plane, stored at ν = ``nu``
        with spacing 1 so that the kernel's ν weights are (1, 0): one plane of
        coefficients is read instead of two, from an array half as large, the same forces
        to round-off. A ``nu``
        outside the table returns the full ``kernel`` (whose flags then say so).
        """
        values, x0, dx, n, cubic, c_x0, c_dx, c_n, coef = self.kernel
        lo = x0[4]
        hi = x0[4] + (n[4] - 1) * dx[4]
        if not (lo - 1e-12 <= nu <= hi + 1e-12) or n[4] < 2:
            return self.kernel
        u = min(max((nu - lo) / dx[4], 0.0), n[4] - 1.0)
        i = min(int(u), int(n[4]) - 2)
        t = u - i
        # padded ν axis: ghost, nodes 0 … n−1, ghost (node k at index k + 1)
        plane = (1.0 - t) * values[:, :, :, :, i + 1] + t * values[:, :, :, :, i + 2]
        # the kernel reads index 1 of the ν axis only (weights 0, 1, 0, 0): two slots, the
        # plane in both, so the a/b neighbours lie 6 values apart instead of 12
        one = np.ascontiguousarray(np.repeat(plane[:, :, :, :, None], 2, axis=4))
        x0n, dxn, nn = x0.copy(), dx.copy(), n.copy()
        x0n[4], dxn[4], nn[4] = float(nu), 1.0, 2
        return (one, x0n, dxn, nn, cubic, c_x0, c_dx, c_n, coef)

    @property
    def domain(self) -> dict:
        """Ranges of the inputs: ``phi_hat`` (|φ̂| max, ``inf`` when s = ±1 is tabulated),
        ``aspect`` (a/b), ``nu``."""
        smax = float(np.max(np.abs(self.axes["s"])))
        return {"phi_hat": np.inf if smax >= 1.0 else smax / (1.0 - smax),
                "aspect": (float(np.exp(self.axes["log_ab"][0])),
                           float(np.exp(self.axes["log_ab"][-1]))),
                "nu": (float(self.axes["nu"][0]), float(self.axes["nu"][-1]))}

    def forces(self, a, b, G, nu, xi, eta, phi, mu, Fn):
        """Creep forces (compiled; arrays of shape (m,)): ``(out (m, 3), flags (m,))``.

        ``out`` holds Fx, Fy [N], Mz [N m]; ``flags`` bit 1: |φ̂| outside, 2: a/b outside,
        4: ν outside the table (forces of the clipped coordinates there).
        """
        m = a.shape[0]
        out = np.empty((m, 3))
        flags = np.empty(m, np.int8)
        evaluate(a, b, G, nu, xi, eta, phi, mu, Fn, *self.kernel, out, flags)
        return out, flags

    def __call__(self, points: np.ndarray, alpha: np.ndarray) -> np.ndarray:
        """Multilinear (fx, fy, mz) at table coordinates, shape (n, 3) (nodes' reference).

        ``points`` (n, 5) are table coordinates, ``alpha`` (n,) the direction [rad] of the
        scaled creepage (ξ̂/C11, (η̂ + φ̂)/C22) of each point (see :func:`table_coordinates`).
        """
        f = self._interp(points)
        ca, sa = np.cos(alpha), np.sin(alpha)
        return np.stack([f[:, 0] * ca - f[:, 1] * sa, f[:, 0] * sa + f[:, 1] * ca, f[:, 2]],
                        axis=-1)


@lru_cache(maxsize=4)
def load_table(path=None) -> TableData:
    """Load a table file (default: the shipped one); cached."""
    path = DEFAULT_TABLE if path is None else Path(path)
    if not path.exists():
        raise InputError(f"creep table {str(path)!r} not found; build it with "
                         "'wheelrail build-table'")
    with np.load(path, allow_pickle=False) as f:
        axes = {k: np.asarray(f[k], float) for k in AXES}
        values = np.asarray(f["values"])
        meta = json.loads(str(f["meta"]))
    if meta.get("version") != TABLE_VERSION:
        raise InputError(f"creep table {str(path)!r} has version {meta.get('version')!r}, "
                         f"this wheelrail reads version {TABLE_VERSION}")
    return TableData(axes, values, meta)


def table_coordinates(a, b, G, nu, xi, eta, phi, mu, Fn):
    """Table coordinates of contacts and creepages (pure array function).

    Parameters
    ----------
    a, b : ndarray, shape (n,)
        Semi-axes [m].
    G, nu : float or ndarray
        Combined shear modulus [Pa] and Poisson's ratio [-].
    xi, eta, phi, mu, Fn : ndarray, shape (n,)
        Creepages [-, -, 1/m], friction [-], normal force [N].

    Returns
    -------
    coords : ndarray, shape (n, 5)
        (r, θ, s, ln a/b, ν) after reflection into ξ, η ≥ 0.
    sx, sy : ndarray, shape (n,)
        Signs (±1) of ξ and η used to reflect the results back.
    phi_hat : ndarray, shape (n,)
        Scaled spin (signed, after reflection).
    alpha : ndarray, shape (n,)
        Direction [rad] of the full-slip force: of (ξ̂/C11, (η̂ + φ̂)/C22).
    """
    ab = a / b
    nu = np.broadcast_to(np.asarray(nu, float), ab.shape)
    C11, C22, C23 = _coefficients(ab, nu)
    c2 = a * b
    unit = G / (3.0 * mu * Fn)
    c = np.sqrt(c2)
    spin_len = _spin_length(c, b, C11, C23)
    xh = unit * c2 * C11 * xi
    ph = unit * c2 * spin_len * phi
    eh = unit * c2 * C22 * eta + unit * c2 * c * C23 * phi   # effective lateral η̂ + φ̂_y
    sx = np.where(xh < 0, -1.0, 1.0)
    sy = np.where(eh < 0, -1.0, 1.0)
    xh, eh, ph = np.abs(xh), np.abs(eh), ph * sy
    rho = np.hypot(xh, eh)
    theta = np.arctan2(eh, xh)
    coords = np.stack([rho / (1.0 + np.abs(ph) + rho), theta, ph / (1.0 + np.abs(ph)),
                       np.log(ab), nu], axis=-1)
    alpha = np.arctan2(np.sin(theta) / C22, np.cos(theta) / C11)
    return coords, sx, sy, ph, alpha


class TableCase(NamedTuple):
    """One random contact of :func:`random_cases`."""

    contact: object        #: :class:`~wheelrail.hertzian.HertzContact`
    creepage: tuple        #: (ξ, η, φ) [-, -, 1/m]
    mu: float              #: friction coefficient
    Fn: float              #: normal force [N]
    c: float               #: √(ab) [m]
    ab: float              #: a/b
    nu: float              #: Poisson's ratio
    rho_hat: float         #: scaled creepage ρ̂ (module docstring)
    theta: float           #: its direction [rad], any quadrant
    phi_hat: float         #: scaled spin φ̂


def random_cases(n, seed=2026, *, s_max=0.95, size=4e-3, E=2.1e11) -> list:
    """Random contacts and creepages spread over the table's whole domain.

    The points on which the table law is measured against the exact theory (benchmark
    ``bench_contact_table_law.py``, ``tests/reference/test_table_law.py``, the validation
    row ``table-law``): a/b log-uniform in [0.05, 20], ν uniform in [0.25, 0.30], Fn in
    2–20 kN, μ in 0.1–0.5, ρ̂ = U(0, 3)² in any direction θ ∈ (−π, π), and the spin
    φ̂ = s/(1 − |s|) with s uniform in (−``s_max``, ``s_max``) (|φ̂| up to 19 for 0.95).

    Parameters
    ----------
    n : int
        Number of cases.
    seed : int
        Seed of :func:`numpy.random.default_rng`.
    s_max : float
        Largest |s|.
    size, E : float
        √(ab) of the Hertz ellipse [m] and Young's modulus [Pa] (by similarity they do
        not change the scaled forces).

    Returns
    -------
    list of TableCase
        Contact, creepages (ξ, η, φ) and the table coordinates of each case.
    """
    rng = np.random.default_rng(seed)
    ab = np.exp(rng.uniform(np.log(0.05), np.log(20.0), n))
    nu = rng.uniform(0.25, 0.30, n)
    load = rng.uniform(2e3, 2e4, n)
    mu = rng.uniform(0.1, 0.5, n)
    rho = rng.uniform(0.0, 3.0, n) ** 2
    th = rng.uniform(-np.pi, np.pi, n)
    s = rng.uniform(-s_max, s_max, n)
    ph = s / (1.0 - np.abs(s))
    out = []
    for i in range(n):
        m = Material(E, float(nu[i]))
        cont = hertz_from_semiaxes(size * math.sqrt(ab[i]), size / math.sqrt(ab[i]),
                                   float(load[i]), m)
        c = float(math.sqrt(cont.a * cont.b))
        C11, C22, C23 = (float(v) for v in _coefficients(ab[i], nu[i]))
        unit = 3.0 * mu[i] * load[i] / m.G
        ell = float(_spin_length(c, cont.b, C11, C23))
        creep = (float(rho[i] * np.cos(th[i]) * unit / (c**2 * C11)),
                 float((rho[i] * np.sin(th[i]) - ph[i] * c * C23 / ell) * unit / (c**2 * C22)),
                 float(ph[i] * unit / (c**2 * ell)))
        out.append(TableCase(cont, creep, float(mu[i]), float(load[i]), c, float(ab[i]),
                             float(nu[i]), float(rho[i]), float(th[i]), float(ph[i])))
    return out


def _table_path(name, v):
    """A table file path (str or path-like) as ``str``; refused if it is not a file."""
    if v is None:
        return None
    if not isinstance(v, (str, Path)):
        raise InputError(f"{name} must be the path of a table file, got {v!r}")
    if not Path(v).is_file():
        raise InputError(f"{name}: creep table {str(v)!r} not found")
    return str(v)


@configured
class Table(TangentialMethod):
    """Creep forces interpolated in a table of exact-theory results (see the module docstring).

    On a :class:`~wheelrail.patch.ContactPatch` (``wr.solve``) this law
    uses the patch's equivalent ellipse (:meth:`ContactPatch.ellipse`: the Hertz
    ellipse of a Hertzian patch, otherwise the ellipse of equal area and
    length/width ratio).

    Other Parameters
    ----------------
    outside : {"raise", "exact", "fastsim"}, default "raise"
        Points outside the table's domain (a/b ∉ [0.05, 20],
        ν ∉ [0.25, 0.30], K ≠ 0; any spin is inside): raise :class:`~wheelrail.errors.InputError`
        naming the value, or compute them with that method.
    table : str or None, default None
        Path of another table file (built by :func:`build_table`).

    Notes
    -----
    ``info["outside"]``: boolean mask (batch) or bool of the points computed
    by the fallback method.
    """

    name = "table"
    references = (
        "J.J. Kalker, Book of tables for the Hertzian creep-force law, Proc. 2nd Mini Conf. "
        "on Contact Mechanics and Wear of Wheel/Rail Systems, Budapest, 1996, 11-20 "
        "(tabulated exact theory; table here built with wheelrail's exact solver).",
    )
    outside: str = option("raise", choices=("raise", "exact", "fastsim"),
                          doc="points outside the table: refuse, or compute with that method")
    table: str | None = option(None, kind="any", allow_none=True, check=_table_path,
                               doc="path of another table file (.npz)")

    def forces(self, contact, creepage, mu):
        """:meth:`TangentialMethod.forces`, with a short path for one contact.

        One contact with a tuple of three finite floats and a float μ > 0 skips the
        batch broadcasting (the same checks: contact type, friction plausibility,
        finite forces); anything else takes the general path.
        """
        if (isinstance(creepage, tuple) and len(creepage) == 3 and isinstance(mu, float)
                and all(isinstance(v, float) and math.isfinite(v) for v in creepage)
                and math.isfinite(mu) and mu > 0.0 and hasattr(contact, "materials")
                and np.ndim(contact.a) == 0):
            check_friction(mu)
            r = self.solve(contact, *creepage, mu)
            if math.isfinite(r.Fx) and math.isfinite(r.Fy) and math.isfinite(r.Mz):
                return r
        return super().forces(contact, creepage, mu)

    def solve(self, contact, xi, eta, phi, mu):
        """Creep forces by interpolation; see the class docstring."""
        outside = self.outside
        data = load_table(self.table)
        shape = np.shape(contact.a)
        a, b, Fn, xs, es, ps, ms = np.broadcast_arrays(
            *(np.asarray(v, float).reshape(-1) for v in
              (contact.a, contact.b, contact.Fn, xi, eta, phi, mu)))
        a, b, Fn, xs, es, ps, ms = (np.ascontiguousarray(v) for v in (a, b, Fn, xs, es, ps, ms))
        pair = contact.materials
        nu = float(pair.nu)
        m = a.shape[0]
        out, flags = data.forces(a, b, np.full(m, float(pair.G)), np.full(m, nu), xs, es, ps,
                                 ms, Fn)
        K = float(getattr(pair, "K", 0.0))
        bad_K = abs(K) > _K_TOL
        out_mask = flags != 0
        if bad_K or out_mask.any():
            out_mask = out_mask | bad_K
            reasons = self._reasons(data, a / b, nu, K, bad_K, flags, a, b, pair, xs, es, ps,
                                    ms, Fn)
            if outside == "raise":
                raise InputError("outside the creep table's domain: " + "; ".join(reasons)
                                 + ". Use outside='exact' or 'fastsim' to compute such points "
                                   "with that method.")
            idx = np.flatnonzero(out_mask)
            sub = contact if not shape else contact[idx]
            r = get(outside).solve(sub, *(v[idx] if shape else v[0]
                                          for v in (xs, es, ps, ms)))
            for k, v in enumerate((r.Fx, r.Fy, r.Mz)):
                out[idx, k] = np.asarray(v, float).reshape(-1)
        if not shape:
            return CreepForcesResult(Fx=float(out[0, 0]), Fy=float(out[0, 1]),
                                     Mz=float(out[0, 2]), Fn=float(Fn[0]), mu=float(ms[0]),
                                     method=self.name, status=Status.CONVERGED,
                                     info={"outside": bool(out_mask[0]),
                                           "table_version": data.meta.get("version")})
        return CreepForcesResult(Fx=out[:, 0].reshape(shape), Fy=out[:, 1].reshape(shape),
                                 Mz=out[:, 2].reshape(shape), Fn=Fn.reshape(shape),
                                 mu=ms.reshape(shape), method=self.name,
                                 status=Status.CONVERGED,
                                 info={"outside": out_mask.reshape(shape),
                                       "table_version": data.meta.get("version")})

    @staticmethod
    def _reasons(data, ab, nu, K, bad_K, flags, a, b, pair, xs, es, ps, ms, Fn):
        """Messages naming the first value outside the table for each kind of violation."""
        dom = data.domain
        reasons = []
        if np.any(flags & 1):
            i = int(np.argmax(flags & 1))
            *_, ph, _ = table_coordinates(a[i:i + 1], b[i:i + 1], pair.G, nu, xs[i:i + 1],
                                          es[i:i + 1], ps[i:i + 1], ms[i:i + 1], Fn[i:i + 1])
            reasons.append(f"scaled spin phi_hat = {abs(ph[0]):.6g} at point {i} "
                           f"(table domain: |phi_hat| <= {dom['phi_hat']:g})")
        if np.any(flags & 2):
            i = int(np.argmax(flags & 2))
            reasons.append(f"a/b = {ab[i]:.6g} at point {i} (table domain: "
                           f"{dom['aspect'][0]:g} <= a/b <= {dom['aspect'][1]:g})")
        if np.any(flags & 4):
            reasons.append(f"Poisson's ratio nu = {nu:.6g} at point 0 (table domain: "
                           f"{dom['nu'][0]:g} <= nu <= {dom['nu'][1]:g})")
        if bad_K:
            reasons.append(f"difference parameter K = {K:.6g} at point 0 (table domain: "
                           f"|K| <= {_K_TOL:g} (quasi-identical materials))")
        return reasons
