"""Public entry functions: one per problem, the method chosen by name or object."""

from __future__ import annotations

import importlib

import numpy as np

from ._validation import as_float_array, positive
from .errors import InputError, WheelrailError
from .plausibility import check_friction
from .results import CreepForces
from .tangential._base import TangentialMethod

__all__ = ["creep_forces", "METHODS", "get_method", "method_key", "as_creepage",
           "available_methods", "solve", "NORMAL_METHODS", "normal_methods", "tangential_methods",
           "get_normal_method"]

#: Registry of creep-force laws: name -> "module:Class".
METHODS = {
    "carter": "wheelrail.tangential.carter:Carter",
    "linear": "wheelrail.tangential.linear:KalkerLinear",
    "fastsim": "wheelrail.tangential.fastsim:Fastsim",
    "shen-hedrick-elkins": "wheelrail.tangential.shen_hedrick_elkins:ShenHedrickElkins",
    "polach": "wheelrail.tangential.polach:Polach",
    "exact": "wheelrail.tangential.exact:Exact",
    "table": "wheelrail.tangential.table:Table",
    "fastrip": "wheelrail.tangential.fastrip:FaStrip",
}
_ALIASES = {
    "kalker-linear": "linear",
    "she": "shen-hedrick-elkins",
    "shen_hedrick_elkins": "shen-hedrick-elkins",
    "kalker": "exact",
}


def method_key(name: str) -> str | None:
    """Registry name of a creep-force method name or alias (case-insensitive), else ``None``."""
    key = _ALIASES.get(name.lower(), name.lower())
    return key if key in METHODS else None


def available_methods() -> list[str]:
    """Names accepted by ``method=`` in :func:`creep_forces`."""
    return list(METHODS)


def _resolve(method, base, key, registry, what, argname):
    """An instance of ``base`` from a name (looked up with ``key`` in ``registry``), a
    subclass or an instance; the one resolver of both method families."""
    if isinstance(method, base):
        return method
    if isinstance(method, type) and issubclass(method, base):
        return method()
    if not isinstance(method, str):
        raise InputError(f"{argname} must be a name or a {base.__name__}, got {method!r}")
    name = key(method)
    if name is None:
        raise InputError(f"unknown {what} {method!r}; choose one of " + ", ".join(registry))
    module, cls = registry[name].split(":")
    return getattr(importlib.import_module(module), cls)()


def get_method(method) -> TangentialMethod:
    """Resolve ``method`` (name, class or instance) to a :class:`TangentialMethod` instance."""
    return _resolve(method, TangentialMethod, method_key, METHODS, "creep-force method",
                    "method")


def as_creepage(creepage):
    """Validate creepages and return ``(xi, eta, phi)`` float arrays.

    Parameters
    ----------
    creepage : sequence of 3 floats, or array_like, shape (n, 3), or mapping
        (ξ [-], η [-], φ [1/m]); a mapping may give ``xi``, ``eta``, ``phi``
        (missing ones are zero).

    Returns
    -------
    xi, eta, phi : ndarray
        0-d arrays for a single case, shape (n,) for a batch.
    """
    if isinstance(creepage, dict):
        unknown = set(creepage) - {"xi", "eta", "phi"}
        if unknown:
            raise InputError(f"unknown creepage component(s) {sorted(unknown)}; use xi, eta, phi")
        creepage = [creepage.get("xi", 0.0), creepage.get("eta", 0.0), creepage.get("phi", 0.0)]
    arr = as_float_array("creepage", creepage)
    if arr.ndim == 1 and arr.shape[0] == 3:
        return arr[0], arr[1], arr[2]
    if arr.ndim == 2 and arr.shape[1] == 3:
        return arr[:, 0].copy(), arr[:, 1].copy(), arr[:, 2].copy()
    raise InputError(f"creepage must be (xi, eta, phi) or an array of shape (n, 3), "
                     f"got shape {arr.shape}")


def _check_contact(contact):
    for attr in ("a", "b", "load", "materials"):
        if not hasattr(contact, attr):
            raise InputError(f"contact must be a HertzContact (from wheelrail.hertz), "
                             f"got {type(contact).__name__} without '{attr}'")


def creep_forces(contact, creepage, mu, method="fastsim", **options) -> CreepForces:
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
        ``"carter"``, ``"linear"``, ``"fastsim"``, ``"shen-hedrick-elkins"``,
        ``"polach"``, ``"exact"`` or an instance.
    **options
        Method options (e.g. ``nx``, ``ny``, ``bound`` for FASTSIM).

    Returns
    -------
    CreepForces
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
    _check_contact(contact)
    impl = get_method(method)
    opts = impl.check_options(options)
    xi, eta, phi = as_creepage(creepage)
    mu = positive("mu", mu)
    check_friction(mu)  # a percentage or a typo: warn above 1, refuse above 2 (plausibility)
    shape = np.broadcast_shapes(np.shape(contact.a), xi.shape, mu.shape)
    if len(shape) > 1:
        raise InputError(f"batch inputs must be one-dimensional, got shape {shape}")
    xi, eta, phi, mu = (np.broadcast_to(v, shape).astype(float) for v in (xi, eta, phi, mu))
    if shape != np.shape(contact.a):
        contact = _broadcast_contact(contact, shape)
    result = impl.solve(contact, xi, eta, phi, mu, **opts)
    for name in ("Fx", "Fy", "Mz"):
        if not np.all(np.isfinite(getattr(result, name))):
            raise WheelrailError(f"method {impl.name!r} produced a non-finite {name}; "
                                 "please report this with the input")
    return result


def _broadcast_contact(contact, shape):
    from dataclasses import replace

    names = ("a", "b", "p0", "penetration", "load", "A", "B")
    return replace(contact, **{n: np.broadcast_to(np.asarray(getattr(contact, n), float), shape).copy()
                               for n in names if hasattr(contact, n)})


