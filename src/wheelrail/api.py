"""Public entry functions: one per problem, the method chosen by name or object."""

from __future__ import annotations

import numpy as np

from . import normal as _normal
from . import tangential as _tangential
from ._validation import positive
from .contact.wheelrail import WheelRailPosition, solve_wheelrail
from .errors import InputError
from .normal import GapProblem
from .options import split_options
from .results import ContactResult, CreepForcesResult, PatchResult
from .tangential import as_creepage

__all__ = ["creep_forces", "solve", "normal_methods", "tangential_methods"]


def normal_methods() -> dict[str, type]:
    """Normal methods: registry name -> class (what ``normal=`` of :func:`solve` accepts).

    Examples
    --------
    >>> import wheelrail as wr
    >>> list(wr.normal_methods())
    ['bem', 'hertz', 'kik-piotrowski', 'linder', 'multi-hertz', 'stripes']
    """
    return _normal.registry()


def tangential_methods() -> dict[str, type]:
    """Creep-force laws: registry name -> class (``tangential=`` of :func:`solve`,
    ``method=`` of :func:`creep_forces`).

    Examples
    --------
    >>> import wheelrail as wr
    >>> list(wr.tangential_methods())
    ['carter', 'exact', 'fastrip', 'fastsim', 'linear', 'polach', 'shen-hedrick-elkins', 'table']
    """
    return _tangential.registry()


def creep_forces(contact, creepage, mu, method="fastsim", **options) -> CreepForcesResult:
    """Creep forces and spin moment on the wheel for given creepages.

    Parameters
    ----------
    contact : HertzContact
        The normal contact (single or a batch of shape (n,)).
    creepage : array_like
        (ξ, η, φ) or shape (n, 3): longitudinal and lateral creepage [-] and
        spin [1/m] of the wheel relative to the rail (Kalker's convention,
        see :mod:`wheelrail.conventions`).
    mu : float or array_like
        Coulomb friction coefficient [-], > 0.
    method : str or TangentialMethod
        A name of :func:`tangential_methods` (``"carter"``, ``"linear"``,
        ``"fastsim"``, ``"fastrip"``, ``"shen-hedrick-elkins"``, ``"polach"``,
        ``"exact"``, ``"table"``: the class with its defaults) or a configured
        law, ``wr.tangential.Fastsim(nx=30)``.
    **options
        Options of the law (e.g. ``nx=30``): the same as
        ``method=wr.tangential.Fastsim(nx=30)``.

    Returns
    -------
    CreepForcesResult
        ``Fx``, ``Fy`` [N], ``Mz`` [N·m] on the wheel; floats for a single
        case, arrays of shape (n,) for a batch.

    Raises
    ------
    InputError
        For NaN/inf creepage, μ ≤ 0, an unknown method or option.

    Examples
    --------
    >>> import wheelrail as wr
    >>> c = wr.hertz(7500.0, A=0.5/0.46, B=0.5/0.30, material=wr.Material(2.1e11, 0.28))
    >>> r = wr.creep_forces(c, creepage=(-1e-3, 0.0, 0.0), mu=0.3, method="linear")
    >>> r.Fx > 0
    True
    """
    impl = _tangential.get(method, options, argname="method")
    return impl.forces(contact, creepage, mu)


def solve(problem, creepage=None, mu=None, *, normal="hertz", tangential="fastsim", motion=None,
          vertical="total", **options):
    """Solve a contact problem: normal method, then tangential method, chosen independently.

    Parameters
    ----------
    problem : HertzContact, GapProblem or WheelRailPosition
        A single Hertzian contact (load and curvatures), a gap h(x, y) with a
        load or approach (:class:`wheelrail.normal.GapProblem`), or a wheelset on
        a track (:class:`wheelrail.WheelRailPosition`).
    creepage : (ξ, η, φ)
        Creepages [-], [-], [1/m] (Kalker's convention) for a contact or a gap;
        for a wheel–rail position they follow from ``motion``.
    mu : float
        Friction coefficient [-], > 0.
    normal : str or NormalMethod
        A name of :func:`normal_methods` (``"hertz"``, ``"multi-hertz"``,
        ``"linder"``, ``"kik-piotrowski"``, ``"stripes"``, ``"bem"``: the class
        with its defaults) or a configured method, ``wr.normal.Bem(element_size=2e-4)``.
    tangential : str or TangentialMethod
        A name of :func:`tangential_methods` or a configured law,
        ``wr.tangential.Exact(elements=40)``.
    motion : Motion
        Wheelset velocities (wheel–rail positions only).
    vertical : {"total", "normal"}
        Wheel–rail positions: whether the prescribed vertical load is the
        total vertical force (creep forces included, default) or carried by
        the normal forces alone (:func:`wheelrail.contact.wheelrail.solve_wheelrail`).
    **options
        Options of the two methods, each given to the one method that declares
        it: ``normal="bem", tangential="exact", element_size=2e-4,
        elements=40`` is ``normal=wr.normal.Bem(element_size=2e-4),
        tangential=wr.tangential.Exact(elements=40)``. An option that neither
        or both methods declare is an error naming both methods' options.

    Returns
    -------
    ContactResult or WheelRailResult
        Per-patch results (``patches``) and totals (``Fn``, ``Fx``, ``Fy``,
        ``Mz``), with a ``status``; a wheel–rail result adds ``force_track``.

    Examples
    --------
    >>> import wheelrail as wr
    >>> c = wr.hertz(Fn=7500.0, A=1.087, B=1.667, material=wr.STEEL)
    >>> r = wr.solve(c, creepage=(-7e-4, 0, 0), mu=0.3, normal="hertz", tangential="fastsim")
    >>> len(r.patches), r.Fx > 0
    (1, True)
    """
    nopts, topts = split_options(_normal.get_class(normal), _tangential.get_class(tangential),
                                 options)
    nimpl = _normal.get(normal, nopts)
    timpl = _tangential.get(tangential, topts)
    if mu is None:
        raise InputError("mu (friction coefficient) is required")
    if isinstance(problem, WheelRailPosition):
        if creepage is not None:
            raise InputError("a wheel-rail position takes motion=, not creepage= (the "
                             "creepages follow from the wheelset's motion)")
        if motion is None:
            raise InputError("a wheel-rail position needs motion=wheelrail.Motion(speed=...)")
        return solve_wheelrail(problem, motion, mu, nimpl, timpl, vertical)
    if motion is not None:
        raise InputError("motion= is only for a WheelRailPosition; give creepage= here")
    if creepage is None:
        raise InputError("creepage=(xi, eta, phi) is required")
    xi, eta, phi = as_creepage(creepage)
    if np.ndim(xi) != 0:
        raise InputError("solve takes one creepage (xi, eta, phi); use creep_forces for batches")
    mu = float(positive("mu", mu))
    if isinstance(problem, GapProblem):
        patches = nimpl.from_gap(problem)
    elif all(hasattr(problem, k) for k in ("a", "b", "Fn", "A", "B", "materials")):
        if np.shape(problem.a) != ():
            raise InputError("solve takes a single HertzContact; use creep_forces for batches")
        patches = nimpl.from_contact(problem)
    else:
        raise InputError(f"problem must be a HertzContact, a GapProblem or a WheelRailPosition, "
                         f"got {type(problem).__name__}")
    c = (float(xi), float(eta), float(phi))
    forces = timpl.solve_patches(patches, [c] * len(patches), mu)
    return ContactResult(tuple(PatchResult(p, f, *c) for p, f in zip(patches, forces)),
                         nimpl.name, timpl.name, info={"mu": mu})
