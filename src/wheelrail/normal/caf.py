"""Ayasse's contact-angle-function (CAF) tables: piecewise-linear γ(t_y) with jump limits.

Piotrowski & Chollet (2005) §2.3 (after Ayasse): with the roll of the
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
of the translated wheel, :func:`~wheelrail.geometry.touching.touching_heights`
with zero roll and yaw; the rigid contact point is the candidate point of
smallest separation, :func:`~wheelrail.geometry.contact_search.find_points`).
All lengths in m, angles in rad, radii in m.

The multi-Hertz variant ``"ayasse"`` (:mod:`wheelrail.normal.multi_hertz`)
reads these tables on the wheel–rail path: :func:`cached_caf_table` builds
one per wheelset/track pair and side, :func:`caf_contacts` gives the
contacts and their load shares at a lateral shift (eq. 3 overlaps). The
checks of Piotrowski & Chollet's relations are in ``tests/reference/test_nonhertz_caf.py``.

References
----------
.. [1] J. Piotrowski, H. Chollet, Wheel–rail contact models for vehicle system
   dynamics including multi-point contact, VSD 43 (2005) 455–483, §2.3,
   eq. (3).
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
from ..geometry._checks import check_side
from ..geometry.contact_search import _Pose, find_points
from ..geometry.touching import touching_heights
from ..hertzian import hertz_kernel
from ..materials import as_material_pair

__all__ = ["CafTable", "caf_table", "cached_caf_table", "caf_contacts", "jump_gap",
           "jump_overlap", "profile_jump_gaps"]


def _angle_growth(gamma1, gamma2, rate):
    """|γ2 − γ1| and the rate c at which it grows with the distance from the jump limit."""
    a0 = gamma2 - gamma1
    return np.abs(a0), np.where(a0 > 0, rate, np.where(a0 < 0, -rate, np.abs(rate)))


def jump_gap(gamma1, gamma2, tau, rate=0.0):
    """Rigid gap of contact 2 at the distance τ from a jump limit, on side 1 (CAF lines).

    On side 1 contact 1 touches rigidly; the other branch's surface lies at
    the gap (along contact 1's normal) ``∫₀^τ tan Δγ dτ' / cos γ1`` with
    Δγ(τ') = |γ2 − γ1| + c τ' the angle between the two branches' lines
    (``rate`` = d(γ2 − γ1)/dτ from their slopes, signed as γ2 − γ1); in
    closed form ``ln(cos Δγ(0) / cos Δγ(τ)) / (c cos γ1)``, and
    ``τ tan|γ2 − γ1| / cos γ1`` for straight lines (the gap behind eq. 3).
    This is the relation :func:`jump_overlap` inverts.

    Parameters
    ----------
    gamma1, gamma2 : array_like
        Contact angles of the two lines at the jump limit [rad].
    tau : array_like
        Lateral distance from the jump limit into side 1 [m], ≥ 0.
    rate : array_like, default 0
        d(γ2 − γ1)/dτ [rad/m].

    Returns
    -------
    ndarray
        Gap [m] (converging lines: the largest gap, where they cross, is kept
        beyond the crossing).
    """
    g1, g2, t, r = np.broadcast_arrays(*(np.asarray(v, dtype=float)
                                         for v in (gamma1, gamma2, tau, rate)))
    a, c = _angle_growth(g1, g2, r)
    with np.errstate(divide="ignore", invalid="ignore"):
        t_eff = np.where(c < 0, np.minimum(t, a / np.abs(c)), t)
        w = c * t_eff
        # ln(cos a / cos(a + w)) / c without cancellation for small w
        gen = -np.log1p(_cos_ratio_m1(a, w)) / c
        out = np.where(c == 0.0, t_eff * np.tan(a), gen)
    return out / np.cos(g1)


def _cos_ratio_m1(a, w):
    """cos(a + w)/cos(a) − 1, accurate for small w."""
    return -2.0 * np.sin(0.5 * w) ** 2 - np.tan(a) * np.sin(w)


def jump_overlap(gamma1, gamma2, delta1, rate=0.0):
    """Overlap width of a jump on side 1 (Piotrowski & Chollet (2005) eq. 3 and a small-jump generalisation).

    Side 1 is the side of the jump limit t_ylim where contact 1 is the rigid
    contact point; contact 2, rigidly separated from the rail there by a gap
    that grows with the distance Δt from t_ylim, still carries load while the
    gap is smaller than contact 1's interpenetration d1 = δ1/2. With straight
    profile lines the gap, measured along contact 1's normal, is
    Δt tan(γ2 − γ1)/cos γ1, which gives eq. (3)::

        Δt_y1 = cos γ1 · (δ1/2) / tan(γ2 − γ1)            (rate = 0)

    It diverges as γ2 → γ1 (the small jump Piotrowski & Chollet (2005) say eq. 3 does not cover;
    its generalisation, their ref. [42], is not given there). Here the
    angle difference follows the two branches of the contact angle function,
    Δγ(τ) = |γ2 − γ1| + c τ, c the rate at which it grows with the distance τ
    from t_ylim (from the CAF slopes: ``rate`` = d(γ2 − γ1)/dτ, signed as
    γ2 − γ1). The gap is then ∫ tan Δγ dτ / cos γ1 = ln(cos Δγ(0)/cos Δγ(Δt)) /
    (c cos γ1) (cos γ1 held at its jump value), so that::

        cos(Δγ(0) + c Δt) = cos Δγ(0) · exp(−c cos γ1 δ1/2)

    gives Δt in closed form (:func:`jump_gap` is the gap as a function of Δt).
    It equals eq. (3) to first order in c, stays
    finite for γ2 = γ1 (Δt ≈ √(cos γ1 δ1 / c) when the lines diverge), and where
    the lines converge (c < 0) the gap is largest where they cross, at
    τ = Δγ(0)/|c|: if it stays below d1 the overlap is capped there. This
    generalisation is this project's derivation from the same geometry as
    eq. (3), not Ayasse's published one.

    Parameters
    ----------
    gamma1, gamma2 : array_like
        Contact angles on both sides of the jump [rad], on the two branches'
        lines extended to the jump limit.
    delta1 : array_like
        Hertz approach of contact 1 under its load [m], ≥ 0.
    rate : array_like, default 0
        d(γ2 − γ1)/dτ [rad/m] with τ ≥ 0 the lateral distance from the jump
        limit into side 1 (0: straight lines, eq. 3).

    Returns
    -------
    ndarray
        Δt_y1 [m], ≥ 0.

    Raises
    ------
    InputError
        γ2 = γ1 with rate = 0 (parallel lines: the overlap is unbounded), or
        δ1 < 0.

    References
    ----------
    .. [1] J. Piotrowski, H. Chollet, VSD 43 (2005), §2.3.3, eq. (3).
    """
    g1, g2, d1, r = np.broadcast_arrays(*(np.asarray(v, dtype=float)
                                          for v in (gamma1, gamma2, delta1, rate)))
    if np.any(d1 < 0):
        raise InputError(f"jump_overlap: delta1 must be >= 0, got {d1!r}")
    if np.any((g2 == g1) & (r == 0.0)):
        raise InputError(f"jump_overlap: gamma2 must differ from gamma1 (got {g1!r}, {g2!r}) "
                         "unless the angle difference changes (rate != 0): parallel lines "
                         "give an unbounded overlap")
    a, c = _angle_growth(g1, g2, r)
    K = np.cos(g1) * 0.5 * d1                       # the gap to close, times cos γ1
    x = c * K
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        eq3 = K / np.tan(a)
        arg = np.cos(a) * np.exp(-x)
        # w = c Δt solves cos(a + w)/cos a − 1 = expm1(−x): closed form, then Newton steps
        # on the cancellation-free form (small w, i.e. nearly straight lines)
        w = np.arccos(np.clip(arg, -1.0, 1.0)) - a
        target = np.expm1(-x)
        for _ in range(4):
            f = _cos_ratio_m1(a, w) - target
            df = -np.sin(a + w) / np.cos(a)
            w = np.where(df != 0.0, w - f / np.where(df != 0.0, df, 1.0), w)
        general = w / c
        crossed = a / np.abs(c)                     # converging lines: capped where they cross
        out = np.where(c == 0.0, eq3, np.where(arg > 1.0, crossed, general))
    return out


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
        """Wheel profile radius R_wx [m] recovered from the CAF (Piotrowski & Chollet (2005) §2.3.2).

        R_rx + R_wx = −1/(cos γ dγ/dt_y) (radii convex positive; a concave
        wheel profile gives R_wx < 0; infinite where the line is flat). The
        paper's relation is for a shift towards the wheel's flange; t_y is
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
        """(t_ylim, γ1, γ2, δ1_unit, δ2_unit, s1, s2) of jump ``k``, memoised: the Hertz
        approach of each side's contact at the jump limit is δ_unit (N/E*)^(2/3) [m]
        (N [N], E* [Pa]), s_i the slope dγ/dt_y of branch i's line [rad/m]; None when a
        side is not convex (A or B ≤ 0) or both lines coincide."""
        memo = self.__dict__.setdefault("_memo", {})
        if k not in memo:
            t_lim = float(self.jumps[k])
            l1, l2 = self.line(t_lim, k), self.line(t_lim, k + 1)
            if (min(l1["A"], l1["B"], l2["A"], l2["B"]) <= 0
                    or (l1["gamma"] == l2["gamma"] and l1["slope"] == l2["slope"])):
                memo[k] = None
            else:
                u = [float(hertz_kernel(1.0, ln["A"], ln["B"], 1.0)[3]) for ln in (l1, l2)]
                memo[k] = (t_lim, l1["gamma"], l2["gamma"], u[0], u[1], l1["slope"],
                           l2["slope"])
        return memo[k]

    def _rate(self, k):
        """s1 − s2 [rad/m] of jump ``k`` (the slopes dγ/dt_y of the two lines): both
        d(γ2 − γ1)/dτ on side 1 (τ = t_ylim − t_y) and d(γ1 − γ2)/dτ on side 2
        (τ = t_y − t_ylim), the ``rate`` of :func:`jump_overlap` on either side."""
        t = float(self.jumps[k])
        return self.line(t, k)["slope"] - self.line(t, k + 1)["slope"]

    def branch_of(self, y):
        """Branch (continuous part of the CAF) of the rigid contact point at shift ``y`` [m]."""
        return int(np.searchsorted(self.jumps, float(y)))

    def overlaps(self, k, delta1, delta2, overlap="general"):
        """Overlap widths (Δt_y1, Δt_y2) [m] at jump ``k`` for the Hertz approaches δ1, δ2
        [m] of the two contacts: Δt_y1 below the jump limit (branch k, contact 1 the
        rigid one), Δt_y2 above it (Piotrowski & Chollet (2005) eq. 3 on each side of the jump).

        ``overlap="eq3"`` is eq. (3) with straight lines; ``"general"`` (default)
        lets the angle difference follow the two lines' slopes
        (:func:`jump_overlap` with its ``rate``), which equals eq. (3) for parallel
        lines and stays finite for small jumps.
        """
        g1, g2 = self.jump_angles(k)
        rate = self._rate(k) if _overlap_kind(overlap) == "general" else 0.0
        return (float(jump_overlap(g1, g2, delta1, rate)),
                float(jump_overlap(g2, g1, delta2, rate)))


def caf_table(wheelset, track, side="right", y=(-0.01, 0.01), *, step=5e-5, tolerance=1e-3,
              jump=1e-3):
    """Build the piecewise-linear CAF table of one side (Piotrowski & Chollet (2005) §2.3.2).

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


def profile_jump_gaps(wheelset, track, table, k, side, tau):
    """Rigid gap of the second contact near jump ``k``, measured on the profiles.

    At the shifts t_ylim ∓ τ (side 1 below the jump limit, side 2 above) the
    contact search (:func:`~wheelrail.geometry.contact_search.find_points`,
    zero roll and yaw, the wheel at its rigid touching height) finds the
    candidate point of the other branch (contact angle within 0.01 rad of that
    branch's line) and its separation: the gap that :func:`jump_gap` models
    from the table's lines. A check of the tables against the geometry.

    Parameters
    ----------
    wheelset, track
        The pair the table was built from.
    table : CafTable
    k : int
        Jump index.
    side : {1, 2}
    tau : array_like
        Distances from the jump limit [m], > 0.

    Returns
    -------
    tau, gap : ndarray
        The distances where the other branch's point was found and its gap [m].
    """

    if side not in (1, 2):
        raise InputError(f"side must be 1 or 2, got {side!r}")
    jd = table._jump_data(k)
    if jd is None:
        raise InputError(f"jump {k!r}: a side is not convex or both lines coincide")
    t_lim, g1, g2, _, _, s1, s2 = jd
    tau = np.atleast_1d(np.asarray(tau, dtype=float))
    y = t_lim + (-1.0 if side == 1 else 1.0) * tau
    zero = np.zeros(y.size)
    z, _ = touching_heights(wheelset, track, y, zero, zero)
    d, _ = find_points(wheelset, track, table.side, _Pose(y, z[table.side], zero, zero),
                       tolerance=1e-3)
    other = (g2 + s2 * (y - t_lim)) if side == 1 else (g1 + s1 * (y - t_lim))
    ok = np.isfinite(d["separation"]) & (d["separation"] > 1e-8)
    j = np.argmin(np.where(ok, np.abs(d["contact_angle"] - other[:, None]), np.inf), axis=1)
    r = np.arange(y.size)
    keep = np.abs(d["contact_angle"][r, j] - other) < 0.01
    return tau[keep], d["separation"][r, j][keep]


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


def _overlap_kind(overlap):
    if overlap not in ("general", "eq3"):
        raise InputError(f"caf_overlap must be 'general' or 'eq3', got {overlap!r}")
    return overlap


def caf_contacts(table, t_y, load, materials, overlap="general"):
    """Ayasse's contacts of one wheel at shift ``t_y`` from its CAF table (Piotrowski & Chollet (2005) §2.3).

    The rigid contact point lies on the branch of ``t_y``; near a jump limit
    t_ylim the two contacts of the neighbouring branches share the load over
    the overlap [t_ylim − Δt_y1, t_ylim + Δt_y2] of eq. (3): on side i of the
    jump, where contact i is the rigid one, the other contact touches while
    its rigid gap is below contact i's interpenetration δ_i/2 (δ_i the Hertz
    approach of contact i under the whole wheel load, at the jump limit: "the
    overlap is determined at the beginning of the jump as a function of the
    dynamic load", §2.3.3). The share of contact 2 rises linearly across the
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
    overlap : {"general", "eq3"}, default "general"
        Overlap widths: :func:`jump_overlap` with the angle difference
        following the lines' slopes, or eq. (3) with straight lines.

    Returns
    -------
    list of (float, dict, int)
        (share w_i, line values of :meth:`CafTable.line`, branch) of each
        contact (one, or two inside an overlap; Σ w_i = 1); the normal loads
        are N_i = w_i N with N = Q / Σ w_i cos γ_i.
    """

    E_star = float(as_material_pair(materials).E_star)
    general = _overlap_kind(overlap) == "general"
    t_y = float(t_y)
    b = table.branch_of(t_y)
    best = None
    for k in (b - 1, b):                 # the jumps at both ends of the branch
        if not 0 <= k < table.jumps.size:
            continue
        jd = table._jump_data(k)
        if jd is None:                   # a side of the jump is not convex: no overlap
            continue
        t_lim, g1, g2, u1, u2, s1, s2 = jd
        # Hertz approach of each contact under the whole wheel load, δ = δ_unit (N/E*)^(2/3)
        d1 = u1 * (load / math.cos(g1) / E_star) ** (2.0 / 3.0)
        d2 = u2 * (load / math.cos(g2) / E_star) ** (2.0 / 3.0)
        if general:
            dt1 = float(jump_overlap(g1, g2, d1, s1 - s2))    # side 1 (below t_ylim)
            dt2 = float(jump_overlap(g2, g1, d2, s1 - s2))    # side 2 (above t_ylim)
        else:
            tg = math.tan(abs(g2 - g1))
            if tg == 0.0:
                raise InputError(f"jump at t_ylim = {t_lim!r} m: equal contact angles "
                                 f"{g1!r} rad on both sides; eq. (3) gives an unbounded "
                                 "overlap (use caf_overlap='general')")
            dt1 = math.cos(g1) * 0.5 * d1 / tg          # eq. (3), side 1
            dt2 = math.cos(g2) * 0.5 * d2 / tg          # eq. (3), side 2
        lo, hi = t_lim - dt1, t_lim + dt2
        if lo < t_y < hi and (best is None or abs(t_y - t_lim) < best[0]):
            best = (abs(t_y - t_lim), k, (t_y - lo) / (hi - lo))
    if best is None:
        return [(1.0, table.line(t_y, b), b)]
    _, k, w2 = best
    return [(1.0 - w2, table.line(t_y, k), k), (w2, table.line(t_y, k + 1), k + 1)]
