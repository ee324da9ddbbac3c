"""Quasi-static analyses: steady curving and flange climb (Pascal's wheelset model).

* :func:`steady_curving` — the equilibrium of a wheelset or bogie model in a
  circular curve at constant speed: all accelerations zero (lateral, vertical,
  roll, yaw, spin of every body, rail deflections), solved by a damped Newton
  iteration on the full nonlinear model (the contact of every wheel by the
  configured methods), with natural continuation in curvature and cant from
  the tangent track where Newton fails. A free wheelset (no suspension) on the tread settles
  where it rolls without longitudinal creep, Δr(y) = 2 r0 l0/R (for constant
  conicity λ: y = r0 l0/(λR); Wickens 2003, §2.4).
* :func:`flange_climb` — Pascal's quasi-static wheelset (Piotrowski & Chollet
  2005, §2.2, fig. 4): at a fixed yaw angle (angle of attack) the wheelset is
  pushed laterally by a force H at rail level while its vertical load stays
  constant; the normal loads of the patches follow from the equilibrium with the
  creep forces (which unload the contact during flanging). The lateral shift is
  the control variable (so that the maximum of H is passed); the result is the
  derailment quotient Y/Q of each wheel along the path up to and beyond wheel
  lift, compared with Nadal's limit (tan γ − μ)/(1 + μ tan γ) for the flange
  angle reached (Nadal 1908; EN 14363).

References
----------
.. [1] J. Piotrowski, H. Chollet, Wheel–rail contact models for vehicle system
   dynamics including multi-point contact, VSD 43 (2005) 455–483, §2.2.
.. [2] M.J. Nadal, Théorie de la stabilité des locomotives, partie 2: mouvement
   de lacet, Annales des Mines 10 (1896) 232; (Y/Q)_lim = (tan γ − μ)/(1 + μ tan γ).
.. [3] A.H. Wickens, *Fundamentals of rail vehicle dynamics*, 2003, §2.4
   (steady curving of a wheelset).
.. [4] D. Boocock, Steady-state motion of railway vehicles on curved track,
   J. Mech. Eng. Sci. 11 (1969) 556–566.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import ConvergenceError, InputError
from ..geometry.contact_table import contact_table
from ._fastcontact import PATCH_FIELDS, WHEEL_FIELDS
from .layout import Curve, TrackLayout
from .model import GRAVITY, Suspension, WheelsetModel
from .simulate import System

__all__ = ["steady_curving", "flange_climb", "nadal", "cant_deficiency", "CurvingResult", "FlangeClimbResult"]

_P = {n: i for i, n in enumerate(PATCH_FIELDS)}
#: Contact angle [rad] from which a patch counts as on the flange flank (tread below).
_FLANK = 0.8
_W = {n: i for i, n in enumerate(WHEEL_FIELDS)}


def nadal(contact_angle, mu):
    """Nadal's limit (tan γ − μ)/(1 + μ tan γ) of the derailment quotient Y/Q.

    Parameters
    ----------
    contact_angle : float or array_like
        Flange contact angle γ [rad].
    mu : float or array_like
        Coefficient of friction [-].

    Returns
    -------
    float or ndarray
        Limit of Y/Q [-] at which the flanging wheel starts to climb.

    References
    ----------
    .. [1] M.J. Nadal, Théorie de la stabilité des locomotives, partie 2:
       mouvement de lacet, Annales des Mines 10 (1896) 232.

    Examples
    --------
    >>> round(float(nadal(math.radians(70.0), 0.3)), 4)
    1.3416
    """
    t = np.tan(contact_angle)
    return (t - mu) / (1.0 + mu * t)


def _newton(fun, x0, scales, steps, maxiter=80, tol=1e-7):
    """Damped Newton on fun(x) = 0 (finite-difference Jacobian, step limited to ``scales``
    as a whole, halved while the residual in Newton-step units grows)."""
    x = np.array(x0, dtype=float)
    f = fun(x)
    for _ in range(maxiter):
        J = np.empty((f.size, x.size))
        for k in range(x.size):
            xp = x.copy()
            xp[k] += steps[k]
            J[:, k] = (fun(xp) - f) / steps[k]
        try:
            d = np.linalg.solve(J, -f)
        except np.linalg.LinAlgError:
            raise ConvergenceError("quasi-static equilibrium: singular Jacobian") from None
        big = float(np.max(np.abs(d) / scales))
        if big > 1.0:
            d = d / big
        merit = float(np.max(np.abs(np.linalg.solve(J, f)) / scales))
        for _ in range(10):
            xn = x + d
            fn = fun(xn)
            if float(np.max(np.abs(np.linalg.solve(J, fn)) / scales)) <= merit:
                break
            d = 0.5 * d
        x, f = xn, fn
        if np.all(np.abs(d) < tol * scales):
            return x
    raise ConvergenceError(f"quasi-static equilibrium not reached in {maxiter} Newton steps")


@dataclass(frozen=True, eq=False)
class CurvingResult:
    """Steady curving equilibrium (frozen).

    Attributes
    ----------
    state : ndarray
        Equilibrium state (names in ``names``).
    names : tuple of str
    y, yaw : ndarray, shape (n_wheelsets,)
        Lateral shift [m] (positive towards the outside of a curve to the right is
        negative: y is to the right) and yaw relative to the track tangent [rad];
        the angle of attack of a wheelset is its yaw (positive nose to the right).
    wheels, patches : ndarray
        Contact outputs (n_wheelsets, 2, ...) as in
        :class:`~wheelrail.dynamics.simulate.SimulationResult`.
    radius, speed, cant : float

    The per-wheel ``vertical_load`` (Q), ``lateral_force`` (Y), ``Y_over_Q`` and
    ``wear_number`` (Tγ) and :meth:`flange_contact` follow the conventions of
    :func:`~wheelrail.dynamics.results.to_dataset`.
    """

    state: np.ndarray
    names: tuple
    y: np.ndarray
    yaw: np.ndarray
    wheels: np.ndarray
    patches: np.ndarray
    radius: float
    speed: float
    cant: float
    info: dict = field(default_factory=dict)

    def contact_angles(self, wheelset=0, side="right") -> np.ndarray:
        """Contact angles [rad] of the loaded patches of one wheel."""
        k = 0 if side == "left" else 1
        rows = self.patches[wheelset, k]
        return rows[rows[:, _P["Fn"]] > 0, _P["contact_angle"]]

    @property
    def vertical_load(self) -> np.ndarray:
        """Q, the vertical force on each wheel [N], shape (n_wheelsets, 2) (left, right)."""
        return self.wheels[..., _W["Fz"]].copy()

    @property
    def lateral_force(self) -> np.ndarray:
        """Y, the lateral force of each wheel on its rail [N], positive towards the field
        side (EN 14363), shape (n_wheelsets, 2)."""
        return -np.array([-1.0, 1.0]) * self.wheels[..., _W["Fy"]]

    @property
    def Y_over_Q(self) -> np.ndarray:
        """Derailment quotient Y/Q of each wheel, shape (n_wheelsets, 2)."""
        Q = self.vertical_load
        return np.where(Q > 0, self.lateral_force / np.where(Q > 0, Q, 1.0), np.nan)

    @property
    def patch_wear_number(self) -> np.ndarray:
        """Tγ = −(Fx ξ + Fy η + Mz φ) of each patch [N] (Pearce & Sherratt 1991), shape
        (n_wheelsets, 2, KMAX)."""
        P = self.patches
        return -(P[..., _P["Fx"]] * P[..., _P["xi"]] + P[..., _P["Fs"]] * P[..., _P["eta"]]
                 + P[..., _P["Mz"]] * P[..., _P["phi"]])

    @property
    def wear_number(self) -> np.ndarray:
        """Tγ summed over each wheel's patches [N], shape (n_wheelsets, 2)."""
        return self.patch_wear_number.sum(axis=-1)

    def flange_contact(self, wheelset=0) -> dict | None:
        """The flange patch of a wheelset: the loaded patch with the largest contact
        angle at or above 0.8 rad (46°) on either wheel, or None.

        Returns
        -------
        dict or None
            ``side``; the patch's ``contact_angle`` [rad], ``Fn`` [N] and
            ``wear_number`` (Tγ) [N]; the wheel's ``Y_over_Q``, ``Y`` and ``Q`` [N],
            its ``wear_number`` [N] and ``n_patches``.
        """
        best = None
        for k, side in enumerate(("left", "right")):
            rows = self.patches[wheelset, k]
            for j in range(rows.shape[0]):
                g = rows[j, _P["contact_angle"]]
                if rows[j, _P["Fn"]] > 0 and g >= _FLANK and (best is None or g > best[2]):
                    best = (k, j, g)
        if best is None:
            return None
        k, j, g = best
        return {"side": ("left", "right")[k], "contact_angle": float(g),
                "Fn": float(self.patches[wheelset, k, j, _P["Fn"]]),
                "wear_number": float(self.patch_wear_number[wheelset, k, j]),
                "Y_over_Q": float(self.Y_over_Q[wheelset, k]),
                "Y": float(self.lateral_force[wheelset, k]),
                "Q": float(self.vertical_load[wheelset, k]),
                "wheel_wear_number": float(self.wear_number[wheelset, k]),
                "n_patches": int(self.wheels[wheelset, k, _W["patches"]])}


