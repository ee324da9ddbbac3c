"""Figures of FE results in the manner of Toumi, Chollet & Yin (2016), Figs. 2-12 (matplotlib; a leaf module)."""

from __future__ import annotations

import numpy as np

__all__ = ["plot_patch", "plot_history", "plot_patch_comparison", "plot_creep_curves", "plot_passes",
           "plot_section", "plot_surface", "plot_transition", "plot_wave"]


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
    """Forces and energies over the travel (Toumi, Chollet & Yin 2016, Fig. 7)."""
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


def _figure(path):
    import matplotlib

    if path is not None:
        matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    return plt


def plot_patch_comparison(elastic, plastic, mu: float, path=None, title=None):
    """Pressure and |q|/(μp) of an elastic and an elasto-plastic patch side by side (in the
    manner of Toumi, Chollet & Yin 2016, Figs. 5, 6, 10, 11).

    Parameters
    ----------
    elastic, plastic : xarray.Dataset
        ``RollingResult.patch`` of the two runs.
    mu : float
        Friction coefficient [-].
    path : str or Path, optional
        Save the figure there.
    title : str, optional
        A title over the whole figure (e.g. the mesh size and the yield stress).
    """
    plt = _figure(path)
    fig, ax = plt.subplots(2, 3, figsize=(15, 8.5))
    if title:
        fig.suptitle(title)
    pmax = max(float(elastic.pressure.max()), float(plastic.pressure.max())) / 1e6
    for row, (name, patch) in enumerate((("elastic", elastic), ("elasto-plastic", plastic))):
        x = patch.x.values * 1e3
        y = patch.y.values * 1e3
        p = patch.pressure.values
        on = p > 0
        i0, i1 = np.flatnonzero(on.any(1))[[0, -1]]
        j0, j1 = np.flatnonzero(on.any(0))[[0, -1]]
        sl = (slice(max(i0 - 2, 0), i1 + 3), slice(max(j0 - 2, 0), j1 + 3))
        X, Y = np.meshgrid(x[sl[0]], y[sl[1]], indexing="ij")
        cs = ax[row, 0].contourf(X, Y, p[sl] / 1e6, np.linspace(0, pmax, 21), cmap="viridis")
        fig.colorbar(cs, ax=ax[row, 0], label="pressure [MPa]")
        ax[row, 0].set_title(f"{name}: pressure, max {p.max() / 1e6:.0f} MPa")
        q = patch.shear.values
        ratio = np.where(p > 0, q / np.maximum(mu * p, 1e-300), np.nan)
        cs = ax[row, 1].contourf(X, Y, ratio[sl], np.linspace(0, 1, 11), cmap="magma")
        fig.colorbar(cs, ax=ax[row, 1], label="|q| / (μ p)")
        st = patch.status.values[sl]
        ax[row, 1].plot(X[st == 1], Y[st == 1], "c.", ms=3, label="stick")
        ax[row, 1].legend(loc="upper right", fontsize=8)
        ax[row, 1].set_title(f"{name}: traction bound, max |q| {q.max() / 1e6:.0f} MPa, "
                             f"stick {patch.attrs['adhesion_fraction']:.0%}")
        qx, qy = patch.shear_x.values[sl], patch.shear_y.values[sl]
        ax[row, 2].quiver(X, Y, qx, qy)
        ax[row, 2].set_title(f"{name}: shear traction vectors")
        for a in ax[row]:
            a.set_xlabel("x [mm] (rolling)")
            a.set_ylabel("y [mm]")
            a.set_aspect("equal")
    fig.tight_layout()
    if path is not None:
        fig.savefig(path, dpi=110)
    return fig


def plot_creep_curves(curves: dict, path=None, reference=None):
    """Creep curves (Toumi et al. 2016, Figs. 8 and 12): force over the creepage shifted by
    each curve's offset.

    Parameters
    ----------
    curves : dict of str to xarray.Dataset
        Label to :func:`wheelrail.fe.creep_curve` result.
    reference : (array, array), optional
        Creepages and forces of a reference curve (e.g. the exact half-space theory).
    """
    plt = _figure(path)
    fig, ax = plt.subplots(figsize=(7, 5))
    comp = None
    for label, ds in curves.items():
        f = ds.attrs["force"]
        comp = ds.attrs["component"]
        ax.errorbar(ds.shifted_creepage.values * 1e3, ds[f].values / 1e3,
                    yerr=ds[f"{f}_std"].values / 1e3, marker="o", capsize=3,
                    label=f"{label} (slope {ds.attrs['slope'] / 1e6:.2f} MN, offset "
                          f"{ds.attrs['offset'] * 1e3:+.3f} ‰)")
    if reference is not None:
        ax.plot(np.asarray(reference[0]) * 1e3, np.asarray(reference[1]) / 1e3, "k--",
                label="exact half-space theory")
    ax.axhline(0, color="0.7", lw=0.8)
    ax.axvline(0, color="0.7", lw=0.8)
    ax.set_xlabel(f"{'ξ' if comp == 'xi' else 'η'} − offset [‰]")
    ax.set_ylabel(f"{'Fx' if comp == 'xi' else 'Fy (contact plane)'} [kN]")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    if path is not None:
        fig.savefig(path, dpi=110)
    return fig


