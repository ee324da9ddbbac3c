"""The explicit time loop of the transition run: its prepared problem, state and steps (private).

:func:`wheelrail.fe.transition.run_transition` prepares a :class:`Transition` (the model,
the step, the masses, dashpots and windows of the run: frozen) and a :class:`LoopState`
(what one step changes: displacements, velocities, the axle's dofs, the outputs) and runs
:func:`step` over the steps: the element forces, :func:`contact` (the node-to-segment
search and law), :func:`node_update` (springs, ties, the central-difference update),
:func:`rigid_dofs` (the axle: vertical, rolling, lateral, roll) and :func:`output` (the
per-patch rows, the axle history, the recorded fields).

References
----------
.. [1] X. Zhao, Z. Li, Wear 271 (2011) 444-452 (explicit transient wheel-track FE model).
"""

from __future__ import annotations

import os
import time
from dataclasses import dataclass

import numpy as np

from .. import _solid as S
from .._explicit import advance
from .contact import (
    adhering,
    nodal_normals_quads,
    node_to_segment,
    patch_summary,
    scatter_master,
    split_patches,
)
from .track import GRAVITY

PATCH_FIELDS = ("Fn", "Fx", "Fy", "Fz", "F_long", "F_lat", "contact_angle", "x", "y", "z",
                "area", "p_max", "q_max", "adhesion", "theta", "n_nodes")
MAX_PATCHES = 3
#: Rows of the wheel surface in the contact-field record: from 30 mm behind to 80 mm ahead
#: of the axle (the yawed flange contact leads by up to ≈ 55 mm at 25 mrad).
FIELD_LEAD = (-0.03, 0.08)

#: The loop's state in a restart file (:func:`write_restart`).
STATE = ("u", "v", "ft", "w", "vw", "zs", "vs", "omega", "omega_mean", "psi", "s", "t",
         "fade", "xs_prev", "xm_prev", "y", "vy", "phi", "vphi", "m_roll0")
# state added after the first restart files were written: their value in older files
# (m_roll0 NaN: the roll spring's preload is taken at the next rolling step)
STATE_DEFAULTS = {"y": 0.0, "vy": 0.0, "phi": 0.0, "vphi": 0.0, "m_roll0": np.nan}


def rot(alpha, psi, phi=0.0):
    """Wheel frame to global: yaw α about z, roll φ about the heading, rolling ψ about the
    axle."""
    ca, sa = np.cos(alpha), np.sin(alpha)
    cp, sp = np.cos(psi), np.sin(psi)
    Rz = np.array([[ca, -sa, 0.0], [sa, ca, 0.0], [0.0, 0.0, 1.0]])
    Ry = np.array([[cp, 0.0, sp], [0.0, 1.0, 0.0], [-sp, 0.0, cp]])
    if phi == 0.0:
        return Rz @ Ry
    cf, sf = np.cos(phi), np.sin(phi)
    Rx = np.array([[1.0, 0.0, 0.0], [0.0, cf, -sf], [0.0, sf, cf]])
    return Rz @ Rx @ Ry


@dataclass(frozen=True)
class Transition:
    """A prepared transition run (frozen): the model and case, the step ``dt`` [s], the
    axle's constants, the dashpots of the start transient, the masses and the windows."""

    case: object
    m: object
    dt: float
    n_steps: int
    n_end: int
    n_pre: int
    every: int
    field_every: int
    progress: bool
    # the axle
    load: float
    M_axle: float
    J: float
    r0: float
    torque: float
    fixed_rolling: bool
    I_roll: float
    lat_free: bool
    roll_free: bool
    omega_roll: float
    # the dashpots of the start transient (fading over `settle`) and of the preload
    c_roll0: float
    c_rot0: float
    tau_rot: float
    alpha_m: float
    c_axle0: float
    c_pre: float
    # the kinematics
    c0: np.ndarray
    heading: np.ndarray
    e_axle: np.ndarray
    Xw: np.ndarray
    xm_ref: np.ndarray
    # contact, masses, node update
    cdamp: np.ndarray
    reach: float
    inv_m_run: np.ndarray
    inv_m_pre: object
    m_alpha_pre: object
    cmap: np.ndarray
    no_beta: np.ndarray
    # outputs: contact-field window, wave record
    fwin: object
    shape2: tuple
    line: np.ndarray
    wave_normal: np.ndarray
    x_wave: float
    j_wave: int
    n_wave: int


