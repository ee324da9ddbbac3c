"""Benchmark of the one- to two-point contact transition model (wheelrail.fe.transition).

Prints the model size, the estimate before the run, the CPU time, the cost per element and
step, the onset of two-point contact, the tread patch before the onset (θ, forces, Σ Fz
against the wheel load) and the patches after it, with the load of the machine. Usage::

    python benchmarks/bench_fe_transition.py [--aoa 0.025] [--mesh 4e-3] [--travel 0.13] \
        [--save RUN.pkl] [--figure RUN.png]
    python benchmarks/bench_fe_transition.py --onset            # 15, 20, 25 mrad
    python benchmarks/bench_fe_transition.py --report RUN.pkl   # a saved run again
    python benchmarks/bench_fe_transition.py --aoa 0.020 --travel 0.24 --results a20_h4_240 \
        --restart-file /tmp/a20.npz            # results/fe_transition/a20_h4_240_*.nc, ...

``--results NAME`` writes ``NAME_patches.nc``, ``NAME_history.nc``, ``NAME_info.json``,
``NAME.png`` and ``report_NAME.txt`` into ``benchmarks/results/fe_transition/``;
``--restart-file``/``--restart-every`` write restart files during the run and
``--restart`` continues one; ``--fields FROM TO`` records the contact's surface fields
over that travel (``NAME_fields.nc``).
"""

from __future__ import annotations

import argparse
import contextlib
import dataclasses
import io
import json
import os
import pickle
import time

import numpy as np

import wheelrail as wr
from wheelrail.fe.transition.analysis import onset_travel


def build_case(kw):
    """``seed004_case`` from the options (JSON-able: ``lateral`` and ``roll`` =
    [stiffness, damping] of the wheel's lateral and roll restraints, the rest
    ``TransitionCase`` fields)."""
    kw = dict(kw)
    track = kw.pop("track", None)
    susp = {}
    for key in ("lateral", "roll"):
        val = kw.pop(key, None)
        if val is not None:
            susp.update({f"{key}_stiffness": float(val[0]), f"{key}_damping": float(val[1])})
    if susp:
        kw["suspension"] = wr.fe.WheelSuspension(**susp)
    case = wr.fe.seed004_case(**kw)
    if track:                                 # changes to the size's own track structure
        case = case.replace(track=dataclasses.replace(case.track, **track))
    return case


def report(run):
    ds, h, info, kw = run["patches"], run["history"], run["info"], run["case_kw"]
    case = build_case(kw)
    s = ds.travel.values
    on = onset_travel(ds)
    print(f"{kw}: {info['elements']} elements, {info['steps']} steps of "
          f"{info['time_step'] * 1e9:.0f} ns, {info['cpu_s']:.0f} s CPU ({info['wall_s']:.0f} s "
          f"wall), {info['ns_per_element_step']:.0f} ns/element/step (CPU)")
    print(f"  wheel load {info['load'] / 1e3:.2f} kN; onset of two-point contact (flange "
          f"patch > 1 kN for 3 outputs) at {on * 1e3:.1f} mm")
    t1, t2 = ds.sel(patch=1), ds.sel(patch=2)
    th1 = np.degrees(t1.theta.values)
    pre = (s >= case.settle) & (s < (on if on == on else np.inf))
    if pre.any():
        fz = h.Fz_total.values[pre]
        print(f"  before the onset ({s[pre][0] * 1e3:.0f}-{s[pre][-1] * 1e3:.0f} mm): tread θ "
              f"median {np.nanmedian(th1[pre]):.1f}° (IQR {np.nanpercentile(th1[pre], 25):.1f}-"
              f"{np.nanpercentile(th1[pre], 75):.1f}°), contact angle "
              f"{np.degrees(np.nanmin(t1.contact_angle.values[pre])):.1f}-"
              f"{np.degrees(np.nanmax(t1.contact_angle.values[pre])):.1f}°, F_long "
              f"{t1.F_long.values[pre].mean() / 1e3:.1f} kN, F_lat "
              f"{t1.F_lat.values[pre].mean() / 1e3:.1f} kN, Σ Fz {fz.mean() / 1e3:.1f} kN "
              f"(std {fz.std() / 1e3:.1f}; {fz.mean() / info['load'] - 1:+.1%} of the load)")
    if on == on:
        k0 = int(np.flatnonzero(s >= on)[0])
        print("  output, travel [mm], Fn tread/flange [kN], θ tread/flange [°], adhering "
              "fraction tread/flange, flange contact angle [°], Σ Fz [kN]")
        for k in range(max(0, k0 - 3), min(s.size, k0 + 12)):
            print(f"   {k - k0:+3d} {s[k] * 1e3:6.1f} {t1.Fn.values[k] / 1e3:6.1f} "
                  f"{t2.Fn.values[k] / 1e3:6.1f} {th1[k]:5.1f} "
                  f"{np.degrees(t2.theta.values[k]):5.1f} {t1.adhesion.values[k]:.2f} "
                  f"{t2.adhesion.values[k]:.2f} {np.degrees(t2.contact_angle.values[k]):5.1f} "
                  f"{h.Fz_total.values[k] / 1e3:6.1f}")
        post = (s >= on) & (t2.Fn.values > 1000)
        a2 = np.degrees(t2.contact_angle.values[post])
        th2 = np.degrees(t2.theta.values[post])
        print(f"  flange patch: contact angle {np.median(a2):.1f}° ({a2.min():.1f}-"
              f"{a2.max():.1f}), θ median {np.median(th2):.1f}° (IQR "
              f"{np.percentile(th2, 25):.1f}-{np.percentile(th2, 75):.1f}), largest adhering "
              f"fraction {np.nanmax(t2.adhesion.values[post]):.2f}; at the end tread "
              f"{t1.Fn.values[-1] / 1e3:.1f} kN, flange {t2.Fn.values[-1] / 1e3:.1f} kN")
    return on


RESULTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "results", "fe_transition")


def save_results(run, name, directory=None):
    """Write a run as ``name``'s netCDF files, info json and text report into ``directory``
    (default :data:`RESULTS`)."""
    directory = directory or RESULTS
    os.makedirs(directory, exist_ok=True)
    run["patches"].to_netcdf(os.path.join(directory, f"{name}_patches.nc"))
    run["history"].to_netcdf(os.path.join(directory, f"{name}_history.nc"))
    info = {k: (float(v) if isinstance(v, (int, float, np.floating, np.integer)) else v)
            for k, v in run["info"].items() if k not in ("fields", "wave")}
    info["load_avg"] = run.get("load_avg")
    with open(os.path.join(directory, f"{name}_info.json"), "w") as f:
        json.dump({"case": run["case_kw"], "info": info}, f, indent=1)
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        report(run)
    with open(os.path.join(directory, f"report_{name}.txt"), "w") as f:
        f.write(buf.getvalue())


def from_restart(kw, path, results=None):
    """Report (and save) the outputs of a run up to its last restart file (a run stopped
    before its end): the CPU time is not stored there (NaN)."""
    patches, history, prog = wr.fe.transition.read_transition_restart(path)
    case = build_case(kw)
    model = wr.fe.transition.build_transition_model(case)
    est = wr.fe.transition.transition_time_estimate(model)
    nan = float("nan")
    info = {"time_step": est["time_step"], "steps": prog["step"] + 1, "cpu_s": nan,
            "wall_s": nan, "ns_per_element_step": nan, "elements": est["elements"],
            "load": case.suspension.wheel_load(float(model.mass[:model.n_wheel].sum())),
            "partial": f"restart file at step {prog['step'] + 1} of {prog['steps']}",
            "onset_travel": onset_travel(patches)}
    run = {"patches": patches, "history": history, "info": info, "case_kw": kw,
           "load_avg": None}
    print(f"partial run: {info['partial']} ({patches.travel.values[-1] * 1e3:.1f} mm of "
          f"{case.travel * 1e3:.0f} mm)")
    if results:
        save_results(run, results)
        from wheelrail.fe.plots import plot_transition

        plot_transition(patches, history, path=os.path.join(RESULTS, f"{results}.png"),
                        title=f"angle of attack {case.angle_of_attack * 1e3:g} mrad (to "
                              f"{patches.travel.values[-1] * 1e3:.0f} mm)")
    return report(run)