def plot_passes(passes, path=None):
    """Depth profiles of the residual stress and the equivalent plastic strain after each
    pass (``RollingResult.passes``)."""
    plt = _figure(path)
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.5))
    d = passes.depth.values * 1e3
    for k in range(passes.sizes["pass"]):
        sel = passes.isel(**{"pass": k})
        lab = f"pass {int(passes['pass'][k])}"
        ax[0].plot(sel.equivalent_plastic_strain.values, d, "o-", ms=3, label=lab)
        ax[1].plot(sel.residual_stress.sel(component="xx").values / 1e6, d, "o-", ms=3, label=lab)
        ax[2].plot(sel.residual_stress.sel(component="xz").values / 1e6, d, "o-", ms=3, label=lab)
    for a, t in zip(ax, ("equivalent plastic strain [-]", "residual σ_xx [MPa]",
                         "residual τ_xz [MPa]")):
        a.set_xlabel(t)
        a.set_ylabel("depth [mm]")
        a.invert_yaxis()
        a.grid(alpha=0.3)
        a.legend(fontsize=8)
    fig.tight_layout()
    if path is not None:
        fig.savefig(path, dpi=110)
    return fig


def plot_section(fields, quantity="rail_von_mises", y=0.0, path=None, depth_max=None,
                 title=None):
    """A longitudinal section (x, depth) of an element field of the rail (Toumi et al. 2016,
    Figs. 2 and 9): ``rail_von_mises`` [Pa], ``rail_equivalent_plastic_strain`` or a stress
    component ``rail_stress:xx``; ``title`` over the figure."""
    plt = _figure(path)
    name, _, comp = quantity.partition(":")
    da = fields[name].sel(y=y, method="nearest")
    if comp:
        da = da.sel(component=comp)
    if depth_max is not None:
        da = da.sel(depth=slice(0, depth_max))
    scale, unit = (1e-6, "MPa") if da.attrs.get("units") == "Pa" else (1.0, "-")
    fig, ax = plt.subplots(figsize=(11, 3.5))
    X, D = np.meshgrid(da.x.values * 1e3, da.depth.values * 1e3, indexing="ij")
    cs = ax.pcolormesh(X, D, da.values * scale, shading="nearest", cmap="jet")
    fig.colorbar(cs, ax=ax, label=f"{quantity} [{unit}]")
    ax.invert_yaxis()
    ax.set_xlabel("x [mm] (rail)")
    ax.set_ylabel("depth [mm]")
    if title:
        ax.set_title(title)
    fig.tight_layout()
    if path is not None:
        fig.savefig(path, dpi=110)
    return fig


