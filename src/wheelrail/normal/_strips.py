"""Shared machinery of the virtual-penetration methods (private).

Kik–Piotrowski, Linder and STRIPES (Piotrowski & Chollet (2005) §3) all work on *lines*: the
separation f(η) of the profiles along the lateral coordinate η of one contact
plane, with the longitudinal curvature A(η) of the undeformed distance
(h(x, η) ≈ f(η) + A(η) x²). The bodies are virtually pressed together by δ0;
the interpenetration g(η) = δ0 − f(η) > 0 (Piotrowski & Chollet (2005) eq. 4) marks the strips,
and every strip is half-length x_l(η) = √(g/A) long (eq. 5 with A = 1/(2R)).

This module holds

* :class:`Line` — one sampled lateral line (η uniform), its curvatures and
  where it lies (a gap problem's minimum or a wheel's contact plane);
* pure kernels: :func:`runs` (connected regions), :func:`kp_integrals`
  (the two integrals of eqs. 13–15, the inner one in closed form with
  complete elliptic integrals), :func:`hertz_penetration_factor`;
* :class:`VirtualPenetration` — the driver every method shares: load
  iteration, gap problems, wheel–rail problems (candidate points grouped by
  contact plane, vertical balance Σ Fn cos γ = Q), patch construction.

Each method implements ``_solve_line(line, delta, opts) -> list of Region``.

All quantities SI (m, N, Pa, 1/m).

References
----------
.. [1] J. Piotrowski, H. Chollet, Wheel–rail contact models for vehicle system
   dynamics including multi-point contact, VSD 43 (2005) 455–483, §3.
.. [2] J. Piotrowski, W. Kik, A simplified model of wheel/rail contact mechanics
   for non-Hertzian problems and its application in rail vehicle dynamic
   simulations, VSD 46 (2008) 27–48.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import ConvergenceError, InputError, NoContactError
from ..hertzian import hertz_kernel
from ..materials import as_material_pair
from ..patch import ContactPatch
from ._base import GapProblem
from ._fast_separation import rail_slopes, separation_fast
from ._gap import _check_search, _evaluate, _minimum
from ._patch_kernel import strip_patch, weighted_means

__all__ = ["Line", "Region", "VirtualPenetration", "runs", "kp_integrals",
           "hertz_penetration_factor", "hertz_shape", "hertz_ab"]

_LINE_NODES = 801        # nodes of the refined lateral line of a gap problem
_WHEEL_NODES = 1601      # nodes of a wheel's separation line (40 mm: 0.025 mm spacing)


def line_samples(n):
    """Profile samples per body (on 80 mm) for a wheel line of ``n`` nodes (on 40 mm): the
    samples 1.6 node spacings apart (2001 for 1601 nodes: 0.04 mm)."""
    return int(round(1.25 * (n - 1))) + 1
_LOAD_TOL = 1e-9         # relative tolerance of the load iteration


# --------------------------------------------------------------------------- kernels
def runs(mask):
    """Connected runs of True in a 1-D boolean array: list of (start, stop) (stop exclusive)."""
    m = np.concatenate(([False], np.asarray(mask, dtype=bool), [False]))
    d = np.diff(m.astype(np.int8))
    starts = np.nonzero(d == 1)[0]
    stops = np.nonzero(d == -1)[0]
    return list(zip(starts.tolist(), stops.tolist()))


def kp_integrals(xl, h, j0):
    """The integrals of Kik & Piotrowski's eqs. (13)–(15) on a uniform strip line (pure kernel).

    Parameters
    ----------
    xl : ndarray, shape (n,)
        Half-lengths x_l of the strips at uniformly spaced nodes [m] (0 outside).
    h : float
        Node spacing [m].
    j0 : int
        Node of the reference point (x = 0, y = y(j0)) where the deflection
        condition is imposed.

    Returns
    -------
    I1 : float
        ∫∫ √(x_l² − x²) dx dy = Σ (π/2) x_l² h [m³].
    I2 : float
        ∫∫ √(x_l² − x²) / √(x² + y²) dx dy [m²]. The inner integral is
        J(x_l, y) = 2√(x_l² + y²) (K(m) − E(m)), m = x_l²/(x_l² + y²); the
        logarithmic singularity at y = 0 is integrated analytically over the
        reference node's cell (J ≈ 2 x_l (ln(4 x_l/|y|) − 1)).
    """
    from scipy.special import ellipe, ellipk

    xl = np.asarray(xl, dtype=float)
    n = xl.size
    y = (np.arange(n) - j0) * h
    I1 = 0.5 * math.pi * float(np.sum(xl * xl)) * h
    on = (xl > 0) & (np.arange(n) != j0)
    r2 = xl[on] ** 2 + y[on] ** 2
    m = xl[on] ** 2 / r2
    J = 2.0 * np.sqrt(r2) * (ellipk(m) - ellipe(m))
    I2 = float(np.sum(J)) * h
    x0 = xl[j0]
    if x0 > 0:
        I2 += 2.0 * x0 * h * math.log(8.0 * x0 / h)
    return I1, I2


_TABLE = {}
_LN_MAX, _LN_STEP = 14.0, 0.005


def _hertz_table():
    """ln a, ln b, ln p0, ln δ of Hertz (unit load, E* = 1, A·B = 1) on a grid of ln(A/B)."""
    t = _TABLE.get("hertz")
    if t is None:
        n = int(round(2 * _LN_MAX / _LN_STEP)) + 1
        lam = np.linspace(-_LN_MAX, _LN_MAX, n)
        A = np.exp(0.5 * lam)
        a, b, p0, d = hertz_kernel(1.0, A, 1.0 / A, 1.0)
        t = (lam, np.log(a), np.log(b), np.log(p0), np.log(d))
        _TABLE["hertz"] = t
    return t


def hertz_shape(A, B):
    """Hertz's unit-load solution (a, b, p0, δ; load 1 N, E* = 1 Pa) for curvatures A, B [1/m].

    Interpolated (linear in ln(A/B), step 0.005, relative error < 1e-5) in a
    table of :func:`wheelrail.hertzian.hertz_kernel` with A·B = 1, scaled
    to s = √(AB) by a, b ∝ s^(-1/3), p0 ∝ s^(2/3), δ ∝ s^(1/3) (Johnson
    1985, eqs. 3.64–3.66).
    """
    A, B = float(A), float(B)
    lam = math.log(A / B)
    if abs(lam) > _LN_MAX:
        a, b, p0, d = hertz_kernel(1.0, A, B, 1.0)
        return float(a), float(b), float(p0), float(d)
    grid, la, lb, lp, ld = _hertz_table()
    s = math.sqrt(A * B)                      # curvature scale (table has A·B = 1)
    a = math.exp(float(np.interp(lam, grid, la))) / s ** (1 / 3)
    b = math.exp(float(np.interp(lam, grid, lb))) / s ** (1 / 3)
    p0 = math.exp(float(np.interp(lam, grid, lp))) * s ** (2 / 3)
    d = math.exp(float(np.interp(lam, grid, ld))) * s ** (1 / 3)
    return a, b, p0, d


def hertz_ab(A, B):
    """(a, b) of :func:`hertz_shape` (the same numbers, two table look-ups instead of four)."""
    A, B = float(A), float(B)
    lam = math.log(A / B)
    if abs(lam) > _LN_MAX:
        return hertz_shape(A, B)[:2]
    grid, la, lb, _, _ = _hertz_table()
    s = math.sqrt(A * B)
    return (math.exp(float(np.interp(lam, grid, la))) / s ** (1 / 3),
            math.exp(float(np.interp(lam, grid, lb))) / s ** (1 / 3))


def hertz_penetration_factor(A, B):
    """Virtual-penetration factor ε = δ0/δ that gives the Hertz area for curvatures A, B.

    The interpenetration region of a Hertzian gap at depth δ0 is the ellipse
    √(δ0/A) × √(δ0/B); its area equals the Hertz contact area πab when
    δ0 = a b √(AB). The ratio to Hertz's approach δ depends only on A/B
    (0.5 for A = B; Linder's and Kik & Piotrowski's constant 0.55 is a
    compromise over the usual wheel–rail ratios).

    Parameters
    ----------
    A, B : float
        Combined curvatures [1/m], > 0.

    Returns
    -------
    float
    """
    a, b, _, d = hertz_shape(A, B)
    return a * b * math.sqrt(A * B) / d


def _rescale(regions, factor):
    """Scale the forces and pressures of ``regions`` by ``factor`` (≈ 1, load closure)."""
    if not (abs(factor - 1.0) <= 1e-3):
        raise ConvergenceError(f"load closure factor {factor!r} is not within 1e-3 of 1")
    for r in regions:
        r.N *= factor
        r.peak = r.peak * factor


def _separation(problem, k, width, n, samples=2001):
    """``problem.separation(k, width, n)`` computed by the numba-spline twin of
    :func:`~wheelrail.geometry.separation.separation_at` (same result to round-off,
    :mod:`wheelrail.normal._fast_separation`; ``samples`` profile samples per body)
    and stored in the problem's cache."""
    f = problem.frames[k]
    key = ("separation", f, width, n, samples)
    if key not in problem.cache:
        pose = problem.pose
        problem.cache[key] = separation_fast(
            problem.wheelset, problem.track, problem.side, y=pose["y"], z=pose["z"],
            roll=pose["roll"], yaw=pose["yaw"], wheel_y=f.wheel_y, track_y=f.track_y,
            contact_angle=f.contact_angle, width=width, n=n, point=k,
            samples=samples)
    return problem.cache[key]


