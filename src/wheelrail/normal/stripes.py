"""Ayasse & Chollet's semi-Hertzian method (STRIPES).

Hertz's relations written with curvatures instead of semi-axes (Piotrowski & Chollet (2005)
§3.3, Table 2: λ = A/B, n/m = b/a, δ = r a0²(A+B)). The crude interpenetration
gives b_g/a_g = √λ instead of Hertz's b/a, so the longitudinal curvature is
compensated (eq. 23)::

    A_c / A = (n/m)² / λ,     h0 = a² A_c = b² B = n² δ / (r (1 + λ))

(h0/δ = b²B/δ from Hertz for the reference curvatures). Every strip i has the
interpenetration h_i = h0 − f(y_i) and the length a_i = √(h_i / A_c) (eq. 24);
its pressure is semi-elliptic with a peak proportional to h_i / a_i (eq. 27)::

    p_i(x) = (p0 a / h0) (h_i / a_i) √(1 − x²/a_i²)

where p0 a / h0 is Hertz's for λ (= (4/(3π)) (1+λ)/n³ · E*-type constant of
eq. 27, evaluated here from the Hertz kernel), so a Hertzian gap gives
Hertz's patch exactly. The lateral curvature B used for λ on each strip is the
local curvature of the separation smoothed over ``smoothing`` (and kept
positive: between close patches it is often negative, §3.3); each strip gets
Kalker coefficients for its own n/m (eq. 25–26: flexibilities with the
virtual semi-axis a_i/k_i = √(h0/A_c), k_i² = h_i/h0).

References
----------
.. [1] J. Piotrowski, H. Chollet, VSD 43 (2005), §3.3, eqs. (23)–(27).
.. [2] J.B. Ayasse, H. Chollet, Determination of the wheel rail contact patch in
   semi-Hertzian conditions, VSD 43 (2005) 161–172.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import InputError
from ..options import configured, option
from ._base import NormalMethod, PatchDescription
from ._patch_kernel import positive_runs
from ._stripes_kernel import half_curvature, smooth_nodes, stripes_line_load
from ._strips import Region, VirtualPenetration, _hertz_table, hertz_shape

__all__ = ["Stripes", "stripes_constants"]


def stripes_constants(A, B):
    """(h0/δ, A_c/A, p0 a / (h0 E*)) for the curvatures A, B [1/m] (Hertz eq. 23)."""
    a, b, p0, d = hertz_shape(A, B)          # unit load, E* = 1
    h0 = b * b * B
    return h0 / d, (b / a) ** 2 * B / A, p0 * a / h0


def _smoothing(eta, f, length):
    """(d2, kernel reversed): half the second derivative of f and the normalised Gaussian of
    ``length`` [m] (kernel None: no smoothing)."""

    h = eta[1] - eta[0]
    d2 = half_curvature(np.ascontiguousarray(f, dtype=float), float(h))
    if length <= 0:
        return d2, None
    sig = length / h
    half = int(min(4 * sig, d2.size // 2))
    if half < 1:
        return d2, None
    k = np.exp(-0.5 * (np.arange(-half, half + 1) / sig) ** 2)
    k /= k.sum()
    return d2, np.ascontiguousarray(k[::-1])


def _smoothed_range(sm, i0, i1):
    """Nodes i0 … i1 − 1 of :func:`_smoothed_B` from :func:`_smoothing`'s output."""
    d2, krev = sm
    if krev is None:
        return d2[i0:i1]
    half = krev.size // 2
    return np.convolve(np.pad(d2, half, mode="edge")[i0:i1 + krev.size - 1], krev[::-1],
                       mode="valid")


def _smoothed_at(line, opts, sm, idx):
    """:func:`_smoothed_B` at the nodes ``idx`` of the line, remembered on it (each node
    computed once)."""
    d2, krev = sm
    if krev is None:
        return d2[idx]
    key = ("stripes_B", opts["smoothing"])
    done = line.extra.get(key)
    if done is None:
        done = line.extra[key] = np.full(d2.size, np.nan)
    v = done[idx]
    miss = np.isnan(v)
    if miss.any():
        todo = idx[miss]
        done[todo] = smooth_nodes(d2, krev, todo)
        v = done[idx]
    return v


def _read_nodes(eta_n, strips):
    """Nodes of a region whose strip ellipses the patch reads: ``np.interp`` at the strip
    centres of :meth:`~wheelrail.normal._strips.VirtualPenetration._make_patch` reads the
    two nodes around each centre (here with one more on each side)."""
    n = eta_n.size
    if n <= 2 * strips + 4:
        return np.arange(n)
    hn = eta_n[1] - eta_n[0]
    lo = eta_n[0] - 0.5 * hn
    dy = (eta_n[-1] + 0.5 * hn - lo) / strips
    ys = lo + (np.arange(strips) + 0.5) * dy
    j = np.searchsorted(eta_n, ys, side="right")       # interval j − 1 … j around ys
    mask = np.zeros(n, dtype=bool)
    mask[np.clip(np.concatenate((j - 2, j - 1, j, j + 1)), 0, n - 1)] = True
    return np.flatnonzero(mask)


def _smoothed_B(eta, f, length):
    """Half the second derivative of f, smoothed with a Gaussian of ``length`` [m] (≥ 0 floor later)."""
    sm = _smoothing(eta, f, length)
    return _smoothed_range(sm, 0, sm[0].size)


