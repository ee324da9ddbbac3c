"""Linder's virtual-penetration method with per-strip virtual ellipses.

The bodies are virtually pressed together by δ0 = 0.55 δ (Piotrowski & Chollet (2005) §3.1);
the interpenetration region is the contact patch, cut into strips along the
rolling direction. Every strip i (lateral position y_i from the middle of the
region, half-length x_l(y_i) = √(2R g(y_i)), eq. 5) belongs to a virtual
Hertz ellipse with the common lateral semi-axis b_e (half the region's width,
eq. 6) and its own longitudinal semi-axis a_ei (eq. 7)::

    b_e = (y_l − y_r)/2,       a_ei = x_l(y_i) b_e / √(b_e² − y_i²)

The penetration of that ellipse follows from the circle through (±b_e, 0)
and (y_i, g(y_i)) (eq. 8)::

    z_mi = (b_e² − y_i² − g²(y_i)) / (2 g(y_i)),  δ_ei = √(b_e² + z_mi²) − z_mi + 0.45 δ

and Hertz's theory gives its load N_i (N = 2π a b E* δ / (3 s K(e)), s the
short semi-axis), the strip's peak pressure (eq. 9) and the patch load (eq. 10)::

    p0i = 3 N_i / (2π a_ei b_e) √(1 − y_i²/b_e²),   N = Σ (π/2) x_l(y_i) p0i Δy

Tangential: FASTSIM with three flexibilities per strip from the strip's
virtual ellipse (a_ei, b_e) (eq. 11 with c_ij(a_ei/b_e)) and a parabolic
traction bound along every strip carrying the strip's load (p0i' = 3π p0i/8).

References
----------
.. [1] J. Piotrowski, H. Chollet, VSD 43 (2005), §3.1, eqs. (4)–(11).
.. [2] C. Linder, Verschleiß von Eisenbahnrädern mit Unrundheiten, Diss. ETH
   Zürich Nr. 12342, 1997.
"""

from __future__ import annotations

import math

import numpy as np

from ..options import configured
from ._base import NormalMethod, PatchDescription
from ._patch_kernel import positive_runs
from ._strips import Region, VirtualPenetration

__all__ = ["Linder", "LINDER_FACTOR"]

#: Linder's virtual penetration factor δ0/δ.
LINDER_FACTOR = 0.55


def hertz_load_from_axes(a, b, delta, E_star):
    """Hertz load [N] of the ellipse with semi-axes a, b [m] at approach δ [m] (pure kernel).

    N = 2π a b E* δ / (3 s K(e)), s = min(a, b), e² = 1 − (s/l)² (Johnson 1985, §4.2).
    """
    from scipy.special import ellipk

    a, b, delta = (np.asarray(v, dtype=float) for v in (a, b, delta))
    s = np.minimum(a, b)
    k = s / np.maximum(a, b)
    K = ellipk(1.0 - k * k)
    return 2.0 * np.pi * a * b * E_star * delta / (3.0 * s * K)


@configured
class Linder(VirtualPenetration, NormalMethod, PatchDescription):
    """Linder's method as a normal method (see the module docstring).

    Problems: a gap h(x, y), a Hertzian contact, a wheel on its rail (as
    :class:`~wheelrail.normal.kik_piotrowski.KikPiotrowski`).

    Other Parameters
    ----------------
    strips, cells : int, default 40, 40
        Strips of each patch and cells per strip of the patch description.

    References
    ----------
    .. [1] Piotrowski & Chollet (2005) §3.1, eqs. (4)–(11); Linder (1997).
    """

    name = "linder"
    references = (
        "J. Piotrowski, H. Chollet, Wheel-rail contact models for vehicle system dynamics "
        "including multi-point contact, Vehicle System Dynamics 43 (2005) 455-483.",
        "C. Linder, Verschleiss von Eisenbahnraedern mit Unrundheiten, Dissertation ETH "
        "Zuerich Nr. 12342, 1997.",
    )

    def _solve_line(self, line, delta, opts):
        d0 = LINDER_FACTOR * delta
        g = d0 - line.f
        E_star = line.extra["E_star"]
        h = line.h
        out = []
        for i0, i1 in positive_runs(g).tolist():
            if i1 - i0 < 3:
                continue
            gi = g[i0:i1]
            xl = np.sqrt(gi / line.Ax[i0:i1])
            eta = line.eta[i0:i1]
            be = 0.5 * (i1 - i0) * h                        # eq. (6)
            yi = eta - 0.5 * (eta[0] + eta[-1])             # from the middle of the region
            c = np.sqrt(np.clip(be * be - yi * yi, (0.25 * h) ** 2, None))
            ae = xl * be / c                                # eq. (7)
            zm = (be * be - yi * yi - gi * gi) / (2.0 * gi)  # eq. (8)
            # eq. (8): + 0.45 δ; for a separate region the 0.45 δ is taken relative to its own
            # virtual depth, 0.45/0.55 max g (= 0.45 δ for the region of the contact point)
            de = np.sqrt(be * be + zm * zm) - zm + (1.0 - LINDER_FACTOR) / LINDER_FACTOR * float(
                gi.max())
            Ni = hertz_load_from_axes(ae, be, de, E_star)
            p0 = 1.5 * Ni / (math.pi * ae * be) * c / be    # eq. (9)
            N = float(np.sum(0.5 * math.pi * xl * p0) * h)  # eq. (10)
            if not N > 0:
                continue
            j = int(np.argmax(gi))
            out.append(Region(slice(i0, i1), i0 + j, N, eta, xl, p0, gi,
                              strip_axes=(ae, np.full(ae.shape, be)),
                              info={"penetration_factor": LINDER_FACTOR,
                                    "virtual_penetration": d0, "b_e": be}))
        return out

    def _patch_info(self, reg, opts):
        return {"traction_bound": "parabolic", "fastsim_flexibility": "three"}
