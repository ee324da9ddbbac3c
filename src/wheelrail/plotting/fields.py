"""Contact-patch fields: tangential traction with adhesion/slip areas, normal pressure."""

from __future__ import annotations

import numpy as np

from ._common import finish, new_figure
from ._fields import field_arrays

__all__ = ["traction_field", "pressure_map"]


def _ellipse(ax, a, b, **kw):
    t = np.linspace(0.0, 2.0 * np.pi, 200)
    ax.plot(1e3 * a * np.cos(t), 1e3 * b * np.sin(t), **kw)


def _cell_mesh(ax, x, y, values, **kw):
    """Draw each grid cell as a rectangle coloured by ``values`` (NaN cells are left out).

    Works for rectilinear grids and for FASTSIM's strip grids, where every
    strip has its own element length; the cell size is the local spacing of
    the centres.
    """
    from matplotlib.collections import PolyCollection

    wx = np.abs(np.gradient(x, axis=0)) if x.shape[0] > 1 else np.full(x.shape, 1.0)
    wy = np.abs(np.gradient(y, axis=1)) if y.shape[1] > 1 else np.full(y.shape, 1.0)
    keep = np.isfinite(values)
    xc, yc, hx, hy = x[keep], y[keep], 0.5 * wx[keep], 0.5 * wy[keep]
    verts = np.stack([np.stack([xc - hx, yc - hy], -1), np.stack([xc + hx, yc - hy], -1),
                      np.stack([xc + hx, yc + hy], -1), np.stack([xc - hx, yc + hy], -1)], axis=1)
    coll = PolyCollection(verts, array=values[keep], edgecolors="face", linewidths=0.2, **kw)
    ax.add_collection(coll)
    if xc.size:
        ax.set_xlim(float(np.min(xc - hx)), float(np.max(xc + hx)))
        ax.set_ylim(float(np.min(yc - hy)), float(np.max(yc + hy)))
    return coll


