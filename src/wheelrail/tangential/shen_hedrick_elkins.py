"""Shen–Hedrick–Elkins creep-force law: Kalker's linear theory saturated by Johnson–Vermeulen.

The linear creep forces of Kalker (with spin, :mod:`wheelrail.conventions`)

    Fx' = −G c² C11 ξ,   Fy' = −G c² (C22 η + c C23 φ),   Mz' = G c³ (C23 η − c C33 φ)

are combined into the resultant F' = √(Fx'² + Fy'²) which is saturated with
the cubic of Johnson and Vermeulen (1964), u = F'/(μ N)::

    F = μN [u − u²/3 + u³/27]   for u < 3,
    F = μN                      for u ≥ 3,

and both force components are scaled by the same factor ε = F / F' (the
direction of the linear force is kept). The cubic has F = μN and dF/dF' = 0
at u = 3, so the law is C¹.

Spin moment
-----------
Shen, Hedrick and Elkins (1983) define the saturation for the resultant of
the tangential forces only; they prescribe no saturation law for the spin
moment, and codes that use their method either keep Kalker's linear moment
or scale it with the same factor ε. Both are offered:
``spin_moment="scaled"`` (default) returns ε·Mz', so that the moment
saturates together with the forces and stays bounded as the creepages grow
(a linear moment grows without limit, which is unphysical at large spin);
``spin_moment="linear"`` returns Kalker's linear Mz' unchanged.

References
----------
.. [1] Z.Y. Shen, J.K. Hedrick, J.A. Elkins, A comparison of alternative creep
   force models for rail vehicle dynamic analysis, Proc. 8th IAVSD Symposium,
   Cambridge MA, 1983 (Swets & Zeitlinger, Lisse, 1984), pp. 591–605.
.. [2] K.L. Johnson, P.J. Vermeulen, Contact of nonspherical elastic bodies
   transmitting tangential forces, J. Appl. Mech. 31 (1964) 338–340.
.. [3] J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
   Kluwer 1990, linear theory (creep coefficients C11 … C33).
.. [4] N. Bosso, M. Spiryagin, A. Gugliotta, A. Somà, *Mechatronic Modeling of Real-Time Wheel-Rail Contact*, Springer 2013, ch. 2 (review of wheel–rail contact models), eq. (2.11).
"""

from __future__ import annotations

import numpy as np

from .._validation import scalar_or_array
from ..options import configured, option
from ..results import CreepForcesResult, Status
from ._base import TangentialMethod
from .linear import kalker_coefficients

__all__ = ["ShenHedrickElkins", "johnson_vermeulen", "she_saturation_ratio",
           "shen_hedrick_elkins_forces"]

_SPIN_MOMENT_CHOICES = ("scaled", "linear")


def johnson_vermeulen(u):
    """Johnson–Vermeulen saturation F/(μN) as a function of u = F_linear/(μN).

    Parameters
    ----------
    u : array_like
        Linear resultant over μN [-], ≥ 0.

    Returns
    -------
    ndarray
        u − u²/3 + u³/27 for u < 3, 1 for u ≥ 3 (same shape as ``u``).
    """
    u = np.asarray(u, dtype=float)
    return np.where(u < 3.0, u * (1.0 + u * (-1.0 / 3.0 + u / 27.0)), 1.0)


def she_saturation_ratio(u):
    """Scaling factor ε = F/F_linear = johnson_vermeulen(u)/u, finite at u = 0 (ε → 1).

    Parameters
    ----------
    u : array_like
        Linear resultant over μN [-], ≥ 0.

    Returns
    -------
    ndarray
        1 − u/3 + u²/27 for u < 3, 1/u for u ≥ 3.
    """
    u = np.asarray(u, dtype=float)
    big = u >= 3.0
    return np.where(big, 1.0 / np.where(big, u, 1.0), 1.0 + u * (-1.0 / 3.0 + u / 27.0))


