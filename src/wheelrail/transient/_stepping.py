"""The time stepping of transient rolling: the problem of a run and its steps (private).

:func:`wheelrail.transient.transient_rolling` validates its inputs into a
:class:`RollingProblem` (the loads at every step and the prepared operators:
grid, kernels, FFT convolutions, collocation of the scheme) and runs it with
:func:`run`: :func:`start` (the unloaded first step), :func:`advance` (one
step), :func:`force_step` (the step with ξ unknown) and :func:`assemble` (the
frozen history). The equations are those of :mod:`wheelrail.transient.rolling`.

References
----------
.. [1] L. Baeza, F.J. Fuenmayor, J. Carballeira, A. Roda, Influence of the
   wheel–rail contact instationary process on contact parameters (Baeza et al.),
   eqs. (2.8)–(2.13), (2.19)–(2.22).
.. [2] J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
   Kluwer 1990, §5.2.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .._validation import as_float_array
from ..errors import ConvergenceError, InputError
from ..normal.bem import solve_normal
from ..tangential.exact import newton_force_step, newton_step
from ._fft import FastBlockConvolution as _BlockConvolution
from ._force import _FORCING, _steady_limit, _xi_for_force
from ._schemes import _steady_step_operator
from .regularised import dense_block, regularised_step

#: the scalar histories of a run
SCALARS = ("xi", "eta", "phi", "Fn", "Fx", "Fy", "p_max", "penetration",
           "n_contact", "n_adhesion", "n_slip")


def as_function(name, value):
    """A function of travel x [m] -> float, from a constant or a callable."""
    if value is None:
        return None
    if callable(value):
        return value
    v = float(as_float_array(name, value))
    if not math.isfinite(v):
        raise InputError(f"{name} must be finite, got {value!r}")
    return lambda x, v=v: v


def evaluate(name, fun, x):
    """``fun(x)`` as a finite float, else an InputError naming the function and travel."""
    try:
        v = float(fun(x))
    except (TypeError, ValueError) as exc:
        raise InputError(f"{name}({x!r}) did not return a number: {exc}") from exc
    if not math.isfinite(v):
        raise InputError(f"{name}({x!r} m) = {v!r} is not finite")
    return v


@dataclass(frozen=True)
class HertzNormal:
    """The normal solution of the Paul–Hashemi strips: Hertz pressure [Pa], penetration [m]."""

    pressure: np.ndarray
    penetration: float


@dataclass(frozen=True)
class RollingProblem:
    """A validated transient rolling run: loads along the travel and prepared operators.

    ``load_at[name]``: each load function at every travel ``xs`` (``normal_name`` is
    ``"Fn"`` or ``"penetration"``; ``"Fx"`` under force control, else ``"xi"``);
    ``steady_from[k]``: the loads stay equal from step k to the end. ``K_now`` [Pa⁻¹
    of slip] and the convolutions ``conv_now`` (tractions now / h), ``conv_old``
    (carried displacement of the previous step), ``conv_n`` (pressure, dissimilar
    materials) act on the grid ``grid``; ``up_o``, ``up_w`` the element offsets and
    weights of the carried displacement (``carry_u``).
    """

    # validated inputs
    pair: object
    mu: float
    h: float
    friction: str
    epsilon: object
    tol: float
    maxiter: int
    force_tol: float
    settle: float
    scheme: str
    discretisation: str
    elements: int
    a: float
    b: float
    A: float
    B: float
    progress: bool
    # loads
    normal_name: str
    F3: object
    F3_const: bool
    by_penetration: bool
    F1: object
    creepage: tuple
    xs: np.ndarray
    load_at: dict
    steady_from: np.ndarray
    keep: list
    # operators
    grid: object
    gap: object
    dA: object
    K_now: np.ndarray
    conv_now: object
    conv_old: object
    conv_n: object
    strip_normal: object
    # collocation and stepping of the scheme
    upwind: bool
    spin_shift: float
    carry_u: bool
    up_o: object = None
    up_w: object = None
    jump: bool = False

    @property
    def n(self):
        return len(self.xs)

    @property
    def material(self):
        return self.discretisation == "material"


@dataclass
class _Run:
    """The state carried from step to step (mutable, private to one run)."""

    p: np.ndarray
    pn: np.ndarray
    nsol: object
    hist: dict
    store: dict
    state_store: np.ndarray
    keep_index: dict
    centre: float = 0.0  # material grid: contact centre relative to the window centre [m]
    xi_prev: float = 0.0
    slope: object = None
    prev: object = None  # (p, xi) of the step before the last, for the predictor
    fixed: object = None  # (loads, tractions, xi, slip) of a step that reproduced its input
    repeating: bool = False  # the last recorded step was a skipped repeat
    skipped: int = 0
    newton: int = 0
    krylov: int = 0
    solves: int = 0
    last_state: object = None
    u_prev: object = None
    u_box: object = None
    M_steady: object = None
    last_try: int = -10 ** 9
    d_prev: float = np.inf
    box_ops: dict = field(default_factory=dict)
    dense_cache: dict = field(default_factory=dict)


@dataclass(frozen=True)
class _Step:
    """What one step solves: ``s = base + ξ e_x + (K_now) p`` with the bound ``g``."""

    k: int
    x: float
    pn: np.ndarray
    g: np.ndarray
    rigid: np.ndarray
    base: np.ndarray
    u_normal: object
    box: object


def normal(problem, centre, x, initial):
    """The normal solution at travel ``x`` (warm started from ``initial``); ``centre``: the
    contact centre relative to the window of the material grid [m]."""
    F = evaluate(problem.normal_name, problem.F3, x)
    if problem.discretisation == "strips":
        return problem.strip_normal
    grid, pair = problem.grid, problem.pair
    gap = problem.gap
    if problem.material:
        gap = problem.A * (grid.X - centre) ** 2 + problem.B * grid.Y ** 2
    if problem.by_penetration:
        return solve_normal(grid, gap, pair, penetration=F, initial=initial)
    return solve_normal(grid, gap, pair, Fn=F, initial=initial)


def start(problem):
    """The state of the unloaded first step (tangential tractions zero), recorded."""
    nxy = problem.grid.shape
    n = problem.n
    keep = problem.keep
    nsol = normal(problem, 0.0, 0.0, None)
    run = _Run(p=np.zeros((2,) + nxy), pn=np.array(nsol.pressure), nsol=nsol,
               hist={k: np.zeros(n) for k in SCALARS},
               store={k: np.zeros((len(keep),) + nxy) for k in ("px", "py", "pn")},
               state_store=np.zeros((len(keep),) + nxy, dtype=np.int8),
               keep_index={k: j for j, k in enumerate(keep)})
    cr = problem.creepage
    record(problem, run, 0, run.pn, run.p, np.zeros_like(run.p),
           (0.0 if problem.F1 else evaluate("xi", cr[0], 0.0),
            evaluate("eta", cr[1], 0.0), evaluate("phi", cr[2], 0.0)))
    return run


def record(problem, run, k, pn, p, s, creepage):
    """Store step k's scalars (and its fields when it is a kept frame): pressure ``pn``,
    tractions ``p`` and slip ``s`` of the step, ``creepage`` = (ξ, η, φ), the normal
    solution ``run.nsol``."""
    hist, dA = run.hist, problem.dA
    g = problem.mu * pn
    contact_ = pn > 0
    norm = np.hypot(p[0], p[1])
    if problem.friction == "regularised":  # no sharp split: slip where |s| > ε (|p| > g/2)
        slip = contact_ & (np.hypot(s[0], s[1]) > problem.epsilon)
    else:
        slip = contact_ & (norm >= g * (1 - 1e-9)) & (np.hypot(s[0], s[1]) > 0)
    hist["xi"][k], hist["eta"][k], hist["phi"][k] = creepage
    hist["Fn"][k] = float((pn * dA).sum())
    hist["Fx"][k] = float((p[0] * dA).sum())
    hist["Fy"][k] = float((p[1] * dA).sum())
    hist["p_max"][k] = float(pn.max())
    hist["penetration"][k] = float(run.nsol.penetration)
    hist["n_contact"][k] = int(contact_.sum())
    hist["n_slip"][k] = int(slip.sum())
    hist["n_adhesion"][k] = int(contact_.sum() - slip.sum())
    run.last_state = np.where(slip, 2, np.where(contact_, 1, 0))
    j = run.keep_index.get(k)
    if j is not None:
        run.store["px"][j], run.store["py"][j], run.store["pn"][j] = p[0], p[1], pn
        run.state_store[j] = run.last_state


def repeat(problem, run, k, p, pn, stop=None):
    """Record step k (to ``stop`` − 1) as a repeat of step k − 1 (the steady fixed
    point: same values)."""
    stop = k + 1 if stop is None else stop
    for v in run.hist.values():
        v[k:stop] = v[k - 1]
    for kk in (problem.keep if stop > k + 1 else (k,)):
        j = run.keep_index.get(kk)
        if j is not None and k <= kk < stop:
            run.store["px"][j], run.store["py"][j], run.store["pn"][j] = p[0], p[1], pn
            run.state_store[j] = run.last_state


def _shift_window(problem, run):
    """Material grid: the contact moves by h over the rail-fixed elements; the window
    follows in whole elements (tractions and pressure move back by one index)."""
    grid = problem.grid
    run.centre += problem.h
    while run.centre >= 0.5 * grid.dx * (1 - 1e-12):
        run.p = np.concatenate((run.p[:, 1:], np.zeros((2, 1, grid.ny))), axis=1)
        run.pn = np.concatenate((run.pn[1:], np.zeros((1, grid.ny))), axis=0)
        run.centre -= grid.dx


def _repeat_fixed(problem, run, k, pn_new, eta, phi):
    """Step k reproduces the steady fixed point: record it unsolved; the number of
    steps it accounts for (all to the end when the loads stay constant)."""
    n = problem.n
    xi = run.fixed[2]
    if not run.repeating:
        record(problem, run, k, pn_new, run.p, run.fixed[3], (xi, eta, phi))
        run.repeating = True
    elif problem.steady_from[k] and problem.F3_const:
        # the loads stay constant to the end: every later step repeats it too
        repeat(problem, run, k, run.p, pn_new, n)
        run.skipped += n - k
        return n - k
    else:
        repeat(problem, run, k, run.p, pn_new)
    run.skipped += 1
    return 1


def _carried(problem, run, ci, cj):
    """The displacement of the previous step at the departure points (over h·…)."""
    grid = problem.grid
    u_box = run.u_box
    up_o = problem.up_o
    if run.u_prev is not None:
        up_lo, up_hi = int(up_o.min()), int(up_o.max())
        if (ci.size and ci.min() + up_lo >= u_box[0].start and ci.max() + up_hi < u_box[0].stop
                and cj.min() >= u_box[1].start and cj.max() < u_box[1].stop):
            # the previous step's displacement field interpolated upstream
            carried = np.zeros((2,) + grid.shape)
            i0, i1 = max(0, -up_lo), grid.nx - max(0, up_hi)
            for o, wk in zip(up_o, problem.up_w):
                carried[:, i0:i1] += wk * run.u_prev[:, i0 + o:i1 + o]
            return carried
    return problem.conv_old(np.concatenate((run.p, run.pn[None])))


def _step_data(problem, run, k, x, pn_new, eta, phi):
    """The right-hand side of step k: rigid slip minus the carried displacement over h."""
    grid, h = problem.grid, problem.h
    g = problem.mu * pn_new
    box = None
    ci, cj = np.nonzero(g > 0)
    if problem.carry_u and problem.friction == "exact" and ci.size:
        # the step's products on the box of the contact (and the rows upstream that
        # the next step's carried displacement needs): a smaller FFT, same numbers
        up_lo, up_hi = int(problem.up_o.min()), int(problem.up_o.max())
        box = (slice(max(0, int(ci.min()) + min(0, up_lo)),
                     min(grid.nx, int(ci.max()) + up_hi + 2)),
               slice(int(cj.min()), int(cj.max()) + 1))
    carried = _carried(problem, run, ci, cj)
    rigid = np.zeros((2,) + grid.shape)
    rigid[0] -= phi * grid.Y
    # the spin's rigid slip phi x is collocated _SPIN_SHIFT dx upstream of the element
    # centre, as in the steady solver: held steady the run ends on its solution
    rigid[1] += eta + phi * (grid.X - run.centre + problem.spin_shift * grid.dx)
    base = rigid - carried / h
    u_normal = None
    if problem.conv_n is not None:
        u_normal = problem.conv_n(pn_new[None])
        base = base + u_normal / h
    return _Step(k=k, x=x, pn=pn_new, g=g, rigid=rigid, base=base, u_normal=u_normal, box=box)


def _box_operator(problem, run, box):
    """The step kernel cropped to a box's size and its FFT convolution (kept)."""
    mx, my = box[0].stop - box[0].start, box[1].stop - box[1].start
    if (mx, my) not in run.box_ops:
        cx, cy = problem.grid.nx - 1, problem.grid.ny - 1
        Kb = np.ascontiguousarray(problem.K_now[:, :, cx - (mx - 1):cx + mx,
                                                cy - (my - 1):cy + my])
        run.box_ops[mx, my] = (Kb, _BlockConvolution(Kb))
    return run.box_ops[mx, my]


