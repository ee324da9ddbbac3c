"""Explicit time loop of the one- to two-point contact transition, and ``seed004_case``.

Reuses the engine's parts without changing them: the element-force kernel
(:func:`wheelrail.fe._solid.element_forces`), the central-difference node update
(:func:`wheelrail.fe._explicit.advance`; all external forces are passed as its "contact"
forces with every node mapped) and the stiffness triplets for the static track solve.
New here: the general contact (:mod:`.contact`), ties, spring–dampers, the
axle's vertical and rolling dofs, and per-patch outputs.

Step
----
1. Static track: the rail, sleepers, pads and ballast under the static wheel load at the
   start contact point (one sparse solve), so that the slow track modes do not start from
   rest; the wheel is placed on the deflected rail and the sprung mass on its static
   suspension deflection.
2. Explicit rolling over ``travel`` at the speed V along the wheel's heading (yawed by α):
   the element forces, the contact, the springs, the axle (vertical: M ẅ = F_z − load
   terms; rolling: J ψ̈ = T − M_contact; optionally lateral along the axle and roll about
   the heading, see :class:`.track.WheelSuspension`), the node update, the ties.
   An axle dashpot (critical on the Hertz stiffness) damps the start transient over ``settle``.
   Outputs every ``output_interval``: the patches (:func:`.contact.patch_summary`).

References
----------
.. [1] X. Zhao, Z. Li, Wear 271 (2011) 444-452 (explicit transient wheel-track FE model).
"""

from __future__ import annotations

import time

import numpy as np

from ...errors import InputError
from ...materials import Material
from ...normal.hertz import hertz
from ...profiles import load as load_profile
from .._explicit import NCHUNK
from . import _loop
from ._loop import FIELD_LEAD, MAX_PATCHES, PATCH_FIELDS  # noqa: F401  (FIELD_LEAD: named in the docs)
from ._loop import STATE as _STATE
from ._loop import STATE_DEFAULTS as _STATE_DEFAULTS
from ._loop import rot as _rot
from .analysis import onset_travel
from .contact import (
    adhering,
    build_buckets,
    nodal_normals_quads,
    node_to_segment,
    patch_summary,
    patches,
)
from .mesh import (
    extrude_section,
    rail_section,
    spacing_axis,
    sweep_section,
    wheel_section,
)
from .model import (TransitionCase, build_transition_model, rail_surface_line,
                               rigid_pose)
from .track import GRAVITY, WheelSuspension, TrackStructure

__all__ = ["TransitionResult", "run_transition", "seed004_case", "transition_time_estimate",
           "pose_contact", "read_transition_restart",
           "NS_PER_ELEMENT_STEP"]

#: Measured CPU cost of one step per element (ns; 412 ns at load 15 on the shared 2-core
#: machine, 54 k elements), used by the
#: estimate before a run (see docs/fe_transition.md).
NS_PER_ELEMENT_STEP = 400.0

_FIELD_VARS = ("x", "y", "z", "area", "pressure", "traction_x", "traction_y", "traction_z",
               "slip_x", "slip_y", "slip_z", "normal_velocity", "contact_angle", "patch", "state")


