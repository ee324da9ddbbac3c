"""The rolling-contact case: bodies, load, kinematics and numerical settings (frozen input)."""

from __future__ import annotations

import functools
import warnings
from dataclasses import dataclass, field, replace

import numpy as np

from .._validation import as_float_array, in_range, integer, non_negative, positive
from ..errors import InputError
from ..materials import STEEL, Material
from ..plausibility import check_friction, check_rolling_radius, check_speed
from ..profiles import Profile
from ._newton import LINEAR_SOLVERS
from .materials import J2Plastic, LinearElastic, r900a

__all__ = ["RollingCase", "INTEGRATORS", "seed000_case", "toumi2016_load", "cone_wheel",
           "head_arc_rail", "TOUMI2016_TABLE3_HERTZ"]

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
    Fn : float
        Vertical wheel load [N] (> 0). The old name ``load=`` is still accepted, with a
        ``DeprecationWarning``, for one release.
    creepage : (float, float, float)
        (ξ [-], η [-], φ [1/m]). ξ is prescribed through the wheel's angular
        velocity (Toumi et al. eq. 1), η through a lateral drift −η V(t) of the
        rail (the small-angle equivalent of the yaw angle of Toumi et al. 2016, eqs. 2-3);
        φ must be 0: spin arises from the geometry (conicity, rail inclination).
        |ξ| or |η| >= 0.05 is rejected; a creepage past the saturation estimate
        of the linear theory gives a warning in :func:`wheelrail.fe.solve`.
    mu : float
        Coulomb friction coefficient [-].
    material : Material, LinearElastic or J2Plastic
        Wheel and rail material (the same for both); :class:`wheelrail.fe.J2Plastic` for
        elasto-plastic bodies (use ``element="reduced"``, or ``"full"`` with B-bar).
    mesh_size : float
        Element edge length in the refined band [m].
    integrator : {"explicit", "implicit-qs", "implicit-hht"}
    lateral_position : float
        Lateral shift of the wheel profile origin relative to the rail profile origin [m].
    inclination : float
        Rail inclination [rad] (e.g. ``np.arctan(1/40)``), positive tilting the head towards
        the gauge side (see :meth:`Profile.rotated`).
    speed : float
        Rolling speed V [m/s] (50 km/h in Toumi et al. 2016).
    travel : float, optional
        Rolled distance [m]; default 6 a + the ramp (enough for steady state).
    ramp : float
        Fraction of ``travel`` over which the speed rises with a smooth step (0.135 in Toumi et al. 2016).
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
        Rayleigh damping C = α M + β K, α [1/s], β [s]: explicit and implicit-hht;
        implicit-qs takes only the stiffness part β (a viscous, Kelvin-Voigt term
        β K u̇ with u̇ = Δu/Δt; α > 0 is rejected there since it needs inertia).
    linear_solver : {"auto", "direct", "reuse", "pardiso"}
        Newton systems of the static indentation and the implicit integrators:
        ``"auto"`` (default) is ``"pardiso"`` where pypardiso is installed, else
        ``"direct"``; ``"direct"`` factorises every iteration (SuperLU,
        symmetric mode); ``"reuse"`` keeps one factorisation as the GMRES preconditioner
        across iterations and steps and refactorises only when GMRES needs more than 40
        iterations (same results to 1e-10; not faster on the meshes measured, see
        docs/fe.md); ``"pardiso"`` factorises every iteration with MKL PARDISO (optional
        extra ``wheelrail[pardiso]``; 2.3-4.6x less CPU than SuperLU on 3 and 2 mm meshes,
        same results to rounding).
    hht_alpha : float
        HHT-α parameter in [-1/3, 0].
    contact_damping : float
        Explicit runs: normal contact dashpots at this fraction of critical damping of the
        penalty springs (damps the contact layer's ringing; see :mod:`wheelrail.fe.explicit`),
        in [0, 1).
    axle_damping : float
        Explicit runs: a vertical dashpot on the axle at this fraction of critical damping of
        the (scaled) wheel mass on the Hertz contact stiffness (damps the wheel's bounce), >= 0.
    passes : int
        Number of passes of the same wheel segment over the same rail section (explicit;
        between passes the wheel returns to the start, the bodies keep their displacement
        and plastic state).
    density : float
        Mass density [kg/m³] when ``material`` is a :class:`wheelrail.Material`.

    References
    ----------
    .. [1] M. Toumi, H. Chollet, H. Yin, Wear 366-367 (2016) 157-166,
       §2, Table 1 and eq. (1).
    """

    wheel: object
    rail: object
    radius: float
    Fn: float
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
    linear_solver: str = "auto"
    hht_alpha: float = -0.05
    density: float = 7800.0
    contact_damping: float = 0.2
    axle_damping: float = 1.0
    passes: int = 1
    meta: dict = field(default_factory=dict, repr=False)

    def __post_init__(self):
        for name in ("wheel", "rail"):
            if not isinstance(getattr(self, name), Profile):
                raise InputError(f"{name} must be a wheelrail Profile, got "
                                 f"{type(getattr(self, name)).__name__}")
        s = object.__setattr__
        s(self, "radius", float(positive("radius", self.radius)))
        check_rolling_radius(self.radius, "radius")
        s(self, "Fn", float(positive("Fn", self.Fn)))
        c = as_float_array("creepage", self.creepage)
        if c.shape != (3,):
            raise InputError(f"creepage must be (xi, eta, phi), got shape {c.shape}")
        if c[2] != 0.0:
            raise InputError(f"creepage phi = {c[2]!r} 1/m: a prescribed spin creepage is not "
                             f"supported by the FE model; spin follows from the profiles "
                             f"(e.g. a conical wheel on an inclined rail) — give phi = 0")
        for k, name in ((0, "xi"), (1, "eta")):
            if abs(c[k]) >= 0.05:
                raise InputError(f"creepage {name} = {c[k]!r} is past any plausible saturation "
                                 f"(|{name}| >= 5 %); full sliding has no steady rolling state "
                                 f"to resolve")
        s(self, "creepage", tuple(float(v) for v in c))
        s(self, "mu", float(non_negative("mu", self.mu)))
        if self.mu > 0:  # mu = 0: a deliberately frictionless contact
            check_friction(self.mu, "mu")
        if not isinstance(self.material, Material):
            if not isinstance(self.material, (LinearElastic, J2Plastic)):
                raise InputError(f"material must be a wheelrail.Material, "
                                 f"wheelrail.fe.LinearElastic or wheelrail.fe.J2Plastic, got "
                                 f"{type(self.material).__name__}")
        s(self, "mesh_size", float(positive("mesh_size", self.mesh_size)))
        if self.integrator not in INTEGRATORS:
            raise InputError(f"integrator must be one of {INTEGRATORS}, got {self.integrator!r}")
        if self.element not in ("full", "reduced"):
            raise InputError(f"element must be 'full' or 'reduced', got {self.element!r}")
        s(self, "lateral_position", float(as_float_array("lateral_position",
                                                         self.lateral_position)))
        s(self, "inclination", float(in_range("inclination", self.inclination, -0.2, 0.2)))
        s(self, "speed", float(positive("speed", self.speed)))
        check_speed(self.speed, "speed")
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
        if self.integrator == "implicit-qs" and r[0] > 0:
            raise InputError(f"rayleigh alpha = {r[0]!r} 1/s (mass-proportional damping) needs "
                             f"inertia: use integrator 'implicit-hht' or 'explicit', or alpha = 0")
        if self.linear_solver not in LINEAR_SOLVERS:
            *first, last = map(repr, LINEAR_SOLVERS)
            raise InputError(f"linear_solver must be {', '.join(first)} or {last}, got "
                             f"{self.linear_solver!r}")
        s(self, "hht_alpha", float(in_range("hht_alpha", self.hht_alpha, -1 / 3, 0.0)))
        s(self, "density", float(positive("density", self.density)))
        s(self, "contact_damping", float(in_range("contact_damping", self.contact_damping, 0.0,
                                                  1.0, hi_open=True)))
        s(self, "axle_damping", float(non_negative("axle_damping", self.axle_damping)))
        s(self, "passes", integer("passes", self.passes))
        if self.passes > 1 and self.integrator != "explicit":
            raise InputError(f"passes = {self.passes!r} needs integrator 'explicit', got "
                             f"{self.integrator!r}")

    def replace(self, **changes) -> "RollingCase":
        """A copy with some fields changed (validated again)."""
        return replace(self, **changes)

    @property
    def xi(self) -> float:
        return self.creepage[0]

    @property
    def load(self) -> float:
        """Deprecated name of :attr:`Fn` [N] (kept for one release)."""
        warnings.warn("RollingCase.load is deprecated, use RollingCase.Fn",
                      DeprecationWarning, stacklevel=2)
        return self.Fn


def _accept_old_load(init):
    """``RollingCase(load=...)``: the old name of ``Fn``, with a DeprecationWarning."""

    @functools.wraps(init)
    def __init__(self, *args, load=None, **kwargs):
        if load is not None:
            if "Fn" in kwargs or len(args) >= 4:
                raise InputError("RollingCase: give the wheel load as Fn (not also as load)")
            warnings.warn("RollingCase(load=...) is deprecated, use Fn=...",
                          DeprecationWarning, stacklevel=2)
            kwargs["Fn"] = load
        init(self, *args, **kwargs)

    return __init__


RollingCase.__init__ = _accept_old_load(RollingCase.__init__)


def cone_wheel(taper: float = 0.1, half_width: float = 0.04, n: int = 17):
    """A conical (straight) wheel tread: profile z = taper · y [m] over |y| <= half_width.

    Parameters
    ----------
    taper : float
        Conicity [-] (1/10 in Toumi et al. 2016, Table 1); 0 gives a cylinder.
    half_width : float
        Half width of the tread [m].
    n : int
        Number of profile points.
    """

    y = np.linspace(-half_width, half_width, integer("n", n))
    name = f"cone 1/{1 / taper:g}" if taper else "cylinder"
    return Profile(y, taper * y, kind="wheel", name=name)


def head_arc_rail(radius: float = 0.3, half_width: float = 0.025, n: int = 201):
    """A rail head made of one circular arc of ``radius`` [m] (crown at y = 0, z = 0).

    Parameters
    ----------
    radius : float
        Head radius [m] (300 mm in Toumi et al. 2016, Table 1).
    half_width : float
        Half width of the head [m] (< radius).
    n : int
        Number of profile points.
    """

    R = float(positive("radius", radius))
    w = float(in_range("half_width", half_width, 0.0, R, lo_open=True, hi_open=True))
    y = np.linspace(-w, w, integer("n", n))
    return Profile(y, -y * y / (R + np.sqrt(R * R - y * y)), kind="rail",
                   name=f"head arc R{R * 1e3:g}")


#: Toumi, Chollet & Yin (2016), Table 3, Hertz row: semi-axes a, b [m] and peak pressure [Pa].
TOUMI2016_TABLE3_HERTZ = {"a": 6.66e-3, "b": 5.05e-3, "p0": 1160e6}
#: Their Table 1 ("7.5 kN load per wheel") [N].
TOUMI2016_PRINTED_LOAD = 7500.0
#: Contact angle of their set-up, arctan(1/10) [rad] (cone 1/10 on a rail inclined 1/10).
TOUMI2016_CONTACT_ANGLE = float(np.arctan(0.1))


def toumi2016_load(which="table3") -> float:
    """Vertical wheel load [N] of Toumi, Chollet & Yin's (2016) Hertzian case.

    ``"table3"``: the load consistent with their Table 3 Hertz row (a = 6.66 mm, b = 5.05 mm,
    p0 = 1160 MPa). Hertz's normal force is F_n = 2π a b p0 / 3 = 81.71 kN (the resultant
    of the ellipsoidal pressure; Johnson 1985, eq. 3.64). It is also the least-squares
    fit of the three values with this package's geometry of their case (every one of a, b,
    p0 scales as F^(1/3), and the log-least-squares load is the product of the three
    ratios: the same formula). Their normal force acts along the contact normal, tilted by
    the contact angle δ = arctan(1/10), so the vertical wheel load is F_n cos δ = 81.31 kN.
    Hertz with the case's curvatures at that load: a = 6.74 mm (+1.2 %), b = 5.05 mm
    (+0.06 %), p0 = 1145 MPa (−1.3 %) — their a/b (1.319) is 1.1 % below the case's (1.334),
    the cone-on-arc geometry not being exactly their S1002-type cone on UIC60.
    ``"printed"``: the 7.5 kN of their Table 1 (which gives a = 3.0 mm, b = 2.3 mm,
    p0 = 518 MPa, not their Table 3).
    """
    if which == "printed":
        return TOUMI2016_PRINTED_LOAD
    if which != "table3":
        raise InputError(f"toumi2016_load: which must be 'table3' or 'printed', got {which!r}")
    t = TOUMI2016_TABLE3_HERTZ
    fn = 2.0 * np.pi * t["a"] * t["b"] * t["p0"] / 3.0
    return float(fn * np.cos(TOUMI2016_CONTACT_ANGLE))


def seed000_case(load="table3", plastic: bool = False, **changes) -> RollingCase:
    """Toumi, Chollet & Yin's (2016) Hertzian case as a :class:`RollingCase`.

    A 1/10 conical wheel of rolling radius 460 mm on a rail head arc of 300 mm inclined by
    1/10 (``inclination = arctan(1/10)``), so that the cone touches the arc at its crown and
    the contact is Hertzian (A = cos δ / (2 r), B = 1 / (2 · 0.3 m)); μ = 0.2, E = 210 GPa,
    ν = 0.28, ρ = 7800 kg/m³, 50 km/h, ξ = −0.7 ‰ (their Table 1).

    Parameters
    ----------
    load : {"table3", "printed"} or float
        ``"table3"`` (default): 81.31 kN vertical, the load consistent with their Table 3
        (:func:`toumi2016_load`); ``"printed"``: the 7.5 kN of their Table 1; or a load [N].
    plastic : bool
        Elasto-plastic R900A bodies (:func:`wheelrail.fe.r900a`: yield 489 MPa, Voce
        hardening) instead of elastic ones.
    **changes
        Any other :class:`RollingCase` field (e.g. ``mesh_size``, ``integrator``,
        ``material``).

    References
    ----------
    .. [1] M. Toumi, H. Chollet, H. Yin, Wear 366-367 (2016) 157-166, §2, Tables 1 and 3.
    """
    if isinstance(load, str):
        load = toumi2016_load(load)
    if plastic:
        material = r900a()
    else:
        material = Material(E=2.1e11, nu=0.28)
    args = dict(wheel=cone_wheel(0.1), rail=head_arc_rail(0.3), radius=0.46, Fn=load,
                creepage=(-7e-4, 0.0, 0.0), mu=0.2, material=material,
                inclination=TOUMI2016_CONTACT_ANGLE, speed=50 / 3.6)
    args.update(changes)
    return RollingCase(**args)
