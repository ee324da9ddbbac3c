"""Subsurface stress sections (matplotlib leaf)."""

from __future__ import annotations

import numpy as np

from ._common import finish, new_figure

__all__ = ["subsurface_section"]


def subsurface_section(stresses, *, field="von_mises", y=0.0, path=None, title=None):
    """Contour plot of a stress measure in a vertical section below the contact.

    Parameters
    ----------
    stresses : wheelrail.halfspace.SubsurfaceStresses
        Evaluated on a line of surface points (shape (nz, n)), e.g. the centre
        line y = 0, or on the grid centres (shape (nz, nx, ny)): then the
        section x–z through the grid row nearest to ``y`` is drawn.
    field : {"von_mises", "tau_max"}
        The stress measure to draw [Pa].
    y : float
        Lateral position of the section for grid stresses [m].
    path : str or Path, optional
        Write the figure there.
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    from dataclasses import replace

    if np.ndim(stresses.x) == 2:  # grid centres: cut the row nearest to y
        j = int(np.argmin(np.abs(stresses.y[0] - y)))
        comps = ("sxx", "syy", "szz", "syz", "sxz", "sxy")
        stresses = replace(stresses, x=stresses.x[:, j], y=stresses.y[:, j],
                           **{c: getattr(stresses, c)[:, :, j] for c in comps})
    values = getattr(stresses, field)
    if values.ndim != 2:
        raise ValueError(f"subsurface_section needs stresses on a line of points, "
                         f"got shape {values.shape}")
    x = np.broadcast_to(stresses.x, values.shape[1:])
    fig, ax = new_figure(size=(7.0, 4.0))
    X, Z = np.meshgrid(x * 1e3, stresses.z * 1e3)
    cs = ax.contourf(X, Z, values / 1e6, levels=16, cmap="magma")
    fig.colorbar(cs, ax=ax, label=f"{field.replace('_', ' ')} [MPa]")
    val, z, xm, _ = stresses.max_location(field)
    ax.plot([xm * 1e3], [z * 1e3], "c+", ms=12, mew=2)
    ax.annotate(f"max {val / 1e6:.0f} MPa at z = {z * 1e3:.2f} mm", (xm * 1e3, z * 1e3),
                textcoords="offset points", xytext=(8, 8), color="c")
    ax.invert_yaxis()
    ax.set_xlabel("x [mm] (rolling direction)")
    ax.set_ylabel(f"depth into the {stresses.body} [mm]")
    finish(fig, path, title)
    return fig