class TransitionResult:
    """Output of :func:`run_transition`.

    Attributes
    ----------
    patches : xarray.Dataset
        Per-patch histories, dims (``time``, ``patch``): patch 1 the tread patch, 2 the
        flange patch (split by the contact angle, ``case.patch_split_angle``), 3 any other
        closed nodes (small islands). Variables: :data:`PATCH_FIELDS` plus ``travel``.
    history : xarray.Dataset
        Axle and suspension histories over ``time``: ``w`` the axle's vertical
        displacement [m], ``omega`` [rad/s], ``creepage`` (ω r0 − V)/V, the total contact
        forces on the wheel ``Fx_total``, ``Fy_total``, ``Fz_total``, ``Fn_total`` [N],
        ``torque_contact`` [N m], ``n_patches``, ``axle_y`` the wheel centre's global y [m],
        ``lateral`` its displacement along the axle from the heading path [m] (0 unless
        ``suspension.lateral_stiffness`` is finite), ``roll_angle`` the wheel's rotation about
        its heading [rad] (0 unless ``suspension.roll_stiffness`` is finite; positive
        turns the wheel's bottom towards +y of the wheel frame) and ``roll_moment`` the
        contact forces' moment about the heading axis through the wheel centre [N m].
    model : TransitionModel
    u : ndarray (n, 3)
        Final displacements (wheel nodes in the wheel frame).
    info : dict
        Step, number of steps (``steps``; ``steps_run`` of them in this call, fewer after a
        restart), CPU time of this call, ns per element per step run, onset of two-point
        contact, ``J`` and ``roll_inertia`` the wheel's rolling and roll inertias [kg m²];
        ``wave`` (with ``case.wave_time`` > 0, else None): ``x`` (n,) [m] of the
        rail line's nodes from the wheel centre at ``wave_travel``, ``t`` (nt,) [s] from
        the start of rolling, ``v`` (nt, n, 3) their velocities [m/s] every step (``vz`` the
        vertical part), ``normal`` (3,) the line's outward surface normal, ``line``,
        ``travel``, ``speed`` (the wheel's speed along the rail [m/s]); after a restart
        only the rows run in this call.
    contact_fields : xarray.Dataset or None
        With ``case.field_travel``: the contact's surface fields on the wheel's surface
        grid near the axle, dims (``time``, ``row``, ``col``): ``row`` the circumferential
        rows of the wheel's surface nodes from ``FIELD_LEAD[0]`` behind to ``FIELD_LEAD[1]``
        ahead of the axle (ordered along the rail), ``col`` the nodes across the profile.
        Variables: ``x``, ``y``, ``z`` node positions [m]; ``area`` the nodes' tributary
        areas [m²]; ``pressure`` [Pa]; ``traction_x``,
        ``_y``, ``_z`` the shear stress on the rail (global components) [Pa]; ``slip_x``,
        ``_y``, ``_z`` the micro-slip, the wheel's tangential velocity relative to the rail
        [m/s]; ``normal_velocity`` the wheel's velocity against the rail along the
        rail's outward normal (negative: approaching) [m/s]; ``contact_angle`` [rad];
        ``patch`` (0 open, 1 tread, 2 flange, 3 other); ``state`` (0 open, 1 slip,
        2 adhesion: μ p − |q| above the tolerance of
        :func:`~wheelrail.fe.transition.contact.adhering`); ``travel`` over ``time``.
        Only the outputs of this call (a restart continues the record after its step).
    """

    def __init__(self, patches, history, model, u, info, contact_fields=None):
        self.patches = patches
        self.history = history
        self.model = model
        self.u = u
        self.info = info
        self.contact_fields = contact_fields

    def __repr__(self):
        onset = self.info.get("onset_travel", float("nan"))
        travel = (float(self.patches["travel"].values[-1]) if "travel" in self.patches
                  and self.patches["travel"].size else float("nan"))
        return (f"TransitionResult(elements={self.model.n_elements}, outputs="
                f"{self.history.sizes.get('time', 0)}, travel={travel * 1e3:.1f} mm, "
                f"onset={onset * 1e3:.1f} mm, cpu_s={self.info.get('cpu_s', float('nan')):.1f})")


def stable_step(model) -> float:
    """Largest stable central-difference step [s]: elements (L/c per material), contact
    springs of the slaves (series with the master), and the track springs."""
    dt = np.inf
    for conn, _, ed, mat in model.groups:
        # the lumped mass may be scaled: the element's own density from its nodes' masses
        dt = min(dt, float(ed.length.min()) / mat.wave_speed
                 * (1.0 if mat is not model.case.material else
                    np.sqrt(max(1.0, (model.case.min_element_fraction * model.case.mesh_size
                                      / ed.length.min()) ** 2))))
    ms = model.mass[model.slave]
    kc = model.kn * model.slave_area
    dt = min(dt, float(np.sqrt(0.5 * ms / kc).min()) * 2.0 * 0.9)
    dt = min(dt, model.springs.stable_step(model.mass))
    return dt


def transition_time_estimate(model, dt=None, case=None) -> dict:
    """Steps and an estimated wall time [s] before a run (from :data:`NS_PER_ELEMENT_STEP`)
    of ``case`` (default: the case the model was built for) on ``model``."""
    c = case if case is not None else model.case
    dt = dt or c.courant * stable_step(model)
    pre = int(np.ceil(c.preload / dt)) if c.preload > 0 else 0
    steps = int(np.ceil(c.travel / c.speed / dt)) + pre
    return {"time_step": dt, "steps": steps, "preload_steps": pre,
            "elements": model.n_elements,
            "estimate_s": steps * model.n_elements * NS_PER_ELEMENT_STEP * 1e-9}


#: Fictitious masses of the dynamic relaxation in the preload (``TransitionCase.preload``):
#: the sleepers' nodes at most at this fraction of their mass (less if their elements' or
#: the pads' stable step would fall below 2 Δt); the axle is massless then.
PRELOAD_SLEEPER_MASS = 1.0 / 100.0


def _preload_masses(m, mass_eff, dt):
    """Lumped masses of the preload's dynamic relaxation: the sleepers' nodes scaled down
    by up to 1 / :data:`PRELOAD_SLEEPER_MASS` within the stable step (elements L/c, pads)."""
    mass = mass_eff.copy()
    sl = [np.unique(conn) for conn, _, ed, mat in m.groups if mat is not m.case.material]
    if not sl:
        return mass
    sl = np.unique(np.concatenate(sl))
    dt_el = min(float(ed.length.min()) / mat.wave_speed for conn, _, ed, mat in m.groups
                if mat is not m.case.material)
    scale = min(1.0 / PRELOAD_SLEEPER_MASS, (dt_el / (2.0 * dt)) ** 2)
    while scale > 1.0:
        trial = m.mass.copy()
        trial[sl] /= scale
        if m.springs.stable_step(trial) >= 2.0 * dt:
            break
        scale /= 2.0
    mass[sl] /= max(scale, 1.0)
    return mass