def _embed(problem, pb, sb, sl):
    """Tractions and slip of the solved box ``sl`` placed in the full grid."""
    pp = np.zeros((2,) + problem.grid.shape)
    ss = np.zeros((2,) + problem.grid.shape)
    pp[sl] = pb
    ss[sl] = sb
    return pp, ss


def _dense_for(problem, run, mask):
    """The dense step kernel over the contact elements (regularised law; kept)."""
    key = mask.tobytes()
    if key not in run.dense_cache:
        run.dense_cache.clear()
        ii, jj = np.nonzero(mask)
        run.dense_cache[key] = dense_block(problem.K_now, ii, jj)
    return run.dense_cache[key]


def _solve_regularised(problem, run, b, g, p0):
    mask = g > 0
    Kd = _dense_for(problem, run, mask)
    pp = np.zeros((2,) + problem.grid.shape)
    qc, sc, its = regularised_step(Kd, b[:, mask], g[mask], problem.epsilon, p0[:, mask],
                                   tol=problem.tol, maxiter=problem.maxiter)
    pp[:, mask] = qc
    ss = b + problem.conv_now(pp)
    run.newton += its
    run.solves += 1
    return pp, ss


def solve(problem, run, st, xi, p0):
    """Tractions and slip ``(p, s)`` of step ``st`` at the creepage ``xi`` from ``p0``."""
    b = st.base.copy()
    b[0] += xi
    if problem.friction == "regularised":
        return _solve_regularised(problem, run, b, st.g, p0)
    kw = dict(tol=problem.tol, maxiter=problem.maxiter, upwind=problem.upwind,
              forcing=_FORCING)
    if st.box is None:
        pp, ss, its, res, kry = newton_step(problem.K_now, b, st.g, conv=problem.conv_now,
                                            initial=p0,
                                            krylov_conv=getattr(problem.conv_now, "single",
                                                                None), **kw)
    else:
        Kb, cb = _box_operator(problem, run, st.box)
        sl = (slice(None),) + st.box
        pb, sb, its, res, kry = newton_step(Kb, b[sl], st.g[st.box], conv=cb, initial=p0[sl],
                                            krylov_conv=cb.single, **kw)
        pp, ss = _embed(problem, pb, sb, sl)
    run.newton += its
    run.krylov += kry
    run.solves += 1
    if not res <= problem.tol:
        raise ConvergenceError(f"step {st.k} (x = {st.x!r} m, xi = {xi!r}): the "
                               f"frictional problem did not converge "
                               f"(residual {res:.2e} > tol={problem.tol:.1e})")
    return pp, ss


