"""Contact forces of a wheel at a pose, for the time integration: compiled or through the library.

Every evaluation of the equations of motion needs the patches and forces of
every wheel at its current pose and velocity. Two paths give them in the same
format (rows of :data:`~wheelrail.dynamics._fastcontact.PATCH_FIELDS` per
patch, :data:`~wheelrail.dynamics._fastcontact.WHEEL_FIELDS` per wheel):

* :class:`FastContact` — the compiled path of
  :mod:`wheelrail.dynamics._fastcontact` for Hertz or Kik–Piotrowski normal
  contact with FASTSIM or the table law (options of the configured methods
  honoured; see the class);
* :class:`GenericContact` — any normal × tangential method of the library, as
  configured objects: the wheel problem of
  :func:`wheelrail.contact.wheelrail.wheel_problem` at the wheel's touching pose
  with the vertical approach of the current pose, the method's ``from_wheel``,
  the creepages of :func:`wheelrail.geometry.kinematics.creepage_kernel` and the
  law's ``solve_patches`` (what :func:`wheelrail.solve` does with ``z=``);
  milliseconds per wheel.

:func:`contact_model` picks the compiled path when it supports the methods
(``contact="auto"``), or the one asked for.

References
----------
.. [1] J. Piotrowski, H. Chollet, Wheel–rail contact models for vehicle system
   dynamics including multi-point contact, VSD 43 (2005) 455–483, §1–3.
"""

from __future__ import annotations

import math
import time
import warnings

import numpy as np

from .. import normal as normal_family
from .. import tangential as tangential_family
from ..contact.wheelrail import WheelRailPosition, _creepage_at, wheel_problem
from ..errors import InputError
from ..geometry._curves import SAMPLE_STEP, PiecewiseCubic
from ..geometry.contact_search import _side_args
from ..geometry.kinematics import Motion
from ..geometry.touching import touching_heights
from ..materials import as_material_pair
from ..normal._strips import _LN_MAX, _hertz_table
from ..normal.hertz import Hertz
from ..normal.kik_piotrowski import KikPiotrowski
from ..options import split_options
from ..plausibility import disabled
from ..tangential.fastsim import Fastsim, _kalker_table, _profile, _resample_weights, _strip_t
from ..tangential.linear import Linear, kalker_coefficients
from ..tangential.table import Table, load_table
from ._fastcontact import KMAX, MP, PATCH_FIELDS, WHEEL_FIELDS, wheel_contact

__all__ = ["FastContact", "GenericContact", "contact_model", "PATCH_FIELDS", "WHEEL_FIELDS",
           "KMAX", "SIDES", "SlowContactWarning"]

#: CPU time of the compiled contact of one wheel [s] (Kik–Piotrowski + FASTSIM, S1002 on
#: 60E1, tread and flange positions; ``benchmarks/bench_dynamics.py``), quoted when a
#: method pair falls back to the generic path.
COMPILED_WHEEL_TIME = 5e-5


class SlowContactWarning(UserWarning):
    """The configured methods have no compiled contact path: every contact evaluation of
    the time integration goes through the library (:class:`GenericContact`), typically
    100 times slower or more."""

SIDES = ("left", "right")
_SIGMA = {"left": -1.0, "right": 1.0}
_P = {n: i for i, n in enumerate(PATCH_FIELDS)}
_W = {n: i for i, n in enumerate(WHEEL_FIELDS)}


_UNIFORM: dict = {}


def _uniform_wheel(wheelset, side):
    """The wheel profile spline of ``side`` re-sampled every 0.05 mm (cached per curve)."""
    wc = wheelset.curve(side)
    hit = _UNIFORM.get(id(wc))
    if hit is None or hit[0] is not wc:
        (v,) = wc.eval(wc.u, 0)
        hit = (wc, PiecewiseCubic.through(wc.u, v, uniform_step=SAMPLE_STEP))
        if len(_UNIFORM) > 32:
            _UNIFORM.clear()
        _UNIFORM[id(wc)] = hit
    return hit[1]


