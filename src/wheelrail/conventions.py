"""Axes, units and sign conventions used everywhere in wheelrail.

This module is the single place where the conventions are written down; every
kernel docstring refers to it.

Units
-----
SI throughout the API: lengths in m, forces in N, moments in N·m, stresses and
moduli in Pa, angles in rad, time in s, speeds in m/s. Creepages ξ, η are
dimensionless; the spin creepage φ is in 1/m (rad/m). Profile files written in
mm are converted to m when they are read.

Contact-plane axes (Kalker)
---------------------------
* ``x`` — rolling direction (the direction in which the contact moves over the
  rail), ``a`` is the semi-axis of the contact patch along ``x``;
* ``y`` — lateral, in the tangent plane, ``b`` the semi-axis along ``y``;
* ``z`` — normal to the contact plane, pointing into the lower body (the rail),
  so that the normal force on the wheel is positive in compression.

(x, y, z) is right-handed: with z pointing down into the rail, y points to the
**right** when looking in the rolling direction. The rigid slip of the wheel
relative to the rail at (x, y) is then V·(ξ − φ y, η + φ x).

Track frame (:mod:`wheelrail.geometry`): x along the track, y lateral to the
right (the same y as the contact frame), z **up**; this triad is left-handed,
which matters only when kinematics (creepages from wheelset motion) are
derived from it. Profile frames are described in :mod:`wheelrail.profiles.core`.
The user documentation of all conventions is ``docs/conventions.md``.

Wheelset motion (:mod:`wheelrail.geometry.kinematics`)
------------------------------------------------------
``Motion.omega`` is the angular velocity about the axle, positive when the
wheelset rolls forwards. The contact frame of a wheel–rail patch has its y
axis to the right on both wheels, so a conical tread of contact angle γ has
spin −sin γ / r on the right wheel and +sin γ / r on the left one. Track-frame
forces on a wheel (σ = +1 right, −1 left): F_y = Σ(Fs cos γ − σ Fn sin γ),
F_z = Σ(σ Fs sin γ + Fn cos γ).

Bodies and sign of forces
-------------------------
Body 1 is the wheel (upper body), body 2 the rail (lower body). Tangential
forces ``Fx``, ``Fy`` and the spin moment ``Mz`` are those **acting on the
wheel**.

Creepages
---------
Creepages are the rigid slip velocity of the wheel relative to the rail in
the contact point, divided by the rolling speed ``V``:

* ξ (``xi``)  = (v_wheel,x − v_rail,x) / V, longitudinal;
* η (``eta``) = (v_wheel,y − v_rail,y) / V, lateral;
* φ (``phi``) = (ω_wheel,z − ω_rail,z) / V, spin, in 1/m.

With these signs a positive creepage produces a negative force. In the
linear (small-creepage) limit, with c = √(ab) and G the combined shear
modulus,

    Fx = −G c² C11 ξ
    Fy = −G c² (C22 η + c C23 φ)
    Mz =  G c³ (C23 η − c C33 φ)

where C11 … C33 are Kalker's creep coefficients (Kalker 1967, 1990).

Names
-----
One name per physical quantity across the public API (arguments, attributes,
case-file keys, dataset variables); :data:`NAMES` lists them and
:data:`RETIRED_NAMES` the synonyms that are not used (a test walks the public
signatures):

* ``Fn`` — normal contact force [N] (``wr.hertz(Fn=...)``, ``HertzContact.Fn``,
  ``PatchResult.Fn``, ``[contact] Fn``, ``transient_rolling(Fn=...)``);
* ``Fx``, ``Fy``, ``Mz`` — tangential forces [N] and spin moment [N·m] on the
  wheel (a prescribed longitudinal force is ``Fx`` too);
* ``penetration`` — approach of the two bodies along the contact normal, δ [m];
* ``vertical_load`` — vertical force carried by one wheel of a wheelset (Q of
  the literature) [N]; ``axle_load`` — the whole wheelset's [N];
* ``vertical_approach`` — vertical displacement of a wheel below its touching
  pose, dz [m];
* ``mu`` — Coulomb friction coefficient [-] (never a modulus: the shear
  modulus is ``G``);
* ``xi``, ``eta``, ``phi`` — creepages [-], [-], [1/m].

References
----------
.. [1] J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
   Kluwer, 1990, ch. 1 and 2.
.. [2] J.J. Kalker, Wheel–rail rolling contact theory, Wear 144 (1991) 243–261,
   eqs. (7)–(9) (linear theory in these signs).
"""

#: Order of the components of a creepage vector.
CREEPAGE_COMPONENTS = ("xi", "eta", "phi")
#: Units of the creepage components.
CREEPAGE_UNITS = {"xi": "1", "eta": "1", "phi": "1/m"}
#: Units of the result quantities.
FORCE_UNITS = {"Fx": "N", "Fy": "N", "Mz": "N m", "Fn": "N"}

#: Forces are reported as acting on this body.
FORCE_ON = "wheel"
#: Creepage is the velocity of this body relative to the other, divided by V.
CREEPAGE_OF = "wheel relative to rail"
#: Sign of the linear creep force relative to creepage (Fx = SIGN * G c^2 C11 xi).
LINEAR_FORCE_SIGN = -1.0

#: name -> (unit, meaning): one name per physical quantity in the public API.
NAMES = {
    "Fn": ("N", "normal contact force"),
    "Fx": ("N", "longitudinal tangential force on the wheel"),
    "Fy": ("N", "lateral tangential force on the wheel"),
    "Mz": ("N m", "spin moment on the wheel"),
    "penetration": ("m", "approach of the bodies along the contact normal"),
    "vertical_load": ("N", "vertical force carried by one wheel"),
    "axle_load": ("N", "vertical force carried by a wheelset"),
    "vertical_approach": ("m", "vertical displacement of a wheel below its touching pose"),
    "mu": ("1", "Coulomb friction coefficient"),
    "G": ("Pa", "(combined) shear modulus"),
    "xi": ("1", "longitudinal creepage"),
    "eta": ("1", "lateral creepage"),
    "phi": ("1/m", "spin creepage"),
}
#: Synonyms that the public API does not use (name used instead).
RETIRED_NAMES = {"load": "Fn", "normal_force": "Fn", "Q": "vertical_load", "delta": "penetration",
                 "approach": "penetration", "dz": "vertical_approach",
                 "tangential_force": "Fx"}

__all__ = [
    "NAMES",
    "RETIRED_NAMES",
    "CREEPAGE_COMPONENTS",
    "CREEPAGE_UNITS",
    "FORCE_UNITS",
    "FORCE_ON",
    "CREEPAGE_OF",
    "LINEAR_FORCE_SIGN",
]
