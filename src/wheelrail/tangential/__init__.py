"""Tangential contact problem: creep-force laws, one per module.

=====================  ==============================================
name                   module
=====================  ==============================================
``"carter"``           :mod:`wheelrail.tangential.carter`
``"linear"``           :mod:`wheelrail.tangential.linear`
``"fastsim"``          :mod:`wheelrail.tangential.fastsim`
``"shen-hedrick-elkins"`` :mod:`wheelrail.tangential.shen_hedrick_elkins`
``"polach"``           :mod:`wheelrail.tangential.polach`
``"exact"``            :mod:`wheelrail.tangential.exact`
``"table"``            :mod:`wheelrail.tangential.table`
=====================  ==============================================

Modules are imported lazily by :func:`wheelrail.creep_forces`.
"""

from ._base import TangentialMethod

__all__ = ["TangentialMethod"]