def _fast_support(nimpl, timpl) -> str:
    """Empty if the compiled path supports the configured methods, else the reason."""
    if type(nimpl) not in (Hertz, KikPiotrowski):
        return f"normal method {nimpl.name!r} (compiled: 'hertz', 'kik-piotrowski')"
    if type(timpl) not in (Fastsim, Table, Linear):
        return f"tangential method {timpl.name!r} (compiled: 'fastsim', 'table', 'linear')"
    if isinstance(timpl, Table) and timpl.outside == "exact":
        return "the table law with outside='exact' (the exact solver is not compiled)"
    if isinstance(nimpl, KikPiotrowski) and nimpl.fastsim_flexibility == "three":
        return (f"Kik-Piotrowski with fastsim_flexibility={nimpl.fastsim_flexibility!r} "
                "(compiled: 'combined', 'weighted')")
    return ""


class FastContact:
    """Compiled contact of the wheels of a wheelset (see :mod:`wheelrail.dynamics._fastcontact`).

    Parameters
    ----------
    wheelset, track : Wheelset, Track
    material : Material or MaterialPair
    normal : Hertz or KikPiotrowski
        Configured normal method. Kik–Piotrowski's options ``penetration_factor``,
        ``shape_correction``, ``strips`` and ``cells`` are honoured;
        ``ellipticity_correction`` and ``fastsim_flexibility`` "combined" or "weighted"
        are honoured; "three" is not compiled (refused here; ``contact="auto"``
        takes the generic path for it).
    tangential : Fastsim, Table or Linear
        Configured law. FASTSIM's ``nx``, ``ny``, ``bound``, ``flexibility`` and
        ``scheme`` are honoured (Kik–Piotrowski patches use one flexibility per patch,
        combined or weighted, as in the library). The table law's points outside its domain are
        refused (``outside="raise"``: :class:`~wheelrail.errors.InputError` naming the
        pose) or computed by FASTSIM with its defaults (``"fastsim"``).
    search_step : float
        Grid step of the contact search along the wheel profile [m] (minima refined
        to ~1 µm).
    line_half_width : float
        Smallest half width of the part of Kik–Piotrowski's separation line that is
        evaluated [m] (widened to the region's extent on the search grid and the
        group's points, and while a region reaches its end); the line's nodes are the
        library's, so this changes the cost, not the result.
    tolerance : float
        Largest undeformed separation of a candidate point [m] (as
        :class:`~wheelrail.contact.wheelrail.WheelRailPosition`).
    connected : {"separate", "shared"}
        Hertz patches of minima of the gap that lie in one connected
        interpenetration region: each with its full depth, as
        :func:`wheelrail.solve` (``"separate"``), or with the region's common
        depth counted once and shared in proportion to each minimum's depth below
        its saddle (``"shared"``: the normal forces are continuous where a minimum
        appears or vanishes inside the region, e.g. at the two-point transition
        between flange root and flange; the default of
        :func:`~wheelrail.dynamics.steady_curving`).
    """

    kind = "compiled"

    def __init__(self, wheelset, track, material, normal, tangential, *, search_step=5e-4,
                 line_half_width=1e-3, tolerance=5e-4, connected="separate"):
        why = _fast_support(normal, tangential)
        if connected not in ("separate", "shared"):
            raise InputError(f"connected must be 'separate' or 'shared', got {connected!r}")
        if why:
            raise InputError(f"contact='fast' does not support {why}; use contact='generic'")
        self.wheelset, self.track = wheelset, track
        self.normal, self.tangential = normal, tangential
        pair = as_material_pair(material)
        self.materials = pair
        self.geometry = {}
        for side in SIDES:
            s, p, p1, lo, hi, h, wu, winv, wc, ru, rinv, rc, rh, r0, e, sig = _side_args(
                wheelset, track, side, float(search_step))
            # the wheel spline re-sampled on a uniform grid (evaluation without a search;
            # differs from the library's spline by ~1e-10 m)
            wcu = _uniform_wheel(wheelset, side)
            wu, winv, wc = wcu.u, 1.0 / wcu._h, wcu.c
            pl = track.placement(side)
            self.geometry[side] = (s, p, p1, float(lo), float(hi), wu, float(winv), wc, ru,
                                   float(rinv), rc, float(r0), float(e), float(sig),
                                   float(pl.offset), float(pl.z_top), float(pl.angle))
        mp = np.zeros(len(MP))
        mp[MP["normal"]] = 0 if isinstance(normal, Hertz) else 1
        mp[MP["tangential"]] = (1 if isinstance(tangential, Table) else
                                2 if isinstance(tangential, Linear) else 0)
        mp[MP["E_star"]] = pair.E_star
        mp[MP["G"]] = pair.G
        mp[MP["nu"]] = pair.nu
        mp[MP["K"]] = float(getattr(pair, "K", 0.0))
        if isinstance(normal, KikPiotrowski):
            pf = normal.penetration_factor
            mp[MP["eps"]] = -1.0 if isinstance(pf, str) else float(pf)
            mp[MP["shape_correction"]] = 1.0 if normal.shape_correction else 0.0
            mp[MP["kpec"]] = 1.0 if normal._kpec(
                {k: getattr(normal, k) for k in ("ellipticity_correction", "penetration_factor",
                                                 "shape_correction")}) else 0.0
            mp[MP["combined"]] = 1.0 if normal.fastsim_flexibility == "combined" else 0.0
            mp[MP["strips"]] = normal.strips
            mp[MP["cells"]] = normal.cells
            mp[MP["line_nodes"]] = normal.line_nodes
            mp[MP["samples"]] = normal.profile_samples
        else:
            mp[MP["strips"]] = mp[MP["cells"]] = 2
            mp[MP["line_nodes"]] = 1601         # (unused by Hertz)
            mp[MP["samples"]] = 2001
        mp[MP["line_stride"]] = 1        # every node of the method's line (its line_nodes)
        mp[MP["line_half_width"]] = float(line_half_width)
        mp[MP["group_angle"]] = 0.2
        mp[MP["tolerance"]] = float(tolerance)
        fs = tangential if isinstance(tangential, Fastsim) else Fastsim()
        mp[MP["nx"]] = fs.nx
        mp[MP["ny"]] = fs.ny
        mp[MP["parabolic"]] = 1.0 if fs.bound == "parabolic" else 0.0
        mp[MP["weighted"]] = 1.0 if fs.flexibility == "weighted" else 0.0
        mp[MP["first_order"]] = 1.0 if fs.scheme == "euler" else 0.0
        mp[MP["search_step"]] = float(search_step)
        mp[MP["connected"]] = 1.0 if connected == "shared" else 0.0
        self.connected = connected
        self.table_raise = isinstance(tangential, Table) and tangential.outside == "raise"
        lam, la, lb, lp, ld = _hertz_table()
        kx, c11, c22, c23 = _kalker_table(float(pair.nu))
        c33 = np.asarray(kalker_coefficients(np.exp(kx), float(pair.nu))[3], dtype=float)
        t = _strip_t(fs.ny)
        half = np.sqrt(1.0 - t * t)
        strip_peak = _profile(fs.bound, t)
        s_cells = _profile(fs.bound, 1.0 - (np.arange(fs.nx) + 0.5) * (2.0 / fs.nx))
        discrete = (4.0 / (fs.nx * fs.ny)) * np.sum(strip_peak * half) * np.sum(s_cells)
        continuous = np.pi / 2.0 if fs.bound == "parabolic" else 2.0 * np.pi / 3.0
        i0, i1, w = _resample_weights(int(mp[MP["cells"]]), fs.nx)
        # the table's compiled form (the library's own kernel evaluates it); with another
        # law the default table's arrays only fill the slots of the compiled signature
        data = load_table(tangential.table if isinstance(tangential, Table) else None)
        kernel = tuple(np.ascontiguousarray(k) for k in data.kernel_at(float(pair.nu)))
        c_ = np.ascontiguousarray
        self.method = (mp, c_(lam), c_(la), c_(lb), c_(lp), c_(ld), c_(kx), c_(c11), c_(c22),
                       c_(c23), c_(c33), c_(t), c_(half), c_(strip_peak), c_(s_cells),
                       float(continuous / discrete), c_(i0), c_(i1), c_(w), *kernel)
        self.ln_max = _LN_MAX

    def wheel(self, side, y, zc, roll, yaw, V, omega, vy, vz, yaw_rate, roll_rate, mu,
              out_p, out_w):
        """Fill ``out_p`` (KMAX, fields) and ``out_w`` for one wheel (see ``wheel_contact``)."""
        n = wheel_contact(*self.geometry[side], float(y), float(zc), float(roll), float(yaw),
                          float(V), float(omega), float(vy), float(vz), float(yaw_rate),
                          float(roll_rate), float(mu), *self.method, out_p, out_w)
        if self.table_raise and out_w[_W["fallbacks"]] > 0:
            self._raise_outside(out_w[None, None], side=side, pose=(y, yaw))
        return n

    def _raise_outside(self, OW, side=None, pose=None):
        """The table law met a contact outside its domain: refuse, as the law is configured."""
        where = ""
        if side is None:
            hit = np.argwhere(OW[..., _W["fallbacks"]] > 0)[0]
            side = SIDES[int(hit[-1])]
            if OW.ndim == 3:
                where = f" of wheelset {int(hit[0])}"
        at = "" if pose is None else f" at y = {pose[0]!r} m, yaw = {pose[1]!r} rad"
        raise InputError(
            f"the table law met a contact outside its domain on the {side} wheel{where}{at} "
            "(a/b or spin beyond the table, e.g. a flange contact); configure "
            "wr.tangential.Table(outside='fastsim') to compute such points with FASTSIM")


