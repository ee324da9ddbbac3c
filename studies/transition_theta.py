"""The tread patch's shear direction θ before the onset: how it is averaged, and the traction.

``fields NAME ...`` reads the surface fields of a run of ``bench_fe_transition.py --fields
FROM TO --results NAME`` (``results/fe_transition/NAME_fields.nc``) and prints, over travel
windows before and after the onset of two-point contact, the medians of the tread patch's
θ as the angle of its mean shear stress (the patch histories' ``theta``), as the
area-weighted mean of the nodes' signed angles and as the mean of their absolute angles
(:func:`wheelrail.fe.transition.analysis.shear_direction`), with the patch's contact angle
and forces.

``jump NAME ...`` resolves the tread θ in time around the onset from a run with fine outputs
(``--output-interval 1e-5`` or finer): times from the flange patch's first contact force,
medians over bins of ``--bin`` seconds of the flange and tread normal forces, the tread θ,
its adhering fraction and its utilisation F_long/(μFn), and the first times at which a
running median of θ over one bin reaches 30°, 40°, ... 70°; where the run recorded its
surface fields, also the tread patch's mean micro-slip along and across the rail and its
direction (:func:`wheelrail.fe.transition.analysis.slip_direction`); where it recorded the
rail's tread line (``--wave TRAVEL TIME tread``), the rail head's lateral velocity under the
wheel over the approach speed V sin α; for a run at a prescribed rolling (``--set
creepage=``), the rigid longitudinal creepage at the tread's contact angle before the onset.

``after`` asks the same theory what the onset can do to θ: at each pre-onset state
(contact angle; F_long = traction × Q at the static load; the wheel moving along its
heading) it keeps the angular velocity and load and reduces the wheel's lateral velocity
against the rail by V sin α (the tread stopped laterally on the rail: the largest lateral
slip the approach can give), and finds the reduction at which θ reaches 70°.

``creep NAME ...`` reads runs at a prescribed creepage (``--set creepage=...``: a constant
angular velocity instead of the driving torque, angle of attack 0): the tread patch's
medians from ``--from`` to the end, against Kalker's exact theory (BEM + exact) at the FE
patch's contact angle and Fn, at the same creepage and at the same F_long.

``module`` gives the quasi-static, independent estimate from Kalker's exact theory. With
the transition case's kinematics (yaw α, the wheel moving along its heading: no lateral
creepage, spin from the contact angle) the tread contact's lateral force comes from spin
alone, so θ = atan(|F_lat| / |F_long|) depends on where the contact sits and on how hard
the wheel is driven: ``solve_wheelrail`` (S1002 on 54E1 1:40, BEM + exact) at the wheelset
shifts where the rigid tread contact has the given contact angles, with the angular
velocity at which the longitudinal force is traction × Q. Usage::

    python benchmarks/bench_fe_transition.py --aoa 0.025 --travel 0.13 \
        --fields 0.06 0.125 --results a25_h4_wave_tread
    python studies/transition_theta.py fields a25_h4_wave_tread a25_h4_t50 \
        --out results/fe_transition/theta_fe_a25.txt
    python studies/transition_theta.py jump a25_h4_jump a25_h4_c7_t55_340 \
        a25_h4_c7_t55_lat0 a25_h4_c7_t3_lat0 a25_h4_c7_t55_roll a25_h4_c7_t55_roll_lat0 \
        a25_h4_c7_t50 a25_h4_c7_t45 \
        --bin 1.2e-4 --before 2.4e-4 --after 2e-3 \
        --out results/fe_transition/theta_jump_a25.txt
    python benchmarks/bench_fe_transition.py --aoa 0.025 --travel 0.34 --clearance 0.007 \
        --set creepage=0.0038 --output-interval 1e-5 --wave 0.272 3.2e-3 tread \
        --results a25_h4_c7_xi38_wave
    python studies/transition_theta.py jump a25_h4_c7_xi38_hold \
        a25_h4_c7_xi38_wave a20_h4_c7_xi38_hold --bin 1.2e-4 --before 4.8e-4 --after 2.4e-3 \
        --out results/fe_transition/theta_jump_xi38.txt
    for c in 0.0015 0.003 0.006 0.012; do python benchmarks/bench_fe_transition.py \
        --aoa 0 --mesh 0.004 --travel 0.06 --clearance 0.003 --preload 1e-3 \
        --output-interval 1e-5 --set creepage=$c --fields 0.035 0.06 \
        --results a0_h4_c3_xi${c#0.}; done
    python studies/transition_theta.py creep a0_h4_c3_xi0015 a0_h4_c3_xi003 \
        a0_h4_c3_xi006 a0_h4_c3_xi012 --out results/fe_transition/creep_a0_tread.txt
    python studies/transition_theta.py module --angles 7 9 16 20 24 \
        --traction 0.3 0.4 0.5 0.55 --out results/fe_transition/theta_module_a25.txt
    python studies/transition_theta.py after \
        --state 21.9 77.9 44.8 --state 20.0 71.2 40.0 --state 23.2 72.4 39.5 \
        --state 23.2 72.8 37.5 --state 23.0 88.7 39.2 \
        --out results/fe_transition/theta_after_a25.txt
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import os
import time

import numpy as np
import xarray as xr
from transition_crosscheck import module_jump_shift

import wheelrail as wr
from wheelrail.contact.wheelrail import WheelRailPosition, solve_wheelrail
from wheelrail.fe.transition.analysis import onset_travel, shear_direction, slip_direction
from wheelrail.fe.transition.model import flange_contact_offset

RESULTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "benchmarks", "results", "fe_transition")
S1002 = wr.profiles.load("S1002")
R54 = wr.profiles.load("54E1")


def wheelset_track(case):
    """The module's S1002 wheelset and 54E1 track with the radius and rail inclination of a
    transition ``case``."""
    return (wr.Wheelset(S1002, nominal_radius=case.radius),
            wr.Track(R54, inclination=np.tan(case.inclination)))


def tread_slip(name):
    """The tread patch's mean micro-slip over time from run NAME's surface fields
    (:func:`slip_direction`), or None where the run recorded none."""
    fpath = os.path.join(RESULTS, f"{name}_fields.nc")
    if not os.path.exists(fpath):
        return None
    with xr.open_dataset(fpath) as fields:
        return slip_direction(fields.load(), patch=1)


def rail_lateral(name, half=6e-3):
    """The rail head's lateral velocity under the wheel from a run's wave record.

    ``NAME_wave.npz`` (``bench_fe_transition.py --wave TRAVEL TIME tread``) holds the
    velocities of the rail's surface line through the start contact every step. Returns
    ``(t, v_y)``: the times [s] and the mean lateral velocity [m/s] of the line's nodes
    within ``half`` of the wheel centre's position along the rail, or None without a
    record. The tread patch at the onset lies 15–16 mm further towards the gauge corner
    on the same head.
    """
    path = os.path.join(RESULTS, f"{name}_wave.npz")
    if not os.path.exists(path):
        return None
    w = np.load(path)
    if str(w["line"]) != "tread":
        return None
    t, x, vy = w["t"], w["x"], w["v"][:, :, 1]
    t0 = float(w["travel"]) / float(w["speed"])            # the wheel centre at x = 0
    xc = float(w["speed"]) * (t - t0)
    near = np.abs(x[None, :] - xc[:, None]) < half
    v = np.where(near, vy, 0.0).sum(axis=1) / np.maximum(near.sum(axis=1), 1)
    return t, np.where(near.any(axis=1), v, np.nan)


def windows(onset, start, end):
    w = [(start, onset - 0.030), (onset - 0.030, onset - 0.010), (onset - 0.010, onset),
         (onset, onset + 0.003), (onset + 0.003, onset + 0.010), (onset + 0.010, end)]
    return [(a, b) for a, b in w if b > a + 1e-4 and a >= start - 1e-9]


def one(name, compare=False):
    fields = xr.open_dataset(os.path.join(RESULTS, f"{name}_fields.nc")).load()
    patches = xr.open_dataset(os.path.join(RESULTS, f"{name}_patches.nc")).load()
    with open(os.path.join(RESULTS, f"{name}_info.json")) as f:
        case = json.load(f)["case"]
    onset = onset_travel(patches)
    sd = shear_direction(fields, patch=1)
    s = sd.travel.values
    k = np.searchsorted(patches.time.values, sd.time.values)
    ang = np.degrees(patches.contact_angle.values[k, 0])
    fl = patches.F_long.values[k, 0] / 1e3
    ft = patches.F_lat.values[k, 0] / 1e3
    fn = patches.Fn.values[k, 0] / 1e3
    print(f"{name}: {case}; onset {onset * 1e3:.1f} mm; fields {s[0] * 1e3:.1f}-"
          f"{s[-1] * 1e3:.1f} mm at {s.size} outputs")
    print("  travel [mm]     outputs  θ mean stress  θ mean angle  θ mean |angle|  "
          "contact angle  Fn [kN]  F_long  F_lat  nodes   (medians)")
    rows = []
    for a, b in windows(onset, s[0], s[-1]):
        m = (s >= a) & (s < b) & np.isfinite(sd.mean_stress.values)
        if not m.any():
            continue
        med = lambda v: float(np.median(v[m]))  # noqa: E731
        if b <= onset + 1e-9:
            rows.append((a, b, med(np.abs(sd.mean_stress.values)), med(ang), med(fn), med(fl)))
        print(f"  {a * 1e3:6.1f}-{b * 1e3:6.1f}  {m.sum():6d}   {med(np.abs(sd.mean_stress.values)):8.1f}°"
              f"    {med(sd.mean_angle.values):8.1f}°    {med(sd.mean_abs_angle.values):8.1f}°"
              f"      {med(ang):6.1f}°    {med(fn):6.1f}  {med(fl):6.1f} {med(ft):6.1f}"
              f"  {med(sd.n_nodes.values):5.0f}")
    if compare:
        # Kalker's exact theory at the FE patch's contact angle, normal and longitudinal force
        c = wr.fe.seed004_case(**{k: v for k, v in case.items() if k != "field_travel"})
        ws, tr = wheelset_track(c)
        print("  against BEM + exact at the FE tread patch's contact angle, Fn and F_long "
              "(medians of the windows before the onset):")
        print("  travel [mm]     F_long/(mu Fn)  θ FE   θ module  (module Fn, F_lat [kN])")
        for a, b, th_fe, ang_fe, fn_fe, fl_fe in rows:
            *_, p = at_state(c, ws, tr, ang_fe, fn_fe * 1e3, fl_fe * 1e3,
                             wr.normal.Bem(element_size=2.5e-4))
            th = theta_of(p)
            print(f"  {a * 1e3:6.1f}-{b * 1e3:6.1f}      {fl_fe / (c.mu * fn_fe):5.2f}      "
                  f"{th_fe:5.1f}°   {th:5.1f}°    ({p.Fn / 1e3:5.1f}, {p.Fs / 1e3:5.1f})",
                  flush=True)


def steady(name, start, width, compare=False, normal=None):
    """The tread patch of a run without onset (angle of attack 0: rolling along the rail on
    the flange root) over travel bins from ``start`` [m]: medians of its forces, contact
    angle, θ, adhering fraction and mean micro-slip; with ``compare``, Kalker's exact theory
    at the last bin's contact angle, Fn and F_long (its creepage ξ·V against the FE slip)."""
    p = xr.open_dataset(os.path.join(RESULTS, f"{name}_patches.nc")).load()
    with open(os.path.join(RESULTS, f"{name}_info.json")) as f:
        case = json.load(f)["case"]
    s = p.travel.values
    slip = tread_slip(name)
    print(f"{name}: {case}")
    print("  travel [mm]   outputs  Fn [kN]  F_long  F_lat  F_long/(mu Fn)  contact angle  "
          "tread θ  adhering  slip long, lat [m/s], angle")
    mu = case.get("mu", 0.6)
    last = None
    for a in np.arange(start, s[-1] - 0.5 * width, width):
        m = (s >= a) & (s < a + width) & np.isfinite(p.Fn.values[:, 0])
        if not m.any():
            continue
        med = lambda v: float(np.median(v[m, 0]))  # noqa: E731
        fn, fl, ft = med(p.Fn.values) / 1e3, med(p.F_long.values) / 1e3, med(p.F_lat.values) / 1e3
        ang, th = np.degrees(med(p.contact_angle.values)), np.degrees(med(np.abs(p.theta.values)))
        cols = ""
        if slip is not None:
            cols = slip_columns(slip, slip.travel.values, a, a + width)
        print(f"  {a * 1e3:5.0f}-{(a + width) * 1e3:4.0f}  {m.sum():6d}   {fn:6.1f}  "
              f"{abs(fl):6.1f} {abs(ft):6.1f}      {abs(fl) / (mu * fn):5.2f}        {ang:5.1f}°"
              f"      {th:5.1f}°   {med(p.adhesion.values):4.2f}   {cols}")
        last = (ang, fn, abs(fl), th)
    if compare and last is not None:
        c = wr.fe.seed004_case(**{k: v for k, v in case.items() if k != "field_travel"})
        ws, tr = wheelset_track(c)
        t0 = time.process_time()
        *_, q = at_state(c, ws, tr, last[0], last[1] * 1e3, last[2] * 1e3, normal)
        print(f"  BEM + exact at the last bin's state ({last[0]:.1f}°, Fn {last[1]:.1f} kN, "
              f"F_long {last[2]:.1f} kN): xi {100 * q.xi:+.2f} %, eta {100 * q.eta:+.2f} %, "
              f"spin {q.phi:+.3f} 1/m, xi V = {abs(q.xi) * c.speed:.3f} m/s, θ {theta_of(q):.1f}° "
              f"(FE {last[3]:.1f}°), F_lat {abs(q.Fs) / 1e3:.1f} kN; "
              f"{time.process_time() - t0:.1f} s CPU", flush=True)


