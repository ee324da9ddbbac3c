"""Static indentation: the first loading step (normal contact only).

Solved implicitly — Newton on ``K u − f_c(u, w) + F e_w = 0`` with the
frictionless penalty contact and a sparse direct solver. A static Newton
solve reaches equilibrium in a handful of iterations, where dynamic relaxation
would need thousands of explicit steps to damp the lowest mode; that is why
the indentation uses it (see docs/fe.md).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._newton import newton
from .model import build_model
from .patch import patch_from_contact

__all__ = ["IndentResult", "indent", "static_equilibrium"]


@dataclass(frozen=True, eq=False)
class IndentResult:
    """Static normal contact from :func:`indent`.

    Attributes
    ----------
    p_max : float
        Largest nodal pressure [Pa].
    a, b : float
        Semi-axes of the contact patch along x and y [m] (half extents of the
        nodes carrying pressure, extended by half a node spacing).
    Fn : float
        Total normal contact force [N].
    approach : float
        Vertical displacement of the axle [m] (negative: down).
    pressure : xarray.DataArray
        Nodal pressure on the wheel surface [Pa] over (x, y) [m], contact frame.
    patch : xarray.Dataset
        Pressure and geometry of the contact nodes.
    hertz : HertzContact or None
        The Hertz solution of the local curvatures (reference).
    iterations : int
    """

    p_max: float
    a: float
    b: float
    Fn: float
    approach: float
    pressure: object
    patch: object
    hertz: object
    iterations: int
    model: object
    u: np.ndarray

    def __repr__(self):
        return (f"IndentResult(p_max={self.p_max / 1e6:.1f} MPa, a={self.a * 1e3:.3f} mm, "
                f"b={self.b * 1e3:.3f} mm, Fn={self.Fn:.1f} N)")


def free_dofs(model):
    n = model.n_nodes
    mask = np.ones(3 * n + 1, bool)
    mask[(3 * model.fixed[:, None] + np.arange(3)).ravel()] = False
    return np.flatnonzero(mask)


def static_equilibrium(model, K=None, psi=0.0, s=0.0):
    """Frictionless static equilibrium under the case load; returns (u, w, contact, iterations)."""
    case = model.case
    if K is None:
        K = model.stiffness()
    free = free_dofs(model)
    Kff = K[free][:, free].tocsr()
    hz = model.geometry["hertz"]
    w0 = -float(hz.penetration) if hz is not None else -0.01 * case.mesh_size
    u = np.zeros((model.n_nodes, 3))
    xs = model.slave_positions(u, w0, psi)
    xm = model.master_positions(u, s)
    ft0 = np.zeros((model.slave.size, 3))
    return newton(model, Kff, free, u, w0, psi, s, xs, xm, ft0, 0.0, case.load)


def indent(case) -> IndentResult:
    """Static indentation of the wheel into the rail under ``case.load``.

    Parameters
    ----------
    case : RollingCase
        Only the geometry, load, material and mesh settings are used (a short
        mesh refined around the contact point; creepage and friction ignored).

    Returns
    -------
    IndentResult

    References
    ----------
    .. [1] Toumi et al., Wear 366-367 (2016), step 1 of §2 and Table 3 (seed 000).
    .. [2] K.L. Johnson, *Contact Mechanics*, CUP 1985, eqs. (3.64)-(3.66) (Hertz reference).
    """
    model = build_model(case, rolling=False)
    u, w, c, it = static_equilibrium(model)
    patch = patch_from_contact(model, c, 0.0)
    return IndentResult(p_max=patch.attrs["p_max"], a=patch.attrs["a"], b=patch.attrs["b"],
                        Fn=patch.attrs["Fn"], approach=w, pressure=patch["pressure"],
                        patch=patch, hertz=model.geometry["hertz"], iterations=it, model=model,
                        u=u)
