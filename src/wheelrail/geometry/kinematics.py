"""Kinematics: creepages and spin at a contact point from the motion of a wheelset.

The creepages are the rigid slip velocity of the wheel relative to the rail
at the contact point, divided by the rolling speed ``V``, in the contact
frame of :mod:`wheelrail.conventions` (x along the rail, y in the contact
plane to the right, z along the normal into the rail; right-handed)::

    ξ = (v_w − v_r)·e_x / V,   η = (v_w − v_r)·e_y / V,   φ = (ω_w − ω_r)·e_z / V

(Bosso et al. (2013), ch. 2, eq. 2.10; Kalker 1990 §1.4). The wheel material velocity at the
contact point P is ``v_w = v_c + ω_w × (P − C)`` with C the axle centre.

Wheelset motion (track frame: x forward, y right, z up; pose as in
:mod:`wheelrail.geometry.contact_search`): forward speed V, lateral and
vertical velocity ẏ, ż of the axle centre, yaw ψ and roll θ with their
rates, and the angular velocity Ω about the axle, **positive when the
wheelset rolls forwards** (Ω ≈ V/r0 in free rolling). The angular velocity
vector is the pitch rotation about the yawed and rolled axle plus the yaw
rate about the vertical and the roll rate about the yawed longitudinal axis.

Contact frame of a point with contact angle γ (the rail's slope in the track
frame at the point, :mod:`~wheelrail.geometry.contact_search`) on side
σ = +1 (right) / −1 (left), written in the track's (y, z)::

    e_x = x,   e_y = (cos γ, σ sin γ),   e_z = (σ sin γ, −cos γ)

so e_y points to the right on **both** wheels (the convention of
:mod:`wheelrail.conventions`). A consequence worth knowing: the spin of a
conical tread of contact angle γ is φ = −sin γ / r on the right wheel and
+sin γ / r on the left one (mirror images give opposite spin in one frame).

A wheel on a roller (roller rig): the rail is a roller of crown radius
``R`` (at the top of rail) whose axis is parallel to the track's y axis and
whose surface moves backwards at ``V`` under a wheelset whose centre does not
advance; rail material at P moves with the roller's rotation. The roller's
rotation adds to the spin: a conical tread gets φ = ∓ sin γ (1/r + 1/R)
instead of ∓ sin γ / r (the known roller-rig spin excess), and the roller's
curvature along x adds 1/R to the longitudinal curvature of the gap.

Normalisation: by the forward speed ``V`` (the roller surface speed on a
roller). Kalker's rolling speed is the mean circumferential speed of the two
bodies; the difference is of the order of the creepage (second order).

References
----------
.. [1] Review of wheel–rail contact models (Bosso et al. (2013), ch. 2), §2.2, eq. (2.10).
.. [2] Baeza et al., eqs. (2.1)–(2.6): creepages from rigid slip.
.. [3] J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
   Kluwer 1990, §1.4 (creepage and spin).
.. [4] A. Jaschinski, H. Chollet, S. Iwnicki, A. Wickens, J. von Würzen, The
   application of roller rigs to railway vehicle dynamics, VSD 31 (1999)
   345–392 (spin on a roller).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validation import as_float_array, positive
from ..errors import InputError
from ..plausibility import check_omega, check_roller_radius, check_speed

__all__ = ["Motion", "creepages", "creepage_kernel"]


@dataclass(frozen=True)
class Motion:
    """Velocities of a wheelset (frozen, SI).

    Attributes
    ----------
    speed : float
        Forward speed V of the wheelset [m/s] (> 0); on a roller, the surface
        speed of the roller. Creepages are normalised by it.
    omega : float or None
        Angular velocity about the axle [rad/s], positive when rolling
        forwards; ``None``: free rolling at the nominal radius, V/r0.
    lateral_velocity, vertical_velocity : float
        ẏ (to the right) and ż (up) of the axle centre [m/s].
    yaw_rate, roll_rate : float
        ψ̇ and θ̇ [rad/s], with the signs of yaw and roll.
    roller_radius : float or None
        Radius of the roller at the top of rail [m] for a wheel on a roller
        rig; ``None`` (default) for a track.
    """

    speed: float
    omega: float | None = None
    lateral_velocity: float = 0.0
    vertical_velocity: float = 0.0
    yaw_rate: float = 0.0
    roll_rate: float = 0.0
    roller_radius: float | None = None

    def __post_init__(self):
        object.__setattr__(self, "speed", float(positive("speed", self.speed)))
        check_speed(self.speed)  # km/h given: warned, a speed of 1e6 m/s refused
        if self.omega is not None:
            w = float(as_float_array("omega", self.omega))
            if not w > 0:
                raise InputError(f"omega must be > 0 (rolling forwards, rad/s), got {w!r}")
            object.__setattr__(self, "omega", w)
            check_omega(w, self.speed)  # rpm or deg/s given: a radius V/ω of no wheel
        for name in ("lateral_velocity", "vertical_velocity", "yaw_rate", "roll_rate"):
            object.__setattr__(self, name, float(as_float_array(name, getattr(self, name))))
        if self.roller_radius is not None:
            object.__setattr__(self, "roller_radius",
                               float(positive("roller_radius", self.roller_radius)))
            check_roller_radius(self.roller_radius)

    def angular_velocity(self, nominal_radius: float) -> float:
        """Ω [rad/s]: ``omega``, or V/r0 for free rolling."""
        return self.omega if self.omega is not None else self.speed / nominal_radius

    def to_dict(self) -> dict:
        return {k: getattr(self, k) for k in self.__dataclass_fields__}


def creepage_kernel(sigma, V, Omega, vy, vz, yaw_rate, roll_rate, yaw, roll, dx, dy, dz, gamma,
                    roller_radius=np.inf, rail_z=0.0):
    """Creepages (ξ, η, φ) at contact points from wheelset velocities (pure array kernel).

    Parameters
    ----------
    sigma : array_like
        +1 right wheel, −1 left wheel.
    V : float
        Forward speed [m/s] (roller surface speed on a roller).
    Omega : array_like
        Angular velocity about the axle [rad/s], positive rolling forwards.
    vy, vz : array_like
        Lateral (right) and vertical (up) velocity of the axle centre [m/s].
    yaw_rate, roll_rate : array_like
        [rad/s].
    yaw, roll : array_like
        Pose [rad] (signs of :mod:`wheelrail.geometry.contact_search`).
    dx, dy, dz : array_like
        Position of the contact point relative to the axle centre in the
        track frame [m] (x forward, y right, z up).
    gamma : array_like
        Contact angle [rad] in the side's profile orientation.
    roller_radius : float
        Roller radius [m]; ``inf`` for a track (rail at rest, wheelset advancing at V).
    rail_z : array_like
        Height of the contact point above the top of rail [m] (roller only).

    Returns
    -------
    xi, eta, phi : ndarray
        Creepages [-], [-] and spin [1/m] (Kalker's convention).
    """
    s, g = np.asarray(sigma, dtype=float), np.asarray(gamma, dtype=float)
    # work in the right-handed frame X forward, Y left, Z up (Y = −y_track)
    cps, sps = np.cos(yaw), np.sin(yaw)
    cth, sth = np.cos(roll), np.sin(roll)
    wX = Omega * cth * sps - roll_rate * cps
    wY = Omega * cth * cps + roll_rate * sps
    wZ = -Omega * sth - yaw_rate
    rX, rY, rZ = np.asarray(dx, float), -np.asarray(dy, float), np.asarray(dz, float)
    roller = np.isfinite(roller_radius)
    vcX = 0.0 if roller else V
    vX = vcX + (wY * rZ - wZ * rY)
    vY = -vy + (wZ * rX - wX * rZ)
    vZ = vz + (wX * rY - wY * rX)
    if roller:
        w_r = -V / roller_radius                       # roller spin about +Y (top moves back)
        zr = np.asarray(rail_z, float) + roller_radius   # height of P above the roller axis
        vX = vX - w_r * zr
        vZ = vZ + w_r * np.asarray(dx, float)
        wY = wY - w_r
    # contact axes in (X, Y, Z): e_y = (0, −cos γ, σ sin γ), e_z = (0, −σ sin γ, −cos γ)
    cg, sg = np.cos(g), np.sin(g)
    xi = vX / V
    eta = (-vY * cg + vZ * s * sg) / V
    phi = (-wY * s * sg - wZ * cg) / V
    return xi, eta, phi


def creepages(motion: Motion, *, side, contact_point, axle_centre, yaw=0.0, roll=0.0,
              contact_angle, nominal_radius, rail_z=0.0):
    """Creepages at contact points of one wheel from the wheelset's :class:`Motion`.

    Parameters
    ----------
    motion : Motion
    side : {"left", "right"}
    contact_point : (x, y, z) array_like
        Contact point(s) on the wheel in the track frame [m] (x ahead of the
        axle centre, y right, z up); arrays broadcast.
    axle_centre : (y, z)
        Lateral position and height of the axle centre in the track frame [m].
    yaw, roll : float
        Pose [rad].
    contact_angle : array_like
        γ [rad].
    nominal_radius : float
        r0 [m], for free rolling (``motion.omega is None``).
    rail_z : array_like
        Height of the contact point above the top of rail [m] (roller only).

    Returns
    -------
    xi, eta, phi : ndarray
        [-], [-], [1/m] (Kalker's convention, :mod:`wheelrail.conventions`).

    Examples
    --------
    Pure rolling of a cylinder gives no creepage; a yawed wheelset gets η = −ψ:

    >>> m = Motion(speed=10.0)
    >>> [round(float(v), 12) for v in creepages(m, side="right", contact_point=(0, 0.75, 0),
    ...     axle_centre=(0.0, 0.46), contact_angle=0.0, nominal_radius=0.46)]
    [0.0, 0.0, 0.0]
    """
    if side not in ("left", "right"):
        raise InputError(f"side must be 'left' or 'right', got {side!r}")
    if not isinstance(motion, Motion):
        raise InputError(f"motion must be a Motion, got {type(motion).__name__}")
    x, y, z = (as_float_array("contact_point", v) for v in contact_point)
    yc, zc = (float(as_float_array("axle_centre", v)) for v in axle_centre)
    sigma = 1.0 if side == "right" else -1.0
    R = np.inf if motion.roller_radius is None else motion.roller_radius
    return creepage_kernel(sigma, motion.speed, motion.angular_velocity(nominal_radius),
                           motion.lateral_velocity, motion.vertical_velocity, motion.yaw_rate,
                           motion.roll_rate, float(yaw), float(roll), x, y - yc, z - zc,
                           as_float_array("contact_angle", contact_angle), R, rail_z)