def jump(name, width, before, after, first=500.0):
    """The tread θ against the time from the flange patch's first force > ``first`` [N]."""
    p = xr.open_dataset(os.path.join(RESULTS, f"{name}_patches.nc")).load()
    with open(os.path.join(RESULTS, f"{name}_info.json")) as f:
        case = json.load(f)["case"]
    mu = case.get("mu", 0.6)
    t = p.time.values
    s = p.travel.values
    fn = np.nan_to_num(p.Fn.values)
    k0 = int(np.argmax(fn[:, 1] > first))
    if fn[k0, 1] <= first:
        print(f"{name}: no flange force above {first:g} N")
        return
    dt = float(np.median(np.diff(t)))
    tau = t - t[k0]
    th = np.degrees(np.abs(p.theta.values[:, 0]))
    ad = p.adhesion.values[:, 0]
    fl = np.abs(p.F_long.values[:, 0])
    ut = fl / (mu * np.maximum(fn[:, 0], 1.0))
    print(f"{name}: {case}")
    print(f"  outputs every {dt * 1e6:.1f} µs; flange patch's first force > {first / 1e3:g} kN "
          f"at {s[k0] * 1e3:.2f} mm (t = {t[k0] * 1e3:.4f} ms); onset "
          f"{onset_travel(p) * 1e3:.1f} mm; medians over {width * 1e6:.0f} µs bins")
    ft = np.abs(p.F_lat.values[:, 0])
    # the wheel bottom's lateral speed from its lateral and roll dofs, over V (a lateral
    # creepage of the tread that the prescribed path does not have)
    h = xr.open_dataset(os.path.join(RESULTS, f"{name}_history.nc")).load()
    ref = wr.fe.seed004_case(angle_of_attack=case["angle_of_attack"])
    bottom = np.zeros_like(t)
    for v, arm in (("lateral", 1.0), ("roll_angle", ref.radius)):
        if v in h:                       # results written before the roll dof have none
            bottom += arm * h[v].values
    v_bot = np.gradient(bottom, t) / ref.speed
    # the tread patch's mean micro-slip from the surface fields, where they were recorded
    slip = tread_slip(name)
    slip_tau = None if slip is None else slip.time.values - t[k0]
    # the rail head's lateral velocity under the wheel, where the run recorded it, over the
    # wheel's approach speed V sin α: the share of the approach the rail head takes up (with
    # the lateral path prescribed, the tread's lateral creepage is the rail's velocity)
    rail = rail_lateral(name)
    approach = ref.speed * np.sin(case["angle_of_attack"])
    print("  time [µs]       outputs  flange Fn [kN]  tread Fn  tread θ  adhering  "
          "F_long/(μFn)  tread |F_long| |F_lat| [kN]  bottom v_y/V [%]"
          + ("  rail v_y/(V sin α)" if rail is not None else "")
          + ("  tread slip long, lat [m/s], angle" if slip is not None else ""))
    edges = np.arange(-before, after + 0.5 * width, width)
    for a, b in zip(edges[:-1], edges[1:]):
        m = (tau >= a - 1e-12) & (tau < b - 1e-12)
        if not m.any():
            continue
        med = lambda v: float(np.nanmedian(v[m]))  # noqa: E731
        print(f"  {a * 1e6:6.0f} to {b * 1e6:5.0f}  {m.sum():5d}     {med(fn[:, 1]) / 1e3:6.1f}"
              f"       {med(fn[:, 0]) / 1e3:6.1f}   {med(th):5.1f}°    {med(ad):4.2f}"
              f"       {med(ut):4.2f}          {med(fl) / 1e3:5.1f}  {med(ft) / 1e3:5.1f}"
              f"         {100 * med(v_bot):+6.2f}"
              + (rail_column(rail, t[k0], a, b, approach) if rail is not None else "")
              + (slip_columns(slip, slip_tau, a, b) if slip is not None else ""))
    n = max(int(round(width / dt)), 1)
    run = np.array([np.nanmedian(th[max(i - n + 1, 0):i + 1]) for i in range(th.size)])
    base = float(np.nanmedian(th[(tau < 0) & (tau >= -before)]))
    print(f"  tread θ over the {before * 1e6:.0f} µs before: {base:.1f}° (median); "
          f"first time the {width * 1e6:.0f} µs running median reaches:")
    for lim in (30, 40, 50, 55, 60, 65, 70):
        hit = np.nonzero((tau >= 0) & (run >= lim))[0]
        when = (f"{tau[hit[0]] * 1e6:6.0f} µs ({s[hit[0]] * 1e3:.2f} mm)" if hit.size
                else "not reached")
        print(f"    {lim:3d}°  {when}")
    print(f"  run ends {tau[-1] * 1e6:.0f} µs after the flange's first force")
    if case.get("creepage") is not None:
        ang = float(np.degrees(np.nanmedian(p.contact_angle.values[(tau < 0)
                                                                    & (tau >= -width), 0])))
        xi, dr = rigid_creepage(case, ang)
        print(f"  prescribed rolling, nominal creepage {100 * case['creepage']:.2f} % (on the "
              f"start contact's radius): at the tread's contact angle {ang:.1f}° of the last "
              f"{width * 1e6:.0f} µs before the flange's first force the rigid contact's "
              f"radius is {dr * 1e3:+.2f} mm larger, its longitudinal creepage "
              f"{100 * xi:.2f} %")


