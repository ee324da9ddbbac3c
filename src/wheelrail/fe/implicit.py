"""The implicit rolling integrators: quasi-static (backward Euler) and HHT-α.

Implicit quasi-static (``"implicit-qs"``): step 1 the static Newton solve of
:func:`wheelrail.fe.indent`'s kind (in load increments for a plastic material), step 2
a sequence of static Newton solves with the friction history carried from step to step
(backward-Euler incremental slip); time step ``time_step`` (default: the contact moves
half an element per step); optional viscous term β_R K Δu/Δt (Rayleigh β only).

Implicit dynamic (``"implicit-hht"``): the HHT-α method (α = ``hht_alpha`` in
[−1/3, 0], β = (1 − α)²/4, γ = ½ − α) with lumped mass, Newton iterations on the
equilibrium at t_{n+1+α} (internal and contact forces weighted (1 + α) at the new
and −α at the old step; contact evaluated at the new positions), same default
step as quasi-static; Rayleigh damping C = α_R M + β_R K enters the same way
((1 + α) C v_{n+1} − α C v_n), its work is reported as ``damping``.

Plastic materials: the residual's internal force comes from the return map of every
integration point from the state of the last converged step; the Newton tangent is
the consistent elasto-plastic tangent (reassembled every iteration), the state is
committed when the step converges. Rayleigh's β_R K uses the elastic K.

References
----------
.. [1] H.M. Hilber, T.J.R. Hughes, R.L. Taylor, Earthquake Eng. Struct. Dyn. 5 (1977)
   283-292, eqs. (9)-(11).
.. [2] J.C. Simo, T.J.R. Hughes, *Computational Inelasticity*, Springer 1998, §3.3
   (consistent tangent).
"""

from __future__ import annotations

import numpy as np

from ._newton import make_solver, newton
from .model import build_model
from .patch_dataset import patch_from_contact
from .restart import read_restart
from .rolling import (
    COLUMNS,
    RollingResult,
    contact_plane_forces,
    contact_state,
    history_dataset,
    plastic_fields,
    progress_bar,
    restart_writer,
    speed_profile,
    steady_statistics,
    steady_window,
)
from .static import free_dofs, static_equilibrium

__all__ = ["solve_implicit_qs", "solve_implicit_hht"]


def _implicit_start(case, io):
    """Model, stiffness, the loaded static state and the time grid of an implicit run."""

    model = build_model(case, rolling=True)
    travel = model.geometry["travel"]
    K = model.stiffness()
    free = free_dofs(model)
    Kff = K[free][:, free].tocsr()
    speed, t_end = speed_profile(case, travel)
    dt_max = 0.5 * case.mesh_size / case.speed
    dt = case.time_step if case.time_step is not None else dt_max
    if dt > dt_max * (1 + 1e-9):
        import warnings

        warnings.warn(f"time_step {dt!r} s moves the contact by "
                      f"{dt * case.speed / case.mesh_size:.2g} elements per step; the implicit "
                      f"friction history needs time_step <= h/(2V) = {dt_max:.3g} s, or the "
                      f"patch slips spuriously (Toumi et al. 2016, §3)",
                      UserWarning, stacklevel=4)
    nsteps = int(np.ceil(t_end / dt))
    state = model.new_state()
    if io["restart"] is None:
        u, w, c, _ = static_equilibrium(model, K, state=state)
    else:
        u = w = c = None
    solver = make_solver(case.linear_solver)
    return (model, K, free, Kff, u, w, c, speed, dt, nsteps, model.geometry["r_c"], solver,
            state)


def _tangent(model, free, state, extra_K=None, factor=1.0):
    """Free-dof Newton stiffness as a function of the iterate (plastic), or None (elastic:
    the constant K is used)."""
    if state is None:
        return None

    def tangent(q):
        Kt = model.stiffness(q[:-1].reshape(-1, 3), state)[free][:, free]
        if extra_K is not None:
            Kt = Kt + factor * extra_K
        return Kt.tocsr()

    return tangent