class GenericContact:
    """Any configured normal × tangential method through the library (milliseconds per wheel).

    The wheel problem at the wheel's touching pose (roll and yaw of the wheelset,
    lateral shift relative to the rail) with the vertical approach of the current
    pose, as :func:`wheelrail.solve` with ``z=``; creep forces on the patches by the
    law's ``solve_patches``.
    """

    kind = "generic"

    def __init__(self, wheelset, track, material, normal, tangential, *, tolerance=5e-4):
        self.wheelset, self.track = wheelset, track
        self.normal, self.tangential = normal, tangential
        self.material = material
        self.tolerance = float(tolerance)

    def wheel(self, side, y, zc, roll, yaw, V, omega, vy, vz, yaw_rate, roll_rate, mu,
              out_p, out_w):
        out_p[:] = 0.0
        out_w[:] = 0.0
        ws, tr = self.wheelset, self.track
        r0 = ws.nominal_radius
        z = float(zc) - r0
        zt, beside = touching_heights(ws, tr, np.array([float(y)]), np.array([float(roll)]),
                                      np.array([float(yaw)]))
        if beside[side][0]:
            out_w[_W["min_gap"]] = 1.0
            return 0
        z_touch = float(zt[side][0])
        dz = z_touch - z
        out_w[_W["min_gap"]] = -dz
        if not dz > 0:
            return 0
        sig = _SIGMA[side]
        with disabled():
            pos = WheelRailPosition(ws, tr, y=float(y), yaw=float(yaw), roll=float(roll), z=z,
                                    material=self.material, tolerance=self.tolerance)
            prob = wheel_problem(pos, side, float(roll), z_touch)
            patches, info = self.normal.from_wheel(prob)
            motion = Motion(speed=float(V), omega=float(omega), lateral_velocity=float(vy),
                            vertical_velocity=float(vz), yaw_rate=float(yaw_rate),
                            roll_rate=float(roll_rate))
            zct = r0 + z_touch
            cr = [_creepage_at(p.frame, sig, motion, float(omega), pos, float(roll), zct, None)
                  for p in patches]
            forces = self.tangential.solve_patches(patches, cr, float(mu))
        out_w[_W["vertical_approach"]] = float(info["vertical_approach"])
        rows = []
        for p, c, f in zip(patches, cr, forces):
            fr = p.frame
            g = fr.contact_angle
            Fn, Fx, Fs, Mz = float(p.Fn), float(f.Fx), float(f.Fy), float(f.Mz)
            row = np.zeros(len(PATCH_FIELDS))
            row[[_P[k] for k in ("Fn", "Fx", "Fs", "Mz", "contact_angle", "track_y", "track_z",
                                 "x", "wheel_y", "rail_y", "a", "b", "xi", "eta", "phi",
                                 "rolling_radius")]] = (
                Fn, Fx, Fs, Mz, g, fr.track_y, fr.track_z, fr.x, fr.wheel_y, fr.rail_y,
                float(p.a), float(p.b), *c, fr.rolling_radius)
            row[_P["p_max"]] = float(getattr(p, "p_max", 0.0) or 0.0)
            row[_P["penetration"]] = float(p.penetration or 0.0)
            rows.append((row, p))
        rows.sort(key=lambda r: -r[0][0])
        ct = math.cos(roll)
        sp = math.sin(yaw)
        e = ws.e_tape
        Q = np.zeros(10)
        F = np.zeros(3)
        a_w = Fn_w = 0.0
        for k, (row, _) in enumerate(rows):
            Fn, Fx, Fs, Mz, g = row[0], row[1], row[2], row[3], row[4]
            cg, sgm = math.cos(g), math.sin(g)
            Fyn, Fzn = -sig * Fn * sgm, Fn * cg
            Fyt, Fzt = Fs * cg, sig * Fs * sgm
            row[_P["Fy_track"]] = Fyn + Fyt
            row[_P["Fz_track"]] = Fzn + Fzt
            ddx = row[_P["x"]] - sig * (e + row[_P["wheel_y"]]) * ct * sp
            ddy = row[_P["track_y"]] - y
            ddz = row[_P["track_z"]] - (r0 + z_touch)
            Q += (Fyn, Fzn, ddy * Fzn - ddz * Fyn, ddx * Fyn, -ddx * Fzn,
                  Fyt, Fzt, ddy * Fzt - ddz * Fyt, ddx * Fyt - ddy * Fx + cg * Mz,
                  ddz * Fx - ddx * Fzt - sig * sgm * Mz)
            F += (Fx, Fyn + Fyt, Fzn + Fzt)
            a_w += Fn * row[_P["a"]]
            Fn_w += Fn
            if k < out_p.shape[0]:
                out_p[k] = row
        out_w[1:11] = Q
        out_w[11:14] = F
        out_w[_W["patches"]] = min(len(rows), out_p.shape[0])
        out_w[_W["a_mean"]] = a_w / Fn_w if Fn_w > 0 else 0.0
        return len(rows)


