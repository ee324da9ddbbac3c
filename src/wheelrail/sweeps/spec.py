"""Sweep specification: what to evaluate, over which axes, in which chunks.

A :class:`SweepSpec` is a frozen description of a parameter study. Every
input quantity of the evaluator is either *fixed* (one value) or varied:

* **grid** mode: each varied quantity is an *axis* (a list or a range) and the
  sweep covers the Cartesian product of the axes, in axis order;
* **points** mode: an explicit list of points, given as columns of equal
  length (one column per varied quantity).

TOML form (``[sweep]`` table; units SI as in case files)::

    [sweep]
    method = "fastsim"          # any creep-force method (or a list: an axis)
    mu = 0.3
    Fn = 10000.0              # N
    A = 1.087                   # 1/m; or a, b [m]; or radii [m] as in [contact]
    B = 1.667
    xi = {start = -0.004, stop = 0.004, num = 101}   # a range ...
    eta = {start = -0.004, stop = 0.004, num = 101}
    phi = [0.0, 0.5, 1.0]                             # ... or a list [1/m]
    chunk = 2000                # points per chunk (written and resumed as a unit)
    [sweep.options]             # options of the method (e.g. nx, ny for FASTSIM)
    nx = 20
    [sweep.material]            # default: steel (E = 2.1e11 Pa, nu = 0.28)
    E = 2.1e11
    nu = 0.28
    # [sweep.points]            # instead of axes: explicit points, equal-length columns
    # xi = [-0.001, -0.002]
    # eta = [0.0, 0.001]

A range is ``{start, stop, num}`` (``num`` ≥ 1 values, both ends included) with
optional ``scale = "log"`` (geometric spacing, start and stop > 0).

The quantities each evaluator takes are listed in
:data:`wheelrail.sweeps.evaluators.EVALUATORS`; the creep-force evaluator
(default, ``evaluator = "creep"``) takes ``xi, eta`` [-], ``phi`` [1/m],
``mu`` [-], ``Fn`` [N], ``A, B`` [1/m] or ``a, b`` [m] or the radii of
:data:`wheelrail.hertzian.RADII_KEYS` [m], ``E`` [Pa], ``nu`` [-] and
``method`` (names). The geometry evaluator (``evaluator = "geometry"``)
takes ``y`` [m], ``yaw`` [rad], ``wheel``, ``rail`` (profile names or files),
``gauge``, ``inclination``, ``nominal_radius``, ``flange_back``.
"""

from __future__ import annotations

import hashlib
import json
import math
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType
from typing import Any, Mapping

import numpy as np

from .._toml import Reader, read_input, renamed_keys, tomllib
from ..errors import CaseFileError, InputError
from .evaluators import get_evaluator

__all__ = ["SweepSpec", "load_sweep", "sweep_from_dict", "expand_range"]

#: Most values of one axis (a range's ``num``); the whole sweep is limited by its estimate.
MAX_AXIS_VALUES = 10_000_000

_MODES = ("grid", "points")
_SPEC_KEYS = ("evaluator", "chunk", "options", "material", "points")
#: Quantities renamed for one name per quantity: former name -> name. Sweep files that use
#: a former name still read, with a :class:`~wheelrail._toml.RenamedKeyWarning` naming the
#: new one.
RENAMED_QUANTITIES = {"load": "Fn"}


