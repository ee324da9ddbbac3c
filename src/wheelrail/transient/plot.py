"""Figures of a transient rolling run, after Baeza et al. Figs. 7–12 (matplotlib, Agg; a leaf).

* :func:`plot_creepage` — longitudinal creepage (and optionally Fx) over the
  travel (Figs. 8, 9, 11);
* :func:`plot_centreline` — longitudinal traction along the centre line of the
  grid for successive positions (Fig. 7);
* :func:`plot_state` — adhesion/slip map at a stored step (Figs. 10, 12).

Each returns the matplotlib ``Figure`` and writes it to ``path`` if given.
"""

from __future__ import annotations

import numpy as np


def new_figure(*args, **kwargs):
    from ..plotting._common import new_figure as _new  # plotting is a leaf: import lazily

    return _new(*args, **kwargs)


def finish(*args, **kwargs):
    from ..plotting._common import finish as _finish

    return _finish(*args, **kwargs)

__all__ = ["plot_creepage", "plot_centreline", "plot_state"]


def plot_creepage(result, *, path=None, title=None, label=None, ax=None):
    """ξ [-] versus travel [mm] (the first step, the Cattaneo shift ξ = W/h, is left out)."""
    if ax is None:
        fig, ax = new_figure()
    else:
        fig = ax.figure
    x = np.asarray(result.x)[1:]
    ax.plot(x * 1e3, np.asarray(result.xi)[1:], label=label)
    if len(x) > 2:
        lo, hi = np.percentile(np.asarray(result.xi)[2:], [0, 100])
        pad = 0.1 * (hi - lo) + 1e-12
        ax.set_ylim(lo - pad, hi + pad)
    ax.set_xlabel("travel x [mm]")
    ax.set_ylabel("longitudinal creepage ξ [-]")
    if label:
        ax.legend()
    finish(fig, path, title)
    return fig


def plot_centreline(result, *, xs=None, path=None, title=None):
    """Traction px [MPa] along the grid row through y = 0, one curve per stored step.

    ``xs`` : travels [m] to draw (nearest stored steps); default about six
    evenly spread frames. Curves are drawn at their position along the rail
    (grid x plus travel), as in Baeza et al.'s Fig. 7.
    """
    fig, ax = new_figure()
    g = result.grid
    j = int(np.argmin(np.abs(g.y)))
    frames = result.frame_x
    if xs is None:
        ks = np.unique(np.linspace(0, len(frames) - 1, min(6, len(frames))).round().astype(int))
    else:
        ks = [int(np.argmin(np.abs(frames - x))) for x in np.atleast_1d(xs)]
    xg = np.asarray(g.X)[:, j]  # element centres along x (per strip for Paul–Hashemi)
    for k in ks:
        ax.plot((xg + frames[k]) * 1e3, result.px[k][:, j] / 1e6,
                label=f"x = {frames[k] * 1e3:.2f} mm")
    ax.set_xlabel("position along the rail x1 [mm]")
    ax.set_ylabel("longitudinal traction px(x1, 0) [MPa]")
    ax.legend(fontsize="small")
    finish(fig, path, title)
    return fig


def plot_state(result, x, *, path=None, title=None):
    """Adhesion (light) and slip (dark) elements at the stored step nearest travel ``x`` [m]."""
    fig, ax = new_figure()
    k = int(np.argmin(np.abs(result.frame_x - x)))
    g = result.grid
    if hasattr(g, "bounds"):
        x0, x1, y0, y1 = g.bounds
        img = ax.imshow(np.asarray(result.state[k]).T, origin="lower", cmap="Greys", vmin=0,
                        vmax=2, extent=(x0 * 1e3, x1 * 1e3, y0 * 1e3, y1 * 1e3), aspect="auto")
    else:  # Paul–Hashemi strips: one marker per element centre
        img = ax.scatter(np.asarray(g.X).ravel() * 1e3, np.asarray(g.Y).ravel() * 1e3,
                         c=np.asarray(result.state[k]).ravel(), cmap="Greys", vmin=0, vmax=2,
                         marker="s", s=12, edgecolors="0.6", linewidths=0.3)
    cb = fig.colorbar(img, ax=ax, ticks=[0, 1, 2])
    cb.ax.set_yticklabels(["out", "adhesion", "slip"])
    ax.set_xlabel("x [mm] (rolling direction →)")
    ax.set_ylabel("y [mm]")
    ax.set_title(f"x = {result.frame_x[k] * 1e3:.2f} mm", fontsize="small")
    finish(fig, path, title)
    return fig
