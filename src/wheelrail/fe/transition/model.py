"""The wheel–track model of the one- to two-point contact transition (case and assembly).

A half-wheelset (wheel rim meshed from its profile with the flange, plate tied to the rim,
hub clamped to a rigid half-axle) rolls at a constant forward speed along its own heading,
which is yawed by the angle of attack α against the rail: the axle's lateral motion is held
at its inner end, so the wheel approaches the gauge corner at V sin α and the flange comes
into contact (the boundary condition of explicit FE studies of the one- to two-point
contact transition; track and vehicle after Zhao & Li 2011).
The rail (head meshed from its profile with the gauge face, web and foot tied to it) lies
on solid sleepers through railpads; the sleepers on ballast (:mod:`.track`).

Kinematics of the wheel (small strain in its own frame)
-------------------------------------------------------
A wheel node's global position is ``c + R_z(α) R_y(ψ) (X + u)``, with the axle centre
``c = c0 + s(t) (cos α, sin α, 0) + w e_z``; ``s`` the distance travelled at the speed V,
``ψ`` the rolling angle driven by the torque (``J ψ̈ = T − M_contact``), ``w`` the axle's
vertical dof under the primary suspension. The rotating frame's fictitious forces are
neglected (as in :mod:`wheelrail.fe.model`) and the axle dofs are driven by the contact
forces directly (the elastic wheel's transients are not fed back into the axle).
The rail and the sleepers are in the global (track) frame at rest.

References
----------
.. [1] X. Zhao, Z. Li, Wear 271 (2011) 444-452 (3-D transient FE wheel-track model with
   a sprung mass on the primary suspension, discrete supports).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from ..._validation import in_range, non_negative, positive
from ...errors import InputError
from ...plausibility import check_friction, check_rolling_radius, check_speed
from ...profiles import Profile
from .._solid import element_chunks
from ..elements import Hex8
from ..materials import LinearElastic
from .contact import build_buckets, nodal_normals_quads
from .mesh import (
    extrude_section,
    line_tie,
    rail_section,
    rail_web_foot_rows,
    spacing_axis,
    sweep_section,
    wheel_plate_rows,
    wheel_section,
)
from .track import SpringSet, WheelSuspension, TrackStructure

__all__ = ["TransitionCase", "TransitionModel", "build_transition_model", "rigid_pose",
           "yawed_contact", "rail_surface_line", "SURFACE_LINES",
           "model_size_estimate"]


@dataclass(frozen=True, eq=False)
class TransitionCase:
    """A half-wheelset rolling into two-point contact on a flexible track (SI units).

    Parameters
    ----------
    wheel, rail : Profile
        Wheel and (uninclined) rail profiles with flange and gauge face.
    radius : float
        Wheel radius at the tape circle [m].
    inclination : float
        Rail inclination [rad].
    angle_of_attack : float
        Yaw of the wheel against the rail [rad], positive towards flange contact.
    speed : float
        Forward speed [m/s].
    mu : float
        Friction coefficient.
    traction : float
        Driving torque as a traction coefficient: T = traction · Q · r0 (Q the static wheel
        load, r0 the rolling radius); must stay below μ. Not used with ``creepage``.
    creepage : float or None
        If given, the wheel's rolling is prescribed once it rolls: a constant angular
        velocity ω = (1 + creepage) V / r0 (r0 the rigid rolling radius at the start
        contact; the history's ``creepage`` column), no torque: the contact takes the
        moment the prescribed rolling needs (the history's ``torque_contact``). A steady
        creepage for creep curves, instead of a torque that spins the wheel up until the
        contact balances it. |creepage| < 0.1.
    flange_clearance : float
        Lateral distance [m] the wheel moves (rigidly, without yaw) from its start to the
        flange contact.
    travel : float
        Distance rolled [m].
    settle : float
        Distance over which the start transients are damped (axle dashpot) [m].
    mesh_size : float
        Element size in the fine zones [m].
    grading : float
        Growth of the element sizes away from the fine zones.
    section_h_max, x_h_max, theta_h_max : float
        Largest sizes in the cross-sections, along the rail and along the wheel's
        circumference [m].
    track, suspension : TrackStructure, WheelSuspension
    material : LinearElastic
        Wheel and rail steel.
    penalty : float
        Normal and tangential contact penalty in units of E / h.
    contact_damping : float
        Normal contact dashpots, fraction of critical.
    courant : float
        Safety factor on the stable step.
    min_element_fraction : float
        Steel elements thinner than this fraction of ``mesh_size`` get their density raised
        to keep the stable step of an element of that thickness (selective mass scaling;
        the added mass is reported in the model's ``meta["added_mass"]``).
    output_interval : float
        Time between outputs [s].
    settle_damping : float
        Mass-proportional damping α [1/s] of all nodes at the start, fading linearly to 0
        over ``settle`` (dissipates the start transient, as the structural damping of the
        explicit studies does; 0 switches it off).
    preload : float
        Duration [s] of a static preload before the wheel starts rolling (0: none): the
        wheel stands at its start pose under the static load, without torque, and the
        structure relaxes to its static equilibrium by dynamic relaxation (fictitious
        masses for the slow lumped dofs — the axle massless on a dashpot, moving at
        (ΣFz − Q) / c, the sleepers at a 100th of their mass — and mass-proportional
        damping ``preload_damping`` of every node); the damping and the fictitious masses
        are switched off when the rolling starts. Removes the start transient of the vertical dynamics
        (the axle and the track on the contact stiffness) that ``settle`` does not reach.
        The outputs of the preload have negative times and zero travel.
    preload_damping : float
        Mass-proportional damping α [1/s] during the preload.
    patch_split_angle : float
        Contact angle [rad] separating the tread patch from the flange patch.
    wave_time : float
        Duration [s] over which the velocities of a rail surface line are stored every step
        (``info["wave"]``, for the wave-speed analysis; 0: none).
    wave_travel : float
        Travel [m] at which that record starts (0: at the start of the rolling).
    wave_line : {"tread", "flange"}
        The recorded line: the rail's surface line along x through the tread contact's
        lateral position, or through the rigid flange contact on the gauge corner
        (:func:`rail_surface_line`).
    field_travel : tuple of float
        ``(from, to)`` [m] of travel in which the contact's surface fields (pressure,
        traction, micro-slip, adhesion/slip per wheel surface node) are recorded at the
        outputs (``TransitionResult.contact_fields``); empty: none.
    field_stride : int
        Record the surface fields at every ``field_stride``-th output in that window.
    """

    wheel: Profile
    rail: Profile
    radius: float = 0.46
    inclination: float = float(np.arctan(1 / 40))
    angle_of_attack: float = 0.020
    speed: float = 80 / 3.6
    mu: float = 0.6
    traction: float = 0.1
    creepage: float | None = None
    flange_clearance: float = 1.0e-3
    travel: float = 0.10
    settle: float = 0.02
    mesh_size: float = 2.0e-3
    grading: float = 1.3
    section_h_max: float = 8e-3
    x_h_max: float = 0.02
    theta_h_max: float = 0.04
    track: TrackStructure = field(default_factory=lambda: TrackStructure(n_sleepers=2))
    suspension: WheelSuspension = field(default_factory=WheelSuspension)
    material: LinearElastic = field(default_factory=lambda: LinearElastic(2.1e11, 0.3, 7850.0))
    penalty: float = 1.0
    contact_damping: float = 0.2
    courant: float = 0.9
    min_element_fraction: float = 0.5
    output_interval: float = 30e-6
    settle_damping: float = 1000.0
    preload: float = 0.0
    preload_damping: float = 2000.0
    patch_split_angle: float = float(np.radians(45.0))
    wave_time: float = 0.0
    wave_travel: float = 0.0
    wave_line: str = "tread"
    field_travel: tuple = ()
    field_stride: int = 1

    def __post_init__(self):
        for name in ("radius", "speed", "mu", "travel", "mesh_size", "section_h_max",
                     "x_h_max", "theta_h_max", "penalty", "output_interval"):
            object.__setattr__(self, name, float(positive(name, getattr(self, name))))
        check_friction(self.mu, "mu")
        check_rolling_radius(self.radius, "radius")
        check_speed(self.speed, "speed")
        object.__setattr__(self, "patch_split_angle",
                           float(in_range("patch_split_angle", self.patch_split_angle,
                                          np.radians(30.0), np.radians(60.0))))
        for name in ("flange_clearance", "settle", "contact_damping", "traction",
                     "settle_damping", "wave_time", "wave_travel", "preload",
                     "preload_damping"):
            object.__setattr__(self, name, float(non_negative(name, getattr(self, name))))
        object.__setattr__(self, "angle_of_attack",
                           float(in_range("angle_of_attack", self.angle_of_attack, -0.1, 0.1)))
        object.__setattr__(self, "courant", float(in_range("courant", self.courant, 0.0, 1.0,
                                                           lo_open=True)))
        object.__setattr__(self, "grading", float(in_range("grading", self.grading, 1.0, 2.0)))
        check_surface_line("wave_line", self.wave_line)
        if self.creepage is not None:
            object.__setattr__(self, "creepage",
                               float(in_range("creepage", self.creepage, -0.1, 0.1)))
        if self.wave_travel >= self.travel:
            raise InputError(f"wave_travel {self.wave_travel!r} m must be below the travel "
                             f"{self.travel!r} m")
        ft = tuple(float(v) for v in self.field_travel)
        if ft and not (len(ft) == 2 and 0.0 <= ft[0] < ft[1]):
            raise InputError(f"field_travel must be (from, to) with 0 <= from < to [m], got "
                             f"{self.field_travel!r}")
        object.__setattr__(self, "field_travel", ft)
        if int(self.field_stride) != self.field_stride or self.field_stride < 1:
            raise InputError(f"field_stride must be a positive integer, got "
                             f"{self.field_stride!r}")
        object.__setattr__(self, "field_stride", int(self.field_stride))
        if self.traction >= self.mu:
            raise InputError(f"traction {self.traction!r} must stay below mu {self.mu!r}")
        if self.mesh_size > 5e-3:
            raise InputError(f"mesh_size {self.mesh_size!r} m is too coarse for a flange "
                             f"contact patch (use <= 5 mm)")
        if not isinstance(self.track, TrackStructure):
            raise InputError(f"track must be a TrackStructure, got {type(self.track).__name__}")
        if not isinstance(self.suspension, WheelSuspension):
            raise InputError(f"suspension must be a WheelSuspension, got "
                             f"{type(self.suspension).__name__}")
        if self.settle >= self.travel:
            raise InputError(f"settle {self.settle!r} m must be shorter than travel "
                             f"{self.travel!r} m")

    def replace(self, **changes) -> "TransitionCase":
        return replace(self, **changes)


# ----------------------------------------------------------------------------- rigid pose
def _curves(case):
    a = case.inclination
    c, s = np.cos(a), np.sin(a)
    ry = c * case.rail.y - s * case.rail.z
    rz = s * case.rail.y + c * case.rail.z
    return (np.asarray(case.wheel.y), np.asarray(case.wheel.z)), (ry, rz)


def _vertical_contact(wy, wz, ry, rz, y_off):
    """Rigid contact of the wheel curve shifted by y_off on the rail curve (no yaw):
    the vertical position z_off of the wheel profile origin where it touches, and the
    contact point (y, index on the rail curve)."""
    yy = wy + y_off
    ok = (yy > ry.min()) & (yy < ry.max())
    # rail height under each wheel point (rail curve single-valued in y after inclination)
    order = np.argsort(ry)
    zr = np.interp(yy[ok], ry[order], rz[order])
    gap = wz[ok] - zr
    k = int(np.argmin(gap))
    # and each rail point against the wheel (catches the gauge face / flange flank)
    order_w = np.argsort(wy)
    okr = (ry - y_off > wy.min()) & (ry - y_off < wy.max())
    zw = np.interp(ry[okr] - y_off, wy[order_w], wz[order_w])
    gap_r = zw - rz[okr]
    kr = int(np.argmin(gap_r))
    if gap_r[kr] < gap[k]:
        y_c = ry[okr][kr]
        return -gap_r[kr], y_c
    return -gap[k], yy[ok][k]


#: The rail surface lines that a pulse strikes or a run records (:func:`rail_surface_line`).
SURFACE_LINES = ("tread", "flange")


def check_surface_line(name: str, value) -> str:
    """``value`` if it names one of :data:`SURFACE_LINES`, else an InputError naming ``name``."""
    if value not in SURFACE_LINES:
        names = " or ".join(repr(v) for v in SURFACE_LINES)
        raise InputError(f"{name} must be {names}, got {value!r}")
    return value


def rail_surface_line(model, x_at: float, at: str = "tread"):
    """The rail's running-surface line along x through the tread or the flange contact.

    Parameters
    ----------
    model : TransitionModel
    x_at : float
        Position along the rail [m] near which the line's cross-section node is chosen.
    at : {"tread", "flange"}
        ``"tread"``: the surface node at the start contact's lateral position on the rail
        head's top; ``"flange"``: the gauge-corner node near the rigid flange contact whose
        outward normal is closest to the rigid flange contact angle.

    Returns
    -------
    line : ndarray of int (n,)
        Global node indices of the surface nodes with that node's (y, z), sorted along x.
    normal : ndarray (3,)
        Outward unit surface normal at the chosen node (reference configuration).
    """
    check_surface_line("at", at)
    m = model
    h = m.case.mesh_size
    xm = m.nodes[m.master]
    nrm = nodal_normals_quads(xm, m.quads)
    near = np.abs(xm[:, 0] - x_at) < 2 * h
    if not near.any():
        raise InputError(f"x_at {x_at!r} m is outside the rail's contact band")
    if at == "tread":
        top = np.flatnonzero(near)[np.argmin(np.abs(xm[near, 1] - m.pose["rail_y_tread"])
                                             + 10 * np.abs(xm[near, 2] - xm[near, 2].max()))]
    else:
        ang = np.arccos(np.clip(np.abs(nrm[:, 2]), 0.0, 1.0))
        cand = np.flatnonzero(near & (np.abs(xm[:, 1] - m.pose["rail_y_flange"]) < 2 * h))
        top = cand[np.argmin(np.abs(ang[cand] - m.pose["flange_angle_rigid"]))]
    on_line = ((np.abs(xm[:, 1] - xm[top, 1]) < 1e-7)
               & (np.abs(xm[:, 2] - xm[top, 2]) < 1e-7))
    line = m.master[on_line]
    line = line[np.argsort(m.nodes[line, 0])]
    return line, nrm[top] / np.linalg.norm(nrm[top])


def rigid_pose(case, y_off: float):
    """Rigid (no yaw) contact of the wheel at lateral offset ``y_off`` of its profile origin
    in the inclined rail frame: dict ``z_off`` (height of the wheel profile origin [m]),
    ``y`` the contact point [m], ``contact_angle`` [rad] (rail slope there)."""
    (wy, wz), (ry, rz) = _curves(case)
    z_off, y_c = _vertical_contact(wy, wz, ry, rz, y_off)
    order = np.argsort(ry)
    h = 2e-4
    slope = (np.interp(y_c + h, ry[order], rz[order]) - np.interp(y_c - h, ry[order],
                                                                 rz[order])) / (2 * h)
    return {"z_off": float(z_off), "y": float(y_c), "contact_angle": float(np.arctan(abs(slope)))}


def flange_contact_offset(case, lo=-0.02, hi=0.02, n=801):
    """Lateral offset of the wheel's profile origin [m] at which the rigid contact jumps to
    the flange (contact angle > 45°), and the tread pose at the start."""
    ys = np.linspace(lo, hi, n)
    ang = np.array([rigid_pose(case, y)["contact_angle"] for y in ys])
    k = np.flatnonzero(ang > np.radians(45))
    if k.size == 0:
        raise InputError("no flange contact found within ±20 mm of lateral offset")
    # the flange is at −y of the wheel: it reaches the gauge face as the wheel moves to +y
    a, b = ys[k[0] - 1], ys[k[0]]
    for _ in range(30):
        m = 0.5 * (a + b)
        if rigid_pose(case, m)["contact_angle"] > np.radians(45):
            b = m
        else:
            a = m
    return float(b)


def yawed_contact(case, y_off: float, yaw: float, hold: str = "touch", dy: float = 1e-5,
                  phi_max: float = 0.3) -> dict:
    """Rigid contact of the wheel yawed by ``yaw`` [rad] about the vertical through its
    profile origin, at lateral offset ``y_off`` [m] in the inclined rail frame (the pose of
    the transition runs' wheel, without roll).

    The rail is prismatic along x, so the contact lies in the wheel's shadow on the (y, z)
    plane: for each rail point y the lowest wheel point over it is found exactly on every
    profile station (the circle of radius r(y_w) yawed by α reaches y at
    sin φ = (y − y_w cos α) / (r sin α); its height R − r cos φ, its position along the
    rail x = r sin φ cos α − y_w sin α). The contact angle is the rail's slope at the
    contact point (the rail's normal has no x component).

    Parameters
    ----------
    case : TransitionCase
    y_off, yaw : float
        Lateral offset [m] and yaw angle [rad] of the wheel.
    hold : {"touch", "tread"}
        ``"touch"``: the wheel rests where it first touches the rail (on the flange once
        that is reached: it climbs); ``"tread"``: the wheel's height is set by its tread
        (rail slope below ``case.patch_split_angle``) and the flange may overlap the rail
        (the elastic runs keep the tread loaded).
    dy : float
        Sampling of the rail and the wheel profile [m].
    phi_max : float
        Largest angle about the axle searched [rad].

    Returns
    -------
    dict
        ``z_off`` (height of the profile origin [m]); ``tread`` and ``flange`` (rail slope
        below / above the split angle): ``angle`` [rad], ``x`` (lead ahead of the profile
        origin [m]), ``y``, ``z`` (rail point [m]) and ``gap`` [m, vertical, negative:
        overlap] of the closest point; for ``flange`` also ``overlap_angle`` and
        ``overlap_x`` (weighted by the normal overlap; NaN without overlap) and
        ``overlap_x_range`` [m].
    """
    if hold not in ("touch", "tread"):
        raise InputError(f"hold must be 'touch' or 'tread', got {hold!r}")
    (wy, wz), (ry, rz) = _curves(case)
    o = np.argsort(ry)
    Y = np.arange(ry.min(), ry.max(), dy)
    Zr = np.interp(Y, ry[o], rz[o])
    ang = np.arctan(np.abs(np.gradient(Zr, Y)))
    ow = np.argsort(wy)
    yw = np.arange(wy.min(), wy.max(), dy)
    R = case.radius
    r = R - np.interp(yw, wy[ow], wz[ow])
    ca, sa = np.cos(yaw), np.sin(yaw)
    Yw = Y - y_off                                  # rail points in the wheel's lateral frame
    zw = np.full(Y.size, np.inf)
    xw = np.zeros(Y.size)
    if abs(sa) < 1e-12:
        ok = (Yw > yw[0]) & (Yw < yw[-1])
        zw[ok] = R - np.interp(Yw[ok], yw, r)
    else:
        half = int(np.ceil(r.max() * abs(sa) * np.sin(phi_max) / (dy * ca))) + 1
        win = np.arange(-half, half + 1)
        i0 = np.round((Yw / ca - yw[0]) / dy).astype(np.int64)
        for a in range(0, Y.size, 2000):
            idx = i0[a:a + 2000, None] + win[None, :]
            valid = (idx >= 0) & (idx < yw.size)
            idx = np.clip(idx, 0, yw.size - 1)
            rr = r[idx]
            sphi = (Yw[a:a + 2000, None] - yw[idx] * ca) / (rr * sa)
            valid &= np.abs(sphi) < np.sin(phi_max)
            z = np.where(valid, R - rr * np.sqrt(np.clip(1.0 - sphi ** 2, 0.0, 1.0)), np.inf)
            k = np.argmin(z, axis=1)
            row = np.arange(z.shape[0])
            zw[a:a + 2000] = z[row, k]
            xw[a:a + 2000] = (rr[row, k] * sphi[row, k] * ca - yw[idx[row, k]] * sa)
    ok = np.isfinite(zw)
    gap0 = np.where(ok, zw - Zr, np.inf)
    split = case.patch_split_angle
    tread = ok & (ang < split)
    flange = ok & (ang >= split)
    z_off = -float(gap0.min() if hold == "touch" else gap0[tread].min())
    gap = gap0 + z_off
    out = {"z_off": z_off}
    for name, reg in (("tread", tread), ("flange", flange)):
        if not reg.any():
            out[name] = None
            continue
        k = np.flatnonzero(reg)[np.argmin(gap[reg])]
        out[name] = {"angle": float(ang[k]), "x": float(xw[k]), "y": float(Y[k]),
                     "z": float(Zr[k]), "gap": float(gap[k])}
    if out["flange"] is not None:
        ov = flange & (gap < 0)
        w = -gap[ov] * np.cos(ang[ov])                 # normal overlap
        f = out["flange"]
        f["overlap_angle"] = float(np.sum(w * ang[ov]) / w.sum()) if ov.any() else np.nan
        f["overlap_x"] = float(np.sum(w * xw[ov]) / w.sum()) if ov.any() else np.nan
        f["overlap_x_range"] = ((float(xw[ov].min()), float(xw[ov].max())) if ov.any()
                                else (np.nan, np.nan))
    return out


#: Height of the wheel plate's hub end above the tape circle [m] (radius R − 0.30).
PLATE_HUB = 0.30


def plate_size(case) -> float:
    """Radial element size of the wheel plate [m]: 30 mm (or ``section_h_max``), but at
    most 50 × the plate's circumferential size at the hub in the fine arc,
    h (R − hub) / R, so that the elements keep an aspect ratio below the mesh check's 60
    (the 1 mm mesh had 84.7 with 30 mm)."""
    return min(max(case.section_h_max, 0.03),
               50.0 * case.mesh_size * (case.radius - PLATE_HUB) / case.radius)


# ----------------------------------------------------------------------------- model
@dataclass(eq=False)
class TransitionModel:
    """Assembled arrays of a :class:`TransitionCase` (built by :func:`build_transition_model`)."""

    case: TransitionCase
    nodes: np.ndarray            # (n, 3) reference: wheel nodes in the wheel frame, others global
    n_wheel: int                 # wheel nodes first
    groups: list                 # [(conn, chunks, edata, material)]
    mass: np.ndarray             # (n,)
    fixed: np.ndarray            # nodes clamped (hub)
    held_xy: np.ndarray          # nodes held in x and y (sleepers; see sleeper_hold)
    tie_slave: np.ndarray        # (nt,)
    tie_master: np.ndarray       # (nt, 2)
    tie_weight: np.ndarray       # (nt, 2)
    springs: SpringSet
    slave: np.ndarray            # wheel surface nodes in the contact band (n_a_band, n_s)
    slave_area: np.ndarray
    master: np.ndarray           # rail surface nodes used by the quads (global node ids)
    quads: np.ndarray            # (nq, 4) indices into master
    buckets: object
    kn: np.ndarray
    g0: float
    pose: dict
    meta: dict

    @property
    def n_nodes(self):
        return int(self.nodes.shape[0])

    @property
    def n_elements(self):
        return int(sum(g[0].shape[0] for g in self.groups))


def _group(conn, nodes, material, n_nodes):
    ed = Hex8("reduced").precompute(nodes, conn, material)
    return (conn, element_chunks(conn, n_nodes), ed, material)


def _x_axis(case, x0, x1, band):
    h = case.mesh_size
    return spacing_axis(x0, x1, [band], h, case.grading, case.x_h_max)


def build_transition_model(case: TransitionCase) -> TransitionModel:
    """Mesh the wheel, rail and sleepers of ``case``, tie, support and pair them."""
    h = case.mesh_size
    # ---- rigid pose: start offset from the flange contact offset
    y_flange = flange_contact_offset(case)
    y0 = y_flange - case.flange_clearance
    start = rigid_pose(case, y0)
    flange = rigid_pose(case, y_flange + 2e-4)
    # contact points in the wheel's profile frame
    yw_tread = start["y"] - y0
    yw_flange = flange["y"] - y_flange
    r0 = case.radius - float(case.wheel(yw_tread))
    # ---- sections
    b_t, b_f = 6 * h, 5 * h
    rail_rows, rail_curve, _ = rail_section(
        case.rail, h, [(start["y"] - b_t, start["y"] + b_t),
                       (flange["y"] - b_f, flange["y"] + b_f)],
        inclination=case.inclination, ratio=case.grading, h_max=case.section_h_max)
    web_rows = rail_web_foot_rows(rail_rows[-1, 0, 1], y_centre=0.0,
                                  h_max=max(case.section_h_max, 0.02))
    wheel_rows, wheel_curve, _ = wheel_section(
        case.wheel, h, [(yw_tread - b_t, yw_tread + b_t), (yw_flange - b_f, yw_flange + b_f)],
        ratio=case.grading, h_max=case.section_h_max)
    plate_rows = wheel_plate_rows(wheel_rows[-1, 0, 1], hub=PLATE_HUB,
                                  h_max=plate_size(case))
    # ---- rail along x: the wheel starts at x = 0; the fine band covers the travel plus the
    # flange contact's lead ahead of the axle
    track = case.track
    lead = 0.05
    x_band = (-3 * h - 0.01, case.travel + lead)
    xs_sl = track.sleeper_positions(0.0)
    xs_sl = xs_sl - 0.5 * (xs_sl[0] + xs_sl[-1]) + 0.5 * (x_band[0] + x_band[1])
    x_lo, x_hi = xs_sl[0] - track.overhang, xs_sl[-1] + track.overhang
    x_axis = _x_axis(case, x_lo, x_hi, x_band)
    rail_head = extrude_section(rail_rows, x_axis, name="rail head")
    rail_web = extrude_section(web_rows, x_axis, name="rail web")
    # ---- wheel: full revolution, fine over the material that rolls through contact
    R = case.radius
    th_band = (-(3 * h + 0.01) / R, (case.travel + lead) / R)
    th = spacing_axis(th_band[0] - np.pi, th_band[0] + np.pi, [th_band], h / R, case.grading,
                      case.theta_h_max / R)[:-1]
    rim = sweep_section(wheel_rows, th, R, periodic=True, name="wheel rim")
    plate = sweep_section(plate_rows, th, R, periodic=True, name="wheel plate")
    # ---- sleepers
    sl_nodes = []
    z_foot = float(web_rows[-1, 0, 1])
    Lx, Ly, Hz = track.sleeper_size
    ex, ey, ez = track.sleeper_elements
    y_in = -0.7525                        # the track centre from the rail centre (standard gauge)
    for xc in xs_sl:
        gx = np.linspace(xc - Lx / 2, xc + Lx / 2, ex + 1)
        gy = np.linspace(y_in, y_in + Ly, ey + 1)
        gz = np.linspace(z_foot - Hz, z_foot, ez + 1)
        X, Y, Z = np.meshgrid(gx, gy, gz, indexing="ij")
        sl_nodes.append(np.stack([X, Y, Z], -1).reshape(-1, 3))
    # ---- assemble node numbering
    blocks = [rim, plate, rail_head, rail_web]
    offs = np.cumsum([0] + [b.n_nodes for b in blocks])
    n_wheel = int(offs[2])
    sl_off = int(offs[-1])
    nsl = (ex + 1) * (ey + 1) * (ez + 1)
    nodes = np.concatenate([b.nodes for b in blocks] + sl_nodes)
    n = nodes.shape[0]
    steel = [b.elements + o for b, o in zip(blocks, offs[:-1])]

    def sl_index(s, i, j, k):
        return sl_off + s * nsl + (i * (ey + 1) + j) * (ez + 1) + k

    conc = []
    for s in range(len(xs_sl)):
        for i in range(ex):
            for j in range(ey):
                for k in range(ez):
                    conc.append([sl_index(s, i, j, k), sl_index(s, i + 1, j, k),
                                 sl_index(s, i + 1, j + 1, k), sl_index(s, i, j + 1, k),
                                 sl_index(s, i, j, k + 1), sl_index(s, i + 1, j, k + 1),
                                 sl_index(s, i + 1, j + 1, k + 1), sl_index(s, i, j + 1, k + 1)])
    conc = np.array(conc, np.int64)
    steel_conn = np.concatenate(steel)
    concrete = LinearElastic(track.sleeper_E, track.sleeper_nu, track.sleeper_density)
    groups = [_group(steel_conn, nodes, case.material, n), _group(conc, nodes, concrete, n)]
    mass = np.zeros(n)
    added = 0.0
    L_min = case.min_element_fraction * h
    for conn, _, ed, mat in groups:
        # selective mass scaling of the few thin elements (the rail's lower gauge and field
        # faces, where the offset layers turn onto the core): density × (L_min / L)²
        scale = np.maximum(1.0, (L_min / ed.length) ** 2) if mat is case.material else 1.0
        me = mat.density * ed.volume * scale
        added += float(np.sum(me - mat.density * ed.volume))
        np.add.at(mass, conn.ravel(), np.repeat(me / 8.0, 8))
    # ---- ties: web top row -> head bottom row; plate top row -> rim inner row
    tie_s, tie_m, tie_w = [], [], []
    for top_body, top_off, base_body, base_off, base_rows in (
            (rail_web, offs[3], rail_head, offs[2], rail_rows),
            (plate, offs[1], rim, offs[0], wheel_rows)):
        na, ns_b, nr_b = base_body.shape
        _, ns_t, nr_t = top_body.shape
        top_rows = top_body.meta["rows"]
        idx, w = line_tie(top_rows[0], base_rows[-1])
        for i in range(na):
            tie_s.append(top_off + (i * ns_t + np.arange(ns_t)) * nr_t)
            tie_m.append(base_off + (i * ns_b + idx) * nr_b + nr_b - 1)
            tie_w.append(w)
    tie_s = np.concatenate(tie_s)
    tie_m = np.concatenate(tie_m)
    tie_w = np.concatenate(tie_w)
    # ---- springs: pads (rail foot bottom -> sleeper top), ballast (sleeper bottom)
    springs = SpringSet(n)
    na_r, ns_w, nr_w = rail_web.shape
    foot = offs[3] + (np.arange(na_r)[:, None] * ns_w + np.arange(ns_w)[None]) * nr_w + nr_w - 1
    gy_all = np.linspace(y_in, y_in + Ly, ey + 1)
    for s, xc in enumerate(xs_sl):
        gx = np.linspace(xc - Lx / 2, xc + Lx / 2, ex + 1)
        seat = np.abs(x_axis - xc) <= track.pad_length / 2 + 1e-12
        nodes_seat = foot[seat].ravel()
        share = 1.0 / nodes_seat.size
        for a in nodes_seat:
            px, py = nodes[a, 0], nodes[a, 1]
            i = int(np.clip(np.searchsorted(gx, px) - 1, 0, ex - 1))
            j = int(np.clip(np.searchsorted(gy_all, py) - 1, 0, ey - 1))
            r = (px - gx[i]) / (gx[i + 1] - gx[i])
            t = (py - gy_all[j]) / (gy_all[j + 1] - gy_all[j])
            sn = [sl_index(s, i, j, ez), sl_index(s, i + 1, j, ez), sl_index(s, i + 1, j + 1, ez),
                  sl_index(s, i, j + 1, ez)]
            sw = [-(1 - r) * (1 - t), -r * (1 - t), -r * t, -(1 - r) * t]
            for d, (k, c) in enumerate(track.pad_springs()):
                springs.add([a] + sn, [1.0] + sw, d, k * share, c * share)
        # ballast: bottom nodes, tributary shares of the bottom face
        wx = np.full(ex + 1, 1.0 / ex)
        wx[[0, -1]] *= 0.5
        wy = np.full(ey + 1, 1.0 / ey)
        wy[[0, -1]] *= 0.5
        for i in range(ex + 1):
            for j in range(ey + 1):
                sh = wx[i] * wy[j]
                springs.add([sl_index(s, i, j, 0)], [1.0], 2, track.ballast_stiffness * sh,
                            track.ballast_damping * sh)
    springs.finish()
    # sleepers held in x and y: every node (they move only vertically on the ballast), or
    # the bottom face only (TrackStructure.sleeper_hold)
    layers = range(ez + 1) if track.sleeper_hold == "body" else (0,)
    held = np.array([sl_index(s, i, j, k) for s in range(len(xs_sl)) for i in range(ex + 1)
                     for j in range(ey + 1) for k in layers], np.int64)
    # ---- contact: wheel surface nodes in the fine θ band (slaves), rail quads in the band
    na_w, ns_wh, nr_wh = rim.shape
    band_i = np.flatnonzero((th >= th_band[0] - 4 * h / R) & (th <= th_band[1] + 4 * h / R))
    slave = (band_i[:, None] * ns_wh + np.arange(ns_wh)[None]) * nr_wh
    # tributary areas of the slaves from the surface quads
    q = rim.surface
    p = rim.nodes[q]
    qa = 0.5 * np.linalg.norm(np.cross(p[..., 2, :] - p[..., 0, :], p[..., 3, :] - p[..., 1, :]),
                              axis=-1)
    area_all = np.zeros(rim.n_nodes)
    for c in range(4):
        np.add.at(area_all, q[..., c].ravel(), 0.25 * qa.ravel())
    slave_area = area_all[slave.ravel()]
    ib = np.flatnonzero((x_axis >= x_band[0] - 4 * h) & (x_axis <= x_band[1] + 4 * h))
    ib = ib[:-1] if ib[-1] == x_axis.size - 1 else ib
    na_r2, ns_r, nr_r = rail_head.shape
    qi, qj = np.meshgrid(ib, np.arange(ns_r - 1), indexing="ij")
    rq = rail_head.surface[qi, qj].reshape(-1, 4) + offs[2]
    master, inv = np.unique(rq, return_inverse=True)
    quads = inv.reshape(-1, 4)
    buckets = build_buckets(nodes[master], quads, cell=max(4 * h, 6e-3), margin=4 * h + 2e-3)
    kn = case.penalty * case.material.E / np.sqrt(slave_area)
    p_ref = 1.0e9
    g0 = 0.05 * p_ref / float(np.median(kn))
    pose = {"y0": y0, "y_flange": y_flange, "z0": start["z_off"], "r0": r0,
            "yw_tread": yw_tread, "yw_flange": yw_flange, "rail_y_tread": start["y"],
            "rail_y_flange": flange["y"], "flange_angle_rigid": flange["contact_angle"],
            "tread_angle_rigid": start["contact_angle"], "sleepers": xs_sl, "x_band": x_band}
    meta = {"sleeper_offset": sl_off, "added_mass": added, "x_axis": x_axis, "theta": th,
            "rim_shape": rim.shape, "band_i": band_i,
            "quality": {b.name: b.meta["quality"] for b in blocks},
            "blocks": {b.name: (int(o), b.n_nodes, b.n_elements) for b, o in zip(blocks, offs)},
            "rail_rows": rail_rows, "wheel_rows": wheel_rows, "rail_curve": rail_curve,
            "wheel_curve": wheel_curve}
    return TransitionModel(case, nodes, n_wheel, groups, mass, offs[1] + plate.fixed, held,
                           tie_s, tie_m, tie_w, springs,
                           slave.ravel(), slave_area, master, quads, buckets, kn, g0, pose, meta)


def model_size_estimate(case: TransitionCase) -> dict:
    """Elements, nodes and surface counts of the model (builds the meshes; seconds)."""
    m = build_transition_model(case)
    return {"n_elements": m.n_elements, "n_nodes": m.n_nodes, "n_slaves": int(m.slave.size),
            "n_quads": int(m.quads.shape[0])}
