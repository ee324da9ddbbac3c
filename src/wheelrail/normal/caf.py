"""Ayasse's contact-angle-function (CAF) tables: piecewise-linear γ(t_y) with jump limits.

Seed 003 §2.3 (Piotrowski & Chollet 2005, after Ayasse): with the roll of the
wheelset neglected (§2.3.1) the relative motion of wheel and rail is a
translation (t_y, t_z), and the contact parameters of one wheel–rail pair can
be precomputed as functions of the lateral translation t_y alone (§2.3.2):

* the contact angle function γ(t_y) of the rigid contact point, piecewise
  linearised — "only a few lines are necessary to describe the function" —
  with the positions t_ylim where the contact point jumps between two
  contact areas;
* the rail radius R_rx as a series of constant values (one per line);
* the wheel radius is not stored: it follows from the slope of the CAF,
  ``R_rx + R_wx = −1/(cos γ dγ/dt_y)`` (§2.3.2; radii convex-positive),
  and with it the Hertz parameters;
* at a jump the overlap widths of eq. (3), ``Δt_y1 = cos γ1 δ1 /
  (2 tan(γ2 − γ1))`` (:func:`jump_overlap`), over which the load moves from
  one ellipse to the other.

:func:`caf_table` builds the table from the profiles (rigid touching height
of the translated wheel, :func:`~wheelrail.contact.wheelrail.touching_heights`
with zero roll and yaw; the rigid contact point is the candidate point of
smallest separation, :func:`~wheelrail.geometry.contact_search.find_points`).
All lengths in m, angles in rad, radii in m.

The multi-Hertz variant ``"ayasse"`` (:mod:`wheelrail.normal.multi_hertz`)
reads these tables on the wheel–rail path: :func:`cached_caf_table` builds
one per wheelset/track pair and side, :func:`caf_contacts` gives the
contacts and their load shares at a lateral shift (eq. 3 overlaps). The
checks of the seed's relations are in ``tests/reference/test_nonhertz_caf.py``.

References
----------
.. [1] J. Piotrowski, H. Chollet, Wheel–rail contact models for vehicle system
   dynamics including multi-point contact, VSD 43 (2005) 455–483, §2.3,
   eq. (3) (seed 003).
.. [2] J.B. Ayasse, H. Chollet, J.L. Maupu, Paramètres caractéristiques du
   contact roue-rail, Rapport INRETS 225 (2000).
.. [3] D.H. Douglas, T.K. Peucker, Algorithms for the reduction of the number
   of points required to represent a digitized line, Cartographica 10 (1973)
   112–122 (the line simplification used for the piecewise linearisation).
"""

from __future__ import annotations

import math
from collections import OrderedDict
from dataclasses import dataclass

import numpy as np

from .._validation import positive
from ..errors import InputError

__all__ = ["CafTable", "caf_table", "cached_caf_table", "caf_contacts", "jump_overlap"]


def jump_overlap(gamma1, gamma2, delta1):
    """Overlap width of a jump on side 1 (seed 003 eq. 3, large jumps).

    Δt_y1 = cos γ1 · (δ1/2) / tan(γ2 − γ1): the lateral distance from the jump
    limit over which contact 1, pressed by its Hertz approach δ1, still
    carries load while the contact point has rigidly moved to zone 2
    (interpenetration d1 = δ1/2).

    Parameters
    ----------
    gamma1, gamma2 : array_like
        Contact angles on both sides of the jump [rad] (γ2 ≠ γ1).
    delta1 : array_like
        Hertz approach of contact 1 under its load [m], ≥ 0.

    Returns
    -------
    ndarray
        Δt_y1 [m], ≥ 0.

    Raises
    ------
    InputError
        γ2 = γ1 (eq. 3 is for large jumps; the small-jump limit diverges).
    """
    g1, g2, d1 = (np.asarray(v, dtype=float) for v in (gamma1, gamma2, delta1))
    dg = np.abs(g2 - g1)
    if np.any(dg == 0.0):
        raise InputError(f"jump_overlap: gamma2 must differ from gamma1 (got {g1!r}, {g2!r}); "
                         "eq. (3) is the large-jump form")
    if np.any(d1 < 0):
        raise InputError(f"jump_overlap: delta1 must be >= 0, got {d1!r}")
    return np.cos(g1) * 0.5 * d1 / np.tan(dg)


