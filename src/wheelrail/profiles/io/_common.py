"""Helpers shared by the profile readers (private).

Every reader parses text with ``float()`` only — nothing from a file is ever
evaluated or executed — and reports problems as :class:`ProfileError` naming
the file and the line.
"""

from __future__ import annotations

import math
import os
import warnings
from pathlib import Path

import numpy as np

from ...errors import ProfileError
from ..core import KINDS, MAX_PLAUSIBLE_WIDTH, MIN_POINTS, Profile, ProfileWarning

#: Files larger than this are refused (a profile has at most a few 10^4 points).
MAX_FILE_BYTES = 20 * 1024 * 1024
#: Largest absolute number accepted in a profile file (any length unit).
MAX_ABS_VALUE = 1e7
#: Default minimum distance between consecutive points [m]; closer points are merged.
POINT_DIST_MIN = 1e-7
#: Readers refuse a contour when more than this fraction of the points must be dropped
#: to make it single-valued.
MAX_DROP_FRACTION = 0.5


def read_lines(path) -> tuple[str, list[str]]:
    """Return (display name, lines) of a text file; undecodable bytes are replaced."""
    p = Path(os.fspath(path))
    name = str(p)
    import stat

    try:
        st = p.stat()
    except OSError as exc:
        raise ProfileError(f"{name}: cannot read profile file ({exc.strerror or exc})") from exc
    if not stat.S_ISREG(st.st_mode):  # a FIFO blocks, /dev/zero never ends
        kind = ("a directory" if stat.S_ISDIR(st.st_mode) else "a FIFO (named pipe)"
                if stat.S_ISFIFO(st.st_mode) else "a device or socket")
        raise ProfileError(f"{name}: is {kind}; a profile file must be a regular file")
    size = st.st_size
    if size > MAX_FILE_BYTES:
        raise ProfileError(f"{name}: file of {size} bytes is too large for a profile")
    try:
        data = p.read_bytes()
    except OSError as exc:
        raise ProfileError(f"{name}: cannot read profile file ({exc.strerror or exc})") from exc
    if b"\x00" in data[:4096]:
        raise ProfileError(f"{name}: binary file (NUL bytes), not a profile text file")
    text = data.decode("utf-8", errors="replace")
    return name, text.splitlines()


def number(token: str, where: str, what: str = "value") -> float:
    """Parse one finite float (``float()`` only) or raise ProfileError at ``where``."""
    tok = token.strip()
    try:
        val = float(tok)
    except ValueError:
        raise ProfileError(f"{where}: {what} {tok[:40]!r} is not a number") from None
    if not math.isfinite(val):
        raise ProfileError(f"{where}: {what} {tok[:40]!r} is not finite")
    if abs(val) > MAX_ABS_VALUE:
        raise ProfileError(f"{where}: {what} {tok[:40]!r} is implausibly large for a profile")
    return val


def append_row(rows: list, toks: list, ncol: int, where: str, hint: str = "") -> None:
    """Append one data row of ``ncol`` numbers to ``rows`` (ProfileError naming the line)."""
    if len(toks) != ncol:
        raise ProfileError(f"{where}: row has {len(toks)} columns, expected {ncol}{hint}")
    rows.append([number(t, where, "column value") for t in toks])
    if isinstance(rows, Rows):
        rows.lines.append(int(where.rsplit("line ", 1)[-1]) if "line " in where else 0)


class Rows(list):
    """Data rows of a profile file with the file line of each (``lines``)."""

    def __init__(self):
        super().__init__()
        self.lines: list[int] = []


def check_row_count(rows: list, name: str) -> None:
    """A profile needs at least :data:`~wheelrail.profiles.core.MIN_POINTS` points."""
    if len(rows) < MIN_POINTS:
        raise ProfileError(f"{name}: {len(rows)} data row(s) found, at least {MIN_POINTS} "
                           f"profile points are needed")


def resolve_kind(kind, guessed, name: str) -> str:
    """Explicit kind > guessed kind; raise if neither is known."""
    if kind is not None:
        if kind not in KINDS:
            raise ProfileError(f"kind must be one of {KINDS} or None, got {kind!r}")
        return kind
    if guessed in KINDS:
        return guessed
    raise ProfileError(f"{name}: cannot tell whether this is a wheel or a rail profile; "
                       f"pass kind='wheel' or kind='rail'")


