"""The transient-rolling case (``[transient]``), run with :func:`wheelrail.transient_rolling`."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import Any, Mapping

from ..materials import MaterialPair
from ..transient import transient_rolling
from .contact import ContactSpec

__all__ = ["TransientCase"]

@dataclass(frozen=True)
class TransientCase:
    """A validated transient-rolling case (``[transient]`` table).

    Attributes
    ----------
    materials : MaterialPair
    contact : ContactSpec
        The Hertzian contact: surfaces, and the grid (sized on its load).
    mu : float
    settings : Mapping
        Keyword arguments of :func:`wheelrail.transient_rolling` (SI units);
        load and creepage histories are
        :class:`~wheelrail.transient.loads.TravelFunction` objects.
    source : str
    """

    materials: MaterialPair
    contact: ContactSpec
    mu: float
    settings: Mapping[str, Any]
    source: str = "<dict>"

    @cached_property
    def hertz_contact(self):
        return self.contact.hertz(self.materials)

    def run(self, progress=False):
        """Solve with :func:`wheelrail.transient_rolling`; returns its ``TransientResult``."""

        return transient_rolling(self.hertz_contact, mu=self.mu, progress=progress,
                                 **dict(self.settings))

    def describe(self) -> dict:
        """Plain description (strings and numbers) of the settings, for summaries."""
        out = {}
        for k, v in self.settings.items():
            if k == "creepage":
                for name, f in zip(("xi", "eta", "phi"), v):
                    if f is not None:
                        out[name] = f.describe() if hasattr(f, "describe") else f
            else:
                out[k] = v.describe() if hasattr(v, "describe") else v
        return out