def shen_hedrick_elkins_forces(G, a, b, C11, C22, C23, C33, xi, eta, phi, mu, Fn,
                               spin_moment="scaled"):
    """Shen–Hedrick–Elkins creep forces (pure array kernel, broadcasting).

    Parameters
    ----------
    G : float or ndarray
        Combined shear modulus [Pa].
    a, b : ndarray, shape (n,) or ()
        Contact semi-axes along x and y [m].
    C11, C22, C23, C33 : ndarray
        Kalker's creep coefficients for a/b and ν [-].
    xi, eta : ndarray
        Longitudinal and lateral creepage [-].
    phi : ndarray
        Spin creepage [1/m].
    mu : ndarray
        Friction coefficient [-], > 0.
    Fn : ndarray
        Normal force [N], > 0.
    spin_moment : {"scaled", "linear"}
        Mz saturated with the force factor, or Kalker's linear Mz.

    Returns
    -------
    Fx, Fy, Mz, ratio : ndarray
        Forces on the wheel [N], spin moment [N·m] (Kalker's signs) and the
        saturation factor ε = F/F_linear [-].
    """
    c = np.sqrt(a * b)
    k = G * c * c
    fx = -k * C11 * xi
    fy = -k * (C22 * eta + c * C23 * phi)
    mz = k * c * (C23 * eta - c * C33 * phi)
    u = np.hypot(fx, fy) / (mu * Fn)
    ratio = she_saturation_ratio(u)
    if spin_moment == "scaled":
        mz = ratio * mz
    return ratio * fx, ratio * fy, mz, ratio


@configured
class ShenHedrickElkins(TangentialMethod):
    """Shen–Hedrick–Elkins (1983) creep-force law (Kalker linear + Johnson–Vermeulen cubic).

    On a :class:`~wheelrail.patch.ContactPatch` (``wr.solve``) this law
    uses the patch's equivalent ellipse (:meth:`ContactPatch.ellipse`: the Hertz
    ellipse of a Hertzian patch, otherwise the ellipse of equal area and
    length/width ratio).

    Other Parameters
    ----------------
    spin_moment : {"scaled", "linear"}
        ``"scaled"`` (default): Mz = ε Mz_linear with the force saturation
        factor ε; ``"linear"``: Kalker's linear moment unchanged.

    Notes
    -----
    Closed form, vectorised over batches; ``info["saturation"]`` holds ε.
    Kalker's coefficients come from
    :func:`wheelrail.tangential.linear.kalker_coefficients` for a/b and the
    combined Poisson ratio of the contact.
    """

    name = "shen-hedrick-elkins"
    references = (
        "Z.Y. Shen, J.K. Hedrick, J.A. Elkins, A comparison of alternative creep force models "
        "for rail vehicle dynamic analysis, Proc. 8th IAVSD Symposium, Cambridge MA, 1983, "
        "pp. 591-605.",
        "K.L. Johnson, P.J. Vermeulen, Contact of nonspherical elastic bodies transmitting "
        "tangential forces, J. Appl. Mech. 31 (1964) 338-340.",
        "J.J. Kalker, Three-dimensional elastic bodies in rolling contact, Kluwer, 1990.",
    )
    aliases = ("she", "shen_hedrick_elkins")
    spin_moment: str = option("scaled", choices=_SPIN_MOMENT_CHOICES,
                              doc="spin moment scaled by the force saturation, or linear")

    def solve(self, contact, xi, eta, phi, mu):
        spin_moment = self.spin_moment
        a = np.asarray(contact.a, dtype=float)
        b = np.asarray(contact.b, dtype=float)
        Fn = np.asarray(contact.Fn, dtype=float)
        C11, C22, C23, C33 = kalker_coefficients(a / b, contact.nu)
        Fx, Fy, Mz, ratio = shen_hedrick_elkins_forces(
            contact.G, a, b, np.asarray(C11), np.asarray(C22), np.asarray(C23),
            np.asarray(C33), xi, eta, phi, mu, Fn, spin_moment)
        s = scalar_or_array
        return CreepForcesResult(Fx=s(Fx), Fy=s(Fy), Mz=s(Mz), Fn=s(Fn), mu=s(np.asarray(mu)),
                           method=self.name, status=Status.CONVERGED,
                           info={"saturation": s(ratio)})