# --------------------------------------------------------------------------- data
@dataclass(eq=False)
class Line:
    """One lateral line of a contact plane (internal, mutable only while built).

    ``eta`` uniform [m]; ``f`` separation [m] (relative to the plane's zero);
    ``Ax`` longitudinal curvature of the undeformed distance [1/m];
    ``angle`` surface angle along η [rad] (wheel lines) or None;
    ``A``, ``B`` curvatures at the reference point [1/m]; ``cos`` projection of the
    vertical approach on the plane normal (wheel lines; 1 for gaps);
    ``sign`` maps η to the patch's y (y = sign·(η − η_ref)).
    """

    eta: np.ndarray
    f: np.ndarray
    Ax: np.ndarray
    A: float
    B: float
    cos: float = 1.0
    angle: np.ndarray | None = None
    sign: float = 1.0
    ref: int = -1
    extra: dict = field(default_factory=dict)

    @property
    def h(self) -> float:
        return float(self.eta[1] - self.eta[0])


@dataclass(eq=False)
class Region:
    """One contact region of a line solved by a method (internal).

    ``nodes`` slice of the line; ``j0`` reference node (deflection condition,
    the deepest point); ``N`` normal force [N]; strips as arrays over the
    region's nodes in the (possibly shape-corrected) coordinates:
    ``eta`` [m], ``xl`` [m], ``peak`` [Pa] (pressure at x = 0 of each strip),
    ``profile`` ("elliptic" along x); ``strip_axes`` optional (a_i, b_i) per node
    for per-strip flexibilities; ``info`` method extras.
    """

    nodes: slice
    j0: int
    N: float
    eta: np.ndarray
    xl: np.ndarray
    peak: np.ndarray
    weights: np.ndarray
    strip_axes: tuple | None = None
    info: dict = field(default_factory=dict)