def _static_track(model, load, point, EI=2.1e11 * 2.346e-5):
    """Initial static track displacements under ``load`` [N] at x = ``point[0]``.

    A 3-D static solve of the track is expensive (minutes with a direct solver; the
    hourglass-stabilised mesh on springs defeats plain AMG-CG), so the initial state is the
    Euler–Bernoulli beam on discrete spring supports (pad and ballast in series) under the
    load: the rail nodes get the beam's vertical deflection w(x), the sleepers sink by their
    reaction over the ballast stiffness. The local contact and section deformation is left
    to the explicit run (it settles within the ``settle`` distance). ``EI`` is the 54E1
    rail's bending stiffness about the horizontal axis (I = 2346 cm⁴, EN 13674-1).
    """
    n = model.n_nodes
    nw = model.n_wheel
    track = model.case.track
    x = model.meta["x_axis"]
    ne = x.size - 1
    Kb = np.zeros((2 * x.size, 2 * x.size))
    for e in range(ne):
        L = x[e + 1] - x[e]
        k = EI / L ** 3 * np.array([[12, 6 * L, -12, 6 * L],
                                    [6 * L, 4 * L * L, -6 * L, 2 * L * L],
                                    [-12, -6 * L, 12, -6 * L],
                                    [6 * L, 2 * L * L, -6 * L, 4 * L * L]])
        Kb[2 * e:2 * e + 4, 2 * e:2 * e + 4] += k
    k_sup = 1.0 / (1.0 / track.pad_stiffness + 1.0 / track.ballast_stiffness)
    sup = [int(np.argmin(np.abs(x - xs))) for xs in model.pose["sleepers"]]
    for i in sup:
        Kb[2 * i, 2 * i] += k_sup
    f = np.zeros(2 * x.size)
    f[2 * int(np.argmin(np.abs(x - point[0])))] = -load
    wb = np.linalg.solve(Kb, f)[0::2]
    u = np.zeros((n, 3))
    rail = np.arange(nw, n)
    rail = rail[~np.isin(rail, np.arange(model.meta["sleeper_offset"], n))]
    u[rail, 2] = np.interp(model.nodes[rail, 0], x, wb)
    nsl = (n - model.meta["sleeper_offset"]) // len(sup)
    for s_, i in enumerate(sup):
        reaction = k_sup * wb[i]
        a = model.meta["sleeper_offset"] + s_ * nsl
        u[a:a + nsl, 2] = reaction / track.ballast_stiffness
    return u


def _static_approach(case, pose, load, model):
    """Normal approach [m] of the static tread contact: Hertz (Johnson 1985, §4.2) from
    the rolling radius and the profile curvatures at the start contact point, plus the
    penalty layer's overlap at the mean pressure; 0.1 mm if the contact is not Hertzian."""
    mat = case.material
    kw = float(case.wheel.curvature(pose["yw_tread"]))
    kr = float(case.rail.curvature(pose["rail_y_tread"]))
    A = 0.5 / pose["r0"]
    B = 0.5 * (kw - kr)
    fn = load / np.cos(pose["tread_angle_rigid"])
    if not B > 1e-9:
        return 1e-4, 5e-3
    hz = hertz(fn, A, B, Material(mat.E, mat.nu))
    p_mean = fn / (np.pi * float(hz.a) * float(hz.b))
    return (float(hz.penetration) * np.cos(pose["tread_angle_rigid"])
            + p_mean / float(np.median(model.kn)), float(np.sqrt(hz.a * hz.b)))


