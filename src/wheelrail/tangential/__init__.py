"""Tangential contact problem: the creep-force laws, one per module.

Each law is a frozen dataclass whose options are fields
(:mod:`wheelrail.options`); pass its registry name or a configured instance to
:func:`wheelrail.creep_forces` or :func:`wheelrail.solve`::

    wr.creep_forces(contact, creepage, mu, method="fastsim")
    wr.creep_forces(contact, creepage, mu, method=wr.tangential.Fastsim(nx=30))

==========================  =====================================  ==========================
name                        class                                  module
==========================  =====================================  ==========================
``"carter"``                :class:`Carter`                        :mod:`.carter`
``"linear"``                :class:`Linear`                        :mod:`.linear`
``"fastsim"``               :class:`Fastsim`                       :mod:`.fastsim`
``"fastrip"``               :class:`Fastrip`                       :mod:`.fastrip`
``"shen-hedrick-elkins"``   :class:`ShenHedrickElkins`             :mod:`.shen_hedrick_elkins`
``"polach"``                :class:`Polach`                        :mod:`.polach`
``"exact"``                 :class:`Exact`                         :mod:`.exact`
``"table"``                 :class:`Table`                         :mod:`.table`
==========================  =====================================  ==========================

:func:`registry` (also :func:`wheelrail.tangential_methods`) gives name -> class;
:func:`get` a configured instance from a name, class or instance and options.
"""

from ._base import TangentialMethod, as_creepage, broadcast_contact, get, get_class, registry
from .carter import Carter
from .exact import Exact
from .fastrip import Fastrip
from .fastsim import Fastsim
from .linear import Linear, kalker_coefficients
from .polach import Polach
from .shen_hedrick_elkins import ShenHedrickElkins
from .table import Table

__all__ = ["TangentialMethod", "get", "get_class", "registry", "as_creepage", "broadcast_contact", "Carter", "Linear", "Fastsim", "Fastrip",
           "ShenHedrickElkins", "Polach", "Exact", "Table", "kalker_coefficients"]
