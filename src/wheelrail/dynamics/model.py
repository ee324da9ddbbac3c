"""Vehicle models of :mod:`wheelrail.dynamics`: suspensions, rail support, wheelset and bogie.

A :class:`WheelsetModel` is one rigid wheelset with five degrees of freedom —
lateral y, vertical z, roll θ, yaw ψ and the angular velocity Ω about its axle
(``spin="free"``; or Ω = V/r0 held, ``spin="fixed"``) — joined by its primary
suspension to a frame that moves along the track centre line at the speed V.
A :class:`BogieModel` is two such wheelsets in a bogie frame (lateral,
vertical, roll, pitch, yaw) joined by the secondary suspension to the car body,
which moves along the track centre line at V and whose weight rests on the
frame. Each wheelset runs on its own piece of rail: rigid, or a
:class:`RailSupport` (per rail, laterally and vertically, the rail head's mass
on two spring–dampers in series — rail/pad and support — as the rail model of
Piotrowski & Chollet 2005, §2.3.3).

Coordinates are those of :mod:`wheelrail.geometry.contact_search`, relative to
the track-following frame at each body's position along the track (x forward,
y right, z up, in the plane of the canted track; roll positive with the right
side higher, yaw positive with the nose to the right; pitch positive with the
front up). All quantities SI.

References
----------
.. [1] J. Piotrowski, H. Chollet, Wheel–rail contact models for vehicle system
   dynamics including multi-point contact, VSD 43 (2005) 455–483, §2.2 (the
   wheelset model of Pascal), §2.3.3 (rail: two serial springs).
.. [2] A.H. Wickens, *Fundamentals of rail vehicle dynamics: guidance and
   stability*, Swets & Zeitlinger 2003, ch. 2–4 (the wheelset and bogie
   equations, primary yaw stiffness 2 kx b²).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError
from ..geometry import Wheelset
from ..materials import STEEL, as_material_pair

__all__ = ["Suspension", "RailSupport", "WheelsetModel", "BogieModel", "GRAVITY"]

#: Standard gravity [m/s²].
GRAVITY = 9.81


def _number(owner, name, value, *, lo=0.0, open_lo=False, allow_inf=False):
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{owner}: {name} must be a number, got {value!r}") from None
    if math.isnan(v) or (math.isinf(v) and not allow_inf):
        raise InputError(f"{owner}: {name} must be finite, got {value!r}")
    if (v <= lo) if open_lo else (v < lo):
        raise InputError(f"{owner}: {name} must be {'>' if open_lo else '>='} {lo:g}, got "
                         f"{value!r}")
    return v


def _pair(owner, name, value, *, open_lo=False):
    try:
        a, b = value
    except (TypeError, ValueError):
        raise InputError(f"{owner}: {name} must be a pair of numbers, got {value!r}") from None
    return (_number(owner, f"{name}[0]", a, open_lo=open_lo),
            _number(owner, f"{name}[1]", b, open_lo=open_lo))


def _inertia(owner, value):
    try:
        vals = tuple(value)
    except TypeError:
        raise InputError(f"{owner}: inertia must be (Ix, Iy, Iz) [kg m²], got {value!r}") from None
    if len(vals) != 3:
        raise InputError(f"{owner}: inertia must be (Ix, Iy, Iz) [kg m²], got {value!r}")
    return tuple(_number(owner, f"inertia[{i}]", v, open_lo=True) for i, v in enumerate(vals))


@dataclass(frozen=True)
class Suspension:
    """Linear spring–damper sets, one on each side (frozen, SI).

    Parameters
    ----------
    kx, ky, kz : float
        Longitudinal, lateral and vertical stiffness of each side [N/m].
    cx, cy, cz : float
        Viscous damping of each side [N s/m].
    half_spacing : float
        Lateral distance b of each side's set from the centre plane [m]; the yaw
        stiffness of a wheelset on this suspension is 2 kx b² (Wickens 2003).

    Examples
    --------
    >>> Suspension(kx=1e6, ky=3.884e6, kz=1e6).yaw_stiffness
    2000000.0
    """

    kx: float = 0.0
    ky: float = 0.0
    kz: float = 0.0
    cx: float = 0.0
    cy: float = 0.0
    cz: float = 0.0
    half_spacing: float = 1.0

    def __post_init__(self):
        for name in ("kx", "ky", "kz", "cx", "cy", "cz"):
            object.__setattr__(self, name, _number("Suspension", name, getattr(self, name)))
        object.__setattr__(self, "half_spacing",
                           _number("Suspension", "half_spacing", self.half_spacing, open_lo=True))

    @property
    def yaw_stiffness(self) -> float:
        """2 kx b² [N m/rad]."""
        return 2.0 * self.kx * self.half_spacing ** 2

    def values(self) -> tuple:
        return (self.kx, self.ky, self.kz, self.cx, self.cy, self.cz, self.half_spacing)


@dataclass(frozen=True)
class RailSupport:
    """Flexible rails: per rail and direction, the rail head's mass on two serial spring–dampers.

    Laterally and vertically, each rail head (mass m) is joined to a massless
    intermediate point by the rail/pad element (k1, c1), which is joined to the
    ground by the support element (k2, c2): two springs in series between the
    contact and the ground, each with its damper (Piotrowski & Chollet 2005,
    §2.3.3). The wheel's contact force acts on the head.

    Parameters
    ----------
    lateral_stiffness, vertical_stiffness : (float, float)
        (k1, k2) [N/m], > 0.
    lateral_damping, vertical_damping : (float, float)
        (c1, c2) [N s/m], ≥ 0 with c1 + c2 > 0 (the intermediate point is massless).
    mass : (float, float)
        Effective mass of the rail head moving laterally and vertically [kg], > 0
        (a massless head would make the contact force depend on its own velocity).
    """

    lateral_stiffness: tuple = (1.0e8, 5.0e7)
    vertical_stiffness: tuple = (5.0e8, 1.5e8)
    lateral_damping: tuple = (5.0e4, 2.0e5)
    vertical_damping: tuple = (5.0e4, 2.0e5)
    mass: tuple = (100.0, 150.0)

    def __post_init__(self):
        for name in ("lateral_stiffness", "vertical_stiffness"):
            object.__setattr__(self, name, _pair("RailSupport", name, getattr(self, name),
                                                 open_lo=True))
        for name in ("lateral_damping", "vertical_damping"):
            object.__setattr__(self, name, _pair("RailSupport", name, getattr(self, name)))
        object.__setattr__(self, "mass", _pair("RailSupport", "mass", self.mass, open_lo=True))
        for name in ("lateral_damping", "vertical_damping"):
            if not sum(getattr(self, name)) > 0:
                raise InputError(f"RailSupport: {name} must have c1 + c2 > 0 (the massless "
                                 f"support point moves through its dampers), got "
                                 f"{getattr(self, name)!r}")

    def direction(self, d: int) -> tuple:
        """(k1, c1, k2, c2, m) of direction 0 (lateral) or 1 (vertical)."""
        k = self.lateral_stiffness if d == 0 else self.vertical_stiffness
        c = self.lateral_damping if d == 0 else self.vertical_damping
        return (k[0], c[0], k[1], c[1], self.mass[d])

    def static_deflection(self, force: float, d: int) -> tuple:
        """(intermediate, head) deflection [m] under a static force on the head [N]."""
        k1, _, k2, _, _ = self.direction(d)
        w = force / k2
        return w, w + force / k1


def _check_support(model, owner, least, what):
    """Rail support, axle load (default and lower bound ``least`` [N], ``what`` it is for the
    message), spin and material of a wheelset or bogie model (set on the frozen ``model``)."""
    if model.rail is not None and not isinstance(model.rail, RailSupport):
        raise InputError(f"rail must be a wheelrail.dynamics.RailSupport or None, got "
                         f"{type(model.rail).__name__}")
    load = least if model.axle_load is None else _number(owner, "axle_load", model.axle_load,
                                                         open_lo=True)
    if load < least * (1 - 1e-12):
        raise InputError(f"axle_load = {load!r} N is less than {what} {least!r} N")
    object.__setattr__(model, "axle_load", float(load))
    _check_spin(model.spin)
    object.__setattr__(model, "material", as_material_pair(model.material))


def _check_spin(spin):
    if spin not in ("free", "fixed"):
        raise InputError(f"spin must be 'free' (Ω a degree of freedom) or 'fixed' (Ω = V/r0), "
                         f"got {spin!r}")
    return spin


@dataclass(frozen=True, eq=False)
class WheelsetModel:
    """A rigid wheelset on its primary suspension, joined to a frame moving at V (frozen, SI).

    Parameters
    ----------
    wheelset : Wheelset
        Profiles and geometry (:class:`wheelrail.Wheelset`).
    mass : float
        Wheelset mass [kg].
    inertia : (float, float, float)
        Moments of inertia about the longitudinal (roll), axle (spin) and vertical
        (yaw) axes [kg m²].
    primary : Suspension
        Springs and dampers between the axleboxes and the frame (per side).
    rail : RailSupport or None
        Flexible rails, or ``None`` for rigid rails.
    axle_load : float or None
        Vertical force of the wheelset on the track at rest [N] (the load it
        carries plus its weight); default its weight. The carried part acts at
        the axle centre under the track frame's apparent gravity (gravity and
        the curve's centripetal acceleration).
    spin : {"free", "fixed"}
        Ω a degree of freedom driven by the longitudinal creep forces, or held at V/r0.
    material : Material or MaterialPair
        Wheel and rail materials (default steel).
    """

    wheelset: object
    mass: float
    inertia: tuple
    primary: Suspension = field(default_factory=Suspension)
    rail: RailSupport | None = None
    axle_load: float | None = None
    spin: str = "free"
    material: object = STEEL

    def __post_init__(self):
        if not isinstance(self.wheelset, Wheelset):
            raise InputError(f"wheelset must be a wheelrail.Wheelset, got "
                             f"{type(self.wheelset).__name__}")
        object.__setattr__(self, "mass", _number("WheelsetModel", "mass", self.mass,
                                                 open_lo=True))
        object.__setattr__(self, "inertia", _inertia("WheelsetModel", self.inertia))
        if not isinstance(self.primary, Suspension):
            raise InputError(f"primary must be a wheelrail.dynamics.Suspension, got "
                             f"{type(self.primary).__name__}")
        _check_support(self, "WheelsetModel", self.mass * GRAVITY, "the wheelset's weight")

    @property
    def n_wheelsets(self) -> int:
        return 1

    @property
    def carried_mass(self) -> float:
        """Mass whose weight the wheelset carries [kg] (axle_load/g − mass)."""
        return max(self.axle_load / GRAVITY - self.mass, 0.0)


@dataclass(frozen=True, eq=False)
class BogieModel:
    """Two wheelsets in a bogie frame, the frame on its secondary suspension (frozen, SI).

    The car body is not a degree of freedom: it moves along the track centre
    line at V; its weight and its share of the curve's unbalanced lateral force
    act on the frame, and the secondary suspension joins the frame to it.

    Parameters
    ----------
    wheelset : Wheelset
        Profiles of both wheelsets.
    mass, inertia : float, (float, float, float)
        Of each wheelset [kg], [kg m²] (roll, spin, yaw).
    primary : Suspension
        Between each wheelset's axleboxes and the frame.
    frame_mass : float
        Bogie frame mass [kg].
    frame_inertia : (float, float, float)
        Frame moments of inertia about roll, pitch and yaw [kg m²].
    semi_wheelbase : float
        Half the distance between the axles [m]; the leading wheelset is at +a.
    secondary : Suspension
        Between the frame and the car body (at the frame centre, per side).
    rail : RailSupport or None
    axle_load : float or None
        Vertical force of each wheelset on the track at rest [N]; default the
        wheelset's weight plus half the frame's (no car body).
    spin : {"free", "fixed"}
    material : Material or MaterialPair
    """

    wheelset: object
    mass: float
    inertia: tuple
    primary: Suspension
    frame_mass: float
    frame_inertia: tuple
    semi_wheelbase: float
    secondary: Suspension = field(default_factory=Suspension)
    rail: RailSupport | None = None
    axle_load: float | None = None
    spin: str = "free"
    material: object = STEEL

    def __post_init__(self):
        if not isinstance(self.wheelset, Wheelset):
            raise InputError(f"wheelset must be a wheelrail.Wheelset, got "
                             f"{type(self.wheelset).__name__}")
        object.__setattr__(self, "mass", _number("BogieModel", "mass", self.mass, open_lo=True))
        object.__setattr__(self, "inertia", _inertia("BogieModel", self.inertia))
        object.__setattr__(self, "frame_mass", _number("BogieModel", "frame_mass",
                                                       self.frame_mass, open_lo=True))
        object.__setattr__(self, "frame_inertia", _inertia("BogieModel", self.frame_inertia))
        object.__setattr__(self, "semi_wheelbase", _number("BogieModel", "semi_wheelbase",
                                                           self.semi_wheelbase, open_lo=True))
        for name in ("primary", "secondary"):
            if not isinstance(getattr(self, name), Suspension):
                raise InputError(f"{name} must be a wheelrail.dynamics.Suspension, got "
                                 f"{type(getattr(self, name)).__name__}")
        _check_support(self, "BogieModel", (self.mass + 0.5 * self.frame_mass) * GRAVITY,
                       "the wheelset's weight plus half the frame's,")

    @property
    def n_wheelsets(self) -> int:
        return 2

    @property
    def body_mass(self) -> float:
        """Car-body mass resting on the frame [kg] (2 axle_load/g − 2 mass − frame_mass)."""
        return max(2.0 * self.axle_load / GRAVITY - 2.0 * self.mass - self.frame_mass, 0.0)


# --------------------------------------------------------------------------- assembly
#: Names of the state variables of a wheelset, a frame and a rail direction.
WHEELSET_STATES = ("y", "z", "roll", "yaw", "vy", "vz", "roll_rate", "yaw_rate", "omega")
FRAME_STATES = ("y", "z", "roll", "pitch", "yaw", "vy", "vz", "roll_rate", "pitch_rate",
                "yaw_rate")
RAIL_STATES = ("support", "head", "head_velocity")
RELAX_STATES = ("Qt_y", "Qt_z", "Qt_roll", "Qt_yaw", "Qt_spin")

#: Indices of the global part of the parameter vector (see :class:`Assembly`).
GP = {n: i for i, n in enumerate((
    "n_ws", "has_frame", "rails", "relax", "spin_free", "g", "r0", "rail_lat_k1", "rail_lat_c1",
    "rail_lat_k2", "rail_lat_c2", "rail_lat_m", "rail_ver_k1", "rail_ver_c1", "rail_ver_k2",
    "rail_ver_c2", "rail_ver_m", "frame_m", "frame_Ix", "frame_Iy", "frame_Iz", "sec_kx",
    "sec_ky", "sec_kz", "sec_cx", "sec_cy", "sec_cz", "sec_b", "body_m", "off_frame",
    "off_rails", "off_relax", "relax_floor", "vehicle"))}
#: Per-wheelset parameters (block of :data:`NWP` after the global part).
WP = {n: i for i, n in enumerate((
    "m", "Ix", "Iy", "Iz", "kx", "ky", "kz", "cx", "cy", "cz", "b", "x", "preload", "carried_m"))}
NGP = len(GP)
NWP = len(WP)


def global_parameters(model, n_params, relax):
    """The parameter vector (length ``n_params``) with the global part shared by every
    model filled in: wheelset count, rails, relaxation, spin, gravity, r0 and the rail
    support's spring–dampers (internal; :class:`Assembly`, ``VehicleAssembly``)."""
    P = np.zeros(n_params)
    P[GP["n_ws"]] = model.n_wheelsets
    P[GP["rails"]] = 1.0 if model.rail is not None else 0.0
    # relaxation length in semi-axes a (True: 1)
    P[GP["relax"]] = (1.0 if relax is True else float(relax)) if relax else 0.0
    P[GP["spin_free"]] = 1.0 if model.spin == "free" else 0.0
    P[GP["g"]] = GRAVITY
    P[GP["r0"]] = model.wheelset.nominal_radius
    P[GP["relax_floor"]] = 1e-3
    if model.rail is not None:
        for d, key in ((0, "rail_lat"), (1, "rail_ver")):
            k1, c1, k2, c2, m = model.rail.direction(d)
            P[GP[key + "_k1"]], P[GP[key + "_c1"]] = k1, c1
            P[GP[key + "_k2"]], P[GP[key + "_c2"]] = k2, c2
            P[GP[key + "_m"]] = m
    return P


