"""Guards of :func:`wheelrail.dynamics.simulate`: estimate and limits before a run,
divergence during it, plausibility of its speed, and derailment (Nadal) after it.

* before: the CPU time (the measured cost of one contact evaluation × the
  evaluations of the scheme) and the memory of the outputs, refused past the
  limits of :mod:`wheelrail._resources` with the estimate; speeds beyond any
  railway's refused, above service speeds warned about (km/h for m/s?);
* during: a state that leaves the physically possible range (non-finite, a
  lateral shift beyond 0.2 m, ...) stops the run naming the time, the state,
  the step and a smaller one to try;
* after: Y/Q beyond Nadal's limit (tan γ − μ)/(1 + μ tan γ) for the wheel's
  flange angle γ — the wheel climbs the rail — flagged.

References
----------
.. [1] M.J. Nadal, Théorie de la stabilité des locomotives, partie 2: mouvement
   de lacet, Annales des Mines 10 (1896) 232.
"""

from __future__ import annotations

import math
import time
import warnings

import numpy as np

from .. import _resources
from ..errors import ConvergenceError, InputError
from ._fastcontact import KMAX, PATCH_FIELDS, WHEEL_FIELDS
from . import store as _store
from ._motion import rhs_fast

__all__ = ["RunWarning", "SimulationInterrupted", "MIN_RADIUS", "MAX_SPEED", "HIGH_SPEED",
           "ABSURD", "check_speed", "check_states", "estimate", "flange_angle", "nadal_limit",
           "nadal_check", "nadal_scan", "nadal_merge", "nadal_warn"]

_W = {n: i for i, n in enumerate(WHEEL_FIELDS)}


class RunWarning(UserWarning):
    """A run whose input or result is implausible: a speed above any service speed (km/h
    given for m/s?), Y/Q beyond Nadal's limit (derailment), a run cut at standstill."""


class SimulationInterrupted(KeyboardInterrupt):
    """Ctrl-C during :func:`simulate`: ``result`` holds what was simulated until then
    (``result.info["interrupted"]`` is True)."""

    def __init__(self, result):
        super().__init__(f"interrupted at t = {float(result.t[-1]):.6g} s")
        self.result = result


#: Curves tighter than this radius [m] are refused (the tightest railway curves, in
#: depots and tramway-like sidings, are about 60–80 m).
MIN_RADIUS = 50.0
#: Speeds above this [m/s] are refused (the rail speed record is 157 m/s).
MAX_SPEED = 200.0
#: Speeds above this [m/s] are warned about (360 km/h; was km/h meant?).
HIGH_SPEED = 100.0
#: States beyond these magnitudes mean a diverged integration (m, rad, m/s, rad/s).
ABSURD = {"y": 0.2, "z": 0.2, "roll": 0.2, "yaw": 0.2, "pitch": 0.2, "vy": 50.0, "vz": 50.0,
          "roll_rate": 100.0, "yaw_rate": 100.0, "pitch_rate": 100.0}

def check_states(system, T, X, dt):
    """Stop a run whose states left the physical range (diverged): the first such output
    named with its time, the step and a smaller one to try."""
    bad = ~np.all(np.isfinite(X), axis=1)
    names = system.asm.names
    worst = None
    for j, name in enumerate(names):
        leaf = name.rsplit(".", 1)[-1]
        lim = ABSURD.get(leaf) if not name.startswith(("rail", "relax")) else None
        if lim is not None:
            over = np.abs(X[:, j]) > lim
            if np.any(over):
                k = int(np.argmax(over))
                if worst is None or k < worst[0]:
                    worst = (k, name, float(X[k, j]), lim)
            bad |= np.abs(X[:, j]) > lim
    if not np.any(bad):
        return
    k = int(np.argmax(bad))
    if worst is not None and worst[0] == k:
        what = f"{worst[1]} = {worst[2]:.3g} (beyond {worst[3]:g})"
    else:
        what = "a state is not finite"
    step = (f"with the fixed step {dt!r} s: the step is too long for the stiffest mode; try "
            f"FixedStep(dt={min(dt / 4, 1e-3):.2g}) or an implicit Adaptive('Radau')") if dt else \
        "(the integration diverged)"
    raise ConvergenceError(f"the simulation diverged at t = {float(T[k]):.6g} s: {what} {step}")