@dataclass
class LoopState:
    """What the steps change (the names of :data:`STATE` are those of a restart file)."""

    u: np.ndarray
    v: np.ndarray
    ft: np.ndarray
    xs_prev: np.ndarray
    xm_prev: np.ndarray
    inv_m: np.ndarray
    m_alpha: np.ndarray
    # buffers
    acc: np.ndarray
    f_int: np.ndarray
    f_tmp: np.ndarray
    fext: np.ndarray
    e_buf: list
    partial: np.ndarray
    out: dict
    status: np.ndarray
    seg: np.ndarray
    fm: np.ndarray
    wave_v: np.ndarray
    # axle and suspension
    zs: float
    omega: float
    omega_mean: float
    fade: float
    t: float
    w: float = 0.0
    vw: float = 0.0
    vs: float = 0.0
    y: float = 0.0
    vy: float = 0.0
    phi: float = 0.0
    vphi: float = 0.0
    m_roll0: float = np.nan
    psi: float = 0.0
    s: float = 0.0
    # outputs
    rows: list = None
    hist: list = None
    fields: list = None
    sf: list = None
    sf_t: list = None
    n_rec: int = 0


def settle_damping(P, st, f):
    """Mass-proportional damping α f m of the start transient (clamped nodes: none)."""
    st.m_alpha[:] = P.alpha_m * f * P.m.mass
    st.m_alpha[P.m.fixed] = 0.0


def step(P, st, k, k0, t_wall):
    """Step ``k`` of the run (``k0``: the first step of this call, ``t_wall``: its start)."""
    m, case, dt = P.m, P.case, P.dt
    pre = k < P.n_pre
    if P.n_pre and k == P.n_pre:
        # the rolling starts: the real masses, the settle damping, the rolling speed
        st.inv_m = P.inv_m_run
        st.omega = st.omega_mean = P.omega_roll
        settle_damping(P, st, st.fade)
    R = rot(case.angle_of_attack, st.psi, st.phi)
    c = P.c0 + st.s * P.heading + np.array([0.0, 0.0, st.w]) + st.y * P.e_axle
    # ---- element forces (both materials)
    st.f_int[:] = 0.0
    for g, (conn, chunks, ed, mat) in enumerate(m.groups):
        S.element_forces(st.u, conn, chunks, ed.dNdx, ed.wdet, ed.gamma, ed.khg, mat.lam,
                         mat.shear_modulus, False, np.zeros(6), np.zeros(0), np.zeros(0),
                         np.zeros((0, 1, 14)), np.zeros((0, 1, 14)), st.f_tmp, st.e_buf[g])
        st.f_int += st.f_tmp
    # ---- contact
    is_out = k % P.every == 0 or k == P.n_end - 1
    fwin = P.fwin
    rec = (is_out and not pre and fwin and fwin[0] <= st.s + dt * case.speed <= fwin[1]
           and st.n_rec % case.field_stride == 0)
    xs, dxs, dxm = contact(P, st, c, R, rec)
    node_update(P, st, R)
    Fc, M_c, m_roll = rigid_dofs(P, st, k, pre, xs, c, R)
    if 0 <= k - P.j_wave < P.n_wave:
        st.wave_v[k - P.j_wave] = st.v[P.line]
    if is_out:
        output(P, st, (k, k0, t_wall, pre, rec), (xs, c, dxs, dxm), (Fc, M_c, m_roll))


def contact(P, st, c, R, rec):
    """The contact of the step: slave and master positions, :func:`node_to_segment`, the
    master forces; ``(xs, dxs, dxm)`` (the increments only for a recorded output)."""
    m, out = P.m, st.out
    xs = c + (P.Xw + st.u[m.slave]) @ R.T
    xm = P.xm_ref + st.u[m.master]
    nmn = nodal_normals_quads(xm, m.quads)
    node_to_segment((xs, xs - st.xs_prev, m.slave_area, m.kn, m.kn, P.cdamp),
                    (xm, xm - st.xm_prev, nmn, m.quads), m.buckets.record,
                    (P.case.mu, P.reach, m.g0, 1.0 / P.dt), st.ft,
                    (out["fs"], out["gap"], out["pn"], out["ft"], st.status, st.seg, out["rt"],
                     out["normal"], out["slip"]))
    st.fm[:] = 0.0
    scatter_master(out["fs"], st.status, st.seg, out["rt"], m.quads, st.fm)
    dxs = dxm = None
    if rec:
        dxs, dxm = xs - st.xs_prev, xm - st.xm_prev
    st.ft[:] = out["ft"]
    st.xs_prev = xs
    st.xm_prev = xm
    return xs, dxs, dxm