def _generic_wheel_time(generic):
    """CPU time [s] of one generic evaluation of a wheel: the centred wheelset pressed 30 µm
    into its rails (the larger of the two wheels' times)."""
    ws, tr = generic.wheelset, generic.track
    r0 = ws.nominal_radius
    zt, _ = touching_heights(ws, tr, np.zeros(1), np.zeros(1), np.zeros(1))
    out_p = np.zeros((KMAX, len(PATCH_FIELDS)))
    out_w = np.zeros(len(WHEEL_FIELDS))
    worst = 0.0
    for side in SIDES:
        zc = r0 + float(zt[side][0]) - 3e-5
        t0 = time.process_time()
        try:
            generic.wheel(side, 0.0, zc, 0.0, 0.0, 10.0, 10.0 / r0, 0.0, 0.0, 0.0, 0.0, 0.3,
                          out_p, out_w)
        except Exception:  # noqa: BLE001 - only an estimate; the run reports its own errors
            return math.nan
        worst = max(worst, time.process_time() - t0)
    return worst


def _warn_slow(generic, nimpl, timpl, why):
    """Say once, when the generic path is chosen for lack of a compiled one, what it costs."""
    t = _generic_wheel_time(generic)
    cost = ("" if not math.isfinite(t) else
            f"; one wheel costs about {t * 1e3:.3g} ms per evaluation here (measured on a "
            f"centred wheelset) against about {COMPILED_WHEEL_TIME * 1e3:.2g} ms compiled "
            f"(~{t / COMPILED_WHEEL_TIME:.0f}x)")
    warnings.warn(
        f"contact pair normal={nimpl.name!r}, tangential={timpl.name!r} has no compiled "
        f"contact path ({why}): every evaluation goes through the library{cost}. Compiled "
        "pairs: normal 'hertz' or 'kik-piotrowski' with tangential 'fastsim', 'table' or "
        "'linear'; pass contact='generic' to choose this path without this warning",
        SlowContactWarning, stacklevel=3)