def wheelset_names(nw):
    """State names of ``nw`` wheelsets, leading first (they start the state vector)."""
    return [f"ws{i}.{s}" for i in range(nw) for s in WHEELSET_STATES]


def append_rail_relax_names(names, nw, rails, relax):
    """Append the rail and relaxation states of ``nw`` wheelsets to ``names``; returns
    their offsets (off_rails, off_relax)."""
    off_rails = len(names)
    if rails:
        for i in range(nw):
            for side in ("left", "right"):
                for d in ("lateral", "vertical"):
                    names += [f"rail{i}.{side}.{d}.{s}" for s in RAIL_STATES]
    off_relax = len(names)
    if relax:
        for i in range(nw):
            for side in ("left", "right"):
                names += [f"relax{i}.{side}.{s}" for s in RELAX_STATES]
    return off_rails, off_relax


def wheelset_rows(add, n_ws, free_spin):
    """The settling positions of the wheelsets for ``quasi_static`` (height, roll; Ω with
    ``free_spin``): ``add(col, row, step, scale)``."""
    for i in range(n_ws):
        add(9 * i + 1, 9 * i + 5, 1e-8, 1e-4)          # z
        add(9 * i + 2, 9 * i + 6, 1e-8, 1e-4)          # roll
        if free_spin:
            add(9 * i + 8, 9 * i + 8, 1e-5, 0.02)      # Ω


