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
"""

from __future__ import annotations

from ..errors import InputError

__all__ = ["TangentialMethod"]


class TangentialMethod:
    """Abstract creep-force law; see the module docstring for the contract."""

    name: str = "abstract"
    references: tuple = ()
    options: dict = {}

    def solve(self, contact, xi, eta, phi, mu, **options):  # pragma: no cover - abstract
        raise NotImplementedError

    def check_options(self, options: dict) -> dict:
        """Merge ``options`` into the defaults, rejecting unknown keywords and bad values.

        Values are checked with the table of :mod:`wheelrail._options`.
        """
        unknown = set(options) - set(self.options)
        if unknown:
            allowed = ", ".join(sorted(self.options)) or "none"
            raise InputError(f"method {self.name!r} does not accept option(s) "
                             f"{', '.join(sorted(unknown))}; allowed: {allowed}")
        merged = dict(self.options)
        merged.update(options)
        from .._options import validate

        validate(self.name, merged)  # every value, before any solve; nothing is clamped
        return merged

    def __repr__(self) -> str:
        return f"{type(self).__name__}()"