def run_transition(case: TransitionCase, *, progress: bool = False, model=None,
                   estimate_only: bool = False, field_every: int = 0, restart=None,
                   restart_file=None, restart_every: int = 0, stop_travel=None):
    """Roll the half-wheelset of ``case`` into two-point contact (explicit FE).

    Parameters
    ----------
    case : TransitionCase
    progress : bool
        Print the estimate and progress lines.
    model : TransitionModel, optional
        A model already built for ``case``.
    estimate_only : bool
        Return :func:`transition_time_estimate` without running.
    field_every : int
        If > 0, store the rail surface nodes' velocities every ``field_every`` outputs
        (for the wave-speed analysis) in ``info["fields"]``.
    restart : path, optional
        Continue from this restart file (written by an earlier run of the same case).
    restart_file : path, optional
        Write the state here every ``restart_every`` steps (overwritten each time).
    restart_every : int
        Steps between restart files (0: a tenth of the steps when ``restart_file`` is given).
    stop_travel : float, optional
        Stop once the wheel has rolled this far [m] (after the preload), before the case's
        ``travel``: the outputs up to there are returned, ``info["stopped_at"]`` is the
        number of steps run in all, and with ``restart_file`` the state is written at
        the stop, so that ``restart=`` continues the same case from there. The output
        options that do not change the motion (``output_interval``, ``field_travel``,
        ``field_stride``, ``wave_travel``, ``wave_time``, ``wave_line``) may differ in
        the continuation: a long run can be stopped before a window and continued with
        its fields recorded.

    Returns
    -------
    TransitionResult
    """
    if isinstance(restart_every, bool) or not isinstance(restart_every, (int, np.integer)) \
            or restart_every < 0:
        raise InputError(f"restart_every must be an integer >= 0 (steps between restart "
                         f"files; 0: a tenth of the steps), got {restart_every!r}")
    m = model if model is not None else build_transition_model(case)
    if case.travel > m.case.travel * (1 + 1e-9):
        raise InputError(f"travel {case.travel!r} m is longer than the {m.case.travel!r} m the "
                         f"model's fine zone was built for")
    dt = case.courant * stable_step(m)
    est = transition_time_estimate(m, dt, case)
    if progress or estimate_only:
        msg = (f"transition FE: {m.n_elements} elements, {est['steps']} steps of "
               f"{dt * 1e9:.1f} ns, estimated {est['estimate_s'] / 60:.1f} min")
        if estimate_only:
            return est
        print(msg, flush=True)
    P, st, sag = _prepare(case, m, dt, est, stop_travel, field_every, progress)
    t_cpu = time.process_time()
    t_wall = time.perf_counter()
    k0 = 0
    if restart is not None:
        k0 = _restore(P, st, restart, stop_travel)
    if restart_file is not None and restart_every <= 0:
        restart_every = max(1, P.n_steps // 10)
    if k0 < P.n_pre:
        # the preload's fictitious masses and damping until the rolling starts
        st.inv_m = P.inv_m_pre
        st.m_alpha[:] = P.m_alpha_pre
    for k in range(k0, P.n_end):
        _loop.step(P, st, k, k0, t_wall)
        if restart_file is not None and k + 1 < P.n_steps and (
                (k + 1) % restart_every == 0 or k + 1 == P.n_end):
            _loop.write_restart(restart_file, m.n_nodes, P.n_steps, k, st)
    cpu = time.process_time() - t_cpu
    wall = time.perf_counter() - t_wall
    ds, hds = _histories(st.rows, st.hist)
    # the cost per step of the steps run in this call (a restart continues at k0)
    n_run = max(1, P.n_end - k0)
    info = {"time_step": dt, "steps": P.n_steps, "steps_run": P.n_end - k0, "cpu_s": cpu,
            "stopped_at": P.n_end if P.n_end < P.n_steps else None,
            "wall_s": wall,
            "ns_per_element_step": cpu / (n_run * m.n_elements) * 1e9,
            "wall_ns_per_element_step": wall / (n_run * m.n_elements) * 1e9,
            "elements": m.n_elements, "load": P.load, "torque": P.torque, "J": P.J,
            "roll_inertia": P.I_roll, "static_sag": sag,
            "fields": np.array(st.fields) if st.fields else None,
            "onset_travel": _onset(ds),
            "wave": _wave_record(m, P.line, P.wave_normal, st.wave_v, P.x_wave, dt, P.n_pre,
                                 P.j_wave, k0, case)}
    return TransitionResult(ds, hds, m, st.u, info,
                            _fields_dataset(st.sf, st.sf_t) if st.sf else None)


def _restore(P, st, restart, stop_travel):
    """Continue from a restart file: the loop's state and outputs; the first step to run."""
    n = P.m.n_nodes
    with np.load(restart, allow_pickle=False) as z:
        if int(z["n_nodes"]) != n or int(z["steps"]) != P.n_steps:
            raise InputError(f"restart file {restart!s} belongs to another case "
                             f"({int(z['n_nodes'])} nodes, {int(z['steps'])} steps; this "
                             f"case {n} nodes, {P.n_steps} steps)")
        saved = {k2: (z[k2] if k2 in z.files else _STATE_DEFAULTS[k2]) for k2 in _STATE}
        k0 = int(z["step"]) + 1
        if k0 >= P.n_end:
            raise InputError(f"restart file {restart!s} is at step {k0}, at or past the "
                             f"stop ({P.n_end} steps; stop_travel {stop_travel!r} m)")
        st.rows = [r for r in z["rows"]]
        st.hist = list(_full_history_rows(z["hist"]))
    st.u[:], st.v[:], st.ft[:] = saved["u"], saved["v"], saved["ft"]
    for k2 in ("w", "vw", "zs", "vs", "y", "vy", "phi", "vphi", "m_roll0", "omega",
               "omega_mean", "psi", "s", "t", "fade"):
        setattr(st, k2, float(saved[k2]))
    st.xs_prev, st.xm_prev = saved["xs_prev"], saved["xm_prev"]
    _loop.settle_damping(P, st, st.fade)
    if P.progress:
        print(f"  continued from {restart!s} at step {k0}", flush=True)
    return k0


def _prepare(case, m, dt, est, stop_travel, field_every, progress):
    """``(P, st, sag)``: the prepared run (:class:`._loop.Transition`), its start state
    (:class:`._loop.LoopState`: static track, the wheel on it) and the static rail sag [m]."""
    n = m.n_nodes
    nw = m.n_wheel
    susp = case.suspension
    alpha = case.angle_of_attack
    V = case.speed
    pose = m.pose
    M_wheel = float(m.mass[:nw].sum())
    load = susp.wheel_load(M_wheel)
    ax = dict(load=load, M_axle=susp.axle_mass + M_wheel)
    # rolling inertia: FE wheel about the axle + half-axle
    rho2 = m.nodes[:nw, 0] ** 2 + m.nodes[:nw, 2] ** 2
    J = ax["J"] = float(np.sum(m.mass[:nw] * rho2)) + susp.axle_inertia
    r0 = ax["r0"] = pose["r0"]
    fixed_rolling = ax["fixed_rolling"] = case.creepage is not None
    # the driving torque; none when the rolling is prescribed (case.creepage)
    ax["torque"] = 0.0 if fixed_rolling else case.traction * load * r0 + susp.torque
    # ---- static track and initial pose
    u = _static_track(m, load, (0.0, pose["rail_y_tread"]))
    sag = float(np.min(u[m.master, 2]))
    # start at 60 % of the Hertz approach: a coarse mesh cannot resolve the narrow flange-root
    # patch and is stiffer at the same overlap; the axle dashpot absorbs the rest
    delta, a_hz = _static_approach(case, pose, load, m)
    delta *= 0.6
    # tangential stiffness of the tread patch (circular, Johnson 1985 §7.2: δ = Q(2-ν)/(8Ga))
    G = case.material.E / (2 * (1 + case.material.nu))
    k_t = 8.0 * G * a_hz / (2.0 - case.material.nu)
    # start creepage: the prescribed one, or the traction's by Kalker's linear theory
    # (C11 ≈ 4.2 at ν = 0.3, a ≈ b)
    xi0 = (case.creepage if fixed_rolling
           else case.traction * load / (G * np.pi * a_hz ** 2 * 4.2))
    c0 = np.array([0.0, pose["y0"], case.radius + pose["z0"] + sag - delta])
    mass_eff = m.mass.copy()
    np.add.at(mass_eff, m.tie_master.ravel(), (m.tie_weight * m.mass[m.tie_slave, None]).ravel())
    inv_m = 1.0 / mass_eff
    inv_m[m.fixed] = 0.0
    inv_m[m.tie_slave] = 0.0
    n_pre = est["preload_steps"]
    inv_m_pre = m_alpha_pre = None
    if n_pre:
        # dynamic relaxation: fictitious masses and damping until the rolling starts
        mass_pre = _preload_masses(m, mass_eff, dt)
        inv_m_pre = np.where(inv_m > 0.0, 1.0 / mass_pre, 0.0)
        m_alpha_pre = case.preload_damping * mass_pre
        m_alpha_pre[m.fixed] = 0.0
    ns = m.slave.size
    cdamp = 2.0 * case.contact_damping * np.sqrt(m.kn * m.slave_area * 0.5 * m.mass[m.slave])
    # lateral dof along the axle (only with a finite lateral_stiffness): y from the path
    # along the heading, driven by the contact forces' part along the axle
    ax["lat_free"] = bool(np.isfinite(susp.lateral_stiffness))
    # roll dof about the heading (only with a finite roll_stiffness), about the static
    # balance at the end of the preload (m_roll0: the contact moment then, the spring's
    # preload; without a preload the first steps' moment is the start transient's); a
    # critical dashpot fading over `settle`
    roll_free = ax["roll_free"] = bool(np.isfinite(susp.roll_stiffness))
    if roll_free and not n_pre:
        raise InputError(f"a finite roll_stiffness ({susp.roll_stiffness!r} N m/rad) needs "
                         f"a static preload (case.preload > 0, e.g. 1e-3 s): the roll "
                         f"spring is balanced by the contact moment at its end")
    I_roll = ax["I_roll"] = (float(np.sum(m.mass[:nw] * (m.nodes[:nw, 1] ** 2
                                                         + m.nodes[:nw, 2] ** 2)))
                             + susp.axle_roll_inertia)
    ax["c_roll0"] = 2.0 * np.sqrt(susp.roll_stiffness * I_roll) if roll_free else 0.0
    ax["omega_roll"] = V / r0 * (1.0 + xi0)
    # rolling dof against the patch's tangential stiffness: ω_n = r0 sqrt(k_t / J); a
    # dashpot on ω − ω̄ (ω̄ low-passed over a few periods, so the mean creepage is free),
    # critical, fading over `settle` like the axle dashpot
    w_rot = r0 * np.sqrt(k_t / J)
    ax["c_rot0"] = 2.0 * J * w_rot
    ax["tau_rot"] = 4.0 / w_rot
    # Hertz-type axle dashpot over the settle distance: critical on k ≈ 1.5 Q / δ, δ ≈ 0.1 mm
    ax["c_axle0"] = 2.0 * np.sqrt(1.5 * load / 1e-4 * ax["M_axle"])
    # the preload's axle dashpot: the massless axle's explicit update w += Δt F / c is
    # stable for c > Δt k / 2; 20 Δt k_Hertz keeps it so for a contact 10 × stiffer and
    # lets the axle follow the track's ≈ 0.1 GN/m within ≈ 0.1 ms
    ax["c_pre"] = 20.0 * dt * 1.5 * load / (delta / 0.6)
    P, n_wave = _windows(case, m, dt, est, stop_travel, n_pre, c0, dict(
        ax, dt=dt, field_every=field_every, progress=progress, n_pre=n_pre,
        alpha_m=case.settle_damping, c0=c0, heading=np.array([np.cos(alpha), np.sin(alpha), 0.0]),
        e_axle=_rot(alpha, 0.0) @ np.array([0.0, 1.0, 0.0]), Xw=m.nodes[m.slave],
        xm_ref=m.nodes[m.master], cdamp=cdamp, reach=4 * case.mesh_size, inv_m_run=inv_m,
        inv_m_pre=inv_m_pre, m_alpha_pre=m_alpha_pre, cmap=np.arange(n, dtype=np.int64),
        no_beta=np.zeros((1, 3)), fwin=case.field_travel,
        shape2=(m.meta["band_i"].size, m.meta["rim_shape"][1])))
    omega = P.omega_roll if not n_pre else 0.0
    st = _loop.LoopState(
        u=u, v=np.zeros((n, 3)), ft=np.zeros((ns, 3)),
        xs_prev=c0 + (P.Xw + u[m.slave]) @ _rot(alpha, 0.0).T, xm_prev=P.xm_ref + u[m.master],
        inv_m=inv_m, m_alpha=np.zeros(n), acc=np.zeros((n, 3)), f_int=np.zeros((n, 3)),
        f_tmp=np.zeros((n, 3)), fext=np.zeros((n, 3)),
        e_buf=[np.zeros((g[0].shape[0], 2)) for g in m.groups],
        partial=np.zeros((NCHUNK, 2)),
        out={k: np.zeros(sh) for k, sh in (("fs", (ns, 3)), ("gap", ns), ("pn", ns),
                                            ("ft", (ns, 3)), ("rt", (ns, 2)),
                                            ("normal", (ns, 3)), ("slip", ns))},
        status=np.zeros(ns, np.int64), seg=np.zeros(ns, np.int64),
        fm=np.zeros((m.master.size, 3)), wave_v=np.zeros((n_wave, P.line.size, 3)),
        zs=-(susp.sprung_mass * GRAVITY) / susp.stiffness,   # suspension deflection, static
        omega=omega, omega_mean=omega,
        # mass-proportional damping of the start transient, fading over `settle`
        fade=1.0 if case.settle > 0 else 0.0, t=-n_pre * dt,
        rows=[], hist=[], fields=[], sf=[], sf_t=[])
    _loop.settle_damping(P, st, st.fade)
    return P, st, sag


def _windows(case, m, dt, est, stop_travel, n_pre, c0, fields):
    """The run's end (``stop_travel``), output interval and wave record window:
    ``(P, n_wave)`` with ``P`` the :class:`._loop.Transition` of ``fields`` and these."""
    alpha = case.angle_of_attack
    V = case.speed
    n_steps = est["steps"]
    every = max(1, int(round(case.output_interval / dt)))
    # a rail surface line (along x) through the contact at the record's start, for the
    # wave analysis: all three velocity components every step over wave_time
    x_wave = c0[0] + case.wave_travel * np.cos(alpha)
    n_wave = int(case.wave_time / dt) if case.wave_time > 0 else 0
    if n_wave:
        line, wave_normal = rail_surface_line(m, x_wave, case.wave_line)
    else:
        line, wave_normal = np.zeros(0, np.int64), np.zeros(3)
    j_wave = n_pre + int(round(case.wave_travel / (V * dt)))     # step of the first record
    n_end = n_steps
    if stop_travel is not None:
        if not np.isfinite(stop_travel) or stop_travel <= 0.0:
            raise InputError(f"stop_travel must be a positive distance [m], got "
                             f"{stop_travel!r}")
        n_end = min(n_steps, n_pre + int(np.ceil(stop_travel / (V * dt))))
    n_wave = max(0, min(n_wave, n_end - j_wave))          # not beyond the run's end
    P = _loop.Transition(case=case, m=m, n_steps=n_steps, n_end=n_end, every=every,
                         line=line, wave_normal=wave_normal, x_wave=x_wave, j_wave=j_wave,
                         n_wave=n_wave, **fields)
    return P, n_wave


def _wave_record(m, line, normal, wave_v, x_wave, dt, n_pre, j_wave, k0, case):
    """``info["wave"]``: the rows actually run (a restart continues at step ``k0``)."""
    first = max(0, k0 - j_wave)
    if first >= wave_v.shape[0]:         # no record, or all of it before the restart
        return None
    t = dt * (np.arange(wave_v.shape[0]) + j_wave + 1 - n_pre)
    v = wave_v[first:]
    return {"x": m.nodes[line, 0] - x_wave, "t": t[first:], "v": v, "vz": v[:, :, 2],
            "normal": normal, "line": case.wave_line, "travel": case.wave_travel,
            "speed": case.speed * float(np.cos(case.angle_of_attack))}


def _fields_dataset(sf, sf_t):
    """The recorded contact fields as an xarray.Dataset (time, row, col)."""
    import xarray as xr

    tt = np.array(sf_t)
    data = {}
    for i, name in enumerate(_FIELD_VARS):
        arr = np.array([f[i] for f in sf])
        if name in ("patch", "state"):
            arr = arr.astype(np.int8)
        data[name] = (("time", "row", "col"), arr)
    ds = xr.Dataset(data, coords={"time": tt[:, 0], "travel": ("time", tt[:, 1])})
    units = {"x": "m", "y": "m", "z": "m", "area": "m2", "pressure": "Pa", "traction_x": "Pa",
             "traction_y": "Pa", "traction_z": "Pa", "slip_x": "m/s", "slip_y": "m/s",
             "slip_z": "m/s", "normal_velocity": "m/s", "contact_angle": "rad"}
    for k2, un in units.items():
        ds[k2].attrs["units"] = un
    ds.attrs["state"] = "0 open, 1 slip, 2 adhesion (tolerance definition)"
    ds.attrs["patch"] = "0 open, 1 tread, 2 flange, 3 other"
    return ds


N_HIST = 15          # columns of the axle history rows: time, travel and the names below


def _full_history_rows(hist):
    """The axle history rows (nt, N_HIST); the rows of a restart file written before the
    last columns existed ("lateral", "roll_angle", "roll_moment") are padded with zeros."""
    hist = np.array(hist, float)
    return np.pad(hist, ((0, 0), (0, N_HIST - hist.shape[1])))


def _histories(rows, hist):
    """The per-patch and axle histories (xarray.Dataset) from the loop's output rows."""
    import xarray as xr

    rows = np.array(rows, float)                 # (nt, patch, field)
    hist = _full_history_rows(hist)
    tt = hist[:, 0]
    data = {f: (("time", "patch"), rows[:, :, i]) for i, f in enumerate(PATCH_FIELDS)}
    ds = xr.Dataset(data, coords={"time": tt, "patch": np.arange(1, MAX_PATCHES + 1),
                                  "travel": ("time", hist[:, 1])})
    units = {"Fn": "N", "Fx": "N", "Fy": "N", "Fz": "N", "F_long": "N", "F_lat": "N",
             "contact_angle": "rad", "x": "m", "y": "m", "z": "m", "area": "m2", "p_max": "Pa",
             "q_max": "Pa", "theta": "rad"}
    for k2, un in units.items():
        ds[k2].attrs["units"] = un
    hnames = ("w", "omega", "creepage", "Fx_total", "Fy_total", "Fz_total", "Fn_total",
              "torque_contact", "n_patches", "axle_y", "lateral", "roll_angle", "roll_moment")
    hds = xr.Dataset({nm: ("time", hist[:, i + 2]) for i, nm in enumerate(hnames)},
                     coords={"time": tt, "travel": ("time", hist[:, 1])})
    return ds, hds


def read_transition_restart(path):
    """The histories stored in a restart file of :func:`run_transition` (a run stopped or
    still running: its outputs up to the file's step).

    Returns
    -------
    patches, history : xarray.Dataset
        As :attr:`TransitionResult.patches` and :attr:`TransitionResult.history`.
    progress : dict
        ``step`` (last step done, 0-based) and ``steps`` (of the whole run).
    """
    with np.load(path, allow_pickle=False) as z:
        ds, hds = _histories(z["rows"], z["hist"])
        return ds, hds, {"step": int(z["step"]), "steps": int(z["steps"])}


def _onset(ds, min_force=1000.0):
    """Travel [m] at which the flange patch first carries > ``min_force`` [N] for three
    consecutive outputs (NaN if never)."""
    return onset_travel(ds, min_force)


def seed004_case(angle_of_attack=0.020, size="reduced", **changes) -> TransitionCase:
    """The one- to two-point contact transition case: S1002 on 54E1 at 1:40, 80 km/h,
    μ = 0.6, a half-wheelset with a sprung mass on a track with discrete sleepers (the set-up
    of explicit FE studies of the transition, with 1 mm elements in a 150 mm solution zone).

    Parameters
    ----------
    angle_of_attack : float
        Angle of attack [rad] (0.015, 0.020 and 0.025 are the studied values).
    size : {"reduced", "full"}
        ``"reduced"``: 2 sleepers, 4 mm elements, 3 mm of flange clearance (the start
        contact on the tread at 6.7°, rigid), a travel of 30 mm + clearance / α (the flange
        patch appears ≈ 10 mm before its end at 25 mrad), traction 0.3 (the driving torque:
        half of μ; with less, the spin of the flange-root contact turns the tread shear
        sideways well before the flange touches), 30 mm of damped settling (5–10 min CPU
        on 2 cores); ``"full"``: 1 mm elements along the whole 0.67 m of travel, five
        sleepers (1.49 M elements, 4.4 GB, 402 066 steps of 75 ns: ≈ 41–45 h CPU measured
        on one thread; not yet run).
    **changes
        Any :class:`TransitionCase` field.

    References
    ----------
    .. [1] "Modelling of non-steady-state transition from single-point to two-point rolling
       contact" (explicit FE study: S1002 on UIC 54E1 at 1:40, 80 km/h, angles of attack
       15–25 mrad, μ = 0.6), built on the model of
    .. [2] X. Zhao, Z. Li, Wear 271 (2011) 444-452.
    """
    base = dict(wheel=load_profile("S1002"), rail=load_profile("54E1"), radius=0.46,
                inclination=float(np.arctan(1 / 40)), angle_of_attack=float(angle_of_attack),
                speed=80 / 3.6, mu=0.6)
    if size == "reduced":
        clearance = float(changes.get("flange_clearance", 3e-3))
        a = abs(float(angle_of_attack))
        base.update(mesh_size=4e-3, flange_clearance=3e-3, traction=0.3, settle=0.03,
                    travel=0.03 + clearance / a if a > 5e-3 else 0.1,
                    track=TrackStructure(n_sleepers=2, overhang=0.25),
                    suspension=WheelSuspension())
    elif size == "full":
        base.update(mesh_size=1e-3, travel=0.67, flange_clearance=6e-3, settle=0.25, traction=0.3,
                    section_h_max=6e-3, x_h_max=0.012, theta_h_max=0.012,
                    track=TrackStructure(n_sleepers=5),
                    suspension=WheelSuspension())
    else:
        raise InputError(f"size must be 'reduced' or 'full', got {size!r}")
    base.update(changes)
    return TransitionCase(**base)


def pose_contact(case: TransitionCase, y_off: float, overlap: float = 5e-5,
                 half_length: float = 0.02, yaw: float = 0.0, z_off: float | None = None):
    """Rigid-pose contact of short wheel and rail pieces (no dynamics): the wheel profile's
    origin at lateral offset ``y_off`` [m] in the inclined rail frame, lowered by ``overlap``
    [m] below the rigid first touch without yaw (or below the height ``z_off`` [m] of the
    profile origin, e.g. ``yawed_contact(case, y_off, yaw)["z_off"]``), the wheel yawed by
    ``yaw`` [rad] about the vertical through its axle centre; one evaluation of the contact
    search with μ = 0 on the case's mesh size.

    Returns
    -------
    list of dict
        :func:`~wheelrail.fe.transition.contact.patch_summary` of every patch, ordered
        from the flange side of the wheel profile.
    """
    h = case.mesh_size
    pose = rigid_pose(case, y_off)
    rr, _, _ = rail_section(case.rail, h, [(-0.04, 0.04)], inclination=case.inclination,
                            ratio=case.grading, h_max=case.section_h_max)
    wr_, _, _ = wheel_section(case.wheel, h, [(-0.08, 0.07)], ratio=case.grading,
                              h_max=case.section_h_max)
    x = spacing_axis(-half_length, half_length, [(-half_length, half_length)], h)
    R = case.radius
    th = x / R
    rail = extrude_section(rr, x)
    wheel = sweep_section(wr_, th, R)
    q = rail.surface.reshape(-1, 4)
    master, inv = np.unique(q, return_inverse=True)
    quads = inv.reshape(-1, 4)
    xm = rail.nodes[master]
    b = build_buckets(xm, quads, cell=max(4 * h, 6e-3), margin=4 * h)
    slave = wheel.surface_nodes.ravel()
    z0 = pose["z_off"] if z_off is None else float(z_off)
    c0 = np.array([0.0, y_off, R + z0 - overlap])
    xs = wheel.nodes[slave] @ _rot(yaw, 0.0).T + c0
    p = wheel.nodes[wheel.surface]
    qa = 0.5 * np.linalg.norm(np.cross(p[..., 2, :] - p[..., 0, :], p[..., 3, :] - p[..., 1, :]),
                              axis=-1)
    area_all = np.zeros(wheel.n_nodes)
    for c in range(4):
        np.add.at(area_all, wheel.surface[..., c].ravel(), 0.25 * qa.ravel())
    area = area_all[slave]
    ns = slave.size
    kn = case.penalty * case.material.E / np.sqrt(area)
    out = {k: np.zeros(sh) for k, sh in (("fs", (ns, 3)), ("gap", ns), ("pn", ns),
                                          ("ft", (ns, 3)), ("rt", (ns, 2)),
                                          ("normal", (ns, 3)), ("slip", ns))}
    status = np.zeros(ns, np.int64)
    seg = np.zeros(ns, np.int64)
    node_to_segment((xs, np.zeros((ns, 3)), area, kn, kn, np.zeros(ns)),
                    (xm, np.zeros_like(xm), nodal_normals_quads(xm, quads), quads), b.record,
                    (0.0, 4 * h, 1e-7, 1.0), np.zeros((ns, 3)),
                    (out["fs"], out["gap"], out["pn"], out["ft"], status, seg, out["rt"],
                     out["normal"], out["slip"]))
    lab, npatch = patches(status.reshape(wheel.shape[0], wheel.shape[1]))
    lab = lab.ravel()
    return [patch_summary(lab == k, xs, out["fs"], out["pn"], out["ft"], out["normal"], area,
                          status, 0.0) for k in range(1, npatch + 1)]