def steady_curving(model, track, radius, speed, normal="hertz", tangential="fastsim", *,
                   mu=0.3, cant=0.0, direction="right", initial=None, contact="auto",
                   contact_options=None, **options) -> CurvingResult:
    """Equilibrium of a model in a circular curve at constant speed (module docstring).

    Parameters
    ----------
    model : WheelsetModel, BogieModel or VehicleModel
    track : Track or TrackLayout
        The cross-section.
    radius : float
        Curve radius [m].
    speed : float
        [m/s].
    cant : float
        Superelevation [m].
    direction : {"right", "left"}
    initial : dict or None
        Start values by state name (e.g. ``{"ws0.y": -0.005}``); default: the
        wheelsets shifted towards the outer rail by 2 r0 l0/(0.2 R).
    contact, contact_options
        As :func:`~wheelrail.dynamics.simulate`, except that the compiled contact's
        ``connected`` defaults to ``"shared"`` and its ``search_step`` to 0.1 mm
        (:class:`~wheelrail.dynamics.FastContact`): with ``"separate"``, or with the
        0.5 mm grid that misses the flange's shallow gap minimum on the steep flank,
        a patch at the two-point transition between flange root and flange
        vanishes while carrying load, and in bands of cant deficiency the
        equilibrium equations then have no root (Manchester vehicle 1, R = 300 m,
        100 mm cant: at 9, 11–15 and 20 m/s).
    **options
        Options of the two methods, each to the one that declares it.

    Returns
    -------
    CurvingResult
        ``info["continuation"]``: the shares of curvature and cant solved on the
        way (``(1.0,)`` when Newton converged directly).

    Raises
    ------
    ConvergenceError
        Naming the radius, speed, cant and cant deficiency, when neither Newton at
        the given values nor the continuation reaches an equilibrium.

    Notes
    -----
    The unknowns are the positions of all bodies (lateral, vertical, roll and
    yaw of wheelsets and frame, the frame's pitch, the free wheelsets' spin); the
    equations are their accelerations. A damped Newton iteration (finite-difference
    Jacobian, step limited and halved while the residual in Newton units grows)
    starts from the static state shifted towards the outer rail. If it fails,
    natural continuation from the tangent track: the curvature s/R and the cant
    s·cant are raised with s from 0.125 to 1 (so the cant deficiency grows as s),
    each step from the secant predictor, the step doubled after a success and
    halved after a failure down to 1/512.
    """
    section = getattr(track, "track", track)

    def layout(share):
        return TrackLayout(section, curves=(Curve(radius / share, start=-1e7, length=math.inf,
                                                  cant=cant * share, direction=direction),))

    if contact != "generic":
        contact_options = {"connected": "shared", "search_step": 1e-4, **(contact_options or {})}
    system = System(model, layout(1.0), speed, normal, tangential, mu=mu, contact=contact,
                    contact_options=contact_options, method_options=options)
    asm = system.asm
    sgn = 1.0 if direction == "right" else -1.0
    r0, l0 = model.wheelset.nominal_radius, model.wheelset.e_tape
    given = {}
    for i in range(asm.n_ws):
        given[f"ws{i}.y"] = -sgn * min(r0 * l0 / (0.2 * radius), 0.006)
    if initial:
        given.update(initial)
    try:
        x = system.initial_state(given)
    except ConvergenceError:
        # the static state on the tangent track as the start (the cant's lateral
        # gravity component can push the static wheelset over the flange)
        system.layout = layout(1e-9)
        try:
            x = system.initial_state(given)
        except ConvergenceError as err:
            raise ConvergenceError(
                f"steady_curving: no static start state for radius = {radius!r} m, "
                f"speed = {speed!r} m/s, cant = {cant!r} m: {err}") from None
        system.layout = layout(1.0)
    cols, rows, steps, scales = _curving_unknowns(asm)
    if asm.relax:
        raise InputError("steady_curving: creep relaxation does not change the steady state; "
                         "use a model without it")

    def residual(v):
        xx = x.copy()
        xx[cols] = v
        return system.rhs(0.0, xx)[rows]

    try:
        v = _newton(residual, x[cols], scales, steps, maxiter=60)
        path = (1.0,)
    except ConvergenceError:
        v, path = _continuation(system, layout, residual, x, cols, scales, steps, radius,
                                speed, cant, l0)
    x[cols] = v
    system.layout = layout(1.0)
    system.rhs(0.0, x)
    return CurvingResult(x, tuple(asm.names), x[[9 * i for i in range(asm.n_ws)]],
                         x[[9 * i + 3 for i in range(asm.n_ws)]], system.OW.copy(),
                         system.OP.copy(), float(radius), float(speed), float(cant),
                         {"normal": system.contact.normal.name,
                          "tangential": system.contact.tangential.name, "mu": mu,
                          "direction": direction, "continuation": path})


