"""Stresses below the surface of a half-space loaded by piecewise-constant tractions.

Method
------
The stress at depth ``z`` due to a uniform traction on one rectangular element
is the point-load stress field (Boussinesq for the pressure, Cerruti for the
shear, closed forms in Cartesian coordinates, Johnson 1985 §3.2)
integrated over the element with an m × m Gauss–Legendre rule, m chosen from
the ratio element size / depth (the integrand is smooth on the scale ``z``).
Contributions of all elements are summed by FFT convolution (evaluation at
the element centres of the grid) or directly (arbitrary points).

Accuracy: the quadrature error is below ~1e-6 relative for z ≥ 0.25·max(dx,
dy) (m ≤ 16); closer to the surface it degrades, and ``z`` must be > 0. The
piecewise-constant traction itself limits the accuracy near the surface to
O(element size).

Conventions
-----------
Stresses [Pa], tension positive, in the axes (x, y, ζ) with ζ = depth **into
the body considered** (``body="rail"``: ζ = z; ``body="wheel"``: ζ = −z). The
tractions are those of :mod:`wheelrail.halfspace.influence` (acting on the
wheel, pressure positive in compression): the rail carries the pressure and the
shear ``(−px, −py)``, the wheel the pressure and ``(px, py)``. Only Poisson's
ratio of the body enters.

References
----------
.. [1] K.L. Johnson, *Contact Mechanics*, CUP 1985, §3.2 (Boussinesq and
   Cerruti stress fields); §3.4 and §4.2 (Hertz subsurface stresses).
.. [2] A.E.H. Love, Phil. Trans. R. Soc. A 228 (1929) 377–420.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._validation import as_float_array, positive
from ..errors import InputError
from ..materials import as_material_pair
from .fft import ConvolutionOperator
from .influence import kernel_offsets

__all__ = ["boussinesq_stress", "cerruti_stress", "SubsurfaceStresses", "subsurface_stresses",
           "STRESS_COMPONENTS"]

#: Order of the stress components (Voigt): σxx, σyy, σζζ, σyζ, σxζ, σxy.
STRESS_COMPONENTS = ("sxx", "syy", "szz", "syz", "sxz", "sxy")


def boussinesq_stress(x, y, z, nu):
    """Stresses per unit normal point force pressing on the surface (Boussinesq).

    Parameters
    ----------
    x, y : array_like
        Horizontal offset of the field point from the force [m].
    z : array_like
        Depth below the surface [m], > 0.
    nu : float
        Poisson's ratio.

    Returns
    -------
    ndarray, shape (6, *shape)
        σxx, σyy, σzz, σyz, σxz, σxy [Pa per N], tension positive.

    Notes
    -----
    Boussinesq's field (Johnson 1985 §3.2) in Cartesian form, written without removable
    singularities on the axis, ρ² = x² + y² + z²::

        σθ = −(1−2ν)/(2π) [1/(ρ(ρ+z)) − z/ρ³]
        D  = 1/(2π) [(1−2ν)(2ρ+z)/(ρ³(ρ+z)²) − 3z/ρ⁵]      (σr − σθ = D r²)
        σxx = σθ + D x², σyy = σθ + D y², σxy = D x y,
        σzz = −3z³/(2πρ⁵), σxz = −3x z²/(2πρ⁵), σyz = −3y z²/(2πρ⁵)
    """
    x, y, z = np.broadcast_arrays(*(np.asarray(v, float) for v in (x, y, z)))
    rho = np.sqrt(x * x + y * y + z * z)
    rz = rho + z
    c = 1.0 / (2.0 * np.pi)
    r5 = rho**5
    s_t = -c * (1 - 2 * nu) * (1.0 / (rho * rz) - z / rho**3)
    D = c * ((1 - 2 * nu) * (2 * rho + z) / (rho**3 * rz**2) - 3 * z / r5)
    out = np.empty((6,) + x.shape)
    out[0] = s_t + D * x * x
    out[1] = s_t + D * y * y
    out[2] = -3 * c * z**3 / r5
    out[3] = -3 * c * y * z * z / r5
    out[4] = -3 * c * x * z * z / r5
    out[5] = D * x * y
    return out


def cerruti_stress(x, y, z, nu):
    """Stresses per unit tangential point force along +x on the surface (Cerruti).

    Parameters and returns as :func:`boussinesq_stress`.

    Notes
    -----
    Cerruti's field (Johnson 1985 §3.2), ρ² = x² + y² + z²::

        σxx = −1/(2π) [3x³/ρ⁵ − (1−2ν)(x/ρ³ − 3x/(ρ(ρ+z)²) + x³/(ρ³(ρ+z)²) + 2x³/(ρ²(ρ+z)³))]
        σyy = −1/(2π) [3xy²/ρ⁵ − (1−2ν)(x/ρ³ − x/(ρ(ρ+z)²) + xy²/(ρ³(ρ+z)²) + 2xy²/(ρ²(ρ+z)³))]
        σzz = −3xz²/(2πρ⁵),  σyz = −3xyz/(2πρ⁵),  σxz = −3x²z/(2πρ⁵)
        σxy = −1/(2π) [3x²y/ρ⁵ + (1−2ν)(y/(ρ(ρ+z)²) − x²y/(ρ³(ρ+z)²) − 2x²y/(ρ²(ρ+z)³))]
    """
    x, y, z = np.broadcast_arrays(*(np.asarray(v, float) for v in (x, y, z)))
    rho = np.sqrt(x * x + y * y + z * z)
    rz = rho + z
    c = 1.0 / (2.0 * np.pi)
    k = 1 - 2 * nu
    r3, r5 = rho**3, rho**5
    a1 = 1.0 / (rho * rz**2)
    a2 = 1.0 / (r3 * rz**2)
    a3 = 2.0 / (rho**2 * rz**3)
    x2, y2 = x * x, y * y
    out = np.empty((6,) + x.shape)
    out[0] = -c * (3 * x * x2 / r5 - k * (x / r3 - 3 * x * a1 + x * x2 * (a2 + a3)))
    out[1] = -c * (3 * x * y2 / r5 - k * (x / r3 - x * a1 + x * y2 * (a2 + a3)))
    out[2] = -3 * c * x * z * z / r5
    out[3] = -3 * c * x * y * z / r5
    out[4] = -3 * c * x2 * z / r5
    out[5] = -c * (3 * x2 * y / r5 + k * (y * a1 - x2 * y * (a2 + a3)))
    return out


def _cerruti_y(x, y, z, nu):
    """Cerruti field of a unit force along +y (x ↔ y exchanged)."""
    s = cerruti_stress(y, x, z, nu)
    return s[[1, 0, 2, 4, 3, 5]]


def _point_stress(j, x, y, z, nu):
    if j == 2:
        return boussinesq_stress(x, y, z, nu)
    if j == 0:
        return cerruti_stress(x, y, z, nu)
    return _cerruti_y(x, y, z, nu)


_CHUNK = 2e5   # points per block of point-load evaluations (memory bound)


def _gauss_order(h: float, z: float) -> int:
    return int(min(16, max(2, math.ceil(2.0 + 3.0 * h / z))))


def _element_rule(grid, z):
    """Gauss points (offsets from the element centre) and weights (incl. area) for depth z."""
    m = _gauss_order(max(grid.dx, grid.dy), z)
    t, w = np.polynomial.legendre.leggauss(m)
    return 0.5 * grid.dx * t, 0.5 * grid.dy * t, 0.25 * grid.dx * grid.dy * np.outer(w, w)


# --------------------------------------------------------------------------- result
@dataclass(frozen=True)
class SubsurfaceStresses:
    """Stress tensors below the surface (frozen).

    Attributes
    ----------
    z : ndarray, shape (nz,)
        Depths [m].
    x, y : ndarray
        Horizontal coordinates of the evaluation points [m] (shape ``S``:
        (nx, ny) for the grid centres, or the broadcast shape of the given points).
    sxx, syy, szz, syz, sxz, sxy : ndarray, shape (nz, *S)
        Stress components [Pa], tension positive, axes (x, y, depth into the body).
    body : str
        "rail" or "wheel".
    """

    z: np.ndarray
    x: np.ndarray
    y: np.ndarray
    sxx: np.ndarray
    syy: np.ndarray
    szz: np.ndarray
    syz: np.ndarray
    sxz: np.ndarray
    sxy: np.ndarray
    body: str

    @property
    def tensor(self) -> np.ndarray:
        """Full tensors, shape (nz, *S, 3, 3) [Pa]."""
        return np.stack([np.stack([self.sxx, self.sxy, self.sxz], -1),
                         np.stack([self.sxy, self.syy, self.syz], -1),
                         np.stack([self.sxz, self.syz, self.szz], -1)], -2)

    @property
    def principal(self) -> np.ndarray:
        """Principal stresses σ1 ≥ σ2 ≥ σ3, shape (3, nz, *S) [Pa]."""
        ev = np.linalg.eigvalsh(self.tensor)           # ascending
        return np.moveaxis(ev[..., ::-1], -1, 0)

    @property
    def tau_max(self) -> np.ndarray:
        """Maximum shear stress (σ1 − σ3)/2 (Tresca), shape (nz, *S) [Pa]."""
        p = self.principal
        return 0.5 * (p[0] - p[2])

    @property
    def von_mises(self) -> np.ndarray:
        """Von Mises equivalent stress, shape (nz, *S) [Pa]."""
        return np.sqrt(0.5 * ((self.sxx - self.syy) ** 2 + (self.syy - self.szz) ** 2
                              + (self.szz - self.sxx) ** 2)
                       + 3.0 * (self.sxy**2 + self.syz**2 + self.sxz**2))

    def max_location(self, field: str = "tau_max"):
        """(value, z, x, y) of the largest value of ``field`` ("tau_max" or "von_mises")."""
        if field not in ("tau_max", "von_mises"):
            raise InputError(f"field must be 'tau_max' or 'von_mises', got {field!r}")
        f = getattr(self, field)
        idx = np.unravel_index(np.argmax(f), f.shape)
        xs = np.broadcast_to(self.x, f.shape[1:])
        ys = np.broadcast_to(self.y, f.shape[1:])
        return float(f[idx]), float(self.z[idx[0]]), float(xs[idx[1:]]), float(ys[idx[1:]])


# --------------------------------------------------------------------------- entry
def subsurface_stresses(grid, px, py, pz, materials, z, x=None, y=None, *,
                        body: str = "rail") -> SubsurfaceStresses:
    """Stresses below the contact from piecewise-constant surface tractions.

    Parameters
    ----------
    grid : Grid
    px, py : array_like, shape (nx, ny), or None
        Tangential tractions on the wheel [Pa] (``None`` = zero).
    pz : array_like, shape (nx, ny), or None
        Pressure [Pa], compression positive.
    materials : Material or MaterialPair
        Poisson's ratio of ``body`` is used.
    z : float or array_like, shape (nz,)
        Depths below the surface [m], > 0.
    x, y : array_like, optional
        Evaluation points (broadcast together) [m]; by default the element
        centres of ``grid`` (FFT convolution).
    body : {"rail", "wheel"}

    Returns
    -------
    SubsurfaceStresses
        Components of shape (nz, nx, ny) (grid) or (nz, *broadcast(x, y).shape).

    Examples
    --------
    >>> import numpy as np, wheelrail as wr
    >>> from wheelrail.halfspace import Grid, subsurface_stresses
    >>> g = Grid.from_bounds(-1e-3, 1e-3, -1e-3, 1e-3, 20, 20)
    >>> s = subsurface_stresses(g, None, None, np.full(g.shape, 1e9), wr.STEEL, z=[1e-3])
    >>> s.szz.shape
    (1, 20, 20)
    """
    pair = as_material_pair(materials)
    if body not in ("rail", "wheel"):
        raise InputError(f"body must be 'rail' or 'wheel', got {body!r}")
    nu = pair.rail.nu if body == "rail" else pair.wheel.nu
    sign_t = -1.0 if body == "rail" else 1.0
    fields = {}
    for j, (name, f) in enumerate((("px", px), ("py", py), ("pz", pz))):
        if f is None:
            continue
        arr = grid.check_field(name, f)
        if np.any(arr != 0):
            fields[j] = arr * (sign_t if j < 2 else 1.0)
    zs = np.atleast_1d(positive("z", z)).astype(float)
    if zs.ndim != 1:
        raise InputError(f"z must be a scalar or a 1-D array of depths, got shape {zs.shape}")

    if (x is None) != (y is None):
        raise InputError("give both x and y, or neither (grid centres)")
    if x is None:
        X, Y = grid.X, grid.Y
        out = np.zeros((6, zs.size) + grid.shape)
        ox, oy = kernel_offsets(grid)
        for iz, zz in enumerate(zs):
            gx, gy, w = _element_rule(grid, zz)
            m = gx.size
            sy = oy[None, None, :, None] - gy[None, None, None, :]
            rows = max(1, int(_CHUNK // (m * m * oy.size)))     # bound the temporary arrays
            for j, f in fields.items():
                k = np.empty((6, ox.size, oy.size))
                for r0 in range(0, ox.size, rows):
                    sx = ox[r0:r0 + rows, None, None, None] - gx[None, :, None, None]
                    k[:, r0:r0 + rows] = np.einsum("cambn,mn->cab",
                                                   _point_stress(j, sx, sy, zz, nu), w)
                ops = [ConvolutionOperator(kc) for kc in k]
                f_hat = ops[0].forward(f)        # one transform of f for the six components
                for c, op in enumerate(ops):
                    out[c, iz] += op.backward(op.multiply(f_hat))
    else:
        X, Y = np.broadcast_arrays(as_float_array("x", x), as_float_array("y", y))
        pts_x, pts_y = X.ravel(), Y.ravel()
        out = np.zeros((6, zs.size, pts_x.size))
        loaded = np.zeros(grid.shape, dtype=bool)
        for f in fields.values():
            loaded |= f != 0
        ex, ey = grid.X[loaded], grid.Y[loaded]
        for iz, zz in enumerate(zs):
            gx, gy, w = _element_rule(grid, zz)
            m = gx.size
            chunk = max(1, int(_CHUNK // max(1, ex.size * m * m)))
            for s0 in range(0, pts_x.size, chunk):
                sl = slice(s0, s0 + chunk)
                dx = pts_x[sl, None, None, None] - ex[None, :, None, None] - gx[None, None, :, None]
                dy = pts_y[sl, None, None, None] - ey[None, :, None, None] - gy[None, None, None, :]
                for j, f in fields.items():
                    k = _point_stress(j, dx, dy, zz, nu)             # (6, P, E, m, m)
                    out[:, iz, sl] += np.einsum("cpemn,mn,e->cp", k, w, f[loaded])
        out = out.reshape((6, zs.size) + X.shape)
    return SubsurfaceStresses(zs, np.array(X), np.array(Y), *out, body=body)
