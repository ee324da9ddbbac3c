"""Wheel–rail contact over many wheelset positions: an ``xarray.Dataset``.

:func:`wheelset_sweep` solves :func:`wheelrail.solve` for each lateral shift
(with its yaw and roll) and collects the per-patch and per-wheel results in
labelled arrays. A position that fails (no contact, no equilibrium, no
convergence) is recorded with its status and message; the sweep goes on.
"""

from __future__ import annotations

import numpy as np

from .. import normal as normal_family
from .. import tangential as tangential_family
from .._validation import as_float_array
from ..errors import InputError, WheelrailError
from ..geometry.contact_table import contact_table
from ..materials import STEEL
from ..normal.hertz import Hertz
from ..options import split_options
from ..plausibility import check_friction, disabled
from ._hertz_batch import check_vertical, hertz_sweep
from ._strip_batch import strip_sweep
from .wheelrail import SIDES, WheelRailPosition, solve_wheelrail

__all__ = ["wheelset_sweep", "PATCH_VARIABLES"]

#: Per-patch variables of the dataset (name: (unit, description)).
PATCH_VARIABLES = {
    "y_rail": ("m", "lateral position of the contact reference point on the rail profile"),
    "y_rail_centre": ("m", "lateral position of the centre of pressure on the rail profile"),
    "y_wheel": ("m", "lateral position on the wheel profile"),
    "contact_angle": ("rad", "contact angle"),
    "xi": ("1", "longitudinal creepage"), "eta": ("1", "lateral creepage"),
    "phi": ("1/m", "spin creepage"),
    "Fn": ("N", "normal force"), "Fx": ("N", "longitudinal creep force on the wheel"),
    "Fs": ("N", "lateral creep force on the wheel in the contact plane"),
    "Mz": ("N m", "spin moment about the patch's centre of pressure"),
    "p_max": ("Pa", "largest pressure"), "area": ("m^2", "contact area"),
    "adhesion_area": ("m^2", "adhesion area"),
}



def wheelset_sweep(wheelset, track, y, yaw=0.0, roll=None, *, vertical_load=None, z=None,
                   motion=None, mu=0.3, normal="hertz", tangential="fastsim", material=None,
                   max_patches=3, progress=None, vertical="total", tolerance=5e-4,
                   batch=True, **options):
    """Solve the wheel–rail contact at many lateral shifts.

    Parameters
    ----------
    wheelset, track
        :class:`wheelrail.Wheelset`, :class:`wheelrail.Track`.
    y : array_like, shape (n,)
        Lateral shifts [m].
    yaw : float or array_like, shape (n,)
        Yaw angles [rad].
    roll : None, float or array_like, shape (n,)
        Roll angles [rad]; ``None`` (or NaN entries): from the rigid contact constraint.
    vertical_load, z
        As in :class:`wheelrail.WheelRailPosition` (load per wheel [N], or axle height [m]).
    motion : Motion
    mu : float
    normal, tangential : str or method object
        Names or configured methods, as for :func:`wheelrail.solve`.
    material : Material or MaterialPair, optional
    max_patches : int
        Patches per wheel kept in the dataset, ordered from the field side to
        the flange (so that a patch keeps its index along the sweep); more are
        counted in ``n_patches``.
    progress : bool or None
        Progress bar (``None``: for more than 20 positions).
    vertical : {"total", "normal"}
        What carries the vertical load (see :func:`wheelrail.solve`).
    tolerance : float
        Largest separation of a candidate contact point [m].
    batch : bool
        With ``normal="hertz"``: solve all positions at once (array
        operations; the same model as the per-position path, see
        :mod:`wheelrail.contact._hertz_batch`). Other methods: the touching
        poses and candidate points of all positions at once, then the same
        normal and tangential solution per position
        (:mod:`wheelrail.contact._strip_batch`). ``False``: one
        :func:`wheelrail.solve` per position.
    **options
        Options of the two methods, each given to the one method that declares
        it (as :func:`wheelrail.solve`).

    Returns
    -------
    xarray.Dataset
        Dimensions ``y`` (n), ``side`` (left, right), ``patch`` (max_patches).
        Per patch: the variables of :data:`PATCH_VARIABLES` (NaN where no
        patch); per wheel: ``Fx_track``, ``Fy_track``, ``Fz_track`` [N],
        ``n_patches``; per position: ``yaw``, ``roll`` [rad], ``status``
        ("ok", "error", or "flange_climb" / "derailed" where the contact table
        flags the rigid pose: the forces are computed, the row is not ordinary
        contact) and ``message``.
    """

    y = np.atleast_1d(as_float_array("y", y))
    if y.ndim != 1 or y.size == 0:
        raise InputError(f"y must be a non-empty 1-D array of lateral shifts, got shape {y.shape}")
    n = y.size
    yaw = np.broadcast_to(as_float_array("yaw", yaw), (n,)) if np.ndim(yaw) else np.full(n, yaw)
    if roll is None:
        roll = np.full(n, np.nan)
    roll = np.broadcast_to(np.asarray(roll, dtype=float), (n,))
    if motion is None:
        raise InputError("motion=wheelrail.Motion(speed=...) is required")
    material = STEEL if material is None else material
    npat = int(max_patches)

    check_vertical(vertical)
    nopts, topts = split_options(normal_family.get_class(normal),
                                 tangential_family.get_class(tangential), options)
    nimpl = normal_family.get(normal, nopts)
    timpl = tangential_family.get(tangential, topts)
    if batch and isinstance(nimpl, Hertz):
        # validate the position arguments once, as WheelRailPosition does
        WheelRailPosition(wheelset, track, float(y[0]), float(yaw[0]),
                          None if np.isnan(roll[0]) else float(roll[0]),
                          vertical_load=vertical_load, z=z, material=material,
                          tolerance=tolerance)
        loads = None if vertical_load is None else np.broadcast_to(
            np.asarray(vertical_load, dtype=float), (2,))

        check_friction(mu)
        with disabled():   # inputs checked above; small secondary patches are normal
            pp, ft, npc, status, message = hertz_sweep(
                wheelset, track, y, np.asarray(yaw, float), roll, loads, z, motion, mu,
                timpl, material, tolerance, vertical, npat)
        status, message = _flag_rows(wheelset, track, y, yaw, status, message, tolerance)
        return _dataset(y, yaw, roll, pp, ft, npc, status, message, nimpl.name, timpl.name, mu,
                        motion)
    per_patch = {k: np.full((n, 2, npat), np.nan) for k in PATCH_VARIABLES}
    ftrack = np.full((n, 2, 3), np.nan)
    npatches = np.zeros((n, 2), dtype=int)
    status = np.full(n, "ok", dtype=object)
    message = np.full(n, "", dtype=object)
    show = (n > 20) if progress is None else bool(progress)
    bar = task = None
    if show:
        from rich.progress import Progress

        bar = Progress(transient=True)
        bar.start()
        task = bar.add_task("wheel-rail contact", total=n)

    def record(i, res):
        if isinstance(res, WheelrailError):
            status[i], message[i] = "error", f"{type(res).__name__}: {res}"
            return
        for s, side in enumerate(SIDES):
            ps = sorted(res.side(side), key=lambda p: -p.y_wheel)  # field side first
            npatches[i, s] = len(ps)
            for k, p in enumerate(ps[:npat]):
                for name in PATCH_VARIABLES:
                    per_patch[name][i, s, k] = getattr(p, name)
            ftrack[i, s] = res.force_track[side]

    try:
        if batch:
            # other methods: poses and candidate points of all positions at once

            strip_sweep(wheelset, track, y, yaw, roll, vertical_load, z, motion, mu, nimpl,
                        timpl, material, tolerance, vertical,
                        record, None if bar is None else (lambda: bar.advance(task)))
        for i in range(0 if batch else n):
            try:
                pos = WheelRailPosition(wheelset, track, y[i], yaw[i],
                                        None if np.isnan(roll[i]) else roll[i],
                                        vertical_load=vertical_load, z=z, material=material,
                                        tolerance=tolerance)
                res = solve_wheelrail(pos, motion, mu, nimpl, timpl, vertical)
            except WheelrailError as exc:
                record(i, exc)
            else:
                record(i, res)
            if bar is not None:
                bar.advance(task)
    finally:
        if bar is not None:
            bar.stop()
    status, message = _flag_rows(wheelset, track, y, yaw, status, message, tolerance)
    return _dataset(y, yaw, roll, per_patch, ftrack, npatches, status, message, nimpl.name,
                    timpl.name, mu, motion)


