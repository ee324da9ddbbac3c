"""Time-domain simulation of a wheelset or bogie model on a track layout.

:func:`simulate` integrates the equations of
:mod:`wheelrail.dynamics._motion` with the contact forces of every wheel
evaluated at every evaluation of the right-hand side (compiled path for Hertz
or Kik–Piotrowski with FASTSIM or the table law, the library's methods
otherwise; :mod:`wheelrail.dynamics.contact`), by

* :class:`Adaptive` — :func:`scipy.integrate.solve_ivp` (``"RK45"``,
  ``"DOP853"`` non-stiff; ``"Radau"``, ``"BDF"``, ``"LSODA"`` stiff). A change
  of the contact configuration (the number of patches of a wheel: a contact
  point appears, vanishes, or jumps) is a terminal event: the integration stops
  there (located by :func:`scipy.optimize.brentq` on the dense output) and
  restarts, so that no step straddles the kink;
* :class:`FixedStep` — the classical Runge–Kutta (or Heun) scheme with a fixed
  step for real-time use (compiled loop with the compiled contact): a step
  across which the configuration changes is redone in halves, down to
  ``dt / 2**max_halvings``.

Results are a :class:`SimulationResult` whose :attr:`~SimulationResult.dataset`
is an :class:`xarray.Dataset` over time.

References
----------
.. [1] J. Piotrowski, H. Chollet, Wheel–rail contact models for vehicle system
   dynamics including multi-point contact, VSD 43 (2005) 455–483 (contact
   evaluated online during the integration; contact jumps).
.. [2] E. Hairer, G. Wanner, *Solving ordinary differential equations II*,
   Springer 1996 (stiff integrators; discontinuities handled by restarting).
"""

from __future__ import annotations

import contextlib
import math
import time
import warnings
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp

from ..errors import ConvergenceError, InputError, WheelrailError
from ..geometry.contact_search import solve_rigid
from ..geometry.touching import touching_heights
from ._fastcontact import KMAX, PATCH_FIELDS, WHEEL_FIELDS
from ._guards import (ABSURD, MIN_RADIUS, RunWarning, SimulationInterrupted, check_speed,
                      check_states, estimate, nadal_scan, nadal_warn)
from ._motion import (N_IN, derivative, relax_decay, relax_derivative, relax_stage, rhs_fast,
                      run_fixed, wheel_inputs)
from ._speed import falls_below, greatest_speed, least_speed, profile_at, profile_eval
from .contact import FastContact, contact_model
from .layout import as_layout
from .model import GP, Assembly, BogieModel, WheelsetModel
from .results import SimulationResult
from .speed import SpeedProfile, _run_table
from ._outputs import Memory, Stream, outputs, shapes
from .store import StoreWriter, open_result
from .vehicle import VehicleAssembly, VehicleModel

__all__ = ["simulate", "FixedStep", "Adaptive", "System", "StepWarning",
           "RunWarning", "SimulationInterrupted", "ABSURD"]

#: A fixed step is divided into sub-steps so that RK4 takes the creep damping's shortest
#: time constant τ in steps of at most _TAU_STEPS τ (RK4 is stable to 2.79 τ on the real axis).
_TAU_STEPS = 2.0
#: Largest number of sub-steps per fixed step (beyond it the run is refused).
_MAX_SUBSTEPS = 1000


class StepWarning(UserWarning):
    """The fixed step is too long for the stiffest creep-damped motion at the run's speed:
    it is divided into sub-steps (the message gives the time constant and the cost)."""


_W = {n: i for i, n in enumerate(WHEEL_FIELDS)}
_P = {n: i for i, n in enumerate(PATCH_FIELDS)}


@dataclass(frozen=True)
class FixedStep:
    """Fixed-step explicit integration (frozen).

    Parameters
    ----------
    dt : float
        Step [s] (1 ms for real time).
    scheme : {"rk4", "heun"}
        Classical fourth-order Runge–Kutta (4 contact evaluations per step) or
        Heun's second-order scheme (2).
    max_halvings : int
        A step across a change of the contact configuration is halved down to
        dt/2**max_halvings.
    """

    dt: float = 1e-3
    scheme: str = "rk4"
    max_halvings: int = 6

    def __post_init__(self):
        if not (isinstance(self.dt, (int, float)) and math.isfinite(self.dt) and self.dt > 0):
            raise InputError(f"FixedStep: dt must be > 0 s, got {self.dt!r}")
        if self.scheme not in ("rk4", "heun"):
            raise InputError(f"FixedStep: scheme must be 'rk4' or 'heun', got {self.scheme!r}")
        if not (isinstance(self.max_halvings, int) and 0 <= self.max_halvings <= 30):
            raise InputError(f"FixedStep: max_halvings must be an integer in [0, 30], got "
                             f"{self.max_halvings!r}")


