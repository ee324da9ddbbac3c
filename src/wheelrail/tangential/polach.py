"""Polach's creep-force law (1999) with the 2005 extension for large creepages.

Notation of Polach: wheel load Q = Fn, semi-axes a (rolling direction) and
b, creepages sx = ξ, sy = η, spin φ [1/m]. The formulas below give forces
Fx_P, Fy_P in the direction of the creepage; the forces on the wheel in
Kalker's convention (:mod:`wheelrail.conventions`) are their negatives,
Fx = −Fx_P, Fy = −Fy_P, which is also what the transcription of Polach's
FORTRAN listing returns (see *Verification*).

Longitudinal and lateral creep (Polach 1999, 2005)
--------------------------------------------------
::

    F   = (2 Q μ / π) [ kA ε / (1 + (kA ε)²) + arctan(kS ε) ]
    ε   = (2/3) C π a² b s_C / (Q μ) = (π/4) G a b c_jj s_C / (Q μ)
    c_jj = √((C11 sx/s)² + (C22 sy/s)²),   s = √(sx² + sy²)

with C = 3 G c_jj / (8 a) taken from Kalker's linear coefficients so that
the initial slope equals Kalker's linear theory (for kA = kS = 1); s_C is
the spin-corrected creepage below (s_C = s without spin). The 1999 law is
the case kA = kS = 1. The direction is that of the creepage:
Fx_P = F sx/s_C, Fy_P = F sy/s_C + F_yS.

Spin (Polach 1999)
------------------
The lateral creepage is increased by the spin where it acts in the same
direction::

    s_yC = sy + φ a   if |sy + φ a| > |sy|,   s_yC = sy otherwise
    s_C  = √(sx² + s_yC²)

(s_C replaces s in ε), and the lateral force gains::

    F_yS = −(9/16) a Q μ K_M [1 + 6.3 (1 − e^(−a/b))] φ / s_C
    K_M  = |ε_M| (δ³/3 − δ²/2 + 1/6) − (1/3) √((1 − δ²)³)
    δ    = (ε_M² − 1) / (ε_M² + 1)
    ε_M  = (8/3) G b √(ab) C23 s_C / (Q μ [1 + 6.3 (1 − e^(−a/b))])

K_M ≈ −(2/3) ε_M for small creepage, so F_yS → G c³ C23 φ, Kalker's linear
spin term. ε_M is taken proportional to s_C; with it the small-creepage spin
force is G c³ C23 φ whatever ξ and η are, as in Kalker's linear theory. The
public transcriptions we could read use |s_yC| instead of s_C in ε_M (see
*Verification*), which lowers the spin force when ξ ≠ 0; the two agree for
ξ = 0. Which one Polach's papers print could not be checked. For combined
ξ and η the small-creepage force is G ab c_jj s, Polach's blend of C11 and
C22, not exactly Kalker's C11 ξ, C22 η. Here K_M / s_C is evaluated in the
algebraically equivalent form ε_M/s_C · [h(δ) − (8/3) ε_M² / (1 + ε_M²)³],
h(δ) = δ³/3 − δ²/2 + 1/6, which has no 0/0 at zero creepage and no
cancellation in √(1 − δ²).

Friction decreasing with slip velocity (Polach 2005)
----------------------------------------------------
::

    μ = μ0 [ (1 − A) e^(−B w) + A ],   w = s_C V

with A = μ∞/μ0 and B [s/m]; μ0 is the ``mu`` passed to
:func:`wheelrail.creep_forces`. The same μ enters ε, ε_M, F and F_yS.
Polach requires kS ≤ kA ≤ 1; with these limits F ≤ μ Q (the bracket is
below π/2). That the spin term keeps √(Fx² + Fy²) ≤ μ Q is not proven here;
it holds on dense parameter scans and in the property tests.

Verification
------------
The papers themselves could not be read (the Bosso et al. (2013), ch. 2 only names the
method, refs. [4, 24, 5] there, and states that the friction of [5] varies
with velocity); no formula above is confirmed against Polach's printed text.
What was checked, against independent public implementations (secondary
sources, listed so that the check can be repeated):

* [S1] a Cython transcription of the FORTRAN listing of [1] (L. Baruffaldi,
  2024, ``polachContactForces.pyx``); [S2] a C++ multibody code
  (``WRcontForce::..._Creepforce``); [S3] a Python Polach routine with kA, kS
  (``polach(a, b, xix, ...)``, 2025); [S4] Open Rails ``Axle.cs``
  ``PolachCalculator`` (longitudinal only); [S5] a Python traction model
  citing "Wear 2005 eqs. (4), (9), (11), Table 2".
* Confirmed by S1, S2, S4 (and S3 for C): ε = π G a b c_jj s_C / (4 Q μ)
  with c_jj from C11, C22 and the *uncorrected* s (c_jj uses sx/s, sy/s,
  ε uses s_C); equivalently ε = (2/3) C π a² b s_C/(Q μ), C = 3 G c_jj/(8 a)
  (S3 writes exactly this C). C11 goes with sx, C22 with sy.
* Confirmed by S1 (1999) and S3, S5 (2005): F = (2Qμ/π)[ε/(1+ε²) + arctan ε]
  and its extension with kA ε/(1 + (kA ε)²) + arctan(kS ε); S5 and S3 keep
  kS ≤ kA ≤ 1. (S4 has a misprint, 1 + kA ε², in the denominator.)
* Confirmed by S2, S3: s_yC = sy + φ a when |sy + φ a| > |sy|, else sy.
  (S1 has the inequality the other way round, which we take for a
  transcription error: it would add the spin only where it opposes η; S4
  always adds φ a.)
* Confirmed by S1, S2 (S3 with a sign slip in the first term of K_M):
  F_yS = −(9/16) a Q μ K_M [1 + 6.3(1 − e^(−a/b))] φ/s_C,
  K_M = |ε_M|(δ³/3 − δ²/2 + 1/6) − (1/3)√((1 − δ²)³),
  δ = (ε_M² − 1)/(ε_M² + 1) and ε_M = (8/3) G b √(ab) C23 (·)/(Q μ
  [1 + 6.3(1 − e^(−a/b))]).
* Signs, confirmed by S1: FX = −Q·MI·SX/SC, FY = −Q(MI·SY + FYS·OM)/SC,
  which is Fx = −F sx/s_C, Fy = −(F sy/s_C + F_yS) with the *uncorrected* sy
  in the first term (also in S2): forces opposite to the creepage, Kalker's
  convention of :mod:`wheelrail.conventions`, and spin acting like positive
  η. (S2 adds F_yS with the opposite sign to the creep term, which would
  contradict Kalker's linear Fy = −G c²(C22 η + c C23 φ).)
* **Not confirmed**: the creepage in ε_M. S1, S2 and S3 all use |s_yC|
  (S2 the signed s_yC, which is the same since only ε_M² and |ε_M| enter);
  we use s_C (see *Spin*). The two differ only when ξ ≠ 0 and φ ≠ 0.
* Confirmed by S4, S5: μ = μ0[(1 − A)e^(−Bw) + A] with A = μ∞/μ0, B in
  s/m. **Not confirmed**: whether Polach's w is s·V or s_C·V (S4, S5 are
  longitudinal only, w = sx V); we use s_C V. Also not confirmed: that the
  2005 method keeps the spin term of 1999 unreduced by kA, kS (done here).
* Parameter sets: S5 gives dry kA 1.00, kS 0.40, A 0.40, B 0.60 s/m and wet
  kA 0.30, kS 0.10, A 0.40, B 0.20 s/m as "Wear 2005 Table 2"; S4
  interpolates kA = 2.8 μ0 − 0.54, kS = 1.2 μ0 − 0.26, B = 1.6 μ0 − 0.28,
  A = 0.4, lines that pass exactly through both sets at μ0 = 0.55 and
  μ0 = 0.30, which supports the μ0 values. The table number is from S5 only.
* No published numeric creep-force values (figures of [2]) could be
  retrieved, so none are pinned in the tests.

Spin moment
-----------
Polach's method gives no spin moment (it is neglected in the original
method); ``Mz`` is returned as 0.

References
----------
.. [1] O. Polach, A fast wheel–rail forces calculation computer code, Vehicle
   System Dynamics 33 (Suppl.) (1999) 728–739.
.. [2] O. Polach, Creep forces in simulations of traction vehicles running on
   adhesion limit, Wear 258 (2005) 992–1000 (extended method, reduction
   factors kA, kS and the friction law μ(w); parameter sets for dry and wet
   rails).
.. [3] J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
   Kluwer 1990 (creep coefficients C11, C22, C23).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numba import njit

from .._validation import positive, scalar_or_array
from ..errors import InputError
from ..options import configured, option
from ..plausibility import LIMITS
from ..results import CreepForcesResult, Status
from ._base import TangentialMethod
from .linear import kalker_coefficients

__all__ = ["Polach", "polach_forces", "polach_friction", "POLACH_2005_PARAMETERS"]

#: Parameters recommended by Polach for typical dry and wet rail conditions
#: (Wear 258 (2005) 992–1000, Table 2 according to a secondary source; values
#: checked against two independent implementations, see the module
#: docstring, *Verification*): kA, kS reduction factors [-], mu0 maximum
#: friction [-], A = μ∞/μ0 [-], B [s/m].
POLACH_2005_PARAMETERS = {
    "dry": {"kA": 1.00, "kS": 0.40, "mu0": 0.55, "A": 0.40, "B": 0.60},
    "wet": {"kA": 0.30, "kS": 0.10, "mu0": 0.30, "A": 0.40, "B": 0.20},
}

_SPIN_SHAPE = 6.3  # Polach's factor in 1 + 6.3 (1 − exp(−a/b))


def polach_friction(mu0, w, A=None, B=None):
    """Slip-velocity dependent friction μ = μ0 [(1 − A) e^(−B w) + A] (Polach 2005).

    Parameters
    ----------
    mu0 : array_like
        Maximum friction coefficient at zero slip velocity [-].
    w : array_like
        Magnitude of the slip velocity [m/s], ≥ 0.
    A : float or None
        Ratio μ∞/μ0 [-]; ``None`` (with ``B``) gives constant friction.
    B : float or None
        Exponential decrease rate [s/m].

    Returns
    -------
    ndarray
        μ [-], broadcast shape of ``mu0`` and ``w``.
    """
    mu0 = np.asarray(mu0, dtype=float)
    if A is None or B is None:
        return np.broadcast_to(mu0, np.broadcast_shapes(mu0.shape, np.shape(w))).astype(float)
    return mu0 * ((1.0 - A) * np.exp(-B * np.asarray(w, dtype=float)) + A)


def polach_forces(G, a, b, C11, C22, C23, xi, eta, phi, mu0, Fn, kA=1.0, kS=1.0,
                  speed=None, A=None, B=None):
    """Polach creep forces on the wheel (pure array kernel, broadcasting).

    Parameters
    ----------
    G : float
        Combined shear modulus [Pa].
    a, b : array_like, shape (n,) or ()
        Semi-axes along x (rolling) and y [m].
    C11, C22, C23 : array_like
        Kalker's creep coefficients for a/b and ν [-].
    xi, eta : array_like
        Creepages [-] (Kalker's definition, wheel relative to rail).
    phi : array_like
        Spin creepage [1/m].
    mu0 : array_like
        Friction coefficient [-] (maximum friction if ``A``, ``B`` are given).
    Fn : array_like
        Normal force Q [N].
    kA, kS : float
        Reduction factors of Polach (2005) in the areas of adhesion and slip;
        1 gives the 1999 method. Must satisfy 0 < kS ≤ kA ≤ 1 (not checked here).
    speed : float or array_like or None
        Rolling speed V [m/s] for the slip velocity w = s_C V (only used with A, B).
    A, B : float or None
        Friction-law parameters (:func:`polach_friction`).

    Returns
    -------
    Fx, Fy, Mz : ndarray
        Forces on the wheel [N] in Kalker's sign convention (broadcast shape
        of the inputs); Mz = 0.
    mu : ndarray
        Friction coefficient used [-] (μ(w) for the extended method).

    Notes
    -----
    All arguments are broadcast, flattened and passed to a fused numba loop
    (one pass, no temporaries), see the module docstring for the formulas.
    """
    law = A is not None and B is not None
    if speed is None:
        speed = 0.0
    arrs = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in
                                 (a, b, C11, C22, C23, xi, eta, phi, mu0, Fn, speed)))
    shape = arrs[0].shape
    flat = [np.ascontiguousarray(v).ravel() for v in arrs]
    n = flat[0].size
    Fx, Fy, mu = np.empty(n), np.empty(n), np.empty(n)
    _polach_loop(float(G), *flat, float(kA), float(kS), bool(law),
                 float(A) if law else 1.0, float(B) if law else 0.0, Fx, Fy, mu)
    return Fx.reshape(shape), Fy.reshape(shape), np.zeros(shape), mu.reshape(shape)


@njit(cache=True)
def _polach_loop(G, a, b, C11, C22, C23, sx, sy, phi, mu0, Q, speed, kA, kS, law, A, B,
                 Fx, Fy, mu_out):  # pragma: no cover - compiled
    for i in range(Fx.shape[0]):
        x, y, ai, bi = sx[i], sy[i], a[i], b[i]
        s = np.sqrt(x * x + y * y)
        syc = y + phi[i] * ai
        if not abs(syc) > abs(y):
            syc = y
        sc = np.sqrt(x * x + syc * syc)
        if s > 0.0:
            u, v = C11[i] * x / s, C22[i] * y / s
            cjj = np.sqrt(u * u + v * v)
        else:
            cjj = C11[i]
        mu = mu0[i]
        if law:
            mu = mu * ((1.0 - A) * np.exp(-B * sc * speed[i]) + A)
        mu_out[i] = mu
        qmu = Q[i] * mu
        eps = 0.25 * np.pi * G * ai * bi * cjj * sc / qmu
        ke = kA * eps
        F = (2.0 / np.pi) * qmu * (ke / (1.0 + ke * ke) + np.arctan(kS * eps))
        f_over_s = F / sc if sc > 0.0 else 0.0
        # spin: F_yS in Polach's sign, written with K_M / s_C (no 0/0, no cancellation)
        shp = 1.0 + _SPIN_SHAPE * (1.0 - np.exp(-ai / bi))
        kappa = (8.0 / 3.0) * G * bi * np.sqrt(ai * bi) * C23[i] / (qmu * shp)  # eps_M / s_C
        em = kappa * sc
        e2 = em * em
        d = (e2 - 1.0) / (e2 + 1.0)
        h = d * d * (d / 3.0 - 0.5) + 1.0 / 6.0
        t = 1.0 + e2
        km_over_sc = kappa * (h - (8.0 / 3.0) * e2 / (t * t * t))
        fys = -(9.0 / 16.0) * ai * qmu * shp * km_over_sc * phi[i]
        Fx[i] = -f_over_s * x
        Fy[i] = -(f_over_s * y + fys)


def _speed(name, v):
    """None, a positive number or an array of positive numbers (one per batch case) [m/s]."""
    if v is None:
        return None
    if isinstance(v, bool):
        raise InputError(f"{name} must be finite and > 0, got {v!r}")
    arr = positive(name, v)
    if arr.ndim == 0:
        return float(arr)
    arr = arr.copy()
    arr.setflags(write=False)
    return arr


def _check_extended(kA, kS, speed, A, B, conditions):
    """Resolve and validate the options of the extended method; returns kA, kS, speed, A, B."""
    if conditions is not None:
        if conditions not in POLACH_2005_PARAMETERS:
            raise InputError(f"conditions must be one of {sorted(POLACH_2005_PARAMETERS)} or None, "
                             f"got {conditions!r}")
        p = POLACH_2005_PARAMETERS[conditions]
        kA = p["kA"] if kA is None else kA
        kS = p["kS"] if kS is None else kS
        A = p["A"] if A is None else A
        B = p["B"] if B is None else B
    kA = 1.0 if kA is None else kA
    kS = 1.0 if kS is None else kS
    for name, v in (("kA", kA), ("kS", kS)):
        if not np.isscalar(v) or not np.isfinite(v) or not 0.0 < v <= 1.0:
            raise InputError(f"{name} must be a number in (0, 1], got {v!r}")
    if kS > kA:
        raise InputError(f"Polach's method needs kS <= kA (got kS={kS!r} > kA={kA!r}); "
                         "otherwise the force can exceed mu*Fn")
    if (A is None) != (B is None):
        raise InputError(f"give both A and B for the slip-velocity dependent friction "
                         f"(got A={A!r}, B={B!r})")
    if A is not None:
        if not np.isscalar(A) or not np.isfinite(A) or not 0.0 < A <= 1.0:
            raise InputError(f"A (= mu_inf/mu0) must be in (0, 1], got {A!r}")
        if not np.isscalar(B) or not np.isfinite(B) or B < 0.0:
            raise InputError(f"B must be a finite number >= 0 [s/m], got {B!r}")
        if speed is None:
            raise InputError("speed (rolling speed V [m/s]) is required when A and B are given: "
                             "the friction depends on the slip velocity w = s*V")
    if speed is not None:
        speed = positive("speed", speed)
    return float(kA), float(kS), speed, A, B


@configured
class Polach(TangentialMethod):
    """Polach's creep-force law (1999), optionally extended as in Polach (2005).

    On a :class:`~wheelrail.patch.ContactPatch` (``wr.solve``) this law
    uses the patch's equivalent ellipse (:meth:`ContactPatch.ellipse`: the Hertz
    ellipse of a Hertzian patch, otherwise the ellipse of equal area and
    length/width ratio).

    Other Parameters
    ----------------
    kA : float, default 1
        Reduction of Kalker's stiffness in the area of adhesion (0 < kA ≤ 1).
    kS : float, default 1
        Reduction in the area of slip (0 < kS ≤ kA).
    speed : float or array_like, optional
        Rolling speed V [m/s]; needed for the slip-velocity dependent friction.
    A : float, optional
        μ∞/μ0 ∈ (0, 1] of the friction law μ = μ0[(1 − A)e^(−Bw) + A].
    B : float, optional
        Rate B [s/m] of the friction law. Without ``A``/``B`` the friction is
        constant (the ``mu`` passed to :func:`wheelrail.creep_forces`).
    conditions : {"dry", "wet"}, optional
        Take kA, kS, A, B from :data:`POLACH_2005_PARAMETERS` (options given
        explicitly win); pass the matching ``mu`` (0.55 dry, 0.30 wet) yourself.

    Notes
    -----
    Closed form, vectorised over batches. The returned ``mu`` is the μ0
    passed in; ``info["mu_slip"]`` holds the friction μ(w) actually used.
    ``Mz`` is 0 (Polach's method has no spin moment).
    """

    name = "polach"
    references = (
        "O. Polach, A fast wheel-rail forces calculation computer code, Vehicle System "
        "Dynamics 33 (Suppl.) (1999) 728-739.",
        "O. Polach, Creep forces in simulations of traction vehicles running on adhesion limit, "
        "Wear 258 (2005) 992-1000.",
        "J.J. Kalker, Three-dimensional elastic bodies in rolling contact, Kluwer, 1990.",
    )
    kA: float | None = option(None, kind="float", lo=0.0, hi=1.0, lo_open=True, allow_none=True,
                              doc="reduction of Kalker's stiffness in adhesion (default 1)")
    kS: float | None = option(None, kind="float", lo=0.0, hi=1.0, lo_open=True, allow_none=True,
                              doc="reduction in slip, <= kA (default 1)")
    speed: Any = option(None, kind="any", unit="m/s", check=_speed, allow_none=True,
                        typical=LIMITS["speed_warn"], plausible=(None, LIMITS["speed_refuse"]),
                        doc="rolling speed V (a number or one per batch case)")
    A: float | None = option(None, kind="float", lo=0.0, hi=1.0, lo_open=True, allow_none=True,
                             doc="mu_inf/mu0 of the slip-velocity dependent friction")
    B: float | None = option(None, kind="float", unit="s/m", lo=0.0, allow_none=True,
                             typical=(0.0, 5.0),
                             doc="rate B of the slip-velocity dependent friction")
    conditions: str | None = option(None, choices=(None, *POLACH_2005_PARAMETERS),
                                    doc="take kA, kS, A, B from Polach (2005), Table 1")

    def _check(self):
        _check_extended(self.kA, self.kS, self.speed, self.A, self.B, self.conditions)

    def solve(self, contact, xi, eta, phi, mu):
        kA, kS, speed, A, B = _check_extended(self.kA, self.kS, self.speed, self.A, self.B,
                                              self.conditions)
        a = np.asarray(contact.a, dtype=float)
        b = np.asarray(contact.b, dtype=float)
        Fn = np.asarray(contact.Fn, dtype=float)
        if speed is not None:
            try:
                ok = np.broadcast_shapes(np.shape(speed), a.shape) == a.shape
            except ValueError:
                ok = False
            if not ok:
                raise InputError(f"speed has shape {np.shape(speed)}, which does not match the "
                                 f"batch shape {a.shape}")
        C11, C22, C23, _ = kalker_coefficients(a / b, contact.nu)
        Fx, Fy, Mz, mu_slip = polach_forces(
            contact.G, a, b, np.asarray(C11), np.asarray(C22), np.asarray(C23),
            xi, eta, phi, mu, Fn, kA=kA, kS=kS, speed=speed, A=A, B=B)
        s = scalar_or_array
        return CreepForcesResult(Fx=s(Fx), Fy=s(Fy), Mz=s(Mz), Fn=s(Fn), mu=s(np.asarray(mu)),
                           method=self.name, status=Status.CONVERGED,
                           info={"mu_slip": s(mu_slip)})
