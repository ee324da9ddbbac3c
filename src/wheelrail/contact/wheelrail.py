"""The wheel–rail contact module: patches and forces of a wheelset on a track.

Given a wheelset pose (lateral shift, yaw, roll), the vertical force on each
wheel (or the height of the axle), the wheelset's velocities and the track,
:func:`solve_wheelrail`

1. finds the pose at which each wheel touches its rail (roll from the rigid
   contact constraint of both wheels, Bosso et al. (2013), ch. 2 eqs. 2.1–2.3, or prescribed)
   and every candidate contact point of each wheel
   (:func:`wheelrail.geometry.contact_points`: all local minima of the
   distance, so that two-point contact is seen);
2. solves the normal problem of each wheel with the chosen normal method
   (:mod:`wheelrail.normal`): the wheel is pressed onto its rail until its
   patches carry the vertical load (Σ Fn cos γ = Q; the creep forces' vertical
   components are not part of this balance, they are reported in the
   track-frame forces);
3. computes the creepages at each patch from the motion
   (:mod:`wheelrail.geometry.kinematics`) and solves the tangential problem
   with the chosen tangential method.

The two wheels are independent once the pose is fixed (the vertical load
per wheel is prescribed, as in CONTACT's wheel–rail module and the
Manchester benchmark).

Track-frame forces on a wheel (x forward, y right, z up) from the patch
forces in the contact frame (Fx along the track, Fs lateral in the contact
plane to the right, Fn along the normal, σ = +1 right / −1 left)::

    F_x = Σ Fx,   F_y = Σ (Fs cos γ − σ Fn sin γ),   F_z = Σ (σ Fs sin γ + Fn cos γ)

References
----------
.. [1] Review of wheel–rail contact models (Bosso et al. (2013), ch. 2), §2.1–2.2, eqs. (2.1)–(2.4), (2.10).
.. [2] J. Piotrowski, H. Chollet, Wheel–rail contact models for vehicle system
   dynamics including multi-point contact, VSD 43 (2005), §1–2.
.. [3] E.A.H. Vollebregt, *User guide for CONTACT*, Vtech CMCC: the wheel–rail
   module (vertical force per wheel, planar contact per patch).
.. [4] P. Shackleton, S. Iwnicki, Comparison of wheel–rail contact codes for
   railway vehicle simulation: an introduction to the Manchester Contact
   Benchmark and initial results, VSD 46 (2008) 91–104.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from .. import normal as normal_family
from .. import tangential as tangential_family
from .._validation import as_float_array, positive
from ..errors import ConvergenceError, InputError
from ..geometry import Track, Wheelset
from ..geometry.contact_search import _Pose, find_points, solve_rigid
from ..geometry.points import _side_from_row
from ..geometry.elastic import _regularised_B
from ..geometry.kinematics import Motion, creepage_kernel
from ..geometry.separation import separation_at
from ..geometry.touching import touching_heights
from ..materials import STEEL, as_material_pair
from ..patch import ContactFrame
from ..plausibility import check_friction, check_load, disabled
from ..results import ContactResult, PatchResult, to_jsonable

__all__ = ["WheelRailPosition", "WheelProblem", "WheelRailResult", "solve_wheelrail", "SIDES"]

SIDES = ("left", "right")
_SIGMA = {"left": -1.0, "right": 1.0}
_MAX_VERTICAL = 12      # passes of the normal/tangential loop for the total vertical load
_VERTICAL_TOL = 1e-5     # relative tolerance on the total vertical force


@dataclass(frozen=True, eq=False)
class WheelRailPosition:
    """A wheelset on a track at a given position (frozen, SI).

    Parameters
    ----------
    wheelset : Wheelset
    track : Track
    y : float
        Lateral shift of the wheelset [m], positive to the right.
    yaw : float
        Yaw angle [rad] (positive: the right wheel moves backwards).
    roll : float or None
        Roll angle [rad] (positive: right wheel higher); ``None``: from the
        rigid contact constraint of both wheels.
    vertical_load : float or (float, float) or None
        Vertical force on **each** wheel [N] (one value for both, or
        (left, right)).
    z : float or None
        Instead of ``vertical_load``: height of the axle centre [m], as in
        :func:`wheelrail.contact_points` (0 when a wheel of radius r0 stands
        on top of rail; each wheel's approach is its touching height minus z).
    material : Material or MaterialPair
        Wheel and rail materials (default steel).
    tolerance : float
        Largest undeformed separation [m] of a candidate contact point
        (default 0.5 mm; points farther away never touch under usual loads).
    """

    wheelset: object
    track: object
    y: float
    yaw: float = 0.0
    roll: float | None = None
    vertical_load: object = None
    z: float | None = None
    material: object = STEEL
    tolerance: float = 5e-4

    def __post_init__(self):
        if not isinstance(self.wheelset, Wheelset):
            raise InputError(f"wheelset must be a Wheelset, got {type(self.wheelset).__name__}")
        if not isinstance(self.track, Track):
            raise InputError(f"track must be a Track, got {type(self.track).__name__}")
        object.__setattr__(self, "y", float(as_float_array("y", self.y)))
        object.__setattr__(self, "yaw", float(as_float_array("yaw", self.yaw)))
        if abs(self.yaw) > 0.2:
            raise InputError(f"|yaw| must be <= 0.2 rad, got {self.yaw!r}")
        if self.roll is not None:
            object.__setattr__(self, "roll", float(as_float_array("roll", self.roll)))
            if abs(self.roll) > 0.2:
                raise InputError(f"|roll| must be <= 0.2 rad, got {self.roll!r}")
        if (self.vertical_load is None) == (self.z is None):
            raise InputError("give exactly one of vertical_load= (N per wheel) and z= (m), got "
                             f"vertical_load={self.vertical_load!r}, z={self.z!r}")
        if self.vertical_load is not None:
            q = np.broadcast_to(as_float_array("vertical_load", self.vertical_load), (2,))
            for side, v in zip(SIDES, q):
                if not v > 0:
                    raise InputError(f"vertical_load on the {side} wheel must be > 0 N, got "
                                     f"{float(v)!r}")
                check_load(float(v), f"vertical_load ({side} wheel)")
            object.__setattr__(self, "vertical_load", (float(q[0]), float(q[1])))
        else:
            object.__setattr__(self, "z", float(as_float_array("z", self.z)))
        object.__setattr__(self, "material", as_material_pair(self.material))
        object.__setattr__(self, "tolerance", float(positive("tolerance", self.tolerance)))

    def load(self, side: str) -> float | None:
        """Vertical load of ``side`` [N] (None with a prescribed height)."""
        return None if self.vertical_load is None else self.vertical_load[SIDES.index(side)]


@dataclass(frozen=True, eq=False)
class WheelProblem:
    """The normal problem of one wheel at a fixed pose (what a normal method's
    ``from_wheel`` reads; see :class:`wheelrail.normal.NormalMethod`).

    Attributes
    ----------
    side : str
    points : SideContacts
        Candidate contact points at the pose where this wheel just touches
        (separation ≥ 0, the smallest 0).
    A, B : ndarray, shape (n,)
        Hertz curvatures at the points [1/m] (B regularised over the patch
        scale where the point value is ≤ 0; A includes a roller's curvature).
    frames : tuple of ContactFrame
    materials : MaterialPair
    vertical_load : float or None
        Q [N] ...
    vertical_approach : float or None
        ... or the vertical approach dz [m] below the touching pose.
    roller_radius : float or None
    pose : dict
        ``y, z, roll, yaw`` of the touching pose (z of this wheel).
    wheelset, track
    """

    side: str
    points: object
    A: np.ndarray
    B: np.ndarray
    frames: tuple
    materials: object
    vertical_load: float | None
    vertical_approach: float | None
    roller_radius: float | None
    pose: dict
    wheelset: object = None
    track: object = None
    cache: dict = field(default_factory=dict, repr=False)

    def separation(self, k, width: float = 0.04, n: int = 801):
        """Profile separation around candidate point ``k`` (or a :class:`ContactFrame`) in its
        contact plane (:func:`wheelrail.geometry.separation.separation_at`); cached."""

        f = self.frames[k] if not isinstance(k, ContactFrame) else k
        key = ("separation", f, width, n)
        if key not in self.cache:
            self.cache[key] = separation_at(
                self.wheelset, self.track, self.side, y=self.pose["y"], z=self.pose["z"],
                roll=self.pose["roll"], yaw=self.pose["yaw"], wheel_y=f.wheel_y,
                track_y=f.track_y, contact_angle=f.contact_angle, width=width, n=n,
                point=k if not isinstance(k, ContactFrame) else -1)
        return self.cache[key]

    def groups(self, group_angle: float, width: float) -> list:
        """Candidate points grouped by contact plane (indices, each group's reference first).

        Points join the group of an earlier (smaller-separation) point when their
        contact angles differ by less than ``group_angle`` [rad] and they lie within
        0.4 ``width`` [m] of it laterally: such points share one contact plane
        (one BEM grid, one strip line), where they interact.
        """
        pts = self.points
        groups: list[list[int]] = []
        for k in np.argsort(pts.separation, kind="stable"):
            for g in groups:
                r = g[0]
                if (abs(pts.contact_angle[k] - pts.contact_angle[r]) < group_angle
                        and abs(pts.track_y[k] - pts.track_y[r]) < 0.4 * width):
                    g.append(int(k))
                    break
            else:
                groups.append([int(k)])
        return groups

    def frame_at(self, k, eta: float, weights=None, eta_samples=None,
                 angle=None, separation=None) -> ContactFrame:
        """Contact frame at lateral position ``eta`` [m] of the contact plane of point ``k``
        (an index of :attr:`frames`, or a :class:`ContactFrame`).

        ``eta`` runs along the plane's tangent towards the field side (as
        :class:`~wheelrail.geometry.separation.Separation`). The contact angle
        is the rail's surface angle there, or, with ``weights`` over
        ``eta_samples``, the weighted mean surface angle (CONTACT's planar
        contact reference, Vollebregt 2022), or ``angle`` if given.
        ``separation``: this plane's separation if the caller has it (any
        resolution; only its rolling radius is read), else :meth:`separation`.
        """
        f = self.frames[k] if not isinstance(k, ContactFrame) else k
        sig = _SIGMA[self.side]
        rc = self.track.curve(self.side)
        u_r = sig * f.track_y
        g = f.contact_angle
        if angle is not None and weights is None and np.ndim(eta) == 0:
            # one point, angle given (the strip methods): scalar arithmetic, same numbers
            e = float(eta)
            u_c = u_r + e * math.cos(g)
            z_c = _curve_value(rc, u_c)
            pl = self.track.placement(self.side)
            ca, sa = math.cos(-pl.angle), math.sin(-pl.angle)
            yr, zr = u_c - pl.offset, z_c + pl.z_top
            sep = self.separation(k) if separation is None else separation
            r = float(np.interp(e, sep.eta, sep.wheel_radius))
            return ContactFrame(self.side, f.wheel_y + float(u_c - u_r), float(ca * yr - sa * zr),
                                float(sig * u_c), float(z_c), f.x, float(angle), r)

        def rail_at(e):
            u = u_r + np.asarray(e, dtype=float) * np.cos(g)
            z, z1 = rc.eval(u, 1)
            return u, z, np.arctan(z1)

        u_c, z_c, ang = rail_at(eta)
        if weights is not None:
            _, _, angs = rail_at(eta_samples)
            ang = float(np.sum(weights * angs) / np.sum(weights))
        if angle is not None:
            ang = float(angle)
        pl = self.track.placement(self.side)
        rail_y, _ = pl.to_profile_frame(u_c, z_c)
        sep = self.separation(k) if separation is None else separation
        r = float(np.interp(eta, sep.eta, sep.wheel_radius))
        return ContactFrame(self.side, f.wheel_y + float(u_c - u_r), float(rail_y),
                            float(sig * u_c), float(z_c), f.x, float(ang), r)


@dataclass(frozen=True, repr=False)
class WheelRailResult(ContactResult):
    """Result of :func:`wheelrail.solve` for a :class:`WheelRailPosition` (frozen, SI).

    Attributes
    ----------
    patches : tuple of PatchResult
        Both wheels, left first, each from field side to flange. Each has
        ``side``, ``y_rail``, ``y_wheel``, ``contact_angle``, ``xi``, ``eta``,
        ``phi``, ``Fn``, ``Fx``, ``Fs``, ``Mz``, ``p_max``, ``area``,
        ``adhesion_area`` and its ``patch`` and ``forces``.
    force_track : dict
        ``{"left": (Fx, Fy, Fz), "right": (...)}``: forces on each wheel in the
        track frame [N] (x forward, y right, z up).
    pose : dict
        ``y, yaw, roll`` and per side ``z`` (touching height) and ``vertical_approach`` [m].
    position : WheelRailPosition
    motion : Motion
    """

    force_track: dict = field(default_factory=dict)
    pose: dict = field(default_factory=dict)
    position: object = None
    motion: object = None

    def side(self, side: str) -> tuple:
        """Patches of one wheel."""
        return tuple(p for p in self.patches if p.side == side)

    def to_dict(self) -> dict:
        out = super().to_dict()
        out["force_track"] = {s: dict(zip(("Fx", "Fy", "Fz"), v)) for s, v in
                              self.force_track.items()}
        out["pose"] = self.pose
        return to_jsonable(out)


# --------------------------------------------------------------------------- geometry
def _curve_value(curve, x: float) -> float:
    """``curve.eval(x, 0)[0]`` of a :class:`~wheelrail.geometry._curves.PiecewiseCubic` for one
    float ``x`` in Python arithmetic (the same operations, without array overhead)."""
    u = curve.u
    if curve._h:
        i = int((x - u[0]) * (1.0 / curve._h))
    else:
        i = int(np.searchsorted(u, x)) - 1
    i = min(max(i, 0), u.size - 2)
    dx = x - float(u[i])
    c = curve.c
    return ((float(c[0, i]) * dx + float(c[1, i])) * dx + float(c[2, i])) * dx + float(c[3, i])


def touching_poses(position):
    """Pose (z of each wheel, roll) at which each wheel just touches its rail.

    Returns ``roll`` and ``{side: z}``.
    """

    ws, tr = position.wheelset, position.track
    y = np.array([position.y])
    yaw = np.array([position.yaw])
    if position.roll is None:
        z, th, _ = solve_rigid(ws, tr, y, yaw)
        return float(th[0]), {s: float(z[0]) for s in SIDES}
    z, beside = touching_heights(ws, tr, y, np.array([position.roll]), yaw)
    for side in SIDES:
        if beside[side][0]:
            raise InputError(f"y = {position.y!r} m: the {side} wheel lies entirely beside its "
                             "rail (lateral shift too large for these profiles)")
    return float(position.roll), {s: float(z[s][0]) for s in SIDES}


def wheel_problem(position, side, roll, z, roller_radius=None) -> WheelProblem:
    """Candidate points, curvatures and frames of one wheel at its touching pose."""

    ws, tr = position.wheelset, position.track
    pose = _Pose(np.array([position.y]), np.array([z]), np.array([roll]),
                 np.array([position.yaw]))
    data, count = find_points(ws, tr, side, pose, tolerance=position.tolerance)
    pts = _side_from_row(data, count, 0)
    zc = ws.nominal_radius + z
    B = _regularised_B(ws, tr, side, pts, pose, zc)
    A = np.array(pts.A, dtype=float)
    if roller_radius is not None:
        A = A + 0.5 / roller_radius
    frames = tuple(ContactFrame(side, float(pts.wheel_y[k]), float(pts.rail_y[k]),
                                float(pts.track_y[k]), float(pts.track_z[k]), float(pts.x[k]),
                                float(pts.contact_angle[k]), float(pts.rolling_radius[k]))
                   for k in range(pts.n))
    approach = None if position.z is None else z - position.z
    if approach is not None and approach <= 0:
        raise InputError(f"z = {position.z!r} m leaves the {side} wheel out of contact (it "
                         f"touches at z = {z!r} m)")
    return WheelProblem(side, pts, A, B, frames, position.material, position.load(side),
                        approach, roller_radius,
                        {"y": position.y, "z": z, "roll": roll, "yaw": position.yaw},
                        ws, tr)


# --------------------------------------------------------------------------- solve
def axle_offset_x(x, wheel_y, sigma, e_tape, roll, yaw):
    """Longitudinal position of a contact point relative to the axle centre [m].

    ``x`` is the offset ahead of the point's wheel circle centre
    (:data:`wheelrail.geometry.contact_search.POINT_FIELDS`); under yaw the
    circle centre itself lies −a cos θ sin ψ ahead of the axle centre, with
    a = σ (e_tape + wheel_y) its position along the axle.
    """
    return x - sigma * (e_tape + wheel_y) * np.cos(roll) * np.sin(yaw)


def _creepage_at(frame, sig, motion, Omega, position, roll, zc, R):
    dx = axle_offset_x(frame.x, frame.wheel_y, sig, position.wheelset.e_tape, roll, position.yaw)
    return tuple(float(v) for v in creepage_kernel(
        sig, motion.speed, Omega, motion.lateral_velocity, motion.vertical_velocity,
        motion.yaw_rate, motion.roll_rate, position.yaw, roll, dx,
        frame.track_y - position.y, frame.track_z - zc, frame.contact_angle,
        np.inf if R is None else R, frame.track_z))


def solve_wheelrail(position, motion, mu, normal="hertz", tangential="fastsim",
                    vertical="total") -> WheelRailResult:
    """Contact patches and forces of a wheelset on a track (see the module docstring).

    Parameters
    ----------
    position : WheelRailPosition
    motion : Motion
        Velocities (:class:`wheelrail.Motion`).
    mu : float
        Friction coefficient [-], > 0.
    normal : str or NormalMethod
        A name of :func:`wheelrail.normal_methods` or a configured method
        (``wr.normal.Bem(element_size=2e-4)``).
    tangential : str or TangentialMethod
        A name of :func:`wheelrail.tangential_methods` or a configured law.
    vertical : {"total", "normal"}
        What carries the prescribed vertical load: the total vertical force
        on the wheel, creep forces included (default; the normal problem is
        re-solved with the load corrected by the creep forces' vertical
        component until the two agree within 1e-5 Q), or the normal forces
        alone (Σ Fn cos γ = Q; one pass).

    Returns
    -------
    WheelRailResult
    """

    if not isinstance(position, WheelRailPosition):
        raise InputError(f"position must be a WheelRailPosition, got {type(position).__name__}")
    if not isinstance(motion, Motion):
        raise InputError(f"motion must be a wheelrail.Motion, got {type(motion).__name__}")
    mu = float(positive("mu", mu))
    nimpl = normal_family.get(normal)
    timpl = tangential_family.get(tangential)
    ws = position.wheelset
    roll, zs = touching_poses(position)
    Omega = motion.angular_velocity(ws.nominal_radius)
    R = motion.roller_radius
    if vertical not in ("total", "normal"):
        raise InputError(f"vertical must be 'total' or 'normal', got {vertical!r}")

    check_friction(mu)
    with disabled():   # the inputs are checked; patches of a few N are normal inside a wheel
        return _solve_sides(position, motion, mu, nimpl, timpl, vertical, roll, zs, Omega, R)


def _solve_sides(position, motion, mu, nimpl, timpl, vertical, roll, zs, Omega, R,
                 problems=None) -> WheelRailResult:
    ws = position.wheelset
    patches, force_track, pose = [], {}, {"y": position.y, "yaw": position.yaw, "roll": roll}
    for side in SIDES:
        # problems: the wheel problems of this pose when the caller has them (batched sweep)
        prob = (wheel_problem(position, side, roll, zs[side], R) if problems is None
                else problems[side])
        zc = ws.nominal_radius + zs[side]
        sig = _SIGMA[side]
        Q = prob.vertical_load
        history = []            # (normal-load target, total vertical force)
        forces = None
        for outer in range(1, _MAX_VERTICAL + 1):
            found, info = nimpl.from_wheel(prob)
            if not found:
                raise InputError(f"no contact on the {side} wheel at y = {position.y!r} m")
            cr = [_creepage_at(p.frame, sig, motion, Omega, position, roll, zc, R) for p in found]
            forces = timpl.solve_patches(found, cr, mu, previous=forces)
            F = np.zeros(3)
            for p, fr in zip(found, forces):
                g = p.frame.contact_angle
                Fs = float(fr.Fy)
                F += (float(fr.Fx), Fs * np.cos(g) - sig * p.Fn * np.sin(g),
                      sig * Fs * np.sin(g) + p.Fn * np.cos(g))
            if Q is None or vertical == "normal" or abs(F[2] - Q) <= _VERTICAL_TOL * Q:
                break
            # the creep forces carry part of the vertical load: press the wheel less (or
            # more); secant steps on the normal-load target q, F_z(q) = Q
            history.append((prob.vertical_load, F[2]))
            if len(history) == 1:
                # all forces scale with the load at first order: the first step is a scaling
                q_new = prob.vertical_load * Q / F[2] if F[2] > 0 else prob.vertical_load + Q - F[2]
            else:
                (q0, f0), (q1, f1) = history[-2:]
                slope = (f1 - f0) / (q1 - q0) if q1 != q0 else 1.0
                q_new = q1 + (Q - f1) / (slope if slope > 0.05 else 1.0)
            if not q_new > 0:
                raise ConvergenceError(f"{side} wheel: the creep forces alone exceed the "
                                       f"vertical load {Q!r} N (vertical force {F[2]!r} N); "
                                       "no equilibrium")
            prob = dataclasses.replace(prob, vertical_load=q_new)
        else:
            raise ConvergenceError(
                f"{side} wheel at y = {position.y!r} m: the total vertical force {F[2]!r} N did "
                f"not reach the vertical load {Q!r} N in {_MAX_VERTICAL} normal/tangential "
                "passes; use vertical='normal' to let the normal forces alone carry it")
        for p, c, fr in zip(found, cr, forces):
            patches.append(PatchResult(p, fr, *c, side=side))
        force_track[side] = tuple(float(v) for v in F)
        pose[f"z_{side}"] = zs[side]
        pose[f"vertical_approach_{side}"] = float(info["vertical_approach"])
        pose[f"vertical_iterations_{side}"] = outer
    return WheelRailResult(tuple(patches), nimpl.name, timpl.name,
                           info={"mu": mu}, force_track=force_track, pose=pose,
                           position=position, motion=motion)


__all__ += ["touching_poses", "wheel_problem"]
