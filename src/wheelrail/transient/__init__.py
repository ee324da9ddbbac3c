"""Instationary (transient) rolling contact: time stepping on a grid moving with the contact.

Public: :func:`transient_rolling` and its frozen result :class:`TransientResult`;
:class:`TravelFunction` (constant, step, sine or tabulated loads along the
travel); the kernels of one step :func:`step_kernels`; measures of Baeza et al.'s
findings in :mod:`wheelrail.transient.measures`.

References
----------
L. Baeza, F.J. Fuenmayor, J. Carballeira, A. Roda, Influence of the wheel–rail
contact instationary process on contact parameters (Baeza et al.), §2.
"""

from .loads import TravelFunction
from .rolling import TransientResult, step_kernels, transient_rolling

__all__ = ["TransientResult", "TravelFunction", "step_kernels", "transient_rolling"]
