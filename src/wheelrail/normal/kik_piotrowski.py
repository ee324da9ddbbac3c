"""Kik & Piotrowski's virtual-penetration method for non-Hertzian normal contact.

The bodies are virtually pressed together by δ0 = ε δ; the interpenetration
region (Piotrowski & Chollet (2005) eqs. 4–5) is taken as the contact patch, the pressure is
semi-elliptic along every strip with one peak p0 (eq. 12), and the load
follows from the deflection condition at the reference point,
2 w0 = δ (eqs. 13–16)::

    N  = π E* δ I1 / I2,   p0 = N x_l(0) / I1,
    I1 = ∫∫ √(x_l² − x²) dx dy,   I2 = ∫∫ √(x_l² − x²)/√(x² + y²) dx dy

(E* the contact modulus; for identical bodies πE* = πE/(2(1 − σ²)) as in
eq. 15). δ of a region is its virtual depth over ε, max g/ε: δ itself for the
region around the rigid contact point; for a separate (secondary) region this
makes its load grow from zero as it appears (δ − f_min would start it with a
finite load and a pressure peak on a sliver; a choice of this implementation). The inner x-integral of I2 is done in closed form with complete
elliptic integrals (:func:`wheelrail.normal._strips.kp_integrals`).

Ellipticity correction (``ellipticity_correction=True``, not the default): Vollebregt's
KPEC variant (CONTACT's user guide, "Fast or detailed solution"). Each region
of real interpenetration gets its own penetration δ_r = δ − f_min and an
equivalent Hertz ellipse (curvature A_x at the deepest node; B from the width w
of the region where f − f_min ≤ δ_r/2, B = δ_r/(2w²)); the virtual penetration
varies across the region, t(y) = A a² − (A a² − B b²)((y − y_m)/b)² (clipped to
[0, δ_r]), so that a quadratic gap gives exactly Hertz's ellipse; the pressure
is Kik & Piotrowski's (eqs. 12–16 below) with δ_r. It replaces the constant
penetration factor and the shape correction described next (kernel:
:func:`wheelrail.normal._kp_kernel.kpec_line_regions`).

Penetration factor ε (``ellipticity_correction=False``, the default): the original method uses ε = 0.55; the default here
(``penetration_factor="hertz"``) takes ε from Hertz's theory for the local
curvatures A, B at the reference point, ε = a b √(AB)/δ, so that a Hertzian
gap gives exactly Hertz's area. The shape correction (eqs. 17–22) stretches
the region across the rail and along it (modified radius, eq. 22) so that
its length/width ratio is Hertz's ratio for the curvatures 4δ0/L², 4δ0/W² of
the uncorrected region, keeping its area; with both (the default) a Hertzian
gap reproduces Hertz's area, maximum pressure and load.

References
----------
.. [1] J. Piotrowski, H. Chollet, Wheel–rail contact models for vehicle system
   dynamics including multi-point contact, VSD 43 (2005), §3.2, eqs. (12)–(22).
.. [2] W. Kik, J. Piotrowski, A fast, approximate method to calculate normal load at
   contact between wheel and rail and creep forces during rolling, 2nd mini
   conference on contact mechanics and wear of rail/wheel systems, Budapest 1996.
.. [3] J. Piotrowski, W. Kik, A simplified model of wheel/rail contact mechanics for
   non-Hertzian problems and its application in rail vehicle dynamic simulations,
   VSD 46 (2008) 27–48.
.. [4] E.A.H. Vollebregt, User guide for CONTACT, rolling and sliding contact with
   friction, VORtech technical report TR20-01 (open-source version), "Fast or detailed
   solution" (KPEC) and "Modified FASTSIM" (flexibilities of the equivalent ellipse).
.. [5] E.A.H. Vollebregt, P. Voltr, Improved accuracy for FASTSIM using one or three
   flexibility values, Vehicle System Dynamics 61 (2023) 309–317.
"""

from __future__ import annotations

import math
import numbers
from typing import Any

import numpy as np

from ..errors import InputError
from ..options import configured, option
from . import _kp_kernel
from ._base import NormalMethod, PatchDescription
from ._patch_kernel import positive_runs
from ._strips import (
    _LN_MAX,
    Region,
    VirtualPenetration,
    _hertz_table,
    hertz_ab,
    hertz_penetration_factor,
    line_samples,
)

__all__ = ["KikPiotrowski", "penetration_factor"]

#: The constant penetration factor of the original method (and of Linder).
ORIGINAL_FACTOR = 0.55