def _curving_unknowns(asm):
    """Unknowns of the steady curving equilibrium (state indices, finite-difference steps,
    largest Newton steps) and the equations (rows of the state derivative)."""
    if hasattr(asm, "curving_unknowns"):        # VehicleAssembly
        return asm.curving_unknowns()
    cols, rows, steps, scales = asm.quasi_static(spin=True)
    cols, rows = list(cols), list(rows)
    steps, scales = list(steps), list(scales)
    for i in range(asm.n_ws):
        for c, r, h, s in ((9 * i, 9 * i + 4, 1e-7, 2e-3), (9 * i + 3, 9 * i + 7, 1e-7, 5e-3)):
            cols.append(c)
            rows.append(r)
            steps.append(h)
            scales.append(s)
    if asm.frame:
        of = asm.off_frame
        for c, r in ((of, of + 5), (of + 4, of + 9)):
            cols.append(c)
            rows.append(r)
            steps.append(1e-7)
            scales.append(2e-3)
    return cols, rows, np.array(steps), np.array(scales)


def cant_deficiency(radius, speed, cant, contact_distance=1.5):
    """Cant deficiency V² G/(g R) − cant [m] (G: distance of the rails' contact points).

    Parameters
    ----------
    radius, speed, cant : float
        Curve radius [m], speed [m/s], cant [m].
    contact_distance : float
        Lateral distance G of the two rails' contact points [m] (1.5 m for standard gauge).

    Returns
    -------
    float
        The cant that would balance the unbalanced lateral acceleration, less the
        cant present [m] (EN 13803).

    Examples
    --------
    >>> round(cant_deficiency(300.0, 15.0, 0.1), 4)
    0.0147
    """
    return speed * speed * contact_distance / (GRAVITY * radius) - cant