def expand_range(name: str, value) -> np.ndarray:
    """Values of an axis given as a list, an array or a ``{start, stop, num[, scale]}`` range.

    Raises
    ------
    InputError
        For an axis without values, a bad range or non-finite values; the
        message names the axis and the value.
    """
    if isinstance(value, Mapping):
        unknown = set(value) - {"start", "stop", "num", "scale"}
        if unknown:
            raise InputError(f"axis {name!r}: unknown range key(s) {sorted(unknown)}; "
                             "a range is {start, stop, num[, scale]}")
        missing = [k for k in ("start", "stop", "num") if k not in value]
        if missing:
            raise InputError(f"axis {name!r}: range {dict(value)!r} lacks {', '.join(missing)}")
        num = value["num"]
        if isinstance(num, bool) or not isinstance(num, (int, np.integer)) or num < 1:
            raise InputError(f"axis {name!r}: num must be an integer >= 1 (an axis needs at "
                             f"least one value), got {num!r}")
        if num > MAX_AXIS_VALUES:  # before allocating: 1e9 values are 8 GB for the axis alone
            raise InputError(f"axis {name!r}: num = {num} values is more than the "
                             f"{MAX_AXIS_VALUES} an axis may have (8 bytes each, and every "
                             "point is computed); use fewer values")
        start, stop = value["start"], value["stop"]
        for k, v in (("start", start), ("stop", stop)):
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise InputError(f"axis {name!r}: {k} must be a finite number, got {v!r}")
        scale = value.get("scale", "linear")
        if scale == "linear":
            return np.linspace(float(start), float(stop), int(num))
        if scale == "log":
            if start <= 0 or stop <= 0:
                raise InputError(f"axis {name!r}: a log range needs start, stop > 0, "
                                 f"got start={start!r}, stop={stop!r}")
            return np.geomspace(float(start), float(stop), int(num))
        raise InputError(f"axis {name!r}: scale must be 'linear' or 'log', got {scale!r}")
    if isinstance(value, str):
        return np.array([value], dtype=object)
    if isinstance(value, (list, tuple)):
        kinds = {isinstance(v, str) for v in value}
        if len(kinds) > 1:
            raise InputError(f"axis {name!r} mixes names and numbers: {list(value)!r}; give "
                             "only numbers (SI units) or only names")
    arr = np.asarray(value)
    if arr.ndim != 1:
        raise InputError(f"axis {name!r} must be one-dimensional, got shape {arr.shape}")
    if arr.size == 0:
        raise InputError(f"axis {name!r} has no values (got {value!r}); give at least one")
    if arr.dtype.kind in "USO":
        if not all(isinstance(v, str) for v in arr.tolist()):
            raise InputError(f"axis {name!r} mixes names and numbers: {list(value)!r}")
        return np.array(arr.tolist(), dtype=object)
    try:
        arr = arr.astype(float)
    except (TypeError, ValueError):
        raise InputError(f"axis {name!r} must hold numbers or names, got {value!r}") from None
    if not np.all(np.isfinite(arr)):
        raise InputError(f"axis {name!r} has a non-finite value "
                         f"{arr[~np.isfinite(arr)][0].item()!r}")
    return arr


def _is_axis(value) -> bool:
    return isinstance(value, (Mapping, list, tuple, np.ndarray))


