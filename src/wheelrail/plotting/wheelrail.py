"""Figures of the wheel–rail contact module: profiles in contact, adhesion/slip maps, sweeps.

* :func:`contact_profiles` — wheel and rail profiles of both sides at the
  solved pose with every patch drawn on the rail head (coloured by its
  pressure), and below each side a top view of the patches' pressure on the
  rail surface (Piotrowski & Chollet (2005), figs. 1 and 13);
* :func:`adhesion_maps` — adhesion and slip areas of every patch (from the
  tangential method's fields: FASTSIM strips or the exact theory's grid);
* :func:`sweep_forces` — forces and patch positions over a lateral-shift
  sweep (the ``xarray.Dataset`` of :func:`wheelrail.wheelset_sweep`).

Coordinates in the figures are millimetres and MPa; the lateral coordinate
of a side is measured in the track's horizontal direction towards that
side's field side (the side-local frame of :meth:`wheelrail.Track.curve`).
A patch's strip at contact-plane position y (to the right) lies at
u = σ (y_track + y cos γ) on the rail (σ = +1 right, −1 left; γ the contact
angle), the drawing's projection of the inclined contact plane.

References
----------
.. [1] J. Piotrowski, H. Chollet, Wheel–rail contact models for vehicle system
   dynamics including multi-point contact, VSD 43 (2005), figs. 1 and 13.
"""

from __future__ import annotations

import numpy as np

from ..geometry.contact_search import silhouette
from ._common import finish, new_figure
from ._fields import field_arrays

__all__ = ["contact_profiles", "adhesion_maps", "sweep_forces", "patch_field_arrays"]

_SIDES = ("left", "right")
_SIGMA = {"left": -1.0, "right": 1.0}
_SIDE_COLOUR = {"left": "tab:blue", "right": "tab:red"}


def _strip_cells(patch, sigma, max_cells=16):
    """Cells of a patch's strips as (u, x, du, dx, p) arrays in the rail's side-local frame [m].

    Cells along a strip are merged (pressure averaged) to at most ``max_cells``."""
    fr = patch.frame
    cosg = np.cos(fr.contact_angle) if fr is not None else 1.0
    u0 = sigma * fr.track_y if fr is not None else 0.0
    xc = patch.cell_x() + (fr.x if fr is not None else 0.0)          # (ny, m)
    pr = patch.strip_pressure
    m = patch.cells
    step = int(np.ceil(m / max_cells))
    starts = np.arange(0, m, step)
    counts = np.diff(np.append(starts, m))
    xc = np.add.reduceat(xc, starts, axis=1) / counts
    pr = np.add.reduceat(pr, starts, axis=1) / counts
    u = u0 + sigma * patch.y * cosg                                    # (ny,)
    du = patch.dy * cosg
    dx = (patch.x_lead - patch.x_trail) / m
    U = np.broadcast_to(u[:, None], xc.shape)
    DU = np.broadcast_to(du[:, None], xc.shape)
    DX = dx[:, None] * counts[None, :]
    return U, xc, DU, DX, pr


def _rects(ax, U, X, DU, DX, P, norm, cmap):
    from matplotlib.collections import PolyCollection

    keep = (P > 0) & (DX > 0)
    u, x, hu, hx, p = (1e3 * U[keep], 1e3 * X[keep], 0.5e3 * DU[keep], 0.5e3 * DX[keep],
                       P[keep] / 1e6)
    verts = np.stack([np.stack([u - hu, x - hx], -1), np.stack([u + hu, x - hx], -1),
                      np.stack([u + hu, x + hx], -1), np.stack([u - hu, x + hx], -1)], axis=1)
    coll = PolyCollection(verts, array=p, cmap=cmap, norm=norm, edgecolors="face",
                          linewidths=0.1)
    ax.add_collection(coll)
    return coll