def rigid_creepage(case, angle_deg):
    """Longitudinal creepage of a prescribed rolling at a tread contact angle.

    The wheel turns at ω = (1 + c) V / r0 (r0 the rolling radius of the rigid start
    contact); the rigid yawed contact whose rail slope is closest to ``angle_deg`` has the
    radius r, so the creepage there is (1 + c) r / r0 − 1. Returns that and r − r0 [m].
    The radius is the height of the axle over the contact point (the contact's angle about
    the axle, its lead over r, is below 0.03 rad here).
    """
    ref = wr.fe.seed004_case(**{k: case[k] for k in ("angle_of_attack", "flange_clearance")
                                if k in case})
    y_flange = flange_contact_offset(ref)

    def radius(y_off, yaw):
        c = wr.fe.transition.yawed_contact(ref, y_off, yaw)
        return c["z_off"] + ref.radius - c["tread"]["z"], np.degrees(c["tread"]["angle"])

    r0, _ = radius(y_flange - ref.flange_clearance, 0.0)
    rows = [radius(y_flange - d, ref.angle_of_attack) for d in np.arange(0.0, 3e-3, 1e-4)]
    r, _ = min(rows, key=lambda ra: abs(ra[1] - angle_deg))
    return (1.0 + case["creepage"]) * r / r0 - 1.0, r - r0


