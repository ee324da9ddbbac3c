"""Contact drivers, one layer above the methods and kernels.

* :class:`ContactPatch` (:mod:`~wheelrail.contact.patch`) — the patch every
  tangential method reads, made by every normal method;
* :func:`solve_gap` (:mod:`~wheelrail.contact.coupled`) — normal + tangential
  boundary-element solve on a grid (Johnson's / Panagiotopoulos' process);
* :func:`solve_gap_auto`, :func:`potential_contact_grid`,
  :func:`contact_patches` (:mod:`~wheelrail.contact.window`) — the window
  chosen from an arbitrary gap;
* :class:`WheelRailPosition`, :func:`solve_wheelrail`, :func:`wheelset_sweep`
  (:mod:`~wheelrail.contact.wheelrail`, :mod:`~wheelrail.contact.sweep`) — the
  wheel–rail contact module: patches and forces of a wheelset on a track.

Names are resolved on first access, so that the normal methods can import
:mod:`wheelrail.contact.patch` without importing the drivers that use them.
"""

from __future__ import annotations

import importlib

_NAMES = {
    "ContactPatch": "patch", "ContactFrame": "patch",
    "GapSolution": "coupled", "solve_gap": "coupled",
    "contact_patches": "window", "potential_contact_grid": "window", "solve_gap_auto": "window",
    "WheelRailPosition": "wheelrail", "solve_wheelrail": "wheelrail",
    "wheelset_sweep": "sweep",
}

__all__ = list(_NAMES)


def __getattr__(name):
    if name in _NAMES:
        value = getattr(importlib.import_module(f"{__name__}.{_NAMES[name]}"), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