def _continuation(system, layout, residual, x, cols, scales, steps, radius, speed, cant, l0,
                  first=0.125, smallest=1.0 / 512.0, maxiter=40):
    """Equilibrium by natural continuation in the share s of the curvature and the cant
    (curvature s/R, cant s·cant, so the cant deficiency grows as s from the tangent
    track): Newton at each share from the secant predictor of the last two, the share's
    step doubled after a success and halved after a failure."""
    base = x.copy()
    done_s, done_v = [0.0], [base[cols].copy()]
    s_now, ds = 0.0, first
    while s_now < 1.0:
        s_try = min(s_now + ds, 1.0)
        if len(done_s) > 1:
            w = (s_try - done_s[-1]) / (done_s[-1] - done_s[-2])
            guess = done_v[-1] + w * (done_v[-1] - done_v[-2])
        else:
            guess = done_v[-1]
        system.layout = layout(s_try)
        try:
            v = _newton(residual, guess, scales, steps, maxiter=maxiter)
        except ConvergenceError:
            ds *= 0.5
            if ds < smallest:
                system.layout = layout(1.0)
                deficiency = cant_deficiency(radius, speed, cant, 2.0 * l0)
                raise ConvergenceError(
                    f"steady_curving: no equilibrium found for radius = {radius!r} m, "
                    f"speed = {speed!r} m/s, cant = {cant!r} m (cant deficiency "
                    f"{deficiency * 1e3:.0f} mm): Newton failed at these values, and the "
                    f"continuation from the tangent track stalled at {s_now:.3f} of the "
                    f"curvature and cant (radius {radius / max(s_now, 1e-300):.4g} m); the "
                    "vehicle may climb the rail or the contact jump between flange root "
                    "and flange may have no equilibrium") from None
            continue
        done_s.append(s_try)
        done_v.append(v)
        s_now = s_try
        ds = min(2.0 * ds, 0.5)
    return done_v[-1], tuple(done_s[1:])