def creep(name, start, normal):
    """A run at a prescribed creepage (``--set creepage=...``, angle of attack 0): the tread
    patch's medians from ``start`` [m] to the end against Kalker's exact theory at its
    contact angle and Fn, (a) at the same creepage and (b) at the same F_long."""
    p = xr.open_dataset(os.path.join(RESULTS, f"{name}_patches.nc")).load()
    h = xr.open_dataset(os.path.join(RESULTS, f"{name}_history.nc")).load()
    with open(os.path.join(RESULTS, f"{name}_info.json")) as f:
        case = json.load(f)["case"]
    s = p.travel.values
    m = (s >= start) & np.isfinite(p.Fn.values[:, 0])
    med = lambda v: float(np.median(v[m, 0]))  # noqa: E731
    fn, fl, ft = med(p.Fn.values), abs(med(p.F_long.values)), abs(med(p.F_lat.values))
    ang, th = np.degrees(med(p.contact_angle.values)), np.degrees(med(np.abs(p.theta.values)))
    xi = float(np.nanmedian(h.creepage.values[h.travel.values >= start]))
    slip = tread_slip(name)
    cols = slip_columns(slip, slip.travel.values, start, s[-1] + 1e-9) if slip is not None else ""
    c = wr.fe.seed004_case(**{k: v for k, v in case.items() if k != "field_travel"})
    mu = c.mu
    print(f"{name}: creepage {100 * xi:.2f} % (prescribed), {start * 1e3:.0f}-{s[-1] * 1e3:.0f} "
          f"mm, {m.sum()} outputs")
    print(f"  FE      : angle {ang:5.2f}°, Fn {fn / 1e3:6.1f} kN, F_long {fl / 1e3:6.2f} kN "
          f"({fl / (mu * fn):4.2f} mu Fn), F_lat {ft / 1e3:6.2f} kN, θ {th:5.1f}°, adhering "
          f"{med(p.adhesion.values):4.2f}; mean slip long, lat [m/s], angle {cols}")
    ws, tr = wheelset_track(c)
    t0 = time.process_time()
    *_, q = at_state(c, ws, tr, ang, fn, None, normal, xi=xi)
    print(f"  Kalker  : same creepage ({100 * -q.xi:.2f} %, spin {q.phi:+.3f} 1/m): Fn "
          f"{q.Fn / 1e3:6.1f} kN, F_long {abs(q.Fx) / 1e3:6.2f} kN ({abs(q.Fx) / (mu * q.Fn):4.2f}"
          f" mu Fn), F_lat {abs(q.Fs) / 1e3:6.2f} kN, θ {theta_of(q):5.1f}°")
    *_, r = at_state(c, ws, tr, ang, fn, fl, normal)
    print(f"  Kalker  : same F_long: creepage {100 * -r.xi:.2f} %, F_lat {abs(r.Fs) / 1e3:6.2f}"
          f" kN, θ {theta_of(r):5.1f}°; {time.process_time() - t0:.0f} s CPU", flush=True)


