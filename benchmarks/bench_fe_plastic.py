"""Elasto-plastic FE rolling contact: the case of Toumi, Chollet & Yin (2016) at its Table-3 load.

Run one part at a time (each prints its figures with problem sizes, CPU times and the
machine load, and saves NetCDF / VTU / PNG files under --out):

  python benchmarks/bench_fe_plastic.py steady --mesh 2e-3            # steady forces, scatter, exact theory
  python benchmarks/bench_fe_plastic.py mass-scaling                  # scaled vs unscaled, small case
  python benchmarks/bench_fe_plastic.py table3 --mesh 2e-3            # Table 3 and the plasticity reductions
  python benchmarks/bench_fe_plastic.py creep --mesh 2e-3 --component xi   # creep curves, elastic/plastic
  python benchmarks/bench_fe_plastic.py figures --mesh 2e-3          # Figs. 9-11 (surface, patch)
  python benchmarks/bench_fe_plastic.py time-increment --mesh 3e-3    # implicit Δt sensitivity (§3)
  python benchmarks/bench_fe_plastic.py time-increment --mesh 3e-3 --material plastic  # J2 bodies
  python benchmarks/bench_fe_plastic.py linear-solvers --mesh 2e-3  # SuperLU vs PARDISO, one Newton matrix
  python benchmarks/bench_fe_plastic.py passes --mesh 2e-3 --passes 4 # repeated passes
  python benchmarks/bench_fe_plastic.py speed                         # ns/element/step, 1 and 2 threads
  python benchmarks/bench_fe_plastic.py speed --baseline /tmp/base/src  # the same, alternating with another version

Unless stated otherwise: explicit, one-point elements, mass scaling 100, kept bodies 4
semi-axes deep and 3 wide, default travel (the ramp plus 8 semi-axes).
"""

from __future__ import annotations

import argparse
import json
import os
import time
import warnings
from pathlib import Path

import numpy as np

import wheelrail as wr
from wheelrail.fe import seed000_case, solve

BODIES = dict(element="reduced", depth=4.0, half_width=3.0, half_length=3.0)


def load():
    return f"load {os.getloadavg()[0]:.1f}"


def seed(mesh, plastic=False, **kw):
    args = dict(BODIES, mesh_size=mesh, mass_scaling=100.0)
    args.update(kw)
    return seed000_case(plastic=plastic, **args)


def exact_reference(case, elements=40):
    """The exact half-space solver at the case's Hertz contact and creepage, with the geometric
    spin φ = sin δ / r_c of the cone on the inclined rail; Kalker's y is minus the FE's
    lateral tangent (η_K = −η, Fy_contact = −Fy_K)."""
    from wheelrail.fe.model import contact_geometry

    g = contact_geometry(case)
    phi = np.sin(g["delta"]) / g["r_c"]
    xi, eta, _ = case.creepage
    r = wr.creep_forces(g["hertz"], (xi, -eta, phi), case.mu, method="exact", elements=elements)
    return float(r.Fx), float(-r.Fy)


def timed(case, **kw):
    t, w = time.process_time(), time.time()
    r = solve(case, **kw)
    return r, time.process_time() - t, time.time() - w


def describe(r, cpu, wall):
    st, g = r.steady, r.model.geometry
    return (f"{r.model.n_elements} elements, {r.info['steps']} steps of {r.info['time_step']:.3g} s, "
            f"CPU {cpu:.0f} s, wall {wall:.0f} s, {load()}\n"
            f"    steady window {st['window'][0] * 1e3:.1f}-{st['window'][1] * 1e3:.1f} mm ({st['n']} "
            f"steps): Fx {st['Fx']:.1f} N (scatter {st['Fx_scatter']:.2%}), Fy_contact "
            f"{st['Fy_contact']:.1f} N ({st['Fy_contact_scatter']:.2%}), Fz {st['Fz']:.1f} N "
            f"({st['Fz'] / r.model.case.Fn - 1:+.2%} of the load, scatter {st['Fz_scatter']:.2%}),"
            f" Fn_contact {st['Fn_contact']:.1f} N ({st['Fn_contact'] / g['normal_load'] - 1:+.2%} "
            f"of load/cos δ)")


# ----------------------------------------------------------------------------- steady
def cmd_steady(a):
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    for ms in a.mass_scaling:
        case = seed(a.mesh, mass_scaling=ms)
        r, cpu, wall = timed(case, progress=True)
        ex_fx, ex_fy = exact_reference(case)
        print(f"steady rolling, elastic, mesh {a.mesh * 1e3:g} mm, mass scaling {ms:g}: "
              + describe(r, cpu, wall))
        print(f"    exact theory (40x40, spin {np.sin(np.arctan(0.1)) / 0.46:.3f} 1/m): Fx {ex_fx:.1f} N"
              f" (FE {r.Fx / ex_fx - 1:+.2%}), Fy {ex_fy:.1f} N (FE {r.Fy_contact / ex_fy - 1:+.2%})",
              flush=True)
        r.dataset.to_netcdf(out / f"steady_{a.mesh * 1e3:g}mm_ms{ms:g}.nc")


