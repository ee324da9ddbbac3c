"""Plain two-column text / CSV profiles.

Format
------
One point per row, ``y`` and ``z`` in the first two columns (further columns
are ignored but must be numeric). The delimiter is detected from the first
data row — comma, semicolon (then a decimal comma is accepted), tab or
blanks — and must stay the same. ``#`` starts a comment. One non-numeric
header row (e.g. ``y,z`` or ``y [mm]; z [mm]``) is allowed before the data.

Comment lines of the form ``# key: value`` set defaults: ``kind`` (wheel/rail),
``units`` (m/mm), ``z`` (up/down), ``name``. :func:`write_text` writes them.

Conventions assumed
-------------------
The wheelrail profile frame (y towards the field side, z up), unless
``z_down=True`` / ``mirror_y=True`` is passed or a ``# z: down`` comment is
present. Units: the ``units`` argument, else a ``# units:`` comment, else
``mm``/``[m]`` in the header row, else guessed from the size (coordinates
larger than 2 → mm, with a warning). The origin is kept.
"""

from __future__ import annotations

import re
import warnings

import numpy as np

from ..._atomic import atomic_open
from ...errors import ProfileError
from ..core import Profile, ProfileWarning
from ._common import (
    POINT_DIST_MIN,
    Rows,
    append_row,
    check_row_count,
    kind_from_extension,
    make_profile,
    read_lines,
    resolve_kind,
)

__all__ = ["read_text", "write_text"]

_DIRECTIVE = re.compile(r"^#\s*(kind|units|z|name)\s*:\s*(.*?)\s*$", re.IGNORECASE)


def _split(s: str, delim: str) -> list[str]:
    if delim == "ws":
        return s.split()
    return [t.strip() for t in s.split(delim)]


def _detect_delimiter(s: str) -> str:
    if ";" in s:
        return ";"
    if "," in s:
        return ","
    if "\t" in s:
        return "\t"
    return "ws"


def parse_text(lines: list[str], name: str):
    """Return (directives, header row or None, data (n, ncol), file line of each row)."""
    directives: dict[str, str] = {}
    header = None
    delim = None
    ncol = None
    rows = Rows()
    for lineno, raw in enumerate(lines, start=1):
        where = f"{name}, line {lineno}"
        m = _DIRECTIVE.match(raw.strip())
        if m:
            directives[m.group(1).lower()] = m.group(2)
            continue
        s = raw.split("#", 1)[0].strip()
        if not s:
            continue
        if delim is None:
            d = _detect_delimiter(s)
            toks = _split(s, d)
            if d == ";":
                toks = [t.replace(",", ".") for t in toks]
            try:
                [float(t) for t in toks]
            except ValueError:
                if header is not None or rows:
                    raise ProfileError(f"{where}: {s[:60]!r} is not a row of numbers") from None
                header = s
                continue
            delim = d
            ncol = len(toks)
            if ncol < 2:
                raise ProfileError(f"{where}: need at least two columns (y, z), got {s[:60]!r}")
        toks = _split(s, delim)
        if delim == ";":
            toks = [t.replace(",", ".") for t in toks]
        append_row(rows, toks, ncol, where,
                   f" (delimiter {'blank' if delim == 'ws' else repr(delim)})")
    check_row_count(rows, name)
    return directives, header, np.array(rows, dtype=float), rows.lines


def read_text(path, kind=None, *, units=None, z_down=None, mirror_y=False, smoothing=0.0,
              tape_circle=None, point_dist_min=POINT_DIST_MIN, lenient=False) -> Profile:
    """Read a two-column text/CSV profile (see the module docstring).

    Parameters
    ----------
    kind : {"rail", "wheel", None}
        None: from a ``# kind:`` comment or the extension; otherwise an error.
    units : {"m", "mm", None}
    z_down : bool or None
        True when the file's z points downward (None: ``# z:`` comment, else up).
    mirror_y : bool
    tape_circle : float or None
        Move the origin to this y [m] (after orientation) and z(0) to 0.
    lenient : bool
        Accept a profile of the wrong shape (gap, wall, head down, flange cut
        off or at +y, columns swapped) with a warning instead of refusing it.
    """
    name, lines = read_lines(path)
    directives, header, data, row_lines = parse_text(lines, name)
    kind = resolve_kind(kind, directives.get("kind", "").lower() or kind_from_extension(path),
                        name)
    if units is None:
        u = directives.get("units", "").lower()
        if not u and header is not None:
            h = header.lower()
            u = "mm" if "mm" in h else ("m" if re.search(r"[\[(]\s*m\s*[\])]", h) else "")
        if not u:
            big = float(np.max(np.abs(data[:, :2]))) > 2.0
            u = "mm" if big else "m"
            warnings.warn(f"{name}: no length unit given; assuming {u} from the size of the data",
                          ProfileWarning, stacklevel=3)
        units = u
    scales = {"m": 1.0, "mm": 1e-3}
    if units not in scales:
        raise ProfileError(f"{name}: units must be 'm' or 'mm', got {units!r}")
    s = scales[units]
    if z_down is None:
        zdir = directives.get("z", "up").lower()
        if zdir not in ("up", "down"):
            raise ProfileError(f"{name}: '# z:' must be 'up' or 'down', got {zdir!r}")
        z_down = zdir == "down"
    y = data[:, 0] * s
    z = data[:, 1] * s * (-1.0 if z_down else 1.0)
    return make_profile(y, z, kind=kind, name=directives.get("name") or name.rsplit("/", 1)[-1],
                        source=name, fmt="text", meta={"units": units, "header": header},
                        smoothing=smoothing, point_dist_min=point_dist_min,
                        mirror_y=bool(mirror_y), wheel_flange_check=False,
                        tape_circle=tape_circle, lines=row_lines, lenient=bool(lenient))


def write_text(profile: Profile, path, *, units: str = "mm", delimiter: str = ",") -> None:
    """Write ``profile`` as text/CSV in the wheelrail frame (z up) with ``# key:`` comments."""
    scales = {"m": 1.0, "mm": 1e3}
    if units not in scales:
        raise ProfileError(f"units must be 'm' or 'mm', got {units!r}")
    if delimiter not in (",", ";", "\t", " "):
        raise ProfileError(f"delimiter must be ',', ';', tab or blank, got {delimiter!r}")
    f = scales[units]
    name = (profile.name or "").replace("\n", " ")
    out = ["# wheelrail profile: y towards the field side, z up",
           f"# kind: {profile.kind}", f"# units: {units}", "# z: up"]
    if name:
        out.append(f"# name: {name}")
    out.append(delimiter.join((f"y [{units}]", f"z [{units}]")))
    out += [delimiter.join((f"{y * f:.9e}", f"{z * f:.9e}")) for y, z in zip(profile.y, profile.z)]

    with atomic_open(path, "w", encoding="utf-8", newline="\n") as fh:
        fh.write("\n".join(out) + "\n")
