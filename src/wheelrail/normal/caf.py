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

The runtime multi-Hertz variant ``"ayasse"`` (:mod:`wheelrail.normal.multi_hertz`)
solves one pose from its own candidate points; these tables are the
precomputed form of the same information for a dynamics code, with the
checks of the seed's relations in ``tests/reference/test_nonhertz_caf.py``.

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
from dataclasses import dataclass

import numpy as np

from .._validation import positive
from ..errors import InputError

__all__ = ["CafTable", "caf_table", "jump_overlap"]


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
    """

    side: str
    y: np.ndarray
    gamma: np.ndarray
    branch: np.ndarray
    jumps: np.ndarray
    rail_radius: np.ndarray
    samples: int
    tolerance: float

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
        wheel profile gives R_wx < 0; infinite where the line is flat).
        """
        g, slope = self.contact_angle(y)
        _, i = self._locate(y)
        with np.errstate(divide="ignore"):
            total = -1.0 / (np.cos(g) * slope)
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
    ys, gs, brs, rr = [], [], [], []
    for b, (i0, i1) in enumerate(zip(starts, stops)):
        seg_y, seg_g = ty[i0:i1], gam[i0:i1]
        keep = _simplify(seg_y, seg_g, tolerance) if seg_y.size > 1 else np.array([0])
        for a, c in zip(keep, np.r_[keep[1:], keep[-1]]):
            kk = kr[i0 + a:i0 + max(c, a + 1)]
            with np.errstate(divide="ignore"):
                rad = float(np.median(1.0 / kk)) if kk.size else float("inf")
            rr.append(rad)
        ys.append(seg_y[keep])
        gs.append(seg_g[keep])
        brs.append(np.full(keep.size, b))
    jumps = 0.5 * (ty[cut] + ty[cut + 1])
    return CafTable(side, np.concatenate(ys), np.concatenate(gs), np.concatenate(brs), jumps,
                    np.asarray(rr), n, tolerance)