def kind_from_extension(path) -> str | None:
    ext = Path(os.fspath(path)).suffix.lower()
    return {".prw": "wheel", ".whl": "wheel", ".whe": "wheel",
            ".prr": "rail", ".ban": "rail", ".rai": "rail"}.get(ext)


def chord_deviation_is_z_down(y: np.ndarray, z: np.ndarray, kind: str) -> bool:
    """Guess whether ``z`` points downward, from the shape of the profile.

    A rail head (z up) lies *above* the chord through its end points (the
    crown); a wheel (z up) has its largest excursion *below* the chord (the
    flange tip). The test compares the largest positive and negative
    deviations from that chord.
    """
    chord = z[0] + (z[-1] - z[0]) * (y - y[0]) / (y[-1] - y[0]) if y[-1] != y[0] else z[0]
    d = z - chord
    up, down = float(np.max(d)), float(-np.min(d))
    if kind == "rail":
        return down > up
    return up > down


def single_valued(y: np.ndarray, z: np.ndarray, name: str, *, point_dist_min: float):
    """Keep the part of a contour that is single-valued as z(y).

    Points are taken in file order after orienting the contour so that ``y``
    increases overall (``y[-1] > y[0]``); points closer than
    ``point_dist_min`` to the previous kept point are merged, and a point is
    kept only if its ``y`` exceeds that of the last kept point. This removes
    closed-contour parts, vertical faces (flange back, rim face), overhangs
    and foldbacks (the contour seen from the contact side is kept). More
    than ``MAX_DROP_FRACTION`` dropped points is an error.

    Returns
    -------
    y, z : ndarray
    info : dict
        ``n_close`` merged near-duplicates, ``n_foldback`` dropped points.
    """
    n = y.size
    if n < 2:
        raise ProfileError(f"{name}: needs at least 4 profile points, found {n}")
    index = np.arange(n)
    if y[-1] < y[0]:
        y, z, index = y[::-1], z[::-1], index[::-1]
    keep = np.zeros(n, dtype=bool)
    keep[0] = True
    ly, lz = y[0], z[0]
    n_close = n_back = 0
    for i in range(1, n):
        if math.hypot(y[i] - ly, z[i] - lz) < point_dist_min:
            n_close += 1
            continue
        if y[i] <= ly:
            n_back += 1
            continue
        keep[i] = True
        ly, lz = y[i], z[i]
    if n_back > MAX_DROP_FRACTION * n:
        raise ProfileError(
            f"{name}: the contour is not single-valued as z(y) — {n_back} of {n} points would "
            f"have to be dropped (closed contour or zig-zag data?); pass only the running "
            f"surface (tread/flange or rail head)")
    return y[keep], z[keep], {"n_close": n_close, "n_foldback": n_back, "_index": index[keep]}


#: A profile narrower than this [m] was almost certainly read in the wrong length unit.
MIN_PLAUSIBLE_WIDTH = 0.005
#: An isolated point further than this [m] from the mean of its neighbours may be a spike.
SPIKE_HEIGHT = 0.002


def check_damage(y, z, source: str) -> None:
    """Detect damaged profile data (values in the wrong unit, spikes) with the likely cause.

    * width below :data:`MIN_PLAUSIBLE_WIDTH` (5 mm): values in metres in a
      file read as millimetres (e.g. 0.07 mm wide instead of 70 mm);
    * a spike: one point more than :data:`SPIKE_HEIGHT` (2 mm) above or below
      the mean of its two neighbours, while the neighbours differ from each
      other by less than a fifth of that — a single bad reading; a real
      vertical face (flange back, gauge face) changes monotonically.

    Raises
    ------
    ProfileError
        Naming the source, the values and the probable cause.
    """
    if y.size >= 2 and 0.0 < np.ptp(y) < MIN_PLAUSIBLE_WIDTH and np.ptp(z) < MIN_PLAUSIBLE_WIDTH:
        raise ProfileError(
            f"{source}: profile is only {np.ptp(y) * 1e3:.3g} mm wide and {np.ptp(z) * 1e3:.3g} mm "
            f"high — values in metres in a file read as millimetres? (Simpack: set "
            f"units.len.f = 1; text: units='m')")
    if y.size >= 3:
        mid = 0.5 * (z[:-2] + z[2:])
        dev = z[1:-1] - mid
        step = np.abs(z[2:] - z[:-2])
        spike = np.flatnonzero((np.abs(dev) > SPIKE_HEIGHT) & (np.abs(dev) > 5.0 * step))
        if spike.size:
            i = int(spike[0]) + 1
            raise ProfileError(
                f"{source}: point {i + 1} (y = {y[i] * 1e3:.3f} mm, z = {z[i] * 1e3:.3f} mm) is a "
                f"spike {abs(dev[i - 1]) * 1e3:.3g} mm {'above' if dev[i - 1] > 0 else 'below'} its "
                f"neighbours — a damaged measurement? Remove or correct that point"
                + (f" ({spike.size} such points)" if spike.size > 1 else ""))


