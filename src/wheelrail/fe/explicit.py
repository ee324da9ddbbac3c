"""The explicit (central-difference) rolling integrator.

Lumped mass × ``mass_scaling``; step = ``courant`` × the smaller of the element
Courant limit and the contact-spring limit (with its dashpot); Rayleigh damping
C = α M + β K; normal contact dashpots at ``contact_damping`` of critical on the
penalty springs. Step 1 (load) by dynamic relaxation: the wheel touches the rail, the load rises
smoothly, mass-proportional damping tuned to the lowest thickness mode and a critical
axle dashpot, friction off. Step 2 rolls.

Why contact dashpots
--------------------
The axle (the wheel's rigid vertical motion) has a dashpot too (``axle_damping`` of
critical on the Hertz stiffness): with mass scaling, the wheel's bounce on the contact is
slow (periods comparable to the travel) and, undamped, biases the mean normal force
over a finite window (+1.5 % with mass scaling 400 on the 2 mm mesh).

The penalty springs of the contact layer carry the stiffest mode of the model (its
frequency sets the stable step). Undamped, it rings at that frequency (2.75 MHz
unscaled, 137 kHz with mass scaling 400 on the 2 mm mesh): the normal force then
swings by ±30 % and Fx has a 17-23 % standard deviation from step to step. A dashpot
on the relative normal velocity of each closed pair damps that mode (its force is
proportional to the rate of change of the penetration, which vanishes in steady
rolling except where nodes enter and leave the patch); docs/fe_plastic.md measures that
the steady forces do not change with it, and do not change with the mass scaling.

Each step (one force evaluation) is two parallel phases of
:func:`wheelrail.fe._explicit.run_steps`, which runs a block of steps in one parallel region:
the element forces and the contact, then the node update fused into the second phase.
The plastic state is updated in place (the explicit step is always accepted).
"""

from __future__ import annotations

import time

import numba
import numpy as np

from ..errors import InputError
from ._explicit import node_groups, phase_one_tasks, run_steps
from .model import build_model
from .patch_dataset import patch_from_contact
from .restart import read_restart
from .rolling import (
    COLUMNS,
    RollingResult,
    _smoothstep,
    contact_dashpots,
    contact_plane_forces,
    contact_state,
    depth_profiles,
    history_dataset,
    plastic_fields,
    progress_bar,
    restart_writer,
    speed_profile,
    stable_time_step,
    steady_statistics,
    steady_window,
)

__all__ = ["solve_explicit", "time_step"]


def time_step(case, model) -> tuple[float, float]:
    """(step, stable step) [s] of an explicit run; an InputError if ``case.time_step`` is
    above the stable step."""
    dt_stable = stable_time_step(model)
    if case.time_step is not None:
        if case.time_step > dt_stable:
            raise InputError(f"time_step {case.time_step!r} s exceeds the stable explicit step "
                             f"{dt_stable:.3g} s (Courant limit of the {case.mesh_size:g} m mesh)")
        return case.time_step, dt_stable
    return case.courant * dt_stable, dt_stable


def axle_dashpot(model, zeta: float, M_w: float) -> float:
    """Vertical dashpot on the axle [N s/m]: ζ of critical damping of the (scaled) wheel mass
    on the Hertz contact stiffness dF/dδ = 3 F / (2 δ) (Johnson 1985, eq. 4.23 differentiated).
    It acts on the axle's rigid vertical velocity only, which vanishes in steady rolling."""
    hz = model.geometry["hertz"]
    if hz is None or zeta == 0:
        return 0.0
    k = 1.5 * model.geometry["normal_load"] / float(hz.penetration)
    return float(2.0 * zeta * np.sqrt(k * M_w))


def relaxation_steps(case, model, dt) -> tuple[int, float]:
    """Steps of the dynamic relaxation and its mass-proportional damping coefficient [1/s].

    Damping: twice the angular frequency ω1 of the lowest thickness mode of the kept
    bodies. Length: 12 periods of that mode; the load rises smoothly over the first 40 %
    (a quasi-static load path for plastic bodies). During the relaxation the axle's inertia
    is reduced so that its bounce on the Hertz stiffness is not slower than ω1 (only the
    path to the static state changes), with a critical dashpot (:func:`relaxation_axle`).
    """
    depth = model.wheel.axes[2][-1]
    omega1 = np.pi * model.material.wave_speed / (2 * depth) / np.sqrt(case.mass_scaling)
    return int(np.ceil(12 * 2 * np.pi / omega1 / dt)), 2.0 * omega1


