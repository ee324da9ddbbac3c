"""FaStrip: a strip theory of rolling contact as an alternative to FASTSIM.

Every strip of a contact patch (along the rolling direction, half-length
a_s, normal load per unit width P_s) is treated as a two-dimensional rolling
contact with a semi-elliptic traction bound μp (Carter's solution, the strip
theory of Haines & Ollerton extended by Kalker to combined creepage): the
adhesion zone starts at the leading edge and shrinks as the creepage grows,
and the strip force per unit width is::

    f = f_sat (1 − (1 − r)²)   (r < 1),   f = f_sat   (r ≥ 1),   f_sat = μ P_s,
    r = |f_lin| / (2 f_sat),   f_lin = −2 a_s² (ξ_s / L1, η_s / L2)

so that its slope at zero creepage is the simplified theory's (FASTSIM's
linear strip force 2a_s² ν / L with Kalker's flexibilities L1, L2, eq. 11)
and it saturates at μ P_s, in the direction of the elastic (linear) force.
Creepages per strip: ξ_s = ξ − φ y (the spin's rigid slip, locally on the
strip at lateral position y) and η_s = η + (L2/L3) φ a_s / 3, the constant
lateral creepage that gives the same linear strip force as the spin term
φ x (∫(a² − x²)/2 dx = (a/3) ∫(a − x) dx).

This follows the idea of Sichani, Enblom & Berg's FaStrip (strip theory for
the translational creepages, spin as a strip-wise equivalent creepage). The
paper itself was not available when this was written: the spin treatment
above is this project's derivation, not a transcription of their equations,
and differs from FaStrip where their spin correction does. Known weakness
(measured, tests/reference/test_nonhertz_fastrip.py): the spin's equivalent
creepage saturates like a translation, so at large spin (φ·√(ab) ≳ 0.5 %)
the lateral force is overestimated (≈ ×2.4 of the exact theory at
φ = 3 1/m, a = b ≈ 6 mm); ``Mz`` comes from strip forces at the strip centres
only and is underestimated.

References
----------
.. [1] M. Sh. Sichani, R. Enblom, M. Berg, An alternative to FASTSIM for
   tangential solution of the wheel–rail contact, Vehicle System Dynamics 54
   (2016) 748–764.
.. [2] J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
   Kluwer 1990, §2.4 (strip theory).
.. [3] F.W. Carter, On the action of a locomotive driving wheel, Proc. R. Soc.
   Lond. A 112 (1926) 151–157.
"""

from __future__ import annotations

import numpy as np

from ..options import configured, option
from ..patch import ContactPatch
from ..results import CreepForcesResult, Status
from ._base import TangentialMethod
from .fastsim import combined_flexibility, flexibilities, weighted_flexibility
from .linear import kalker_coefficients

__all__ = ["Fastrip", "fastrip_strips"]


def fastrip_strips(y, dy, a_s, xc, P, L1, L2, L3, xi, eta, phi, mu):
    """Strip-theory creep forces of a patch given by strips (pure kernel).

    Parameters
    ----------
    y, dy, a_s, xc : ndarray, shape (ny,)
        Strip centres, widths, half-lengths and longitudinal centres [m].
    P : ndarray, shape (ny,)
        Normal load per unit width of every strip [N/m].
    L1, L2, L3 : ndarray, shape (ny,)
        Kalker's flexibilities [m/Pa].
    xi, eta, phi, mu : float
        Creepages [-], [-], [1/m] and friction coefficient [-].

    Returns
    -------
    Fx, Fy, Mz : float
        Forces [N] and moment about the origin [N m] on the wheel (strip
        forces acting at the strip centres (xc, y)).
    slip_fraction : float
        Share of the load in saturated strips.
    """
    on = a_s > 0
    xs = xi - phi * y
    es = eta + (L2 / L3) * phi * a_s / 3.0
    fx = -2.0 * a_s * a_s * xs / L1
    fy = -2.0 * a_s * a_s * es / L2
    flin = np.hypot(fx, fy)
    fsat = mu * P
    with np.errstate(invalid="ignore", divide="ignore"):
        r = np.where(fsat > 0, flin / (2.0 * np.where(fsat > 0, fsat, 1.0)), np.inf)
        mag = np.where(r < 1.0, fsat * (1.0 - (1.0 - r) ** 2), fsat)
        scale = np.where(flin > 0, mag / np.where(flin > 0, flin, 1.0), 0.0)
    scale = np.where(on, scale, 0.0)
    Fx = float(np.sum(scale * fx * dy))
    Fy = float(np.sum(scale * fy * dy))
    Mz = float(np.sum((xc * scale * fy - y * scale * fx) * dy))
    sat = (r >= 1.0) & on
    tot = float(np.sum(P * dy))
    return Fx, Fy, Mz, (float(np.sum((P * dy)[sat])) / tot if tot > 0 else 0.0)