def contact_profiles(result, *, path=None, title=None, cmap="inferno", window=0.045):
    """Wheel and rail profiles at the solved pose, patches on the rail head in colour.

    Parameters
    ----------
    result : WheelRailResult
        From :func:`wheelrail.solve` with a :class:`wheelrail.WheelRailPosition`.
    path, title : optional
        Output file and figure title.
    cmap : str
        Colour map of the pressure.
    window : float
        Width [m] of the cross-section window around the rail head.

    Returns
    -------
    matplotlib.figure.Figure
        Top row: cross-sections of the left and right wheel on their rails
        (the wheel at its touching pose), each patch as a band along the rail
        profile coloured by the largest pressure of its strips. Bottom row:
        top view of each side's patches, pressure [MPa] over the lateral
        position on the rail (horizontal) and the rolling direction x.
    """
    from matplotlib.colors import Normalize


    pos = result.position
    ws, tr = pos.wheelset, pos.track
    pose = result.pose
    pmax = max([p.p_max for p in result.patches] + [1.0]) / 1e6
    norm = Normalize(0.0, pmax)
    fig, axes = _figure_rows((12.0, 5.4), (1.3, 1.0))
    for col, side in enumerate(_SIDES):
        sig = _SIGMA[side]
        ax, axt = axes[0, col], axes[1, col]
        wc, rc = ws.curve(side), tr.curve(side)
        s = np.linspace(wc.u_min, wc.u_max, 1500)
        p, p1 = wc.eval(s, 1)
        one = np.ones_like(s)
        z = pose.get(f"z_{side}", 0.0)
        _, Yw, Zw, _ = silhouette(s, p, p1, ws.nominal_radius, ws.e_tape, sig, pose["y"] * one,
                                  (ws.nominal_radius + z) * one, pose["roll"] * one,
                                  pose["yaw"] * one)
        ax.plot(sig * Yw * 1e3, Zw * 1e3, color="tab:blue", lw=1.2, label="wheel")
        u_r = np.linspace(rc.u_min, rc.u_max, 1200)
        z_r = rc.eval(u_r, 0)[0]
        ax.plot(u_r * 1e3, z_r * 1e3, color="k", lw=1.2, label="rail")
        patches = result.side(side)
        for k, pr in enumerate(patches):
            U, X, DU, DX, P = _strip_cells(pr.patch, sig)
            # band on the rail head: each strip coloured by its largest pressure
            from matplotlib.collections import LineCollection

            u_s = U[:, 0]
            z_s = np.interp(u_s, u_r, z_r)
            seg = np.stack([np.stack([1e3 * (u_s - 0.5 * DU[:, 0]),
                                      1e3 * np.interp(u_s - 0.5 * DU[:, 0], u_r, z_r)], -1),
                            np.stack([1e3 * (u_s + 0.5 * DU[:, 0]),
                                      1e3 * np.interp(u_s + 0.5 * DU[:, 0], u_r, z_r)], -1)],
                           axis=1)
            lc = LineCollection(seg, array=P.max(axis=1) / 1e6, cmap=cmap, norm=norm, lw=6)
            ax.add_collection(lc)
            fr = pr.patch.frame
            ax.annotate(f"{k + 1}: Fn {pr.Fn / 1e3:.1f} kN\nγ {np.degrees(pr.contact_angle):.1f}°",
                        (1e3 * sig * fr.track_y, 1e3 * float(np.max(z_s))), fontsize=7,
                        xytext=[(6, 8), (-64, 8), (6, -30)][k % 3],
                        textcoords="offset points",
                        arrowprops={"arrowstyle": "-", "lw": 0.5, "color": "0.4"})
            _rects(axt, U, X, DU, DX, P, norm, cmap)
            axt.annotate(str(k + 1), (1e3 * float(np.max(U + 0.5 * DU)), 0.0), fontsize=8,
                         xytext=(3, 0), textcoords="offset points", va="center")
        if patches:
            uc = [1e3 * sig * pr.patch.frame.track_y for pr in patches]
        else:
            uc = [1e3 * 0.5 * (rc.u_min + rc.u_max)]
        mid = 0.5 * (min(uc) + max(uc))
        half = 0.5e3 * window
        ax.set_xlim(mid - half, mid + half)
        zmid = float(np.interp(mid / 1e3, u_r, z_r)) * 1e3
        ax.set_ylim(zmid - 0.5 * half, zmid + 0.2 * half)
        ax.set_aspect("equal")
        ax.set_xlabel(f"lateral position, {side} side, towards field side [mm]")
        ax.set_ylabel("height [mm]")
        ax.set_title(f"{side} wheel: {len(patches)} patch(es), "
                     f"Q = {result.force_track[side][2] / 1e3:.1f} kN", fontsize="small")
        ax.grid(True, alpha=0.25)
        axt.set_xlim(mid - half, mid + half)
        xs = [abs(v) for pr in patches for v in (pr.patch.x_lead.max(), pr.patch.x_trail.min())]
        xm = 1e3 * 1.3 * max(xs + [0.004])
        axt.set_ylim(-xm, xm)
        axt.set_aspect("equal")
        axt.set_xlabel("lateral position on the rail [mm]")
        axt.set_ylabel("x [mm] (rolling direction)")
        axt.set_title(f"{side}: pressure on the rail surface (top view)", fontsize="small")
        axt.grid(True, alpha=0.25)
    axes[0, 0].legend(fontsize="x-small", loc="lower left")
    from matplotlib.cm import ScalarMappable

    fig.colorbar(ScalarMappable(norm=norm, cmap=cmap), ax=axes.ravel().tolist(),
                 label="pressure [MPa] (bands: largest of each strip)", shrink=0.7)
    return finish(fig, path, title or _default_title(result))


