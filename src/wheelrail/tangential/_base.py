"""Base class of the creep-force laws (tangential contact methods).

A creep-force law is a subclass of :class:`TangentialMethod` living in its own
module of :mod:`wheelrail.tangential`; :func:`wheelrail.creep_forces` picks it
by name (see ``wheelrail.api.METHODS``) or takes an instance directly.

What an implementation must provide
-----------------------------------
``name`` : str
    The registry name (e.g. ``"fastsim"``).
``references`` : tuple of str
    Full citations of the papers implemented (collected by
    :func:`wheelrail.citation`).
``options`` : dict
    Keyword options the method accepts, with their defaults. Unknown keywords
    passed to :func:`wheelrail.creep_forces` are rejected with a clear error.
``solve(contact, xi, eta, phi, mu, **options) -> CreepForces``
    ``contact`` is a :class:`wheelrail.HertzContact` (single or batch);
    ``xi``, ``eta`` [-], ``phi`` [1/m] and ``mu`` [-] are float arrays already
    validated (finite; μ > 0) and broadcast to the common batch shape, which
    is also the shape of ``contact.a``. The method returns a
    :class:`wheelrail.results.CreepForces` whose ``Fx, Fy, Mz`` have that shape
    (0-d arrays or floats for a single case). Forces act on the wheel and
    follow Kalker's sign convention (:mod:`wheelrail.conventions`).
``solve_patch(patch, xi, eta, phi, mu, **options) -> CreepForces`` (optional)
    One :class:`~wheelrail.contact.patch.ContactPatch` (any normal method),
    scalar creepages and μ. The base implementation solves the patch's
    equivalent ellipse (:meth:`ContactPatch.ellipse`: the Hertz ellipse of a
    Hertzian patch, otherwise the ellipse of equal area and length/width
    ratio) with :meth:`solve`; this is what the closed-form laws (Carter,
    linear, Shen–Hedrick–Elkins, Polach) do. Strip and grid methods (FASTSIM,
    the exact theory) override it to use the strips or the pressure field.
    ``Mz`` is about the patch's centre of pressure.
"""

from __future__ import annotations

from .._method import Method

__all__ = ["TangentialMethod"]


class TangentialMethod(Method):
    """Abstract creep-force law; see the module docstring for the contract."""

    def solve(self, contact, xi, eta, phi, mu, **options):  # pragma: no cover - abstract
        raise NotImplementedError

    def solve_patch(self, patch, xi, eta, phi, mu, **options):
        """Creep forces on one contact patch; default: its equivalent ellipse (see above)."""
        import numpy as np

        f = np.asarray
        return self.solve(patch.ellipse(), f(float(xi)), f(float(eta)), f(float(phi)),
                          f(float(mu)), **options)

    def solve_patches(self, patches, creepages, mu, previous=None, **options):
        """Creep forces on several patches (one :class:`CreepForces` each).

        ``creepages`` has one (ξ, η, φ) per patch, at the patch's reference
        point. ``previous`` may hold the results of a nearby problem (e.g. the
        last pass of a load iteration), which iterative methods use as a
        starting point; it never changes the converged result. The default
        solves the patches one by one; the exact theory overrides it to solve
        patches that share a grid together (their elastic interaction included).
        """
        return tuple(self.solve_patch(p, *c, mu, **options) for p, c in zip(patches, creepages))
