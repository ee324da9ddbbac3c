"""The rolling-contact case: bodies, load, kinematics and numerical settings (frozen input)."""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from .._validation import as_float_array, in_range, integer, non_negative, positive
from ..errors import InputError
from ..materials import STEEL, Material

__all__ = ["RollingCase", "INTEGRATORS"]

#: Names accepted by ``RollingCase(integrator=...)``.
INTEGRATORS = ("explicit", "implicit-qs", "implicit-hht")


@dataclass(frozen=True, eq=False)
class RollingCase:
    """A wheel rolling on a rail, meshed from their profiles (SI units).

    Parameters
    ----------
    wheel, rail : Profile
        Wheel and rail cross-sections (profile frames of
        :mod:`wheelrail.profiles.core`); the rail is inclined by
        ``inclination`` before meshing.
    radius : float
        Wheel rolling radius [m] at the wheel profile's origin (tape circle).
    load : float
        Vertical wheel load [N] (> 0).
    creepage : (float, float, float)
        (ξ, η, φ); only the longitudinal creepage ξ [-] is prescribed (through
        the wheel's angular velocity, Toumi et al. eq. 1); η must be 0 (yaw
        not implemented yet) and φ must be 0 (spin arises from the geometry).
    mu : float
        Coulomb friction coefficient [-].
    material : Material or LinearElastic
        Wheel and rail material (the same for both).
    mesh_size : float
        Element edge length in the refined band [m].
    integrator : {"explicit", "implicit-qs", "implicit-hht"}
    lateral_position : float
        Lateral shift of the wheel profile origin relative to the rail profile origin [m].
    inclination : float
        Rail inclination [rad] (e.g. ``np.arctan(1/40)``), positive tilting the head towards
        the gauge side (see :meth:`Profile.rotated`).
    speed : float
        Rolling speed V [m/s] (50 km/h in the seed paper).
    travel : float, optional
        Rolled distance [m]; default 6 a + the ramp (enough for steady state).
    ramp : float
        Fraction of ``travel`` over which the speed rises with a smooth step (0.135 in the seed).
    element : {"full", "reduced"}
        Hex8 integration (see :class:`wheelrail.fe.Hex8`).
    penalty : float
        Normal penalty stiffness in units of E / h [-]; the tangential penalty is the same.
    depth, half_width, half_length : float, optional
        Kept depth of each body, lateral half-width of the meshes and half-length of the
        static (indentation) mesh, in units of the Hertz semi-axes; defaults 10, 8, 8.
    grading : float
        Growth ratio of the element size outside the refined band.
    courant : float
        Safety factor on the Courant step (explicit), in (0, 1].
    time_step : float, optional
        Explicit: a requested step [s] (error if above the stable one); implicit: the step
        (default: the contact crosses one element per step... see the integrators).
    mass_scaling : float
        Density multiplier (>= 1) of the explicit run: the step grows by its square root.
    rayleigh : (float, float)
        Rayleigh damping C = α M + β K, α [1/s], β [s].
    hht_alpha : float
        HHT-α parameter in [-1/3, 0].
    density : float
        Mass density [kg/m³] when ``material`` is a :class:`wheelrail.Material`.

    References
    ----------
    .. [1] M. Toumi, H. Chollet, H. Yin, Wear 366-367 (2016) 157-166 (seed paper 000),
       §2, Table 1 and eq. (1).
    """

    wheel: object
    rail: object
    radius: float
    load: float
    creepage: tuple = (0.0, 0.0, 0.0)
    mu: float = 0.3
    material: object = STEEL
    mesh_size: float = 1e-3
    integrator: str = "explicit"
    lateral_position: float = 0.0
    inclination: float = 0.0
    speed: float = 50 / 3.6
    travel: float | None = None
    ramp: float = 0.135
    element: str = "full"
    penalty: float = 10.0
    depth: float = 10.0
    half_width: float = 8.0
    half_length: float = 8.0
    grading: float = 1.3
    courant: float = 0.9
    time_step: float | None = None
    mass_scaling: float = 1.0
    rayleigh: tuple = (0.0, 0.0)
    hht_alpha: float = -0.05
    density: float = 7800.0
    meta: dict = field(default_factory=dict, repr=False)

    def __post_init__(self):
        from ..profiles import Profile

        for name in ("wheel", "rail"):
            if not isinstance(getattr(self, name), Profile):
                raise InputError(f"{name} must be a wheelrail Profile, got "
                                 f"{type(getattr(self, name)).__name__}")
        s = object.__setattr__
        s(self, "radius", float(positive("radius", self.radius)))
        s(self, "load", float(positive("load", self.load)))
        c = as_float_array("creepage", self.creepage)
        if c.shape != (3,):
            raise InputError(f"creepage must be (xi, eta, phi), got shape {c.shape}")
        if c[1] != 0.0 or c[2] != 0.0:
            raise InputError(f"creepage (eta, phi) = ({c[1]!r}, {c[2]!r}): only the longitudinal "
                             f"creepage can be prescribed in the FE model (yaw for eta is not "
                             f"implemented; spin follows from the profiles)")
        if abs(c[0]) >= 0.05:
            raise InputError(f"creepage xi = {c[0]!r} is past any plausible saturation "
                             f"(|xi| >= 5 %); full sliding has no steady rolling state to resolve")
        s(self, "creepage", tuple(float(v) for v in c))
        s(self, "mu", float(non_negative("mu", self.mu)))
        if not isinstance(self.material, Material):
            from .materials import LinearElastic
            if not isinstance(self.material, LinearElastic):
                raise InputError(f"material must be a wheelrail.Material or "
                                 f"wheelrail.fe.LinearElastic, got {type(self.material).__name__}")
        s(self, "mesh_size", float(positive("mesh_size", self.mesh_size)))
        if self.integrator not in INTEGRATORS:
            raise InputError(f"integrator must be one of {INTEGRATORS}, got {self.integrator!r}")
        if self.element not in ("full", "reduced"):
            raise InputError(f"element must be 'full' or 'reduced', got {self.element!r}")
        s(self, "lateral_position", float(as_float_array("lateral_position",
                                                         self.lateral_position)))
        s(self, "inclination", float(in_range("inclination", self.inclination, -0.2, 0.2)))
        s(self, "speed", float(positive("speed", self.speed)))
        if self.travel is not None:
            s(self, "travel", float(positive("travel", self.travel)))
        s(self, "ramp", float(in_range("ramp", self.ramp, 0.0, 0.9)))
        for name in ("penalty", "depth", "half_width", "half_length"):
            s(self, name, float(positive(name, getattr(self, name))))
        s(self, "grading", float(in_range("grading", self.grading, 1.0, 2.0)))
        s(self, "courant", float(in_range("courant", self.courant, 0.0, 1.0, lo_open=True)))
        if self.time_step is not None:
            s(self, "time_step", float(positive("time_step", self.time_step)))
        s(self, "mass_scaling", float(in_range("mass_scaling", self.mass_scaling, 1.0, 1e6)))
        r = as_float_array("rayleigh", self.rayleigh)
        if r.shape != (2,) or np.any(r < 0):
            raise InputError(f"rayleigh must be (alpha >= 0, beta >= 0), got {self.rayleigh!r}")
        s(self, "rayleigh", (float(r[0]), float(r[1])))
        s(self, "hht_alpha", float(in_range("hht_alpha", self.hht_alpha, -1 / 3, 0.0)))
        s(self, "density", float(positive("density", self.density)))

    def replace(self, **changes) -> "RollingCase":
        """A copy with some fields changed (validated again)."""
        return replace(self, **changes)

    @property
    def xi(self) -> float:
        return self.creepage[0]


def _unused():  # keep integer imported for later options (steps)
    return integer
