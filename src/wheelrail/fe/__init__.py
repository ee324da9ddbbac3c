"""Finite-element frictional rolling contact of a wheel on a rail (3-D, hex8, SI units).

Public names
------------
``RollingCase``
    Frozen input: wheel and rail profiles, rolling radius, load, creepage,
    friction, material, mesh size and integrator.
``seed000_case(load="table3", plastic=False, **changes)``, ``toumi2016_load``,
``cone_wheel``, ``head_arc_rail``
    The Hertzian case of Toumi, Chollet & Yin (2016): a 1/10 cone on a 300 mm head arc
    inclined by 1/10, at the load of their Table 3 (81.3 kN) or as printed (7.5 kN).
``indent(case)``
    Static normal contact (the first loading step of Toumi et al. 2016): ``p_max``, ``a``,
    ``b``, ``pressure`` (and plastic fields).
``solve(case)``
    Rolling (both steps) with the explicit, implicit quasi-static or HHT integrator:
    histories over the travel, the final patch, steady ``Fx``, ``Fy`` with their scatter
    (``steady``), and for plastic bodies ``equivalent_plastic_strain``, ``residual_stress``;
    ``passes`` > 1 rolls the same section again.
``creep_curve(case, creepages, component="xi")``
    Steady creep forces over a range of creepage (xarray.Dataset with the offset).
``Hex8``, ``LinearElastic``, ``J2Plastic``, ``Voce``, ``TabulatedHardening``, ``r900a``
    The element and the material laws (swappable parts).
``build_model``, ``write_vtu``
    The meshed model, and VTU output for ParaView.
``saturation_creepage``
    The creepage beyond which the patch slides entirely (warning threshold).
``read_restart``, ``write_restart``
    Restart files of a rolling run (``solve(case, restart=...)``).
``seed004_case``, ``run_transition``, ``read_transition_restart``, ``pose_contact``
    The one- to two-point contact transition (docs/fe_transition.md).
``rail_pulse``, ``pulse_arrivals``, ``phase_velocity``, ``elastic_wave_speeds``
    Surface-wave speed on the transition model's rail: from a clean force pulse
    (arrival times) or from any record, a rolling run's included (phase spectra).

Parts: :mod:`.mesh` (structured generator), :mod:`.elements`, :mod:`.materials`,
:mod:`._solid` (parallel element kernels, J2 return map), :mod:`._kernels` (contact),
:mod:`.model` (kinematics and assembly), :mod:`.static`, :mod:`.rolling`, :mod:`.explicit`,
:mod:`.implicit`, :mod:`.curves`, :mod:`.patch`, :mod:`.output`, :mod:`.restart`.

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

from .case import (
                   INTEGRATORS,
                   TOUMI2016_TABLE3_HERTZ,
                   RollingCase,
                   cone_wheel,
                   head_arc_rail,
                   seed000_case,
                   toumi2016_load,
)
from .curves import creep_curve
from .elements import Hex8
from .materials import R900A_HARDENING, J2Plastic, LinearElastic, TabulatedHardening, Voce, r900a
from .mesh import MeshQualityError, check_quality
from .model import build_model
from .output import write_vtu
from .restart import read_restart, write_restart
from .rolling import (
                   RollingResult,
                   plastic_fields,
                   saturation_creepage,
                   stable_time_step,
                   steady_window,
)
from .run import solve
from .static import IndentResult, indent
from .transition import (
                   TransitionResult,
                   pose_contact,
                   read_transition_restart,
                   run_transition,
                   seed004_case,
)
from .transition_model import TransitionCase, build_transition_model, yawed_contact
from .transition_track import Suspension, TrackStructure
from .transition_wave import elastic_wave_speeds, phase_velocity, pulse_arrivals, rail_pulse

__all__ = ["creep_curve", "RollingCase", "INTEGRATORS", "seed000_case", "toumi2016_load", "TOUMI2016_TABLE3_HERTZ", "cone_wheel", "head_arc_rail",
           "solve", "indent", "RollingResult", "IndentResult",
           "Hex8", "LinearElastic", "J2Plastic", "Voce", "TabulatedHardening",
           "R900A_HARDENING", "r900a", "plastic_fields", "steady_window", "build_model", "write_vtu", "check_quality",
           "MeshQualityError", "stable_time_step", "saturation_creepage", "read_restart",
           "write_restart", "seed004_case", "run_transition", "TransitionCase", "TransitionResult",
           "TrackStructure", "Suspension", "build_transition_model", "pose_contact",
           "read_transition_restart", "rail_pulse", "pulse_arrivals", "phase_velocity",
           "elastic_wave_speeds", "yawed_contact"]