def _simplify(x, y, tol):
    """Indices of a Douglas–Peucker simplification of (x, y) with |Δy| ≤ tol (vertical)."""
    keep = np.zeros(x.size, dtype=bool)
    keep[0] = keep[-1] = True
    stack = [(0, x.size - 1)]
    while stack:
        i, j = stack.pop()
        if j <= i + 1:
            continue
        t = (x[i + 1:j] - x[i]) / (x[j] - x[i])
        err = np.abs(y[i + 1:j] - (y[i] + t * (y[j] - y[i])))
        k = int(np.argmax(err))
        if err[k] > tol:
            m = i + 1 + k
            keep[m] = True
            stack += [(i, m), (m, j)]
    return np.nonzero(keep)[0]


@dataclass(frozen=True)
class CafTable:
    """Piecewise-linear contact angle function of one wheel–rail pair (frozen).

    Attributes
    ----------
    side : str
    y : ndarray, shape (m,)
        Breakpoints: lateral wheelset shift t_y [m], increasing within a branch.
    gamma : ndarray, shape (m,)
        Contact angle at the breakpoints [rad].
    branch : ndarray of int, shape (m,)
        Continuous branch of each breakpoint (0, 1, …); a jump separates
        consecutive branches.
    jumps : ndarray, shape (branches − 1,)
        Jump limits t_ylim [m] (midway between the sampled shifts around the jump).
    rail_radius : ndarray, shape (m,)
        Rail profile radius R_rx of the line starting at each breakpoint [m]
        (convex positive; one constant value per line; the last breakpoint of
        a branch repeats its line's value).
    samples : int
        Number of sampled shifts the table was built from.
    tolerance : float
        Largest deviation of the lines from the sampled γ [rad].
    wheel_y, rail_y : ndarray, shape (m,)
        Contact point on the wheel and rail profiles at the breakpoints [m]
        (profile frames); linear between breakpoints (on a line of constant
        rail radius the rail point moves by R_rx dγ, linear in t_y).
    track_y, track_z : ndarray, shape (m,)
        Contact point in the track frame at the breakpoints [m].
    rolling_radius : ndarray, shape (m,)
        Wheel radius at the contact point [m] (for the longitudinal curvature
        A = cos γ / (2 r)); linear between breakpoints.
    """

    side: str
    y: np.ndarray
    gamma: np.ndarray
    branch: np.ndarray
    jumps: np.ndarray
    rail_radius: np.ndarray
    samples: int
    tolerance: float
    wheel_y: np.ndarray = None
    rail_y: np.ndarray = None
    track_y: np.ndarray = None
    track_z: np.ndarray = None
    rolling_radius: np.ndarray = None

    @property
    def _sigma(self):
        return 1.0 if self.side == "right" else -1.0

    def _locate(self, y):
        y = np.atleast_1d(np.asarray(y, dtype=float))
        br = np.searchsorted(self.jumps, y)            # branch of each query
        out_i = np.empty(y.size, dtype=int)
        for b in np.unique(br):
            sel = br == b
            idx = np.nonzero(self.branch == b)[0]
            k = np.clip(np.searchsorted(self.y[idx], y[sel]) - 1, 0, max(idx.size - 2, 0))
            out_i[sel] = idx[k]
        return y, out_i

    def contact_angle(self, y):
        """γ(t_y) [rad] and its slope dγ/dt_y [rad/m] at shifts ``y`` [m] (arrays)."""
        y, i = self._locate(y)
        j = np.minimum(i + 1, self.y.size - 1)
        same = self.branch[j] == self.branch[i]
        dy = np.where(same, self.y[j] - self.y[i], 1.0)
        slope = np.where(same, (self.gamma[j] - self.gamma[i]) / dy, 0.0)
        return self.gamma[i] + slope * (y - self.y[i]), slope

    def wheel_radius(self, y):
        """Wheel profile radius R_wx [m] recovered from the CAF (seed 003 §2.3.2).

        R_rx + R_wx = −1/(cos γ dγ/dt_y) (radii convex positive; a concave
        wheel profile gives R_wx < 0; infinite where the line is flat). The
        seed's relation is for a shift towards the wheel's flange; t_y is
        positive to the right, so for the left wheel the sign of dγ/dt_y is
        reversed: R_rx + R_wx = +1/(cos γ dγ/dt_y).
        """
        g, slope = self.contact_angle(y)
        _, i = self._locate(y)
        with np.errstate(divide="ignore"):
            total = -self._sigma / (np.cos(g) * slope)
        return total - self.rail_radius[i]

    def jump_angles(self, k):
        """(γ1, γ2) [rad]: both branches' lines extended to the jump limit ``k``."""
        t = float(self.jumps[k])
        i1 = np.nonzero(self.branch == k)[0][-2:]
        i2 = np.nonzero(self.branch == k + 1)[0][:2]

        def at(ii):
            if ii.size == 1:
                return float(self.gamma[ii[0]])
            y0, y1 = self.y[ii]
            g0, g1 = self.gamma[ii]
            return float(g0 + (g1 - g0) * (t - y0) / (y1 - y0))

        return at(i1), at(i2)

    def line(self, y, b):
        """Values of branch ``b``'s line through shift ``y`` [m] (extrapolated beyond the
        branch's ends, as on the far side of a jump inside an overlap).

        Returns a dict of floats: ``gamma`` [rad], ``slope`` dγ/dt_y [rad/m],
        ``rail_radius``, ``wheel_radius`` [m] (§2.3.2), ``A``, ``B`` [1/m] (Hertz
        curvatures ½ cos γ/r and ½(1/R_rx + 1/R_wx)), and the contact point
        ``wheel_y``, ``rail_y``, ``track_y``, ``track_z``, ``rolling_radius`` [m].
        """
        idx = np.nonzero(self.branch == b)[0]
        y = float(y)
        if idx.size == 1:
            i = j = int(idx[0])
            t = 0.0
        else:
            k = int(np.clip(np.searchsorted(self.y[idx], y) - 1, 0, idx.size - 2))
            i, j = int(idx[k]), int(idx[k + 1])
            t = (y - self.y[i]) / (self.y[j] - self.y[i])
        out = {}
        for name in ("gamma", "wheel_y", "rail_y", "track_y", "track_z", "rolling_radius"):
            v = getattr(self, name)
            out[name] = float(v[i] + t * (v[j] - v[i]))
        slope = 0.0 if i == j else float((self.gamma[j] - self.gamma[i]) / (self.y[j] - self.y[i]))
        rr = float(self.rail_radius[i])
        cg = math.cos(out["gamma"])
        total = math.inf if slope == 0.0 else -self._sigma / (cg * slope)
        rw = total - rr
        out.update(slope=slope, rail_radius=rr, wheel_radius=rw,
                   A=0.5 * cg / out["rolling_radius"],
                   B=0.5 * (1.0 / rr + (0.0 if math.isinf(rw) else 1.0 / rw)))
        return out

    def _jump_data(self, k):
        """(t_ylim, γ1, γ2, δ1_unit, δ2_unit) of jump ``k``, memoised: the Hertz approach
        of each side's contact at the jump limit is δ_unit (N/E*)^(2/3) [m] (N [N],
        E* [Pa]); None when a side is not convex (A or B ≤ 0) or γ1 = γ2."""
        memo = self.__dict__.setdefault("_memo", {})
        if k not in memo:
            from .hertz import hertz_kernel

            t_lim = float(self.jumps[k])
            l1, l2 = self.line(t_lim, k), self.line(t_lim, k + 1)
            if (min(l1["A"], l1["B"], l2["A"], l2["B"]) <= 0
                    or l1["gamma"] == l2["gamma"]):
                memo[k] = None
            else:
                u = [float(hertz_kernel(1.0, ln["A"], ln["B"], 1.0)[3]) for ln in (l1, l2)]
                memo[k] = (t_lim, l1["gamma"], l2["gamma"], u[0], u[1])
        return memo[k]

    def branch_of(self, y):
        """Branch (continuous part of the CAF) of the rigid contact point at shift ``y`` [m]."""
        return int(np.searchsorted(self.jumps, float(y)))

    def overlaps(self, k, delta1, delta2):
        """Overlap widths (Δt_y1, Δt_y2) [m] at jump ``k`` for the Hertz approaches δ1, δ2
        [m] of the two contacts (seed 003 eq. 3 on each side of the jump)."""
        g1, g2 = self.jump_angles(k)
        return (float(jump_overlap(g1, g2, delta1)), float(jump_overlap(g2, g1, delta2)))