def _implicit_result(case, model, rows, c, psi, dt, nsteps, iters, u, solver, k0, state,
                     extra=None):
    info = {"time_step": dt, "steps": nsteps, "newton_iterations": iters,
            "restarted_at_step": int(k0)}
    info.update(factorizations=solver.factorizations, krylov_iterations=solver.krylov_iterations,
                linear_solves=solver.solves, linear_solve_seconds=solver.seconds)
    ds = history_dataset(rows, case, model, {**info, **(extra or {})})
    patch = patch_from_contact(model, c, psi, dt)
    fy_c, fn_c = contact_plane_forces(model, ds.Fy.values, ds.Fz.values)
    steady = steady_statistics(ds.travel.values, {"Fx": ds.Fx.values, "Fy": ds.Fy.values,
                                                  "Fz": ds.Fz.values, "Fn": ds.Fn.values,
                                                  "Fy_contact": fy_c, "Fn_contact": fn_c},
                               steady_window(case, model))
    return RollingResult(ds, patch, steady["Fx"], steady["Fy"], patch.attrs["p_max"],
                         patch.attrs["a"], patch.attrs["b"], model, u, info, steady, state,
                         plastic_fields(model, u, state))


def _forces_row(c):
    fs = c["fs"]
    return fs[:, 0].sum(), fs[:, 1].sum(), fs[:, 2].sum(), c["pn"].sum()


def _internal_energy(model, u, state):
    _, e = model.internal_force(u, state=state)
    return e, (state.energies[1] if state is not None else 0.0)


def solve_implicit_qs(case, progress, io):
    (model, K, free, Kff, u, w, c, speed, dt, nsteps, R, solver,
     state) = _implicit_start(case, io)
    beta_r = case.rayleigh[1]
    # viscous (Kelvin-Voigt) term β K (q − q_n)/Δt, backward Euler: tangent K (1 + β/Δt)
    Kff_eff = Kff * (1.0 + beta_r / dt) if beta_r > 0 else Kff
    tangent = _tangent(model, free, state, Kff if beta_r > 0 else None, beta_r / dt)
    if io["restart"] is not None:
        st = read_restart(io["restart"], model, dt)
        u, w, psi, s, t, k0, iters = (st[k] for k in ("u", "w", "psi", "s", "t", "k", "iters"))
        c, E, rows = st["c"], st["E"], st["rows"].tolist()
        ft, e_int0 = c["ft"], st["e_int0"]
        if state is not None:
            state.committed[:] = st["plastic"]
    else:
        ft, psi, s, t, rows, E, iters, k0, e_int0 = _fresh_implicit_state(model, u, state)
    fc, fcw = model.generalized_contact_force(c, psi)
    bar = progress_bar(progress, nsteps - k0, f"FE implicit-qs ({model.n_elements} el.)")

    def snapshot(k_done):
        return dict(u=u, w=w, psi=psi, s=s, t=t, k=k_done, iters=iters, e_int0=e_int0,
                    c=contact_state(c), E=E, rows=np.array(rows, float).reshape(-1, len(COLUMNS)),
                    **({"plastic": state.committed} if state is not None else {}))

    maybe_write = restart_writer(io, model, dt, nsteps)
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
                             case.Fn, dyn=dyn, solver=solver, state=state, tangent=tangent)
        if state is not None:
            state.commit()
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
        E["external"] += -case.Fn * dq[-1]
        e_int, e_pl = _internal_energy(model, u, state)
        rows.append([t, s, *_forces_row(c), 0.0, e_int - e_int0, float(c["energy"].sum()),
                     E["friction"], E["damping"], E["external"], E["contact_work"], e_pl])
        if bar is not None:
            bar.update(bar.task_ids[0], completed=k + 1 - k0)
        if maybe_write(k + 1, lambda: snapshot(k + 1)):
            solver.lu = None          # a restart starts from a fresh factorisation: same numbers
    if bar is not None:
        bar.stop()
    return _implicit_result(case, model, rows, c, psi, dt, nsteps, iters, u, solver, k0, state)


