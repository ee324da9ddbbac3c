"""Exceptions raised by wheelrail.

Every error names the offending value so that a user can fix the input without
reading a traceback from deep inside numpy.
"""

__all__ = [
    "WheelrailError",
    "InputError",
    "OptionError",
    "ConvergenceError",
    "NoContactError",
    "ProfileError",
    "CaseFileError",
]


import re

_NUMPY_SCALAR = re.compile(r"np\.(?:float|int|uint|complex|bool_|str_)\w*\(([^()]*)\)")


def tidy(text: str) -> str:
    """``np.float64(0.5)`` → ``0.5`` in a message (NumPy ≥ 2 scalar reprs)."""
    return _NUMPY_SCALAR.sub(r"\1", text)


class WheelrailError(Exception):
    """Base class of every error raised by wheelrail.

    The message is shown without NumPy scalar wrappers (``np.float64(…)``).
    """

    def __str__(self):
        return tidy(super().__str__())


class InputError(WheelrailError, ValueError):
    """An argument has a value outside its valid range (negative load, mu <= 0, NaN, ...)."""


class OptionError(InputError):
    """A method option is unknown or has a bad value.

    Attributes
    ----------
    method : str
        Registry name of the method.
    option : str or None
        The option (None for a check of a combination of options).
    reason : str
        The message without the method's name (what case files show after
        the file, table and key).
    """

    def __init__(self, message, *, method="", option=None, reason=""):
        super().__init__(message)
        self.method = method
        self.option = option
        self.reason = reason or message


class ConvergenceError(WheelrailError, RuntimeError):
    """An iterative solver did not reach its tolerance within the allowed iterations."""


class NoContactError(WheelrailError, ValueError):
    """No contact was found (the bodies are separated everywhere)."""


class ProfileError(WheelrailError, ValueError):
    """A profile or profile file is unreadable or geometrically invalid."""


class CaseFileError(WheelrailError, ValueError):
    """A case file is malformed or holds an invalid value."""