def _figure_rows(size, height_ratios):
    """A 2 × 2 figure (Agg canvas) whose rows have the given height ratios."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=size, layout="constrained")
    FigureCanvasAgg(fig)
    return fig, fig.subplots(2, 2, gridspec_kw={"height_ratios": list(height_ratios)})


def _default_title(result):
    pos = result.position
    return (f"y = {pos.y * 1e3:.2f} mm, yaw = {pos.yaw * 1e3:.2f} mrad: "
            f"{result.normal} + {result.tangential}")


def patch_field_arrays(patch_result):
    """Traction and adhesion arrays of one patch, or ``None`` (closed-form laws).

    Like :func:`wheelrail.plotting.field_arrays`; on a boundary-element grid
    shared by several patches, only the patch's elements (``patch.mask``) are
    ``inside`` and the arrays are cut to the patch's bounding box.
    """
    f = field_arrays(patch_result.forces.fields)
    if f is None:
        return None
    mask = getattr(patch_result.patch, "mask", None)
    if mask is not None and np.shape(mask) == f["x"].shape:
        inside = np.asarray(mask, bool) & (f["inside"] if f["inside"] is not None else True)
        ii, jj = np.nonzero(inside)
        if ii.size:
            sl = (slice(max(ii.min() - 1, 0), ii.max() + 2), slice(max(jj.min() - 1, 0),
                                                                    jj.max() + 2))
            f = {k: (v[sl] if isinstance(v, np.ndarray) and v.shape == inside.shape else v)
                 for k, v in f.items()}
            f["inside"] = inside[sl]
            if f.get("adhesion") is not None:
                f["adhesion"] = f["adhesion"] & f["inside"]
    return f


def adhesion_maps(result, *, path=None, title=None):
    """Adhesion (blue) and slip (red) areas of every patch, with the traction direction.

    Parameters
    ----------
    result : WheelRailResult or ContactResult
        With a tangential method that returns fields (FASTSIM, exact).
    path, title : optional

    Returns
    -------
    matplotlib.figure.Figure
        One panel per patch in the contact plane (x rolling direction, y to
        the right) [mm]; patches of a closed-form law say so instead.
    """
    from matplotlib.patches import Patch

    from .fields import _cell_mesh

    pats = result.patches
    n = max(len(pats), 1)
    ncols = min(n, 3)
    nrows = int(np.ceil(n / ncols))
    fig, axes = new_figure(nrows, ncols, size=(4.6 * ncols, 4.2 * nrows))
    axes = np.atleast_1d(axes).ravel()
    for ax, pr in zip(axes, pats):
        f = patch_field_arrays(pr)
        head = (f"{pr.side or ''} y_rail = {pr.y_rail * 1e3:.1f} mm" if pr.side else "patch")
        if f is None or f.get("adhesion") is None:
            ax.text(0.5, 0.5, f"{pr.forces.method}: no traction field\n(closed-form law)",
                    ha="center", va="center", transform=ax.transAxes)
            ax.set_title(head, fontsize="small")
            ax.set_xticks([])
            ax.set_yticks([])
            continue
        inside = f["inside"] if f["inside"] is not None else np.hypot(f["px"], f["py"]) > 0
        state = np.where(inside, np.where(f["adhesion"], 1.0, 2.0), np.nan)
        x, y = 1e3 * f["x"], 1e3 * f["y"]
        m = _cell_mesh(ax, x, y, state, cmap="coolwarm")
        m.set_clim(0.5, 2.5)
        step = (max(1, x.shape[0] // 10), max(1, x.shape[1] // 10))
        sl = (slice(None, None, step[0]), slice(None, None, step[1]))
        ax.quiver(x[sl], y[sl], np.where(inside, f["px"], 0)[sl],
                  np.where(inside, f["py"], 0)[sl], color="k", width=0.005)
        ax.set_aspect("equal")
        ax.set_xlabel("x [mm] (rolling)")
        ax.set_ylabel("y [mm] (right)")
        frac = pr.adhesion_area / pr.area if pr.area > 0 else float("nan")
        ax.set_title(f"{head}\nFn {pr.Fn / 1e3:.1f} kN, Fx {pr.Fx:.0f} N, Fs {pr.Fs:.0f} N, "
                     f"adhesion {100 * frac:.0f} %", fontsize="small")
    for ax in axes[len(pats):]:
        ax.set_visible(False)
    from matplotlib import colormaps

    cm = colormaps["coolwarm"]
    fig.legend(handles=[Patch(color=cm(0.25), label="adhesion"),
                        Patch(color=cm(0.75), label="slip")],
               loc="lower right", fontsize="small")
    if title is None and hasattr(result, "position") and result.position is not None:
        title = "adhesion/slip, " + _default_title(result)
    return finish(fig, path, title)


def _status_note(statuses) -> str:
    """"2 positions flange climb, 1 not converged": the rows of a sweep whose status is not
    ``ok``, by status (a flange climb is a result, not a failure)."""
    names, counts = np.unique(np.asarray(statuses, dtype=str), return_counts=True)
    parts = [f"{n} {name.replace('_', ' ')}" for name, n in zip(names, counts)]
    total = int(counts.sum())
    return f"{total} position{'s' if total != 1 else ''}: " + ", ".join(parts)


def sweep_forces(ds, *, path=None, title=None):
    """Forces and patch positions over a lateral-shift sweep.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`wheelrail.wheelset_sweep` (dimensions ``y``, ``side``, ``patch``).
    path, title : optional

    Returns
    -------
    matplotlib.figure.Figure
        Four panels against the lateral shift y [mm]: normal force Fn of each
        patch; creep forces Fx and Fs of each patch; the patches' positions on
        the rail profile; the track-frame lateral force F_y of each wheel.
        Colour: side; line style/marker: patch (largest Fn first).
    """
    y = 1e3 * np.asarray(ds["y"].values, float)
    fig, axes = new_figure(2, 2, size=(12.0, 8.0))
    styles = [("-", "o"), ("--", "s"), (":", "^"), ("-.", "v")]
    npatch = ds.sizes.get("patch", 1)
    for side in _SIDES:
        c = _SIDE_COLOUR[side]
        for k in range(npatch):
            ls, mk = styles[k % len(styles)]
            kw = {"color": c, "ls": ls, "marker": mk, "ms": 2.5, "lw": 1.1}

            def v(name):
                return np.asarray(ds[name].sel(side=side).isel(patch=k).values, float)

            Fn = v("Fn")
            if not np.any(np.isfinite(Fn)):
                continue
            lab = f"{side} {k + 1}"
            axes[0, 0].plot(y, Fn / 1e3, label=lab, **kw)
            axes[0, 1].plot(y, v("Fx") / 1e3, label=f"Fx {lab}", **kw)
            axes[0, 1].plot(y, v("Fs") / 1e3, label=f"Fs {lab}", alpha=0.55,
                            **{**kw, "marker": "x"})
            axes[1, 0].plot(y, 1e3 * v("y_rail"), label=lab, **kw)
        axes[1, 1].plot(y, np.asarray(ds["Fy_track"].sel(side=side).values, float) / 1e3,
                        color=c, marker="o", ms=2.5, label=f"F_y {side}")
    bad = np.asarray(ds["status"].values) != "ok" if "status" in ds else np.zeros(y.size, bool)
    for ax in axes.ravel():
        ax.set_xlabel("lateral shift y [mm]")
        ax.grid(True, alpha=0.3)
        for yb in y[bad]:
            ax.axvline(yb, color="0.6", lw=0.6, ls=":")
    axes[0, 0].set_ylabel("Fn [kN]")
    axes[0, 0].set_title("normal force per patch", fontsize="small")
    axes[0, 1].set_ylabel("creep force on the wheel [kN]")
    axes[0, 1].set_title("Fx (markers o/s) and Fs (x) per patch", fontsize="small")
    axes[1, 0].set_ylabel("position on the rail profile [mm]")
    axes[1, 0].set_title("patch positions (rail profile y, field side +)", fontsize="small")
    axes[1, 1].set_ylabel("F_y, track frame [kN]")
    axes[1, 1].set_title("lateral force on each wheel (track frame, y right)", fontsize="small")
    for ax in axes.ravel():
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize="x-small", ncol=2)
    if title is None:
        title = (f"wheelset sweep: {ds.attrs.get('normal', '')} + "
                 f"{ds.attrs.get('tangential', '')}, μ = {ds.attrs.get('mu', '')}"
                 + (f" ({_status_note(ds['status'].values[bad])}, dotted)" if bad.any() else ""))
    return finish(fig, path, title)
