"""Profile evolution: the wear loop over mileage on wheelset, bogie and vehicle dynamics.

:func:`evolve` repeats, until the mileage is reached:

1. **simulate** every case of the :class:`Route` (a weighted set of
   :class:`RouteCase`: tangent or curved track with cant, speed, friction,
   an irregularity) with :func:`wheelrail.dynamics.simulate` on the current
   wheel profile — the cases of one step are independent and run in
   parallel (Dask by default; :mod:`wheelrail.sweeps.executors`);
2. **wear per case**: at every stored time after the case's run-in, each
   contact patch of the dynamics (equivalent ellipse a, b, normal force,
   creepages) is solved again with FASTSIM for its traction and slip fields
   (the usual post-processing of wear loops: Jendel 2002, Braghin et al.
   2006), the wear law gives the depth per passage across the patch
   (:func:`~wheelrail.wear.patch_wear`), placed on the wheel profile around
   the contact point (:meth:`PatchWear.on_profile`) and turned into depth per
   metre travelled (÷ 2π r, r the rolling radius); the time average is the
   case's wear rate per wheel, and the route's rate is the weighted mean;
3. **smooth** the wear rate (moving average over ``smoothing`` metres of the
   profile's lateral coordinate) and **scale** it to a step of mileage
   ΔL = ``step_depth`` / max(rate) (at most the remaining mileage): the
   largest depth change per step is ``step_depth``;
4. **update** the wheel profile: the depth is removed along the surface
   normal, z ← z + d √(1 + z'²) (the wheel lies above its profile z(y));
   with ``profiles="mean"`` (default) one profile for all wheels (the mean
   of their wear), with ``"sides"`` a left and a right profile (each the
   mean over the wheelsets); ``wheelsets`` declares which wheelsets' wear
   sets the profile (default all; e.g. ``(0,)`` the leading one). The
   dynamics run every wheelset of the model on the one
   :class:`~wheelrail.Wheelset` (wheelset, bogie and whole vehicle alike), so
   the wear is computed and recorded per wheel of every wheelset but all
   wheelsets carry the same updated profile(s); with ``update_rail=True`` also every case's
   rails (their wear per axle passage × ``rail_passages`` × ΔL, removed along
   the normal, z ← z − d √(1 + z'²): the rail lies below its profile);
5. **record** the profile, Sh, Sd, qR (:func:`wheelrail.profiles.flange_dimensions`),
   the equivalent conicity (EN 15302, on the case's rail), the wear rate
   per wheel and the rail's wear per axle passage (and the rail profiles
   with ``update_rail``), and **checkpoint** the step (``store``): a killed run resumes
   from its last finished step with nothing lost or repeated.

References
----------
.. [1] T. Jendel, Prediction of wheel profile wear — comparisons with field
   measurements, Wear 253 (2002) 89–99 (loop, step control by depth, smoothing).
.. [2] F. Braghin, R. Lewis, R.S. Dwyer-Joyce, S. Bruni, A mathematical model
   to predict railway wheel profile evolution due to wear, Wear 261 (2006)
   1253–1264 (FASTSIM post-processing of the dynamics' patches, USFD law).
.. [3] R. Enblom, M. Berg, Simulation of railway wheel profile development due
   to wear — influence of disc braking and contact environment, Wear 258
   (2005) 1055–1063.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import xarray as xr

from .._atomic import atomic_path, write_text
from ..errors import InputError
from ..geometry import Track, equivalent_conicity
from ..hertzian import hertz_from_semiaxes
from ..profiles import Profile, flange_dimensions
from ..tangential import Fastsim
from ..dynamics import TrackLayout, simulate
from ..dynamics.model import BogieModel, WheelsetModel
from ..dynamics.vehicle import VehicleModel
from ..sweeps.executors import make_executor
from ._base import WearLaw, get
from .patch import deposit, patch_wear

__all__ = ["RouteCase", "Route", "EvolveResult", "evolve"]


@dataclass(frozen=True)
class RouteCase:
    """One simulation case of a route (frozen, SI).

    Parameters
    ----------
    track : Track or TrackLayout
        Tangent track (a cross-section) or a layout with curves and an irregularity.
    speed : float
        Speed [m/s].
    weight : float
        Share of the mileage run in this case (weights are normalised over the route).
    distance : float
        Distance simulated per step [m] (after ``run_in``).
    run_in : float
        Distance simulated first and not counted (transients, curve entry) [m].
    mu : float
        Friction coefficient [-].
    name : str
    initial : dict or None
        Initial state of the dynamics (:func:`wheelrail.dynamics.simulate`).
    """

    track: object
    speed: float
    weight: float = 1.0
    distance: float = 50.0
    run_in: float = 0.0
    mu: float = 0.3
    name: str = ""
    initial: dict | None = None

    def __post_init__(self):
        if not isinstance(self.track, (Track, TrackLayout)):
            raise InputError(f"track must be a wheelrail.Track or a dynamics.TrackLayout, got "
                             f"{type(self.track).__name__}")
        for key, lo in (("speed", 0.0), ("weight", 0.0), ("distance", 0.0), ("mu", 0.0)):
            v = getattr(self, key)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > lo):
                raise InputError(f"RouteCase {self.name!r}: {key} must be > {lo:g}, got {v!r}")
        if not (isinstance(self.run_in, (int, float)) and math.isfinite(self.run_in)
                and self.run_in >= 0):
            raise InputError(f"RouteCase {self.name!r}: run_in must be >= 0 m, "
                             f"got {self.run_in!r}")

    @property
    def rail_track(self) -> Track:
        """The cross-section (for the equivalent conicity)."""
        return self.track if isinstance(self.track, Track) else self.track.track

    def fingerprint(self) -> dict:
        layout = self.track if isinstance(self.track, TrackLayout) else None
        curves = [] if layout is None else [dataclasses.astuple(c) for c in layout.curves]
        return {"speed": self.speed, "weight": self.weight, "distance": self.distance,
                "run_in": self.run_in, "mu": self.mu, "name": self.name, "curves": curves,
                "irregularity": None if layout is None or layout.irregularity is None else
                float(np.sum(np.abs(layout.irregularity.lateral)))}


@dataclass(frozen=True)
class Route:
    """A weighted set of :class:`RouteCase` (frozen); weights are normalised to sum 1."""

    cases: tuple

    def __post_init__(self):
        cases = tuple(self.cases)
        if not cases or not all(isinstance(c, RouteCase) for c in cases):
            raise InputError("a Route needs at least one wheelrail.wear.RouteCase")
        names = [c.name or f"case{i}" for i, c in enumerate(cases)]
        if len(set(names)) != len(names):
            raise InputError(f"route case names must differ, got {names}")
        cases = tuple(dataclasses.replace(c, name=n) for c, n in zip(cases, names))
        object.__setattr__(self, "cases", cases)

    @property
    def weights(self) -> np.ndarray:
        w = np.array([c.weight for c in self.cases], dtype=float)
        return w / w.sum()

    @property
    def names(self) -> list:
        return [c.name for c in self.cases]


@dataclass(frozen=True)
class EvolveResult:
    """Result of :func:`evolve` (frozen).

    Attributes
    ----------
    dataset : xarray.Dataset
        Over ``step`` (0 = the initial profile): ``mileage`` [m], ``Sh``, ``Sd``,
        ``qR`` [m], ``conicity`` [-] (per profile side), ``wheel_z`` (step, side, y)
        the profile heights on the grid ``y``, ``wear_rate`` (step, case, wheelset,
        side, y) [m/m] per metre travelled of each case, ``rail_wear`` (step, case,
        wheelset, side, y_rail) [m per axle passage], ``Tgamma`` (step, case,
        wheelset, side) [N] time-mean wear number, ``case_cpu`` (step) [s] CPU time of
        the step's cases and ``cpu_per_case`` (step, case) [s] that of each; with
        ``update_rail``, ``rail_z`` (step, case, side, y_rail)
        the rail profile heights [m]; step 0 has the initial values and the rates of
        the first simulation.
    profiles : list of dict
        Per step ``{"left": Profile, "right": Profile}`` (the same object twice
        with ``profiles="mean"``).
    """

    dataset: xr.Dataset
    profiles: list
    info: dict = field(default_factory=dict)


# ----------------------------------------------------------------------------- one case
def _case_wear(model, case, law, grid, rail_grid, opts):
    """Wear rate per wheel on the profile grid for one case (runs on a worker)."""
    t0 = time.process_time()
    V = float(case.speed)
    duration = (case.run_in + case.distance) / V
    dt_out = case.distance / V / opts["samples"]
    res = simulate(model, case.track, V, duration, normal=opts["normal"],
                   tangential=opts["tangential"], mu=case.mu, output_step=dt_out,
                   initial=case.initial, **opts["method_options"])
    ds = res.dataset
    keep = ds["position"].values - ds["position"].values[0] >= case.run_in - 1e-9
    sel = ds.isel(time=np.nonzero(keep)[0])
    nt = int(sel.sizes["time"])
    nw = int(sel.sizes["wheelset"])
    g = {k: sel[k].values for k in ("Fn", "a", "b", "xi", "eta", "phi", "wheel_y", "rail_y",
                                    "contact_angle", "rolling_radius")}
    act = g["Fn"] > 0
    edges = np.concatenate([[grid[0] - 0.5 * (grid[1] - grid[0])],
                            0.5 * (grid[1:] + grid[:-1]),
                            [grid[-1] + 0.5 * (grid[-1] - grid[-2])]])
    redges = np.concatenate([[rail_grid[0] - 0.5 * (rail_grid[1] - rail_grid[0])],
                             0.5 * (rail_grid[1:] + rail_grid[:-1]),
                             [rail_grid[-1] + 0.5 * (rail_grid[-1] - rail_grid[-2])]])
    W = np.zeros((nw, 2, grid.size))
    R = np.zeros((nw, 2, rail_grid.size))
    T = np.zeros((nw, 2))
    idx = np.argwhere(act)
    if idx.size:
        pick = tuple(idx.T)
        c = hertz_from_semiaxes(g["a"][pick], g["b"][pick], g["Fn"][pick], model.material)
        cr = np.stack([g["xi"][pick], g["eta"][pick], g["phi"][pick]], axis=1)
        fs = Fastsim(nx=opts["cells"], ny=opts["cells"], fields=True)
        r = fs.forces(c, cr, case.mu)
        fields = r.fields if isinstance(r.fields, tuple) else (r.fields,)
        for n, (it, iw, iside, ip) in enumerate(idx):
            w = patch_wear(fields[n], law, speed=V)
            sigma = -1.0 if iside == 0 else 1.0
            gam = float(g["contact_angle"][it, iw, iside, ip])
            cg = math.cos(gam)
            lo_c, hi_c = w.y - 0.5 * w.dy, w.y + 0.5 * w.dy
            for ref, E, out, scale in (
                    (g["wheel_y"][it, iw, iside, ip], edges, W,
                     1.0 / (2 * math.pi * float(g["rolling_radius"][it, iw, iside, ip]))),
                    (g["rail_y"][it, iw, iside, ip], redges, R, 1.0)):
                a_ = ref + sigma * cg * lo_c
                b_ = ref + sigma * cg * hi_c
                out[iw, iside] += scale * deposit(np.minimum(a_, b_), np.maximum(a_, b_),
                                                  w.depth, E)
            T[iw, iside] += w.Tgamma
    n = max(nt, 1)
    return {"wear_rate": W / n, "rail_wear": R / n, "Tgamma": T / n, "samples": nt,
            "cpu": time.process_time() - t0}


# ----------------------------------------------------------------------------- helpers
def _smooth(values, spacing, window):
    """Moving average over ``window`` [m] along the last axis (normalised at the ends)."""
    n = int(round(window / spacing))
    if n <= 1:
        return values
    kernel = np.ones(n)
    ones = np.convolve(np.ones(values.shape[-1]), kernel, mode="same")
    return np.apply_along_axis(lambda v: np.convolve(v, kernel, mode="same") / ones, -1, values)


def _worn(profile, grid, depth):
    """The wheel profile with ``depth`` [m] removed along the normal on ``grid``."""
    z = np.asarray(profile(grid), dtype=float)
    dz = np.asarray(profile.slope(grid), dtype=float)
    z_new = z + depth * np.sqrt(1.0 + dz * dz)
    meta = dict(profile.meta)
    return Profile(grid, z_new, kind="wheel", name=profile.name, meta=meta)


def _with_profiles(model, left, right):
    """The model with the wheel profiles ``left``, ``right`` on every wheelset."""
    ws = dataclasses.replace(model.wheelset, wheel=left, wheel_right=right)
    if isinstance(model, VehicleModel):
        if model.bogies is not None:     # both bogies run on the one Wheelset object
            return dataclasses.replace(model, bogies=tuple(
                dataclasses.replace(b, wheelset=ws) for b in model.bogies))
        return dataclasses.replace(model, wheelsets=dataclasses.replace(model.wheelsets,
                                                                        wheelset=ws))
    return dataclasses.replace(model, wheelset=ws)


def _measure(model, route, conicity=True):
    ws = model.wheelset
    out = {}
    for side, prof in (("left", ws.wheel), ("right", ws.wheel_right)):
        try:
            fd = flange_dimensions(prof)
            out[side] = (fd.Sh, fd.Sd, fd.qR)
        except Exception:   # a profile without a measurable flange: NaN, not an abort
            out[side] = (math.nan,) * 3
    con = math.nan
    if conicity:
        try:
            con = float(equivalent_conicity(ws, route.cases[0].rail_track))
        except Exception:   # no contact table on this profile: NaN, not an abort
            con = math.nan
    return out, con


def _fingerprint(model, route, law, settings) -> str:
    ws = model.wheelset
    h = hashlib.sha256()
    for p in (ws.wheel, ws.wheel_right):
        h.update(np.asarray(p.y).tobytes())
        h.update(np.asarray(p.z).tobytes())
    h.update(json.dumps({"route": [c.fingerprint() for c in route.cases], "law": repr(law),
                         "model": type(model).__name__, "settings": settings},
                        sort_keys=True, default=str).encode())
    return h.hexdigest()[:16]


# ----------------------------------------------------------------------------- entry point
def evolve(model, route, *, mileage, law="usfd", step_depth=0.1e-3, smoothing=2e-3,
           resolution=0.25e-3, max_steps=200, profiles="mean", normal="kik-piotrowski",
           tangential="fastsim", samples=100, cells=12, conicity=True, executor="dask",
           workers=None, scheduler=None, store=None, progress=False, on_step=None,
           update_rail=False, rail_passages=None, wheelsets=None,
           **options) -> EvolveResult:
    """Evolve the wheel profiles of a wheelset, bogie or vehicle model over a route by wear.

    Parameters
    ----------
    model : WheelsetModel, BogieModel or VehicleModel
        The vehicle model (its ``wheelset`` carries the profiles that wear; a
        :class:`~wheelrail.dynamics.VehicleModel` has four wheelsets on two
        bogies, or two, all on one :class:`~wheelrail.Wheelset`).
    route : Route or sequence of RouteCase
        The simulation cases and their shares of the mileage.
    mileage : float
        Distance to run [m].
    law : str or WearLaw
        Wear law (:mod:`wheelrail.wear`; default the USFD law).
    step_depth : float
        Largest wear depth change per step [m] (default 0.1 mm).
    smoothing : float
        Window of the moving average of the wear rate along the profile [m].
    resolution : float
        Spacing of the profile grid [m] (the updated profile's points).
    max_steps : int
        Refuse to run more steps than this (raise ``step_depth`` instead).
    profiles : {"mean", "sides"}
        One profile for all wheels or one per side (module docstring).
    wheelsets : sequence of int or None
        Indices of the wheelsets (0 the leading one) whose mean wear rate
        updates the profile(s); default all. Every wheelset then runs on the
        updated profile(s) (the dynamics have one Wheelset for all of them); the
        wear of each wheel stays in ``dataset.wear_rate``.
    normal, tangential, **options
        The dynamics' contact methods and their options (:func:`wheelrail.dynamics.simulate`).
    samples : int
        Stored time points per case and step used for the wear.
    cells : int
        FASTSIM cells per side of each patch in the wear post-processing.
    conicity : bool
        Record the equivalent conicity of every step (NaN otherwise).
    executor, workers, scheduler
        Where the cases of a step run: ``"dask"`` (default; a ``LocalCluster``
        of ``workers`` processes, or the scheduler at ``scheduler``),
        ``"processes"``, ``"serial"`` (:func:`wheelrail.sweeps.make_executor`).
    store : path or None
        Checkpoint directory: every finished step is written there, and a run
        started again with the same inputs continues after the last one.
    progress : bool
        Print one line per step.
    update_rail : bool
        Also wear the rails: each case's left and right rail profile loses its
        wear per axle passage (summed over the model's wheelsets, smoothed) ×
        ``rail_passages`` × the step's mileage, removed along the normal
        (z ← z − d √(1 + z'²); the rail lies below its profile), and the next
        step runs on the worn rails; the step control then takes the largest
        depth change of wheels and rails. Default False: the rails keep their
        profile (their wear is still recorded).
    rail_passages : float
        With ``update_rail``: passages of the model over each case's rail
        section per metre of the model's mileage [1/m] (the traffic the rail
        sees relative to the wheels' running; e.g. a fleet of N such vehicles
        each running a route of length L_r: N / L_r).
    on_step : callable or None
        Called after every step computed in this call (not for the steps
        read back from ``store``) as ``on_step(info)`` with a dict: ``step``,
        ``mileage`` [m] reached, ``total`` [m], ``Sd`` [m] (left, right),
        ``conicity``, ``cpu`` [s] of the step's cases, ``cpu_per_case`` [s] (one per
        case) and ``steps_left``, the
        estimated number of remaining steps (remaining mileage × largest wear
        rate / ``step_depth``, rounded up).

    Returns
    -------
    EvolveResult
        ``.dataset`` (:class:`xarray.Dataset` over steps) and ``.profiles``.
    """
    if not isinstance(model, (WheelsetModel, BogieModel, VehicleModel)):
        raise InputError(f"model must be a dynamics.WheelsetModel, BogieModel or VehicleModel, "
                         f"got {type(model).__name__}")
    if not isinstance(route, Route):
        route = Route(tuple(route))
    impl = law if isinstance(law, WearLaw) else get(law)
    for key, v in (("mileage", mileage), ("step_depth", step_depth), ("resolution", resolution)):
        if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
            raise InputError(f"{key} must be > 0, got {v!r}")
    if not (isinstance(smoothing, (int, float)) and smoothing >= 0):
        raise InputError(f"smoothing must be >= 0 m, got {smoothing!r}")
    if profiles not in ("mean", "sides"):
        raise InputError(f"profiles must be 'mean' or 'sides', got {profiles!r}")
    if not isinstance(update_rail, bool):
        raise InputError(f"update_rail must be True or False, got {update_rail!r}")
    if update_rail and not (isinstance(rail_passages, (int, float)) and not
                            isinstance(rail_passages, bool) and math.isfinite(rail_passages)
                            and rail_passages > 0):
        raise InputError(f"update_rail=True needs rail_passages > 0 (passages over the rail "
                         f"per metre of mileage), got {rail_passages!r}")
    if not (isinstance(max_steps, int) and max_steps >= 1):
        raise InputError(f"max_steps must be an integer >= 1, got {max_steps!r}")
    nws = int(model.n_wheelsets)
    if wheelsets is None:
        group = list(range(nws))
    else:
        try:
            group = sorted({int(i) for i in wheelsets})
            bad = [j for j in wheelsets if isinstance(j, bool) or int(j) != j
                   or not 0 <= int(j) < nws]
        except (TypeError, ValueError):
            group, bad = [], [wheelsets]
        if bad or not group:
            raise InputError(f"wheelsets must be indices 0 … {nws - 1} of the model's "
                             f"wheelsets, got {wheelsets!r}")

    ws = model.wheelset
    lo = max(ws.wheel.y_min, ws.wheel_right.y_min)
    hi = min(ws.wheel.y_max, ws.wheel_right.y_max)
    grid = np.arange(lo + 1e-6, hi - 1e-6, resolution)
    rail = route.cases[0].rail_track.rail
    rail_grid = np.arange(rail.y_min + 1e-6, rail.y_max - 1e-6, resolution)
    opts = {"normal": normal, "tangential": tangential, "samples": int(samples),
            "cells": int(cells), "method_options": dict(options)}
    settings = {"mileage": float(mileage), "step_depth": step_depth, "smoothing": smoothing,
                "resolution": resolution, "profiles": profiles, "normal": str(normal),
                "tangential": str(tangential), "samples": samples, "cells": cells,
                "options": {k: repr(v) for k, v in options.items()}}
    if update_rail:
        settings["update_rail"] = float(rail_passages)
    if wheelsets is not None:
        settings["wheelsets"] = group
    key = _fingerprint(model, route, impl, settings)
    weights = route.weights
    store = None if store is None else Path(store)
    records = _load_store(store, key) if store is not None else []

    current = model
    done = 0.0
    rail = dict(update=update_rail, passages=rail_passages, grid=rail_grid,
                smoothing=smoothing, resolution=resolution)
    route0 = route
    if records:
        last = records[-1]
        # step 0 ran on the given profiles (not their grid samples): resume from those, so
        # that the next step is the one the uninterrupted run computes
        if len(records) > 1:
            current = _with_profiles(model,
                                     _profile_from(last["left_z"], last["grid"], ws.wheel),
                                     _profile_from(last["right_z"], last["grid"],
                                                   ws.wheel_right))
            if update_rail:
                route = _route_with_rails(route0, last["rail_z"], rail_grid)
        done = float(last["mileage"])
        if float(mileage) - done > 1e-9 * float(mileage):
            current, route, done = _advance(model, current, route, last, grid, done, mileage,
                                            step_depth, profiles, rail)
        else:
            return _result(records, route0, rail_grid, ws, 0.0)
    ex = make_executor(executor, workers, scheduler)
    t_start = time.process_time()
    with ex:
        while True:
            k = len(records)
            if k > max_steps:
                raise InputError(f"more than max_steps = {max_steps} steps needed; raise "
                                 f"step_depth or max_steps")
            results = {}
            tasks = [(i, (current, c, impl, grid, rail_grid, opts))
                     for i, c in enumerate(route.cases)]
            ex.run(_case_wear, tasks, lambda i, v: results.__setitem__(i, v))
            rate = np.stack([results[i]["wear_rate"] for i in range(len(route.cases))])
            mean = np.tensordot(weights, rate, axes=1)[group]      # (nw, 2, ny)
            if profiles == "mean":
                per_side = np.repeat(mean.mean(axis=(0, 1))[None], 2, axis=0)
            else:
                per_side = mean.mean(axis=0)
            per_side = _smooth(per_side, resolution, smoothing)
            dims, con = _measure(current, route, conicity)
            rec = {"step": k, "mileage": done, "grid": grid,
                   "left_z": np.asarray(current.wheelset.wheel(grid)),
                   "right_z": np.asarray(current.wheelset.wheel_right(grid)),
                   "wear_rate": rate, "per_side": per_side,
                   "rail_wear": np.stack([results[i]["rail_wear"]
                                          for i in range(len(route.cases))]),
                   "Tgamma": np.stack([results[i]["Tgamma"] for i in range(len(route.cases))]),
                   "dims": np.array([dims["left"], dims["right"]]), "conicity": con,
                   "cpu": float(sum(results[i]["cpu"] for i in results)),
                   "cpu_per_case": np.array([results[i]["cpu"]
                                             for i in range(len(route.cases))])}
            if update_rail:
                rec["rail_z"] = _rail_heights(route, rail_grid)
            records.append(rec)
            if store is not None:
                _save_record(store, key, rec)
            if progress:
                print(f"wear step {k}: {done / 1e3:.1f} km, Sd {dims['left'][1] * 1e3:.3f} / "
                      f"{dims['right'][1] * 1e3:.3f} mm, conicity {con:.4f}", flush=True)
            if on_step is not None:
                top = float(np.max(per_side))
                left = float(mileage) - done
                on_step({"step": k, "mileage": done, "total": float(mileage),
                         "Sd": (dims["left"][1], dims["right"][1]), "conicity": con,
                         "cpu": rec["cpu"], "cpu_per_case": rec["cpu_per_case"],
                         "steps_left": 0 if left <= 1e-9 * float(mileage) else
                         (1 if top <= 0 else max(1, math.ceil(left * top / step_depth)))})
            if float(mileage) - done <= 1e-9 * float(mileage):
                break
            current, route, done = _advance(model, current, route, rec, grid, done, mileage,
                                            step_depth, profiles, rail)
    return _result(records, route0, rail_grid, ws, time.process_time() - t_start)


def _rail_rate(rec, rail):
    """Rail depth per metre of mileage (case, side, y_rail): the wear per axle passage summed
    over the wheelsets, smoothed, × passages per metre."""
    per_pass = np.asarray(rec["rail_wear"]).sum(axis=1)                 # (case, side, y)
    return rail["passages"] * _smooth(per_pass, rail["resolution"], rail["smoothing"])


def _advance(model, current, route, rec, grid, done, mileage, step_depth, profiles, rail):
    """Apply one wear step: ΔL = step_depth / max(rate), at most the remaining mileage."""
    per_side = np.asarray(rec["per_side"])
    remaining = float(mileage) - done
    top = float(np.max(per_side))
    rrate = _rail_rate(rec, rail) if rail["update"] else None
    if rrate is not None:
        top = max(top, float(np.max(rrate)))
    dL = remaining if top <= 0 else min(step_depth / top, remaining)
    left = _worn(current.wheelset.wheel, grid, per_side[0] * dL)
    right = left if profiles == "mean" else _worn(current.wheelset.wheel_right, grid,
                                                    per_side[1] * dL)
    if rrate is not None:
        z = _rail_heights(route, rail["grid"])                            # (case, side, y)
        route = _route_with_rails(route, _rail_worn(route, rail["grid"], z, rrate * dL),
                                  rail["grid"])
    return _with_profiles(model, left, right), route, done + dL


def _rail_heights(route, rgrid):
    """Heights of every case's left and right rail on ``rgrid`` (case, side, y_rail)."""
    return np.stack([np.stack([np.asarray(c.rail_track.rail(rgrid), dtype=float),
                               np.asarray(c.rail_track.rail_right(rgrid), dtype=float)])
                     for c in route.cases])


def _rail_worn(route, rgrid, z, depth):
    """Rail heights with ``depth`` removed along the normal (the rail lies below z(y))."""
    out = np.empty_like(z)
    for i, c in enumerate(route.cases):
        for j, prof in enumerate((c.rail_track.rail, c.rail_track.rail_right)):
            dz = np.asarray(prof.slope(rgrid), dtype=float)
            out[i, j] = z[i, j] - depth[i, j] * np.sqrt(1.0 + dz * dz)
    return out


def _route_with_rails(route, z, rgrid):
    """The route with every case's rails replaced by the profiles of heights ``z``."""
    cases = []
    for i, c in enumerate(route.cases):
        tr = c.rail_track
        left = Profile(np.asarray(rgrid), np.asarray(z[i][0]), kind="rail", name=tr.rail.name,
                       meta=dict(tr.rail.meta))
        right = Profile(np.asarray(rgrid), np.asarray(z[i][1]), kind="rail",
                        name=tr.rail_right.name, meta=dict(tr.rail_right.meta))
        new = dataclasses.replace(tr, rail=left, rail_right=right)
        track = new if isinstance(c.track, Track) else dataclasses.replace(c.track, track=new)
        cases.append(dataclasses.replace(c, track=track))
    return Route(tuple(cases))


def _profile_from(z, grid, like):
    return Profile(np.asarray(grid), np.asarray(z), kind="wheel", name=like.name,
                   meta=dict(like.meta))


def _save_record(store: Path, key: str, rec: dict) -> None:
    store.mkdir(parents=True, exist_ok=True)
    path = store / f"step_{rec['step']:05d}.npz"
    with atomic_path(path) as tmp:
        with open(tmp, "wb") as fh:
            np.savez(fh, **{k: np.asarray(v) for k, v in rec.items()})
    write_text(store / "state.json", json.dumps({"key": key, "steps": rec["step"] + 1,
                                                 "mileage": rec["mileage"]}))


def _load_store(store: Path, key: str) -> list:
    state = store / "state.json"
    if not state.exists():
        return []
    info = json.loads(state.read_text())
    if info.get("key") != key:
        raise InputError(f"the store {str(store)!r} holds a different wear run (other model, "
                         f"route, law or settings); use another directory")
    out = []
    for k in range(int(info["steps"])):
        with np.load(store / f"step_{k:05d}.npz") as z:
            rec = {n: z[n] for n in z.files}
        rec = {n: (v.item() if v.ndim == 0 else v) for n, v in rec.items()}
        out.append(rec)
    return out


def _result(records, route, rail_grid, ws, cpu) -> EvolveResult:
    grid = np.asarray(records[0]["grid"])
    steps = np.arange(len(records))
    dims = np.stack([r["dims"] for r in records])                 # (step, side, 3)
    sides = ["left", "right"]
    nw = records[0]["wear_rate"].shape[1]
    coords = {"step": steps, "side": sides, "y": grid, "y_rail": rail_grid,
              "case": route.names, "wheelset": np.arange(nw)}
    data = {
        "mileage": ("step", np.array([float(r["mileage"]) for r in records]), {"units": "m"}),
        "Sh": (("step", "side"), dims[..., 0], {"units": "m", "description": "flange height"}),
        "Sd": (("step", "side"), dims[..., 1], {"units": "m",
                                                "description": "flange thickness"}),
        "qR": (("step", "side"), dims[..., 2], {"units": "m", "description": "qR dimension"}),
        "conicity": ("step", np.array([float(r["conicity"]) for r in records]),
                     {"units": "1", "description": "equivalent conicity (3 mm, EN 15302)"}),
        "wheel_z": (("step", "side", "y"), np.stack([np.stack([r["left_z"], r["right_z"]])
                                                      for r in records]), {"units": "m"}),
        "wear_rate": (("step", "case", "wheelset", "side", "y"),
                      np.stack([r["wear_rate"] for r in records]),
                      {"units": "m/m", "description": "wheel wear depth per metre travelled"}),
        "rail_wear": (("step", "case", "wheelset", "side", "y_rail"),
                      np.stack([r["rail_wear"] for r in records]),
                      {"units": "m", "description": "rail wear depth per axle passage"}),
        "Tgamma": (("step", "case", "wheelset", "side"), np.stack([r["Tgamma"] for r in records]),
                   {"units": "N", "description": "time-mean wear number (FASTSIM fields)"}),
        "case_cpu": ("step", np.array([float(r["cpu"]) for r in records]),
                     {"units": "s", "description": "CPU time of the step's cases (workers)"}),
    }
    if all("cpu_per_case" in r for r in records):
        data["cpu_per_case"] = (("step", "case"),
                                np.stack([np.atleast_1d(r["cpu_per_case"]) for r in records]),
                                {"units": "s", "description": "CPU time of each case (worker)"})
    if "rail_z" in records[0]:
        data["rail_z"] = (("step", "case", "side", "y_rail"),
                          np.stack([r["rail_z"] for r in records]),
                          {"units": "m", "description": "rail profile heights (update_rail)"})
    ds = xr.Dataset(data, coords=coords,
                    attrs={"cpu_time": cpu, "weights": list(map(float, route.weights))})
    profs = []
    for r in records:
        left = _profile_from(r["left_z"], grid, ws.wheel)
        right = _profile_from(r["right_z"], grid, ws.wheel_right)
        profs.append({"left": left, "right": right})
    return EvolveResult(dataset=ds, profiles=profs, info={"cpu_time": cpu})
