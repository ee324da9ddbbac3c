"""Reading wheelset case files (``[wheelset]``, ``[track]``, ``[motion]``, ``[position]``)."""

from __future__ import annotations

import math
from pathlib import Path
from types import MappingProxyType
from typing import Mapping

import numpy as np

from ... import profiles
from ..wheelset import WheelsetCase
from ...errors import CaseFileError, InputError, ProfileError
from ...geometry import Track, Wheelset
from ...geometry.kinematics import Motion
from ...plausibility import check_flange_back
from ._reader import Reader, read_friction, read_materials, read_methods

__all__ = ["wheelset_case_from_dict", "is_wheelset_case", "MAX_POSITIONS"]

#: Top-level tables of a wheelset case (a wheelset on a track, real profiles).
_WHEELSET_TABLES = ("material", "wheelset", "track", "motion", "position", "friction", "method")
_WHEELSET_KEYS = ("profile", "profile_right", "nominal_radius", "flange_back",
                  "tape_circle_offset")
_TRACK_KEYS = ("profile", "profile_right", "gauge", "inclination", "gauge_height", "canted")
_MOTION_KEYS = ("speed", "omega", "lateral_velocity", "vertical_velocity", "yaw_rate",
                "roll_rate", "roller_radius")
_POSITION_KEYS = ("y", "yaw", "yaw_per_y", "roll", "vertical_load", "z", "tolerance")
#: Largest number of positions of a sweep read from a case file.
MAX_POSITIONS = 100_001


def is_wheelset_case(data: Mapping) -> bool:
    return any(k in data for k in ("wheelset", "track", "position", "motion"))


def _base_dir(source: str) -> Path:
    return Path(source).parent if not source.startswith("<") else Path.cwd()


def _read_profile(r: Reader, table: str, tbl: Mapping, key: str, kind: str, default):
    if key not in tbl and default is None:
        return None, None
    spec = r.string(table, tbl, key, default)
    names = {n.lower() for n in profiles.available()}
    try:
        if spec.lower() in names:
            prof = profiles.load(spec)
            if getattr(prof, "kind", kind) != kind:
                r.fail(table, key, f"{spec!r} is a {prof.kind} profile; a {kind} profile is "
                       "needed here")
            return prof, spec
        path = Path(spec).expanduser()
        if not path.is_absolute():
            path = _base_dir(r.source) / path
        if not path.exists():
            r.fail(table, key, f"{spec!r} is neither a built-in profile ("
                   + ", ".join(profiles.available()) + f") nor an existing file ({path})")
        return profiles.read(path, kind=kind), str(path)
    except (ProfileError, InputError) as exc:
        r.fail(table, key, f"{spec!r}: {' '.join(str(exc).split())}")


def _construct(r: Reader, table: str, make):
    try:
        return make()
    except (InputError, ProfileError) as exc:
        r.fail(table, None, " ".join(str(exc).split()))


def _read_slope(r: Reader, table: str, tbl: Mapping, key: str, default: float) -> float:
    if key not in tbl:
        return default
    v = tbl[key]
    if isinstance(v, str):
        s = v.strip()
        try:
            if "/" in s:
                num, den = s.split("/", 1)
                out = float(num) / float(den)
            else:
                out = float(s)
        except (ValueError, ZeroDivisionError):
            r.fail(table, key, f"must be a slope like \"1/40\" or 0.025, got {v!r}")
        if not math.isfinite(out):
            r.fail(table, key, f"must be finite, got {v!r}")
        return out
    return r.number(table, tbl, key)