def penetration_factor(value, A, B):
    """ε = δ0/δ: ``"hertz"`` (from the curvatures A, B [1/m]) or a number in (0, 1]."""
    if isinstance(value, str):
        if value != "hertz":
            raise InputError(f"penetration_factor must be 'hertz' or a number in (0, 1], got "
                             f"{value!r}")
        if A > 0 and B > 0:
            return hertz_penetration_factor(A, B), "hertz"
        return ORIGINAL_FACTOR, "0.55 (curvatures at the reference point not convex)"
    v = float(value)
    if not (math.isfinite(v) and 0.0 < v <= 1.0):
        raise InputError(f"penetration_factor must lie in (0, 1], got {value!r}")
    return v, "given"


def _penetration_factor_option(name, value):
    """The ``penetration_factor`` option: ``"hertz"`` or a number in (0, 1]."""
    if isinstance(value, str):
        if value != "hertz":
            raise InputError(f"{name} must be 'hertz' or a number in (0, 1], got {value!r}")
        return value
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        raise InputError(f"{name} must be 'hertz' or a number in (0, 1], got {value!r}")
    if not (math.isfinite(float(value)) and 0.0 < float(value) <= 1.0):
        raise InputError(f"{name} must lie in (0, 1], got {value!r}")
    return float(value)


def shape_correction(eta, xl, h, j0):
    """Kik & Piotrowski's shape correction of one region (Piotrowski & Chollet (2005) eqs. 17–22) (pure kernel).

    Parameters
    ----------
    eta, xl : ndarray, shape (n,)
        Nodes [m] (uniform, spacing ``h``) and strip half-lengths [m].
    j0 : int
        Node kept in place (the geometric point of contact).

    Returns
    -------
    eta_c, xl_c : ndarray
        Stretched nodes and half-lengths (W_c/W across, L_c/L along; L_c W_c = L W).
    h_c : float
        New node spacing.
    alpha : float
        L_c / W_c (Hertz's a/b for A/B = (W/L)²).
    """
    L = 2.0 * float(np.max(xl))
    W = xl.size * h
    a, b = hertz_ab((W / L) ** 2, 1.0)
    alpha = a / b
    sy = math.sqrt(L / (alpha * W))          # W_c / W   (eq. 19)
    sx = 1.0 / sy                            # L_c / L   (area kept)
    eta_c = eta[j0] + (eta - eta[j0]) * sy   # eq. (20)-(21): stretch about y0
    return eta_c, xl * sx, h * sy, alpha


