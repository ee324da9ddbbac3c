"""Simpack rail/wheel profile files (``.prr`` rail, ``.prw`` wheel).

Format (as written by Simpack and by CONTACT)
---------------------------------------------
Text, ``!`` starts a comment (outside quotes); lines whose first non-blank
character is ``%`` are comments too (used in CONTACT's files to switch
points off). Three nested sections::

    header.begin  version = 1   type = 0|1 (0 rail, 1 wheel)   header.end
    spline.begin  key = value ...  point.begin  y z [weight] ...  point.end  spline.end

Keys of the ``spline`` section that change the points are applied in
Simpack's order: ``point.dist.min`` (drop points closer in y), ``shift.y``,
``shift.z``, ``rotate`` (angle in ``units.ang`` about the profile origin,
counter-clockwise in (y, z)), ``bound.y.min/max`` (drop points outside, if
min < max), ``bound.z.min/max`` (clip, if min < max), ``mirror.y``,
``mirror.z``, ``inversion`` (reverse order), and finally the length unit
``units.len.f`` (user length per metre: 1000 for mm). Without
``units.len.f`` the unit is taken from ``units.len`` ('mm'/'m') or, failing
that, guessed from the size (> 2 → mm, with a warning). ``approx.smooth`` is
stored in ``meta`` but not applied (pass ``smoothing=`` to :func:`read`).

Conventions assumed
-------------------
After the processing above, a Simpack profile has ``y`` towards the field
side and ``z`` **downward** (rail top / wheel tape circle at z = 0); the
reader negates z. The origin is kept (Simpack: rail head centre / tape
circle); use ``tape_circle=`` when a wheel file has another origin.
"""

from __future__ import annotations

import warnings

import numpy as np

from ..._atomic import atomic_open
from ...errors import ProfileError
from ..core import MIN_POINTS, Profile, ProfileWarning
from ._common import (
    POINT_DIST_MIN,
    kind_from_extension,
    make_profile,
    number,
    read_lines,
    resolve_kind,
)

__all__ = ["read_simpack", "write_simpack", "looks_like_simpack"]

_SECTIONS = ("header", "spline", "point")


def looks_like_simpack(lines: list[str]) -> bool:
    """True when the text has Simpack section markers."""
    for line in lines[:400]:
        s = line.split("!", 1)[0].strip().lower()
        if s in ("header.begin", "spline.begin", "point.begin"):
            return True
    return False


def _strip_comment(line: str) -> str:
    """Remove a ``!`` comment that is not inside single or double quotes."""
    quote = None
    for i, ch in enumerate(line):
        if quote:
            if ch == quote:
                quote = None
        elif ch in "'\"":
            quote = ch
        elif ch == "!":
            return line[:i]
    return line


def _value(raw: str, where: str):
    raw = raw.strip()
    if len(raw) >= 2 and raw[0] == raw[-1] and raw[0] in "'\"":
        return raw[1:-1]
    try:
        return number(raw, where, "value")
    except ProfileError:
        return raw


