"""Finite-element frictional rolling contact of a wheel on a rail (3-D, hex8, SI units).

Two programs on one engine: a wheel rolling on a rail (steady rolling, indentation,
elastic or elasto-plastic bodies; user guides docs/fe.md and docs/fe_plastic.md) and the
one- to two-point contact transition of a half-wheelset on a flexible track
(:mod:`wheelrail.fe.transition`, docs/fe_transition.md).

Public names
------------
``solve(case)``
    Every FE case: a :class:`RollingCase` rolls (both loading steps, explicit, implicit
    quasi-static or HHT; ``mode="indent"``: static normal contact only), a
    :class:`TransitionCase` rolls into two-point contact (:func:`run_transition`).
``indent(case)``, ``creep_curve(case, creepages, component="xi")``
    Static normal contact; steady creep forces over a range of creepage.
``RollingCase``, ``RollingResult``, ``IndentResult``
    The rolling case (profiles, radius, ``Fn``, creepage, friction, material, mesh,
    integrator) and its results.
``seed000_case(load="table3", plastic=False, **changes)``, ``toumi2016_load``,
``cone_wheel``, ``head_arc_rail``
    The Hertzian case of Toumi, Chollet & Yin (2016): a 1/10 cone on a 300 mm head arc
    inclined by 1/10, at the load of their Table 3 (81.3 kN) or as printed (7.5 kN).
``Hex8``, ``LinearElastic``, ``J2Plastic``, ``Voce``, ``TabulatedHardening``, ``r900a``
    The element and the material laws (swappable parts).
``write_vtu``, ``read_restart``
    VTU output for ParaView; restart files of a rolling run (``solve(case, restart=...)``).
``TransitionCase``, ``TransitionResult``, ``TrackStructure``, ``WheelSuspension``,
``seed004_case``, ``run_transition``, ``transition``
    The one- to two-point contact transition; the rest of it (wave speed, rigid poses,
    analysis) in :mod:`wheelrail.fe.transition`.

Parts of the rolling engine: :mod:`.mesh` (structured generator), :mod:`.elements`,
:mod:`.materials`, :mod:`._solid` (parallel element kernels, J2 return map),
:mod:`._kernels` (contact), :mod:`.model` (kinematics and assembly), :mod:`.static`,
:mod:`.rolling`, :mod:`.explicit`, :mod:`.implicit`, :mod:`.curves`,
:mod:`.patch_dataset`, :mod:`.output`, :mod:`.restart`.

Threads: the kernels use all numba threads (``NUMBA_NUM_THREADS`` or
``numba.set_num_threads``); the results do not depend on their number.

References
----------
.. [1] M. Toumi, H. Chollet, H. Yin, "Finite element analysis of the frictional
   wheel-rail rolling contact using explicit and implicit methods", Wear 366-367
   (2016) 157-166.
"""

import os as _os

# The parallel kernels (numba, OpenMP layer) synchronise a few times per explicit step. With
# GNU OpenMP's default (active, spinning) wait, a barrier on a shared or oversubscribed
# machine costs a scheduler time slice: measured 5x slower than one thread at load 5 on
# 2 cores. Passive waiting (threads sleep at barriers) avoids that; it must be set before
# the OpenMP runtime starts. An explicit setting of the user's is kept.
_os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

from . import transition
from .case import RollingCase, cone_wheel, head_arc_rail, seed000_case, toumi2016_load
from .curves import creep_curve
from .elements import Hex8
from .materials import J2Plastic, LinearElastic, TabulatedHardening, Voce, r900a
from .output import write_vtu
from .restart import read_restart
from .rolling import RollingResult
from .run import solve
from .static import IndentResult, indent
from .transition import (
                   TrackStructure,
                   TransitionCase,
                   TransitionResult,
                   WheelSuspension,
                   run_transition,
                   seed004_case,
)

__all__ = ["solve", "indent", "creep_curve", "RollingCase", "RollingResult", "IndentResult",
           "seed000_case", "toumi2016_load", "cone_wheel", "head_arc_rail",
           "Hex8", "LinearElastic", "J2Plastic", "Voce", "TabulatedHardening", "r900a",
           "write_vtu", "read_restart",
           "TransitionCase", "TransitionResult", "TrackStructure", "WheelSuspension",
           "seed004_case", "run_transition", "transition"]

#: Names that moved out of the ``wr.fe`` namespace: where they live now. Still found here,
#: with a DeprecationWarning, for one release.
_MOVED = {
    "INTEGRATORS": "wheelrail.fe.case", "TOUMI2016_TABLE3_HERTZ": "wheelrail.fe.case",
    "R900A_HARDENING": "wheelrail.fe.materials", "MeshQualityError": "wheelrail.fe.mesh",
    "check_quality": "wheelrail.fe.mesh", "build_model": "wheelrail.fe.model",
    "write_restart": "wheelrail.fe.restart", "plastic_fields": "wheelrail.fe.rolling",
    "saturation_creepage": "wheelrail.fe.rolling", "stable_time_step": "wheelrail.fe.rolling",
    "steady_window": "wheelrail.fe.rolling",
    "build_transition_model": "wheelrail.fe.transition",
    "pose_contact": "wheelrail.fe.transition", "yawed_contact": "wheelrail.fe.transition",
    "read_transition_restart": "wheelrail.fe.transition",
    "rail_pulse": "wheelrail.fe.transition", "pulse_arrivals": "wheelrail.fe.transition",
    "phase_velocity": "wheelrail.fe.transition",
    "elastic_wave_speeds": "wheelrail.fe.transition",
}


def __getattr__(name):
    import importlib
    import warnings

    if name == "Suspension":
        warnings.warn("wheelrail.fe.Suspension is now wheelrail.fe.WheelSuspension (the "
                      "vehicle model's suspension is wheelrail.dynamics.Suspension)",
                      DeprecationWarning, stacklevel=2)
        return WheelSuspension
    if name in _MOVED:
        warnings.warn(f"wheelrail.fe.{name} moved to {_MOVED[name]}.{name}",
                      DeprecationWarning, stacklevel=2)
        return getattr(importlib.import_module(_MOVED[name]), name)
    raise AttributeError(f"module 'wheelrail.fe' has no attribute {name!r}")
