"""Exceptions raised by wheelrail.

Every error names the offending value so that a user can fix the input without
reading a traceback from deep inside numpy.
"""

__all__ = [
    "WheelrailError",
    "InputError",
    "ConvergenceError",
    "NoContactError",
    "ProfileError",
    "CaseFileError",
]


class WheelrailError(Exception):
    """Base class of every error raised by wheelrail."""


class InputError(WheelrailError, ValueError):
    """An argument has a value outside its valid range (negative load, mu <= 0, NaN, ...)."""


class ConvergenceError(WheelrailError, RuntimeError):
    """An iterative solver did not reach its tolerance within the allowed iterations."""


class NoContactError(WheelrailError, ValueError):
    """No contact was found (the bodies are separated everywhere)."""


class ProfileError(WheelrailError, ValueError):
    """A profile or profile file is unreadable or geometrically invalid."""


class CaseFileError(WheelrailError, ValueError):
    """A case file is malformed or holds an invalid value."""