def parse_simpack(lines: list[str], name: str):
    """Parse the sections; return (header dict, spline dict, points (n, 2) in file units)."""
    stack: list[str] = []
    header: dict = {}
    spline: dict = {}
    pts: list[tuple[float, float]] = []
    point_line = None
    for lineno, raw in enumerate(lines, start=1):
        where = f"{name}, line {lineno}"
        s = _strip_comment(raw).strip()
        if not s or s.startswith("%"):
            continue
        low = s.lower()
        if low.endswith(".begin") or low.endswith(".end"):
            sect, _, mark = low.rpartition(".")
            if sect not in _SECTIONS:
                raise ProfileError(f"{where}: unknown section {s!r}")
            if mark == "begin":
                expected = {"header": [], "spline": [], "point": ["spline"]}[sect]
                if stack != expected:
                    raise ProfileError(f"{where}: section {sect!r} opened in the wrong place "
                                       f"(inside {'.'.join(stack) or 'nothing'})")
                stack.append(sect)
                if sect == "point":
                    point_line = lineno
            else:
                if not stack or stack[-1] != sect:
                    raise ProfileError(f"{where}: {s!r} without matching {sect}.begin")
                stack.pop()
            continue
        if "=" in s and stack and stack[-1] in ("header", "spline"):
            key, _, val = s.partition("=")
            key = key.strip().lower()
            if not key or " " in key:
                raise ProfileError(f"{where}: malformed keyword line {s[:60]!r}")
            (header if stack[-1] == "header" else spline)[key] = _value(val, where)
            continue
        if stack == ["spline", "point"]:
            toks = s.replace(",", " ").split()
            if len(toks) not in (2, 3):
                raise ProfileError(f"{where}: expected 'y z [weight]', got {s[:60]!r}")
            yv = number(toks[0], where, "y")
            zv = number(toks[1], where, "z")
            if len(toks) == 3:
                number(toks[2], where, "weight")
            pts.append((yv, zv))
            continue
        raise ProfileError(f"{where}: unexpected text {s[:60]!r} "
                           f"{'outside any section' if not stack else 'in ' + stack[-1]}")
    if stack:
        raise ProfileError(f"{name}: unterminated section {'.'.join(stack)!r} "
                           f"(missing {stack[-1]}.end)")
    if point_line is None:
        raise ProfileError(f"{name}: no 'point.begin' ... 'point.end' section with profile points")
    if len(pts) < MIN_POINTS:
        raise ProfileError(f"{name}, line {point_line}: point section holds {len(pts)} point(s), "
                           f"at least {MIN_POINTS} are needed")
    return header, spline, np.array(pts, dtype=float)


def _flag(opts, key, where):
    v = opts.get(key, 0)
    if isinstance(v, str) or v not in (0, 1, 0.0, 1.0):
        raise ProfileError(f"{where}: {key} must be 0 or 1, got {v!r}")
    return bool(v)


def _real(opts, key, where, default=0.0):
    v = opts.get(key, default)
    if isinstance(v, str):
        raise ProfileError(f"{where}: {key} must be a number, got {v!r}")
    return float(v)


def apply_spline_options(points: np.ndarray, opts: dict, name: str) -> tuple[np.ndarray, float]:
    """Apply the Simpack processing keys; return (points in file length unit, metres per unit)."""
    where = f"{name} (spline section)"
    p = points.copy()
    dmin = _real(opts, "point.dist.min", where)
    if dmin > 0.0:
        keep = [0]
        for i in range(1, len(p)):
            if abs(p[i, 0] - p[keep[-1], 0]) > dmin:
                keep.append(i)
        p = p[keep]
    p[:, 0] += _real(opts, "shift.y", where)
    p[:, 1] += _real(opts, "shift.z", where)
    ang_f = _real(opts, "units.ang.f", where, 1.0)
    if ang_f <= 0.0:
        raise ProfileError(f"{where}: units.ang.f must be > 0, got {ang_f!r}")
    rot = _real(opts, "rotate", where) / ang_f
    if rot != 0.0:
        c, s = np.cos(rot), np.sin(rot)
        p = np.c_[c * p[:, 0] - s * p[:, 1], s * p[:, 0] + c * p[:, 1]]
    ylo, yhi = _real(opts, "bound.y.min", where), _real(opts, "bound.y.max", where)
    if ylo < yhi:
        p = p[(p[:, 0] >= ylo) & (p[:, 0] <= yhi)]
    zlo, zhi = _real(opts, "bound.z.min", where), _real(opts, "bound.z.max", where)
    if zlo < zhi:
        p[:, 1] = np.clip(p[:, 1], zlo, zhi)
    if _flag(opts, "mirror.y", where):
        p[:, 0] = -p[:, 0]
    if _flag(opts, "mirror.z", where):
        p[:, 1] = -p[:, 1]
    if _flag(opts, "inversion", where):
        p = p[::-1]
    if len(p) < MIN_POINTS:
        raise ProfileError(f"{where}: fewer than {MIN_POINTS} points left after bound.y.min/max")
    if "units.len.f" in opts:
        f = _real(opts, "units.len.f", where)
        if f <= 0.0:
            raise ProfileError(f"{where}: units.len.f must be > 0, got {f!r}")
        scale = 1.0 / f
    elif str(opts.get("units.len", "")).strip().lower() in ("mm", "m", "cm"):
        scale = {"mm": 1e-3, "cm": 1e-2, "m": 1.0}[str(opts["units.len"]).strip().lower()]
    else:
        big = float(np.max(np.abs(p))) > 2.0
        scale = 1e-3 if big else 1.0
        warnings.warn(f"{name}: no length unit (units.len.f) given; assuming "
                      f"{'mm' if big else 'm'} from the size of the data", ProfileWarning,
                      stacklevel=3)
    return p, scale