@dataclass(frozen=True, eq=False)
class FlangeClimbResult:
    """Pascal's quasi-static flange climb (frozen; arrays along the lateral shift).

    Attributes
    ----------
    y : ndarray
        Lateral shift of the wheelset [m] (towards the flanging right wheel).
    lateral_force : ndarray
        External lateral force H at rail level [N] needed for equilibrium.
    Y_over_Q : ndarray
        Derailment quotient of the flanging (right) wheel.
    vertical_load : ndarray
        Q of the flanging wheel [N].
    contact_angle : ndarray
        Largest contact angle of the flanging wheel's loaded patches [rad].
    tread_load : ndarray
        Normal force of the flanging wheel's patches with contact angle < 0.8 rad [N]
        (zero: the wheel has lifted off its tread and flange root).
    friction_ratio : ndarray
        Fy/Fn in the contact plane of the flange patch (μ when it slides laterally).
    lift : int
        Index of the first point without tread contact (−1: none).
    peak : int
        Index of the largest Y/Q.
    nadal : float
        Nadal's limit for the largest contact angle reached and μ.
    """

    y: np.ndarray
    lateral_force: np.ndarray
    Y_over_Q: np.ndarray
    vertical_load: np.ndarray
    contact_angle: np.ndarray
    tread_load: np.ndarray
    friction_ratio: np.ndarray
    lift: int
    peak: int
    nadal: float
    mu: float
    yaw: float
    info: dict = field(default_factory=dict)

    @property
    def flange_angle(self) -> float:
        """Largest contact angle reached on the flange [rad]."""
        return float(np.nanmax(self.contact_angle))

    @property
    def Y_over_Q_at_lift(self) -> float:
        """The largest Y/Q of the path (reached on the flange after the lift)."""
        return float(self.Y_over_Q[self.peak])