def _solve_force(problem, run, st, target, xi0, p0, ftol):
    """``(xi, p, s, its)`` of one Newton iteration with ξ unknown, or None if it fails."""
    dA = problem.dA
    kw = dict(weights=dA, Fx=target, xi=xi0, force_tol=ftol, tol=problem.tol,
              maxiter=problem.maxiter, upwind=problem.upwind, forcing=_FORCING)
    if st.box is None:
        pp, ss, xi, its, res, kry = newton_force_step(
            problem.K_now, st.base, st.g, conv=problem.conv_now, initial=p0,
            krylov_conv=getattr(problem.conv_now, "single", None), **kw)
    else:
        Kb, cb = _box_operator(problem, run, st.box)
        sl = (slice(None),) + st.box
        if np.ndim(dA):
            kw["weights"] = dA[st.box]
        pb, sb, xi, its, res, kry = newton_force_step(
            Kb, st.base[sl], st.g[st.box], conv=cb, initial=p0[sl], krylov_conv=cb.single,
            **kw)
        pp, ss = _embed(problem, pb, sb, sl)
    run.newton += its
    run.krylov += kry
    run.solves += 1
    return (xi, pp, ss, its) if res <= problem.tol else None


def force_step(problem, run, st, target):
    """Step ``st`` under the prescribed force F1 = ``target`` [N]: ``(xi, p, s, extrapolate)``.

    ξ is one more unknown of the Newton iteration (one solve per step), started from the
    state extrapolated from the two previous steps; the secant iteration on ξ around the
    step where that fails.
    """
    mu, dA = problem.mu, problem.dA
    Fn_k = float((st.pn * dA).sum())
    if not abs(target) < mu * Fn_k:
        raise InputError(f"Fx({st.x!r} m) = {target!r} N must be smaller "
                         f"in magnitude than mu*Fn = {mu * Fn_k!r} N (full sliding)")
    ftol = problem.force_tol * mu * Fn_k
    p_guess, xi_guess = run.p, run.xi_prev
    if run.prev is not None:
        p_guess, xi_guess = 2.0 * run.p - run.prev[0], 2.0 * run.xi_prev - run.prev[1]
    exact = problem.friction == "exact"
    got = _solve_force(problem, run, st, target, xi_guess, p_guess, ftol) if exact else None
    if got is None and exact and xi_guess == 0.0:
        # from rest without creepage the slip vanishes and has no scale: start
        # from a small creepage of the sign that gives the force
        got = _solve_force(problem, run, st, target, -math.copysign(1e-6, target), p_guess,
                           ftol)
    if got is not None:
        xi, p_new, s_new, its = got
        # a step that met the tolerance at its starting point (the steady state,
        # reproduced exactly from an unextrapolated start) predicts no change for the next
        return xi, p_new, s_new, its > 0
    xi, p_new, s_new, run.slope = _xi_for_force(
        lambda xi_, p0: solve(problem, run, st, xi_, p0), target, run.xi_prev, run.slope,
        run.p, dA, ftol, st.k, st.x)
    return xi, p_new, s_new, False


