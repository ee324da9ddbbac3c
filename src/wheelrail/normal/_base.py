"""Base class of the normal-contact methods.

A normal method is a subclass of :class:`NormalMethod` in its own module of
:mod:`wheelrail.normal`; :func:`wheelrail.solve` picks it by name (the table
``wheelrail.api.NORMAL_METHODS``, listed by :func:`wheelrail.normal_methods`)
or takes an instance. It turns a contact problem into one or more
:class:`~wheelrail.contact.patch.ContactPatch` objects with their normal
forces; a tangential method then reads the patches.

What an implementation must provide
-----------------------------------
``name`` : str
    The registry name (e.g. ``"hertz"``).
``references`` : tuple of str
    Full citations of what it implements (collected by :func:`wheelrail.citation`).
``options`` : dict
    Keyword options with their defaults; unknown keywords are rejected.
``from_contact(contact, **options) -> tuple of ContactPatch``
    A single :class:`~wheelrail.normal.hertz.HertzContact` (load and
    curvatures given): the patch(es) carrying ``contact.load``.
``from_gap(problem, **options) -> tuple of ContactPatch``
    A :class:`GapProblem`: an undeformed gap h(x, y) with a prescribed load or
    approach.
``from_wheel(problem, **options) -> (tuple of ContactPatch, dict)``
    A :class:`~wheelrail.contact.wheelrail.WheelProblem`: one wheel on its
    rail at a fixed pose, its candidate contact points, and either the
    vertical load the wheel carries or its vertical approach. The patches
    must carry the vertical load through their normal forces
    (Σ Fn cos γ = Q) and have their :class:`~wheelrail.contact.patch.ContactFrame`;
    the dict holds at least ``approach``, the vertical approach dz [m].

A method that cannot treat a kind of problem keeps the base implementation,
which raises :class:`~wheelrail.errors.InputError` saying why. All inputs
and outputs are in SI units; axes as in :mod:`wheelrail.conventions`.
"""

from __future__ import annotations

from dataclasses import dataclass

from .._method import Method
from ..errors import InputError

__all__ = ["NormalMethod", "GapProblem"]


@dataclass(frozen=True)
class GapProblem:
    """A normal contact problem given by its undeformed gap (frozen, SI).

    Attributes
    ----------
    gap : callable
        ``gap(x, y) -> h`` [m], vectorised over arrays of equal shape
        (contact-plane x, y in m, :mod:`wheelrail.conventions`).
    materials : Material or MaterialPair
    load : float or None
        Prescribed normal force [N] ...
    penetration : float or None
        ... or prescribed approach δ [m] (contact where h < δ); exactly one.
    search : (xmin, xmax, ymin, ymax) or None
        Box [m] in which the contact is looked for (default ±20 mm).
    """

    gap: object
    materials: object
    load: float | None = None
    penetration: float | None = None
    search: tuple | None = None

    def __post_init__(self):
        if not callable(self.gap):
            raise InputError(f"GapProblem.gap must be a callable h(x, y) [m], got "
                             f"{type(self.gap).__name__}")
        if (self.load is None) == (self.penetration is None):
            raise InputError("GapProblem: give exactly one of load= and penetration= "
                             f"(got load={self.load!r}, penetration={self.penetration!r})")


class NormalMethod(Method):
    """Abstract normal-contact method; see the module docstring for the contract."""

    family = "normal "

    def from_contact(self, contact, **options):
        raise InputError(f"normal method {self.name!r} cannot solve a Hertzian contact")

    def from_gap(self, problem, **options):
        raise InputError(f"normal method {self.name!r} cannot solve a contact given by a gap "
                         "h(x, y)")

    def from_wheel(self, problem, **options):
        raise InputError(f"normal method {self.name!r} cannot solve a wheel-rail position")