def rail_column(rail, t_first, a, b, approach):
    """Median of the rail head's lateral velocity over the bin [a, b) from the flange's
    first force, over the approach speed (empty where the record does not cover it)."""
    t, v = rail
    m = (t - t_first >= a) & (t - t_first < b) & np.isfinite(v)
    return f"   {np.median(v[m]) / approach:+7.2f}      " if m.any() else " " * 22


def slip_columns(slip, tau, a, b):
    """Medians of the tread's mean slip and its angle over the fields' outputs in [a, b)."""
    m = (tau >= a - 1e-12) & (tau < b - 1e-12) & np.isfinite(slip.angle.values)
    if not m.any():
        return ""
    sl, st = np.median(slip.slip_long.values[m]), np.median(slip.slip_lat.values[m])
    return f"   {sl:+6.2f} {st:+6.2f}  {np.median(np.abs(slip.angle.values[m])):5.1f}° ({m.sum()})"


def shift_at_angle(ws, tr, target_deg):
    """Wheelset shift [m] at which the right wheel's rigid primary contact has the given
    contact angle (bisection below the jump onto the flange)."""
    jump = module_jump_shift(ws, tr)
    lo, hi = jump - 6e-3, jump - 1e-5
    for _ in range(30):
        m = 0.5 * (lo + hi)
        cp = wr.contact_points(ws, tr, m)
        if np.degrees(cp.right.contact_angle[cp.right.primary]) < target_deg:
            lo = m
        else:
            hi = m
    cp = wr.contact_points(ws, tr, 0.5 * (lo + hi))
    return 0.5 * (lo + hi), float(np.degrees(cp.right.contact_angle[cp.right.primary]))


