"""Material laws of the FE engine: linear elasticity and J2 elasto-plasticity.

A material gives the element kernels what they need to turn strains into
stresses: :class:`LinearElastic` its Lamé constants λ and G (the shear modulus);
:class:`J2Plastic` also its hardening parameters, and the kernels then carry a
state per integration point (plastic strain, equivalent plastic strain, back
stress; :mod:`wheelrail.fe._solid`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validation import as_float_array, in_range, non_negative, positive
from ..errors import InputError
from ..materials import Material
from ..plausibility import check_modulus, check_yield_stress

__all__ = ["LinearElastic", "J2Plastic", "Voce", "TabulatedHardening", "R900A_HARDENING",
           "r900a", "as_fe_material"]


@dataclass(frozen=True)
class LinearElastic:
    """Isotropic linear elasticity, σ = λ tr(ε) I + 2 G ε (small strain; G the shear modulus).

    Parameters
    ----------
    E : float
        Young's modulus [Pa].
    nu : float
        Poisson's ratio [-], in [0, 0.5).
    density : float
        Mass density [kg/m³] (7800 for the R900A steel of Toumi et al. 2016, Table 1).
    """

    E: float
    nu: float
    density: float = 7800.0
    kind = "linear-elastic"

    def __post_init__(self):
        object.__setattr__(self, "E", float(positive("E", self.E)))
        object.__setattr__(self, "nu", float(in_range("nu", self.nu, 0.0, 0.5, hi_open=True)))
        object.__setattr__(self, "density", float(positive("density", self.density)))

    @property
    def lam(self) -> float:
        """First Lamé constant λ = E ν / ((1 + ν)(1 − 2ν)) [Pa]."""
        return self.E * self.nu / ((1 + self.nu) * (1 - 2 * self.nu))

    @property
    def shear_modulus(self) -> float:
        """Shear modulus (second Lamé constant) G = E / (2 (1 + ν)) [Pa]."""
        return self.E / (2 * (1 + self.nu))

    @property
    def G(self) -> float:
        """Alias of :attr:`shear_modulus` [Pa]."""
        return self.shear_modulus

    @property
    def plastic(self) -> bool:
        """False: no plastic state."""
        return False

    @property
    def wave_speed(self) -> float:
        """Dilatational wave speed c = √((λ + 2G)/ρ) [m/s] (sets the Courant step)."""
        return ((self.lam + 2 * self.shear_modulus) / self.density) ** 0.5


@dataclass(frozen=True)
class Voce:
    """Voce isotropic hardening (plus a linear term): σ_y(p) = σ_0 + Q (1 − e^(−b p)) + H p.

    Parameters
    ----------
    saturation : float
        Q [Pa], the saturation increase of the yield stress (>= 0).
    rate : float
        b [-], the rate of saturation with the equivalent plastic strain p (>= 0).
    linear : float
        H [Pa], an additional linear hardening modulus (>= 0).

    References
    ----------
    .. [1] E. Voce, "The relationship between stress and strain for homogeneous
       deformation", J. Inst. Metals 74 (1948) 537-562.
    """

    saturation: float
    rate: float
    linear: float = 0.0

    def __post_init__(self):
        for name in ("saturation", "rate", "linear"):
            object.__setattr__(self, name, float(non_negative(name, getattr(self, name))))


@dataclass(frozen=True, eq=False)
class TabulatedHardening:
    """Yield stress over equivalent plastic strain, interpolated linearly (constant beyond).

    Parameters
    ----------
    plastic_strain : array_like, shape (n,)
        Equivalent plastic strains [-], strictly increasing from 0.
    stress : array_like, shape (n,)
        Yield stresses [Pa] at those strains; ``stress[0]`` is the initial yield stress.
    """

    plastic_strain: tuple
    stress: tuple

    def __post_init__(self):
        p = as_float_array("plastic_strain", self.plastic_strain).ravel()
        y = as_float_array("stress", self.stress).ravel()
        if p.size < 2 or p.shape != y.shape:
            raise InputError(f"a hardening table needs n >= 2 (plastic_strain, stress) pairs of "
                             f"equal length, got {p.size} and {y.size}")
        if p[0] != 0.0 or np.any(np.diff(p) <= 0):
            raise InputError(f"hardening table plastic_strain must start at 0 and increase "
                             f"strictly, got {p.tolist()}")
        if np.any(y <= 0):
            raise InputError(f"hardening table stresses must be > 0, got {y.tolist()}")
        object.__setattr__(self, "plastic_strain", tuple(p.tolist()))
        object.__setattr__(self, "stress", tuple(y.tolist()))


#: Default hardening of the R900A / R260 rail steel of Toumi, Chollet & Yin (2016): a Voce
#: law from the initial yield stress 489 MPa (their Table 1), through the minimum tensile
#: strength of grade R260 (UIC 900A), 880 MPa (EN 13674-1:2011, Table 6; UIC 860-O), by
#: Considère's necking condition dσ/dε = σ at an assumed uniform elongation of 8 %
#: (true strain 0.08): Q = 490 MPa, b = 36.7 (saturation 979 MPa, initial slope 18 GPa).
#: The uniform elongation is an assumption (EN 13674-1 prescribes only A >= 10 % at
#: fracture); see docs/fe_plastic.md.
R900A_HARDENING = Voce(saturation=490.24e6, rate=36.733)


@dataclass(frozen=True)
class J2Plastic:
    """Isotropic elasticity with von Mises (J2) plasticity, associative flow, small strain.

    Yield: √(3/2) |s − α| = σ_y(p), s the stress deviator, α the back stress and p the
    equivalent plastic strain (ṗ = √(2/3) |ε̇_p|). Isotropic hardening σ_y(p): a constant
    (perfect plasticity, ``hardening=0``), linear (``hardening=H`` [Pa]), :class:`Voce`,
    or a :class:`TabulatedHardening` (also given as a pair ``(plastic_strain, stress)``).
    Kinematic hardening dα = (2/3) C dε_p − γ α dp: Prager (linear, ``kinematic=C``) or
    Armstrong–Frederick (``kinematic_recovery=γ > 0``; uniaxial back stress
    (C/γ)(1 − e^(−γ p))). Integrated by the radial return (backward Euler) with the
    consistent tangent.

    Parameters
    ----------
    E : float
        Young's modulus [Pa].
    nu : float
        Poisson's ratio [-], in [0, 0.5).
    yield_stress : float
        Initial (uniaxial) yield stress σ_0 [Pa].
    hardening : float, Voce, TabulatedHardening or (array_like, array_like)
        Isotropic hardening (see above); a table must start at ``yield_stress``.
    density : float
        Mass density [kg/m³].
    kinematic : float
        Kinematic hardening modulus C [Pa] (>= 0).
    kinematic_recovery : float
        Armstrong–Frederick recovery γ [-] (>= 0; 0 is Prager's linear rule).

    References
    ----------
    .. [1] J.C. Simo, T.J.R. Hughes, *Computational Inelasticity*, Springer 1998, §3.3.
    .. [2] J. Lemaitre, J.-L. Chaboche, *Mechanics of Solid Materials*, CUP 1990, §5.4
       (Voce and Armstrong–Frederick hardening).
    """

    E: float
    nu: float
    yield_stress: float
    hardening: object = 0.0
    density: float = 7800.0
    kinematic: float = 0.0
    kinematic_recovery: float = 0.0
    kind = "j2-plastic"

    def __post_init__(self):
        s = object.__setattr__
        s(self, "E", float(positive("E", self.E)))
        s(self, "nu", float(in_range("nu", self.nu, 0.0, 0.5, hi_open=True)))
        check_modulus(self.E)
        s(self, "yield_stress", float(positive("yield_stress", self.yield_stress)))
        check_yield_stress(self.yield_stress)
        s(self, "density", float(positive("density", self.density)))
        s(self, "kinematic", float(non_negative("kinematic", self.kinematic)))
        s(self, "kinematic_recovery", float(non_negative("kinematic_recovery",
                                                           self.kinematic_recovery)))
        h = self.hardening
        if h is None:
            h = 0.0
        if isinstance(h, (tuple, list)) and len(h) == 2:
            h = TabulatedHardening(*h)
        if isinstance(h, TabulatedHardening):
            if abs(h.stress[0] - self.yield_stress) > 1e-9 * self.yield_stress:
                raise InputError(f"hardening table starts at {h.stress[0]!r} Pa, the yield_stress "
                                 f"is {self.yield_stress!r} Pa: they must agree")
        elif isinstance(h, Voce):
            pass
        elif isinstance(h, (int, float, np.floating, np.integer)) and not isinstance(h, bool):
            h = float(non_negative("hardening", h))
        else:
            raise InputError(f"hardening must be a modulus [Pa], a wheelrail.fe.Voce, a "
                             f"wheelrail.fe.TabulatedHardening or a (plastic_strain, stress) "
                             f"pair, got {type(h).__name__}")
        s(self, "hardening", h)

    lam = LinearElastic.lam
    shear_modulus = LinearElastic.shear_modulus
    G = LinearElastic.G
    wave_speed = LinearElastic.wave_speed

    @property
    def plastic(self) -> bool:
        """True: the kernels carry a plastic state per integration point."""
        return True

    def kernel_parameters(self):
        """(hp, tp, ts): hardening parameters (σ0, Q, b, H, C, γ) and the table arrays."""
        h = self.hardening
        hp = np.array([self.yield_stress, 0.0, 0.0, 0.0, self.kinematic, self.kinematic_recovery])
        tp = ts = np.zeros(0)
        if isinstance(h, Voce):
            hp[1:4] = h.saturation, h.rate, h.linear
        elif isinstance(h, TabulatedHardening):
            tp, ts = np.array(h.plastic_strain), np.array(h.stress)
        else:
            hp[3] = float(h)
        return hp, tp, ts

    def flow_stress(self, p):
        """Isotropic yield stress σ_y(p) [Pa] at equivalent plastic strains p (array_like)."""
        p = np.asarray(p, dtype=float)
        hp, tp, ts = self.kernel_parameters()
        if tp.size:
            return np.interp(p, tp, ts)
        return hp[0] + hp[1] * (1.0 - np.exp(-hp[2] * p)) + hp[3] * p

    def back_stress(self, p):
        """Uniaxial back stress [Pa] after monotonic plastic straining p (array_like)."""
        p = np.asarray(p, dtype=float)
        if self.kinematic_recovery > 0:
            return self.kinematic / self.kinematic_recovery * (1 - np.exp(-self.kinematic_recovery * p))
        return self.kinematic * p



def r900a(**changes) -> J2Plastic:
    """The R900A rail steel of Toumi, Chollet & Yin (2016), Table 1, as a :class:`J2Plastic`:
    E = 210 GPa, ν = 0.28, ρ = 7800 kg/m³, yield 489 MPa, isotropic hardening
    :data:`R900A_HARDENING`; ``changes`` override any field."""
    args = dict(E=2.1e11, nu=0.28, yield_stress=489e6, hardening=R900A_HARDENING, density=7800.0)
    args.update(changes)
    return J2Plastic(**args)


def as_fe_material(material, density: float = 7800.0):
    """Accept a :class:`wheelrail.Material` (elastic constants) or an FE material."""
    if isinstance(material, (LinearElastic, J2Plastic)):
        return material
    if isinstance(material, Material):
        return LinearElastic(material.E, material.nu, density)
    raise InputError(f"material must be a wheelrail.Material, wheelrail.fe.LinearElastic or "
                     f"wheelrail.fe.J2Plastic, got {type(material).__name__}")
