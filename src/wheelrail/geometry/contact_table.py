"""Contact tables: rigid contact geometry versus the lateral shift of the wheelset.

:func:`contact_table` solves the rigid constraint (Bosso et al. (2013), ch. 2, eqs. 2.1–2.3)
for every lateral shift and returns an :class:`xarray.Dataset` with dimension
``y`` (and ``point`` for the per-point quantities of both sides), the
rolling-radius difference Δr = r_right − r_left (Piotrowski & Chollet (2005), fig. 1), roll,
height, contact angles, positions, radii, curvatures and separations, and the
lateral shifts at which a contact point jumps (``jump_y``). Helpers write the
table to CSV and NetCDF (scipy engine; no netCDF4 dependency).
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from .._atomic import atomic_open, atomic_path
from .._validation import as_float_array, positive
from ..errors import InputError
from .contact_search import POINT_FIELDS, SIDES, STATUS, solve_rigid_rows
from .points import check_inputs, solve_rows

__all__ = ["contact_table", "locate_jumps", "write_csv", "write_netcdf"]


def _primary(data):
    """Index of the point with the smallest separation per row."""
    sep = np.where(np.isnan(data["separation"]), np.inf, data["separation"])
    return np.argmin(sep, axis=1)


def _primary_wheel_y(ws, tr, y, yaw, step, side, z0=None, roll0=None):
    """Wheel coordinate of the rigid contact point of ``side`` for each shift in ``y``."""
    y = np.atleast_1d(np.asarray(y, dtype=float))
    yaw = np.broadcast_to(np.asarray(yaw, dtype=float), y.shape)
    return solve_rigid_rows(ws, tr, y, yaw, step=step, z0=z0, roll0=roll0).wheel_y[side]


def locate_jumps(ws, tr, y, primary_wheel_y, side, *, threshold, yaw=0.0, step=2e-4,
                 refine=8, z=None, roll=None):
    """Lateral shifts where the rigid contact point on the wheel of ``side`` jumps.

    A jump is a change of the primary contact position on the wheel profile by
    more than ``threshold`` between neighbouring table rows. It is then
    located by bisection between the two rows (``refine`` halvings, all jumps
    at once; the result is accurate to ``Δy / 2**(refine+1)``); with
    ``refine = 0`` the mid-point of the interval is returned (to within half a
    sampling step). After bisection a change that has shrunk below
    ``threshold`` was a fast but continuous motion and is dropped.

    Returns
    -------
    list of (y_jump, size) : float [m], float [m] (signed change of wheel_y)
    """
    with np.errstate(invalid="ignore"):
        idx = np.flatnonzero(np.abs(np.diff(primary_wheel_y)) > threshold)
    if idx.size == 0:
        return []
    lo, hi = np.asarray(y, float)[idx].copy(), np.asarray(y, float)[idx + 1].copy()
    wlo, whi = primary_wheel_y[idx].copy(), primary_wheel_y[idx + 1].copy()
    z0 = None if z is None else 0.5 * (z[idx] + z[idx + 1])
    r0 = None if roll is None else 0.5 * (roll[idx] + roll[idx + 1])
    for _ in range(refine):
        mid = 0.5 * (lo + hi)
        wm = _primary_wheel_y(ws, tr, mid, yaw, step, side, z0, r0)
        if not np.all(np.isfinite(wm)):  # a row that cannot be solved: stop refining it
            wm = np.where(np.isfinite(wm), wm, wlo)
        left = np.abs(wm - wlo) <= np.abs(wm - whi)
        lo, wlo = np.where(left, mid, lo), np.where(left, wm, wlo)
        hi, whi = np.where(left, hi, mid), np.where(left, whi, wm)
    size = whi - wlo
    keep = np.abs(size) > threshold
    return [(float(a), float(b)) for a, b in zip(0.5 * (lo + hi)[keep], size[keep])]


def contact_table(wheelset, track, y=None, yaw=0.0, *, tolerance=1e-4, step=2e-4,
                  jump_threshold=1e-3, refine_jumps=6):
    """Rigid contact geometry of a wheelset on a track versus lateral shift.

    The table never aborts for one row: every row carries a ``status`` —
    ``ok``, ``flange_climb`` (the contact lies on the flange beyond its
    steepest point), ``derailed`` (the wheel rides on its flange tip),
    ``no_contact`` (a wheel lies entirely beside its rail) or
    ``not_converged`` — and ``status_reason`` explains every flagged row.
    Rows with ``no_contact`` or ``not_converged`` hold NaN.

    Parameters
    ----------
    wheelset : Wheelset
    track : Track
    y : array_like, shape (n,), optional
        Lateral shifts [m], strictly increasing (default
        ``np.linspace(-0.01, 0.01, 201)``).
    yaw : float
        Yaw angle [rad].
    tolerance : float
        Separation [m] below which local minima are reported as (potential)
        contact points (default 0.1 mm).
    step : float
        Search grid spacing along the wheel profile [m].
    jump_threshold : float
        A change of the primary contact position on the wheel profile by more
        than this [m] between neighbouring rows is a jump (default 1 mm).
    refine_jumps : int
        Bisection steps locating each jump between its two rows (default 6:
        to within Δy/128; 0: the mid-point, to within half a sampling step).

    Returns
    -------
    xarray.Dataset
        Coordinates ``y`` [m] and ``point`` (index, field side first). Data
        variables (SI units in ``attrs["units"]``):

        * ``delta_r`` (y): r_right − r_left of the primary points [m];
        * ``roll`` (y) [rad] (positive: right wheel higher), ``z`` (y): height
          of the axle centre above r0 over the top of rail [m];
        * ``n_contact_left``, ``n_contact_right`` (y): points with separation
          ≤ ``tolerance``;
        * ``primary_left``, ``primary_right`` (y): index of the rigid contact point;
        * ``<field>_left``, ``<field>_right`` (y, point) for every field of
          :data:`~wheelrail.geometry.contact_search.POINT_FIELDS`
          (``contact_angle``, ``rolling_radius``, ``wheel_y``, ``rail_y``,
          ``A``, ``B``, ``separation``, …), NaN where a row has fewer points;
        * ``rolling_radius_left/right_primary``, ``contact_angle_..._primary`` (y);
        * ``jump_y`` (jump): lateral shifts of the jumps [m], ``jump_side``
          (−1 left, +1 right), ``jump_size`` (change of wheel_y [m]);
        * ``status`` (y): int8 code, meanings in ``attrs["flag_meanings"]``
          (0 ok, 1 flange_climb, 2 derailed, 3 no_contact, 4 not_converged);
          ``status_reason`` (y): one line per flagged row, empty if ok.

    Examples
    --------
    >>> import numpy as np, wheelrail as wr
    >>> ws = wr.Wheelset(wr.profiles.load("S1002"))
    >>> tr = wr.Track(wr.profiles.load("60E1"))
    >>> t = wr.contact_table(ws, tr, np.linspace(-0.005, 0.005, 11))
    >>> float(t.delta_r.sel(y=0.0, method="nearest")) == 0.0
    True
    """
    import xarray as xr

    yaw_f, tolerance, step = check_inputs(wheelset, track, yaw, tolerance, step)
    y = np.linspace(-0.01, 0.01, 201) if y is None else as_float_array("y", y)
    if y.ndim != 1 or y.size < 1:
        raise InputError(f"y must be a 1-D array of lateral shifts, got shape {y.shape}")
    if y.size > 1 and np.any(np.diff(y) <= 0):
        raise InputError("y must be strictly increasing")
    if np.max(np.abs(y)) > 0.05:
        raise InputError(f"|y| must be <= 0.05 m, got {float(np.max(np.abs(y))):.6g} (mm given?)")
    jump_threshold = float(positive("jump_threshold", jump_threshold))
    refine_jumps = int(refine_jumps)
    if refine_jumps < 0:
        raise InputError(f"refine_jumps must be >= 0, got {refine_jumps!r}")

    z, th, sides, status, reasons = solve_rows(wheelset, track, y, yaw_f, tolerance, step,
                                               detail=True)
    npt = max(sides[s][0]["separation"].shape[1] for s in SIDES)
    rows = np.arange(y.size)
    coords = {"y": ("y", y, {"units": "m", "long_name": "lateral shift of the wheelset (right +)"}),
              "point": ("point", np.arange(npt))}
    data_vars = {
        "z": ("y", z, {"units": "m", "long_name": "height of the axle centre above r0 over top of rail"}),
        "roll": ("y", th, {"units": "rad", "long_name": "roll angle (right wheel higher +)"}),
        "status": ("y", status.astype(np.int8),
                   {"long_name": "row status", "flag_values": np.arange(len(STATUS), dtype=np.int8),
                    "flag_meanings": " ".join(STATUS.values())}),
        "status_reason": ("y", np.array(reasons, dtype=str), {"long_name": "why a row is flagged"}),
    }
    prim = {}
    jumps = []
    for side in SIDES:
        data, count = sides[side]
        pad = npt - data["separation"].shape[1]
        p = _primary(data)
        p = np.where(status >= 3, 0, p)
        prim[side] = p
        sep = data["separation"]
        n_contact = np.sum(np.nan_to_num(sep, nan=np.inf) <= tolerance, axis=1)
        data_vars[f"n_contact_{side}"] = ("y", n_contact.astype(np.int32),
                                          {"long_name": f"points with separation <= {tolerance} m"})
        data_vars[f"primary_{side}"] = ("y", np.where(status >= 3, -1, p).astype(np.int32),
                                        {"long_name": "index of the rigid contact point "
                                                      "(-1: row not solved)"})
        for key, (unit, desc) in POINT_FIELDS.items():
            arr = data[key]
            if pad:
                arr = np.concatenate([arr, np.full((y.size, pad), np.nan)], axis=1)
            data_vars[f"{key}_{side}"] = (("y", "point"), arr,
                                          {"units": unit, "long_name": f"{desc} ({side})"})
        for key in ("rolling_radius", "contact_angle", "wheel_y", "rail_y"):
            unit = POINT_FIELDS[key][0]
            data_vars[f"{key}_{side}_primary"] = ("y", data[key][rows, p],
                                                  {"units": unit,
                                                   "long_name": f"{key} of the rigid contact point"})
        if y.size > 1:
            wy = np.where(status >= 3, np.nan, data["wheel_y"][rows, p])
            for yj, size in locate_jumps(wheelset, track, y, wy, side,
                                         threshold=jump_threshold, yaw=yaw_f, step=step,
                                         refine=refine_jumps, z=z, roll=th):
                jumps.append((yj, -1 if side == "left" else 1, size))
    rr = data_vars["rolling_radius_right_primary"][1]
    rl = data_vars["rolling_radius_left_primary"][1]
    data_vars["delta_r"] = ("y", rr - rl, {"units": "m", "long_name": "r_right - r_left"})
    jumps.sort()
    data_vars["jump_y"] = ("jump", np.array([j[0] for j in jumps], dtype=float),
                           {"units": "m", "long_name": "lateral shift of a contact-point jump"})
    data_vars["jump_side"] = ("jump", np.array([j[1] for j in jumps], dtype=np.int32),
                              {"long_name": "-1 left, +1 right"})
    data_vars["jump_size"] = ("jump", np.array([j[2] for j in jumps], dtype=float),
                              {"units": "m", "long_name": "change of the contact position on the wheel"})
    attrs = {
        "title": "wheelrail rigid contact table",
        "wheel_left": str(getattr(wheelset.wheel, "name", "")),
        "wheel_right": str(getattr(wheelset.wheel_right, "name", "")),
        "rail_left": str(getattr(track.rail, "name", "")),
        "rail_right": str(getattr(track.rail_right, "name", "")),
        "nominal_radius": wheelset.nominal_radius, "flange_back": wheelset.flange_back,
        "tape_circle_offset": wheelset.tape_circle_offset,
        "gauge": track.gauge, "inclination": track.inclination, "canted": int(track.canted),
        "gauge_height": track.gauge_height, "yaw": yaw_f, "tolerance": tolerance,
        "step": step, "jump_threshold": jump_threshold,
        "rows_flagged": int(np.count_nonzero(status)),
        "rows_failed": int(np.count_nonzero(status >= 3)),
        "conventions": "SI; y right, z up; roll + = right wheel higher; contact angle + towards "
                       "the flange; delta_r = r_right - r_left",
    }
    return xr.Dataset(data_vars, coords=coords, attrs=attrs)


def write_netcdf(table, path) -> Path:
    """Write a contact table to NetCDF-3 with the scipy engine (no netCDF4 needed), atomically."""

    path = Path(path)
    with atomic_path(path) as tmp:
        table.to_netcdf(tmp, engine="scipy")
    return path


def write_csv(table, path) -> Path:
    """Write a contact table as CSV: one row per ``y``, per-point columns suffixed ``_<point>``.

    The file is written atomically (temporary file, then rename); text
    variables (``status_reason``) are written as quoted strings.
    """

    path = Path(path)
    cols, names = [np.asarray(table["y"].values, dtype=object)], ["y"]
    for name, var in table.data_vars.items():
        if var.dims == ("y",):
            cols.append(np.asarray(var.values, dtype=object))
            names.append(name)
        elif var.dims == ("y", "point"):
            for k in range(var.shape[1]):
                cols.append(np.asarray(var.values[:, k], dtype=object))
                names.append(f"{name}_{k}")

    def cell(v):
        if isinstance(v, str):
            return v
        v = float(v)
        return "" if np.isnan(v) else repr(v)

    with atomic_open(path, "w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh)
        w.writerow(names)
        for i in range(len(cols[0])):
            w.writerow([cell(c[i]) for c in cols])
    return path
