"""Profile file readers and writers, chosen by sniffed content and extension.

========  =======================  ===========================================
format    extensions               module
========  =======================  ===========================================
simpack   ``.prr`` ``.prw``        :mod:`~wheelrail.profiles.io.simpack`
miniprof  ``.ban`` ``.whl``        :mod:`~wheelrail.profiles.io.miniprof`
text      ``.csv`` ``.txt`` ...    :mod:`~wheelrail.profiles.io.text`
========  =======================  ===========================================

:func:`read` looks at the content first (Simpack section markers, MiniProf
``MINIPROF`` line or ``ColumnDef=``/``XYPoints=`` keys), then at the
extension; anything else is read as text. The wheel/rail kind comes from the
``kind`` argument, then the file (Simpack ``header.type``, ``# kind:``), then
the extension (``.prw``/``.whl`` wheel, ``.prr``/``.ban`` rail). Every reader
converts to the profile-frame convention of :mod:`wheelrail.profiles.core`
(SI, y towards the field side, z up) and keeps only the single-valued part
z(y) of the contour. Malformed files raise
:class:`~wheelrail.errors.ProfileError` naming the file and the line;
nothing in a file is evaluated.
"""

from __future__ import annotations

import inspect
import os
from pathlib import Path

from ...errors import ProfileError
from ..core import Profile
from ._common import kind_from_extension, read_lines
from .miniprof import looks_like_miniprof, read_miniprof
from .simpack import looks_like_simpack, parse_simpack, read_simpack, write_simpack
from .text import parse_text, read_text, write_text

__all__ = ["read", "write", "formats", "detect_format", "declared_kind", "READERS", "WRITERS",
           "read_simpack", "write_simpack", "read_miniprof", "read_text", "write_text"]

#: format name -> (reader, extensions)
READERS = {
    "simpack": (read_simpack, (".prr", ".prw")),
    "miniprof": (read_miniprof, (".ban", ".whl")),
    "text": (read_text, (".csv", ".txt", ".dat", ".xy")),
}
#: format name -> (writer, extensions)
WRITERS = {
    "simpack": (write_simpack, (".prr", ".prw")),
    "text": (write_text, (".csv", ".txt", ".dat", ".xy")),
}


def formats() -> dict[str, tuple[str, ...]]:
    """Readable formats and their extensions."""
    return {k: v[1] for k, v in READERS.items()}


def detect_format(path) -> str:
    """Format name of a file from its content, else its extension, else ``"text"``."""
    _, lines = read_lines(path)
    if looks_like_simpack(lines):
        return "simpack"
    if looks_like_miniprof(lines):
        return "miniprof"
    ext = Path(os.fspath(path)).suffix.lower()
    for fmt, (_, exts) in READERS.items():
        if ext in exts and fmt != "simpack":  # a .prr without sections is not Simpack
            return fmt
    return "text"


def declared_kind(path) -> tuple[str | None, str]:
    """The body a profile file says it holds, without reading its points.

    Returns
    -------
    kind : {"wheel", "rail", None}
        From the Simpack header ``type`` (0 rail, 1 wheel), a text file's ``# kind:``
        comment, else the extension (``.prw``/``.whl`` wheel, ``.prr``/``.ban`` rail);
        None when neither says.
    why : str
        Where the kind was found (``"its Simpack header type = 0"``, ``"its '# kind:
        rail' comment"``, ``"its extension .prr"``), for messages; ``""`` for None.

    Raises
    ------
    ProfileError
        Unreadable file, or a malformed Simpack header.
    """
    name, lines = read_lines(path)
    if looks_like_simpack(lines):
        t = parse_simpack(lines, name)[0].get("type")
        if t in (0, 1):
            return ("wheel" if t == 1 else "rail"), f"its Simpack header type = {int(t)}"
    elif not looks_like_miniprof(lines):
        try:
            k = parse_text(lines, name)[0].get("kind", "").strip().lower()
        except ProfileError:  # damaged data: reading the file will say what is wrong
            k = ""
        if k in ("wheel", "rail"):
            return k, f"its '# kind: {k}' comment"
    k = kind_from_extension(path)
    if k is not None:
        return k, f"its extension {Path(os.fspath(path)).suffix.lower()}"
    return None, ""


def read(path, kind: str | None = None, *, fmt: str | None = None, **options) -> Profile:
    """Read a wheel or rail profile file.

    Parameters
    ----------
    path : path-like
    kind : {"wheel", "rail", None}
        None: from the file or its extension (see the module docstring).
    fmt : {"simpack", "miniprof", "text", None}
        None: detected.
    **options
        Passed to the reader: ``smoothing`` [m], ``mirror_y``, ``tape_circle``
        [m], ``point_dist_min`` [m]; MiniProf/text also ``z_down``; text also
        ``units``.

    Returns
    -------
    Profile
        In SI units and the profile-frame convention; ``meta["source"]``,
        ``meta["format"]`` and what was repaired.

    Raises
    ------
    ProfileError
        Unreadable or malformed file, unknown format or option.
    """
    if fmt is None:
        fmt = detect_format(path)
    if fmt not in READERS:
        raise ProfileError(f"unknown profile format {fmt!r}; known: {sorted(READERS)}")
    reader = READERS[fmt][0]
    try:
        inspect.signature(reader).bind(path, kind, **options)
    except TypeError as exc:  # unknown keyword for this reader
        raise ProfileError(f"{path}: invalid option for the {fmt} reader ({exc})") from None
    return reader(path, kind, **options)


def write(profile: Profile, path, fmt: str | None = None, **options) -> None:
    """Write ``profile`` to ``path`` (format from ``fmt`` or the extension; default text).

    Simpack files are written in mm with z downward, text files in the
    wheelrail frame (z up) with ``# kind/units/z/name`` comments; both read
    back to the same points with :func:`read`.
    """
    if not isinstance(profile, Profile):
        raise ProfileError(f"write expects a Profile, got {type(profile).__name__}")
    if fmt is None:
        ext = Path(os.fspath(path)).suffix.lower()
        fmt = next((f for f, (_, exts) in WRITERS.items() if ext in exts), "text")
    if fmt not in WRITERS:
        raise ProfileError(f"no writer for format {fmt!r}; writable: {sorted(WRITERS)}")
    WRITERS[fmt][0](profile, path, **options)