@dataclass(frozen=True)
class SweepSpec:
    """A parameter study (frozen). Build with :meth:`grid`, :meth:`from_points` or :func:`load_sweep`.

    Attributes
    ----------
    evaluator : str
        What is computed at each point (``"creep"``: creep forces of a
        Hertzian contact, see :mod:`wheelrail.sweeps.evaluators`).
    fixed : mapping of str to float or str
        Quantities with one value (SI units).
    axes : tuple of (str, ndarray)
        Grid mode: the axes, in order (the dataset's dimensions). Points
        mode: the columns, all of one length (dimension ``point``).
    mode : {"grid", "points"}
    options : mapping
        Options of the method (e.g. ``nx`` for FASTSIM, ``elements`` for the
        exact theory).
    chunk : int
        Points per chunk (the unit of work, of writing and of resuming).
    source : str
        File the spec was read from, or ``"<python>"``.
    source_sha256 : str or None
        SHA-256 of that file's bytes.
    """

    evaluator: str
    fixed: Mapping[str, Any]
    axes: tuple
    mode: str = "grid"
    options: Mapping[str, Any] = field(default_factory=lambda: MappingProxyType({}))
    chunk: int = 2000
    source: str = "<python>"
    source_sha256: str | None = None

    # ------------------------------------------------------------------ construction
    @classmethod
    def grid(cls, *, evaluator="creep", options=None, chunk=2000, **quantities) -> "SweepSpec":
        """A Cartesian-product sweep: sequences and ``{start, stop, num}`` dicts are axes.

        Parameters
        ----------
        evaluator : str
            ``"creep"`` (default).
        options : dict, optional
            Options of the method.
        chunk : int
            Points per chunk.
        **quantities
            Each quantity the evaluator takes: a scalar (fixed) or an axis, in
            SI units (``xi=np.linspace(-4e-3, 4e-3, 101), mu=0.3, ...``).

        Examples
        --------
        >>> from wheelrail.sweeps import SweepSpec
        >>> s = SweepSpec.grid(method="linear", mu=0.3, Fn=1e4, A=1.0, B=1.5,
        ...                    xi=[-1e-3, 0.0, 1e-3], eta={"start": 0, "stop": 1e-3, "num": 2})
        >>> s.shape, s.size
        ((3, 2), 6)
        """
        fixed, axes = {}, []
        for name, value in quantities.items():
            if _is_axis(value):
                axes.append((name, expand_range(name, value)))
            else:
                fixed[name] = value
        return cls._make(evaluator, fixed, axes, "grid", options, chunk)

    @classmethod
    def from_points(cls, points: Mapping, *, evaluator="creep", options=None, chunk=2000,
                    **fixed) -> "SweepSpec":
        """A sweep over an explicit list of points, given as equal-length columns."""
        if not isinstance(points, Mapping) or not points:
            raise InputError(f"points must be a non-empty mapping of columns, got {points!r}")
        cols = [(name, expand_range(name, list(np.atleast_1d(v)) if not isinstance(v, Mapping)
                                    else v)) for name, v in points.items()]
        lengths = {name: len(v) for name, v in cols}
        if len(set(lengths.values())) != 1:
            raise InputError(f"point columns must have one length, got {lengths}")
        return cls._make(evaluator, fixed, cols, "points", options, chunk)

    @classmethod
    def _make(cls, evaluator, fixed, axes, mode, options, chunk, source="<python>",
              sha=None) -> "SweepSpec":
        if isinstance(chunk, bool) or not isinstance(chunk, (int, np.integer)) or chunk < 1:
            raise InputError(f"chunk must be an integer >= 1 (points per chunk), got {chunk!r}")
        ev = get_evaluator(evaluator)
        names = [n for n, _ in axes]
        dup = (set(fixed) & set(names)) | {n for n in names if names.count(n) > 1}
        if dup:
            raise InputError(f"quantity {sorted(dup)[0]!r} given more than once")
        fixed = {k: _fixed_value(k, v) for k, v in fixed.items()}
        spec = cls(evaluator=ev.name, fixed=MappingProxyType(fixed),
                   axes=tuple((n, _frozen(v)) for n, v in axes), mode=mode,
                   options=MappingProxyType(dict(options or {})), chunk=int(chunk), source=source,
                   source_sha256=sha)
        ev.check(spec)
        return spec

    def __reduce__(self):  # mapping proxies do not pickle: rebuild from plain dicts
        return (_rebuild, (self.evaluator, dict(self.fixed), self.axes, self.mode,
                           dict(self.options), self.chunk, self.source, self.source_sha256))

    # ------------------------------------------------------------------ geometry
    @property
    def dims(self) -> tuple:
        """Dimension names of the result (axis names, or ``("point",)``)."""
        return tuple(n for n, _ in self.axes) if self.mode == "grid" else ("point",)

    @property
    def shape(self) -> tuple:
        """Shape of the result arrays."""
        if self.mode == "points":
            return (len(self.axes[0][1]),) if self.axes else (1,)
        return tuple(len(v) for _, v in self.axes) if self.axes else ()

    @property
    def size(self) -> int:
        """Number of points."""
        return math.prod(self.shape) if self.shape else 1  # Python int: no overflow

    def chunk_shape(self) -> tuple:
        """Block shape of one chunk: whole trailing axes, a slab of one axis, ones before.

        Every chunk is a rectangular block of the result arrays holding at most
        :attr:`chunk` points (at least one row of the last axis).
        """
        shape = self.shape
        if not shape:
            return ()
        out = list(shape)
        trailing = 1
        for j in range(len(shape) - 1, -1, -1):
            if trailing * shape[j] <= self.chunk:
                trailing *= shape[j]
                continue
            out[j] = max(1, self.chunk // trailing)
            for k in range(j):
                out[k] = 1
            break
        return tuple(out)

    def chunks(self) -> list[tuple]:
        """Index slices of every chunk, in order (chunk id = position in this list)."""
        shape, cs = self.shape, self.chunk_shape()
        if not shape:
            return [()]
        counts = [-(-n // c) for n, c in zip(shape, cs)]
        return [tuple(slice(i * c, min((i + 1) * c, n)) for i, c, n in zip(idx, cs, shape))
                for idx in np.ndindex(*counts)]

    def columns(self, block: tuple) -> dict:
        """Input values of the points of one chunk: ``{name: ndarray, shape (m,)}``.

        Fixed quantities are broadcast; points are in C order of the block.
        """
        if self.mode == "points":
            sl = block[0] if block else slice(None)
            cols = {n: np.asarray(v)[sl] for n, v in self.axes}
            m = len(next(iter(cols.values()))) if cols else 1
        else:
            vals = [np.asarray(v)[s] for (_, v), s in zip(self.axes, block)]
            grids = np.meshgrid(*vals, indexing="ij") if vals else []
            cols = {n: g.reshape(-1) for (n, _), g in zip(self.axes, grids)}
            m = int(np.prod([len(v) for v in vals])) if vals else 1
        for k, v in self.fixed.items():
            cols[k] = np.full(m, v, dtype=object if isinstance(v, str) else float)
        return cols

    # ------------------------------------------------------------------ identity
    def to_dict(self) -> dict:
        """JSON-ready description (axes as lists); equal specs give equal dicts."""
        return {
            "evaluator": self.evaluator, "mode": self.mode, "chunk": self.chunk,
            "fixed": dict(self.fixed), "options": dict(self.options),
            "axes": {n: [v.item() if hasattr(v, "item") else v for v in np.asarray(a).tolist()]
                     for n, a in self.axes},
        }

    @property
    def sha256(self) -> str:
        """Hash of :meth:`to_dict`: a resumed sweep must have the same one."""
        text = json.dumps(self.to_dict(), sort_keys=True, default=str)
        return hashlib.sha256(text.encode()).hexdigest()


def _rebuild(evaluator, fixed, axes, mode, options, chunk, source, sha):
    return SweepSpec(evaluator, MappingProxyType(fixed), tuple((n, _frozen(v)) for n, v in axes),
                     mode, MappingProxyType(options), chunk, source, sha)


def _frozen(v: np.ndarray) -> np.ndarray:
    v = np.array(v, copy=True)
    v.flags.writeable = False
    return v


def _fixed_value(name, v):
    if isinstance(v, str):
        return v
    if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)):
        raise InputError(f"{name} must be a number, a name or an axis, got {v!r}")
    if not math.isfinite(float(v)):
        raise InputError(f"{name} must be finite, got {v!r}")
    return float(v)


# ---------------------------------------------------------------------- TOML
def load_sweep(path_or_str) -> SweepSpec:
    """Read a ``[sweep]`` case (file path or TOML text) into a :class:`SweepSpec`.

    Raises
    ------
    CaseFileError
        Unreadable or malformed file, unknown keys, axes without values; the
        message names the file, the table, the key and the value.
    """
    sha = None
    if isinstance(path_or_str, str) and ("\n" in path_or_str or "=" in path_or_str):
        text, source = path_or_str, "<string>"
        sha = hashlib.sha256(text.encode()).hexdigest()
    else:
        path = Path(path_or_str)
        source = str(path)
        raw = read_input(path, "sweep file")
        sha = hashlib.sha256(raw).hexdigest()
        try:
            text = raw.decode("utf-8")
        except UnicodeDecodeError as exc:
            raise CaseFileError(f"{source}: cannot read sweep file: {exc}") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise CaseFileError(f"{source}: malformed TOML: {exc}") from None
    return sweep_from_dict(data, source=source, sha256=sha)


def sweep_from_dict(data: Mapping, source: str = "<dict>", sha256: str | None = None) -> SweepSpec:
    """Validate a parsed sweep case (``{"sweep": {...}}``) into a :class:`SweepSpec`."""

    r = Reader(source)
    r.unknown("", data, ("sweep",))
    tbl = r.required_table(data, "sweep")
    if not isinstance(tbl, Mapping):
        r.fail("", "sweep", f"must be a table [sweep], got {tbl!r}")
    evaluator = r.string("sweep", tbl, "evaluator", "creep")
    try:
        ev = get_evaluator(evaluator)
    except InputError as exc:
        r.fail("sweep", "evaluator", str(exc))
    renames = {o: n for o, n in RENAMED_QUANTITIES.items() if n in ev.quantities}
    tbl = renamed_keys(r, "sweep", tbl, renames)
    r.unknown("sweep", tbl, (*_SPEC_KEYS, *ev.quantities))
    chunk = tbl.get("chunk", 2000)
    if isinstance(chunk, bool) or not isinstance(chunk, int) or chunk < 1:
        r.fail("sweep", "chunk", f"must be an integer >= 1, got {chunk!r}")
    options = tbl.get("options", {})
    if not isinstance(options, Mapping):
        r.fail("sweep", "options", f"must be a table [sweep.options], got {options!r}")
    fixed: dict = {}
    axes: list = []
    material = tbl.get("material", {})
    if not isinstance(material, Mapping):
        r.fail("sweep", "material", f"must be a table [sweep.material], got {material!r}")
    r.unknown("sweep.material", material, ("E", "nu"))
    for k in ("E", "nu"):
        if k in material:
            if k in tbl:
                r.fail("sweep", k, "given both in [sweep] and [sweep.material]")
            fixed[k] = r.number("sweep.material", material, k, positive=(k == "E"))
    points = tbl.get("points")
    for name, value in tbl.items():
        if name in _SPEC_KEYS:
            continue
        try:
            if _is_axis(value):
                if points is not None:
                    r.fail("sweep", name, "axes cannot be combined with [sweep.points]; give "
                           "the values as a column of [sweep.points] or as one value")
                axes.append((name, expand_range(name, value)))
            elif isinstance(value, str):
                fixed[name] = value
            else:
                fixed[name] = r.number("sweep", tbl, name, allow_inf=name.endswith("radius"))
        except InputError as exc:
            r.fail("sweep", name, str(exc))
    mode = "grid"
    if points is not None:
        if not isinstance(points, Mapping) or not points:
            r.fail("sweep", "points", f"must be a table of equal-length columns, got {points!r}")
        points = renamed_keys(r, "sweep.points", points, renames)
        r.unknown("sweep.points", points, ev.quantities)
        for name, value in points.items():
            if name in fixed:
                r.fail("sweep.points", name, "also given as a fixed value in [sweep]")
            try:
                axes.append((name, expand_range(name, value)))
            except InputError as exc:
                r.fail("sweep.points", name, str(exc))
        lengths = {n: len(v) for n, v in axes}
        if len(set(lengths.values())) != 1:
            r.fail("sweep.points", None, f"columns must have one length, got {lengths}")
        mode = "points"
    try:
        return SweepSpec._make(ev.name, fixed, axes, mode, options, chunk, source=source,
                               sha=sha256)
    except InputError as exc:
        raise CaseFileError(f"{source}: [sweep]: {exc}") from None
