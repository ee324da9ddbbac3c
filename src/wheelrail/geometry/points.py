"""Contact points of a wheelset on a track: the public entry :func:`contact_points` and its
frozen result (the rigid constraint and the point search are :mod:`.contact_search`).

References
----------
.. [1] N. Bosso, M. Spiryagin, A. Gugliotta, A. Somà, *Mechatronic Modeling of Real-Time
   Wheel-Rail Contact*, Springer 2013, ch. 2, §2.1.1, eqs. (2.1)–(2.3).
.. [2] J. Piotrowski, H. Chollet, Wheel–rail contact models for vehicle system dynamics
   including multi-point contact, VSD 43 (2005) 455–483, fig. 1.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np

from .._validation import as_float_array, non_negative, positive
from ..errors import ConvergenceError, InputError
from ..plausibility import check_flange_back, check_yaw
from ._checks import SIDES, check_side
from .contact_search import (
    _MAX_YAW,
    POINT_FIELDS,
    STATUS,
    STATUS_CODE,
    ContactWarning,
    _Pose,
    classify_rows,
    find_points,
    solve_rigid_rows,
)
from .track import Track
from .wheelset import Wheelset

__all__ = ["ContactPointsResult", "SideContacts", "contact_points", "solve_rows", "check_inputs"]


@dataclass(frozen=True)
class SideContacts:
    """Contact points on one side (arrays of shape (n,), field side first).

    See :data:`POINT_FIELDS` for the meaning and units of every attribute;
    ``primary`` is the index of the point with the smallest separation (the
    rigid contact point).
    """

    wheel_y: np.ndarray
    wheel_z: np.ndarray
    rail_y: np.ndarray
    rail_z: np.ndarray
    track_y: np.ndarray
    track_z: np.ndarray
    x: np.ndarray
    contact_angle: np.ndarray
    rolling_radius: np.ndarray
    wheel_curvature_x: np.ndarray
    wheel_curvature_y: np.ndarray
    rail_curvature_y: np.ndarray
    A: np.ndarray
    B: np.ndarray
    separation: np.ndarray
    gap: np.ndarray

    @property
    def n(self) -> int:
        """Number of reported points."""
        return int(np.size(self.separation))

    @property
    def primary(self) -> int:
        """Index of the point with the smallest separation."""
        return int(np.argmin(self.separation))

    def in_contact(self, tolerance: float = 1e-6) -> np.ndarray:
        """Mask of the points with separation ≤ ``tolerance`` [m]."""
        return self.separation <= tolerance


@dataclass(frozen=True)
class ContactPointsResult:
    """Rigid contact of a wheelset at one lateral shift and yaw (frozen).

    Attributes
    ----------
    y, yaw : float
        Prescribed lateral shift [m] and yaw [rad].
    z, roll : float
        Height of the axle centre above r0 over the top of rail [m] and roll
        angle [rad] from the rigid constraint (positive: right wheel higher).
    left, right : SideContacts
        All points with separation ≤ ``tolerance``.
    tolerance : float
        Reporting tolerance on the separation [m].
    status : str
        ``"ok"``, ``"flange_climb"`` (the rigid contact lies on the flange
        beyond its steepest point) or ``"derailed"`` (the wheel rides on its
        flange tip); see :func:`classify_rows`.
    reason : str
        One line explaining a status other than ``"ok"``.
    """

    y: float
    yaw: float
    z: float
    roll: float
    left: SideContacts
    right: SideContacts
    tolerance: float
    status: str = "ok"
    reason: str = ""

    def side(self, side: str) -> SideContacts:
        """``left`` or ``right``."""
        return getattr(self, check_side(side))

    @property
    def delta_r(self) -> float:
        """Rolling radius difference r_right − r_left of the primary points [m]."""
        return float(self.right.rolling_radius[self.right.primary]
                     - self.left.rolling_radius[self.left.primary])


def _side_from_row(data, count, row) -> SideContacts:
    n = int(count[row])
    return SideContacts(**{f.name: np.array(data[f.name][row, :n]) for f in fields(SideContacts)})


def solve_rows(ws, tr, y, yaw, tolerance, step, *, detail=False):
    """Rigid pose and all contact points of both sides for the shifts ``y`` (shape (n,)).

    Returns ``z, roll`` (shape (n,)) and ``{side: (data, count)}`` of :func:`find_points`
    (rows that could not be solved are NaN with count 0). With ``detail=True`` also
    ``status`` (int8 codes of :data:`STATUS`, shape (n,)) and ``reasons`` (list of str).
    Without it, a row without contact or solution raises (InputError, ConvergenceError).
    """
    yaw = np.broadcast_to(np.asarray(yaw, dtype=float), y.shape)
    rows = solve_rigid_rows(ws, tr, y, yaw, step=step)
    if not detail and np.any(rows.status >= 3):
        i = int(np.flatnonzero(rows.status >= 3)[0])
        raise (InputError if rows.status[i] == 3 else ConvergenceError)(rows.reason[i])
    status, reasons = classify_rows(ws, y, rows.z, rows.wheel_y, rows.status, rows.roll)
    reasons = [r or rr for r, rr in zip(reasons, rows.reason)]
    good = np.flatnonzero(rows.status < 3)
    pose = _Pose(y[good], rows.z[good], rows.roll[good], yaw[good])
    sides = {}
    for side in SIDES:
        if good.size:
            data, count = find_points(ws, tr, side, pose, step=step, tolerance=tolerance)
        else:
            data, count = {k: np.full((0, 1), np.nan) for k in POINT_FIELDS}, np.zeros(0, int)
        npt = data["separation"].shape[1]
        full = {k: np.full((y.size, npt), np.nan) for k in data}
        for k in data:
            full[k][good] = data[k]
        cnt = np.zeros(y.size, dtype=int)
        cnt[good] = count
        sides[side] = (full, cnt)
    if detail:
        return rows.z, rows.roll, sides, status, reasons
    return rows.z, rows.roll, sides


def check_inputs(ws, tr, yaw, tolerance, step):
    """Validate the common arguments of the contact functions; returns (yaw, tolerance, step).

    ``yaw`` must be a scalar (returned as a float).
    """
    if not isinstance(ws, Wheelset):
        raise InputError(f"wheelset must be a Wheelset, got {type(ws).__name__}")
    if not isinstance(tr, Track):
        raise InputError(f"track must be a Track, got {type(tr).__name__}")
    yaw = as_float_array("yaw", yaw)
    if yaw.ndim != 0:
        raise InputError(f"yaw must be a scalar, got an array of shape {yaw.shape}")
    check_yaw(yaw)  # degrees given: refused; beyond a wheelset's yaw in track: warned
    if np.any(np.abs(yaw) > _MAX_YAW):
        raise InputError(f"|yaw| must be <= {_MAX_YAW} rad, got {yaw!r}")
    check_flange_back(ws.flange_back, tr.gauge)
    tolerance = float(non_negative("tolerance", tolerance))
    step = float(positive("step", step))
    if step > 2e-3:
        raise InputError(f"step must be <= 2e-3 m (search grid on the wheel), got {step!r}")
    return float(yaw), tolerance, step


def contact_points(wheelset: Wheelset, track: Track, y, yaw=0.0, *, tolerance=1e-4,
                   step=2e-4) -> ContactPointsResult:
    """All wheel–rail contact points of a wheelset at lateral shift ``y`` and yaw ``yaw``.

    Parameters
    ----------
    wheelset : Wheelset
    track : Track
    y : float
        Lateral shift of the wheelset [m], positive to the right.
    yaw : float
        Yaw angle [rad] (|ψ| ≤ 0.2).
    tolerance : float
        Report every local minimum of the distance with separation ≤
        ``tolerance`` [m] (default 0.1 mm): secondary / potential contact points.
    step : float
        Search grid spacing along the wheel profile [m] (default 0.2 mm);
        minima are refined far below it.

    Returns
    -------
    ContactPointsResult
        With ``status`` ``"ok"``, ``"flange_climb"`` or ``"derailed"``;
        ``"derailed"`` also issues a :class:`ContactWarning`.

    Raises
    ------
    InputError
        A wheel lies entirely beside its rail at this shift.
    ConvergenceError
        No pose satisfies the rigid constraint.

    Examples
    --------
    >>> import wheelrail as wr
    >>> ws = wr.Wheelset(wr.profiles.load("S1002"))
    >>> tr = wr.Track(wr.profiles.load("60E1"))
    >>> cp = wr.contact_points(ws, tr, 0.0)
    >>> abs(cp.delta_r) < 1e-9
    True
    """
    yaw, tolerance, step = check_inputs(wheelset, track, yaw, tolerance, step)
    y = as_float_array("y", y)
    if y.ndim != 0:
        raise InputError("contact_points takes a scalar y; use contact_table for arrays")
    z, th, rows, status, reasons = solve_rows(wheelset, track, y.reshape(1), yaw, tolerance,
                                              step, detail=True)
    if status[0] >= 3:
        raise (InputError if status[0] == 3 else ConvergenceError)(reasons[0])
    sides = {side: _side_from_row(*rows[side], 0) for side in SIDES}
    if status[0] == STATUS_CODE["derailed"]:
        import warnings

        warnings.warn(reasons[0], ContactWarning, stacklevel=2)
    return ContactPointsResult(float(y), yaw, float(z[0]), float(th[0]), sides["left"],
                         sides["right"], tolerance, STATUS[int(status[0])], reasons[0])
