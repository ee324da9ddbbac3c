"""The vehicle part of a dynamics case file (private).

``[model] kind = "vehicle"`` builds a :class:`wheelrail.dynamics.VehicleModel`, either
a built-in vehicle by name (``vehicle = "manchester1"``) or from the bogie keys of
``kind = "bogie"`` plus ``[model.carbody]`` and ``[model.secondary]``. Every refusal
names the file, the table, the key and the value (:class:`wheelrail._toml.Reader`).
"""

from __future__ import annotations

from collections.abc import Mapping

__all__ = ["VEHICLE_KEYS", "BUILT_IN_VEHICLES", "read_vehicle"]

#: Keys of ``[model]`` that only a vehicle takes.
VEHICLE_KEYS = ("vehicle", "carbody", "bogie_semi_spacing", "frame_height", "primary_height",
                "yaw_damper")
#: Built-in vehicles by case-file name.
BUILT_IN_VEHICLES = ("manchester1",)

_SECONDARY_KEYS = ("kx", "ky", "kz", "cx", "cy", "cz", "half_spacing", "height",
                   "yaw_stiffness", "anti_roll", "yaw_damper", "bumpstop")
_YAW_DAMPER_KEYS = ("damping", "stiffness", "half_spacing")
_CARBODY_KEYS = ("mass", "inertia", "height")


def _table(r, name, tbl):
    if not isinstance(tbl, Mapping):
        r.fail(name, None, f"must be a table, got {tbl!r}")
    return tbl


def _construct(r, table, make):
    """``make()``, its InputError re-raised naming the case file and ``table``."""
    from ..errors import InputError

    try:
        return make()
    except InputError as exc:
        r.fail(table, None, str(exc))


def _list(r, table, tbl, key):
    v = tbl.get(key)
    if (not isinstance(v, (list, tuple)) or len(v) < 2
            or any(isinstance(x, bool) or not isinstance(x, (int, float)) for x in v)):
        r.fail(table, key, f"must be a list of at least 2 numbers, got {v!r}")
    return tuple(float(x) for x in v)


def _yaw_damper(r, table, tbl):
    from ..dynamics import YawDamper

    tbl = _table(r, table, tbl)
    r.unknown(table, tbl, _YAW_DAMPER_KEYS)
    vals = {k: r.number(table, tbl, k, positive=True) for k in _YAW_DAMPER_KEYS if k in tbl}
    for k in ("damping", "stiffness"):
        if k not in vals:
            r.fail(table, k, "missing (required)")
    return _construct(r, table, lambda: YawDamper(**vals))


def _secondary(r, tbl):
    from ..dynamics import BumpStop, SecondarySuspension

    table = "model.secondary"
    tbl = _table(r, table, tbl)
    r.unknown(table, tbl, _SECONDARY_KEYS)
    vals = {k: r.number(table, tbl, k, lo=0.0) for k in _SECONDARY_KEYS[:10] if k in tbl}
    if "yaw_damper" in tbl:
        vals["yaw_damper"] = _yaw_damper(r, table + ".yaw_damper", tbl["yaw_damper"])
    if "bumpstop" in tbl:
        b = _table(r, table + ".bumpstop", tbl["bumpstop"])
        r.unknown(table + ".bumpstop", b, ("displacement", "force"))
        d = _list(r, table + ".bumpstop", b, "displacement")
        f = _list(r, table + ".bumpstop", b, "force")
        vals["bumpstop"] = _construct(r, table + ".bumpstop", lambda: BumpStop(d, f))
    return _construct(r, table, lambda: SecondarySuspension(**vals))


def _required_string(r, table, tbl, key):
    if key not in tbl:
        r.fail(table, key, "missing (required)")
    return r.string(table, tbl, key, "")


def read_vehicle(r, m, bogie_kw, rail, numbers):
    """The :class:`~wheelrail.dynamics.VehicleModel` of a ``[model] kind = "vehicle"``.

    Parameters
    ----------
    r : Reader
    m : Mapping
        The ``[model]`` table.
    bogie_kw : callable
        ``bogie_kw()`` → the keyword arguments of :class:`~wheelrail.dynamics.BogieModel`
        read from ``m`` (the keys of ``kind = "bogie"``); called only for a vehicle
        defined key by key.
    rail : RailSupport or None
        From ``[model.rail_support]``.
    numbers : callable
        ``numbers(r, table, tbl, key, n)`` → a tuple of n numbers.
    """
    from .. import dynamics as dyn

    if "vehicle" in m:
        name = _required_string(r, "model", m, "vehicle")
        if name not in BUILT_IN_VEHICLES:
            r.fail("model", "vehicle", f"must be one of {', '.join(BUILT_IN_VEHICLES)}, got "
                                       f"{name!r}")
        allowed = ("kind", "vehicle", "spin", "rail_support", "yaw_damper")
        extra = [k for k in m if k not in allowed]
        if extra:
            r.fail("model", extra[0], f"cannot be combined with the built-in vehicle {name!r} "
                                      f"(it sets its own profiles, masses and suspensions; "
                                      f"only spin, rail_support and yaw_damper can be given)")
        kw = {"spin": r.string("model", m, "spin", "fixed"), "rail": rail}
        if "yaw_damper" in m:
            kw["yaw_damper"] = _yaw_damper(r, "model.yaw_damper", m["yaw_damper"])
        return _construct(r, "model", lambda: dyn.manchester_vehicle1(**kw))
    if "yaw_damper" in m:
        r.fail("model", "yaw_damper", "belongs to [model.secondary] for a vehicle defined key "
                                      "by key (or to a built-in vehicle)")
    if "carbody" not in m:
        r.fail("model", "carbody", "missing: give vehicle = \"manchester1\" or a "
                                   "[model.carbody] table with the bogie keys")
    cb = _table(r, "model.carbody", m["carbody"])
    r.unknown("model.carbody", cb, _CARBODY_KEYS)
    body_kw = {"mass": r.number("model.carbody", cb, "mass", positive=True),
               "inertia": numbers(r, "model.carbody", cb, "inertia", 3)}
    if "height" in cb:
        body_kw["height"] = r.number("model.carbody", cb, "height", lo=0.0)
    body = _construct(r, "model.carbody", lambda: dyn.CarBody(**body_kw))
    if "secondary" not in m:
        r.fail("model", "secondary", "missing: a vehicle needs [model.secondary]")
    sec = _secondary(r, m["secondary"])
    bkw = bogie_kw()
    bogie = _construct(r, "model", lambda: dyn.BogieModel(**bkw))
    vkw = {k: r.number("model", m, k, lo=0.0, positive=k == "bogie_semi_spacing")
           for k in ("bogie_semi_spacing", "frame_height", "primary_height") if k in m}
    return _construct(r, "model", lambda: dyn.VehicleModel(carbody=body, bogies=bogie,
                                                           secondary=sec, **vkw))
