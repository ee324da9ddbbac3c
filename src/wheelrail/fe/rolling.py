"""Rolling: seed 000's two steps with the explicit or the implicit quasi-static integrator.

Step 1 establishes the normal contact under the load; step 2 rolls: the rail
is pulled back with speed V(t) rising by a smooth step over the first
``ramp`` fraction of the travel, and the wheel turns with

    dψ/dt = V(t) (1 − ξ) / r_c,

so that the rigid longitudinal creepage (v_wheel − v_rail)/V is ξ
(Toumi et al. 2016, eq. 1, in Kalker's sign convention).

Explicit (``"explicit"``): central differences, lumped mass (times
``mass_scaling``), step = ``courant`` × the smallest of the element Courant
limits L_e/c and the contact springs' limit 2√(m/k_c); Rayleigh damping
C = αM + βK. Step 1 is dynamic relaxation (load held, mass-proportional
damping tuned to the lowest thickness mode, until the contact force settles).

Implicit quasi-static (``"implicit-qs"``): step 1 the static Newton solve of
:func:`wheelrail.fe.indent`'s kind, step 2 a sequence of static Newton solves
with the friction history carried from step to step (backward-Euler
incremental slip); time step ``time_step`` (default: the contact moves half an
element per step); optional viscous term β_R K Δu/Δt (Rayleigh β only).

The lateral creepage η is imposed by a lateral rail drift −η V(t)
(:meth:`wheelrail.fe.model.Model.lateral_shift`).

Implicit dynamic (``"implicit-hht"``): the HHT-α method (α = ``hht_alpha`` in
[−1/3, 0], β = (1 − α)²/4, γ = ½ − α) with lumped mass, Newton iterations on the
equilibrium at t_{n+1+α} (internal and contact forces weighted (1 + α) at the new
and −α at the old step; contact evaluated at the new positions), same default
step as quasi-static; Rayleigh damping C = α_R M + β_R K enters the same way
((1 + α) C v_{n+1} − α C v_n), its work is reported as ``damping``.

Implicit Newton systems reuse one sparse LU factorisation as a GMRES
preconditioner across iterations and steps (``linear_solver="reuse"``), see
:class:`wheelrail.fe._newton.ReusedFactorSolver`. Every integrator can write
restart files and continue from them (:mod:`wheelrail.fe.restart`).

References
----------
.. [1] Toumi et al., Wear 366-367 (2016) 157-166 (seed 000), §2-3, eq. (1).
.. [3] H.M. Hilber, T.J.R. Hughes, R.L. Taylor, "Improved numerical dissipation for
   time integration algorithms in structural dynamics", Earthquake Eng. Struct.
   Dyn. 5 (1977) 283-292, eqs. (9)-(11).
.. [2] T. Belytschko, W.K. Liu, B. Moran, *Nonlinear Finite Elements for
   Continua and Structures*, Wiley 2000, §6.2 (central differences, stable step,
   energy balance).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ._newton import newton
from .model import build_model
from .patch import patch_from_contact
from .static import free_dofs, static_equilibrium

__all__ = ["RollingResult", "solve", "stable_time_step", "saturation_creepage"]


@dataclass(frozen=True, eq=False)
class RollingResult:
    """Result of :func:`solve`.

    Attributes
    ----------
    dataset : xarray.Dataset
        Histories over ``travel`` [m]: Fx, Fy, Fz [N] (contact force on the
        wheel, global axes: x rolling, y the profiles' lateral axis, z up), Fn [N]
        (sum of the normal nodal forces), Fy_contact and Fn_contact [N] (the force on
        the wheel along the lateral tangent and the normal of the undeformed contact
        plane, tilted by the contact angle δ), kinetic, internal, contact (penalty),
        friction (dissipated), damping (dissipated), external (load work) energies
        [J] and energy_error [J]. Explicit: energies of step 2 (rolling), counted from
        its start (``internal`` is the change of the strain energy);
        ``contact_work`` is the work of the contact forces on the elastic motion, and
        energy_error = kinetic + internal + damping − external − contact_work (the
        balance of the elastic bodies; trapezoidal rule).
    patch : xarray.Dataset
        Contact nodes at the end (see :func:`wheelrail.fe.patch.patch_from_contact`).
    Fx, Fy : float
        Steady-state longitudinal and lateral (global y) force on the wheel [N] (mean
        over the last quarter of the travel); :attr:`Fy_contact` is the lateral force
        in the tilted contact plane.
    p_max, a, b : float
        Peak pressure [Pa] and equivalent semi-axes [m] of the final patch.
    """

    dataset: object
    patch: object
    Fx: float
    Fy: float
    p_max: float
    a: float
    b: float
    model: object
    u: np.ndarray
    info: dict

    @property
    def Fy_contact(self) -> float:
        """Steady lateral force in the contact plane [N] (the creep force to compare with a
        half-space solution when the contact is inclined; equals ``Fy`` at δ = 0)."""
        return _steady(self.dataset, "Fy_contact")

    def __repr__(self):
        return (f"RollingResult(Fx={self.Fx:.1f} N, Fy={self.Fy:.1f} N, p_max="
                f"{self.p_max / 1e6:.1f} MPa, a={self.a * 1e3:.3f} mm, b={self.b * 1e3:.3f} mm)")


def _smoothstep(tau):
    tau = np.clip(tau, 0.0, 1.0)
    return tau ** 3 * (10 - 15 * tau + 6 * tau ** 2)


def stable_time_step(model) -> float:
    """Largest stable central-difference step [s] (before the safety factor), mass scaling included.

    The smaller of the element limit L_e / c (L_e = volume / largest face area, c the
    dilatational wave speed of the scaled density) and the limit 2 √(m / k) of a surface
    node on the contact spring k = k_n A, halved for the master node in series.
    """
    c = model.material.wave_speed / np.sqrt(model.case.mass_scaling)
    L = min(model.edata_w.length.min(), model.edata_r.length.min())
    dt_el = L / c
    ms = model.mass[model.slave] * model.case.mass_scaling
    kc = model.kn * model.slave_area
    # only slaves of the refined lateral band can touch the rail
    y = model.wheel.nodes[model.slave, 1]
    band = np.abs(y - model.geometry["y_c"]) <= 1.5 * model.geometry["b"] + 2 * model.case.mesh_size
    dt_c = float(np.sqrt(ms[band] / kc[band]).min())      # slave and master springs in series
    return float(min(dt_el, dt_c))


def _speed_profile(case, travel):
    """Rail displacement s(t) by integrating the smooth-step speed (distance-based ramp)."""
    V = case.speed
    d_ramp = case.ramp * travel
    # time to cover the ramp with V(t) = V S(t / t_r): ∫ = V t_r / 2 for the quintic step
    t_r = 2 * d_ramp / V if d_ramp > 0 else 0.0
    t_end = t_r + (travel - d_ramp) / V

    def speed(t):
        return V * (_smoothstep(t / t_r) if t_r > 0 else 1.0)

    return speed, t_end


def _forces_row(c):
    fs = c["fs"]
    return fs[:, 0].sum(), fs[:, 1].sum(), fs[:, 2].sum(), c["pn"].sum()


def solve(case, *, progress: bool = True, output_every: int | None = None,
          restart=None, restart_file=None, restart_every: int | None = None) -> RollingResult:
    """Roll the wheel over the rail: seed 000's two loading steps.

    Parameters
    ----------
    case : RollingCase
    progress : bool
        Show a rich progress bar.
    output_every : int, optional
        Explicit: record the histories every this many steps (default: about 400 rows).
    restart : str or Path, optional
        Continue from this restart file (written by a run of the same case).
    restart_file : str or Path, optional
        Write the state of the rolling step to this ``.npz`` file every
        ``restart_every`` steps (and at the end), see :mod:`wheelrail.fe.restart`;
        ``{step}`` in the name is replaced by the step number (one file per write),
        otherwise the file is overwritten with the latest state.
    restart_every : int, optional
        Steps between restart writes (default: a tenth of the rolling steps).

    Returns
    -------
    RollingResult

    Warns
    -----
    UserWarning
        The creepage is past the saturation estimate (:func:`saturation_creepage`): the
        patch slides entirely and the force is μ F_n whatever the creepage; or an implicit
        ``time_step`` above h/(2V) (spurious slip, seed 000 §3).
    """
    _warn_saturation(case)
    io = {"restart": restart, "file": restart_file, "every": restart_every}
    if case.integrator == "explicit":
        return _solve_explicit(case, progress, output_every, io)
    if case.integrator == "implicit-qs":
        return _solve_implicit_qs(case, progress, io)
    return _solve_implicit_hht(case, progress, io)


def saturation_creepage(case) -> float | None:
    """Creepage magnitude [-] beyond which the whole patch slides (saturation estimate).

    Johnson's and Vermeulen's cubic saturation law reaches μ F_n at three times the
    creepage where Kalker's linear force does: √((C11 ξ)² + (C22 η)²) G c² = 3 μ F_n,
    c = √(ab), with Kalker's coefficients of the Hertz contact of the case (None if the
    case is not Hertzian or the creepage is zero).

    References
    ----------
    .. [1] J.J. Kalker, *Three-Dimensional Elastic Bodies in Rolling Contact*, Kluwer 1990,
       §2.3 (linear theory).
    .. [2] P.J. Vermeulen, K.L. Johnson, "Contact of nonspherical elastic bodies
       transmitting tangential forces", J. Appl. Mech. 31 (1964) 338-340 (cubic law).
    """
    from .model import contact_geometry

    geo = contact_geometry(case)
    hz = geo["hertz"]
    if hz is None:
        return None
    from ..tangential.linear import kalker_coefficients
    from .materials import as_fe_material

    mat = as_fe_material(case.material, case.density)
    c11, c22, _, _ = (float(v) for v in kalker_coefficients(float(hz.a / hz.b), mat.nu))
    xi, eta = case.creepage[0], case.creepage[1]
    n = float(np.hypot(xi, eta))
    if n == 0:
        return None
    stiff = float(np.hypot(c11 * xi / n, c22 * eta / n))
    return float(3.0 * case.mu * geo["normal_load"] / (mat.shear_modulus * hz.a * hz.b * stiff))


def _warn_saturation(case):
    import warnings

    sat = saturation_creepage(case) if case.mu > 0 else None
    if sat is None:
        return
    xi, eta = case.creepage[0], case.creepage[1]
    n = float(np.hypot(xi, eta))
    if n > sat:
        warnings.warn(f"creepage (xi, eta) = ({xi!r}, {eta!r}) is past saturation (cubic "
                      f"law on the linear theory: full sliding beyond |creepage| = "
                      f"{sat:.3g}): the patch slides entirely and the creep force is mu Fn "
                      f"whatever the creepage",
                      UserWarning, stacklevel=3)


def _progress(progress, total, label):
    if not progress:
        return None
    from rich.progress import (BarColumn, Progress, TextColumn, TimeElapsedColumn,
                               TimeRemainingColumn)

    p = Progress(TextColumn(label), BarColumn(), TextColumn("{task.percentage:>3.0f}%"),
                 TimeElapsedColumn(), TimeRemainingColumn(), transient=True)
    p.start()
    p.add_task(label, total=total)
    return p


def _dataset(rows, case, model, extra):
    import xarray as xr

    rows = np.array(rows)
    names = ["time", "travel", "Fx", "Fy", "Fz", "Fn", "kinetic", "internal", "contact",
             "friction", "damping", "external", "contact_work"]
    data = {n: ("travel", rows[:, k]) for k, n in enumerate(names) if n != "travel"}
    ds = xr.Dataset(data, coords={"travel": rows[:, 1]})
    units = {"time": "s", "Fx": "N", "Fy": "N", "Fz": "N", "Fn": "N"}
    for n in names[6:]:
        units[n] = "J"
    for n, un in units.items():
        ds[n].attrs["units"] = un
    ds.travel.attrs["units"] = "m"
    ds["energy_error"] = ds.kinetic + ds.internal + ds.damping - ds.external - ds.contact_work
    ds["energy_error"].attrs["units"] = "J"
    # forces in the (undeformed) contact plane: differ from Fy, Fz on an inclined contact
    t, nv = model.geometry["lateral"], model.geometry["normal"]
    ds["Fy_contact"] = ds.Fy * t[1] + ds.Fz * t[2]
    ds["Fn_contact"] = ds.Fy * nv[1] + ds.Fz * nv[2]
    for name in ("Fy_contact", "Fn_contact"):
        ds[name].attrs["units"] = "N"
    ds.attrs.update({"integrator": case.integrator, "creepage_xi": case.xi, "mu": case.mu,
                     "load": case.load, "speed": case.speed, "n_elements": model.n_elements,
                     "mesh_size": case.mesh_size, **extra})
    return ds


def _steady(ds, name):
    v = ds[name].values
    n = max(1, len(v) // 4)
    return float(np.mean(v[-n:]))


def _restart_writer(io, model, dt, n_steps):
    """A callable ``maybe_write(k_done, state_fn)`` writing every ``every`` steps and at the end."""
    from .restart import write_restart

    path = io["file"]
    every = io["every"] or max(1, n_steps // 10)

    def maybe_write(k_done, state_fn, force=False):
        if path is None:
            return False
        if k_done % every == 0 or k_done == n_steps or force:
            write_restart(str(path).format(step=k_done), model, dt, state_fn())
            return True
        return False

    return maybe_write


def _contact_state(c):
    return {k: v for k, v in c.items() if isinstance(v, np.ndarray)}


def _solve_explicit(case, progress, output_every, io):
    from .restart import read_restart

    model = build_model(case, rolling=True)
    travel = model.geometry["travel"]
    dt_stable = stable_time_step(model)
    if case.time_step is not None:
        if case.time_step > dt_stable:
            raise InputError(f"time_step {case.time_step!r} s exceeds the stable explicit step "
                             f"{dt_stable:.3g} s (Courant limit of the {case.mesh_size:g} m mesh)")
        dt = case.time_step
    else:
        dt = case.courant * dt_stable
    m = model.mass * case.mass_scaling
    n = model.n_nodes
    fixed = model.fixed
    inv_m = np.where(m > 0, 1.0 / np.where(m > 0, m, 1.0), 0.0)
    inv_m[fixed] = 0.0
    M_w = float(m[:model.nw].sum())
    alpha, beta = case.rayleigh
    load, mu = case.load, case.mu
    R = model.geometry["r_c"]

    depth = model.wheel.axes[2][-1]
    omega1 = np.pi * model.material.wave_speed / (2 * depth) / np.sqrt(case.mass_scaling)
    a_dr = 2.0 * omega1
    n1 = int(np.ceil(12 * 2 * np.pi / omega1 / dt))
    speed, t_end = _speed_profile(case, travel)
    n2 = int(np.ceil(t_end / dt))
    every = output_every or max(1, n2 // 400)
    f = np.zeros((n, 3))

    def accel(u, v, w, vw, psi, s, xs_prev, xm_prev, ft, mu_now, damp_a):
        f[:] = 0.0
        _, e_int = model.internal_force(u, f)
        c = model.contact(u, w, psi, s, xs_prev, xm_prev, ft, mu_now)
        fc, fcw = model.generalized_contact_force(c, psi)
        fd = (damp_a * m)[:, None] * v
        if beta > 0:
            fb = np.zeros((n, 3))
            model.internal_force(v, fb)
            fd += beta * fb
        acc = (fc - f - fd) * inv_m[:, None]
        aw = (fcw - load - damp_a * M_w * vw) / M_w
        return acc, aw, c, e_int, fc, fcw, fd

    if io["restart"] is not None:
        st = read_restart(io["restart"], model, dt)
        u, v, acc, fc, fd = st["u"], st["v"], st["acc"], st["fc"], st["fd"]
        w, vw, aw, fcw, psi, s, t = (st[k] for k in ("w", "vw", "aw", "fcw", "psi", "s", "t"))
        e_int, e_int0, relax_error, k0 = st["e_int"], st["e_int0"], st["relax_error"], st["k"]
        c, E, rows = st["c"], st["E"], st["rows"].tolist()
        ft = c["ft"]
        bar = _progress(progress, n2 - k0, f"FE explicit ({model.n_elements} el.), restart")
    else:
        u = np.zeros((n, 3))
        v = np.zeros((n, 3))
        hz = model.geometry["hertz"]
        w = -float(hz.penetration) if hz is not None else 0.0
        vw = 0.0
        psi = s = 0.0
        ft = np.zeros((model.slave.size, 3))
        xs_prev = model.slave_positions(u, w, psi)
        xm_prev = model.master_positions(u, s)
        bar = _progress(progress, n1 + n2, f"FE explicit ({model.n_elements} el.)")
        rows = []
        E = dict(kinetic=0.0, internal=0.0, contact=0.0, friction=0.0, damping=0.0,
                 external=0.0, contact_work=0.0)

        # ---- step 1: dynamic relaxation to the static contact (mass-proportional damping)
        t = 0.0
        acc, aw, c, e_int, fc, fcw, fd = accel(u, v, w, vw, psi, s, xs_prev, xm_prev, ft, 0.0,
                                               a_dr)
        for k in range(n1):
            v += dt * acc
            vw += dt * aw
            u += dt * v
            w += dt * vw
            xs_prev, xm_prev = c["xs"], c["xm"]
            acc, aw, c, e_int, fc, fcw, fd = accel(u, v, w, vw, psi, s, xs_prev, xm_prev, ft,
                                                   0.0, a_dr)
            if bar is not None and k % 200 == 0:
                bar.update(bar.task_ids[0], completed=k)
        relax_error = abs(fcw - load) / load
        v[:] = 0.0
        vw = 0.0
        ft = c["ft"].copy()
        e_int0 = e_int
        fd = np.zeros_like(fd)
        k0 = 0

    def state(k_done):
        return dict(u=u, v=v, acc=acc, fc=fc, fd=fd, w=w, vw=vw, aw=aw, fcw=fcw, psi=psi, s=s,
                    t=t, e_int=e_int, e_int0=e_int0, relax_error=relax_error, k=k_done,
                    c=_contact_state(c), E=E, rows=np.array(rows, float).reshape(-1, 13))

    maybe_write = _restart_writer(io, model, dt, n2)

    # ---- step 2: rolling (energies counted from here)
    for k in range(k0, n2):
        t_half = t + 0.5 * dt
        V = speed(t_half)
        v += dt * acc
        vw += dt * aw
        du = dt * v
        u += du
        dw = dt * vw
        w += dw
        s += V * dt
        psi += V * (1.0 - case.xi) / R * dt
        t += dt
        xs_prev, xm_prev = c["xs"], c["xm"]
        E["damping"] += 0.5 * float(np.sum(fd * du))
        E["contact_work"] += 0.5 * (float(np.sum(fc * du)) + fcw * dw)
        E["external"] += -load * dw
        acc, aw, c, e_int, fc, fcw, fd = accel(u, v, w, vw, psi, s, xs_prev, xm_prev, ft, mu,
                                               alpha)
        # trapezoidal rule: the other half with the forces at the end of the step
        E["damping"] += 0.5 * float(np.sum(fd * du))
        E["contact_work"] += 0.5 * (float(np.sum(fc * du)) + fcw * dw)
        E["friction"] += float(np.sum(np.linalg.norm(c["ft"], axis=1) * c["slip"]))
        ft = c["ft"]
        if k % every == 0 or k == n2 - 1:
            # kinetic energy at the full step: v_n = v_{n-1/2} + dt/2 a_n
            vn = v + 0.5 * dt * acc
            vwn = vw + 0.5 * dt * aw
            E["kinetic"] = 0.5 * float(np.sum(m[:, None] * vn * vn)) + 0.5 * M_w * vwn * vwn
            E["internal"] = e_int - e_int0
            E["contact"] = float(c["energy"].sum())
            rows.append([t, s, *_forces_row(c), E["kinetic"], E["internal"], E["contact"],
                         E["friction"], E["damping"], E["external"], E["contact_work"]])
            if bar is not None:
                bar.update(bar.task_ids[0], completed=(k - k0) if io["restart"] else n1 + k)
        maybe_write(k + 1, lambda: state(k + 1))
    if bar is not None:
        bar.stop()
    ds = _dataset(rows, case, model, {"time_step": dt, "steps": n1 + n2,
                                      "relaxation_steps": n1, "relaxation_load_error": relax_error})
    patch = patch_from_contact(model, c, psi, dt)
    return RollingResult(ds, patch, _steady(ds, "Fx"), _steady(ds, "Fy"), patch.attrs["p_max"],
                         patch.attrs["a"], patch.attrs["b"], model, u,
                         {"time_step": dt, "steps": n1 + n2, "stable_time_step": dt_stable,
                          "restarted_at_step": int(k0)})


def _implicit_start(case, io):
    """Model, stiffness, the loaded static state and the time grid of an implicit run."""
    from ._newton import DirectSolver, ReusedFactorSolver

    model = build_model(case, rolling=True)
    travel = model.geometry["travel"]
    K = model.stiffness()
    free = free_dofs(model)
    Kff = K[free][:, free].tocsr()
    speed, t_end = _speed_profile(case, travel)
    dt_max = 0.5 * case.mesh_size / case.speed
    dt = case.time_step if case.time_step is not None else dt_max
    if dt > dt_max * (1 + 1e-9):
        import warnings

        warnings.warn(f"time_step {dt!r} s moves the contact by "
                      f"{dt * case.speed / case.mesh_size:.2g} elements per step; the implicit "
                      f"friction history needs time_step <= h/(2V) = {dt_max:.3g} s, or the "
                      f"patch slips spuriously (seed 000 §3)",
                      UserWarning, stacklevel=4)
    nsteps = int(np.ceil(t_end / dt))
    if io["restart"] is None:
        u, w, c, _ = static_equilibrium(model, K)
    else:
        u = w = c = None
    solver = ReusedFactorSolver() if case.linear_solver == "reuse" else DirectSolver()
    return model, K, free, Kff, u, w, c, speed, dt, nsteps, model.geometry["r_c"], solver


def _implicit_result(case, model, rows, c, psi, dt, nsteps, iters, u, solver, k0, extra=None):
    info = {"time_step": dt, "steps": nsteps, "newton_iterations": iters,
            "restarted_at_step": int(k0)}
    info.update(factorizations=solver.factorizations, krylov_iterations=solver.krylov_iterations,
                linear_solves=solver.solves, linear_solve_seconds=solver.seconds)
    ds = _dataset(rows, case, model, {**info, **(extra or {})})
    patch = patch_from_contact(model, c, psi, dt)
    return RollingResult(ds, patch, _steady(ds, "Fx"), _steady(ds, "Fy"), patch.attrs["p_max"],
                         patch.attrs["a"], patch.attrs["b"], model, u, info)


def _solve_implicit_qs(case, progress, io):
    from .restart import read_restart

    model, K, free, Kff, u, w, c, speed, dt, nsteps, R, solver = _implicit_start(case, io)
    beta_r = case.rayleigh[1]
    # viscous (Kelvin-Voigt) term β K (q − q_n)/Δt, backward Euler: tangent K (1 + β/Δt)
    Kff_eff = Kff * (1.0 + beta_r / dt) if beta_r > 0 else Kff
    if io["restart"] is not None:
        st = read_restart(io["restart"], model, dt)
        u, w, psi, s, t, k0, iters = (st[k] for k in ("u", "w", "psi", "s", "t", "k", "iters"))
        c, E, rows = st["c"], st["E"], st["rows"].tolist()
        ft, e_int0 = c["ft"], st["e_int0"]
    else:
        ft, psi, s, t, rows, E, iters, k0, e_int0 = _fresh_implicit_state(model, u)
    fc, fcw = model.generalized_contact_force(c, psi)
    bar = _progress(progress, nsteps - k0, f"FE implicit-qs ({model.n_elements} el.)")

    def state(k_done):
        return dict(u=u, w=w, psi=psi, s=s, t=t, k=k_done, iters=iters, e_int0=e_int0,
                    c=_contact_state(c), E=E, rows=np.array(rows, float).reshape(-1, 13))

    maybe_write = _restart_writer(io, model, dt, nsteps)
    for k in range(k0, nsteps):
        V = speed(t + 0.5 * dt)
        s += V * dt
        psi += V * (1.0 - case.xi) / R * dt
        t += dt
        q_n = np.concatenate([u.ravel(), [w]])
        dyn = None
        if beta_r > 0:
            dyn = _rayleigh_force(K, beta_r / dt, q_n)
        u, w, c, it = newton(model, Kff_eff, free, u, w, psi, s, c["xs"], c["xm"], ft, case.mu,
                             case.load, dyn=dyn, solver=solver)
        iters += it
        ft = c["ft"]
        dq = np.concatenate([u.ravel(), [w]]) - q_n
        fc_new, fcw_new = model.generalized_contact_force(c, psi)
        E["contact_work"] += 0.5 * (float(np.sum((fc + fc_new).ravel() * dq[:-1]))
                                    + (fcw + fcw_new) * dq[-1])
        fc, fcw = fc_new, fcw_new
        if beta_r > 0:
            E["damping"] += (beta_r / dt) * float(dq @ (K @ dq))
        E["friction"] += float(np.sum(np.linalg.norm(ft, axis=1) * c["slip"]))
        E["external"] += -case.load * dq[-1]
        _, e_int = model.internal_force(u)
        rows.append([t, s, *_forces_row(c), 0.0, e_int - e_int0, float(c["energy"].sum()),
                     E["friction"], E["damping"], E["external"], E["contact_work"]])
        if bar is not None:
            bar.update(bar.task_ids[0], completed=k + 1 - k0)
        if maybe_write(k + 1, lambda: state(k + 1)):
            solver.lu = None          # a restart starts from a fresh factorisation: same numbers
    if bar is not None:
        bar.stop()
    return _implicit_result(case, model, rows, c, psi, dt, nsteps, iters, u, solver, k0)


def _solve_implicit_hht(case, progress, io):
    from .restart import read_restart

    model, K, free, Kff, u, w, c, speed, dt, nsteps, R, solver = _implicit_start(case, io)
    al = case.hht_alpha
    beta, gamma = (1 - al) ** 2 / 4, 0.5 - al
    alpha_r, beta_r = case.rayleigh
    m = model.mass * case.mass_scaling
    M_w = float(m[:model.nw].sum())
    mvec = np.concatenate([np.repeat(m, 3), [M_w]])
    # tangent: (1+α)[K (1 + γ β_R/(β Δt)) + K_c] + M (1 + (1+α) γ α_R Δt) / (β Δt²)
    cv = gamma / (beta * dt)
    diag = mvec[free] / (beta * dt * dt) + (1.0 + al) * cv * alpha_r * mvec[free]
    Kff_eff = Kff * (1.0 + cv * beta_r) if beta_r > 0 else Kff
    fixed = np.setdiff1d(np.arange(3 * model.n_nodes + 1), free)

    def damping_force(vv):
        out = alpha_r * mvec * vv
        if beta_r > 0:
            out = out + beta_r * (K @ vv)
        return out

    def static_residual(q, c):
        f_int, _ = model.internal_force(q[:-1].reshape(-1, 3))
        fc, fcw = model.generalized_contact_force(c, psi)
        return np.concatenate([(f_int - fc).ravel(), [case.load - fcw]])

    if io["restart"] is not None:
        st = read_restart(io["restart"], model, dt)
        q, v, a = st["q"], st["v"], st["a"]
        psi, s, t, k0, iters, e_int0 = (st[k] for k in ("psi", "s", "t", "k", "iters", "e_int0"))
        c, E, rows = st["c"], st["E"], st["rows"].tolist()
        ft = c["ft"]
    else:
        q = np.concatenate([u.ravel(), [w]])
        v = np.zeros_like(q)
        a = np.zeros_like(q)
        ft, psi, s, t, rows, E, iters, k0, e_int0 = _fresh_implicit_state(model, u)
    r_old = static_residual(q, c)
    fc, fcw = model.generalized_contact_force(c, psi)
    fdamp = damping_force(v)
    bar = _progress(progress, nsteps - k0, f"FE implicit-hht ({model.n_elements} el.)")

    def state(k_done):
        return dict(q=q, v=v, a=a, psi=psi, s=s, t=t, k=k_done, iters=iters, e_int0=e_int0,
                    c=_contact_state(c), E=E, rows=np.array(rows, float).reshape(-1, 13))

    maybe_write = _restart_writer(io, model, dt, nsteps)
    for k in range(k0, nsteps):
        V = speed(t + 0.5 * dt)
        s += V * dt
        psi += V * (1.0 - case.xi) / R * dt
        t += dt
        q_n, v_n, a_n = q.copy(), v.copy(), a.copy()

        def acc(qq):
            return (qq - q_n - dt * v_n) / (beta * dt * dt) - (0.5 / beta - 1.0) * a_n

        def dyn(qq, r_old=r_old, fd_old=fdamp):
            r = mvec * acc(qq) - al * r_old
            if alpha_r > 0 or beta_r > 0:
                vv = v_n + dt * ((1 - gamma) * a_n + gamma * acc(qq))
                r = r + (1.0 + al) * damping_force(vv) - al * fd_old
            return r

        u1, w1, c, it = newton(model, Kff_eff, free, q[:-1].reshape(-1, 3), q[-1], psi, s,
                               c["xs"], c["xm"], ft, case.mu, case.load, dyn=dyn,
                               static_scale=1.0 + al, diag=diag, solver=solver)
        iters += it
        q = np.concatenate([u1.ravel(), [w1]])
        a = acc(q)
        a[fixed] = 0.0
        v = v_n + dt * ((1 - gamma) * a_n + gamma * a)
        dq = q - q_n
        r_old = static_residual(q, c)
        fc_new, fcw_new = model.generalized_contact_force(c, psi)
        E["contact_work"] += 0.5 * (float(np.sum((fc + fc_new).ravel() * dq[:-1]))
                                    + (fcw + fcw_new) * dq[-1])
        fc, fcw = fc_new, fcw_new
        fd_new = damping_force(v)
        E["damping"] += 0.5 * float((fdamp + fd_new) @ dq)
        fdamp = fd_new
        ft = c["ft"]
        E["friction"] += float(np.sum(np.linalg.norm(ft, axis=1) * c["slip"]))
        E["external"] += -case.load * dq[-1]
        _, e_int = model.internal_force(u1)
        rows.append([t, s, *_forces_row(c), 0.5 * float(np.sum(mvec * v * v)), e_int - e_int0,
                     float(c["energy"].sum()), E["friction"], E["damping"], E["external"],
                     E["contact_work"]])
        if bar is not None:
            bar.update(bar.task_ids[0], completed=k + 1 - k0)
        if maybe_write(k + 1, lambda: state(k + 1)):
            solver.lu = None          # a restart starts from a fresh factorisation: same numbers
    if bar is not None:
        bar.stop()
    return _implicit_result(case, model, rows, c, psi, dt, nsteps, iters, q[:-1].reshape(-1, 3),
                            solver, k0, {"hht_alpha": al})


def _rayleigh_force(K, factor, q_n):
    """Stiffness-proportional damping force ``factor · K (q − q_n)`` of one step."""
    def dyn(qq):
        return factor * (K @ (qq - q_n))
    return dyn


def _fresh_implicit_state(model, u):
    """Start of an implicit run without a restart file: tangential contact history,
    rolling angle, travel, time, output rows, energy accounts, iteration and step
    counters, and the internal energy of the initial displacement ``u``."""
    _, e_int0 = model.internal_force(u)
    E = dict(friction=0.0, external=0.0, damping=0.0, contact_work=0.0)
    return np.zeros((model.slave.size, 3)), 0.0, 0.0, 0.0, [], E, 0, 0, e_int0
