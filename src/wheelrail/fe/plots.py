"""Figures of FE results in the manner of seed 000 Figs. 4-7 (matplotlib; a leaf module)."""

from __future__ import annotations

import numpy as np

__all__ = ["plot_patch", "plot_history"]


def plot_patch(patch, mu: float, reference=None, path=None):
    """Pressure map, |q|/(μp) with stick/slip, and centre-line profiles.

    Parameters
    ----------
    patch : xarray.Dataset
        ``RollingResult.patch`` or ``IndentResult.patch``.
    mu : float
        Friction coefficient [-] (normalisation of the shear).
    reference : TangentialSolution, optional
        Half-space solution (``wr.creep_forces(..., method="exact").fields.tangential``);
        its centre-line pressure and shear are drawn as lines.
    path : str or Path, optional
        Save the figure there.

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib

    if path is not None:
        matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    x = patch.x.values * 1e3
    y = patch.y.values * 1e3
    p = patch.pressure.values
    q = patch.shear.values
    on = p > 0
    if not on.any():
        on = np.ones_like(p, bool)
    i0, i1 = np.flatnonzero(on.any(1))[[0, -1]]
    j0, j1 = np.flatnonzero(on.any(0))[[0, -1]]
    sl = (slice(max(i0 - 2, 0), i1 + 3), slice(max(j0 - 2, 0), j1 + 3))
    X, Y = np.meshgrid(x[sl[0]], y[sl[1]], indexing="ij")
    fig, ax = plt.subplots(1, 3, figsize=(14, 4.2))
    cs = ax[0].contourf(X, Y, p[sl] / 1e6, 20, cmap="viridis")
    fig.colorbar(cs, ax=ax[0], label="pressure [MPa]")
    ax[0].set_title("contact pressure")
    ratio = np.where(p > 0, q / np.maximum(mu * p, 1e-300), np.nan)
    cs = ax[1].contourf(X, Y, ratio[sl], np.linspace(0, 1, 11), cmap="magma")
    fig.colorbar(cs, ax=ax[1], label="|q| / (μ p)")
    st = patch.status.values[sl]
    ax[1].plot(X[st == 2], Y[st == 2], "k.", ms=3, label="slip")
    ax[1].plot(X[st == 1], Y[st == 1], "c.", ms=3, label="stick")
    ax[1].legend(loc="upper right", fontsize=8)
    ax[1].set_title("shear / traction bound")
    for a in ax[:2]:
        a.set_xlabel("x [mm] (rolling)")
        a.set_ylabel("y [mm]")
        a.set_aspect("equal")
    jc = int(np.argmax(p.max(axis=0)))
    ax[2].plot(x, p[:, jc] / 1e6, "o-", ms=3, label="FE pressure")
    ax[2].plot(x, patch.shear_x.values[:, jc] / 1e6, "s-", ms=3, label="FE shear q_x")
    ax[2].plot(x, mu * p[:, jc] / 1e6, ":", label="μ p (FE)")
    if reference is not None:
        g = reference.grid
        jr = int(np.argmax(reference.pressure.max(axis=1))) if reference.pressure.ndim == 2 else 0
        xc = patch.attrs.get("x_centre", 0.0) * 1e3
        ax[2].plot(g.x * 1e3 + xc, reference.pressure[jr] / 1e6, "k-", label="half-space pressure")
        ax[2].plot(g.x * 1e3 + xc, reference.px[jr] / 1e6, "k--", label="half-space shear")
    ax[2].set_xlim(x[sl[0]][0], x[sl[0]][-1])
    ax[2].set_xlabel("x [mm]")
    ax[2].set_ylabel("[MPa]")
    ax[2].set_title("centre line")
    ax[2].legend(fontsize=8)
    fig.tight_layout()
    if path is not None:
        fig.savefig(path, dpi=120)
    return fig


def plot_history(dataset, path=None):
    """Forces and energies over the travel (seed 000 Fig. 7)."""
    import matplotlib

    if path is not None:
        matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    d = dataset.travel.values * 1e3
    fig, ax = plt.subplots(1, 2, figsize=(11, 4))
    for name in ("Fx", "Fy", "Fn"):
        ax[0].plot(d, dataset[name].values, label=name)
    ax[0].set_xlabel("travel [mm]")
    ax[0].set_ylabel("force on the wheel [N]")
    ax[0].legend()
    for name in ("kinetic", "internal", "contact", "friction", "damping", "external",
                 "energy_error"):
        ax[1].plot(d, dataset[name].values, label=name)
    ax[1].set_xlabel("travel [mm]")
    ax[1].set_ylabel("energy [J]")
    ax[1].legend(fontsize=8)
    fig.tight_layout()
    if path is not None:
        fig.savefig(path, dpi=120)
    return fig
