"""Wear and rolling-contact fatigue: local wear laws, wear on a patch, RCF indices.

Public names
------------
Wear laws (configured objects, options declared once as for the contact methods):
    :class:`Archard` (constant k), :class:`KTHMap` (Jendel's wear map),
    :class:`USFD` (Tγ/A law), :class:`Energy` (frictional work);
    :func:`wear_laws` (name -> class).
Wear on a patch:
    :func:`patch_wear` -> :class:`PatchWear` (depth per passage across the
    patch, worn volume per metre rolled, Tγ).
RCF:
    :func:`rcf` -> :class:`RCFResult` (Ekberg's FI_surf, shakedown-map
    position, Burstow's damage); :class:`Burstow`, :func:`surface_fatigue_index`.
Profile evolution:
    :func:`evolve` (model, :class:`Route` of :class:`RouteCase`, mileage, law) ->
    :class:`EvolveResult` with ``.dataset`` and ``.profiles``.
"""

from __future__ import annotations

from ._base import WearLaw, get, wear_laws
from .archard import Archard
from .energy import Energy
from .kth import KTHMap
from .loop import EvolveResult, Route, RouteCase, evolve
from .patch import PatchWear, deposit, patch_wear
from .fatigue import Burstow, RCFResult, rcf, surface_fatigue_index
from .usfd import USFD, usfd_rate

__all__ = ["WearLaw", "wear_laws", "get", "Archard", "KTHMap", "USFD", "Energy", "usfd_rate",
           "patch_wear", "PatchWear", "deposit", "rcf", "RCFResult", "Burstow",
           "surface_fatigue_index", "Route", "RouteCase", "evolve", "EvolveResult"]
