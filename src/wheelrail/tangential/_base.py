"""Base class and registry of the creep-force laws (tangential contact methods).

A creep-force law is a frozen dataclass, subclass of :class:`TangentialMethod`,
in its own module of :mod:`wheelrail.tangential`, decorated with
:func:`wheelrail.options.configured`; its options are fields declared once with
:func:`wheelrail.options.option`. Defining such a class registers it under its
``name`` (and ``aliases``): :func:`wheelrail.creep_forces` and
:func:`wheelrail.solve` accept the name (the class with its defaults) or a
configured instance, ``wr.tangential.Fastsim(nx=30)``.

What an implementation must provide
-----------------------------------
``name`` : str
    The registry name (e.g. ``"fastsim"``); ``aliases`` other accepted names.
``references`` : tuple of str
    Full citations of the papers implemented (collected by
    :func:`wheelrail.citation`).
options
    Dataclass fields declared with :func:`~wheelrail.options.option` (type,
    unit, default, bounds); :meth:`_check` may check their combination.
``solve(contact, xi, eta, phi, mu) -> CreepForcesResult``
    ``contact`` is a :class:`wheelrail.HertzContact` (single or batch);
    ``xi``, ``eta`` [-], ``phi`` [1/m] and ``mu`` [-] are float arrays already
    validated (finite; μ > 0) and broadcast to the common batch shape, which
    is also the shape of ``contact.a``. The method returns a
    :class:`wheelrail.results.CreepForcesResult` whose ``Fx, Fy, Mz`` have that
    shape (floats for a single case). Forces act on the wheel and follow
    Kalker's sign convention (:mod:`wheelrail.conventions`).
``solve_patch(patch, xi, eta, phi, mu) -> CreepForcesResult`` (optional)
    One :class:`~wheelrail.patch.ContactPatch` (any normal method), scalar
    creepages and μ. The base implementation solves the patch's equivalent
    ellipse (:meth:`ContactPatch.ellipse`: the Hertz ellipse of a Hertzian
    patch, otherwise the ellipse of equal area and length/width ratio) with
    :meth:`solve`; this is what the closed-form laws (Carter, linear,
    Shen–Hedrick–Elkins, Polach) do. Strip and grid methods (FASTSIM, the
    exact theory) override it to use the strips or the pressure field. ``Mz``
    is about the patch's centre of pressure.
"""

from __future__ import annotations

import numpy as np

from .._validation import as_float_array, positive
from ..errors import InputError, WheelrailError
from ..options import Method, Registry
from ..plausibility import check_friction

__all__ = ["TangentialMethod", "registry", "get", "get_class", "as_creepage", "broadcast_contact"]

_REGISTRY = Registry("tangential")


class TangentialMethod(Method):
    """Abstract creep-force law; see the module docstring for the contract."""

    family = "tangential"

    _registry = _REGISTRY

    def solve(self, contact, xi, eta, phi, mu):  # pragma: no cover - abstract
        raise NotImplementedError

    def forces(self, contact, creepage, mu):
        """Creep forces of validated, broadcast inputs (what :func:`wheelrail.creep_forces` does
        after choosing the law).

        Parameters
        ----------
        contact : HertzContact
            Single or a batch of shape (n,).
        creepage : array_like
            (ξ [-], η [-], φ [1/m]) or shape (n, 3), or a mapping (:func:`as_creepage`).
        mu : float or array_like
            Friction coefficient [-], > 0.

        Returns
        -------
        CreepForcesResult
            On the wheel, Kalker's convention; floats for a single case.

        Raises
        ------
        InputError
            A contact that is not a HertzContact, NaN/inf creepage, μ ≤ 0,
            batch shapes that do not broadcast.
        WheelrailError
            A non-finite force (a defect, reported with the method's name).
        """
        _check_contact(contact)
        xi, eta, phi = as_creepage(creepage)
        mu = positive("mu", mu)
        check_friction(mu)  # a percentage or a typo: warn above 1, refuse above 2 (plausibility)
        shape = np.broadcast_shapes(np.shape(contact.a), xi.shape, mu.shape)
        if len(shape) > 1:
            raise InputError(f"batch inputs must be one-dimensional, got shape {shape}")
        xi, eta, phi, mu = (np.broadcast_to(v, shape).astype(float) for v in (xi, eta, phi, mu))
        if shape != np.shape(contact.a):
            contact = broadcast_contact(contact, shape)
        result = self.solve(contact, xi, eta, phi, mu)
        for name in ("Fx", "Fy", "Mz"):
            if not np.all(np.isfinite(getattr(result, name))):
                raise WheelrailError(f"method {self.name!r} produced a non-finite {name}; "
                                     "please report this with the input")
        return result

    def solve_patch(self, patch, xi, eta, phi, mu):
        """Creep forces on one contact patch; default: its equivalent ellipse (see above)."""
        f = np.asarray
        return self.solve(patch.ellipse(), f(float(xi)), f(float(eta)), f(float(phi)),
                          f(float(mu)))

    def solve_patches(self, patches, creepages, mu, previous=None):
        """Creep forces on several patches (one :class:`CreepForcesResult` each).

        ``creepages`` has one (ξ, η, φ) per patch, at the patch's reference
        point. ``previous`` may hold the results of a nearby problem (e.g. the
        last pass of a load iteration), which iterative methods use as a
        starting point; it never changes the converged result. The default
        solves the patches one by one; the exact theory overrides it to solve
        patches that share a grid together (their elastic interaction included).
        """
        return tuple(self.solve_patch(p, *c, mu) for p, c in zip(patches, creepages))


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
    for attr in ("a", "b", "Fn", "materials"):
        if not hasattr(contact, attr):
            raise InputError(f"contact must be a HertzContact (from wheelrail.hertz), "
                             f"got {type(contact).__name__} without '{attr}'")


def broadcast_contact(contact, shape):
    from dataclasses import replace

    names = ("a", "b", "p0", "penetration", "Fn", "A", "B")
    return replace(contact, **{n: np.broadcast_to(np.asarray(getattr(contact, n), float), shape).copy()
                               for n in names if hasattr(contact, n)})


def registry() -> dict[str, type]:
    """Registry name -> class of every creep-force law defined so far, by name (no aliases).

    :func:`wheelrail.tangential_methods` imports the whole family first.
    """
    return _REGISTRY.classes()


def get(spec, options=None, *, argname: str = "tangential") -> TangentialMethod:
    """A configured creep-force law from a name, class or instance (and options)."""
    return _REGISTRY.get(spec, TangentialMethod, options, argname=argname)


def get_class(spec, *, argname: str = "tangential") -> type:
    """The class of a creep-force law given by name, class or instance."""
    return _REGISTRY.get_class(spec, TangentialMethod, argname=argname)
