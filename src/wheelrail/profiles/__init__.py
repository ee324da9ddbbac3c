"""Wheel and rail profiles: the :class:`Profile` (z(y), SI, z up), standard profiles and file I/O.

Public names
------------
``Profile``
    Frozen cross-section z(y); conventions in :mod:`wheelrail.profiles.core`.
``load(name)``
    A standard profile generated from its geometric definition
    (``"S1002"``, ``"60E1"``/``"UIC60"``, ``"54E1"``/``"UIC54"``).
``available()``
    Names accepted by :func:`load`.
``read(path, kind=None)`` / ``write(profile, path, fmt=None)``
    Profile files (Simpack ``.prr``/``.prw``, MiniProf ``.ban``/``.whl``,
    two-column text/CSV), converted to the profile-frame convention.
"""

from __future__ import annotations

from .core import Profile, ProfileWarning
from .io import read as _read
from .io import write as _write
from .standard import available as _available
from .standard import load as _load

__all__ = ["Profile", "ProfileWarning", "load", "available", "read", "write"]


def load(name: str, **options) -> Profile:
    """Standard profile by name (case-insensitive); see :func:`wheelrail.profiles.standard.load`."""

    return _load(name, **options)


def available() -> list[str]:
    """Names (and aliases) of the built-in standard profiles."""

    return _available()


def read(path, kind: str | None = None, **options) -> Profile:
    """Read a profile file; see :func:`wheelrail.profiles.io.read`."""

    return _read(path, kind=kind, **options)


def write(profile: Profile, path, fmt: str | None = None, **options) -> None:
    """Write a profile file; see :func:`wheelrail.profiles.io.write`."""

    return _write(profile, path, fmt=fmt, **options)