def secant(f, goal, a_, b_, tol, iters):
    """Secant iteration for ``f(x)[0] = goal`` from ``a_`` and ``b_``: the last iterate
    and ``f(x)[1]`` there (within ``tol`` of the goal, or after ``iters`` updates)."""
    fa, _ = f(a_)
    fb, extra = f(b_)
    for _ in range(iters):
        if abs(fb - goal) < tol:
            break
        c_ = b_ + (goal - fb) * (b_ - a_) / (fb - fa)
        a_, fa = b_, fb
        b_, (fb, extra) = c_, f(c_)
    return b_, extra


def solve(case, shift, traction, normal, Q=None, f_long=None, xi=None):
    """The module's tread contact with F_long = traction × Q (or ``f_long`` [N]), or with
    the creepage ``xi`` of its largest patch (the wheel's, positive when driven), under the
    vertical load Q [N] (default the static wheel load)."""
    ws, tr = wheelset_track(case)
    alpha, V = case.angle_of_attack, case.speed
    if Q is None:
        Q = case.suspension.wheel_load(211.0)      # the FE wheel's mass on the 4 mm mesh
    pos = WheelRailPosition(ws, tr, shift, yaw=alpha, roll=0.0, vertical_load=Q)
    om0 = V / case.radius
    if xi is None:
        goal = traction * Q if f_long is None else f_long

        def fx(omega):
            ps = tread_patches(case, pos, omega, V * np.sin(alpha), normal)
            return sum(p.Fx for p in ps), ps

        om, ps = secant(fx, goal, om0 * (1 + 1e-3), om0 * (1 + 4e-3),
                        0.002 * abs(goal) + 5.0, 12)
    else:
        def creepage(omega):
            ps = tread_patches(case, pos, omega, V * np.sin(alpha), normal)
            return -max(ps, key=lambda q: q.Fn).xi, ps

        om, ps = secant(creepage, xi, om0 * (1 + xi - 5e-4), om0 * (1 + xi + 5e-4),
                        1e-3 * abs(xi) + 1e-6, 8)
    return Q, om / om0 - 1.0, ps


def at_state(case, ws, tr, angle, fn, f_long, normal, xi=None):
    """The module's tread contact at the contact angle ``angle`` [deg], normal force ``fn``
    and longitudinal force ``f_long`` [N] (or creepage ``xi``, see :func:`solve`): the
    shift, the vertical load (iterated until the module's Fn is ``fn``), the relative
    angular velocity and the patch."""
    shift, got = shift_at_angle(ws, tr, angle)
    Q = fn * np.cos(np.radians(got))
    for _ in range(3):
        _, dom, ps = solve(case, shift, 0.0, normal, Q=Q, f_long=f_long, xi=xi)
        p = max(ps, key=lambda q: q.Fn)
        Q *= fn / p.Fn
    return shift, got, Q, dom, p