@dataclass(frozen=True)
class Adaptive:
    """Adaptive integration with :func:`scipy.integrate.solve_ivp` (frozen).

    Parameters
    ----------
    method : {"RK45", "DOP853", "RK23", "Radau", "BDF", "LSODA"}
    rtol, atol : float
        Tolerances (``atol`` on every state; states are in m, rad, m/s, rad/s, N).
    max_step : float
        Largest step [s].
    """

    method: str = "RK45"
    rtol: float = 1e-6
    atol: float = 1e-9
    max_step: float = 2e-3

    def __post_init__(self):
        if self.method not in ("RK45", "DOP853", "RK23", "Radau", "BDF", "LSODA"):
            raise InputError(f"Adaptive: method must be one of RK45, DOP853, RK23, Radau, BDF, "
                             f"LSODA, got {self.method!r}")
        for name in ("rtol", "atol", "max_step"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise InputError(f"Adaptive: {name} must be > 0, got {v!r}")


def _integrator(spec):
    if isinstance(spec, (FixedStep, Adaptive)):
        return spec
    if spec in ("rk4", "heun"):
        return FixedStep(scheme=spec)
    if isinstance(spec, str):
        return Adaptive(method=spec)
    raise InputError(f"integrator must be FixedStep(...), Adaptive(...) or a name ('rk4', "
                     f"'heun', 'RK45', 'Radau', ...), got {spec!r}")


# --------------------------------------------------------------------------- the system
class System:
    """A model on a layout with its contact evaluator: right-hand side and contact outputs.

    Parameters
    ----------
    model : WheelsetModel, BogieModel or VehicleModel
    track : Track or TrackLayout
    speed : float or SpeedProfile
        Speed at t = 0 [m/s], or the speed over the run
        (:class:`~wheelrail.dynamics.SpeedProfile`, its table in ``SP``).
    normal, tangential : str or configured method
    mu : float
        Friction coefficient.
    deceleration : float
        dV/dt = −deceleration [m/s²] (a speed ramp) with a float ``speed``. The
        speed of the kinematics is floored at ``min_speed``.
    creep_relaxation : bool or float
        First-order relaxation of the creep forces (time constant a/V, or
        ``creep_relaxation`` · a/V for a number).
    contact : {"auto", "fast", "generic"}
    start : float
        Position of the model (frame centre) along the track at t = 0 [m].
    contact_options : dict
        Options of :class:`~wheelrail.dynamics.contact.FastContact`.
    method_options : dict
        Options of the normal and tangential methods, each to the method that
        declares it (:func:`~wheelrail.dynamics.contact.configured_methods`).
    """

    def __init__(self, model, track, speed, normal="kik-piotrowski", tangential="fastsim", *,
                 mu=0.3, deceleration=0.0, creep_relaxation=False, contact="auto", start=0.0,
                 min_speed=0.5, contact_options=None, method_options=None):
        if not isinstance(model, (WheelsetModel, BogieModel, VehicleModel)):
            raise InputError(f"model must be a WheelsetModel, BogieModel or VehicleModel, got "
                             f"{type(model).__name__}")
        self.model = model
        self.layout = as_layout(track)
        for c in self.layout.curves:
            if c.radius < MIN_RADIUS:
                raise InputError(f"curve radius = {c.radius!r} m is below {MIN_RADIUS:g} m "
                                 f"(the tightest railway curves are about 60–80 m); a radius "
                                 f"in km or mm?")
        if not (isinstance(mu, (int, float, np.floating)) and math.isfinite(mu) and mu > 0):
            raise InputError(f"mu must be a number > 0, got {mu!r}")
        if not (isinstance(deceleration, (int, float, np.floating))
                and math.isfinite(deceleration)):
            raise InputError(f"deceleration must be finite, got {deceleration!r}")
        if not (isinstance(start, (int, float, np.floating)) and math.isfinite(start)):
            raise InputError(f"start must be a finite position [m], got {start!r}")
        self.profile, self.SP = _run_table(speed, deceleration, start)
        #: speed [m/s] and dV/dt [m/s²] at t = 0
        self.speed = float(self.SP[1, 0])
        self.aV = float(self.SP[3, 0])
        if self.profile is not None and not (self.speed > 0 or self.aV > 0):
            raise InputError(f"the speed profile starts at {self.speed!r} m/s and does not "
                             f"accelerate: the run stands still")
        self.mu = float(mu)
        self.start = float(start)
        self.min_speed = float(min_speed)
        if not (isinstance(creep_relaxation, (bool, np.bool_)) or (
                isinstance(creep_relaxation, (int, float, np.floating))
                and math.isfinite(creep_relaxation) and creep_relaxation >= 0)):
            raise InputError(f"creep_relaxation must be True, False or a relaxation length "
                             f"in semi-axes a (a number > 0), got {creep_relaxation!r}")
        self.asm = (VehicleAssembly if isinstance(model, VehicleModel) else Assembly)(
            model, relax=creep_relaxation)
        self.contact = contact_model(model.wheelset, self.layout.track, model.material, normal,
                                     tangential, contact=contact, method_options=method_options,
                                     **(contact_options or {}))
        self.fast = isinstance(self.contact, FastContact)
        nw = self.asm.n_ws
        self.OP = np.zeros((nw, 2, KMAX, len(PATCH_FIELDS)))
        self.OW = np.zeros((nw, 2, len(WHEEL_FIELDS)))
        self.n_eval = 0
        self._last = None

    # ---------------------------------------------------------------- evaluation
    def V(self, t):
        """Speed of the kinematics at ``t`` [m/s] (floored at ``min_speed``)."""
        return max(profile_at(self.SP, float(t))[0], self.min_speed)

    def dVdt(self, t):
        """dV/dt of the run at ``t`` [m/s²]."""
        return profile_at(self.SP, float(t))[1]

    def s_ref(self, t):
        """Position of the reference along the track at ``t`` [m]."""
        return profile_at(self.SP, float(t))[2]

    def least_speed(self, t0, t1):
        """Least speed of the kinematics over [t0, t1] [m/s] (floored at ``min_speed``)."""
        return max(least_speed(self.SP, float(t0), float(t1)), self.min_speed)

    def rhs(self, t, x):
        """dx/dt at (t, x); the contact outputs of this evaluation in ``OP``, ``OW``."""
        x = np.ascontiguousarray(x, dtype=float)
        dx = np.empty_like(x)
        self.n_eval += 1
        if self.fast:
            c = self.contact
            rhs_fast(float(t), x, self.asm.P, self.layout.arrays, self.SP, self.min_speed,
                     c.geometry["left"], c.geometry["right"], c.method, self.mu, self.OP,
                     self.OW, dx)
            if c.table_raise and np.any(self.OW[..., _W["fallbacks"]] > 0):
                c._raise_outside(self.OW)
        else:
            self._generic(t, x, dx)
        self._last = (float(t), x.copy(), dx)
        return dx

    def _generic(self, t, x, dx):
        nw = self.asm.n_ws
        V, aV, s_ref = profile_at(self.SP, float(t))
        V = max(V, self.min_speed)
        W = np.empty((nw, 2, N_IN))
        wheel_inputs(float(t), x, self.asm.P, self.layout.arrays, V, s_ref, W)
        for i in range(nw):
            for side, name in enumerate(("left", "right")):
                w = W[i, side]
                self.contact.wheel(name, *w, self.mu, self.OP[i, side], self.OW[i, side])
        Qn = np.ascontiguousarray(self.OW[..., 1:6])
        Qt = np.ascontiguousarray(self.OW[..., 6:11])
        am = np.ascontiguousarray(self.OW[..., _W["a_mean"]])
        if self.asm.P[GP["relax"]] > 0:
            ox = self.asm.off_relax
            Qr = x[ox:ox + 10 * nw].reshape(nw, 2, 5).copy()
            derivative(float(t), x, self.asm.P, self.layout.arrays, V, aV, s_ref, Qn, Qr, am,
                       dx)
            relax_derivative(x, self.asm.P, V, Qt, am, dx)
        else:
            derivative(float(t), x, self.asm.P, self.layout.arrays, V, aV, s_ref, Qn, Qt, am,
                       dx)

    @contextlib.contextmanager
    def steady(self):
        """Within: the creep forces act at once, without relaxation (the relaxation states
        are ignored and their rates zero) — for the static equilibrium and the step
        control."""
        j = GP["relax"]
        keep = self.asm.P[j]
        self.asm.P[j] = 0.0
        self._last = None
        try:
            yield self
        finally:
            self.asm.P[j] = keep
            self._last = None

    def creep_rate(self, t, x):
        """The fastest creep-damped motion at (t, x): (rate [1/s], its name).

        The creep forces damp the lateral, yaw and (free) spin velocities of each
        wheelset with time constants proportional to V (e.g. Iy V / (2 f11 r0²) for
        the spin, f11 Kalker's longitudinal creep coefficient); the rate is the
        largest diagonal entry |∂v̇/∂v| of those velocities, by finite differences
        of the steady (unrelaxed) equations with a creepage of 1e-5.
        """
        nw = self.asm.n_ws
        V = self.V(t)
        r0 = self.asm.P[GP["r0"]]
        l0 = 0.5 * float(self.layout.track.gauge) if hasattr(self.layout.track, "gauge") \
            else 0.75
        x = np.asarray(x, dtype=float)
        best, which = 0.0, "lateral"
        with self.steady():
            f0 = self.rhs(t, x).copy()
            dofs = [(4, 1e-5 * V, "lateral"), (7, 1e-5 * V / l0, "yaw")]
            if self.model.spin == "free":
                dofs.append((8, 1e-5 * V / r0, "spin"))
            groups = [([9 * i + off for i in range(nw)], d, name) for off, d, name in dofs]
            # flexible rails: the creep forces damp the rail heads' lateral motion too, on
            # a mass far below the wheelset's (the stiffest creep-damped motion there)
            heads = [k for k, n in enumerate(self.asm.names)
                     if n.startswith("rail") and n.endswith(".lateral.head_velocity")]
            if heads:
                groups.append((heads, 1e-5 * V, "rail head lateral"))
            for idx, d, name in groups:
                xp = x.copy()
                xp[idx] += d
                f1 = self.rhs(t, xp)
                rate = float(np.max(np.abs(f1[idx] - f0[idx]))) / d
                if rate > best:
                    best, which = rate, name
            self.rhs(t, x)
        return best, which

    def substeps(self, t, x, dt, span=0.0):
        """Sub-steps per fixed step ``dt`` for the creep damping over [t, t + span]:
        (n, rate, name).

        The rate is :meth:`creep_rate` at (t, x) scaled by V(t)/V_least, V_least the
        least speed over the span (the creep damping rates go as 1/V: the creep
        forces are f · creepage, the creepages velocity/V).
        """
        rate, which = self.creep_rate(t, x)
        V = self.V(t)
        least = self.least_speed(t, t + span) if span > 0 else V
        if least < V:
            rate *= V / least
        n = max(1, int(math.ceil(dt * rate / _TAU_STEPS - 1e-9)))
        if n > _MAX_SUBSTEPS:
            raise InputError(
                f"at V = {least:.3g} m/s the creep forces damp the {which} motion with a "
                f"time constant of {1.0 / rate:.3g} s: a fixed step of {dt!r} s would need "
                f"{n} sub-steps (more than {_MAX_SUBSTEPS}); use FixedStep(dt="
                f"{_TAU_STEPS / rate:.2g}) or an implicit Adaptive('Radau'), or a higher speed")
        self.substeps_speed = least
        return n, rate, which

    def mean_substeps(self, x0, dt, duration):
        """Sub-steps per fixed step ``dt`` on average over a run of ``duration`` from x0
        (refused, as :meth:`substeps`, when the run's least speed needs too many)."""
        n, rate, _ = self.substeps(0.0, x0, dt, duration)
        if self.SP.shape[1] == 1 and self.SP[3, 0] == 0.0:
            return n                                  # constant speed
        rate0 = rate * self.substeps_speed / self.V(0.0)     # at the speed at t = 0
        n_t = [max(1, math.ceil(dt * rate0 * self.V(0.0) / self.V(t) / _TAU_STEPS - 1e-9))
               for t in np.linspace(0.0, duration, 201)]
        return float(np.mean(n_t))

    def signature(self, t, x):
        """Patch count of every wheel at (t, x) (reuses the last evaluation when it is there)."""
        if self._last is None or self._last[0] != float(t) or not np.array_equal(self._last[1], x):
            self.rhs(t, x)
        return tuple(int(v) for v in self.OW[..., 0].reshape(-1))

    # ---------------------------------------------------------------- statics
    def initial_state(self, initial=None):
        """Static equilibrium on the track at t = 0 (y, yaw and velocities from ``initial``)."""
        asm = self.asm
        x = np.zeros(asm.n)
        nw = asm.n_ws
        r0 = asm.P[6]
        for i in range(nw):
            x[9 * i + 8] = self.V(0.0) / r0
        given = {}
        if initial is not None:
            if isinstance(initial, dict):
                for k, v in initial.items():
                    given[asm.index(k)] = float(v)
            else:
                arr = np.asarray(initial, dtype=float)
                if arr.shape != (asm.n,):
                    raise InputError(f"initial must be a dict of state names or an array of "
                                     f"shape ({asm.n},), got shape {arr.shape}")
                return arr.copy()
        for j, v in given.items():
            x[j] = v
        # rails: deflected by the static wheel load
        Q = asm.wheel_load()
        if asm.rails:
            rail = self.model.rail
            w, u = rail.static_deflection(-Q, 1)
            for i in range(nw):
                for side in range(2):
                    rb = asm.off_rails + 12 * i + 6 * side + 3
                    x[rb], x[rb + 1] = w, u
        # heights, rolls, rail deflections (and the free wheelsets' spin): Newton on their
        # accelerations
        cols, rows, steps, scales = self.asm.quasi_static(spin=True)
        keep = [k for k, c in enumerate(cols) if c not in given]
        cols, rows = [cols[k] for k in keep], [rows[k] for k in keep]
        steps, scales = steps[keep], scales[keep]
        with self.steady():
            x = self._static(x, given, cols, rows, steps, scales)
        if self.asm.relax:
            # relaxation states at their steady values (unless given)
            with self.steady():
                self.rhs(0.0, x)
            ox = asm.off_relax
            q = self.OW[..., 6:11].reshape(-1)
            for j in range(10 * nw):
                if ox + j not in given:
                    x[ox + j] = q[j]
        return x

    def _static(self, x, given, cols, rows, steps, scales):
        asm = self.asm
        nw = asm.n_ws
        for i in range(nw):
            # start from the rigid contact (roll of both wheels touching), pressed in slightly
            if 9 * i + 2 not in given:
                W = np.empty((nw, 2, N_IN))
                wheel_inputs(0.0, x, asm.P, self.layout.arrays, self.V(0.0), self.s_ref(0.0),
                             W)
                try:
                    _, th, _ = solve_rigid(self.model.wheelset, self.layout.track,
                                           np.array([0.5 * (W[i, 0, 0] + W[i, 1, 0])]),
                                           np.array([x[9 * i + 3]]))
                    # plus the roll of the rails' cross level (right rail higher: W[.., 1] lower)
                    x[9 * i + 2] = float(th[0]) + (W[i, 0, 1] - W[i, 1, 1]) / (
                        2.0 * self.model.wheelset.e_tape)
                except WheelrailError:
                    pass
            if 9 * i + 1 not in given:
                x[9 * i + 1] = self._touch_height(x, i) - 5e-5
        return self.equilibrium(x, cols, rows, steps, scales)

    def equilibrium(self, x, cols, rows, steps, scales, t=0.0, maxiter=60):
        """Newton iteration on ``x[cols]`` for ``rhs(t, x)[rows] = 0`` (finite-difference
        Jacobian with the steps ``steps``, each Newton step limited to ``scales``)."""
        x = np.array(x, dtype=float)
        if not cols:
            return x
        for _ in range(maxiter):
            f = self.rhs(t, x)[rows]
            J = np.empty((len(rows), len(cols)))
            for k, c in enumerate(cols):
                xp = x.copy()
                xp[c] += steps[k]
                J[:, k] = (self.rhs(t, xp)[rows] - f) / steps[k]
            try:
                step = np.linalg.solve(J, -f)
            except np.linalg.LinAlgError:
                raise ConvergenceError("static equilibrium: singular Jacobian") from None
            # the step limited as a whole (its direction kept), then halved while the
            # residual, in units of the Newton step, grows (the contact is stiff and
            # saturates: the linear model is good over a few micrometres only)
            big = float(np.max(np.abs(step) / scales))
            if big > 1.0:
                step = step / big
            w = np.abs(np.linalg.solve(J, f)) / scales
            merit = float(np.max(w))
            for _ in range(8):
                xn = x.copy()
                xn[cols] += step
                fn = self.rhs(t, xn)[rows]
                wn = np.abs(np.linalg.solve(J, fn)) / scales
                if float(np.max(wn)) <= merit or float(np.max(np.abs(step) / scales)) < 1e-6:
                    break
                step = 0.5 * step
            x = xn
            if np.all(np.abs(step) < 1e-6 * scales):
                return x
        if np.all(np.abs(step) < 1e-4 * scales):
            return x              # stalled on the contact's resolution (0.2 µm), close enough
        raise ConvergenceError(f"static equilibrium not reached (last Newton step "
                               f"{np.max(np.abs(step / scales))!r} of its limit)")

    def _touch_height(self, x, i):
        """Height z of wheelset ``i`` at which its lower wheel just touches its (displaced) rail."""
        W = np.empty((self.asm.n_ws, 2, N_IN))
        wheel_inputs(0.0, x, self.asm.P, self.layout.arrays, self.V(0.0), self.s_ref(0.0), W)
        r0 = self.asm.P[GP["r0"]]
        best = -np.inf
        for side, name in enumerate(("left", "right")):
            w = W[i, side]
            z, beside = touching_heights(self.model.wheelset, self.layout.track,
                                         np.array([w[0]]), np.array([w[2]]), np.array([w[3]]))
            if beside[name][0]:
                raise InputError(f"wheelset {i}: the {name} wheel lies beside its rail at the "
                                 f"initial lateral position {x[9 * i]!r} m")
            # the wheel touches when zc_rel = r0 + z_touch, zc_rel = r0 + z − u_rail
            best = max(best, float(z[name][0]) + (x[9 * i + 1] + r0 - w[1]))
        return best


# --------------------------------------------------------------------------- integration
def _progress(enabled, duration):
    """A rich progress bar over simulated time (or a no-op)."""
    if not enabled:
        return None
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

    prog = Progress(TextColumn("simulating"), BarColumn(), TextColumn("{task.completed:.3f} s of "
                    "{task.total:.3f} s"), TimeElapsedColumn(), transient=True)
    prog.start()
    prog.add_task("sim", total=duration)
    return prog


def _advance(prog, t):
    if prog is not None:
        prog.update(prog.task_ids[0], completed=t)


def _run_fixed_compiled(system, x0, duration, integ, every, prog, sink=None):
    c = system.contact
    dt = integ.dt
    nsteps = int(round(duration / dt))
    n_out = nsteps // every + 2
    out = Memory(n_out, system) if sink is None else sink
    events = np.zeros((10000, 3))
    chunk = max(1, int(round(0.05 / dt)))
    chunk = max(every, chunk - chunk % every)
    done, ne, nev, rej = 0, 0, 0, 0
    x, t = x0.copy(), 0.0
    scheme = 4 if integ.scheme == "rk4" else 2
    sub = _Substeps(system, dt)
    system.interrupted = False
    while done < nsteps:
        try:
            k = min(chunk, nsteps - done)
            ns = sub.at(t, x, k * dt)
            To, Xo, OPo, OWo = outputs(k // every + 2, system)
            ev = np.zeros((1000, 3))
            no, nei, nv, rj = run_fixed(x, t, dt / ns, k * ns, every * ns, system.asm.P,
                                        system.layout.arrays, system.SP, system.min_speed,
                                        c.geometry["left"], c.geometry["right"], c.method,
                                        system.mu, scheme, integ.max_halvings, To, Xo, OPo, OWo, ev)
            if c.table_raise and np.any(OWo[:no, ..., _W["fallbacks"]] > 0):
                c._raise_outside(OWo[:no][np.any(OWo[:no, ..., _W["fallbacks"]] > 0,
                                                 axis=(1, 2))][0])
            # the last output of a chunk is its end state: the next chunk starts there
            keep = no - 1 if done + k < nsteps else no
            out.put(To[:keep], Xo[:keep], OPo[:keep], OWo[:keep])
            events[ne:ne + nei] = ev[:nei]
            ne += nei
            nev += nv
            rej += rj
            x, t = Xo[no - 1].copy(), float(To[no - 1])
            done += k
            _advance(prog, t)
            check_states(system, To[:no], Xo[:no], dt)
            last = (To[no - 1], Xo[no - 1], OPo[no - 1], OWo[no - 1])
        except KeyboardInterrupt:
            system.interrupted = True
            if done > 0 and done < nsteps and not out.full:
                # the end state of the last finished chunk
                out.put(*(np.asarray(v)[None] for v in last))
            break
    system.n_eval += nev
    sub.report(system)
    if sink is not None:
        return None, events[:ne], rej
    return (*out.arrays(), events[:ne], rej)


class _Substeps:
    """Sub-steps of a fixed step for the creep damping, re-estimated along the run (every
    50 ms of simulated time); warns once when the step is divided."""

    def __init__(self, system, dt):
        self.system, self.dt = system, dt
        self.max, self.warned = 1, False

    def at(self, t, x, span=0.0):
        """Sub-steps for the steps over [t, t + span] (at the least speed there)."""
        n, rate, which = self.system.substeps(t, x, self.dt, span)
        if n > 1 and not self.warned:
            self.warned = True
            warnings.warn(
                f"at V = {self.system.substeps_speed:.3g} m/s the creep forces damp the {which} "
                f"motion with a time constant of {1e3 / rate:.3g} ms, too short for a fixed "
                f"step of {self.dt * 1e3:g} ms (RK4 is stable to 2.8 time constants): each "
                f"step is divided into {n} sub-steps (cost ×{n}; FixedStep(dt="
                f"{self.dt / n:.2g}) would say so at once)", StepWarning, stacklevel=4)
        self.max = max(self.max, n)
        return n

    def report(self, system):
        system.substeps_max = self.max


def _run_fixed_python(system, x0, duration, integ, every, prog):
    """The fixed-step scheme of :func:`run_fixed` in Python (generic contact)."""
    dt = integ.dt
    nsteps = int(round(duration / dt))
    n_out = nsteps // every + 2
    T, X, OP, OW = outputs(n_out, system)
    events, rej = [], 0
    x, t = x0.copy(), 0.0
    k1 = system.rhs(t, x)
    sig = system.signature(t, x)
    cur = (system.OP.copy(), system.OW.copy())
    nout = 0
    sub = _Substeps(system, dt)
    P = system.asm.P
    relax = P[GP["relax"]] > 0
    ox = system.asm.off_relax
    nr = 10 * system.asm.n_ws

    def stage(xs, F, E, x0):
        # the relaxation states: exact for the steady force F held (as run_fixed)
        if relax:
            relax_stage(xs, x0, F, E, ox)
        return xs

    def forces():
        return system.OW[..., 6:11].reshape(-1).copy()

    system.interrupted = False
    state = {"t": t, "x": x, "k1": k1, "sig": sig, "cur": cur, "nout": nout, "rej": rej,
             "events": events}
    try:
        _python_steps(system, integ, dt, nsteps, every, sub, P, relax, ox, nr, prog, stage,
                      forces, state, (T, X, OP, OW))
    except KeyboardInterrupt:
        system.interrupted = True
    t, x, cur, nout, rej = state["t"], state["x"], state["cur"], state["nout"], state["rej"]
    if not system.interrupted or (nout > 0 and T[nout - 1] < t):
        T[nout], X[nout], OP[nout], OW[nout] = t, x, cur[0], cur[1]
        nout += 1
    sub.report(system)
    return T[:nout], X[:nout], OP[:nout], OW[:nout], np.array(events).reshape(-1, 3), rej


def _python_steps(system, integ, dt, nsteps, every, sub, P, relax, ox, nr, prog, stage, forces,
                  st, out):
    """The step loop of :func:`_run_fixed_python` (its progress kept in ``st``)."""
    T, X, OP, OW = out
    t, x, k1, sig, cur = st["t"], st["x"], st["k1"], st["sig"], st["cur"]
    nout, rej, events = st["nout"], st["rej"], st["events"]
    hcap = dt
    for step in range(nsteps):
        if step % every == 0:
            T[nout], X[nout], OP[nout], OW[nout] = t, x, cur[0], cur[1]
            nout += 1
            st["nout"] = nout
        every_check = max(1, int(round(0.05 / dt)))
        if step % every_check == 0:
            hcap = dt / sub.at(t, x, min(every_check, nsteps - step) * dt)
            system.rhs(t, x)
        hmin = hcap / 2.0 ** integ.max_halvings
        t_end = (step + 1) * dt
        h = hcap
        while t < t_end - 1e-12 * dt:
            hh = min(h, t_end - t)
            Eh, Ef = np.empty(nr), np.empty(nr)
            F1 = None
            if relax:
                Vt = system.V(t)
                relax_decay(P, Vt, cur[1], 0.5 * hh, Eh)
                relax_decay(P, Vt, cur[1], hh, Ef)
                F1 = cur[1][..., 6:11].reshape(-1).copy()
            if integ.scheme == "rk4":
                k2 = system.rhs(t + 0.5 * hh, stage(x + 0.5 * hh * k1, F1, Eh, x))
                F2 = forces()
                k3 = system.rhs(t + 0.5 * hh, stage(x + 0.5 * hh * k2, F2, Eh, x))
                F3 = forces()
                k4 = system.rhs(t + hh, stage(x + hh * k3, F3, Ef, x))
                xn = x + hh / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
                if relax:
                    stage(xn, (F1 + 2 * F2 + 2 * F3 + forces()) / 6.0, Ef, x)
            else:
                k2 = system.rhs(t + hh, stage(x + hh * k1, F1, Ef, x))
                xn = x + 0.5 * hh * (k1 + k2)
                if relax:
                    stage(xn, 0.5 * (F1 + forces()), Ef, x)
            kn = system.rhs(t + hh, xn)
            new = tuple(int(v) for v in system.OW[..., 0].reshape(-1))
            if new != sig and hh > hmin * (1 + 1e-9):
                h = 0.5 * hh
                rej += 1
                continue
            t, x, k1 = t + hh, xn, kn
            cur = (system.OP.copy(), system.OW.copy())
            st.update(t=t, x=x, cur=cur, rej=rej)
            if new != sig:
                for j, (a, b) in enumerate(zip(sig, new)):
                    if a != b:
                        events.append((t, j, b))
                sig = new
                h = hmin
            else:
                h = min(2 * hh, hcap)
        if step % 50 == 0:
            _advance(prog, t)
        check_states(system, np.array([t]), x[None, :], dt)
    st.update(t=t, x=x, cur=cur, rej=rej)


def _run_adaptive(system, x0, duration, integ, out_dt, prog):
    """solve_ivp with the contact configuration as a terminal event (restart at each change)."""
    t_out = np.arange(0.0, duration + 0.5 * out_dt, out_dt)
    t_out[-1] = min(t_out[-1], duration)
    T, X, OP, OW = outputs(t_out.size, system)
    events = []
    t, x = 0.0, x0.copy()
    k = 0
    restarts = 0
    system.interrupted = False
    try:
        while t < duration - 1e-12:
            sig = system.signature(t, x)

            def changed(tt, xx, sig=sig):
                return 1.0 if system.signature(tt, xx) == sig else -1.0

            changed.terminal = True
            sol = solve_ivp(system.rhs, (t, duration), x, method=integ.method, rtol=integ.rtol,
                            atol=integ.atol, max_step=integ.max_step, dense_output=True,
                            events=changed)
            if sol.status == -1:
                raise ConvergenceError(f"solve_ivp failed at t = {sol.t[-1]!r} s: {sol.message}")
            t_end = float(sol.t[-1])
            if sol.status == 1:
                t_ev = float(sol.t_events[0][0])
                # continue just after the change (the dense output of the step that holds it)
                t_new = min(t_ev + 1e-7, t_end)
                x_new = sol.sol(t_new)
                new = system.signature(t_new, x_new)
                for j, (a, b) in enumerate(zip(sig, new)):
                    if a != b:
                        events.append((t_ev, j, b))
                restarts += 1
                if restarts > 100000:
                    raise ConvergenceError("more than 100000 contact events: chattering contact")
            else:
                t_new, x_new = t_end, sol.y[:, -1]
            while k < t_out.size and t_out[k] <= t_new + 1e-12:
                xs = sol.sol(t_out[k]) if t_out[k] > t else x
                system.rhs(t_out[k], xs)
                T[k], X[k], OP[k], OW[k] = t_out[k], xs, system.OP, system.OW
                check_states(system, T[k:k + 1], X[k:k + 1], None)
                k += 1
            t, x = t_new, np.asarray(x_new, dtype=float)
            _advance(prog, t)
    except KeyboardInterrupt:
        system.interrupted = True
    return T[:k], X[:k], OP[:k], OW[:k], np.array(events).reshape(-1, 3), restarts


def simulate(model, track, speed, duration, normal="kik-piotrowski", tangential="fastsim", *,
             mu=0.3, integrator="rk4", output_step=None, initial=None, start=0.0,
             deceleration=0.0, creep_relaxation=False, contact="auto", contact_options=None,
             progress=False, store=None, **options) -> SimulationResult:
    """Integrate a wheelset or bogie model along a track in time.

    Parameters
    ----------
    model : WheelsetModel, BogieModel or VehicleModel
    track : Track or TrackLayout
        A cross-section (tangent track) or a :class:`~wheelrail.dynamics.TrackLayout`
        with curves and an irregularity.
    speed : float or SpeedProfile
        Forward speed at t = 0 [m/s], or a speed that varies along the run:
        :class:`~wheelrail.dynamics.SpeedProfile` (piecewise linear in time or in
        the distance along the track, integrated exactly; its acceleration acts in
        the inertia terms; a profile against distance is read at the track
        position ``start`` at t = 0).
    duration : float
        Simulated time [s].
    normal, tangential : str or configured method
        Any normal method × creep-force law of the library, by name or as a
        configured object (``wr.normal.KikPiotrowski()``, ``wr.tangential.Table()``).
    mu : float
        Friction coefficient [-].
    integrator : FixedStep, Adaptive or str
        ``"rk4"`` / ``"heun"`` (fixed step 1 ms) or a :func:`~scipy.integrate.solve_ivp`
        method name (``"RK45"``, ``"Radau"``, ...), or a configured object.
    output_step : float or None
        Time between stored outputs [s] (default: the fixed step, or 1 ms).
    initial : dict or ndarray or None
        Initial state: values by state name (``{"ws0.y": 0.003}``; the rest from the
        static equilibrium) or a whole state vector.
    start : float
        Position along the track at t = 0 [m].
    deceleration : float
        Constant deceleration [m/s²] (speed ramp; negative: acceleration) of a
        float ``speed`` (with a profile: 0).
    creep_relaxation : bool or float
        First-order relaxation of the creep forces with the time constant L/V,
        L = a (``True``) or L = ``creep_relaxation`` · a (a number), a the
        patches' load-weighted semi-axis along the rolling direction. Against
        Kalker's transient rolling (:func:`wheelrail.transient_rolling`) the
        lag of length a rises too fast; the step response and the phase lag of
        the lateral force are those of L ≈ 1.45 a (docs/dynamics.md).
    contact : {"auto", "fast", "generic"}
        Compiled contact where it supports the methods, or the library's path.
    contact_options : dict or None
        Options of :class:`~wheelrail.dynamics.contact.FastContact`.
    progress : bool
        Show a progress bar (rich).
    store : str or Path or None
        Write the outputs to this Zarr store while the run goes (a buffer of about
        16 MB is held, so the memory does not grow with the duration; the compiled
        fixed-step loop streams, the other paths write at their end) and return the
        result read back lazily (:func:`wheelrail.dynamics.open_result`). Ctrl-C
        leaves everything up to the last finished chunk in the store, marked
        interrupted. Needs ``wheelrail[sweep]`` (Zarr, Dask).
    **options
        Options of the two methods, each given to the one that declares it
        (``tangential="fastsim", nx=20`` is ``tangential=wr.tangential.Fastsim(nx=20)``;
        as :func:`wheelrail.solve`).

    Returns
    -------
    SimulationResult
        With ``.dataset`` (:class:`xarray.Dataset` over time).

    Raises
    ------
    wheelrail._resources.ResourceLimitError
        The run's estimated CPU time or output memory is past the limit (the
        estimate in the message).
    ConvergenceError
        The states left the physical range (the time, the state and a step to try).
    SimulationInterrupted
        Ctrl-C (a ``KeyboardInterrupt``); its ``result`` holds what was simulated.

    Warns
    -----
    StepWarning
        The fixed step is divided into sub-steps for the creep damping at low speed
        (at the least speed of every 50 ms of the run).
    RunWarning
        A speed above 100 m/s (km/h meant?), a run ended at standstill, Y/Q
        beyond Nadal's limit (``info["derailment"]``).

    Examples
    --------
    A conical wheelset on nearly knife-edge rails, released 1 mm off centre,
    runs a kinematic (Klingel) oscillation:

    >>> import wheelrail as wr
    >>> from wheelrail.dynamics.reference import cone_track
    >>> ws, track = cone_track(0.2, 0.46, 0.75, crown_radius=0.02)
    >>> model = wr.dynamics.WheelsetModel(ws, 1813.0, (1120.0, 100.0, 1120.0), spin="fixed")
    >>> res = wr.dynamics.simulate(model, track, 5.0, 0.2, normal="hertz",
    ...                            tangential=wr.tangential.Fastsim(nx=10),
    ...                            initial={"ws0.y": 0.001})
    >>> res.dataset["y"].dims
    ('time', 'wheelset')
    """
    integ = _integrator(integrator)
    if not (isinstance(duration, (int, float)) and math.isfinite(duration) and duration > 0):
        raise InputError(f"duration must be > 0 s, got {duration!r}")
    if isinstance(speed, SpeedProfile):
        check_speed(greatest_speed(speed.table(start), 0.0, float(duration)), 0.0, duration)
    else:
        check_speed(speed, deceleration, duration)
    system = System(model, track, speed, normal, tangential, mu=mu, deceleration=deceleration,
                    creep_relaxation=creep_relaxation, contact=contact, start=start,
                    contact_options=contact_options, method_options=options)
    x0 = system.initial_state(initial)
    if output_step is not None and not (isinstance(output_step, (int, float, np.floating))
                                        and math.isfinite(output_step) and output_step > 0):
        raise InputError(f"output_step must be > 0 s, got {output_step!r}")
    if isinstance(integ, FixedStep):
        out_dt = integ.dt if output_step is None else float(output_step)
        if out_dt < integ.dt * (1 - 1e-9):
            raise InputError(f"output_step = {output_step!r} s is below the time step dt = "
                             f"{integ.dt!r} s (outputs are states at step ends; give "
                             f"FixedStep(dt={out_dt!r}) for outputs that dense)")
        every = max(1, int(round(out_dt / integ.dt)))
    else:
        out_dt = 1e-3 if output_step is None else float(output_step)
    duration = float(duration)
    t_stop = falls_below(system.SP, system.min_speed, duration,
                         held=system.profile is not None)
    if t_stop is not None:
        # decelerating past standstill: the run ends where the speed reaches its floor
        if t_stop <= 0:
            raise InputError(f"speed = {system.speed!r} m/s is at or below the least speed "
                             f"{system.min_speed:g} m/s of the creep model with a deceleration")
        why = (f"the deceleration {deceleration!r} m/s²" if system.profile is None else
               "the speed profile")
        warnings.warn(f"{why} brings the speed to {system.min_speed:g} m/s (standstill for the "
                      f"creep model) at t = {t_stop:.4g} s, before the end {duration:g} s: "
                      f"the run ends there", RunWarning, stacklevel=2)
        duration = t_stop
    streams = store is not None and isinstance(integ, FixedStep) and system.fast
    estimate(system, x0, duration, integ, out_dt, store=store, streamed=streams)
    sink = None
    if store is not None:
        sink = Stream(StoreWriter(store, system.asm.names, shapes(system)), system)
    prog = _progress(progress, float(duration))
    n0 = system.n_eval
    cpu = time.process_time()
    try:
        if streams:
            _, ev, rej = _run_fixed_compiled(system, x0, float(duration), integ, every, prog,
                                             sink)
            kind = f"fixed step {integ.scheme}, compiled loop"
        elif isinstance(integ, FixedStep) and system.fast:
            T, X, OP, OW, ev, rej = _run_fixed_compiled(system, x0, float(duration), integ,
                                                        every, prog)
            kind = f"fixed step {integ.scheme}, compiled loop"
        elif isinstance(integ, FixedStep):
            T, X, OP, OW, ev, rej = _run_fixed_python(system, x0, float(duration), integ,
                                                      every, prog)
            kind = f"fixed step {integ.scheme}"
        else:
            T, X, OP, OW, ev, rej = _run_adaptive(system, x0, float(duration), integ, out_dt,
                                                  prog)
            kind = f"solve_ivp {integ.method}"
    finally:
        if prog is not None:
            prog.stop()
    cpu = time.process_time() - cpu
    if sink is not None and not streams:
        sink.put(T, X, OP, OW)
    if sink is not None:
        sink.flush()
        t_span = sink.writer.t_last - sink.writer.t_first if sink.writer.n else 0.0
    else:
        t_span = float(T[-1] - T[0])
    events = tuple({"t": float(e[0]), "wheelset": int(e[1]) // 2,
                    "side": ("left", "right")[int(e[1]) % 2], "patches": int(e[2])} for e in ev)
    info = {"normal": system.contact.normal.name, "tangential": system.contact.tangential.name,
            "contact_path": system.contact.kind, "integrator": kind,
            "integrator_options": repr(integ), "mu": system.mu, "cpu_time": cpu,
            "contact_evaluations": system.n_eval - n0,
            "rejected_steps" if isinstance(integ, FixedStep) else "restarts": int(rej),
            "real_time_factor": t_span / cpu if cpu > 0 else math.inf,
            "creep_relaxation": float(creep_relaxation)}
    if isinstance(integ, FixedStep):
        info["substeps"] = int(getattr(system, "substeps_max", 1))
    info["interrupted"] = int(bool(system.interrupted))
    if system.profile is not None:
        info["speed_profile"] = repr(system.profile)
    info["estimated_cpu_time"] = float(getattr(system, "estimate_seconds", math.nan))
    if sink is not None:
        info["derailment"] = nadal_warn(system, sink.derailment)
        sink.writer.close(info, events, system.interrupted)
        result = open_result(store, model=model, layout=system.layout)
        if system.interrupted:
            raise SimulationInterrupted(result)
        return result
    info["derailment"] = nadal_warn(system, nadal_scan(system, T, OW))
    speed_t, accel, pos = np.empty(T.shape), np.empty(T.shape), np.empty(T.shape)
    profile_eval(system.SP, np.ascontiguousarray(T, dtype=float), speed_t, accel, pos)
    speed_t = np.maximum(speed_t, system.min_speed)
    result = SimulationResult(T, X, OW, OP, tuple(system.asm.names), speed_t, pos, events, info,
                              model, system.layout)
    if system.interrupted:
        raise SimulationInterrupted(result)
    return result
