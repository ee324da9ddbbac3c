"""The wheelset case: a wheelset on a track with real profiles (``[wheelset]``, ``[track]``,
``[motion]``, ``[position]``), and its solution through :func:`wheelrail.solve` or
:func:`wheelrail.wheelset_sweep`."""

from __future__ import annotations

from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any, Mapping

import numpy as np

from ..api import solve
from ..contact.sweep import wheelset_sweep
from ..contact.wheelrail import WheelRailPosition
from ..errors import InputError
from ..materials import MaterialPair
from ..normal import NormalMethod
from ..results import to_jsonable
from ..tangential import TangentialMethod
from ._methods import configured_methods

__all__ = ["WheelsetCase", "solve_wheelset_case"]

@dataclass(frozen=True, eq=False)
class WheelsetCase:
    """A validated wheelset-on-track case (``[wheelset]``, ``[track]``, ``[motion]``,
    ``[position]``; see the module docstring and ``docs/cli.md``). SI units.

    Attributes
    ----------
    wheelset : Wheelset
    track : Track
    motion : Motion
    y : ndarray, shape (n,)
        Lateral shifts [m] (one for a single position).
    yaw : ndarray, shape (n,)
        Yaw angle at each shift [rad].
    roll : float or None
        Roll angle [rad]; ``None``: from the rigid contact constraint.
    vertical_load : tuple of float or None
        Vertical force on the (left, right) wheel [N] ...
    z : float or None
        ... or the height of the axle centre [m].
    tolerance : float
        Largest separation of a candidate contact point [m].
    sweep : bool
        True when ``[position] y`` is a range or a list (even of one value).
    materials : MaterialPair
    mu : float
    normal : NormalMethod
    tangential : TangentialMethod
        The configured methods.
    methods : mapping
        Every configured method of the case by registry name.
    source : str
    tables : mapping
        The tables as read (for the JSON output).
    """

    wheelset: Any
    track: Any
    motion: Any
    y: np.ndarray
    yaw: np.ndarray
    roll: float | None
    vertical_load: tuple | None
    z: float | None
    tolerance: float
    sweep: bool
    materials: MaterialPair
    mu: float
    normal: NormalMethod = None
    tangential: TangentialMethod = None
    methods: Mapping[str, Any] = field(default_factory=lambda: MappingProxyType({}))
    source: str = "<case>"
    tables: Mapping[str, Any] = field(default_factory=lambda: MappingProxyType({}))

    def __post_init__(self):
        n, t, methods = configured_methods(self.normal, self.tangential, self.methods)
        object.__setattr__(self, "normal", n)
        object.__setattr__(self, "tangential", t)
        object.__setattr__(self, "methods", methods)

    def position(self, i: int = 0):
        """The :class:`wheelrail.WheelRailPosition` of shift number ``i``."""

        return WheelRailPosition(self.wheelset, self.track, float(self.y[i]), float(self.yaw[i]),
                                 self.roll, vertical_load=self.vertical_load, z=self.z,
                                 material=self.materials, tolerance=self.tolerance)

    def to_dict(self) -> dict:
        """The validated input (JSON-ready, SI)."""
        return to_jsonable({**{k: dict(v) if isinstance(v, Mapping) else v
                               for k, v in self.tables.items()},
                            "y": self.y, "yaw": self.yaw, "source": self.source})


def solve_wheelset_case(case: WheelsetCase, progress=None):
    """Solve a :class:`WheelsetCase` through :func:`wheelrail.solve`.

    Returns
    -------
    WheelRailResult
        For a single position (``[position] y`` a number).
    xarray.Dataset
        For a sweep (``y`` a range or list): :func:`wheelrail.wheelset_sweep`.
    """

    if not isinstance(case, WheelsetCase):
        raise InputError(f"solve_wheelset_case needs a WheelsetCase (from load_case), got "
                         f"{type(case).__name__}")
    if not case.sweep:
        return solve(case.position(0), motion=case.motion, mu=case.mu, normal=case.normal,
                     tangential=case.tangential)

    ds = wheelset_sweep(case.wheelset, case.track, y=case.y, yaw=case.yaw,
                        roll=case.roll, vertical_load=case.vertical_load, z=case.z,
                        motion=case.motion, mu=case.mu, normal=case.normal,
                        tangential=case.tangential, material=case.materials,
                        progress=progress)
    ds.attrs["source"] = case.source
    return ds