def _try_steady(problem, run, st, xi, p_new, p_in, control):
    """The steady fixed point of the step, ``(xi, p, s)``, if it lies within ``settle`` of
    the current tractions once they change little per step (else None)."""
    gmax = float(st.g.max())
    d = float(np.abs(p_new - p_in).max()) / gmax
    got = None
    if d <= 0.1 * problem.settle and d <= run.d_prev:
        run.last_try = st.k
        if run.M_steady is None:
            run.M_steady = _steady_step_operator(problem.grid, problem.pair, problem.h,
                                                 problem.scheme)
        mu, dA = problem.mu, problem.dA
        stl = _steady_limit(run.M_steady, st.rigid, st.pn, st.g, xi, p_new,
                            control if problem.F1 is not None else None, dA,
                            problem.force_tol * mu * float((st.pn * dA).sum()), problem.tol,
                            problem.maxiter, run.slope, st.k, st.x, problem.upwind)
        run.solves += 1
        if stl is not None and np.abs(stl[1] - p_new).max() <= problem.settle * gmax:
            got = stl
    run.d_prev = d
    return got


def advance(problem, run, k):
    """Solve and record step k; the number of steps it accounts for (``n − k`` when the
    run has reached its steady fixed point under loads constant to the end)."""
    x = problem.xs[k]
    load_at = problem.load_at
    if problem.material:
        _shift_window(problem, run)
    if not problem.F3_const or problem.material:
        run.nsol = normal(problem, run.centre, x, run.pn)
    pn_new = np.array(run.nsol.pressure)
    eta, phi = float(load_at["eta"][k]), float(load_at["phi"][k])
    control = float(load_at["xi" if problem.F1 is None else "Fx"][k])
    key = (eta, phi, control)
    fixed = run.fixed
    if (fixed is not None and not problem.material and fixed[0] == key
            and np.array_equal(fixed[1], run.p) and np.array_equal(run.pn, pn_new)):
        # the previous step reproduced its input exactly under the same loads: the
        # run has reached its steady fixed point and every such step repeats it
        return _repeat_fixed(problem, run, k, pn_new, eta, phi)
    st = _step_data(problem, run, k, x, pn_new, eta, phi)
    p_in, xi_in = run.p, run.xi_prev
    extrapolate = False
    if problem.F1 is None:
        xi = control
        p_new, s_new = solve(problem, run, st, xi, run.p)
    else:
        xi, p_new, s_new, extrapolate = force_step(problem, run, st, control)
        run.xi_prev = xi
    # (with settle=0 every step is solved, as documented)
    run.fixed = ((key, p_in, xi, s_new) if problem.settle > 0 and np.array_equal(p_new, p_in)
                 else None)
    if problem.carry_u:
        # the displacement difference C (p, pn) of this step: h (s − b) + C_tn pn
        b_fin = st.base.copy()
        b_fin[0] += xi
        run.u_prev = problem.h * (s_new - b_fin) + (0.0 if st.u_normal is None
                                                    else st.u_normal)
        run.u_box = (st.box if st.box is not None
                     else (slice(0, problem.grid.nx), slice(0, problem.grid.ny)))
    if (problem.jump and run.fixed is None and problem.steady_from[k]
            and k - run.last_try >= 10):
        got = _try_steady(problem, run, st, xi, p_new, p_in, control)
        if got is not None:
            xi, p_new, s_new = got
            run.xi_prev = xi
            run.u_prev = None  # recomputed by the next step's convolution
            extrapolate = False
    run.prev = (p_in, xi_in) if extrapolate and not problem.material else None
    run.p, run.pn = p_new, pn_new
    record(problem, run, k, run.pn, run.p, s_new, (xi, eta, phi))
    run.repeating = False
    return 1


