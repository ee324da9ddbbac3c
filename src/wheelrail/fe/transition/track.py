"""Track structure and vehicle suspension of the transition model (frozen, SI units).

:class:`TrackStructure` — a rail on discrete solid sleepers: railpads as
spring–dampers between the rail foot and the sleeper top, the ballast as vertical
spring–dampers under the sleeper, the sleepers held laterally and longitudinally
(every node by default: they move only vertically; Zhao, Li & Liu 2012).
:class:`WheelSuspension` — the sprung mass (car body and bogie lumped, per wheel) on the
primary suspension, the half-axle's mass and inertia, the driving torque.

Default values
--------------
Explicit FE studies of the two-point contact transition take their track and suspension
parameters from Zhao, Li & Liu (2012), which could not be consulted for this implementation.
The defaults are the values this research group publishes for the same Dutch ballasted
track with 54E1 rail and concrete sleepers in Li, Zhao, Esveld, Dollevoet & Molodova (2008, Table 1) and
Zhao & Li (2011, Table 1), as remembered and **not verified against the papers**:
railpad 1300 MN/m and 45 kN s/m, ballast 45 MN/m and 32 kN s/m per rail seat, sleeper
spacing 0.6 m, primary suspension 1.15 MN/m and 2.5 kN s/m. The sprung mass per wheel
(8 t) is chosen for a wheel load of about 80 kN (a Dutch intercity coach); the sleeper is
a half monoblock sleeper (1.3 × 0.25 × 0.2 m, concrete E = 38.4 GPa, 2480 kg/m³).
Replace them with checked values before drawing conclusions on the track dynamics.

References
----------
.. [1] X. Zhao, Z. Li, J. Liu, "Wheel-rail impact and the dynamic forces at discrete
   supports of rails in the presence of singular rail surface defects", Proc. IMechE
   Part F 226 (2012) 124-139.
.. [2] Z. Li, X. Zhao, C. Esveld, R. Dollevoet, M. Molodova, "An investigation into the
   causes of squats — correlation analysis and numerical modeling", Wear 265 (2008)
   1349-1355.
.. [3] X. Zhao, Z. Li, "The solution of frictional wheel-rail rolling contact with a 3D
   transient finite element model: validation and error analysis", Wear 271 (2011)
   444-452.
.. [4] F. Huo, H. Dai, "Formulation of a linearized model for vehicle-track
   interactions", Shock and Vibration 2019, 2015465.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..._validation import non_negative, positive
from ...errors import InputError

__all__ = ["TrackStructure", "WheelSuspension", "SpringSet"]

GRAVITY = 9.81


def _check(obj, positive_names, non_negative_names):
    for name in positive_names:
        object.__setattr__(obj, name, float(positive(name, getattr(obj, name))))
    for name in non_negative_names:
        object.__setattr__(obj, name, float(non_negative(name, getattr(obj, name))))


@dataclass(frozen=True)
class TrackStructure:
    """A rail on discrete solid sleepers, railpads and ballast (one rail, SI units).

    Parameters
    ----------
    sleeper_spacing : float
        Distance between sleeper centres [m].
    n_sleepers : int
        Sleepers in the model (>= 2); the rail spans them plus ``overhang`` at each end.
    overhang : float
        Rail beyond the outer sleepers' centres [m].
    pad_stiffness, pad_damping : float
        Railpad vertical stiffness [N/m] and damping [N s/m] per rail seat.
    pad_shear_stiffness, pad_shear_damping : float
        Railpad longitudinal stiffness [N/m] and damping [N s/m] per rail seat (the
        fastening's hold of the rail foot), and its lateral ones unless
        ``pad_lateral_stiffness`` / ``pad_lateral_damping`` are given.
    pad_lateral_stiffness, pad_lateral_damping : float or None
        Railpad lateral stiffness [N/m] and damping [N s/m] per rail seat; ``None``
        (default): the ``pad_shear_*`` values. A vehicle–slab-track model gives a
        fastening 15 MN/m and 50 kN s/m laterally (Huo & Dai 2019, Table 2), far less
        than the default shear stiffness.
    ballast_stiffness, ballast_damping : float
        Vertical ballast stiffness [N/m] and damping [N s/m] under one (half) sleeper.
    pad_length : float
        Length of the rail seat along the rail [m].
    sleeper_size : tuple of float
        (length along the track [m], width across the track (half sleeper) [m], height [m]).
    sleeper_E, sleeper_nu, sleeper_density : float
        Concrete sleeper material [Pa], [-], [kg/m³].
    sleeper_elements : tuple of int
        Elements of a sleeper along (x, y, z): 12 solid elements by default.
    sleeper_hold : {"body", "bottom"}
        How the sleepers are held laterally and longitudinally. ``"body"`` (default): every
        sleeper node is held in x and y, the sleepers move only vertically on the ballast
        (vertical spring–dampers whose displacements are constrained laterally and
        longitudinally, as in the explicit FE transition study). ``"bottom"``: only the
        bottom face's nodes are held; the sleepers can then pitch and roll on the vertical
        ballast springs, and a model with few sleepers and a short rail lets the rail run
        backwards under a driving force (≈ 0.12 m/s at 14 kN on two sleepers: half a
        percent of creepage at 80 km/h) — the model before 2026-11.
    """

    sleeper_spacing: float = 0.6
    n_sleepers: int = 3
    overhang: float = 0.3
    pad_stiffness: float = 1.3e9
    pad_damping: float = 4.5e4
    pad_shear_stiffness: float = 2.8e8
    pad_shear_damping: float = 4.5e4
    pad_lateral_stiffness: float | None = None
    pad_lateral_damping: float | None = None
    ballast_stiffness: float = 4.5e7
    ballast_damping: float = 3.2e4
    pad_length: float = 0.18
    sleeper_size: tuple = (0.25, 1.3, 0.2)
    sleeper_E: float = 3.84e10
    sleeper_nu: float = 0.2
    sleeper_density: float = 2480.0
    sleeper_elements: tuple = (2, 3, 2)
    sleeper_hold: str = "body"

    def __post_init__(self):
        _check(self, ("sleeper_spacing", "pad_stiffness", "ballast_stiffness", "pad_length",
                      "sleeper_E", "sleeper_density", "pad_shear_stiffness"),
               ("pad_damping", "ballast_damping", "overhang", "pad_shear_damping"))
        # None stays None (follows pad_shear_*, also through dataclasses.replace)
        _check(self, ("pad_lateral_stiffness",) if self.pad_lateral_stiffness is not None
               else (), ("pad_lateral_damping",) if self.pad_lateral_damping is not None
               else ())
        n = self.n_sleepers
        if isinstance(n, bool) or not isinstance(n, (int, float, np.integer, np.floating)) \
                or not np.isfinite(n) or int(n) != n or n < 2:
            raise InputError(f"n_sleepers must be an integer >= 2, got {self.n_sleepers!r}")
        object.__setattr__(self, "n_sleepers", int(self.n_sleepers))
        if not 0.0 <= self.sleeper_nu < 0.5:
            raise InputError(f"sleeper_nu must be in [0, 0.5), got {self.sleeper_nu!r}")
        size = tuple(float(v) for v in self.sleeper_size)
        if len(size) != 3 or min(size) <= 0:
            raise InputError(f"sleeper_size must be three positive lengths [m], got "
                             f"{self.sleeper_size!r}")
        object.__setattr__(self, "sleeper_size", size)
        el = tuple(int(v) for v in self.sleeper_elements)
        if len(el) != 3 or min(el) < 1:
            raise InputError(f"sleeper_elements must be three integers >= 1, got "
                             f"{self.sleeper_elements!r}")
        object.__setattr__(self, "sleeper_elements", el)
        if self.sleeper_hold not in ("body", "bottom"):
            raise InputError(f"sleeper_hold must be 'body' or 'bottom', got "
                             f"{self.sleeper_hold!r}")
        if self.pad_length > self.sleeper_size[0] * 1.5 or self.pad_length >= self.sleeper_spacing:
            raise InputError(f"pad_length {self.pad_length!r} m does not fit the sleeper "
                             f"({self.sleeper_size[0]} m) and spacing ({self.sleeper_spacing} m)")

    def pad_springs(self) -> tuple:
        """One rail seat's railpad as ((k, c) longitudinal, lateral, vertical) [N/m],
        [N s/m]: the lateral values fall back to the shear ones when not given."""
        k_lat = (self.pad_shear_stiffness if self.pad_lateral_stiffness is None
                 else self.pad_lateral_stiffness)
        c_lat = (self.pad_shear_damping if self.pad_lateral_damping is None
                 else self.pad_lateral_damping)
        return ((self.pad_shear_stiffness, self.pad_shear_damping), (k_lat, c_lat),
                (self.pad_stiffness, self.pad_damping))

    @property
    def length(self) -> float:
        """Rail length of the model [m]."""
        return (self.n_sleepers - 1) * self.sleeper_spacing + 2 * self.overhang

    def sleeper_positions(self, x0: float = 0.0) -> np.ndarray:
        """Sleeper centres along x [m], the first at ``x0``."""
        return x0 + self.sleeper_spacing * np.arange(self.n_sleepers)


@dataclass(frozen=True)
class WheelSuspension:
    """Sprung mass on the primary suspension, the half-axle and the drive (one wheel).

    Parameters
    ----------
    sprung_mass : float
        Car body and bogie lumped, per wheel [kg].
    stiffness, damping : float
        Primary suspension per wheel [N/m], [N s/m].
    axle_mass : float
        Half-axle (and axle box) mass not in the FE wheel [kg].
    axle_inertia : float
        Polar moment of inertia of the half-axle about its axis [kg m²] (the FE wheel's
        own inertia is added).
    torque : float
        Driving torque on the axle [N m] (positive drives the wheel forward).
    lateral_stiffness, lateral_damping : float
        The wheel's lateral restraint [N/m], [N s/m] against the path along its heading
        (the direction of the axle, in the horizontal plane). ``inf`` (default): the lateral
        motion is prescribed, the wheel follows its heading whatever the contact forces.
        Finite: a lateral degree of freedom of the half-axle and wheel mass driven by the
        contact forces' lateral part, on a spring–damper to the heading path (0: free
        lateral motion, only the inertia resists).
    roll_stiffness, roll_damping : float
        The wheel's roll restraint [N m/rad], [N m s/rad]: its rotation φ about its heading
        axis through the wheel centre. ``inf`` (default): no roll. Finite: a roll degree
        of freedom driven by the contact forces' moment about that axis, on a torsion
        spring–damper about the static balance: the spring's preload is the contact
        moment at the end of the case's static preload (``TransitionCase.preload`` > 0 is
        required). A half-wheelset whose axle is held laterally at its symmetry plane
        rolls by bending its half-axle: :meth:`half_axle_roll_stiffness`. A critical dashpot on
        roll fades over the case's ``settle`` distance like the axle's vertical one.
    axle_roll_inertia : float
        The half-axle's share of the roll inertia [kg m²], added to the FE wheel's own
        Σ m (y² + z²) about its centre. Default 8: a 300 kg, 0.75 m half-axle bent by a
        moment at the wheel with zero slope at the symmetry plane (deflection φ s²/(2L)
        at distance s from that plane) has the kinetic energy of m L²/20 ≈ 8.4 kg m².
    """

    sprung_mass: float = 8000.0
    stiffness: float = 1.15e6
    damping: float = 2.5e3
    axle_mass: float = 300.0
    axle_inertia: float = 5.0
    torque: float = 0.0
    lateral_stiffness: float = np.inf
    lateral_damping: float = 0.0
    roll_stiffness: float = np.inf
    roll_damping: float = 0.0
    axle_roll_inertia: float = 8.0

    def __post_init__(self):
        _check(self, ("sprung_mass", "stiffness", "axle_mass"),
               ("damping", "axle_inertia", "lateral_damping", "roll_damping",
                "axle_roll_inertia"))
        for name, what in (("lateral_stiffness", "prescribed lateral motion"),
                           ("roll_stiffness", "no roll")):
            k = float(getattr(self, name))
            if np.isnan(k) or k < 0.0:
                raise InputError(f"{name} must be >= 0 (inf: {what}), got "
                                 f"{getattr(self, name)!r}")
            object.__setattr__(self, name, k)
        object.__setattr__(self, "torque", float(self.torque))
        if not np.isfinite(self.torque):
            raise InputError(f"torque must be finite, got {self.torque!r}")

    @staticmethod
    def half_axle_roll_stiffness(diameter: float = 0.18, length: float = 0.75,
                                 youngs_modulus: float = 2.1e11) -> float:
        """Roll stiffness of a wheel on a half-axle bent by a moment at the wheel, with zero
        slope at the axle's symmetry plane: k = E I / L, I = π d⁴ / 64 [N m/rad].

        Parameters
        ----------
        diameter : float
            Axle body diameter [m] (solid).
        length : float
            Distance from the symmetry plane to the wheel [m].
        youngs_modulus : float
            [Pa].

        References
        ----------
        .. [1] S. P. Timoshenko, J. M. Gere, Mechanics of Materials, 1972 (a beam in pure
           bending: end rotation M L / (E I)).
        """
        for name, v in (("diameter", diameter), ("length", length),
                        ("youngs_modulus", youngs_modulus)):
            if not (np.isfinite(v) and v > 0.0):
                raise InputError(f"{name} must be a positive finite number, got {v!r}")
        return youngs_modulus * np.pi * diameter ** 4 / 64.0 / length

    def wheel_load(self, wheel_mass: float) -> float:
        """Static vertical wheel load (sprung + axle + wheel mass) × g [N]."""
        return (self.sprung_mass + self.axle_mass + float(wheel_mass)) * GRAVITY


class SpringSet:
    """Linear spring–dampers between weighted node groups, per direction.

    Spring ``m`` has a relative displacement δ_m = Σ_a B[m, a] u_a (one component ``d``);
    its force −(k δ + c δ̇) acts on each node a with weight B[m, a]. Built as a sparse
    matrix; grounded springs have a single node.
    """

    def __init__(self, n_nodes: int):
        self.n = int(n_nodes)
        self.rows, self.cols, self.vals, self.dirs, self.k, self.c = [], [], [], [], [], []

    def add(self, nodes, weights, direction: int, k: float, c: float):
        m = len(self.k)
        for a, w in zip(np.atleast_1d(nodes), np.atleast_1d(weights)):
            self.rows.append(m)
            self.cols.append(int(a))
            self.vals.append(float(w))
        self.dirs.append(int(direction))
        self.k.append(float(k))
        self.c.append(float(c))

    def finish(self):
        import scipy.sparse as sp

        nm = len(self.k)
        self.B = sp.csr_matrix((self.vals, (self.rows, self.cols)), shape=(nm, self.n))
        self.BT = self.B.T.tocsr()
        self.kv = np.array(self.k)
        self.cv = np.array(self.c)
        self.d = np.array(self.dirs, np.int64)
        self.masks = [self.d == d for d in range(3)]
        return self

    def forces(self, u, v, f):
        """Add the spring–damper forces on the nodes to ``f`` (n, 3); returns their energy."""
        e = 0.0
        for d in range(3):
            msk = self.masks[d]
            if not np.any(msk):
                continue
            B = self.B[msk]
            dl = B @ u[:, d]
            dv = B @ v[:, d]
            fm = self.kv[msk] * dl + self.cv[msk] * dv
            f[:, d] -= B.T @ fm
            e += 0.5 * float(np.sum(self.kv[msk] * dl * dl))
        return e

    def stiffness(self):
        """The springs' stiffness as a sparse (3n, 3n) matrix (dof 3 a + d)."""
        import scipy.sparse as sp

        mats = []
        for d in range(3):
            msk = self.masks[d]
            if not np.any(msk):
                continue
            B = self.B[msk].tocoo()
            P = sp.csr_matrix((B.data, (B.row, 3 * B.col + d)), shape=(B.shape[0], 3 * self.n))
            mats.append(P.T @ sp.diags(self.kv[msk]) @ P)
        return sum(mats)

    def stable_step(self, mass) -> float:
        """A bound on the stable step of the springs: 2/ω, ω² = k Σ w² / m_min of a spring."""
        dt = np.inf
        Bc = self.B.tocsr()
        for m in range(Bc.shape[0]):
            a = Bc.indices[Bc.indptr[m]:Bc.indptr[m + 1]]
            w = Bc.data[Bc.indptr[m]:Bc.indptr[m + 1]]
            mm = np.min(mass[a] / np.maximum(w * w * len(a), 1e-300))
            if self.kv[m] > 0 and mm > 0:
                dt = min(dt, 2.0 / np.sqrt(self.kv[m] / mm))
        return float(dt)