def node_update(P, st, R):
    """External forces (contact into the wheel frame, springs, ties) and the node update."""
    m, u, v, fext = P.m, st.u, st.v, st.fext
    fext[:] = 0.0
    fext[m.slave] = st.out["fs"] @ R            # into the wheel frame
    fext[m.master] += st.fm
    m.springs.forces(u, v, fext)
    # ties: the slaves' internal and external forces act on their masters
    fs_t = fext[m.tie_slave] - st.f_int[m.tie_slave]
    for col in range(2):
        np.add.at(fext, m.tie_master[:, col], m.tie_weight[:, col, None] * fs_t)
    advance(u, v, st.acc, st.f_int, P.no_beta, False, st.m_alpha, st.inv_m, P.cmap, fext,
            P.dt, st.partial)
    u[m.tie_slave] = (m.tie_weight[:, :, None] * u[m.tie_master]).sum(axis=1)
    v[m.tie_slave] = (m.tie_weight[:, :, None] * v[m.tie_master]).sum(axis=1)
    u[m.held_xy, :2] = 0.0
    v[m.held_xy, :2] = 0.0


def rigid_dofs(P, st, k, pre, xs, c, R):
    """The axle's dofs after the step: vertical (with the primary suspension), lateral,
    roll, rolling; the fading dashpots, the travel and time. ``(Fc, M_c, m_roll)``: the
    contact force [N], its moment about the axle and about the heading [N m]."""
    case, susp, dt, out = P.case, P.case.suspension, P.dt, st.out
    Fc = out["fs"].sum(axis=0)
    arm = xs - c
    moments = np.cross(arm, out["fs"]).sum(axis=0)
    M_c = float(moments @ R[:, 1])                 # about the (rolled) axle
    m_roll = float(moments @ P.heading)
    # primary suspension: zs its extension from free length (static: −M_s g / k)
    f_sprung = -susp.stiffness * st.zs - susp.damping * (st.vs - st.vw)   # on the sprung mass
    fade_now = max(0.0, 1.0 - st.s / case.settle) if case.settle > 0 else 0.0
    c_axle = P.c_axle0 * fade_now
    if pre:
        # a massless axle on a dashpot: it creeps towards the vertical balance (the
        # sprung mass and the rolling held); the dashpots that its own velocity
        # loads (the closed contact nodes' normal dashpots, the suspension's) are
        # taken implicitly, else a stiff patch's dashpots exceed c_pre and the
        # explicit update flips sign every step
        closed = st.status > 0
        c_c = float(np.sum(P.cdamp[closed] * out["normal"][closed, 2] ** 2))
        f_el = Fc[2] + c_c * st.vw + susp.stiffness * st.zs
        c_tot = P.c_pre + c_c + susp.damping
        st.vw = (f_el - P.M_axle * GRAVITY) / c_tot if k + 1 < P.n_pre else 0.0
    else:
        aw = (Fc[2] - f_sprung - P.M_axle * GRAVITY - c_axle * st.vw) / P.M_axle
        a_s = (f_sprung - susp.sprung_mass * GRAVITY) / susp.sprung_mass
        st.vw += dt * aw
        st.vs += dt * a_s
    st.w += dt * st.vw
    st.zs += dt * (st.vs - st.vw)
    if P.lat_free and not pre:
        ay = (float(Fc @ P.e_axle) - susp.lateral_stiffness * st.y
              - susp.lateral_damping * st.vy) / P.M_axle
        st.vy += dt * ay
        st.y += dt * st.vy
    if P.roll_free and not pre:
        if np.isnan(st.m_roll0):
            st.m_roll0 = m_roll
        a_phi = (m_roll - st.m_roll0 - susp.roll_stiffness * st.phi
                 - (susp.roll_damping + P.c_roll0 * fade_now) * st.vphi) / P.I_roll
        st.vphi += dt * a_phi
        st.phi += dt * st.vphi
    if not pre:
        if not P.fixed_rolling:
            st.omega += dt * (P.torque + M_c - P.c_rot0 * fade_now
                              * (st.omega - st.omega_mean)) / P.J
            st.omega_mean += dt * (st.omega - st.omega_mean) / P.tau_rot
        st.psi += dt * st.omega
    # (re)set in steps of 2 % of the start value, and to exactly 0 at the settle distance
    if not pre and st.fade > 0.0 and (fade_now < st.fade - 0.02 or fade_now == 0.0):
        st.fade = fade_now
        settle_damping(P, st, st.fade)
    if not pre:
        st.s += dt * case.speed
    st.t += dt
    return Fc, M_c, m_roll