#: A wheel whose highest point rises more than this [m] above its median (and that has
#: no flange below) has its flange pointing up: z down in the file read as z up.
FLANGE_UP_HEIGHT = 0.010
#: A gap between neighbouring points wider than this [m] and GAP_FACTOR × the median
#: spacing is reported (points missing from a measurement or a cut file).
GAP_WIDTH = 0.003
GAP_FACTOR = 10.0
#: A wheel whose lowest point is an end of the profile this far [m] below the tread median
#: has its flange cut off.
FLANGE_CUT_DEPTH = 0.005
#: A vertical step within this [m] of either end of a profile is its side face, not a wall.
END_WIDTH = 0.002


def check_orientation(y, z, kind: str, source: str) -> None:
    """Refuse a wheel whose flange points up (z down read as z up).

    With z up a wheel's flange is its lowest part, 25–35 mm below the tread; a
    profile whose highest point lies more than :data:`FLANGE_UP_HEIGHT` above
    the median with nothing comparable below is the same wheel with z
    pointing down. (A rail head profile has no such signature: its gauge and
    field faces drop as far as a flange would.)
    """
    if y.size < 4:
        return
    med = float(np.median(z))
    up, down = float(np.max(z)) - med, med - float(np.min(z))
    hint = ("z pointing down in the file? Pass z_down=True (text files: a '# z: down' "
            "comment) or negate z")
    if kind == "wheel" and up > FLANGE_UP_HEIGHT and down < 0.3 * up:
        j = int(np.argmax(z))
        raise ProfileError(f"{source}: the wheel's flange points up (its tip at y = "
                           f"{y[j] * 1e3:.1f} mm rises {up * 1e3:.1f} mm above the tread; with z "
                           f"up a flange hangs below the tread) — {hint}")


class _Where:
    """Names a stored point by its file line (when known) or its number in the file."""

    def __init__(self, source, lines, index):
        self.source, self.lines, self.index = source, lines, index

    def __call__(self, i: int) -> str:
        j = int(self.index[i]) if self.index is not None else int(i)
        if self.lines is not None and j < len(self.lines) and self.lines[j] > 0:
            return f"{self.source}, line {self.lines[j]}"
        return f"{self.source}, point {j + 1}"

    def span(self, i: int) -> str:
        """The stored points ``i`` and ``i + 1`` (file lines or point numbers)."""
        a, b = (self(k).rsplit(", ", 1)[-1] for k in (i, i + 1))
        kind, a = a.split(" ", 1)
        return f"{self.source}, {kind}s {a}–{b.split(' ', 1)[-1]}"


def _refuse_or_warn(message: str, lenient: bool) -> None:
    if lenient:
        warnings.warn(message + " (accepted: lenient)", ProfileWarning, stacklevel=5)
        return
    raise ProfileError(message + "; if the file is right, read it with lenient=True "
                       "(command line: --lenient)")


