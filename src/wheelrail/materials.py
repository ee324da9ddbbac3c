"""Elastic materials of the wheel and the rail.

All moduli in Pa; Poisson's ratio dimensionless.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

from ._validation import in_range, positive
from .errors import InputError
from .plausibility import check_modulus

__all__ = ["Material", "MaterialPair", "STEEL", "as_material_pair"]


@dataclass(frozen=True)
class Material:
    """A linear elastic, isotropic material.

    Parameters
    ----------
    E : float
        Young's modulus [Pa], > 0.
    nu : float
        Poisson's ratio [-], in [0, 0.5).

    Examples
    --------
    >>> steel = Material(E=2.1e11, nu=0.28)
    >>> round(steel.G / 1e9, 2)
    82.03
    """

    E: float
    nu: float

    def __post_init__(self):
        object.__setattr__(self, "E", float(positive("E", self.E)))

        check_modulus(self.E)
        object.__setattr__(self, "nu", float(in_range("nu", self.nu, 0.0, 0.5, hi_open=True)))
        if not (1e-300 < self.E < 1e300):  # G, 1/G and E* must be representable
            raise InputError(f"E must lie in (1e-300, 1e300) Pa, got {self.E!r}")

    @property
    def G(self) -> float:
        """Shear modulus G = E / (2 (1 + ν)) [Pa]."""
        return self.E / (2.0 * (1.0 + self.nu))

    @classmethod
    def from_shear(cls, G: float, nu: float) -> "Material":
        """Build a material from its shear modulus ``G`` [Pa] and ``nu``."""
        G = float(positive("G", G))
        return cls(E=2.0 * G * (1.0 + nu), nu=nu)


@dataclass(frozen=True)
class MaterialPair:
    """The materials of wheel (body 1) and rail (body 2) and their combined constants.

    Parameters
    ----------
    wheel, rail : Material

    Notes
    -----
    Kalker's combined constants (Kalker 1990, §1.6):

    * ``G``:  1/G = ½ (1/G1 + 1/G2)
    * ``nu``: ν/G = ½ (ν1/G1 + ν2/G2)
    * ``K``:  K = (G/4) [(1 − 2ν1)/G1 − (1 − 2ν2)/G2], the difference parameter
      (K = 0 for quasi-identical bodies);
    * ``E_star``: 1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2, the contact modulus of
      Hertz theory.

    References
    ----------
    .. [1] J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
       Kluwer 1990, eqs. (1.58)–(1.60).
    """

    wheel: Material
    rail: Material

    @cached_property
    def G(self) -> float:
        """Combined shear modulus [Pa]."""
        return 2.0 / (1.0 / self.wheel.G + 1.0 / self.rail.G)

    @cached_property
    def nu(self) -> float:
        """Combined Poisson's ratio [-]."""
        return 0.5 * self.G * (self.wheel.nu / self.wheel.G + self.rail.nu / self.rail.G)

    @cached_property
    def K(self) -> float:
        """Kalker's difference parameter [-] (0 for quasi-identical materials)."""
        w, r = self.wheel, self.rail
        return 0.25 * self.G * ((1 - 2 * w.nu) / w.G - (1 - 2 * r.nu) / r.G)

    @cached_property
    def E_star(self) -> float:
        """Hertz contact modulus E* [Pa]."""
        w, r = self.wheel, self.rail
        return 1.0 / ((1 - w.nu**2) / w.E + (1 - r.nu**2) / r.E)

    @property
    def identical(self) -> bool:
        """True if both bodies have the same elastic constants."""
        return self.wheel == self.rail

    @classmethod
    def same(cls, material: Material) -> "MaterialPair":
        """Wheel and rail of the same material."""
        return cls(material, material)


#: Wheel and rail steel, E = 210 GPa, ν = 0.28.
STEEL = Material(E=2.1e11, nu=0.28)


def as_material_pair(material) -> MaterialPair:
    """Accept a :class:`Material` (same for both bodies) or a :class:`MaterialPair`."""
    if isinstance(material, MaterialPair):
        return material
    if isinstance(material, Material):
        return MaterialPair.same(material)

    raise InputError(f"material must be a Material or MaterialPair, got {type(material).__name__}")