def solve_implicit_hht(case, progress, io):
    (model, K, free, Kff, u, w, c, speed, dt, nsteps, R, solver,
     state) = _implicit_start(case, io)
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
    tangent = _tangent(model, free, state, Kff if beta_r > 0 else None, cv * beta_r)
    fixed = np.setdiff1d(np.arange(3 * model.n_nodes + 1), free)

    def damping_force(vv):
        out = alpha_r * mvec * vv
        if beta_r > 0:
            out = out + beta_r * (K @ vv)
        return out

    def static_residual(q, c):
        f_int, _ = model.internal_force(q[:-1].reshape(-1, 3), state=state)
        fc, fcw = model.generalized_contact_force(c, psi)
        return np.concatenate([(f_int - fc).ravel(), [case.Fn - fcw]])

    if io["restart"] is not None:
        st = read_restart(io["restart"], model, dt)
        q, v, a = st["q"], st["v"], st["a"]
        psi, s, t, k0, iters, e_int0 = (st[k] for k in ("psi", "s", "t", "k", "iters", "e_int0"))
        c, E, rows = st["c"], st["E"], st["rows"].tolist()
        ft = c["ft"]
        if state is not None:
            state.committed[:] = st["plastic"]
    else:
        q = np.concatenate([u.ravel(), [w]])
        v = np.zeros_like(q)
        a = np.zeros_like(q)
        ft, psi, s, t, rows, E, iters, k0, e_int0 = _fresh_implicit_state(model, u, state)
    r_old = static_residual(q, c)
    fc, fcw = model.generalized_contact_force(c, psi)
    fdamp = damping_force(v)
    bar = progress_bar(progress, nsteps - k0, f"FE implicit-hht ({model.n_elements} el.)")

    def snapshot(k_done):
        return dict(q=q, v=v, a=a, psi=psi, s=s, t=t, k=k_done, iters=iters, e_int0=e_int0,
                    c=contact_state(c), E=E, rows=np.array(rows, float).reshape(-1, len(COLUMNS)),
                    **({"plastic": state.committed} if state is not None else {}))

    maybe_write = restart_writer(io, model, dt, nsteps)
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
                               c["xs"], c["xm"], ft, case.mu, case.Fn, dyn=dyn,
                               static_scale=1.0 + al, diag=diag, solver=solver, state=state,
                               tangent=tangent)
        if state is not None:
            state.commit()
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
        E["external"] += -case.Fn * dq[-1]
        e_int, e_pl = _internal_energy(model, u1, state)
        rows.append([t, s, *_forces_row(c), 0.5 * float(np.sum(mvec * v * v)), e_int - e_int0,
                     float(c["energy"].sum()), E["friction"], E["damping"], E["external"],
                     E["contact_work"], e_pl])
        if bar is not None:
            bar.update(bar.task_ids[0], completed=k + 1 - k0)
        if maybe_write(k + 1, lambda: snapshot(k + 1)):
            solver.lu = None          # a restart starts from a fresh factorisation: same numbers
    if bar is not None:
        bar.stop()
    return _implicit_result(case, model, rows, c, psi, dt, nsteps, iters, q[:-1].reshape(-1, 3),
                            solver, k0, state, {"hht_alpha": al})


def _rayleigh_force(K, factor, q_n):
    """Stiffness-proportional damping force ``factor · K (q − q_n)`` of one step."""
    def dyn(qq):
        return factor * (K @ (qq - q_n))
    return dyn


def _fresh_implicit_state(model, u, state):
    """Start of an implicit run without a restart file: tangential contact history,
    rolling angle, travel, time, output rows, energy accounts, iteration and step
    counters, and the internal energy of the initial displacement ``u``."""
    e_int0, _ = _internal_energy(model, u, state)
    E = dict(friction=0.0, external=0.0, damping=0.0, contact_work=0.0)
    return np.zeros((model.slave.size, 3)), 0.0, 0.0, 0.0, [], E, 0, 0, e_int0
