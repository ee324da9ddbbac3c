"""Material laws of the FE engine (one class per law; linear elasticity for now).

A material gives the element kernels what they need to turn strains into
stresses. :class:`LinearElastic` passes its Lamé constants; an elasto-plastic
law (next issue) will add per-integration-point state arrays and its own
kernel, chosen by the element through :attr:`kind`.
"""

from __future__ import annotations

from dataclasses import dataclass

from .._validation import in_range, positive
from ..errors import InputError
from ..materials import Material

__all__ = ["LinearElastic", "as_fe_material"]


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
    def wave_speed(self) -> float:
        """Dilatational wave speed c = √((λ + 2G)/ρ) [m/s] (sets the Courant step)."""
        return ((self.lam + 2 * self.shear_modulus) / self.density) ** 0.5


def as_fe_material(material, density: float = 7800.0) -> LinearElastic:
    """Accept a :class:`wheelrail.Material` (elastic constants) or an FE material."""
    if isinstance(material, LinearElastic):
        return material
    if isinstance(material, Material):
        return LinearElastic(material.E, material.nu, density)
    raise InputError(f"material must be a wheelrail.Material or wheelrail.fe.LinearElastic, "
                     f"got {type(material).__name__}")