def cmd_mass_scaling(a):
    """The steady forces do not depend on the mass scaling: a small case unscaled and scaled."""
    flat = wr.Profile(np.linspace(-0.04, 0.04, 9), np.zeros(9), kind="wheel")
    for ms in (1.0, 25.0, 100.0, 400.0):
        case = wr.fe.RollingCase(wheel=flat, rail=wr.profiles.load("60E1"), radius=0.46,
                                 Fn=7500.0, mu=0.2, creepage=(7e-4, 0.0, 0.0), mesh_size=2e-3,
                                 mass_scaling=ms, travel=0.02, **BODIES)
        r, cpu, wall = timed(case, progress=False)
        print(f"cylinder on 60E1 crown, 7.5 kN, xi = 7e-4, 2 mm, mass scaling {ms:g}: "
              + describe(r, cpu, wall), flush=True)
    ref = wr.creep_forces(wr.hertz(7500.0, r.model.geometry["A"], r.model.geometry["B"],
                                   wr.Material(2.1e11, 0.28)), (7e-4, 0, 0), 0.2, method="exact",
                          elements=40)
    print(f"    exact theory (40x40): Fx {ref.Fx:.1f} N")


# ----------------------------------------------------------------------------- Table 3
SEED_TABLE3 = {"CONTACT": (6.75, 5.25, 1132), "Hertz": (6.66, 5.05, 1160),
               "Explicit Dyn": (7.25, 5.50, 1126), "Implicit QS": (7.00, 5.50, 1158),
               "Implicit MD": (7.25, 5.50, 1158)}
SEED_PLASTIC = {"p_max explicit": (1126, 987), "p_max implicit MD": (1158, 994),
                "tau_max": (210, 191), "von Mises max (plastic)": (None, 491)}


def cmd_table3(a):
    from wheelrail.fe import indent
    from wheelrail.fe.model import contact_geometry
    from wheelrail.fe.output import write_vtu
    from wheelrail.fe.plots import plot_patch_comparison

    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    case = seed(a.mesh)
    g = contact_geometry(case)
    hz = g["hertz"]
    bem = wr.solve(hz, creepage=(-7e-4, 0, 0), mu=0.2, normal="bem", tangential="fastsim",
                   element_size=2.5e-4).patches[0]
    print(f"Table 3, load {case.Fn:.1f} N vertical ({g['normal_load']:.1f} N normal), "
          f"mesh {a.mesh * 1e3:g} mm")
    print(f"  seed rows (a mm, b mm, p_max MPa): {json.dumps(SEED_TABLE3)}")
    print(f"  Hertz (this geometry): a {hz.a * 1e3:.2f}, b {hz.b * 1e3:.2f}, p0 {hz.p0 / 1e6:.0f}")
    print(f"  BEM (wr.solve normal='bem', 0.25 mm): a {bem.patch.a * 1e3:.2f}, "
          f"b {bem.patch.b * 1e3:.2f}, p_max {bem.p_max / 1e6:.0f}", flush=True)
    if a.mesh >= 1.5e-3:          # the static solve is a sparse direct one: small meshes only
        t = time.process_time()
        ri = indent(case)
        print(f"  FE indentation ({ri.model.n_elements} el., CPU {time.process_time() - t:.0f} s): "
              f"a {ri.a * 1e3:.2f}, b {ri.b * 1e3:.2f}, p_max {ri.p_max / 1e6:.0f}", flush=True)
    res = {}
    for plastic in (False, True):
        name = "plastic" if plastic else "elastic"
        r, cpu, wall = timed(seed(a.mesh, plastic=plastic, **a.extra), progress=True)
        res[name] = r
        p = r.patch
        _, vm_r = r.model.von_mises(r.u, r.state)
        print(f"  FE rolling {name}: " + describe(r, cpu, wall))
        if not plastic:
            ex_fx, ex_fy = exact_reference(r.model.case)
            print(f"    exact theory (40x40, with the geometric spin): Fx {ex_fx:.1f} N (FE "
                  f"{r.Fx / ex_fx - 1:+.2%}), Fy {ex_fy:.1f} N (FE {r.Fy_contact / ex_fy - 1:+.2%})")
        print(f"    a {r.a * 1e3:.2f}, b {r.b * 1e3:.2f}, p_max {r.p_max / 1e6:.0f} MPa, tau_max "
              f"{float(p.shear.max()) / 1e6:.0f} MPa, von Mises max (rail) {vm_r.max() / 1e6:.0f} MPa,"
              f" adhesion fraction {p.attrs['adhesion_fraction']:.2f}, pressure centre x "
              f"{p.attrs['x_centre'] * 1e3:+.2f} mm, asymmetry {asymmetry(p):+.3f}", flush=True)
        if r.fields is not None:
            f = r.fields
            print(f"    equivalent plastic strain max: rail {float(f.rail_equivalent_plastic_strain.max()):.4f},"
                  f" wheel {float(f.wheel_equivalent_plastic_strain.max()):.4f}")
            f.to_netcdf(out / f"fields_{a.mesh * 1e3:g}mm.nc")
        p.to_netcdf(out / f"patch_{name}_{a.mesh * 1e3:g}mm.nc")
        write_vtu(out / f"rolling_{name}_{a.mesh * 1e3:g}mm.vtu", r.model, r.u, state=r.state)
    e, pl = res["elastic"], res["plastic"]
    te, tp = float(e.patch.shear.max()), float(pl.patch.shear.max())
    print(f"  plasticity: p_max {pl.p_max / e.p_max - 1:+.1%} (seed -12.3 % explicit, -14.2 % "
          f"implicit MD), tau_max {tp / te - 1:+.1%} (seed -9.0 %), Fx {pl.Fx / e.Fx - 1:+.1%}")
    plot_patch_comparison(e.patch, pl.patch, 0.2, path=out / f"patch_elastic_plastic_{a.mesh * 1e3:g}mm.png")


