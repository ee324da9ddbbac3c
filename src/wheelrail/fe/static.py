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

from ._newton import make_solver, newton
from .model import build_model
from .patch_dataset import patch_from_contact
from .rolling import plastic_fields

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
    model : Model
    u : ndarray, shape (n_nodes, 3)
        Displacements in the body frames [m].
    state : PlasticState or None
        The plastic state (plastic materials).
    fields : xarray.Dataset or None
        Equivalent plastic strain, stress and von Mises stress per element (plastic
        materials; :func:`wheelrail.fe.rolling.plastic_fields`).
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
    state: object = None
    fields: object = None

    def __repr__(self):
        return (f"IndentResult(p_max={self.p_max / 1e6:.1f} MPa, a={self.a * 1e3:.3f} mm, "
                f"b={self.b * 1e3:.3f} mm, Fn={self.Fn:.1f} N)")


def free_dofs(model):
    n = model.n_nodes
    mask = np.ones(3 * n + 1, bool)
    mask[(3 * model.fixed[:, None] + np.arange(3)).ravel()] = False
    return np.flatnonzero(mask)


#: Load increments of a plastic static solve (the return map is path-dependent).
PLASTIC_INCREMENTS = 8


def static_equilibrium(model, K=None, psi=0.0, s=0.0, state=None, increments=None):
    """Frictionless static equilibrium under the case load; returns (u, w, contact, iterations).

    A plastic material (``state``, committed in place) is loaded in ``increments`` equal
    load steps (default :data:`PLASTIC_INCREMENTS`) with the consistent tangent; an elastic
    one in one step.
    """
    case = model.case
    solver = make_solver(getattr(case, "linear_solver", "direct"))
    if K is None:
        K = model.stiffness()
    free = free_dofs(model)
    Kff = K[free][:, free].tocsr()
    hz = model.geometry["hertz"]
    u = np.zeros((model.n_nodes, 3))
    ft0 = np.zeros((model.slave.size, 3))
    if state is None:
        w0 = -float(hz.penetration) if hz is not None else -0.01 * case.mesh_size
        xs = model.slave_positions(u, w0, psi)
        xm = model.master_positions(u, s)
        return newton(model, Kff, free, u, w0, psi, s, xs, xm, ft0, 0.0, case.Fn,
                      solver=solver)

    def tangent(q):
        return model.stiffness(q[:-1].reshape(-1, 3), state)[free][:, free].tocsr()

    n_inc = increments or PLASTIC_INCREMENTS
    iters = 0
    w = None
    for i in range(1, n_inc + 1):
        load = case.Fn * i / n_inc
        if w is None:
            w = -float(hz.penetration) * (i / n_inc) ** (2 / 3) if hz is not None \
                else -0.01 * case.mesh_size
        xs = model.slave_positions(u, w, psi)
        xm = model.master_positions(u, s)
        u, w, c, it = newton(model, Kff, free, u, w, psi, s, xs, xm, ft0, 0.0, load,
                             state=state, tangent=tangent, solver=solver)
        state.commit()
        iters += it
    return u, w, c, iters


def indent(case, *, increments: int | None = None) -> IndentResult:
    """Static indentation of the wheel into the rail under ``case.Fn``.

    Parameters
    ----------
    case : RollingCase
        Only the geometry, load, material and mesh settings are used (a short
        mesh refined around the contact point; creepage and friction ignored).
    increments : int, optional
        Load steps of a plastic material (default :data:`PLASTIC_INCREMENTS`).

    Returns
    -------
    IndentResult

    References
    ----------
    .. [1] Toumi et al., Wear 366-367 (2016), step 1 of §2 and Table 3.
    .. [2] K.L. Johnson, *Contact Mechanics*, CUP 1985, eqs. (3.64)-(3.66) (Hertz reference).
    """
    model = build_model(case, rolling=False)
    state = model.new_state()
    u, w, c, it = static_equilibrium(model, state=state, increments=increments)
    patch = patch_from_contact(model, c, 0.0)

    return IndentResult(p_max=patch.attrs["p_max"], a=patch.attrs["a"], b=patch.attrs["b"],
                        Fn=patch.attrs["Fn"], approach=w, pressure=patch["pressure"],
                        patch=patch, hertz=model.geometry["hertz"], iterations=it, model=model,
                        u=u, state=state, fields=plastic_fields(model, u, state))