@configured
class KikPiotrowski(VirtualPenetration, NormalMethod, PatchDescription):
    """Kik–Piotrowski virtual penetration as a normal method (see the module docstring).

    Works on a gap h(x, y) (rolling direction x; load or approach prescribed),
    on a Hertzian contact (its quadratic gap), and on a wheel on its rail:
    candidate contact points are grouped by contact plane, each plane's
    profile separation f(η) (:meth:`WheelProblem.separation`) is
    interpenetrated by ε·dz·cos, every connected region is a patch, and the
    vertical approach dz follows from Σ Fn cos γ = Q.

    Other Parameters
    ----------------
    penetration_factor : "hertz" or float in (0, 1], default "hertz"
        ε = δ0/δ; 0.55 gives the original method.
    shape_correction : bool, default True
        Kik & Piotrowski's correction of the length/width ratio (eqs. 17–22).
    strips, cells : int, default 40, 40
        Strips of each patch and cells per strip of the patch description
        (the integrals use the full line resolution).
    line_nodes : int, default 1601
        Nodes of a wheel's separation line, 40 mm wide (1601: 0.025 mm apart); the
        profiles are sampled 1.6 node spacings apart. Coarser lines are faster
        (``wr.dynamics`` uses 201 by default; see there for the measured difference).

    ellipticity_correction : bool, default False
        Vollebregt's KPEC (see the module docstring): a variable virtual penetration
        from each region's equivalent Hertz ellipse. When True, ``penetration_factor``
        and ``shape_correction`` do not apply (setting them to other than their
        defaults is refused); False gives Kik & Piotrowski's method with them. Not the
        default: in the quasi-static flange climb of S1002 on 60E1 (20 mrad, 100 kN
        axle) its flange patch reports a contact angle of 88.6° instead of the
        flange's 70° (an open defect).
    fastsim_flexibility : {"weighted", "combined", "three"}, default "weighted"
        Flexibility FASTSIM uses on these patches (``info["fastsim_flexibility"]``),
        from the three flexibilities L1, L2, L3 of the patch's equivalent ellipse:
        one combined flexibility (Vollebregt & Voltr 2023; the value CONTACT blends
        to at large creepage), L = (ξ² + η² + s²)/(ξ²/L1 + η²/L2 + s²/L3) with
        s = 3πaφ/32, the one flexibility that keeps the linear theory's
        ξFx + η Fy + φ-part work (cross term ηφ left out); Kalker's weighted
        L = (L1|ξ| + L2|η| + L3 c|φ|)/√(ξ² + η² + c²φ²) (Kik & Piotrowski's choice); or
        L1, L2, L3 themselves. On Manchester A-2.2 against CONTACT's full solution
        (``benchmarks/bench_manchester.py``), with the ellipticity correction: max
        error 4.2 % of μFn in Fx and 11.05 % in Fs (combined); 7.0 / 22.2 % (weighted);
        4.4 / 12.0 % (three). Without it (Kik & Piotrowski's patch, the default):
        11.5 / 24.7 % (weighted), 13.6 / 12.0 % (combined), 12.9 / 12.5 % (three).

    Tangential: FASTSIM solves these patches strip by strip with the flexibility above.

    References
    ----------
    .. [1] Piotrowski & Chollet (2005) §3.2, eqs. (12)–(22); Piotrowski & Kik, VSD 46 (2008).
    """

    name = "kik-piotrowski"
    references = (
        "J. Piotrowski, H. Chollet, Wheel-rail contact models for vehicle system dynamics "
        "including multi-point contact, Vehicle System Dynamics 43 (2005) 455-483.",
        "J. Piotrowski, W. Kik, A simplified model of wheel/rail contact mechanics for "
        "non-Hertzian problems and its application in rail vehicle dynamic simulations, "
        "Vehicle System Dynamics 46 (2008) 27-48.",
    )
    penetration_factor: Any = option("hertz", kind="any", check=_penetration_factor_option,
                                     doc="epsilon = delta0/delta: 'hertz' or a number in (0, 1]")
    shape_correction: bool = option(True, doc="Kik & Piotrowski's length/width correction")
    line_nodes: int = option(1601, lo=101, hi=6401,
                             doc="nodes of a wheel's separation line (40 mm wide)")
    ellipticity_correction: bool = option(False, doc="Vollebregt's KPEC: variable virtual "
                                                    "penetration from Hertz's ellipse")
    fastsim_flexibility: str = option("weighted", choices=("combined", "weighted", "three"),
                                      doc="flexibility FASTSIM uses on these patches: one "
                                          "combined (Vollebregt & Voltr), Kalker's weighted "
                                          "(Kik & Piotrowski) or L1, L2, L3 of the equivalent "
                                          "ellipse")

    @property
    def profile_samples(self) -> int:
        """Profile samples per body (on 80 mm) behind a wheel line of ``line_nodes`` nodes."""
        return line_samples(self.line_nodes)

    def _kpec(self, opts):
        """True for the ellipticity correction; refuses options it replaces."""
        if not opts.get("ellipticity_correction", False):
            return False
        if opts["penetration_factor"] != "hertz" or not opts["shape_correction"]:
            raise InputError("penetration_factor and shape_correction apply with "
                             "ellipticity_correction=False only (got penetration_factor="
                             f"{opts['penetration_factor']!r}, shape_correction="
                             f"{opts['shape_correction']!r})")
        return True

    @staticmethod
    def _line_arrays(line):
        Ax = line.extra.get("Ax_array")
        if Ax is None:
            Ax = line.extra["Ax_array"] = np.ascontiguousarray(
                np.broadcast_to(line.Ax, line.f.shape), dtype=float)
        return Ax

    def _solve_line(self, line, delta, opts):
        if self._kpec(opts):
            lam, la, lb, _, ld = _hertz_table()
            _, meta, eta_c, xl_c, peak, g = _kp_kernel.kpec_line_regions(
                line.f, self._line_arrays(line), line.eta, float(line.h), float(delta),
                line.extra["E_star"], lam, la, lb, ld, _LN_MAX)
            out = []
            for i0, i1, j, N, p0, alpha, pen, eps_j in meta.tolist():
                i0, i1, j = int(i0), int(i1), int(j)
                out.append(Region(slice(i0, i1), i0 + j, N, eta_c[i0:i1].copy(),
                                  xl_c[i0:i1].copy(), peak[i0:i1].copy(), g[i0:i1].copy(),
                                  info={"penetration_factor": eps_j, "factor_from": "kpec",
                                        "virtual_penetration": eps_j * pen,
                                        "shape_correction": False, "alpha": alpha, "p0": p0}))
            return out
        eps, how = self._eps(line, opts)
        correct = bool(opts["shape_correction"])
        d0 = eps * delta
        g = d0 - line.f
        E_star = line.extra["E_star"]

        # the regions in one kernel (the arithmetic of the loop below)
        Ax = line.extra.get("Ax_array")
        if Ax is None:
            Ax = line.extra["Ax_array"] = np.ascontiguousarray(
                np.broadcast_to(line.Ax, line.f.shape), dtype=float)
        lam, la, lb, _, _ = _hertz_table()
        ok, meta, eta_c, xl_c, peak = _kp_kernel.kp_line_regions(
            line.f, Ax, line.eta, float(line.h), d0, eps, E_star, correct, lam, la, lb, _LN_MAX)
        if ok:
            out = []
            for i0, i1, j, N, p0, alpha in meta.tolist():
                i0, i1, j = int(i0), int(i1), int(j)
                out.append(Region(slice(i0, i1), i0 + j, N, eta_c[i0:i1] if correct else
                                  line.eta[i0:i1], xl_c[i0:i1], peak[i0:i1], g[i0:i1],
                                  info={"penetration_factor": eps, "factor_from": how,
                                        "virtual_penetration": d0, "shape_correction": correct,
                                        "alpha": alpha if correct else None, "p0": p0}))
            return out

        out = []
        h_line = line.h
        for i0, i1 in positive_runs(g).tolist():
            if i1 - i0 < 3:
                continue                # narrower than the line's resolution
            gi = g[i0:i1]
            xl = np.sqrt(gi / line.Ax[i0:i1])
            j = int(np.argmax(gi))
            # penetration of the region consistent with its virtual depth: g_max / ε
            # (= δ − f_min for the region of the rigid contact point, where f_min = 0; for a
            # separate region the load then vanishes with the region instead of jumping)
            real = float(gi[j]) / eps
            eta = line.eta[i0:i1]
            h = h_line
            alpha = None
            if correct:
                eta, xl, h, alpha = shape_correction(eta, xl, h, j)
            I1, I2 = _kp_kernel.kp_integrals_kernel(np.ascontiguousarray(xl, dtype=float),
                                                    float(h), j)
            N = math.pi * E_star * real * I1 / I2
            p0 = N * xl[j] / I1
            out.append(Region(slice(i0, i1), i0 + j, N, eta, xl, p0 * xl / xl[j], gi,
                              info={"penetration_factor": eps, "factor_from": how,
                                    "virtual_penetration": d0, "shape_correction": correct,
                                    "alpha": alpha, "p0": p0}))
        return out

    def _line_loads(self, line, delta, opts):
        # the load iteration's hot path: the same equations as _solve_line in one kernel
        if self._kpec(opts):
            args = line.extra.get("kpec_load")
            if args is None:
                ang = line.angle
                if ang is None:
                    ang = np.zeros_like(line.f)
                lam, la, lb, _, ld = _hertz_table()
                args = line.extra["kpec_load"] = (
                    self._line_arrays(line), np.ascontiguousarray(line.eta, dtype=float),
                    np.ascontiguousarray(ang, dtype=float), float(line.h),
                    line.extra["E_star"], lam, la, lb, ld)
            Ax, eta, ang, h, E_star, lam, la, lb, ld = args
            N, Nz = _kp_kernel.kpec_line_load(line.f, Ax, eta, ang, h, float(delta), E_star,
                                              lam, la, lb, ld, _LN_MAX)
            return float(N), float(Nz)
        key = ("kp_load", opts["penetration_factor"],
               bool(opts["shape_correction"]))
        args = line.extra.get(key)
        if args is None:
            eps = self._eps(line, opts)[0]
            ang = line.angle
            if ang is None:
                ang = np.zeros_like(line.f)
            lam, la, lb, _, _ = _hertz_table()
            args = line.extra[key] = (_kp_kernel.kp_line_load, line.f,
                                      np.asarray(line.Ax, dtype=float), ang, line.h, eps,
                                      line.extra["E_star"], key[2], lam, la, lb)
        kern, f, Ax, ang, h, eps, E_star, correct, lam, la, lb = args
        N, Nz = kern(f, Ax, ang, h, eps * delta, eps, E_star, correct, lam, la, lb)
        return float(N), float(Nz)

    @staticmethod
    def _eps(line, opts):
        """(ε, how) of the line for the option penetration_factor (cached on the line)."""
        key = ("eps", opts["penetration_factor"])
        if key not in line.extra:
            line.extra[key] = penetration_factor(opts["penetration_factor"],
                                                 line.A, line.B)
        return line.extra[key]

    def _patch_info(self, reg, opts):
        return {"fastsim_flexibility": opts.get("fastsim_flexibility", "weighted")}