def check_gaps(y, z, kind: str, source: str, *, where=None, lenient: bool = False) -> None:
    """Refuse a gap or a vertical wall between neighbouring points (a damaged measurement).

    The step between neighbouring stored points (arc length) is compared with
    the median step: more than :data:`GAP_WIDTH` and :data:`GAP_FACTOR` × the
    median is a gap (mostly along y: points missing from a measurement or a
    cut file) or a wall (mostly along z: a vertical step in the surface).
    With ``lenient`` a warning (:class:`ProfileWarning`) instead.
    """
    y = np.asarray(y, dtype=float)
    z = np.asarray(z, dtype=float)
    if y.size < 8:
        return
    where = where or _Where(source, None, None)
    dy, dz = np.diff(y), np.diff(z)
    d = np.hypot(dy, dz)
    # a steep face at an end (a rail's gauge or field face, a wheel's flange back, whose
    # hidden points the single-valued part dropped) is not a wall in the running surface
    ends = (np.abs(dz) > np.abs(dy)) & ((y[1:] - y[0] < END_WIDTH) | (y[-1] - y[:-1] < END_WIDTH))
    d = np.where(ends, 0.0, d)
    med = float(np.median(d[d > 0])) if np.any(d > 0) else 0.0
    i = int(np.argmax(d))
    if not (med > 0 and d[i] > GAP_WIDTH and d[i] > GAP_FACTOR * med):
        return
    if abs(dz[i]) > abs(dy[i]):
        _refuse_or_warn(
            f"{where.span(i)}: a vertical wall in the {kind} profile — z jumps "
            f"{dz[i] * 1e3:+.1f} mm over {abs(dy[i]) * 1e3:.2f} mm of y at y = "
            f"{y[i] * 1e3:.2f} mm ({d[i] / med:.0f} × the median spacing of {med * 1e3:.2g} mm): "
            "a damaged or spliced measurement?", lenient)
    else:
        _refuse_or_warn(
            f"{where.span(i)}: no {kind} profile points between y = {y[i] * 1e3:.2f} mm and "
            f"{y[i + 1] * 1e3:.2f} mm (a gap of {d[i] * 1e3:.1f} mm, {d[i] / med:.0f} × the "
            f"median spacing of {med * 1e3:.2g} mm): points missing from the measurement?",
            lenient)


def check_shape(y, z, kind: str, source: str, *, where, lenient: bool = False,
                fmt: str = "") -> None:
    """Refuse a profile of the wrong shape: head down, flange cut off, flange at +y.

    Called on the single-valued points in the profile frame (y towards the
    field side, z up):

    * a rail whose largest excursion from the chord through its ends lies
      below it: the head points down (z flipped);
    * a wheel whose lowest point is an end point more than
      :data:`FLANGE_CUT_DEPTH` below the tread: the flange is cut off (its tip
      and back are missing);
    * a wheel whose flange tip lies on the +y side (the convention puts it at
      negative y): mirrored y.
    """
    if y.size < 8:
        return
    if kind == "rail" and fmt != "miniprof" and np.ptp(z) > 0.002 \
            and chord_deviation_is_z_down(y, z, "rail"):
        _refuse_or_warn(f"{source}: the rail head points down (the profile lies below the "
                        "chord through its ends; with z up a rail head is a crown above it) — "
                        "z pointing down in the file? Pass z_down=True (text files: a "
                        "'# z: down' comment) or negate z", lenient)
        return
    if kind != "wheel":
        return
    i = int(np.argmin(z))
    depth = float(np.median(z) - z[i])
    if depth > FLANGE_CUT_DEPTH and (i <= 1 or i >= y.size - 2):
        _refuse_or_warn(f"{where(i)}: the wheel's flange is cut off — the profile ends at its "
                        f"lowest point (y = {y[i] * 1e3:.1f} mm, {depth * 1e3:.1f} mm below the "
                        "tread) on the flange's flank; a wheel profile runs over the flange "
                        "tip to the flange back", lenient)
        return
    frac = (y[i] - y[0]) / (y[-1] - y[0])
    if frac > 0.6 and depth > 0.010:
        _refuse_or_warn(f"{source}: the wheel's flange lies at +y (tip at y = "
                        f"{y[i] * 1e3:.1f} mm); in the profile frame y points away from the "
                        "flange, towards the field side — pass mirror_y=True", lenient)


def check_swapped(y, z, kind: str, source: str, *, lenient: bool = False) -> None:
    """Refuse a profile higher than it is wide: y and z columns swapped."""
    w, h = float(np.ptp(y)), float(np.ptp(z))
    if y.size >= 4 and h > 1.2 * w:
        _refuse_or_warn(f"{source}: the {kind} profile is {h * 1e3:.1f} mm high and only "
                        f"{w * 1e3:.1f} mm wide — the y and z columns swapped? (a wheel or rail "
                        "profile is wider than high, with z(y) single-valued)", lenient)


