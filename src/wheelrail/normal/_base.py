"""Base class of the normal-contact methods.

A normal method is a frozen dataclass, subclass of :class:`NormalMethod`, in
its own module of :mod:`wheelrail.normal`, decorated with
:func:`wheelrail.options.configured`; its options are fields declared once with
:func:`wheelrail.options.option`. Defining the class registers it under its
``name``: :func:`wheelrail.solve` takes the name (the class with its defaults)
or a configured instance, ``wr.normal.Bem(element_size=2e-4)``
(:func:`wheelrail.normal_methods` lists them). A method turns a contact
problem into one or more :class:`~wheelrail.patch.ContactPatch` objects with
their normal forces; a tangential method then reads the patches.

What an implementation must provide
-----------------------------------
``name`` : str
    The registry name (e.g. ``"hertz"``); ``aliases`` other accepted names.
``references`` : tuple of str
    Full citations of what it implements (collected by :func:`wheelrail.citation`).
options
    Dataclass fields declared with :func:`~wheelrail.options.option` (type,
    unit, default, bounds); :meth:`_check` may check their combination.
``from_contact(contact) -> tuple of ContactPatch``
    A single :class:`~wheelrail.hertzian.HertzContact` (load and
    curvatures given): the patch(es) carrying ``contact.Fn``.
``from_gap(problem) -> tuple of ContactPatch``
    A :class:`GapProblem`: an undeformed gap h(x, y) with a prescribed load or
    approach.
``from_wheel(problem) -> (tuple of ContactPatch, dict)``
    A :class:`~wheelrail.contact.wheelrail.WheelProblem`: one wheel on its
    rail at a fixed pose, its candidate contact points, and either the
    vertical load the wheel carries or its vertical approach. The patches
    must carry the vertical load through their normal forces
    (Σ Fn cos γ = Q) and have their :class:`~wheelrail.patch.ContactFrame`;
    the dict holds at least ``vertical_approach``, the vertical approach dz [m].

A method that cannot treat a kind of problem keeps the base implementation,
which raises :class:`~wheelrail.errors.InputError` saying why. All inputs
and outputs are in SI units; axes as in :mod:`wheelrail.conventions`.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..errors import InputError
from ..options import Method, Registry, configured, option

__all__ = ["NormalMethod", "GapProblem", "PatchDescription", "registry", "get", "get_class"]

_REGISTRY = Registry("normal")


@dataclass(frozen=True)
class GapProblem:
    """A normal contact problem given by its undeformed gap (frozen, SI).

    Attributes
    ----------
    gap : callable
        ``gap(x, y) -> h`` [m], vectorised over arrays of equal shape
        (contact-plane x, y in m, :mod:`wheelrail.conventions`).
    materials : Material or MaterialPair
    Fn : float or None
        Prescribed normal force [N] ...
    penetration : float or None
        ... or prescribed penetration (approach of the bodies) δ [m]
        (contact where h < δ); exactly one.
    search : (xmin, xmax, ymin, ymax) or None
        Box [m] in which the contact is looked for (default ±20 mm).
    """

    gap: object
    materials: object
    Fn: float | None = None
    penetration: float | None = None
    search: tuple | None = None

    def __post_init__(self):
        if not callable(self.gap):
            raise InputError(f"GapProblem.gap must be a callable h(x, y) [m], got "
                             f"{type(self.gap).__name__}")
        if (self.Fn is None) == (self.penetration is None):
            raise InputError("GapProblem: give exactly one of Fn= and penetration= "
                             f"(got Fn={self.Fn!r}, penetration={self.penetration!r})")


class NormalMethod(Method):
    """Abstract normal-contact method; see the module docstring for the contract."""

    family = "normal"

    _registry = _REGISTRY

    def from_contact(self, contact):
        raise InputError(f"normal method {self.name!r} cannot solve a Hertzian contact")

    def from_gap(self, problem):
        raise InputError(f"normal method {self.name!r} cannot solve a contact given by a gap "
                         "h(x, y)")

    def from_wheel(self, problem):
        raise InputError(f"normal method {self.name!r} cannot solve a wheel-rail position")


@configured
class PatchDescription:
    """The two options of a strip description of the patches (shared by the methods that
    build patches from strips): ``strips`` across, ``cells`` along each strip."""

    strips: int = option(40, lo=2, hi=2000, doc="strips across each patch")
    cells: int = option(40, lo=2, hi=2000, doc="cells per strip of the patch description")


def registry() -> dict[str, type]:
    """Registry name -> class of every normal method defined so far, by name (no aliases).

    :func:`wheelrail.normal_methods` imports the whole family first.
    """
    return _REGISTRY.classes()


def get(spec, options=None, *, argname: str = "normal") -> NormalMethod:
    """A configured normal method from a name, class or instance (and options)."""
    return _REGISTRY.get(spec, NormalMethod, options, argname=argname)


def get_class(spec, *, argname: str = "normal") -> type:
    """The class of a normal method given by name, class or instance."""
    return _REGISTRY.get_class(spec, NormalMethod, argname=argname)
