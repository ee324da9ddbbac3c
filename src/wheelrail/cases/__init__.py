"""Cases: validated inputs of whole problems and their solution through the public API.

A case is what a case file describes (:mod:`wheelrail.cases.files` reads and
validates the files): a single Hertzian contact (:class:`Case`), a wheelset on
a track (:class:`WheelsetCase`) or a transient rolling run
(:class:`TransientCase`). The methods of a case are configured method objects
(:mod:`wheelrail.options`), the same as ``wr.solve`` takes.

=============================  ==================================================
:func:`solve_case`             a :class:`Case` through :func:`wheelrail.solve`
:func:`solve_wheelset_case`    a :class:`WheelsetCase` (one position or a sweep)
:func:`run_case`               either, as a JSON-ready dictionary (SI units)
``TransientCase.run``          :func:`wheelrail.transient_rolling`
=============================  ==================================================
"""

from .contact import DEFAULT_CASE, UNITS, Case, CaseResult, ContactSpec, run_case, solve_case
from .transient import TransientCase
from .wheelset import WheelsetCase, solve_wheelset_case

__all__ = ["Case", "ContactSpec", "CaseResult", "WheelsetCase", "TransientCase", "solve_case",
           "solve_wheelset_case", "run_case", "DEFAULT_CASE", "UNITS"]