# --------------------------------------------------------------------------- normal methods
#: Registry of normal-contact methods: name -> "module:Class".
NORMAL_METHODS = {
    "hertz": "wheelrail.normal.hertz:Hertz",
    "multi-hertz": "wheelrail.normal.multi_hertz:MultiHertz",
    "linder": "wheelrail.normal.linder:Linder",
    "kik-piotrowski": "wheelrail.normal.kik_piotrowski:KikPiotrowski",
    "stripes": "wheelrail.normal.stripes:Stripes",
    "bem": "wheelrail.normal.bem:Bem",
}


def normal_methods() -> list[str]:
    """Names accepted by ``normal=`` in :func:`solve`."""
    return list(NORMAL_METHODS)


def tangential_methods() -> list[str]:
    """Names accepted by ``tangential=`` in :func:`solve` (and ``method=`` in :func:`creep_forces`)."""
    return list(METHODS)


def get_normal_method(method):
    """Resolve ``method`` (name, class or instance) to a :class:`~wheelrail.normal.NormalMethod`."""
    from .normal._base import NormalMethod

    def key(name):
        return name.lower() if name.lower() in NORMAL_METHODS else None

    return _resolve(method, NormalMethod, key, NORMAL_METHODS, "normal method", "normal")


def _split_options(nimpl, timpl, options):
    """Route keyword options to the normal and/or tangential method that accepts them."""
    nopts, topts = {}, {}
    for k, v in options.items():
        n_ok, t_ok = k in nimpl.options, k in timpl.options
        if not (n_ok or t_ok):
            raise InputError(
                f"option {k!r} is accepted neither by normal method {nimpl.name!r} (options: "
                f"{', '.join(sorted(nimpl.options)) or 'none'}) nor by tangential method "
                f"{timpl.name!r} (options: {', '.join(sorted(timpl.options)) or 'none'})")
        if n_ok:
            nopts[k] = v
        if t_ok:
            topts[k] = v
    return nopts, topts


def solve(problem, creepage=None, mu=None, *, normal="hertz", tangential="fastsim", motion=None,
          normal_options=None, tangential_options=None, vertical="total", **options):
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
        :func:`normal_methods`: ``"hertz"``, ``"bem"``.
    tangential : str or TangentialMethod
        :func:`tangential_methods`: ``"fastsim"``, ``"exact"``, ``"polach"``, ...
    motion : Motion
        Wheelset velocities (wheel–rail positions only).
    vertical : {"total", "normal"}
        Wheel–rail positions: whether the prescribed vertical load is the
        total vertical force (creep forces included, default) or carried by
        the normal forces alone (:func:`wheelrail.contact.wheelrail.solve_wheelrail`).
    normal_options, tangential_options : dict, optional
        Options for one method explicitly.
    **options
        Further options, each given to the method(s) that accept it (an
        option no chosen method accepts is an error).

    Returns
    -------
    ContactResult or WheelRailResult
        Per-patch results (``patches``) and totals (``Fn``, ``Fx``, ``Fy``,
        ``Mz``), with a ``status``; a wheel–rail result adds ``force_track``.

    Examples
    --------
    >>> import wheelrail as wr
    >>> c = wr.hertz(load=7500.0, A=1.087, B=1.667, material=wr.STEEL)
    >>> r = wr.solve(c, creepage=(-7e-4, 0, 0), mu=0.3, normal="hertz", tangential="fastsim")
    >>> len(r.patches), r.Fx > 0
    (1, True)
    """
    from .contact.wheelrail import WheelRailPosition, solve_wheelrail
    from .normal._base import GapProblem
    from .results import ContactResult, PatchResult

    nimpl = get_normal_method(normal)
    timpl = get_method(tangential)
    nopts, topts = _split_options(nimpl, timpl, options)
    nopts.update(normal_options or {})
    topts.update(tangential_options or {})
    if mu is None:
        raise InputError("mu (friction coefficient) is required")
    if isinstance(problem, WheelRailPosition):
        if creepage is not None:
            raise InputError("a wheel-rail position takes motion=, not creepage= (the "
                             "creepages follow from the wheelset's motion)")
        if motion is None:
            raise InputError("a wheel-rail position needs motion=wheelrail.Motion(speed=...)")
        return solve_wheelrail(problem, motion, mu, nimpl, timpl, nopts, topts, vertical)
    if motion is not None:
        raise InputError("motion= is only for a WheelRailPosition; give creepage= here")
    if creepage is None:
        raise InputError("creepage=(xi, eta, phi) is required")
    xi, eta, phi = as_creepage(creepage)
    if np.ndim(xi) != 0:
        raise InputError("solve takes one creepage (xi, eta, phi); use creep_forces for batches")
    mu = float(positive("mu", mu))
    nopts = nimpl.check_options(nopts)
    topts = timpl.check_options(topts)
    if isinstance(problem, GapProblem):
        patches = nimpl.from_gap(problem, **nopts)
    elif all(hasattr(problem, k) for k in ("a", "b", "load", "A", "B", "materials")):
        if np.shape(problem.a) != ():
            raise InputError("solve takes a single HertzContact; use creep_forces for batches")
        patches = nimpl.from_contact(problem, **nopts)
    else:
        raise InputError(f"problem must be a HertzContact, a GapProblem or a WheelRailPosition, "
                         f"got {type(problem).__name__}")
    c = (float(xi), float(eta), float(phi))
    forces = timpl.solve_patches(patches, [c] * len(patches), mu, **topts)
    return ContactResult(tuple(PatchResult(p, f, *c) for p, f in zip(patches, forces)),
                         nimpl.name, timpl.name, info={"mu": mu})
