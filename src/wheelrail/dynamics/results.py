"""The results of a dynamics simulation as an :class:`xarray.Dataset` over time.

Dimensions: ``time``, ``wheelset`` (0 leading), ``side`` (``"left"``,
``"right"``), ``patch`` (largest normal force first) and, for flexible rails,
``direction`` (``"lateral"``, ``"vertical"``). Names follow
:data:`wheelrail.conventions.NAMES`: per patch ``Fn``, ``Fx``, ``Fy`` (creep
forces in the contact plane, on the wheel, Kalker's convention), ``Mz``,
``xi``, ``eta``, ``phi``, ``contact_angle``; per wheel the forces in the track
frame, ``vertical_load`` (Q), ``lateral_force`` (Y, the wheel's force on the
rail, positive towards the field side), ``Y_over_Q`` and the wear number
``wear_number`` (Tγ = −(Fx ξ + Fy η + Mz φ), the frictional power per unit
distance rolled, summed over the wheel's patches).

References
----------
.. [1] EN 14363:2016, Railway applications — testing and simulation for the
   acceptance of running characteristics (Y/Q, guiding forces).
.. [2] T.G. Pearce, N.D. Sherratt, Prediction of wheel profile wear, Wear 144
   (1991) 343–351 (the wear number Tγ).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import xarray as xr

from .._version import __version__
from ..errors import InputError
from ._fastcontact import PATCH_FIELDS, WHEEL_FIELDS
from .model import FRAME_STATES, WHEELSET_STATES

__all__ = ["SimulationResult", "to_dataset"]

_P = {n: i for i, n in enumerate(PATCH_FIELDS)}
_W = {n: i for i, n in enumerate(WHEEL_FIELDS)}

_WS_UNITS = {"y": "m", "z": "m", "roll": "rad", "yaw": "rad", "vy": "m/s", "vz": "m/s",
             "roll_rate": "rad/s", "yaw_rate": "rad/s", "omega": "rad/s", "pitch": "rad",
             "pitch_rate": "rad/s"}
_PATCH = {  # dataset name: (field, unit, description)
    "Fn": ("Fn", "N", "normal force of the patch"),
    "Fx": ("Fx", "N", "longitudinal creep force on the wheel (contact frame)"),
    "Fy": ("Fs", "N", "lateral creep force on the wheel in the contact plane"),
    "Mz": ("Mz", "N m", "spin moment on the wheel"),
    "contact_angle": ("contact_angle", "rad", "contact angle (positive towards the flange)"),
    "xi": ("xi", "1", "longitudinal creepage"),
    "eta": ("eta", "1", "lateral creepage"),
    "phi": ("phi", "1/m", "spin creepage"),
    "a": ("a", "m", "semi-axis along the rolling direction (equivalent ellipse)"),
    "b": ("b", "m", "semi-axis across (equivalent ellipse)"),
    "p_max": ("p_max", "Pa", "maximum pressure"),
    "penetration": ("penetration", "m", "approach of the bodies along the normal"),
    "wheel_y": ("wheel_y", "m", "contact point on the wheel profile (profile frame)"),
    "rail_y": ("rail_y", "m", "contact point on the rail profile (profile frame)"),
    "rolling_radius": ("rolling_radius", "m", "wheel radius at the contact point"),
}


def _array(a):
    """A NumPy array, or a Dask array as it is (a result read from a store stays lazy)."""
    return a if hasattr(a, "dask") else np.asarray(a)


def to_dataset(result) -> xr.Dataset:
    """The :class:`~wheelrail.dynamics.simulate.SimulationResult` as an xarray Dataset.

    Returns
    -------
    xarray.Dataset
        Variables: wheelset states (time, wheelset), frame states (time), rail
        states (time, wheelset, side, direction), per-wheel forces (time,
        wheelset, side), per-patch quantities (time, wheelset, side, patch);
        ``speed`` and ``position`` (time). Attributes: methods, integrator, CPU
        time, real-time factor, contact events.
    """
    t = np.asarray(result.t)
    names = list(result.names)
    X = _array(result.states)
    OW = _array(result.wheels)
    OP = _array(result.patches)
    nw = OW.shape[1]
    coords = {"time": t, "wheelset": np.arange(nw), "side": ["left", "right"],
              "patch": np.arange(OP.shape[3])}
    data = {}
    for s in WHEELSET_STATES:
        v = np.stack([X[:, names.index(f"ws{i}.{s}")] for i in range(nw)], axis=1)
        data[s] = (("time", "wheelset"), v, {"units": _WS_UNITS[s]})
    if "frame.y" in names:
        for s in FRAME_STATES:
            data[f"frame_{s}"] = ("time", X[:, names.index(f"frame.{s}")],
                                  {"units": _WS_UNITS[s]})
    for body in ("frame0", "frame1", "body"):          # VehicleModel
        if f"{body}.y" in names:
            for s in FRAME_STATES:
                data[f"{body}_{s}"] = ("time", X[:, names.index(f"{body}.{s}")],
                                       {"units": _WS_UNITS[s]})
    if any(n.startswith("rail0.") for n in names):
        coords["direction"] = ["lateral", "vertical"]
        for s, unit in (("head", "m"), ("head_velocity", "m/s"), ("support", "m")):
            def col(i, side, dn, s=s):
                return X[:, names.index(f"rail{i}.{side}.{dn}.{s}")]

            # (time, wheelset, side, direction)
            v = np.stack([np.stack([np.stack([col(i, side, dn) for dn in ("lateral", "vertical")],
                                             axis=1) for side in ("left", "right")], axis=1)
                          for i in range(nw)], axis=1)
            data[f"rail_{s}"] = (("time", "wheelset", "side", "direction"), v, {"units": unit})
    sig = np.array([-1.0, 1.0])[None, None, :]
    Fy_w = OW[..., _W["Fy"]]
    Fz_w = OW[..., _W["Fz"]]
    wheel_dims = ("time", "wheelset", "side")
    data["longitudinal_force"] = (wheel_dims, OW[..., _W["Fx"]],
                                  {"units": "N", "description": "track-frame x force on the wheel"})
    data["wheel_Fy"] = (wheel_dims, Fy_w, {"units": "N", "description":
                                           "track-frame y force on the wheel (y to the right)"})
    data["vertical_load"] = (wheel_dims, Fz_w, {"units": "N", "description":
                                                "vertical force on the wheel (Q)"})
    Y = -sig * Fy_w
    data["lateral_force"] = (wheel_dims, Y, {"units": "N", "description":
                                             "lateral force of the wheel on the rail (Y), "
                                             "positive towards the field side"})
    with np.errstate(divide="ignore", invalid="ignore"):
        yq = np.where(Fz_w > 0, Y / np.where(Fz_w > 0, Fz_w, 1.0), np.nan)
    data["Y_over_Q"] = (wheel_dims, yq, {"units": "1", "description": "derailment quotient"})
    data["vertical_approach"] = (wheel_dims, OW[..., _W["vertical_approach"]], {"units": "m"})
    data["n_patches"] = (wheel_dims, OW[..., _W["patches"]].astype(int), {"units": "1"})
    data["table_fallbacks"] = (wheel_dims, OW[..., _W["fallbacks"]].astype(int),
                               {"units": "1", "description":
                                "patches the table law left to FASTSIM (outside its domain)"})
    pdims = ("time", "wheelset", "side", "patch")
    for name, (f, unit, desc) in _PATCH.items():
        data[name] = (pdims, OP[..., _P[f]], {"units": unit, "description": desc})
    tg = -(OP[..., _P["Fx"]] * OP[..., _P["xi"]] + OP[..., _P["Fs"]] * OP[..., _P["eta"]]
           + OP[..., _P["Mz"]] * OP[..., _P["phi"]])
    data["patch_wear_number"] = (pdims, tg, {"units": "N", "description": "Tγ of the patch"})
    data["wear_number"] = (wheel_dims, tg.sum(axis=-1), {"units": "N", "description":
                                                         "Tγ summed over the wheel's patches"})
    data["speed"] = ("time", _array(result.speed), {"units": "m/s"})
    data["position"] = ("time", _array(result.position), {"units": "m"})
    attrs = {k: (v if isinstance(v, (str, int, float)) else repr(v))
             for k, v in result.info.items()}
    attrs["wheelrail_version"] = __version__
    attrs["events"] = len(result.events)
    if result.events:
        ev = np.array([[e["t"], e["wheelset"], 0 if e["side"] == "left" else 1, e["patches"]]
                       for e in result.events])
        coords["event"] = np.arange(ev.shape[0])
        data["event_time"] = ("event", ev[:, 0], {"units": "s"})
        data["event_wheelset"] = ("event", ev[:, 1].astype(int))
        data["event_side"] = ("event", np.where(ev[:, 2] > 0, "right", "left"))
        data["event_patches"] = ("event", ev[:, 3].astype(int))
    return xr.Dataset(data, coords=coords, attrs=attrs)


@dataclass(frozen=True, eq=False)
class SimulationResult:
    """Result of :func:`simulate` (frozen).

    Attributes
    ----------
    t : ndarray, shape (n,)
        Output times [s].
    states : ndarray, shape (n, n_states)
        State vectors (names in ``names``).
    wheels : ndarray, shape (n, n_wheelsets, 2, len(WHEEL_FIELDS))
        Per-wheel contact outputs (left, right).
    patches : ndarray, shape (n, n_wheelsets, 2, KMAX, len(PATCH_FIELDS))
        Per-patch contact outputs (largest normal force first; zero rows unused).
    names : tuple of str
    speed : ndarray, shape (n,)
        Speed at the output times [m/s].
    position : ndarray, shape (n,)
        Position of the model along the track [m].
    events : tuple of dict
        Contact-configuration changes: ``t``, ``wheelset``, ``side``, ``patches``.
    info : dict
        Methods, integrator, CPU time, contact evaluations, real-time factor, ...
    model, layout

    A result read from a store (``simulate(..., store=...)``,
    :func:`~wheelrail.dynamics.open_result`) holds Dask arrays instead of NumPy arrays
    (all but ``t``); ``info["store_status"]`` says whether the run completed.
    """

    t: np.ndarray
    states: np.ndarray
    wheels: np.ndarray
    patches: np.ndarray
    names: tuple
    speed: np.ndarray
    position: np.ndarray
    events: tuple = ()
    info: dict = field(default_factory=dict)
    model: object = None
    layout: object = None

    def state(self, name: str) -> np.ndarray:
        """Time series of one state (``"ws0.y"``, ``"frame.yaw"``, ...)."""
        try:
            return self.states[:, self.names.index(name)]
        except ValueError:
            raise InputError(f"no state {name!r}; states: {', '.join(self.names)}") from None

    @property
    def dataset(self):
        """The result as an :class:`xarray.Dataset` over time
        (:func:`wheelrail.dynamics.results.to_dataset`)."""
        return to_dataset(self)