def plot_surface(fields, quantity="rail_von_mises", y_section=None, path=None, depth_max=None,
                 yield_stress=None):
    """The rail's running surface seen from above and a longitudinal section below it
    (Toumi, Chollet & Yin 2016, Fig. 9: von Mises stress at the rail surface during rolling,
    the loaded patch ahead and the residual field behind).

    Parameters
    ----------
    fields : xarray.Dataset
        ``RollingResult.fields`` of a plastic run (element centres; the contact is at
        x = travel at the end of the run).
    quantity : str
        ``rail_von_mises`` [Pa], ``rail_equivalent_plastic_strain`` or ``rail_stress:xx``
        (a component).
    y_section : float, optional
        Lateral position of the section [m] (default: the y of the field's maximum).
    depth_max : float, optional
        Deepest layer drawn in the section [m].
    yield_stress : float, optional
        Drawn as a contour line on stress maps [Pa].
    """
    plt = _figure(path)
    name, _, comp = quantity.partition(":")
    da = fields[name]
    if comp:
        da = da.sel(component=comp)
    scale, unit = (1e-6, "MPa") if da.attrs.get("units") == "Pa" else (1.0, "-")
    top = da.isel(depth=0)
    if y_section is None:
        k = np.unravel_index(int(np.nanargmax(np.abs(da.values))), da.shape)
        y_section = float(da.y[k[1]])
    sec = da.sel(y=y_section, method="nearest")
    if depth_max is not None:
        sec = sec.sel(depth=slice(0, depth_max))
    vmax = float(np.nanmax(np.abs(da.values))) * scale
    vmin = -vmax if float(np.nanmin(da.values)) < 0 else 0.0
    fig, ax = plt.subplots(2, 1, figsize=(11, 6.5))
    X, Y = np.meshgrid(top.x.values * 1e3, top.y.values * 1e3, indexing="ij")
    cs = ax[0].pcolormesh(X, Y, top.values * scale, shading="nearest", cmap="jet", vmin=vmin,
                          vmax=vmax)
    fig.colorbar(cs, ax=ax[0], label=f"{quantity} [{unit}]")
    if yield_stress is not None and unit == "MPa":
        ax[0].contour(X, Y, top.values, [yield_stress], colors="w", linewidths=0.8)
    ax[0].axhline(y_section * 1e3, color="w", ls="--", lw=0.7)
    ax[0].set_title(f"top element layer (depth {float(top.depth) * 1e3:.2f} mm)")
    ax[0].set_xlabel("x [mm] (rail; rolling towards +x)")
    ax[0].set_ylabel("y [mm]")
    X, D = np.meshgrid(sec.x.values * 1e3, sec.depth.values * 1e3, indexing="ij")
    cs = ax[1].pcolormesh(X, D, sec.values * scale, shading="nearest", cmap="jet", vmin=vmin,
                          vmax=vmax)
    fig.colorbar(cs, ax=ax[1], label=f"{quantity} [{unit}]")
    ax[1].invert_yaxis()
    ax[1].set_title(f"section at y = {y_section * 1e3:.1f} mm")
    ax[1].set_xlabel("x [mm] (rail)")
    ax[1].set_ylabel("depth [mm]")
    fig.tight_layout()
    if path is not None:
        fig.savefig(path, dpi=110)
    return fig


