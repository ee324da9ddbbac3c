"""Wheel and rail profiles: the :class:`Profile` (z(y), SI, z up), standard profiles and file I/O.

Public names
------------
``Profile``
    Frozen cross-section z(y); conventions in :mod:`wheelrail.profiles.core`.
``load(name_or_path)``
    A standard profile generated from its geometric definition
    (``"S1002"``, ``"60E1"``/``"UIC60"``, ``"54E1"``/``"UIC54"``), or a
    profile file (then as :func:`read`).
``available()``
    Names accepted by :func:`load`.
``flange_dimensions(profile)``
    Flange height Sh, flange thickness Sd and qR of a wheel (EN 15313).
``read(path, kind=None)`` / ``write(profile, path, fmt=None)``
    Profile files (Simpack ``.prr``/``.prw``, MiniProf ``.ban``/``.whl``,
    two-column text/CSV), converted to the profile-frame convention.
"""

from __future__ import annotations

from pathlib import Path

from ..errors import ProfileError
from .core import Profile, ProfileWarning
from .flange import FlangeDimensions, flange_dimensions
from .io import read as _read
from .io import write as _write
from .standard import available as _available
from .standard import load as _load

__all__ = ["Profile", "ProfileWarning", "load", "available", "read", "write",
           "flange_dimensions", "FlangeDimensions"]


def load(name, kind: str | None = None, **options) -> Profile:
    """A standard profile by name, or a profile file by path.

    Parameters
    ----------
    name : str or os.PathLike
        A built-in name (case-insensitive, :func:`available`; options are
        passed to its generator, :mod:`wheelrail.profiles.standard`), or the
        path of a profile file (Simpack ``.prr``/``.prw``, MiniProf
        ``.ban``/``.whl``, text/CSV; read with :func:`read`, ``kind`` and
        ``options`` passed on).
    kind : {"wheel", "rail"}, optional
        For files: the body, when the format does not say it.

    Raises
    ------
    ProfileError
        Neither a built-in name nor an existing file: the message lists the
        names and the path looked for.
    """
    if isinstance(name, str) and name.strip().lower().replace("_", "").replace("-", "") in {
            n.lower().replace("_", "").replace("-", "") for n in _available()}:
        return _load(name, **options)
    path = Path(name).expanduser()
    if path.is_file():
        return _read(path, kind=kind, **options)
    raise ProfileError(f"{str(name)!r} is neither a built-in profile (available: "
                       f"{', '.join(_available())}) nor an existing profile file "
                       f"({path.resolve()})")


def available() -> list[str]:
    """Names (and aliases) of the built-in standard profiles."""

    return _available()


def read(path, kind: str | None = None, **options) -> Profile:
    """Read a profile file; see :func:`wheelrail.profiles.io.read`."""

    return _read(path, kind=kind, **options)


def write(profile: Profile, path, fmt: str | None = None, **options) -> None:
    """Write a profile file; see :func:`wheelrail.profiles.io.write`."""

    return _write(profile, path, fmt=fmt, **options)