def _read_y(r: Reader, tbl: Mapping):
    """``[position] y``: a number, a list, or a range {start, stop, num}; -> (array, sweep)."""
    if "y" not in tbl:
        r.fail("position", "y", "missing (required): a lateral shift [m], a list of shifts or "
               "a range {start = ..., stop = ..., num = ...}")
    v = tbl["y"]
    if isinstance(v, Mapping):
        r.unknown("position.y", v, ("start", "stop", "num"))
        start = r.number("position.y", v, "start")
        stop = r.number("position.y", v, "stop")
        num = v.get("num")
        if isinstance(num, bool) or not isinstance(num, int) or not 1 <= num <= MAX_POSITIONS:
            r.fail("position.y", "num", f"must be an integer in 1..{MAX_POSITIONS}, got {num!r}")
        if num > 1 and stop <= start:
            r.fail("position.y", "stop", f"must be > start = {start!r}, got {stop!r}")
        return np.linspace(start, stop, num), True
    if isinstance(v, list):
        if not v:
            r.fail("position", "y", "the list of lateral shifts is empty")
        vals = [r.number("position", {"y": x}, "y") for x in v]
        return np.array(vals, dtype=float), True
    return np.array([r.number("position", tbl, "y")]), False


def _read_position(r: Reader, tbl: Mapping):
    r.unknown("position", tbl, _POSITION_KEYS)
    y, sweep = _read_y(r, tbl)
    if np.any(np.abs(y) > 0.05):
        bad = float(y[np.argmax(np.abs(y))])
        r.fail("position", "y", f"lateral shifts are in metres and |y| <= 0.05 m, got {bad!r}")
    if "yaw" in tbl and "yaw_per_y" in tbl:
        r.fail("position", None, "give yaw [rad] or yaw_per_y [rad/m], not both")
    if isinstance(tbl.get("yaw"), list):
        yaw = np.array([r.number("position", {"yaw": x}, "yaw") for x in tbl["yaw"]], float)
        if yaw.shape != y.shape:
            r.fail("position", "yaw", f"a list of yaw angles needs one per lateral shift "
                   f"({y.size}), got {yaw.size}")
    elif "yaw_per_y" in tbl:
        yaw = r.number("position", tbl, "yaw_per_y") * y
    else:
        yaw = np.full(y.shape, r.number("position", tbl, "yaw", default=0.0))
    if np.any(np.abs(yaw) > 0.2):
        bad = float(yaw[np.argmax(np.abs(yaw))])
        r.fail("position", "yaw_per_y" if "yaw_per_y" in tbl else "yaw",
               f"gives a yaw angle of {bad!r} rad; |yaw| must be <= 0.2 rad")
    roll = None
    if "roll" in tbl:
        roll = r.number("position", tbl, "roll")
        if abs(roll) > 0.2:
            r.fail("position", "roll", f"|roll| must be <= 0.2 rad, got {roll!r}")
    if ("vertical_load" in tbl) == ("z" in tbl):
        r.fail("position", None, "give exactly one of vertical_load (N per wheel, or "
               "[left, right]) and z (height of the axle centre, m)")
    load = z = None
    if "vertical_load" in tbl:
        v = tbl["vertical_load"]
        if isinstance(v, list):
            if len(v) != 2:
                r.fail("position", "vertical_load", f"must be one number or [left, right], "
                       f"got {v!r}")
            load = tuple(r.number("position", {"vertical_load": x}, "vertical_load",
                                  positive=True) for x in v)
        else:
            q = r.number("position", tbl, "vertical_load", positive=True)
            load = (q, q)
    else:
        z = r.number("position", tbl, "z")
    tol = r.number("position", tbl, "tolerance", default=5e-4, positive=True)
    return y, sweep, yaw, roll, load, z, tol