def asymmetry(patch):
    """(x centre of the pressure − centre of the loaded extent) / a: 0 for an ellipse."""
    x = patch.x.values
    on = patch.pressure.values.max(axis=1) > 0
    mid = 0.5 * (x[on].min() + x[on].max())
    return (patch.attrs["x_centre"] - mid) / patch.attrs["a"]


# ----------------------------------------------------------------------------- creep curves
def cmd_creep(a):
    from wheelrail.fe import creep_curve

    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    warnings.simplefilter("ignore")
    values = np.array(a.creepages) * 1e-3
    curves = {}
    for plastic in {"both": (False, True), "elastic": (False,), "plastic": (True,)}[a.material]:
        name = "elastic"
        case = seed(a.mesh, plastic=plastic, **a.extra)
        if plastic:
            name, case = with_hardening(case, a.hardening)
        if a.component == "eta":
            case = case.replace(creepage=(0.0, 0.0, 0.0))
        t = time.process_time()
        stem = f"creep_{a.component}_{name}_{a.mesh * 1e3:g}mm"
        if a.per_point:                 # one file per point, a line of progress after each
            parts = []
            for v in values:
                parts.append(creep_curve(case, [v], component=a.component, progress=False,
                                         path=out / f"{stem}_{v * 1e3:+.3f}.nc"))
                d = parts[-1]
                print(f"  {time.strftime('%H:%M:%S')} {name} {a.component} {v * 1e3:+.3f} permille: "
                      f"{d.attrs['force']} {float(d[d.attrs['force']][0]):.1f} N, CPU "
                      f"{float(d.cpu_seconds[0]):.0f} s, {load()}", flush=True)
            ds = _merge_points(parts)
        else:
            ds = creep_curve(case, values, component=a.component, progress=True,
                             path=out / f"{stem}.nc")
        curves[name] = ds
        f = ds.attrs["force"]
        print(f"creep curve {a.component}, {name}, mesh {a.mesh * 1e3:g} mm, "
              f"{len(values)} points, CPU {time.process_time() - t:.0f} s, {load()}")
        for c, F, sc, cpu in zip(ds.creepage.values, ds[f].values,
                                 ds[f"{f}_scatter"].values, ds.cpu_seconds.values):
            ex = exact_reference(case.replace(creepage=(c, 0, 0) if a.component == "xi"
                                              else (0, c, 0)))
            exf = ex[0] if a.component == "xi" else ex[1]
            print(f"    {a.component} {c * 1e3:+.2f} permille: {f} {F:9.1f} N (scatter {sc:.2%}), "
                  f"exact {exf:9.1f} N, CPU {cpu:.0f} s")
        print(f"    offset {ds.attrs['offset'] * 1e3:+.4f} permille, initial slope "
              f"{ds.attrs['slope']:.4g} N ({ds.attrs['fit_points']} points)", flush=True)
    if len(curves) == 2:
        compare_creep(a, curves)


def with_hardening(case, hardening):
    """The plastic case with another hardening law (``--hardening``) and its file name:
    ``r900a`` the default Voce law (name "plastic"), ``perfect`` perfect plasticity at the
    same yield stress 489 MPa (the softest isotropic law; name "perfect"), ``kinematic`` the
    same uniaxial monotonic curve as the default law but from an Armstrong–Frederick back
    stress on a constant yield surface (C/γ = Q, γ = b of the Voce law: back stress
    Q (1 − e^(−b p)); name "kinematic")."""
    if hardening == "r900a":
        return "plastic", case
    from wheelrail.fe import r900a
    from wheelrail.fe.materials import R900A_HARDENING

    if hardening == "kinematic":
        h = R900A_HARDENING
        return hardening, case.replace(material=r900a(
            hardening=0.0, kinematic=h.saturation * h.rate, kinematic_recovery=h.rate))
    return hardening, case.replace(material=r900a(hardening=0.0))


def _merge_points(parts):
    from wheelrail.fe.curves import merge_creep_curves

    return merge_creep_curves(parts)