#: Nodes of Kik–Piotrowski's separation line (40 mm) when the dynamics is given the method
#: by name: 0.2 mm apart (the library's default 1601: 0.025 mm). On Manchester A-2.2 and
#: at flange contacts of S1002 on 60E1 the forces differ from the 6401-node line by at
#: most 0.4 % of μQ in Fn and 0.2 % in Fx, Fs (0.02 % with 1601 nodes), at a third of
#: the cost of the wheel's contact (benchmarks/bench_vehicle_speed.py).
LINE_NODES = 201


def configured_methods(normal, tangential, options=None):
    """The configured normal and tangential methods from names or objects and options.

    Kik–Piotrowski given by name gets the dynamics' line of :data:`LINE_NODES` nodes
    unless ``line_nodes`` is among the options (an object is used as it is).

    Each option goes to the one method that declares it (as :func:`wheelrail.solve`:
    ``normal="kik-piotrowski", tangential="fastsim", nx=20`` is
    ``tangential=wr.tangential.Fastsim(nx=20)``); an option declared by neither or
    both is an :class:`~wheelrail.errors.InputError` naming both methods' options.
    """
    ncls = normal_family.get_class(normal)
    nopts, topts = split_options(ncls, tangential_family.get_class(tangential),
                                 dict(options or {}))
    if isinstance(normal, str) and ncls is KikPiotrowski and "line_nodes" not in nopts:
        nopts["line_nodes"] = LINE_NODES         # the dynamics' default line (see there)
    return normal_family.get(normal, nopts), tangential_family.get(tangential, topts)


