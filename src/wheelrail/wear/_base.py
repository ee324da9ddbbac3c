"""Base class and registry of the local wear laws.

A wear law is a frozen dataclass, subclass of :class:`WearLaw`, in its own
module of :mod:`wheelrail.wear`, decorated with
:func:`wheelrail.options.configured`; its options are fields declared once with
:func:`wheelrail.options.option` (as the contact methods). Defining such a
class registers it under its ``name``: :func:`wheelrail.wear.patch_wear`
accepts the name (the class with its defaults) or a configured instance,
``wr.wear.Archard(k=2e-4)``.

What an implementation must provide
-----------------------------------
``name`` : str
    The registry name (``"archard"``); ``references`` its sources.
``depth_rate(pressure, traction, slip, speed) -> ndarray``
    The local law: the wear depth removed from a surface point per metre it
    rolls through the contact, dz/dx [m/m], at every cell of a patch.
    ``pressure`` p [Pa], ``traction`` ‖τ‖ [Pa], ``slip`` ‖s‖ [-] (slip
    velocity divided by the rolling speed, zero in adhesion) are arrays of one
    shape; ``speed`` is the rolling speed V [m/s] (only the KTH map needs it).
    A surface point crossing a cell of length Δx slides ‖s‖ Δx over it, so
    its depth loss in the cell is ``depth_rate · Δx``; the worn volume per
    metre rolled is ``Σ depth_rate · ΔA``.
``per_patch`` : bool (class attribute)
    ``True`` for a law stated for a whole patch (USFD with
    ``application="patch"``): :func:`~wheelrail.wear.patch_wear` then calls
    ``patch_rate(Tgamma_over_A)`` [m/m] and distributes it (see there).
"""

from __future__ import annotations

from typing import ClassVar

import numpy as np

from ..errors import InputError
from ..options import Method, Registry

__all__ = ["WearLaw", "registry", "get", "wear_laws"]

_REGISTRY = Registry("wear")


class WearLaw(Method):
    """Abstract local wear law; see the module docstring for the contract."""

    family = "wear"
    _registry = _REGISTRY
    #: the law is stated for a whole patch (see the module docstring)
    per_patch: ClassVar[bool] = False
    #: the law needs the rolling speed (sliding velocity = ‖s‖ V)
    needs_speed: ClassVar[bool] = False

    def depth_rate(self, pressure, traction, slip, speed=None):  # pragma: no cover - abstract
        raise NotImplementedError

    @property
    def is_per_patch(self) -> bool:
        return bool(self.per_patch)


def get(spec, **options) -> WearLaw:
    """A configured wear law from a name, a class or an instance (options applied)."""
    return _REGISTRY.get(spec, WearLaw, options, argname="law")


def wear_laws() -> dict:
    """Registry name -> wear-law class."""
    return _REGISTRY.classes()


def _arrays(*values):
    out = []
    for v in values:
        a = np.asarray(v, dtype=float)
        if not np.all(np.isfinite(a)):
            raise InputError("wear law inputs must be finite (pressure, traction, slip)")
        out.append(a)
    return np.broadcast_arrays(*out)
