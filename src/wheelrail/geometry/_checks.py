"""Input checks shared by the geometry package (private)."""

from __future__ import annotations

from ..errors import InputError, ProfileError

__all__ = ["SIDES", "check_side", "check_profile"]

SIDES = ("left", "right")


def check_side(side) -> str:
    """Return ``side`` if it is "left" or "right", else raise InputError naming it."""
    if side not in SIDES:
        raise InputError(f"side must be 'left' or 'right', got {side!r}")
    return side


def check_profile(name: str, profile, kind: str) -> None:
    """Raise unless ``profile`` is a profile (duck-typed) of ``kind`` ("wheel" or "rail")."""
    if not (hasattr(profile, "y_min") and callable(profile)):
        raise InputError(f"{name} must be a wheelrail.profiles.Profile, "
                         f"got {type(profile).__name__}")
    got = getattr(profile, "kind", kind)
    if got != kind:
        raise ProfileError(f"{name} must be a {kind} profile, got a {got!r} profile "
                           f"{getattr(profile, 'name', '')!r}")