def caf_table(wheelset, track, side="right", y=(-0.01, 0.01), *, step=5e-5, tolerance=1e-3,
              jump=1e-3):
    """Build the piecewise-linear CAF table of one side (seed 003 §2.3.2).

    Parameters
    ----------
    wheelset, track
        :class:`wheelrail.Wheelset`, :class:`wheelrail.Track` (nominal gauge).
    side : {"left", "right"}
    y : (float, float)
        Range of the lateral wheelset shift t_y [m].
    step : float
        Sampling step of t_y [m] (the jump limits are known to ± step/2).
    tolerance : float
        Largest deviation of the lines from the sampled γ(t_y) [rad].
    jump : float
        A change of the contact point's wheel coordinate larger than this
        between two samples is a jump [m].

    Returns
    -------
    CafTable
    """
    from ..contact.wheelrail import touching_heights
    from ..geometry._checks import check_side
    from ..geometry.contact_search import _Pose, find_points

    check_side(side)
    step = float(positive("step", step))
    tolerance = float(positive("tolerance", tolerance))
    jump = float(positive("jump", jump))
    lo, hi = (float(v) for v in y)
    if not hi > lo:
        raise InputError(f"y must be an increasing (start, stop) range, got {y!r}")
    n = int(math.floor((hi - lo) / step + 1e-9)) + 1
    if n < 3:
        raise InputError(f"step={step!r} leaves fewer than 3 samples in y={y!r}")
    ty = lo + step * np.arange(n)
    zero = np.zeros(n)
    z, beside = touching_heights(wheelset, track, ty, zero, zero)
    if np.any(beside[side]):
        bad = ty[beside[side]][0]
        raise InputError(f"y = {bad!r} m: the {side} wheel lies beside its rail; narrow the "
                         "range")
    data, _ = find_points(wheelset, track, side, _Pose(ty, z[side], zero, zero),
                          tolerance=1e-9)
    k = np.nanargmin(data["separation"], axis=1)
    r = np.arange(n)
    gam = data["contact_angle"][r, k]
    wy = data["wheel_y"][r, k]
    kr = data["rail_curvature_y"][r, k]
    cut = np.nonzero(np.abs(np.diff(wy)) > jump)[0]          # jump between cut and cut+1
    starts = np.concatenate(([0], cut + 1))
    stops = np.concatenate((cut + 1, [n]))
    ys, gs, brs, rr, kept = [], [], [], [], []
    for b, (i0, i1) in enumerate(zip(starts, stops)):
        seg_y, seg_g = ty[i0:i1], gam[i0:i1]
        keep = _simplify(seg_y, seg_g, tolerance) if seg_y.size > 1 else np.array([0])
        for a, c in zip(keep, np.r_[keep[1:], keep[-1]]):
            kk = kr[i0 + a:i0 + max(c, a + 1)]
            with np.errstate(divide="ignore"):
                rad = float(np.median(1.0 / kk)) if kk.size else float("inf")
            rr.append(rad)
        kept.append(i0 + keep)
        ys.append(seg_y[keep])
        gs.append(seg_g[keep])
        brs.append(np.full(keep.size, b))
    jumps = 0.5 * (ty[cut] + ty[cut + 1])
    kept = np.concatenate(kept)
    pts = {f: np.asarray(data[f][r, k][kept], dtype=float)
           for f in ("wheel_y", "rail_y", "track_y", "track_z", "rolling_radius")}
    return CafTable(side, np.concatenate(ys), np.concatenate(gs), np.concatenate(brs), jumps,
                    np.asarray(rr), n, tolerance, **pts)