def compare_creep(a, curves):
    """Elastic against plastic (slope, saturation), each against the exact theory at its
    creepage shifted through the origin (creepage − offset), and the figure."""
    out = Path(a.out)
    e, p = curves["elastic"], curves["plastic"]
    case = seed(a.mesh, **a.extra)
    for name, ds in curves.items():
        f = ds.attrs["force"]
        c0 = ds.attrs["offset"]
        print(f"  {name}: offset {c0 * 1e3:+.4f} permille, slope {ds.attrs['slope']:.4g} N")
        for c, F in zip(ds.creepage.values, ds[f].values):
            cs = c - c0
            ex = exact_reference(case.replace(creepage=(cs, 0, 0) if a.component == "xi"
                                              else (0, cs, 0)))
            exf = ex[0] if a.component == "xi" else ex[1]
            print(f"    {a.component} {c * 1e3:+.3f} permille (shifted {cs * 1e3:+.4f}): {f} "
                  f"{F:9.1f} N, exact at the shifted creepage {exf:9.1f} N ({F / exf - 1:+.2%})")
    f = e.attrs["force"]
    sat = np.abs(e.creepage.values) == np.abs(e.creepage.values).max()
    print(f"  plasticity: initial slope {p.attrs['slope'] / e.attrs['slope'] - 1:+.1%} (seed: "
          f"{'-15' if a.component == 'xi' else '-13'} %), saturation (largest |creepage|) "
          f"{np.mean(p[f].values[sat] / e[f].values[sat]) - 1:+.1%} (seed: unchanged)")
    from wheelrail.fe.plots import plot_creep_curves

    plot_creep_curves(curves, path=out / f"creep_{a.component}_{a.mesh * 1e3:g}mm.png")


# ----------------------------------------------------------------------------- figures 9-11
def cmd_figures(a):
    """Figures in the manner of Toumi et al. (2016) Figs. 9-11 from one elastic and one
    elasto-plastic run of the seed case (ξ = −0.7 ‰); Fig. 12 is the ``creep`` part's."""
    from wheelrail.fe.plots import plot_patch_comparison, plot_surface

    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    warnings.simplefilter("ignore")
    runs = {}
    for plastic in (False, True):
        r, cpu, wall = timed(seed(a.mesh, plastic=plastic, **a.extra), progress=False)
        runs[plastic] = r
        print(f"{'plastic' if plastic else 'elastic'}: {describe(r, cpu, wall)}", flush=True)
    el, pl = runs[False], runs[True]
    tag = f"{a.mesh * 1e3:g}mm"
    sy = pl.model.material.yield_stress
    plot_surface(pl.fields, "rail_von_mises", y_section=pl.model.geometry["y_c"],
                 depth_max=4 * pl.a, yield_stress=sy, path=out / f"fig9_von_mises_{tag}.png")
    plot_surface(pl.fields, "rail_equivalent_plastic_strain", y_section=pl.model.geometry["y_c"],
                 depth_max=4 * pl.a, path=out / f"fig9_plastic_strain_{tag}.png")
    plot_patch_comparison(el.patch, pl.patch, el.model.case.mu,
                          path=out / f"fig10_11_patch_{tag}.png")
    vm = pl.fields.rail_von_mises
    print(f"  von Mises max (rail, end of the run) {float(vm.max()) / 1e6:.0f} MPa (yield "
          f"{sy / 1e6:.0f} MPa); max eps_p {float(pl.fields.rail_equivalent_plastic_strain.max()):.5f}"
          f"; p_max {el.p_max / 1e6:.0f} -> {pl.p_max / 1e6:.0f} MPa; max |q| "
          f"{float(el.patch.shear.max()) / 1e6:.0f} -> {float(pl.patch.shear.max()) / 1e6:.0f} MPa;"
          f" stick {el.patch.attrs['adhesion_fraction']:.0%} -> "
          f"{pl.patch.attrs['adhesion_fraction']:.0%}; figures in {out}/", flush=True)


# ----------------------------------------------------------------------------- §3 time increment
def cmd_creep_compare(a):
    """Compare creep curves written by earlier ``creep --material elastic|plastic`` runs."""
    import xarray as xr

    out = Path(a.out)
    curves = {}
    for name in ("elastic", "plastic"):      # one file per curve, or per point (--per-point)
        stem = name if name == "elastic" or a.hardening == "r900a" else a.hardening
        files = sorted(out.glob(f"creep_{a.component}_{stem}_{a.mesh * 1e3:g}mm*.nc"))
        curves[name] = _merge_points([xr.load_dataset(f) for f in files])
    warnings.simplefilter("ignore")
    compare_creep(a, curves)


def _time_increment_plastic(a):
    """time-increment: elasto-plastic (R900A) with ``--material plastic`` (or ``--extra
    '{"plastic": true}'``), else elastic."""
    return a.material == "plastic" or bool(a.extra.get("plastic"))