# --------------------------------------------------------------------------- driver
class VirtualPenetration:
    """Mixin: the gap, Hertz-contact and wheel–rail drivers of a line method.

    Subclasses (also :class:`~wheelrail.normal.NormalMethod`) implement
    ``_solve_line(line, delta, opts) -> list[Region]`` where ``delta`` is the
    real approach of the bodies along the line's normal [m], and
    ``_patch_info(region, opts) -> dict`` (extras stored in the patch).
    """

    _default_strips = 40
    _default_cells = 40

    # ----------------------------------------------------------- helpers
    def _line_load(self, line, delta, opts):
        regs = self._solve_line(line, delta, opts)
        return regs, float(sum(r.N for r in regs))

    def _line_loads(self, line, delta, opts):
        """(Σ N, Σ N cos ᾱ) of a line at the real approach ``delta`` (what the load
        iterations need; ᾱ the interpenetration-weighted surface angle, 0 for gap
        lines). Methods may override it with a kernel that builds no regions."""
        regs = self._solve_line(line, delta, opts)
        N = Nz = 0.0
        for r in regs:
            N += r.N
            if line.angle is None:
                Nz += r.N
            else:
                w = r.weights
                Nz += r.N * math.cos(float(np.sum(w * line.angle[r.nodes]) / np.sum(w)))
        return N, Nz

    def _iterate(self, total, target, d_start, what):
        """Solve total(d) = target for the approach d (increasing, ~ d^1.5).

        Power-law secant steps inside a bracket (bisection when a step leaves
        it). The load of a sampled line jumps slightly where a node enters the
        region, so the iteration stops at 1e-9 relative or when the bracket
        closes; the caller removes the remaining mismatch (< 1e-3) by scaling.
        """
        d = float(d_start)
        lo, hi = 0.0, math.inf
        hist = []
        best = (math.inf, d, 0.0)
        for _ in range(100):
            F = total(d)
            err = abs(F - target) / target
            if err < best[0]:
                best = (err, d, F)
            if err <= _LOAD_TOL:
                return d
            if F < target:
                lo = max(lo, d)
            else:
                hi = min(hi, d)
            if hi < math.inf and hi - lo <= 1e-13 * hi:
                break
            if F > 0:
                hist.append((d, F))
            if len(hist) >= 2 and hist[-1][0] != hist[-2][0] and hist[-1][1] != hist[-2][1]:
                (d0, F0), (d1, F1) = hist[-2:]
                p = math.log(F1 / F0) / math.log(d1 / d0)
                p = min(max(p, 0.5), 3.0)
            else:
                p = 1.5
            d_new = d * (target / F) ** (1.0 / p) if F > 0 else 2.0 * d
            if not (lo < d_new < hi):
                d_new = 0.5 * (lo + hi) if hi < math.inf else 2.0 * max(d, lo)
            d = d_new
        if best[0] <= 1e-3:
            return best[1]
        raise ConvergenceError(f"{what}: the load {target!r} N was not reached (last approach "
                               f"{best[1]!r} m, load {best[2]!r} N)")

    # ----------------------------------------------------------- Hertzian contact
    def from_contact(self, contact):
        A, B = float(contact.A), float(contact.B)
        a, b = float(contact.a), float(contact.b)
        L = 4.0 * max(a, b)

        def gap(x, y):
            return A * np.asarray(x, dtype=float) ** 2 + B * np.asarray(y, dtype=float) ** 2

        prob = GapProblem(gap, contact.materials, Fn=float(contact.Fn),
                          search=(-L, L, -L, L))
        return self.from_gap(prob)

    # ----------------------------------------------------------- gap problems
    def _gap_line(self, problem, centre, ylim, n, dx):
        xm, ym, hmin = centre
        eta = np.linspace(ylim[0], ylim[1], n)
        X0 = np.full(n, xm)
        Y = ym + eta
        h0 = np.asarray(_evaluate(problem.gap, X0, Y), dtype=float)
        hp = np.asarray(_evaluate(problem.gap, X0 + dx, Y), dtype=float)
        hm = np.asarray(_evaluate(problem.gap, X0 - dx, Y), dtype=float)
        Ax = (hp + hm - 2.0 * h0) / (2.0 * dx * dx)
        return eta, h0 - hmin, Ax

    def from_gap(self, problem):
        opts = self.option_values()

        search = _check_search(problem.search)
        pair = as_material_pair(problem.materials)
        xm, ym, hmin, spacing = _minimum(problem.gap, search)
        # curvatures at the minimum along x and y (the method's rolling axis is x)
        hx, hy = spacing
        A = B = None
        for _ in range(3):
            h = np.asarray(_evaluate(problem.gap, xm + np.array([0.0, hx, -hx, 0.0, 0.0]),
                                     ym + np.array([0.0, 0.0, 0.0, hy, -hy])), dtype=float)
            A = (h[1] + h[2] - 2 * h[0]) / (2 * hx * hx)
            B = (h[3] + h[4] - 2 * h[0]) / (2 * hy * hy)
            if not (A > 0 and B > 0):
                raise InputError(
                    f"normal method {self.name!r}: the gap is not convex at its minimum "
                    f"(x, y) = ({xm!r}, {ym!r}) m (A = {A!r}, B = {B!r} 1/m); this patch cannot be "
                    "represented by a virtual-penetration method, use normal='bem'")
            if problem.Fn is not None:
                a1, b1, _, d1 = hertz_kernel(float(problem.Fn), A, B, pair.E_star)
            else:
                d = float(problem.penetration) - hmin
                if not d > 0:
                    raise NoContactError(f"no contact: the penetration {problem.penetration!r} m "
                                         f"does not exceed the smallest gap {hmin!r} m")
                _, _, _, dd = hertz_kernel(1.0, A, B, pair.E_star)
                s = math.sqrt(d / float(dd))
                a1, b1, _, _ = hertz_kernel(s ** 3, A, B, pair.E_star)
            hx, hy = 0.5 * float(a1), 0.5 * float(b1)
        a_est, b_est = 2 * hx, 2 * hy
        ylim0 = (max(search[2] - ym, -12 * b_est), min(search[3] - ym, 12 * b_est))
        dx = 0.5 * a_est
        centre = (xm, ym, hmin)
        eta, f, Ax = self._gap_line(problem, centre, ylim0, _LINE_NODES, dx)
        line = Line(eta, f, Ax, float(A), float(B), ref=int(np.argmin(np.abs(eta))))
        # first pass on the wide line, then refine around the regions and solve again
        delta = self._gap_delta(problem, line, hmin, pair, opts)
        regs = self._solve_line(line, delta, opts)
        if not regs:
            raise NoContactError(f"normal method {self.name!r}: no contact region")
        lo = min(line.eta[r.nodes.start] for r in regs)
        hi = max(line.eta[r.nodes.stop - 1] for r in regs)
        pad = 0.15 * (hi - lo) + 3 * line.h
        ylim = (max(lo - pad, ylim0[0]), min(hi + pad, ylim0[1]))
        eta, f, Ax = self._gap_line(problem, centre, ylim, _LINE_NODES, dx)
        line = Line(eta, f, Ax, float(A), float(B), ref=int(np.argmin(np.abs(eta))))
        delta = self._gap_delta(problem, line, hmin, pair, opts, start=delta)
        regs = self._solve_line(line, delta, opts)
        if problem.Fn is not None:
            _rescale(regs, float(problem.Fn) / sum(r.N for r in regs))
        patches = []
        for reg in regs:
            patches.append(self._make_patch(line, reg, pair, opts, frame=None,
                                            delta=delta,
                                            extra={"centre": (xm, ym), "gap_minimum": hmin}))
        return tuple(patches)

    def _gap_delta(self, problem, line, hmin, pair, opts, start=None):
        line.extra["E_star"] = pair.E_star
        line.extra["materials"] = pair
        if problem.penetration is not None:
            return float(problem.penetration) - hmin
        Q = float(problem.Fn)
        if start is None:
            _, _, _, d1 = hertz_shape(line.A, line.B)
            start = d1 * (Q / pair.E_star) ** (2.0 / 3.0) / 1.0
            start = float(start)
        return self._iterate(lambda d: self._line_loads(line, d, opts)[0], Q, start,
                             f"normal method {self.name!r}")

    # ----------------------------------------------------------- patches
    def _make_patch(self, line, reg, pair, opts, frame, delta, extra=None):
        strips = int(opts["strips"])
        cells = int(opts["cells"])
        eta_n = reg.eta
        eta_ref = float(reg.info.get("eta_ref", eta_n[reg.j0 - reg.nodes.start]))
        # strips: x_l² (linear in the interpenetration) and the peaks interpolated from the
        # nodes, the strip pressures scaled to keep the patch force exactly
        # (:func:`wheelrail.normal._patch_kernel.strip_patch`)
        y, xl, sp, ys, dy, width, area, L, ok = strip_patch(
            np.ascontiguousarray(eta_n, dtype=float), np.ascontiguousarray(reg.xl, dtype=float),
            np.ascontiguousarray(reg.peak, dtype=float), float(line.h), strips, cells,
            float(reg.N), eta_ref, float(line.sign))
        ratio = L / width
        a = math.sqrt(area * ratio / math.pi)
        b = math.sqrt(area / (ratio * math.pi))
        info = dict(reg.info)
        info.update(extra or {})
        info["L_W"] = (L, width)
        if reg.strip_axes is not None:
            ax = np.interp(ys, eta_n, reg.strip_axes[0])
            bx = np.interp(ys, eta_n, reg.strip_axes[1])
            if line.sign < 0:
                ax, bx = ax[::-1], bx[::-1]
            info["strip_semiaxes"] = (ax, bx)
        info.update(self._patch_info(reg, opts))
        N = float(reg.N)
        values = dict(y=y, dy=np.full(strips, dy), x_lead=xl, x_trail=-xl, strip_pressure=sp,
                      Fn=N, materials=pair, a=a, b=b, penetration=float(delta), A=line.A,
                      B=line.B, frame=frame, method=self.name, info=info)
        if ok and all(math.isfinite(v) and v > 0 for v in (N, a, b)):
            return ContactPatch._trusted(**values)
        return ContactPatch(**values)      # the checks say what is wrong

    def _patch_info(self, reg, opts):
        return {}

    # ----------------------------------------------------------- wheel on rail
    def _line_resolution(self):
        """Nodes of a wheel's separation line (40 mm) and profile samples per body (80 mm)."""
        n = int(getattr(self, "line_nodes", _WHEEL_NODES))
        return n, line_samples(n)

    def _wheel_lines(self, problem, group_angle=0.2, width=0.04):
        n, m = self._line_resolution()
        key = ("vp_lines", self.name, group_angle, width, n)
        if key in problem.cache:
            return problem.cache[key]

        sigma = 1.0 if problem.side == "right" else -1.0
        groups = problem.groups(group_angle, width)
        rc = problem.track.curve(problem.side)
        lines = []
        for g in groups:
            r = g[0]
            s = _separation(problem, r, width, n, m)
            f = problem.frames[r]
            Ax = s.cos_factor / (2.0 * s.wheel_radius)
            if problem.roller_radius is not None:
                Ax = Ax + 0.5 / problem.roller_radius
            u = sigma * f.track_y + s.eta * math.cos(f.contact_angle)
            ang = np.arctan(rail_slopes(rc.u, rc.c, rc._h, u))
            A, B = float(problem.A[r]), float(problem.B[r])
            lines.append(Line(np.asarray(s.eta, float), np.asarray(s.f, float), np.asarray(Ax),
                              A, B, cos=float(s.cos_factor), angle=ang, sign=sigma, ref=r,
                              extra={"E_star": problem.materials.E_star,
                                     "materials": problem.materials, "group": g,
                                     "separation": s}))
        problem.cache[key] = lines
        return lines

    def _wheel_solve(self, problem, opts, group_angle=0.2, width=0.04):
        pair = as_material_pair(problem.materials)
        lines = self._wheel_lines(problem, group_angle, width)
        if not lines:
            raise NoContactError(f"{problem.side} wheel: no candidate contact point")


        def solve_all(dz):
            out, Fz = [], 0.0
            for line in lines:
                regs = self._solve_line(line, dz * line.cos, opts)
                for reg in regs:
                    # the weighted mean surface angle (ContactFrame's, see frame_at) and
                    # lateral position of the region, weights = its interpenetration
                    ang, eta_c = weighted_means(
                        np.ascontiguousarray(reg.weights, dtype=float),
                        line.angle[reg.nodes], line.eta[reg.nodes])
                    reg.info["_angle"], reg.info["_eta"] = ang, eta_c
                    Fz += reg.N * math.cos(ang)
                out.append(regs)
            return out, Fz

        if problem.vertical_approach is not None:
            dz = float(problem.vertical_approach)
        else:
            Q = float(problem.vertical_load)
            l0 = lines[0]
            if "start" not in l0.extra:        # (min f, Hertz's approach at 1 N, E* = 1)
                d1 = hertz_shape(l0.A, l0.B)[3] if l0.A > 0 and l0.B > 0 else None
                l0.extra["start"] = (float(np.min(l0.f)), d1)
            fmin, d1 = l0.extra["start"]
            if d1 is not None:
                start = fmin + d1 * (Q / pair.E_star) ** (2 / 3)
            else:
                start = fmin + 5e-5
            start = max(start, 1e-7) / l0.cos
            def vertical(d):
                return sum(self._line_loads(line, d * line.cos, opts)[1] for line in lines)

            dz = self._iterate(vertical, Q, start,
                               f"{problem.side} wheel, normal method {self.name!r}")
        sols, Fz = solve_all(dz)
        if problem.vertical_approach is None:
            _rescale([r for regs in sols for r in regs], float(problem.vertical_load) / Fz)
        patches = []
        for line, regs in zip(lines, sols):
            for reg in regs:
                e_nodes = line.eta[reg.nodes]
                eta_c = reg.info.pop("_eta")
                # angle: the weighted mean of the rail's surface angle over the region's
                # nodes, i.e. frame_at(..., weights=w, eta_samples=e_nodes), from the line
                frame = problem.frame_at(line.ref, eta_c, angle=reg.info.pop("_angle"),
                                         separation=line.extra.get("separation"))
                reg.info["eta_ref"] = self._eta_in_region_coords(reg, eta_c, e_nodes)
                patches.append(self._make_patch(line, reg, pair, opts, frame, dz * line.cos,
                                                extra={"group_point": line.ref}))
        if not patches:
            raise NoContactError(f"{problem.side} wheel: no contact at the vertical approach "
                                 f"{dz!r} m")
        # field side first (as the other methods), i.e. by lateral track position
        sig = 1.0 if problem.side == "right" else -1.0
        patches.sort(key=lambda p: -sig * p.frame.track_y)
        return tuple(patches), {"vertical_approach": float(dz), "groups": len(lines)}

    @staticmethod
    def _eta_in_region_coords(reg, eta_c, e_nodes):
        """Reference η in the region's (possibly stretched) coordinates."""
        if reg.eta.size < 2 or e_nodes.size < 2:
            return float(reg.eta[0])
        t = (eta_c - e_nodes[0]) / (e_nodes[-1] - e_nodes[0])
        return float(reg.eta[0] + t * (reg.eta[-1] - reg.eta[0]))

    def from_wheel(self, problem):
        opts = self.option_values()
        return self._wheel_solve(problem, opts)