def traction_field(result_fields, *, mu=None, contact=None, path=None, title=None, arrows=12):
    """Tangential traction, adhesion/slip areas and the centre-line traction.

    Parameters
    ----------
    result_fields : mapping, xarray.Dataset or object
        ``CreepForcesResult.fields`` of FASTSIM or the exact theory: grid
        coordinates ``x``, ``y`` [m], tractions ``px``, ``py`` [Pa] on the
        wheel and, if available, pressure ``p`` [Pa] and an adhesion/slip mask
        (see :func:`wheelrail.plotting.field_arrays` for the names understood).
    mu : float, optional
        Friction coefficient: draws the traction bound μ p on the centre line.
    contact : HertzContact, optional
        Draws the contact ellipse.
    path, title : optional
        Output file and figure title.
    arrows : int
        About this many traction arrows along each axis.

    Returns
    -------
    matplotlib.figure.Figure
    """
    f = field_arrays(result_fields)
    if f is None:
        raise ValueError("these fields hold no tangential traction grid (px, py) to plot")
    x, y = 1e3 * f["x"], 1e3 * f["y"]
    pt = np.hypot(f["px"], f["py"])
    inside = f["inside"] if f["inside"] is not None else pt > 0
    fig, axes = new_figure(1, 3, size=(15.5, 4.4))
    ax0, ax1, ax2 = axes

    m = _cell_mesh(ax0, x, y, np.where(inside, pt / 1e6, np.nan), cmap="viridis")
    fig.colorbar(m, ax=ax0, label="|traction| [MPa]")
    sx = max(1, x.shape[0] // arrows)
    sy = max(1, x.shape[1] // arrows)
    sl = (slice(None, None, sx), slice(None, None, sy))
    ax0.quiver(x[sl], y[sl], np.where(inside, f["px"], 0)[sl], np.where(inside, f["py"], 0)[sl],
               color="white", scale_units="xy", angles="xy", width=0.004)
    ax0.set_title("tangential traction on the wheel")

    if f["adhesion"] is not None:
        state = np.where(inside, np.where(f["adhesion"], 1.0, 2.0), np.nan)
        m1 = _cell_mesh(ax1, x, y, state, cmap="coolwarm")
        m1.set_clim(0.5, 2.5)
        ax1.set_title("adhesion (blue) / slip (red)")
    elif f["p"] is not None and mu is not None:
        ratio = np.where(inside & (f["p"] > 0), pt / (mu * np.where(f["p"] > 0, f["p"], 1.0)),
                         np.nan)
        m1 = _cell_mesh(ax1, x, y, ratio, cmap="coolwarm")
        m1.set_clim(0.0, 1.0)
        fig.colorbar(m1, ax=ax1, label="|traction| / (μ p) [-]")
        ax1.set_title("traction utilisation (1 = slip)")
    else:
        ax1.text(0.5, 0.5, "no adhesion/slip data", ha="center", va="center",
                 transform=ax1.transAxes)
    for ax in (ax0, ax1):
        ax.set_xlabel("x [mm] (rolling direction)")
        ax.set_ylabel("y [mm]")
        ax.set_aspect("equal")
        if contact is not None:
            _ellipse(ax, contact.a, contact.b, color="k", lw=0.8)

    j = int(np.argmin(np.abs(f["y"][0, :]))) if f["y"].shape[1] > 1 else 0
    xc = x[:, j]
    ax2.plot(xc, f["px"][:, j] / 1e6, label="px")
    ax2.plot(xc, f["py"][:, j] / 1e6, label="py")
    if f["p"] is not None and mu is not None:
        bound = mu * f["p"][:, j] / 1e6
        ax2.plot(xc, bound, color="0.5", ls="--", label="±μ p")
        ax2.plot(xc, -bound, color="0.5", ls="--")
    ax2.set_xlabel("x [mm]")
    ax2.set_ylabel("traction [MPa]")
    ax2.set_title(f"centre line y = {f['y'][0, j] * 1e3:.2g} mm")
    ax2.grid(True, alpha=0.3)
    ax2.legend(fontsize="small")
    return finish(fig, path, title)


def pressure_map(contact=None, *, x=None, y=None, p=None, path=None, title=None, n=121):
    """Normal pressure in the contact plane.

    Parameters
    ----------
    contact : HertzContact, optional
        A single Hertz contact: its elliptic pressure p0 √(1 − (x/a)² − (y/b)²).
    x, y : array_like, optional
        Grid coordinates [m] (1-D axes or 2-D, indexed ``[i_x, i_y]``), with
    p : array_like, optional
        the pressure [Pa] on that grid (e.g. a boundary-element solution).
    n : int
        Points per axis for the Hertz map.

    Returns
    -------
    matplotlib.figure.Figure
    """
    if p is None:
        if contact is None:
            raise ValueError("pressure_map needs a HertzContact or x, y and p")
        a, b = float(contact.a), float(contact.b)
        x, y = np.meshgrid(np.linspace(-1.15 * a, 1.15 * a, n), np.linspace(-1.15 * b, 1.15 * b, n),
                           indexing="ij")
        p = contact.pressure(x, y)
    else:
        p = np.asarray(p, dtype=float)
        x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
        if x.ndim == 1 and y.ndim == 1:
            x, y = np.meshgrid(x, y, indexing="ij")
        if x.shape != p.shape or y.shape != p.shape:
            raise ValueError(f"x, y and p must describe one grid, got shapes {x.shape}, "
                             f"{y.shape}, {p.shape}")
    fig, ax = new_figure(size=(6.5, 4.8))
    levels = np.linspace(0.0, max(float(np.max(p)), 1.0) / 1e6, 13)
    cs = ax.contourf(1e3 * x, 1e3 * y, p / 1e6, levels=levels, cmap="magma")
    fig.colorbar(cs, ax=ax, label="pressure [MPa]")
    if contact is not None:
        _ellipse(ax, float(contact.a), float(contact.b), color="w", lw=1.0)
    ax.set_xlabel("x [mm] (rolling direction)")
    ax.set_ylabel("y [mm]")
    ax.set_aspect("equal")
    ax.set_title(f"p_max = {np.max(p) / 1e6:.0f} MPa")
    return finish(fig, path, title)
