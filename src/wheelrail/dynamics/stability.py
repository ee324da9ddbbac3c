"""Critical speeds of a wheelset or bogie model: linear (eigenvalues) and nonlinear (ramp).

* ``method="linear"`` — the model linearised about its equilibrium on tangent
  track (:func:`wheelrail.dynamics.linear.linearise`, the real profiles and
  contact methods), the lowest speed at which an eigenvalue's real part
  becomes positive;
* ``method="ramp"`` — the nonlinear critical speed by a speed ramp-down: the
  model is started above the critical speed with a lateral disturbance, runs
  into its hunting limit cycle and is slowed down at a constant rate; the
  nonlinear critical speed is the speed at which the oscillation dies out
  (its amplitude, the largest |y| of the leading wheelset over the last
  hunting period, falls below ``threshold``). For a subcritical Hopf
  bifurcation, the usual case of worn or S1002-type profiles, it lies below
  the linear critical speed (Polach 2006; True 1999).

References
----------
.. [1] O. Polach, On non-linear methods of bogie stability assessment using
   computer simulations, Proc. IMechE F 220 (2006) 13–27 (ramp-down method).
.. [2] H. True, On the theory of nonlinear dynamics and its applications in
   vehicle systems dynamics, VSD 31 (1999) 393–421.
.. [3] A.H. Wickens, *Fundamentals of rail vehicle dynamics*, 2003, ch. 4.
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass, field

import numpy as np

from ..errors import ConvergenceError, InputError
from .linear import linear_critical_speed
from .simulate import FixedStep, System, simulate

__all__ = ["critical_speed", "CriticalSpeedResult"]


@dataclass(frozen=True)
class CriticalSpeedResult:
    """A critical speed and how it was found (frozen).

    Attributes
    ----------
    speed : float
        Critical speed [m/s].
    method : str
        ``"linear"`` or ``"ramp"``.
    frequency : float
        Frequency of the critical mode [Hz] (linear) or of the limit cycle just
        before it dies out (ramp).
    info : dict
        ``scan`` (linear: speeds and largest real parts), or the ramp's time
        series (``time``, ``speed``, ``y``, ``amplitude``), ``cpu_time`` [s] and the
        simulated time ``simulated`` [s].
    """

    speed: float
    method: str
    frequency: float = math.nan
    info: dict = field(default_factory=dict)


def _amplitude(t, y, window):
    """Largest |y| over the trailing ``window`` [s] at every sample."""
    out = np.empty_like(y)
    dq = deque()
    for i in range(y.size):
        while dq and abs(y[dq[-1]]) <= abs(y[i]):
            dq.pop()
        dq.append(i)
        while t[dq[0]] < t[i] - window:
            dq.popleft()
        out[i] = abs(y[dq[0]])
    return out


def critical_speed(model, track, normal="hertz", tangential="fastsim", *, method="linear",
                   mu=0.3, bracket=(5.0, 200.0), start_speed=None, deceleration=2.0,
                   disturbance=0.005, threshold=2e-4, settle=2.0, window=None, dt=1e-3,
                   contact="auto", progress=False, **options) -> CriticalSpeedResult:
    """Critical speed of a model on tangent track (see the module docstring).

    Parameters
    ----------
    model : WheelsetModel, BogieModel or VehicleModel
    track : Track or TrackLayout
        Its cross-section is used (tangent track, no irregularity).
    normal, tangential : str or configured method
    method : {"linear", "ramp"}
    mu : float
        Friction coefficient.
    bracket : (float, float)
        Speeds scanned by the linear method [m/s].
    start_speed : float or None
        Ramp: initial speed [m/s] (default 1.2 × the linear critical speed).
    deceleration : float
        Ramp: dV/dt [m/s²].
    disturbance : float
        Ramp: initial lateral displacement of every wheelset [m].
    threshold : float
        Ramp: amplitude [m] below which the oscillation counts as died out.
    settle : float
        Ramp: time at the start speed before the ramp begins [s].
    window : float or None
        Ramp: window of the amplitude [s] (default two kinematic periods at the
        start speed, from the linear analysis).
    dt : float
        Ramp: fixed step [s].
    contact : {"auto", "fast", "generic"}
        Compiled contact where it supports the methods, or the library's path.
    progress : bool
        Ramp: show a progress bar while settling.
    **options
        Options of the two methods, each to the one that declares it (as
        :func:`~wheelrail.dynamics.simulate`).

    Returns
    -------
    CriticalSpeedResult
    """
    lay_track = getattr(track, "track", track)

    def make(V):
        return System(model, lay_track, V, normal, tangential, mu=mu, contact=contact,
                      method_options=options)

    if method == "linear":
        r = linear_critical_speed(make, bracket)
        return CriticalSpeedResult(r["speed"], "linear", r["frequency"],
                                   {"scan": r["scan"], "wavelength": r["wavelength"]})
    if method != "ramp":
        raise InputError(f"method must be 'linear' or 'ramp', got {method!r}")
    if not deceleration > 0:
        raise InputError(f"deceleration must be > 0 m/s², got {deceleration!r}")
    lin = None
    if start_speed is None or window is None:
        lin = linear_critical_speed(make, bracket)
    V0 = 1.2 * lin["speed"] if start_speed is None else float(start_speed)
    if window is None:
        window = 2.0 * lin["wavelength"] / V0
    V_end = max(bracket[0], 1.0)
    # settle at V0, then ramp down to V_end
    init = {f"ws{i}.y": disturbance for i in range(model.n_wheelsets)}
    settle_res = simulate(model, lay_track, V0, settle, normal, tangential, mu=mu,
                          integrator=FixedStep(dt=dt), initial=init, contact=contact,
                          output_step=dt, progress=progress, **options)
    # the ramp in pieces of 1 s (continued from the last state), stopped once the
    # oscillation has stayed below the threshold for a window
    pieces = []
    x, V, t0 = settle_res.states[-1], V0, 0.0
    while V > V_end + 1e-9:
        span = min(1.0, (V - V_end) / deceleration)
        piece = simulate(model, lay_track, V, span, normal, tangential, mu=mu,
                         integrator=FixedStep(dt=dt), initial=x, deceleration=deceleration,
                         contact=contact, output_step=dt, progress=False, **options)
        pieces.append((piece.t + t0, piece))
        x, V, t0 = piece.states[-1], float(piece.speed[-1]), t0 + float(piece.t[-1])
        tt = np.concatenate([p[0] for p in pieces])
        yy = np.concatenate([p[1].state("ws0.y") for p in pieces])
        recent = tt > tt[-1] - 1.5 * window
        if tt[-1] > 2 * window and np.max(np.abs(yy[recent])) < 0.5 * threshold:
            break
    t = np.concatenate([p[0] for p in pieces])
    y = np.concatenate([p[1].state("ws0.y") for p in pieces])
    speeds = np.concatenate([p[1].speed for p in pieces])
    cpu = sum(p[1].info["cpu_time"] for p in pieces) + settle_res.info["cpu_time"]
    amp = _amplitude(t, y, window)
    alive = amp[0] >= threshold
    if not alive:
        raise ConvergenceError(f"no limit cycle at the start speed {V0!r} m/s (amplitude "
                               f"{amp[0]!r} m after {settle!r} s): start higher, disturb more "
                               "or settle longer")
    below = np.flatnonzero(amp < threshold)
    if below.size == 0:
        raise ConvergenceError(f"the oscillation did not die out down to {V_end!r} m/s")
    k = int(below[0])
    # the amplitude lags the speed by the window: take the speed at its centre
    tc = max(t[k] - 0.5 * window, 0.0)
    Vc = float(np.interp(tc, t, speeds))
    seg = (t > tc - 2 * window) & (t < tc)
    zc = np.flatnonzero(np.diff(np.sign(y[seg])) != 0)
    f = 0.5 * (zc.size - 1) / (t[seg][zc[-1]] - t[seg][zc[0]]) if zc.size > 2 else math.nan
    return CriticalSpeedResult(Vc, "ramp", f, {
        "time": t, "speed": speeds, "y": y, "amplitude": amp, "start_speed": V0,
        "window": window, "threshold": threshold, "linear": lin, "cpu_time": cpu,
        "simulated": float(t[-1]) + settle})