def read_simpack(path, kind=None, *, smoothing=0.0, mirror_y=None, tape_circle=None,
                 point_dist_min=POINT_DIST_MIN, lenient=False) -> Profile:
    """Read a Simpack ``.prr``/``.prw`` profile (see the module docstring).

    Parameters
    ----------
    path : path-like
    kind : {"rail", "wheel", None}
        None: from ``header.type`` (0 rail, 1 wheel), else from the extension.
    smoothing : float
        Passed to :class:`Profile` [m].
    mirror_y : bool or None
        Mirror y after the file's own processing. None: no mirroring, except
        that a wheel whose flange lies at +y is mirrored automatically.
    tape_circle : float or None
        Move the origin to this y [m] (final frame) and z(0) to 0.
    point_dist_min : float
        Points closer than this [m] to the previous one are merged.

    Raises
    ------
    ProfileError
        Malformed file (message names file and line), too few points,
        non-single-valued contour.
    """
    name, lines = read_lines(path)
    header, spline, pts = parse_simpack(lines, name)
    guessed = None
    t = header.get("type")
    if t in (0, 1, 0.0, 1.0):
        guessed = "wheel" if t == 1 else "rail"
    elif t is not None:
        raise ProfileError(f"{name}: header type must be 0 (rail) or 1 (wheel), got {t!r}")
    if guessed is None:
        guessed = kind_from_extension(path)
    kind = resolve_kind(kind, guessed, name)
    p, scale = apply_spline_options(pts, spline, name)
    meta = {"header": header, "spline": {k: v for k, v in spline.items()},
            "z_down_in_file": True}
    label = str(spline.get("comment", "")) or name.rsplit("/", 1)[-1]
    return make_profile(p[:, 0] * scale, -p[:, 1] * scale, kind=kind,
                        name=name.rsplit("/", 1)[-1], source=name, fmt="simpack",
                        meta={**meta, "comment": label}, smoothing=smoothing,
                        point_dist_min=point_dist_min, mirror_y=bool(mirror_y),
                        wheel_flange_check=mirror_y is None, tape_circle=tape_circle,
                        lenient=bool(lenient))


def write_simpack(profile: Profile, path, *, comment: str | None = None) -> None:
    """Write ``profile`` as a Simpack file (mm, z downward, no processing keys).

    Reading the file back with :func:`read_simpack` returns the same points.
    """
    kind_flag = 1 if profile.kind == "wheel" else 0
    text = (comment if comment is not None else profile.name or "wheelrail profile")
    text = text.replace("'", " ").replace("!", " ").replace("\n", " ")
    out = ["! Simpack rail-wheel profile written by wheelrail",
           "! y towards the field side, z downward, lengths in mm",
           "header.begin",
           "  version = 1",
           f"  type    = {kind_flag}        ! 0=rail profile, 1=wheel profile",
           "header.end",
           "spline.begin",
           "  approx.smooth = 0.0",
           f"  comment       = '{text}'",
           "  units.len.f   = 1000.0       ! mm",
           "  units.ang.f   = 1.0          ! rad",
           "  point.begin"]
    out += [f"    {y * 1e3:+.9e}  {-z * 1e3:+.9e}" for y, z in zip(profile.y, profile.z)]
    out += ["  point.end", "spline.end", ""]

    with atomic_open(path, "w", encoding="utf-8", newline="\n") as fh:
        fh.write("\n".join(out))