@configured
class Stripes(VirtualPenetration, NormalMethod, PatchDescription):
    """STRIPES (semi-Hertzian) as a normal method (see the module docstring).

    Other Parameters
    ----------------
    smoothing : float, default 0.002
        Length [m] of the Gaussian smoothing of the lateral curvature B(y).
    strips, cells : int, default 40, 40

    References
    ----------
    .. [1] Piotrowski & Chollet (2005) §3.3, eqs. (23)–(27); Ayasse & Chollet (2005).
    """

    name = "stripes"
    references = (
        "J. Piotrowski, H. Chollet, Wheel-rail contact models for vehicle system dynamics "
        "including multi-point contact, Vehicle System Dynamics 43 (2005) 455-483.",
        "J.B. Ayasse, H. Chollet, Determination of the wheel rail contact patch in "
        "semi-Hertzian conditions, Vehicle System Dynamics 43 (2005) 161-172.",
    )
    smoothing: float = option(0.002, lo=0.0, unit="m",
                              doc="length of the Gaussian smoothing of B(y)")

    def _line_data(self, line, opts):
        key = ("stripes", opts["smoothing"])
        if key not in line.extra:
            A, B = line.A, line.B
            if not (A > 0 and B > 0):
                raise InputError(f"stripes: the curvatures at the reference point are not "
                                 f"convex (A = {A!r}, B = {B!r} 1/m); use normal='bem'")
            eps, comp, kp = stripes_constants(A, B)
            # B(y) smoothed: computed on the nodes of the regions only (_solve_line)
            sm = _smoothing(line.eta, line.f, float(opts["smoothing"]))
            line.extra[key] = (eps, comp, kp, sm)
        return line.extra[key]

    def _solve_line(self, line, delta, opts):
        eps, comp, kp, sm = self._line_data(line, opts)
        h0 = eps * delta
        hi_all = h0 - line.f
        E_star = line.extra["E_star"]
        out = []
        for i0, i1 in positive_runs(hi_all).tolist():
            if i1 - i0 < 3:
                continue
            hi = hi_all[i0:i1]
            Ac = comp * line.Ax[i0:i1]
            ai = np.sqrt(hi / Ac)                          # eq. (24)
            peak = kp * E_star * hi / ai                   # eq. (27), Hertz constant
            N = float(np.sum(0.5 * math.pi * ai * peak) * line.h)
            if not N > 0:
                continue
            # per-strip virtual ellipse (eqs. 25-26): a_v = a_i / k_i, b_v = a_v (n/m)(λ_i),
            # λ_i with the smoothed B, floored (negative between close patches: small
            # positive); only at the nodes the patch's strips read (1 elsewhere, unused)
            idx = _read_nodes(line.eta[i0:i1], int(opts["strips"]))
            Bs = np.maximum(_smoothed_at(line, opts, sm, i0 + idx), 0.05 * line.B)
            nm = np.ones(i1 - i0)
            nm[idx] = _n_over_m_array(line.Ax[i0 + idx] / Bs)
            av = np.sqrt(h0 / Ac)
            j = int(np.argmax(hi))
            out.append(Region(slice(i0, i1), i0 + j, N, line.eta[i0:i1], ai, peak, hi,
                              strip_axes=(av, av * nm),
                              info={"virtual_penetration": h0, "h0_over_delta": eps,
                                    "A_c_over_A": comp}))
        return out

    def _line_loads(self, line, delta, opts):
        # the load iteration's hot path: with eq. (27) the strip force ½π a_i p_i h is
        # ½π k_p E* h_i h (a_i cancels), so the load needs no virtual ellipses

        eps, comp, kp, _ = self._line_data(line, opts)
        c = 0.5 * math.pi * kp * line.extra["E_star"] * line.h
        ang = line.angle
        N, Nz = stripes_line_load(line.f, line.f if ang is None else ang, ang is not None,
                                  eps * delta, c)
        return float(N), float(Nz)

    def _patch_info(self, reg, opts):
        return {"fastsim_flexibility": "three"}


_NM_CACHE: dict = {}


_NM_K = 691                 # round(50 ln 1e6): the quantised ln λ is k/50, |k| <= _NM_K
_NM_TABLE: list = []


def _nm_table():
    """Hertz's n/m = b/a at λ = exp(k/50), |k| ≤ ``_NM_K``: :func:`_n_over_m` of every
    grid value, computed at once (the table of :func:`~wheelrail.normal._strips.hertz_shape`
    interpolated for all of them; equal to the scalar look-up to round-off)."""
    if not _NM_TABLE:
        grid, la, lb, _, _ = _hertz_table()
        lam = np.exp(np.arange(-_NM_K, _NM_K + 1) / 50.0)
        x = np.log(lam)
        s3 = np.sqrt(lam) ** (1 / 3)
        a = np.exp(np.interp(x, grid, la)) / s3
        b = np.exp(np.interp(x, grid, lb)) / s3
        _NM_TABLE.append(b / a)
    return _NM_TABLE[0]


def _n_over_m_array(lam):
    """:func:`_n_over_m` of every λ, quantised on the 2 % grid of ln λ (from :func:`_nm_table`)."""
    k = np.round(np.log(np.clip(lam, 1e-6, 1e6)) * 50.0)
    return _nm_table()[k.astype(np.intp) + _NM_K]


def _n_over_m(lam):
    """Hertz's n/m = b/a for one λ = A/B (Table 2), memoised (the scalar form of
    :func:`_nm_table`, which the method uses)."""
    key = round(float(lam), 12)
    v = _NM_CACHE.get(key)
    if v is None:
        a, b, _, _ = hertz_shape(lam, 1.0)
        v = b / a
        _NM_CACHE[key] = v
    return v