_CACHE: OrderedDict = OrderedDict()
_CACHE_SIZE = 8


def cached_caf_table(wheelset, track, side, y=(-0.01, 0.01), *, step=5e-5, tolerance=2e-4,
                     jump=1e-3):
    """:func:`caf_table`, built once per wheelset, track and settings (LRU of 8 tables).

    The key is the identity of the ``wheelset`` and ``track`` objects (frozen,
    so their profiles cannot change) with the side and the table settings; a
    table is built once per wheel/rail profile pair and reused by every
    position of a run or sweep. Same parameters and result as :func:`caf_table`.
    """
    key = (id(wheelset), id(track), side, tuple(float(v) for v in y), float(step),
           float(tolerance), float(jump))
    hit = _CACHE.get(key)
    if hit is not None and hit[0] is wheelset and hit[1] is track:
        _CACHE.move_to_end(key)
        return hit[2]
    table = caf_table(wheelset, track, side, y, step=step, tolerance=tolerance, jump=jump)
    _CACHE[key] = (wheelset, track, table)     # the objects keep their ids alive
    while len(_CACHE) > _CACHE_SIZE:
        _CACHE.popitem(last=False)
    return table


def caf_contacts(table, t_y, load, materials):
    """Ayasse's contacts of one wheel at shift ``t_y`` from its CAF table (seed 003 §2.3).

    The rigid contact point lies on the branch of ``t_y``; near a jump limit
    t_ylim the two contacts of the neighbouring branches share the load over
    the overlap [t_ylim − Δt_y2, t_ylim + Δt_y1] of eq. (3) (δ_i the Hertz
    approach of contact i under the whole wheel load, at the jump limit: "the
    overlap is determined at the beginning of the jump as a function of the
    dynamic load", §2.3.3); the share of contact 2 rises linearly across the
    overlap ("the normal load varies quasi-linearly with the lateral
    displacement", fig. 8). Each contact's angle, rail radius, wheel radius
    (from the CAF slope) and point come from its branch's line (extended
    beyond the jump inside the overlap).

    Parameters
    ----------
    table : CafTable
    t_y : float
        Lateral shift of the wheelset [m], inside the table's range.
    load : float
        Vertical load Q of the wheel [N], > 0.
    materials : Material or MaterialPair

    Returns
    -------
    list of (float, dict, int)
        (share w_i, line values of :meth:`CafTable.line`, branch) of each
        contact (one, or two inside an overlap; Σ w_i = 1); the normal loads
        are N_i = w_i N with N = Q / Σ w_i cos γ_i.
    """
    from ..materials import as_material_pair

    E_star = float(as_material_pair(materials).E_star)
    t_y = float(t_y)
    b = table.branch_of(t_y)
    best = None
    for k in (b - 1, b):                 # the jumps at both ends of the branch
        if not 0 <= k < table.jumps.size:
            continue
        jd = table._jump_data(k)
        if jd is None:                   # a side of the jump is not convex: no overlap
            continue
        t_lim, g1, g2, u1, u2 = jd
        # Hertz approach of each contact under the whole wheel load, δ = δ_unit (N/E*)^(2/3)
        d1 = u1 * (load / math.cos(g1) / E_star) ** (2.0 / 3.0)
        d2 = u2 * (load / math.cos(g2) / E_star) ** (2.0 / 3.0)
        tg = math.tan(abs(g2 - g1))
        dt1 = math.cos(g1) * 0.5 * d1 / tg          # eq. (3), side 1
        dt2 = math.cos(g2) * 0.5 * d2 / tg          # eq. (3), side 2
        lo, hi = t_lim - dt2, t_lim + dt1
        if lo < t_y < hi and (best is None or abs(t_y - t_lim) < best[0]):
            best = (abs(t_y - t_lim), k, (t_y - lo) / (hi - lo))
    if best is None:
        return [(1.0, table.line(t_y, b), b)]
    _, k, w2 = best
    return [(1.0 - w2, table.line(t_y, k), k), (w2, table.line(t_y, k + 1), k + 1)]
