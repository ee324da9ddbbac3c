"""Whole-vehicle models: a rigid car body on two bogies or directly on two wheelsets.

A :class:`VehicleModel` is a rigid :class:`CarBody` (lateral, vertical, roll,
pitch and yaw) carried by

* two bogies (each a :class:`~wheelrail.dynamics.BogieModel`: a frame and two
  wheelsets on their primary suspension) through a
  :class:`SecondarySuspension` per bogie side — springs and dampers in three
  directions, a rotational yaw stiffness, yaw dampers with their series
  stiffness (:class:`YawDamper`, a Maxwell element with one internal state),
  lateral bump stops (:class:`BumpStop`, clearance and a piecewise-linear
  progressive force) and an anti-roll bar; or
* two wheelsets (a :class:`~wheelrail.dynamics.WheelsetModel` gives the
  wheelset and its primary suspension) directly under the body: the two-axle
  vehicle.

Every body — car body, frames, wheelsets — has its coordinates relative to the
track-following frame at its own position along the track (the car body's
centre at the reference position s, bogie j at s ± a_b, its wheelsets at
± a_w from the bogie centre), with the apparent gravity and centripetal
acceleration of that frame in curves with cant. The car body is free: in a
curve its centre sits on the chord between the bogies, inside the centre line
at s by the versine κ a_b²/2, and its lateral position is that at which the
secondary springs balance its unbalanced lateral force.

Suspension elements act between points of two bodies; the deflection of an
element is the relative displacement of its two points, each point p = (px,
py, pz) of a body moving with the body's small rotations by
(−py ψ − pz χ, y + px ψ − pz θ, z + py θ + px χ) (roll θ positive with the right
side up, pitch χ with the front up, yaw ψ with the nose to the right), with
the track frames' lateral offset, heading and cant differences between the
two bodies' positions added to the child body (the bogie or wheelset).
Heights are measured above the rail top; each body's centre of mass is at its
height, the primary springs act at the primary height (default the axle) and
the secondary elements at the secondary height. The springs' vertical preloads
(the weights they carry) turn with the bodies they act on: the overturning
moments of the weights carried above the springs (−p_z θ P in roll and pitch)
are in the equations; the car body has no longitudinal degree of freedom (the
longitudinal springs act on its pitch and yaw only).

References
----------
.. [1] S. Iwnicki, Manchester benchmarks for rail vehicle simulation, Vehicle
   System Dynamics 30 (1998) 295–313 (vehicle 1).
.. [2] A.H. Wickens, *Fundamentals of rail vehicle dynamics: guidance and
   stability*, Swets & Zeitlinger 2003, ch. 2–6 (the bogie vehicle's equations).
.. [3] S. Iwnicki (ed.), *Handbook of railway vehicle dynamics*, CRC 2006,
   ch. 5 (suspension components: air springs, yaw dampers with their series
   stiffness, bump stops, anti-roll bars).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..geometry import Wheelset
from ..materials import STEEL
from ..profiles import load as load_profile
from ._vehicle_motion import BUMP_MAX, NVP, VP
from .model import (FRAME_STATES, GP, GRAVITY, NGP, NWP, WP, BogieModel, Suspension,
                    WheelsetModel, _inertia, _Layout, _number, append_rail_relax_names,
                    global_parameters, rail_rows, wheelset_names, wheelset_rows)

__all__ = ["CarBody", "SecondarySuspension", "YawDamper", "BumpStop", "VehicleModel",
           "manchester_bogie", "manchester_vehicle1", "VehicleAssembly"]

#: Names of the car body's states.
BODY_STATES = FRAME_STATES


@dataclass(frozen=True)
class CarBody:
    """A rigid car body (frozen, SI).

    Parameters
    ----------
    mass : float
        [kg].
    inertia : (float, float, float)
        Moments of inertia about the roll, pitch and yaw axes through its centre of
        mass [kg m²].
    height : float
        Height of the centre of mass above the rail top [m].
    """

    mass: float
    inertia: tuple
    height: float = 1.8

    def __post_init__(self):
        object.__setattr__(self, "mass", _number("CarBody", "mass", self.mass, open_lo=True))
        object.__setattr__(self, "inertia", _inertia("CarBody", self.inertia))
        object.__setattr__(self, "height", _number("CarBody", "height", self.height))


@dataclass(frozen=True)
class YawDamper:
    """A longitudinal yaw damper on each bogie side with its series stiffness (frozen, SI).

    Spring k and damper c in series (a Maxwell element) between the frame and the
    car body at lateral ±``half_spacing`` and the secondary height: with the
    element's elongation d and the damper's u (a state), the force is
    F = k (d − u) = c u̇.

    Parameters
    ----------
    damping : float
        c [N s/m], > 0.
    stiffness : float
        Series stiffness k (mountings, rubber bushes) [N/m], > 0.
    half_spacing : float
        Lateral distance of each damper from the centre plane [m].
    """

    damping: float
    stiffness: float
    half_spacing: float = 1.3

    def __post_init__(self):
        for name in ("damping", "stiffness", "half_spacing"):
            object.__setattr__(self, name, _number("YawDamper", name, getattr(self, name),
                                                   open_lo=True))


@dataclass(frozen=True)
class BumpStop:
    """A lateral bump stop between frame and car body at each bogie (frozen, SI).

    The force against the lateral deflection d (symmetric, odd in d) is zero for
    |d| up to the clearance ``displacement[0]``, then interpolated linearly in the
    table and extrapolated beyond its last point with the last segment's slope.

    Parameters
    ----------
    displacement : sequence of float
        Increasing deflections [m]; the first is the clearance.
    force : sequence of float
        Forces at them [N], non-decreasing, the first 0.
    """

    displacement: tuple
    force: tuple

    def __post_init__(self):
        try:
            d = tuple(float(v) for v in self.displacement)
            f = tuple(float(v) for v in self.force)
        except (TypeError, ValueError):
            raise InputError(f"BumpStop: displacement and force must be sequences of numbers, "
                             f"got {self.displacement!r}, {self.force!r}") from None
        if len(d) != len(f) or not 2 <= len(d) <= BUMP_MAX:
            raise InputError(f"BumpStop: displacement and force need the same length, 2 to "
                             f"{BUMP_MAX} points, got {len(d)} and {len(f)}")
        if not all(math.isfinite(v) for v in d + f):
            raise InputError(f"BumpStop: values must be finite, got {d!r}, {f!r}")
        if d[0] < 0 or any(b <= a for a, b in zip(d, d[1:])):
            raise InputError(f"BumpStop: displacement must start at the clearance >= 0 and "
                             f"increase, got {d!r}")
        if f[0] != 0.0 or any(b < a for a, b in zip(f, f[1:])):
            raise InputError(f"BumpStop: force must start at 0 and not decrease, got {f!r}")
        object.__setattr__(self, "displacement", d)
        object.__setattr__(self, "force", f)

    @property
    def clearance(self) -> float:
        """Free play on each side [m]."""
        return self.displacement[0]

    def __call__(self, d):
        """Force [N] at deflection ``d`` [m] (array or scalar), of the sign of d."""
        d = np.asarray(d, dtype=float)
        a = np.abs(d)
        xs, fs = np.array(self.displacement), np.array(self.force)
        slope = (fs[-1] - fs[-2]) / (xs[-1] - xs[-2])
        f = np.where(a <= xs[0], 0.0, np.interp(a, xs, fs))
        f = np.where(a > xs[-1], fs[-1] + slope * (a - xs[-1]), f)
        return np.sign(d) * f


@dataclass(frozen=True)
class SecondarySuspension:
    """The secondary suspension of each bogie (per side, frozen, SI).

    Parameters
    ----------
    kx, ky, kz : float
        Stiffness of each side's spring set [N/m] (air spring or coils).
    cx, cy, cz : float
        Viscous damping of each side [N s/m].
    half_spacing : float
        Lateral distance of each side's set from the centre plane [m].
    height : float
        Height of the springs, dampers and bump stop above the rail top [m].
    yaw_stiffness : float
        Rotational stiffness about the vertical of each side's set [N m/rad]
        (an air spring's torsion), besides the 2 kx b² of the longitudinal springs.
    anti_roll : float
        Anti-roll bar stiffness per bogie [N m/rad] against the roll of the car body
        relative to the frame.
    yaw_damper : YawDamper or None
    bumpstop : BumpStop or None
    """

    kx: float = 0.0
    ky: float = 0.0
    kz: float = 0.0
    cx: float = 0.0
    cy: float = 0.0
    cz: float = 0.0
    half_spacing: float = 1.0
    height: float = 0.8
    yaw_stiffness: float = 0.0
    anti_roll: float = 0.0
    yaw_damper: YawDamper | None = None
    bumpstop: BumpStop | None = None

    def __post_init__(self):
        for name in ("kx", "ky", "kz", "cx", "cy", "cz", "height", "yaw_stiffness",
                     "anti_roll"):
            object.__setattr__(self, name, _number("SecondarySuspension", name,
                                                   getattr(self, name)))
        object.__setattr__(self, "half_spacing", _number("SecondarySuspension", "half_spacing",
                                                         self.half_spacing, open_lo=True))
        if self.yaw_damper is not None and not isinstance(self.yaw_damper, YawDamper):
            raise InputError(f"yaw_damper must be a YawDamper or None, got "
                             f"{type(self.yaw_damper).__name__}")
        if self.bumpstop is not None and not isinstance(self.bumpstop, BumpStop):
            raise InputError(f"bumpstop must be a BumpStop or None, got "
                             f"{type(self.bumpstop).__name__}")

    @classmethod
    def from_suspension(cls, s: Suspension, **kw) -> "SecondarySuspension":
        """From a :class:`~wheelrail.dynamics.Suspension` (spring sets only)."""
        return cls(s.kx, s.ky, s.kz, s.cx, s.cy, s.cz, s.half_spacing, **kw)


@dataclass(frozen=True, eq=False)
class VehicleModel:
    """A rigid car body on two bogies, or on two wheelsets (frozen, SI; module docstring).

    Parameters
    ----------
    carbody : CarBody
    bogies : BogieModel or (BogieModel, BogieModel) or None
        The bogies (leading first; one model is used for both). Of each, the
        wheelsets, primary suspension, frame and semi-wheelbase are used; its
        ``secondary`` and ``axle_load`` are replaced by the vehicle's. The rail
        support, spin and material of the first apply to the whole vehicle.
    secondary : SecondarySuspension or Suspension or None
        Between each frame and the car body (required with bogies).
    bogie_semi_spacing : float
        Half the distance between the bogie centres [m] (bogie 0 at +a_b).
    frame_height : float
        Height of the frames' centres of mass above the rail top [m].
    primary_height : float or None
        Height of the primary springs above the rail top [m]; default the axle
        (the wheelsets' nominal rolling radius).
    wheelsets : WheelsetModel or None
        Two-axle vehicle: the wheelset and its primary suspension (to the car body);
        ``bogies`` and ``secondary`` must then be None.
    semi_wheelbase : float or None
        Two-axle vehicle: half the distance between the axles [m].

    Attributes
    ----------
    axle_load : float
        Static vertical force of each wheelset on the track [N] (the vehicle's
        weight shared equally: the bodies are symmetric fore and aft).
    """

    carbody: CarBody
    bogies: object = None
    secondary: object = None
    bogie_semi_spacing: float = 9.5
    frame_height: float = 0.6
    primary_height: float | None = None
    wheelsets: WheelsetModel | None = None
    semi_wheelbase: float | None = None

    def __post_init__(self):
        if not isinstance(self.carbody, CarBody):
            raise InputError(f"carbody must be a wheelrail.dynamics.CarBody, got "
                             f"{type(self.carbody).__name__}")
        if self.bogies is not None:
            bg = (self.bogies, self.bogies) if isinstance(self.bogies, BogieModel) \
                else tuple(self.bogies) if isinstance(self.bogies, (tuple, list)) else None
            if bg is None or len(bg) != 2 or not all(isinstance(b, BogieModel) for b in bg):
                raise InputError(f"bogies must be a BogieModel or a pair of them, got "
                                 f"{self.bogies!r}")
            if self.wheelsets is not None:
                raise InputError("give either bogies (a bogie vehicle) or wheelsets (a two-axle "
                                 "vehicle), not both")
            object.__setattr__(self, "bogies", bg)
            sec = self.secondary
            if isinstance(sec, Suspension):
                sec = SecondarySuspension.from_suspension(sec)
            if not isinstance(sec, SecondarySuspension):
                raise InputError(f"secondary must be a SecondarySuspension (or a Suspension), "
                                 f"got {type(sec).__name__}")
            object.__setattr__(self, "secondary", sec)
            b0, b1 = bg
            if b1.wheelset is not b0.wheelset:
                raise InputError("both bogies must run on the same Wheelset object (the "
                                 "profiles of all wheels)")
            object.__setattr__(self, "bogie_semi_spacing", _number(
                "VehicleModel", "bogie_semi_spacing", self.bogie_semi_spacing, open_lo=True))
            if self.bogie_semi_spacing <= max(b.semi_wheelbase for b in bg):
                raise InputError(f"bogie_semi_spacing = {self.bogie_semi_spacing!r} m must exceed "
                                 f"the bogies' semi-wheelbase")
            template = b0
        elif self.wheelsets is not None:
            if not isinstance(self.wheelsets, WheelsetModel):
                raise InputError(f"wheelsets must be a WheelsetModel, got "
                                 f"{type(self.wheelsets).__name__}")
            if self.secondary is not None:
                raise InputError("a two-axle vehicle has no secondary suspension: give "
                                 "secondary=None")
            if self.semi_wheelbase is None:
                raise InputError("a two-axle vehicle needs semi_wheelbase [m]")
            object.__setattr__(self, "semi_wheelbase", _number(
                "VehicleModel", "semi_wheelbase", self.semi_wheelbase, open_lo=True))
            template = self.wheelsets
        else:
            raise InputError("VehicleModel needs bogies=... (with secondary=...) or "
                             "wheelsets=... (two-axle vehicle)")
        object.__setattr__(self, "frame_height", _number("VehicleModel", "frame_height",
                                                         self.frame_height))
        r0 = template.wheelset.nominal_radius
        ph = r0 if self.primary_height is None else _number("VehicleModel", "primary_height",
                                                            self.primary_height)
        object.__setattr__(self, "primary_height", ph)
        object.__setattr__(self, "_template", template)
        if self.bogies is not None:
            total = self.carbody.mass + sum(b.frame_mass + 2 * b.mass for b in self.bogies)
        else:
            total = self.carbody.mass + 2 * template.mass
        object.__setattr__(self, "axle_load", total * GRAVITY / self.n_wheelsets)

    # the wheelset-level properties the simulation and contact need
    @property
    def wheelset(self):
        """The wheel and rail profiles' :class:`~wheelrail.Wheelset` of all wheelsets."""
        return self._template.wheelset

    @property
    def rail(self):
        return self._template.rail

    @property
    def spin(self) -> str:
        return self._template.spin

    @property
    def material(self):
        return self._template.material

    @property
    def n_wheelsets(self) -> int:
        return 4 if self.bogies is not None else 2

    @property
    def n_frames(self) -> int:
        return 2 if self.bogies is not None else 0

    @property
    def mass(self) -> float:
        """Total mass of the vehicle [kg]."""
        return self.axle_load * self.n_wheelsets / GRAVITY

    def wheelset_models(self):
        """(mass, inertia, primary, position relative to the car body's centre [m],
        parent frame index or −1 for the car body) of each wheelset, leading first."""
        out = []
        if self.bogies is not None:
            for j, b in enumerate(self.bogies):
                xb = self.bogie_semi_spacing * (1.0 if j == 0 else -1.0)
                for k in (1.0, -1.0):
                    out.append((b.mass, b.inertia, b.primary, xb + k * b.semi_wheelbase, j,
                                k * b.semi_wheelbase))
        else:
            w = self.wheelsets
            for k in (1.0, -1.0):
                out.append((w.mass, w.inertia, w.primary, k * self.semi_wheelbase, -1,
                            k * self.semi_wheelbase))
        return out


def manchester_bogie(spin: str = "fixed", rail=None, *, material=None) -> BogieModel:
    """The bogie of vehicle 1 of the Manchester benchmarks, with its share of the car body.

    Values (Iwnicki 1998, as compiled in ``manchester_vehicle1.md`` of the project's
    benchmark data, see :func:`manchester_vehicle1`): two wheelsets of 1813 kg,
    roll/spin/yaw inertia 1120/112/1120 kg m², S1002 wheels with a nominal rolling
    radius of 0.46 m and 1.360 m back-to-back; primary per axlebox kx/ky/kz =
    31.391/3.884/1.22 MN/m, cx/cy/cz = 15/2/4 kN s/m at ±1.0 m; frame 2615 kg,
    1722/1476/3067 kg m²; semi-wheelbase 1.28 m; secondary per side kx/ky/kz =
    0.160/0.160/0.430 MN/m, cy/cz = 32/20 kN s/m at ±1.0 m, to the car body. The car
    body (32 000 kg) is not a degree of freedom of a bogie model: a quarter of it rests
    on each axle, so the axle load is (32 000/4 + 2615/2 + 1813) kg × g = 109.09 kN.
    The benchmark track is ``wr.Track(wr.profiles.load("60E1"))`` (1.435 m, 1:40).

    Parameters
    ----------
    spin : {"fixed", "free"}
        Wheelset spin: Ω = V/r0 or a degree of freedom.
    rail : RailSupport or None
        Flexible rails; None for a rigid track.
    material : Material or MaterialPair or None
        Default steel.

    Returns
    -------
    BogieModel
        The bogie, leading wheelset at +1.28 m. :func:`manchester_vehicle1` puts two of
        them under the car body (replacing their ``secondary`` and ``axle_load`` by the
        vehicle's).

    References
    ----------
    .. [1] S. Iwnicki, Manchester benchmarks for rail vehicle simulation, Vehicle
       System Dynamics 30 (1998) 295–313.
    """
    ws = Wheelset(load_profile("S1002"), nominal_radius=0.46, flange_back=1.360)
    prim = Suspension(kx=31.391e6, ky=3.884e6, kz=1.22e6, cx=15e3, cy=2e3, cz=4e3,
                      half_spacing=1.0)
    sec = Suspension(kx=0.160e6, ky=0.160e6, kz=0.430e6, cy=32e3, cz=20e3, half_spacing=1.0)
    axle_load = (32000.0 / 4 + 2615.0 / 2 + 1813.0) * GRAVITY
    return BogieModel(ws, 1813.0, (1120.0, 112.0, 1120.0), prim, 2615.0,
                      (1722.0, 1476.0, 3067.0), 1.28, sec, rail=rail, axle_load=axle_load,
                      spin=spin, material=STEEL if material is None else material)


def manchester_vehicle1(spin: str = "fixed", rail=None, *, yaw_damper: YawDamper | None = None,
                        material=None) -> VehicleModel:
    """Vehicle 1 of the Manchester benchmarks (a passenger coach on two bogies).

    Values (Iwnicki 1998, as compiled in ``manchester_vehicle1.md`` of the project's
    benchmark data, a public parameter file of a vehicle–track code citing that paper;
    the paper's own table could not be read here): wheelset 1813 kg, roll/spin/yaw
    inertia 1120/112/1120 kg m²; frame 2615 kg, 1722/1476/3067 kg m²; car body
    32 000 kg, 56 800/1 970 000/1 970 000 kg m²; primary per axlebox kx/ky/kz =
    31.391/3.884/1.22 MN/m, cx/cy/cz = 15/2/4 kN s/m at ±1.0 m; secondary per bogie
    side kx/ky/kz = 0.160/0.160/0.430 MN/m, cy/cz = 32/20 kN s/m at ±1.0 m, rotational
    yaw stiffness 10.5 kN m/rad per side; anti-roll bar 940 kN m/rad; semi-wheelbase
    1.28 m, bogie centres at ±9.5 m; heights above rail: car body 1.8 m, secondary
    0.8275 m, frame 0.6 m, axle 0.46 m; lateral bump stop with 25 mm clearance and
    the force table 0.6/1.76/3.73/6.87/11.58/17.17/29.2/230 kN at 30 … 65 mm.
    Profiles S1002 on 60E1 (UIC60) at 1:40, gauge 1.435 m, back-to-back 1.360 m,
    nominal rolling radius 0.46 m (library built-ins: ``wr.profiles.load("S1002")``,
    ``"60E1"``). No longitudinal secondary damping (cx = 0) and no yaw damper are
    given for this vehicle; ``yaw_damper`` adds one.

    Parameters
    ----------
    spin : {"fixed", "free"}
    rail : RailSupport or None
    yaw_damper : YawDamper or None
    material : Material or MaterialPair or None
        Default steel.

    Returns
    -------
    VehicleModel
        With the track of the benchmark in ``model.track`` is not stored; use
        ``wr.Track(wr.profiles.load("60E1"))`` (1.435 m, 1:40).

    References
    ----------
    .. [1] S. Iwnicki, Manchester benchmarks for rail vehicle simulation, Vehicle
       System Dynamics 30 (1998) 295–313.
    """
    bogie = manchester_bogie(spin, rail, material=material)
    bump = BumpStop((0.025, 0.030, 0.035, 0.040, 0.045, 0.050, 0.055, 0.060, 0.065),
                    (0.0, 600.0, 1760.0, 3730.0, 6870.0, 11580.0, 17170.0, 29200.0, 230000.0))
    sec = SecondarySuspension(kx=0.160e6, ky=0.160e6, kz=0.430e6, cy=32e3, cz=20e3,
                              half_spacing=1.0, height=0.8275, yaw_stiffness=10.5e3,
                              anti_roll=940e3, yaw_damper=yaw_damper, bumpstop=bump)
    body = CarBody(32000.0, (56800.0, 1.97e6, 1.97e6), height=1.8)
    return VehicleModel(carbody=body, bogies=bogie, secondary=sec, bogie_semi_spacing=9.5,
                        frame_height=0.6, primary_height=0.46)


# --------------------------------------------------------------------------- assembly


class VehicleAssembly(_Layout):
    """Parameter vector and state layout of a :class:`VehicleModel` (internal; the
    interface of :class:`wheelrail.dynamics.model.Assembly`).

    States: ``ws{i}.*`` (9 each, leading first), ``frame{j}.*`` (10 each),
    ``body.*`` (10), ``yawdamper{j}.{left,right}`` (the dampers' elongations),
    then rails and relaxation states as for the bogie.
    """

    def __init__(self, model, relax=False):
        self.model = model
        nw = model.n_wheelsets
        nf = model.n_frames
        rails = model.rail is not None
        P = global_parameters(model, NGP + NWP * nw + NVP, relax)
        P[GP["has_frame"]] = 0.0
        P[GP["vehicle"]] = 1.0
        vb = NGP + NWP * nw
        V = {k: vb + i for k, i in VP.items()}
        names = wheelset_names(nw)
        off_frame = len(names)
        for j in range(nf):
            names += [f"frame{j}.{s}" for s in FRAME_STATES]
        off_body = len(names)
        names += [f"body.{s}" for s in BODY_STATES]
        off_yd = len(names)
        sec = model.secondary
        if nf and sec.yaw_damper is not None:
            for j in range(nf):
                names += [f"yawdamper{j}.left", f"yawdamper{j}.right"]
        off_rails, off_relax = append_rail_relax_names(names, nw, rails, relax)
        P[GP["off_frame"]] = off_frame
        P[GP["off_rails"]] = off_rails
        P[GP["off_relax"]] = off_relax
        cb = model.carbody
        P[V["n_frames"]] = nf
        P[V["body_m"]] = cb.mass
        P[V["body_Ix"]], P[V["body_Iy"]], P[V["body_Iz"]] = cb.inertia
        P[V["body_h"]] = cb.height
        P[V["frame_h"]] = model.frame_height
        P[V["prim_h"]] = model.primary_height
        P[V["off_body"]] = off_body
        P[V["off_yd"]] = off_yd
        if nf:
            for j, b in enumerate(model.bogies):
                P[V[f"fm{j}"]] = b.frame_mass
                P[V[f"fIx{j}"]], P[V[f"fIy{j}"]], P[V[f"fIz{j}"]] = b.frame_inertia
                P[V[f"xf{j}"]] = model.bogie_semi_spacing * (1.0 if j == 0 else -1.0)
            for k in ("kx", "ky", "kz", "cx", "cy", "cz"):
                P[V["s_" + k]] = getattr(sec, k)
            P[V["s_b"]] = sec.half_spacing
            P[V["s_h"]] = sec.height
            P[V["s_kpsi"]] = sec.yaw_stiffness
            P[V["s_arb"]] = sec.anti_roll
            P[V["s_pre"]] = cb.mass * GRAVITY / 4.0
            if sec.yaw_damper is not None:
                P[V["yd"]] = 1.0
                P[V["yd_c"]] = sec.yaw_damper.damping
                P[V["yd_k"]] = sec.yaw_damper.stiffness
                P[V["yd_b"]] = sec.yaw_damper.half_spacing
            if sec.bumpstop is not None:
                bs = sec.bumpstop
                P[V["bs_n"]] = len(bs.displacement)
                for k, (d, f) in enumerate(zip(bs.displacement, bs.force)):
                    P[V[f"bs_d{k}"]] = d
                    P[V[f"bs_f{k}"]] = f
        for i, (m, inertia, prim, x, parent, xrel) in enumerate(model.wheelset_models()):
            b = NGP + NWP * i
            P[b + WP["m"]] = m
            P[b + WP["Ix"]], P[b + WP["Iy"]], P[b + WP["Iz"]] = inertia
            for k, v in zip(("kx", "ky", "kz", "cx", "cy", "cz", "b"), prim.values()):
                P[b + WP[k]] = v
            P[b + WP["x"]] = x
            if parent >= 0:
                fm = model.bogies[parent].frame_mass
                P[b + WP["preload"]] = (fm + 0.5 * cb.mass) * GRAVITY / 4.0
            else:
                P[b + WP["preload"]] = cb.mass * GRAVITY / 4.0
            P[V[f"par{i}"]] = parent
            P[V[f"xr{i}"]] = xrel
        self.P = P
        self.names = names
        self.n = len(names)
        self.n_ws = nw
        self.n_frames = nf
        self.frame = False
        self.vehicle = True
        self.rails = rails
        self.relax = relax
        self.off_frame, self.off_rails, self.off_relax = off_frame, off_rails, off_relax
        self.off_body, self.off_yd = off_body, off_yd
        self.n_yd = off_rails - off_yd

    def _bodies(self):
        return [self.off_frame + 10 * j for j in range(self.n_frames)] + [self.off_body]

    def quasi_static(self, spin: bool = False, linear: bool = False):
        """As :meth:`wheelrail.dynamics.model.Assembly.quasi_static`: heights and rolls of
        the wheelsets, heights, rolls and pitches of frames and car body, the rail
        deflections (and with ``spin`` the free wheelsets' Ω). With ``linear`` (the states
        :func:`~wheelrail.dynamics.linearise` condenses) the frames' and car body's are
        left out: their modes are as slow as the lateral ones."""
        cols, rows, steps, scales = [], [], [], []

        def add(c, r, h, s):
            cols.append(c)
            rows.append(r)
            steps.append(h)
            scales.append(s)

        wheelset_rows(add, self.n_ws, spin and self.model.spin == "free")
        if not linear:
            for ob in self._bodies():
                for k in (1, 2, 3):
                    add(ob + k, ob + 5 + k, 1e-8, 1e-3)
        if self.rails:
            rail_rows(add, self.n_ws, self.off_rails)
        return cols, rows, np.array(steps), np.array(scales)

    def curving_unknowns(self):
        """Unknowns and equations of the steady-curving equilibrium: :meth:`quasi_static`
        (with spin) and the lateral positions and yaws of all bodies."""
        cols, rows, steps, scales = self.quasi_static(spin=True)
        cols, rows, steps, scales = list(cols), list(rows), list(steps), list(scales)
        for i in range(self.n_ws):
            for c, r, s in ((9 * i, 9 * i + 4, 2e-3), (9 * i + 3, 9 * i + 7, 5e-3)):
                cols.append(c)
                rows.append(r)
                steps.append(1e-7)
                scales.append(s)
        for ob in self._bodies():
            for c, r in ((ob, ob + 5), (ob + 4, ob + 9)):
                cols.append(c)
                rows.append(r)
                steps.append(1e-7)
                scales.append(2e-2)
        for k in range(self.n_yd):                  # the yaw dampers at rest: u = d
            cols.append(self.off_yd + k)
            rows.append(self.off_yd + k)
            steps.append(1e-8)
            scales.append(1e-2)
        return cols, rows, np.array(steps), np.array(scales)
