"""VTU output of the deformed meshes for ParaView (meshio; a leaf module)."""

from __future__ import annotations

import numpy as np

from ._solid import von_mises

__all__ = ["write_vtu"]


def write_vtu(path, model, u, *, psi: float = 0.0, s: float = 0.0, w: float = 0.0,
              state=None) -> None:
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
    state : PlasticState, optional
        The plastic state (plastic materials): adds the equivalent plastic strain and uses
        the plastic strain in the stresses.

    Point data: ``displacement`` [m] (body frames); cell data: ``von_mises`` [Pa],
    ``stress`` [Pa] (6 Voigt components xx, yy, zz, xy, yz, xz, body frames), ``body`` (0
    wheel, 1 rail) and, with a state, ``equivalent_plastic_strain`` [-].
    """
    import meshio

    nw = model.nw
    Q = model.rotation(psi)
    xw = (model.wheel.nodes + u[:nw]) @ Q.T + np.array([0.0, 0.0, model.z_axle + w])
    xr = model.rail.nodes + u[nw:] - np.array([s, 0.0, 0.0])

    sig = np.concatenate(model.stress(u, state))
    nw_e = model.wheel.n_elements
    cells = {"von_mises": [von_mises(sig)], "stress": [sig],
             "body": [np.concatenate([np.zeros(nw_e, int), np.ones(model.rail.n_elements, int)])]}
    if state is not None:
        cells["equivalent_plastic_strain"] = [np.concatenate(state.equivalent_plastic_strain())]
    mesh = meshio.Mesh(np.concatenate([xw, xr]), [("hexahedron", model.conn)],
                       point_data={"displacement": u}, cell_data=cells)
    mesh.write(str(path))