def relaxation_axle(model, M_w, omega1):
    """(mass [kg], dashpot [N s/m]) of the axle dof during the dynamic relaxation."""
    hz = model.geometry["hertz"]
    if hz is None:
        return M_w, omega1 * M_w
    k = 1.5 * model.geometry["normal_load"] / float(hz.penetration)
    M = min(M_w, k / omega1 ** 2)
    return M, 2.0 * np.sqrt(k * M)


#: Fraction of the dynamic relaxation over which the load rises (smooth step).
RELAXATION_RAMP = 0.4

#: Most steps per call of the numba loop (the progress bar moves between calls).
BLOCK = 256

#: The energies of a rolling result, in the order of its history columns.
ENERGIES = ("kinetic", "internal", "contact", "friction", "damping", "external",
            "contact_work", "plastic_work")


def _relaxation_inputs(model, n1, n_ramp, load):
    """Per-step inputs of the dynamic relaxation (:meth:`_ContactLoop.run`): the wheel angle
    and the rail travel are zero; the axle load rises by a smooth step over ``n_ramp``."""
    loads = np.array([load * float(_smoothstep((k + 1) / n_ramp)) for k in range(n1)])
    return (np.full(n1, np.cos(0.0)), np.full(n1, np.sin(0.0)), np.zeros(n1),
            np.full(n1, model.lateral_shift(0.0)), np.zeros(n1), loads)


def _rolling_inputs(model, case, speed, R, dt, n2, k0, s, psi, t):
    """Per-step inputs of the rolling step from step k0 on, accumulated as the time loop
    does: the rail speed V at the half step, s += V Δt, ψ += V (1 − ξ) / r_c Δt, t += Δt.
    Returns (cos ψ, sin ψ, s, lateral drift, t, loads (unused)) over the steps, and s, ψ,
    t at the start of every step (index n2: the end)."""
    s_k = np.zeros(n2 + 1)
    psi_k = np.zeros(n2 + 1)
    t_k = np.zeros(n2 + 1)
    cps = np.zeros(n2)
    sps = np.zeros(n2)
    lat = np.zeros(n2)
    for k in range(k0, n2 + 1):
        s_k[k], psi_k[k], t_k[k] = s, psi, t
        if k == n2:
            break
        cps[k], sps[k] = np.cos(psi), np.sin(psi)
        lat[k] = model.lateral_shift(s)
        V = speed(t + 0.5 * dt)
        s += V * dt
        psi += V * (1.0 - case.xi) / R * dt
        t += dt
    return (cps, sps, s_k[:n2], lat, t_k[:n2], np.zeros(n2)), s_k, psi_k, t_k