def make_profile(y_m, z_up_m, *, kind, name, source, fmt, meta, smoothing=0.0,
                 point_dist_min=POINT_DIST_MIN, mirror_y=False, wheel_flange_check=True,
                 tape_circle=None, auto_tape_circle=True, lines=None, lenient=False):
    """Common tail of all readers: orientation, single-valued part, origin, Profile.

    Parameters
    ----------
    y_m, z_up_m : ndarray
        Coordinates already converted to metres and to z up.
    mirror_y : bool
        Mirror y (after which y must point to the field side).
    wheel_flange_check : bool
        For wheels, mirror automatically when the flange tip lies on the +y
        side (the convention puts the flange at negative y).
    tape_circle : float or None
        y [m] of the tape circle in the (oriented) file frame: the origin is
        moved there and z shifted so that z(0) = 0.
    auto_tape_circle : bool
        Wheels without ``tape_circle``: when every y is ≥ 0 and the flange
        tip lies within 35 mm of y = 0 (origin on the flange back), move the
        origin to the tape circle 70 mm from it, with a ProfileWarning.

    Raises
    ------
    ProfileError
        See :func:`check_damage` (values in the wrong unit, spikes).
    """
    y = np.asarray(y_m, dtype=float)
    z = np.asarray(z_up_m, dtype=float)
    meta = dict(meta)
    meta.update(source=source, format=fmt)
    if y.size and (np.ptp(y) > MAX_PLAUSIBLE_WIDTH or np.ptp(z) > MAX_PLAUSIBLE_WIDTH):
        raise ProfileError(f"{source}: profile of {np.ptp(y):.4g} m x {np.ptp(z):.4g} m is "
                           f"implausible — wrong length unit? (give units='mm' or 'm')")
    check_damage(y, z, source)
    check_swapped(y, z, kind, source, lenient=lenient)
    if mirror_y:
        y = -y
    y, z, info = single_valued(y, z, source, point_dist_min=point_dist_min)
    where = _Where(source, lines, info.pop("_index"))
    meta.update(info)
    if info["n_foldback"]:
        warnings.warn(f"{source}: dropped {info['n_foldback']} point(s) to keep the "
                      f"single-valued part z(y) (vertical faces, overhangs or foldbacks)",
                      ProfileWarning, stacklevel=4)
    if fmt != "miniprof":  # MiniProf's reader detects the z direction from the shape itself
        check_orientation(y, z, kind, source)
    check_gaps(y, z, kind, source, where=where, lenient=lenient)
    if kind == "wheel" and wheel_flange_check and y.size >= 4 and np.ptp(y) > 0:
        i = int(np.argmin(z))
        frac = (y[i] - y[0]) / (y[-1] - y[0])
        depth = float(np.median(z) - z[i])
        if frac > 0.6 and depth > 0.010:  # flange found on the +y side: mirror
            y, z = -y[::-1], z[::-1]
            where.index = where.index[::-1]
            meta["auto_mirrored"] = True
    check_shape(y, z, kind, source, where=where, lenient=lenient, fmt=fmt)
    if (tape_circle is None and kind == "wheel" and auto_tape_circle and y.size >= 4
            and y[0] >= -0.001 and y[-1] > 0.080 and y[int(np.argmin(z))] < 0.035):
        # all y >= 0 with the flange tip near y = 0: the origin is on the back of the flange
        # (as in MiniProf wheels and some Simpack files); the tape circle is 70 mm from it
        tape_circle = 0.070
        warnings.warn(f"{source}: wheel profile starts at the flange back (all y >= 0, flange "
                      f"tip at y = {y[int(np.argmin(z))] * 1e3:.1f} mm); the tape circle is "
                      f"assumed 70 mm from it (pass tape_circle= to override)",
                      ProfileWarning, stacklevel=4)
        meta["tape_circle_assumed"] = 0.070
    if tape_circle is not None:
        yt = float(tape_circle)
        if not (y[0] <= yt <= y[-1]):
            raise ProfileError(f"{source}: tape circle y = {yt} m lies outside the profile "
                               f"[{y[0]:.4g}, {y[-1]:.4g}] m")
        zt = float(np.interp(yt, y, z))
        y, z = y - yt, z - zt
        meta["origin_shift"] = (yt, zt)
    try:
        return Profile(y, z, kind=kind, name=name, smoothing=smoothing, meta=meta)
    except ProfileError as exc:
        raise ProfileError(f"{source}: {exc}") from None