def tread_patches(case, pos, omega, v_lat, normal):
    """The module's right-wheel patches (Fn > 1 N) at angular velocity ``omega`` [rad/s] and
    the wheelset's lateral velocity ``v_lat`` [m/s] (V sin α: moving along its heading)."""
    mot = wr.Motion(case.speed, omega=omega, lateral_velocity=v_lat)
    res = solve_wheelrail(pos, mot, case.mu, normal=normal, tangential="exact")
    return [p for p in res.side("right") if p.Fn > 1.0]


def theta_of(p):
    """θ [deg] of a module patch: atan(|lateral| / |longitudinal| tangential force)."""
    return float(np.degrees(np.arctan2(abs(p.Fs), abs(p.Fx))))


def after(a):
    """θ of the tread patch once the flange stops the wheel's lateral approach: at each
    pre-onset state (contact angle, F_long = traction × Q, the wheel moving along its
    heading) the angular velocity is kept and the lateral velocity against the rail reduced
    by ``dv``: by V sin α (the tread stopped laterally on the rail, the largest lateral slip
    the approach can give) and by the dv at which θ reaches ``--target``."""
    case = wr.fe.seed004_case(a.aoa)
    ws, tr = wheelset_track(case)
    V, alpha = case.speed, case.angle_of_attack
    v0 = V * np.sin(alpha)
    normal = wr.normal.Bem(element_size=a.element)
    print(f"S1002 on 54E1 1:{1 / np.tan(case.inclination):.0f}, yaw {a.aoa * 1e3:g} mrad, "
          f"V sin(yaw) = {v0:.3f} m/s, mu {case.mu}, BEM {a.element * 1e3:g} mm + exact; "
          f"before: F_long = traction x Q, moving along the heading; after: the same omega "
          f"and load, lateral velocity V sin(yaw) - dv")
    print("  contact angle  traction  xi [%]  eta [%]  spin [1/m]  theta before  "
          f"theta at dv = V sin(yaw)  dv for {a.target:g} deg [m/s] (/ V sin yaw)  CPU [s]")
    states = [(ang, trc, None) for ang in a.angles for trc in a.traction]
    states += [(st[0], None, st[1:]) for st in a.state]
    for ang, trc, forces in states:
        t0 = time.process_time()
        if forces is None:          # the static load, F_long = traction × Q
            shift, got = shift_at_angle(ws, tr, ang)
            Q, dom, ps = solve(case, shift, trc, normal)
            p0 = max(ps, key=lambda q: q.Fn)
            label = f"{trc:4.2f}"
        else:                       # an FE state: Fn and F_long [kN]
            shift, got, Q, dom, p0 = at_state(case, ws, tr, ang, forces[0] * 1e3,
                                              forces[1] * 1e3, normal)
            label = f"Fn {forces[0]:g}, F_long {forces[1]:g} kN"
        omega = (1.0 + dom) * V / case.radius
        pos = WheelRailPosition(ws, tr, shift, yaw=alpha, roll=0.0, vertical_load=Q)

        def th(dv, pos=pos, omega=omega):
            return theta_of(max(tread_patches(case, pos, omega, v0 - dv, normal),
                                key=lambda q: q.Fn))

        th_stop = th(v0)
        lo, hi = 0.0, 4.0 * v0
        if th(hi) < a.target:
            need = f"> {hi:.2f}"
        else:
            for _ in range(12):
                mid = 0.5 * (lo + hi)
                lo, hi = (mid, hi) if th(mid) < a.target else (lo, mid)
            need = f"{0.5 * (lo + hi):5.2f} ({0.5 * (lo + hi) / v0:4.2f})"
        print(f"  {got:8.1f}°      {label}   {100 * p0.xi:+6.2f}  {100 * p0.eta:+6.2f}"
              f"    {p0.phi:+6.3f}      {theta_of(p0):5.1f}°          {th_stop:5.1f}°"
              f"                  {need}          {time.process_time() - t0:5.1f}",
              flush=True)


