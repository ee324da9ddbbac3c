"""MiniProf profile files (``.ban`` rail, ``.whl`` wheel), lengths in mm.

Formats
-------
* *Regular* (``.ban``/``.whl``): ``Key=Value`` header lines (``ColumnDef=X,Y,...``
  names the columns, default ``X,Y``), then the data rows (numbers separated
  by blanks, tabs or commas).
* *Old style*: a first line containing ``MINIPROF``, free header lines, then
  the data rows (columns X, Y, ...). The header ends at the first empty line
  or, in files written without one, at the first line that is a row of at
  least two numbers.

A double quote ``"``, ``!`` or ``%`` starts a comment that runs to the end of
the line (MiniProf uses ``"`` to switch off keys and points). Column ``X`` is
the lateral, ``Y`` the vertical coordinate; other columns are ignored.

Conventions assumed and detected
--------------------------------
* units: always mm;
* rails: MiniProf's ``X`` points towards the gauge side (track centre), so
  ``y = -X`` (``mirror_y=False`` switches this off);
* wheels: ``X`` points towards the field side (``y = X``); the origin is on
  the back of the flange, and the tape circle lies 70 mm from it: when the
  flange-side end of the data is within 10 mm of X = 0 the origin is moved to
  X = 70 mm and z(0) = 0 (``tape_circle=`` overrides; ``tape_circle=False``
  keeps the file origin);
* z direction: MiniProf files come with ``Y`` up or down; it is detected from
  the shape (a rail crown lies above the chord through the end points, a
  wheel flange below it); ``z_down=True/False`` overrides.
"""

from __future__ import annotations

import numpy as np

from ...errors import ProfileError
from ..core import Profile
from ._common import (
    POINT_DIST_MIN,
    Rows,
    append_row,
    check_row_count,
    chord_deviation_is_z_down,
    kind_from_extension,
    make_profile,
    read_lines,
    resolve_kind,
)

__all__ = ["read_miniprof", "looks_like_miniprof"]

_MM = 1e-3


def looks_like_miniprof(lines: list[str]) -> bool:
    """True for an old-style (``MINIPROF``) or regular (``ColumnDef=``/``XYPoints=``) file."""
    if any("MINIPROF" in ln.upper() for ln in lines[:3]):
        return True
    for ln in lines[:200]:
        key = ln.strip().lstrip('"').split("=", 1)[0].strip().lower()
        if "=" in ln and key in ("columndef", "xypoints", "mptypeno", "mpserno"):
            return True
    return False


def _strip(line: str) -> str:
    for ch in '"!%':
        i = line.find(ch)
        if i >= 0:
            line = line[:i]
    return line.strip()


def _is_switched_off_point(line: str) -> bool:
    """A data row switched off with a leading double quote (``" 43.7 38.5``)."""
    s = line.strip()
    if not s.startswith('"'):
        return False
    toks = s[1:].replace(",", " ").replace(";", " ").split()
    if len(toks) < 2:
        return False
    try:
        [float(t) for t in toks]
    except ValueError:
        return False
    return True


def _is_number_row(s: str) -> bool:
    """True when ``s`` (comments stripped) is a row of at least two numbers."""
    toks = s.replace(",", " ").replace(";", " ").split()
    if len(toks) < 2:
        return False
    try:
        [float(t) for t in toks]
    except ValueError:
        return False
    return True