def wheelset_case_from_dict(r: Reader, data: Mapping) -> WheelsetCase:
    for name in ("contact", "creepage", "force"):
        if name in data:
            r.fail(name, None, "a wheelset case ([wheelset], [track], [motion], [position]) "
                   "takes no [contact], [creepage] or [force] table: the contact follows from "
                   "the profiles, the creepages from [motion]")
    r.unknown("", data, _WHEELSET_TABLES)
    for name in _WHEELSET_TABLES:
        if name in data and not isinstance(data[name], Mapping):
            raise CaseFileError(f"{r.source}: '{name}' must be a table [{name}], "
                                f"got {data[name]!r}")
    materials = read_materials(r, data.get("material", {}))

    wt = data.get("wheelset", {})
    r.unknown("wheelset", wt, _WHEELSET_KEYS)
    wheel, wheel_src = _read_profile(r, "wheelset", wt, "profile", "wheel", "S1002")
    wheel_r, wheel_r_src = _read_profile(r, "wheelset", wt, "profile_right", "wheel", None)
    wkw = {k: r.number("wheelset", wt, k, positive=True) for k in _WHEELSET_KEYS[2:] if k in wt}
    ws = _construct(r, "wheelset", lambda: Wheelset(wheel, wheel_right=wheel_r, **wkw))

    tt = data.get("track", {})
    r.unknown("track", tt, _TRACK_KEYS)
    rail, rail_src = _read_profile(r, "track", tt, "profile", "rail", "60E1")
    rail_r, rail_r_src = _read_profile(r, "track", tt, "profile_right", "rail", None)
    tkw = {k: r.number("track", tt, k, positive=True) for k in ("gauge",) if k in tt}
    if "gauge_height" in tt:
        tkw["gauge_height"] = r.number("track", tt, "gauge_height", lo=0.0)
    tkw["inclination"] = _read_slope(r, "track", tt, "inclination", 1.0 / 40.0)
    if "canted" in tt:
        if not isinstance(tt["canted"], bool):
            r.fail("track", "canted", f"must be true or false, got {tt['canted']!r}")
        tkw["canted"] = tt["canted"]
    tr = _construct(r, "track", lambda: Track(rail, rail_right=rail_r, **tkw))
    _construct(r, "wheelset", lambda: check_flange_back(ws.flange_back, tr.gauge))

    mt = r.required_table(data, "motion")
    r.unknown("motion", mt, _MOTION_KEYS)
    mkw = {"speed": r.number("motion", mt, "speed", positive=True)}
    if "omega" in mt:
        mkw["omega"] = r.number("motion", mt, "omega", positive=True)
    for k in ("lateral_velocity", "vertical_velocity", "yaw_rate", "roll_rate"):
        if k in mt:
            mkw[k] = r.number("motion", mt, k)
    if "roller_radius" in mt:
        mkw["roller_radius"] = r.number("motion", mt, "roller_radius", positive=True)
    motion = _construct(r, "motion", lambda: Motion(**mkw))

    y, sweep, yaw, roll, load, z, tol = _read_position(r, r.required_table(data, "position"))
    mu = read_friction(r, data)
    normal, tangential, methods = read_methods(r, data.get("method", {}))
    tables = {"wheelset": {"profile": wheel_src, "profile_right": wheel_r_src,
                           "nominal_radius": ws.nominal_radius, "flange_back": ws.flange_back,
                           "tape_circle_offset": ws.tape_circle_offset},
              "track": {"profile": rail_src, "profile_right": rail_r_src, "gauge": tr.gauge,
                        "inclination": tr.inclination, "gauge_height": tr.gauge_height,
                        "canted": tr.canted},
              "motion": motion.to_dict(),
              "position": {"roll": roll, "vertical_load": load, "z": z, "tolerance": tol},
              "friction": {"mu": mu},
              "method": {"normal": normal.name, "tangential": tangential.name,
                         **{k: m.option_values() for k, m in methods.items()}}}
    case = WheelsetCase(wheelset=ws, track=tr, motion=motion, y=y, yaw=yaw, roll=roll,
                        vertical_load=load, z=z, tolerance=tol, sweep=sweep,
                        materials=materials, mu=mu, normal=normal, tangential=tangential,
                        methods=MappingProxyType(methods), source=r.source,
                        tables=MappingProxyType(tables))
    _construct(r, "position", lambda: case.position(0))   # the remaining checks of the pose
    return case