def output(P, st, when, kin, forces):
    """One output: the per-patch row, the axle history row, the recorded fields.
    ``when`` = (k, k0, t_wall, pre, rec), ``kin`` = (xs, c, dxs, dxm), ``forces`` =
    (Fc, M_c, m_roll) of :func:`rigid_dofs`."""
    k, k0, t_wall, pre, rec = when
    xs, c, dxs, dxm = kin
    Fc, M_c, m_roll = forces
    m, case, out, status = P.m, P.case, st.out, st.status
    shape2 = P.shape2
    ang = np.arccos(np.minimum(1.0, np.abs(out["normal"][:, 2])))
    lab, counts = split_patches(status.reshape(shape2), ang.reshape(shape2),
                                out["pn"].reshape(shape2), case.patch_split_angle)
    npatch = int(min(counts[0], 1) + min(counts[1], 1))
    lab = lab.ravel()
    row = []
    for p in range(1, MAX_PATCHES + 1):
        d = patch_summary(lab == p, xs, out["fs"], out["pn"], out["ft"], out["normal"],
                          m.slave_area, status, case.mu)
        row.append([d[f] for f in PATCH_FIELDS])
    st.rows.append(row)
    fwin = P.fwin
    if fwin and not pre and fwin[0] <= st.s <= fwin[1]:
        if rec:
            st.sf.append(contact_fields(xs, c, dxs, dxm, P.dt, out, status, st.seg, lab,
                                        m, case.mu, shape2))
            st.sf_t.append((st.t, st.s))
        st.n_rec += 1
    creep = (st.omega * P.r0 - case.speed) / case.speed if not pre else np.nan
    st.hist.append([st.t, st.s, st.w, st.omega, creep, Fc[0], Fc[1], Fc[2],
                    float(out["pn"].sum()), M_c, npatch, c[1], st.y, st.phi, m_roll])
    if P.field_every and (len(st.rows) - 1) % P.field_every == 0:
        st.fields.append(st.v[m.master].copy())
    if P.progress and len(st.rows) % 20 == 1:
        done = (k + 1 - k0) / max(1, P.n_end - k0)
        el = time.perf_counter() - t_wall
        print(f"  {100 * (k + 1) / P.n_steps:5.1f} %  t = {st.t * 1e3:7.3f} ms  "
              f"s = {st.s * 1e3:6.1f} mm  patches {npatch}  Fz = {Fc[2] / 1e3:7.2f} kN  "
              f"elapsed {el:6.0f} s, left ~{el * (1 - done) / max(done, 1e-9):6.0f} s",
              flush=True)


def contact_fields(xs, c, dxs, dxm, dt, out, status, seg, lab, m, mu, shape2):
    """One output of the contact's surface fields on the rows of the wheel's surface grid
    within :data:`FIELD_LEAD` of the axle (see :class:`TransitionResult`)."""
    nr, nc = shape2
    h = m.case.mesh_size
    n_keep = int(round((FIELD_LEAD[1] - FIELD_LEAD[0]) / h)) + 2
    X = xs.reshape(nr, nc, 3)
    lead = X[:, :, 0].mean(axis=1) - c[0]
    mid = 0.5 * (FIELD_LEAD[0] + FIELD_LEAD[1])
    keep = np.sort(np.argsort(np.abs(lead - mid))[:min(n_keep, nr)])
    keep = keep[np.argsort(lead[keep])]
    A = m.slave_area
    closed = status > 0
    pres = np.where(closed, out["pn"] / A, 0.0)
    trac = np.where(closed[:, None], -out["ft"] / A[:, None], 0.0)
    # micro-slip: the wheel node's velocity against the rail point under it, tangential part
    r_, t_ = out["rt"][:, 0], out["rt"][:, 1]
    w = np.stack(((1 - r_) * (1 - t_), r_ * (1 - t_), r_ * t_, (1 - r_) * t_), axis=1)
    q = m.quads[np.maximum(seg, 0)]
    vr = (dxs - np.einsum("sa,sad->sd", w, dxm[q])) / dt
    nrm = out["normal"]
    vn = (vr * nrm).sum(axis=1)
    vt = vr - vn[:, None] * nrm
    vt[~closed] = 0.0
    vn[~closed] = 0.0
    ang = np.where(closed, np.arccos(np.minimum(1.0, np.abs(nrm[:, 2]))), np.nan)
    state = closed.astype(np.int64)
    qn = np.linalg.norm(out["ft"], axis=1)
    for p in range(1, MAX_PATCHES + 1):
        sel = closed & (lab == p)
        if sel.any():
            state[np.flatnonzero(sel)[adhering(out["pn"][sel], qn[sel], mu)]] = 2
    cols = [xs[:, 0], xs[:, 1], xs[:, 2], A, pres, trac[:, 0], trac[:, 1], trac[:, 2], vt[:, 0],
            vt[:, 1], vt[:, 2], vn, ang, lab, state]
    return [np.asarray(v).reshape(nr, nc)[keep] for v in cols]


def write_restart(path, n, n_steps, k, st):
    """State of the loop after step ``k`` (atomically: a temporary file renamed)."""
    tmp = str(path) + ".tmp.npz"
    np.savez(tmp, n_nodes=n, steps=n_steps, step=k, rows=np.array(st.rows, float),
             hist=np.array(st.hist, float), **{k2: np.asarray(getattr(st, k2)) for k2 in STATE})
    os.replace(tmp, path)
