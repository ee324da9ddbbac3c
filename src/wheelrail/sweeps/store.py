"""Chunked, resumable result stores (Zarr; NetCDF written at the end).

Layout of a sweep store ``table.zarr`` (Zarr format 2, readable with
``xarray.open_zarr``):

* one array per output (``Fx``, ``Fy``, ..., ``status``, ``message``) with the
  sweep's dimensions, chunked exactly like the sweep's chunks, and one
  coordinate array per axis;
* attributes with provenance (``wheelrail_version``, ``evaluator``,
  ``method``, ``options``, ``spec`` (JSON), ``spec_sha256``, ``input_file``,
  ``input_sha256``, ``created``);
* ``.sweep_done/<id>``: one empty marker file per completed chunk, created by an
  atomic rename *after* the chunk's data is written. A chunk without a marker
  is (re)computed and rewritten by a resumed run, so a killed run loses no
  results and duplicates none: every chunk's data is written by exactly the
  one run that then marks it done.

Only the process running the sweep writes (workers return arrays), so a
store never sees concurrent writers.
"""

from __future__ import annotations

import datetime as _dt
import json
import os
import shutil
from pathlib import Path

import numpy as np

from .._version import __version__
from ..errors import InputError
from .evaluators import MESSAGE_LENGTH, STATUS_CODES, get_evaluator

__all__ = ["SweepStore", "open_sweep"]

_DONE = ".sweep_done"


def _is_netcdf(path: Path) -> bool:
    return path.suffix.lower() in (".nc", ".nc4", ".netcdf")


class SweepStore:
    """The Zarr store of one sweep (created, or opened to resume)."""

    def __init__(self, path, spec):
        self.path = Path(path)
        self.spec = spec
        self.done_dir = self.path / _DONE

    # ------------------------------------------------------------------ life cycle
    @classmethod
    def create(cls, path, spec, provenance: dict) -> "SweepStore":
        """Write the empty store (coordinates, fill values, attributes)."""
        import dask.array as da
        import xarray as xr

        store = cls(path, spec)
        ev = get_evaluator(spec.evaluator)
        shape, cs = spec.shape, spec.chunk_shape()
        coords = {}
        if spec.mode == "grid":
            for name, values in spec.axes:
                v = np.asarray(values)
                coords[name] = (name, v.astype(str) if v.dtype == object else v)
        else:
            coords["point"] = ("point", np.arange(spec.size))
            for name, values in spec.axes:
                v = np.asarray(values)
                coords[name] = ("point", v.astype(str) if v.dtype == object else v)
        data = {}
        encoding = {}
        for name in ev.output_names(spec):
            dtype, units, desc = ev.outputs[name]
            data[name] = (spec.dims, da.full(shape, np.nan, dtype=dtype, chunks=cs),
                          {"units": units, "long_name": desc})
        data["status"] = (spec.dims, da.full(shape, STATUS_CODES["pending"], dtype=np.int8,
                                             chunks=cs),
                          {"flag_values": list(STATUS_CODES.values()),
                           "flag_meanings": " ".join(STATUS_CODES)})
        data["message"] = (spec.dims, da.full(shape, "", dtype=f"<U{MESSAGE_LENGTH}", chunks=cs),
                           {"long_name": "failure message (empty when ok)"})
        for name in data:
            encoding[name] = {"chunks": cs}
        ds = xr.Dataset(data, coords=coords, attrs=provenance)
        ds.to_zarr(store.path, mode="w-", compute=False, encoding=encoding, zarr_format=2,
                   consolidated=True)
        store.done_dir.mkdir()
        return store

    @classmethod
    def open(cls, path, spec) -> "SweepStore":
        """Open an existing store to resume ``spec``; it must be the same sweep."""
        import zarr

        store = cls(path, spec)
        try:
            attrs = dict(zarr.open_group(str(store.path), mode="r").attrs)
        except Exception as exc:  # noqa: BLE001 - anything unreadable is "not a sweep store"
            raise InputError(f"cannot resume {str(path)!r}: not a sweep store ({exc})") from None
        if attrs.get("spec_sha256") != spec.sha256:
            raise InputError(f"cannot resume {str(path)!r}: it holds a different sweep "
                             f"(spec hash {attrs.get('spec_sha256')!r}, this sweep "
                             f"{spec.sha256!r}); use another --out path")
        store.done_dir.mkdir(exist_ok=True)
        return store

    # ------------------------------------------------------------------ chunks
    def done(self) -> set[int]:
        """Ids of the chunks recorded as complete."""
        return {int(p.name) for p in self.done_dir.iterdir() if p.name.isdigit()}

    def write(self, chunk_id: int, block: tuple, outputs: dict) -> None:
        """Write one chunk's outputs, then record it complete (atomic rename)."""
        import zarr

        group = zarr.open_group(str(self.path), mode="r+")
        shape = tuple(s.stop - s.start for s in block)
        for name, values in outputs.items():
            group[name][block] = np.asarray(values).reshape(shape)
        tmp = self.done_dir / f".{chunk_id}.tmp"
        tmp.write_text("")
        os.replace(tmp, self.done_dir / str(chunk_id))


def provenance(spec, method_names, options) -> dict:
    """Attributes recording what produced a store."""

    return {
        "title": "wheelrail sweep",
        "wheelrail_version": __version__,
        "evaluator": spec.evaluator,
        "method": ", ".join(method_names),
        "options": json.dumps(options, sort_keys=True, default=str),
        "spec": json.dumps(spec.to_dict(), sort_keys=True, default=str),
        "spec_sha256": spec.sha256,
        "input_file": spec.source,
        "input_sha256": spec.source_sha256 or "",
        "created": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
        "conventions": "SI units; forces on the wheel, Kalker's sign convention",
    }


def open_sweep(path):
    """Open a sweep result (Zarr directory or NetCDF file) as an :class:`xarray.Dataset`.

    Arrays are read lazily from disk (no dask needed).
    """
    import xarray as xr

    path = Path(path)
    if not path.exists():
        raise InputError(f"no sweep result at {str(path)!r}")
    if _is_netcdf(path):
        return xr.open_dataset(path)
    return xr.open_dataset(path, engine="zarr", chunks=None, consolidated=True)


def to_netcdf(zarr_path: Path, out: Path) -> None:
    """Copy a finished Zarr store to NetCDF ``out`` (atomically) and delete the store."""
    import xarray as xr

    tmp = out.with_name(out.name + ".tmp")
    with xr.open_dataset(zarr_path, engine="zarr", chunks=None, consolidated=True) as ds:
        ds.load().to_netcdf(tmp)
    os.replace(tmp, out)
    shutil.rmtree(zarr_path)