def parse_miniprof(lines: list[str], name: str):
    """Return (keys dict, data (n, ncol), x column, y column)."""
    old = any("MINIPROF" in ln.upper() for ln in lines[:3])
    keys: dict[str, str] = {}
    rows = Rows()
    ncol = None
    in_data = not old
    for lineno, raw in enumerate(lines, start=1):
        where = f"{name}, line {lineno}"
        s = _strip(raw)
        if old and not in_data:
            if not raw.strip():
                in_data = True
                continue
            if not _is_number_row(s):
                continue
            in_data = True      # no empty line after the header: the data start here
        if not s:
            continue
        if "=" in s:
            if rows:
                raise ProfileError(f"{where}: keyword line {s[:60]!r} after the data rows")
            key, _, val = s.partition("=")
            keys[key.strip().lower()] = val.strip()
            continue
        toks = s.replace(",", " ").replace(";", " ").split()
        if ncol is None:
            ncol = len(toks)
            if ncol < 2:
                raise ProfileError(f"{where}: data row needs at least 2 columns, got {s[:60]!r}")
        append_row(rows, toks, ncol, where, " like the first row")
    check_row_count(rows, name)
    declared = keys.get("xypoints")
    if declared is not None:
        try:
            n_decl = int(float(declared))
        except ValueError:
            raise ProfileError(f"{name}: XYPoints={declared!r} is not a number") from None
        # MiniProf switches points off with a leading '"'; they count as declared points
        n_off = sum(1 for ln in lines if _is_switched_off_point(ln))
        if n_decl != len(rows) + n_off:
            cause = ("truncated file (incomplete copy or download?)" if len(rows) + n_off < n_decl
                     else "extra rows after the declared points?")
            raise ProfileError(f"{name}: XYPoints={n_decl} declares {n_decl} points but the file "
                               f"holds {len(rows) + n_off} data rows — {cause}")
    cols = [c.strip().upper() for c in keys.get("columndef", "X,Y").split(",")]
    try:
        ix, iy = cols.index("X"), cols.index("Y")
    except ValueError:
        raise ProfileError(f"{name}: ColumnDef={keys['columndef']!r} must name columns X and Y"
                           ) from None
    if max(ix, iy) >= ncol:
        raise ProfileError(f"{name}: ColumnDef names {len(cols)} columns but the data rows have "
                           f"{ncol}")
    return keys, np.array(rows, dtype=float), ix, iy, rows.lines


def read_miniprof(path, kind=None, *, smoothing=0.0, mirror_y=None, z_down=None,
                  tape_circle=None, point_dist_min=POINT_DIST_MIN, lenient=False) -> Profile:
    """Read a MiniProf ``.ban``/``.whl`` profile (see the module docstring).

    Parameters
    ----------
    kind : {"rail", "wheel", None}
        None: from the extension (``.whl`` wheel, ``.ban`` rail).
    mirror_y : bool or None
        None: the format default (rails mirrored, wheels not).
    z_down : bool or None
        None: detect from the shape.
    tape_circle : float, False or None
        Wheels: y [m] of the tape circle in the oriented file frame; None:
        70 mm from the flange back when the origin is on the flange back;
        False: keep the file origin.

    Raises
    ------
    ProfileError
        Malformed file (message names file and line), too few points, ...
    """
    name, lines = read_lines(path)
    kind = resolve_kind(kind, kind_from_extension(path), name)
    keys, data, ix, iy, row_lines = parse_miniprof(lines, name)
    x, yv = data[:, ix] * _MM, data[:, iy] * _MM
    if np.ptp(x) == 0.0:
        raise ProfileError(f"{name}: zero width (all X = {x[0] / _MM:g} mm)")
    down = chord_deviation_is_z_down(x, yv, kind) if z_down is None else bool(z_down)
    mirror = (kind == "rail") if mirror_y is None else bool(mirror_y)
    yy = -x if mirror else x
    meta = {"keys": keys, "z_down_in_file": down, "mirrored": mirror}
    tc = None
    if kind == "wheel" and tape_circle is None:
        # origin on the flange back (MiniProf wheels): tape circle 70 mm from it
        if abs(float(np.min(yy))) <= 0.010 and np.max(yy) > 0.080:
            tc = 0.070
    elif tape_circle is not None and tape_circle is not False:
        tc = float(tape_circle)
    return make_profile(yy, -yv if down else yv, kind=kind, name=name.rsplit("/", 1)[-1],
                        source=name, fmt="miniprof", meta=meta, smoothing=smoothing,
                        point_dist_min=point_dist_min, mirror_y=False,
                        wheel_flange_check=mirror_y is None, tape_circle=tc,
                        auto_tape_circle=tape_circle is not False, lines=row_lines,
                        lenient=bool(lenient))