def _flange_start(wheelset, section):
    """Lateral shift [m] at which the right wheel's rigid contact first lies on the flange."""
    tab = contact_table(wheelset, section, y=np.arange(0.0, 0.015, 2.5e-4))
    g = np.asarray(tab["contact_angle_right_primary"].values, dtype=float)
    yy = np.asarray(tab["y"].values, dtype=float)
    on = np.flatnonzero(np.nan_to_num(g) >= 0.5)
    if on.size == 0:
        raise InputError("flange_climb: the right wheel's contact never reaches the flange "
                         "(contact angle > 0.5 rad) for y up to 15 mm")
    return float(yy[on[0]])


def flange_climb(model, track, yaw=0.01, normal="kik-piotrowski", tangential="fastsim", *,
                 mu=0.3, speed=10.0, y=None, contact="auto", contact_options=None,
                 spin="free", roll_step=5e-5, roll_range=0.03, **options) -> FlangeClimbResult:
    """Quasi-static flange climb of a wheelset (Pascal's model; see the module docstring).

    The model's mass, inertia, axle load and wheelset are used; its suspension is
    not (the wheelset is free but for the lateral force H at rail level, the
    vertical load at the axle centre and the prescribed yaw).

    Parameters
    ----------
    model : WheelsetModel
    track : Track
    yaw : float
        Angle of attack [rad] (positive: the right wheel steers into its rail).
    mu : float
        Friction coefficient.
    speed : float
        [m/s] (creepages are independent of it).
    y : float or None
        Lateral shift [m] where the path starts (default 1 mm before the rigid
        contact reaches the flange).
    roll_step, roll_range : float
        The path is followed in the roll angle [rad] (steps halved where the Newton
        iteration fails), up to ``roll_range`` beyond the start or past the flange tip.
    spin : {"free", "fixed"}
        The wheelset's spin balances the longitudinal creep torque, or Ω = V/r0.
    contact, contact_options
        As :func:`~wheelrail.dynamics.simulate`.
    **options
        Options of the two methods, each to the one that declares it.

    Returns
    -------
    FlangeClimbResult
    """
    if not isinstance(model, WheelsetModel):
        raise InputError(f"flange_climb needs a WheelsetModel, got {type(model).__name__}")
    if not (math.isfinite(yaw) and abs(yaw) < 0.1):
        raise InputError(f"yaw must be a number in (-0.1, 0.1) rad, got {yaw!r}")
    free = dataclasses.replace(model, primary=Suspension(), rail=None, spin=spin)
    section = getattr(track, "track", track)
    system = System(free, section, speed, normal, tangential, mu=mu, contact=contact,
                    contact_options=contact_options, method_options=options)
    m, Ix = free.mass, free.inertia[0]
    r0 = free.wheelset.nominal_radius
    if y is None:
        # from 1 mm before the rigid flange contact (contact angle > 0.5 rad) on
        ys = [_flange_start(free.wheelset, section) - 1e-3]
    else:
        ys = [float(y)]
    x = system.initial_state({"ws0.y": float(ys[0]), "ws0.yaw": float(yaw)})
    # unknowns z, roll, (Ω), H; equations ÿ, z̈, θ̈, (Ω̇) with H at rail level
    # the path is followed in the roll angle, which grows monotonically as the flanging
    # wheel unloads its tread and climbs (the lateral shift and the force H are found;
    # a lateral-force or lateral-shift control fails at the lift, where H(y) is steep)
    spin_cols = [8] if spin == "free" else []
    out = {k: [] for k in ("y", "H", "yq", "Q", "gam", "tread", "fr")}

    def solve_at(fixed, fixed_value, unknown_cols, guess):
        sc = np.array([1e-4 if c in (0, 1, 2) else 0.02 for c in unknown_cols] + [2e4])
        st = np.array([1e-8 if c in (0, 1, 2) else 1e-5 for c in unknown_cols] + [1.0])
        rows = [4, 5, 6] + ([8] if spin == "free" else [])

        def residual(u):
            xx = x.copy()
            xx[fixed] = fixed_value
            xx[unknown_cols] = u[:-1]
            d = system.rhs(0.0, xx)[rows].copy()
            d[0] += u[-1] / m               # H at rail level: lateral ...
            d[2] += u[-1] * r0 / Ix         # ... and its roll moment about the axle centre
            return d

        return _newton(residual, guess, sc, st)

    # the first point at the given lateral shift
    y0 = float(ys[0])
    cols0 = [1, 2] + spin_cols
    v = solve_at(0, y0, cols0, np.concatenate([x[cols0], [0.0]]))
    x[0] = y0
    x[cols0] = v[:-1]
    cols = [0, 1] + spin_cols
    v = np.concatenate([x[cols], [v[-1]]])
    th, dth = float(x[2]), float(roll_step)
    th_end = th + float(roll_range)
    hist = None
    n_fail = 0
    while th <= th_end:
        guess = v if hist is None else v + (v - hist[1]) * (dth / (th - hist[0]))
        try:
            v_new = solve_at(2, th + dth if out["y"] else th, cols, guess)
        except ConvergenceError:
            n_fail += 1
            if n_fail > 6 or not out["y"]:
                break
            dth *= 0.5
            continue
        n_fail = 0
        th_new = th + dth if out["y"] else th
        hist = (th, v) if out["y"] else None
        th, v = th_new, v_new
        dth = min(2 * dth, float(roll_step))
        xx = x.copy()
        xx[2] = th
        xx[cols] = v[:-1]
        system.rhs(0.0, xx)
        x = xx
        yy = float(x[0])
        OW, OP = system.OW[0, 1], system.OP[0, 1]
        Q = OW[_W["Fz"]]
        yq = -OW[_W["Fy"]] / Q if Q > 0 else math.nan
        loaded = OP[:, _P["Fn"]] > 0
        angles = OP[loaded, _P["contact_angle"]]
        flange = loaded & (OP[:, _P["contact_angle"]] >= _FLANK)
        tread = float(np.sum(OP[loaded & (OP[:, _P["contact_angle"]] < _FLANK), _P["Fn"]]))
        if np.any(flange):
            k = int(np.argmax(np.where(flange, OP[:, _P["Fn"]], -1.0)))
            fr = OP[k, _P["Fs"]] / OP[k, _P["Fn"]]
        else:
            fr = math.nan
        out["y"].append(yy)
        out["H"].append(v[-1])
        out["yq"].append(yq)
        out["Q"].append(Q)
        out["gam"].append(float(np.max(angles)) if angles.size else math.nan)
        out["tread"].append(tread)
        out["fr"].append(fr)
        if len(out["gam"]) > 3 and out["gam"][-1] < 0.5 < max(out["gam"]):
            break                           # past the flange tip
    if not out["y"]:
        raise ConvergenceError("flange_climb: no equilibrium at the first lateral shift")
    arr = {k: np.array(v_) for k, v_ in out.items()}
    on_flange = arr["gam"] >= _FLANK
    lifted = np.flatnonzero(on_flange & (arr["tread"] <= 0.0))
    lift = int(lifted[0]) if lifted.size else -1
    peak = int(np.nanargmax(arr["yq"]))
    gmax = float(np.nanmax(arr["gam"]))
    return FlangeClimbResult(arr["y"], arr["H"], arr["yq"], arr["Q"], arr["gam"],
                             arr["tread"], arr["fr"], lift, peak, float(nadal(gmax, mu)),
                             float(mu), float(yaw),
                             {"normal": system.contact.normal.name,
                              "tangential": system.contact.tangential.name,
                              "axle_load": free.axle_load, "weight": free.mass * GRAVITY})