def assemble(problem, run):
    """The fields of the frozen :class:`~wheelrail.transient.TransientResult` of a run."""
    for d in (run.hist, run.store):
        for v in d.values():
            v.setflags(write=False)
    run.state_store.setflags(write=False)
    xs, grid = problem.xs, problem.grid
    frame_x = xs[problem.keep]
    frame_x.setflags(write=False)
    xs.setflags(write=False)
    epsilon = problem.epsilon
    info = {"step": problem.h, "mu": problem.mu, "elements": problem.elements,
            "nx": grid.nx, "ny": grid.ny, "dx": float(np.max(grid.dx)), "dy": grid.dy,
            "discretisation": problem.discretisation, "a": problem.a, "b": problem.b,
            "friction": problem.friction,
            "epsilon": float(epsilon) if epsilon is not None else float("nan"),
            "newton": run.newton, "krylov": run.krylov, "solves": run.solves,
            "steady_steps": run.skipped,
            "control": "force" if problem.F1 is not None else "creepage"}
    return dict(x=xs, history=run.hist, grid=grid, frame_x=frame_x, px=run.store["px"],
                py=run.store["py"], pn=run.store["pn"], state=run.state_store, info=info)


def run(problem):
    """Step ``problem`` through its travel; the fields of its result (:func:`assemble`)."""
    state = start(problem)
    n = problem.n
    bar = None
    if problem.progress:
        from rich.progress import Progress
        bar = Progress(transient=True)
        bar.start()
        task = bar.add_task("transient rolling", total=n - 1)
    try:
        k = 1
        while k < n:
            done = advance(problem, state, k)
            if bar is not None:
                bar.advance(task, done)
            k += done
    finally:
        if bar is not None:
            bar.stop()
    return assemble(problem, state)
