"""Contact drivers, one layer above the methods: the wheel–rail contact module and windows.

* :class:`WheelRailPosition`, :func:`solve_wheelrail`, :func:`wheelset_sweep`
  (:mod:`~wheelrail.contact.wheelrail`, :mod:`~wheelrail.contact.sweep`) — the
  wheel–rail contact module: patches and forces of a wheelset on a track with
  any normal method and any creep-force law;
* :func:`solve_gap_auto`, :func:`potential_contact_grid`,
  :func:`contact_patches` (:mod:`~wheelrail.contact.window`) — the
  boundary-element window chosen from an arbitrary gap, around
  :func:`wheelrail.tangential.exact.solve_gap` (normal + tangential on a grid).

The contact patch every method reads or makes is a core type,
:class:`wheelrail.patch.ContactPatch`.
"""

from .sweep import wheelset_sweep
from .wheelrail import WheelRailPosition, WheelRailResult, solve_wheelrail
from .window import contact_patches, potential_contact_grid, solve_gap_auto

__all__ = ["WheelRailPosition", "WheelRailResult", "solve_wheelrail", "wheelset_sweep",
           "contact_patches", "potential_contact_grid", "solve_gap_auto"]