def cmd_time_increment(a):
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    warnings.simplefilter("ignore")
    V = 50 / 3.6
    plastic = _time_increment_plastic(a)
    extra = {k: v for k, v in a.extra.items() if k != "plastic"}
    for dt in a.dts:
        k = dt / (a.mesh / (2 * V))
        case = seed(a.mesh, plastic=plastic, integrator="implicit-hht", mass_scaling=1.0,
                    time_step=dt, travel=a.travel, **extra)
        r, cpu, wall = timed(case, progress=True)
        p = r.patch
        _, vm_r = r.model.von_mises(r.u, r.state)
        amp, wl, wx, wz = rear_waves(r, profile=True)
        row = dict(dt=dt, Fx=r.Fx, p_max=r.p_max, tau=float(p.shear.max()), vm=float(vm_r.max()),
                   a=r.a, b=r.b, waves=amp, wavelength=wl)
        if plastic and r.fields is not None:
            row["eps_p"] = float(r.fields.rail_equivalent_plastic_strain.max())
        print(f"implicit HHT, {'elasto-plastic' if plastic else 'elastic'}, dt = {dt:.3g} s "
              f"({k:g} x h/(2V)): " + describe(r, cpu, wall))
        print(f"    p_max {row['p_max'] / 1e6:.0f} MPa, tau_max {row['tau'] / 1e6:.0f} MPa, von Mises max "
              f"{row['vm'] / 1e6:.0f} MPa, a {row['a'] * 1e3:.2f} mm, b {row['b'] * 1e3:.2f} mm, "
              f"rear-wave amplitude {row['waves'] * 1e6:.2f} um, wavelength {wl * 1e3:.1f} mm (2 V dt "
              f"= {2 * V * dt * 1e3:.1f} mm)" + (f", max eps_p (rail) {row['eps_p']:.5f}"
                                                  if "eps_p" in row else ""), flush=True)
        tag = f"hht_dt{dt:g}_{a.mesh * 1e3:g}mm{'_plastic' if plastic else ''}"
        r.dataset.to_netcdf(out / f"{tag}.nc")
        from wheelrail.fe.plots import plot_section
        from wheelrail.fe.rolling import stress_fields

        fields = r.fields if r.fields is not None else stress_fields(r.model, r.u)

        plot_section(fields, "rail_von_mises", y=r.model.geometry["y_c"],
                     depth_max=4 * r.model.geometry["a"],
                     path=out / f"{tag}_von_mises.png")
        (out / f"{tag}.json").write_text(json.dumps(dict(row, cpu=cpu, steps=r.info["steps"],
                                                         travel=a.travel, profile_x=wx,
                                                         profile_uz=wz, hht_alpha=r.model.case.hht_alpha,
                                                         fx_scatter=r.steady["Fx_scatter"],
                                                         n_steady=r.steady["n"])))
    time_increment_table(a)


def time_increment_table(a):
    """The differences against the smallest step of every run saved in --out for this mesh
    (runs may be split over several processes, one --dts value each)."""
    plastic = "_plastic" if _time_increment_plastic(a) else ""
    rows = sorted((json.loads(f.read_text()) for f in
                   Path(a.out).glob(f"hht_dt*_{a.mesh * 1e3:g}mm{plastic}.json")),
                  key=lambda r: r["dt"])
    if len(rows) < 2:
        return
    base = rows[0]
    print(f"  {a.mesh * 1e3:g} mm, {'elasto-plastic' if plastic else 'elastic'}: differences "
          f"relative to the smallest step, {base['dt']:.3g} s (p_max {base['p_max'] / 1e6:.0f} MPa, "
          f"von Mises max {base['vm'] / 1e6:.0f} MPa, Fx {base['Fx']:.0f} N, rear waves "
          f"{base['waves'] * 1e6:.2f} um)")
    print("  (Toumi et al. Table 2: 3.7e-4 vs 2e-5 s: p_max -2.5 %, a +10.3 %, b 0, von Mises "
          "+31.5 %, tau_max +8 %, Fx +27.2 %; 1e-4 vs 2e-5 s: 0.3, 0, 0, 3.7, 5, 7 %)")
    for row in rows[1:]:
        print(f"    dt {row['dt']:.3g} s: " + ", ".join(
            f"{k} {row[k] / base[k] - 1:+.1%}" for k in ("p_max", "a", "b", "vm", "tau", "Fx"))
              + f", rear waves {row['waves'] * 1e6:.2f} um, wavelength "
              f"{row.get('wavelength', np.nan) * 1e3:.1f} mm")
    plot_rear_profiles(rows, Path(a.out) / f"hht_rear_{a.mesh * 1e3:g}mm{plastic}.png",
                       f"{a.mesh * 1e3:g} mm mesh, {'elasto-plastic' if plastic else 'elastic'}")


