"""Instationary (transient) rolling contact: time stepping on a grid moving with the contact.

Public: :func:`transient_rolling` and its frozen result :class:`TransientResult`.

References
----------
L. Baeza, F.J. Fuenmayor, J. Carballeira, A. Roda, Influence of the wheel–rail
contact instationary process on contact parameters (seed paper 001), §2.
"""

from .rolling import TransientResult, transient_rolling

__all__ = ["TransientResult", "transient_rolling"]
