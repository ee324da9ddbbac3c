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

Only the process running the sweep writes (workers return arrays). A store
is created in a temporary directory and renamed into place, so of two runs
started at once with the same output one creates it and the other is refused
naming it; a running sweep holds a lock (``.sweep_lock``, released when the
process ends, also when killed), so a second ``--resume`` of a store being
written is refused too.
"""

from __future__ import annotations

import datetime as _dt
import json
import os
import shutil
import tempfile
from pathlib import Path

import numpy as np

from .._atomic import naming
from .._version import __version__
from ..errors import InputError
from .evaluators import MESSAGE_LENGTH, STATUS_CODES, get_evaluator

__all__ = ["SweepStore", "open_sweep"]

_DONE = ".sweep_done"
_LOCK = ".sweep_lock"


def _is_netcdf(path: Path) -> bool:
    return path.suffix.lower() in (".nc", ".nc4", ".netcdf")


class SweepStore:
    """The Zarr store of one sweep (created, or opened to resume)."""

    def __init__(self, path, spec):
        self.path = Path(path)
        self.spec = spec
        self.done_dir = self.path / _DONE
        self._lock = None

    def lock(self) -> "SweepStore":
        """Take the store's writer lock, or refuse naming the store if another run holds it."""
        try:
            import fcntl
        except ImportError:  # pragma: no cover - not POSIX: no lock
            return self
        with naming(self.path / _LOCK):
            fh = open(self.path / _LOCK, "a")
        try:
            fcntl.flock(fh.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            fh.close()
            try:
                who = f" (process {int((self.path / _LOCK).read_text().split()[0])})"
            except (OSError, ValueError, IndexError):
                who = ""
            raise InputError(f"output {str(self.path)!r} is being written by another wheelrail "
                             f"sweep{who}; wait for it to finish (then --resume if it was "
                             "stopped) or choose another path") from None
        fh.truncate(0)
        fh.write(f"{os.getpid()}\n")
        fh.flush()
        self._lock = fh
        return self

    def close(self) -> None:
        """Release the writer lock."""
        if self._lock is not None:
            self._lock.close()
            self._lock = None

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
        with naming(store.path):
            store.path.parent.mkdir(parents=True, exist_ok=True)
            tmp = Path(tempfile.mkdtemp(prefix=f".{store.path.name}.", suffix=".creating",
                                        dir=store.path.parent))
        try:
            with naming(store.path):
                ds.to_zarr(tmp, mode="w-", compute=False, encoding=encoding, zarr_format=2,
                           consolidated=True)
                (tmp / _DONE).mkdir()
            try:  # atomic: of two runs creating the same store, one wins
                os.rename(tmp, store.path)
            except OSError:
                raise InputError(f"output {str(store.path)!r} was created by another run at "
                                 "the same time; wait for it to finish (then --resume if it "
                                 "was stopped) or choose another path (nothing is "
                                 "overwritten)") from None
        except BaseException:
            shutil.rmtree(tmp, ignore_errors=True)
            raise
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
        if "spec_sha256" not in attrs:
            raise InputError(f"cannot resume {str(path)!r}: its attributes (.zattrs) hold no "
                             "sweep description (damaged, or not a wheelrail sweep); use "
                             "another --out path")
        if attrs.get("spec_sha256") != spec.sha256:
            raise InputError(f"cannot resume {str(path)!r}: it holds a different sweep "
                             f"(spec hash {attrs.get('spec_sha256')!r}, this sweep "
                             f"{spec.sha256!r}); use another --out path")
        store.done_dir.mkdir(exist_ok=True)
        return store

    # ------------------------------------------------------------------ checks
    def validate(self) -> list[int]:
        """Check every chunk marked complete; unmark (and clear) those that are not.

        A marked chunk is kept only if every array of it can be read, no point of
        it is still ``pending`` and no point marked ``ok`` lacks its first output
        (a marker written without its data, a chunk file damaged on disk). The
        chunks unmarked here are computed again by the resumed run. A missing
        consolidated metadata file (``.zmetadata``) is rebuilt from the arrays.

        Returns
        -------
        list of int
            Ids of the chunks unmarked.

        Raises
        ------
        InputError
            An array's metadata or a coordinate cannot be read (the store cannot
            be repaired by recomputing chunks).
        """
        import zarr

        ev = get_evaluator(self.spec.evaluator)
        names = [*ev.output_names(self.spec), "status", "message"]
        try:
            group = zarr.open_group(str(self.path), mode="r")
            arrays = {n: group[n] for n in names}
            for n in self.spec.dims:
                if n in group:
                    group[n][...]
        except Exception as exc:  # noqa: BLE001 - any damage of the metadata is fatal
            raise InputError(f"cannot resume {str(self.path)!r}: the store is damaged "
                             f"({type(exc).__name__}: {' '.join(str(exc).split())[:160]}); "
                             "start the sweep again with another --out path") from None
        for name, arr in arrays.items():
            if tuple(arr.shape) != tuple(self.spec.shape):
                raise InputError(f"cannot resume {str(self.path)!r}: array {name!r} has shape "
                                 f"{tuple(arr.shape)}, the sweep {tuple(self.spec.shape)}; "
                                 "start the sweep again with another --out path")
        blocks = self.spec.chunks()
        first = names[0]
        bad = []
        for cid in sorted(self.done()):
            if cid >= len(blocks):
                bad.append(cid)
                continue
            block = blocks[cid]
            try:
                values = {n: np.asarray(arrays[n][block]) for n in names}
            except Exception:  # noqa: BLE001 - a damaged chunk file: recompute it
                bad.append(cid)
                self._clear(block)
                continue
            status = values["status"]
            ok = status == STATUS_CODES["ok"]
            if ((status == STATUS_CODES["pending"]).any()
                    or not np.isin(status, list(STATUS_CODES.values())).all()
                    or (values[first].dtype.kind == "f" and np.isnan(values[first][ok]).any())):
                bad.append(cid)
        for cid in bad:
            (self.done_dir / str(cid)).unlink(missing_ok=True)
        if not (self.path / ".zmetadata").exists():
            import warnings

            with naming(self.path), warnings.catch_warnings():
                warnings.simplefilter("ignore")  # the markers and lock are not Zarr objects
                zarr.consolidate_metadata(str(self.path), zarr_format=2)
        return bad

    def _clear(self, block: tuple) -> None:
        """Delete the chunk files of ``block`` in every array (they are rewritten)."""
        cs = self.spec.chunk_shape()
        key = ".".join(str(s.start // c) for s, c in zip(block, cs)) or "0"
        for sub in self.path.iterdir():
            f = sub / key
            if sub.is_dir() and (sub / ".zarray").exists() and f.is_file():
                f.unlink(missing_ok=True)

    # ------------------------------------------------------------------ chunks
    def done(self) -> set[int]:
        """Ids of the chunks recorded as complete."""
        return {int(p.name) for p in self.done_dir.iterdir() if p.name.isdigit()}

    def write(self, chunk_id: int, block: tuple, outputs: dict) -> None:
        """Write one chunk's outputs, then record it complete (atomic rename)."""
        import zarr

        with naming(self.path):
            group = zarr.open_group(str(self.path), mode="r+")
        shape = tuple(s.stop - s.start for s in block)
        for name, values in outputs.items():
            with naming(self.path / name):
                group[name][block] = np.asarray(values).reshape(shape)
        tmp = self.done_dir / f".{chunk_id}.tmp"
        with naming(tmp):
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
    try:
        if _is_netcdf(path):
            return xr.open_dataset(path)
        return xr.open_dataset(path, engine="zarr", chunks=None, consolidated=True)
    except Exception as exc:  # noqa: BLE001 - a damaged file: one clear line, not a traceback
        raise InputError(f"cannot read the sweep result {str(path)!r} ({type(exc).__name__}: "
                         f"{' '.join(str(exc).split())[:160]}); it is damaged: run the sweep "
                         "again with another --out path") from None


def to_netcdf(zarr_path: Path, out: Path) -> None:
    """Copy a finished Zarr store to NetCDF ``out`` (atomically) and delete the store."""
    import xarray as xr

    from .._atomic import atomic_path

    with xr.open_dataset(zarr_path, engine="zarr", chunks=None, consolidated=True) as ds:
        with atomic_path(out) as tmp:
            ds.load().to_netcdf(tmp)
    shutil.rmtree(zarr_path)