def plot_rear_profiles(rows, path, title):
    """The detrended rail-surface u_z behind the contact of every run (x from the contact,
    the wheel rolling towards +x), with a cosine of wavelength 2 V dt for each step."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    V = 50 / 3.6
    fig, ax = plt.subplots(figsize=(7, 3.6))
    for k, row in enumerate(rows):
        if not row.get("profile_x"):
            continue
        x = (np.asarray(row["profile_x"]) - row["travel"]) * 1e3
        uz = np.asarray(row["profile_uz"]) * 1e6
        ax.plot(x, uz, "o-", color=f"C{k}", ms=3,
                label=f"dt = {row['dt']:.2g} s ({row['travel'] * 1e3:g} mm of travel"
                      + (", elasto-plastic)" if "eps_p" in row else ")"))
        xx = np.linspace(x.min(), x.max(), 300)
        lam = 2 * V * row["dt"] * 1e3
        if lam > 2 * np.min(np.diff(np.sort(x))):
            ax.plot(xx, np.std(uz) * np.sqrt(2) * np.cos(2 * np.pi * xx / lam), ":",
                    color=f"C{k}", lw=0.8, label=f"2 V dt = {lam:.1f} mm (phase arbitrary)")
    ax.set_xlabel("rail x minus the travel [mm] (behind the wheel: < 0)")
    ax.set_ylabel("detrended rail-surface $u_z$ [µm]")
    ax.set_title(f"Rail surface behind the patch, implicit HHT: {title}", fontsize=9)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def cmd_linear_solvers(a):
    """The implicit HHT run's first Newton matrix (static step, unscaled mass, the
    time-increment case with --dts[0], --travel) factorised and solved by SuperLU
    (`linear_solver="direct"`) and MKL PARDISO (`"pardiso"`), CPU time of each over
    --repeats, alternating; MKL on one thread unless MKL_NUM_THREADS says otherwise."""
    import scipy.sparse as sp

    import wheelrail.fe._newton as nw

    os.environ.setdefault("MKL_NUM_THREADS", "1")
    grabbed = {}

    class Stop(Exception):
        pass

    def grab(J, b):
        grabbed.update(J=sp.csr_matrix(J), b=np.array(b))
        raise Stop

    case = seed(a.mesh, plastic=_time_increment_plastic(a), integrator="implicit-hht",
                mass_scaling=1.0, time_step=a.dts[0], travel=a.travel, **a.extra)
    real = nw.solve_linear
    nw.solve_linear = grab
    try:
        solve(case)
    except Stop:
        pass
    finally:
        nw.solve_linear = real
    J, b = grabbed["J"], grabbed["b"]
    print(f"  {a.mesh * 1e3:g} mm mesh: {J.shape[0]} unknowns, {J.nnz} non-zeros")
    cpu = {"direct": [], "pardiso": []}
    for _ in range(a.repeats):
        for name in cpu:
            solver = nw.make_solver(name)
            t = time.process_time()
            x = solver.solve(J, b)
            cpu[name].append(time.process_time() - t)
            res = np.linalg.norm(J @ x - b) / np.linalg.norm(b)
            print(f"    {name:8s}: CPU {cpu[name][-1]:.2f} s, relative residual {res:.1e}",
                  flush=True)
    print(f"  best: SuperLU {min(cpu['direct']):.2f} s, PARDISO {min(cpu['pardiso']):.2f} s, "
          f"ratio {min(cpu['direct']) / min(cpu['pardiso']):.2f}, {load()}")


def rear_waves(r, profile=False):
    """Amplitude [m] of the vertical rail-surface displacement oscillation behind the contact
    (std of u_z of the rail surface nodes from 1.5 a to 6 a behind the contact, after removing
    a linear trend) — the waves of Toumi et al.'s Fig. 2(a). With ``profile``: also the
    wavelength [m] (twice the mean distance between sign changes of the detrended u_z; nan
    if fewer than two) and the profile (x, detrended u_z) [m]."""
    m = r.model
    g = m.geometry
    s = float(r.dataset.travel.values[-1])
    nodes = m.rail.surface_nodes[:, np.argmin(np.abs(m.rail.axes[1] - g["y_c"]))]
    x = m.rail.axes[0]
    uz = r.u[nodes + m.nw, 2]
    sel = (x < s - 1.5 * g["a"]) & (x > s - 6 * g["a"])
    if sel.sum() < 4:
        return (float("nan"), float("nan"), [], []) if profile else float("nan")
    c = np.polyfit(x[sel], uz[sel], 1)
    d = uz[sel] - np.polyval(c, x[sel])
    amp = float(np.std(d))
    if not profile:
        return amp
    xs = x[sel]
    k = np.flatnonzero(np.sign(d[1:]) != np.sign(d[:-1]))
    # crossing abscissae by linear interpolation
    xc = xs[k] - d[k] * (xs[k + 1] - xs[k]) / (d[k + 1] - d[k])
    wl = float(2 * np.mean(np.diff(xc))) if xc.size >= 2 else float("nan")
    return amp, wl, xs.tolist(), d.tolist()


# ----------------------------------------------------------------------------- passes
def cmd_passes(a):
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    case = seed(a.mesh, plastic=True, passes=a.passes, **a.extra)
    r, cpu, wall = timed(case, progress=True)
    print(f"repeated passes ({a.passes}), plastic: " + describe(r, cpu, wall))
    ps = r.passes
    ps.to_netcdf(out / f"passes_{a.mesh * 1e3:g}mm.nc")
    for k in range(ps.sizes["pass"]):
        pe = ps.equivalent_plastic_strain.isel(**{"pass": k})
        rs = ps.residual_stress.isel(**{"pass": k})
        kd = int(pe.argmax())
        print(f"  pass {k + 1}: Fx {float(ps.Fx[k]):.0f} N, Fy {float(ps.Fy[k]):.0f} N, max eps_p "
              f"{float(pe.max()):.5f} at depth {float(pe.depth[kd]) * 1e3:.1f} mm; residual stress "
              f"at the surface row: xx {float(rs.sel(component='xx')[0]) / 1e6:.0f} MPa, yy "
              f"{float(rs.sel(component='yy')[0]) / 1e6:.0f} MPa, xz (depth {float(pe.depth[kd]) * 1e3:.1f} mm) "
              f"{float(rs.sel(component='xz')[kd]) / 1e6:.0f} MPa", flush=True)
    from wheelrail.fe.plots import plot_passes

    plot_passes(ps, path=out / f"passes_{a.mesh * 1e3:g}mm.png")


# ----------------------------------------------------------------------------- speed
def machine_speedup(repeats=20):
    """Speed-up of a trivially parallel numba loop on 2 threads (the machine's available
    parallelism while the benchmark runs: 2.0 on an idle 2-core machine)."""
    import numba

    @numba.njit(parallel=True)
    def work(n):
        s = np.zeros(64)
        for c in numba.prange(64):
            acc = 0.0
            for i in range(n):
                acc += np.sin(i * 1e-3 + c)
            s[c] = acc
        return s.sum()

    work(10)
    best = {}
    for threads in (1, 2, 1, 2):
        numba.set_num_threads(threads)
        for _ in range(repeats):
            t = time.perf_counter()
            work(20000)
            best[threads] = min(best.get(threads, np.inf), time.perf_counter() - t)
    numba.set_num_threads(numba.config.NUMBA_NUM_THREADS)
    return best[1] / best[2]


def cmd_speed(a):
    if a.baseline:
        return speed_against_baseline(a)
    import numba

    print(f"control: a trivially parallel numba loop runs {machine_speedup():.2f}x faster on 2 "
          f"threads than on 1 now ({load()})", flush=True)
    rows = []
    for plastic in (False, True):
        case = seed(a.mesh, plastic=plastic, travel=a.travel, mass_scaling=400.0)
        solve(case.replace(travel=0.3 * a.travel), progress=False)          # compile, warm
        for rep in range(a.repeats):
            for threads in (1, 2):
                numba.set_num_threads(threads)
                r, cpu, wall = timed(case, progress=False)
                n = r.info["steps"] * r.model.n_elements
                rows.append((plastic, threads, wall / n * 1e9, cpu / n * 1e9,
                             r.info["loop_wall"] / n * 1e9))
                print(f"{'plastic' if plastic else 'elastic'}, {threads} thread(s): "
                      f"{r.model.n_elements} elements x {r.info['steps']} steps: wall "
                      f"{wall / n * 1e9:.1f} ns/element/step, CPU {cpu / n * 1e9:.1f} (time loop "
                      f"only: wall {r.info['loop_wall'] / n * 1e9:.1f}), {load()}", flush=True)
    numba.set_num_threads(numba.config.NUMBA_NUM_THREADS)
    for plastic in (False, True):
        w1 = min(r[2] for r in rows if r[0] == plastic and r[1] == 1)
        w2 = min(r[2] for r in rows if r[0] == plastic and r[1] == 2)
        l1 = min(r[4] for r in rows if r[0] == plastic and r[1] == 1)
        l2 = min(r[4] for r in rows if r[0] == plastic and r[1] == 2)
        print(f"  {'plastic' if plastic else 'elastic'}: best wall 1 thread {w1:.1f}, 2 threads "
              f"{w2:.1f} ns/element/step, speed-up {w1 / w2:.2f}; time loop only {l1:.1f}, "
              f"{l2:.1f}, speed-up {l1 / l2:.2f}")


def cmd_speed_one(a):
    """One timed run (a subprocess of ``speed --baseline``): prints one JSON line."""
    import numba

    numba.set_num_threads(a.threads)
    case = seed(a.mesh, plastic=a.material == "plastic", travel=a.travel, mass_scaling=400.0)
    solve(case.replace(travel=0.3 * a.travel), progress=False)              # compile, warm
    r, cpu, wall = timed(case, progress=False)
    print(json.dumps(dict(steps=r.info["steps"], elements=r.model.n_elements, cpu=cpu, wall=wall,
                          loop_wall=r.info.get("loop_wall", float("nan")),
                          loop_cpu=r.info.get("loop_cpu", float("nan")),
                          Fx=r.steady["Fx"], load=os.getloadavg()[0])))


def speed_against_baseline(a):
    """The explicit step of this code and of another version (``--baseline``: its ``src``
    directory, e.g. ``git archive main src | tar -x -C /tmp/base``), run alternately in
    subprocesses (each compiles/warms, then one timed run), interleaved so that both see the
    same machine load: ns/element/step wall and CPU, 1 and 2 threads, elastic and plastic."""
    import subprocess
    import sys

    here = str(Path(wr.__file__).resolve().parents[1])
    codes = {"baseline": str(Path(a.baseline).resolve()), "this": here}
    rows = []
    for rep in range(a.repeats):
        print(f"repeat {rep + 1}: control loop {machine_speedup():.2f}x on 2 threads ({load()})",
              flush=True)
        for material in ("elastic", "plastic"):
            for threads in (1, 2):
                for code, path in codes.items():
                    env = dict(os.environ, PYTHONPATH=path, NUMBA_NUM_THREADS="2")
                    out = subprocess.run(
                        [sys.executable, __file__, "speed-one", "--mesh", str(a.mesh), "--travel",
                         str(a.travel), "--material", material, "--threads", str(threads)],
                        env=env, capture_output=True, text=True, check=True).stdout
                    row = json.loads(out.strip().splitlines()[-1])
                    n = row["steps"] * row["elements"]
                    row.update(code=code, material=material, threads=threads, rep=rep,
                               wall_ns=row["wall"] / n * 1e9, cpu_ns=row["cpu"] / n * 1e9,
                               loop_ns=row["loop_wall"] / n * 1e9,
                               loop_cpu_ns=row["loop_cpu"] / n * 1e9)
                    rows.append(row)
                    print(f"  {code:8s} {material}, {threads} thread(s): {row['elements']} elements"
                          f" x {row['steps']} steps: wall {row['wall_ns']:.1f}, CPU "
                          f"{row['cpu_ns']:.1f} ns/element/step (time loop only: wall "
                          f"{row['loop_ns']:.1f}, CPU {row['loop_cpu_ns']:.1f}), steady Fx "
                          f"{row['Fx']:.6f} N, load {row['load']:.1f}", flush=True)
    print(f"summary (ns/element/step, min-median-max over {a.repeats} repeats; speed-up = best "
          f"1-thread wall / best 2-thread wall, and the range of the per-repeat ratios):")
    for material in ("elastic", "plastic"):
        for code in codes:
            sel = {t: [r for r in rows if r["code"] == code and r["material"] == material
                       and r["threads"] == t] for t in (1, 2)}
            txt = []
            for t in (1, 2):
                w = np.array([r["wall_ns"] for r in sel[t]])
                c = np.array([r["cpu_ns"] for r in sel[t]])
                txt.append(f"{t} thread(s) wall {w.min():.0f}-{np.median(w):.0f}-{w.max():.0f}, "
                           f"CPU {c.min():.0f}-{np.median(c):.0f}-{c.max():.0f}")
            w1 = np.array([r["wall_ns"] for r in sel[1]])
            w2 = np.array([r["wall_ns"] for r in sel[2]])
            ratios = w1 / w2
            l1 = np.array([r["loop_ns"] for r in sel[1]])
            l2 = np.array([r["loop_ns"] for r in sel[2]])
            loop = (f"; time loop only: 1 thread {l1.min():.0f}, 2 threads {l2.min():.0f}, speed-up "
                    f"{l1.min() / l2.min():.2f}" if np.isfinite(l1).all() else "")
            print(f"  {material}, {code}: " + "; ".join(txt) + f"; speed-up {w1.min() / w2.min():.2f}"
                  f" (per repeat {ratios.min():.2f}-{ratios.max():.2f})" + loop)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("part", choices=["steady", "mass-scaling", "table3", "creep", "creep-compare", "figures",
                                     "time-increment", "linear-solvers",
                                     "passes", "speed", "speed-one"])
    ap.add_argument("--mesh", type=float, default=2e-3)
    ap.add_argument("--out", default="fe_plastic_out")
    ap.add_argument("--mass-scaling", type=float, nargs="+", default=[100.0])
    ap.add_argument("--component", choices=["xi", "eta"], default="xi")
    ap.add_argument("--creepages", type=float, nargs="+",
                    default=[-3.0, -1.5, -0.7, -0.35, 0.0, 0.35, 0.7, 1.5, 3.0],
                    help="creepages in permille")
    ap.add_argument("--material", choices=["both", "elastic", "plastic"], default="both",
                    help="creep: run only one material (compare later with creep-compare); "
                         "time-increment: plastic for the elasto-plastic R900A bodies (else "
                         "elastic)")
    ap.add_argument("--hardening", choices=["r900a", "perfect", "kinematic"], default="r900a",
                    help="creep, creep-compare: the plastic material's hardening (r900a: the "
                         "default Voce law; perfect: perfect plasticity at 489 MPa; kinematic: "
                         "the same tensile curve from an Armstrong-Frederick back stress)")
    ap.add_argument("--per-point", action="store_true",
                    help="creep: one NetCDF file per point (creep-compare merges them)")
    ap.add_argument("--dts", type=float, nargs="+", default=[2e-5, 1e-4, 3.7e-4],
                    help="implicit time steps [s] (the smallest first: the reference)")
    ap.add_argument("--travel", type=float, default=0.02)
    ap.add_argument("--passes", type=int, default=4)
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--baseline", default=None,
                    help="speed: the src directory of another version, timed alternately")
    ap.add_argument("--threads", type=int, default=1, help="speed-one: numba threads")
    ap.add_argument("--extra", type=json.loads, default={},
                    help="JSON of more RollingCase fields, e.g. '{\"mass_scaling\": 400}'")
    a = ap.parse_args()
    if a.part == "speed-one":
        return cmd_speed_one(a)
    print(f"bench_fe_plastic {a.part}: {time.strftime('%Y-%m-%d %H:%M')}, {load()}, "
          f"{os.cpu_count()} cores", flush=True)
    globals()["cmd_" + a.part.replace("-", "_")](a)


if __name__ == "__main__":
    main()
