"""Creep-force curves: normalised force against creepage for several methods."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from ._common import finish, new_figure

__all__ = ["creep_curves"]

_SYMBOL = {"xi": "ξ [-]", "eta": "η [-]", "phi": "φ [1/m]"}
_STYLE = {
    "linear": dict(color="0.45", ls="--", lw=1.2),
    "carter": dict(color="tab:purple", ls="-."),
    "fastsim": dict(color="tab:blue", lw=2.0),
    "shen-hedrick-elkins": dict(color="tab:orange"),
    "polach": dict(color="tab:green"),
    "fastrip": dict(color="tab:cyan", ls=(0, (4, 2))),
    "table": dict(color="tab:red", ls=":", lw=2.0),
    "exact": dict(color="black", ls="", marker="o", ms=3),
}


def creep_curves(creepage, curves: Mapping, *, component: str = "xi", force: str | None = None,
                 clip: float = 1.5, clip_methods=("linear",), ax=None, path=None, title=None):
    """Plot normalised creep force against one creepage component.

    Parameters
    ----------
    creepage : array_like, shape (n,)
        The swept creepage (ξ, η [-] or φ [1/m]).
    curves : mapping of str to array_like, shape (n,)
        Method name → force / (μ Fn) [-] (Kalker's sign convention: a positive
        creepage gives a negative force).
    component : {"xi", "eta", "phi"}
        Which creepage is swept (axis label).
    force : str, optional
        Force name for the axis label (default ``Fx`` for ξ, ``Fy`` otherwise).
    clip : float
        Curves of ``clip_methods`` (unbounded laws such as the linear theory)
        are drawn only where |force/(μFn)| ≤ ``clip``.
    ax : matplotlib Axes, optional
        Draw into these axes instead of a new figure.
    path : str or Path, optional
        Write the figure there (PNG, PDF, SVG from the suffix).
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    s = np.asarray(creepage, dtype=float)
    force = force or ("Fx" if component == "xi" else "Fy")
    if ax is None:
        fig, ax = new_figure(size=(7.5, 5.0))
    else:
        fig = ax.figure
    ymax = 0.0
    for name, values in curves.items():
        v = np.asarray(values, dtype=float)
        if v.shape != s.shape:
            raise ValueError(f"curve {name!r} has shape {v.shape}, creepage has {s.shape}")
        if name in clip_methods:
            v = np.where(np.abs(v) <= clip, v, np.nan)
        if np.any(np.isfinite(v)):
            ymax = max(ymax, float(np.nanmax(np.abs(v))))
        ax.plot(s, v, label=name, **_STYLE.get(name, {}))
    ax.axhline(0.0, color="0.8", lw=0.8)
    ax.axvline(0.0, color="0.8", lw=0.8)
    for lim in (-1.0, 1.0):
        ax.axhline(lim, color="0.6", lw=0.8, ls=":")
    ylim = min(max(ymax, 1.0), clip) * 1.08
    ax.set_ylim(-ylim, ylim)
    ax.set_xlabel(_SYMBOL.get(component, component))
    ax.set_ylabel(f"{force} / (μ Fn) [-]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize="small")
    return finish(fig, path, title)
