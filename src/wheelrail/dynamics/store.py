"""Dynamics results on disk: a run written chunk by chunk into a Zarr store, read back lazily.

A long run keeps its outputs (about 1–5 kB per output: states, per-wheel and
per-patch contact quantities) in memory until it ends unless it is given a
store (``simulate(..., store="run.zarr")``): then the outputs are appended to
the store every few thousand outputs and only that buffer is held, so the
memory of a run does not grow with its duration (only its time axis, 8 bytes
per output, is read back as a coordinate). A run stopped by Ctrl-C has
everything up to its last finished chunk in the store, marked
``interrupted``; a finished run's store says ``complete``.

:func:`open_result` reads a store as a
:class:`~wheelrail.dynamics.SimulationResult` whose arrays are Dask arrays
(nothing is loaded until used): ``result.dataset`` is the same
:class:`xarray.Dataset` as that of a run kept in memory, lazily, and
:func:`~wheelrail.dynamics.assess` reads only the channels it needs.

Needs Zarr and Dask (``pip install "wheelrail[sweep]"``).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from ..errors import InputError
from .results import SimulationResult

__all__ = ["open_result"]

_FORMAT = "wheelrail.dynamics result store"
_ARRAYS = ("t", "states", "wheels", "patches", "speed", "position")
#: Bytes of the outputs held before they are written (one store chunk).
BUFFER_BYTES = 16e6


def _zarr():
    try:
        import zarr
    except ImportError:                              # pragma: no cover - extra not installed
        raise InputError("writing or reading a dynamics result store needs Zarr and Dask: "
                         "pip install \"wheelrail[sweep]\"") from None
    return zarr


class StoreWriter:
    """Appends the outputs of a run to a new Zarr store (private to ``simulate``).

    Parameters
    ----------
    path : str or Path
        The store (a directory; ``.zarr`` by convention). An existing store is replaced
        only if it is a dynamics result store; another existing path is refused.
    names : sequence of str
        State names.
    shapes : dict
        Trailing shapes of ``states``, ``wheels`` and ``patches``.
    """

    def __init__(self, path, names, shapes):
        zarr = _zarr()
        self.path = Path(path)
        if self.path.exists():
            try:
                fmt = dict(zarr.open_group(str(self.path), mode="r").attrs).get("format")
            except Exception:
                fmt = None
            if fmt != _FORMAT:
                raise InputError(f"store = {str(path)!r} exists and is not a dynamics result "
                                 "store: give a new path (nothing was overwritten)")
        self.group = zarr.open_group(str(self.path), mode="w")
        row = 8.0 * (3 + int(np.prod(shapes["states"])) + int(np.prod(shapes["wheels"]))
                     + int(np.prod(shapes["patches"])))
        self.rows = max(256, int(BUFFER_BYTES // row))
        make = getattr(self.group, "create_array", None) or self.group.create_dataset
        self.arrays = {}
        for name in _ARRAYS:
            tail = tuple(shapes.get(name, ()))
            self.arrays[name] = make(name, shape=(0,) + tail, chunks=(self.rows,) + tail,
                                     dtype="f8")
        self.group.attrs.update({"format": _FORMAT, "names": list(names), "status": "running",
                                 "rows": 0})
        self.n = 0
        self.t_first = math.nan
        self.t_last = math.nan

    def append(self, **data):
        """Append rows (``t``, ``states``, ``wheels``, ``patches``, ``speed``, ``position``)."""
        n = len(data["t"])
        if n == 0:
            return
        for name in _ARRAYS:
            self.arrays[name].append(np.ascontiguousarray(data[name], dtype=float), axis=0)
        if self.n == 0:
            self.t_first = float(data["t"][0])
        self.n += n
        self.t_last = float(data["t"][-1])
        self.group.attrs["rows"] = self.n

    def close(self, info, events, interrupted):
        """Write the run's information, contact events and status."""
        attrs = {k: (v if isinstance(v, (str, int, float, bool)) or v is None else repr(v))
                 for k, v in info.items()}
        self.group.attrs.update({"info": json.loads(json.dumps(attrs, default=repr)),
                                 "events": [dict(e) for e in events],
                                 "status": "interrupted" if interrupted else "complete",
                                 "rows": self.n})


def open_result(path, *, model=None, layout=None):
    """Read a dynamics result store as a :class:`~wheelrail.dynamics.SimulationResult`.

    Parameters
    ----------
    path : str or Path
        A store written by ``simulate(..., store=path)`` or ``wheelrail dynamics``.
    model, layout : optional
        The run's model and track layout, if the caller has them (the store holds the
        outputs, not the model).

    Returns
    -------
    SimulationResult
        ``t`` is loaded (the time coordinate); ``states``, ``wheels``, ``patches``,
        ``speed`` and ``position`` are Dask arrays over the store's chunks;
        ``info["store_status"]`` is ``"complete"``, ``"interrupted"`` or ``"running"``
        (a run still writing, or killed without Ctrl-C: the rows written so far).

    Raises
    ------
    InputError
        The path is not a dynamics result store.
    """
    zarr = _zarr()
    import dask.array as da

    p = Path(path)
    try:
        g = zarr.open_group(str(p), mode="r")
        attrs = dict(g.attrs)
    except Exception as exc:
        raise InputError(f"{str(path)!r} is not a readable dynamics result store "
                         f"({type(exc).__name__}: {exc})") from None
    if attrs.get("format") != _FORMAT:
        raise InputError(f"{str(path)!r} is not a dynamics result store (no format "
                         f"{_FORMAT!r} in its attributes)")
    n = int(attrs.get("rows", 0))
    arr = {name: da.from_zarr(g[name])[:n] for name in _ARRAYS}
    info = dict(attrs.get("info", {}))
    info["store_status"] = attrs.get("status", "running")
    info["store"] = str(p)
    events = tuple(attrs.get("events", ()))
    return SimulationResult(np.asarray(arr["t"]), arr["states"], arr["wheels"],
                            arr["patches"], tuple(attrs["names"]), arr["speed"],
                            arr["position"], events, info, model, layout)