def check_speed(speed, deceleration, duration):
    """Refuse a speed beyond any railway's, warn above service speeds (km/h for m/s?)."""
    try:
        top = max(float(speed), float(speed) - float(deceleration) * float(duration))
    except (TypeError, ValueError):
        return                                   # System names the bad value
    if not math.isfinite(top):
        return
    if top > MAX_SPEED:
        raise InputError(f"speed = {top!r} m/s ({top * 3.6:.0f} km/h) is beyond any railway "
                         f"speed (record 157 m/s); a speed in km/h? {top!r} km/h = "
                         f"{top / 3.6:.4g} m/s")
    if top > HIGH_SPEED:
        warnings.warn(f"speed = {top!r} m/s is {top * 3.6:.0f} km/h, above any service speed; "
                      f"if km/h was meant: {top / 3.6:.4g} m/s", RunWarning, stacklevel=3)


def output_bytes(system):
    nw = system.asm.n_ws
    return 8.0 * (1 + system.asm.n + nw * 2 * (KMAX * len(PATCH_FIELDS) + len(WHEEL_FIELDS)))


def _eval_cost(system, x0, compiled, n=20):
    """CPU time of one evaluation of the right-hand side [s] (median of ``n``)."""
    times = []
    if compiled:
        c = system.contact
        dx = np.empty_like(x0)
        for _ in range(n):
            t0 = time.process_time()
            rhs_fast(0.0, x0, system.asm.P, system.layout.arrays, system.SP, system.min_speed,
                     c.geometry["left"], c.geometry["right"], c.method, system.mu, system.OP,
                     system.OW, dx)
            times.append(time.process_time() - t0)
    else:
        for _ in range(max(3, n // 4)):
            t0 = time.process_time()
            system.rhs(0.0, x0)
            times.append(time.process_time() - t0)
    return float(np.median(times))


def estimate(system, x0, duration, integ, out_dt, store=None, streamed=False):
    """CPU time and output memory of the run, refused past the limits (see
    :func:`wheelrail._resources.check`; long runs are announced). A run written to a
    ``store`` needs the outputs' size on that disk; ``streamed``: only one chunk and the
    time axis in memory."""
    n_out = duration / out_dt + 2
    if streamed:
        memory = 8.0 * n_out + 2 * _store.BUFFER_BYTES + 200e6
    else:
        memory = n_out * output_bytes(system) + 200e6
    # cost of one evaluation of the right-hand side, measured (CPU time; the compiled
    # kernel directly where the run's loop is compiled)
    per_eval = _eval_cost(system, x0, compiled=hasattr(integ, "dt") and system.fast)
    if hasattr(integ, "dt"):
        n_sub = system.mean_substeps(x0, integ.dt, duration)
        steps = duration / integ.dt * n_sub
        evals = steps * (4 if integ.scheme == "rk4" else 2)
        what = (f"dynamics run of {duration:.6g} s ({steps:.3g} {integ.scheme} steps of "
                f"{integ.dt / n_sub:.3g} s, {n_out:.3g} outputs)")
    else:
        evals = duration / integ.max_step * (6 if integ.method in ("RK45", "DOP853", "RK23")
                                             else 4 + system.asm.n)
        what = (f"dynamics run of {duration:.6g} s (solve_ivp {integ.method}, at least "
                f"{duration / integ.max_step:.3g} steps, {n_out:.3g} outputs)")
    # × 1.2: the step halvings at contact changes and the loop's own work (measured
    # estimate / CPU time 0.75–0.92 without it, benchmarks/bench_dynamics_estimate.py)
    seconds = 1.2 * evals * per_eval
    system.estimate_seconds = seconds
    system.estimate = _resources.check(what, seconds, memory,
                                       f"{per_eval * 1e3:.3g} ms per contact evaluation, "
                                       f"measured; {output_bytes(system) / 1e3:.3g} kB per "
                                       f"output")
    if store is not None:
        import shutil
        from pathlib import Path

        disk = n_out * output_bytes(system)
        where = Path(store).resolve().parent
        while not where.exists():
            where = where.parent
        free = shutil.disk_usage(where).free
        if disk > 0.9 * free:
            raise _resources.ResourceLimitError(
                f"store = {str(store)!r}: the outputs need about {_resources._human(disk)} "
                f"(uncompressed, {n_out:.3g} outputs of {output_bytes(system) / 1e3:.3g} kB), "
                f"more than the {_resources._human(free)} free on that disk; a larger "
                f"output_step or another disk")


def flange_angle(wheelset):
    """The flange angle [rad]: the steepest slope of the wheel profile's working face, between
    the flange tip (its lowest point) and the field side (the smaller of the two wheels')."""
    worst = math.pi / 2
    for prof in {id(p): p for p in (wheelset.wheel, getattr(wheelset, "wheel_right", None))
                 if p is not None}.values():
        y, z = np.asarray(prof.y), np.asarray(prof.z)
        i = int(np.argmin(z))
        slope = np.abs(np.diff(z[i:]) / np.diff(y[i:]))
        worst = min(worst, math.atan(float(np.max(slope))) if slope.size else 0.0)
    return worst


def nadal_limit(flange_angle, mu):
    """Nadal's limit (tan γ − μ)/(1 + μ tan γ) of Y/Q (Nadal 1896)."""
    t = math.tan(flange_angle)
    return (t - mu) / (1.0 + mu * t)


def nadal_scan(system, T, OW):
    """Y/Q beyond Nadal's limit in outputs ``T``, ``OW``: None, or a dict naming the first
    wheel and time (``t``, ``wheelset``, ``side``, ``max_Y_over_Q``, ``nadal_limit``)."""
    gamma = flange_angle(system.model.wheelset)
    if T.size == 0 or gamma < math.radians(45.0):
        return None                               # no flange: no climbing limit
    limit = nadal_limit(gamma, system.mu)
    sig = np.array([-1.0, 1.0])[None, None, :]
    Q = OW[..., _W["Fz"]]
    with np.errstate(divide="ignore", invalid="ignore"):
        yq = np.where(Q > 0, -sig * OW[..., _W["Fy"]] / np.where(Q > 0, Q, 1.0), 0.0)
    over = yq > limit
    if not np.any(over):
        return None
    k, i, side = (int(v[0]) for v in np.nonzero(over))
    return {"t": float(T[k]), "wheelset": i, "side": ("left", "right")[side],
            "max_Y_over_Q": float(np.max(yq)), "nadal_limit": limit}


def nadal_merge(first, later):
    """Two scans of consecutive parts of a run as one (the first time, the largest Y/Q)."""
    if first is None or later is None:
        return first if later is None else later
    return dict(first, max_Y_over_Q=max(first["max_Y_over_Q"], later["max_Y_over_Q"]))


def nadal_warn(system, hit):
    """Warn (:class:`RunWarning`) about a :func:`nadal_scan` hit; returns ``hit``."""
    if hit is None:
        return None
    gamma = flange_angle(system.model.wheelset)
    V = system.V(hit["t"])
    hint = (f"; speed {V:.4g} m/s = {V * 3.6:.0f} km/h — if km/h was meant: {V / 3.6:.4g} m/s"
            if V > 55.0 else "")
    warnings.warn(f"Y/Q reaches {hit['max_Y_over_Q']:.3g} (wheelset {hit['wheelset']}, "
                  f"{hit['side']} wheel, first at t = {hit['t']:.4g} s), beyond Nadal's limit "
                  f"{hit['nadal_limit']:.3g} (flange angle {math.degrees(gamma):.1f}°, μ = "
                  f"{system.mu:g}): the wheel climbs the rail — a derailment; the motion after "
                  f"it is not physical{hint}", RunWarning, stacklevel=3)
    return hit


def nadal_check(system, T, OW):
    """Y/Q beyond Nadal's limit (the wheel climbs the rail): None, or a dict naming the first
    wheel and time, with a :class:`RunWarning`."""
    return nadal_warn(system, nadal_scan(system, T, OW))