@configured
class Fastrip(TangentialMethod):
    """FaStrip strip theory as a creep-force law (see the module docstring).

    Works on every patch (Hertzian ellipses through their strips, the
    virtual-penetration patches with their per-strip or weighted
    flexibilities as in FASTSIM, boundary-element patches).

    Other Parameters
    ----------------
    ny : int, default 40
        Strips across an ellipse (Hertzian contacts; other patches use their
        own strips).
    """

    name = "fastrip"
    references = (
        "M. Sh. Sichani, R. Enblom, M. Berg, An alternative to FASTSIM for tangential solution "
        "of the wheel-rail contact, Vehicle System Dynamics 54 (2016) 748-764.",
        "J.J. Kalker, Three-dimensional elastic bodies in rolling contact, Kluwer, 1990.",
    )
    ny: int = option(40, lo=2, hi=2000, doc="strips across an ellipse (Hertzian contacts)")

    def solve(self, contact, xi, eta, phi, mu):
        ny = self.ny
        single = np.shape(contact.a) == ()
        xi, eta, phi, mu = (np.atleast_1d(np.asarray(v, dtype=float)) for v in (xi, eta, phi, mu))
        n = xi.shape[0]
        F = np.zeros((3, n))
        for k in range(n):
            c = contact if single else contact[k]
            p = ContactPatch.from_hertz(c, strips=ny, cells=8)
            r = self.solve_patch(p, xi[k], eta[k], phi[k], mu[k])
            F[:, k] = (r.Fx, r.Fy, r.Mz)
        Fn = np.atleast_1d(np.asarray(contact.Fn, dtype=float))
        out = (lambda v: float(v[0])) if single else (lambda v: np.asarray(v))
        return CreepForcesResult(Fx=out(F[0]), Fy=out(F[1]), Mz=out(F[2]), Fn=out(Fn),
                           mu=out(mu), method=self.name, status=Status.CONVERGED,
                           iterations=None, fields=None, info={"ny": ny})

    def solve_patch(self, patch, xi, eta, phi, mu):
        xi, eta, phi, mu = float(xi), float(eta), float(phi), float(mu)
        G, nu = patch.materials.G, patch.materials.nu
        axes = patch.info.get("strip_semiaxes")
        if axes is not None:
            sa, sb = (np.asarray(v, dtype=float) for v in axes)
        else:
            sa = np.full(patch.y.shape, patch.a)
            sb = np.full(patch.y.shape, patch.b)
        C11, C22, C23, _ = kalker_coefficients(sa / sb, nu)
        L1, L2, L3 = flexibilities(sa, sb, G, C11, C22, C23)
        if patch.info.get("fastsim_flexibility") == "weighted":
            L1 = L2 = L3 = weighted_flexibility(L1, L2, L3, xi, eta, phi, np.sqrt(sa * sb))
        elif patch.info.get("fastsim_flexibility") == "combined":
            L1 = L2 = L3 = np.array([combined_flexibility(*v, xi, eta, phi, ak)
                                     for *v, ak in zip(L1, L2, L3, sa)])
        length = np.clip(patch.x_lead - patch.x_trail, 0.0, None)
        P = patch.strip_pressure.sum(axis=1) * length / patch.cells
        # the strip loads sampled at the cells' midpoints differ slightly from Fn (on an
        # ellipse's 8 cells per strip by 1.3 %): scale the loads, i.e. the bounds μ P_s, to
        # the patch force, and leave the linear (elastic) strip forces as they are
        tot = float(np.sum(P * patch.dy))
        if tot > 0:
            P = P * (patch.Fn / tot)
        Fx, Fy, Mz, sat = fastrip_strips(patch.y, patch.dy, 0.5 * length,
                                         0.5 * (patch.x_lead + patch.x_trail), P,
                                         np.broadcast_to(L1, patch.y.shape),
                                         np.broadcast_to(L2, patch.y.shape),
                                         np.broadcast_to(L3, patch.y.shape), xi, eta, phi, mu)
        xc, yc = patch.centre
        Mz = Mz - xc * Fy + yc * Fx
        status = Status.FULL_SLIP if sat >= 1.0 else Status.CONVERGED
        return CreepForcesResult(Fx=Fx, Fy=Fy, Mz=float(Mz), Fn=patch.Fn, mu=mu, method=self.name,
                           status=status, iterations=None, fields=None,
                           info={"saturated_load_fraction": sat})
