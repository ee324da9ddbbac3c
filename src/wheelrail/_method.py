"""Shared base of the method families (normal and tangential): name, references, options."""

from __future__ import annotations

from .errors import InputError

__all__ = ["Method"]


class Method:
    """A named method with documented keyword options (see the family base classes)."""

    name: str = "abstract"
    references: tuple = ()
    options: dict = {}
    #: Word put before "method" in messages ("normal ", "" for creep-force laws).
    family: str = ""

    def check_options(self, options: dict) -> dict:
        """Merge ``options`` into the defaults, rejecting unknown keywords and bad values.

        Values are checked with the table of :mod:`wheelrail._options` (before any
        solve; nothing is clamped).
        """
        unknown = set(options) - set(self.options)
        if unknown:
            allowed = ", ".join(sorted(self.options)) or "none"
            raise InputError(f"{self.family}method {self.name!r} does not accept option(s) "
                             f"{', '.join(sorted(unknown))}; allowed: {allowed}")
        merged = dict(self.options)
        merged.update(options)
        from ._options import validate

        validate(self.name, merged)
        return merged

    def __repr__(self) -> str:
        return f"{type(self).__name__}()"