def solve_explicit(case, progress, output_every, io):
    model = build_model(case, rolling=True)
    travel = model.geometry["travel"]
    dt, dt_stable = time_step(case, model)
    m = model.mass * case.mass_scaling
    n = model.n_nodes
    inv_m = np.where(m > 0, 1.0 / np.where(m > 0, m, 1.0), 0.0)
    inv_m[model.fixed] = 0.0
    M_w = float(m[:model.nw].sum())
    alpha, beta = case.rayleigh
    load, mu = case.Fn, case.mu
    R = model.geometry["r_c"]
    n1, a_dr = relaxation_steps(case, model, dt)
    speed, t_end = speed_profile(case, travel)
    n2 = int(np.ceil(t_end / dt))
    every = output_every or max(1, n2 // 400)
    window = steady_window(case, model)
    passes = case.passes

    # contact nodes: slaves (wheel surface) then masters (rail surface), rows of fcon
    master_nodes = model.master.ravel()
    cidx = np.concatenate([model.slave, master_nodes])
    cmap = -np.ones(n, np.int64)
    cmap[cidx] = np.arange(cidx.size)
    fcon = np.zeros((cidx.size, 3))
    cdamp = contact_dashpots(model, case.contact_damping)
    c_axle = axle_dashpot(model, case.axle_damping, M_w)
    M_dr, c_axle_dr = relaxation_axle(model, M_w, 0.5 * a_dr)
    m_alpha_dr = a_dr * m
    m_alpha_roll = alpha * m
    f_int = np.zeros((n, 3))
    fd_beta = np.zeros((n, 3))
    state = model.new_state()

    fast = _ContactLoop(model, cdamp, dt, fcon)
    has_beta = beta > 0

    clock = np.zeros(2)                      # wall and CPU seconds in the time loop

    def run(k0, k1, relax, per_step, ax, axle, mu_now, m_alpha, **rolling):
        """Steps k0 … k1 − 1 in numba (with β damping one at a time: β K v from Python)."""
        t0 = (time.perf_counter(), time.process_time())
        try:
            return _run(k0, k1, relax, per_step, ax, axle, mu_now, m_alpha, **rolling)
        finally:
            clock[0] += time.perf_counter() - t0[0]
            clock[1] += time.process_time() - t0[1]

    def _run(k0, k1, relax, per_step, ax, axle, mu_now, m_alpha, **rolling):
        if has_beta and not relax:
            for k in range(k0, k1):          # β K v_{k-1/2}: from v only, before the update
                model.internal_force(v, fd_beta, elastic=True)
                fd_beta[...] *= beta
                c = fast.run(k, k + 1, relax, per_step, ax, axle, mu_now, m_alpha, True, state,
                             u, v, f_int, fd_beta, inv_m, m, cmap, dt, **rolling)
            return c
        return fast.run(k0, k1, relax, per_step, ax, axle, mu_now, m_alpha, False, state, u, v,
                        f_int, fd_beta, inv_m, m, cmap, dt, **rolling)

    pass_rows = []
    if io["restart"] is not None:
        st = read_restart(io["restart"], model, dt)
        u, v, w, vw, psi, s, t = (st[k] for k in ("u", "v", "w", "vw", "psi", "s", "t"))
        e_int0, relax_error, k0, p0 = st["e_int0"], st["relax_error"], st["k"], st["pass"]
        c, E, rows = st["c"], st["E"], st["rows"].tolist()
        hist = st["hist"]
        pass_rows = list(st["pass_rows"]) if "pass_rows" in st else []
        if state is not None:
            state.committed[:] = st["plastic"]
        fast.restore(c)
        fresh = False
        label = f"FE explicit ({model.n_elements} el.), restart"
    else:
        u = np.zeros((n, 3))
        v = np.zeros((n, 3))
        w = 0.0                           # touching: the load rises during the relaxation
        vw = 0.0
        k0, p0 = 0, 0
        fresh = True
        label = f"FE explicit ({model.n_elements} el.)"
    total = passes * (n1 + n2)
    bar = progress_bar(progress, total, label)
    done = p0 * (n1 + n2) + (n1 + k0 if not fresh else 0)

    for p in range(p0, passes):
        if fresh:
            # ---- step 1: dynamic relaxation to the static contact (friction off)
            psi = s = t = 0.0
            w = 0.0                       # back at the start, touching; the load rises again
            v[:] = 0.0
            vw = 0.0
            fast.start(u, w, psi, s)
            n_ramp = max(1, int(RELAXATION_RAMP * n1))
            per_step = _relaxation_inputs(model, n1, n_ramp, load)
            ax = np.array([w, vw, 0.0, 0.0])
            for k in range(0, n1, BLOCK):
                c = run(k, min(n1, k + BLOCK), True, per_step, ax, np.array([M_dr, c_axle_dr]),
                        0.0, m_alpha_dr)
                if bar is not None:
                    bar.update(bar.task_ids[0], completed=done + k)
            w, fcw = float(ax[0]), fast.sums[2]
            done += n1
            relax_error = abs(fcw - load) / load
            v[:] = 0.0
            vw = 0.0
            e_int0 = float(fast.sums[6] + fast.sums[7])
            k0 = 0
            rows = []
            hist = np.zeros((n2, 5))
            E = dict(kinetic=0.0, internal=0.0, contact=0.0, friction=0.0, damping=0.0,
                     external=0.0, contact_work=0.0, plastic_work=0.0)
        fresh = True

        def snapshot(k_done):
            return dict(u=u, v=v, w=w, vw=vw, psi=psi, s=s, t=t, e_int0=e_int0,
                        relax_error=relax_error, k=k_done, c=contact_state(c), E=E,
                        rows=np.array(rows, float).reshape(-1, len(COLUMNS)), hist=hist,
                        **{"pass": p}, pass_rows=np.array(pass_rows, float),
                        **({"plastic": state.committed} if state is not None else {}))

        maybe_write = restart_writer(io, model, dt, n2)
        # ---- step 2: rolling (energies counted from here)
        per_step, s_end, psi_end, t_end_k = _rolling_inputs(model, case, speed, R, dt, n2, k0,
                                                            s, psi, t)
        ax = np.array([w, vw, e_int0, 0.0])
        axle = np.array([load, M_w, alpha * M_w + c_axle])
        Ea = np.array([E[key] for key in ENERGIES])
        buf = np.zeros((n2 // every + 2, len(COLUMNS)))
        k = k0
        while k < n2:
            k1 = min(n2, k + BLOCK)
            if maybe_write.every:
                k1 = min(k1, (k // maybe_write.every + 1) * maybe_write.every)
            nrow = np.zeros(1, np.int64)
            c = run(k, k1, False, per_step, ax, axle, mu, m_alpha_roll, E=Ea, hist=hist,
                    rows=buf, nrow=nrow, every=every, n_steps=n2)
            rows.extend(buf[:nrow[0]].tolist())
            E = dict(zip(ENERGIES, Ea.tolist()))
            w, vw = float(ax[0]), float(ax[1])
            s, psi, t = s_end[k1], psi_end[k1], t_end_k[k1]
            if bar is not None:
                bar.update(bar.task_ids[0], completed=done + k1 - 1)
            k = k1
            maybe_write(k, lambda: snapshot(k))
        done += n2
        if passes > 1:
            pass_rows.append(_pass_summary(model, case, u, state, hist, window))
    if bar is not None:
        bar.stop()
    steady = _steady(model, hist, window)
    extra = {"time_step": dt, "steps": passes * (n1 + n2), "relaxation_steps": n1,
             "relaxation_load_error": relax_error, "passes": passes,
             "contact_damping": case.contact_damping}
    ds = history_dataset(rows, case, model, extra)
    patch = patch_from_contact(model, c, psi, dt)
    fields = plastic_fields(model, u, state)
    info = {"time_step": dt, "steps": passes * (n1 + n2), "stable_time_step": dt_stable,
            "restarted_at_step": int(st["k"]) if io["restart"] is not None else 0,
            "relaxation_steps": n1, "rolling_steps": n2,
            "loop_wall": float(clock[0]), "loop_cpu": float(clock[1])}
    return RollingResult(ds, patch, steady["Fx"], steady["Fy"], patch.attrs["p_max"],
                         patch.attrs["a"], patch.attrs["b"], model, u, info, steady, state,
                         fields, _passes_dataset(pass_rows, model, state))


class _ContactLoop:
    """The explicit steps in preallocated buffers.

    Per step the two phases of :func:`wheelrail.fe._explicit.run_steps`: the element
    forces (into ``f``, which must hold zeros: the node update leaves it so), the surface
    kinematics and :func:`wheelrail.fe._kernels.node_to_surface` per slave, the contact
    forces into ``fcon`` (rows: slaves in the wheel frame, then the master grid) and the
    node update (:attr:`totals`: its sums, :data:`wheelrail.fe._explicit.ADV_COLUMNS`);
    :meth:`run` runs blocks of steps in one parallel region. The
    per-slave results are those of :meth:`wheelrail.fe.model.Model.contact` (same positions,
    increments, normals and contact law). Positions and tangential forces are
    double-buffered (row :attr:`cur` holds the last ones); :attr:`sums` holds Fx, Fy, Fz,
    Σ p_n, the friction dissipation, the penalty energy, the elastic strain energy and the
    plastic work of the last step.
    """

    def __init__(self, model, cdamp, dt, fcon):
        self.model = model
        ns = model.slave.size
        nx, ny = model.master.shape
        self.slave = np.ascontiguousarray(model.slave, np.int64)
        self.master = np.ascontiguousarray(model.master, np.int64)
        self.ref_s = np.ascontiguousarray(model.wheel.nodes[self.slave], float)
        self.ref_m = np.ascontiguousarray(model.rail.nodes[self.master - model.nw], float)
        self.x_ref = np.ascontiguousarray(model.rail.axes[0], float)
        self.y_ref0 = np.ascontiguousarray(model.rail.axes[1], float)
        self.y_ref = self.y_ref0.copy()
        self.cdamp, self.inv_dt, self.fcon = cdamp, 1.0 / dt, fcon
        self.reach = 5.0 * model.case.mesh_size
        self.xsb = np.zeros((2, ns, 3))            # row cur: the last positions
        self.xmb = np.zeros((2, nx, ny, 3))
        self.ftb = np.zeros((2, ns, 3))
        self.cur = 0
        self.dxs = np.zeros((ns, 3))
        self.dxm = np.zeros((nx, ny, 3))
        self.nm = np.zeros((nx, ny, 3))
        self.out = {
            "fs": np.zeros((ns, 3)), "fm": np.zeros((nx, ny, 3)), "gap": np.ones(ns),
            "pn": np.zeros(ns), "status": np.zeros(ns, np.int64),
            "cell": np.zeros((ns, 2), np.int64), "rt": np.zeros((ns, 2)),
            "normal": np.zeros((ns, 3)), "slip": np.zeros(ns), "energy": np.zeros(ns),
        }
        self.sums = np.zeros(8)
        nc = model.chunks.size - 1
        self.echunk = np.zeros((nc, 2))
        self.energy = np.zeros((0, 2))             # element energies: summed, not stored
        self.tasks = phase_one_tasks((nc + 1) // 2, min(64, max(1, ns // 64)))
        self.gptr, self.gnodes = node_groups(model.conn, model.chunks, model.n_nodes)
        self.partial = np.zeros((self.gptr.size - 1, 7))
        self.totals = np.zeros(7)
        # the element kernel streams its connectivity every step: 32 bytes per element
        self.conn = model.conn.astype(np.int32) if model.conn.max() < 2**31 else model.conn
        self.mat = (model.material.lam, model.material.shear_modulus) + tuple(model._hardening)

    def start(self, u, w, psi, s):
        """The positions of the first step's 'previous' state; zero tangential forces."""
        m = self.model
        self.xsb[self.cur] = m.slave_positions(u, w, psi)
        self.xmb[self.cur] = m.master_positions(u, s)
        self.ftb[self.cur] = 0.0

    def restore(self, c):
        """The previous state from a contact dict (a restart file)."""
        self.xsb[self.cur] = c["xs"]
        self.xmb[self.cur] = c["xm"]
        self.ftb[self.cur] = c["ft"]
        for k, buf in self.out.items():
            if k in c:
                buf[...] = c[k]

    def contact(self):
        """The contact dict of the last step (views of the buffers)."""
        c = self.cur
        return dict(self.out, xs=self.xsb[c], xm=self.xmb[c], ft=self.ftb[c])

    def run(self, k0, k1, relax, per_step, ax, axle, mu, m_alpha, has_beta, state, u, v, f,
            fd_beta, inv_m, mass, cmap, dt, E=None, hist=None, rows=None, nrow=None,
            every=1, n_steps=0):
        """Steps k0 … k1 − 1 (:func:`wheelrail.fe._explicit.run_steps`): ``per_step`` =
        (cos ψ, sin ψ, rail travel, lateral drift, time, axle load) arrays over the steps;
        ``ax`` = [w, vw, e_int0, F_z] is updated; the plastic state in place."""
        m, o = self.model, self.out
        ed = m.edata
        lam, G, hp, tp, ts = self.mat
        plastic = state is not None
        # an explicit step is always accepted: the state is updated in place (st_out = st_in;
        # each integration point reads its own state before writing it)
        st = state.committed if plastic else _NO_STATE
        hg = ed.hx if ed.hx.shape[0] else ed.gamma          # compact hourglass data
        if E is None:
            E, hist, rows, nrow = _NO_E, _NO_HIST, _NO_HIST, _NO_ROW
        self.cur = run_steps(
            k0, k1, self.cur, relax, numba.get_num_threads(),
            (every, n_steps, ax, E, hist, rows, nrow, axle), tuple(per_step),
            (u, self.conn, m.chunks, ed.dNdx, ed.wdet, hg, ed.khg, lam, G, plastic, hp, tp, ts,
             st, st, f, self.energy, self.echunk),
            (self.ref_s, self.slave, m.z_axle, self.dxs, self.ref_m, self.master, self.dxm,
             self.nm, m.slave_area, m.kn, self.cdamp, self.x_ref, self.y_ref, self.y_ref0,
             self.xsb, self.xmb, self.ftb),
            (mu, self.reach, m.g0, self.inv_dt),
            (o["energy"], o["fs"], o["fm"], o["gap"], o["pn"], o["status"], o["cell"], o["rt"],
             o["normal"], o["slip"], self.fcon, self.sums),
            (v, fd_beta, has_beta, m_alpha, inv_m, mass, cmap, dt, self.gptr, self.gnodes,
             self.partial, self.totals),
            self.tasks)
        if plastic:                          # updated in place: nothing to commit
            state.energies = (float(self.sums[6]), float(self.sums[7]))
        return self.contact()


_NO_E = np.zeros(8)
_NO_HIST = np.zeros((0, 5))
_NO_ROW = np.zeros(1, np.int64)
_NO_STATE = np.zeros((0, 1, 14))


def _steady(model, hist, window):
    fy_c, fn_c = contact_plane_forces(model, hist[:, 2], hist[:, 3])
    return steady_statistics(hist[:, 0], {"Fx": hist[:, 1], "Fy": hist[:, 2], "Fz": hist[:, 3],
                                          "Fn": hist[:, 4], "Fy_contact": fy_c,
                                          "Fn_contact": fn_c}, window)


def _pass_summary(model, case, u, state, hist, window):
    """One row per pass: steady Fx, Fy, Fn and (plastic) the depth profiles of the residual
    stress (6 components), von Mises and equivalent plastic strain at the section middle."""
    st = _steady(model, hist, window)
    row = [st["Fx"], st["Fy"], st["Fn"], st["Fx_scatter"]]
    if state is not None:
        prof = _section_profiles(model, u, state)
        row += list(prof["residual_stress"].values.ravel()) + list(prof["von_mises"].values)
        row += list(prof["equivalent_plastic_strain"].values)
    return row


def _section_profiles(model, u, state):
    fields = plastic_fields(model, u, state)
    travel = model.geometry["travel"]
    a = model.geometry["a"]
    x0 = 0.25 * travel
    x1 = max(x0 + model.case.mesh_size, 0.75 * travel - 3 * a)
    return depth_profiles(fields, (x0, x1), y=model.geometry["y_c"])


def _passes_dataset(pass_rows, model, state):
    if not pass_rows:
        return None
    import xarray as xr

    rows = np.array(pass_rows, float)
    npass = rows.shape[0]
    data = {"Fx": ("pass", rows[:, 0], {"units": "N"}), "Fy": ("pass", rows[:, 1], {"units": "N"}),
            "Fn": ("pass", rows[:, 2], {"units": "N"}), "Fx_scatter": ("pass", rows[:, 3])}
    coords = {"pass": np.arange(1, npass + 1)}
    if state is not None:
        depth = 0.5 * (model.rail.axes[2][1:] + model.rail.axes[2][:-1])
        nd = depth.size
        sig = rows[:, 4:4 + 6 * nd].reshape(npass, nd, 6)
        vm = rows[:, 4 + 6 * nd:4 + 7 * nd]
        pe = rows[:, 4 + 7 * nd:4 + 8 * nd]
        coords.update(depth=("depth", depth, {"units": "m"}),
                      component=["xx", "yy", "zz", "xy", "yz", "xz"])
        data.update(residual_stress=(("pass", "depth", "component"), sig, {"units": "Pa"}),
                    von_mises=(("pass", "depth"), vm, {"units": "Pa"}),
                    equivalent_plastic_strain=(("pass", "depth"), pe))
    return xr.Dataset(data, coords=coords)
