"""Multi-Hertzian normal contact: a non-elliptic contact as a set of Hertz ellipses.

Three variants (Piotrowski & Chollet (2005) §2), chosen with ``variant=``:

``"sauvage"`` / ``"sauvage-half"``
    Sauvage's secondary ellipses (§2.1, fig. 2). On the lateral line of each
    contact plane the profiles are interpenetrated by h1 = δ (Sauvage) or
    h1 = δ/2 (``"sauvage-half"``, the later recommendation); the Hertzian
    interpenetration section of the first ellipse, the parabola
    h1 − B1 (η − η1)² with the local curvatures A1, B1, is subtracted; where
    the rest still interpenetrates a further ellipse appears with depth h_k at
    the deepest point, and so on (at most ``max_ellipses``). Ellipse k has the
    local Hertz curvatures A_k, B_k of the profiles there and the approach
    δ_k = h_k δ / h1; its load follows from δ ∝ N^(2/3) (eq. 1),
    N_k = (δ_k / δ_1(A_k, B_k))^(3/2) with δ_1 the approach under unit load.
    The approach of the wheel carries the vertical load Σ N_k cos γ_k = Q.
``"pascal"``
    Pascal's equivalent ellipse (§2.2, eq. 2): the ellipses of
    ``"sauvage-half"`` in one contact plane are replaced by one ellipse with
    (a/b)_eq = Σ N_k (a_k/b_k) / Σ N_k, the total area and the total load, at
    the load-weighted position. (Pascal fitted the ellipse to wheelset
    equilibrium forces; the weighted ratio is the rule quoted by Piotrowski & Chollet (2005).)
``"ayasse"``
    Ayasse's contact-angle-function (CAF) method (§2.3, eq. 3): the two
    lowest candidate contact points of a wheel (contact angles γ1, γ2) share
    the load across the jump of the contact point; the overlap widths are
    Δt_i = cos γ_i d_i / tan(γ2 − γ1) with d_i = δ_i/2, δ_i the Hertz
    approach of point i under the wheel's load, and the load moves linearly
    across the overlap. For one pose the lateral distance to the jump limit
    is s·cos γ/tan(γ2 − γ1) (s the rigid gap of the point not in contact), so
    the share of point 2 is w2 = cos γ1 (d1 − s2) / (cos γ1 d1 + cos γ2 d2)
    (point 1 touching) or (cos γ2 s1 + cos γ1 d1)/(cos γ1 d1 + cos γ2 d2)
    (point 2 touching), clipped to [0, 1]; tan(γ2 − γ1) cancels, so the
    small-jump limit γ2 → γ1 is regular here. The vertical load is
    prescribed (a prescribed approach is rejected).

    With ``caf="table"`` (the default) the wheel–rail path reads Ayasse's
    precomputed piecewise-linear CAF tables instead (§2.3.2,
    :mod:`wheelrail.normal.caf`): built once per wheelset/track pair and side
    (:func:`~wheelrail.normal.caf.cached_caf_table`, lateral shifts
    ``caf_range``, lines within ``caf_tolerance`` of the sampled γ), they give
    at the position's shift t_y the contact angle, the contact point, the rail
    radius and the wheel radius (from the CAF slope) of the rigid contact's
    line; within the overlap [t_ylim − Δt_y1, t_ylim + Δt_y2] of a jump
    (eq. 3 on side i, where contact i is the rigid one, with δ_i the Hertz
    approach of contact i under the wheel load at the jump limit; by default
    with the angle difference following the lines' slopes, ``caf_overlap``)
    the load moves linearly from one contact to the other
    (:func:`~wheelrail.normal.caf.caf_contacts`). As in Piotrowski & Chollet (2005, §2.3.1) the
    roll and yaw of the wheelset are neglected in the table (the contact
    geometry is that of a pure translation). ``caf="direct"`` keeps the
    per-pose form above (the candidate points of the actual pose).

On a single Hertzian contact every variant gives its Hertz ellipse.

References
----------
.. [1] J. Piotrowski, H. Chollet, VSD 43 (2005), §2, eqs. (1)–(3).
.. [2] J.P. Pascal, G. Sauvage, The available methods to calculate the
   wheel/rail forces in non Hertzian contact patches and rail damaging, VSD 22
   (1993) 263–275.
.. [3] J.B. Ayasse, H. Chollet, J.L. Maupu, Paramètres caractéristiques du
   contact roue-rail, Rapport INRETS 225 (2000).
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import ConvergenceError, InputError, NoContactError
from ..geometry.contact_search import _SIGMA, silhouette
from ..hertzian import HertzContact, hertz, hertz_from_penetration, hertz_from_semiaxes
from ..materials import as_material_pair
from ..options import configured, option
from ..patch import ContactFrame, ContactPatch
from ..plausibility import disabled
from ._base import NormalMethod, PatchDescription
from ._gap import _check_search, _minimum
from ._strips import Line, VirtualPenetration, hertz_shape
from .caf import cached_caf_table, caf_contacts
from .stripes import _smoothed_B

__all__ = ["MultiHertz", "sauvage_ellipses"]

VARIANTS = ("pascal", "sauvage", "sauvage-half", "ayasse")
_MIN_DEPTH = 0.005       # a further ellipse needs h_k > 0.5 % of h1


def sauvage_ellipses(eta, f, Ax, Bx, h1_factor, delta, max_ellipses=7):
    """Sauvage's successive ellipses on one lateral line (pure kernel).

    Parameters
    ----------
    eta, f, Ax, Bx : ndarray, shape (n,)
        Lateral nodes [m], profile separation [m], longitudinal and (smoothed,
        positive) lateral curvature of the gap [1/m].
    h1_factor : float
        h1/δ: 1 (Sauvage) or 0.5.
    delta : float
        Approach [m] along the line's normal.

    Returns
    -------
    list of (index, h_k, delta_k)
        Node of each ellipse's centre, its interpenetration depth and approach [m].
    """
    g = h1_factor * delta - f
    out = []
    caps = np.zeros_like(g)
    h1 = None
    for _ in range(max_ellipses):
        r = g - caps
        k = int(np.argmax(r))
        hk = float(r[k])
        if not hk > 0 or (h1 is not None and hk < _MIN_DEPTH * h1):
            break
        if h1 is None:
            h1 = hk
        out.append((k, hk, hk / h1_factor))
        caps = caps + np.clip(hk - Bx[k] * (eta - eta[k]) ** 2, 0.0, None)
    return out


def _caf_range(name, value):
    """The ``caf_range`` option: (start, stop) [m], start < stop, as a tuple of floats."""
    try:
        lo, hi = (float(v) for v in value)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be (start, stop) in m, got {value!r}") from None
    if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
        raise InputError(f"{name} must be (start, stop) in m with start < stop, got {value!r}")
    return (lo, hi)


@configured
class MultiHertz(VirtualPenetration, NormalMethod, PatchDescription):
    """Multi-Hertzian methods (Sauvage, Pascal, Ayasse); see the module docstring.

    Other Parameters
    ----------------
    variant : {"pascal", "sauvage", "sauvage-half", "ayasse"}, default "pascal"
    max_ellipses : int, default 7
        Most ellipses per contact plane (Sauvage's code used seven).
    strips, cells : int, default 40, 40
        Patch description of every ellipse.
    caf : {"table", "direct"}, default "table"
        Variant ``"ayasse"`` on a wheel: precomputed CAF tables or the
        candidate points of the pose.
    caf_range : (float, float), default (-0.02, 0.02)
        Lateral shifts covered by the CAF tables [m].
    caf_tolerance : float, default 2e-4
        Largest deviation of the CAF lines from the sampled contact angle [rad].
    caf_overlap : {"general", "eq3"}, default "general"
        Overlap widths at a jump of the CAF tables: eq. (3) with the angle
        difference following the two lines' slopes (finite for small jumps;
        :func:`~wheelrail.normal.caf.jump_overlap`), or eq. (3) as printed.
    """

    name = "multi-hertz"
    references = (
        "J. Piotrowski, H. Chollet, Wheel-rail contact models for vehicle system dynamics "
        "including multi-point contact, Vehicle System Dynamics 43 (2005) 455-483.",
        "J.P. Pascal, G. Sauvage, The available methods to calculate the wheel/rail forces "
        "in non Hertzian contact patches and rail damaging, Vehicle System Dynamics 22 "
        "(1993) 263-275.",
        "J.B. Ayasse, H. Chollet, J.L. Maupu, Parametres caracteristiques du contact "
        "roue-rail, Rapport INRETS 225, 2000.",
    )
    variant: str = option("pascal", choices=VARIANTS, doc="multi-Hertzian variant")
    max_ellipses: int = option(7, lo=1, hi=20, doc="most ellipses per contact plane")
    caf: str = option("table", choices=("table", "direct"),
                      doc="variant 'ayasse' on a wheel: CAF tables or the pose's points")
    caf_range: tuple = option((-0.02, 0.02), kind="any", unit="m", check=_caf_range,
                              doc="lateral shifts (start, stop) covered by the CAF tables")
    caf_tolerance: float = option(2e-4, lo=0.0, lo_open=True, unit="rad",
                                  doc="largest deviation of the CAF lines from the contact angle")
    caf_overlap: str = option("general", choices=("general", "eq3"),
                              doc="overlap widths at a jump of the CAF tables")

    @staticmethod
    def _variant(opts):
        v = opts["variant"]
        if v not in VARIANTS:
            raise InputError(f"variant must be one of {', '.join(VARIANTS)}, got {v!r}")
        return v

    # ------------------------------------------------------------------ contact
    def from_contact(self, contact):
        opts = self.option_values()

        self._variant(opts)
        return (ContactPatch.from_hertz(contact, strips=opts["strips"],
                                        cells=opts["cells"], method=self.name),)

    # ------------------------------------------------------------------ lines
    def _curv(self, line):
        if "Bx" not in line.extra:
            Bs = _smoothed_B(line.eta, line.f, 1e-3)
            floor = 0.05 * line.B if line.B > 0 else 0.05 * float(np.max(np.abs(Bs)) + 1e-12)
            line.extra["Bx"] = np.maximum(Bs, floor)
        return line.extra["Bx"]

    def _ellipses(self, line, delta, opts):
        """[(node, A, B, δ_k, N_k)] of one line at approach δ."""
        variant = self._variant(opts)
        c = 1.0 if variant == "sauvage" else 0.5
        Bx = self._curv(line)
        E_star = line.extra["E_star"]
        out = []
        for k, hk, dk in sauvage_ellipses(line.eta, line.f, line.Ax, Bx, c, delta,
                                          int(opts["max_ellipses"])):
            A, B = float(line.Ax[k]), float(Bx[k])
            _, _, _, d1 = hertz_shape(A, B)
            d1 = d1 / E_star ** (2.0 / 3.0)          # approach of a unit load [m/N^(2/3)]
            out.append((k, A, B, dk, (dk / d1) ** 1.5))
        return out

    def _solve_line(self, line, delta, opts):        # used for the load iteration only
        class _R:                                    # minimal region: the load
            def __init__(self, N):
                self.N = N
        return [_R(e[4]) for e in self._ellipses(line, delta, opts)]

    def _hertz_patches(self, line, delta, opts, pair, frame_of):
        variant = self._variant(opts)
        ell = self._ellipses(line, delta, opts)
        strips, cells = int(opts["strips"]), int(opts["cells"])
        if variant == "pascal" and len(ell) > 1:
            hcs = [hertz_from_penetration(e[3], e[1], e[2], pair) for e in ell]
            N = np.array([e[4] for e in ell])
            ratio = float(np.sum(N * [float(h.a / h.b) for h in hcs]) / N.sum())   # eq. (2)
            area = float(sum(float(h.area) for h in hcs))
            a = math.sqrt(area * ratio / math.pi)
            b = math.sqrt(area / (ratio * math.pi))
            hc = hertz_from_semiaxes(a, b, float(N.sum()), pair)
            eta_c = float(np.sum(N * line.eta[[e[0] for e in ell]]) / N.sum())
            p = ContactPatch.from_hertz(hc, strips=strips, cells=cells,
                                        frame=frame_of(eta_c), method=self.name)
            p.info.update({"variant": variant, "ellipses": len(ell)})
            return [p]
        out = []
        for i, e in enumerate(ell):
            # the secondary ellipses may carry a few N by design (depth down to 0.5 % of
            # the first's): the plausibility checks of user input stay on the first only
            with _quiet(i > 0):
                hc = hertz_from_penetration(e[3], e[1], e[2], pair)
            p = ContactPatch.from_hertz(hc, strips=strips, cells=cells,
                                        frame=frame_of(float(line.eta[e[0]])), method=self.name)
            p.info.update({"variant": variant})
            out.append(p)
        return out

    # ------------------------------------------------------------------ gap
    def from_gap(self, problem):
        opts = self.option_values()
        if self._variant(opts) == "ayasse":
            raise InputError("variant 'ayasse' works on the candidate contact points of a "
                             "wheel on its rail (its contact-angle function); use it with a "
                             "WheelRailPosition, or variant='pascal'/'sauvage' for a gap")

        search = _check_search(problem.search)
        pair = as_material_pair(problem.materials)
        xm, ym, hmin, _ = _minimum(problem.gap, search)
        eta, f, Ax = self._gap_line(problem, (xm, ym, hmin),
                                    (search[2] - ym, search[3] - ym), 1601, 1e-3)

        j = int(np.argmin(f))
        Bx0 = (f[j + 1] + f[j - 1] - 2 * f[j]) / (2 * (eta[1] - eta[0]) ** 2)
        line = Line(eta, f, Ax, float(Ax[j]), float(Bx0), ref=j,
                    extra={"E_star": pair.E_star, "materials": pair})
        if problem.penetration is not None:
            delta = float(problem.penetration) - hmin
            if not delta > 0:
                raise NoContactError(f"no contact: the penetration {problem.penetration!r} m "
                                     f"does not exceed the smallest gap {hmin!r} m")
        else:
            _, _, _, d1 = hertz_shape(line.A, line.B)
            start = d1 * (float(problem.Fn) / pair.E_star) ** (2 / 3)
            delta = self._iterate(lambda d: self._line_load(line, d, opts)[1],
                                  float(problem.Fn), start, "multi-hertz")
        patches = self._hertz_patches(line, delta, opts, pair, lambda e: None)
        if problem.Fn is not None:
            patches = _scale_patches(patches, float(problem.Fn) / sum(p.Fn for p in patches),
                                     pair)
        return tuple(patches)

    # ------------------------------------------------------------------ wheel
    def from_wheel(self, problem):
        opts = self.option_values()

        variant = self._variant(opts)
        if variant == "ayasse":
            return self._ayasse(problem, opts)
        pair = as_material_pair(problem.materials)
        lines = self._wheel_lines(problem)

        def total(dz):
            Fz = 0.0
            for line in lines:
                ell = self._ellipses(line, dz * line.cos, opts)
                if not ell:
                    continue
                N = np.array([e[4] for e in ell])
                eta = line.eta[[e[0] for e in ell]]
                if variant == "pascal":     # one ellipse at the load-weighted position
                    eta = np.array([float(np.sum(N * eta) / N.sum())])
                    N = np.array([N.sum()])
                Fz += float(np.sum(N * np.cos(np.interp(eta, line.eta, line.angle))))
            return Fz

        if problem.vertical_approach is not None:
            dz = float(problem.vertical_approach)
        else:
            Q = float(problem.vertical_load)
            l0 = lines[0]
            _, _, _, d1 = hertz_shape(max(l0.A, 1e-6), max(l0.B, 1e-6))
            start = (float(np.min(l0.f)) + d1 * (Q / pair.E_star) ** (2 / 3)) / l0.cos
            dz, jump = self._approach_for_load(total, Q, max(start, 1e-7), problem.side)
        patches = []
        for line in lines:
            patches += self._hertz_patches(line, dz * line.cos, opts, pair,
                                           lambda e, line=line: problem.frame_at(
                                               line.ref, e,
                                               separation=line.extra.get("separation")))
        if not patches:
            raise NoContactError(f"{problem.side} wheel: no contact at the approach {dz!r} m")
        info = {"vertical_approach": float(dz), "variant": variant}
        if problem.vertical_load is not None:
            Fz = sum(p.Fn * math.cos(p.frame.contact_angle) for p in patches)
            limit = 1e-3 if jump is None else 1e-3 + abs(jump[1] - jump[0]) / float(Fz)
            patches = _scale_patches(patches, float(problem.vertical_load) / Fz, pair, limit)
            if jump is not None:
                info["load_jump"] = jump
        sig = 1.0 if problem.side == "right" else -1.0
        patches.sort(key=lambda p: -sig * p.frame.track_y)
        return tuple(patches), info

    def _approach_for_load(self, total, Q, start, side):
        """Approach [m] at which the ellipses carry the vertical load ``Q`` [N].

        Returns ``(dz, None)``, or ``(dz, (F_below, F_above))`` where the
        method's load jumps over ``Q`` at one approach: the greedy choice of
        ellipses (each next one at the largest remaining interpenetration)
        changes there, so no approach carries ``Q`` exactly; the side whose
        load is nearer ``Q`` is returned and its ellipses are scaled to ``Q``
        by the caller (``info["load_jump"]`` gives both loads).
        """
        evals = []

        def recorded(dz):
            F = total(dz)
            evals.append((dz, F))
            return F

        try:
            return self._iterate(recorded, Q, start, f"{side} wheel, multi-hertz"), None
        except ConvergenceError:
            below = [e for e in evals if e[1] < Q]
            above = [e for e in evals if e[1] >= Q]
            if not below or not above:
                raise
            lo, hi = max(below), min(above)
            if not 0.0 <= hi[0] - lo[0] <= 1e-9 * hi[0]:
                raise
            best = min((lo, hi), key=lambda e: abs(e[1] - Q))
            return best[0], (float(lo[1]), float(hi[1]))

    @staticmethod
    def _uses_tables(opts):
        """True when the options select variant "ayasse" with the CAF tables."""
        caf = opts["caf"]
        if caf not in ("table", "direct"):
            raise InputError(f"caf must be 'table' or 'direct', got {caf!r}")
        return opts["variant"] == "ayasse" and caf == "table"

    @staticmethod
    def _lead(problem, wheel_y):
        """Longitudinal offset [m] of the wheel point ``wheel_y`` on the contact locus at the
        pose (yaw, roll) of ``problem`` (:func:`~wheelrail.geometry.contact_search.silhouette`):
        under yaw a contact point on a sloped part of the wheel lies ahead of or behind the
        wheel centre, which changes its creepages; 0 without yaw."""
        pose = problem.pose
        if pose["yaw"] == 0.0:
            return 0.0

        ws = problem.wheelset
        s = np.array([float(wheel_y)])
        p, p1 = ws.curve(problem.side).eval(s, 1)
        x, _, _, _ = silhouette(s, p, p1, ws.nominal_radius, ws.e_tape, _SIGMA[problem.side],
                                np.float64(pose["y"]), np.float64(ws.nominal_radius + pose["z"]),
                                np.float64(pose["roll"]), np.float64(pose["yaw"]))
        return float(x[0])

    def _ayasse_table(self, problem, opts):
        if problem.vertical_load is None:
            raise InputError("variant 'ayasse' needs the vertical load of the wheel (the CAF "
                             "overlap depends on it); got a prescribed approach")
        rng = opts["caf_range"]
        try:
            lo, hi = (float(v) for v in rng)
        except (TypeError, ValueError):
            raise InputError(f"caf_range must be (start, stop) in m, got {rng!r}") from None
        # the relative lateral translation of the profiles at rail level: the wheelset's
        # shift plus the lateral displacement r0 sin θ of the wheel's running surface by the
        # roll θ (the rotation of the profile itself is neglected §2.3.1)
        ty = float(problem.pose["y"]) + float(problem.wheelset.nominal_radius) * math.sin(
            float(problem.pose["roll"]))
        if not lo <= ty <= hi:
            raise InputError(f"y = {ty!r} m (lateral shift of the profiles, roll included) "
                             f"lies outside the CAF table range caf_range = {rng!r} m; widen "
                             "caf_range or use caf='direct'")
        table = cached_caf_table(problem.wheelset, problem.track, problem.side, (lo, hi),
                                 tolerance=float(opts["caf_tolerance"]))
        pair = as_material_pair(problem.materials)
        Q = float(problem.vertical_load)
        contacts = caf_contacts(table, ty, Q, pair, overlap=opts["caf_overlap"])
        extra_A = 0.0 if problem.roller_radius is None else 0.5 / problem.roller_radius
        N = Q / sum(w * math.cos(ln["gamma"]) for w, ln, _ in contacts)
        rigid = table.branch_of(ty)
        patches, dz = [], 0.0
        for w, ln, br in contacts:
            A, B = ln["A"] + extra_A, ln["B"]
            if not (A > 0 and B > 0):
                raise InputError(f"{problem.side} wheel at y = {ty!r} m: the CAF line gives "
                                 f"A = {A!r}, B = {B!r} 1/m (not convex); the CAF method cannot "
                                 "represent this contact")
            hc = _hertz_fast(w * N, A, B, pair)
            frame = ContactFrame(problem.side, ln["wheel_y"], ln["rail_y"], ln["track_y"],
                                 ln["track_z"], self._lead(problem, ln["wheel_y"]), ln["gamma"],
                                 ln["rolling_radius"])
            p = ContactPatch.from_hertz(hc, strips=int(opts["strips"]),
                                        cells=int(opts["cells"]), frame=frame,
                                        method=self.name)
            p.info.update({"variant": "ayasse", "share": w, "caf": "table"})
            patches.append(p)
            if br == rigid:     # the rigid contact point: its approach is the wheel's
                dz = float(hc.penetration) / math.cos(ln["gamma"])
        sig = 1.0 if problem.side == "right" else -1.0
        patches.sort(key=lambda p: -sig * p.frame.track_y)
        return tuple(patches), {"vertical_approach": float(dz), "variant": "ayasse", "caf": "table"}

    def _ayasse(self, problem, opts):
        if self._uses_tables(opts):
            return self._ayasse_table(problem, opts)

        if problem.vertical_load is None:
            raise InputError("variant 'ayasse' needs the vertical load of the wheel (the CAF "
                             "overlap depends on it); got a prescribed approach")
        pair = as_material_pair(problem.materials)
        pts = problem.points
        A = np.asarray(problem.A, float)
        B = np.asarray(problem.B, float)
        cg = np.cos(np.asarray(pts.contact_angle, float))
        s = np.asarray(pts.separation, float) / cg          # vertical rigid gaps
        order = np.argsort(s, kind="stable")
        ok = [k for k in order if A[k] > 0 and B[k] > 0]
        if not ok:
            raise InputError(f"{problem.side} wheel: no convex candidate point (A = {A.tolist()}, "
                             f"B = {B.tolist()} 1/m); the CAF method cannot represent it")
        Q = float(problem.vertical_load)
        k1 = ok[0]
        shares = {k1: 1.0}
        if len(ok) > 1:
            k2 = ok[1]
            d = {}
            for k in (k1, k2):
                d[k] = 0.5 * float(hertz(Q / cg[k], A[k], B[k], pair).penetration) / cg[k]
            c1, c2 = cg[k1], cg[k2]
            den = c1 * d[k1] + c2 * d[k2]
            w2 = c1 * (d[k1] - (s[k2] - s[k1])) / den       # k1 touches rigidly (s1 <= s2)
            w2 = min(max(w2, 0.0), 1.0)
            if w2 > 0:
                shares = {k1: 1.0 - w2, k2: w2}
        N = Q / sum(w * cg[k] for k, w in shares.items())
        patches = []
        for k, w in shares.items():
            if w <= 0:
                continue
            hc = hertz(w * N, A[k], B[k], pair)
            p = ContactPatch.from_hertz(hc, strips=int(opts["strips"]),
                                        cells=int(opts["cells"]),
                                        frame=problem.frames[k], method=self.name)
            p.info.update({"variant": "ayasse", "share": w})
            patches.append(p)
        sig = 1.0 if problem.side == "right" else -1.0
        patches.sort(key=lambda p: -sig * p.frame.track_y)
        dz = (s[k1] * cg[k1] + float(patches[0].penetration)) / cg[k1]
        return tuple(patches), {"vertical_approach": float(dz), "variant": "ayasse"}


def _quiet(on):
    """No plausibility warnings inside the block when ``on`` (internal secondary ellipses)."""
    import contextlib


    return disabled() if on else contextlib.nullcontext()


def _hertz_fast(load, A, B, pair):
    """Hertz's solution for one contact from the interpolated unit-load solution
    (:func:`~wheelrail.normal._strips.hertz_shape`, relative error < 1e-5): a, b ∝
    (N/E*)^(1/3), δ ∝ (N/E*)^(2/3), p0 = 3N/(2πab) (Johnson 1985, eqs. 3.64–3.66)."""

    au, bu, _, du = hertz_shape(A, B)
    s = (load / pair.E_star) ** (1.0 / 3.0)
    a, b = au * s, bu * s
    return HertzContact(a, b, 1.5 * load / (math.pi * a * b), du * s * s, float(load),
                        float(A), float(B), pair)


def _scale_patches(patches, factor, pair, limit=1e-3):
    """Hertz patches rescaled to carry ``factor`` × their loads (load closure, |factor − 1|
    ≤ ``limit``)."""
    from dataclasses import replace


    if abs(factor - 1.0) > limit:
        raise InputError(f"multi-hertz: load closure factor {factor!r} is not within {limit!r} "
                         "of 1")
    out = []
    largest = max(range(len(patches)), key=lambda i: patches[i].Fn)
    for i, p in enumerate(patches):
        with _quiet(i != largest):
            hc = hertz(p.Fn * factor, float(p.hertz.A), float(p.hertz.B), pair)
        q = ContactPatch.from_hertz(hc, strips=p.y.size, cells=p.cells, frame=p.frame,
                                    method=p.method)
        out.append(replace(q, info=dict(p.info)))
    return out