def contact_model(wheelset, track, material, normal="kik-piotrowski", tangential="fastsim", *,
                  contact="auto", method_options=None, **options):
    """The contact evaluator for configured methods (:class:`FastContact` or :class:`GenericContact`).

    Parameters
    ----------
    normal, tangential : str or configured method
        Names or configured objects (``wr.normal.KikPiotrowski()``, ``wr.tangential.Table()``).
    contact : {"auto", "fast", "generic"}
        ``"auto"``: the compiled path where it supports the methods, else the generic one.
    method_options : dict or None
        Options of the two methods (:func:`configured_methods`).
    **options
        Options of :class:`FastContact` (``search_step``, ``line_half_width``, ...); the
        generic path takes ``tolerance`` only (``connected`` concerns the compiled
        multi-Hertz search and is not passed on).
    """
    nimpl, timpl = configured_methods(normal, tangential, method_options)
    if contact not in ("auto", "fast", "generic"):
        raise InputError(f"contact must be 'auto', 'fast' or 'generic', got {contact!r}")
    why = _fast_support(nimpl, timpl)
    if contact == "generic" or (contact == "auto" and why):
        tol = options.get("tolerance", 5e-4)
        generic = GenericContact(wheelset, track, material, nimpl, timpl, tolerance=tol)
        if contact == "auto":
            _warn_slow(generic, nimpl, timpl, why)
        return generic
    return FastContact(wheelset, track, material, nimpl, timpl, **options)