def module(a):
    case = wr.fe.seed004_case(a.aoa)
    ws, tr = wheelset_track(case)
    print(f"S1002 on 54E1 1:{1 / np.tan(case.inclination):.0f}, yaw {a.aoa * 1e3:g} mrad, "
          f"lateral velocity V sin(yaw) (no lateral creepage), mu {case.mu}, BEM "
          f"{a.element * 1e3:g} mm + exact; F_long = traction x Q")
    print("  contact angle  shift [mm]  traction  Fn [kN]  F_long  F_lat [kN]  "
          "theta [deg]  spin [1/m]  CPU [s]")
    for ang in a.angles:
        shift, got = shift_at_angle(ws, tr, ang)
        for trc in a.traction:
            t0 = time.process_time()
            Q, dom, ps = solve(case, shift, trc, wr.normal.Bem(element_size=a.element))
            p = max(ps, key=lambda q: q.Fn)
            th = theta_of(p)
            print(f"  {got:8.1f}°     {shift * 1e3:7.2f}     {trc:4.2f}   {p.Fn / 1e3:7.1f}"
                  f"  {p.Fx / 1e3:6.1f}  {p.Fs / 1e3:6.1f}      {th:5.1f}"
                  f"       {p.phi:6.3f}   {time.process_time() - t0:5.1f}", flush=True)


def main():
    ap = argparse.ArgumentParser()
    sub = ap.add_subparsers(dest="cmd", required=True)
    pf = sub.add_parser("fields", help="θ of FE runs from their surface fields")
    pf.add_argument("names", nargs="+")
    pf.add_argument("--module", action="store_true",
                    help="compare with BEM + exact at each window's FE state")
    pj = sub.add_parser("jump", help="the tread θ in time around the onset")
    pj.add_argument("names", nargs="+")
    pj.add_argument("--bin", type=float, default=3e-5, help="bin width [s]")
    pj.add_argument("--before", type=float, default=1.2e-4, help="[s]")
    pj.add_argument("--after", type=float, default=1.2e-3, help="[s]")
    ps = sub.add_parser("steady", help="the tread patch of a run without onset over travel, "
                        "against Kalker's exact theory at its state")
    ps.add_argument("names", nargs="+")
    ps.add_argument("--from", dest="start", type=float, default=0.03, help="[m]")
    ps.add_argument("--width", type=float, default=0.02, help="bin width [m]")
    ps.add_argument("--module", action="store_true",
                    help="BEM (--element) + exact at the last bin's state")
    ps.add_argument("--element", type=float, default=5e-4, help="BEM element size [m]")
    pc = sub.add_parser("creep", help="runs at a prescribed creepage against Kalker's exact "
                        "theory at the same creepage and at the same F_long")
    pc.add_argument("names", nargs="+")
    pc.add_argument("--from", dest="start", type=float, default=0.035, help="[m]")
    pc.add_argument("--element", type=float, default=5e-4, help="BEM element size [m]")
    pm = sub.add_parser("module", help="θ from Kalker's exact theory against the traction")
    pm.add_argument("--aoa", type=float, default=0.025)
    pm.add_argument("--angles", type=float, nargs="+", default=[8.0, 16.0, 20.0, 24.0])
    pm.add_argument("--traction", type=float, nargs="+", default=[0.3, 0.4, 0.5])
    pm.add_argument("--element", type=float, default=2.5e-4, help="BEM element size [m]")
    pa = sub.add_parser("after", help="θ from Kalker's exact theory once the flange stops "
                        "the wheel's lateral approach")
    pa.add_argument("--aoa", type=float, default=0.025)
    pa.add_argument("--angles", type=float, nargs="+", default=[7.0, 16.0, 20.0])
    pa.add_argument("--traction", type=float, nargs="+", default=[0.3, 0.4, 0.5, 0.55])
    pa.add_argument("--target", type=float, default=70.0, help="θ to reach [deg]")
    pa.add_argument("--state", type=float, nargs=3, action="append", default=[],
                    metavar=("ANGLE", "FN", "F_LONG"), help="also an FE tread state: contact "
                    "angle [deg], Fn and F_long [kN] (repeatable)")
    pa.add_argument("--element", type=float, default=5e-4, help="BEM element size [m]")
    for p in (pf, pj, ps, pc, pm, pa):
        p.add_argument("--out")
    a = ap.parse_args()
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf) if a.out else contextlib.nullcontext():
        if a.cmd == "fields":
            for name in a.names:
                one(name, a.module)
        elif a.cmd == "jump":
            for name in a.names:
                jump(name, a.bin, a.before, a.after)
        elif a.cmd == "steady":
            for name in a.names:
                steady(name, a.start, a.width, a.module, wr.normal.Bem(element_size=a.element))
        elif a.cmd == "creep":
            for name in a.names:
                creep(name, a.start, wr.normal.Bem(element_size=a.element))
        elif a.cmd == "after":
            after(a)
        else:
            module(a)
        print(f"load average {os.getloadavg()[0]:.1f}")
    if a.out:
        print(buf.getvalue(), end="")
        with open(a.out, "w") as f:
            f.write(buf.getvalue())


if __name__ == "__main__":
    main()