def one(kw, save=None, figure=None, results=None, restart=None, restart_file=None,
        restart_every=0, stop=None):
    case = build_case(kw)
    t0 = time.process_time()
    model = wr.fe.transition.build_transition_model(case)
    t_build = time.process_time() - t0
    load0 = os.getloadavg()[0]
    r = wr.fe.run_transition(case, model=model, progress=True, restart=restart,
                             restart_file=restart_file, restart_every=restart_every,
                             stop_travel=stop)
    if r.contact_fields is not None and results:
        r.contact_fields.to_netcdf(os.path.join(RESULTS, f"{results}_fields.nc"))
    wave = r.info.get("wave")
    if wave is not None and results:
        np.savez_compressed(os.path.join(RESULTS, f"{results}_wave.npz"),
                            **{k: np.asarray(v) for k, v in wave.items() if k != "vz"})
    info = {k: v for k, v in r.info.items() if k not in ("fields", "wave")}
    run = {"patches": r.patches, "history": r.history, "info": info, "case_kw": kw,
           "load_avg": [load0, os.getloadavg()[0]]}
    print(f"build {t_build:.1f} s CPU; load {load0:.1f} at the start, "
          f"{os.getloadavg()[0]:.1f} at the end (1-min average)")
    if save:
        with open(save, "wb") as f:
            pickle.dump(run, f)
    if results:
        save_results(run, results)
        figure = figure or os.path.join(RESULTS, f"{results}.png")
    if figure:
        from wheelrail.fe.plots import plot_transition

        plot_transition(r.patches, r.history, path=figure,
                        title=f"angle of attack {case.angle_of_attack * 1e3:g} mrad")
    return report(run)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--aoa", type=float, default=0.025)
    ap.add_argument("--mesh", type=float, default=None)
    ap.add_argument("--travel", type=float, default=None)
    ap.add_argument("--onset", action="store_true")
    ap.add_argument("--save")
    ap.add_argument("--figure")
    ap.add_argument("--report")
    ap.add_argument("--results", help="name of the run's files in results/fe_transition")
    ap.add_argument("--restart", help="continue from this restart file")
    ap.add_argument("--restart-file", help="write restart files here during the run")
    ap.add_argument("--restart-every", type=int, default=0, help="steps between them")
    ap.add_argument("--report-restart", help="report (and --results: save) the outputs "
                    "stored in this restart file of a run with the same --aoa/--travel")
    ap.add_argument("--clearance", type=float, default=None,
                    help="flange clearance at the start [m] (reduced case: 3e-3)")
    ap.add_argument("--fields", type=float, nargs=2, metavar=("FROM", "TO"),
                    help="record the contact's surface fields over this travel [m] "
                         "(written as NAME_fields.nc with --results)")
    ap.add_argument("--field-stride", type=int, default=1, help="every N-th output")
    ap.add_argument("--preload", type=float, default=None,
                    help="static preload (dynamic relaxation) before rolling [s]")
    ap.add_argument("--settle", type=float, default=None, help="damped settle distance [m]")
    ap.add_argument("--output-interval", type=float, default=None, help="[s]")
    ap.add_argument("--traction", type=float, default=None,
                    help="driving torque as a traction coefficient (reduced case: 0.3)")
    ap.add_argument("--lateral", type=float, nargs=2, metavar=("K", "C"),
                    help="the wheel's lateral restraint to its heading path [N/m] [N s/m] "
                         "(default: lateral motion prescribed; 0 0: free)")
    ap.add_argument("--roll", type=float, nargs=2, metavar=("K", "C"),
                    help="the wheel's roll restraint about its heading [N m/rad] "
                         "[N m s/rad] (default: no roll; the half-axle's bending: "
                         "WheelSuspension.half_axle_roll_stiffness() = 1.44e7)")
    ap.add_argument("--track", nargs="+", default=[], metavar="FIELD=VALUE",
                    help="TrackStructure fields with a number, changed from the case's own, "
                         "e.g. n_sleepers=4 pad_shear_stiffness=2.8e9")
    ap.add_argument("--set", nargs="+", default=[], metavar="FIELD=VALUE",
                    help="any other TransitionCase field with a number, e.g. "
                         "section_h_max=6e-3 x_h_max=0.012 theta_h_max=0.012 (1 mm meshes)")
    ap.add_argument("--wave", nargs=3, metavar=("TRAVEL", "TIME", "LINE"),
                    help="record a rail surface line's velocities every step from TRAVEL [m] "
                         "for TIME [s]; LINE tread or flange (NAME_wave.npz with --results)")
    ap.add_argument("--stop", type=float, default=None,
                    help="stop at this travel [m] (the restart file is written there; "
                         "continue with --restart, output options may change)")
    a = ap.parse_args()
    if a.report:
        with open(a.report, "rb") as f:
            report(pickle.load(f))
        return
    extra = {k: v for k, v in (("mesh_size", a.mesh), ("travel", a.travel),
                               ("flange_clearance", a.clearance), ("preload", a.preload),
                               ("settle", a.settle), ("output_interval", a.output_interval),
                               ("traction", a.traction))
             if v is not None}
    def assignments(flag, items):
        out = {}
        for item in items:
            key, sep, val = item.partition("=")
            if not sep:
                ap.error(f"--{flag} takes FIELD=VALUE, got {item!r}")
            out[key] = float(val)         # the dataclasses check and convert (n_sleepers)
        return out

    extra.update(assignments("set", a.set))
    track = assignments("track", a.track)
    if track:
        extra["track"] = track
    if a.lateral:
        extra["lateral"] = list(a.lateral)
    if a.roll:
        extra["roll"] = list(a.roll)
    if a.fields:
        extra.update(field_travel=tuple(a.fields), field_stride=a.field_stride)
    if a.wave:
        extra.update(wave_travel=float(a.wave[0]), wave_time=float(a.wave[1]),
                     wave_line=a.wave[2])
    if a.report_restart:
        from_restart(dict(angle_of_attack=a.aoa, **extra), a.report_restart, a.results)
        return
    if a.onset:
        onsets = {aoa: one(dict(angle_of_attack=aoa, **extra)) for aoa in (0.015, 0.020, 0.025)}
        print("onset [mm]:", {k: round(v * 1e3, 1) for k, v in onsets.items()})
    else:
        one(dict(angle_of_attack=a.aoa, **extra), a.save, a.figure, a.results, a.restart,
            a.restart_file, a.restart_every, a.stop)


if __name__ == "__main__":
    main()
