"""VTU output of the deformed meshes for ParaView (meshio; a leaf module)."""

from __future__ import annotations

import numpy as np

__all__ = ["write_vtu"]


def write_vtu(path, model, u, *, psi: float = 0.0, s: float = 0.0, w: float = 0.0) -> None:
    """Write both bodies as one unstructured hexahedral grid (``.vtu``).

    Parameters
    ----------
    path : str or Path
    model : Model
    u : ndarray, shape (n_nodes, 3)
        Displacements in the body frames [m].
    psi, s, w : float
        Wheel rolling angle [rad], rail shift [m] and axle displacement [m] used to place the
        bodies in the global frame.

    Point data: ``displacement`` [m] (body frames); cell data: ``von_mises`` [Pa],
    ``body`` (0 wheel, 1 rail).
    """
    import meshio

    nw = model.nw
    Q = model.rotation(psi)
    xw = (model.wheel.nodes + u[:nw]) @ Q.T + np.array([0.0, 0.0, model.z_axle + w])
    xr = model.rail.nodes + u[nw:] - np.array([s, 0.0, 0.0])
    vm_w, vm_r = model.von_mises(u)
    mesh = meshio.Mesh(np.concatenate([xw, xr]), [("hexahedron", model.conn)],
                       point_data={"displacement": u},
                       cell_data={"von_mises": [np.concatenate([vm_w, vm_r])],
                                  "body": [np.concatenate([np.zeros(vm_w.size, int),
                                                           np.ones(vm_r.size, int)])]})
    mesh.write(str(path))