def _flag_rows(wheelset, track, y, yaw, status, message, tolerance):
    """Rows solved "ok" whose rigid pose the contact table flags (flange climbing beyond the
    flange's steepest point, or riding on the flange tip) take that status and reason, so a
    force sweep does not report them as ordinary contact. Returns new (status, message)."""
    status = np.array(status, dtype=object)
    message = np.array(message, dtype=object)
    ok = np.flatnonzero(status == "ok")
    yaw = np.broadcast_to(np.asarray(yaw, dtype=float), y.shape)
    for psi in np.unique(yaw[ok]):
        rows = ok[yaw[ok] == psi]
        ys, inv = np.unique(y[rows], return_inverse=True)
        if ys.size == 0:
            continue
        try:
            t = contact_table(wheelset, track, ys, yaw=float(psi), tolerance=tolerance,
                              refine_jumps=0)
        except WheelrailError:
            continue                     # no table: the rows keep their own status
        names = t.status.attrs.get("flag_meanings", "").split()
        code = np.asarray(t.status.values)[inv]
        reason = np.asarray(t.status_reason.values)[inv]
        for r, c, why in zip(rows, code, reason):
            if c in (1, 2):
                status[r] = names[c] if c < len(names) else ("flange_climb", "derailed")[c - 1]
                message[r] = str(why)
    return status, message


def _dataset(y, yaw, roll, per_patch, ftrack, npatches, status, message, normal, tangential, mu,
             motion):
    import xarray as xr

    npat = next(iter(per_patch.values())).shape[2]
    dims = ("y", "side", "patch")
    data = {k: (dims, v, {"units": PATCH_VARIABLES[k][0], "long_name": PATCH_VARIABLES[k][1]})
            for k, v in per_patch.items()}
    for j, comp in enumerate(("Fx", "Fy", "Fz")):
        data[f"{comp}_track"] = (("y", "side"), ftrack[:, :, j],
                                 {"units": "N", "long_name": f"{comp} on the wheel, track frame"})
    data["n_patches"] = (("y", "side"), npatches, {"long_name": "patches found"})
    data["yaw"] = ("y", np.asarray(yaw, float), {"units": "rad"})
    data["roll_prescribed"] = ("y", np.asarray(roll, float), {"units": "rad",
                                                               "long_name": "NaN: from contact"})
    data["status"] = ("y", status.astype(str))
    data["message"] = ("y", message.astype(str))
    return xr.Dataset(data, coords={"y": ("y", y, {"units": "m"}), "side": list(SIDES),
                                    "patch": np.arange(npat)},
                      attrs={"normal": str(normal), "tangential": str(tangential), "mu": mu,
                             "speed": motion.speed,
                             "conventions": "Kalker: forces on the wheel; SI units"})