def plot_transition(patches, history=None, path=None, title=None):
    """Per-patch histories of a one- to two-point contact transition over the travel:
    normal, lateral and longitudinal force of the tread (patch 1) and flange (patch 2)
    patches (in the manner of Fig. 4 of the explicit FE transition studies), the shear
    direction θ (Fig. 7, bottom row), the adhering fraction of each patch and the contact
    angles.

    Parameters
    ----------
    patches : xarray.Dataset
        ``TransitionResult.patches``.
    history : xarray.Dataset, optional
        ``TransitionResult.history``: the total vertical contact force is drawn beside Fz.
    path : str or Path, optional
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    plt = _figure(path)
    d = patches.travel.values * 1e3
    fig, ax = plt.subplots(2, 3, figsize=(14, 7), sharex=True)
    names = {1: "patch 1 (tread)", 2: "patch 2 (flange)"}
    for p, nm in names.items():
        row = patches.sel(patch=p)
        on = row.Fn.values > 0
        for a, key, lab in ((ax[0, 0], "Fn", "normal force"), (ax[0, 1], "F_lat", "lateral force"),
                            (ax[0, 2], "F_long", "longitudinal force")):
            a.plot(d[on], row[key].values[on] / 1e3, ".-", ms=3, label=nm)
            a.set_ylabel(f"{lab} on the wheel [kN]")
        ax[1, 0].plot(d[on], np.degrees(row.theta.values[on]), ".-", ms=3, label=nm)
        ax[1, 1].plot(d[on], row.adhesion.values[on], ".-", ms=3, label=nm)
        ax[1, 2].plot(d[on], np.degrees(row.contact_angle.values[on]), ".-", ms=3, label=nm)
    if history is not None:
        ax[0, 0].plot(history.travel.values * 1e3, history.Fz_total.values / 1e3, "k-", lw=0.8,
                      label="Σ Fz (all patches)")
    ax[1, 0].set_ylabel("θ: shear on the rail against −x [deg]")
    ax[1, 1].set_ylabel("adhering fraction of the area")
    ax[1, 2].set_ylabel("contact angle [deg]")
    for a in ax.ravel():
        a.grid(alpha=0.3)
        a.legend(fontsize=8)
    for a in ax[1]:
        a.set_xlabel("travel [mm]")
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    if path is not None:
        fig.savefig(path, dpi=120)
    return fig


def plot_wave(wave, fit=None, path=None):
    """Space–time map of the rail surface's vertical velocity along the line through the
    start contact, with the fitted arrival line (surface wave speed).

    Parameters
    ----------
    wave : dict
        ``TransitionResult.info["wave"]``.
    fit : dict, optional
        :func:`wheelrail.fe.transition.analysis.wave_speed` of it.
    path : str or Path, optional
    """
    plt = _figure(path)
    fig, ax = plt.subplots(figsize=(7, 5))
    vz = np.asarray(wave["vz"])
    lim = np.percentile(np.abs(vz), 99.5) or 1.0
    ax.pcolormesh(wave["x"] * 1e3, wave["t"] * 1e6, vz, cmap="RdBu_r", vmin=-lim, vmax=lim,
                  shading="nearest")
    if fit is not None:
        ax.plot(fit["d"] * 1e3, fit["t_arrival"] * 1e6, "k.", ms=4, label="arrival of max |v_z|")
        tt = np.linspace(0, wave["t"][-1], 10)
        ax.plot(fit["speed"] * tt * 1e3, tt * 1e6, "k--", lw=0.8,
                label=f"{fit['speed'] / 1e3:.2f} km/s")
        ax.legend()
    ax.set_xlabel("distance along the rail from the start contact [mm]")
    ax.set_ylabel("time [µs]")
    ax.set_title("rail surface vertical velocity")
    fig.tight_layout()
    if path is not None:
        fig.savefig(path, dpi=120)
    return fig


def _onset_outputs(fields, n_before=4, n_after=4):
    """Indices of the outputs around the first one with a flange patch (patch 2)."""
    has2 = (fields.patch.values == 2).any(axis=(1, 2))
    k = int(np.argmax(has2)) if has2.any() else fields.sizes["time"] // 2
    return list(range(max(0, k - n_before), min(fields.sizes["time"], k + n_after)))


def _patch_local(fields, i, p):
    """Patch ``p`` at output ``i`` in its own frame: the block of the surface grid around it
    (one node of margin), coordinates along the rail and across the patch in its tangent
    plane [m] (centre: pressure-weighted), the lateral unit vector and the patch mask."""
    lab = fields.patch.values[i]
    sel = lab == p
    if not sel.any():
        return None
    r_, c_ = np.nonzero(sel)
    rs = slice(max(0, r_.min() - 1), r_.max() + 2)
    cs = slice(max(0, c_.min() - 1), c_.max() + 2)
    w = (fields.pressure.values[i] * fields.area.values[i])[sel]
    w = w if w.sum() > 0 else np.ones_like(w)
    phi = float(np.sum(w * fields.contact_angle.values[i][sel]) / w.sum())
    X, Y, Z = (fields[k].values[i] for k in ("x", "y", "z"))
    xc, yc, zc = (float(np.sum(w * V[sel]) / w.sum()) for V in (X, Y, Z))
    e_lat = np.array([0.0, np.cos(phi), np.sin(phi)])
    eta = (Y - yc) * e_lat[1] + (Z - zc) * e_lat[2]
    return {"rs": rs, "cs": cs, "xi": (X - xc)[rs, cs], "eta": eta[rs, cs], "e_lat": e_lat,
            "mask": sel[rs, cs], "phi": phi}


def plot_contact_fields(fields, outputs=None, kind="stress", mu=None, path=None, title=None):
    """Maps of the contact's surface fields of a transition run for a few outputs, tread
    patch (left) and flange patch (right), each in its own tangent plane (along the rail ×
    across the patch), in the manner of Figs. 5–6 (pressure and surface shear) and 11–12
    (micro-slip) of the explicit FE transition study.

    Parameters
    ----------
    fields : xarray.Dataset
        ``TransitionResult.contact_fields``.
    outputs : list of int, optional
        Output indices (default: four before and four from the first flange patch).
    kind : {"stress", "slip", "line"}
        ``"stress"``: pressure (colour, interpolated between the nodes), the shear stress on
        the rail (arrows, common scale), adhering nodes (black dots; tolerance definition);
        ``"slip"``: the normal relative velocity (colour; negative: approaching) and the
        micro-slip of the wheel against the rail (arrows); ``"line"``: μ·p and |q| along
        the rail on the patch's most loaded row of nodes across the profile (adhesion where
        the two curves part; Figs. 9–10 of the study; needs ``mu``).
    mu : float, optional
        Friction coefficient (for ``kind="line"``).
    path : str or Path, optional
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    if kind not in ("stress", "slip", "line"):
        raise ValueError(f"kind must be 'stress', 'slip' or 'line', got {kind!r}")
    if kind == "line" and mu is None:
        raise ValueError("kind='line' needs mu")
    plt = _figure(path)
    outputs = list(outputs) if outputs is not None else _onset_outputs(fields)
    n = len(outputs)
    fig, ax = plt.subplots(n, 2, figsize=(10, 2.2 * n + 0.8), squeeze=False,
                           layout="constrained")
    s = fields.travel.values
    clabel, cmap = {"stress": ("pressure [MPa]", "viridis"),
                     "slip": ("normal relative velocity [m/s]", "coolwarm"),
                     "line": ("", "")}[kind]
    cval = (fields.pressure.values / 1e6 if kind == "stress"
            else fields.normal_velocity.values)
    sub = np.array(outputs)
    if kind != "line":
        vmax = float(np.nanmax(np.abs(cval[sub]))) or 1.0
        vmin = 0.0 if kind == "stress" else -vmax
        if kind == "stress":
            vec = np.stack([fields[f"traction_{c}"].values for c in "xyz"], -1) / 1e6
        else:
            vec = np.stack([fields[f"slip_{c}"].values for c in "xyz"], -1)
        vscale = float(np.nanmax(np.linalg.norm(vec[sub], axis=-1))) or 1.0
    mesh = None
    for r, i in enumerate(outputs):
        for col, p in enumerate((1, 2)):
            a = ax[r, col]
            loc = _patch_local(fields, i, p)
            name = "tread" if p == 1 else "flange"
            if loc is None:
                a.text(0.5, 0.5, f"no {name} patch", ha="center", va="center",
                       transform=a.transAxes)
                a.set_xticks([])
                a.set_yticks([])
                a.set_title(f"{s[i] * 1e3:.1f} mm", fontsize=8)
                continue
            rs, cs, m_ = loc["rs"], loc["cs"], loc["mask"]
            xi, eta = loc["xi"] * 1e3, loc["eta"] * 1e3
            st = fields.state.values[i][rs, cs]
            if kind == "line":
                P = fields.pressure.values[i][rs, cs] / 1e6
                Q = np.linalg.norm(np.stack([fields[f"traction_{c}"].values[i][rs, cs]
                                             for c in "xyz"], -1), axis=-1) / 1e6
                j = int(np.argmax((P * m_).sum(axis=0)))
                o = np.argsort(xi[:, j])
                a.plot(xi[o, j], mu * P[o, j], "o-", ms=3, label="μ·p")
                a.plot(xi[o, j], Q[o, j], "s--", ms=3, label="|q|")
                adh = st[o, j] == 2
                a.plot(xi[o, j][adh], Q[o, j][adh], "k.", ms=8, label="adhesion")
                a.set_ylabel("stress [MPa]", fontsize=8)
                if r == 0:
                    a.legend(fontsize=7)
            else:
                mesh = a.pcolormesh(xi, eta, cval[i][rs, cs],
                                    shading="gouraud", cmap=cmap, vmin=vmin, vmax=vmax)
                v = vec[i][rs, cs]
                vl = (v[..., 0], v @ loc["e_lat"])
                a.quiver(xi[m_], eta[m_], vl[0][m_], vl[1][m_], color="r", angles="xy",
                         scale_units="xy", scale=vscale / 4.0, width=0.006)
                if kind == "stress":
                    adh = m_ & (st == 2)
                    a.plot(xi[adh], eta[adh], "k.", ms=6)
                a.set_aspect("equal")
                a.set_ylabel("across [mm]", fontsize=8)
            sel = fields.patch.values[i] == p
            A = fields.area.values[i][sel]
            Fn = float(np.sum(fields.pressure.values[i][sel] * A))
            Ft = np.array([np.sum(fields[f"traction_{c}"].values[i][sel] * A) for c in "xyz"])
            th = np.degrees(np.arccos(np.clip(-Ft[0] / max(np.linalg.norm(Ft), 1e-300), -1, 1)))
            a.set_title(f"{s[i] * 1e3:.1f} mm, {name} at {np.degrees(loc['phi']):.0f}°: "
                        f"Fn {Fn / 1e3:.1f} kN, θ {th:.0f}°", fontsize=8)
            a.tick_params(labelsize=7)
            if r == n - 1:
                a.set_xlabel("along the rail [mm]", fontsize=8)
    if mesh is not None:
        fig.colorbar(mesh, ax=ax, shrink=0.5, label=clabel)
    sup = {"stress": "pressure (colour), shear stress on the rail (arrows), adhesion (dots)",
           "slip": "normal relative velocity (colour), micro-slip of the wheel (arrows)",
           "line": "μ·p and |q| along the rail"}[kind]
    fig.suptitle((title + ": " if title else "") + sup, fontsize=9)
    if path:
        fig.savefig(path, dpi=110)
    return fig