def rail_rows(add, n_ws, off_rails):
    """The settling positions of the flexible rails for ``quasi_static`` (support point,
    head): ``add(col, row, step, scale)``."""
    for i in range(n_ws):
        for side in range(2):
            for d in range(2):
                rb = off_rails + 12 * i + 6 * side + 3 * d
                add(rb, rb, 1e-8, 1e-3)            # support point: ẇ = 0
                add(rb + 1, rb + 2, 1e-8, 1e-3)    # head: v̇ = 0


class _Layout:
    """State lookup and wheel load shared by :class:`Assembly` and the vehicle's assembly
    (both have ``names`` and ``model.axle_load``)."""

    def index(self, name: str) -> int:
        """Index of a state variable by name."""
        try:
            return self.names.index(name)
        except ValueError:
            raise InputError(f"no state {name!r}; states: {', '.join(self.names)}") from None

    def wheel_load(self) -> float:
        """Static vertical force of each wheel [N]."""
        return 0.5 * self.model.axle_load


class Assembly(_Layout):
    """The numbers the compiled equations need: parameter vector and state layout (internal).

    Attributes
    ----------
    P : ndarray
        Parameters (:data:`GP`, then :data:`WP` per wheelset).
    n : int
        Number of states.
    names : list of str
        State names (``ws0.y``, ``frame.yaw``, ``rail0.right.lateral.head``, ...).
    """

    def __init__(self, model, relax=False):
        self.model = model
        nw = model.n_wheelsets
        frame = isinstance(model, BogieModel)
        rails = model.rail is not None
        P = global_parameters(model, NGP + NWP * nw, relax)
        P[GP["has_frame"]] = 1.0 if frame else 0.0
        names = wheelset_names(nw)
        off_frame = len(names)
        if frame:
            names += [f"frame.{s}" for s in FRAME_STATES]
            P[GP["frame_m"]] = model.frame_mass
            P[GP["frame_Ix"]], P[GP["frame_Iy"]], P[GP["frame_Iz"]] = model.frame_inertia
            sec = model.secondary
            for k, v in zip(("kx", "ky", "kz", "cx", "cy", "cz", "b"), sec.values()):
                P[GP["sec_" + k]] = v
            P[GP["body_m"]] = model.body_mass
        off_rails, off_relax = append_rail_relax_names(names, nw, rails, relax)
        P[GP["off_frame"]] = off_frame
        P[GP["off_rails"]] = off_rails
        P[GP["off_relax"]] = off_relax
        for i in range(nw):
            b = NGP + NWP * i
            P[b + WP["m"]] = model.mass
            P[b + WP["Ix"]], P[b + WP["Iy"]], P[b + WP["Iz"]] = model.inertia
            for k, v in zip(("kx", "ky", "kz", "cx", "cy", "cz", "b"), model.primary.values()):
                P[b + WP[k]] = v
            if frame:
                P[b + WP["x"]] = model.semi_wheelbase * (1.0 if i == 0 else -1.0)
                # the primary springs carry the frame and the body at rest
                P[b + WP["preload"]] = (model.frame_mass + model.body_mass) * GRAVITY / 4.0
            else:
                P[b + WP["carried_m"]] = model.carried_mass
        self.P = P
        self.names = names
        self.n = len(names)
        self.n_ws = nw
        self.frame = frame
        self.rails = rails
        self.relax = relax
        self.off_frame, self.off_rails, self.off_relax = off_frame, off_rails, off_relax

    def quasi_static(self, spin: bool = False):
        """The positions that settle fast (heights, rolls, pitch, rail deflections; with
        ``spin`` the free wheelsets' Ω) and the rows of their accelerations.

        Returns
        -------
        cols, rows : list of int
            State indices and the indices of the equations that vanish at equilibrium.
        steps, scales : ndarray
            Finite-difference steps and largest Newton steps of each.
        """
        cols, rows, steps, scales = [], [], [], []

        def add(c, r, h, s):
            cols.append(c)
            rows.append(r)
            steps.append(h)
            scales.append(s)

        wheelset_rows(add, self.n_ws, spin and self.model.spin == "free")
        if self.frame:
            of = self.off_frame
            for k in (1, 2, 3):                            # z, roll, pitch
                add(of + k, of + 5 + k, 1e-8, 1e-3)
        if self.rails:
            rail_rows(add, self.n_ws, self.off_rails)
        return cols, rows, np.array(steps), np.array(scales)

